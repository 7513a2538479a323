//! Cost of `ColorTable`: one lookup, one footprint mean, and one build, with `Spectral::xyz`
//! (`Exact`, `Asymptotic` and the peak search) in the same run as the baselines a renderer would otherwise call
//! at every hit.
//!
//! Lookups and means take a batch of 1024 phase projections u (half uniform on (−2, 2), half
//! log-uniform in |u| down to 10⁻⁹), so the figure per element is ns per colour averaged over
//! directions; `Spectral::xyz` takes the first 16 of them. Means are over intervals of width
//! 10⁻³ centred there. Tables are built with `diffraction::spectrum::DEFAULT_ACCURACY` under D65, slit width
//! d/2.
//!
//! The `radiometric_table` groups do the same for `ColorTable` of the radiometric BSDF (its
//! colour in physical units) against `Spectral::xyz_response`, its builds beside
//! the paper's table of the same grating, and (feature `serde`) a load of its cached JSON.
//!
//! The `tabulated_table` group (feature `presets`) times `xyz(wo, wi)` of the table of the CD
//! preset (N = 34, Gaussian groove σ = 0.02, D65, accuracy 10⁻³; `xyz_fine` at 2.5·10⁻⁴) at
//! 1024 random pairs against the generic colour of the same BSDF on 16 of them: `GenericStrategy::WINDOWS` (what the
//! Whitted renderer called before) and 8-point Gauss-Legendre on 512 intervals (the tests'
//! reference); `xyz_conical` times the table of the CD as `GratingBsdf::preset` reads it
//! (conically: 9 planes of |wi.y|) at pairs off the plane across the grooves.
//!
//! `cargo bench --features serde --bench color_table -- --warm-up-time 1 --measurement-time 2`

use criterion::{black_box, BenchmarkId, Criterion, Throughput};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{ColorTable, Grating};
use std::time::Duration;

const ACCURACY: f64 = diffraction::spectrum::DEFAULT_ACCURACY;
/// (period nm, N) of the lookup benchmarks.
const LOOKUP_GRATINGS: [(f64, u32); 3] = [(1600.0, 1000), (740.0, 1_000_000), (10_000.0, 30)];
/// (period nm, N) of the build benchmarks.
const BUILD_GRATINGS: [(f64, u32); 4] =
    [(400.0, 30), (1600.0, 21), (1600.0, 1000), (100_000.0, 300)];
const BATCH: usize = 1024;
const BASELINE_BATCH: usize = 16;

fn batch() -> Vec<f64> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..BATCH)
        .map(|k| {
            let sign = if next() < 0.5 { -1.0 } else { 1.0 };
            let a = if k % 2 == 0 {
                2.0 * next()
            } else {
                2.0 * 10f64.powf(-9.0 * next())
            };
            sign * a
        })
        .collect()
}

fn bench_lookup(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let us = batch();
    for (d, n) in LOOKUP_GRATINGS {
        let g = Grating::new(d, d / 2.0, n).unwrap();
        let table = ColorTable::new(&s, &g, ACCURACY).unwrap();
        let mut group = c.benchmark_group(format!("color_table/d{d}_n{n}"));
        group.throughput(Throughput::Elements(BATCH as u64));
        group.bench_function("lookup", |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &u in &us {
                    acc += table.lookup(black_box(u)).y;
                }
                acc
            })
        });
        group.bench_function("mean_1e-3", |b| {
            b.iter(|| {
                let mut acc = 0.0;
                for &u in &us {
                    acc += table.mean(black_box(u - 5e-4), black_box(u + 5e-4)).y;
                }
                acc
            })
        });
        group.throughput(Throughput::Elements(BASELINE_BATCH as u64));
        for strategy in [Strategy::EXACT, Strategy::ASYMPTOTIC, Strategy::PEAK_SEARCH] {
            group.bench_function(BenchmarkId::new("xyz", strategy), |b| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for &u in &us[..BASELINE_BATCH] {
                        acc += s.xyz(&g, black_box(u), strategy).y;
                    }
                    acc
                })
            });
        }
        group.finish();
    }
}

fn bench_build(c: &mut Criterion) {
    let s = Spectral::new(Illuminant::D65);
    let mut group = c.benchmark_group("color_table/build");
    group
        .sample_size(10)
        .sampling_mode(criterion::SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(100));
    for (d, n) in BUILD_GRATINGS {
        let g = Grating::new(d, d / 2.0, n).unwrap();
        group.bench_function(format!("d{d}_n{n}"), |b| {
            b.iter(|| ColorTable::new(&s, black_box(&g), ACCURACY).unwrap())
        });
    }
    group.finish();
}

