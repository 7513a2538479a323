//! Properties of the slit kernels against their closed forms (proptest), in f32 and f64.

#[path = "support/fixed_seed.rs"]
mod fixed_seed;
#[path = "support/tolerance.rs"]
mod tolerance;

use diffraction::kernel::{n_slit, n_slit_cycles, naive, single_slit, single_slit_cycles};
use proptest::prelude::*;
use std::f64::consts::PI;

/// |x| range of the f64 accuracy claim in cycles (|α| ≤ 10⁵ radians).
const X_MAX: f64 = 1e5 / PI;

fn slits() -> impl Strategy<Value = u32> {
    prop_oneof![
        1u32..=10,
        10u32..=100_000,
        Just(1_000_000u32),
        Just(10_000_000u32)
    ]
}

proptest! {
    #![proptest_config(fixed_seed::config(2000, 0x5EED_0009, "tests/kernel_properties.proptest-regressions"))]

    #[test]
    fn n_slit_lies_in_unit_interval(x in -X_MAX..X_MAX, n in slits()) {
        let v = n_slit_cycles(x, n);
        prop_assert!((0.0..=1.0).contains(&v), "F_{}({}) = {}", n, x, v);
        let v32 = n_slit_cycles(x as f32, n);
        prop_assert!((0.0..=1.0).contains(&v32), "f32 F_{}({}) = {}", n, x, v32);
        let a = n_slit(x * PI, n);
        prop_assert!((0.0..=1.0).contains(&a));
    }

    #[test]
    fn n_slit_is_one_at_every_integer(m in -1_000_000i64..1_000_000, n in slits()) {
        prop_assert_eq!(n_slit_cycles(m as f64, n), 1.0);
        prop_assert_eq!(n_slit_cycles(m as f32, n), 1.0);
    }

    /// Zeros at x = m + k/N (k not a multiple of N). The double x = m + k/N + δ carries the
    /// rounding δ of forming it, where F_N = sin²(πNδ)/(N² sin²(πk/N)) ≤ (πδ)²/sin²(πk/N).
    #[test]
    fn n_slit_vanishes_at_k_over_n(m in -1000i64..1000, k in 1u32..10_000, n in 2u32..10_000) {
        prop_assume!(k % n != 0);
        let x = m as f64 + k as f64 / n as f64;
        let frac = (k % n) as f64 / n as f64;
        // Two roundings: of k/N and of the sum; each is at most half an ulp of its result.
        let delta = (x.abs() + k as f64 / n as f64 + 1.0) * f64::EPSILON;
        let bound = (PI * delta).powi(2) / (PI * frac).sin().powi(2) * tolerance::ZERO_ROUNDING + 1e-300;
        let v = n_slit_cycles(x, n);
        prop_assert!(v <= bound, "F_{}({}) = {} > {}", n, x, v, bound);
    }

    /// F_N(−x) = F_N(x) and S(−y) = S(y), bit for bit.
    #[test]
    fn kernels_are_even(x in -X_MAX..X_MAX, n in slits()) {
        prop_assert_eq!(n_slit_cycles(x, n).to_bits(), n_slit_cycles(-x, n).to_bits());
        prop_assert_eq!(single_slit_cycles(x).to_bits(), single_slit_cycles(-x).to_bits());
        prop_assert_eq!(n_slit(x, n).to_bits(), n_slit(-x, n).to_bits());
    }

    /// Period 1 in cycles: x and x + k on a 2⁻²⁰ grid are both exact, and F_N agrees exactly.
    #[test]
    fn n_slit_has_period_one_in_cycles(i in -1_000_000i64..1_000_000, k in -10_000i64..10_000,
                                       n in slits()) {
        let x = i as f64 / 1_048_576.0;
        prop_assert_eq!(n_slit_cycles(x, n), n_slit_cycles(x + k as f64, n));
    }

    /// Period π in radians: α and α + kπ differ after rounding by at most ulp(α + kπ), and
    /// |dF_N/dα| ≤ N, so the values agree to a few N·ε·|α + kπ| (`PERIOD_PI_ROUNDING`).
    #[test]
    fn n_slit_has_period_pi(a in -10.0f64..10.0, k in -1000i32..1000, n in 1u32..1000) {
        let b = a + k as f64 * PI;
        let tol = tolerance::PERIOD_PI_ROUNDING * n as f64 * f64::EPSILON * b.abs().max(1.0);
        prop_assert!((n_slit(a, n) - n_slit(b, n)).abs() <= tol);
    }

    /// One slit: F_1 ≡ 1, so the intensity is the single-slit factor alone.
    #[test]
    fn one_slit_gives_the_single_slit(x in -X_MAX..X_MAX) {
        prop_assert_eq!(n_slit_cycles(x, 1), 1.0);
        prop_assert_eq!(n_slit(x, 1), 1.0);
    }

    /// Away from the maxima the stable kernel agrees with the textbook formula in f64.
    #[test]
    fn agrees_with_naive_formula_where_that_is_well_conditioned(x in -50.0f64..50.0,
                                                                 n in 1u32..200) {
        let r = x - x.round();
        prop_assume!(r.abs() > 0.01);
        let want = naive::n_slit(PI * x, n);
        prop_assert!((n_slit_cycles(x, n) - want).abs() <= tolerance::NAIVE_N_SLIT * (1.0 + x.abs() * n as f64));
        let y = x * 0.37;
        prop_assume!(y.abs() > 0.01);
        let s_want = naive::single_slit(PI * y);
        prop_assert!((single_slit_cycles(y) - s_want).abs() <= tolerance::NAIVE_SINGLE_SLIT);
    }

    #[test]
    fn single_slit_lies_in_unit_interval(y in -1e6f64..1e6) {
        let s = single_slit_cycles(y);
        prop_assert!((0.0..=1.0).contains(&s));
        prop_assert!((0.0..=1.0).contains(&single_slit(y)));
        prop_assert!((0.0..=1.0).contains(&single_slit_cycles(y as f32)));
        // The envelope bound S ≤ 1/(πy)².
        prop_assert!(s * (PI * y).powi(2) <= 1.0 + tolerance::ENVELOPE_ROUNDING || y.abs() < 0.32);
    }

    #[test]
    fn single_slit_vanishes_at_nonzero_integers(m in 1i64..1_000_000) {
        // sin(π·m) is exactly 0 with the exact phase reduction.
        prop_assert_eq!(single_slit_cycles(m as f64), 0.0);
        prop_assert_eq!(single_slit_cycles(-(m as f64)), 0.0);
    }
}

