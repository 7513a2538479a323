//! Closed forms and identities: Fresnel for a flat metal (classical and conical), the scalar J_m²
//! limit of a shallow sinusoid, energy balance on lossless media, the conical formulation at
//! φ = 0 against the classical one, and reciprocity.

use diffraction::relief::Metal;
use diffraction_fmm::{Grating, Incidence, Method, Options, Profile, Solver};

/// The Fourier modal method (a staircase of the smooth profiles): these are its tests; the C
/// method's are in tests/cmethod.rs.
fn fmm() -> Solver {
    Solver::new(Options {
        method: Method::Fmm,
        ..Options::default()
    })
    .unwrap()
}

/// Fresnel against the flat solve: both evaluate the same closed form, to rounding.
const FRESNEL_TOLERANCE: f64 = 1e-12;
/// Σ R + Σ T = 1 on lossless media: measured 3.6e-12 (classical and conical); 1e-10 asked.
const ENERGY_TOLERANCE: f64 = 1e-10;
/// The conical formulation at β = 0 against the classical split: measured 2.5e-12.
const CONICAL_CLASSICAL_TOLERANCE: f64 = 1e-10;

fn flat(metal: Metal) -> Grating {
    Grating {
        period_nm: 800.0,
        profile: Profile::Flat,
        metal,
        cover: None,
    }
}

#[test]
fn flat_metal_is_fresnel_classical_and_conical() {
    let solver = fmm();
    for metal in [Metal::AL, Metal::AG, Metal::custom(1.5, 0.0).unwrap()] {
        for theta in [0.0f64, 0.3, 0.8, 1.3] {
            for phi in [0.0, 0.6, 1.5] {
                let inc = Incidence::new(theta, phi, 550.0).unwrap();
                let sol = solver.solve(&flat(metal), inc).unwrap();
                let o = sol.order(0).unwrap();
                let (rs, rp) = metal.reflectance(550.0, theta.cos());
                assert!(
                    (o.te - rs).abs() < FRESNEL_TOLERANCE,
                    "{metal} θ {theta} φ {phi}: {} vs {rs}",
                    o.te
                );
                assert!(
                    (o.tm - rp).abs() < FRESNEL_TOLERANCE,
                    "{metal} θ {theta} φ {phi}: {} vs {rp}",
                    o.tm
                );
                // Every other order carries nothing.
                for other in sol.orders.iter().filter(|o| o.m != 0) {
                    assert!(other.te < 1e-20 && other.tm < 1e-20);
                }
            }
        }
    }
}

fn bessel_j(m: i32, x: f64) -> f64 {
    // J_m(x) = (1/π)∫₀^π cos(mτ − x sin τ) dτ (Simpson, 2000 panels).
    let n = 2000;
    let h = core::f64::consts::PI / n as f64;
    let f = |t: f64| (m as f64 * t - x * t.sin()).cos();
    let mut s = f(0.0) + f(core::f64::consts::PI);
    for i in 1..n {
        s += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
    }
    s * h / 3.0 / core::f64::consts::PI
}

/// A shallow sinusoid far from its Wood anomalies (d = 10λ, h = λ/50, normal incidence, TE on
/// silver), TE at 101 harmonics (converged there to 1e-6): η_m → R·J_m²(k·h·(1 + cos θm)/2).
/// (TM is left out: a staircase on a metal converges erratically in TM; see the README.)
#[test]
fn shallow_sinusoid_tends_to_the_scalar_bessel_limit() {
    let lambda = 500.0;
    let (d, h) = (5000.0, 10.0);
    let g = Grating {
        period_nm: d,
        profile: Profile::Sinusoid { depth_nm: h },
        metal: Metal::AG,
        cover: None,
    };
    let sol = fmm()
        .solve_at(&g, Incidence::new(0.0, 0.0, lambda).unwrap(), 101)
        .unwrap();
    let r = Metal::AG.reflectance(lambda, 1.0).0;
    let k = core::f64::consts::TAU / lambda;
    for m in [-1, 0, 1] {
        let s = m as f64 * lambda / d;
        let c = (1.0 - s * s).sqrt();
        let scalar = r * bessel_j(m, k * h * (1.0 + c) / 2.0).powi(2);
        let te = sol.order(m).unwrap().te;
        let rel = (te - scalar).abs() / scalar;
        println!("m {m}: rigorous {te:.6e} scalar {scalar:.6e} rel {rel:.2e}");
        assert!(
            rel < if m == 0 { 3e-2 } else { 6e-2 },
            "order {m}: {te} vs {scalar}"
        );
    }
}

