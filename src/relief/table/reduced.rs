//! Reduced conical tables (version 3, feature `alloc`): η_m on |β| planes, each plane a grid
//! in (s′, λ) with **its own wavelength nodes**, interpolated across |β| at fixed reduced
//! coordinates (s′, λ′) = (α, λ)/√(1 − β²) by the rule of `docs/efficiency_tables.md`
//! ("Reduced conical tables").
//!
//! Why: order m propagates iff (s′ + m·λ′/d)² < 1, so in (s′, λ′) the Rayleigh lines are the
//! classical ones whatever β, and so is cos θm/cos θi = √(1 − (s′ + m·λ′/d)²)/√(1 − s′²). For a
//! perfect conductor the conical problem *is* the classical one at (s′, λ′) (the unpolarised
//! efficiencies do not depend on β there); for a metal the rest of the β dependence goes through
//! c = √(1 − β²) alone in the conical-to-classical mapping (the metal's ε at λ = c·λ′ and
//! ε′ = 1 + (ε − 1)/c²), smoothly. So a query reads each of its two planes at the plane's own
//! physical wavelength λ_p = λ′·c_p and blends them linearly in c: no square-root onset or
//! plasmon dip moves across a cell between the planes, as it does at fixed λ (version 2).
//!
//! The cost is that a plane must hold the wavelengths its neighbours' queries map to:
//! plane p is read for the band [λ0, λ1] at λ·c_p/c with c between c_{p+1} and c_{p−1}, so it
//! must reach from λ0·c_p/c_{p−1} to λ1·c_p/c_{p+1} (checked on load): a ragged grid, each
//! plane with its own wavelength nodes.
//!
//! A query's cell is eight corners, four from each plane (the plane's cell around
//! (s′, λ_p)), with weights (1 − t)·(bilinear on plane p) and t·(bilinear on plane p + 1), t
//! linear in c; the rest (the corners' q = η·cos θi/cos θm, corner dropping, the exact cosines
//! at the query, the normalisation) is the rule of every table, through [`Cell3`]. Cells are
//! numbered per slab between two planes by i + (n_s − 1)·(j_p + j_{p+1}) (the two planes'
//! wavelength cells move together as λ′ grows, so their sum names the pair), for the
//! single-order reads' marks (`unit.rs`), whose cos θm/cos θi bound is taken over the cell's
//! box in (s′, λ′), where it does not depend on β.

#[cfg(feature = "std")]
use alloc::vec;
use alloc::vec::Vec;

use super::conical::Cell3;
use super::nodes_q::Computed;
use super::unit::Bits;
use super::{interval, EfficiencyTable, Polarised, Storage};
use crate::num::math;

/// The grid of a reduced conical table (version 3), for [`EfficiencyTable::new_reduced`]: the
/// s′ nodes shared by every plane, the |β| of each plane, the band of physical wavelengths the
/// table answers for, and each plane's own wavelength nodes.
///
/// ```
/// use diffraction::relief::ReducedGrid;
/// // Planes at |β| = 0 and 0.6 (c = 1 and 0.8) for the band 400-700 nm: the β = 0 plane is read
/// // up to 700/0.8 = 875 nm, the other one down to 400·0.8 = 320 nm.
/// let grid = ReducedGrid {
///     sin_theta_i: vec![-0.9, 0.0, 0.9],
///     abs_beta: vec![0.0, 0.6],
///     lambda_range_nm: (400.0, 700.0),
///     lambda_nm: vec![vec![400.0, 600.0, 875.0], vec![320.0, 500.0, 700.0]],
/// };
/// assert_eq!(grid.rows(), 6);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedGrid {
    /// The nodes of s′ = α/√(1 − β²), strictly increasing in [−1, 1], shared by every plane.
    pub sin_theta_i: Vec<f64>,
    /// The |β| of each plane, strictly increasing in [0, 0.99999] (at least 2 planes).
    pub abs_beta: Vec<f64>,
    /// The band [λ0, λ1] of physical wavelengths (nm) a query is clamped to.
    pub lambda_range_nm: (f64, f64),
    /// Each plane's wavelength nodes (physical, nm), strictly increasing: plane p must reach from
    /// λ0·c_p/c_{p−1} (λ0 for the first) to λ1·c_p/c_{p+1} (λ1 for the last), c = √(1 − β²).
    pub lambda_nm: Vec<Vec<f64>>,
}

