//! `Exact`'s pieces across the rows of the tables: ∫ sin²(πNx)·R(x) dx over a piece [a, b] of
//! the phase x = d·|u|/λ away from the integers, whatever the number of 1 nm rows and lobes it
//! holds, exactly for the tables' piecewise form.
//!
//! Write R = W(λ)·K(x) with W = E·cmf the tables' weight, within each row a quadratic in λ
//! (E and the observer interpolated linearly), and K = S·env·norm·|dλ/dx| / (N·sin πx)² smooth on
//! the piece (its poles are the integers, at least the piece's width away). Around the piece's
//! centre wavelength λ_c each row's W is w₀ + w₁·τ + w₂·τ² in τ = λ − λ_c, so
//!
//! ```text
//! ∫ sin²(πNx)·R dx = Σ_rows Σ_k w_k,row · [H_k]_row,   H_k(x) = ∫^x sin²(πNs)·τ(s)^k·K(s) ds.
//! ```
//!
//! The three smooth functions g_k = τ^k·K are interpolated at [`POINTS`] Chebyshev nodes by one
//! polynomial p_k(t) each (t ∈ [−1, 1] across the piece), and both halves of sin² = ½ − ½·cos(2πNx)
//! are integrated in closed form: ½·∫p_k by its antiderivative, and ½·∫cos(2πNx)·p_k by Levin's
//! non-oscillatory antiderivative Re[e^{2πiNx}·P_k(t)], P_k the polynomial with
//! P_k' + iω·P_k = p_k (ω = 2πN·h, h the half-width), which is exact for a polynomial p_k and
//! found from the top coefficient down, P_n = (p_n − (n + 1)·P_{n+1})/(iω), with no growth of
//! rounding for a piece of [`MIN_LOBES`] lobes or more. The cost per row is one evaluation of
//! nine polynomials (three antiderivatives, three complex Levin polynomials) and one phase, with
//! no evaluation of S or of the pole, and the kinks of W at the rows are exact.
//!
//! The error is that of the interpolation of K: the double pole 1/sin²(πx) at a distance ε ≥ w
//! from a piece of width w (its Bernstein ellipse ρ ≥ 3 + √8, about 2·10⁻¹¹ of K's largest value
//! at [`POINTS`] = 16), S and the envelope's sinc² over at most `SLIT_SPAN` of their periods,
//! smooth factors beside. Where the colour comes from a piece at all, `Exact` agrees with a
//! composite rule of an eighth of a lobe to 1.8·10⁻¹¹ (`exact`'s tests).

use glam::DVec3;

use super::lobes::{Lobes, Row};
use crate::num::kernel::{single_slit_cycles, sinpi};
use crate::num::math::{ceil, rint};

/// Interpolation points per piece (Chebyshev points of the first kind; degree POINTS − 1): with
/// the pole at least one width away, the interpolant of K is within about 2·POINTS·ρ^(−POINTS)
/// = 2·10⁻¹¹ of its largest value (ρ = 3 + √8; `tests`), where 12 points left 2·10⁻⁸ of the
/// colour against the lobe walk.
pub(super) const POINTS: usize = 16;

/// A piece integrated here holds at least this many lobes of F_N, so ω = 2πN·h ≥ 4π: the
/// downward recursion of Levin's antiderivative multiplies by (n + 1)/ω at step n, whose partial
/// products stay below 1.8 for POINTS = 16, so it does not amplify rounding.
pub(super) const MIN_LOBES: f64 = 4.0;

/// The positive half of the Chebyshev points cos(π·(j + ½)/16), j = 0..7 (the test checks them
/// against `cos`).
const HALF_NODES: [f64; POINTS / 2] = [
    0.9951847266721969,
    0.9569403357322088,
    0.881921264348355,
    0.773010453362737,
    0.6343932841636455,
    0.4713967368259978,
    0.29028467725446233,
    0.09801714032956077,
];

