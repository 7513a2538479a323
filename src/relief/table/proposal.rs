//! The sampler's order proposal from a table: the stored efficiencies of the query's cell
//! corners, weighted by the query's bilinear (trilinear) weights, over the candidate orders that
//! propagate at the query. Reading it costs one cell search and a few stored values per order
//! (no q-factor, no square root), against the interpolation of every order that the exact
//! weights η_m(query) need; the BSDF mixes it with a defensive share (`grating_bsdf`'s order
//! weights), so that every order the query's interpolation can give a positive efficiency has
//! a positive probability.

use core::ops::RangeInclusive;
#[cfg(feature = "std")]
use std::vec::Vec;

use super::{conical, Cell, EfficiencyTable, OrderCell, Storage, Values};

/// The largest table (values per polarisation) whose stored values are kept node by node
/// ([`ByNode`]): 2²⁰, 8 MiB of them.
#[cfg(feature = "std")]
const MAX_BY_NODE_VALUES: usize = 1 << 20;

/// The stored unpolarised efficiencies (TE + TM)/2 node by node, derived on first use (feature
/// `std`) for the proposals of the tables the generic rule reads: node n's order k at n·K + k
/// (K stored orders). A proposal's sum and an order's weight then read each corner's values of
/// neighbouring orders side by side, instead of one order's slice after another (the values of
/// a corner's orders lie K·(nodes) apart in the table's own layout).
#[cfg(feature = "std")]
#[derive(Debug, Clone)]
pub(super) struct ByNode {
    orders: usize,
    eta: Vec<f64>,
}

#[cfg(feature = "std")]
impl ByNode {
    /// The stored values `te`, `tm` of `orders` orders of `slice` nodes each; `None` past
    /// [`MAX_BY_NODE_VALUES`].
    fn new<T: Values + ?Sized>(te: &T, tm: &T, slice: usize, orders: usize) -> Option<ByNode> {
        if slice.checked_mul(orders)? > MAX_BY_NODE_VALUES {
            return None;
        }
        let mut eta = Vec::with_capacity(slice * orders);
        for n in 0..slice {
            for k in 0..orders {
                // stored_unpolarised's operations.
                let v = k * slice + n;
                eta.push(0.5 * (te.at(v) + tm.at(v)));
            }
        }
        Some(ByNode { orders, eta })
    }
}

/// A query's order proposal ([`EfficiencyTable::cell_proposal`]): the cell's corners of
/// positive weight, the candidate orders that propagate at the query (the query clamped to the
/// grid, as the interpolation clamps it) and the sum of the corners' weighted stored
/// unpolarised efficiencies over them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CellProposal {
    /// The query's cell corners of positive weight: weights and flat indices (`count` of them).
    w: [f64; 8],
    at: [usize; 8],
    count: usize,
    slice: usize,
    lo: i32,
    hi: i32,
    total: f64,
}

impl CellProposal {
    /// The candidate orders that propagate at the query: every order whose interpolated
    /// efficiency there can be positive.
    #[must_use]
    pub fn orders(&self) -> RangeInclusive<i32> {
        self.lo..=self.hi
    }

    /// How many orders [`orders`](Self::orders) holds (at least 1).
    #[must_use]
    pub fn count(&self) -> usize {
        (i64::from(self.hi) - i64::from(self.lo) + 1) as usize
    }

    /// Σ over [`orders`](Self::orders) of the weighted stored unpolarised efficiencies.
    #[must_use]
    pub fn total(&self) -> f64 {
        self.total
    }
}

impl EfficiencyTable {
    /// The proposal for the incident direction of travel (α, β) = (`alpha`,
    /// `beta`) at `lambda_nm` among the candidate orders `candidates`: `None` where no
    /// candidate stored order propagates at the query (then every interpolated efficiency of
    /// the candidates is 0), or the query has no cell (non-finite, grazing, beyond the
    /// incidence). A classical table ignores β.
    pub(crate) fn cell_proposal(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
        candidates: RangeInclusive<i64>,
    ) -> Option<CellProposal> {
        let first = i64::from(self.order_min);
        let last = first + self.order_count as i64 - 1;
        let (lo, hi) = (
            (*candidates.start()).max(first),
            (*candidates.end()).min(last),
        );
        if hi < lo {
            return None;
        }
        // In i32: the stored orders are.
        let (lo, hi) = (lo as i32, hi as i32);
        #[cfg(feature = "alloc")]
        if let Some(r) = self.reduced() {
            // The proposal reads the stored values at the corners' weights alone.
            let cell = r.find(alpha, beta, lambda_nm, false)?;
            return self.propose(&cell, (lo, hi), r.slice(), r.te, r.tm);
        }
        with_arrays!(self, |sin, bet, lam, te, tm| {
            let slice = sin.count() * bet.count().max(1) * lam.count();
            if bet.count() > 0 {
                let cell = conical::Cell3::find(sin, bet, lam, alpha, beta, lambda_nm)?;
                self.propose(&cell, (lo, hi), slice, te, tm)
            } else {
                let cell = Cell::find(sin, lam, alpha, lambda_nm)?;
                self.propose(&cell, (lo, hi), slice, te, tm)
            }
        })
    }

