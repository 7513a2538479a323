//! The amplitude reading's order distribution of the grating's sampler (the counterpart of pbrt's microfacet
//! distribution): which orders a direction `wo` can reach at λ, their weights, the choice of one
//! order and its probability.
//!
//! Order m's period in the phase x = u/(λ/d) is [m − ½, m + ½) for finite N (its lobe spreads
//! over the whole period), and the point x = m for N = ∞. The **candidates** for `wo` are the
//! orders whose period (or point) meets the u-range (wo.x − 1, wo.x + 1) of the disk D. Order m
//! is chosen with probability P(m) = w_m/Σ w over the candidates, with
//! w_m = η_m/ρ² + ε·U_m for finite N (ε = [`DEFENSIVE_ORDER_SHARE`], η_m the order's efficiency,
//! U_m = 3/(3 + (π·ρ·(|m| − ½)₊)²) an upper bound of S(π·ρ·x)/1 over the period, since
//! S(β) ≤ 3/(3 + β²)), and w_m = η_m/ρ² for N = ∞. The defensive term keeps P(m) > 0 for
//! missing orders (η_m = 0), where the finite-N value is small but not 0. Above
//! `MAX_WEIGHTED_ORDERS` candidates (d/λ above about 127) the choice is uniform instead
//! (bounded work).

use core::f64::consts::PI;

use glam::DVec3;

use crate::num::kernel::single_slit_cycles;
use crate::num::math;
use crate::{Grating, Slits};

/// The share ε of the envelope bound U_m in the order weights w_m = η_m/ρ² + ε·U_m.
#[doc(hidden)]
pub const DEFENSIVE_ORDER_SHARE: f64 = 0.125;
/// Above this many candidate orders the order is chosen uniformly (bounded work per call).
pub(crate) const MAX_WEIGHTED_ORDERS: i64 = 256;
/// x = d·u/λ beyond this magnitude is not sampled (orders would not fit an `i64` exactly).
const MAX_PHASE: f64 = 4.0e15;
/// Orders |m| ≤ this have their weights w_m and prefix sums in a table, so that the candidates'
/// total and an order's probability cost O(1) instead of O(K).
const TABLE_ORDERS: usize = 64;
/// Windows of at most this many candidates that contain order 0 are chosen from by a
/// bisection of fixed depth over this many lanes (a power of two).
const CHOICE_LANES: usize = 16;
const _: () = assert!(CHOICE_LANES.is_power_of_two());
/// The index of order m = 0 in [`AmplitudeOrders`]'s `cum` table (which starts at m = −65).
const CUM_ZERO: i64 = TABLE_ORDERS as i64 + 1;
/// The `cum` table's length: m = −65 ..= 64, and `CHOICE_LANES` entries of padding.
const CUM_LEN: usize = 2 * TABLE_ORDERS + 2 + CHOICE_LANES;

/// The candidate orders for one (wo, λ) and the normaliser of their weights.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidates {
    pub lo: i64,
    pub hi: i64,
    /// Σ w over the candidates (their count for the uniform choice).
    pub total: f64,
    /// The choice is uniform (more than `MAX_WEIGHTED_ORDERS` candidates).
    pub uniform: bool,
}

/// The amplitude reading's order weights of one grating: w_m for |m| ≤ 64 and their prefix
/// sums, so that the candidates' total costs O(1); other orders are weighed on the fly.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct AmplitudeOrders {
    slits: Slits,
    rho: f64,
    /// w_0.
    w0: f64,
    /// prefix\[k\] = Σ_{j=1}^{k} w_j (w is even in m).
    prefix: [f64; TABLE_ORDERS + 1],
    /// weight\[k\] = w_k = w_{−k}, exactly as [`AmplitudeOrders::weight_of`] computes it.
    weight: [f64; TABLE_ORDERS + 1],
    /// cum\[m + 65\] = C(m), the cumulative weight anchored at order 0: Σ_{j=0}^{m} w_j for
    /// m ≥ 0 and −Σ_{j=m+1}^{−1} w_j for m < 0, so that Σ_{j=a}^{b} w_j = C(b) − C(a − 1); for
    /// m = −65 ..= 64, then padded with C(64).
    cum: [f64; CUM_LEN],
}

