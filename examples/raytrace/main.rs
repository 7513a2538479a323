//! The reference ray tracer of the `diffraction` crate: the scenes of Agu & Hill's figures 4-6
//! (gratings, twisted and checkerboard gratings, a CD-ROM beside an image-mapped can, a mirror
//! cube, all on wood), rendered Whitted-style with the crate's diffraction shading.
//!
//! ```text
//! cargo run --release --example raytrace                       # every scene into out/
//! cargo run --release --example raytrace -- fig6 --out cd.png --width 800 --height 600 --spp 16
//! cargo run --release --example raytrace -- fig4b --frames 36 --out anim/
//! cargo run --release --example raytrace -- --help
//! ```
//!
//! Only the diffraction shading and the colour pipeline come from the crate (`Grating`,
//! `AguHill`, `frame::{GratingField, Tile, ShadingFrame}`, `spectrum::Spectral`,
//! `color::{Xyz, LinearSrgb, Clip}`); geometry, textures, scene files and output are here.

mod cli;
mod diagnostics;
mod font;
mod footprint;
mod geometry;
mod limits;
mod material;
mod output;
mod path;
mod radiometric;
mod render;
mod scene;
mod schema;
mod texture;

#[cfg(test)]
mod footprint_tests;
#[cfg(test)]
mod path_tests;
#[cfg(test)]
mod tests;

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use cli::{Command, Options};
use output::{Kind, Target};
use scene::Scene;

/// Where the shipped scenes live.
fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

/// Where the generated can label is shipped.
fn label_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/assets/label.png")
}

/// The shipped scene names, sorted.
fn scene_names() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(scenes_dir())
        .map(|dir| {
            dir.filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| x == "toml"))
                .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

/// A scene argument: a shipped scene's name, or a path to a `.toml` file.
fn scene_path(arg: &str) -> Result<PathBuf, String> {
    let as_path = Path::new(arg);
    if arg.ends_with(".toml") || arg.contains(std::path::MAIN_SEPARATOR) || arg.contains('/') {
        return Ok(as_path.to_path_buf());
    }
    let p = scenes_dir().join(format!("{arg}.toml"));
    if p.exists() {
        Ok(p)
    } else {
        Err(format!(
            "unknown scene \"{arg}\": expected one of {} or a path to a .toml file",
            scene_names().join(", ")
        ))
    }
}

/// Loads a scene and applies the command line's overrides.
fn prepare(path: &Path, opts: &Options) -> Result<Scene, String> {
    let mut scene = scene::load(path).map_err(|e| e.to_string())?;
    let s = &mut scene.settings;
    let (w0, h0) = (s.width, s.height);
    match (opts.width, opts.height) {
        (Some(w), Some(h)) => (s.width, s.height) = (w, h),
        // One side given: keep the scene's aspect ratio.
        (Some(w), None) => {
            (s.width, s.height) = (
                w,
                ((w as f64 * h0 as f64 / w0 as f64).round() as u32).clamp(1, limits::MAX_SIZE),
            )
        }
        (None, Some(h)) => {
            (s.width, s.height) = (
                ((h as f64 * w0 as f64 / h0 as f64).round() as u32).clamp(1, limits::MAX_SIZE),
                h,
            )
        }
        (None, None) => {}
    }
    if let Some(spp) = opts.spp {
        s.spp = spp;
    }
    if let Some(depth) = opts.max_depth {
        s.max_depth = depth;
    }
    if let Some(seed) = opts.seed {
        s.seed = seed;
    }
    if let Some(clip) = opts.clip {
        s.clip = clip;
    }
    if let Some(strategy) = opts.strategy {
        scene.set_strategy(strategy);
    }
    if opts.filter != footprint::Filter::None {
        let (n, took) = footprint::prepare(&mut scene, opts.filter)?;
        note(
            opts,
            &format!(
                "{}: {n} colour table(s) built in {:.2} s",
                scene.name,
                took.as_secs_f64()
            ),
        );
    }
    Ok(scene)
}

