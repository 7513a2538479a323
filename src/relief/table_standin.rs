//! A minimal stand-in for the tabulated order efficiencies (`EfficiencyTable`, `Preset`), with
//! the interface and the interpolation rule of `docs/efficiency_tables.md`, until the table
//! type proper lands; removed then.
#![allow(clippy::neg_cmp_op_on_partial_ord, clippy::nonminimal_bool)]

use super::scalar::Polarised;
#[cfg(feature = "alloc")]
use super::scalar::ScalarRelief;
use crate::efficiency_presets_data as data;
#[cfg(feature = "alloc")]
use crate::error::{Error, Requirement};
use crate::math;
use core::ops::RangeInclusive;

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

/// Storage of a table's numbers: the presets' static f32, or owned f64.
#[derive(Debug, Clone, PartialEq)]
enum Store {
    Static {
        s: &'static [f32],
        l: &'static [f32],
        te: &'static [f32],
        tm: &'static [f32],
    },
    #[cfg(feature = "alloc")]
    Owned {
        s: Vec<f64>,
        l: Vec<f64>,
        te: Vec<f64>,
        tm: Vec<f64>,
    },
}

/// Order efficiencies tabulated in (sin θi, λ) (stand-in).
#[derive(Debug, Clone, PartialEq)]
pub struct EfficiencyTable {
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    store: Store,
}

/// The shipped rigorous tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Preset {
    /// CD.
    Cd,
    /// DVD.
    Dvd,
    /// 600 lines/mm blazed.
    Blazed600,
    /// Sinusoidal foil.
    Foil,
}

static CD: EfficiencyTable = EfficiencyTable {
    period_nm: data::CD_PERIOD_NM,
    order_min: data::CD_ORDER_MIN,
    order_count: data::CD_ORDER_COUNT,
    store: Store::Static {
        s: &data::CD_SIN_THETA_I,
        l: &data::CD_LAMBDA_NM,
        te: &data::CD_TE,
        tm: &data::CD_TM,
    },
};
static DVD: EfficiencyTable = EfficiencyTable {
    period_nm: data::DVD_PERIOD_NM,
    order_min: data::DVD_ORDER_MIN,
    order_count: data::DVD_ORDER_COUNT,
    store: Store::Static {
        s: &data::DVD_SIN_THETA_I,
        l: &data::DVD_LAMBDA_NM,
        te: &data::DVD_TE,
        tm: &data::DVD_TM,
    },
};
static BLAZED600: EfficiencyTable = EfficiencyTable {
    period_nm: data::BLAZED600_PERIOD_NM,
    order_min: data::BLAZED600_ORDER_MIN,
    order_count: data::BLAZED600_ORDER_COUNT,
    store: Store::Static {
        s: &data::BLAZED600_SIN_THETA_I,
        l: &data::BLAZED600_LAMBDA_NM,
        te: &data::BLAZED600_TE,
        tm: &data::BLAZED600_TM,
    },
};
static FOIL: EfficiencyTable = EfficiencyTable {
    period_nm: data::FOIL_PERIOD_NM,
    order_min: data::FOIL_ORDER_MIN,
    order_count: data::FOIL_ORDER_COUNT,
    store: Store::Static {
        s: &data::FOIL_SIN_THETA_I,
        l: &data::FOIL_LAMBDA_NM,
        te: &data::FOIL_TE,
        tm: &data::FOIL_TM,
    },
};

impl Preset {
    /// The preset's table.
    #[must_use]
    pub fn table(self) -> &'static EfficiencyTable {
        match self {
            Preset::Cd => &CD,
            Preset::Dvd => &DVD,
            Preset::Blazed600 => &BLAZED600,
            Preset::Foil => &FOIL,
        }
    }

    /// The preset's period, nm.
    #[must_use]
    pub fn period_nm(self) -> f64 {
        self.table().period_nm
    }
}

/// The cell of `x` in the nodes: (i, t) with nodes\[i\] ≤ x ≤ nodes\[i + 1\], x clamped.
fn cell(nodes: &dyn Fn(usize) -> f64, n: usize, x: f64) -> (usize, f64) {
    let x = x.clamp(nodes(0), nodes(n - 1));
    let (mut a, mut b) = (0, n - 1);
    while b - a > 1 {
        let mid = (a + b) / 2;
        if nodes(mid) <= x {
            a = mid;
        } else {
            b = mid;
        }
    }
    let (x0, x1) = (nodes(a), nodes(a + 1));
    (a, ((x - x0) / (x1 - x0)).clamp(0.0, 1.0))
}