impl ReducedGrid {
    /// The wavelength rows of every plane together.
    #[must_use]
    pub fn rows(&self) -> usize {
        self.lambda_nm.iter().map(Vec::len).sum()
    }

    /// The wavelengths plane `plane` must reach (nm): from λ0·c_p/c_{p−1} to λ1·c_p/c_{p+1}
    /// (λ0 for the first plane, λ1 for the last), c = √(1 − β²); `None` past the last plane.
    #[must_use]
    pub fn plane_reach_nm(&self, plane: usize) -> Option<(f64, f64)> {
        reach(&self.abs_beta, self.lambda_range_nm, plane)
    }
}

/// c = √(1 − β²), the factor between the physical and the reduced coordinates.
#[inline]
fn cb(b: f64) -> f64 {
    math::sqrt(1.0 - b * b)
}

/// (x − a)/(b − a) in [0, 1] for x between the nodes a and b, as a product by the interval's
/// stored reciprocal width `inv` (within an ulp of the quotient; it can pass 1 by an ulp at
/// the far node, hence the clamp), the quotient itself where that reciprocal overflowed (a
/// subnormal width, where the product would read a query on a node as the next node). A
/// width of 0 (planes coincident in c) has `inv` 0: the first node.
#[inline(always)]
fn fraction(x: f64, a: f64, b: f64, inv: f64) -> f64 {
    let t = if inv.is_finite() {
        (x - a) * inv
    } else {
        (x - a) / (b - a)
    };
    t.clamp(0.0, 1.0)
}

/// The wavelengths plane `p` of the planes `bet` must reach for the band `band`.
fn reach(bet: &[f64], band: (f64, f64), p: usize) -> Option<(f64, f64)> {
    let c = cb(*bet.get(p)?);
    let lo = if p > 0 {
        band.0 * (c / cb(bet[p - 1]))
    } else {
        band.0
    };
    let hi = match bet.get(p + 1) {
        Some(&b) => band.1 * (c / cb(b)),
        None => band.1,
    };
    Some((lo, hi))
}

/// A reduced conical table's arrays, borrowed.
pub(super) struct Reduced<'a> {
    sin: &'a [f64],
    bet: &'a [f64],
    lam: &'a [f64],
    rows: &'a [usize],
    band: (f64, f64),
    pub(super) te: &'a [f64],
    pub(super) tm: &'a [f64],
    loc: &'a Locator,
}

