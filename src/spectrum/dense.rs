//! Bounded work at the two extremes of d·|u|: where the whole band lies inside order 0's central
//! lobe (the colour is the white, to rounding), and where the band holds so many orders that
//! walking them one by one would not end in reasonable time (a dense comb, summed block by
//! block in closed form).
//!
//! # The dense comb
//!
//! With q = d·|u| and a = w/d, order m peaks at λ_m = q/m and S(β_m) = sin²(π·a·m)/(π·a·m)².
//! Over a block of consecutive orders A..=B (the orders of a sixteenth of a 1 nm table row or
//! less, so the weight E·cmf is linear and 1/m² changes by a relative 2·10⁻⁴ at most across it),
//! each sum
//! the strategies need is the smooth factor at the block's centre times a sum of sin²(π·a·m) (or
//! of cos(2π·a·m)) over the block, which has the closed form of a Dirichlet sum:
//!
//! ```text
//! Σ_{m=A}^{B} cos(2π·a·m) = sin(π·a·n)·cos(π·a·(A + B)) / sin(π·a),   n = B − A + 1.
//! ```
//!
//! The smooth factor is taken at the block's centre (the midpoint rule in m, error O((n/m)²)
//! relative, below 10⁻⁷ with the blocks used here). For `Exact`, the light of one whole period
//! of x around order m is (q/m²)·E·cmf(q/m)·(π·a·m)⁻²·∫ sin²(π·a·x)·F_N(x) dx, and the period
//! integral is 1/(2N) − ½·cos(2π·a·m)·K_N(a), with K_N(a) = ∫_{−½}^{½} cos(2π·a·r)·F_N(r) dr
//! (lobe-exact quadrature for N ≤ [`K_QUADRATURE_SLITS`], else 1/N − J(a)/N² with
//! J(a) = ∫ sin²(π·a·r)/sin²(π·r) dr, whose error is O(N⁻⁴)); the partial periods at the band
//! ends are integrated by `Exact`'s own lobe walk.

use glam::DVec3;

use super::lobes::Lobes;
use super::{Spectral, BAND};
use crate::data::cie;
use crate::num::kernel::{n_slit_cycles, single_slit_cycles, sinpi};
use crate::num::math::{ceil, floor, rint};
use crate::num::quadrature::GL8;
use crate::Grating;

/// Above this many orders in the band (d·|u|·(1/360 − 1/830) > 4096, so d·|u| > 2.6 mm), the
/// grating strategies `PeakSearch`, `PaperPeaks` and `Exact` sum the orders block by block in
/// closed form instead of one at a time, so their work is bounded (about 2·10⁴ weights)
/// whatever the period. Below it they walk the orders, at most this many.
pub(crate) const DENSE_ORDERS: f64 = 4096.0;

/// `Exact` over a dense comb walks the lobes of the partial periods at the band ends only where
/// N·x stays below this (so that a lobe, 1/N wide in x, spans at least 2¹² ulp of x); beyond it
/// those few orders get their peak weight: an error of at most 3.5/N of two orders out of at
/// least 0.56·x, below 12.5/(N·x) < 10⁻¹¹ of the colour.
const WALK_ENDS_BELOW: f64 = 1_099_511_627_776.0; // 2⁴⁰

/// The first-order correction of a block is computed for blocks of at most this many orders
/// (2²⁶: n² stays exact enough; larger blocks hold orders beyond 2⁵³).
const MOMENT_MAX_BLOCK: f64 = 67_108_864.0;

/// Blocks per 1 nm row of the tables in the dense comb.
const BLOCKS_PER_ROW: usize = 16;

/// Below this many slits K_N(a) is integrated lobe by lobe (8·N evaluations); above it the
/// asymptotic form 1/N − J(a)/N² (error O(N⁻⁴) < 10⁻¹⁹ relative) is used.
const K_QUADRATURE_SLITS: u32 = 1024;

