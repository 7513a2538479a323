//! Each node's q = η·cos θi/cos θm, per order and polarisation: the quantity the interpolation
//! weighs at the corners of a query's cell (parent module, step 4 of the rule). Computed once
//! per table on first use (feature `std`: a `OnceLock`), it spares every query two square
//! roots and a division per corner; a query without it (no `std`, or a table of more than
//! [`MAX_Q_VALUES`] values) computes each corner's q with the same operations, so both give
//! the same bits.

#[cfg(feature = "std")]
use std::{sync::OnceLock, vec::Vec};

use super::corner_q;
use super::{EfficiencyTable, Values};
use crate::num::math;

/// The largest table (values per polarisation) whose q's are kept: 2²⁰, 32 MiB of them; a
/// larger table computes them at each query.
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(super) const MAX_Q_VALUES: usize = 1 << 20;

/// A corner where its order does not propagate (cos² θm at or below the grazing corner): the
/// q's stand-in (every real q is ≥ 0).
pub(super) const NOT_PROPAGATING: f64 = -1.0;

/// The nodes' (q_TE, q_TM) of one table, flattened as its values, computed on first use.
#[derive(Debug, Clone, Default)]
pub(super) struct NodeQ {
    #[cfg(feature = "std")]
    q: OnceLock<Option<Vec<[f64; 2]>>>,
}

impl PartialEq for NodeQ {
    /// Derived data: equal tables have equal q's, computed or not.
    fn eq(&self, _other: &NodeQ) -> bool {
        true
    }
}

/// The q's of a table, or `None` where they are not kept.
#[cfg(feature = "std")]
pub(super) type Computed = Option<Vec<[f64; 2]>>;
/// Without `std` nothing is kept.
#[cfg(not(feature = "std"))]
pub(super) type Computed = Option<[[f64; 2]; 0]>;

impl NodeQ {
    // Every table is built by a constructor (feature `alloc`) or is a preset.
    #[cfg_attr(not(any(feature = "alloc", feature = "presets")), allow(dead_code))]
    pub(super) const fn new() -> NodeQ {
        NodeQ {
            #[cfg(feature = "std")]
            q: OnceLock::new(),
        }
    }

    /// The q's, computed by `compute` on the first call; `None` without `std` or where
    /// `compute` keeps none.
    #[inline]
    pub(super) fn get(&self, compute: impl FnOnce() -> Computed) -> Option<&[[f64; 2]]> {
        #[cfg(feature = "std")]
        {
            self.q.get_or_init(compute).as_deref()
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = compute;
            None
        }
    }
}