impl EfficiencyTable {
    /// The grating's period, nm.
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.period_nm
    }

    /// The orders stored.
    #[must_use]
    pub fn orders(&self) -> RangeInclusive<i32> {
        self.order_min..=self.order_min + self.order_count as i32 - 1
    }

    fn sizes(&self) -> (usize, usize) {
        match &self.store {
            Store::Static { s, l, .. } => (s.len(), l.len()),
            #[cfg(feature = "alloc")]
            Store::Owned { s, l, .. } => (s.len(), l.len()),
        }
    }

    fn s_node(&self, i: usize) -> f64 {
        match &self.store {
            Store::Static { s, .. } => f64::from(s[i]),
            #[cfg(feature = "alloc")]
            Store::Owned { s, .. } => s[i],
        }
    }

    fn l_node(&self, j: usize) -> f64 {
        match &self.store {
            Store::Static { l, .. } => f64::from(l[j]),
            #[cfg(feature = "alloc")]
            Store::Owned { l, .. } => l[j],
        }
    }

    fn node(&self, idx: usize) -> (f64, f64) {
        match &self.store {
            Store::Static { te, tm, .. } => (f64::from(te[idx]), f64::from(tm[idx])),
            #[cfg(feature = "alloc")]
            Store::Owned { te, tm, .. } => (te[idx], tm[idx]),
        }
    }

    /// η of one order (the interpolation rule of `docs/efficiency_tables.md`), not normalised.
    fn raw(&self, k: usize, s: f64, lambda: f64) -> Polarised {
        let (ns, nl) = self.sizes();
        let s = s.clamp(self.s_node(0), self.s_node(ns - 1));
        let lambda = lambda.clamp(self.l_node(0), self.l_node(nl - 1));
        let m = f64::from(self.order_min + k as i32);
        let sm = s + m * lambda / self.period_nm;
        if !(sm.abs() < 1.0) {
            return Polarised::default();
        }
        let (i, tx) = cell(&|i| self.s_node(i), ns, s);
        let (j, ty) = cell(&|j| self.l_node(j), nl, lambda);
        let (mut qte, mut qtm, mut wsum) = (0.0, 0.0, 0.0);
        for (di, dj, w) in [
            (0, 0, (1.0 - tx) * (1.0 - ty)),
            (1, 0, tx * (1.0 - ty)),
            (0, 1, (1.0 - tx) * ty),
            (1, 1, tx * ty),
        ] {
            let (sc, lc) = (self.s_node(i + di), self.l_node(j + dj));
            let a = sc + m * lc / self.period_nm;
            let c = 1.0 - a * a;
            if c > 1e-6 {
                let r = math::sqrt((1.0 - sc * sc).max(0.0)) / math::sqrt(c);
                let (te, tm) = self.node((k * nl + j + dj) * ns + i + di);
                qte += w * te * r;
                qtm += w * tm * r;
                wsum += w;
            }
        }
        if wsum <= 0.0 {
            return Polarised::default();
        }
        let cos_i = math::sqrt((1.0 - s * s).max(1e-300));
        let g = math::sqrt(1.0 - sm * sm) / cos_i / wsum;
        Polarised {
            te: (qte * g).max(0.0),
            tm: (qtm * g).max(0.0),
        }
    }

    /// η_m (TE, TM) of `order` for incidence sin θi = `sin_theta_i` at `lambda_nm`; the orders
    /// scaled down together where their sum would exceed 1.
    #[must_use]
    pub fn efficiency(&self, order: i32, sin_theta_i: f64, lambda_nm: f64) -> Polarised {
        if !self.orders().contains(&order) || !(sin_theta_i.is_finite() && lambda_nm.is_finite()) {
            return Polarised::default();
        }
        let mut buf = [Polarised::default(); 64];
        if self.order_count <= buf.len() {
            self.efficiencies(sin_theta_i, lambda_nm, &mut buf);
            buf[(order - self.order_min) as usize]
        } else {
            self.raw((order - self.order_min) as usize, sin_theta_i, lambda_nm)
        }
    }

    /// Every stored order into `out` (as many as fit); returns Σ unpolarised.
    pub fn efficiencies(&self, sin_theta_i: f64, lambda_nm: f64, out: &mut [Polarised]) -> f64 {
        let n = self.order_count.min(out.len());
        if !(sin_theta_i.is_finite() && lambda_nm.is_finite()) {
            out[..n].fill(Polarised::default());
            return 0.0;
        }
        let (mut ste, mut stm) = (0.0, 0.0);
        for (k, o) in out[..n].iter_mut().enumerate() {
            *o = self.raw(k, sin_theta_i, lambda_nm);
            ste += o.te;
            stm += o.tm;
        }
        let (fte, ftm) = (1.0 / ste.max(1.0), 1.0 / stm.max(1.0));
        let mut total = 0.0;
        for o in &mut out[..n] {
            o.te *= fte;
            o.tm *= ftm;
            total += o.unpolarised();
        }
        total
    }

    /// Bakes the scalar relief model at the nodes `s` × `lambda`.
    #[cfg(feature = "alloc")]
    pub fn from_scalar(
        relief: &ScalarRelief,
        s: &[f64],
        lambda: &[f64],
    ) -> Result<EfficiencyTable, Error> {
        let bad = |name: &'static str, v: f64| Err(Error::invalid(name, v, Requirement::Finite));
        if s.len() < 2
            || s.windows(2).any(|w| !(w[0] < w[1]))
            || s[0] <= -1.0
            || s[s.len() - 1] >= 1.0
        {
            return bad("s", s.first().copied().unwrap_or(f64::NAN));
        }
        if lambda.len() < 2 || lambda.windows(2).any(|w| !(w[0] < w[1])) || !(lambda[0] > 0.0) {
            return bad("lambda", lambda.first().copied().unwrap_or(f64::NAN));
        }
        let d = relief.period_nm();
        let lmax = lambda[lambda.len() - 1];
        let hi = math::floor(2.0 * d / lambda[0]) as i32;
        let _ = lmax;
        let (lo, count) = (-hi, (2 * hi + 1) as usize);
        let (ns, nl) = (s.len(), lambda.len());
        let mut te = Vec::with_capacity(count * ns * nl);
        let mut tm = Vec::with_capacity(count * ns * nl);
        for k in 0..count {
            for &l in lambda {
                for &si in s {
                    let e = relief.order(lo + k as i32, si, l).unwrap_or_default();
                    te.push(e.te);
                    tm.push(e.tm);
                }
            }
        }
        Ok(EfficiencyTable {
            period_nm: d,
            order_min: lo,
            order_count: count,
            store: Store::Owned {
                s: s.to_vec(),
                l: lambda.to_vec(),
                te,
                tm,
            },
        })
    }
}