/// The whole band is inside order 0's central lobe when N·x < this at the shortest wavelength:
/// there S(β) and F_N(α) differ from 1 by less than (π·N·x)²/3 < 4·10⁻¹⁶, so the colour is the
/// illuminant's white to rounding (and the phase-space Jacobian q/x² would overflow below
/// d·|u| ≈ 5·10⁻³⁰³).
const ORDER0_EVERYWHERE: f64 = 1e-8;

/// sin(π·t) for any finite t (exact reduction; t beyond 2⁵³ is an even integer: 0).
fn sin_pi(t: f64) -> f64 {
    let k = rint(t);
    let s = sinpi(t - k);
    if rint(0.5 * k) * 2.0 == k {
        s
    } else {
        -s
    }
}

/// cos(π·t) for any finite t.
fn cos_pi(t: f64) -> f64 {
    let k = rint(t);
    let r = t - k;
    let c = sinpi(0.5 - r.abs());
    if rint(0.5 * k) * 2.0 == k {
        c
    } else {
        -c
    }
}

/// Σ_{m=A}^{A+n−1} cos(2π·a·m), clamped to [−n, n] (it is inside for exact arithmetic).
fn cos_sum(a: f64, first: f64, n: f64) -> f64 {
    // a in (0, 1]: sin(π·a) = 0 only for a = 1, where every term is 1.
    let den = sin_pi(a);
    if den == 0.0 {
        return n;
    }
    let last = first + n - 1.0;
    let v = sin_pi(a * n) * cos_pi(a * first + a * last) / den;
    v.clamp(-n, n)
}

/// Σ_{m=A}^{A+n−1} (m − m_c)·cos(2π·a·m), m_c the centre, clamped to its bound n²/4: the
/// first-order term of a smooth factor across the block.
fn cos_moment(a: f64, first: f64, n: f64) -> f64 {
    let sa = sin_pi(a);
    if sa == 0.0 || !(2.0..=MOMENT_MAX_BLOCK).contains(&n) {
        // a = 1: Σ(m − m_c) = 0; one order: m = m_c; huge blocks: orders beyond 2⁵³, where
        // the correction is far below the rounding of m itself.
        return 0.0;
    }
    let bound = 0.25 * n * n;
    let centre = first + 0.5 * (n - 1.0);
    // With m = m_c + j: −sin(2π·a·m_c)·Σ_j j·sin(2π·a·j), and
    // Σ_j j·sin(2π·a·j) = −[n·cos(π·a·n)·sin(π·a) − sin(π·a·n)·cos(π·a)] / (2·sin²(π·a)).
    let t = -(n * cos_pi(a * n) - sin_pi(a * n) * cos_pi(a) / sa) / (2.0 * sa);
    let v = -sin_pi(2.0 * a * centre) * t;
    if v.is_finite() {
        v.clamp(-bound, bound)
    } else {
        0.0
    }
}

/// Σ_{m=A}^{A+n−1} g(m)·(α − β·cos(2π·a·m)) for a smooth g, from g at the centre and the ends
/// (its first-order change across the block included).
fn block_sum(
    a: f64,
    first: f64,
    n: f64,
    (alpha, beta): (f64, f64),
    g: &dyn Fn(f64) -> DVec3,
) -> DVec3 {
    let last = first + n - 1.0;
    let centre = first + 0.5 * (n - 1.0);
    let gc = g(centre);
    let slope = if n >= 2.0 {
        (g(last) - g(first)) / (n - 1.0)
    } else {
        DVec3::ZERO
    };
    let v =
        gc * (alpha * n - beta * cos_sum(a, first, n)) - slope * (beta * cos_moment(a, first, n));
    v.max(DVec3::ZERO)
}

