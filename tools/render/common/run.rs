//! One run of a renderer: the scenes named on the command line (or every shipped scene the
//! renderer takes) are loaded and their outputs checked, then prepared, then rendered into
//! temporary files that are renamed into place together when every one is complete
//! ([`crate::files`]): an error found at any step leaves every existing file as it was, and
//! one that can be known before rendering is reported before anything is rendered.

use std::path::{Path, PathBuf};
use std::time::Instant;

use crate::budget::Estimate;
use crate::camera::{progress_wanted, Camera};
use crate::cli::Options;
use crate::files::{self, Kind, Target, Transaction};
use crate::limits;
use crate::output::{self, Image};
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
    /// The work of rendering `frames` pictures of `scene` and of preparing it, before it is
    /// prepared ([`crate::budget`]).
    fn estimate(&self, scene: &Scene<Self::Physics>, frames: u32) -> Estimate;
    /// The scene of a prepared scene.
    fn scene<'a>(&self, prepared: &'a Self::Prepared) -> &'a Scene<Self::Physics>;
    /// Renders from `camera` with the scene's settings, with a progress bar of that label.
    fn render(&self, prepared: &Self::Prepared, camera: &Camera, progress: Option<&str>) -> Image;
    /// The integrator's name, for the summary of a render.
    fn integrator(&self) -> &'static str;
    /// Whether a run that names no scene renders `scene` (default: every scene it takes).
    fn renders_by_default(&self, _scene: &Scene<Self::Physics>) -> bool {
        true
    }
}

/// The renderers' directory (`tools/render`: `scenes/` and `assets/` are there): the including
/// package's manifest directory, or `DIFFRACTION_EXAMPLES_ROOT` at compile time (set by the build
/// script of the workspace member `gpu-tests`, which includes these files too).
pub const ROOT: &str = match option_env!("DIFFRACTION_EXAMPLES_ROOT") {
    Some(root) => root,
    None => env!("CARGO_MANIFEST_DIR"),
};