const fn nodes() -> [f64; POINTS] {
    let mut t = [0.0; POINTS];
    let mut j = 0;
    while j < POINTS / 2 {
        t[j] = HALF_NODES[j];
        t[POINTS - 1 - j] = -HALF_NODES[j];
        j += 1;
    }
    t
}

/// The interpolation nodes in t ∈ [−1, 1].
const NODES: [f64; POINTS] = nodes();

/// The monomial coefficients of the Chebyshev polynomials: `T[n][k]` of t^k in T_n.
const fn chebyshev_monomials() -> [[f64; POINTS]; POINTS] {
    let mut t = [[0.0; POINTS]; POINTS];
    t[0][0] = 1.0;
    t[1][1] = 1.0;
    let mut n = 2;
    while n < POINTS {
        let mut k = 0;
        while k < POINTS {
            let mut v = -t[n - 2][k];
            if k > 0 {
                v += 2.0 * t[n - 1][k - 1];
            }
            t[n][k] = v;
            k += 1;
        }
        n += 1;
    }
    t
}

/// `MONO[k][j]`: the weight of the value at node j in the coefficient of t^k of the interpolant
/// (the discrete Chebyshev transform, then each T_n in monomials).
const fn monomial_matrix() -> [[f64; POINTS]; POINTS] {
    let tm = chebyshev_monomials();
    let mut m = [[0.0; POINTS]; POINTS];
    let mut j = 0;
    while j < POINTS {
        let x = NODES[j];
        let (mut prev, mut cur) = (1.0, x);
        let mut n = 0;
        while n < POINTS {
            let tn = if n == 0 {
                1.0
            } else if n == 1 {
                x
            } else {
                let next = 2.0 * x * cur - prev;
                prev = cur;
                cur = next;
                next
            };
            let scale = if n == 0 { 1.0 } else { 2.0 };
            let cn = scale / POINTS as f64 * tn;
            let mut k = 0;
            while k < POINTS {
                m[k][j] += cn * tm[n][k];
                k += 1;
            }
            n += 1;
        }
        j += 1;
    }
    m
}

/// See [`monomial_matrix`].
const MONO: [[f64; POINTS]; POINTS] = monomial_matrix();

