//! `grating-table`: an efficiency table of any grating, to a tolerance, with no Python.
//!
//! ```text
//! grating-table --lines-per-mm 1200 --profile sinusoid --depth 150 --metal Ag --out ag1200.json
//! grating-table --period 1600 --profile lamellar --depth 110 --duty 0.3125 --metal Al \
//!     --cover polycarbonate --tolerance 1e-2 --out cd.json
//! ```
//!
//! Writes the JSON table of `docs/efficiency_tables.md` (what `diffraction::relief::EfficiencyTable`
//! loads), built by `diffraction_fmm::table::build_table` until the interpolation error at
//! held-out rigorous solves is below `--tolerance`; the file records the achieved error. The file
//! is written to a temporary name beside `--out` and renamed: a failed or interrupted run never
//! leaves a partial file, nor replaces an existing one; an `--out` that cannot be written (a
//! directory, a missing or read-only folder) is refused before any solve. Exit codes: 0 written;
//! 1 the build failed (tolerance not reached within the budget, a solver failure); 2 bad input
//! (the message names the flag; a flag given twice is bad input too).

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use diffraction::relief::Metal;
use diffraction_fmm::table::{build_table, Progress, Rigorous, TableError, TableMeta, TableSpec};
use diffraction_fmm::{
    Cover, CoverIndex, CoverPasses, Extrapolation, Grating, Options, Profile, Solver,
};

