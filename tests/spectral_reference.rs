//! Spectral integration against the independent reference of `python_ref/` (float64 lobe-by-lobe
//! quadrature in numpy, cross-checked with mpmath; `tests/data/spectral_xyz.csv`): each
//! strategy's stated bound (see `Strategy`) on the grating path (`Spectral::xyz`, and
//! `Spectral::xyz_response` on `AguHill`'s grating form), over every row; and, as regression
//! measurements, the generic rules (`Spectral::xyz_brdf`, `GenericStrategy`) on `AguHill`, a
//! model outside their contract (its F_N side lobes are narrow features it does not report).

#[path = "support/generic_models.rs"]
mod generic_models;
#[path = "support/tolerance.rs"]
mod tolerance;

use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
use diffraction::{AguHill, Grating, Slits, SpectralResponse};
use generic_models::retro;
use std::collections::{BTreeMap, HashMap};
use std::fs;
use tolerance as tol;

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

/// A way of computing a row's colour: a strategy on the grating path, or a generic rule.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Path {
    /// `Spectral::xyz` on the grating.
    Grating(Strategy),
    /// `Spectral::xyz_brdf` on the grating's `AguHill` model at the retro-reflecting pair
    /// with phase projection u.
    Generic(GenericStrategy),
}

fn grating(r: &Row) -> Grating {
    Grating::with_slits(r.d, r.w, Slits::Finite(r.n)).unwrap()
}

fn xyz(s: &Spectral, r: &Row, path: Path) -> [f64; 3] {
    let g = grating(r);
    let c = match path {
        Path::Grating(strategy) => s.xyz(&g, r.u, strategy),
        Path::Generic(strategy) => {
            let (wo, wi) = retro(r.u);
            s.xyz_brdf(&AguHill::new(g), wo, wi, strategy)
        }
    };
    [c.x, c.y, c.z]
}

fn spectral_for(r: &Row) -> Spectral {
    Spectral::new(r.ill)
}

/// Largest reference Y over the diffracted directions (d·|u| ≥ 360 nm, where some order m ≠ 0
/// can reach the band) for each grating and illuminant: the exposure scale of the relative
/// error, which puts the grating's brightest diffraction colour at Y = 1. (The white order 0 at
/// u = 0 always has Y = 1 and would hide the colours' errors.) See docs/accuracy.md.
fn brightest(rows: &[Row]) -> HashMap<(u64, u64, u32, Illuminant), f64> {
    let ybar_area = diffraction::cie::cmf_areas()[1]; // only to set a floor
    let mut m = HashMap::new();
    for r in rows {
        let k = (r.d.to_bits(), r.w.to_bits(), r.n, r.ill);
        // Floor: the Y of an ideal first-order peak (S = 1) at 555 nm under E, 555/(N·∫ȳ),
        // for gratings that diffract nothing (w = d puts every order on a zero of S).
        let e = m.entry(k).or_insert(555.0 / (r.n as f64 * ybar_area));
        if r.d * r.u.abs() >= 360.0 {
            *e = e.max(r.xyz[1]);
        }
    }
    m
}

fn scale(bright: &HashMap<(u64, u64, u32, Illuminant), f64>, r: &Row) -> f64 {
    bright[&(r.d.to_bits(), r.w.to_bits(), r.n, r.ill)]
}

/// Whether order 0's half period (x < ½) reaches into the band: d·|u|/830 nm < ½.
fn order0_in_band(r: &Row) -> bool {
    r.d * r.u.abs() / 830.0 < 0.5
}

fn describe(r: &Row) -> String {
    format!("d={} w={} N={} u={} {:?}", r.d, r.w, r.n, r.u, r.ill)
}

/// `AguHill` says it is its grating's intensity, so its grating form on `xyz_response` is
/// `xyz`, bit for bit, for every strategy: the grating path's bounds below hold for it.
#[test]
fn agu_hill_takes_the_grating_path() {
    let rows = rows();
    let strategies = [
        Strategy::EXACT,
        Strategy::PEAK_SEARCH,
        Strategy::PEAK_SEARCH_REFINED,
        Strategy::ASYMPTOTIC,
        Strategy::auto(1e-3).unwrap(),
        Strategy::gauss_legendre(4).unwrap(),
        Strategy::uniform(7).unwrap(),
    ];
    for r in rows.iter().step_by(7) {
        let s = spectral_for(r);
        let (wo, wi) = retro(r.u);
        let response = AguHill::new(grating(r)).grating_response(wo, wi).unwrap();
        for st in strategies {
            let want = s.xyz(&grating(r), r.u, st);
            assert_eq!(s.xyz_response(&response, st), want, "{st} {}", describe(r));
        }
    }
}

/// The worst relative error of `Exact` against the colour itself, over every component of
/// every row, with the place where it occurs.
fn exact_worst(rows: &[Row]) -> (f64, String) {
    let mut worst = (0.0f64, String::new());
    for r in rows {
        let got = xyz(&spectral_for(r), r, Path::Grating(Strategy::EXACT));
        for (c, (&g, &want)) in got.iter().zip(&r.xyz).enumerate() {
            let rel = (g - want).abs() / want.abs();
            if rel > worst.0 {
                worst = (
                    rel,
                    format!("{} channel {c}: got {g} want {want}", describe(r)),
                );
            }
        }
    }
    worst
}

/// `Exact` on the grating path: within its documented 10⁻⁶ of the colour itself, and within
/// the measured worst error with its margin, component by component.
#[test]
fn exact_meets_its_bound_on_the_grating_path() {
    let rows = rows();
    assert!(rows.len() > 2000);
    let (worst, at) = exact_worst(&rows);
    println!("exact, grating path: worst relative error {worst:.3e} at {at}");
    assert!(worst <= tol::EXACT_DOCUMENTED, "{worst:e} at {at}");
    assert!(worst <= tol::EXACT_GRATING, "{worst:e} at {at}");
}

