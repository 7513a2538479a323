//! `ColorTable` against the reference `Spectral::xyz(.., Strategy::EXACT)`: lookups at random u,
//! means over intervals against a fine quadrature of the reference in u, and extreme inputs.
//!
//! Errors are measured as in docs/accuracy.md: relative to the grating's brightest diffracted
//! colour Y_b (the largest reference Y over the sampled u with d·|u| ≥ 360 nm, at least
//! 555/(N·∫ȳ)), or to the reference's own Y where that is brighter (order 0 near u = 0); and
//! in ΔE2000 at that exposure. Y_b here comes from the reference, not from the table.
//!
//! The CI tests take a few gratings and about 3000 reference colours (about 6 s in release); the
//! full sweep of the issue (9 N × 5 periods × 2 illuminants × 10⁴ u) and a representative
//! subset of it (20 gratings × 2000 u, about a minute) are `#[ignore]`d:
//! `cargo test --release --test color_table -- --ignored --nocapture sweep_subset`.

#[path = "support/fine_quadrature.rs"]
mod fine_quadrature;

#[path = "support/color_table_tolerance.rs"]
mod tol;

use diffraction::color::Xyz;
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{ColorTable, Grating};

/// The accuracy the measured bounds below are taken at (finer than the default, so that a
/// regression of the table's refinement shows).
const ACCURACY: f64 = 1e-4;

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

/// `count` values of u: half uniform on (−2, 2), half log-uniform in |u| over [10⁻¹², 2] with a
/// random sign (order 0's lobe and tail live at small |u|).
fn sample_u(count: usize, seed: u64) -> Vec<f64> {
    let mut r = Lcg(seed);
    (0..count)
        .map(|k| {
            let sign = if r.next() < 0.5 { -1.0 } else { 1.0 };
            let a = if k % 2 == 0 {
                2.0 * r.next()
            } else {
                2.0 * 10f64.powf(-12.0 * r.next())
            };
            sign * a
        })
        .collect()
}

/// The scale Y_b of the brightest diffracted colour, from reference values at `us`.
fn brightest(grating: &Grating, n: u32, us: &[f64], reference: &[Xyz]) -> f64 {
    let mut b = 555.0 / (n as f64 * diffraction::cie::cmf_areas()[1]);
    for (u, x) in us.iter().zip(reference) {
        if grating.period_nm() * u.abs() >= 360.0 {
            b = b.max(x.y);
        }
    }
    b
}

/// (relative error, ΔE2000) of `got` against `want` at exposure max(Y_b, want.y).
fn errors(got: Xyz, want: Xyz, bright: f64, white: Xyz) -> (f64, f64) {
    let k = 1.0 / bright.max(want.y);
    let rel = [got.x - want.x, got.y - want.y, got.z - want.z]
        .iter()
        .fold(0.0f64, |m, d| m.max(d.abs()))
        * k;
    let white = diffraction::color::WhitePoint::new(white).expect("an illuminant's white");
    let de = got
        .scale(k)
        .to_lab(white)
        .delta_e2000(want.scale(k).to_lab(white));
    (rel, de)
}

/// The worst lookup errors of one grating over `count` random u.
struct Worst {
    rel: f64,
    rel_u: f64,
    de: f64,
    de_u: f64,
}

fn lookup_errors(s: &Spectral, g: &Grating, n: u32, table: &ColorTable, us: &[f64]) -> Worst {
    let reference: Vec<Xyz> = us.iter().map(|&u| s.xyz(g, u, Strategy::EXACT)).collect();
    let bright = brightest(g, n, us, &reference);
    let mut w = Worst {
        rel: 0.0,
        rel_u: 0.0,
        de: 0.0,
        de_u: 0.0,
    };
    for (&u, &want) in us.iter().zip(&reference) {
        let (rel, de) = errors(table.lookup(u), want, bright, s.white());
        if rel > w.rel {
            (w.rel, w.rel_u) = (rel, u);
        }
        if de > w.de {
            (w.de, w.de_u) = (de, u);
        }
    }
    w
}