const USAGE: &str =
    "usage: grating-table (--lines-per-mm N | --period NM) --profile lamellar|sinusoid|sawtooth
       [--depth NM] [--duty F] [--blaze DEG] (--metal Al|Ag|Au|Cu|Cr | --nk N,K)
       [--cover none|polycarbonate] [--cover-passes multiple|single] [--tolerance ABS]
       [--lambda MIN,MAX] [--sin-max S] [--abs-beta B0,B1,...] [--conical-version 3|2]
       [--max-plane-ratio R] [--max-solves N] [--threads N] [--name NAME]
       [--nodes-of TABLE] [--validation N] [--solve-tolerance ABS] [--max-harmonics N] [--description TEXT]
       [--keep-best] --out FILE

  --depth      ridge height (lamellar) or peak-to-valley depth (sinusoid), nm
  --duty       ridge width / period (lamellar), in (0, 1)
  --blaze      blaze angle (sawtooth), degrees in (0, 45); its depth is d sin(b) cos(b)
  --tolerance  largest interpolation error allowed, absolute per order (default 0.01)
  --lambda     wavelength range, nm (default 360,830)
  --sin-max    the table covers sin(theta_i) in [-S, S] (default 0.9999)
  --abs-beta   a conical table: its starting |beta| nodes, increasing in [0, 0.99999] (beta: the
               incident direction cosine along the grooves; default: a classical table). Written as
               a reduced conical table (version 3: planes with their own wavelengths, read at fixed
               (s', lambda/sqrt(1-beta^2))), planes added until neighbours' sqrt(1-beta^2) differ by
               at most --max-plane-ratio
  --conical-version  3 (default) or 2 (the tensor grid in (s', |beta|, lambda) of version 2)
  --max-plane-ratio  a reduced table's largest ratio of neighbouring planes' sqrt(1-beta^2) (default 2.5; lowered to keep every plane inside the metal's data)
  --max-solves bound on rigorous solves (default 20000)
  --nodes-of   solve at the (s, lambda) nodes of this classical table file instead: no refinement, no
               --tolerance; the held-out error at --validation random points is measured and stored
  --validation random held-out points (default 64)
  --solve-tolerance  each solve's convergence tolerance, absolute per order (default 1e-3)
  --max-harmonics    each solve's harmonic cap (default 801, at most 1601; a node not converged by then
               is kept at the cap's count and marked)
  --keep-best  if the tolerance is not reached, write the best table anyway (exit 1)";

/// Polycarbonate: Sultanova et al. 2009's Sellmeier fit ([`CoverIndex::POLYCARBONATE`], as
/// python_ref/fmm.py and the presets), and a CD's 1.2 mm.
const POLYCARBONATE_THICKNESS_NM: f64 = 1.2e6;

/// A bad flag: the message names it; exit code 2.
struct Bad(String);

fn bad(flag: &str, value: &str, why: &str) -> Bad {
    Bad(format!("{flag} {value:?}: {why}"))
}

#[derive(Debug)]
struct Args {
    period_nm: f64,
    profile: String,
    depth_nm: Option<f64>,
    duty: Option<f64>,
    blaze_deg: Option<f64>,
    metal: Metal,
    metal_text: String,
    cover: bool,
    passes: CoverPasses,
    spec: TableSpec,
    nodes_of: Option<PathBuf>,
    solve_tolerance: f64,
    max_harmonics: usize,
    description: Option<String>,
    name: Option<String>,
    keep_best: bool,
    out: PathBuf,
    command: String,
}

fn number(flag: &str, v: &str) -> Result<f64, Bad> {
    match v.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(bad(flag, v, "not a finite number")),
    }
}

fn positive(flag: &str, v: &str) -> Result<f64, Bad> {
    let x = number(flag, v)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(bad(flag, v, "must be > 0"))
    }
}

fn pair(flag: &str, v: &str) -> Result<(f64, f64), Bad> {
    let (a, b) = v
        .split_once(',')
        .ok_or_else(|| bad(flag, v, "expected two numbers separated by a comma"))?;
    Ok((number(flag, a)?, number(flag, b)?))
}

fn parse(argv: &[String]) -> Result<Args, Bad> {
    let mut lines_per_mm = None;
    let mut period = None;
    let mut profile = None;
    let mut depth = None;
    let mut duty = None;
    let mut blaze = None;
    let mut metal = None;
    let mut nk = None;
    let mut cover = "none".to_string();
    let mut passes = CoverPasses::Multiple;
    let mut spec = TableSpec::default();
    let mut name = None;
    let mut nodes_of = None;
    let mut tolerance_given = false;
    let mut solve_tolerance = diffraction_fmm::DEFAULT_TOLERANCE;
    let mut max_harmonics = diffraction_fmm::TABLE_MAX_HARMONICS;
    let mut description = None;
    let mut keep_best = false;
    let mut out = None;
    let mut seen: Vec<&str> = Vec::new();
    let mut i = 0;
    while i < argv.len() {
        let flag = argv[i].as_str();
        if flag == "--keep-best" {
            keep_best = true;
            i += 1;
            continue;
        }
        if flag == "--help" || flag == "-h" {
            return Err(Bad(String::new()));
        }
        // A flag given twice is ambiguous (which value was meant?): refused, never the last.
        if seen.contains(&flag) {
            return Err(Bad(format!("{flag}: given more than once")));
        }
        seen.push(flag);
        let v = argv
            .get(i + 1)
            .ok_or_else(|| Bad(format!("{flag}: missing value")))?
            .as_str();
        match flag {
            "--lines-per-mm" => lines_per_mm = Some(positive(flag, v)?),
            "--period" => period = Some(positive(flag, v)?),
            "--profile" => match v {
                "lamellar" | "sinusoid" | "sawtooth" => profile = Some(v.to_string()),
                _ => return Err(bad(flag, v, "expected lamellar, sinusoid or sawtooth")),
            },
            "--depth" => {
                let x = number(flag, v)?;
                if x < 0.0 {
                    return Err(bad(flag, v, "must be >= 0"));
                }
                depth = Some(x);
            }
            "--duty" => {
                let x = number(flag, v)?;
                if !(x > 0.0 && x < 1.0) {
                    return Err(bad(flag, v, "must be inside (0, 1)"));
                }
                duty = Some(x);
            }
            "--blaze" => {
                let x = number(flag, v)?;
                if !(x > 0.0 && x < 45.0) {
                    return Err(bad(flag, v, "must be inside (0, 45) degrees"));
                }
                blaze = Some(x);
            }
            "--metal" => {
                let m: Metal = v
                    .parse()
                    .map_err(|_| bad(flag, v, "expected Al, Ag, Au, Cu or Cr (or use --nk N,K)"))?;
                metal = Some((m, v.to_string()));
            }
            "--nk" => {
                let (n, k) = pair(flag, v)?;
                let m = Metal::custom(n, k)
                    .map_err(|e| bad(flag, v, &format!("needs 0 < n and 0 <= k ({e})")))?;
                nk = Some((m, format!("{n}+{k}i")));
            }
            "--cover" => match v {
                "none" | "polycarbonate" => cover = v.to_string(),
                _ => return Err(bad(flag, v, "expected none or polycarbonate")),
            },
            "--cover-passes" => {
                passes = match v {
                    "multiple" => CoverPasses::Multiple,
                    "single" => CoverPasses::Single,
                    _ => return Err(bad(flag, v, "expected multiple or single")),
                }
            }
            "--tolerance" => {
                let x = number(flag, v)?;
                if !(1e-6..=0.5).contains(&x) {
                    return Err(bad(flag, v, "must be in [1e-6, 0.5]"));
                }
                spec.tolerance = x;
                tolerance_given = true;
            }
            "--solve-tolerance" => {
                let x = number(flag, v)?;
                if !(1e-8..=0.1).contains(&x) {
                    return Err(bad(flag, v, "must be in [1e-8, 0.1]"));
                }
                solve_tolerance = x;
            }
            "--max-harmonics" => {
                max_harmonics = v
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (21..=diffraction_fmm::MAX_HARMONICS).contains(n))
                    .ok_or_else(|| bad(flag, v, "expected an integer in [21, 1601]"))?;
            }
            "--validation" => {
                spec.validation_points = v
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (1..=diffraction_fmm::table::MAX_VALIDATION_POINTS).contains(n))
                    .ok_or_else(|| bad(flag, v, "expected an integer in [1, 100000]"))?;
            }
            "--nodes-of" => nodes_of = Some(PathBuf::from(v)),
            "--description" => description = Some(v.to_string()),
            "--lambda" => {
                let (a, b) = pair(flag, v)?;
                if !(a >= 100.0 && b <= 20_000.0 && b > a) {
                    return Err(bad(
                        flag,
                        v,
                        "expected MIN,MAX with 100 <= MIN < MAX <= 20000 nm",
                    ));
                }
                spec.lambda_range_nm = (a, b);
            }
            "--sin-max" => {
                let x = number(flag, v)?;
                if !(x > 0.0 && x <= 0.99999) {
                    return Err(bad(flag, v, "must be in (0, 0.99999]"));
                }
                spec.sin_theta_range = (-x, x);
            }
            "--abs-beta" => {
                let mut nodes = Vec::new();
                for part in v.split(',') {
                    let b = number(flag, part)?;
                    if !(0.0..=0.99999).contains(&b) || nodes.last().is_some_and(|&l| b <= l) {
                        return Err(bad(
                            flag,
                            v,
                            "expected at least two increasing values in [0, 0.99999]",
                        ));
                    }
                    nodes.push(b);
                }
                if nodes.len() < 2 {
                    return Err(bad(
                        flag,
                        v,
                        "expected at least two increasing values in [0, 0.99999]",
                    ));
                }
                spec.abs_beta = nodes;
            }
            "--conical-version" => {
                spec.reduced = match v {
                    "3" => true,
                    "2" => false,
                    _ => return Err(bad(flag, v, "expected 3 or 2")),
                }
            }
            "--max-plane-ratio" => {
                let x = number(flag, v)?;
                if !(1.01..=10.0).contains(&x) {
                    return Err(bad(flag, v, "must be in [1.01, 10]"));
                }
                spec.max_plane_ratio = x;
            }
            "--max-solves" => {
                spec.max_solves = v
                    .parse::<usize>()
                    .ok()
                    .filter(|&n| n > 0)
                    .ok_or_else(|| bad(flag, v, "expected a positive integer"))?;
            }
            "--threads" => {
                spec.threads = v
                    .parse::<usize>()
                    .ok()
                    .filter(|&n| (1..=256).contains(&n))
                    .ok_or_else(|| bad(flag, v, "expected an integer in [1, 256]"))?;
            }
            "--name" => name = Some(v.to_string()),
            "--out" => out = Some(PathBuf::from(v)),
            _ => return Err(Bad(format!("{flag}: unknown flag"))),
        }
        i += 2;
    }
    let period_nm = match (lines_per_mm, period) {
        (Some(n), None) => 1e6 / n,
        (None, Some(d)) => d,
        (Some(_), Some(_)) => {
            return Err(Bad(
                "--lines-per-mm and --period: give one of them, not both".into(),
            ))
        }
        (None, None) => return Err(Bad("--period (or --lines-per-mm): required".into())),
    };
    let profile = profile.ok_or_else(|| Bad("--profile: required".into()))?;
    let (metal, metal_text) = match (metal, nk) {
        (Some(m), None) | (None, Some(m)) => m,
        (Some(_), Some(_)) => {
            return Err(Bad("--metal and --nk: give one of them, not both".into()))
        }
        (None, None) => return Err(Bad("--metal (or --nk): required".into())),
    };
    match profile.as_str() {
        "lamellar" => {
            if depth.is_none() {
                return Err(Bad("--depth: required for a lamellar profile".into()));
            }
            if duty.is_none() {
                return Err(Bad("--duty: required for a lamellar profile".into()));
            }
            if blaze.is_some() {
                return Err(Bad("--blaze: only for a sawtooth profile".into()));
            }
        }
        "sinusoid" => {
            if depth.is_none() {
                return Err(Bad("--depth: required for a sinusoid".into()));
            }
            if duty.is_some() || blaze.is_some() {
                return Err(Bad("--duty and --blaze: not for a sinusoid".into()));
            }
        }
        _ => {
            if blaze.is_none() {
                return Err(Bad("--blaze: required for a sawtooth profile".into()));
            }
            if depth.is_some() {
                return Err(Bad(
                    "--depth: a sawtooth's depth follows from --blaze (d sin b cos b)".into(),
                ));
            }
            if duty.is_some() {
                return Err(Bad("--duty: only for a lamellar profile".into()));
            }
        }
    }
    let out = out.ok_or_else(|| Bad("--out: required".into()))?;
    if nodes_of.is_some() && (tolerance_given || !spec.abs_beta.is_empty()) {
        return Err(Bad(
            "--nodes-of: takes the table's own grid; not with --tolerance or --abs-beta".into(),
        ));
    }
    Ok(Args {
        period_nm,
        profile,
        depth_nm: depth,
        duty,
        blaze_deg: blaze,
        metal,
        metal_text,
        cover: cover == "polycarbonate",
        passes,
        spec,
        nodes_of,
        solve_tolerance,
        max_harmonics,
        description,
        name,
        keep_best,
        out,
        command: String::new(),
    })
}

fn grating(a: &Args) -> Grating {
    let profile = match a.profile.as_str() {
        "lamellar" => Profile::Lamellar {
            duty: a.duty.unwrap_or(0.5),
            depth_nm: a.depth_nm.unwrap_or(0.0),
        },
        "sinusoid" => Profile::Sinusoid {
            depth_nm: a.depth_nm.unwrap_or(0.0),
        },
        _ => Profile::Sawtooth {
            blaze: a.blaze_deg.unwrap_or(0.0).to_radians(),
        },
    };
    Grating {
        period_nm: a.period_nm,
        profile,
        metal: a.metal,
        cover: a.cover.then_some(Cover {
            index: CoverIndex::POLYCARBONATE,
            thickness_nm: POLYCARBONATE_THICKNESS_NM,
        }),
    }
}

fn meta(a: &Args, g: &Grating, solver: &Solver) -> TableMeta {
    let depth = g.depth_nm();
    let name = a.name.clone().unwrap_or_else(|| {
        a.out
            .file_stem()
            .map_or("table".into(), |s| s.to_string_lossy().into_owned())
    });
    let mut description = format!(
        "{} grating, d = {:.6} nm ({:.6} lines/mm), depth {:.6} nm",
        a.profile,
        a.period_nm,
        1e6 / a.period_nm,
        depth
    );
    if let Some(f) = a.duty {
        let _ = write!(description, ", duty {f}");
    }
    if let Some(b) = a.blaze_deg {
        let _ = write!(description, ", blaze {b} deg");
    }
    let _ = write!(description, ", {}", a.metal_text);
    if a.cover {
        description.push_str(", under polycarbonate");
    }
    if let Some(d) = &a.description {
        description.clone_from(d);
    }
    let o = solver.options();
    TableMeta {
        name,
        description,
        profile: a.profile.clone(),
        period_nm: a.period_nm,
        depth_nm: depth,
        duty: a.duty,
        blaze_deg: a.blaze_deg,
        metal: a.metal_text.clone(),
        cover: if a.cover { "polycarbonate" } else { "none" }.into(),
        symmetric: a.profile != "sawtooth",
        method: "diffraction-fmm: Fourier modal method, Li's factorisation rules, S-matrix recursion".into(),
        harmonics: None,
        convergence: format!(
            "every solve: the harmonic count raised x1.5 until two successive steps agree to {:e} \
             ({}), cap {}",
            o.tolerance,
            match o.extrapolation {
                Extrapolation::Richardson =>
                    "TM, and conical solves, extrapolated in 1/N (Richardson): three successive extrapolations agree",
                Extrapolation::Off => "no extrapolation",
            },
            o.max_harmonics
        ),
        cover_model: a.cover.then(|| {
            format!(
                "flat polycarbonate cover (Sultanova 2009 Sellmeier: n^2 = 1 + 1.4182 l^2/(l^2 - 0.021304), l in um), \
                 {} mm, incoherent, {:?} passes",
                POLYCARBONATE_THICKNESS_NM / 1e6,
                o.cover_passes
            )
        }),
        command: a.command.clone(),
    }
}

/// Largest table file `--nodes-of` reads.
const MAX_NODES_FILE_BYTES: u64 = 16 << 20;

/// The (s, λ) nodes of a classical table file: a regular file (checked before it is opened, so
/// a FIFO or a device is refused without blocking) of at most [`MAX_NODES_FILE_BYTES`], read
/// by the library's bounded JSON reader.
fn read_nodes(path: &PathBuf) -> Result<(Vec<f64>, Vec<f64>), String> {
    use std::io::Read;
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    let max = MAX_NODES_FILE_BYTES;
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(max + 1).read_to_end(&mut bytes))
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > max {
        return Err(format!("more than {max} bytes"));
    }
    let text = String::from_utf8(bytes).map_err(|_| "not UTF-8".to_string())?;
    let table: diffraction::relief::EfficiencyTable =
        serde_json::from_str(&text).map_err(|e| e.to_string())?;
    if table.is_conical() {
        return Err("a conical table (version 2 or 3): --nodes-of takes a classical one".into());
    }
    Ok((table.sin_theta_i().collect(), table.lambda_nm().collect()))
}

