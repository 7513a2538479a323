//! The fast reading of a classical table: what the tabulated BSDF reads on every `eval`,
//! `sample` and `pdf`, derived once per table on first use (feature `std`: a `OnceLock`, for
//! the tables whose nodes' q's are kept, `nodes_q.rs`, of at most [`MAX_FAST_VALUES`] values).
//! The parent module's rule, to rounding:
//!
//! * **The cell in O(1).** Each axis is binned uniformly, the bin width its smallest node
//!   spacing (at most 8 bins per interval), and each bin keeps the count of the inner nodes
//!   below it, the node inside it and, for the two intervals its values can be in, the
//!   interval's first node and reciprocal width. The bin of a value is monotone in the value
//!   (a difference, a product by a positive constant, a truncation), so the count plus one
//!   comparison is the binary search's interval exactly, whatever the rounding; a bin holding
//!   several nodes (the cap) searches them.
//! * **Plain reads.** Where a cell needs no normalisation (`unit.rs`) and order m propagates
//!   at its four corners, the rule is q's bilinear interpolation with the cell's own weights
//!   (they sum to 1 and none is dropped), the same for TE and TM: unpolarised,
//!   η = q̄·√((1 − sin² θm)/(1 − sin² θi)) with q̄ = (q_TE + q_TM)/2 kept per cell and order
//!   (the four corners in one record), tx = (s − s_i)·(1/Δs_i) and ty likewise.
//! * **Other reads.** An order that does not propagate at every corner of such a cell: q̄
//!   over the corners where it does, with the parent module's weights renormalised; a cell
//!   that may need the normalisation: every stored order's TE and TM at the query and the
//!   factors 1/Σ. Evanescence is the parent module's test with its operations
//!   (sin θm = s + m·λ/d), and so is the proposal's set of orders.
//! * **The pair.** The BSDF's η̃ = min(η_m(a), η_m(b)) of two incidences at one λ: the
//!   wavelength is located once for both reads, and the incidences once for any number of
//!   wavelengths (`eval4`, `pdf4`, `sample4`; `sample` reuses its proposal's incidence). Symmetric in (a, b) to
//!   the bit. Comparing q̄²·c_m·c_i′ to finish only the smaller read (one square root) was
//!   measured slower than finishing both: its branch is unpredictable.
//! * **The proposal.** The sampler's cell proposal ([`FastProposal`]): the candidates that
//!   propagate at the query, each order's weighted stored unpolarised efficiency from the
//!   corners' values kept per cell, and their sum from the corners' running sums over the
//!   orders (two records instead of one per candidate).
//!
//! Measured against the parent module's (`tests`, presets and random tables): every read
//! within 2.8·10⁻¹⁶ of its rounding's scale (the corners' q's times cos θm/cos θi), the
//! proposals' orders the same, their sums within 2.1·10⁻¹⁶ of the running sums. Without
//! `std`, for a conical table, for a larger table and for one with a node spacing below about
//! 10⁻³⁰⁸ (whose reciprocal or bin scale overflows) every read is the parent module's.

use core::ops::RangeInclusive;

use super::EfficiencyTable;
#[cfg(feature = "std")]
use super::{nodes_q::NOT_PROPAGATING, scale, Storage, Values};
#[cfg(feature = "std")]
use crate::num::math;
#[cfg(feature = "std")]
use std::{sync::OnceLock, vec::Vec};

#[cfg(feature = "std")]
use bins::Bins;

/// The largest table (values per polarisation) with a fast reading: 2¹⁷ (its derived data take
/// about 104 bytes a value, 13 MiB at the cap; the CD preset's 10,625 values 1.1 MB, derived
/// in 0.3-0.6 ms after its marks and q's, 1.7 ms). A larger table is read by the parent
/// module's rule.
#[cfg(feature = "std")]
const MAX_FAST_VALUES: usize = 1 << 17;

