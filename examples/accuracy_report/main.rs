//! Error against run time of the spectral strategies of `diffraction::spectrum`: the data behind
//! `docs/accuracy.md`.
//!
//! For every strategy and parameter, every number of slits N and period d (slit width d/2) and a
//! grid of 64 phase projections u in (−2, 2) under D65, it computes the colour error against
//! `Strategy::EXACT` and the median time per evaluation, writes one row per (strategy, parameter,
//! N, period) to `docs/accuracy.csv` and prints a summary and the report's targets. It also
//! measures one-wavelength BRDF evaluation (f64, f32 and the naive formula) and the naive
//! formula's worst errors in the stiff cases.
//!
//! Errors are taken at the exposure that puts the grating's brightest diffraction colour at Y = 1
//! (the largest reference Y over the u with d·|u| ≥ 360 nm, floored at 555/(N·106.857), as in
//! `tests/spectral_reference.rs`): both XYZs are divided by that Y, converted to CIELAB relative
//! to the illuminant's white and compared with ΔE2000. `rel_xyz_max` is the largest channel
//! difference divided by the same Y. Times are single-threaded wall-clock medians over repeated
//! batches of the u grid; run a release build on a quiet machine:
//!
//! ```text
//! cargo run --release --example accuracy_report                 # the report (a few minutes)
//! cargo run --release --example accuracy_report -- --quick      # a smoke test (seconds; CSV to the temp dir)
//! cargo run --release --example accuracy_report -- --eval-only  # one wavelength, stiff cases
//! cargo run --release --example accuracy_report -- --budget-ms 100 --out /tmp/accuracy.csv
//! ```

use std::fmt::Write as _;
use std::fs;
use std::hint::black_box;
use std::time::{Duration, Instant};

use diffraction::color::{WhitePoint, Xyz};
use diffraction::kernel::{n_slit, naive};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{AguHill, ColorTable, DiffractionBrdf, Grating};
use glam::{DVec3, Vec3};

/// Periods d of the sweep, nm (DVD, CD, a coarse and a very coarse grating); w = d/2.
const PERIODS: [f64; 4] = [740.0, 1600.0, 10_000.0, 100_000.0];
/// Numbers of slits of the sweep.
const SLITS: [u32; 9] = [1, 2, 5, 30, 300, 1000, 3000, 30_000, 1_000_000];
/// The shortest wavelength of the band: d·|u| below it diffracts no order into the band.
const BAND_MIN_NM: f64 = 360.0;

/// What is evaluated at each u.
#[derive(Clone, Copy)]
enum Kind {
    /// `Spectral::xyz` with a strategy.
    Xyz(Strategy),
    /// `Spectral::paper_peaks`, the paper's own colours (not an integral).
    Paper,
    /// `Spectral::xyz_stratified` with this many strata (one estimate, fixed random numbers).
    Stratified(usize),
    /// `Spectral::xyz_hero` with this many wavelengths (one estimate, fixed random number).
    Hero(u32),
    /// `ColorTable::lookup` of a table built for the grating at this accuracy (the build's time
    /// and memory go into the row's `build_ms` and `table_bytes`).
    Table(f64),
}

/// One row family of the CSV: a strategy name, its parameter and what to evaluate.
struct Method {
    name: &'static str,
    param: String,
    kind: Kind,
}

