//! Conical tables: η_m on a grid in (s′, |β|, λ), where β is the incident direction cosine along
//! the grooves and s′ = α/√(1 − β²) the reduced direction cosine across them (α = −wi.x,
//! β = −wi.y: the incident direction of travel), interpolated by the rule of
//! `docs/efficiency_tables.md` ("Conical tables").
//!
//! s′ is the sine of the angle between the normal and the incident direction's projection on
//! the plane across the grooves; every node with |s′| < 1 is a real incidence, whatever β, so
//! the grid is a full box. By the mirror symmetry y → −y of a 1-D grating, unpolarised (and
//! TE + TM summed) efficiencies depend on |β| only: the table stores β ≥ 0. Order m leaves
//! with α_m = α + m·λ/d and β_m = β and propagates iff α_m² + β² < 1.

#[cfg(feature = "alloc")]
use alloc::vec;
#[cfg(feature = "alloc")]
use alloc::vec::Vec;

use super::nodes_q::NOT_PROPAGATING;
use super::{corner_mean, corner_q, interval, scale, AxisName, EfficiencyTable, OrderCell, Values};
#[cfg(feature = "alloc")]
use super::{
    load::{check_axis, check_period, order_count, SUM_TOLERANCE},
    Lookup, NodeQ, Storage, UnitCells,
};
#[cfg(feature = "alloc")]
use crate::error::{Error, Requirement};
use crate::num::math;
use crate::relief::Polarised;

/// The largest |β| node of a conical table (the solvers need cos θi > 0).
pub const MAX_TABLE_ABS_BETA: f64 = 0.99999;

/// One query's interpolation cell in (s′, |β|, λ), shared by every order.
pub(super) struct Cell3 {
    /// The query clamped to the grid: α, β², λ and cos θi.
    pub(super) alpha: f64,
    pub(super) beta2: f64,
    pub(super) lambda_nm: f64,
    pub(super) cos_i: f64,
    /// Per corner: trilinear weight, α, β², λ and cos θi of the node, flat index in a slice.
    pub(super) w: [f64; 8],
    pub(super) a_c: [f64; 8],
    pub(super) b2_c: [f64; 8],
    pub(super) l_c: [f64; 8],
    pub(super) cos_c: [f64; 8],
    pub(super) index: [usize; 8],
    /// The cell's index (k·(n_λ − 1) + j)·(n_s − 1) + i, for `UnitCells`.
    pub(super) cell: usize,
}

impl Cell3 {
    /// The cell `cell` of the clamped query (α, β², λ, cos θi), its corners still to be set.
    pub(super) fn empty(alpha: f64, beta2: f64, lambda_nm: f64, cos_i: f64, cell: usize) -> Cell3 {
        Cell3 {
            alpha,
            beta2,
            lambda_nm,
            cos_i,
            w: [0.0; 8],
            a_c: [0.0; 8],
            b2_c: [0.0; 8],
            l_c: [0.0; 8],
            cos_c: [0.0; 8],
            index: [0; 8],
            cell,
        }
    }

