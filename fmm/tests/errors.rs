//! Bad input gets a typed error naming the parameter and value; every solve is bounded.

use diffraction::relief::Metal;
use diffraction_fmm::{Cover, CoverIndex, Error, Grating, Incidence, Options, Profile, Solver};

fn lamellar(period_nm: f64, depth_nm: f64) -> Grating {
    Grating {
        period_nm,
        profile: Profile::Lamellar {
            duty: 0.5,
            depth_nm,
        },
        metal: Metal::AL,
        cover: None,
    }
}

fn message(r: Result<impl std::fmt::Debug, Error>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn bad_inputs_have_exact_messages() {
    let s = Solver::default();
    let inc = Incidence::new(0.2, 0.0, 550.0).unwrap();
    assert_eq!(
        message(s.solve(&lamellar(-5.0, 50.0), inc)),
        "period_nm = -5: must be finite, in [1, 1e5] nm"
    );
    assert_eq!(
        message(s.solve(&lamellar(f64::NAN, 50.0), inc)),
        "period_nm = NaN: must be finite, in [1, 1e5] nm"
    );
    assert_eq!(
        message(s.solve(&lamellar(1000.0, 20000.0), inc)),
        "depth_nm = 20000: must be finite, >= 0, at most 10 periods and 1e5 nm"
    );
    assert_eq!(
        message(s.solve(&lamellar(1e5, 50.0), inc)),
        "period_nm = 100000: must be small enough that the propagating orders (2·n·d/λ + 1, ×2 and ×3 for the convergence steps) fit under max_harmonics"
    );
    let g = Grating {
        profile: Profile::Lamellar {
            duty: 1.0,
            depth_nm: 50.0,
        },
        ..lamellar(1000.0, 0.0)
    };
    assert_eq!(message(s.solve(&g, inc)), "duty = 1: must be in (0, 1)");
    let g = Grating {
        profile: Profile::Sawtooth { blaze: 1.0 },
        ..lamellar(1000.0, 0.0)
    };
    assert_eq!(
        message(s.solve(&g, inc)),
        "blaze = 1: must be in (0, π/4) radians"
    );
    let g = Grating {
        profile: Profile::Sampled(vec![0.0, f64::NAN]),
        ..lamellar(1000.0, 0.0)
    };
    assert_eq!(
        message(s.solve(&g, inc)),
        "samples = NaN: must be finite heights"
    );
    let g = Grating {
        cover: Some(Cover {
            index: CoverIndex::Constant(1.58),
            thickness_nm: 100.0,
        }),
        ..lamellar(1000.0, 50.0)
    };
    assert_eq!(
        message(s.solve(&g, inc)),
        "cover.thickness_nm = 100: must be in [1e4, 1e9] nm (a thick, incoherent cover)"
    );
    let g = Grating {
        cover: Some(Cover {
            index: CoverIndex::Constant(f64::NAN),
            thickness_nm: 1e6,
        }),
        ..lamellar(1000.0, 50.0)
    };
    assert_eq!(
        message(s.solve(&g, inc)),
        "cover.index = NaN: must be finite, in (1, 4]"
    );
    // A dispersive cover: its coefficients checked on their own, its index at the solve's
    // wavelength (polycarbonate's pole is at 146 nm).
    let sellmeier = |b: f64, c_um2: f64| Grating {
        cover: Some(Cover {
            index: CoverIndex::Sellmeier { b, c_um2 },
            thickness_nm: 1e6,
        }),
        ..lamellar(1000.0, 50.0)
    };
    assert_eq!(
        message(s.solve(&sellmeier(-1.0, 0.02), inc)),
        "cover.index.b = -1: must be finite, in (0, 10]"
    );
    assert_eq!(
        message(s.solve(&sellmeier(1.4, f64::INFINITY), inc)),
        "cover.index.c_um2 = inf: must be finite, in [0, 1] µm²"
    );
    let near_pole = Incidence::new(0.3, 0.0, 150.0).unwrap();
    let g = Grating {
        cover: Some(Cover {
            index: CoverIndex::POLYCARBONATE,
            thickness_nm: 1e6,
        }),
        ..lamellar(100.0, 10.0)
    };
    assert!(
        message(s.solve(&g, near_pole)).starts_with("cover.index = 5.26"),
        "{}",
        message(s.solve(&g, near_pole))
    );
    // The index itself: finite wherever it is defined, None elsewhere (never NaN).
    let pc = CoverIndex::POLYCARBONATE;
    assert_eq!(pc.at(120.0), None);
    assert_eq!(pc.at(f64::MIN_POSITIVE), None);
    assert_eq!(pc.at(-550.0), None);
    assert_eq!(pc.at(f64::NAN), None);
    assert_eq!(pc.at(1e300), Some((1.4182f64 + 1.0).sqrt()));
    assert_eq!(pc.at(f64::MAX), Some((1.4182f64 + 1.0).sqrt()));
    assert!(pc.at(146.0 + 1e-9).unwrap().is_finite());
    let below_pole = Incidence::new(0.3, 0.0, 120.0).unwrap();
    assert_eq!(
        message(s.solve(&g, below_pole)),
        "cover.index = NaN: must be finite, in (1, 4] at the solve's wavelength (a dispersive cover: not at or near its pole)"
    );
    assert_eq!(
        message(Incidence::new(f64::NAN, 0.0, 550.0)),
        "theta = NaN: must be in [0, 89.9°] (radians)"
    );
    assert_eq!(
        message(Incidence::new(0.1, 0.0, 5.0)),
        "wavelength_nm = 5: must be in [100, 20000] nm"
    );
    assert_eq!(
        message(Incidence::from_cosines(0.8, 0.8, 550.0)),
        "alpha = 0.8: must be with beta, sqrt(alpha² + beta²) <= sin(89.9°)"
    );
    // Only the sum of squares is too large: the larger cosine is named.
    assert_eq!(
        message(Incidence::from_cosines(0.1, 0.9999, 550.0)),
        "beta = 0.9999: must be with alpha, sqrt(alpha² + beta²) <= sin(89.9°)"
    );
    assert_eq!(
        message(Incidence::from_cosines(-0.9999, 0.1, 550.0)),
        "alpha = -0.9999: must be with beta, sqrt(alpha² + beta²) <= sin(89.9°)"
    );
    assert_eq!(
        message(Solver::new(Options {
            tolerance: 0.0,
            ..Options::default()
        })),
        "tolerance = 0: must be in [1e-9, 0.5]"
    );
    assert_eq!(
        message(Solver::new(Options {
            max_harmonics: 100_000,
            ..Options::default()
        })),
        "max_harmonics = 100000: must be in [3, 1601]"
    );
    assert_eq!(
        message(s.solve_at(&lamellar(1000.0, 50.0), inc, 5000)),
        "harmonics = 5000: must be in [3, 1601]"
    );
    // NaN indices are refused where the metal is made.
    assert_eq!(Metal::custom(f64::NAN, 1.0).unwrap_err().parameter(), "n");
}

#[test]
fn not_converged_within_the_cap_is_an_error() {
    let s = Solver::new(Options {
        tolerance: 1e-9,
        max_harmonics: 61,
        ..Options::default()
    })
    .unwrap();
    let inc = Incidence::new(0.2, 0.0, 550.0).unwrap();
    let e = s.solve(&lamellar(1000.0, 100.0), inc).unwrap_err();
    let Error::NotConverged {
        harmonics,
        change,
        tolerance,
    } = e
    else {
        panic!("{e}")
    };
    assert_eq!((harmonics, tolerance), (51, 1e-9));
    assert!(change > 1e-9 && change.is_finite());
    assert!(
        e.to_string()
            .starts_with("harmonics: not converged to 0.000000001 by 51 harmonics"),
        "{e}"
    );
}

fn sinusoid(depth_nm: f64) -> Grating {
    Grating {
        period_nm: 1000.0,
        profile: Profile::Sinusoid { depth_nm },
        metal: Metal::AL,
        cover: None,
    }
}

#[test]
fn the_work_cap_is_validated() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY, 2e11] {
        let e = Solver::new(Options {
            max_work: bad,
            ..Options::default()
        })
        .unwrap_err();
        assert_eq!(e.parameter(), "max_work", "{bad}: {e}");
    }
    assert_eq!(
        message(Solver::new(Options {
            max_work: 0.0,
            ..Options::default()
        })),
        "max_work = 0: must be in (0, 1e11]"
    );
}