/// The fast reading of one table, derived on first use.
#[derive(Debug, Clone, Default)]
pub(super) struct Lookup {
    #[cfg(feature = "std")]
    fast: OnceLock<Option<Fast>>,
    /// The stored values node by node for the proposals of the generic rule (`proposal.rs`).
    #[cfg(feature = "std")]
    pub(super) by_node: OnceLock<Option<super::proposal::ByNode>>,
}

impl PartialEq for Lookup {
    /// Derived data: equal tables have equal lookups, derived or not.
    fn eq(&self, _other: &Lookup) -> bool {
        true
    }
}

impl Lookup {
    // Every table is built by a constructor (feature `alloc`) or is a preset.
    #[cfg_attr(not(any(feature = "alloc", feature = "presets")), allow(dead_code))]
    pub(super) const fn new() -> Lookup {
        Lookup {
            #[cfg(feature = "std")]
            fast: OnceLock::new(),
            #[cfg(feature = "std")]
            by_node: OnceLock::new(),
        }
    }
}

/// The derived data of a classical table.
#[cfg(feature = "std")]
#[derive(Debug, Clone)]
pub(super) struct Fast {
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    /// The axes as f64, the reciprocals of their spacings and their binnings.
    s: Vec<f64>,
    l: Vec<f64>,
    inv_ds: Vec<f64>,
    inv_dl: Vec<f64>,
    s_bins: Bins,
    l_bins: Bins,
    /// Per cell j·(n_s − 1) + i: whether it needs no normalisation (`unit.rs`).
    unit: Vec<bool>,
    /// Per order index k and node (k·n_λ + j)·n_s + i: the nodes' (q_TE, q_TM) (`nodes_q.rs`,
    /// copied), for the reads outside the plain cells.
    q: Vec<[f64; 2]>,
    /// Per order index k and cell c, at k·(cells) + c: the corners' stored unpolarised values
    /// (TE + TM)/2, and their running sums Σ_{k′ ≤ k} (the proposal's).
    eta: Vec<[f64; 4]>,
    cum: Vec<[f64; 4]>,
    /// Per order index k and cell c, at k·(cells) + c: the corners' q̄ (numbered as `Cell`'s)
    /// where the cell needs no normalisation and the order propagates at every corner, else
    /// NaN.
    cells: Vec<[f64; 4]>,
    cell_count: usize,
}

/// One incidence located on the sin θi axis: s clamped to the grid, c_i = 1 − s² > 0, the
/// interval i and the weight tx of the plain reading. A non-finite incidence, or one at
/// grazing incidence on the grid, reads 0 for every order (`ok` false).
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy)]
struct Side {
    s: f64,
    c_i: f64,
    i: usize,
    tx: f64,
    ok: bool,
}

/// One wavelength located on the λ axis: λ clamped to the grid, the interval j and the weight
/// ty of the plain reading.
#[cfg(feature = "std")]
#[derive(Debug, Clone, Copy)]
struct Wave {
    l: f64,
    j: usize,
    ty: f64,
    /// The first cell of the interval's row, j·(n_s − 1).
    row: usize,
}

#[cfg(feature = "std")]
impl Fast {
    /// The located incidence s (`ok` false for a non-finite s and for grazing incidence on
    /// the grid, where the parent module's `Cell::find` finds no cell).
    #[inline(always)]
    fn side(&self, s: f64) -> Side {
        let finite = s.is_finite();
        // Clamped to the grid (a finite s; a NaN is refused below).
        let s = self.s_bins.clamp(s);
        let c_i = 1.0 - s * s;
        // The parent module's tests: a finite query, and √(1 − s²) > 0.
        if !(finite && c_i > 0.0) {
            return Side {
                s: 0.0,
                c_i: 1.0,
                i: 0,
                tx: 0.0,
                ok: false,
            };
        }
        let at = self.s_bins.locate(&self.s, &self.inv_ds, s);
        Side {
            s,
            c_i,
            i: at.i,
            tx: ((s - at.node) * at.inv).min(1.0),
            ok: true,
        }
    }

