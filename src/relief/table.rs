//! Tabulated order efficiencies: η_m on a grid in (sin θi, λ), interpolated by the rule of
//! `docs/efficiency_tables.md`, with the crate's rigorous presets as static tables.

use core::ops::RangeInclusive;

#[cfg(feature = "alloc")]
use alloc::vec::Vec;

use super::scalar::Polarised;
use crate::num::math;

/// Runs `$body` with `$sin, $bet, $lam, $te, $tm` bound to the table's axes and values (f32 or
/// f64 slices), once per storage type.
macro_rules! with_arrays {
    ($table:expr, |$sin:ident, $bet:ident, $lam:ident, $te:ident, $tm:ident| $body:expr) => {
        match &$table.storage {
            Storage::Static {
                sin_theta_i: $sin,
                abs_beta: $bet,
                lambda_nm: $lam,
                te: $te,
                tm: $tm,
            } => {
                let ($sin, $bet, $lam, $te, $tm): (&[f32], &[f32], &[f32], &[f32], &[f32]) =
                    (*$sin, *$bet, *$lam, *$te, *$tm);
                $body
            }
            // A reduced conical table binds its concatenated wavelength rows: the functions
            // that interpolate branch to `reduced.rs` before this (its rows are per plane); the
            // others read values by flat index.
            #[cfg(feature = "alloc")]
            Storage::Owned {
                sin_theta_i: $sin,
                abs_beta: $bet,
                lambda_nm: $lam,
                te: $te,
                tm: $tm,
            }
            | Storage::Reduced {
                sin_theta_i: $sin,
                abs_beta: $bet,
                lambda_nm: $lam,
                te: $te,
                tm: $tm,
                ..
            } => {
                let ($sin, $bet, $lam, $te, $tm): (&[f64], &[f64], &[f64], &[f64], &[f64]) = (
                    $sin.as_slice(),
                    $bet.as_slice(),
                    $lam.as_slice(),
                    $te.as_slice(),
                    $tm.as_slice(),
                );
                $body
            }
        }
    };
}

mod conical;
#[cfg(feature = "alloc")]
mod load;
mod lookup;
mod nodes_q;
#[cfg(feature = "presets")]
mod preset;
mod proposal;
#[cfg(feature = "alloc")]
mod reduced;
mod unit;

use lookup::Lookup;
use nodes_q::NodeQ;

pub(crate) use lookup::{FastProposal, Incidences};
pub(crate) use proposal::CellProposal;
#[cfg(all(feature = "alloc", feature = "gpu"))]
pub(crate) use reduced::ReducedParts;

use unit::UnitCells;

pub use conical::MAX_TABLE_ABS_BETA;
#[cfg(feature = "presets")]
pub use preset::Preset;

#[cfg(feature = "alloc")]
pub use load::{MAX_TABLE_NODES, MAX_TABLE_ORDERS, MAX_TABLE_VALUES};
#[cfg(feature = "alloc")]
pub use reduced::{ReducedGrid, REDUCED_PLANES};

/// A corner of the interpolation cell closer than this to its order's Rayleigh line
/// (cos² θm ≤ 10⁻⁶, cos θm ≤ 10⁻³) counts as evanescent: there η and cos θm are both tiny and
/// their ratio is rounding (`docs/efficiency_tables.md`, "Interpolation", step 4).
const GRAZING_CORNER: f64 = 1e-6;