/// ∫ over [a, b] of sin²(πNx)·R(x) (see the module), [a, b] inside one period of F_N's
/// envelope away from the integers (R's poles at least b − a away), holding at least
/// [`MIN_LOBES`] lobes, and within `SLIT_SPAN` periods of S and of the envelope's sinc².
pub(super) fn piece(l: &Lobes<'_>, a: f64, b: f64) -> DVec3 {
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let lc = l.q / c;
    // g_k = τ^k·K at the nodes.
    let mut g = [[0.0; POINTS]; 3];
    for (j, &t) in NODES.iter().enumerate() {
        let x = c + h * t;
        let lambda = l.q / x;
        let den = l.n * sinpi(x - rint(x)) * x;
        let k = single_slit_cycles(l.duty * x) * l.q * l.s.envelope_norm(lambda) / (den * den);
        let tau = lambda - lc;
        g[0][j] = k;
        g[1][j] = k * tau;
        g[2][j] = k * tau * tau;
    }
    // The polynomials of each boundary value, by lanes: ∫p_k (its constant cancels in the
    // differences) in lanes 0-2, Levin's P_k = re + i·im with P_k' + iω·P_k = p_k in lanes 3-5
    // and 6-8, coefficient n of t^n in row n.
    let inv = 1.0 / (2.0 * core::f64::consts::PI * l.n * h);
    let mut coefficients = [[0.0; LANES]; POINTS + 1];
    for (k, gk) in g.iter().enumerate() {
        // The nodes are symmetric (t_{P−1−j} = −t_j), so the coefficient of t^n takes the even
        // or the odd part of the values.
        let mut even = [0.0; POINTS / 2];
        let mut odd = [0.0; POINTS / 2];
        for j in 0..POINTS / 2 {
            even[j] = gk[j] + gk[POINTS - 1 - j];
            odd[j] = gk[j] - gk[POINTS - 1 - j];
        }
        let mut p = [0.0; POINTS];
        for (n, (pn, weights)) in p.iter_mut().zip(MONO.iter()).enumerate() {
            let part = if n % 2 == 0 { &even } else { &odd };
            *pn = weights.iter().zip(part.iter()).map(|(w, v)| w * v).sum();
        }
        for (n, pn) in p.iter().enumerate() {
            coefficients[n + 1][k] = pn / (n + 1) as f64;
        }
        // From the top coefficient down: P_n = (p_n − (n + 1)·P_{n+1})/(iω).
        let (mut re, mut im) = (0.0, -p[POINTS - 1] * inv);
        coefficients[POINTS - 1][3 + k] = re;
        coefficients[POINTS - 1][6 + k] = im;
        for n in (0..POINTS - 1).rev() {
            let f = (n + 1) as f64;
            let re_n = -im * (f * inv);
            let im_n = (re * f - p[n]) * inv;
            re = re_n;
            im = im_n;
            coefficients[n][3 + k] = re;
            coefficients[n][6 + k] = im;
        }
    }
    // The boundaries: λ = q/x falls from q/a to q/b; rows change at x = q/j for integers j.
    // They are taken in chunks, the polynomials evaluated across a chunk at once.
    let illuminant = l.s.illuminant();
    let mut acc = DVec3::ZERO;
    let mut previous: Option<(f64, [f64; 3])> = None;
    let mut j = ceil(l.q / a) - 1.0;
    let j_end = l.q / b;
    let mut next = a;
    let mut done = false;
    while !done {
        let mut xs = [b; CHUNK];
        let mut count = 0;
        while count < CHUNK && !done {
            xs[count] = next;
            count += 1;
            if next >= b {
                done = true;
                break;
            }
            loop {
                let hi = if j > j_end { (l.q / j).min(b) } else { b };
                j -= 1.0;
                if hi > next {
                    next = hi;
                    break;
                }
            }
        }
        let values = boundary_values(&coefficients, &xs, c, h, l.n);
        for (&x, v) in xs.iter().zip(values.iter()).take(count) {
            if let Some((x_prev, v_prev)) = previous {
                let row = Row::new(illuminant, l.q / (0.5 * (x_prev + x)));
                let [w0, w1, w2] = row.tau_expansion(lc);
                acc += w0 * (v[0] - v_prev[0]) + w1 * (v[1] - v_prev[1]) + w2 * (v[2] - v_prev[2]);
            }
            previous = Some((x, *v));
        }
    }
    acc
}

/// Polynomials evaluated at each boundary: ∫p_k, Re P_k, Im P_k for k = 0, 1, 2.
const LANES: usize = 9;
/// Boundaries evaluated together by `boundary_values`.
const CHUNK: usize = 8;

/// H_k(x) = h·(½·∫p_k − ½·Re[e^{2πiNx}·P_k]) (up to a constant) at each x of the chunk.
fn boundary_values(
    coefficients: &[[f64; LANES]; POINTS + 1],
    xs: &[f64; CHUNK],
    c: f64,
    h: f64,
    n: f64,
) -> [[f64; 3]; CHUNK] {
    let ts: [f64; CHUNK] = core::array::from_fn(|i| (xs[i] - c) / h);
    // Horner across the chunk, three lanes at a time (24 independent chains that fit the
    // registers); the Levin lanes' top coefficient is 0.
    let mut v = [[0.0; CHUNK]; LANES];
    for group in 0..LANES / 3 {
        let mut w = [[0.0; CHUNK]; 3];
        for row in coefficients.iter().rev() {
            for (l, wl) in w.iter_mut().enumerate() {
                let cn = row[3 * group + l];
                for (wi, &t) in wl.iter_mut().zip(ts.iter()) {
                    *wi = *wi * t + cn;
                }
            }
        }
        v[3 * group..3 * group + 3].copy_from_slice(&w);
    }
    let mut out = [[0.0; 3]; CHUNK];
    for (i, (o, &x)) in out.iter_mut().zip(xs.iter()).enumerate() {
        let (s, co) = sincos_2pi(n * x);
        for (k, ok) in o.iter_mut().enumerate() {
            *ok = 0.5 * h * (v[k][i] - (v[3 + k][i] * co - v[6 + k][i] * s));
        }
    }
    out
}