/// The generic `WINDOWS` rule on `AguHill` (outside its contract: F_N's side lobes are not
/// reported peaks) against the same reference: the measured error, relative to the brightest
/// order, as a regression bound.
#[test]
fn windows_on_a_grating_error_is_as_measured() {
    let rows = rows();
    let bright = brightest(&rows);
    let worst = auto_worst(&rows, &bright, Path::Generic(GenericStrategy::WINDOWS));
    println!(
        "windows on AguHill: worst {:.3e} of the brightest at {}",
        worst.0, worst.1
    );
    assert!(
        worst.0 <= tol::WINDOWS_ON_GRATING_OF_BRIGHTEST,
        "{:e} at {}",
        worst.0,
        worst.1
    );
}

/// Per N: the worst error of the peak search away from order 0, times N, relative to the
/// brightest order; and in order 0's region the worst excess over the documented orders' term
/// 8/N, relative to the colour itself.
fn peak_search_table(rows: &[Row], path: Path) -> BTreeMap<u32, (f64, f64)> {
    let bright = brightest(rows);
    let mut table: BTreeMap<u32, (f64, f64)> = BTreeMap::new();
    for r in rows {
        let got = xyz(&spectral_for(r), r, path);
        let err = (0..3)
            .map(|c| (got[c] - r.xyz[c]).abs())
            .fold(0.0, f64::max);
        let scale = scale(&bright, r);
        let n = r.n as f64;
        let e = table.entry(r.n).or_default();
        if order0_in_band(r) {
            let size = r.xyz.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
            e.1 = e.1.max((err - 8.0 / n * scale).max(0.0) / size);
        } else {
            e.0 = e.0.max(err * n / scale);
        }
    }
    for (n, (orders, order0)) in &table {
        println!(
            "{path:?} N = {n:>7}: error {orders:.3}/N of the brightest, \
             order-0 region {order0:.2e} of the colour beyond 8/N"
        );
    }
    table
}

/// `PeakSearch` (both modes) on the grating path: within 8/N of the brightest order's colour
/// plus, where order 0's half period reaches into the band, 2·10⁻³ of the colour itself (the
/// documented bound, for every N of the grid), and within the measured error per N with its
/// margin.
#[test]
fn peak_search_meets_its_bound_on_the_grating_path() {
    let rows = rows();
    for (strategy, column) in [
        (Strategy::PEAK_SEARCH, 1),
        (Strategy::PEAK_SEARCH_REFINED, 2),
    ] {
        let refine = column == 2;
        let table = peak_search_table(&rows, Path::Grating(strategy));
        assert_eq!(table.len(), tol::PEAK_SEARCH_GRATING.len());
        for (&(n, plain, refined), (&m, &(orders, order0))) in
            tol::PEAK_SEARCH_GRATING.iter().zip(&table)
        {
            assert_eq!(n, m);
            let measured = if column == 1 { plain } else { refined };
            assert!(orders <= 8.0, "refine={refine} N={n}: {orders}/N > 8/N");
            assert!(
                orders <= measured * tol::PEAK_SEARCH_MARGIN,
                "refine={refine} N={n}: {orders}/N, measured {measured}/N"
            );
            assert!(
                order0 <= tol::PEAK_SEARCH_ORDER0,
                "refine={refine} N={n}: {order0:e}"
            );
        }
    }
}

/// The generic `PEAK_SEARCH` on `AguHill` (outside its contract): the measured error per N away
/// from order 0, as a regression bound.
#[test]
fn generic_peak_search_on_a_grating_error_is_as_measured() {
    let rows = rows();
    let table = peak_search_table(&rows, Path::Generic(GenericStrategy::PEAK_SEARCH));
    assert_eq!(table.len(), tol::PEAK_SEARCH_GENERIC.len());
    for (&(n, measured), (&m, &(orders, _))) in tol::PEAK_SEARCH_GENERIC.iter().zip(&table) {
        assert_eq!(n, m);
        assert!(
            orders <= measured * tol::PEAK_SEARCH_MARGIN,
            "N={n}: {orders}/N, measured {measured}/N"
        );
    }
}

/// The worst error relative to the brightest order's colour.
fn auto_worst(
    rows: &[Row],
    bright: &HashMap<(u64, u64, u32, Illuminant), f64>,
    path: Path,
) -> (f64, String) {
    let mut worst = (0.0f64, String::new());
    for r in rows {
        let got = xyz(&spectral_for(r), r, path);
        let scale = scale(bright, r);
        for (c, (&g, &want)) in got.iter().zip(&r.xyz).enumerate() {
            let err = (g - want).abs() / scale;
            if err > worst.0 {
                worst = (
                    err,
                    format!("{} channel {c}: got {g} want {want}", describe(r)),
                );
            }
        }
    }
    worst
}

/// `Auto { accuracy }` on the grating path: within `accuracy` of the brightest order's colour
/// (the documented bound), and within the measured worst error with its margin.
#[test]
fn auto_meets_its_accuracy_on_the_grating_path() {
    let rows = rows();
    let bright = brightest(&rows);
    for (accuracy, measured) in tol::AUTO_GRATING {
        let auto = Strategy::auto(accuracy).unwrap();
        let (worst, at) = auto_worst(&rows, &bright, Path::Grating(auto));
        println!("auto:{accuracy:e}, grating path: worst {worst:.3e} of the brightest at {at}");
        assert!(worst <= accuracy, "auto:{accuracy:e}: {worst:e} at {at}");
        assert!(
            worst <= measured * tol::AUTO_MARGIN,
            "auto:{accuracy:e}: {worst:e} at {at}"
        );
    }
}
