//! The grating: parameters, intensity at the closed-form maxima, the grating equation and the
//! peak search, the forward (outgoing-direction) form, and the paper's half-vector error.

#[path = "support/fixed_seed.rs"]
mod fixed_seed;
#[path = "support/tolerance.rs"]
mod tolerance;

use diffraction::frame::{paper_half_vector_projection, phase_projection};
use diffraction::kernel::single_slit_cycles;
use diffraction::{Band, Error, Grating, Requirement, Slits};
use glam::DVec3;
use proptest::prelude::*;

fn grating() -> impl Strategy<Value = Grating> {
    (
        prop_oneof![300.0f64..3000.0, 3000.0f64..100_000.0],
        0.01f64..=1.0,
        prop_oneof![
            (1u32..100).prop_map(Slits::Finite),
            (100u32..10_000_000).prop_map(Slits::Finite),
            Just(Slits::Infinite)
        ],
    )
        .prop_map(|(d, duty, n)| Grating::with_slits(d, duty * d, n).unwrap())
}

proptest! {
    #![proptest_config(fixed_seed::config(1000, 0x5EED_0007, "tests/grating.proptest-regressions"))]

    /// At λ_m the N-slit factor is 1, so the intensity equals S(β_m) (closed form:
    /// (sin πmw/d / (πmw/d))²), and every reported peak satisfies d·u = m·λ.
    #[test]
    fn peaks_sit_on_the_grating_equation(g in grating(), u in -2.0f64..2.0) {
        let d = g.period_nm();
        for p in g.peaks(u, Band::VISIBLE) {
            prop_assert!(p.order != 0 && (p.order > 0) == (u > 0.0));
            let rel = (d * u - p.order as f64 * p.wavelength_nm).abs() / (d * u).abs();
            prop_assert!(rel <= tolerance::GRATING_EQUATION, "d·u = {} vs m·λ = {}", d * u, p.order as f64 * p.wavelength_nm);
            prop_assert!(Band::VISIBLE.contains(p.wavelength_nm));
            let y = g.slit_width_nm() * p.order as f64 / d;
            let closed = if y == 0.0 { 1.0 } else {
                let b = std::f64::consts::PI * y;
                (b.sin() / b).powi(2)
            };
            prop_assert!((p.intensity - closed).abs() <= tolerance::PEAK_VALUE, "S = {} vs {}", p.intensity, closed);
            // x = d·u/λ_m is m up to a few roundings; F_N there is 1 − O((πNmε)²).
            let i = g.intensity(u, p.wavelength_nm);
            prop_assert!((i - p.intensity).abs()
                <= tolerance::INTENSITY_AT_PEAK_REL * p.intensity + tolerance::INTENSITY_AT_PEAK_ABS,
                "I(u, λ_m) = {} vs S(β_m) = {}", i, p.intensity);
            if let Slits::Finite(n) = g.slits() {
                let w = p.wavelength_nm / (p.order.unsigned_abs() as f64 * n as f64);
                prop_assert!((p.equivalent_width_nm - w).abs() <= tolerance::EQUIVALENT_WIDTH * w);
            }
        }
    }

    /// Brute force over every order finds no visible peak the search missed.
    #[test]
    fn peak_search_misses_nothing(g in grating(), u in -2.0f64..2.0) {
        let found: Vec<i32> = g.peaks(u, Band::VISIBLE).map(|p| p.order).collect();
        let q = g.period_nm() * u.abs();
        let m_max = (q / 360.0) as i32 + 2;
        let mut want = vec![];
        for m in 1..=m_max {
            let lambda = q / m as f64;
            if (360.0..=830.0).contains(&lambda) {
                want.push(if u < 0.0 { -m } else { m });
            }
        }
        prop_assert_eq!(found, want);
    }

    /// I(u, λ) = I(−u, λ): the pattern is symmetric about the mirror direction.
    #[test]
    fn intensity_is_symmetric_in_u(g in grating(), u in -2.0f64..2.0, l in 360.0f64..830.0) {
        prop_assert_eq!(g.intensity(u, l), g.intensity(-u, l));
        let v = g.intensity(u, l);
        prop_assert!((0.0..=1.0).contains(&v));
        let v32 = g.intensity(u as f32, l as f32);
        prop_assert!((0.0..=1.0).contains(&v32));
    }

    /// N = 1: the intensity is the single-slit factor alone.
    #[test]
    fn one_slit_is_the_single_slit(d in 300.0f64..1e5, duty in 0.01f64..=1.0,
                                   u in -2.0f64..2.0, l in 360.0f64..830.0) {
        let g = Grating::new(d, duty * d, 1).unwrap();
        // The two sides form y = w·u/λ with different roundings (relative 4ε); |dS/dy| ≤ 2/y
        // bounds the difference by 8ε.
        prop_assert!((g.intensity(u, l) - single_slit_cycles(duty * d * u / l)).abs() < tolerance::ONE_SLIT_INTENSITY);
    }

    /// The forward form: each propagating order satisfies the conical grating equation and is a
    /// unit vector; every order that propagates is listed.
    #[test]
    fn diffracted_orders_satisfy_the_grating_equation(
        g in grating(), theta in 0.0f64..1.5, phi in 0.0f64..std::f64::consts::TAU, l in 360.0f64..830.0) {
        let wi = DVec3::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos());
        let step = l / g.period_nm();
        let orders: Vec<_> = g.diffracted_orders(wi, l).collect();
        for o in &orders {
            let wo = o.direction;
            prop_assert!(wo.z > 0.0 && (wo.length() - 1.0).abs() <= tolerance::UNIT_LENGTH);
            prop_assert!((wi.x + wo.x - o.order as f64 * step).abs() <= tolerance::FORWARD_GRATING_EQUATION);
            prop_assert_eq!(wi.y + wo.y, 0.0); // wo.y = −wi.y exactly
        }
        let listed: Vec<i32> = orders.iter().map(|o| o.order).collect();
        let lim = (2.0 / step) as i32 + 2;
        let want: Vec<i32> = (-lim..=lim)
            .filter(|&m| { let ox = m as f64 * step - wi.x; ox * ox + wi.y * wi.y < 1.0 })
            .collect();
        prop_assert_eq!(listed, want);
        prop_assert!(orders.iter().any(|o| o.order == 0));
    }
}