/// The radiometric table (`ColorTable::new(&s, &bsdf, ·)`) of the `GratingBsdf` with a Gaussian groove
/// σ = 0.02 (and of N = ∞): lookups, `xyz(wo, wi)` and means per colour against the direct
/// colour `Spectral::xyz_response` (`Exact` and `auto(1e-3)`) at the same directions; builds
/// at accuracy 10⁻⁴ beside `ColorTable`'s of the same grating; a load of the cached JSON
/// (feature `serde`).
fn bench_radiometric(c: &mut Criterion) {
    use diffraction::{GratingBsdf, GrooveSpread, SpectralResponse};
    use glam::DVec3;
    let s = Spectral::new(Illuminant::D65);
    let rough = GrooveSpread::gaussian(0.02).unwrap();
    let us = batch();
    // Direction pairs with u = wi.x + wo.x from the batch (halved into both) and v = 0.01.
    let pairs: Vec<(DVec3, DVec3)> = us
        .iter()
        .map(|&u| {
            let (x, y) = (0.5 * u.clamp(-1.98, 1.98), 0.005);
            let z = (1.0 - x * x - y * y).sqrt();
            (DVec3::new(x, y, z), DVec3::new(x, y, z))
        })
        .collect();
    let bsdfs = [
        (
            "d1600_n1000",
            GratingBsdf::new(Grating::new(1600.0, 800.0, 1000).unwrap()).with_groove(rough),
        ),
        (
            "d1600_inf",
            GratingBsdf::new(Grating::infinite(1600.0, 800.0).unwrap()).with_groove(rough),
        ),
    ];
    for (name, b) in &bsdfs {
        let table = ColorTable::new(&s, b, ACCURACY).unwrap();
        let mut group = c.benchmark_group(format!("radiometric_table/{name}"));
        group.throughput(Throughput::Elements(BATCH as u64));
        group.bench_function("lookup", |bch| {
            bch.iter(|| {
                us.iter()
                    .map(|&u| table.lookup(black_box(u)).y)
                    .sum::<f64>()
            })
        });
        group.bench_function("xyz", |bch| {
            bch.iter(|| {
                pairs
                    .iter()
                    .map(|&(o, i)| table.xyz(black_box(o), i).y)
                    .sum::<f64>()
            })
        });
        group.bench_function("mean_1e-3", |bch| {
            bch.iter(|| {
                us.iter()
                    .map(|&u| table.mean(black_box(u - 5e-4), u + 5e-4).y)
                    .sum::<f64>()
            })
        });
        group.throughput(Throughput::Elements(BASELINE_BATCH as u64));
        // N = ∞ has no grating response (delta lobes): no baseline.
        let baselines = if b.grating().slits().as_f64().is_finite() {
            vec![Strategy::EXACT, Strategy::auto(1e-3).unwrap()]
        } else {
            vec![]
        };
        for strategy in baselines {
            group.bench_function(BenchmarkId::new("xyz_response", strategy), |bch| {
                bch.iter(|| {
                    pairs[..BASELINE_BATCH]
                        .iter()
                        .filter_map(|&(o, i)| b.grating_response(black_box(o), i))
                        .map(|r| s.xyz_response(&r, strategy).y)
                        .sum::<f64>()
                })
            });
        }
        group.finish();
    }
    let mut group = c.benchmark_group("radiometric_table/build_1e-4");
    group
        .sample_size(10)
        .sampling_mode(criterion::SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(100));
    for (d, n) in [(1600.0, 1000), (740.0, 30)] {
        let g = Grating::new(d, d / 2.0, n).unwrap();
        let b = GratingBsdf::new(g).with_groove(rough);
        group.bench_function(format!("radiometric_d{d}_n{n}"), |bch| {
            bch.iter(|| ColorTable::new(&s, black_box(&b), 1e-4).unwrap())
        });
        group.bench_function(format!("color_table_d{d}_n{n}"), |bch| {
            bch.iter(|| ColorTable::new(&s, black_box(&g), 1e-4).unwrap())
        });
    }
    let (_, inf) = &bsdfs[1];
    group.bench_function("radiometric_d1600_inf", |bch| {
        bch.iter(|| ColorTable::new(&s, black_box(inf), 1e-4).unwrap())
    });
    #[cfg(feature = "serde")]
    {
        let table = ColorTable::new(&s, &bsdfs[0].1, 1e-4).unwrap();
        let json = serde_json::to_string(&table).unwrap();
        group.bench_function("load_json_d1600_n1000", |bch| {
            bch.iter(|| serde_json::from_str::<ColorTable>(black_box(&json)).unwrap())
        });
    }
    group.finish();
}

