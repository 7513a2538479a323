//! Cost of one BRDF evaluation at one wavelength: `AguHill`'s `eval` (f64) and `eval_f32`,
//! against the textbook formula written directly in f32 and f64 (`kernel::naive`).
//!
//! Each iteration evaluates a fixed, deterministic batch of 1024 (wi, wo, λ), half of them within
//! a few lobes of a diffraction peak, so the figure reported per element is ns per evaluation.
//! Gratings: N ∈ {1, 30, 1000, 10⁶} slits, periods 740, 1600 and 100 000 nm, slit width d/2.

use criterion::{black_box, BenchmarkId, Criterion, Throughput};
use diffraction::{AguHill, DiffractionBrdf, Grating};
use glam::{DVec3, Vec3};
use std::time::Duration;

const BATCH: usize = 1024;
const SLITS: [u32; 4] = [1, 30, 1000, 1_000_000];
const PERIODS: [f64; 3] = [740.0, 1600.0, 100_000.0];

#[path = "support/naive.rs"]
mod naive_formula;
use naive_formula::{naive_f32, naive_f64};
#[path = "support/rng.rs"]
mod rng;

/// The batch for one grating: (wi, wo, λ), every other one near a peak of order 1-4.
fn samples(period: f64, n: u32) -> Vec<(DVec3, DVec3, f64)> {
    rng::near_peak_samples(period, n, BATCH)
}

fn bench_eval(c: &mut Criterion) {
    let mut g = c.benchmark_group("brdf_eval");
    g.throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(1))
        .sample_size(50);
    for period in PERIODS {
        for n in SLITS {
            let w = period / 2.0;
            let brdf = AguHill::new(Grating::new(period, w, n).expect("valid grating"));
            let s64 = samples(period, n);
            let s32: Vec<(Vec3, Vec3, f32)> = s64
                .iter()
                .map(|&(a, b, l)| (a.as_vec3(), b.as_vec3(), l as f32))
                .collect();
            let (d32, w32) = (period as f32, w as f32);
            let id = format!("N={n},d={period}");
            g.bench_function(BenchmarkId::new("eval_f64", &id), |b| {
                b.iter(|| {
                    s64.iter()
                        .map(|&(wi, wo, l)| brdf.eval(black_box(wi), wo, l))
                        .sum::<f64>()
                })
            });
            g.bench_function(BenchmarkId::new("eval_f32", &id), |b| {
                b.iter(|| {
                    s32.iter()
                        .map(|&(wi, wo, l)| brdf.eval_f32(black_box(wi), wo, l))
                        .sum::<f32>()
                })
            });
            g.bench_function(BenchmarkId::new("naive_f64", &id), |b| {
                b.iter(|| {
                    s64.iter()
                        .map(|&(wi, wo, l)| naive_f64(period, w, n, black_box(wi), wo, l))
                        .sum::<f64>()
                })
            });
            g.bench_function(BenchmarkId::new("naive_f32", &id), |b| {
                b.iter(|| {
                    s32.iter()
                        .map(|&(wi, wo, l)| naive_f32(d32, w32, n, black_box(wi), wo, l))
                        .sum::<f32>()
                })
            });
        }
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_eval(&mut c);
    c.final_summary();
}
