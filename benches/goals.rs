//! The goals of the speed work in one run, each as a ratio against a baseline measured in the
//! same run (docs/accuracy.md, "Where the time goes"):
//!
//! * `goals/xyz/*`: ns per XYZ over the accuracy report's 64 directions u (D65, w = d/2) for
//!   `uniform:471` (the baseline), `asymptotic`, `auto:1e-3` and `exact`, on a CD-like grating
//!   (d = 1600 nm, N = 1000) and on d = 740 nm, N = 10⁶; ratios auto / uniform and the
//!   per-XYZ medians.
//! * `goals/asymptotic_worst/*`: single directions where `Asymptotic` is slowest, against
//!   `uniform:471` at the same u: the slowest of a scan of the report's 64 u for d ∈ {400, 740,
//!   1600, 10⁴, 10⁵} nm and N ∈ {5, …, 10⁶} (coarse gratings with few slits: d = 100 µm,
//!   N = 5 and 10), the slowest of the same scan for N = 2-4 (d = 30 and 100 µm, where
//!   `Asymptotic` writes F_N as its cosines), the slowest of a scan (instructions per colour)
//!   for N = 5-10, 12, 15, 20 at d = 10, 30 and 100 µm (d = 30 µm, N = 5 and 6, the walk's
//!   slowest before F_N's cosines took N ≤ 7; d = 30 µm, N = 7, the cosines' slowest; d =
//!   100 µm, N = 8, the walk's slowest since), and the slowest of earlier scans (near the
//!   mirror direction with huge N).
//! * `goals/table_build/*`: `ColorTable::new` at `ColorTable::DEFAULT_ACCURACY` for the gratings of the
//!   goal (d ≤ 2 µm and a coarse one), against one `uniform:471` XYZ.
//! * `goals/bsdf/*`: `sample` + `pdf` of `GratingBsdf` against `AguHill::eval`, batches of 1024
//!   inputs near the peaks, N ∈ {1, 30, 1000, 10⁶}. Goal ≤ 3×; measured 6.8-7.3×, 3.7×,
//!   3.4-3.6×, 3.5-3.6× (two runs under a load of 4; docs/accuracy.md, "Where the time goes").
//!
//! `cargo bench --bench goals`

use criterion::{black_box, BenchmarkId, Criterion, SamplingMode, Throughput};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{AguHill, Bsdf, ColorTable, DiffractionBrdf, Grating, GratingBsdf};
use glam::DVec2;
use std::time::Duration;

#[path = "support/rng.rs"]
mod rng;

/// The accuracy report's 64 directions (examples/accuracy_report/main.rs).
fn u_grid() -> Vec<f64> {
    let mut v: Vec<f64> = (0..6).map(|k| 10f64.powf(-8.0 + k as f64)).collect();
    let ratio = (0.15f64 / 0.002).powf(1.0 / 13.0);
    v.extend((0..14).map(|k| 0.002 * ratio.powi(k)));
    v.extend((0..44).map(|k| 0.15 + 1.83 * (k as f64 + 0.5) / 44.0));
    v
}

fn bench_xyz(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let us = u_grid();
    let mut g = c.benchmark_group("goals/xyz");
    g.throughput(Throughput::Elements(us.len() as u64))
        .sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_secs(2));
    for (d, n) in [(1600.0, 1000u32), (740.0, 1_000_000)] {
        let grating = Grating::new(d, d / 2.0, n).expect("valid grating");
        for st in [
            Strategy::uniform(471).expect("valid"),
            Strategy::ASYMPTOTIC,
            Strategy::auto(1e-3).expect("valid"),
            Strategy::EXACT,
        ] {
            let id = BenchmarkId::new(format!("d{d}_n{n}"), st);
            g.bench_function(id, |b| {
                b.iter(|| {
                    us.iter()
                        .map(|&u| s.xyz(&grating, black_box(u), st).y)
                        .sum::<f64>()
                })
            });
        }
    }
    g.finish();
}