impl Reduced<'_> {
    /// Plane p's wavelength nodes.
    #[inline]
    fn plane(&self, p: usize) -> &[f64] {
        &self.lam[self.rows[p]..self.rows[p + 1]]
    }

    /// Values per order: n_s times the rows of every plane.
    #[inline]
    pub(super) fn slice(&self) -> usize {
        self.sin.len() * self.rows[self.bet.len()]
    }

    /// The number of the first cell of the slab between planes k and k + 1: slab k' has
    /// (n_s − 1)·(n_k' + n_k'+1 − 3) numbers (its pairs' sums j_k' + j_k'+1 run from 0 to
    /// n_k' + n_k'+1 − 4).
    #[inline]
    fn slab_offset(&self, k: usize) -> usize {
        let r = self.rows;
        (self.sin.len() - 1) * ((r[k] - r[0]) + (r[k + 1] - r[1]) - 3 * k)
    }

    /// The number of cells (the marks' length).
    #[cfg(feature = "std")]
    fn cell_count(&self) -> usize {
        self.slab_offset(self.bet.len() - 1)
    }

    /// The cell of the incidence (α, β) at λ (`None` for a non-finite query, α² + β² ≥ 1, or
    /// grazing incidence on the grid): s′, |β| and λ clamped to the axes and the band (the
    /// query is then the clamped point), λ′ = λ/c; plane p read at λ·c_p/c (clamped to its
    /// nodes, which only rounding can leave), the planes blended linearly in c. The corners'
    /// α, β², λ and cos θi are set only with `geometry` (the reads without the nodes' q's need
    /// them; the others leave them 0).
    #[inline(always)]
    pub(super) fn find(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
        geometry: bool,
    ) -> Option<Cell3> {
        if !(alpha.is_finite() && beta.is_finite() && lambda_nm.is_finite()) {
            return None;
        }
        let b0 = beta.abs();
        if alpha * alpha + b0 * b0 >= 1.0 {
            return None;
        }
        let (sin, bet, loc) = (self.sin, self.bet, self.loc);
        let (n_s, n_b) = (sin.len(), bet.len());
        let s0 = alpha / cb(b0);
        let sp = s0.max(sin[0]).min(sin[n_s - 1]);
        let b = b0.max(bet[0]).min(bet[n_b - 1]);
        let lambda_nm = lambda_nm.max(self.band.0).min(self.band.1);
        let c = cb(b);
        // cos θi = c·√(1 − s′²); where nothing was clamped that is √(1 − β² − α²), which does
        // not wait for the division (the chain a query's reads start from).
        let cos_i = if sp == s0 && b == b0 {
            math::sqrt((1.0 - b * b) - alpha * alpha)
        } else {
            c * math::sqrt(1.0 - sp * sp)
        };
        if cos_i.is_nan() || cos_i <= 0.0 {
            return None;
        }
        let i = loc.sin.interval(sin, sp);
        let k = loc.bet.interval(bet, b);
        let cp = [loc.c[k], loc.c[k + 1]];
        let tb = fraction(c, cp[0], cp[1], loc.inv_dc[k]);
        let tx = fraction(sp, sin[i], sin[i + 1], loc.inv_ds[i]);
        let (mut row, mut ty) = ([0usize; 2], [0.0f64; 2]);
        for d in 0..2 {
            let first = self.rows[k + d];
            let nodes = &self.lam[first..self.rows[k + d + 1]];
            let l = (lambda_nm * (cp[d] / c))
                .max(nodes[0])
                .min(nodes[nodes.len() - 1]);
            let j = loc.planes[k + d].interval(nodes, l);
            row[d] = first + j;
            ty[d] = fraction(l, nodes[j], nodes[j + 1], loc.inv_dl[first + j]);
        }
        // j_k + j_{k+1}, the pair's number in its slab.
        let pair = row[0] + row[1] - self.rows[k] - self.rows[k + 1];
        let cell_index = self.slab_offset(k) + pair * (n_s - 1) + i;
        let mut cell = Cell3::empty(sp * c, b * b, lambda_nm, cos_i, cell_index);
        let wt = |d: usize, t: f64| if d == 1 { t } else { 1.0 - t };
        for n in 0..8 {
            let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
            cell.w[n] = wt(di, tx) * wt(dk, tb) * wt(dj, ty[dk]);
            cell.index[n] = (row[dk] + dj) * n_s + i + di;
        }
        if geometry {
            // The two s′ nodes' √(1 − s′²), shared by the planes' corners.
            let root = [loc.root[i], loc.root[i + 1]];
            for n in 0..8 {
                let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
                let b_n = bet[k + dk];
                cell.a_c[n] = sin[i + di] * cp[dk];
                cell.b2_c[n] = b_n * b_n;
                cell.l_c[n] = self.lam[row[dk] + dj];
                cell.cos_c[n] = cp[dk] * root[di];
            }
        }
        Some(cell)
    }
}

impl Reduced<'_> {
    /// The cell of plane `p` alone at s′ = `sp` and its own physical wavelength `lambda_nm`
    /// (both clamped to the plane's axes; the query is then the clamped point): the eight
    /// corners of [`find`](Self::find) with the other plane's weights 0. `None` for a non-finite
    /// query or grazing incidence on the grid.
    fn find_plane(&self, p: usize, sp: f64, lambda_nm: f64) -> Option<Cell3> {
        if !(sp.is_finite() && lambda_nm.is_finite()) || p >= self.bet.len() {
            return None;
        }
        let (sin, n_s) = (self.sin, self.sin.len());
        let sp = sp.max(sin[0]).min(sin[n_s - 1]);
        let c = cb(self.bet[p]);
        let cos_i = c * math::sqrt(1.0 - sp * sp);
        if cos_i.is_nan() || cos_i <= 0.0 {
            return None;
        }
        let nodes = self.plane(p);
        let l = lambda_nm.max(nodes[0]).min(nodes[nodes.len() - 1]);
        let (i, j) = (interval(sin, sp), interval(nodes, l));
        let tx = (sp - sin[i]) / (sin[i + 1] - sin[i]);
        let ty = (l - nodes[j]) / (nodes[j + 1] - nodes[j]);
        let b = self.bet[p];
        let mut cell = Cell3::empty(sp * c, b * b, l, cos_i, 0);
        let wt = |d: usize, t: f64| if d == 1 { t } else { 1.0 - t };
        for n in 0..8 {
            let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
            // Corners 0..4 (dk = 0) are the plane's; the others repeat them with weight 0.
            cell.w[n] = if dk == 0 {
                wt(di, tx) * wt(dj, ty)
            } else {
                0.0
            };
            let s_n = sin[i + di];
            cell.a_c[n] = s_n * c;
            cell.b2_c[n] = b * b;
            cell.l_c[n] = nodes[j + dj];
            cell.cos_c[n] = c * math::sqrt(1.0 - s_n * s_n);
            cell.index[n] = (self.rows[p] + j + dj) * n_s + i + di;
        }
        Some(cell)
    }
}