fn methods() -> Vec<Method> {
    let mut v = Vec::new();
    let mut push = |name, param: String, kind| v.push(Method { name, param, kind });
    for k in [8, 16, 32, 64, 128, 471, 1000, 4000] {
        push(
            "uniform",
            k.to_string(),
            Kind::Xyz(Strategy::uniform(k).unwrap()),
        );
    }
    for k in [1, 2, 4, 8, 16, 59, 470] {
        push(
            "gauss",
            k.to_string(),
            Kind::Xyz(Strategy::gauss_legendre(k).unwrap()),
        );
    }
    push("peaks", "-".into(), Kind::Xyz(Strategy::PEAK_SEARCH));
    push(
        "peaks-refined",
        "-".into(),
        Kind::Xyz(Strategy::PEAK_SEARCH_REFINED),
    );
    push("paper", "-".into(), Kind::Paper);
    push("exact", "-".into(), Kind::Xyz(Strategy::EXACT));
    push("asymptotic", "-".into(), Kind::Xyz(Strategy::ASYMPTOTIC));
    for e in 1..=6 {
        let accuracy = 10f64.powi(-e);
        push(
            "auto",
            format!("1e-{e}"),
            Kind::Xyz(Strategy::auto(accuracy).unwrap()),
        );
    }
    push(
        "table",
        format!("{:e}", diffraction::spectrum::DEFAULT_ACCURACY),
        Kind::Table(diffraction::spectrum::DEFAULT_ACCURACY),
    );
    push("stratified", "8".into(), Kind::Stratified(8));
    push("hero", "4".into(), Kind::Hero(4));
    v
}

/// Command-line settings.
struct Settings {
    quick: bool,
    /// Only the one-wavelength and stiff-case sections (no sweep, no CSV).
    eval_only: bool,
    budget: Duration,
    out: String,
}

fn settings() -> Settings {
    let mut s = Settings {
        quick: false,
        eval_only: false,
        budget: Duration::from_millis(80),
        out: concat!(env!("CARGO_MANIFEST_DIR"), "/docs/accuracy.csv").to_string(),
    };
    let mut out_given = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--quick" => {
                s.quick = true;
                s.budget = Duration::from_millis(5);
            }
            "--eval-only" => s.eval_only = true,
            "--budget-ms" => {
                let ms: u64 = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .expect("--budget-ms takes a whole number of milliseconds");
                s.budget = Duration::from_millis(ms);
            }
            "--out" => {
                s.out = args.next().expect("--out takes a path");
                out_given = true;
            }
            "-h" | "--help" => {
                println!("accuracy_report [--quick] [--eval-only] [--budget-ms MS] [--out PATH]");
                std::process::exit(0);
            }
            other => panic!("unknown argument {other:?} (try --help)"),
        }
    }
    // A smoke test never replaces the committed report's data.
    if s.quick && !out_given {
        s.out = std::env::temp_dir()
            .join("accuracy_quick.csv")
            .to_string_lossy()
            .into_owned();
    }
    s
}

/// 64 phase projections in (−2, 2): 6 near the mirror direction (1e-8 to 1e-3: inside order 0's
/// lobe or its side lobes for large N·d, no order m ≠ 0 in the band), 14 spaced by a constant
/// factor over [0.002, 0.15] (where the first orders of the coarse gratings lie) and 44 evenly
/// spaced over (0.15, 1.98), with alternating signs (I is even in u; both signs go through the
/// same code). The quick grid keeps 4, 4 and 8 of them.
fn u_grid(quick: bool) -> Vec<f64> {
    let (near, log, even) = if quick { (4, 4, 8) } else { (6, 14, 44) };
    let mut v: Vec<f64> = (0..near)
        .map(|k| 10f64.powf(-8.0 + 5.0 * k as f64 / (near - 1) as f64))
        .collect();
    let ratio = (0.15f64 / 0.002).powf(1.0 / (log - 1) as f64);
    v.extend((0..log).map(|k| 0.002 * ratio.powi(k)));
    v.extend((0..even).map(|k| 0.15 + 1.83 * (k as f64 + 0.5) / even as f64));
    v.iter()
        .enumerate()
        .map(|(i, &u)| if i % 2 == 0 { u } else { -u })
        .collect()
}

mod eval;
#[path = "../../benches/support/naive.rs"]
mod naive_formula;
mod targets;
use eval::{print_eval, print_stiff};
use naive_formula::{naive_f32, naive_f64};
use targets::print_targets;
#[path = "../../benches/support/rng.rs"]
mod rng;
use rng::Rng;

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n == 0 {
        f64::NAN
    } else if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Median ns per call of `f` over `inputs`: batches of the whole input list, repeated so that
