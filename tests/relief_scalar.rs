//! The scalar relief model: its phase screens against closed forms computed elsewhere (mpmath's
//! J_m and binary-screen coefficients, `tests/data/stam_orders.csv`) and against independent
//! Gauss-Legendre quadrature of the Fourier integral; Parseval; the renormalisation over the
//! propagating orders; energy (Σ η ≤ max R ≤ 1) on a sweep of profiles, metals, angles and
//! wavelengths; finite, bounded answers on extreme input.

#[path = "support/fixed_seed.rs"]
mod fixed_seed;
#[path = "support/quadrature.rs"]
mod quadrature;
#[path = "support/relief_tolerance.rs"]
mod relief_tolerance;

use diffraction::relief::{Metal, Relief, ScalarRelief, MAX_DEPTH_NM, MAX_RELIEF_ORDER};
use proptest::prelude::*;
use relief_tolerance as tol;
use std::f64::consts::PI;

/// |(1/d)∫₀^d exp(−i·κ·h(x) − 2πimx/d) dx|² by Gauss-Legendre on `pieces` pieces of each of the
/// given smooth parts [a, b) of the period (h smooth on each part).
fn quadrature_power(
    h: &dyn Fn(f64) -> f64,
    parts: &[(f64, f64)],
    pieces: usize,
    m: i32,
    kappa: f64,
    d: f64,
) -> f64 {
    let phase = |x: f64| -kappa * h(x) - 2.0 * PI * f64::from(m) * x / d;
    let (mut re, mut im) = (0.0, 0.0);
    for &(a, b) in parts {
        re += quadrature::integrate(a, b, pieces, &|x| phase(x).cos());
        im += quadrature::integrate(a, b, pieces, &|x| phase(x).sin());
    }
    (re * re + im * im) / (d * d)
}

#[test]
fn sinusoid_and_lamellar_match_mpmath() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/stam_orders.csv");
    let text = std::fs::read_to_string(path).expect("tests/data/stam_orders.csv");
    let (mut sine, mut lamellar, mut rows) = (0.0f64, 0.0f64, 0);
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let c: Vec<&str> = line.split(',').collect();
        let phase: f64 = c[2].parse().unwrap();
        let order: i32 = c[3].parse().unwrap();
        let want: f64 = c[5].parse().unwrap();
        // Depth 100 nm: the sine's amplitude is 50 nm, so κ·50 = φ.
        let got = match c[0] {
            "sine" => Relief::sinusoid(100.0)
                .unwrap()
                .power(order, phase / 50.0, 1000.0),
            "binary" => Relief::lamellar(100.0, c[1].parse().unwrap())
                .unwrap()
                .power(order, phase / 100.0, 1000.0),
            other => panic!("{other}"),
        };
        let e = (got - want).abs();
        if c[0] == "sine" {
            sine = sine.max(e);
        } else {
            lamellar = lamellar.max(e);
        }
        rows += 1;
    }
    assert_eq!(rows, 2437);
    println!("against mpmath: sinusoid {sine:.3e}, lamellar {lamellar:.3e} (absolute)");
    assert!(sine <= tol::SINUSOID_MPMATH, "{sine:e}");
    assert!(lamellar <= tol::LAMELLAR_MPMATH, "{lamellar:e}");
}

#[test]
fn sawtooth_fourier_and_sampled_match_quadrature() {
    let d = 1000.0;
    let mut worst = [0.0f64; 3];
    for &blaze_deg in &[3.0, 10.0, 24.0, 45.0, 70.0] {
        let blaze = f64::to_radians(blaze_deg);
        let r = Relief::sawtooth(blaze).unwrap();
        let (f1, h) = (blaze.cos().powi(2), r.depth_nm(d));
        let profile = move |x: f64| {
            if x < d * f1 {
                h - blaze.tan() * x
            } else {
                (x - d * f1) / blaze.tan()
            }
        };
        for &kappa in &[0.0, 0.004, 0.02, 0.05, 0.11] {
            for m in -12..=12 {
                let want =
                    quadrature_power(&profile, &[(0.0, d * f1), (d * f1, d)], 64, m, kappa, d);
                worst[0] = worst[0].max((r.power(m, kappa, d) - want).abs());
            }
        }
    }
    // A two-harmonic Fourier series.
    let (a1, b1, a2, b2) = (20.0, 35.0, -12.0, 8.0);
    let fourier = Relief::fourier(&[(a1, b1), (a2, b2)]).unwrap();
    let smooth = move |x: f64| {
        let t = 2.0 * PI * x / d;
        a1 * t.cos() + b1 * t.sin() + a2 * (2.0 * t).cos() + b2 * (2.0 * t).sin()
    };
    // A sampled profile: 7 heights joined by straight lines.
    let heights = [0.0, 40.0, 95.0, 60.0, 62.0, 10.0, -20.0];
    let sampled = Relief::sampled(&heights).unwrap();
    let step = d / heights.len() as f64;
    let lines = move |x: f64| {
        let j = ((x / step).floor() as usize).min(heights.len() - 1);
        let t = x / step - j as f64;
        heights[j] + t * (heights[(j + 1) % heights.len()] - heights[j])
    };
    let pieces: Vec<(f64, f64)> = (0..heights.len())
        .map(|j| (j as f64 * step, (j + 1) as f64 * step))
        .collect();
    for &kappa in &[0.0, 0.01, 0.03, 0.08] {
        for m in -15..=15 {
            let want = quadrature_power(&smooth, &[(0.0, d)], 256, m, kappa, d);
            worst[1] = worst[1].max((fourier.power(m, kappa, d) - want).abs());
            let want = quadrature_power(&lines, &pieces, 32, m, kappa, d);
            worst[2] = worst[2].max((sampled.power(m, kappa, d) - want).abs());
        }
    }
    println!(
        "against quadrature: sawtooth {:.3e}, fourier {:.3e}, sampled {:.3e}",
        worst[0], worst[1], worst[2]
    );
    assert!(worst[0] <= tol::SCREEN_QUADRATURE, "{:e}", worst[0]);
    assert!(worst[1] <= tol::SCREEN_QUADRATURE, "{:e}", worst[1]);
    assert!(worst[2] <= tol::SCREEN_QUADRATURE, "{:e}", worst[2]);
}