/// The mean of `Exact` over [a, b] (0 ≤ a < b) by 8-point Gauss-Legendre on pieces no wider than
/// (b − a)/16 nor than max(u/8, lobe/32), lobe = 360 nm/(N·d) the width of order 0's lobe.
fn reference_integral(s: &Spectral, g: &Grating, n: u32, a: f64, b: f64) -> [f64; 3] {
    use fine_quadrature::{W8 as W, X8 as X};
    let lobe = 360.0 / (n as f64 * g.period_nm());
    let mut acc = [0.0; 3];
    let mut x = a;
    while x < b {
        let step = (x / 8.0).max(lobe / 32.0).min((b - a) / 16.0);
        let e = (x + step).min(b);
        let (mid, half) = (0.5 * (x + e), 0.5 * (e - x));
        for (xi, wi) in X.iter().zip(W) {
            let c = s.xyz(g, mid + half * xi, Strategy::EXACT);
            acc[0] += wi * half * c.x;
            acc[1] += wi * half * c.y;
            acc[2] += wi * half * c.z;
        }
        x = e;
    }
    acc
}

/// The reference mean over [u0, u1] (u0 < u1), both sides of 0 by symmetry.
fn reference_mean(s: &Spectral, g: &Grating, n: u32, u0: f64, u1: f64) -> Xyz {
    let mut acc = [0.0; 3];
    let mut add = |a: f64, b: f64| {
        let i = reference_integral(s, g, n, a, b);
        for c in 0..3 {
            acc[c] += i[c];
        }
    };
    if u0 >= 0.0 {
        add(u0, u1);
    } else if u1 <= 0.0 {
        add(-u1, -u0);
    } else {
        add(0.0, -u0);
        add(0.0, u1);
    }
    let len = u1 - u0;
    Xyz::new(acc[0] / len, acc[1] / len, acc[2] / len)
}

/// Footprint intervals for a grating: through order 0's lobe, across 0, inside one order, and
/// pixel-sized ones at random places.
fn intervals(g: &Grating, n: u32, seed: u64) -> Vec<(f64, f64)> {
    let lobe = 360.0 / (n as f64 * g.period_nm());
    let first = 500.0 / g.period_nm();
    let mut r = Lcg(seed);
    let mut v = vec![
        (0.0, 3.0 * lobe),
        (-0.7 * lobe, 2.0 * lobe),
        (-1e-3, 2e-3),
        (0.9 * first, 1.1 * first),
        (1.1, 1.5),
    ];
    for _ in 0..3 {
        let c = 2.0 * r.next();
        let w = 10f64.powf(-4.0 * r.next()) * 0.05;
        v.push((c - w, c + w));
    }
    v
}

/// Errors of the footprint means of one grating, worst (relative, ΔE2000).
fn mean_errors(s: &Spectral, g: &Grating, n: u32, table: &ColorTable, seed: u64) -> (f64, f64) {
    let us = sample_u(100, seed);
    let reference: Vec<Xyz> = us.iter().map(|&u| s.xyz(g, u, Strategy::EXACT)).collect();
    let bright = brightest(g, n, &us, &reference);
    let mut worst = (0.0f64, 0.0f64);
    for (u0, u1) in intervals(g, n, seed) {
        let want = reference_mean(s, g, n, u0, u1);
        let (rel, de) = errors(table.mean(u0, u1), want, bright, s.white());
        worst = (worst.0.max(rel), worst.1.max(de));
    }
    worst
}

/// The CI subset: one grating per regime (few slits, the N ≈ 21 of a fitted CD, many slits, the
/// N → ∞ side), both illuminants.
const SUBSET: [(f64, u32, Illuminant); 4] = [
    (400.0, 5, Illuminant::E),
    (1600.0, 21, Illuminant::D65),
    (740.0, 1000, Illuminant::E),
    (400.0, 1_000_000, Illuminant::D65),
];

/// The subset's tables, built once for the tests that share them.
fn subset_tables() -> &'static [(Spectral, Grating, ColorTable)] {
    static TABLES: std::sync::OnceLock<Vec<(Spectral, Grating, ColorTable)>> =
        std::sync::OnceLock::new();
    TABLES.get_or_init(|| {
        SUBSET
            .iter()
            .map(|&(d, n, ill)| {
                let s = Spectral::new(ill);
                let g = Grating::new(d, d / 2.0, n).unwrap();
                let t = ColorTable::new(&s, &g, ACCURACY).unwrap();
                (s, g, t)
            })
            .collect()
    })
}