#[cfg(feature = "presets")]
fn bench_tabulated(c: &mut Criterion) {
    use diffraction::grating_bsdf::OrderEfficiency;
    use diffraction::relief::Preset;
    use diffraction::spectrum::GenericStrategy;
    use diffraction::{GratingBsdf, GrooveSpread};
    use glam::DVec3;
    let s = Spectral::new(Illuminant::D65);
    // The preset's classical table: the colour the table holds (`GratingBsdf::preset`'s
    // conical reading makes the same table).
    let classical = OrderEfficiency::from_static(Preset::Cd.table()).unwrap();
    let b = GratingBsdf::preset(Preset::Cd, 34)
        .and_then(|b| b.with_efficiency(classical))
        .unwrap()
        .with_groove(GrooveSpread::gaussian(0.02).unwrap());
    let table = ColorTable::new(&s, &b, 1e-3).unwrap();
    // wi.x, wo.x uniform in (−0.98, 0.98), v = 0.01 (a fixed LCG: no extra dependency).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let pairs: Vec<(DVec3, DVec3)> = (0..BATCH)
        .map(|_| {
            let (ix, ox) = (1.96 * next() - 0.98, 1.96 * next() - 0.98);
            let (iy, oy) = (0.0, 0.01);
            let wi = DVec3::new(ix, iy, (1.0 - ix * ix - iy * iy).sqrt());
            let wo = DVec3::new(ox, oy, (1.0 - ox * ox - oy * oy).sqrt());
            (wo, wi)
        })
        .collect();
    let lookups = |t: &ColorTable| {
        pairs
            .iter()
            .map(|&(o, i)| t.xyz(black_box(o), i).y)
            .sum::<f64>()
    };
    let mut group = c.benchmark_group("tabulated_table/cd_n34");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("xyz", |bch| bch.iter(|| lookups(&table)));
    // The finest table (2.5·10⁻⁴: about a minute to build, so only when its benchmark runs).
    let fine = std::cell::OnceCell::new();
    group.bench_function("xyz_fine", |bch| {
        let fine = fine.get_or_init(|| ColorTable::new(&s, &b, 2.5e-4).unwrap());
        bch.iter(|| lookups(fine))
    });
    // The conical reading (`GratingBsdf::preset`'s): its table of 9 planes of |wi.y| (about 20 s
    // to build, so only when its benchmark runs), at pairs off the plane across the grooves,
    // wi.y uniform in [0, 0.6] and wo.y = −wi.y − 0.01 (the groove lobe).
    let conical = GratingBsdf::preset(Preset::Cd, 34)
        .unwrap()
        .with_groove(GrooveSpread::gaussian(0.02).unwrap());
    let off_plane: Vec<(DVec3, DVec3)> = pairs
        .iter()
        .map(|&(o, i)| {
            let iy = 0.6 * next();
            let oy = -iy - 0.01;
            let (ix, ox) = (i.x * (1.0 - iy * iy).sqrt(), o.x * (1.0 - oy * oy).sqrt());
            let wi = DVec3::new(ix, iy, (1.0 - ix * ix - iy * iy).sqrt());
            let wo = DVec3::new(ox, oy, (1.0 - ox * ox - oy * oy).sqrt());
            (wo, wi)
        })
        .collect();
    let conical_table = std::cell::OnceCell::new();
    group.bench_function("xyz_conical", |bch| {
        let t = conical_table.get_or_init(|| ColorTable::new(&s, &conical, 1e-3).unwrap());
        bch.iter(|| {
            off_plane
                .iter()
                .map(|&(o, i)| t.xyz(black_box(o), i).y)
                .sum::<f64>()
        })
    });
    group.throughput(Throughput::Elements(BASELINE_BATCH as u64));
    let rules = [
        ("windows", GenericStrategy::WINDOWS),
        ("gl512", GenericStrategy::gauss_legendre(512).unwrap()),
    ];
    for (name, rule) in rules {
        group.bench_function(BenchmarkId::new("xyz_brdf", name), |bch| {
            bch.iter(|| {
                pairs[..BASELINE_BATCH]
                    .iter()
                    .map(|&(o, i)| s.xyz_brdf(&b, black_box(o), i, rule).y)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_lookup(&mut c);
    bench_build(&mut c);
    bench_radiometric(&mut c);
    #[cfg(feature = "presets")]
    bench_tabulated(&mut c);
    c.final_summary();
}