impl AmplitudeOrders {
    pub(super) fn new(grating: &Grating) -> AmplitudeOrders {
        let mut d = AmplitudeOrders {
            slits: grating.slits(),
            rho: grating.open_fraction(),
            w0: 0.0,
            prefix: [0.0; TABLE_ORDERS + 1],
            weight: [0.0; TABLE_ORDERS + 1],
            cum: [0.0; CUM_LEN],
        };
        d.w0 = d.weight_of(0);
        d.weight[0] = d.w0;
        for k in 1..=TABLE_ORDERS {
            d.weight[k] = d.weight_of(k as i64);
            d.prefix[k] = d.prefix[k - 1] + d.weight[k];
        }
        // C(m) = prefix[m] + w_0 for m ≥ 0, C(−1) = 0, C(m) = −prefix[−m − 1] for m < −1.
        for (i, c) in d.cum.iter_mut().enumerate() {
            let m = (i as i64 - CUM_ZERO).min(TABLE_ORDERS as i64);
            *c = if m >= 0 {
                d.prefix[m as usize] + d.w0
            } else {
                -d.prefix[(-m - 1) as usize]
            };
        }
        d
    }

    /// The open fraction ρ = w/d.
    #[inline]
    pub(super) fn rho(&self) -> f64 {
        self.rho
    }

    /// The grating's N.
    #[inline]
    pub(super) fn slits(&self) -> Slits {
        self.slits
    }

    /// η_m = ρ²·S(π·ρ·m), the amplitude reading's efficiency of order m.
    #[inline]
    pub(super) fn efficiency(&self, m: i64) -> f64 {
        self.rho * self.rho * single_slit_cycles(self.rho * m as f64)
    }

    /// The weight w_m of order m, computed.
    #[inline]
    fn weight_of(&self, m: i64) -> f64 {
        let s = single_slit_cycles(self.rho * m as f64);
        match self.slits {
            Slits::Infinite => s,
            Slits::Finite(_) => s + DEFENSIVE_ORDER_SHARE * envelope_bound(self.rho, m),
        }
    }

    /// The weight w_m of order m.
    #[inline]
    pub(super) fn weight(&self, m: i64) -> f64 {
        let k = m.unsigned_abs();
        if k <= TABLE_ORDERS as u64 {
            self.weight[k as usize]
        } else {
            self.weight_of(m)
        }
    }

    /// Σ_{k=a}^{b} w_k for −64 ≤ a ≤ b ≤ 64.
    #[inline(always)]
    fn sum(&self, a: i64, b: i64) -> f64 {
        let p = |k: i64| self.prefix[k as usize];
        if a >= 1 {
            p(b) - p(a - 1)
        } else if b <= -1 {
            p(-a) - p(-b - 1)
        } else {
            p(-a) + self.w0 + p(b)
        }
    }

    /// Whether [lo, hi] lies inside the table.
    #[inline]
    fn tabled(lo: i64, hi: i64) -> bool {
        lo >= -(TABLE_ORDERS as i64) && hi <= TABLE_ORDERS as i64
    }

    /// The candidate orders for wo, given the orders per unit of u, d/λ (the inverse of the
    /// step λ/d: products, not quotients, on the path of every sample), or `None` when there
    /// are none. Inlined so that the result stays in registers.
    #[inline(always)]
    pub(super) fn candidates(&self, wo: DVec3, inv_step: f64) -> Option<Candidates> {
        let (lo, hi) = candidate_range(self.slits, wo, inv_step)?;
        let count = hi - lo + 1;
        if count > MAX_WEIGHTED_ORDERS {
            return Some(Candidates {
                lo,
                hi,
                total: count as f64,
                uniform: true,
            });
        }
        let total = if Self::tabled(lo, hi) {
            self.sum(lo, hi)
        } else {
            (lo..=hi).map(|m| self.weight(m)).sum()
        };
        (total > 0.0).then_some(Candidates {
            lo,
            hi,
            total,
            uniform: false,
        })
    }

    /// The weight of order m among the candidates `c` (1 for the uniform choice).
    #[inline]
    pub(super) fn candidate_weight(&self, c: &Candidates, m: i64) -> f64 {
        if c.uniform {
            1.0
        } else {
            self.weight(m)
        }
    }

