//! The measurement behind `ColorTable::DEFAULT_ACCURACY`: tables of a sweep of gratings built at
//! that accuracy, looked up at random u against `Strategy::EXACT`, in ΔE2000 at the exposure of
//! the grating's brightest diffracted colour Y_b (as `tests/color_table.rs`: the largest
//! reference Y over the sampled u with d·|u| ≥ 360 nm, at least 555/(N·∫ȳ); the reference's own
//! Y where brighter). The sweep is `#[ignore]`d (about ten minutes on one thread):
//! `cargo test --release --test color_table_default -- --ignored --nocapture`
//! (`COLOR_TABLE_ACCURACY` overrides the accuracy, to compare others).

#[path = "support/tolerance.rs"]
mod tol;

use diffraction::color::{WhitePoint, Xyz};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{ColorTable, Grating};

/// Deterministic uniform numbers in [0, 1) (PCG-style LCG, top 53 bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` values of |u|: half uniform on (0, 2), half log-uniform over [2·10⁻¹², 2] (order 0's
/// lobe and tail live at small |u|).
fn sample_u(count: usize, seed: u64) -> Vec<f64> {
    let mut r = Lcg(seed);
    (0..count)
        .map(|k| {
            if k % 2 == 0 {
                2.0 * r.next()
            } else {
                2.0 * 10f64.powf(-12.0 * r.next())
            }
        })
        .collect()
}

/// The worst lookup ΔE2000 of a table of (d, N) under `ill` at `accuracy`, over `count` u.
fn worst_lookup(d: f64, n: u32, ill: Illuminant, accuracy: f64, count: usize) -> (f64, f64) {
    let s = Spectral::new(ill);
    let white = WhitePoint::new(s.white()).expect("an illuminant's white");
    let g = Grating::new(d, d / 2.0, n).expect("valid grating");
    let us = sample_u(count, (d as u64) * 31 + u64::from(n));
    let reference: Vec<Xyz> = us.iter().map(|&u| s.xyz(&g, u, Strategy::EXACT)).collect();
    let mut bright = 555.0 / (n as f64 * diffraction::cie::cmf_areas()[1]);
    for (u, x) in us.iter().zip(&reference) {
        if d * u >= 360.0 {
            bright = bright.max(x.y);
        }
    }
    let table = ColorTable::new(&s, &g, accuracy).expect("valid accuracy");
    let mut worst = (0.0f64, 0.0);
    for (&u, &want) in us.iter().zip(&reference) {
        let k = 1.0 / bright.max(want.y);
        let de = table
            .lookup(u)
            .scale(k)
            .to_lab(white)
            .delta_e2000(want.scale(k).to_lab(white));
        if de > worst.0 {
            worst = (de, u);
        }
    }
    worst
}

#[test]
#[ignore = "about ten minutes: 165 000 Exact colours"]
fn default_accuracy_keeps_lookups_within_the_target() {
    let accuracy = std::env::var("COLOR_TABLE_ACCURACY")
        .ok()
        .and_then(|a| a.parse().ok())
        .unwrap_or(ColorTable::DEFAULT_ACCURACY);
    const SLITS: [u32; 11] = [1, 2, 3, 4, 5, 21, 30, 300, 1000, 3000, 1_000_000];
    const PERIODS: [f64; 5] = [400.0, 740.0, 1600.0, 10_000.0, 100_000.0];
    let mut worst = (0.0f64, String::new());
    for ill in [Illuminant::D65, Illuminant::E] {
        for d in PERIODS {
            for n in SLITS {
                let (de, u) = worst_lookup(d, n, ill, accuracy, 1500);
                println!("d = {d:>6}, N = {n:>7}, {ill:?}: ΔE2000 {de:.4} at u = {u:.4e}");
                if de > worst.0 {
                    worst = (de, format!("d = {d}, N = {n}, {ill:?}, u = {u}"));
                }
            }
        }
    }
    println!(
        "accuracy {accuracy:e}: worst ΔE2000 {:.4} ({})",
        worst.0, worst.1
    );
    assert!(worst.0 <= tol::TABLE_DEFAULT_DE2000, "{worst:?}");
}

/// The CD-like grating and the coarse two-slit one of the sweep, a few hundred u each: a quick
/// check of the default in CI.
#[test]
fn default_accuracy_on_two_gratings() {
    for (d, n) in [(1600.0, 1000u32), (100_000.0, 2)] {
        let (de, u) = worst_lookup(d, n, Illuminant::D65, ColorTable::DEFAULT_ACCURACY, 300);
        println!("d = {d}, N = {n}: ΔE2000 {de:.4} at u = {u:.4e}");
        assert!(
            de <= tol::TABLE_DEFAULT_DE2000,
            "d = {d}, N = {n}: {de} at u = {u}"
        );
    }
}