/// Order efficiencies η_m (TE and TM) of a grating on a grid of (sin θi, λ) nodes, the crate's
/// tabulated efficiency model (`docs/efficiency_tables.md`).
///
/// A table holds the grating's period, the consecutive orders `order_min ..= order_max` and, for
/// each, TE and TM efficiencies at every node. The four rigorous presets ([`Preset`]) are static
/// data (no allocation); user tables come from [`EfficiencyTable::new`], from a JSON file
/// (`serde` and `alloc`: `Deserialize`) or from the scalar model
/// ([`EfficiencyTable::from_scalar`]), all checked on load.
///
/// Queries follow the documented rule: s = sin θi and λ clamped to the grid; 0 where the order
/// is evanescent (|s + m·λ/d| ≥ 1) or not stored; otherwise q = η·cos θi/cos θm is bilinearly
/// interpolated over the cell's corners where the order propagates and η = q·cos θm/cos θi at
/// the query, so each order appears exactly on its Rayleigh line with its square-root onset.
/// Then, **per polarisation**, if the sum over the stored orders at the query exceeds 1 (bilinear
/// interpolation can overshoot between nodes) every order is scaled by 1/Σ: Σ_m η_m ≤ 1 holds
/// for TE and for TM (and so for unpolarised light) at every query.
///
/// ```
/// # #[cfg(feature = "presets")] {
/// use diffraction::relief::Preset;
/// let cd = Preset::Cd.table();
/// assert_eq!(cd.orders(), -8..=8);
/// let first = cd.efficiency(1, 0.0, 550.0);
/// assert!(first.te > 0.0 && first.tm > 0.0);
/// // Order 3 at normal incidence: sin θ3 = 3·550/1600 > 1, evanescent.
/// assert_eq!(cd.efficiency(3, 0.0, 550.0).te, 0.0);
/// # }
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct EfficiencyTable {
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    storage: Storage,
    /// The cells whose queries need no normalisation (`unit.rs`), computed on first use.
    unit: UnitCells,
    /// The nodes' q's (`nodes_q.rs`), computed on first use.
    q: NodeQ,
    /// The fast reading of a classical table (`lookup.rs`), derived on first use.
    lookup: Lookup,
}

/// The nodes and values: static f32 data of the presets, or owned f64 data of user tables.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(not(feature = "presets"), allow(dead_code))]
enum Storage {
    Static {
        sin_theta_i: &'static [f32],
        /// The |β| nodes of a conical table; empty for a classical (2-D) table.
        abs_beta: &'static [f32],
        lambda_nm: &'static [f32],
        te: &'static [f32],
        tm: &'static [f32],
    },
    #[cfg(feature = "alloc")]
    Owned {
        sin_theta_i: Vec<f64>,
        /// The |β| nodes of a conical table; empty for a classical (2-D) table.
        abs_beta: Vec<f64>,
        lambda_nm: Vec<f64>,
        te: Vec<f64>,
        tm: Vec<f64>,
    },
    /// A reduced conical table (version 3, `reduced.rs`): every |β| plane has its own
    /// wavelength nodes, concatenated in `lambda_nm` (plane p's are `rows[p]..rows[p + 1]`),
    /// and the values are flattened `[order][plane][λ of the plane][s′]`.
    #[cfg(feature = "alloc")]
    Reduced {
        sin_theta_i: Vec<f64>,
        abs_beta: Vec<f64>,
        lambda_nm: Vec<f64>,
        /// Plane p's wavelength nodes start at `rows[p]` (n_β + 1 entries, the last the total).
        rows: Vec<usize>,
        /// The band [λ0, λ1] queries are clamped to, nm.
        band: (f64, f64),
        te: Vec<f64>,
        tm: Vec<f64>,
        /// The cell's location in O(1) (`reduced/locate.rs`), derived from the grid (boxed:
        /// the variants stay of similar size).
        locator: alloc::boxed::Box<reduced::Locator>,
    },
}

/// Read access to one axis or value array, f32 or f64, as f64.
trait Values {
    fn at(&self, i: usize) -> f64;
    fn count(&self) -> usize;
}

impl Values for [f32] {
    #[inline]
    fn at(&self, i: usize) -> f64 {
        f64::from(self[i])
    }
    fn count(&self) -> usize {
        self.len()
    }
}

impl Values for [f64] {
    #[inline]
    fn at(&self, i: usize) -> f64 {
        self[i]
    }
    fn count(&self) -> usize {
        self.len()
    }
}