impl EfficiencyTable {
    /// The nodes' q's of every order (`nodes_q.rs`), with the corners' formulas of
    /// [`Cell::find`] and `Cell3::find`; `None` for a table of more than
    /// [`MAX_Q_VALUES`] values.
    #[cfg_attr(not(feature = "std"), allow(dead_code))]
    pub(super) fn q_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
    ) -> Computed {
        #[cfg(feature = "std")]
        {
            let slice = sin.count() * bet.count().max(1) * lam.count();
            if slice * self.order_count > MAX_Q_VALUES {
                return None;
            }
            let mut q = std::vec::Vec::with_capacity(slice * self.order_count);
            self.each_node_q_in(sin, bet, lam, te, tm, |v| q.push(v));
            Some(q)
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = (sin, bet, lam, te, tm);
            None
        }
    }

    /// Every node's (q_TE, q_TM) in the values' order (order, |β| plane, λ, s), or
    /// [`NOT_PROPAGATING`] twice where the order does not propagate there: `corner_q` with the
    /// corner formulas of [`Cell::find`] (a classical table) and `Cell3::find` (a conical one).
    #[cfg_attr(not(any(feature = "std", feature = "gpu")), allow(dead_code))]
    pub(super) fn each_node_q_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
        mut f: impl FnMut([f64; 2]),
    ) {
        let (n_s, n_b, n_l) = (sin.count(), bet.count().max(1), lam.count());
        let slice = n_s * n_b * n_l;
        for k in 0..self.order_count {
            let mf = f64::from(self.order_min) + k as f64;
            for b in 0..n_b {
                // A classical table: β = 0 and the corner formulas of `Cell::find`.
                let (b2, cb) = match bet.count() {
                    0 => (0.0, 1.0),
                    _ => {
                        let bn = bet.at(b);
                        (bn * bn, math::sqrt(1.0 - bn * bn))
                    }
                };
                for j in 0..n_l {
                    for i in 0..n_s {
                        let sn = sin.at(i);
                        let (alpha, cos_i) = match bet.count() {
                            0 => (sn, math::sqrt(1.0 - sn * sn)),
                            _ => (sn * cb, cb * math::sqrt(1.0 - sn * sn)),
                        };
                        let at = k * slice + (b * n_l + j) * n_s + i;
                        f(corner_q(
                            alpha,
                            b2,
                            lam.at(j),
                            cos_i,
                            mf,
                            self.period_nm,
                            (te, tm),
                            at,
                        ));
                    }
                }
            }
        }
    }
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::super::{conical::Cell3, Cell, EfficiencyTable, OrderCell, Storage, Values};

    /// One order's interpolation (the order, its slice's start, the q's or none) as bits.
    type OrderBits<'a> = &'a dyn Fn(i32, usize, Option<&[[f64; 2]]>) -> [u64; 2];

    /// Every order at `count` random queries of `t`, interpolated from the kept q's and from
    /// q's computed at the query: the same bits.
    fn same_bits(t: &EfficiencyTable, count: usize, state: &mut u64) -> usize {
        let mut next = || {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (*state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut compared = 0;
        with_arrays!(t, |sin, bet, lam, te, tm| {
            let q = t
                .q_in(sin, bet, lam, te, tm)
                .expect("a small table keeps its q's");
            let slice = sin.count() * bet.count().max(1) * lam.count();
            for _ in 0..count {
                let s = -1.05 + 2.1 * next();
                let l = 340.0 + 520.0 * next();
                let b = 0.95 * next();
                let check = |cell: OrderBits<'_>| {
                    let mut n = 0;
                    for (k, m) in t.orders().enumerate() {
                        assert_eq!(cell(m, k * slice, None), cell(m, k * slice, Some(&q)));
                        n += 1;
                    }
                    n
                };
                let bits = |e: crate::relief::Polarised| [e.te.to_bits(), e.tm.to_bits()];
                compared += if bet.count() > 0 {
                    let a = s * (1.0 - b * b).sqrt();
                    match Cell3::find(sin, bet, lam, a, b, l) {
                        Some(c) => {
                            check(&|m, base, q| bits(c.order(t.period_nm, m, base, (te, tm), q)))
                        }
                        None => 0,
                    }
                } else {
                    match Cell::find(sin, lam, s, l) {
                        Some(c) => check(&|m, base, q| {
                            bits(OrderCell::order(&c, t.period_nm, m, base, (te, tm), q))
                        }),
                        None => 0,
                    }
                };
            }
        });
        compared
    }

    #[test]
    fn kept_and_computed_q_give_the_same_bits() {
        let mut state = 17u64;
        let mut compared = 0;
        #[cfg(feature = "presets")]
        for p in crate::relief::Preset::ALL {
            compared += same_bits(p.table(), 3000, &mut state);
        }
        // A conical table: two |β| planes, values 0 exactly where an order is evanescent.
        let (d, sn, bn, ln) = (
            1600.0,
            [-0.9, -0.3, 0.2, 0.9],
            [0.0, 0.7],
            [400.0, 550.0, 700.0],
        );
        let mut values = std::vec::Vec::new();
        for k in 0..5 {
            for &b in &bn {
                for &l in &ln {
                    for &x in &sn {
                        let am = x * (1.0f64 - b * b).sqrt() + f64::from(k - 2) * l / d;
                        let live = 1.0 - am * am - b * b > 0.0;
                        values.push(if live {
                            0.01 + 0.02 * f64::from(k)
                        } else {
                            0.0
                        });
                    }
                }
            }
        }
        let t = EfficiencyTable::new_conical(
            d,
            -2,
            sn.to_vec(),
            bn.to_vec(),
            ln.to_vec(),
            values.clone(),
            values.iter().map(|v| 0.5 * v).collect(),
        )
        .unwrap();
        compared += same_bits(&t, 3000, &mut state);
        assert!(compared > 10_000, "{compared}");
    }
}
