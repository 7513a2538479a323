//! A reduced conical table read from a classical one (`docs/efficiency_tables.md`, "A reduced
//! table from a classical one"): the conical efficiencies of the reduced reading, in the cover's
//! medium under a cover, at the nodes of a version-3 table, so that the BSDF's conical reading
//! (sampler, proposal, albedo) takes them as they are.

use alloc::vec::Vec;

use super::super::load::check_axis;
use super::super::{EfficiencyTable, MAX_TABLE_ABS_BETA, MAX_TABLE_NODES, MAX_TABLE_VALUES};
use super::{cb, ReducedGrid};
use crate::error::{Error, Requirement};
use crate::num::math;
use crate::relief::Polarised;

/// The |β| planes of [`EfficiencyTable::reduced_from_classical`]'s tables when the caller has
/// no reason to choose others: dense where c = √(1 − β²) changes fastest, up to
/// [`MAX_TABLE_ABS_BETA`].
pub const REDUCED_PLANES: [f64; 11] = [
    0.0, 0.3, 0.5, 0.64, 0.75, 0.84, 0.9, 0.95, 0.98, 0.995, 0.99999,
];

/// The ratio between successive wavelength nodes of a plane beyond the classical table's band,
/// where its values are the band edge's (clamped) and only the orders' cut-offs change.
const BEYOND_RATIO: f64 = 1.15;

