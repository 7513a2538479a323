//! Work limits that multiply: scenes where every value is within its documented limit but the
//! product is not. Each is refused with its estimate before any scan, table or pixel is
//! computed, or its estimate is within the budget; the quick sweep renders the cheap ones, the
//! long one (`--ignored`) every accepted one, printing measured time against the estimate.

use std::path::Path;

use crate::budget::{self, Estimate};
use crate::footprint::Filter;
use crate::model::Paper;
use crate::run::Renderer;
use crate::scene::{self, Scene};
use crate::Raytracer;

fn parse(src: &str) -> Scene<Paper> {
    scene::parse::<Paper>(src, "sweep.toml", "sweep", Path::new(".")).unwrap()
}

/// A 16 × 12 camera looking up at nothing, `lights` point lights, and `gratings` objects far
/// below it, object i with `material(i)`.
fn looking_away(gratings: usize, material: &dyn Fn(usize) -> String) -> String {
    let mut s = String::from(
        "[render]\nwidth = 16\nheight = 12\nspp = 1\n[camera]\nposition = [0.0, 0.0, 0.0]\n\
         look_at = [0.0, 1.0, 0.01]\n[[lights]]\nposition = [0.0, -5.0, 0.0]\n",
    );
    for i in 0..gratings {
        s += &format!(
            "[[objects]]\nshape = \"quad\"\ntranslate = [{}.0, -10.0, 0.0]\n[objects.material]\n{}\n",
            i,
            material(i)
        );
    }
    s
}

/// The render parts of [`looking_away`]: every camera ray tests every object and hits none.
fn away_ns(objects: usize) -> f64 {
    192.0 * budget::SAMPLE_NS + 192.0 * objects as f64 * budget::RAY_TEST_NS
}

/// 256 Stam gratings of depth 10⁴ nm: 256 exposure scans, estimated 2.8 s each (up to 6 s measured). One is accepted.
#[cfg(feature = "stam")]
#[test]
fn deep_stam_exposure_scans_are_bounded() {
    let stam = |i: usize| {
        format!(
            "type = \"grating\"\nmodel = \"stam-sine\"\ndepth_nm = 1e4\nperiod_nm = {}",
            38888 + i
        )
    };
    let scans = 256.0 * 4001.0 * 7e5;
    let e = crate::run::run(
        &Raytracer::default(),
        &opts(&write("stam", &looking_away(256, &stam))),
    );
    assert_eq!(
        e,
        Err(format!(
            "stam: an estimated {} s of work on one core, above the budget of 120 s \
             (--budget; tools/render/common/budget.rs); most of it, {} s, is 256 exposure scans of 4001 colours \
             each: reduce the number of distinct gratings or their models' parameters",
            budget::short((scans + away_ns(256)) * 1e-9),
            budget::short(scans * 1e-9)
        ))
    );
    let one = Raytracer::default().estimate(&parse(&looking_away(1, &stam)), 1);
    let expected = (4001.0 * 7e5 + away_ns(1)) * 1e-9;
    assert!((one.seconds() / expected - 1.0).abs() < 1e-12, "{one:?}");
    assert_eq!(one.check("one", budget::BUDGET_S), Ok(()));
}

fn write(name: &str, src: &str) -> std::path::PathBuf {
    let dir = crate::common_tests::scratch(&format!("sweep-{name}"));
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, src).unwrap();
    file
}

fn opts(file: &Path) -> crate::cli::Options {
    crate::cli::Options {
        scenes: vec![file.display().to_string()],
        out: Some(file.with_extension("png")),
        quiet: true,
        ..Default::default()
    }
}

/// 256 distinct gratings with `--filter footprint`: 256 table builds, counted (3.8 s) and
/// within the budget; with the paper's filter off, none.
#[test]
fn colour_tables_are_counted() {
    let grating = |i: usize| format!("type = \"grating\"\nperiod_nm = {}", 1000 + i);
    let scene = parse(&looking_away(256, &grating));
    let tables = |est: &Estimate| {
        est.parts
            .iter()
            .find(|p| p.what.ends_with("colour tables"))
            .map(|p| (p.what.clone(), p.ns))
    };
    let with = Raytracer {
        filter: Filter::Footprint,
    }
    .estimate(&scene, 1);
    assert_eq!(
        tables(&with),
        Some(("256 colour tables".into(), 256.0 * budget::TABLE_NS))
    );
    assert_eq!(with.check("tables", budget::BUDGET_S), Ok(()));
    // The whole: 256 exposure scans (one per distinct grating) and the camera rays, which see
    // nothing.
    let scans: f64 = scene
        .materials
        .iter()
        .map(|m| {
            let g = m.grating.as_ref().unwrap();
            let scan = crate::model::exposure_strategy(g.strategy);
            4001.0 * budget::colour_ns(&scene.spectral, g.model.integrand(), scan)
        })
        .sum();
    let expected = away_ns(256) + 256.0 * budget::TABLE_NS + scans;
    assert!(
        (with.seconds() * 1e9 / expected - 1.0).abs() < 1e-12,
        "{with:?}"
    );
    assert_eq!(tables(&Raytracer::default().estimate(&scene, 1)), None);
}

