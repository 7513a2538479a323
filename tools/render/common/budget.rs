//! The work budget of a run: its work is estimated before anything is prepared or rendered,
//! and a run above [`BUDGET_S`] is refused with the estimate and the options or scene fields
//! that reduce it.
//!
//! Each limit of [`crate::limits`] bounds one factor; this bounds their product. The estimate
//! counts, per scene:
//!
//! - **ray-object tests** (every ray is tested against every object: there is no acceleration
//!   structure): camera samples × (rays + shadow rays per sample) × objects;
//! - **colour evaluations** (a grating's spectral colour toward one light or light sample) and,
//!   for the path tracer, **BSDF evaluations** per path vertex;
//! - **load-time work**: each distinct grating's exposure scan (4001 colours) and, with
//!   `--filter`, each colour table's build.
//!
//! The rays, hits, shadow rays, grating hits and the lights that light them (in front and not
//! occluded: the renderers compute no colour for another) per camera sample come from a
//! [`Pilot`]: the scene's own rays through a grid of pixel centres (at most [`PILOT_TESTS`]
//! ray-object tests, so the estimate itself is cheap), following mirrors for the Whitted
//! renderers. Each count is weighted by its cost on one core of the development machine (2-core
//! x86-64 shared with other builds: the constants below are from what was measured there, most
//! of them upper bounds, with the colour costs over d = 400-10⁵ nm and N = 10-2³²), and the
//! total is compared with
//! [`BUDGET_S`] seconds of one core (or `--budget`'s). The estimate is deterministic (the same
//! run, the same number). The path integrator's counts come from its own paths instead
//! (`pathtrace/path.rs`'s `pilot`: Russian roulette and the sky end most of them at the first
//! vertex). Against measured CPU time it is 0.64-2.08 times that of every shipped scene on both
//! renderers and of the two reproducers of `tools/render/tests/data` (docs/work_budget.md, made
//! by `tools/render/calibrate.sh`; the tests check every row stays within 5×).

use diffraction::spectrum::{GenericStrategyKind, Spectral, StrategyKind};
use diffraction::{Grating, Slits};

use crate::camera::{Camera, CameraRays};
use crate::colour::Colour;
use crate::geometry::{nearest, occluded, Ray, SHADOW_REACH};
use crate::scene::{Physics, Scene};

/// The budget of one scene's run by default: seconds of work on one core (two minutes, a minute
/// of wall time on the two cores of the development machine; `--budget` sets another). Every
/// shipped scene at its defaults takes under 4 % of it, but for `cd_preset` and `cd_rainbow`
/// by `--integrator whitted` (13 %, most of it their colour table's build); the estimate is within 5× of the measured CPU time
/// (docs/work_budget.md), so a refused run would take at least 24 s of one core.
pub const BUDGET_S: f64 = 120.0;

/// One ray-object test, ns (measured 7 ns in a scene of 200 objects and 8-9 ns in scenes of
/// 10⁴, most tests misses; half again for a margin).
pub const RAY_TEST_NS: f64 = 15.0;
/// One camera sample beyond its rays: the camera ray, the film, ns.
pub const SAMPLE_NS: f64 = 100.0;
/// One surface hit beyond its ray-object tests: the material (a wood texture's noise), the
/// shading frame, the illumination model or the BSDF's lobes, ns (fitted: the shipped scenes
/// take 0.2-0.4 µs per hit).
pub const HIT_NS: f64 = 300.0;
/// One shadow ray or light sample beyond its ray-object tests: sampling the light and shading
/// toward it, ns (fitted: `cd_area_light`'s Whitted renderer takes 120 ns).
pub const SHADOW_NS: f64 = 100.0;
/// One evaluation of the grating BSDF by the path tracer at a vertex (sample, f4 and pdf4:
/// measured 516 ns), ns.
pub const BSDF_NS: f64 = 600.0;
/// One evaluation of a grating BSDF with tabulated efficiencies (a preset or a table file) by
/// the path tracer at a vertex (`cd_preset`: about 1 µs at four wavelengths, from
/// `benches/bsdf.rs`'s 129 ns an `f` and 272 ns a `sample` + `pdf`; twice that), ns.
pub const BSDF_TABLE_NS: f64 = 2e3;
/// The same for a conical table (the presets' default reading, `Preset::conical_table`, or a
/// conical table file), ns: `benches/bsdf.rs` puts its `f` at 3.4-3.7× and its `sample` +
/// `pdf` at 4.7-5.0× the classical table's, so 2.5× the classical figure.
pub const BSDF_CONICAL_NS: f64 = 5e3;
/// One colour table build at accuracy 10⁻³, ns (measured 4-8 ms a table in scenes of 16 and
/// 256 gratings over d = 400 nm-99 µm and N = 10-10⁹; twice that for a margin).
pub const TABLE_NS: f64 = 1.5e7;
/// One diffraction colour from a colour table over a pixel footprint (`--filter`): the four
/// offset rays' hits and the table's mean, ns.
pub const FOOTPRINT_NS: f64 = 1e3;
/// The most ray-object tests of a pilot.
pub const PILOT_TESTS: f64 = 2e6;
/// The fewest and most rays of a pilot.
const PILOT_RAYS: (f64, f64) = (16.0, 1024.0);