/// each timed sample lasts about `budget`/10, at least 3 samples and until `budget` is spent.
fn time_ns<T: Copy>(inputs: &[T], budget: Duration, mut f: impl FnMut(T) -> f64) -> f64 {
    let mut sink = 0.0;
    let mut batch = |reps: usize, sink: &mut f64| {
        let t = Instant::now();
        for _ in 0..reps {
            for &x in inputs {
                *sink += f(black_box(x));
            }
        }
        t.elapsed().as_secs_f64()
    };
    let one = batch(1, &mut sink).max(1e-9); // warm-up and calibration
    let target = budget.as_secs_f64() / 10.0;
    let reps = ((target / one).ceil() as usize).clamp(1, 100_000);
    let mut samples = Vec::new();
    let start = Instant::now();
    while samples.len() < 3 || (samples.len() < 50 && start.elapsed() < budget) {
        samples.push(batch(reps, &mut sink) / (reps * inputs.len()) as f64);
    }
    black_box(sink);
    median(&mut samples) * 1e9
}

/// The exposure scale Y_brightest of a grating from its reference colours on the u grid.
fn brightest(period: f64, n: u32, us: &[f64], refs: &[Xyz]) -> f64 {
    let floor = 555.0 / (n as f64 * diffraction::cie::cmf_areas()[1]);
    us.iter()
        .zip(refs)
        .filter(|(u, _)| period * u.abs() >= BAND_MIN_NM)
        .fold(floor, |m, (_, c)| m.max(c.y))
}

/// The largest reference Y over the diffracted directions (d·|u| ≥ 360 nm), without the floor.
fn brightest_unfloored(period: f64, us: &[f64], refs: &[Xyz]) -> f64 {
    us.iter()
        .zip(refs)
        .filter(|(u, _)| period * u.abs() >= BAND_MIN_NM)
        .fold(0.0, |m, (_, c)| m.max(c.y))
}

/// The x = d·|u|/λ below which order 0's half period reaches into the band (at 830 nm).
const ORDER0_HALF_PERIOD: f64 = 0.5;

/// Peak search cost over the u of the grid with d·|u|/830 nm ≥ ½ (only orders m ≠ 0 in the
/// band: O(orders)) and over the others (order 0's tail integrated by quadrature).
fn peaks_by_region(s: &Spectral, g: &Grating, us: &[f64], budget: Duration) -> [(f64, usize); 2] {
    let strategy = Strategy::PEAK_SEARCH;
    let split = |orders: bool| -> Vec<f64> {
        us.iter()
            .copied()
            .filter(|u| (g.period_nm() * u.abs() / 830.0 >= ORDER0_HALF_PERIOD) == orders)
            .collect()
    };
    [true, false].map(|orders| {
        let sub = split(orders);
        if sub.is_empty() {
            (f64::NAN, 0)
        } else {
            (
                time_ns(&sub, budget, |u| s.xyz(g, u, strategy).y),
                sub.len(),
            )
        }
    })
}

/// ΔE2000 and the relative XYZ error of `got` against `want`, both scaled by 1/`bright`.
///
/// Where the scaled reference is brighter than the white (Y > 1: the specular white near u = 0,
/// up to 10⁵ times the exposure for large N·d), both are divided further by the reference's Y,
/// so that they are compared at Y = 1 as a display's intensity clipping shows them; CIELAB at
/// L* in the thousands is outside its domain and turns chromatic differences of 10⁻⁴ into ΔE ≈ 2.
/// Returns (ΔE2000 with that clipping, ΔE2000 without it, relative XYZ error without it).
fn errors(got: Xyz, want: Xyz, bright: f64, white: Xyz) -> (f64, f64, f64) {
    let white = WhitePoint::new(white).expect("the white of a spectral integrator is positive");
    let k = 1.0 / bright;
    let (g, w) = (got.scale(k), want.scale(k));
    let de_raw = g.to_lab(white).delta_e2000(w.to_lab(white));
    let de = if w.y > 1.0 {
        let c = 1.0 / w.y;
        g.scale(c)
            .to_lab(white)
            .delta_e2000(w.scale(c).to_lab(white))
    } else {
        de_raw
    };
    let rel = [got.x - want.x, got.y - want.y, got.z - want.z]
        .iter()
        .fold(0.0f64, |m, d| m.max(d.abs()))
        * k;
    (de, de_raw, rel)
}