fn note(opts: &Options, msg: &str) {
    if !opts.quiet {
        eprintln!("{msg}");
    }
}

fn has_extension(p: &Path, ext: &str) -> bool {
    p.extension().is_some_and(|x| x.eq_ignore_ascii_case(ext))
}

/// One scene's work, its outputs checked.
enum Job {
    Still {
        scene: Scene,
        png: Option<Target>,
        pfm: Vec<Target>,
    },
    Animation {
        scene: Scene,
        frames: Vec<Target>,
        gif: Target,
        dir: PathBuf,
    },
}

/// Renders one still; writes a PNG and/or a PFM.
fn still(
    scene: &Scene,
    png: Option<&Target>,
    pfm: &[Target],
    opts: &Options,
) -> Result<(), String> {
    let start = Instant::now();
    if !scene.description.is_empty() {
        note(opts, &format!("{}: {}", scene.name, scene.description));
    }
    let image = path::render_with(
        opts.integrator,
        scene,
        &scene.camera,
        render::progress_wanted(opts.quiet),
        &scene.name,
    )?;
    if let Some(t) = png {
        let picture = if opts.compare_clip {
            output::clip_panels(&image)
        } else {
            output::to_rgb8(&image, scene.settings.clip)
        };
        output::write_png(&t.path, &picture)?;
    }
    for t in pfm {
        output::write_pfm(&t.path, &image)?;
    }
    let s = &scene.settings;
    let written: Vec<String> = png
        .into_iter()
        .chain(pfm)
        .map(|t| t.shown.display().to_string())
        .collect();
    note(
        opts,
        &format!(
            "{}: {}x{}, {} spp, {}, {}, clip {} in {:.2} s -> {}",
            scene.name,
            s.width,
            s.height,
            s.spp,
            opts.integrator,
            s.strategy,
            if opts.compare_clip {
                "all".to_string()
            } else {
                s.clip.to_string()
            },
            start.elapsed().as_secs_f64(),
            written.join(", ")
        ),
    );
    Ok(())
}

/// Renders one frame per target orbiting the camera once around its target, as numbered PNGs
/// and an animated GIF streamed frame by frame.
fn animation(
    scene: &Scene,
    frames: &[Target],
    gif: &Target,
    dir: &Path,
    opts: &Options,
) -> Result<(), String> {
    let start = Instant::now();
    let bar = render::progress_wanted(opts.quiet);
    let n = frames.len();
    let mut encoder = output::Gif::create(&gif.path, 80)?;
    for (i, frame) in frames.iter().enumerate() {
        let angle = std::f64::consts::TAU * i as f64 / n as f64;
        let camera = render::orbit(&scene.camera, angle);
        let image = path::render_with(
            opts.integrator,
            scene,
            &camera,
            bar,
            &format!("{} {}/{}", scene.name, i + 1, n),
        )?;
        let png = output::to_rgb8(&image, scene.settings.clip);
        output::write_png(&frame.path, &png)?;
        encoder.add(&png)?;
    }
    encoder.finish()?;
    note(
        opts,
        &format!(
            "{}: {n} frames in {:.1} s -> {}/{}_NNNN.png, {}",
            scene.name,
            start.elapsed().as_secs_f64(),
            dir.display(),
            scene.name,
            gif.shown.display()
        ),
    );
    Ok(())
}

