//! The sweep of the round-3 input surfaces: random and adversarial inputs to
//! `EfficiencyTable::new`, `efficiency` and `efficiencies`, the JSON reader, `ScalarRelief`,
//! `GratingBsdf` with tabulated efficiencies (`eval`, `pdf`, `sample`, `sample4`, `albedo`),
//! the colour table's stored form, `SampledWavelengths` and `SampledSpectrum::to_xyz`.
//!
//! Every accepted input must give finite, non-negative outputs with Σ η ≤ 1 and sample weights
//! within `sample_weight_bound`; every refused one a message naming a field (short, whatever
//! the input). Work is counted as what each call reports of its own (orders written, orders
//! visited, nodes and evaluations of a loaded table), never timed, and bounded by the
//! documented caps.
//!
//! `sweep` (CI: about a second in release) draws [`QUICK_CASES`] cases; `sweep_long` (ignored:
//! `cargo test --release --all-features --test surfaces_sweep -- --ignored`) draws a hundred
//! times as many from another seed. Each prints its tally: calls per surface, the classes of
//! input drawn, accepted and refused.
#![cfg(feature = "serde")]

use std::sync::Arc;

use diffraction::grating_bsdf::{OrderEfficiency, MAX_TABULATED_ORDERS};
use diffraction::relief::{
    EfficiencyTable, Metal, Polarised, Preset, Relief, ScalarRelief, MAX_TABLE_ORDERS,
};
use diffraction::spectrum::{Illuminant, Spectral};
use diffraction::{
    Bsdf, ColorTable, DiffractionBrdf, Grating, GratingBsdf, SampledSpectrum, SampledWavelengths,
    SpectralFilm,
};

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;
#[path = "support/sweep.rs"]
mod sweep;
use sweep::{MAX_MESSAGE, SUM_ROUNDING};

/// Cases drawn by the quick sweep.
const QUICK_CASES: usize = 400;

/// Values that break arithmetic: subnormals, the ends of the range, exact grid values.
const EXTREMES: [f64; 14] = [
    0.0,
    -0.0,
    5e-324,
    1e-310,
    f64::MIN_POSITIVE,
    1e-300,
    1e-17,
    0.5,
    1.0,
    -1.0,
    1e300,
    f64::MAX,
    0.9999,
    999.9995,
];

#[derive(Debug, Default)]
struct Tally {
    tables_built: u64,
    tables_refused: u64,
    queries: u64,
    orders_written: u64,
    json_accepted: u64,
    json_refused: u64,
    relief_calls: u64,
    relief_orders: u64,
    bsdf_calls: u64,
    bsdf_refused: u64,
    stored_accepted: u64,
    stored_refused: u64,
    wavelength_calls: u64,
}

/// A number from [`EXTREMES`], or random in a range, or a random bit pattern's float.
fn value(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    sweep::value(r, &EXTREMES, lo, hi)
}