/// The convergence loop stops before a step that would pass `max_work`: a 40-slab staircase
/// of a sinusoid (the Fourier modal method) starts at 21 harmonics (4·d/λ + 11 < 21 at
/// 1000/550 nm), whose work is 40·21³; the next step, at least 31 harmonics, costs 40·31³, more
/// than 2.5× the first, so a cap of 2.5× the first step's work stops after one solve.
#[test]
fn the_work_cap_stops_the_convergence_loop() {
    let first = 40.0 * 21f64.powi(3);
    assert_eq!(diffraction_fmm::work(21, 40, false, false), first);
    let s = Solver::new(Options {
        method: diffraction_fmm::Method::Fmm,
        slabs: Some(40),
        tolerance: 1e-9,
        max_work: 2.5 * first,
        ..Options::default()
    })
    .unwrap();
    let inc = Incidence::new(0.2, 0.0, 550.0).unwrap();
    let e = s.solve(&sinusoid(100.0), inc).unwrap_err();
    assert!(
        matches!(e, Error::NotConverged { harmonics: 21, .. }),
        "{e}"
    );
    // A cap below the first step's work: refused before any solve, naming the slabs.
    let s = Solver::new(Options {
        max_work: 0.5 * first,
        ..*s.options()
    })
    .unwrap();
    assert_eq!(
        s.solve(&sinusoid(100.0), inc).unwrap_err().parameter(),
        "slabs"
    );
    // The C method's first step (21 harmonics: 4·21³) likewise, naming the harmonics; and a
    // fixed truncation above the cap.
    let c = Solver::new(Options {
        max_work: 4.0 * 21f64.powi(3) - 1.0,
        ..Options::default()
    })
    .unwrap();
    assert_eq!(
        c.solve(&sinusoid(100.0), inc).unwrap_err().parameter(),
        "harmonics"
    );
    assert_eq!(
        c.solve_at(&sinusoid(100.0), inc, 21)
            .unwrap_err()
            .parameter(),
        "harmonics"
    );
    // The default admits what it did before: the C method converges on a shallow sinusoid.
    assert!(Solver::default().solve(&sinusoid(100.0), inc).is_ok());
}

