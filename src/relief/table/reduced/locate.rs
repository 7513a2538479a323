//! A reduced table's cell location in O(1) (`Reduced::find`): uniform bins on each axis (the
//! s′ nodes, the planes' |β| and every plane's wavelengths) that name the interval of their
//! start, and what the corners need of the nodes alone (each plane's c = √(1 − β²), each s′
//! node's √(1 − s′²) and the reciprocal widths of the intervals), derived once when the table
//! is made. A query takes its bin's interval and steps to its own, so the interval is the
//! binary search's (`interval`) for every query, and c and the roots are the formulas' own
//! bits; the weights are products by the reciprocal widths (as the classical table's fast
//! reading takes them), within an ulp or two of the quotients, and the quotients themselves
//! where a subnormal width's reciprocal overflows (`fraction` in the parent module).

use alloc::vec::Vec;

use super::super::interval;
use super::cb;
use crate::num::math;

/// The most bins of one axis: a bin per smallest gap of the nodes up to this (a denser axis
/// takes a few steps from its bin's interval).
const MAX_BINS: usize = 4096;

/// Uniform bins over an axis's nodes, each holding the interval of its start.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::relief::table) struct Bins {
    lo: f64,
    /// Bins per unit of the axis.
    scale: f64,
    first: Vec<u32>,
}

impl Bins {
    /// The bins of `nodes` (strictly increasing, at least 2).
    fn new(nodes: &[f64]) -> Bins {
        let (lo, hi) = (nodes[0], nodes[nodes.len() - 1]);
        let gap = nodes
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        let span = hi - lo;
        let count = if gap > 0.0 && span > 0.0 && (span / gap).is_finite() {
            (math::ceil(span / gap) as usize).clamp(1, MAX_BINS)
        } else {
            1
        };
        let scale = count as f64 / span;
        let scale = if scale.is_finite() { scale } else { 0.0 };
        let first = (0..count)
            .map(|k| interval(nodes, lo + k as f64 / scale.max(f64::MIN_POSITIVE)) as u32)
            .collect();
        Bins { lo, scale, first }
    }

    /// The interval of `x` among `nodes` (the nodes the bins were made of): the largest i ≤
    /// n − 2 with nodes[i] ≤ x (0 below the first node), as `interval` finds it.
    #[inline]
    pub(in crate::relief::table) fn interval(&self, nodes: &[f64], x: f64) -> usize {
        let n = nodes.len();
        // A negative or NaN position saturates to bin 0.
        let k = ((x - self.lo) * self.scale) as usize;
        let mut i = self.first[k.min(self.first.len() - 1)] as usize;
        while i > 0 && nodes[i] > x {
            i -= 1;
        }
        while i + 2 < n && nodes[i + 1] <= x {
            i += 1;
        }
        i
    }
}

/// The locator of a reduced table.
#[derive(Debug, Clone, PartialEq)]
pub(in crate::relief::table) struct Locator {
    pub(in crate::relief::table) sin: Bins,
    pub(in crate::relief::table) bet: Bins,
    /// Plane p's wavelength bins.
    pub(in crate::relief::table) planes: Vec<Bins>,
    /// Plane p's c = √(1 − β_p²).
    pub(in crate::relief::table) c: Vec<f64>,
    /// Each s′ node's √(1 − s′²).
    pub(in crate::relief::table) root: Vec<f64>,
    /// 1/(s′_{i+1} − s′_i) of each s′ interval.
    pub(in crate::relief::table) inv_ds: Vec<f64>,
    /// 1/(c_{k+1} − c_k) of each pair of neighbouring planes (c falls as |β| grows; 0 where
    /// they coincide in c).
    pub(in crate::relief::table) inv_dc: Vec<f64>,
    /// 1/(λ_{j+1} − λ_j) of each plane's wavelength intervals, at the row of λ_j.
    pub(in crate::relief::table) inv_dl: Vec<f64>,
}

impl Locator {
    /// The locator of the checked grid: s′ nodes `sin`, planes `bet`, and the planes'
    /// wavelengths `lam`, plane p's at `rows[p]..rows[p + 1]`.
    pub(in crate::relief::table) fn new(
        sin: &[f64],
        bet: &[f64],
        lam: &[f64],
        rows: &[usize],
    ) -> Locator {
        let inv = |w: &[f64]| 1.0 / (w[1] - w[0]);
        let c: Vec<f64> = bet.iter().map(|&b| cb(b)).collect();
        Locator {
            sin: Bins::new(sin),
            bet: Bins::new(bet),
            planes: rows
                .windows(2)
                .map(|r| Bins::new(&lam[r[0]..r[1]]))
                .collect(),
            root: sin.iter().map(|&s| math::sqrt(1.0 - s * s)).collect(),
            inv_ds: sin.windows(2).map(inv).collect(),
            inv_dc: c
                .windows(2)
                .map(|w| {
                    if w[0] > w[1] {
                        1.0 / (w[1] - w[0])
                    } else {
                        0.0
                    }
                })
                .collect(),
            // A plane's last row starts no interval: 0 there.
            inv_dl: rows
                .windows(2)
                .flat_map(|r| lam[r[0]..r[1]].windows(2).map(inv).chain([0.0]))
                .collect(),
            c,
        }
    }
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use super::*;

    /// The bins' interval is the binary search's at every node, between nodes, beyond both
    /// ends and at the nodes' neighbours in f64, on even, graded and nearly coincident nodes.
    #[test]
    fn bins_find_the_binary_searchs_interval() {
        let axes: [Vec<f64>; 4] = [
            vec![-1.0, 1.0],
            (0..25).map(|k| -0.9999 + 0.083329 * f64::from(k)).collect(),
            vec![360.0, 380.0, 400.0, 820.0, 830.0, 954.5, 1097.7, 1262.3],
            vec![0.0, 1e-12, 2e-12, 0.5, 0.99999],
        ];
        for nodes in &axes {
            let bins = Bins::new(nodes);
            let mut xs = vec![f64::NEG_INFINITY, -1e300, 1e300, f64::INFINITY];
            for w in nodes.windows(2) {
                for t in [0.0, 0.1, 0.5, 0.9, 1.0] {
                    xs.push(w[0] + t * (w[1] - w[0]));
                }
            }
            for &x in nodes {
                // The neighbours in f64 (of a finite non-zero x, or 0's subnormals).
                let (up, down) = if x == 0.0 {
                    (f64::from_bits(1), -f64::from_bits(1))
                } else {
                    let b = x.to_bits();
                    let (a, c) = (f64::from_bits(b + 1), f64::from_bits(b - 1));
                    if x > 0.0 {
                        (a, c)
                    } else {
                        (c, a)
                    }
                };
                xs.extend([x, up, down]);
            }
            for x in xs {
                assert_eq!(
                    bins.interval(nodes, x),
                    interval(&nodes[..], x),
                    "{nodes:?} {x}"
                );
            }
        }
    }
}
