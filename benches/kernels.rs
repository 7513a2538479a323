//! Cost of the slit kernels: stable (this crate) against the naive formula, f32 and f64.
//!
//! Each iteration evaluates a fixed batch of 1024 phases spread over orders 1-40 near and away
//! from the peaks, so the figure reported per element is ns per evaluation.

use criterion::{black_box, BenchmarkId, Criterion, Throughput};
use diffraction::kernel::{n_slit, n_slit_cycles, naive, single_slit, single_slit_cycles};

const BATCH: usize = 1024;

fn phases() -> Vec<f64> {
    // Deterministic spread: orders 1..40, offsets within a few peak widths and mid-period.
    (0..BATCH)
        .map(|i| {
            let m = (i % 40 + 1) as f64;
            let off = ((i * 7919) % 1000) as f64 / 1000.0 - 0.5;
            m + off * if i % 2 == 0 { 1e-3 } else { 1.0 }
        })
        .collect()
}

fn bench_n_slit(c: &mut Criterion) {
    let xs = phases();
    let alphas: Vec<f64> = xs.iter().map(|x| x * core::f64::consts::PI).collect();
    let xs32: Vec<f32> = xs.iter().map(|&x| x as f32).collect();
    let alphas32: Vec<f32> = alphas.iter().map(|&a| a as f32).collect();
    let mut g = c.benchmark_group("n_slit");
    g.throughput(Throughput::Elements(BATCH as u64));
    for n in [30u32, 5000, 1_000_000] {
        g.bench_with_input(BenchmarkId::new("stable_cycles_f64", n), &n, |b, &n| {
            b.iter(|| {
                xs.iter()
                    .map(|&x| n_slit_cycles(black_box(x), n))
                    .sum::<f64>()
            })
        });
        g.bench_with_input(BenchmarkId::new("stable_radians_f64", n), &n, |b, &n| {
            b.iter(|| alphas.iter().map(|&a| n_slit(black_box(a), n)).sum::<f64>())
        });
        g.bench_with_input(BenchmarkId::new("naive_f64", n), &n, |b, &n| {
            b.iter(|| {
                alphas
                    .iter()
                    .map(|&a| naive::n_slit(black_box(a), n))
                    .sum::<f64>()
            })
        });
        g.bench_with_input(BenchmarkId::new("stable_cycles_f32", n), &n, |b, &n| {
            b.iter(|| {
                xs32.iter()
                    .map(|&x| n_slit_cycles(black_box(x), n))
                    .sum::<f32>()
            })
        });
        g.bench_with_input(BenchmarkId::new("naive_f32", n), &n, |b, &n| {
            b.iter(|| {
                alphas32
                    .iter()
                    .map(|&a| naive::n_slit(black_box(a), n))
                    .sum::<f32>()
            })
        });
    }
    g.finish();
}

fn bench_single_slit(c: &mut Criterion) {
    let ys: Vec<f64> = phases().iter().map(|x| 0.5 * x + 0.1).collect();
    let betas: Vec<f64> = ys.iter().map(|y| y * core::f64::consts::PI).collect();
    let betas32: Vec<f32> = betas.iter().map(|&b| b as f32).collect();
    let mut g = c.benchmark_group("single_slit");
    g.throughput(Throughput::Elements(BATCH as u64));
    g.bench_function("stable_cycles_f64", |b| {
        b.iter(|| {
            ys.iter()
                .map(|&y| single_slit_cycles(black_box(y)))
                .sum::<f64>()
        })
    });
    g.bench_function("stable_radians_f64", |b| {
        b.iter(|| {
            betas
                .iter()
                .map(|&x| single_slit(black_box(x)))
                .sum::<f64>()
        })
    });
    g.bench_function("naive_f64", |b| {
        b.iter(|| {
            betas
                .iter()
                .map(|&x| naive::single_slit(black_box(x)))
                .sum::<f64>()
        })
    });
    g.bench_function("naive_f32", |b| {
        b.iter(|| {
            betas32
                .iter()
                .map(|&x| naive::single_slit(black_box(x)))
                .sum::<f32>()
        })
    });
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_n_slit(&mut c);
    bench_single_slit(&mut c);
    c.final_summary();
}
