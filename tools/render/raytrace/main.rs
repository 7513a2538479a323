//! The reference ray tracer of the `diffraction` crate: the scenes of Agu & Hill's figures 4-6
//! (gratings, twisted and checkerboard gratings, a CD-ROM beside an image-mapped can, a mirror
//! cube, all on wood), rendered Whitted-style with the paper's illumination model (eq. 12,
//! `diffraction::Illumination`) and the crate's diffraction colours.
//!
//! ```text
//! cargo run --release -p diffraction-render --bin raytrace                       # every paper scene into out/
//! cargo run --release -p diffraction-render --bin raytrace -- fig6 --out cd.png --width 800 --height 600 --spp 16
//! cargo run --release -p diffraction-render --bin raytrace -- fig4b --frames 36 --out anim/
//! cargo run --release -p diffraction-render --bin raytrace -- --help
//! ```
//!
//! Only the diffraction shading and the colour pipeline come from the crate (`Grating`,
//! `AguHill`, `Illumination`, `frame::{GratingField, Tile, ShadingFrame}`,
//! `spectrum::Spectral`, `color::{Xyz, LinearSrgb, Clip}`); geometry, textures, scene files and
//! output are in `tools/render/common`, shared with the path tracer (`tools/render/pathtrace`), which
//! renders the scenes in physical units.

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

mod footprint;
mod label;
mod model;
mod whitted;

#[cfg(test)]
#[path = "../common/budget_tests.rs"]
mod budget_tests;
#[cfg(test)]
#[path = "../common/calibration_tests.rs"]
mod calibration_tests;
#[cfg(test)]
#[path = "../common/tests.rs"]
mod common_tests;
#[cfg(test)]
#[path = "../common/files_tests.rs"]
mod files_tests;
#[cfg(test)]
mod footprint_tests;
#[cfg(test)]
mod sweep_tests;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use budget::Estimate;
use cli::{Command, Options};
use files::Kind;
use footprint::Filter;
use model::Paper;
use scene::Scene;
use whitted::PaperScene;

const USAGE: &str = "\
raytrace: the diffraction crate's reference ray tracer (Agu & Hill, figures 4-6)

USAGE:
    raytrace [SCENE...] [OPTIONS]
    raytrace make-label [--out FILE]

With no SCENE, renders every paper scene of tools/render/scenes into out/ (NAME.png and the linear
NAME.pfm). SCENE is a shipped scene's name (fig4a, fig4b, fig5a, fig5b, fig6) or a path to a
.toml scene file. Scenes in physical units (a [radiometry] table, e.g. cd_area_light) and the
path tracer (formerly --integrator path) are the binary pathtrace:
cargo run --release -p diffraction-render --bin pathtrace -- cd_area_light

";