#[test]
fn lookups_match_exact_on_a_subset() {
    for (k, ((s, g, table), &(d, n, ill))) in subset_tables().iter().zip(&SUBSET).enumerate() {
        assert!(table.size_bytes() <= 512 * 1024);
        let w = lookup_errors(s, g, n, table, &sample_u(500, 17 + k as u64));
        println!(
            "d = {d}, N = {n}, {ill:?}: {} nodes, {} KiB, estimate {:.1e}; worst {:.2e} of Y_b at \
             u = {:.4e}, ΔE2000 {:.3} at u = {:.4e}",
            table.node_count(),
            table.size_bytes() / 1024,
            table.error_estimate(),
            w.rel,
            w.rel_u,
            w.de,
            w.de_u
        );
        assert!(w.rel <= tol::LOOKUP_REL, "d = {d}, N = {n}: {:e}", w.rel);
        assert!(
            w.de <= tol::LOOKUP_DE2000,
            "d = {d}, N = {n}: ΔE2000 {}",
            w.de
        );
        assert!(table.error_estimate() <= tol::ESTIMATE_CAPPED);
    }
}

#[test]
fn footprint_means_match_a_quadrature_of_exact() {
    for (k, ((s, g, table), &(d, n, ill))) in subset_tables().iter().zip(&SUBSET).enumerate() {
        let (rel, de) = mean_errors(s, g, n, table, 101 + k as u64);
        println!("d = {d}, N = {n}, {ill:?}: means worst {rel:.2e} of Y_b, ΔE2000 {de:.3}");
        assert!(rel <= tol::MEAN_REL, "d = {d}, N = {n}: {rel:e}");
        assert!(de <= tol::MEAN_DE2000, "d = {d}, N = {n}: ΔE2000 {de}");
    }
}

#[test]
fn order_zero_lobe_integral_is_right_when_lobe_is_tiny() {
    // N·d = 10⁹ nm: order 0's lobe is 3.6e-7 wide in u, its integral λ/(N·d)-ish, 10⁵ times
    // the mean of the diffracted colours over [0, 0.01]; the mean must carry it.
    let s = Spectral::new(Illuminant::D65);
    let (d, n) = (1000.0, 1_000_000);
    let g = Grating::new(d, d / 2.0, n).unwrap();
    let table = ColorTable::new(&s, &g, ACCURACY).unwrap();
    for &(a, b) in &[(0.0, 1e-2), (-2e-6, 5e-6), (0.0, 3.6e-7)] {
        let want = reference_mean(&s, &g, n, a, b);
        let got = table.mean(a, b);
        let rel = [got.x - want.x, got.y - want.y, got.z - want.z]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            / want.y;
        println!(
            "[{a:e}, {b:e}]: mean Y {:.4e}, relative error {rel:.2e}",
            want.y
        );
        assert!(rel <= tol::LOBE_MEAN_REL, "[{a}, {b}]: {rel:e}");
    }
}