/// Σ_m |c_m|² = 1 at a fixed phase: the sums over |m| ≤ M, with the analytic bound of each
/// profile's tail.
#[test]
fn parseval_holds_before_fresnel() {
    let d = 1600.0;
    let mut worst = 0.0f64;
    let sum = |r: &Relief, kappa: f64, top: i32| -> f64 {
        (-top..=top).map(|m| r.power(m, kappa, d)).sum::<f64>()
    };
    for &kappa in &[0.001, 0.02, 0.1, 0.5] {
        // Sinusoid: J_m decays faster than exponentially beyond |m| ≈ κh/2: no tail.
        let s = Relief::sinusoid(120.0).unwrap();
        worst = worst.max((sum(&s, kappa, 200) - 1.0).abs());
        // Lamellar: tail ≤ 2·Σ_{m>M} 4/(π²m²) < 8/(π²·M).
        let top = 100_000;
        let l = Relief::lamellar(120.0, 0.3).unwrap();
        let e = 1.0 - sum(&l, kappa, top);
        assert!(e > -tol::PARSEVAL && e < 8.0 / (PI * PI * f64::from(top)) + tol::PARSEVAL);
        // Sawtooth: each facet's sinc² tail ≤ 2·Σ 1/(π²(m − m₀)²) beyond |m| ≫ φ.
        let w = Relief::sawtooth(0.3).unwrap();
        let e = 1.0 - sum(&w, kappa, top);
        assert!(e > -tol::PARSEVAL && e < 16.0 / (PI * PI * f64::from(top) / 2.0));
        // A Fourier profile's trapezoid rule is a discrete Fourier transform: Parseval is exact
        // over one period of its nodes.
        let f = Relief::fourier(&[(30.0, 0.0), (0.0, 10.0), (5.0, 5.0)]).unwrap();
        let total: f64 = (0..4096).map(|m| f.power(m, kappa, d)).sum();
        worst = worst.max((total - 1.0).abs());
    }
    println!("Parseval: worst |Σ − 1| {worst:.3e} (sinusoid, Fourier)");
    assert!(worst <= tol::PARSEVAL, "{worst:e}");
}

/// A near-perfect conductor (R > 1 − 10⁻¹⁰ at every angle) sends all the light into its
/// propagating orders: the renormalisation makes the scalar shares sum to 1.
#[test]
fn renormalised_shares_sum_to_one_on_a_perfect_conductor() {
    let pec = Metal::custom(1e-3, 1e4).unwrap();
    let mut worst = 0.0f64;
    for relief in [
        Relief::sinusoid(250.0).unwrap(),
        Relief::lamellar(120.0, 0.5).unwrap(),
        Relief::sawtooth(0.4).unwrap(),
        Relief::sampled(&[0.0, 80.0, 30.0]).unwrap(),
    ] {
        for &d in &[500.0, 1000.0, 5000.0] {
            let g = ScalarRelief::new(relief.clone(), pec, d).unwrap();
            for &s in &[-0.9, -0.3, 0.0, 0.5, 0.99] {
                for &lambda in &[400.0, 550.0, 700.0] {
                    let (te, tm) = g.orders(s, lambda).fold((0.0, 0.0), |(a, b), o| {
                        (a + o.efficiency.te, b + o.efficiency.tm)
                    });
                    worst = worst.max((te - 1.0).abs()).max((tm - 1.0).abs());
                }
            }
        }
    }
    println!("perfect conductor: worst |Σ η − 1| {worst:.3e}");
    assert!(worst <= tol::RENORMALISED_SUM, "{worst:e}");
}