/// How a model's colour is integrated: the crate's lobe-exact grating paths (Agu-Hill and the
/// radiometric grating), or the generic path through the model's `eval` (Thorman, Stam).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrand {
    /// A grating's intensity (times an envelope).
    Grating(Grating),
    /// Thorman's lobes, period in nm.
    Thorman(f64),
    /// Stam's Fourier optics, period in nm.
    Stam(f64),
    /// The radiometric grating with tabulated efficiencies (η depends on λ, so its colour takes
    /// the generic path around every peak), period in nm.
    Tabulated(f64),
}

/// The cost of one colour of `integrand` by `strategy`, ns: upper bounds of the measured costs
/// (on the grating paths the peak search 0.7-7 µs, `Exact` 60 µs-4.8 ms growing with the
/// period; on the generic paths, which evaluate the model at every wavelength of a rule or
/// around every peak, 0.1-1.5 ms for the peak search and up to 6 ms for `Exact`).
pub fn colour_ns(spectral: &Spectral, integrand: Integrand, colour: Colour) -> f64 {
    match integrand {
        Integrand::Grating(g) => grating_ns(spectral, &g, colour),
        // The peak search: `cd_preset` and `cd_rainbow` (d = 1600 nm, N = 34) by the Whitted
        // renderer took 0.27 and 0.26 of the time this constant's earlier 1.5 ms + 100 ns·d
        // estimated, once a table's single order no longer interpolated every order; more
        // orders cost more. The other rules' costs are the earlier upper bounds.
        Integrand::Tabulated(d) => match colour.generic().map(|g| g.kind()) {
            Some(GenericStrategyKind::Uniform { samples }) => 600.0 * samples as f64,
            Some(GenericStrategyKind::GaussLegendre { intervals }) => 4800.0 * intervals as f64,
            Some(GenericStrategyKind::PeakSearch) | None => 4.5e5 + 30.0 * d,
            Some(_) => 6e6 + 400.0 * d,
        },
        Integrand::Thorman(d) | Integrand::Stam(d) => {
            let stam = matches!(integrand, Integrand::Stam(_));
            let Some(generic) = colour.generic() else {
                // The paper's peak colours.
                return 1e3 + 1.3 * d;
            };
            // A wavelength of Stam's model, of Thorman's (measured 350 and 140 ns an interval
            // of 8 wavelengths in `compare`; about twice that).
            let per_lambda = if stam { 100.0 } else { 40.0 };
            match generic.kind() {
                // Stam's profiles in `compare` (d = 3200 nm, depth 120-150 nm): 180-460 µs; the
                // sine of depth 10⁴ nm: up to 1.5 ms.
                GenericStrategyKind::PeakSearch if stam => 7e5,
                // Thorman's lobes in `compare` (width 0.0062, d = 3200 nm): 75 µs; of width
                // 0.005 at d = 10⁵ nm: 1.2 ms.
                GenericStrategyKind::PeakSearch => 3e4 + 12.0 * d,
                GenericStrategyKind::Uniform { samples } => per_lambda * samples as f64,
                GenericStrategyKind::GaussLegendre { intervals } => {
                    8.0 * per_lambda * intervals as f64
                }
                // The windows rule (and Auto, at its dearest).
                _ if stam => 2e6 + 60.0 * d,
                _ => 2e5 + 15.0 * d,
            }
        }
    }
}