#[test]
fn six_hundred_lines_per_mm_sends_532_nm_to_18_6_degrees() {
    // A physical fact (paper summary): asin(532/1666.7) ≈ 18.6°.
    let g = Grating::from_lines_per_mm(600.0, 0.5, Slits::Finite(10_000)).unwrap();
    let first = g
        .diffracted_orders(DVec3::Z, 532.0)
        .find(|o| o.order == 1)
        .unwrap();
    let angle = first.direction.x.asin().to_degrees();
    // 18.61° to the two decimals quoted.
    assert!(
        (angle - 18.61).abs() < tolerance::QUOTED_ANGLE_DEG,
        "{angle}"
    );
    // and the closed form sin θ = λ/d at normal incidence (d = 10⁶/600 nm).
    let sin_theta = first.direction.x;
    assert!((sin_theta - 532.0 * 600.0 / 1e6).abs() <= tolerance::FORWARD_GRATING_EQUATION);
    // and the intensity there is the maximum S(β₁) = (sin(π/2)/(π/2))² = 4/π².
    let u = DVec3::Z.x + first.direction.x;
    let want = 4.0 / std::f64::consts::PI.powi(2);
    let tol = tolerance::INTENSITY_AT_PEAK_REL * want + tolerance::INTENSITY_AT_PEAK_ABS;
    assert!((g.intensity(u, 532.0) - want).abs() <= tol);
}