/// One query's interpolation cell, shared by every order.
struct Cell {
    s: f64,
    lambda_nm: f64,
    cos_i: f64,
    /// Per corner: bilinear weight, s and λ of the node, flat index j·n_s + i.
    w: [f64; 4],
    s_c: [f64; 4],
    l_c: [f64; 4],
    index: [usize; 4],
    /// The cell's index j·(n_s − 1) + i, for [`UnitCells`].
    cell: usize,
}

/// One query's interpolation cell, classical ([`Cell`]) or conical (`Cell3`).
trait OrderCell {
    /// Order m's interpolated efficiencies before the normalisation, reading the order's slice
    /// starting at `base` of `te` and `tm` (or of the nodes' q's `q`, where kept).
    fn order<T: Values + ?Sized>(
        &self,
        period_nm: f64,
        m: i32,
        base: usize,
        values: (&T, &T),
        q: Option<&[[f64; 2]]>,
    ) -> Polarised;
    /// The cell's index among the table's cells.
    fn index(&self) -> usize;
    /// Whether order m propagates at the query: the test by which [`order`](Self::order)
    /// returns 0 before reading any corner, with its operations.
    fn propagates(&self, period_nm: f64, m: i32) -> bool;
    /// The corners' interpolation weights and flat indices in an order's slice.
    fn corners(&self) -> (&[f64], &[usize]);
}