fn grating_ns(spectral: &Spectral, g: &Grating, colour: Colour) -> f64 {
    let d = g.period_nm();
    // Few slits: broad lobes, more work at the band ends.
    let few = match g.slits() {
        Slits::Finite(n) if n < 100 => 6e3,
        _ => 0.0,
    };
    let Colour::Integral(strategy) = colour else {
        // The paper's peak colours: 0.2-3 µs.
        return 200.0 + 0.03 * d + few;
    };
    // Each line: the measured worst over N = 10-2³² at each period (400, 1600, 10⁴, 10⁵ nm),
    // as a constant plus a slope in d (the number of orders in the band grows with d).
    match strategy.kind() {
        // 0.7-4.4 µs (7 µs for N < 100).
        StrategyKind::PeakSearch | StrategyKind::PeakSearchRefined => 1.5e3 + 0.05 * d + few,
        // 60-310 µs at d = 400 nm, 0.7-4.8 ms at 10⁵ nm.
        StrategyKind::Exact => 3e5 + 45.0 * d,
        // 5-27 µs.
        StrategyKind::Asymptotic => 3e4,
        // 40-55 ns a wavelength.
        StrategyKind::Uniform { samples } => 60.0 * samples as f64,
        // 8 wavelengths an interval: 330-420 ns.
        StrategyKind::GaussLegendre { intervals } => 450.0 * intervals as f64,
        // What Auto picks over u in (0, 2], at its dearest.
        StrategyKind::Auto { .. } => (1..=40)
            .map(|i| {
                let picked = spectral.choose(g, i as f64 / 20.0, strategy);
                if matches!(picked.kind(), StrategyKind::Auto { .. }) {
                    3e5 + 45.0 * d
                } else {
                    grating_ns(spectral, g, Colour::Integral(picked))
                }
            })
            .fold(0.0, f64::max),
        // A strategy this estimate does not know: as dear as `Exact`.
        _ => 3e5 + 45.0 * d,
    }
}

/// What a scene's rays meet per camera sample, from its own rays through a grid of pixel
/// centres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pilot {
    /// Rays traced per camera sample (the camera ray and its mirror reflections).
    pub rays: f64,
    /// Surface hits per camera sample.
    pub hits: f64,
    /// Hits per camera sample on a grating (not a plain square of a checkerboard).
    pub grating_hits: f64,
    /// Shadow rays per camera sample: at every hit, the samples of each light in front of the
    /// surface (the renderers test no light behind it).
    pub shadow_rays: f64,
    /// Lights per camera sample that light a grating hit: in front of it and its centre not
    /// occluded (the renderers compute a colour for no other).
    pub lit: f64,
    /// The same, each light counted by its samples (a Whitted integrator of area lights
    /// computes a colour per visible light sample).
    pub lit_samples: f64,
}

/// The pilot of `scene` seen from `camera`: at most [`PILOT_TESTS`] ray-object tests for the
/// rays and as many for the occlusion of the lights' centres seen from grating hits (past
/// them, a light in front of a grating hit counts as visible); mirror reflections are
/// followed up to `render.max_depth` when `mirrors`.
pub fn pilot<P: Physics>(scene: &Scene<P>, camera: &Camera, mirrors: bool) -> Pilot {
    let s = &scene.settings;
    let objects = scene.objects.len().max(1) as f64;
    let depth = if mirrors { s.max_depth as f64 } else { 0.0 };
    let n = (PILOT_TESTS / (objects * (1.0 + depth))).clamp(PILOT_RAYS.0, PILOT_RAYS.1);
    // A grid of about n rays with the picture's aspect ratio.
    let aspect = s.width as f64 / s.height as f64;
    let cols = ((n * aspect).sqrt().round() as u32).clamp(1, s.width);
    let rows = ((n / aspect).sqrt().round() as u32).clamp(1, s.height);
    let rays = CameraRays::new(camera, s.width, s.height);
    let (mut traced, mut hits, mut gratings) = (0u64, 0u64, 0u64);
    let (mut shadow, mut lit, mut lit_samples) = (0u64, 0u64, 0u64);
    let mut occlusion_tests = 0.0;
    for j in 0..rows {
        for i in 0..cols {
            let x = (i as f64 + 0.5) / cols as f64 * s.width as f64;
            let y = (j as f64 + 0.5) / rows as f64 * s.height as f64;
            let mut ray = rays.ray(x, y);
            for bounce in 0..=s.max_depth {
                traced += 1;
                let Some(hit) = nearest(&scene.objects, &ray, f64::INFINITY) else {
                    break;
                };
                hits += 1;
                let m = &scene.materials[scene.objects[hit.object].material];
                let on_grating = m.grating.as_ref().is_some_and(|g| !g.is_plain_at(hit.p));
                gratings += on_grating as u64;
                let origin = hit.spawn_point();
                for light in &scene.lights {
                    let to = light.position - hit.point;
                    if hit.normal.dot(to) <= 0.0 {
                        continue;
                    }
                    let samples = light.samples.max(1) as u64;
                    shadow += samples;
                    if !on_grating {
                        continue;
                    }
                    let visible = occlusion_tests >= PILOT_TESTS || {
                        occlusion_tests += objects;
                        let dist = to.length();
                        !occluded(&scene.objects, &Ray::new(origin, to), dist * SHADOW_REACH)
                    };
                    if visible {
                        lit += 1;
                        lit_samples += samples;
                    }
                }
                if !(mirrors && m.mirror > 0.0 && bounce < s.max_depth) {
                    break;
                }
                let d = ray.dir;
                let n = hit.normal;
                ray = Ray::new(origin, d - n * (2.0 * d.dot(n)));
            }
        }
    }
    let per = 1.0 / (cols as f64 * rows as f64);
    Pilot {
        rays: traced as f64 * per,
        hits: hits as f64 * per,
        grating_hits: gratings as f64 * per,
        shadow_rays: shadow as f64 * per,
        lit: lit as f64 * per,
        lit_samples: lit_samples as f64 * per,
    }
}