impl EfficiencyTable {
    /// Every stored order's efficiencies of plane `plane` of a reduced conical table read
    /// alone (feature `alloc`), at s′ = `sin_theta_i` and the plane's own physical wavelength
    /// `lambda_nm`, each clamped to the plane's nodes: the rule of
    /// [`efficiencies_conical`](Self::efficiencies_conical) on that plane's corners only, with
    /// its normalisation, written to `out` as there; returns the unpolarised sum. A query of
    /// the table reads a plane at wavelengths beyond the band (its neighbours' queries), which
    /// this reaches directly (the table builder checks a plane's interpolation with it). 0
    /// (and `out` zeroed) for any other table, a plane past the last, or a non-finite query.
    ///
    /// ```
    /// use diffraction::relief::{EfficiencyTable, Polarised, ReducedGrid};
    /// let grid = ReducedGrid {
    ///     sin_theta_i: vec![-0.5, 0.5],
    ///     abs_beta: vec![0.0, 0.6],
    ///     lambda_range_nm: (400.0, 700.0),
    ///     lambda_nm: vec![vec![400.0, 875.0], vec![320.0, 700.0]],
    /// };
    /// let te = vec![0.9, 0.9, 0.9, 0.9, 0.5, 0.5, 0.5, 0.5];
    /// let t = EfficiencyTable::new_reduced(1000.0, 0, grid, te.clone(), te)?;
    /// let mut out = [Polarised::default(); 1];
    /// // The β = 0 plane at 850 nm, past the band: its own value.
    /// t.plane_efficiencies(0, 0.2, 850.0, &mut out);
    /// assert!((out[0].te - 0.9).abs() < 1e-12);
    /// t.plane_efficiencies(1, 0.2, 330.0, &mut out);
    /// assert!((out[0].te - 0.5).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn plane_efficiencies(
        &self,
        plane: usize,
        sin_theta_i: f64,
        lambda_nm: f64,
        out: &mut [Polarised],
    ) -> f64 {
        for o in out.iter_mut() {
            *o = Polarised::default();
        }
        let Some(r) = self.reduced() else {
            return 0.0;
        };
        let Some(cell) = r.find_plane(plane, sin_theta_i, lambda_nm) else {
            return 0.0;
        };
        let q = self.q.get(|| self.reduced_q(&r));
        let first = self.order_min;
        let (st, sm) = self.sum_cell(&cell, r.slice(), (r.te, r.tm), q, |m, e| {
            if let Some(o) = out.get_mut((m - first) as usize) {
                *o = e;
            }
        });
        let (kt, km) = (super::scale(st), super::scale(sm));
        for o in out.iter_mut() {
            o.te *= kt;
            o.tm *= km;
        }
        0.5 * (st * kt + sm * km)
    }

    /// The arrays of a reduced conical table, `None` for any other.
    pub(super) fn reduced(&self) -> Option<Reduced<'_>> {
        match &self.storage {
            Storage::Reduced {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                rows,
                band,
                te,
                tm,
                locator,
            } => Some(Reduced {
                sin: sin_theta_i,
                bet: abs_beta,
                lam: lambda_nm,
                rows,
                band: *band,
                te,
                tm,
                loc: locator,
            }),
            _ => None,
        }
    }

    /// Whether the table is a reduced conical table (version 3, feature `alloc`): its |β|
    /// planes each have their own wavelength nodes ([`plane_lambda_nm`](Self::plane_lambda_nm))
    /// and are blended at fixed reduced coordinates (`docs/efficiency_tables.md`, "Reduced
    /// conical tables"). Such a table [`is_conical`](Self::is_conical) too.
    #[must_use]
    pub fn is_reduced(&self) -> bool {
        self.reduced().is_some()
    }

    /// Plane `plane`'s wavelength nodes (nm, feature `alloc`): a reduced conical table's own
    /// for each plane; every plane of a classical (one plane) or version-2 conical table has
    /// [`lambda_nm`](Self::lambda_nm). Empty past the last plane.
    ///
    /// ```
    /// use diffraction::relief::{EfficiencyTable, ReducedGrid};
    /// let grid = ReducedGrid {
    ///     sin_theta_i: vec![-0.5, 0.5],
    ///     abs_beta: vec![0.0, 0.6],
    ///     lambda_range_nm: (400.0, 700.0),
    ///     lambda_nm: vec![vec![400.0, 875.0], vec![320.0, 700.0]],
    /// };
    /// // One order (0), η = 0.9 (TE) and 0.8 (TM) at every node.
    /// let t = EfficiencyTable::new_reduced(1000.0, 0, grid, vec![0.9; 8], vec![0.8; 8])?;
    /// assert!(t.is_reduced() && t.is_conical());
    /// assert_eq!(t.plane_lambda_nm(1).collect::<Vec<_>>(), [320.0, 700.0]);
    /// assert_eq!(t.lambda_range_nm(), (400.0, 700.0));
    /// assert!((t.efficiency_conical(0, 0.1, 0.3, 550.0).tm - 0.8).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn plane_lambda_nm(&self, plane: usize) -> impl ExactSizeIterator<Item = f64> + '_ {
        let planes = self.abs_beta().len().max(1);
        let nodes: Vec<f64> = match self.reduced() {
            Some(r) if plane < planes => r.plane(plane).to_vec(),
            None if plane < planes => self.lambda_nm().collect(),
            _ => Vec::new(),
        };
        nodes.into_iter()
    }

    /// The band of physical wavelengths (nm) the table answers for, a query's λ being clamped
    /// to it: a reduced conical table's `lambda_range_nm`, else the first and last wavelength
    /// nodes.
    #[must_use]
    pub fn lambda_range_nm(&self) -> (f64, f64) {
        match self.reduced() {
            Some(r) => r.band,
            None => {
                let mut l = self.lambda_nm();
                let first = l.next().unwrap_or(0.0);
                (first, l.last().unwrap_or(first))
            }
        }
    }

    /// Every stored order of a reduced table at (α, β, λ) through `f`, and the TE and TM sums.
    pub(super) fn each_reduced(
        &self,
        r: &Reduced<'_>,
        (alpha, beta, lambda_nm): (f64, f64, f64),
        f: impl FnMut(i32, Polarised),
    ) -> (f64, f64) {
        let q = self.q.get(|| self.reduced_q(r));
        match r.find(alpha, beta, lambda_nm, q.is_none()) {
            Some(cell) => self.sum_cell(&cell, r.slice(), (r.te, r.tm), q, f),
            None => (0.0, 0.0),
        }
    }

    /// One stored order of a reduced table at (α, β, λ), normalised.
    pub(super) fn one_reduced(
        &self,
        r: &Reduced<'_>,
        order: i32,
        (alpha, beta, lambda_nm): (f64, f64, f64),
    ) -> Polarised {
        let q = self.q.get(|| self.reduced_q(r));
        match r.find(alpha, beta, lambda_nm, q.is_none()) {
            Some(cell) => {
                let marks = || self.reduced_marks(r);
                self.one_cell(&cell, order, r.slice(), (r.te, r.tm), q, marks)
            }
            None => Polarised::default(),
        }
    }

    /// The stored efficiencies of order `order` at node (λ row `j`, s′ node `i`) of a reduced
    /// table's first plane, scaled down with the node's other orders where their sum exceeds 1
    /// (what a query at that node of the plane alone gives): the GPU's classical reading of
    /// the first plane. 0 for any other table or index.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub(crate) fn first_plane_node(&self, order: i32, j: usize, i: usize) -> Polarised {
        let Some(r) = self.reduced() else {
            return Polarised::default();
        };
        let n_s = r.sin.len();
        if i >= n_s || j >= r.rows[1] || !self.orders().contains(&order) {
            return Polarised::default();
        }
        let (slice, at) = (r.slice(), j * n_s + i);
        let (mut st, mut sm) = (0.0, 0.0);
        for k in 0..self.order_count {
            st += r.te[k * slice + at];
            sm += r.tm[k * slice + at];
        }
        let k = (i64::from(order) - i64::from(self.order_min)) as usize;
        Polarised {
            te: r.te[k * slice + at] * super::scale(st),
            tm: r.tm[k * slice + at] * super::scale(sm),
        }
    }

    /// The nodes' q's of a reduced table (`nodes_q.rs`), with the corner formulas of
    /// [`Reduced::find`]; `None` without `std` or past `MAX_Q_VALUES` values.
    fn reduced_q(&self, r: &Reduced<'_>) -> Computed {
        #[cfg(feature = "std")]
        {
            if r.slice() * self.order_count > super::nodes_q::MAX_Q_VALUES {
                return None;
            }
            let mut q = Vec::with_capacity(r.slice() * self.order_count);
            self.each_node_q(r, |v| q.push(v));
            Some(q)
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = r;
            None
        }
    }

    /// Every node's (q_TE, q_TM) in the values' order (order k, row, s′ node), or
    /// `NOT_PROPAGATING` twice where the order does not propagate there: `corner_q` at the
    /// node's conical incidence (α = s′·c_p, β_p, the row's wavelength), the corner formulas
    /// of [`Reduced::find`].
    #[cfg_attr(not(any(feature = "std", feature = "gpu")), allow(dead_code))]
    fn each_node_q(&self, r: &Reduced<'_>, mut f: impl FnMut([f64; 2])) {
        let (n_s, slice) = (r.sin.len(), r.slice());
        for k in 0..self.order_count {
            let mf = f64::from(self.order_min) + k as f64;
            for (p, &bn) in r.bet.iter().enumerate() {
                let (b2, cp) = (bn * bn, cb(bn));
                for (j, &l) in r.plane(p).iter().enumerate() {
                    for (i, &sn) in r.sin.iter().enumerate() {
                        let at = k * slice + (r.rows[p] + j) * n_s + i;
                        let cos_i = cp * math::sqrt(1.0 - sn * sn);
                        let v = (r.te, r.tm);
                        f(super::corner_q(
                            sn * cp,
                            b2,
                            l,
                            cos_i,
                            mf,
                            self.period_nm,
                            v,
                            at,
                        ));
                    }
                }
            }
        }
    }

    /// The marks of a reduced table's cells (`unit.rs`): cell c is marked where its bound
    /// ([`reduced_bounds`](Self::reduced_bounds)) is at most `UNIT_BOUND` for TE and TM.
    fn reduced_marks(&self, r: &Reduced<'_>) -> Bits {
        #[cfg(feature = "std")]
        {
            use super::unit::{MAX_MARKED_VALUES, UNIT_BOUND};
            let cells = r.cell_count();
            let mut bits = vec![0u64; cells.div_ceil(64)];
            if r.slice() * self.order_count > MAX_MARKED_VALUES {
                return Bits(bits);
            }
            for (c, &b) in self.reduced_bounds(r).iter().enumerate() {
                if b <= UNIT_BOUND {
                    bits[c / 64] |= 1 << (c % 64);
                }
            }
            Bits(bits)
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = r;
            Bits()
        }
    }

    /// Every cell's bound of Σ_m η_m over its queries, the larger of TE's and TM's (`unit.rs`;
    /// ∞ for a number no query reaches): for each slab, each pair of the two planes'
    /// wavelength cells whose reduced ranges λ/c_p overlap (to a relative 10⁻⁹) inside the
    /// slab's queries, and each s′ cell, the bound of the eight corners with cos θm/cos θi
    /// bounded over the (s′, λ′) box. A number two pairs share (only where both planes' nodes
    /// meet at one λ′) takes the larger bound.
    #[cfg(feature = "std")]
    fn reduced_bounds(&self, r: &Reduced<'_>) -> Vec<f64> {
        use super::unit::{bound_with, ratio_bound, Corner};
        const EPS: f64 = 1e-9;
        let (slice, d) = (r.slice(), self.period_nm);
        let mut bounds = vec![f64::NEG_INFINITY; r.cell_count()];
        let (n_s, sin) = (r.sin.len(), r.sin);
        for k in 0..r.bet.len() - 1 {
            let cp = [cb(r.bet[k]), cb(r.bet[k + 1])];
            let (lo, hi) = (r.band.0 / cp[0], r.band.1 / cp[1]);
            let red = |p: usize, j: usize| r.plane(k + p)[j] / cp[p];
            let (na, nb) = (r.plane(k).len(), r.plane(k + 1).len());
            let mut start = 0;
            for ja in 0..na - 1 {
                let (a0, a1) = (red(0, ja), red(0, ja + 1));
                while start + 1 < nb - 1 && red(1, start + 1) < a0 * (1.0 - EPS) {
                    start += 1;
                }
                for jb in start..nb - 1 {
                    let (b0, b1) = (red(1, jb), red(1, jb + 1));
                    if b0 > a1 * (1.0 + EPS) {
                        break;
                    }
                    let (l0, l1) = (a0.max(b0).max(lo), a1.min(b1).min(hi));
                    if l0 > l1 * (1.0 + EPS) {
                        continue;
                    }
                    let (l0, l1) = (l0.min(l1) * (1.0 - EPS), l0.max(l1) * (1.0 + EPS));
                    for i in 0..n_s - 1 {
                        let mut c = [Corner::default(); 8];
                        for (n, corner) in c.iter_mut().enumerate() {
                            let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
                            let s = sin[i + di];
                            let (b, j) = (r.bet[k + dk], [ja, jb][dk] + dj);
                            *corner = Corner {
                                s,
                                b,
                                alpha: s * cp[dk],
                                beta2: b * b,
                                lambda_nm: r.plane(k + dk)[j],
                                cos_i: cp[dk] * math::sqrt(1.0 - s * s),
                                index: (r.rows[k + dk] + j) * n_s + i + di,
                            };
                        }
                        // The box in (s′, λ′) as a classical cell's corners.
                        let mut boxed = [Corner::default(); 4];
                        for (n, corner) in boxed.iter_mut().enumerate() {
                            corner.s = sin[i + (n & 1)];
                            corner.lambda_nm = if n < 2 { l0 } else { l1 };
                        }
                        let (first, count) = (self.order_min, self.order_count);
                        let ratio = |mf: f64| ratio_bound(d, mf, &boxed);
                        let (bt, bm) = bound_with(d, first, count, slice, &c, (r.te, r.tm), ratio);
                        let at = r.slab_offset(k) + (ja + jb) * (n_s - 1) + i;
                        bounds[at] = bounds[at].max(bt.max(bm));
                    }
                }
            }
        }
        for b in &mut bounds {
            if *b == f64::NEG_INFINITY {
                *b = f64::INFINITY;
            }
        }
        bounds
    }
}