fn bench_asymptotic_worst(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let mut g = c.benchmark_group("goals/asymptotic_worst");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(200))
        .measurement_time(Duration::from_millis(800));
    for (d, n, u) in [
        (740.0, 1_000_000u32, 1e-4),
        (740.0, 3000, 0.020_449_296_327_101_688),
        (10_000.0, 5, 0.919_431_818_181_818_3),
        (100_000.0, 5, 0.669_886_363_636_363_7),
        (100_000.0, 5, 0.877_840_909_090_909_1),
        (100_000.0, 10, 0.586_704_545_454_545_4),
        (100_000.0, 8, 0.545_113_636_363_636_4),
        (30_000.0, 5, 1.959_204_545_454_545_5),
        (30_000.0, 6, 1.959_204_545_454_545_5),
        (30_000.0, 7, 1.127_386_363_636_363_7),
        (100_000.0, 2, 1.418_522_727_272_727_2),
        (100_000.0, 3, 1.335_340_909_090_909),
        (100_000.0, 4, 0.836_25),
        (30_000.0, 4, 1.792_840_909_090_909),
    ] {
        let grating = Grating::new(d, d / 2.0, n).expect("valid grating");
        for st in [Strategy::uniform(471).expect("valid"), Strategy::ASYMPTOTIC] {
            let id = BenchmarkId::new(format!("d{d}_n{n}_u{u:.3e}"), st);
            g.bench_function(id, |b| b.iter(|| s.xyz(&grating, black_box(u), st).y));
        }
    }
    g.finish();
}

fn bench_table_build(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let mut g = c.benchmark_group("goals/table_build");
    g.sample_size(10)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(100))
        .measurement_time(Duration::from_secs(3));
    for (d, n) in [
        (740.0, 1_000_000u32),
        (1600.0, 1000),
        (1600.0, 21),
        (100_000.0, 300),
    ] {
        let grating = Grating::new(d, d / 2.0, n).expect("valid grating");
        g.bench_function(format!("d{d}_n{n}"), |b| {
            b.iter(|| {
                ColorTable::new(&s, black_box(&grating), ColorTable::DEFAULT_ACCURACY)
                    .expect("valid")
            })
        });
    }
    let cd = Grating::new(1600.0, 800.0, 1000).expect("valid grating");
    let uniform = Strategy::uniform(471).expect("valid");
    g.bench_function("baseline_uniform471_xyz", |b| {
        b.iter(|| s.xyz(&cd, black_box(0.4), uniform).y)
    });
    g.finish();
}

fn bench_bsdf(c: &mut Criterion) {
    const BATCH: usize = 1024;
    let mut g = c.benchmark_group("goals/bsdf");
    g.throughput(Throughput::Elements(BATCH as u64))
        .sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(800));
    for n in [1u32, 30, 1000, 1_000_000] {
        let grating = Grating::new(1600.0, 800.0, n).expect("valid grating");
        let paper = AguHill::new(grating);
        let bsdf = GratingBsdf::new(grating);
        let inputs = rng::near_peak_samples(1600.0, n, BATCH);
        let mut r = rng::Rng(0x5eed ^ u64::from(n));
        let randoms: Vec<(f64, DVec2)> = (0..BATCH).map(|_| (r.next_f64(), r.u2())).collect();
        g.bench_with_input(BenchmarkId::new("agu_hill_eval", n), &inputs, |b, s| {
            b.iter(|| {
                let mut acc = 0.0;
                for &(wi, wo, l) in s {
                    acc += paper.eval(black_box(wo), black_box(wi), l);
                }
                acc
            })
        });
        g.bench_with_input(BenchmarkId::new("sample_and_pdf", n), &inputs, |b, s| {
            b.iter(|| {
                let mut acc = 0.0;
                for (&(_, wo, l), &(uc, u2)) in s.iter().zip(&randoms) {
                    if let Some(x) = bsdf.sample(black_box(wo), l, uc, u2) {
                        acc += bsdf.pdf(wo, black_box(x.wi), l);
                    }
                }
                acc
            })
        });
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_xyz(&mut c);
    bench_asymptotic_worst(&mut c);
    bench_table_build(&mut c);
    bench_bsdf(&mut c);
    c.final_summary();
}