impl OrderCell for Cell {
    #[inline]
    fn order<T: Values + ?Sized>(
        &self,
        period_nm: f64,
        m: i32,
        base: usize,
        (te, tm): (&T, &T),
        q: Option<&[[f64; 2]]>,
    ) -> Polarised {
        let mf = f64::from(m);
        let sm = self.s + mf * self.lambda_nm / period_nm;
        if sm.abs() >= 1.0 {
            return Polarised::default();
        }
        // The corners where the order propagates, with their bilinear weights and
        // q = η·cos θi,c/cos θm,c.
        let mut w = [0.0f64; 4];
        let mut qc = [[0.0f64; 2]; 4];
        for c in 0..4 {
            if self.w[c] <= 0.0 {
                continue;
            }
            let at = base + self.index[c];
            let value = match q {
                Some(q) => q[at],
                None => {
                    let cos_c = math::sqrt(1.0 - self.s_c[c] * self.s_c[c]);
                    corner_q(
                        self.s_c[c],
                        0.0,
                        self.l_c[c],
                        cos_c,
                        mf,
                        period_nm,
                        (te, tm),
                        at,
                    )
                }
            };
            if value[0] != nodes_q::NOT_PROPAGATING {
                w[c] = self.w[c];
                qc[c] = value;
            }
        }
        let Some([num_te, num_tm]) = corner_mean(&w, &qc) else {
            return Polarised::default();
        };
        let k = math::sqrt(1.0 - sm * sm) / self.cos_i;
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
    fn propagates(&self, period_nm: f64, m: i32) -> bool {
        (self.s + f64::from(m) * self.lambda_nm / period_nm).abs() < 1.0
    }
    #[inline]
    fn corners(&self) -> (&[f64], &[usize]) {
        (&self.w, &self.index)
    }
}

/// The index i of the grid interval [x_i, x_{i+1}] holding `x` (clamped to the grid), as
/// numpy's `searchsorted(side="right") - 1` clamped to [0, n - 2].
fn interval<T: Values + ?Sized>(nodes: &T, x: f64) -> usize {
    let n = nodes.count();
    // The count of nodes at or below x (the axis ascends), by halving without a data-dependent
    // branch (a conditional move per step: no mispredicted jumps on the query's hot path).
    let (mut base, mut size) = (0usize, n);
    while size > 1 {
        let half = size / 2;
        let mid = base + half;
        base = if nodes.at(mid) <= x { mid } else { base };
        size -= half;
    }
    let at_or_below = base + usize::from(nodes.at(base) <= x);
    at_or_below.saturating_sub(1).min(n - 2)
}

impl Cell {
    /// The cell of (s, λ), `None` for a non-finite query or one at grazing incidence (no flux).
    fn find<T: Values + ?Sized>(sin: &T, lam: &T, s: f64, lambda_nm: f64) -> Option<Cell> {
        if !(s.is_finite() && lambda_nm.is_finite()) {
            return None;
        }
        let (n_s, n_l) = (sin.count(), lam.count());
        let s = s.max(sin.at(0)).min(sin.at(n_s - 1));
        let lambda_nm = lambda_nm.max(lam.at(0)).min(lam.at(n_l - 1));
        let cos_i = math::sqrt(1.0 - s * s);
        if cos_i <= 0.0 {
            return None;
        }
        let i = interval(sin, s);
        let j = interval(lam, lambda_nm);
        let (s0, s1, l0, l1) = (sin.at(i), sin.at(i + 1), lam.at(j), lam.at(j + 1));
        let tx = (s - s0) / (s1 - s0);
        let ty = (lambda_nm - l0) / (l1 - l0);
        Some(Cell {
            s,
            lambda_nm,
            cos_i,
            w: [
                (1.0 - tx) * (1.0 - ty),
                tx * (1.0 - ty),
                (1.0 - tx) * ty,
                tx * ty,
            ],
            s_c: [s0, s1, s0, s1],
            l_c: [l0, l0, l1, l1],
            index: [
                j * n_s + i,
                j * n_s + i + 1,
                (j + 1) * n_s + i,
                (j + 1) * n_s + i + 1,
            ],
            cell: j * (n_s - 1) + i,
        })
    }
}

/// The mean of the corners' q's `q` with the weights `w` renormalised over the corners where
/// the order propagates (w > 0 there, 0 elsewhere); `None` where there are none. The weights are
/// renormalised before they multiply anything: a cell whose only propagating corner has a tiny
/// (even subnormal) weight gives that corner's q, never 0·∞ (each normalised weight is in
/// [0, 1]).
#[inline]
fn corner_mean(w: &[f64], q: &[[f64; 2]]) -> Option<[f64; 2]> {
    let den: f64 = w.iter().sum();
    if den <= 0.0 {
        return None;
    }
    let (mut num_te, mut num_tm) = (0.0, 0.0);
    for (&wc, qc) in w.iter().zip(q) {
        if wc > 0.0 {
            let f = wc / den;
            num_te += f * qc[0];
            num_tm += f * qc[1];
        }
    }
    Some([num_te, num_tm])
}

/// The (q_TE, q_TM) of the node at flat index `at` for order m = `mf`: η·cos θi/cos θm, or
/// [`nodes_q::NOT_PROPAGATING`] where cos² θm ≤ [`GRAZING_CORNER`]. The node is at α = `alpha`
/// (s, or s′·√(1 − β²) conical), β² = `beta2`, λ = `lambda_nm`, with cos θi = `cos_i`; the
/// operations are the query's for sin θm (at a node the two cancel exactly, which matters near
/// a Rayleigh line, cos θm small), and the same whether the q's are kept or not.
#[allow(clippy::too_many_arguments)]
#[inline]
fn corner_q<T: Values + ?Sized>(
    alpha: f64,
    beta2: f64,
    lambda_nm: f64,
    cos_i: f64,
    mf: f64,
    period_nm: f64,
    (te, tm): (&T, &T),
    at: usize,
) -> [f64; 2] {
    let am = alpha + mf * lambda_nm / period_nm;
    let cm2 = 1.0 - am * am - beta2;
    if cm2 > GRAZING_CORNER {
        let g = cos_i / math::sqrt(cm2);
        [g * te.at(at), g * tm.at(at)]
    } else {
        [nodes_q::NOT_PROPAGATING; 2]
    }
}

impl EfficiencyTable {
    /// The grating period d, nm.
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// assert_eq!(Preset::Dvd.table().period_nm(), 740.0);
    /// # }
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.period_nm
    }

