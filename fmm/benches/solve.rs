//! One solve at a fixed truncation: lamellar (TE + TM, classical) and conical, at 41 and 81
//! harmonics, and one staircased sinusoid.
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
    let lamellar = Grating {
        period_nm: 740.0,
        profile: Profile::Lamellar {
            duty: 0.5,
            depth_nm: 120.0,
        },
        metal: Metal::AL,
        cover: None,
    };
    let sinusoid = Grating {
        period_nm: 1000.0,
        profile: Profile::Sinusoid { depth_nm: 150.0 },
        metal: Metal::AG,
        cover: None,
    };
    let classical = Incidence::new(0.5, 0.0, 550.0).unwrap();
    let conical = Incidence::new(0.5, 0.8, 550.0).unwrap();
    let mut group = c.benchmark_group("fmm");
    group.sample_size(10);
    for nh in [41, 81] {
        group.bench_function(format!("lamellar_classical_{nh}"), |b| {
            b.iter(|| solver.solve_at(&lamellar, classical, nh).unwrap())
        });
        group.bench_function(format!("lamellar_conical_{nh}"), |b| {
            b.iter(|| solver.solve_at(&lamellar, conical, nh).unwrap())
        });
    }
    group.bench_function("sinusoid_classical_41_8_slabs", |b| {
        b.iter(|| solver.solve_at(&sinusoid, classical, 41).unwrap())
    });
    group.finish();
}

criterion_group!(benches, solves);
criterion_main!(benches);