    /// Σ_c w_c·(TE + TM)/2 of order `m`'s stored values at the corners of the proposal `p`
    /// (its weights w_c); 0 outside its orders.
    #[inline]
    pub(crate) fn cell_efficiency(&self, p: &CellProposal, m: i32) -> f64 {
        if m < p.lo || m > p.hi {
            return 0.0;
        }
        // m − order_min is in 0..order_count: p's orders are stored ones.
        let k = (i64::from(m) - i64::from(self.order_min)) as usize;
        #[cfg(feature = "std")]
        if let Some(Some(b)) = self.lookup.by_node.get() {
            // The same products, in the same order, of the same values.
            let mut e = 0.0;
            for c in 0..p.count {
                e += p.w[c] * b.eta[p.at[c] * b.orders + k];
            }
            return e;
        }
        let base = k * p.slice;
        with_arrays!(self, |_sin, _bet, _lam, te, tm| {
            let mut e = 0.0;
            for c in 0..p.count {
                // stored_unpolarised's operations.
                let v = base + p.at[c];
                e += p.w[c] * (0.5 * (te.at(v) + tm.at(v)));
            }
            e
        })
    }

    /// Σ over the orders `lo..=hi` of the corners' weighted stored unpolarised values (`w`, at
    /// the flat indices `at` of an order's `slice` nodes): corner by corner from [`ByNode`]
    /// where it is kept, else order by order (the same terms, summed in another order).
    fn proposal_total<T: Values + ?Sized>(
        &self,
        (lo, hi): (i32, i32),
        (w, at): (&[f64], &[usize]),
        slice: usize,
        te: &T,
        tm: &T,
    ) -> f64 {
        let first = |m: i32| (i64::from(m) - i64::from(self.order_min)) as usize;
        let (k0, k1) = (first(lo), first(hi) + 1);
        #[cfg(feature = "std")]
        if let Some(b) = self
            .lookup
            .by_node
            .get_or_init(|| ByNode::new(te, tm, slice, self.order_count))
        {
            let mut total = 0.0;
            for (&wc, &n) in w.iter().zip(at) {
                let row = &b.eta[n * b.orders + k0..n * b.orders + k1];
                total += wc * row.iter().sum::<f64>();
            }
            return total;
        }
        let mut total = 0.0;
        for k in k0..k1 {
            for (&wc, &n) in w.iter().zip(at) {
                // stored_unpolarised's operations.
                let v = k * slice + n;
                total += wc * (0.5 * (te.at(v) + tm.at(v)));
            }
        }
        total
    }

    /// The stored unpolarised efficiency (TE + TM)/2 at flat index `at` of the values (order
    /// k's node n at k·slice + n): what the proposal reads, and what the GPU's packed table
    /// holds for it.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    #[inline]
    pub(crate) fn stored_unpolarised(&self, at: usize) -> f64 {
        with_arrays!(self, |_sin, _bet, _lam, te, tm| 0.5
            * (te.at(at) + tm.at(at)))
    }

    /// The proposal of a query's cell: the stored orders `lo..=hi` trimmed to those that
    /// propagate at the query (a contiguous run: α_m grows with m), the corners of positive
    /// weight, and the sum.
    fn propose<C: OrderCell, T: Values + ?Sized>(
        &self,
        cell: &C,
        (mut lo, mut hi): (i32, i32),
        slice: usize,
        te: &T,
        tm: &T,
    ) -> Option<CellProposal> {
        while lo <= hi && !cell.propagates(self.period_nm, lo) {
            lo += 1;
        }
        while hi >= lo && !cell.propagates(self.period_nm, hi) {
            hi -= 1;
        }
        if hi < lo {
            return None;
        }
        let (cw, ci) = cell.corners();
        let (mut w, mut at, mut count) = ([0.0; 8], [0usize; 8], 0);
        for (c, &x) in cw.iter().enumerate() {
            if x > 0.0 {
                w[count] = x;
                at[count] = ci[c];
                count += 1;
            }
        }
        let total = self.proposal_total((lo, hi), (&w[..count], &at[..count]), slice, te, tm);
        Some(CellProposal {
            w,
            at,
            count,
            slice,
            lo,
            hi,
            total,
        })
    }
}