    /// The located wavelength; `None` where it is not finite.
    #[inline(always)]
    fn wave(&self, lambda_nm: f64) -> Option<Wave> {
        if !lambda_nm.is_finite() {
            return None;
        }
        let l = self.l_bins.clamp(lambda_nm);
        let at = self.l_bins.locate(&self.l, &self.inv_dl, l);
        Some(Wave {
            l,
            j: at.i,
            ty: ((l - at.node) * at.inv).min(1.0),
            row: at.i * (self.s.len() - 1),
        })
    }

    /// Order `order` (index k) at (s, λ): in a cell that needs no normalisation, where the
    /// order propagates at the four corners, the plain reading q̄·√(c_m/c_i) with q̄ bilinear
    /// (finite and ≥ 0); otherwise [`read_other`](Self::read_other).
    #[inline(always)]
    fn read(&self, order: i32, k: usize, a: &Side, w: &Wave) -> f64 {
        let c = self.cells[k * self.cell_count + w.row + a.i];
        if c[0].is_nan() {
            return self.read_other(order, k, a, w);
        }
        let sm = a.s + f64::from(order) * w.l / self.period_nm;
        let (tx, ty) = (a.tx, w.ty);
        let wc = [
            (1.0 - tx) * (1.0 - ty),
            tx * (1.0 - ty),
            (1.0 - tx) * ty,
            tx * ty,
        ];
        let q = (wc[0] * c[0] + wc[1] * c[1]) + (wc[2] * c[2] + wc[3] * c[3]);
        q * math::sqrt((1.0 - sm * sm) / a.c_i)
    }

    /// Order `order` (index k) at (s, λ) outside the plain reading: 0 where it is evanescent;
    /// in a cell that needs no normalisation q̄ renormalised over the corners where the order
    /// propagates; else from every stored order's polarised reading, normalised. 0 unless
    /// finite and positive.
    #[inline(never)]
    fn read_other(&self, order: i32, k: usize, a: &Side, w: &Wave) -> f64 {
        let sm = a.s + f64::from(order) * w.l / self.period_nm;
        if sm.abs() >= 1.0 {
            return 0.0;
        }
        let n_s = self.s.len();
        let slice = n_s * self.l.len();
        let base = w.j * n_s + a.i;
        let nodes = [base, base + 1, base + n_s, base + n_s + 1];
        // The parent module's weights themselves (`Cell::at`), so that a corner has weight 0
        // exactly where it has there (a query on its interval's far node).
        let (i, j) = (a.i, w.j);
        let tx = (a.s - self.s[i]) / (self.s[i + 1] - self.s[i]);
        let ty = (w.l - self.l[j]) / (self.l[j + 1] - self.l[j]);
        let wc = [
            (1.0 - tx) * (1.0 - ty),
            tx * (1.0 - ty),
            (1.0 - tx) * ty,
            tx * ty,
        ];
        // Order k′'s (TE, TM) at the query before the normalisation: the mean of its corners'
        // q over those of positive weight where it propagates, times cos θm/cos θi.
        let polarised = |k: usize, sm: f64| {
            let (mut te, mut tm, mut den) = (0.0, 0.0, 0.0);
            for (&n, &w) in nodes.iter().zip(&wc) {
                let q = self.q[k * slice + n];
                if w > 0.0 && q[0] != NOT_PROPAGATING {
                    te += w * q[0];
                    tm += w * q[1];
                    den += w;
                }
            }
            if den > 0.0 {
                let r = math::sqrt((1.0 - sm * sm) / a.c_i) / den;
                (te * r, tm * r)
            } else {
                (0.0, 0.0)
            }
        };
        let e = if self.unit[w.j * (n_s - 1) + a.i] {
            let (te, tm) = polarised(k, sm);
            0.5 * (te + tm)
        } else {
            // Every stored order for the sums of the normalisation.
            let (mut sum_te, mut sum_tm, mut want) = (0.0, 0.0, (0.0, 0.0));
            for kk in 0..self.order_count {
                let m = f64::from(self.order_min) + kk as f64;
                let smm = a.s + m * w.l / self.period_nm;
                if smm.abs() >= 1.0 {
                    continue;
                }
                let e = polarised(kk, smm);
                sum_te += e.0;
                sum_tm += e.1;
                if kk == k {
                    want = e;
                }
            }
            0.5 * (want.0 * scale(sum_te) + want.1 * scale(sum_tm))
        };
        if e > 0.0 && e < f64::INFINITY {
            e
        } else {
            0.0
        }
    }

