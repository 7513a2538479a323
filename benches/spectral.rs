//! Cost of one XYZ colour, `Spectral::xyz`, for every strategy, and of the Monte-Carlo
//! estimators `xyz_stratified` (8 wavelengths) and `xyz_hero` (4), under D65.
//!
//! Each iteration evaluates a fixed batch of 16 phase projections u spread evenly over (−2, 2),
//! so the figure reported per element is ns per XYZ averaged over directions. Gratings: N ∈ {1,
//! 30, 1000, 10⁶} slits, periods 740, 1600 and 100 000 nm, slit width d/2; one group per grating,
//! the strategies side by side. The group `peaks_by_region` separates the peak search's two
//! regimes: u where every wavelength of the band sees only orders m ≠ 0 (d·|u| ≥ 415 nm) and u
//! where order 0's half period reaches into the band (integrated by quadrature).
//!
//! Some strategies cost milliseconds per XYZ (the lobe-exact one for coarse gratings with many
//! slits, the peak searches for a few slits); a benchmark whose batch takes more than 2 ms takes
//! 10 samples of one batch each (flat sampling) to keep the default run to a few minutes.

use criterion::measurement::WallTime;
use criterion::{black_box, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode, Throughput};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::Grating;
use std::time::{Duration, Instant};

const SLITS: [u32; 4] = [1, 30, 1000, 1_000_000];
const PERIODS: [f64; 3] = [740.0, 1600.0, 100_000.0];
/// Number of u values per iteration.
const BATCH: usize = 16;

/// 16 values of u at the centres of equal steps of (−2, 2): ±0.125, ±0.375, …, ±1.875.
fn u_batch() -> Vec<f64> {
    (0..BATCH)
        .map(|k| -2.0 + 4.0 * (k as f64 + 0.5) / BATCH as f64)
        .collect()
}

/// Deterministic numbers in [0, 1) for the Monte-Carlo estimators (one set, reused).
const STRATA: [f64; 8] = [0.12, 0.87, 0.45, 0.33, 0.71, 0.05, 0.58, 0.94];
const HERO_XI: f64 = 0.37;

fn strategies() -> Vec<Strategy> {
    vec![
        Strategy::uniform(471).unwrap(),
        Strategy::uniform(32).unwrap(),
        Strategy::uniform(128).unwrap(),
        Strategy::gauss_legendre(4).unwrap(),
        Strategy::gauss_legendre(16).unwrap(),
        Strategy::gauss_legendre(59).unwrap(),
        Strategy::PEAK_SEARCH,
        Strategy::PEAK_SEARCH_REFINED,
        Strategy::EXACT,
        Strategy::ASYMPTOTIC,
        Strategy::auto(1e-2).unwrap(),
        Strategy::auto(1e-3).unwrap(),
        Strategy::auto(1e-4).unwrap(),
    ]
}

/// Whether one batch takes more than 2 ms (then fewer, flat samples).
fn slow(batch: impl FnOnce() -> f64) -> bool {
    let t = Instant::now();
    black_box(batch());
    t.elapsed() > Duration::from_millis(2)
}

fn configure(g: &mut BenchmarkGroup<'_, WallTime>, slow: bool) {
    if slow {
        g.sample_size(10)
            .sampling_mode(SamplingMode::Flat)
            .warm_up_time(Duration::from_millis(100))
            .measurement_time(Duration::from_secs(2));
    } else {
        g.sample_size(20)
            .sampling_mode(SamplingMode::Auto)
            .warm_up_time(Duration::from_millis(300))
            .measurement_time(Duration::from_millis(800));
    }
}

fn bench_xyz(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let us = u_batch();
    for period in PERIODS {
        for n in SLITS {
            let grating = Grating::new(period, period / 2.0, n).expect("valid grating");
            let mut g = c.benchmark_group(format!("xyz_N={n}_d={period}"));
            g.throughput(Throughput::Elements(BATCH as u64));
            for strategy in strategies() {
                let batch = || {
                    us.iter()
                        .map(|&u| s.xyz(&grating, black_box(u), strategy).y)
                        .sum::<f64>()
                };
                configure(&mut g, slow(batch));
                g.bench_function(BenchmarkId::from_parameter(strategy), |b| b.iter(batch));
            }
            configure(&mut g, false);
            g.bench_function("paper", |b| {
                b.iter(|| {
                    us.iter()
                        .map(|&u| s.paper_peaks(&grating, black_box(u)).y)
                        .sum::<f64>()
                })
            });
            g.bench_function("stratified:8", |b| {
                b.iter(|| {
                    us.iter()
                        .map(|&u| s.xyz_stratified(&grating, black_box(u), &STRATA).y)
                        .sum::<f64>()
                })
            });
            g.bench_function("hero:4", |b| {
                b.iter(|| {
                    us.iter()
                        .map(|&u| s.xyz_hero(&grating, black_box(u), HERO_XI, 4).y)
                        .sum::<f64>()
                })
            });
            g.finish();
        }
    }
}

fn bench_peaks_by_region(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let mut g = c.benchmark_group("peaks_by_region");
    configure(&mut g, false);
    for period in [740.0, 1600.0] {
        // d·|u| ≥ 415 nm: x = d·|u|/λ ≥ ½ over the whole band.
        let u_orders = 415.0 / period;
        let orders: Vec<f64> = (0..BATCH)
            .map(|k| u_orders + (1.99 - u_orders) * (k as f64 + 0.5) / BATCH as f64)
            .collect();
        let order0: Vec<f64> = (0..BATCH)
            .map(|k| u_orders * (k as f64 + 0.5) / BATCH as f64)
            .collect();
        for n in [1000u32, 1_000_000] {
            let grating = Grating::new(period, period / 2.0, n).expect("valid grating");
            g.throughput(Throughput::Elements(BATCH as u64));
            for (region, us) in [("orders", &orders), ("order0", &order0)] {
                let id = BenchmarkId::new(region, format!("N={n},d={period}"));
                g.bench_function(id, |b| {
                    b.iter(|| {
                        us.iter()
                            .map(|&u| {
                                let st = Strategy::PEAK_SEARCH;
                                s.xyz(&grating, black_box(u), st).y
                            })
                            .sum::<f64>()
                    })
                });
            }
        }
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_xyz(&mut c);
    bench_peaks_by_region(&mut c);
    c.final_summary();
}