    /// Chooses an order from `uc` in [0, 1); returns it with its probability.
    #[inline]
    pub(super) fn choose(&self, c: &Candidates, uc: f64) -> (i64, f64) {
        if c.uniform {
            let k = ((uc * c.total) as i64).clamp(0, c.hi - c.lo);
            return (c.lo + k, 1.0 / c.total);
        }
        let target = uc * c.total;
        if c.lo <= 0 && c.hi >= 0 && c.hi - c.lo < CHOICE_LANES as i64 {
            // The first m with Σ_{lo}^{m} w = C(m) − C(lo − 1) > target (hi if none), as the
            // number of m ≥ lo with C(m) − C(lo − 1) ≤ target, at most hi − lo: counted over
            // fixed lanes (C is non-decreasing, so the lanes past hi count only where target
            // rounds to the total, and the cap takes them back).
            // Order 0 lies in the window, so |C| is at most the window's total and the
            // differences round like a running sum. An order of weight 0 has C(m) = C(m − 1)
            // and is never the first above target, except as hi.
            let start = (c.lo + CUM_ZERO) as usize;
            if let Some(lanes) = self.cum.get(start..start + CHOICE_LANES) {
                let base = self.cum[start - 1];
                // C(m) − C(lo − 1) is non-decreasing along the lanes (a difference with a
                // constant is monotone), so the count is the lanes' partition point: log₂ 16
                // halvings, each a comparison and a conditional add.
                let (mut k, mut half) = (0usize, CHOICE_LANES / 2);
                while half > 0 {
                    if lanes[k + half - 1] - base <= target {
                        k += half;
                    }
                    half /= 2;
                }
                let mut m = c.lo + (k as i64).min(c.hi - c.lo);
                while m > c.lo && self.weight(m) == 0.0 {
                    m -= 1;
                }
                return (m, self.weight(m) / c.total);
            }
        }
        if Self::tabled(c.lo, c.hi) {
            // The first m with Σ_{lo}^{m} w > target (hi if none), by a scan of the table's
            // weights: a handful of candidates in practice, and one mispredicted branch where a
            // bisection has one per step.
            let mut m = c.lo;
            let mut acc = self.weight[m.unsigned_abs() as usize];
            while acc <= target && m < c.hi {
                m += 1;
                acc += self.weight[m.unsigned_abs() as usize];
            }
            while m > c.lo && self.weight(m) == 0.0 {
                m -= 1;
            }
            return (m, self.weight(m) / c.total);
        }
        let mut acc = 0.0;
        let mut last = c.lo;
        for m in c.lo..=c.hi {
            let w = self.weight(m);
            if w > 0.0 {
                last = m;
                acc += w;
                if target < acc {
                    return (m, w / c.total);
                }
            }
        }
        (last, self.weight(last) / c.total)
    }

    /// max over the candidates of U_m/w_m (the order part of the weight bound); U_m/1 for the
    /// uniform choice's worst order.
    pub(super) fn worst_envelope_ratio(&self, c: &Candidates) -> f64 {
        if c.uniform {
            return 1.0;
        }
        (c.lo..=c.hi).fold(0.0, |w, m| {
            w.max(envelope_bound(self.rho, m) / self.weight(m))
        })
    }
}

/// The candidate orders [lo, hi] for wo, given the orders per unit of u, d/λ: those whose
/// period [m − ½, m + ½) in the phase (finite N) or point m (N = ∞) meets the disk's u-range
/// (wo.x − 1, wo.x + 1); `None` when there are none or the phase is beyond [`MAX_PHASE`].
#[inline(always)]
pub(super) fn candidate_range(slits: Slits, wo: DVec3, inv_step: f64) -> Option<(i64, i64)> {
    let x_lo = (wo.x - 1.0) * inv_step;
    let x_hi = (wo.x + 1.0) * inv_step;
    if !(x_lo.abs() < MAX_PHASE && x_hi.abs() < MAX_PHASE) {
        return None;
    }
    let (lo, hi) = match slits {
        Slits::Finite(_) => (
            floor_exact(x_lo - 0.5) as i64 + 1,
            ceil_exact(x_hi + 0.5) as i64 - 1,
        ),
        Slits::Infinite => (floor_exact(x_lo) as i64 + 1, ceil_exact(x_hi) as i64 - 1),
    };
    (hi >= lo).then_some((lo, hi))
}