mod from_classical;
#[cfg(feature = "gpu")]
mod gpu;
mod locate;
mod new;

#[cfg(feature = "gpu")]
pub(crate) use gpu::ReducedParts;
pub(super) use locate::Locator;

pub use from_classical::REDUCED_PLANES;

#[cfg(all(test, feature = "std"))]
mod tests {
    use std::vec::Vec;

    use super::{reach, EfficiencyTable, ReducedGrid};

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A random reduced table: 2-4 planes, each with its own 3-6 wavelength nodes reaching a
    /// little past what it must, node sums random in [`low`, 1] (TE) and [0.97, 1] (TM), or
    /// both in [0.3, 0.7] for `low` = 0 (cells that need no normalisation).
    fn random_reduced(next: &mut impl FnMut() -> f64, low: f64) -> EfficiencyTable {
        let d = 900.0 + 800.0 * next();
        let (orders, first) = (5usize, -2i32);
        let n_s = 4 + (4.0 * next()) as usize;
        let s: Vec<f64> = (0..n_s)
            .map(|i| -0.99 + 1.98 * (i as f64 + 0.3 * next()) / (n_s - 1) as f64)
            .map(|x: f64| x.min(0.999))
            .collect();
        let n_b = 2 + (3.0 * next()) as usize;
        let mut b = vec![if next() < 0.5 { 0.0 } else { 0.3 * next() }];
        while b.len() < n_b {
            let last = b[b.len() - 1];
            b.push((last + 0.1 + 0.25 * next()).min(0.95 + 0.01 * b.len() as f64));
        }
        let l0 = 380.0 + 40.0 * next();
        let band = (l0, l0 + 200.0 + 200.0 * next());
        let planes: Vec<Vec<f64>> = (0..n_b)
            .map(|p| {
                let (lo, hi) = reach(&b, band, p).unwrap();
                let (lo, hi) = (lo * (1.0 - 0.05 * next()), hi * (1.0 + 0.05 * next()));
                let n_l = 3 + (4.0 * next()) as usize;
                (0..n_l)
                    .map(|j| {
                        let jitter = if j == 0 || j == n_l - 1 {
                            0.0
                        } else {
                            0.3 * next()
                        };
                        lo + (hi - lo) * (j as f64 + jitter) / (n_l - 1) as f64
                    })
                    .collect()
            })
            .collect();
        let grid = ReducedGrid {
            sin_theta_i: s,
            abs_beta: b,
            lambda_range_nm: band,
            lambda_nm: planes,
        };
        let slice = n_s * grid.rows();
        let (mut te, mut tm) = (vec![0.0; orders * slice], vec![0.0; orders * slice]);
        let mut row = 0;
        for (&beta, nodes) in grid.abs_beta.iter().zip(&grid.lambda_nm) {
            let c = (1.0 - beta * beta).sqrt();
            for &lam in nodes {
                for (i, &x) in grid.sin_theta_i.iter().enumerate() {
                    let at = row * n_s + i;
                    let mut raw = vec![(0.0, 0.0); orders];
                    let (mut st, mut sm) = (0.0, 0.0);
                    for (k, r) in raw.iter_mut().enumerate() {
                        let am = x * c + f64::from(first + k as i32) * lam / d;
                        if 1.0 - am * am - beta * beta > 0.0 {
                            *r = (next(), next());
                            st += r.0;
                            sm += r.1;
                        }
                    }
                    let (gt, gm) = if low > 0.0 {
                        (low + (1.0 - low) * next(), 0.97 + 0.03 * next())
                    } else {
                        (0.3 + 0.4 * next(), 0.3 + 0.4 * next())
                    };
                    for (k, r) in raw.iter().enumerate() {
                        if st > 0.0 {
                            te[k * slice + at] = r.0 / st * gt;
                        }
                        if sm > 0.0 {
                            tm[k * slice + at] = r.1 / sm * gm;
                        }
                    }
                }
                row += 1;
            }
        }
        EfficiencyTable::new_reduced(d, first, grid, te, tm).unwrap()
    }