/// (sin 2πt, cos 2πt), from sin and cos of π·(t − round(t)) by the polynomial `sinpi`.
#[inline]
fn sincos_2pi(t: f64) -> (f64, f64) {
    let r = t - rint(t);
    let (s, c) = (sinpi(r), sinpi(0.5 - r.abs()));
    (2.0 * s * c, (c - s) * (c + s))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The nodes against `cos`. Measured 1.1e-16; margin above 10×.
    const NODES_TOL: f64 = 1e-14;
    /// The interpolant of a polynomial of degree POINTS − 1 (coefficients 3 − k/2, all of
    /// order one: the worst case for the monomial form, whose T_15 has coefficients up to 2¹⁴)
    /// against its own coefficients. Measured 1.1e-9; margin 10×.
    const COEFF_TOL: f64 = 1e-8;
    /// The interpolant of the double pole 1/(t + 3)² on [−1, 1] (a piece of width w at distance
    /// w from the pole, the closest `exact::filon_walk` takes) at 401 points, relative to its
    /// largest value: the Bernstein ellipse ρ = 3 + √8 gives about 2·16·ρ⁻¹⁶ = 2·10⁻¹¹.
    /// Measured 1.7e-11; margin 11×.
    const POLE_TOL: f64 = 2e-10;

    #[test]
    fn nodes_are_chebyshev_points() {
        for (j, &t) in NODES.iter().enumerate() {
            let want = (core::f64::consts::PI * (j as f64 + 0.5) / POINTS as f64).cos();
            assert!((t - want).abs() <= NODES_TOL, "node {j}: {t} vs {want}");
        }
    }

    /// The monomial coefficients of the interpolant of `f` at the nodes.
    fn interpolate(f: &dyn Fn(f64) -> f64) -> [f64; POINTS] {
        core::array::from_fn(|k| {
            MONO[k]
                .iter()
                .zip(NODES.iter())
                .map(|(w, &t)| w * f(t))
                .sum()
        })
    }

    #[test]
    fn the_interpolant_of_a_polynomial_is_the_polynomial() {
        let coefficients: [f64; POINTS] = core::array::from_fn(|k| 3.0 - 0.5 * k as f64);
        let f = |t: f64| coefficients.iter().rev().fold(0.0, |acc, c| acc * t + c);
        let got = interpolate(&f);
        let worst = got
            .iter()
            .zip(coefficients.iter())
            .map(|(g, c)| (g - c).abs())
            .fold(0.0f64, f64::max);
        assert!(worst <= COEFF_TOL, "worst {worst:e}");
        std::println!("monomial interpolation: worst {worst:.2e}");
    }

    #[test]
    fn the_interpolant_resolves_the_nearest_pole() {
        let f = |t: f64| 1.0 / ((t + 3.0) * (t + 3.0));
        let p = interpolate(&f);
        let mut worst = 0.0f64;
        for i in 0..=400 {
            let t = -1.0 + i as f64 / 200.0;
            let v = p.iter().rev().fold(0.0, |acc, c| acc * t + c);
            worst = worst.max((v - f(t)).abs() / 0.25);
        }
        assert!(worst <= POLE_TOL, "worst {worst:e}");
        std::println!("interpolant of the pole: worst {worst:.2e}");
    }
}