    /// min(η_m(a), η_m(b)) at the located wavelength `w`; 0 for an order not stored.
    #[inline(always)]
    fn min_of(&self, order: i64, a: &Side, b: &Side, w: &Wave) -> f64 {
        let k = order.wrapping_sub(i64::from(self.order_min)) as u64;
        if k >= self.order_count as u64 || !(a.ok && b.ok) {
            return 0.0;
        }
        // A stored order fits an i32.
        let (m, k) = (order as i32, k as usize);
        self.read(m, k, a, w).min(self.read(m, k, b, w))
    }
}

/// Two incident directions of travel, (α, β) each (α = −wi.x, β = −wi.y), located once in a
/// table and read at any order and wavelength: the tabulated BSDF's
/// η̃_m = min(η_m(a), η_m(b)) (`EfficiencyTable::incidences`).
#[derive(Clone, Copy)]
pub(crate) struct Incidences<'a> {
    table: &'a EfficiencyTable,
    /// A classical table's fast reading and the incidences located in it.
    #[cfg(feature = "std")]
    fast: Option<(&'a Fast, Side, Side)>,
    dirs: [(f64, f64); 2],
}

impl<'a> Incidences<'a> {
    /// η̃_m = min(η_m(a, λ), η_m(b, λ)), unpolarised and normalised: 0 for an order the
    /// table does not store, where either read is 0, and where either is not a finite
    /// positive number.
    #[inline(always)]
    pub(crate) fn min(&self, order: i64, lambda_nm: f64) -> f64 {
        let t = self.table;
        #[cfg(feature = "std")]
        if let Some((f, a, b)) = &self.fast {
            return match f.wave(lambda_nm) {
                Some(w) => f.min_of(order, a, b, &w),
                None => 0.0,
            };
        }
        if order < i64::from(t.order_min)
            || order > i64::from(t.order_min) + t.order_count as i64 - 1
        {
            return 0.0;
        }
        // A stored order fits an i32.
        let m = order as i32;
        let e = t.unpolarised(m, self.dirs[0], lambda_nm);
        if e == 0.0 {
            return 0.0;
        }
        e.min(t.unpolarised(m, self.dirs[1], lambda_nm))
    }

    /// The fast reading's proposal at the first incidence (a) for `lambda_nm` and the
    /// candidates (the table's [`fast_proposal`](EfficiencyTable::fast_proposal) at a, with
    /// the incidence's location reused); `None` where the table has no fast reading.
    #[inline(always)]
    pub(crate) fn proposal(
        &self,
        lambda_nm: f64,
        candidates: RangeInclusive<i64>,
    ) -> Option<Option<FastProposal<'a>>> {
        #[cfg(feature = "std")]
        if let Some((f, a, _)) = &self.fast {
            return Some(FastProposal::at(f, *a, lambda_nm, candidates));
        }
        let _ = (lambda_nm, candidates);
        None
    }
}