/// The paper's step 5 (normalised half vector) misplaces the peak; the exact u puts it on the
/// grating equation.
#[test]
fn paper_half_vector_misplaces_peaks() {
    let g = Grating::new(1600.0, 800.0, 2000).unwrap();
    let t = DVec3::X;
    // Light at 20° on one side; viewer where the first order of 550 nm leaves.
    let wi = DVec3::new(-(20f64.to_radians().sin()), 0.0, 20f64.to_radians().cos());
    let wo_x = 550.0 / 1600.0 - wi.x;
    let wo = DVec3::new(wo_x, 0.0, (1.0 - wo_x * wo_x).sqrt());
    let u = phase_projection(wo, wi, t);
    let u_paper = paper_half_vector_projection(wo, wi, t);
    let peak = g.peaks(u, Band::VISIBLE).next().unwrap();
    assert!((peak.wavelength_nm - 550.0).abs() <= tolerance::GRATING_EQUATION * 550.0);
    let tol = tolerance::INTENSITY_AT_PEAK_REL * peak.intensity + tolerance::INTENSITY_AT_PEAK_ABS;
    assert!((g.intensity(u, 550.0) - peak.intensity).abs() <= tol);
    // With the paper's projection the 550 nm peak is not seen at this viewer at all ...
    assert!(g.intensity(u_paper, 550.0) < tolerance::PAPER_PROJECTION_DARK * peak.intensity);
    // ... and the first-order wavelength it predicts here, d·h·t, is not 550 nm.
    let predicted = g.period_nm() * u_paper;
    assert!((predicted - 550.0).abs() > 100.0, "{predicted}");
}

#[test]
fn mirror_direction_is_the_white_order_zero() {
    let g = Grating::new(1600.0, 800.0, 1000).unwrap();
    let peaks = g.peaks(0.0, Band::VISIBLE);
    assert!(peaks.specular());
    assert_eq!(peaks.count(), 0);
    for l in [360.0, 500.0, 830.0] {
        assert_eq!(g.intensity(0.0, l), 1.0);
    }
    // The central lobe's first zero: |u| = λ/(N·d).
    let u = g.specular_half_width(550.0);
    assert!(g.intensity(u, 550.0) < tolerance::AT_A_ZERO);
    assert!(!g
        .peaks(2.0 * 830.0 / (1000.0 * 1600.0), Band::VISIBLE)
        .specular());
    let inf = Grating::infinite(1600.0, 800.0).unwrap();
    assert!(inf.peaks(0.0, Band::VISIBLE).specular());
    assert!(!inf.peaks(1e-12, Band::VISIBLE).specular());
    assert_eq!(inf.intensity(0.3, 480.0), inf.single_slit(0.3, 480.0));
    assert_eq!(inf.intensity(0.3, 480.5), 0.0);
}

#[test]
fn open_fraction_one_puts_all_light_in_order_zero() {
    // w = d: S(β_m) = sinc²(πm) = 0 at every m ≠ 0.
    let g = Grating::new(1600.0, 1600.0, 1000).unwrap();
    for p in g.peaks(1.2, Band::VISIBLE) {
        assert!(p.intensity < tolerance::SINC_ZEROS, "{p:?}");
    }
    // w → 0: S → 1 everywhere.
    let thin = Grating::new(1600.0, 1e-300, 1000).unwrap();
    for p in thin.peaks(1.2, Band::VISIBLE) {
        assert_eq!(p.intensity, 1.0);
    }
}

#[test]
fn band_edges_are_inclusive_and_grazing_u_works() {
    let g = Grating::new(1660.0, 830.0, 1_000_000).unwrap();
    // d·u = 1660 → order 2 exactly at 830 nm, orders 2..=4 (λ 830, 553.3, 415).
    let orders: Vec<_> = g.peaks(1.0, Band::VISIBLE).map(|p| p.order).collect();
    assert_eq!(orders, [2, 3, 4]);
    let g = Grating::new(1800.0, 900.0, 1_000_000).unwrap();
    // d·u = 3600: order 10 exactly at 360 nm.
    let last = g.peaks(2.0, Band::VISIBLE).last().unwrap();
    assert_eq!(last.order, 10);
    assert_eq!(last.wavelength_nm, 360.0);
    // Grazing: |u| → 2.
    let u = 2.0 - 1e-15;
    for p in g.peaks(-u, Band::VISIBLE) {
        assert!(p.order < 0);
        let tol = tolerance::INTENSITY_AT_PEAK_REL * p.intensity + tolerance::INTENSITY_AT_PEAK_ABS;
        assert!((g.intensity(-u, p.wavelength_nm) - p.intensity).abs() <= tol);
    }
}