/// The quick sweep: objects × shadow rays × bounces × strategies × sizes, each refused with
/// the part that dominates named, or (when cheap) rendered.
#[test]
fn the_quick_sweep_refuses_or_renders() {
    let mut refused = 0;
    for (objects, samples, depth) in scenes() {
        let base = parse(&scene_of(objects, samples, depth, "peaks", 16));
        for (strategy, width) in variants() {
            let est = Raytracer::default().estimate(&variant(&base, strategy, width), 1);
            match est.check("case", budget::BUDGET_S) {
                Err(e) => {
                    refused += 1;
                    assert!(est.seconds() > budget::BUDGET_S, "{e}");
                    assert!(e.contains(": reduce --width/--height, --spp"), "{e}");
                }
                Ok(()) if est.seconds() < 0.05 => {
                    let file = write("quick", &scene_of(objects, samples, depth, strategy, width));
                    assert_eq!(crate::run::run(&Raytracer::default(), &opts(&file)), Ok(()));
                    assert!(image::open(file.with_extension("png")).is_ok());
                }
                Ok(()) => {}
            }
        }
    }
    assert!(refused >= 4, "{refused}");
}

/// The sweep's scenes: objects, light samples (of each of 4 lights), mirror bounces.
fn scenes() -> Vec<(usize, u32, u32)> {
    let mut v = Vec::new();
    for objects in [1, 100, 10_000] {
        for samples in [1, 1024] {
            for depth in [0, 64] {
                v.push((objects, samples, depth));
            }
        }
    }
    v
}