/// The sampler's cell proposal from the fast reading of a classical table (the parent
/// module's `CellProposal`, to rounding): the located incidence and wavelength, the cell's
/// bilinear weights, the candidate orders that propagate at the query and the sum of their
/// weighted stored unpolarised efficiencies, here from the corners' running sums over the
/// orders (two records instead of one per candidate).
#[derive(Clone, Copy)]
pub(crate) struct FastProposal<'a> {
    #[cfg(feature = "std")]
    fast: &'a Fast,
    #[cfg(feature = "std")]
    side: Side,
    #[cfg(feature = "std")]
    wave: Wave,
    /// The corners' bilinear weights and the cell j·(n_s − 1) + i.
    #[cfg(feature = "std")]
    w: [f64; 4],
    #[cfg(feature = "std")]
    cell: usize,
    lo: i32,
    hi: i32,
    total: f64,
    /// Without `std` there is no fast reading: uninhabited.
    #[cfg(not(feature = "std"))]
    never: (core::convert::Infallible, core::marker::PhantomData<&'a ()>),
}

#[cfg(not(feature = "std"))]
impl FastProposal<'_> {
    /// Uninhabited without `std`.
    pub(crate) fn efficiency(&self, _m: i32) -> f64 {
        match self.never.0 {}
    }

    /// Uninhabited without `std`.
    pub(crate) fn min_efficiency(&self, _order: i64, _alpha: f64) -> f64 {
        match self.never.0 {}
    }
}

impl FastProposal<'_> {
    /// The candidate orders that propagate at the query.
    #[inline]
    pub(crate) fn orders(&self) -> RangeInclusive<i32> {
        self.lo..=self.hi
    }

    /// How many orders [`orders`](Self::orders) holds (at least 1).
    #[inline]
    pub(crate) fn count(&self) -> usize {
        (i64::from(self.hi) - i64::from(self.lo) + 1) as usize
    }

    /// Σ over [`orders`](Self::orders) of the weighted stored unpolarised efficiencies.
    #[inline]
    pub(crate) fn total(&self) -> f64 {
        self.total
    }
}

#[cfg(feature = "std")]
impl<'a> FastProposal<'a> {
    /// The proposal at (s, λ) among the stored `candidates`; `None` where none propagates at
    /// the query or the query has no cell.
    #[inline(always)]
    fn new(
        f: &'a Fast,
        s: f64,
        lambda_nm: f64,
        candidates: RangeInclusive<i64>,
    ) -> Option<FastProposal<'a>> {
        FastProposal::at(f, f.side(s), lambda_nm, candidates)
    }

    /// [`new`](Self::new) at the located incidence `a`.
    #[inline(always)]
    fn at(
        f: &'a Fast,
        a: Side,
        lambda_nm: f64,
        candidates: RangeInclusive<i64>,
    ) -> Option<FastProposal<'a>> {
        let first = i64::from(f.order_min);
        let last = first + f.order_count as i64 - 1;
        let (lo, hi) = (
            (*candidates.start()).max(first),
            (*candidates.end()).min(last),
        );
        if hi < lo {
            return None;
        }
        let w = f.wave(lambda_nm)?;
        if !a.ok {
            return None;
        }
        // The candidates that propagate at the query, by the parent module's test (and the
        // fast read's). Of the amplitude model's candidates (the periods meeting the disk's
        // u-range) at most the first and the last do not: the four tests are independent.
        let live = |m: i64| (a.s + m as f64 * w.l / f.period_nm).abs() < 1.0;
        let (l0, l1, h0, h1) = (live(lo), live(lo + 1), live(hi), live(hi - 1));
        let (mut lo, mut hi) = (lo + i64::from(!l0), hi - i64::from(!h0));
        if !(l0 || l1) || !(h0 || h1) || hi < lo {
            // Other candidates (a range from elsewhere, or rounding): trimmed one by one.
            while lo <= hi && !live(lo) {
                lo += 1;
            }
            while hi >= lo && !live(hi) {
                hi -= 1;
            }
            if hi < lo {
                return None;
            }
        }
        let cell = w.j * (f.s.len() - 1) + a.i;
        let (tx, ty) = (a.tx, w.ty);
        let wc = [
            (1.0 - tx) * (1.0 - ty),
            tx * (1.0 - ty),
            (1.0 - tx) * ty,
            tx * ty,
        ];
        // Per corner, the running sum through hi less the one through lo − 1.
        let (k_lo, k_hi) = ((lo - first) as usize, (hi - first) as usize);
        let upper = f.cum[k_hi * f.cell_count + cell];
        let lower = if k_lo > 0 {
            f.cum[(k_lo - 1) * f.cell_count + cell]
        } else {
            [0.0; 4]
        };
        let total = (wc[0] * (upper[0] - lower[0]) + wc[1] * (upper[1] - lower[1]))
            + (wc[2] * (upper[2] - lower[2]) + wc[3] * (upper[3] - lower[3]));
        // Stored orders fit an i32.
        Some(FastProposal {
            fast: f,
            side: a,
            wave: w,
            w: wc,
            cell,
            lo: lo as i32,
            hi: hi as i32,
            total,
        })
    }

    /// Σ_c w_c·(TE + TM)/2 of order `m`'s stored values at the cell's corners; 0 outside the
    /// proposal's orders.
    #[inline(always)]
    pub(crate) fn efficiency(&self, m: i32) -> f64 {
        if m < self.lo || m > self.hi {
            return 0.0;
        }
        let f = self.fast;
        // m is a stored order: m − order_min is in 0..order_count.
        let e = f.eta[(m - f.order_min) as usize * f.cell_count + self.cell];
        (self.w[0] * e[0] + self.w[1] * e[1]) + (self.w[2] * e[2] + self.w[3] * e[3])
    }

    /// η̃_m = min(η_m(s, λ), η_m(s′, λ)) of the fast reading for the proposal's incidence s
    /// and wavelength λ and the incidence s′ = `alpha` (the pair of [`Incidences::min`],
    /// with the proposal's location reused).
    #[inline(always)]
    pub(crate) fn min_efficiency(&self, order: i64, alpha: f64) -> f64 {
        let f = self.fast;
        f.min_of(order, &self.side, &f.side(alpha), &self.wave)
    }
}

