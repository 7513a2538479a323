//! One run of a renderer: the scenes named on the command line (or every shipped scene the
//! renderer takes), loaded and checked with their outputs before anything is rendered, then
//! rendered and written.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::camera::{progress_wanted, Camera};
use crate::cli::Options;
use crate::limits;
use crate::output::{self, Image, Kind, Target};
use crate::scene::{self, Physics, Scene};

/// A renderer: what it makes of a scene at load, and how it renders it.
pub trait Renderer: Sync {
    /// Its model of gratings and light units.
    type Physics: Physics;
    /// A scene ready to render (the scene and what the renderer computes for it once).
    type Prepared: Sync;
    /// The other example's name (for scenes that are the other's).
    const OTHER: &'static str;
    /// Computes what rendering `scene` needs once (after the command line's overrides);
    /// `note` prints a progress message.
    fn prepare(
        &self,
        scene: Scene<Self::Physics>,
        note: &dyn Fn(&str),
    ) -> Result<Self::Prepared, String>;
    /// The scene of a prepared scene.
    fn scene<'a>(&self, prepared: &'a Self::Prepared) -> &'a Scene<Self::Physics>;
    /// Renders from `camera` with the scene's settings, with a progress bar of that label.
    fn render(&self, prepared: &Self::Prepared, camera: &Camera, progress: Option<&str>) -> Image;
    /// The integrator's name, for the summary of a render.
    fn integrator(&self) -> &'static str;
}

/// Where the shipped scenes live.
pub fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes")
}

/// The shipped scene names, sorted.
pub fn scene_names() -> Vec<String> {
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

/// Loads a scene for renderer `R` and applies the command line's overrides; `Ok(None)` for a
/// scene that is the other renderer's when `skip_others` (every shipped scene is rendered).
fn load<R: Renderer>(
    arg: &str,
    opts: &Options,
    skip_others: bool,
) -> Result<Option<Scene<R::Physics>>, String> {
    let path = scene_path(arg)?;
    let mut scene = match scene::load::<R::Physics>(&path) {
        Ok(scene) => scene,
        Err(e) if e.other_renderer && skip_others => return Ok(None),
        Err(e) if e.other_renderer => {
            return Err(format!(
                "{e}: render it with `cargo run --release --example {} -- {arg}`",
                R::OTHER
            ))
        }
        Err(e) => return Err(e.to_string()),
    };
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
    Ok(Some(scene))
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
enum Job<P> {
    Still {
        scene: P,
        png: Option<Target>,
        pfm: Vec<Target>,
    },
    Animation {
        scene: P,
        frames: Vec<Target>,
        gif: Target,
        dir: PathBuf,
    },
}

/// The progress bar's label, when one is wanted.
fn bar<'a>(opts: &Options, label: &'a str) -> Option<&'a str> {
    progress_wanted(opts.quiet).then_some(label)
}

/// Renders one still; writes a PNG and/or a PFM.
fn still<R: Renderer>(
    r: &R,
    prepared: &R::Prepared,
    png: Option<&Target>,
    pfm: &[Target],
    opts: &Options,
) -> Result<(), String> {
    let scene = r.scene(prepared);
    let start = Instant::now();
    if !scene.description.is_empty() {
        note(opts, &format!("{}: {}", scene.name, scene.description));
    }
    let image = r.render(prepared, &scene.camera, bar(opts, &scene.name));
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
            r.integrator(),
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
fn animation<R: Renderer>(
    r: &R,
    prepared: &R::Prepared,
    frames: &[Target],
    gif: &Target,
    dir: &Path,
    opts: &Options,
) -> Result<(), String> {
    let scene = r.scene(prepared);
    let start = Instant::now();
    let n = frames.len();
    let mut encoder = output::Gif::create(&gif.path, 80)?;
    for (i, frame) in frames.iter().enumerate() {
        let angle = std::f64::consts::TAU * i as f64 / n as f64;
        let camera = scene.camera.orbit(angle);
        let label = format!("{} {}/{}", scene.name, i + 1, n);
        let image = r.render(prepared, &camera, bar(opts, &label));
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

/// Loads one scene and checks its work and its outputs (`None`: the other renderer's scene,
/// skipped when rendering every shipped scene).
fn plan<R: Renderer>(
    r: &R,
    name: &str,
    single: bool,
    all: bool,
    opts: &Options,
) -> Result<Option<Job<R::Prepared>>, String> {
    let Some(scene) = load::<R>(name, opts, all)? else {
        return Ok(None);
    };
    let s = &scene.settings;
    limits::work(s.width, s.height, s.spp, opts.frames.unwrap_or(1))
        .map_err(|e| format!("{}: {e}", scene.name))?;
    let scene_name = scene.name.clone();
    let prepared = r.prepare(scene, &|m| note(opts, m))?;
    let out = opts.out.clone();
    if let Some(n) = opts.frames {
        let dir = match &out {
            Some(d) if single => d.clone(),
            Some(d) => d.join(&scene_name),
            None => PathBuf::from("out").join(&scene_name),
        };
        let dir = output::directory(&dir)?;
        let frames = (0..n)
            .map(|i| output::target(&dir.join(format!("{scene_name}_{i:04}.png")), Kind::Png))
            .collect::<Result<_, _>>()?;
        let gif = output::target(&dir.join(format!("{scene_name}.gif")), Kind::Gif)?;
        return Ok(Some(Job::Animation {
            scene: prepared,
            frames,
            gif,
            dir,
        }));
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
            let png = dir.join(format!("{scene_name}{suffix}.png"));
            let pfm = if all && !opts.compare_clip {
                vec![dir.join(format!("{scene_name}.pfm"))]
            } else {
                vec![]
            };
            (Some(png), pfm)
        }
    };
    pfm.extend(opts.pfm.clone());
    Ok(Some(Job::Still {
        png: png.map(|p| output::target(&p, Kind::Png)).transpose()?,
        pfm: pfm
            .iter()
            .map(|p| output::target(p, Kind::Pfm))
            .collect::<Result<_, _>>()?,
        scene: prepared,
    }))
}

/// Renders the scenes of `opts` (every shipped scene `r` takes when none is named).
pub fn run<R: Renderer>(r: &R, opts: &Options) -> Result<(), String> {
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
    let mut jobs = Vec::new();
    for name in &names {
        match plan(r, name, single, all, opts)? {
            Some(job) => jobs.push(job),
            None => note(
                opts,
                &format!(
                    "{name}: skipped, rendered by the example {} (cargo run --release \
                     --example {} -- {name})",
                    R::OTHER,
                    R::OTHER
                ),
            ),
        }
    }
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
            Job::Still { scene, png, pfm } => still(r, scene, png.as_ref(), pfm, opts)?,
            Job::Animation {
                scene,
                frames,
                gif,
                dir,
            } => animation(r, scene, frames, gif, dir, opts)?,
        }
    }
    if jobs.len() > 1 {
        note(
            opts,
            &format!(
                "{} scenes in {:.1} s",
                jobs.len(),
                start.elapsed().as_secs_f64()
            ),
        );
    }
    Ok(())
}