impl EfficiencyTable {
    /// The reduced reading of this classical table as a reduced conical table (version 3,
    /// feature `alloc`), which the BSDF reads conically ([`is_conical`](Self::is_conical)).
    ///
    /// The conical efficiencies at incidence (α, β) and wavelength λ are read from the classical
    /// table at s″ = α/c and λ″ = λ/c, with c = √(1 − β²/n(λ)²): the reduction in the medium of
    /// the cover of index n (`cover_index(λ)`, nm → n; `|_| 1.0` for a bare grating). Under a
    /// cover each order is then scaled by the cover-air interface's unpolarised Fresnel
    /// transmittance on the real path over the reduced problem's, in at (α, β) and out at
    /// (α_m, β) (so η → 0 at an order's cut-off in air; a node whose sum this lifts above 1 is
    /// scaled back to 1). Orders that propagate in the cover but not in air are 0 (one pass:
    /// they are trapped). For a perfect conductor in air the reading is exact; for the four
    /// presets' tables it puts 80.8 % of the conical orders with η ≥ 1 % within 10 % of a
    /// conical solve at azimuths 30-80°, where their classical reading puts 41.2 %
    /// (`docs/validity.md`, "Conical incidence").
    ///
    /// The table has one plane per `abs_beta` ([`REDUCED_PLANES`] is a good choice), the
    /// classical table's s nodes as its s′ nodes and band, and each plane the wavelengths that
    /// map onto the classical nodes (for a bare grating its values at the nodes are then the
    /// classical table's own, and a query between two planes reads both at the same
    /// classical coordinates). Where λ″ leaves the classical band (λ″ > λ1 off the plane,
    /// the wavelengths the classical table does not hold) the band's edge is read, the orders'
    /// cut-offs follow λ″ and the power of the orders cut off goes to the others in proportion
    /// (as the scalar model redistributes evanescent power): that part is an extrapolation. The
    /// cover's index is taken at the physical wavelength clamped to the band.
    ///
    /// # Errors
    ///
    /// - `table` ([`Requirement::Classical`]): `self` is conical already.
    /// - `cover_index` ([`Requirement::AtLeast`] 1): an index below 1 or not finite at a
    ///   wavelength of the band.
    /// - `abs_beta`: as [`new_reduced`](Self::new_reduced) (at least 2 planes, strictly
    ///   increasing in [0, 0.99999]); and ([`Requirement::AtMost`], the value the count) when
    ///   the table would hold more than [`MAX_TABLE_VALUES`] values per polarisation, checked
    ///   before anything is read. `lambda_nm` when a plane would need more than
    ///   [`MAX_TABLE_NODES`] wavelengths.
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::{Preset, REDUCED_PLANES};
    /// let foil = Preset::Foil.table();
    /// let t = foil.reduced_from_classical(&REDUCED_PLANES, |_| 1.0).unwrap();
    /// assert!(t.is_reduced());
    /// // On the plane across the grooves it is the classical table.
    /// let (a, b) = (t.efficiency_conical(1, 0.2, 0.0, 600.0), foil.efficiency(1, 0.2, 600.0));
    /// assert!((a.te - b.te).abs() < 1e-12);
    /// // Off it, a bare grating's efficiency at (α, β, λ) is the classical one at (α, λ)/c.
    /// let (alpha, beta) = (0.2, 0.6);
    /// let c = (1.0f64 - beta * beta).sqrt();
    /// let (a, b) = (
    ///     t.efficiency_conical(1, alpha, beta, 480.0),
    ///     foil.efficiency(1, alpha / c, 480.0 / c),
    /// );
    /// assert!((a.tm - b.tm).abs() < 1e-12);
    /// # }
    /// ```
    pub fn reduced_from_classical(
        &self,
        abs_beta: &[f64],
        cover_index: impl Fn(f64) -> f64,
    ) -> Result<EfficiencyTable, Error> {
        if self.is_conical() {
            let orders = self.order_count() as f64;
            return Err(Error::invalid("table", orders, Requirement::Classical));
        }
        check_axis("abs_beta", abs_beta, Some((0.0, MAX_TABLE_ABS_BETA)))?;
        let sin: Vec<f64> = self.sin_theta_i().collect();
        let lam: Vec<f64> = self.lambda_nm().collect();
        let band = (lam[0], lam[lam.len() - 1]);
        // The index, checked, at the physical wavelength clamped to the band.
        let index = |lambda_nm: f64| -> Result<f64, Error> {
            let n = cover_index(lambda_nm.clamp(band.0, band.1));
            if n.is_finite() && n >= 1.0 {
                Ok(n)
            } else {
                let requirement = Requirement::AtLeast {
                    bound_name: "1",
                    bound: 1.0,
                };
                Err(Error::invalid("cover_index", n, requirement))
            }
        };
        // c of the cover's medium at the physical wavelength λ on the plane |β| = b.
        let c_cover = |b: f64, lambda_nm: f64| -> Result<f64, Error> {
            let n = index(lambda_nm)?;
            Ok(math::sqrt(1.0 - (b / n) * (b / n)))
        };
        // The physical wavelength whose λ″ = λ/c_cover(λ) is `classical` (a fixed point: n
        // changes slowly with λ; exact in one step for a constant index).
        let physical = |b: f64, classical: f64| -> Result<f64, Error> {
            let mut l = classical * c_cover(b, classical)?;
            for _ in 0..4 {
                l = classical * c_cover(b, l)?;
            }
            Ok(l)
        };
        let mut grid = ReducedGrid {
            sin_theta_i: sin.clone(),
            abs_beta: abs_beta.to_vec(),
            lambda_range_nm: band,
            lambda_nm: Vec::new(),
        };
        // Each plane's classical wavelengths: the table's nodes, continued geometrically
        // beyond each end until the plane's physical nodes reach what its queries read.
        let mut classical_rows: Vec<Vec<f64>> = Vec::with_capacity(abs_beta.len());
        for p in 0..abs_beta.len() {
            let b = abs_beta[p];
            // Some: p is a plane.
            let (lo, hi) = super::reach(abs_beta, band, p).unwrap_or(band);
            let mut below = Vec::new();
            let mut l = band.0;
            while physical(b, l)? > lo * (1.0 - 1e-12) && below.len() < MAX_TABLE_NODES {
                l /= BEYOND_RATIO;
                below.push(l);
            }
            let mut nodes: Vec<f64> = below.into_iter().rev().collect();
            nodes.extend_from_slice(&lam);
            let mut l = band.1;
            while physical(b, l)? < hi * (1.0 + 1e-12) && nodes.len() < MAX_TABLE_NODES + 1 {
                l *= BEYOND_RATIO;
                nodes.push(l);
            }
            if nodes.len() > MAX_TABLE_NODES {
                let requirement = Requirement::PlaneNodes { plane: p };
                return Err(Error::invalid("lambda_nm", nodes.len() as f64, requirement));
            }
            let mut row = Vec::with_capacity(nodes.len());
            for &x in &nodes {
                row.push(physical(b, x)?);
            }
            grid.lambda_nm.push(row);
            classical_rows.push(nodes);
        }
        let (n_s, rows, orders) = (sin.len(), grid.rows(), self.order_count());
        // Bounded before anything is allocated or read (n_s, rows ≤ 4096·4097: no overflow).
        let slice = n_s * rows;
        if slice.saturating_mul(orders) > MAX_TABLE_VALUES {
            let requirement = Requirement::AtMost {
                bound_name: "MAX_TABLE_VALUES",
                bound: MAX_TABLE_VALUES as f64,
            };
            let values = slice as f64 * orders as f64;
            return Err(Error::invalid("abs_beta", values, requirement));
        }
        let mut te = alloc::vec![0.0; orders * slice];
        let mut tm = alloc::vec![0.0; orders * slice];
        let mut out = alloc::vec![Polarised::default(); orders];
        let d = self.period_nm;
        let mut row = 0;
        for (p, &b) in abs_beta.iter().enumerate() {
            let c = cb(b);
            for (&l, &classical) in grid.lambda_nm[p].iter().zip(&classical_rows[p]) {
                // λ″ = λ/c_cover is `classical` (to the fixed point's rounding); s″ = α/c_cover.
                let cc = c_cover(b, l)?;
                let n = index(l)?;
                let n2 = index(classical)?;
                for (i, &s) in sin.iter().enumerate() {
                    let alpha = s * c;
                    let sp = alpha / cc;
                    self.efficiencies(sp, classical, &mut out);
                    if classical > band.1 {
                        redistribute(&mut out, sp, classical / d, self.order_min);
                    }
                    // The interfaces' transmittances of the real path over the reduced
                    // problem's (1 for a bare grating): in at (α, β), out at (α_m, β).
                    let inc = interfaces(n, n2, alpha * alpha + b * b, alpha / cc);
                    let (mut sum_te, mut sum_tm) = (0.0, 0.0);
                    for (k, e) in out.iter().enumerate() {
                        // Evanescent in air at the node (new_reduced's test, the same
                        // arithmetic): 0, whatever the cover lets through.
                        let am = alpha + (f64::from(self.order_min) + k as f64) * l / d;
                        if 1.0 - am * am - b * b > 0.0 {
                            let out_ = interfaces(n, n2, am * am + b * b, am / cc);
                            let at = k * slice + row * n_s + i;
                            te[at] = e.te * inc.0 * out_.0;
                            tm[at] = e.tm * inc.1 * out_.1;
                            sum_te += te[at];
                            sum_tm += tm[at];
                        }
                    }
                    // A ratio above 1 (the real path nearer normal than the reduced one) may
                    // lift a sum above 1: scaled back to 1.
                    for (v, sum) in [(&mut te, sum_te), (&mut tm, sum_tm)] {
                        if sum > 1.0 {
                            for k in 0..orders {
                                v[k * slice + row * n_s + i] /= sum;
                            }
                        }
                    }
                }
                row += 1;
            }
        }
        EfficiencyTable::new_reduced(d, self.order_min, grid, te, tm)
    }
}