fn relief_strategy() -> impl Strategy<Value = Relief> {
    prop_oneof![
        (0.0..2000.0f64).prop_map(|h| Relief::sinusoid(h).unwrap()),
        (0.0..2000.0f64, 0.0..=1.0f64).prop_map(|(h, f)| Relief::lamellar(h, f).unwrap()),
        (0.0..std::f64::consts::FRAC_PI_2).prop_map(|b| Relief::sawtooth(b).unwrap()),
        prop::collection::vec((-300.0..300.0f64, -300.0..300.0f64), 1..6)
            .prop_map(|c| Relief::fourier(&c).unwrap()),
        prop::collection::vec(-500.0..500.0f64, 2..40).prop_map(|h| Relief::sampled(&h).unwrap()),
    ]
}

fn metal_strategy() -> impl Strategy<Value = Metal> {
    prop_oneof![
        (0usize..5).prop_map(|i| Metal::TABULATED[i]),
        (0.01..10.0f64, 0.0..20.0f64).prop_map(|(n, k)| Metal::custom(n, k).unwrap()),
    ]
}

proptest! {
    #![proptest_config(fixed_seed::config(3000, 0x5ca1a5, "tests/relief_scalar.proptest-regressions"))]

    /// Σ η ≤ max R ≤ 1 in both polarisations, every η finite and ≥ 0, the orders exactly the
    /// propagating ones of the grating equation.
    #[test]
    fn energy_is_never_created(
        relief in relief_strategy(),
        metal in metal_strategy(),
        d in 200.0..20_000.0f64,
        s in -0.9999..0.9999f64,
        lambda in 360.0..830.0f64,
    ) {
        let g = ScalarRelief::new(relief, metal, d).unwrap();
        let (mut te, mut tm, mut max_rs, mut max_rp, mut count) = (0.0, 0.0, 0.0f64, 0.0f64, 0);
        for o in g.orders(s, lambda) {
            let e = o.efficiency;
            prop_assert!(e.te.is_finite() && e.tm.is_finite() && e.te >= 0.0 && e.tm >= 0.0);
            prop_assert!((o.sin_theta - (s + f64::from(o.order) * lambda / d)).abs() < relief_tolerance::SCALAR_DIRECTION);
            prop_assert!(o.sin_theta.abs() < 1.0);
            te += e.te;
            tm += e.tm;
            let cos_m = (1.0 - o.sin_theta * o.sin_theta).sqrt();
            let cos_i = (1.0 - s * s).sqrt();
            let dx = o.sin_theta - s;
            let c = 0.5 * (dx * dx + (cos_i + cos_m).powi(2)).sqrt();
            let (rs, rp) = metal.reflectance(lambda, c);
            max_rs = max_rs.max(rs);
            max_rp = max_rp.max(rp);
            count += 1;
        }
        let expected = (-5000..=5000)
            .filter(|&m| (s + f64::from(m) * lambda / d).abs() < 1.0)
            .count();
        prop_assert_eq!(count, expected);
        prop_assert!(te <= max_rs * (1.0 + tol::ENERGY_ROUNDING) && te <= 1.0 + tol::ENERGY_ROUNDING);
        prop_assert!(tm <= max_rp * (1.0 + tol::ENERGY_ROUNDING) && tm <= 1.0 + tol::ENERGY_ROUNDING);
    }

    /// Unphysical and extreme input: finite answers, no panic, bounded counts.
    #[test]
    fn extreme_input_stays_finite(
        h in 0.0..=MAX_DEPTH_NM,
        d in prop_oneof![1e-3..1.0f64, 1.0..1e6f64],
        s in prop_oneof![-1.5..1.5f64, Just(1.0), Just(-1.0), Just(f64::NAN)],
        lambda in prop_oneof![1e-3..1.0f64, 1.0..1e5f64, Just(0.0), Just(-5.0), Just(f64::INFINITY)],
        which in 0usize..3,
    ) {
        let relief = match which {
            0 => Relief::sinusoid(h).unwrap(),
            1 => Relief::lamellar(h, 0.4).unwrap(),
            _ => Relief::sawtooth(0.6).unwrap(),
        };
        let g = ScalarRelief::new(relief, Metal::AL, d).unwrap();
        let mut count = 0;
        for o in g.orders(s, lambda) {
            prop_assert!(o.efficiency.te.is_finite() && o.efficiency.tm.is_finite());
            prop_assert!(o.efficiency.te >= 0.0 && o.efficiency.te <= 1.0);
            prop_assert!(o.order.abs() <= MAX_RELIEF_ORDER);
            count += 1;
        }
        prop_assert!(count <= 2 * MAX_RELIEF_ORDER as usize + 1);
        if !(s.abs() < 1.0 && lambda > 0.0 && lambda.is_finite()) {
            prop_assert_eq!(count, 0);
        }
    }
}