/// One CSV row.
struct Row {
    name: String,
    param: String,
    n: u32,
    period: f64,
    ns: f64,
    de_max: f64,
    de_median: f64,
    rel_max: f64,
    /// The u of the largest ΔE2000.
    worst_u: f64,
    /// The largest ΔE2000 without the clipping of overexposed colours (see `errors`).
    de_raw_max: f64,
    /// For `table`: the build's wall-clock time, ms (0 for the others).
    build_ms: f64,
    /// For `table`: `ColorTable::size_bytes` (0 for the others).
    table_bytes: usize,
}

/// Per-grating data kept for the summary.
struct GratingInfo {
    n: u32,
    period: f64,
    /// The exposure scale (floored).
    bright: f64,
    /// The largest reference Y over the diffracted directions, without the floor.
    bright_unfloored: f64,
    /// The paper mode's own exposure scale (floored the same way).
    paper_bright: f64,
    /// Peak search, ns per XYZ, over the u where only orders m ≠ 0 reach the band and over the
    /// rest (order 0's half period reaches into the band); how many u of the grid are in each.
    peaks_split: [(f64, usize); 2],
}

fn main() {
    let cfg = settings();
    if cfg.eval_only {
        print_eval(cfg.budget);
        print_stiff();
        return;
    }
    let spectral = Spectral::new(Illuminant::D65);
    let white = spectral.white();
    let us = u_grid(cfg.quick);
    let slits: Vec<u32> = if cfg.quick {
        vec![1, 30, 1000, 1_000_000]
    } else {
        SLITS.to_vec()
    };
    let methods = methods();
    // Fixed random numbers: per u for the errors, one set for the timing.
    let mut rng = Rng(0x5EED);
    let strata: Vec<Vec<f64>> = us
        .iter()
        .map(|_| (0..8).map(|_| rng.next_f64()).collect())
        .collect();
    let heroes: Vec<f64> = us.iter().map(|_| rng.next_f64()).collect();
    let started = Instant::now();

    let mut rows = Vec::new();
    let mut infos = Vec::new();
    let mut refs_all = Vec::new();
    for &period in &PERIODS {
        for &n in &slits {
            let g = Grating::new(period, period / 2.0, n).expect("valid grating");
            let refs: Vec<Xyz> = us
                .iter()
                .map(|&u| spectral.xyz(&g, u, Strategy::EXACT))
                .collect();
            let bright = brightest(period, n, &us, &refs);
            let bright_unfloored = brightest_unfloored(period, &us, &refs);
            let mut paper_bright = 0.0;
            for m in &methods {
                // The table of this grating, built once (its build timed once, single-threaded).
                let table = match m.kind {
                    Kind::Table(accuracy) => {
                        let t0 = Instant::now();
                        let t = ColorTable::new(&spectral, &g, accuracy).expect("valid accuracy");
                        Some((t0.elapsed().as_secs_f64() * 1e3, t))
                    }
                    _ => None,
                };
                let got: Vec<Xyz> = us
                    .iter()
                    .enumerate()
                    .map(|(i, &u)| match m.kind {
                        Kind::Xyz(s) => spectral.xyz(&g, u, s),
                        Kind::Paper => spectral.paper_peaks(&g, u),
                        Kind::Stratified(k) => spectral.xyz_stratified(&g, u, &strata[i][..k]),
                        Kind::Hero(k) => spectral.xyz_hero(&g, u, heroes[i], k),
                        Kind::Table(_) => table.as_ref().expect("built above").1.lookup(u),
                    })
                    .collect();
                let ns = match m.kind {
                    Kind::Xyz(s) => time_ns(&us, cfg.budget, |u| spectral.xyz(&g, u, s).y),
                    Kind::Paper => time_ns(&us, cfg.budget, |u| spectral.paper_peaks(&g, u).y),
                    Kind::Stratified(k) => time_ns(&us, cfg.budget, |u| {
                        spectral.xyz_stratified(&g, u, &strata[0][..k]).y
                    }),
                    Kind::Hero(k) => time_ns(&us, cfg.budget, |u| {
                        spectral.xyz_hero(&g, u, heroes[0], k).y
                    }),
                    Kind::Table(_) => {
                        let t = &table.as_ref().expect("built above").1;
                        time_ns(&us, cfg.budget, |u| t.lookup(u).y)
                    }
                };
                let (build_ms, table_bytes) = table
                    .as_ref()
                    .map_or((0.0, 0), |(ms, t)| (*ms, t.size_bytes()));
                let mut push = |name: &str, scale_got: f64| {
                    let mut des = Vec::with_capacity(us.len());
                    let (mut rel_max, mut de_raw_max, mut de_max, mut worst_u) =
                        (0.0f64, 0.0f64, 0.0f64, 0.0);
                    for ((c, r), &u) in got.iter().zip(&refs).zip(&us) {
                        // Scaling `got` by bright/scale_got puts its own brightest colour at Y = 1.
                        let (de, de_raw, rel) =
                            errors(c.scale(bright / scale_got), *r, bright, white);
                        des.push(de);
                        rel_max = rel_max.max(rel);
                        de_raw_max = de_raw_max.max(de_raw);
                        if de > de_max {
                            (de_max, worst_u) = (de, u);
                        }
                    }
                    rows.push(Row {
                        name: name.to_string(),
                        param: m.param.clone(),
                        n,
                        period,
                        ns,
                        de_max,
                        de_median: median(&mut des),
                        rel_max,
                        worst_u,
                        de_raw_max,
                        build_ms,
                        table_bytes,
                    });
                };
                push(m.name, bright);
                if m.name == "paper" {
                    // The paper's mode at its own exposure: its colours, not its brightness.
                    paper_bright = brightest(period, n, &us, &got);
                    push("paper-own-exposure", paper_bright);
                }
            }
            let peaks_split = peaks_by_region(&spectral, &g, &us, cfg.budget);
            infos.push(GratingInfo {
                n,
                period,
                bright,
                bright_unfloored,
                paper_bright,
                peaks_split,
            });
            refs_all.push(((n, period), refs));
            eprintln!(
                "d = {period:>6} nm, N = {n:>7}: done at {:.1} s",
                started.elapsed().as_secs_f64()
            );
        }
    }

    write_csv(&cfg.out, &rows);
    println!(
        "# Error against run time: D65, w = d/2, {} values of u",
        us.len()
    );
    println!("(wrote {} rows to {})", rows.len(), cfg.out);
    println!();
    exact_check(&spectral, &infos);
    print_tables(&rows, &slits);
    print_paper(&infos);
    print_targets(&rows, &slits, &infos);
    print_eval(cfg.budget);
    print_stiff();
    eprintln!("total {:.1} s", started.elapsed().as_secs_f64());
}