    /// The cell of the incidence (α, β) at λ: s′ = α/√(1 − β²), |β| and λ clamped to the grid
    /// (the query is then the clamped point); `None` for a non-finite query, one with
    /// α² + β² ≥ 1 or at grazing incidence on the grid.
    pub(super) fn find<T: Values + ?Sized>(
        sin: &T,
        bet: &T,
        lam: &T,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
    ) -> Option<Cell3> {
        if !(alpha.is_finite() && beta.is_finite() && lambda_nm.is_finite()) {
            return None;
        }
        let b = beta.abs();
        if alpha * alpha + b * b >= 1.0 {
            return None;
        }
        let (n_s, n_b, n_l) = (sin.count(), bet.count(), lam.count());
        let sp = alpha / math::sqrt(1.0 - b * b);
        let sp = sp.max(sin.at(0)).min(sin.at(n_s - 1));
        let b = b.max(bet.at(0)).min(bet.at(n_b - 1));
        let lambda_nm = lambda_nm.max(lam.at(0)).min(lam.at(n_l - 1));
        let cb = math::sqrt(1.0 - b * b);
        let cos_i = cb * math::sqrt(1.0 - sp * sp);
        if cos_i.is_nan() || cos_i <= 0.0 {
            return None;
        }
        let i = interval(sin, sp);
        let k = interval(bet, b);
        let j = interval(lam, lambda_nm);
        let t = [
            (sp - sin.at(i)) / (sin.at(i + 1) - sin.at(i)),
            (b - bet.at(k)) / (bet.at(k + 1) - bet.at(k)),
            (lambda_nm - lam.at(j)) / (lam.at(j + 1) - lam.at(j)),
        ];
        let mut cell = Cell3::empty(
            sp * cb,
            b * b,
            lambda_nm,
            cos_i,
            (k * (n_l - 1) + j) * (n_s - 1) + i,
        );
        for c in 0..8 {
            let (di, dk, dj) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
            let wt = |d: usize, t: f64| if d == 1 { t } else { 1.0 - t };
            cell.w[c] = wt(di, t[0]) * wt(dk, t[1]) * wt(dj, t[2]);
            let (s_n, b_n) = (sin.at(i + di), bet.at(k + dk));
            let cbn = math::sqrt(1.0 - b_n * b_n);
            cell.a_c[c] = s_n * cbn;
            cell.b2_c[c] = b_n * b_n;
            cell.l_c[c] = lam.at(j + dj);
            cell.cos_c[c] = cbn * math::sqrt(1.0 - s_n * s_n);
            cell.index[c] = ((k + dk) * n_l + (j + dj)) * n_s + (i + di);
        }
        Some(cell)
    }
}

impl OrderCell for Cell3 {
    /// Whether order m propagates at the query (α_m² + β² < 1), with the operations of
    /// [`order`](Self::order).
    #[inline]
    fn propagates(&self, period_nm: f64, m: i32) -> bool {
        let am = self.alpha + f64::from(m) * self.lambda_nm / period_nm;
        1.0 - am * am - self.beta2 > 0.0
    }

    /// Order m's interpolated efficiencies before the normalisation, reading the order's slice
    /// starting at `base` (or the nodes' q's, where kept): the rule of the classical cell over
    /// the eight corners.
    #[inline]
    fn order<T: Values + ?Sized>(
        &self,
        period_nm: f64,
        m: i32,
        base: usize,
        values: (&T, &T),
        q: Option<&[[f64; 2]]>,
    ) -> Polarised {
        let mf = f64::from(m);
        let am = self.alpha + mf * self.lambda_nm / period_nm;
        let cm2q = 1.0 - am * am - self.beta2;
        if cm2q <= 0.0 {
            return Polarised::default();
        }
        let (mut qc, mut w) = ([[0.0f64; 2]; 8], [0.0f64; 8]);
        for c in 0..8 {
            if self.w[c] <= 0.0 {
                continue;
            }
            let at = base + self.index[c];
            let value = match q {
                Some(q) => q[at],
                None => corner_q(
                    self.a_c[c],
                    self.b2_c[c],
                    self.l_c[c],
                    self.cos_c[c],
                    mf,
                    period_nm,
                    values,
                    at,
                ),
            };
            if value[0] != NOT_PROPAGATING {
                w[c] = self.w[c];
                qc[c] = value;
            }
        }
        let Some([num_te, num_tm]) = corner_mean(&w, &qc) else {
            return Polarised::default();
        };
        let k = math::sqrt(cm2q) / self.cos_i;
        Polarised {
            te: num_te * k,
            tm: num_tm * k,
        }
    }

    #[inline]
    fn index(&self) -> usize {
        self.cell
    }

    #[inline]
    fn corners(&self) -> (&[f64], &[usize]) {
        (&self.w, &self.index)
    }
}