/// Each scene's variants: the strategy of the grating, the picture's width (4:3).
fn variants() -> [(&'static str, u32); 4] {
    [("peaks", 16), ("peaks", 320), ("exact", 16), ("exact", 320)]
}

fn variant(base: &Scene<Paper>, strategy: &str, width: u32) -> Scene<Paper> {
    let mut s = base.clone();
    s.set_strategy(strategy.parse().unwrap());
    (s.settings.width, s.settings.height) = (width, width * 3 / 4);
    s
}

/// A grating floor under a mirror ceiling, `objects` − 2 small cubes on the floor, four
/// spherical lights of `samples` samples.
fn scene_of(objects: usize, samples: u32, depth: u32, strategy: &str, width: u32) -> String {
    let mut s = format!(
        "[render]\nwidth = {width}\nheight = {}\nspp = 1\nmax_depth = {depth}\nstrategy = \"{strategy}\"\n\
         [camera]\nposition = [0.0, 1.0, 4.0]\nlook_at = [0.0, 0.5, 0.0]\n\
         [[objects]]\nshape = \"quad\"\nscale = 40.0\n[objects.material]\ntype = \"grating\"\n\
         period_nm = 1600\nslits = 1000000000\n\
         [[objects]]\nshape = \"quad\"\nscale = 40.0\ntranslate = [0.0, 3.0, 0.0]\n\
         [objects.material]\ntype = \"mirror\"\nmirror = 1.0\n",
        width * 3 / 4
    );
    for i in 0..4 {
        s += &format!(
            "[[lights]]\nposition = [{}.0, 2.0, 1.0]\nradius = 0.1\nsamples = {samples}\n",
            i - 2
        );
    }
    for i in 2..objects {
        s += &format!(
            "[[objects]]\nshape = \"cube\"\nscale = 0.01\ntranslate = [{}, 0.005, -5.0]\n\
             material = {{ type = \"diffuse\" }}\n",
            (i % 1000) as f64 * 0.02 - 10.0
        );
    }
    s
}

/// The longest estimate the long sweep renders, s of one core.
const LONG_SWEEP_S: f64 = 120.0;

/// The long sweep: renders every case estimated under [`LONG_SWEEP_S`] and prints its measured
/// time against its estimate (the estimate is meant as an upper bound: 1.5-5 times the shipped
/// scenes' time).
#[test]
#[ignore = "renders every accepted case of the sweep (minutes)"]
fn the_long_sweep_renders_every_accepted_case() {
    for ((objects, samples, depth), (strategy, size)) in scenes()
        .into_iter()
        .flat_map(|s| variants().map(move |v| (s, v)))
    {
        let src = scene_of(objects, samples, depth, strategy, size);
        let est = Raytracer::default().estimate(&parse(&src), 1);
        if est.seconds() > LONG_SWEEP_S {
            println!("{objects} objects, {samples} samples, depth {depth}, {strategy}, {size} px: not rendered, estimate {} s", budget::short(est.seconds()));
            continue;
        }
        let file = write("long", &src);
        let (t, cpu) = (std::time::Instant::now(), cpu_seconds());
        assert_eq!(crate::run::run(&Raytracer::default(), &opts(&file)), Ok(()));
        println!(
            "{objects} objects, {samples} samples, depth {depth}, {strategy}, {size} px: {:.2} s \
             wall, {:.2} s of CPU, estimate {} s of one core",
            t.elapsed().as_secs_f64(),
            cpu_seconds() - cpu,
            budget::short(est.seconds())
        );
    }
}

/// The CPU time of this process so far (all threads; Linux, else 0), s.
fn cpu_seconds() -> f64 {
    /// The kernel's clock ticks per second (USER_HZ).
    const TICKS: f64 = 100.0;
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let fields: Vec<&str> = stat
        .rsplit(')')
        .next()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let tick = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    (tick(11) + tick(12)) / TICKS
}

/// The ray tracer's rows of `tools/render/budget_calibration.csv`: each estimate within 5× of
/// its measured CPU time (the measurement is the file's; nothing is timed here).
#[test]
fn the_estimates_stay_within_five_times_the_measured_time() {
    let checked = crate::calibration_tests::check(
        "raytrace",
        |args| match crate::cli::parse::<crate::Args>(args).unwrap() {
            crate::cli::Command::Render(o, a) => (Raytracer { filter: a.filter }, o),
            crate::cli::Command::Help => panic!("{args:?}"),
        },
        // The baselines' scene needs the feature `stam`.
        |row| !cfg!(feature = "stam") && row.args.iter().any(|a| a.ends_with("compare.toml")),
    );
    assert_eq!(checked.len(), if cfg!(feature = "stam") { 12 } else { 11 });
}

/// The reproducer `work_limits_multiply` (tools/render/tests/data): 2³² camera samples (4096 ×
/// 4096 pixels × 256), four lights of 1024 samples, 64 bounces between two grating mirrors of
/// d = 10⁵ nm with the `exact` colour, each value within its limit. Refused before any scan or
/// pixel, the estimate in closed form: every ray bounces 64 times, every hit is on a grating
/// and sees the four lights; nothing is written.
#[test]
fn work_limits_that_multiply_are_refused_with_the_estimate() {
    let src = include_str!("../tests/data/work_limits_multiply.toml");
    let dir = crate::common_tests::scratch("work_limits_multiply");
    let file = dir.join("work_limits_multiply.toml");
    std::fs::write(&file, src).unwrap();
    let e = crate::run::run(&Raytracer::default(), &opts(&file)).unwrap_err();
    let samples = 2f64.powi(32);
    let hits = samples * 65.0;
    let shadow = hits * 4096.0;
    let tests = (samples * 65.0 + shadow) * 2.0;
    let scene = parse(src);
    let scan =
        crate::model::exposure_strategy(scene.materials[0].grating.as_ref().unwrap().strategy);
    let integrand = scene.materials[0]
        .grating
        .as_ref()
        .unwrap()
        .model
        .integrand();
    let colours = hits * 4.0;
    let colour_ns = 3e5 + 45.0 * 1e5;
    let total = samples * budget::SAMPLE_NS
        + hits * budget::HIT_NS
        + shadow * budget::SHADOW_NS
        + tests * budget::RAY_TEST_NS
        + 4001.0 * budget::colour_ns(&scene.spectral, integrand, scan)
        + colours * colour_ns;
    assert_eq!(
        e,
        format!(
            "work_limits_multiply: an estimated {} s of work on one core, above the budget of \
             120 s (--budget; tools/render/common/budget.rs); most of it, {} s, is {} colour \
             evaluations (strategy exact of objects[0].material): reduce --width/--height, \
             --spp, --frames, the number of lights, or a cheaper --strategy or material strategy",
            budget::short(total * 1e-9),
            budget::short(colours * colour_ns * 1e-9),
            budget::count(colours)
        )
    );
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}