impl EfficiencyTable {
    /// The fast reading of a classical table whose nodes' q's are kept (`None` otherwise, and
    /// without `std`).
    #[cfg(feature = "std")]
    #[inline]
    fn fast(&self) -> Option<&Fast> {
        self.lookup
            .fast
            .get_or_init(|| {
                with_arrays!(self, |sin, bet, lam, te, tm| self
                    .fast_in(sin, bet, lam, te, tm))
            })
            .as_ref()
    }

    /// The two incidences a = (α, β) and b of the pair read by [`Incidences::min`].
    #[inline(always)]
    pub(crate) fn incidences(&self, a: (f64, f64), b: (f64, f64)) -> Incidences<'_> {
        Incidences {
            table: self,
            #[cfg(feature = "std")]
            fast: self.fast().map(|f| (f, f.side(a.0), f.side(b.0))),
            dirs: [a, b],
        }
    }

    /// The unpolarised efficiency of stored order `order` for the incident direction of
    /// travel (α, β) = `dir` at `lambda_nm` (the parent module's reading, normalised), 0 where
    /// it is not a finite positive number.
    #[inline]
    pub(crate) fn unpolarised(&self, order: i32, dir: (f64, f64), lambda_nm: f64) -> f64 {
        let e = self.one(order, dir.0, dir.1, lambda_nm).unpolarised();
        if e.is_finite() && e > 0.0 {
            e
        } else {
            0.0
        }
    }

    /// The sampler's cell proposal from the fast reading for the incidence s = α at λ among
    /// the candidate orders `candidates` (β is ignored: a classical table): the parent
    /// module's [`cell_proposal`](EfficiencyTable::cell_proposal) to rounding (`Some(None)`
    /// where that gives `None`); `None` where the table has no fast reading.
    #[inline(always)]
    pub(crate) fn fast_proposal(
        &self,
        alpha: f64,
        lambda_nm: f64,
        candidates: RangeInclusive<i64>,
    ) -> Option<Option<FastProposal<'_>>> {
        #[cfg(feature = "std")]
        if let Some(f) = self.fast() {
            return Some(FastProposal::new(f, alpha, lambda_nm, candidates));
        }
        let _ = (alpha, lambda_nm, candidates);
        None
    }

    /// The derived data of a classical table (`None` for a conical one and where the q's are
    /// not kept).
    #[cfg(feature = "std")]
    fn fast_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
    ) -> Option<Fast> {
        if bet.count() > 0 || sin.count() * lam.count() * self.order_count > MAX_FAST_VALUES {
            return None;
        }
        let q = self.q.get(|| self.q_in(sin, bet, lam, te, tm))?;
        let s: Vec<f64> = (0..sin.count()).map(|i| sin.at(i)).collect();
        let l: Vec<f64> = (0..lam.count()).map(|j| lam.at(j)).collect();
        let (n_s, n_l) = (s.len(), l.len());
        let slice = n_s * n_l;
        let inv = |x: &[f64]| {
            x.windows(2)
                .map(|w| 1.0 / (w[1] - w[0]))
                .collect::<Vec<f64>>()
        };
        let k_count = self.order_count;
        let unit: Vec<bool> = (0..(n_s - 1) * (n_l - 1))
            .map(|cell| {
                self.unit
                    .is_unit(cell, || self.marks_in(sin, bet, lam, te, tm))
            })
            .collect();
        let cell_count = (n_s - 1) * (n_l - 1);
        let mut cells = Vec::with_capacity(k_count * cell_count);
        for k in 0..k_count {
            for j in 0..n_l - 1 {
                for i in 0..n_s - 1 {
                    let at = k * slice + j * n_s + i;
                    let c = [q[at][0], q[at + 1][0], q[at + n_s][0], q[at + n_s + 1][0]];
                    let plain = unit[j * (n_s - 1) + i] && c.iter().all(|&v| v != NOT_PROPAGATING);
                    cells.push(if plain {
                        [at, at + 1, at + n_s, at + n_s + 1].map(|n| 0.5 * (q[n][0] + q[n][1]))
                    } else {
                        [f64::NAN; 4]
                    });
                }
            }
        }
        // The parent module's stored unpolarised value, (TE + TM)/2 with its operations, per
        // cell's corners.
        let mut eta = Vec::with_capacity(k_count * cell_count);
        for k in 0..k_count {
            for j in 0..n_l - 1 {
                for i in 0..n_s - 1 {
                    let at = k * slice + j * n_s + i;
                    eta.push(
                        [at, at + 1, at + n_s, at + n_s + 1].map(|n| 0.5 * (te.at(n) + tm.at(n))),
                    );
                }
            }
        }
        let mut cum = eta.clone();
        for at in cell_count..k_count * cell_count {
            let below = cum[at - cell_count];
            for (c, b) in cum[at].iter_mut().zip(below) {
                *c += b;
            }
        }
        let (inv_ds, inv_dl) = (inv(&s), inv(&l));
        // A node spacing so small (below about 10⁻³⁰⁸) that its reciprocal or the binning's
        // scale overflows: the parent module's rule, whose divisions are exact there.
        if inv_ds.iter().chain(&inv_dl).any(|x| !x.is_finite()) {
            return None;
        }
        Some(Fast {
            period_nm: self.period_nm,
            order_min: self.order_min,
            order_count: k_count,
            inv_ds,
            inv_dl,
            s_bins: Bins::new(&s)?,
            l_bins: Bins::new(&l)?,
            s,
            l,
            unit,
            q: q.to_vec(),
            eta,
            cum,
            cells,
            cell_count,
        })
    }
}

#[cfg(feature = "std")]
mod bins;
#[cfg(all(test, feature = "std"))]
mod tests;
