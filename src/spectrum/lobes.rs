//! The lobe walker: quadrature of the Agu-Hill integrand in the phase x = d·|u|/λ, one lobe of
//! F_N (between its zeros x = k/N) at a time, the building block of the peak searches and of
//! `Exact`.

use glam::DVec3;

use super::rules::{gl3, gl4, gl8};
use super::Spectral;
use crate::data::cie::Illuminant;
use crate::num::kernel::{intensity_ratio_flat, single_slit_cycles, sinpi};
use crate::num::math::{ceil, floor, rint};
use crate::num::quadrature::GL8;
use crate::Grating;

/// Largest wavelength span of one 4-point Gauss-Legendre piece in the peak searches' treatment
/// of order 0.
pub(super) const COARSE_SPAN_NM: f64 = 16.0;

/// A quadrature rule applied to one piece [a, b] of a [`Lobes`] integral.
pub(super) type PieceRule<'a> = fn(&Lobes<'a>, f64, f64, &mut DVec3, &dyn Fn(f64) -> DVec3);

/// Quadrature in the phase x = q/λ (q = d·|u|) of E·S·cmf·F_N·norm·q/x².
pub(super) struct Lobes<'a> {
    pub(super) s: &'a Spectral,
    pub(super) q: f64,
    pub(super) n: f64,
    n_int: u32,
    pub(super) duty: f64,
}