/// A strictly increasing axis most of the time (sometimes not: the check must refuse it).
fn axis(r: &mut Rng, lo: f64, hi: f64) -> Vec<f64> {
    let n = 2 + (r.next_u64() % 5) as usize;
    let mut v: Vec<f64> = (0..n).map(|_| lo + (hi - lo) * r.next_f64()).collect();
    if r.next_u64() % 6 != 0 {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    if r.next_u64() % 8 == 0 {
        // A node on or next to a Rayleigh line, or a tiny step.
        let k = (r.next_u64() % v.len() as u64) as usize;
        v[k] = value(r, lo, hi);
    }
    v
}

/// Checks one query of an accepted table and counts it.
fn check_query(t: &EfficiencyTable, s: f64, lambda: f64, tally: &mut Tally) {
    let mut out = vec![Polarised::default(); t.order_count()];
    let total = t.efficiencies(s, lambda, &mut out);
    tally.queries += 1;
    tally.orders_written += out.len() as u64;
    let repro = || format!("{t:?} at s = {s:e}, λ = {lambda:e}");
    assert!(
        total.is_finite() && (0.0..=1.0 + SUM_ROUNDING).contains(&total),
        "{total}: {}",
        repro()
    );
    let (te, tm): (f64, f64) = (
        out.iter().map(|e| e.te).sum(),
        out.iter().map(|e| e.tm).sum(),
    );
    assert!(
        te <= 1.0 + SUM_ROUNDING && tm <= 1.0 + SUM_ROUNDING,
        "{te} {tm}: {}",
        repro()
    );
    for e in &out {
        assert!(
            e.te.is_finite() && e.te >= 0.0 && e.tm.is_finite() && e.tm >= 0.0,
            "{}",
            repro()
        );
    }
    let m = t.orders().start() + (s.to_bits() % t.order_count() as u64) as i32;
    let one = t.efficiency(m, s, lambda);
    assert!(
        one.te.is_finite() && one.te >= 0.0 && one.tm.is_finite() && one.tm >= 0.0,
        "{}",
        repro()
    );
}

/// A random table: mostly accepted (values scaled below 1 per node and zero where evanescent),
/// sometimes corrupted.
fn random_table(r: &mut Rng, tally: &mut Tally) -> Option<EfficiencyTable> {
    let period = if r.next_u64() % 4 == 0 {
        value(r, 100.0, 1e5)
    } else {
        200.0 + 4000.0 * r.next_f64()
    };
    let s = axis(r, -1.0, 1.0);
    let l = axis(r, 300.0, 1200.0);
    let orders = 1 + (r.next_u64() % 9) as usize;
    let order_min = -((r.next_u64() % 6) as i32);
    let slice = s.len() * l.len();
    let mut te = vec![0.0; orders * slice];
    for (i, x) in te.iter_mut().enumerate() {
        let k = i / slice;
        let (j, ii) = ((i % slice) / s.len(), i % s.len());
        let sm = s[ii] + f64::from(order_min + k as i32) * l[j] / period;
        if 1.0 - sm * sm > 0.0 {
            *x = r.next_f64() / orders as f64;
        }
    }
    if r.next_u64() % 10 == 0 {
        let k = (r.next_u64() % te.len() as u64) as usize;
        te[k] = value(r, 0.0, 1.0);
    }
    let tm: Vec<f64> = te.iter().map(|x| 0.9 * x).collect();
    match EfficiencyTable::new(period, order_min, s, l, te, tm) {
        Ok(t) => {
            tally.tables_built += 1;
            Some(t)
        }
        Err(e) => {
            tally.tables_refused += 1;
            assert!(!e.parameter().is_empty() && e.to_string().len() < MAX_MESSAGE);
            None
        }
    }
}

/// A JSON text of a table, mutated: a token replaced by a hostile one, or the text cut.
fn hostile_json(r: &mut Rng) -> String {
    let good = r#"{"format": "diffraction-efficiency-table", "version": 1, "grating": {"period_nm": 1000.0}, "sin_theta_i": [0.0, 0.5], "lambda_nm": [999.9995, 1200.0], "order_min": -1, "order_max": 0, "te": [[[0.01, 0.3], [0.0, 0.2]], [[0.9, 0.6], [0.9, 0.7]]], "tm": [[[0.01, 0.3], [0.0, 0.2]], [[0.9, 0.6], [0.9, 0.7]]]}"#;
    const TOKENS: [&str; 16] = [
        "null",
        "1e400",
        "-0",
        "[]",
        "{}",
        "\"x\"",
        "NaN",
        "1.5",
        "9223372036854775807",
        "-9223372036854775809",
        "18446744073709551616",
        "[[[]]]",
        "true",
        "5e-324",
        "2",
        "[0.5, 0.5]",
    ];
    let numbers: Vec<(usize, usize)> = {
        let b = good.as_bytes();
        let mut out = vec![];
        let mut i = 0;
        while i < b.len() {
            if b[i].is_ascii_digit() || b[i] == b'-' {
                let start = i;
                while i < b.len() && (b[i].is_ascii_digit() || b"-.e".contains(&b[i])) {
                    i += 1;
                }
                out.push((start, i));
            }
            i += 1;
        }
        out
    };
    match r.next_u64() % 4 {
        0 => good[..(r.next_u64() % good.len() as u64) as usize].to_string(),
        _ => {
            let (a, b) = numbers[(r.next_u64() % numbers.len() as u64) as usize];
            let t = TOKENS[(r.next_u64() % TOKENS.len() as u64) as usize];
            format!("{}{t}{}", &good[..a], &good[b..])
        }
    }
}

/// The field names a refusal may start with (or serde's own words for a whole-file problem).
const FIELDS: [&str; 14] = [
    "format",
    "version",
    "grating",
    "sin_theta_i",
    "lambda_nm",
    "order_min",
    "order_max",
    "te",
    "tm",
    "invalid ",
    "missing field",
    "duplicate field",
    "EOF",
    "expected",
];

fn sweep_with(cases: usize, seed: u64) {
    let mut r = Rng::new(seed);
    let mut tally = Tally::default();
    let spectral = Spectral::new(Illuminant::D65);
    let film = SpectralFilm::new(Illuminant::D65);
    // A stored colour table to corrupt.
    let stored = serde_json::to_value(
        ColorTable::new(&spectral, &Grating::new(1600.0, 800.0, 30).unwrap(), 1e-2).unwrap(),
    )
    .unwrap();
    let presets: Vec<Arc<EfficiencyTable>> = Preset::ALL
        .iter()
        .map(|p| Arc::new(p.table().clone()))
        .collect();
    for case in 0..cases {
        // Tables built in memory, and their queries.
        let table = random_table(&mut r, &mut tally);
        let table = table
            .map(Arc::new)
            .unwrap_or_else(|| presets[case % presets.len()].clone());
        for _ in 0..4 {
            let s = value(&mut r, -1.0, 1.0);
            let lambda = value(&mut r, 300.0, 1200.0);
            check_query(&table, s, lambda, &mut tally);
            // A query a subnormal step from a node.
            let node = table
                .sin_theta_i()
                .nth((r.next_u64() % 2) as usize)
                .unwrap();
            check_query(
                &table,
                node + 5e-324,
                table.lambda_nm().next().unwrap(),
                &mut tally,
            );
        }
        // The JSON reader.
        let text = hostile_json(&mut r);
        match serde_json::from_str::<EfficiencyTable>(&text) {
            Ok(t) => {
                tally.json_accepted += 1;
                assert!(t.order_count() <= MAX_TABLE_ORDERS);
                check_query(&t, 5e-324, 999.9995, &mut tally);
            }
            Err(e) => {
                tally.json_refused += 1;
                let e = e.to_string();
                assert!(e.len() < MAX_MESSAGE, "{text}: {e}");
                assert!(FIELDS.iter().any(|f| e.starts_with(f)), "{text}: {e}");
            }
        }
        // The scalar relief model: Σ η ≤ 1 over its orders, each finite and ≥ 0.
        let d = value(&mut r, 100.0, 1e5);
        let relief = match r.next_u64() % 3 {
            0 => Relief::sinusoid(value(&mut r, 0.0, 500.0)),
            1 => Relief::lamellar(value(&mut r, 0.0, 500.0), r.next_f64()),
            _ => Relief::sawtooth(value(&mut r, 0.0, 0.7)),
        };
        let metal = [Metal::AL, Metal::AG, Metal::AU, Metal::CU, Metal::CR][case % 5];
        if let Ok(g) = relief.and_then(|rl| ScalarRelief::new(rl, metal, d)) {
            let (s, lambda) = (value(&mut r, -1.0, 1.0), value(&mut r, 300.0, 1200.0));
            let (mut te, mut tm, mut n) = (0.0, 0.0, 0u64);
            for o in g.orders(s, lambda) {
                let e = o.efficiency;
                assert!(e.te.is_finite() && e.te >= 0.0 && e.tm.is_finite() && e.tm >= 0.0);
                te += e.te;
                tm += e.tm;
                n += 1;
            }
            tally.relief_calls += 1;
            tally.relief_orders += n;
            assert!(n <= 2 * 2048 + 1, "{g:?} at {s:e}, {lambda:e}: {n} orders");
            assert!(
                te <= 1.0 + SUM_ROUNDING && tm <= 1.0 + SUM_ROUNDING,
                "{g:?} at {s:e}, {lambda:e}"
            );
        }
        // The grating BSDF with tabulated efficiencies.
        if table.order_count() <= MAX_TABULATED_ORDERS {
            let slits = [1u32, 34, 1000, u32::MAX][case % 4];
            // Any grating: `with_efficiency` takes the table's period, or reports the grating
            // it cannot build there (a period so small that half of it rounds to 0).
            let g = Grating::new(1600.0, 800.0, slits).unwrap();
            let e = OrderEfficiency::from_table(table.clone()).unwrap();
            let built = GratingBsdf::new(g).with_efficiency(e);
            if let Err(e) = &built {
                assert_eq!(e.parameter(), "slit_width_nm", "{table:?}");
                tally.bsdf_refused += 1;
            }
            if let Ok(b) = built {
                let (wo, wi) = (r.direction(1e-3), r.direction(1e-3));
                let lambda = value(&mut r, 360.0, 830.0);
                let f = b.eval(wo, wi, lambda);
                let p = b.pdf(wo, wi, lambda);
                assert!(
                    f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
                    "{b:?} {wo} {wi} {lambda}"
                );
                let bound = b.sample_weight_bound(wo, lambda);
                if let Some(x) = b.sample(wo, lambda, r.next_f64(), r.u2()) {
                    let w = x.weight();
                    assert!(
                        w.is_finite() && w >= 0.0 && w <= bound * (1.0 + 1e-9),
                        "{w} > {bound}: {b:?} {wo} {lambda}"
                    );
                }
                if let Some(a) = b.albedo(wo, lambda) {
                    assert!(
                        a.is_finite() && (0.0..=1.0 + SUM_ROUNDING).contains(&a),
                        "albedo {a}"
                    );
                }
                let ls = SampledWavelengths::sample_visible(r.next_f64());
                if let Some(x) = b.sample4(wo, &ls, r.next_f64(), r.u2()) {
                    for w in x.weight().values() {
                        assert!(w.is_finite() && w >= 0.0, "sample4 weight {w}");
                    }
                }
                tally.bsdf_calls += 5;
            }
        }
        // The colour table's stored form, one field corrupted.
        let mut v = stored.clone();
        let target = match r.next_u64() % 6 {
            0 => &mut v["grid"]["scale"],
            1 => &mut v["grid"]["error"],
            2 => &mut v["grid"]["evaluations"],
            3 => &mut v["grid"]["u_lo"],
            4 => &mut v["accuracy"],
            _ => &mut v["grid"]["values"][(case % 9) + 1][case % 3],
        };
        *target = if r.next_u64() % 3 == 0 {
            serde_json::json!(r.next_u64())
        } else {
            let x = value(&mut r, 0.0, 2.0);
            if x.is_finite() {
                serde_json::json!(x)
            } else {
                serde_json::json!(null)
            }
        };
        match serde_json::from_value::<ColorTable>(v) {
            Ok(t) => {
                tally.stored_accepted += 1;
                assert!(t.node_count() <= ColorTable::MAX_NODES);
                assert!(t.evaluations() <= 2 * t.node_count());
                for u in [0.0, 5e-324, 0.3, 1.0, 2.0] {
                    let c = t.lookup(u);
                    assert!(c.x.is_finite() && c.x >= 0.0 && c.y.is_finite() && c.z.is_finite());
                    assert!(c.y <= 2.0 * spectral.white().y, "{c:?}");
                }
                assert!(t.scale().is_finite() && t.error_estimate().is_finite());
            }
            Err(e) => {
                tally.stored_refused += 1;
                assert!(e.to_string().len() < MAX_MESSAGE);
            }
        }
        // Sampled wavelengths and the film's estimate.
        let lambda = [0; 4].map(|_| value(&mut r, 360.0, 830.0));
        let pdf = [0; 4].map(|_| value(&mut r, 0.0, 1.0));
        if let Ok(l) = SampledWavelengths::new(lambda, pdf) {
            // Finite values (a random bit pattern may be NaN: not finite input).
            let v = [0; 4].map(|_| value(&mut r, -1e300, 1e300));
            let v = SampledSpectrum::new(v.map(|x| if x.is_finite() { x } else { f64::MAX }));
            let xyz = v.to_xyz(&l, &film);
            assert!(
                xyz.x.is_finite() && xyz.y.is_finite() && xyz.z.is_finite(),
                "{v:?} {l:?}"
            );
        }
        tally.wavelength_calls += 1;
    }
    println!("{cases} cases (seed {seed:#x}): {tally:?}");
    // Every surface was reached, accepted and refused.
    assert!(
        tally.tables_built > 0 && tally.tables_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.json_accepted > 0 && tally.json_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.stored_accepted > 0 && tally.stored_refused > 0,
        "{tally:?}"
    );
    assert!(tally.bsdf_calls > 0 && tally.relief_calls > 0, "{tally:?}");
}

#[test]
fn sweep() {
    sweep_with(QUICK_CASES, 0x29);
}

#[test]
#[ignore = "a hundred times the quick sweep: about six minutes in release (341 s on the loaded development machine)"]
fn sweep_long() {
    sweep_with(100 * QUICK_CASES, 0x2929_3333);
}