/// K_N(a) = ∫_{−½}^{½} cos(2π·a·r)·F_N(r) dr.
fn k_n(a: f64, n: u32) -> f64 {
    let nf = n as f64;
    if n <= K_QUADRATURE_SLITS {
        // Even integrand: twice the integral over [0, ½], lobe by lobe (zeros at r = k/N).
        let mut sum = 0.0;
        let mut lo = 0.0;
        let mut k = 1.0;
        while lo < 0.5 {
            let hi = (k / nf).min(0.5);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for (x, w) in GL8.nodes.iter().zip(GL8.weights) {
                let r = mid + half * x;
                sum += w * half * cos_pi(2.0 * a * r) * n_slit_cycles(r, n);
            }
            lo = hi;
            k += 1.0;
        }
        return 2.0 * sum;
    }
    // 1/N − (1/N²)·J(a), J(a) = 2∫_0^½ sin²(π·a·r)/sin²(π·r) dr (smooth: a² at r = 0).
    let mut j = 0.0;
    for piece in 0..4 {
        let (lo, hi) = (piece as f64 * 0.125, (piece + 1) as f64 * 0.125);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        for (x, w) in GL8.nodes.iter().zip(GL8.weights) {
            let r = mid + half * x;
            let q = sinpi(a * r) / sinpi(r);
            j += w * half * q * q;
        }
    }
    1.0 / nf - 2.0 * j / (nf * nf)
}

impl Spectral {
    /// Whether the whole band lies inside order 0's central lobe (see [`ORDER0_EVERYWHERE`]).
    pub(super) fn order0_everywhere(grating: &Grating, q: f64) -> bool {
        grating.slits().as_f64() * (q / BAND.min_nm()) < ORDER0_EVERYWHERE
    }

    /// Whether the band holds more than [`DENSE_ORDERS`] orders for q = d·|u|.
    pub(super) fn is_dense(q: f64) -> bool {
        q * (1.0 / BAND.min_nm() - 1.0 / BAND.max_nm()) > DENSE_ORDERS
    }

    /// Σ over blocks of consecutive orders first..=last of `block(first_m, count, centre_m)`,
    /// blocks at most 1/[`BLOCKS_PER_ROW`] of a 1 nm row, never straddling a row.
    fn blocks(
        q: f64,
        first: f64,
        last: f64,
        block: &mut dyn FnMut(f64, f64, f64) -> DVec3,
    ) -> DVec3 {
        let mut acc = DVec3::ZERO;
        if last.is_nan() || first.is_nan() || last < first {
            return acc;
        }
        // Orders of the row (j, j + 1] nm are m in [ceil(q/(j + 1)), ceil(q/j) − 1]; the rows
        // telescope, so every order between first and last is counted once.
        let rows = (BAND.max_nm() - BAND.min_nm()) as usize;
        let parts = rows * BLOCKS_PER_ROW;
        let edge = |i: usize| {
            let l = BAND.max_nm() - i as f64 / BLOCKS_PER_ROW as f64;
            ceil(q / l).clamp(first, last + 1.0)
        };
        let mut lo = edge(0).min(first);
        for i in 1..=parts {
            let hi = if i == parts { last + 1.0 } else { edge(i) };
            if hi > lo {
                let n = hi - lo;
                acc += block(lo, n, lo + 0.5 * (n - 1.0));
                lo = hi;
            }
        }
        acc
    }

    /// The first and last order m ≥ 1 with q/m inside the band, as floats (for any q > 0, also
    /// beyond `i32::MAX`).
    fn order_span(q: f64) -> (f64, f64) {
        let mut first = ceil(q / BAND.max_nm()).max(1.0);
        let mut last = floor(q / BAND.min_nm());
        if first > 1.0 && BAND.contains(q / (first - 1.0)) {
            first -= 1.0;
        }
        if !BAND.contains(q / first) {
            first += 1.0;
        }
        if BAND.contains(q / (last + 1.0)) {
            last += 1.0;
        }
        if !BAND.contains(q / last) {
            last -= 1.0;
        }
        (first, last)
    }