impl EfficiencyTable {
    /// Whether the table has a conical axis |β| (a version-2 table): then
    /// [`efficiencies_conical`](Self::efficiencies_conical) reads η_m(α, β, λ). A classical
    /// table ignores β: read off the plane across the grooves, it is the classical-mount
    /// approximation (`docs/efficiency_tables.md`, "Conical tables").
    #[must_use]
    pub fn is_conical(&self) -> bool {
        self.axis(AxisName::Beta).len() > 0
    }

    /// The |β| nodes of a conical table (empty for a classical one).
    pub fn abs_beta(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.axis(AxisName::Beta)
    }

    /// Order `order`'s efficiencies for an incident direction of travel with direction cosines
    /// α = `alpha` across and β = `beta` along the grooves (α = −wi.x, β = −wi.y) at
    /// `lambda_nm`, normalised as [`efficiency`](Self::efficiency). A classical table reads
    /// s = α and ignores β (the classical-mount approximation); a conical table follows its
    /// rule (0 where α_m² + β² ≥ 1, and for α² + β² ≥ 1).
    #[must_use]
    pub fn efficiency_conical(
        &self,
        order: i32,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
    ) -> Polarised {
        if !self.orders().contains(&order) {
            return Polarised::default();
        }
        self.one(order, alpha, beta, lambda_nm)
    }

    /// Every stored order's efficiencies at (α, β, λ) at once, as
    /// [`efficiencies`](Self::efficiencies) does at (s, λ) (which is this at β = 0). Returns
    /// the unpolarised sum, at most 1.
    ///
    /// ```
    /// use diffraction::relief::{EfficiencyTable, Polarised};
    /// // One order (0) of a 1000 nm grating, η = 0.9 everywhere on a 2 × 2 × 2 grid.
    /// let t = EfficiencyTable::new_conical(
    ///     1000.0, 0, vec![-0.5, 0.5], vec![0.0, 0.6], vec![500.0, 600.0],
    ///     vec![0.9; 8], vec![0.8; 8],
    /// )?;
    /// assert!(t.is_conical());
    /// let mut out = [Polarised::default(); 1];
    /// let total = t.efficiencies_conical(0.1, -0.3, 550.0, &mut out);
    /// assert!((out[0].te - 0.9).abs() < 1e-12 && (total - 0.85).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn efficiencies_conical(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
        out: &mut [Polarised],
    ) -> f64 {
        for o in out.iter_mut() {
            *o = Polarised::default();
        }
        let first = self.order_min;
        let (sum_te, sum_tm) = self.each(alpha, beta, lambda_nm, |m, e| {
            if let Some(o) = out.get_mut((m - first) as usize) {
                *o = e;
            }
        });
        let (k_te, k_tm) = (scale(sum_te), scale(sum_tm));
        for o in out.iter_mut() {
            o.te *= k_te;
            o.tm *= k_tm;
        }
        0.5 * (sum_te * k_te + sum_tm * k_tm)
    }
}

/// Checks one polarisation's values of a conical table: finite and ≥ 0, each node's sum over
/// orders ≤ 1 + `SUM_TOLERANCE`, 0 where the order is evanescent at the node.
#[cfg(feature = "alloc")]
fn check_values(
    name: &'static str,
    period_nm: f64,
    order_min: i32,
    axes: (&[f64], &[f64], &[f64]),
    v: &[f64],
) -> Result<(), Error> {
    let (sin, bet, lam) = axes;
    if let Some(&bad) = v.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
        return Err(Error::invalid(name, bad, Requirement::NonNegative));
    }
    let slice = sin.len() * bet.len() * lam.len();
    let orders = v.len() / slice;
    let mut sums = vec![0.0; slice];
    for k in 0..orders {
        let m = f64::from(order_min) + k as f64;
        for (b, &beta) in bet.iter().enumerate() {
            let cb = math::sqrt(1.0 - beta * beta);
            for (j, &l) in lam.iter().enumerate() {
                for (i, &s) in sin.iter().enumerate() {
                    let at = (b * lam.len() + j) * sin.len() + i;
                    let x = v[k * slice + at];
                    sums[at] += x;
                    let am = s * cb + m * l / period_nm;
                    if x != 0.0 && 1.0 - am * am - beta * beta <= 0.0 {
                        let requirement = Requirement::ZeroWhereEvanescentConical {
                            order: order_min + k as i32,
                        };
                        return Err(Error::invalid(name, x, requirement));
                    }
                }
            }
        }
    }
    let bound = 1.0 + SUM_TOLERANCE;
    if let Some(&worst) = sums.iter().find(|&&t| t > bound) {
        let worst = sums.iter().fold(worst, |a, &b| a.max(b));
        return Err(Error::invalid(
            name,
            worst,
            Requirement::SumAtMost { bound },
        ));
    }
    Ok(())
}