const OWN_OPTIONS: &str = "\
    --filter NAME      diffraction colour of the paper's model: none (default, at each
                       sample's u), footprint (the mean over the pixel footprint's u and the
                       light's size, from a colour table per grating built at load) or point
                       (the table at each sample's u)
    --max-depth D      mirror recursion, 0-64
    --integrator NAME  whitted, the only one here (path: see the binary pathtrace)
";

const MAKE_LABEL: &str = "
make-label writes the can label (default tools/render/assets/label.png).
";

/// The ray tracer's own arguments.
#[derive(Debug, Default, Clone, PartialEq)]
pub struct Args {
    /// `--filter`.
    pub filter: Filter,
    /// `make-label`: write the can label instead of rendering.
    pub make_label: bool,
}

impl cli::Extra for Args {
    fn take(
        &mut self,
        arg: &str,
        value: &mut dyn FnMut() -> Result<String, String>,
        opts: &Options,
    ) -> Result<bool, String> {
        match arg {
            "--filter" => {
                let v = value()?;
                self.filter = v
                    .parse()
                    .map_err(|e| format!("--filter: {e}, got \"{v}\""))?;
            }
            "--integrator" => match value()?.as_str() {
                "whitted" => {}
                "path" => {
                    return Err(
                        "--integrator path: the path tracer is the binary pathtrace: \
                                cargo run --release -p diffraction-render --bin pathtrace -- SCENE"
                            .into(),
                    )
                }
                v => return Err(format!("--integrator: expected whitted, got \"{v}\"")),
            },
            "make-label" if opts.scenes.is_empty() && !self.make_label => self.make_label = true,
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// The paper's renderer with its `--filter`.
#[derive(Debug, Clone, Copy, Default)]
pub struct Raytracer {
    /// How the diffraction colour is filtered.
    pub filter: Filter,
}

impl run::Renderer for Raytracer {
    type Physics = Paper;
    type Prepared = PaperScene;
    const OTHER: &'static str = "pathtrace";

    fn prepare(&self, scene: Scene<Paper>, note: &dyn Fn(&str)) -> Result<PaperScene, String> {
        let exposures = model::exposures(&scene.spectral, &scene.materials);
        let mut p = PaperScene {
            scene,
            exposures,
            filter: Filter::None,
            tables: Vec::new(),
        };
        let (n, took) = footprint::prepare(&mut p, self.filter)?;
        if self.filter != Filter::None {
            note(&format!(
                "{}: {n} colour table(s) built in {:.2} s",
                p.scene.name,
                took.as_secs_f64()
            ));
        }
        Ok(p)
    }

    /// The Whitted tracer's rays and colours (one per light at every grating hit, the dearest
    /// grating's), each distinct grating's exposure scan, and `--filter`'s tables.
    fn estimate(&self, scene: &Scene<Paper>, frames: u32) -> Estimate {
        let s = &scene.settings;
        let samples = s.width as f64 * s.height as f64 * s.spp as f64 * frames as f64;
        let pilot = budget::pilot(scene, &scene.camera, true);
        let mut est = Estimate::default();
        budget::tracing(&mut est, samples, &pilot, scene.objects.len());
        let gratings = scene.materials.iter().enumerate();
        let gratings = gratings.filter_map(|(i, m)| m.grating.as_ref().map(|g| (i, g)));
        let tabled = |g: &material::GratingMaterial<model::Model>| {
            self.filter != Filter::None && footprint::tabulable(g)
        };
        let mut dearest = (0.0, String::new());
        let (mut seen, mut scans, mut tables) = (std::collections::HashSet::new(), 0.0, Vec::new());
        for (i, g) in gratings {
            let colour = match tabled(g) {
                true => budget::FOOTPRINT_NS,
                false => budget::colour_ns(&scene.spectral, g.model.integrand(), g.strategy),
            };
            if colour > dearest.0 {
                dearest = (
                    colour,
                    format!("strategy {} of objects[{i}].material", g.strategy),
                );
            }
            let scan = model::exposure_strategy(g.strategy);
            if seen.insert(format!("{:?} {scan:?}", g.model)) {
                scans += budget::colour_ns(&scene.spectral, g.model.integrand(), scan);
            }
            if tabled(g) && !tables.contains(&g.model.integrand()) {
                tables.push(g.model.integrand());
            }
        }
        let n = (model::EXPOSURE_SCAN + 1) as f64;
        est.add(
            format!("{} exposure scans of {n} colours each", seen.len()),
            n * scans,
            "the number of distinct gratings or their models' parameters",
        );
        let colours = samples * pilot.lit;
        est.add(
            format!(
                "{} colour evaluations ({})",
                budget::count(colours),
                dearest.1
            ),
            colours * dearest.0,
            "--width/--height, --spp, --frames, the number of lights, or a cheaper --strategy or \
             material strategy",
        );
        est.add(
            format!("{} colour tables", tables.len()),
            tables.len() as f64 * budget::TABLE_NS,
            "the number of distinct gratings, or --filter none",
        );
        est
    }

    fn scene<'a>(&self, p: &'a PaperScene) -> &'a Scene<Paper> {
        &p.scene
    }

    fn render(
        &self,
        p: &PaperScene,
        camera: &camera::Camera,
        progress: Option<&str>,
    ) -> output::Image {
        whitted::render(p, camera, progress)
    }

    fn integrator(&self) -> &'static str {
        "whitted"
    }
}

/// Where the generated can label is shipped.
fn label_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/label.png")
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match cli::parse::<Args>(&args) {
        Err(e) => {
            eprintln!("error: {e}\n\nRun with --help for usage.");
            return ExitCode::from(2);
        }
        Ok(Command::Help) => {
            print!(
                "{USAGE}{}{OWN_OPTIONS}{}{MAKE_LABEL}",
                cli::OPTIONS,
                cli::OUTPUTS
            );
            Ok(())
        }
        Ok(Command::Render(opts, extra)) if extra.make_label => {
            if opts.scenes.is_empty() {
                let (out, flag) = match opts.out {
                    Some(out) => (out, "--out"),
                    None => (label_path(), ""),
                };
                files::write_one(&out, Kind::Png, flag, |w| {
                    output::png_to(w, &label::make_label())
                })
                .map(|()| eprintln!("wrote {}", out.display()))
            } else {
                Err("make-label takes no scene".into())
            }
        }
        Ok(Command::Render(opts, extra)) => run::run(
            &Raytracer {
                filter: extra.filter,
            },
            &opts,
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