impl<'a> Lobes<'a> {
    pub(super) fn new(s: &'a Spectral, grating: &Grating, q: f64, n: f64) -> Lobes<'a> {
        Lobes {
            s,
            q,
            n,
            n_int: n as u32,
            duty: grating.slit_width_nm() / grating.period_nm(),
        }
    }

    /// E·S·cmf·norm·|dλ/dx| at phase x, without F_N.
    #[inline]
    pub(super) fn envelope_at(&self, x: f64) -> DVec3 {
        let l = self.q / x;
        let jac = l / x;
        let s = single_slit_cycles(self.duty * x);
        let w = self.s.weight(l);
        let k = s * jac;
        w * k
    }

    /// E·S·cmf·F_N·norm·|dλ/dx| at phase x: S·F_N as one ratio without branches on the phase
    /// (`intensity_ratio_flat`), one division.
    #[inline]
    pub(super) fn integrand_at(&self, x: f64) -> DVec3 {
        let l = self.q / x;
        let (num, den) = intensity_ratio_flat(x, self.duty * x, self.n_int);
        let r = num / den;
        let i = (r * r).min(1.0);
        self.s.weight(l) * (i * (l / x))
    }

    /// F_N at phase x.
    #[inline]
    pub(super) fn n_slit(&self, x: f64) -> f64 {
        crate::num::kernel::n_slit_cycles(x, self.n_int)
    }

    /// ∫ over [a, b] lobe by lobe, split at the 1 nm rows of the tables (8-point rule).
    pub(super) fn lobes(&self, a: f64, b: f64) -> DVec3 {
        self.lobes_by(a, b, Self::split_at_rows)
    }

    /// ∫ over [a, b] lobe by lobe, each lobe in pieces of at most COARSE_SPAN_NM, 4-point
    /// Gauss-Legendre, not split at the table rows.
    pub(super) fn coarse_lobes(&self, a: f64, b: f64) -> DVec3 {
        self.lobes_by(a, b, Self::coarse)
    }

    /// ∫ over [a, b] of the full integrand, one lobe (between zeros x = k/N) at a time, each
    /// lobe handed to `rule`.
    pub(super) fn lobes_by(&self, a: f64, b: f64, rule: PieceRule<'a>) -> DVec3 {
        let mut acc = DVec3::ZERO;
        if b.is_nan() || a.is_nan() || b <= a {
            return acc;
        }
        let integrand = |x: f64| self.integrand_at(x);
        let mut k = floor(a * self.n) + 1.0;
        let mut lo = a;
        while lo < b {
            let hi = (k / self.n).min(b);
            if hi > lo {
                rule(self, lo, hi, &mut acc, &integrand);
            }
            lo = hi;
            k += 1.0;
        }
        acc
    }

    /// 4-point Gauss-Legendre on pieces of [a, b] spanning at most COARSE_SPAN_NM.
    fn coarse(&self, a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
        let span = self.q / a - self.q / b;
        let pieces = ceil(span / COARSE_SPAN_NM).max(1.0);
        let step = (b - a) / pieces;
        let count = pieces as u32;
        let mut t = a;
        for j in 1..=count {
            let e = if j == count { b } else { a + j as f64 * step };
            gl4(t, e, acc, f);
            t = e;
        }
    }

    /// ∫ F_N dr over [−h, h] (lobe-exact Gauss-Legendre), h a whole number of lobes.
    pub(super) fn kernel_mass(&self, h: f64) -> f64 {
        let mut sum = 0.0;
        let lobes = rint(h * self.n) as u32;
        let width = 1.0 / self.n;
        for j in 0..lobes {
            let (mid, half) = ((j as f64 + 0.5) * width, 0.5 * width);
            for (xi, wi) in GL8.nodes.iter().zip(GL8.weights) {
                sum += wi * half * crate::num::kernel::n_slit_cycles(mid + half * xi, self.n_int);
            }
        }
        2.0 * sum
    }

    /// ∫ over [a, b] (away from integers) with sin²(πNx) replaced by its mean ½, on a grid
    /// where the distance to the nearest integer changes by at most a factor 2 per piece.
    pub(super) fn envelope(&self, a: f64, b: f64, split_rows: bool) -> DVec3 {
        let mut acc = DVec3::ZERO;
        let mut lo = a;
        while lo < b {
            let m = floor(lo);
            let mid = m + 0.5;
            let hi = if lo < mid {
                (lo + (lo - m)).min(mid)
            } else {
                lo + 0.5 * (m + 1.0 - lo)
            };
            let hi = if hi > lo { hi.min(b) } else { b };
            let f = |x: f64| {
                let den = self.n * sinpi(x - rint(x));
                let f = 0.5 / (den * den);
                let e = self.envelope_at(x);
                e * f
            };
            if split_rows {
                self.split_at_rows(lo, hi, &mut acc, &f);
            } else {
                self.coarse(lo, hi, &mut acc, &f);
            }
            lo = hi;
        }
        acc
    }

    /// ∫ over [a, b] lobe by lobe, split at the 1 nm rows, each piece by the Gauss-Legendre
    /// rule its width in lobes allows (`graded_rule`).
    pub(super) fn graded_lobes(&self, a: f64, b: f64) -> DVec3 {
        self.lobes_by(a, b, Self::split_at_rows_graded)
    }

    /// As `split_at_rows`, each piece by `graded_rule`.
    /// `f` is the full integrand (`integrand_at`): each piece lies in one row of the tables,
    /// whose interpolation coefficients are taken once for it.
    fn split_at_rows_graded(&self, a: f64, b: f64, acc: &mut DVec3, _f: &dyn Fn(f64) -> DVec3) {
        let piece = |lo: f64, hi: f64, acc: &mut DVec3| {
            let row = Row::new(self.s.illuminant(), self.q / (0.5 * (lo + hi)));
            graded_rule(self.n * (hi - lo), lo, hi, acc, &|x| {
                row.integrand_at(self, x)
            });
        };
        let mut lo = a;
        let mut j = ceil(self.q / a) - 1.0;
        let j_end = self.q / b;
        while j > j_end && lo < b {
            let x = (self.q / j).min(b);
            if x > lo {
                piece(lo, x, acc);
                lo = x;
            }
            j -= 1.0;
        }
        if b > lo {
            piece(lo, b, acc);
        }
    }

    /// Gauss-Legendre over [a, b] split where λ = q/x crosses an integer nanometre.
    fn split_at_rows(&self, a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
        // λ runs from q/a down to q/b; rows j with q/b < j < q/a sit at x = q/j.
        let mut lo = a;
        let mut j = ceil(self.q / a) - 1.0;
        let j_end = self.q / b;
        while j > j_end && lo < b {
            let x = (self.q / j).min(b);
            if x > lo {
                gl8(lo, x, acc, f);
                lo = x;
            }
            j -= 1.0;
        }
        if b > lo {
            gl8(lo, b, acc, f);
        }
    }
}

/// One row of the tables (between the 1 nm rows i and i + 1): E and the observer as
/// value + slope·t, t the fraction of the row, as `cie::power_and_cmf` interpolates them.
pub(super) struct Row {
    start: f64,
    e0: f64,
    de: f64,
    c0: DVec3,
    dc: DVec3,
}

impl Row {
    /// The row that holds λ (the last one at 830 nm).
    #[inline]
    pub(super) fn new(illuminant: Illuminant, lambda_nm: f64) -> Row {
        use crate::data::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};
        let last = (LAST_NM - FIRST_NM) as usize - 1;
        let s = (lambda_nm - FIRST_NM as f64).max(0.0);
        let i = (s as usize).min(last);
        let (e0, e1) = match illuminant {
            Illuminant::E => (1.0, 1.0),
            Illuminant::D65 => (D65[i], D65[i + 1]),
            Illuminant::A => (ILLUMINANT_A[i], ILLUMINANT_A[i + 1]),
        };
        let (a, b) = (
            DVec3::from_array(CIE1931_2DEG[i]),
            DVec3::from_array(CIE1931_2DEG[i + 1]),
        );
        Row {
            start: i as f64,
            e0,
            de: e1 - e0,
            c0: a,
            dc: b - a,
        }
    }