#[test]
fn extreme_inputs_never_panic_nor_give_nan() {
    let s = Spectral::new(Illuminant::E);
    let g = Grating::new(1600.0, 800.0, 300).unwrap();
    let t = ColorTable::new(&s, &g, 1e-3).unwrap();
    let finite = |c: Xyz| c.x.is_finite() && c.y.is_finite() && c.z.is_finite();
    let nonneg = |c: Xyz| c.x >= 0.0 && c.y >= 0.0 && c.z >= 0.0;
    let black = Xyz::default();
    // Documented results.
    assert_eq!(t.lookup(0.0), s.white());
    assert_eq!(t.lookup(-0.0), s.white());
    assert_eq!(t.lookup(5e-324), s.white()); // subnormal: inside order 0's flat top
    assert_eq!(t.lookup(1e300), t.lookup(2.0));
    assert_eq!(t.lookup(-1e300), t.lookup(2.0));
    assert_eq!(t.lookup(f64::MAX), t.lookup(2.0));
    assert_eq!(t.lookup(f64::NAN), black);
    assert_eq!(t.lookup(f64::INFINITY), black);
    assert_eq!(t.lookup(f64::NEG_INFINITY), black);
    assert_eq!(t.mean(3.0, 5.0), t.lookup(2.0));
    assert_eq!(t.mean(-f64::MAX, f64::MAX), t.lookup(2.0));
    assert_eq!(t.mean(f64::NAN, 1.0), black);
    assert_eq!(t.mean(0.0, f64::INFINITY), black);
    assert_eq!(t.mean(0.0, 0.0), s.white());
    assert_eq!(t.mean(0.5, 0.5), t.lookup(0.5));
    assert_eq!(t.mean(0.7, 0.2), t.mean(0.2, 0.7));
    assert_eq!(t.mean(-0.7, -0.2), t.mean(0.2, 0.7));
    let specials = [
        0.0,
        -0.0,
        5e-324,
        -5e-324,
        f64::MIN_POSITIVE,
        1e-300,
        1e-12,
        0.1,
        1.0,
        1.999_999_999_999_999_8,
        2.0,
        2.000_000_000_000_000_4,
        3.0,
        1e300,
        f64::MAX,
        -f64::MAX,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for &a in &specials {
        let c = t.lookup(a);
        assert!(finite(c) && nonneg(c), "lookup({a}) = {c:?}");
        for &b in &specials {
            let m = t.mean(a, b);
            assert!(finite(m) && nonneg(m), "mean({a}, {b}) = {m:?}");
        }
    }
    // Zero width at subnormal scale and intervals straddling a node or 2.
    for &(a, b) in &[
        (0.0, 5e-324),
        (1.0 - 1e-15, 1.0 + 1e-15),
        (1.9, 2.1),
        (-2.5, 2.5),
    ] {
        let m = t.mean(a, b);
        assert!(finite(m) && nonneg(m), "mean({a}, {b}) = {m:?}");
    }
    // A mean over a range beyond 2 on one side: the colour at 2 stands for the excess.
    let half = t.mean(1.0, 3.0);
    let expected = (t.mean(1.0, 2.0).y + t.lookup(2.0).y) * 0.5;
    assert!((half.y - expected).abs() <= tol::MEAN_BEYOND_RANGE * expected.max(1e-300));
}

#[test]
fn bad_parameters_are_rejected() {
    let s = Spectral::new(Illuminant::E);
    let g = Grating::new(1600.0, 800.0, 30).unwrap();
    for a in [0.0, -1.0, 1e-7, 2.0, f64::NAN, f64::INFINITY] {
        let e = ColorTable::new(&s, &g, a).unwrap_err();
        assert_eq!(e.parameter(), "accuracy", "{a}");
    }
    let ideal = Grating::infinite(1600.0, 800.0).unwrap();
    assert_eq!(
        ColorTable::new(&s, &ideal, 1e-3).unwrap_err().parameter(),
        "slits"
    );
}

/// The sweep: every N × period × illuminant, 10⁴ random u each, lookups against
/// `Exact`; prints each grating's build figures and errors and the worst overall.
#[test]
#[ignore = "a quarter of an hour on two threads: 900 000 Exact colours"]
fn full_sweep_lookups_match_exact() {
    const SLITS: [u32; 9] = [1, 2, 5, 21, 30, 300, 1000, 3000, 1_000_000];
    const PERIODS: [f64; 5] = [400.0, 740.0, 1600.0, 10_000.0, 100_000.0];
    let mut cases = Vec::new();
    for ill in [Illuminant::E, Illuminant::D65] {
        for d in PERIODS {
            for n in SLITS {
                cases.push((d, n, ill));
            }
        }
    }
    let (rel, de, mem) = sweep(&cases, ACCURACY, 10_000);
    assert!(rel <= tol::LOOKUP_REL);
    assert!(de <= tol::LOOKUP_DE2000);
    assert!(mem <= 512 * 1024);
}

/// A representative fifth of the sweep: two (period, illuminant) pairs for every N, and two of
/// the worst gratings of the full sweep (dark order-0 tails at N = 300-3000).
const SWEEP_SUBSET: [(f64, u32, Illuminant); 20] = [
    (400.0, 1, Illuminant::E),
    (100_000.0, 1, Illuminant::D65),
    (740.0, 2, Illuminant::D65),
    (10_000.0, 2, Illuminant::E),
    (1600.0, 5, Illuminant::E),
    (100_000.0, 5, Illuminant::D65),
    (1600.0, 21, Illuminant::D65),
    (400.0, 21, Illuminant::E),
    (740.0, 30, Illuminant::E),
    (10_000.0, 30, Illuminant::D65),
    (400.0, 300, Illuminant::D65),
    (100_000.0, 300, Illuminant::E),
    (1600.0, 1000, Illuminant::D65),
    (740.0, 1000, Illuminant::E),
    (740.0, 3000, Illuminant::D65),
    (10_000.0, 3000, Illuminant::E),
    (400.0, 1_000_000, Illuminant::D65),
    (1600.0, 1_000_000, Illuminant::E),
    (740.0, 300, Illuminant::D65),
    (100_000.0, 3000, Illuminant::D65),
];

/// Builds every table of `cases` at `accuracy` on two threads and compares 'count' random u of
/// each with `Exact`; prints each grating's figures and returns the worst (relative, ΔE2000,
/// bytes).
fn sweep(cases: &[(f64, u32, Illuminant)], accuracy: f64, count: usize) -> (f64, f64, usize) {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&(d, n, ill)) = cases.get(k) else {
                    break;
                };
                let s = Spectral::new(ill);
                let g = Grating::new(d, d / 2.0, n).unwrap();
                let t0 = std::time::Instant::now();
                let table = ColorTable::new(&s, &g, accuracy).unwrap();
                let build = t0.elapsed().as_secs_f64();
                let w = lookup_errors(&s, &g, n, &table, &sample_u(count, 1000 + k as u64));
                println!(
                    "d = {d:>6}, N = {n:>7}, {ill:?}: build {:.3} s, {} nodes, {} KiB, \
                     estimate {:.1e}; worst {:.2e} of Y_b at u = {:.4e}, ΔE2000 {:.3} at u = {:.4e}",
                    build,
                    table.node_count(),
                    table.size_bytes() / 1024,
                    table.error_estimate(),
                    w.rel,
                    w.rel_u,
                    w.de,
                    w.de_u
                );
                results
                    .lock()
                    .unwrap()
                    .push((w.rel, w.de, table.size_bytes()));
            });
        }
    });
    let results = results.into_inner().unwrap();
    let worst_rel = results.iter().fold(0.0f64, |m, r| m.max(r.0));
    let worst_de = results.iter().fold(0.0f64, |m, r| m.max(r.1));
    let worst_mem = results.iter().map(|r| r.2).max().unwrap();
    println!(
        "worst: {worst_rel:.2e} of Y_b, ΔE2000 {worst_de:.3}, {} KiB",
        worst_mem / 1024
    );
    (worst_rel, worst_de, worst_mem)
}