/// The default work cap admits a lamellar solve's ×1.5 sequence to the default harmonic cap in
/// the classical mount and to 1359 harmonics (the sequence from 21 below the cap) in the conical
/// one, and the C method's to 1037 harmonics (the presets' solves); it ends the conical and the C
/// method's sequences before a step to the cap, and stops a 400-slab staircase near 300
/// harmonics (at the harmonic cap alone it would run for hours).
#[test]
fn the_default_work_cap_admits_the_presets_solves() {
    use diffraction_fmm::{work, DEFAULT_MAX_HARMONICS, DEFAULT_MAX_WORK};
    // The ×1.5 sequence's total is below 1/(1 − 1.5⁻³) = 1.42 times its last step.
    let sequence = |last: usize, slabs, conical, c| 1.42 * work(last, slabs, conical, c);
    assert!(sequence(DEFAULT_MAX_HARMONICS, 1, false, false) < DEFAULT_MAX_WORK);
    assert!(sequence(1359, 1, true, false) < DEFAULT_MAX_WORK);
    assert!(sequence(1037, 1, false, false) < DEFAULT_MAX_WORK);
    assert!(sequence(1037, 0, false, true) < DEFAULT_MAX_WORK);
    assert!(work(DEFAULT_MAX_HARMONICS, 1, true, false) > DEFAULT_MAX_WORK);
    assert!(work(DEFAULT_MAX_HARMONICS, 0, false, true) > DEFAULT_MAX_WORK);
    assert!(work(401, 400, false, false) > DEFAULT_MAX_WORK);
}
