//! The spectral path tracer of the `diffraction` crate: scenes in physical units (a
//! `[radiometry]` table, e.g. the CD of `cd_area_light`), with the energy-normalised grating
//! `GratingBsdf`, four hero wavelengths per path, next-event estimation and BSDF sampling
//! combined by MIS; and the Whitted-style renderer of the same scenes for comparison.
//!
//! ```text
//! cargo run --release -p diffraction-render --bin pathtrace                          # every such scene into out/
//! cargo run --release -p diffraction-render --bin pathtrace -- cd_area_light --spp 64 --out cd.png
//! cargo run --release -p diffraction-render --bin pathtrace -- cd_area_light --integrator whitted
//! ```
//!
//! The paper's scenes (fig4a … fig6, no `[radiometry]` table) render too when named
//! (`pathtrace -- fig6 --integrator path --out fig6_path.png`): [`paper`] maps their unitless
//! lights, ambient light, eq. 12 coefficients and Agu-Hill gratings to physical units, and says
//! what has no counterpart (the ambient coefficients, the per-grating exposure, the
//! `diffraction` coefficient).
//!
//! Geometry, textures, scene files and output are in `tools/render/common`, shared with the paper's
//! ray tracer (`tools/render/raytrace`).

#[path = "../common/budget.rs"]
pub mod budget;
#[path = "../common/camera.rs"]
pub mod camera;
#[path = "../common/cli.rs"]
pub mod cli;
#[path = "../common/colour.rs"]
pub mod colour;
#[path = "../common/diagnostics.rs"]
pub mod diagnostics;
#[path = "../common/files.rs"]
pub mod files;
#[path = "../common/font.rs"]
pub mod font;
#[path = "../common/geometry.rs"]
pub mod geometry;
#[path = "../common/limits.rs"]
pub mod limits;
#[path = "../common/material.rs"]
pub mod material;
#[path = "../common/output.rs"]
pub mod output;
#[path = "../common/run.rs"]
pub mod run;
#[path = "../common/sampling.rs"]
pub mod sampling;
#[path = "../common/scene.rs"]
pub mod scene;
#[path = "../common/schema.rs"]
pub mod schema;
#[path = "../common/texture.rs"]
pub mod texture;

mod paper;
mod path;
mod radiometry;
mod surface;
mod whitted;

#[cfg(test)]
#[path = "../common/calibration_tests.rs"]
mod calibration_tests;
#[cfg(test)]
mod paper_tests;
#[cfg(test)]
mod table_tests;
#[cfg(test)]
mod tests;

use std::process::ExitCode;

use budget::{Estimate, Integrand};
use cli::{Command, Options};
use path::PathOptions;
use radiometry::Radiometric;
use scene::Scene;

const USAGE: &str = "\
pathtrace: the diffraction crate's spectral path tracer, for scenes in physical units

USAGE:
    pathtrace [SCENE...] [OPTIONS]

With no SCENE, renders every shipped scene with a [radiometry] table (cd_area_light) into
out/ (NAME.png and the linear NAME.pfm). SCENE is a shipped scene's name or a path to a .toml
scene file. A scene without a [radiometry] table (the paper's fig4a ... fig6, the example
raytrace's) is mapped to physical units: the lights give the paper's irradiance at the
camera's look_at point and fall off as 1/r^2, the ambient light is a uniform sky of its
luminance, gratings of model agu-hill are the radiometric grating of the same d, w and N
(the module paper of tools/render/pathtrace says all of it). Name it with --out to keep the
ray tracer's out/NAME.png.

";

const OWN_OPTIONS: &str = "\
    --integrator NAME  path (default: spectral path tracing with MIS) or whitted (direct
                       light from the emitters, each area light by its light samples)
    --max-depth D      bounces: path length (path; 1 = direct light only) or mirror
                       recursion (whitted), 0-64
    --filter NAME      none only (the default): footprint, the binary raytrace's filter of
                       the paper's colour over a pixel's interval of u, is refused with the
                       reason for each integrator
";

/// The path tracer's own arguments: `--integrator`, and `--filter`, which takes `none` only
/// ([`command`] refuses `footprint` with the reason for the integrator).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Args {
    /// `--integrator`.
    pub integrator: Integrator,
    /// `--filter footprint` was given.
    pub footprint: bool,
}

