//! Cost of the tabulated order efficiencies on a BSDF's hot path: ns per
//! `EfficiencyTable::efficiencies(s, λ, out)` (all 17 orders of the `cd` preset at once, the
//! normalisation included) and per single-order `efficiency`, against the scalar relief model's
//! `orders` for the same grating (lamellar Al, d = 1600 nm, 110 nm, duty 0.3125) and a table
//! baked from it (`from_scalar`, f64 storage), in one group so the ratios come from one run.
//!
//! Each iteration runs a fixed batch of 1024 (sin θi, λ) queries from the benches' shared
//! generator (s uniform in (−1, 1), λ uniform in 360-830 nm), so criterion's per-element figure
//! is ns per call.

use criterion::{black_box, Criterion, Throughput};
use diffraction::relief::{EfficiencyTable, Metal, Polarised, Preset, Relief, ScalarRelief};
use std::time::Duration;

#[path = "support/rng.rs"]
mod rng;

const BATCH: usize = 1024;

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("efficiency");
    g.throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(1))
        .sample_size(30);
    let mut r = rng::Rng(0xEFF1);
    let queries: Vec<(f64, f64)> = (0..BATCH)
        .map(|_| (2.0 * r.next_f64() - 1.0, 360.0 + 470.0 * r.next_f64()))
        .collect();
    let cd = Preset::Cd.table();
    let scalar = ScalarRelief::new(
        Relief::lamellar(110.0, 0.3125).expect("valid relief"),
        Metal::AL,
        1600.0,
    )
    .expect("valid grating");
    let (s_grid, l_grid) = EfficiencyTable::default_grid();
    let baked = EfficiencyTable::from_scalar(&scalar, s_grid, l_grid).expect("valid grid");
    let mut out = vec![Polarised::default(); cd.order_count()];
    g.bench_function("cd_efficiencies", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(s, l) in &queries {
                acc += cd.efficiencies(black_box(s), black_box(l), &mut out);
            }
            acc
        })
    });
    g.bench_function("cd_efficiency_one_order", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(s, l) in &queries {
                acc += cd.efficiency(1, black_box(s), black_box(l)).te;
            }
            acc
        })
    });
    let mut out_baked = vec![Polarised::default(); baked.order_count()];
    g.bench_function("baked_scalar_efficiencies", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(s, l) in &queries {
                acc += baked.efficiencies(black_box(s), black_box(l), &mut out_baked);
            }
            acc
        })
    });
    g.bench_function("scalar_orders", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &(s, l) in &queries {
                for o in scalar.orders(black_box(s), black_box(l)) {
                    acc += o.efficiency.te;
                }
            }
            acc
        })
    });
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
