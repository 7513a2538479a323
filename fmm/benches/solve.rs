//! One solve at a fixed truncation: lamellar (TE + TM, classical; s + p, conical) at 41, 81 and
//! 121 harmonics (the cases of tests/data/nannos_timing.csv), one staircased sinusoid, and the C method on the foil and blazed600 gratings
//! (compare with `python_ref/cmethod_cases.py --time`, the same solves in Python), classical and
//! conical.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use diffraction::relief::Metal;
use diffraction_fmm::{Grating, Incidence, Method, Options, Profile, Solver};

fn solves(c: &mut Criterion) {
    let solver = Solver::new(Options {
        method: Method::Fmm,
        ..Options::default()
    })
    .unwrap();
    let sinusoid = Grating {
        period_nm: 1000.0,
        profile: Profile::Sinusoid { depth_nm: 150.0 },
        metal: Metal::AG,
        cover: None,
    };
    // The lamellar cases of tests/data/nannos_timing.csv (`python_ref/conical.py --timing`, the
    // same solves in nannos, both polarisations): 1000 nm, 120 nm deep, duty 0.5 on aluminium at
    // 550 nm, θ = 30° at φ = 0 (classical) and φ = 60°; 1600 nm, 50 nm deep on silver at 450 nm,
    // θ = 60°, φ = 30°.
    let al = Grating {
        period_nm: 1000.0,
        profile: Profile::Lamellar {
            duty: 0.5,
            depth_nm: 120.0,
        },
        metal: Metal::AL,
        cover: None,
    };
    let ag = Grating {
        period_nm: 1600.0,
        profile: Profile::Lamellar {
            duty: 0.5,
            depth_nm: 50.0,
        },
        metal: Metal::AG,
        cover: None,
    };
    let deg = |t: f64, p: f64, l: f64| Incidence::new(t.to_radians(), p.to_radians(), l).unwrap();
    let cases = [
        ("classical_al", &al, deg(30.0, 0.0, 550.0)),
        ("conical_al", &al, deg(30.0, 60.0, 550.0)),
        ("conical_ag", &ag, deg(60.0, 30.0, 450.0)),
    ];
    let mut group = c.benchmark_group("fmm");
    group.sample_size(10);
    for nh in [41, 81, 121] {
        for (name, g, at) in &cases {
            group.bench_function(format!("lamellar_{name}_{nh}"), |b| {
                b.iter(|| solver.solve_at(g, *at, nh).unwrap())
            });
        }
    }
    let classical = Incidence::classical(0.5, 550.0).unwrap();
    group.bench_function("sinusoid_classical_41_8_slabs", |b| {
        b.iter(|| solver.solve_at(&sinusoid, classical, 41).unwrap())
    });
    group.finish();

    // The C method at equal truncation with python_ref/cmethod.py (TE and TM both): the foil
    // preset's grating (Al sinusoid, 1000 l/mm, 100 nm) and blazed600 (Al sawtooth, 600 l/mm).
    let c_method = Solver::new(Options {
        method: Method::CMethod,
        ..Options::default()
    })
    .unwrap();
    let foil = Grating {
        period_nm: 1000.0,
        profile: Profile::Sinusoid { depth_nm: 100.0 },
        metal: Metal::AL,
        cover: None,
    };
    let blazed = Grating {
        period_nm: 1e6 / 600.0,
        profile: Profile::Sawtooth {
            blaze: (500.0f64 / (2.0 * 1e6 / 600.0)).asin(),
        },
        metal: Metal::AL,
        cover: None,
    };
    let at = Incidence::classical(0.5, 550.0).unwrap();
    let mut group = c.benchmark_group("cmethod");
    group.sample_size(10);
    for nh in [41, 81] {
        group.bench_function(format!("foil_{nh}"), |b| {
            b.iter(|| c_method.solve_at(&foil, at, nh).unwrap())
        });
    }
    group.bench_function("blazed600_81", |b| {
        b.iter(|| c_method.solve_at(&blazed, at, 81).unwrap())
    });
    // The conical mount against the classical one in the same run: the same gratings and
    // harmonic counts at θ = 30°, φ = 60° (one 4N system and two 2N eigenproblems, against
    // three 2N eigenproblems and two 2N systems), s and p.
    let conical = Incidence::new(30f64.to_radians(), 60f64.to_radians(), 550.0).unwrap();
    for nh in [41, 81] {
        group.bench_function(format!("foil_conical_{nh}"), |b| {
            b.iter(|| c_method.solve_at(&foil, conical, nh).unwrap())
        });
    }
    group.bench_function("blazed600_conical_81", |b| {
        b.iter(|| c_method.solve_at(&blazed, conical, 81).unwrap())
    });
    group.finish();
}

criterion_group!(benches, solves);
criterion_main!(benches);