#[cfg(feature = "alloc")]
impl EfficiencyTable {
    /// A conical table (feature `alloc`): as [`new`](Self::new) with a third axis `abs_beta`
    /// of |β| nodes (2 to `MAX_TABLE_NODES`, strictly increasing, in [0, 0.99999]), the
    /// `sin_theta_i` nodes being s′ = α/√(1 − β²) in [−1, 1], and the TE and TM values
    /// flattened `[order][|β|][λ][s′]`: `te[((k·n_β + b)·n_λ + j)·n_s + i]`. Each value must be
    /// 0 where its order is evanescent at the node ((s′·√(1 − β²) + m·λ/d)² + β² ≥ 1), and each
    /// node's sum over orders at most 1 + `SUM_TOLERANCE`. Errors name the field.
    ///
    /// ```
    /// use diffraction::relief::EfficiencyTable;
    /// // Order 1 of a 1000 nm grating at s′ = 0.5, |β| = 0.6, λ = 600 nm: α₁ = 0.4 + 0.6,
    /// // evanescent, so its value must be 0.
    /// let mut te = vec![0.0; 2 * 8];
    /// te[8 + 7] = 0.01;
    /// let e = EfficiencyTable::new_conical(
    ///     1000.0, 0, vec![-0.5, 0.5], vec![0.0, 0.6], vec![500.0, 600.0], te.clone(), te,
    /// ).unwrap_err();
    /// assert_eq!(e.parameter(), "te");
    /// ```
    pub fn new_conical(
        period_nm: f64,
        order_min: i32,
        sin_theta_i: Vec<f64>,
        abs_beta: Vec<f64>,
        lambda_nm: Vec<f64>,
        te: Vec<f64>,
        tm: Vec<f64>,
    ) -> Result<EfficiencyTable, Error> {
        check_period("period_nm", period_nm)?;
        check_axis("sin_theta_i", &sin_theta_i, Some((-1.0, 1.0)))?;
        check_axis("abs_beta", &abs_beta, Some((0.0, MAX_TABLE_ABS_BETA)))?;
        check_axis("lambda_nm", &lambda_nm, None)?;
        // Each axis has at most 4096 nodes: the product fits a usize on 64-bit targets; on
        // smaller ones saturate (and the slice count check refuses the table).
        let slice = sin_theta_i
            .len()
            .saturating_mul(abs_beta.len())
            .saturating_mul(lambda_nm.len());
        let orders = order_count(&te, &tm, slice, order_min, |slice, max_slices| {
            Requirement::ConicalSlices { slice, max_slices }
        })?;
        let axes = (
            sin_theta_i.as_slice(),
            abs_beta.as_slice(),
            lambda_nm.as_slice(),
        );
        check_values("te", period_nm, order_min, axes, &te)?;
        check_values("tm", period_nm, order_min, axes, &tm)?;
        Ok(EfficiencyTable {
            period_nm,
            order_min,
            order_count: orders,
            storage: Storage::Owned {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                te,
                tm,
            },
            unit: UnitCells::new(),
            q: NodeQ::new(),
            lookup: Lookup::new(),
        })
    }
}