    /// `PeakSearch` over a dense comb: Σ_m S(β_m)·E·cmf(λ_m)·norm·λ_m/(|m|·N), block by block.
    pub(super) fn dense_peak_search(&self, grating: &Grating, q: f64) -> DVec3 {
        let n = grating.slits().as_f64();
        let h = |m: f64| {
            let l = q / m;
            self.weight(l) * (l / (m * n))
        };
        self.dense_slit_sum(grating, q, &h)
    }

    /// `PaperPeaks` over a dense comb: Σ_m S(β_m)·(E(λ_m)/Ē)·cmf(λ_m), block by block.
    pub(super) fn dense_paper_peaks(&self, grating: &Grating, q: f64) -> DVec3 {
        let scale = 1.0 / self.mean_power;
        let h = |m: f64| {
            let l = q / m;
            DVec3::from(cie::cmf(l)) * (self.illuminant.power(l) * scale)
        };
        // The paper's sum grows with the number of orders (about q/360 nm): beyond ~10³⁰⁰ of
        // them it saturates instead of overflowing.
        self.dense_slit_sum(grating, q, &h)
            .min(DVec3::splat(f64::MAX))
    }

    /// Σ_m S(β_m)·h(m) over the orders in the band, h smooth.
    fn dense_slit_sum(&self, grating: &Grating, q: f64, h: &dyn Fn(f64) -> DVec3) -> DVec3 {
        let a = grating.slit_width_nm() / grating.period_nm();
        let (first, last) = Self::order_span(q);
        let pa = core::f64::consts::PI * a;
        Self::blocks(q, first, last, &mut |m0, count, mid| {
            if a * (m0 + count - 1.0) < 1e-3 {
                // S is smooth across the block (it changes on a scale of 1/a orders), and
                // ½ − ½·cos would cancel: S itself at the centre.
                return h(mid) * (count * single_slit_cycles(a * mid));
            }
            // S(a·m) = sin²(π·a·m)/(π·a·m)² = (½ − ½·cos(2π·a·m))/(π·a·m)².
            block_sum(a, m0, count, (0.5, 0.5), &|m| h(m) / ((pa * m) * (pa * m)))
        })
    }