#[test]
fn no_order_in_band_for_fine_gratings_at_small_u() {
    // d·u = 124 nm < 360 nm: nothing but the dark region between orders 0 and 1.
    let g = Grating::new(400.0, 200.0, 1000).unwrap();
    let p = g.peaks(0.31, Band::VISIBLE);
    assert_eq!(p.len(), 0);
    assert!(!p.specular());
}

#[test]
fn bad_parameters_are_named() {
    let cases: [(Result<Grating, Error>, &str, f64); 8] = [
        (Grating::new(0.0, 1.0, 1), "period_nm", 0.0),
        (Grating::new(-5.0, 1.0, 1), "period_nm", -5.0),
        (Grating::new(f64::NAN, 1.0, 1), "period_nm", f64::NAN),
        (Grating::new(1600.0, 0.0, 1), "slit_width_nm", 0.0),
        (Grating::new(1600.0, 1600.5, 1), "slit_width_nm", 1600.5),
        (
            Grating::new(1600.0, f64::INFINITY, 1),
            "slit_width_nm",
            f64::INFINITY,
        ),
        (Grating::new(1600.0, 800.0, 0), "slits", 0.0),
        (
            Grating::from_lines_per_mm(600.0, 1.5, Slits::Infinite),
            "open_fraction",
            1.5,
        ),
    ];
    for (r, name, value) in cases {
        let e = r.unwrap_err();
        assert_eq!(e.parameter(), name);
        assert!(e.value() == value || (value.is_nan() && e.value().is_nan()));
        assert!(e.to_string().contains(name), "{e}");
    }
    let e = Band::new(500.0, 400.0).unwrap_err();
    assert!(matches!(
        e,
        Error::InvalidParameter {
            name: "max_nm",
            requirement: Requirement::GreaterThan { .. },
            ..
        }
    ));
}

#[test]
fn non_physical_wavelengths_give_zero_not_nan() {
    let g = Grating::new(1600.0, 800.0, 100).unwrap();
    for l in [0.0f64, -550.0, 1e-320] {
        let v = g.intensity(0.5, l);
        assert!(v.is_finite() && (0.0..=1.0).contains(&v), "{l} -> {v}");
    }
    assert_eq!(g.intensity(1e308, 1e-10), 0.0);
    assert_eq!(g.diffracted_orders(DVec3::Z, 0.0).count(), 0);
    assert_eq!(g.peak_wavelength(0.5, 0), None);
}

proptest! {
    #![proptest_config(fixed_seed::config(2000, 0x5EED_0008, "tests/grating.proptest-regressions"))]

    /// The fused intensity (one division) is the product of the two kernels at the same phases
    /// x = d·(u/λ), y = w·(u/λ), to a few ulp.
    #[test]
    fn intensity_is_the_product_of_the_factors(g in grating(), u in -2.0f64..2.0,
                                               l in 360.0f64..830.0) {
        use diffraction::kernel::n_slit_cycles;
        let q = u / l;
        let (x, y) = (g.period_nm() * q, g.slit_width_nm() * q);
        let want = match g.slits() {
            Slits::Finite(n) => single_slit_cycles(y) * n_slit_cycles(x, n),
            Slits::Infinite => return Ok(()),
        };
        let got = g.intensity(u, l);
        prop_assert!((got - want).abs() <= tolerance::FUSED_INTENSITY * want + 1e-300, "{} vs {}", got, want);
    }
}