    /// E·cmf in this row (without the envelope and the norm) as w₀ + w₁·τ + w₂·τ², τ = λ − λ_c:
    /// the row's two linear interpolants, extended beyond the row, multiplied out around λ_c.
    #[inline]
    pub(super) fn tau_expansion(&self, lambda_c: f64) -> [DVec3; 3] {
        use crate::data::cie_data::FIRST_NM;
        let d = (lambda_c - FIRST_NM as f64) - self.start;
        let e = self.e0 + self.de * d;
        let c = self.c0 + self.dc * d;
        [c * e, self.dc * e + c * self.de, self.dc * self.de]
    }

    /// E·cmf·env·norm at λ in this row.
    #[inline]
    fn weight(&self, l: &Lobes<'_>, lambda: f64) -> DVec3 {
        use crate::data::cie_data::FIRST_NM;
        let t = (lambda - FIRST_NM as f64) - self.start;
        let e = (self.e0 + t * self.de) * l.s.envelope_norm(lambda);
        (self.c0 + self.dc * t) * e
    }

    /// `Lobes::integrand_at` at x for an x whose wavelength lies in this row.
    #[inline]
    fn integrand_at(&self, l: &Lobes<'_>, x: f64) -> DVec3 {
        let lambda = l.q / x;
        let (num, den) = intensity_ratio_flat(x, l.duty * x, l.n_int);
        let r = num / den;
        let i = (r * r).min(1.0);
        self.weight(l, lambda) * (i * (lambda / x))
    }
}

/// Gauss-Legendre on a piece of at most one lobe, `lobes` wide (in lobes of F_N, whose
/// derivatives scale as (πN)^k; S's lobes are wider, 1/duty ≥ 1): 8 points above 1/8 lobe, else
/// the fewest points whose error on cos(2πN·x) over the piece, κ^{2n}·(n!)⁴/((2n+1)·((2n)!)³)
/// with κ = 2π·lobes, is below 10⁻¹⁰ relative (4 points to 1/8 lobe, 3 to 1/32).
/// Not fewer than 3: over a 1 nm row the smooth factors (|dλ/dx| = q/x², the weight in λ = q/x)
/// leave the 2-point rule a few 10⁻¹¹ of the colour.
pub(super) fn graded_rule(lobes: f64, a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    if lobes > 0.125 {
        gl8(a, b, acc, f);
    } else if lobes > 1.0 / 32.0 {
        gl4(a, b, acc, f);
    } else {
        gl3(a, b, acc, f);
    }
}