impl cli::Extra for Args {
    fn take(
        &mut self,
        arg: &str,
        value: &mut dyn FnMut() -> Result<String, String>,
        opts: &Options,
    ) -> Result<bool, String> {
        if arg != "--filter" {
            return self.integrator.take(arg, value, opts);
        }
        self.footprint = match value()?.as_str() {
            "none" => false,
            "footprint" => true,
            v => return Err(format!("--filter: expected none or footprint, got \"{v}\"")),
        };
        Ok(true)
    }
}

/// The command of the arguments `args`: `--filter footprint` is refused on either integrator
/// (the path integrator averages each pixel by its samples; the radiometric grating's colour
/// is not a function of u, so there is no colour table to average over a footprint).
pub fn command(args: &[String]) -> Result<Command<Args>, String> {
    let command = cli::parse::<Args>(args)?;
    if let Command::Render(_, a) = &command {
        if a.footprint {
            return Err(match a.integrator {
                Integrator::Path => "--filter footprint: not with the path integrator, which \
                    averages each pixel's radiance by its samples (raise --spp); the footprint \
                    filter averages the paper's diffraction colour over a pixel's interval of u, \
                    in the binary raytrace"
                    .to_string(),
                Integrator::Whitted => "--filter footprint: not with --integrator whitted of the \
                    path tracer: the radiometric grating's colour depends on the direction along \
                    the grooves as well as on u, so no colour table over u can average it; the \
                    footprint filter is the binary raytrace's, for the paper's model"
                    .to_string(),
            });
        }
    }
    Ok(command)
}

/// The integrator of a render (`--integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// The spectral path tracer.
    #[default]
    Path,
    /// Direct light from the emitters, integrated over each area light by its light samples,
    /// and mirror recursion.
    Whitted,
}

impl cli::Extra for Integrator {
    fn take(
        &mut self,
        arg: &str,
        value: &mut dyn FnMut() -> Result<String, String>,
        _: &Options,
    ) -> Result<bool, String> {
        if arg != "--integrator" {
            return Ok(false);
        }
        *self = match value()?.as_str() {
            "path" => Integrator::Path,
            "whitted" => Integrator::Whitted,
            v => {
                return Err(format!(
                    "--integrator: expected path or whitted, got \"{v}\""
                ))
            }
        };
        Ok(true)
    }
}

impl run::Renderer for Integrator {
    type Physics = Radiometric;
    type Prepared = Scene<Radiometric>;
    const OTHER: &'static str = "raytrace";

    fn prepare(
        &self,
        scene: Scene<Radiometric>,
        _: &dyn Fn(&str),
    ) -> Result<Scene<Radiometric>, String> {
        Ok(scene)
    }

