//! Spectral integration against the independent reference of `python_ref/` (float64 lobe-by-lobe
//! quadrature in numpy, cross-checked with mpmath; `tests/data/spectral_xyz.csv`).

use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{Grating, Slits};
use std::collections::HashMap;
use std::fs;

struct Row {
    d: f64,
    w: f64,
    n: u32,
    u: f64,
    ill: Illuminant,
    xyz: [f64; 3],
}

fn rows() -> Vec<Row> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spectral_xyz.csv");
    let text = fs::read_to_string(path).expect("tests/data/spectral_xyz.csv");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("period_nm,slit_width_nm,n,u,illuminant,X,Y,Z")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            Row {
                d: f[0].parse().unwrap(),
                w: f[1].parse().unwrap(),
                n: f[2].parse().unwrap(),
                u: f[3].parse().unwrap(),
                ill: f[4].parse().unwrap(),
                xyz: [
                    f[5].parse().unwrap(),
                    f[6].parse().unwrap(),
                    f[7].parse().unwrap(),
                ],
            }
        })
        .collect()
}

fn xyz(s: &Spectral, r: &Row, strategy: Strategy) -> [f64; 3] {
    let g = Grating::with_slits(r.d, r.w, Slits::Finite(r.n)).unwrap();
    let c = s.xyz(&g, r.u, strategy);
    [c.x, c.y, c.z]
}

/// Largest reference Y over the diffracted directions (d·|u| ≥ 360 nm, where some order m ≠ 0
/// can reach the band) for each grating and illuminant: the exposure scale of the relative
/// error, which puts the grating's brightest diffraction colour at Y = 1. (The white order 0 at
/// u = 0 always has Y = 1 and would hide the colours' errors.) See docs/accuracy.md.
fn brightest(rows: &[Row]) -> HashMap<(u64, u64, u32, Illuminant), f64> {
    let mut m = HashMap::new();
    for r in rows {
        let k = (r.d.to_bits(), r.w.to_bits(), r.n, r.ill);
        // Floor: the Y of an ideal first-order peak (S = 1) at 555 nm under E, 555/(N·∫ȳ),
        // for gratings that diffract nothing (w = d puts every order on a zero of S).
        let e = m.entry(k).or_insert(555.0 / (r.n as f64 * 106.857));
        if r.d * r.u.abs() >= 360.0 {
            *e = e.max(r.xyz[1]);
        }
    }
    m
}

#[test]
fn exact_strategy_matches_reference_to_1e_6() {
    let rows = rows();
    assert!(rows.len() > 2000);
    let spectral = [Spectral::new(Illuminant::E), Spectral::new(Illuminant::D65)];
    let mut worst = 0.0f64;
    for r in &rows {
        let s = &spectral[(r.ill == Illuminant::D65) as usize];
        let got = xyz(s, r, Strategy::Exact);
        for (c, (&g, &want)) in got.iter().zip(&r.xyz).enumerate() {
            let err = (g - want).abs();
            let tol = 1e-6 * want.abs() + 1e-12;
            assert!(
                err <= tol,
                "d={} w={} N={} u={} {:?} channel {c}: got {} want {} (rel {:e})",
                r.d,
                r.w,
                r.n,
                r.u,
                r.ill,
                g,
                want,
                err / want.abs()
            );
            if want.abs() > 1e-9 {
                worst = worst.max(err / want.abs());
            }
        }
    }
    println!("exact: worst relative error {worst:e}");
}