/// Past the classical band the table's edge was read at λ1, where more orders propagate than
/// at λ″: the power of the orders that do not propagate at (s″, λ″) goes to those that do, in
/// proportion (the scalar model's rule for evanescent power), per polarisation, so each sum
/// stays the edge's; the others are set to 0. `lambda_over_d` = λ″/d. Each kept value is
/// scaled as (η/Σ kept)·Σ all, both factors at most 1: finite whatever the sums' size.
fn redistribute(out: &mut [Polarised], sp: f64, lambda_over_d: f64, order_min: i32) {
    let kept_at = |k: usize| {
        let x = sp + (f64::from(order_min) + k as f64) * lambda_over_d;
        x * x < 1.0
    };
    let (mut all, mut kept) = ([0.0f64; 2], [0.0f64; 2]);
    for (k, e) in out.iter().enumerate() {
        all[0] += e.te;
        all[1] += e.tm;
        if kept_at(k) {
            kept[0] += e.te;
            kept[1] += e.tm;
        }
    }
    let scale = |x: f64, kept: f64, all: f64| if kept > 0.0 { x / kept * all } else { x };
    for (k, e) in out.iter_mut().enumerate() {
        if kept_at(k) {
            e.te = scale(e.te, kept[0], all[0]);
            e.tm = scale(e.tm, kept[1], all[1]);
        } else {
            *e = Polarised::default();
        }
    }
}

/// The ratio of the cover-air interface's unpolarised transmittance (T_s + T_p)/2 on the real
/// path (squared direction cosines `real2` = α² + β² in air, index `n`) to the reduced
/// problem's (sine `red` in air, index `n2`), for TE and TM alike: off the plane across the
/// grooves the interface's s and p are not the grating's TE and TM (measured: per
/// polarisation, T_s to TE and T_p to TM, put 78.8 % of the presets' conical orders within
/// 10 %; the unpolarised ratio 80.3 %, both before the redistribution past the band). 1 for a
/// bare grating.
fn interfaces(n: f64, n2: f64, real2: f64, red: f64) -> (f64, f64) {
    if n == 1.0 && n2 == 1.0 {
        return (1.0, 1.0);
    }
    let t = |n: f64, sin2: f64| {
        let ca = math::sqrt((1.0 - sin2).max(0.0));
        let cc = math::sqrt((1.0 - sin2 / (n * n)).max(0.0));
        let s = 4.0 * n * cc * ca / ((n * cc + ca) * (n * cc + ca));
        let p = 4.0 * n * cc * ca / ((cc + n * ca) * (cc + n * ca));
        (s, p)
    };
    let (a, b) = (t(n, real2), t(n2, red * red));
    let ratio = if b.0 + b.1 > 0.0 {
        (a.0 + a.1) / (b.0 + b.1)
    } else {
        0.0
    };
    (ratio, ratio)
}