/// U_m = 3/(3 + (π·ρ·(|m| − ½)₊)²) ≥ S(π·ρ·x) on the period of m, since S(β) ≤ 3/(3 + β²).
#[inline]
fn envelope_bound(rho: f64, m: i64) -> f64 {
    let a = ((m.unsigned_abs() as f64) - 0.5).max(0.0) * rho * PI;
    3.0 / (3.0 + a * a)
}

/// ⌊a⌋ for finite a through `rint` (no library call where `floor` is not an instruction).
#[inline(always)]
pub(super) fn floor_exact(a: f64) -> f64 {
    let r = math::rint(a);
    if r > a {
        r - 1.0
    } else {
        r
    }
}

/// ⌈a⌉ for finite a through `rint`.
#[inline(always)]
pub(super) fn ceil_exact(a: f64) -> f64 {
    let r = math::rint(a);
    if r < a {
        r + 1.0
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::{ceil_exact, floor_exact, AmplitudeOrders, CHOICE_LANES};
    use crate::Grating;
    use glam::DVec3;

    /// The order choice is the inverse CDF of w_m/Σ w over the candidates: the first m whose
    /// running sum from lo exceeds uc·Σ w, with its probability w_m/Σ w (a direct running sum
    /// here), for the branch-free windows around order 0 and for the scanned ones, finite N
    /// (every weight positive) and N = ∞ (the even orders of ρ = ½ weigh 0 and are never
    /// chosen).
    #[test]
    fn choice_is_the_inverse_cdf() {
        let (mut lanes, mut scanned) = (0, 0);
        for g in [
            Grating::new(1600.0, 800.0, 30).unwrap(),
            Grating::infinite(1600.0, 800.0).unwrap(),
            Grating::new(10_000.0, 2500.0, 5).unwrap(),
        ] {
            let o = AmplitudeOrders::new(&g);
            for wx in [-0.95, -0.6, 0.0, 0.3, 0.9] {
                for l in [360.0, 450.0, 633.0, 830.0] {
                    let wo = DVec3::new(wx, 0.0, (1.0 - wx * wx).sqrt());
                    let Some(c) = o.candidates(wo, g.period_nm() / l) else {
                        continue;
                    };
                    if c.lo <= 0 && c.hi >= 0 && c.hi - c.lo < CHOICE_LANES as i64 {
                        lanes += 1;
                    } else {
                        scanned += 1;
                    }
                    for i in 0..1000 {
                        let uc = (i as f64 + 0.37) / 1000.0;
                        let target = uc * c.total;
                        let mut acc = 0.0;
                        let mut want = c.hi;
                        for m in c.lo..=c.hi {
                            acc += o.weight(m);
                            if acc > target {
                                want = m;
                                break;
                            }
                        }
                        while want > c.lo && o.weight(want) == 0.0 {
                            want -= 1;
                        }
                        let (m, p) = o.choose(&c, uc);
                        assert_eq!(m, want, "{g:?} wo.x={wx} λ={l} uc={uc}");
                        assert!(o.weight(m) > 0.0);
                        assert_eq!(p, o.weight(m) / c.total);
                    }
                }
            }
        }
        assert!(lanes > 10 && scanned > 10, "{lanes} {scanned}");
    }

    /// `floor_exact` and `ceil_exact` agree with `floor` and `ceil` on the ties, the signed
    /// zeros, the largest exact integers and a dense grid of fractions.
    #[test]
    fn floor_and_ceil_through_rint() {
        let mut cases = vec![
            -2.5,
            -2.0,
            -1.5,
            -0.5,
            -0.0,
            0.0,
            0.3,
            0.5,
            1.5,
            2.5,
            1e15 + 0.5,
            -4e15,
        ];
        cases.extend((-4000..=4000).map(|k| k as f64 * 0.125 + 0.0625 * (k % 3) as f64));
        for a in cases {
            assert_eq!(floor_exact(a), a.floor(), "{a}");
            assert_eq!(ceil_exact(a), a.ceil(), "{a}");
        }
    }
}