    /// Path tracing: at most `max_depth` vertices past each primary hit, each with a shadow ray
    /// and a BSDF evaluation; Whitted: the rays of the pilot, and at every grating hit one
    /// colour per light sample (the dearest grating's).
    fn estimate(&self, scene: &Scene<Radiometric>, frames: u32) -> Estimate {
        let s = &scene.settings;
        let samples = s.width as f64 * s.height as f64 * s.spp as f64 * frames as f64;
        let mut est = Estimate::default();
        let objects = scene.objects.len();
        match self {
            Integrator::Path => {
                // The integrator's own paths through a grid of pixel centres: their rays,
                // vertices, shadow rays and grating vertices per camera sample.
                let options = PathOptions {
                    grating_sampler: true,
                    max_depth: s.max_depth,
                };
                let p = path::pilot(scene, &scene.camera, options);
                let traced = budget::Pilot {
                    rays: p.rays,
                    hits: p.vertices,
                    grating_hits: p.grating_vertices,
                    shadow_rays: p.shadow_rays,
                    lit: 0.0,
                    lit_samples: 0.0,
                };
                budget::tracing(&mut est, samples, &traced, objects);
                let on_gratings = samples * p.grating_vertices;
                let (bsdf_ns, what) = dearest_bsdf(scene);
                est.add(
                    format!(
                        "{} grating BSDF evaluations ({what})",
                        budget::count(on_gratings)
                    ),
                    on_gratings * bsdf_ns,
                    "--width/--height, --spp, --frames or --max-depth",
                );
            }
            Integrator::Whitted => {
                let pilot = budget::pilot(scene, &scene.camera, true);
                budget::tracing(&mut est, samples, &pilot, objects);
                let dearest = scene
                    .materials
                    .iter()
                    .enumerate()
                    .filter_map(|(i, m)| m.grating.as_ref().map(|g| (i, g)))
                    .map(|(i, g)| {
                        let integrand = if g.model.order_efficiency().is_tabulated() {
                            Integrand::Tabulated(g.model.grating().period_nm())
                        } else {
                            Integrand::Grating(*g.model.grating())
                        };
                        let ns = if whitted::tabled(g) {
                            whitted::TABLE_LOOKUP_NS
                        } else {
                            budget::colour_ns(&scene.spectral, integrand, g.strategy)
                        };
                        (
                            ns,
                            format!("strategy {} of objects[{i}].material", g.strategy),
                        )
                    })
                    .fold((0.0, String::new()), |a, b| if b.0 > a.0 { b } else { a });
                let tabled: Vec<_> = scene
                    .materials
                    .iter()
                    .filter_map(|m| m.grating.as_ref().filter(|g| whitted::tabled(g)))
                    .collect();
                est.add(
                    format!("{} colour tables of tabulated gratings", tabled.len()),
                    tabled
                        .iter()
                        .map(|g| whitted::table_build_ns(g))
                        .sum::<f64>(),
                    "a coherence-length groove (the generic colour, no table)",
                );
                let colours = samples * pilot.lit_samples;
                est.add(
                    format!(
                        "{} colour evaluations ({})",
                        budget::count(colours),
                        dearest.1
                    ),
                    colours * dearest.0,
                    "--width/--height, --spp, --frames, the lights' samples, or a cheaper \
                     --strategy or material strategy",
                );
            }
        }
        est
    }

    fn scene<'a>(&self, scene: &'a Scene<Radiometric>) -> &'a Scene<Radiometric> {
        scene
    }

    fn render(
        &self,
        scene: &Scene<Radiometric>,
        camera: &camera::Camera,
        progress: Option<&str>,
    ) -> output::Image {
        match self {
            Integrator::Path => {
                let options = PathOptions {
                    grating_sampler: true,
                    max_depth: scene.settings.max_depth,
                };
                path::render(scene, camera, options, progress)
            }
            Integrator::Whitted => whitted::render(scene, camera, progress),
        }
    }

    /// The scenes in physical units only: the paper's are the ray tracer's pictures in out/
    /// (named, they render here too, mapped by [`paper`]).
    fn renders_by_default(&self, scene: &Scene<Radiometric>) -> bool {
        !scene.units.from_paper
    }

    fn integrator(&self) -> &'static str {
        match self {
            Integrator::Path => "path",
            Integrator::Whitted => "whitted",
        }
    }
}

/// The cost of one vertex on the dearest grating of `scene` (a tabulated one's BSDF reads its
/// efficiency table), ns, and which it is.
fn dearest_bsdf(scene: &Scene<Radiometric>) -> (f64, String) {
    scene
        .materials
        .iter()
        .enumerate()
        .filter_map(|(i, m)| m.grating.as_ref().map(|g| (i, g)))
        .map(|(i, g)| {
            let efficiency = g.model.order_efficiency();
            let (ns, kind) = match efficiency.table() {
                Some(t) if t.is_conical() => (budget::BSDF_CONICAL_NS, "conical tabulated"),
                Some(_) => (budget::BSDF_TABLE_NS, "tabulated"),
                None => (budget::BSDF_NS, "amplitude"),
            };
            (ns, format!("{kind} efficiencies of objects[{i}].material"))
        })
        .fold((0.0, String::new()), |a, b| if b.0 > a.0 { b } else { a })
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match command(&args) {
        Err(e) => {
            eprintln!("error: {e}\n\nRun with --help for usage.");
            return ExitCode::from(2);
        }
        Ok(Command::Help) => {
            print!("{USAGE}{}{OWN_OPTIONS}{}", cli::OPTIONS, cli::OUTPUTS);
            Ok(())
        }
        Ok(Command::Render(opts, a)) => run::run(&a.integrator, &opts),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
