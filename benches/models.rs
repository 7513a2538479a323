//! Cost of the three grating models side by side: Agu-Hill (the paper), Thorman (peaks only) and
//! Stam (Fourier optics, feature `baselines`, sinusoidal and binary profiles).
//!
//! * `eval`: one spectral evaluation; each iteration evaluates a fixed, deterministic batch of
//!   1024 (wi, wo, λ), half of them near a peak of order 1-3 (for Stam also near the plane of
//!   the diffracted cone, where its lobes are not cut off early), so the figure per element is
//!   ns per evaluation.
//! * `xyz`: one colour through the generic path `Spectral::xyz_brdf` with its peak search and
//!   its `WINDOWS` rule, for every model alike (Agu-Hill's lobe-exact grating paths are in
//!   `benches/spectral.rs`), over a batch of 64 near-peak direction pairs.
//!
//! The models are set up to have the same peak widths: N = 10 slits, Thorman's
//! `matching` lobe at 550 nm, Stam's σ_c = N·d/(2√π).

use criterion::{black_box, BenchmarkId, Criterion, Throughput};
use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral};
use diffraction::{AguHill, DiffractionBrdf, Grating, SpectralResponse, Thorman};
use glam::DVec3;
use std::time::Duration;

const BATCH: usize = 1024;
const COLOURS: usize = 64;
const PERIOD: f64 = 1600.0;
const SLITS: u32 = 10;

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;

/// A model with its value and its colour (`dyn` needs one trait for both).
trait Model: DiffractionBrdf + SpectralResponse {}
impl<M: DiffractionBrdf + SpectralResponse> Model for M {}

/// (wi, wo, λ): every other one near order 1-3 of λ and near v = 0.
fn sample(rng: &mut Rng, i: usize) -> (DVec3, DVec3, f64) {
    let lambda = 380.0 + 400.0 * rng.next_f64();
    loop {
        let wi = rng.direction(0.2);
        if i % 2 == 1 {
            return (wi, rng.direction(0.2), lambda);
        }
        let m = 1.0 + (3.0 * rng.next_f64()).floor();
        let x = m * lambda / PERIOD - wi.x + 0.01 * (rng.next_f64() - 0.5);
        let y = -wi.y + 0.01 * (rng.next_f64() - 0.5);
        let z2 = 1.0 - x * x - y * y;
        if z2 > 0.04 {
            return (wi, DVec3::new(x, y, z2.sqrt()), lambda);
        }
    }
}

type Models = Vec<(&'static str, Box<dyn Model>)>;

/// The models under comparison, by name.
fn models() -> Models {
    let grating = Grating::new(PERIOD, PERIOD / 2.0, SLITS).unwrap();
    let mut v: Models = vec![
        ("agu_hill", Box::new(AguHill::new(grating))),
        (
            "thorman",
            Box::new(Thorman::matching(&grating, 550.0).unwrap()),
        ),
    ];
    v.extend(stam_models());
    v
}

#[cfg(feature = "baselines")]
fn stam_models() -> Models {
    use diffraction::{Profile, Stam};
    let coherence = SLITS as f64 * PERIOD / (2.0 * std::f64::consts::PI.sqrt());
    vec![
        (
            "stam_sine",
            Box::new(Stam::new(Profile::Sine, PERIOD, 80.0, coherence).unwrap()),
        ),
        (
            "stam_binary",
            Box::new(
                Stam::new(Profile::Binary { fraction: 0.5 }, PERIOD, 120.0, coherence).unwrap(),
            ),
        ),
    ]
}

#[cfg(not(feature = "baselines"))]
fn stam_models() -> Models {
    Vec::new()
}

fn bench_eval(c: &mut Criterion) {
    let mut rng = Rng(7);
    let batch: Vec<_> = (0..BATCH).map(|i| sample(&mut rng, i)).collect();
    let mut g = c.benchmark_group("eval");
    g.throughput(Throughput::Elements(BATCH as u64));
    for (name, model) in models() {
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                batch
                    .iter()
                    .map(|&(wi, wo, l)| model.eval(black_box(wo), black_box(wi), l))
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

fn bench_xyz(c: &mut Criterion) {
    let mut rng = Rng(11);
    let batch: Vec<_> = (0..COLOURS).map(|_| sample(&mut rng, 0)).collect();
    let spectral = Spectral::new(Illuminant::D65);
    let mut g = c.benchmark_group("xyz");
    g.throughput(Throughput::Elements(COLOURS as u64));
    g.measurement_time(Duration::from_secs(4));
    for (strategy, label) in [
        (GenericStrategy::PEAK_SEARCH, "peaks"),
        (GenericStrategy::WINDOWS, "windows"),
    ] {
        for (name, model) in models() {
            g.bench_function(BenchmarkId::new(label, name), |b| {
                b.iter(|| {
                    batch
                        .iter()
                        .map(|&(wi, wo, _)| {
                            spectral.xyz_brdf(&*model, black_box(wo), wi, strategy).y
                        })
                        .sum::<f64>()
                })
            });
        }
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_eval(&mut c);
    bench_xyz(&mut c);
    c.final_summary();
}