/// Loads one scene and checks its work and its outputs.
fn plan(name: &str, single: bool, all: bool, opts: &Options) -> Result<Job, String> {
    let path = scene_path(name)?;
    let scene = prepare(&path, opts)?;
    let s = &scene.settings;
    limits::work(s.width, s.height, s.spp, opts.frames.unwrap_or(1))
        .map_err(|e| format!("{}: {e}", scene.name))?;
    let out = opts.out.clone();
    if let Some(n) = opts.frames {
        let dir = match &out {
            Some(d) if single => d.clone(),
            Some(d) => d.join(&scene.name),
            None => PathBuf::from("out").join(&scene.name),
        };
        let dir = output::directory(&dir)?;
        let frames = (0..n)
            .map(|i| output::target(&dir.join(format!("{}_{i:04}.png", scene.name)), Kind::Png))
            .collect::<Result<_, _>>()?;
        let gif = output::target(&dir.join(format!("{}.gif", scene.name)), Kind::Gif)?;
        return Ok(Job::Animation {
            scene,
            frames,
            gif,
            dir,
        });
    }
    // One scene and a file name: write exactly that; otherwise a directory of NAME.png
    // (and NAME.pfm when rendering everything or when asked).
    let file_out = out
        .as_ref()
        .filter(|p| single && (has_extension(p, "png") || has_extension(p, "pfm")));
    if let Some(p) = out.as_ref().filter(|_| single && file_out.is_none()) {
        if p.extension().is_some() && !p.is_dir() {
            return Err(format!(
                "--out {}: expected a file name ending in .png or .pfm, or a directory",
                p.display()
            ));
        }
    }
    let suffix = if opts.compare_clip { "-clipping" } else { "" };
    let (png, mut pfm) = match file_out {
        Some(p) if has_extension(p, "pfm") => (None, vec![p.clone()]),
        Some(p) => (Some(p.clone()), vec![]),
        None => {
            let dir = output::directory(&out.unwrap_or_else(|| PathBuf::from("out")))?;
            let png = dir.join(format!("{}{suffix}.png", scene.name));
            let pfm = if all && !opts.compare_clip {
                vec![dir.join(format!("{}.pfm", scene.name))]
            } else {
                vec![]
            };
            (Some(png), pfm)
        }
    };
    pfm.extend(opts.pfm.clone());
    Ok(Job::Still {
        png: png.map(|p| output::target(&p, Kind::Png)).transpose()?,
        pfm: pfm
            .iter()
            .map(|p| output::target(p, Kind::Pfm))
            .collect::<Result<_, _>>()?,
        scene,
    })
}

fn run(opts: &Options) -> Result<(), String> {
    let all = opts.scenes.is_empty();
    let names: Vec<String> = if all {
        scene_names()
    } else {
        opts.scenes.clone()
    };
    if names.is_empty() {
        return Err(format!("no scenes found in {}", scenes_dir().display()));
    }
    let single = names.len() == 1;
    let start = Instant::now();
    // Every scene is loaded and every output checked before anything is rendered.
    let jobs = names
        .iter()
        .map(|name| plan(name, single, all, opts))
        .collect::<Result<Vec<_>, _>>()?;
    let targets: Vec<Target> = jobs
        .iter()
        .flat_map(|job| match job {
            Job::Still { png, pfm, .. } => png.iter().chain(pfm.iter()).cloned().collect(),
            Job::Animation { frames, gif, .. } => {
                frames.iter().chain([gif]).cloned().collect::<Vec<_>>()
            }
        })
        .collect();
    output::distinct(&targets)?;
    for job in &jobs {
        match job {
            Job::Still { scene, png, pfm } => still(scene, png.as_ref(), pfm, opts)?,
            Job::Animation {
                scene,
                frames,
                gif,
                dir,
            } => animation(scene, frames, gif, dir, opts)?,
        }
    }
    if !single {
        note(
            opts,
            &format!(
                "{} scenes in {:.1} s",
                names.len(),
                start.elapsed().as_secs_f64()
            ),
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let command = match cli::parse(&args) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}\n\nRun with --help for usage.");
            return ExitCode::from(2);
        }
    };
    let result = match command {
        Command::Help => {
            print!("{}", cli::USAGE);
            Ok(())
        }
        Command::MakeLabel { out } => {
            let out = out.unwrap_or_else(label_path);
            output::target(&out, Kind::Png)
                .and_then(|t| output::write_png(&t.path, &texture::make_label()))
                .map(|()| eprintln!("wrote {}", out.display()))
        }
        Command::Render(opts) => run(&opts),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