    /// The stored orders, `order_min ..= order_max` (every other order has η = 0).
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// assert_eq!(Preset::Foil.table().orders(), -5..=5);
    /// # }
    /// ```
    #[must_use]
    pub fn orders(&self) -> RangeInclusive<i32> {
        // The count is checked on load: order_min + count − 1 fits an i32.
        self.order_min..=self.order_min + (self.order_count as i32 - 1)
    }

    /// The number of stored orders (the length [`efficiencies`](Self::efficiencies) fills).
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// assert_eq!(Preset::Blazed600.table().order_count(), 19);
    /// # }
    /// ```
    #[must_use]
    pub fn order_count(&self) -> usize {
        self.order_count
    }

    /// The efficiencies of order `order` for light arriving with s = sin θi = `sin_theta_i`
    /// (= −wi.x) at `lambda_nm`, by the interpolation rule of the type's docs: 0 where the order
    /// is evanescent or not stored, and scaled with every other order so that each
    /// polarisation's sum over the stored orders at the query is at most 1. A non-finite query,
    /// and grazing incidence (|s| = 1, clamped to a grid reaching it), give 0. Computes every
    /// stored order (the normalisation needs their sum): use
    /// [`efficiencies`](Self::efficiencies) for all of them.
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// let foil = Preset::Foil.table();
    /// // Order −1 appears at s − λ/d = −1: just inside it propagates, just beyond it does not.
    /// let s = -1.0 + 500.0 / 1000.0;
    /// assert_eq!(foil.efficiency(-1, s - 1e-9, 500.0).te, 0.0);
    /// assert!(foil.efficiency(-1, s + 1e-3, 500.0).te > 0.0);
    /// assert_eq!(foil.efficiency(0, f64::NAN, 500.0).te, 0.0);
    /// # }
    /// ```
    #[must_use]
    pub fn efficiency(&self, order: i32, sin_theta_i: f64, lambda_nm: f64) -> Polarised {
        if !self.orders().contains(&order) {
            return Polarised::default();
        }
        self.one(order, sin_theta_i, 0.0, lambda_nm)
    }