/// Where the shipped scenes live.
pub fn scenes_dir() -> PathBuf {
    Path::new(ROOT).join("scenes")
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
pub fn scene_path(arg: &str) -> Result<PathBuf, String> {
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
pub fn load<R: Renderer>(
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
                "{e}: render it with `cargo run --release -p diffraction-render --bin {} -- {arg}`",
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

/// Whether the file name of `p` ends in `.ext` (any case; also the bare `.png`, which is an
/// error later, not a directory).
fn has_extension(p: &Path, ext: &str) -> bool {
    p.file_name().is_some_and(|n| {
        n.to_string_lossy()
            .to_lowercase()
            .ends_with(&format!(".{ext}"))
    })
}

/// The outputs of one scene, checked.
enum Outputs {
    Still {
        png: Option<Target>,
        pfm: Vec<Target>,
    },
    Animation {
        frames: Vec<Target>,
        gif: Target,
    },
}

impl Outputs {
    fn targets(&self) -> Vec<&Target> {
        match self {
            Outputs::Still { png, pfm } => png.iter().chain(pfm).collect(),
            Outputs::Animation { frames, gif } => frames.iter().chain([gif]).collect(),
        }
    }
}

/// The progress bar's label, when one is wanted.
fn bar<'a>(opts: &Options, label: &'a str) -> Option<&'a str> {
    progress_wanted(opts.quiet).then_some(label)
}

/// Renders one still into staged PNG and/or PFM files.
fn still<R: Renderer>(
    r: &R,
    prepared: &R::Prepared,
    (png, pfm): (Option<&Target>, &[Target]),
    files: &mut Transaction,
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
        files.write(t, |w| output::png_to(w, &picture))?;
    }
    for t in pfm {
        files.write(t, |w| output::pfm_to(w, &image).map_err(|e| e.to_string()))?;
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

/// Renders one frame per target orbiting the camera once around its target, into staged
/// numbered PNGs and an animated GIF streamed frame by frame.
fn animation<R: Renderer>(
    r: &R,
    prepared: &R::Prepared,
    (frames, gif): (&[Target], &Target),
    files: &mut Transaction,
    opts: &Options,
) -> Result<(), String> {
    let scene = r.scene(prepared);
    let start = Instant::now();
    let n = frames.len();
    let mut staged_gif = files.create(gif)?;
    let fail = |e: String| format!("cannot write {}: {e}", gif.shown.display());
    let mut encoder = output::Gif::new(&mut staged_gif, 80).map_err(fail)?;
    for (i, frame) in frames.iter().enumerate() {
        let angle = std::f64::consts::TAU * i as f64 / n as f64;
        let camera = scene.camera.orbit(angle);
        let label = format!("{} {}/{}", scene.name, i + 1, n);
        let image = r.render(prepared, &camera, bar(opts, &label));
        let png = output::to_rgb8(&image, scene.settings.clip);
        files.write(frame, |w| output::png_to(w, &png))?;
        encoder.add(&png).map_err(fail)?;
    }
    encoder.finish().map_err(fail)?;
    files.close(staged_gif)?;
    let dir = frames[0].shown.parent().unwrap_or(Path::new("."));
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

/// The outputs of scene `name`: for `--frames`, a directory of frames and a GIF; for one scene
/// and a file name, exactly that file; otherwise a directory of NAME.png (and NAME.pfm when
/// rendering everything), and `--pfm`.
fn outputs(name: &str, single: bool, all: bool, opts: &Options) -> Result<Outputs, String> {
    let (out, flag) = match &opts.out {
        Some(out) => (out.clone(), "--out"),
        None => (PathBuf::from("out"), ""),
    };
    if let Some(n) = opts.frames {
        let dir = match &opts.out {
            Some(d) if single => files::directory(d, flag, "the frames of --frames")?,
            _ => files::directory(&out, flag, "the frames of --frames")?.join(name),
        };
        let frames = (0..n)
            .map(|i| files::target(&dir.join(format!("{name}_{i:04}.png")), Kind::Png, ""))
            .collect::<Result<_, _>>()?;
        let gif = files::target(&dir.join(format!("{name}.gif")), Kind::Gif, "")?;
        return Ok(Outputs::Animation { frames, gif });
    }
    let file_out = opts
        .out
        .as_ref()
        .filter(|p| single && (has_extension(p, "png") || has_extension(p, "pfm")));
    if let Some(p) = opts.out.as_ref().filter(|_| single && file_out.is_none()) {
        if p.extension().is_some() && !p.is_dir() {
            return Err(format!(
                "--out {}: expected a file name ending in .png or .pfm, or a directory",
                p.display()
            ));
        }
    }
    let suffix = if opts.compare_clip { "-clipping" } else { "" };
    let (png, mut pfm) = match file_out {
        Some(p) if has_extension(p, "pfm") => (None, vec![files::target(p, Kind::Pfm, "--out")?]),
        Some(p) => (Some(files::target(p, Kind::Png, "--out")?), vec![]),
        None => {
            let why = if single {
                "the pictures"
            } else {
                "the pictures of several scenes"
            };
            let dir = files::directory(&out, flag, why)?;
            let png = files::target(&dir.join(format!("{name}{suffix}.png")), Kind::Png, "")?;
            let pfm = if all && !opts.compare_clip {
                vec![files::target(
                    &dir.join(format!("{name}.pfm")),
                    Kind::Pfm,
                    "",
                )?]
            } else {
                vec![]
            };
            (Some(png), pfm)
        }
    };
    if let Some(p) = &opts.pfm {
        pfm.push(files::target(p, Kind::Pfm, "--pfm")?);
    }
    Ok(Outputs::Still { png, pfm })
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
    // Every scene is loaded, its work bounded and every output checked before anything is
    // prepared; everything is prepared before anything is rendered.
    let mut planned = Vec::new();
    for name in &names {
        let Some(scene) = load::<R>(name, opts, all)? else {
            note(
                opts,
                &format!(
                    "{name}: skipped, rendered by the binary {} (cargo run --release \
                     -p diffraction-render --bin {} -- {name})",
                    R::OTHER,
                    R::OTHER
                ),
            );
            continue;
        };
        if all && !r.renders_by_default(&scene) {
            note(
                opts,
                &format!(
                    "{name}: skipped (the example {}'s; name it to render it here too)",
                    R::OTHER
                ),
            );
            continue;
        }
        let s = &scene.settings;
        let frames = opts.frames.unwrap_or(1);
        limits::work(s.width, s.height, s.spp, frames)
            .map_err(|e| format!("{}: {e}", scene.name))?;
        let estimate = r.estimate(&scene, frames);
        let budget = opts.budget.map_or(crate::budget::BUDGET_S, |b| b as f64);
        estimate.check(&scene.name, budget)?;
        if opts.dry_run {
            println!(
                "{}: estimated work {} s of one core ({})",
                scene.name,
                crate::budget::short(estimate.seconds()),
                estimate
                    .parts
                    .iter()
                    .map(|p| format!("{} s for {}", crate::budget::short(p.ns * 1e-9), p.what))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        let outputs = outputs(&scene.name, single, all, opts)?;
        planned.push((scene, outputs, estimate.seconds()));
    }
    let targets: Vec<Target> = planned
        .iter()
        .flat_map(|(_, o, _)| o.targets())
        .cloned()
        .collect();
    let inputs: Vec<files::Input> = planned
        .iter()
        .flat_map(|(s, _, _)| s.inputs.iter().cloned())
        .collect();
    files::check(&targets, &inputs)?;
    if opts.dry_run {
        return Ok(());
    }
    let mut jobs = Vec::new();
    for (scene, outputs, estimate) in planned {
        let work = format!(
            "{}: estimated work {} s of one core",
            scene.name,
            crate::budget::short(estimate)
        );
        jobs.push((r.prepare(scene, &|m| note(opts, m))?, outputs));
        note(opts, &work);
    }
    let mut staged = Transaction::default();
    for (prepared, outputs) in &jobs {
        match outputs {
            Outputs::Still { png, pfm } => {
                still(r, prepared, (png.as_ref(), pfm), &mut staged, opts)?
            }
            Outputs::Animation { frames, gif } => {
                animation(r, prepared, (frames, gif), &mut staged, opts)?
            }
        }
    }
    staged.commit()?;
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