/// The naive formula in f32 leaves [0, 1] near the maxima (values measured with N = 5000);
/// the crate's kernel does not, at the very same f32 inputs.
#[test]
fn naive_f32_leaves_unit_interval_where_stable_does_not() {
    let mut worst_naive = 0.0f32;
    let mut worst_stable = 0.0f32;
    for m in (1..=8).chain([40]) {
        for k in -2000..=2000 {
            let x = m as f32 + k as f32 * 1e-6;
            let a = std::f32::consts::PI * x;
            let v = naive::n_slit(a, 5000);
            if v.is_finite() {
                worst_naive = worst_naive.max(v);
            }
            let s = n_slit(a, 5000);
            assert!(s.is_finite());
            worst_stable = worst_stable.max(s).max(n_slit_cycles(x, 5000));
        }
    }
    assert!(worst_naive > 1.5, "naive max {worst_naive}");
    assert!(worst_stable <= 1.0, "stable max {worst_stable}");
}

/// The naive formula divides 0 by 0 at the maxima; the crate returns the limit 1.
#[test]
fn naive_is_nan_at_exact_maxima_stable_is_one() {
    assert!(naive::n_slit(0.0f64, 10).is_nan());
    assert!(naive::single_slit(0.0f64).is_nan());
    assert_eq!(n_slit(0.0f64, 10), 1.0);
    assert_eq!(single_slit(0.0f64), 1.0);
}

/// The stiff inputs of docs/conventions.md (Numerics) never produce NaN or values outside [0, 1].
#[test]
fn stiff_inputs_stay_finite_and_bounded() {
    let ns = [0u32, 1, 2, 1_000_000, 10_000_000, u32::MAX];
    let xs = [
        0.0,
        -0.0,
        1e-300,
        5e-324,
        1e-12,
        1.0 - 1e-12,
        3.0 + 1e-12,
        1e4,
        1e4 + 1e-12,
        -9999.5,
        1e15,
        4503599627370495.5,
        1e300,
        f64::MAX,
        f64::MIN_POSITIVE,
    ];
    for &n in &ns {
        for &x in &xs {
            for v in [
                n_slit_cycles(x, n),
                n_slit(x, n),
                single_slit_cycles(x),
                single_slit(x),
            ] {
                assert!((0.0..=1.0).contains(&v), "n={n} x={x} -> {v}");
            }
            let x32 = x as f32;
            if x32.is_finite() {
                let v32 = n_slit_cycles(x32, n);
                assert!((0.0..=1.0).contains(&v32), "f32 n={n} x={x} -> {v32}");
                let s32 = single_slit(x32);
                assert!((0.0..=1.0).contains(&s32), "f32 n={n} x={x} -> {s32}");
            }
        }
    }
    assert_eq!(n_slit_cycles(0.3f64, 0), 0.0);
}