/// One part of an estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct Part {
    /// What is counted: "3.1e6 colour evaluations (strategy exact)".
    pub what: String,
    /// Its cost, ns.
    pub ns: f64,
    /// The options or scene fields that reduce it.
    pub reduce: String,
}

/// The estimated work of one scene's run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Estimate {
    /// Its parts.
    pub parts: Vec<Part>,
}

/// A count in three significant digits (`3.1e6`, `4001`).
pub fn count(v: f64) -> String {
    if v < 1e4 {
        format!("{}", v.round())
    } else {
        format!("{v:.2e}")
    }
}

/// A duration or cost in three significant digits (`0.37`, `37`, `1.23e4`).
pub fn short(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if !(1e-2..1e4).contains(&v.abs()) {
        return format!("{v:.2e}");
    }
    let decimals = (2 - v.abs().log10().floor() as i32).clamp(0, 3) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl Estimate {
    /// Adds a part of `ns` nanoseconds.
    pub fn add(&mut self, what: String, ns: f64, reduce: &str) {
        if ns > 0.0 {
            self.parts.push(Part {
                what,
                ns,
                reduce: reduce.to_string(),
            });
        }
    }

    /// The estimate, seconds of one core.
    pub fn seconds(&self) -> f64 {
        self.parts.iter().map(|p| p.ns).sum::<f64>() * 1e-9
    }

    /// `Err` above `budget` (seconds of one core, [`BUDGET_S`] by default), naming the estimate,
    /// the budget, its largest part and what reduces it.
    pub fn check(&self, scene: &str, budget: f64) -> Result<(), String> {
        let total = self.seconds();
        if total <= budget {
            return Ok(());
        }
        let Some(top) = self.parts.iter().max_by(|a, b| a.ns.total_cmp(&b.ns)) else {
            return Ok(());
        };
        Err(format!(
            "{scene}: an estimated {} s of work on one core, above the budget of {} s \
             (--budget; tools/render/common/budget.rs); most of it, {} s, is {}: reduce {}",
            short(total),
            short(budget),
            short(top.ns * 1e-9),
            top.what,
            top.reduce
        ))
    }
}

/// The rays of a renderer: `samples` camera samples, each with the pilot's rays and shadow
/// rays, all tested against every object.
pub fn tracing(est: &mut Estimate, samples: f64, pilot: &Pilot, objects: usize) {
    let o = objects as f64;
    let hits = samples * pilot.hits;
    let shadow_rays = samples * pilot.shadow_rays;
    let tests = samples * pilot.rays * o + shadow_rays * o;
    est.add(
        format!("{} camera samples", count(samples)),
        samples * SAMPLE_NS,
        "--width/--height, --spp or --frames",
    );
    est.add(
        format!("{} surface hits", count(hits)),
        hits * HIT_NS,
        "--width/--height, --spp, --frames or --max-depth",
    );
    est.add(
        format!("{} shadow rays", count(shadow_rays)),
        shadow_rays * SHADOW_NS,
        "--width/--height, --spp, --frames, --max-depth or the lights' samples",
    );
    est.add(
        format!("{} ray-object tests", count(tests)),
        tests * RAY_TEST_NS,
        "--width/--height, --spp, --frames, --max-depth, the lights' samples or the number of \
         objects",
    );
}