fn write_csv(path: &str, rows: &[Row]) {
    let mut s = String::from(
        "strategy,param,n,period_nm,ns_per_eval,de2000_max,de2000_median,rel_xyz_max,build_ms,\
         table_bytes\n",
    );
    for r in rows {
        writeln!(
            s,
            "{},{},{},{},{:.1},{:.4e},{:.4e},{:.4e},{:.1},{}",
            r.name,
            r.param,
            r.n,
            r.period,
            r.ns,
            r.de_max,
            r.de_median,
            r.rel_max,
            r.build_ms,
            r.table_bytes
        )
        .unwrap();
    }
    if let Some(dir) = std::path::Path::new(path).parent() {
        fs::create_dir_all(dir).expect("create the output directory");
    }
    fs::write(path, s).expect("write the CSV");
}

/// `Strategy::EXACT` against the independent reference of `python_ref/` on the rows of
/// `tests/data/spectral_xyz.csv` that this sweep covers (D65, w = d/2, its periods and N).
fn exact_check(spectral: &Spectral, infos: &[GratingInfo]) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spectral_xyz.csv");
    let Ok(text) = fs::read_to_string(path) else {
        println!("(tests/data/spectral_xyz.csv not found: no check of Exact)\n");
        return;
    };
    let white = spectral.white();
    let (mut count, mut worst_rel, mut worst_scaled, mut worst_de) = (0, 0.0f64, 0.0f64, 0.0f64);
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let p = |i: usize| f[i].parse::<f64>().expect("number");
        let (d, w, n, u) = (p(0), p(1), p(2) as u32, p(3));
        if f[4] != "D65" || w != d / 2.0 {
            continue;
        }
        let Some(info) = infos.iter().find(|i| i.period == d && i.n == n) else {
            continue;
        };
        let want = Xyz::new(p(5), p(6), p(7));
        let g = Grating::new(d, w, n).expect("valid grating");
        let got = spectral.xyz(&g, u, Strategy::EXACT);
        for (a, b) in [(got.x, want.x), (got.y, want.y), (got.z, want.z)] {
            if b.abs() > 1e-9 {
                worst_rel = worst_rel.max((a - b).abs() / b.abs());
            }
        }
        let (de, _, rel) = errors(got, want, info.bright, white);
        worst_scaled = worst_scaled.max(rel);
        worst_de = worst_de.max(de);
        count += 1;
    }
    println!("## Exact against python_ref (tests/data/spectral_xyz.csv)");
    println!(
        "{count} rows: worst relative error per channel {worst_rel:.1e}, worst error relative to \
         the brightest Y {worst_scaled:.1e}, worst ΔE2000 {worst_de:.1e}"
    );
    println!();
}