    /// Every stored order's efficiencies at once, written to `out[k]` for order
    /// `order_min + k` (`out` should have [`order_count`](Self::order_count) elements; a
    /// shorter one gets the first orders, the rest of a longer one is set to 0), with the
    /// normalisation of [`efficiency`](Self::efficiency) applied. Returns the unpolarised sum
    /// Σ_m (TE + TM)/2 over the stored orders, at most 1. One cell search for all orders and no
    /// allocation: the hot path of a BSDF.
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::{Polarised, Preset};
    /// let cd = Preset::Cd.table();
    /// let mut out = [Polarised::default(); 17];
    /// let total = cd.efficiencies(0.3, 600.0, &mut out);
    /// assert!(total > 0.5 && total <= 1.0);
    /// assert_eq!(out[8 + 1], cd.efficiency(1, 0.3, 600.0)); // order 1
    /// # }
    /// ```
    pub fn efficiencies(&self, sin_theta_i: f64, lambda_nm: f64, out: &mut [Polarised]) -> f64 {
        for o in out.iter_mut() {
            *o = Polarised::default();
        }
        let first = self.order_min;
        let (sum_te, sum_tm) = self.each(sin_theta_i, 0.0, lambda_nm, |m, e| {
            // m − order_min is in 0..order_count.
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

    /// Calls `f(m, η_m)` for every stored order before the normalisation and returns the TE
    /// and TM sums; `beta` is read only by a conical table.
    fn each(&self, s: f64, beta: f64, lambda_nm: f64, f: impl FnMut(i32, Polarised)) -> (f64, f64) {
        #[cfg(feature = "alloc")]
        if let Some(r) = self.reduced() {
            return self.each_reduced(&r, (s, beta, lambda_nm), f);
        }
        with_arrays!(self, |sin, bet, lam, te, tm| self.each_in(
            sin,
            bet,
            lam,
            te,
            tm,
            (s, beta, lambda_nm),
            f
        ))
    }

    /// Order `order`'s efficiencies (a stored order) after the normalisation: that order's
    /// interpolation alone in a cell whose queries need no normalisation (`unit.rs`),
    /// otherwise from the sum over every stored order; `beta` is read only by a conical table.
    fn one(&self, order: i32, s: f64, beta: f64, lambda_nm: f64) -> Polarised {
        #[cfg(feature = "alloc")]
        if let Some(r) = self.reduced() {
            return self.one_reduced(&r, order, (s, beta, lambda_nm));
        }
        with_arrays!(self, |sin, bet, lam, te, tm| self.one_in(
            sin,
            bet,
            lam,
            te,
            tm,
            order,
            (s, beta, lambda_nm)
        ))
    }

    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn each_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
        (s, beta, lambda_nm): (f64, f64, f64),
        f: impl FnMut(i32, Polarised),
    ) -> (f64, f64) {
        let slice = sin.count() * bet.count().max(1) * lam.count();
        let q = self.q.get(|| self.q_in(sin, bet, lam, te, tm));
        if bet.count() > 0 {
            match conical::Cell3::find(sin, bet, lam, s, beta, lambda_nm) {
                Some(cell) => self.sum_cell(&cell, slice, (te, tm), q, f),
                None => (0.0, 0.0),
            }
        } else {
            match Cell::find(sin, lam, s, lambda_nm) {
                Some(cell) => self.sum_cell(&cell, slice, (te, tm), q, f),
                None => (0.0, 0.0),
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    #[inline]
    fn one_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
        order: i32,
        (s, beta, lambda_nm): (f64, f64, f64),
    ) -> Polarised {
        let slice = sin.count() * bet.count().max(1) * lam.count();
        let marks = || self.marks_in(sin, bet, lam, te, tm);
        let q = self.q.get(|| self.q_in(sin, bet, lam, te, tm));
        if bet.count() > 0 {
            match conical::Cell3::find(sin, bet, lam, s, beta, lambda_nm) {
                Some(cell) => self.one_cell(&cell, order, slice, (te, tm), q, marks),
                None => Polarised::default(),
            }
        } else {
            match Cell::find(sin, lam, s, lambda_nm) {
                Some(cell) => self.one_cell(&cell, order, slice, (te, tm), q, marks),
                None => Polarised::default(),
            }
        }
    }

    /// Every stored order of one cell through `f`, and the TE and TM sums.
    #[inline]
    fn sum_cell<C: OrderCell, T: Values + ?Sized>(
        &self,
        cell: &C,
        slice: usize,
        values: (&T, &T),
        q: Option<&[[f64; 2]]>,
        mut f: impl FnMut(i32, Polarised),
    ) -> (f64, f64) {
        let (mut sum_te, mut sum_tm) = (0.0, 0.0);
        let mut m = self.order_min;
        for k in 0..self.order_count {
            let e = cell.order(self.period_nm, m, k * slice, values, q);
            sum_te += e.te;
            sum_tm += e.tm;
            f(m, e);
            m = m.wrapping_add(1);
        }
        (sum_te, sum_tm)
    }

    /// One stored order of one cell, normalised: alone where the cell is marked (the factor
    /// is exactly 1 there), else from the sum over every order.
    #[inline]
    fn one_cell<C: OrderCell, T: Values + ?Sized>(
        &self,
        cell: &C,
        order: i32,
        slice: usize,
        values: (&T, &T),
        q: Option<&[[f64; 2]]>,
        marks: impl FnOnce() -> unit::Bits,
    ) -> Polarised {
        // `order` is stored: order − order_min is in 0..order_count.
        let k = (i64::from(order) - i64::from(self.order_min)) as usize;
        if self.unit.is_unit(cell.index(), marks) {
            return cell.order(self.period_nm, order, k * slice, values, q);
        }
        let mut wanted = Polarised::default();
        let (sum_te, sum_tm) = self.sum_cell(cell, slice, values, q, |m, e| {
            if m == order {
                wanted = e;
            }
        });
        Polarised {
            te: wanted.te * scale(sum_te),
            tm: wanted.tm * scale(sum_tm),
        }
    }

    /// The table's sin θi nodes as f64 (the presets' f32 nodes widened exactly).
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// let s: Vec<f64> = Preset::Cd.table().sin_theta_i().collect();
    /// assert_eq!(s.len(), 25);
    /// assert_eq!(s[12], 0.0);
    /// # }
    /// ```
    pub fn sin_theta_i(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.axis(AxisName::Sin)
    }

    /// The table's wavelength nodes, nm, as f64 (of a reduced conical table, version 3, its
    /// first |β| plane's: [`plane_lambda_nm`](Self::plane_lambda_nm) gives every plane's).
    ///
    /// ```
    /// # #[cfg(feature = "presets")] {
    /// use diffraction::relief::Preset;
    /// let l: Vec<f64> = Preset::Blazed600.table().lambda_nm().collect();
    /// assert_eq!((l[0], l[8]), (360.0, 830.0));
    /// # }
    /// ```
    pub fn lambda_nm(&self) -> impl ExactSizeIterator<Item = f64> + '_ {
        self.axis(AxisName::Lambda)
    }

    fn axis(&self, which: AxisName) -> Axis<'_> {
        match &self.storage {
            Storage::Static {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                ..
            } => Axis::F32(
                match which {
                    AxisName::Sin => sin_theta_i,
                    AxisName::Beta => abs_beta,
                    AxisName::Lambda => lambda_nm,
                }
                .iter(),
            ),
            #[cfg(feature = "alloc")]
            Storage::Owned {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                ..
            } => Axis::F64(
                match which {
                    AxisName::Sin => sin_theta_i,
                    AxisName::Beta => abs_beta,
                    AxisName::Lambda => lambda_nm,
                }
                .iter(),
            ),
            // A reduced conical table's wavelength nodes are its first plane's.
            #[cfg(feature = "alloc")]
            Storage::Reduced {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                rows,
                ..
            } => Axis::F64(
                match which {
                    AxisName::Sin => &sin_theta_i[..],
                    AxisName::Beta => &abs_beta[..],
                    AxisName::Lambda => &lambda_nm[rows[0]..rows[1]],
                }
                .iter(),
            ),
        }
    }
}

/// Which axis of a table.
#[derive(Clone, Copy)]
enum AxisName {
    Sin,
    Beta,
    Lambda,
}

/// The factor that brings a sum over orders down to 1 where it exceeds 1.
#[inline]
fn scale(sum: f64) -> f64 {
    if sum > 1.0 {
        1.0 / sum
    } else {
        1.0
    }
}

/// The nodes of one axis of a table.
enum Axis<'a> {
    F32(core::slice::Iter<'a, f32>),
    #[cfg(feature = "alloc")]
    F64(core::slice::Iter<'a, f64>),
}

impl Iterator for Axis<'_> {
    type Item = f64;
    fn next(&mut self) -> Option<f64> {
        match self {
            Axis::F32(it) => it.next().map(|&v| f64::from(v)),
            #[cfg(feature = "alloc")]
            Axis::F64(it) => it.next().copied(),
        }
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        match self {
            Axis::F32(it) => it.size_hint(),
            #[cfg(feature = "alloc")]
            Axis::F64(it) => it.size_hint(),
        }
    }
}

impl ExactSizeIterator for Axis<'_> {}