/// Auto meets the accuracy it is asked for, relative to the brightest colour of the grating
/// (the exposure that puts it at Y = 1).
#[test]
fn auto_strategy_meets_requested_accuracy() {
    let rows = rows();
    let bright = brightest(&rows);
    let spectral = [Spectral::new(Illuminant::E), Spectral::new(Illuminant::D65)];
    for accuracy in [1e-2, 1e-3, 1e-4, 1e-6] {
        let mut worst = 0.0f64;
        for r in &rows {
            let s = &spectral[(r.ill == Illuminant::D65) as usize];
            let got = xyz(s, r, Strategy::Auto { accuracy });
            let scale = bright[&(r.d.to_bits(), r.w.to_bits(), r.n, r.ill)];
            for (c, (&g, &want)) in got.iter().zip(&r.xyz).enumerate() {
                let err = (g - want).abs() / scale;
                worst = worst.max(err);
                assert!(
                    err <= accuracy,
                    "auto:{accuracy:e} d={} w={} N={} u={} {:?} channel {c}: got {} want {} \
                     (error {err:e} of the brightest Y)",
                    r.d,
                    r.w,
                    r.n,
                    r.u,
                    r.ill,
                    g,
                    want
                );
            }
        }
        println!("auto:{accuracy:e}: worst error {worst:e} of the brightest Y");
    }
}

/// The error of each cheap strategy, per N, relative to the brightest colour (printed with
/// --nocapture; the bounds asserted are those `Spectral::choose` relies on): 8/N of the brightest
/// diffraction colour, plus, where order 0's half period reaches into the band
/// (d·|u|/830 nm < ½), 2e-3 of the colour itself (the peak search integrates that broad light
/// coarsely).
#[test]
fn peak_search_error_bounds_hold() {
    let rows = rows();
    let bright = brightest(&rows);
    let spectral = [Spectral::new(Illuminant::E), Spectral::new(Illuminant::D65)];
    let mut table: std::collections::BTreeMap<u32, [f64; 3]> = Default::default();
    for r in &rows {
        let s = &spectral[(r.ill == Illuminant::D65) as usize];
        let scale = bright[&(r.d.to_bits(), r.w.to_bits(), r.n, r.ill)];
        let order0 = r.d * r.u.abs() / 830.0 < 0.5;
        let size = r.xyz.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
        for (i, refine) in [false, true].into_iter().enumerate() {
            let got = xyz(s, r, Strategy::PeakSearch { refine });
            let err = (0..3)
                .map(|c| (got[c] - r.xyz[c]).abs())
                .fold(0.0, f64::max);
            let e = table.entry(r.n).or_default();
            if order0 {
                // Part of the error not covered by the orders' bound, relative to the colour.
                let excess = (err - 8.0 / r.n as f64 * scale).max(0.0) / size;
                e[2] = e[2].max(excess);
            } else {
                e[i] = e[i].max(err / scale);
            }
        }
    }
    for (n, [plain, refined, order0]) in &table {
        println!(
            "N = {n:>8}: peaks {plain:.2e}  peaks-refined {refined:.2e}  (order-0 region: {order0:.2e} of the colour)"
        );
        if *n >= 100 {
            assert!(
                *plain <= 8.0 / *n as f64,
                "plain peak search N={n}: {plain:e}"
            );
            assert!(
                *refined <= 8.0 / *n as f64,
                "refined peak search N={n}: {refined:e}"
            );
            assert!(*order0 <= 2e-3, "order-0 region N={n}: {order0:e}");
        }
    }
}

#[test]
#[ignore = "diagnostic listing"]
fn list_worst_peak_cases() {
    let rows = rows();
    let bright = brightest(&rows);
    let s = Spectral::new(Illuminant::E);
    for n in [30u32, 300, 3000, 30000, 1000000] {
        let mut v: Vec<(f64, String)> = vec![];
        for r in rows.iter().filter(|r| r.n == n && r.ill == Illuminant::E) {
            let scale = bright[&(r.d.to_bits(), r.w.to_bits(), r.n, r.ill)];
            for refine in [false, true] {
                let got = xyz(&s, r, Strategy::PeakSearch { refine });
                let err = (0..3)
                    .map(|c| (got[c] - r.xyz[c]).abs() / scale)
                    .fold(0.0, f64::max);
                v.push((
                    err,
                    format!(
                        "refine={refine} d={} w={} u={} got {:?} want {:?}",
                        r.d, r.w, r.u, got, r.xyz
                    ),
                ));
            }
        }
        v.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap());
        for (e, s) in v.iter().take(4) {
            println!("N={n} err {e:.2e} {s}");
        }
    }
}