    /// `Exact` over a dense comb: the whole periods [m − ½, m + ½] inside the band in closed
    /// form block by block, the partial periods at the ends by `ends` (the lobe walk).
    pub(super) fn dense_exact(
        &self,
        grating: &Grating,
        lobes: &Lobes<'_>,
        q: f64,
        n: u32,
        ends: &dyn Fn(&Lobes<'_>, f64, f64) -> DVec3,
    ) -> DVec3 {
        let nf = n as f64;
        let a = grating.slit_width_nm() / grating.period_nm();
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        // Whole periods strictly inside, with one period of margin for the rounding of x.
        let first = ceil(x_lo) + 1.0;
        let last = floor(x_hi) - 1.0;
        let k = k_n(a, n);
        let pa = core::f64::consts::PI * a;
        let mut acc = Self::blocks(q, first, last, &mut |m0, count, mid| {
            // Light of period m: (q/m²)·E·cmf(q/m)·norm·∫ S(a·x)·F_N(x) dx.
            let g = |m: f64| {
                let l = q / m;
                self.weight(l) * (l / m)
            };
            if a * (m0 + count - 1.0) < 1e-3 {
                // S smooth over the block and across each period: S(a·m)·∫F_N = S(a·m)/N.
                return g(mid) * (count * single_slit_cycles(a * mid) / nf);
            }
            let coeffs = (0.5 / nf, 0.5 * k);
            block_sum(a, m0, count, coeffs, &|m| g(m) / ((pa * m) * (pa * m)))
        });
        if nf * x_hi <= WALK_ENDS_BELOW {
            acc += ends(lobes, x_lo, first - 0.5);
            acc += ends(lobes, last + 0.5, x_hi);
        } else {
            // Lobes of width 1/N are not resolved at this x: the orders of the partial end
            // periods get their peak weight S(a·m)·(q/m²)/N (see `WALK_ENDS_BELOW`).
            for m in [first - 2.0, first - 1.0, last + 1.0, last + 2.0] {
                let l = q / m;
                if m >= 1.0 && BAND.contains(l) {
                    acc += self.weight(l) * (single_slit_cycles(a * m) * l / (m * nf));
                }
            }
        }
        acc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dirichlet_sums_match_direct_sums() {
        for &a in &[0.5, 1.0 / 3.0, 0.123456, 0.999, 1.0, 1e-4] {
            for &(first, n) in &[(1.0, 1.0), (7.0, 40.0), (1000.0, 333.0)] {
                let direct: f64 = (0..n as u32)
                    .map(|j| cos_pi(2.0 * a * (first + j as f64)))
                    .sum();
                assert!((cos_sum(a, first, n) - direct).abs() < 1e-9 * n, "a = {a}");
            }
        }
    }

    #[test]
    fn k_n_forms_agree_at_the_switch() {
        // The quadrature and the asymptotic form of K_N at N = K_QUADRATURE_SLITS.
        for &a in &[0.5, 0.25, 0.9, 1.0] {
            let n = K_QUADRATURE_SLITS;
            let nf = n as f64;
            let quad = k_n(a, n);
            let mut j = 0.0;
            let steps = 20000;
            for i in 0..steps {
                let r = (i as f64 + 0.5) / steps as f64 * 0.5;
                let s = sinpi(a * r) / sinpi(r);
                j += s * s * 0.5 / steps as f64;
            }
            let asym = 1.0 / nf - 2.0 * j / (nf * nf);
            assert!((quad - asym).abs() < 1e-9 / nf, "a = {a}: {quad} vs {asym}");
        }
        // N = 1: F_1 = 1, K = sin(πa)/(πa).
        let a = 0.3;
        let expected = sin_pi(a) / (core::f64::consts::PI * a);
        assert!((k_n(a, 1) - expected).abs() < 1e-14);
    }

    /// The closed forms against walking the orders one by one, just above the switch
    /// (about 5000 orders), where both are affordable.
    #[test]
    fn dense_sums_match_the_order_walk() {
        // Measured worst 8.7e-8 relative (Exact, N = 1); the bound keeps a margin of 6×.
        const TOL: f64 = 5e-7;
        use crate::data::cie::Illuminant;
        let s = Spectral::new(Illuminant::D65);
        for &(d, w, n) in &[
            (3.2e6, 1.6e6, 1000u32),
            (3.2e6, 0.7e6, 7),
            (3.3e6, 3.3e6, 50),
            (3.2e6, 1.0, 100_000),
            (3.25e6, 1.1e6, 1),
        ] {
            let g = Grating::new(d, w, n).unwrap();
            let u = 1.0;
            let q = d * u;
            assert!(Spectral::is_dense(q));
            // Peak search and the paper's sum: the walk over every peak.
            let mut walk = DVec3::ZERO;
            let mut paper = DVec3::ZERO;
            for p in g.peaks(u, BAND) {
                walk += s.weight(p.wavelength_nm) * p.intensity * p.equivalent_width_nm;
                let e = s.illuminant.power(p.wavelength_nm) / s.mean_power * p.intensity;
                paper += DVec3::from(cie::cmf(p.wavelength_nm)) * e;
            }
            let dense = s.dense_peak_search(&g, q);
            let close = |a: DVec3, b: DVec3| (a - b).abs().max_element() <= TOL * b.max_element();
            assert!(close(dense, walk), "{d} {w} {n}: {dense} vs {walk}");
            let dp = s.dense_paper_peaks(&g, q);
            assert!(close(dp, paper), "{d} {w} {n}: {dp} vs {paper}");
            // Exact: its own order-by-order walk (pieces across the rows, lobes near
            // every integer) over the whole band.
            let lobes = Lobes::new(&s, &g, q, n as f64);
            let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
            let walk = super::super::exact::filon_walk(&lobes, x_lo, x_hi);
            let dense = s.exact(&g, u);
            assert!(close(dense, walk), "exact {d} {w} {n}: {dense} vs {walk}");
        }
    }
}