fn find<'a>(rows: &'a [Row], name: &str, param: &str, n: u32, period: f64) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.name == name && r.param == param && r.n == n && r.period == period)
}

fn label(r: &Row) -> String {
    if r.param == "-" {
        r.name.clone()
    } else {
        format!("{}:{}", r.name, r.param)
    }
}

fn print_tables(rows: &[Row], slits: &[u32]) {
    let mut names: Vec<(String, String)> = Vec::new();
    for r in rows {
        if !names.iter().any(|(a, b)| *a == r.name && *b == r.param) {
            names.push((r.name.clone(), r.param.clone()));
        }
    }
    for &period in &PERIODS {
        println!("## d = {period} nm: ΔE2000 max over u @ ns per evaluation");
        let mut head = format!("{:<20}", "strategy");
        for n in slits {
            write!(head, "{:>15}", format!("N={n}")).unwrap();
        }
        println!("{head}");
        for (name, param) in &names {
            let mut line = String::new();
            for &n in slits {
                let Some(r) = find(rows, name, param, n, period) else {
                    continue;
                };
                if line.is_empty() {
                    line = format!("{:<20}", label(r));
                }
                write!(line, "{:>15}", format!("{:.2e}@{:.0}", r.de_max, r.ns)).unwrap();
            }
            println!("{line}");
        }
        println!();
    }
}

fn print_paper(infos: &[GratingInfo]) {
    println!(
        "## Exposure (brightest diffraction Y, floored at 555/(N·106.857)) and the paper's peak \
         colours"
    );
    for i in infos {
        println!(
            "d = {:>6} nm, N = {:>7}: exposure Y {:.3e} (unfloored {:.3e}, {:.2} of it); paper's \
             mode {:.3e}, {:.3e} times the integral's",
            i.period,
            i.n,
            i.bright,
            i.bright_unfloored,
            i.bright_unfloored / i.bright,
            i.paper_bright,
            i.paper_bright / i.bright
        );
    }
    println!();
}