/// The representative subset of the sweep at `ACCURACY`, 2000 random u per grating
/// (`COLOR_TABLE_ACCURACY` overrides the accuracy, to compare).
#[test]
#[ignore = "a few minutes on two threads: 40 000 Exact colours"]
fn sweep_subset_lookups_match_exact() {
    let accuracy = std::env::var("COLOR_TABLE_ACCURACY")
        .ok()
        .and_then(|a| a.parse().ok())
        .unwrap_or(ACCURACY);
    println!("accuracy {accuracy:e}");
    let (rel, de, mem) = sweep(&SWEEP_SUBSET, accuracy, 2000);
    assert!(rel <= tol::LOOKUP_REL);
    assert!(de <= tol::LOOKUP_DE2000);
    assert!(mem <= 512 * 1024);
}

#[test]
fn the_most_slits_build_within_the_memory_cap() {
    // N = 2³² − 1: order 0's lobe is 2e-10 wide in u at d = 400 nm, 38 octaves of blocks.
    let s = Spectral::new(Illuminant::E);
    let g = Grating::new(400.0, 200.0, u32::MAX).unwrap();
    let t = ColorTable::new(&s, &g, 1e-2).unwrap();
    assert!(t.size_bytes() <= 512 * 1024);
    assert_eq!(t.lookup(0.0), s.white());
    let m = t.mean(-1e-9, 1e-9);
    let want = reference_mean(&s, &g, u32::MAX, -1e-9, 1e-9);
    let rel = (m.y - want.y).abs() / want.y;
    println!("N = 2³² − 1: mean Y relative error {rel:.1e}");
    assert!(rel <= tol::MOST_SLITS_MEAN_REL, "{m:?} {want:?}");
}