fn dielectric(profile: Profile) -> Grating {
    Grating {
        period_nm: 800.0,
        profile,
        metal: Metal::custom(1.5, 0.0).unwrap(),
        cover: None,
    }
}

#[test]
fn energy_is_conserved_on_lossless_media() {
    let solver = fmm();
    let mut worst: f64 = 0.0;
    for profile in [
        Profile::Lamellar {
            duty: 0.4,
            depth_nm: 300.0,
        },
        Profile::Sinusoid { depth_nm: 200.0 },
        Profile::Sawtooth { blaze: 0.3 },
    ] {
        for (theta, phi) in [
            (0.0, 0.0),
            (0.4, 0.0),
            (0.9, 0.0),
            (0.4, 0.7),
            (0.9, 1.2),
            (0.2, 2.5),
        ] {
            let inc = Incidence::new(theta, phi, 550.0).unwrap();
            let sol = solver
                .solve_at(&dielectric(profile.clone()), inc, 41)
                .unwrap();
            let (r_te, r_tm) = sol.total();
            let (t_te, t_tm) = sol.transmitted.unwrap();
            worst = worst
                .max((r_te + t_te - 1.0).abs())
                .max((r_tm + t_tm - 1.0).abs());
        }
    }
    println!("energy balance: worst |ΣR + ΣT − 1| = {worst:.2e}");
    assert!(worst < ENERGY_TOLERANCE);
}

#[test]
fn conical_formulation_at_phi_zero_is_the_classical_one() {
    let classical = fmm();
    let conical = Solver::new(Options {
        always_conical: true,
        method: Method::Fmm,
        ..Options::default()
    })
    .unwrap();
    let mut worst: f64 = 0.0;
    for (profile, metal) in [
        (
            Profile::Lamellar {
                duty: 0.5,
                depth_nm: 120.0,
            },
            Metal::AL,
        ),
        (Profile::Sinusoid { depth_nm: 150.0 }, Metal::AG),
        (
            Profile::Sawtooth { blaze: 0.4 },
            Metal::custom(1.5, 0.0).unwrap(),
        ),
    ] {
        let g = Grating {
            period_nm: 1000.0,
            profile,
            metal,
            cover: None,
        };
        for theta in [0.0, 0.5, -0.8] {
            let inc = Incidence::classical(f64::sin(theta), 600.0).unwrap();
            let a = classical.solve_at(&g, inc, 31).unwrap();
            let b = conical.solve_at(&g, inc, 31).unwrap();
            assert_eq!(a.orders.len(), b.orders.len());
            for (x, y) in a.orders.iter().zip(&b.orders) {
                worst = worst.max((x.te - y.te).abs()).max((x.tm - y.tm).abs());
            }
        }
    }
    println!("conical at φ = 0 vs classical: {worst:.2e}");
    assert!(worst < CONICAL_CLASSICAL_TOLERANCE);
}

/// Reciprocity: η_m(α) = η_m(−α − mλ/d) (the reversed path), on the asymmetric sawtooth, at a
/// fixed truncation: on a dielectric both polarisations, on aluminium TE (its staircase TM is
/// far from converged at 61 harmonics). The truncated method is reciprocal to within its own
/// truncation error: measured worst difference printed, asserted at 1e-4.
#[test]
fn efficiencies_are_reciprocal() {
    let lambda = 550.0;
    let solver = fmm();
    let mut worst: f64 = 0.0;
    for (metal, tm) in [(Metal::custom(1.5, 0.0).unwrap(), true), (Metal::AL, false)] {
        let g = Grating {
            period_nm: 1000.0,
            profile: Profile::Sawtooth { blaze: 0.35 },
            metal,
            cover: None,
        };
        for s in [-0.6, -0.2, 0.1, 0.45] {
            let a = solver
                .solve_at(&g, Incidence::classical(s, lambda).unwrap(), 61)
                .unwrap();
            for o in &a.orders {
                let back = -o.alpha;
                if back.abs() > 0.99 {
                    continue;
                }
                let b = solver
                    .solve_at(&g, Incidence::classical(back, lambda).unwrap(), 61)
                    .unwrap();
                let ob = b.order(o.m).unwrap();
                worst = worst.max((o.te - ob.te).abs());
                if tm {
                    worst = worst.max((o.tm - ob.tm).abs());
                }
            }
        }
    }
    println!("reciprocity: worst {worst:.2e}");
    assert!(worst < 1e-4);
}