    /// No query's sum over orders (before the normalisation) exceeds its cell's bound, on
    /// random reduced tables with node sums close to 1; some cells are marked and some not.
    #[test]
    fn reduced_cell_bounds_hold() {
        let mut next = rng(5);
        let (mut worst, mut marked, mut cells, mut queries) = (0.0f64, 0usize, 0usize, 0usize);
        for n in 0..60 {
            let t = random_reduced(&mut next, if n % 2 == 0 { 0.9 } else { 0.0 });
            let r = t.reduced().unwrap();
            let bounds = t.reduced_bounds(&r);
            cells += bounds.len();
            marked += bounds
                .iter()
                .filter(|&&b| b <= super::super::unit::UNIT_BOUND)
                .count();
            let (l0, l1) = r.band;
            for q in 0..400 {
                let wide = if q % 10 == 0 { 60.0 } else { 0.0 };
                let lam = l0 - wide + (l1 - l0 + 2.0 * wide) * next();
                let beta = 0.99 * next();
                let alpha = (1.0 - beta * beta).sqrt() * (-1.0 + 2.0 * next());
                let Some(cell) = r.find(alpha, beta, lam, false) else {
                    continue;
                };
                let (st, sm) = t.each_reduced(&r, (alpha, beta, lam), |_, _| {});
                let b = bounds[cell.cell];
                if st.max(sm) > 0.0 {
                    worst = worst.max(st.max(sm) / b);
                    queries += 1;
                }
            }
        }
        std::println!("{marked} of {cells} cells marked; {queries} queries, sum/bound <= {worst}");
        assert!(worst <= 1.0 + 1e-12, "{worst}");
        assert!(marked > 0 && marked < cells, "{marked} of {cells}");
        assert!(queries > 10_000, "{queries}");
    }
}