/// Checks, before any solve, that `out` can be written the way [`write_atomic`] writes it: not
/// a directory, and a file can be created (and is removed again) beside it. An existing `out` is
/// not touched.
fn check_out(out: &std::path::Path) -> Result<(), String> {
    if out.as_os_str().is_empty() {
        return Err("empty path".into());
    }
    if out.is_dir() {
        return Err("is a directory".into());
    }
    let mut probe = out.as_os_str().to_owned();
    probe.push(format!(".tmp-{}", std::process::id()));
    let probe = PathBuf::from(probe);
    std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
        .map_err(|e| format!("cannot write beside it: {e}"))?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

/// Writes `text` to a temporary file beside `out`, then renames it over `out`.
fn write_atomic(out: &PathBuf, text: &str) -> std::io::Result<()> {
    let mut tmp = out.clone().into_os_string();
    tmp.push(format!(".tmp-{}", std::process::id()));
    let tmp = PathBuf::from(tmp);
    let result = std::fs::write(&tmp, text).and_then(|()| std::fs::rename(&tmp, out));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn progress_line(p: &Progress, tolerance: f64, last: &mut Instant) {
    if last.elapsed().as_secs_f64() < 0.25 && p.done != p.planned {
        return;
    }
    *last = Instant::now();
    let eta = p.seconds_per_solve * (p.planned - p.done) as f64;
    let err = if p.error.is_nan() {
        "first grid".to_string()
    } else {
        format!("held-out error {:.2e} (tolerance {tolerance:.0e})", p.error)
    };
    eprint!(
        "\rround {}: {}/{} solves, {} in all, {:.2} s a solve, ETA {:.0} s for this round; {err}   ",
        p.round, p.done, p.planned, p.total_solves, p.seconds_per_solve, eta
    );
    let _ = std::io::stderr().flush();
}

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let mut args = match parse(&argv) {
        Ok(a) => a,
        Err(Bad(msg)) if msg.is_empty() => {
            println!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(Bad(msg)) => {
            eprintln!("grating-table: error: {msg}\n\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    args.command = std::iter::once("grating-table".to_string())
        .chain(argv.iter().cloned())
        .collect::<Vec<_>>()
        .join(" ");
    if let Err(msg) = check_out(&args.out) {
        eprintln!("grating-table: error: --out {}: {msg}", args.out.display());
        return ExitCode::from(2);
    }
    let g = grating(&args);
    if let Err(e) = g.validate() {
        eprintln!(
            "grating-table: error: {e} (from --period/--lines-per-mm, --depth, --duty, --blaze)"
        );
        return ExitCode::from(2);
    }
    if let Some(path) = &args.nodes_of {
        match read_nodes(path) {
            Ok(nodes) => args.spec.fixed_nodes = Some(nodes),
            Err(msg) => {
                eprintln!("grating-table: error: --nodes-of {}: {msg}", path.display());
                return ExitCode::from(2);
            }
        }
    }
    let options = Options {
        cover_passes: args.passes,
        tolerance: args.solve_tolerance,
        max_harmonics: args.max_harmonics,
        ..Options::default()
    };
    let solver = match Solver::new(options) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("grating-table: error: {e}");
            return ExitCode::from(2);
        }
    };
    let meta = meta(&args, &g, &solver);
    let rigorous = Rigorous {
        grating: g,
        solver,
        accept_unconverged: if args.nodes_of.is_some() {
            args.solve_tolerance
        } else {
            0.25 * args.spec.tolerance
        },
    };
    let t0 = Instant::now();
    let mut last = Instant::now();
    let tol = args.spec.tolerance;
    let result = build_table(&rigorous, &args.spec, &mut |p| {
        progress_line(p, tol, &mut last)
    });
    eprintln!();
    let (built, code) = match result {
        Ok(b) => (b, ExitCode::SUCCESS),
        Err(TableError::Invalid(e)) => {
            eprintln!("grating-table: error: {e}");
            return ExitCode::from(2);
        }
        Err(TableError::Budget {
            best: Some(best), ..
        }) if args.keep_best => {
            eprintln!(
                "grating-table: tolerance {tol:e} not reached; writing the best table (held-out error {:.3e})",
                best.report.achieved_abs_error
            );
            (*best, ExitCode::from(1))
        }
        Err(e) => {
            eprintln!(
                "grating-table: failed: {e}; {} not written",
                args.out.display()
            );
            return ExitCode::from(1);
        }
    };
    let text = built.to_json(&meta);
    if let Err(e) = write_atomic(&args.out, &text) {
        eprintln!("grating-table: --out {}: {e}", args.out.display());
        return ExitCode::from(1);
    }
    let r = &built.report;
    let rows = if built.plane_lambda_nm.is_empty() {
        format!("{}", built.lambda_nm.len())
    } else {
        let r: Vec<String> = built
            .plane_lambda_nm
            .iter()
            .map(|p| p.len().to_string())
            .collect();
        format!("({})", r.join("+"))
    };
    eprintln!(
        "wrote {}: {} x {} x {} nodes (s x |beta| x lambda), orders {}..={}, {} solves in {:.1} s; \
         held-out error max {:.3e}, p95 {:.3e} over {} points (tolerance {:e}); \
         {} unconverged solves (largest last change {:.2e})",
        args.out.display(),
        built.sin_theta_i.len(),
        built.abs_beta.len().max(1),
        rows,
        built.order_min,
        built.order_max,
        r.solves,
        t0.elapsed().as_secs_f64(),
        r.achieved_abs_error,
        r.abs_error_p95,
        r.held_out_points,
        r.tolerance,
        r.unconverged.0,
        r.unconverged.1
    );
    code
}
