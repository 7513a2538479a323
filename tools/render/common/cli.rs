//! Hand-written command-line parsing: the options both renderers take, and a hook for each
//! one's own ([`Extra`]).

use std::path::PathBuf;

use crate::colour::Colour;
use diffraction::color::Clip;

use crate::limits::{self, MAX_DEPTH, MAX_FRAMES, MAX_SIZE, MAX_SPP};

/// The options both renderers take, for their `--help` (after their own header and before
/// their own options).
pub const OPTIONS: &str = "\
OPTIONS:
    --width W          image width in pixels (1-16384; alone, keeps the scene's aspect ratio)
    --height H         image height in pixels (1-16384; width x height at most 16777216)
    --spp S            samples per pixel, stratified (1-4096; width x height x spp x frames
                       at most 4294967296 camera samples)
    --seed N           seed of the jitter (the same seed gives the same bytes)
    --strategy NAME    spectral evaluation: peaks (default), peaks-refined, paper, exact,
                       uniform:K (K <= 4096), gauss:K (K <= 512), auto or auto:ACCURACY
                       (ACCURACY in [1e-6, 1])
    --clip SCHEME      gamut clipping: clamp, intensity (default), constant
    --out PATH         one scene: the output file (.png, or .pfm for linear floats);
                       several scenes or --frames: the output directory (default out/)
    --pfm FILE         also write the linear, unclipped image as a PFM (one scene)
    --frames N         an animation of N frames (1-10000) orbiting the camera once around
                       its target: PATH/NAME_0000.png ... and PATH/NAME.gif
    --compare-clip     one picture of three panels: the render clipped with clamp,
                       intensity and constant (default file out/NAME-clipping.png)
    --dry-run          load the scenes, check the outputs and estimate the work (printed),
                       but prepare, render and write nothing
    --budget S         the work budget of a scene, seconds of one core (1-10000000; default
                       120, a minute on two cores): a scene estimated above it is refused
    --quiet            no progress bar and no messages
    -h, --help         this text
";

/// What both renderers promise about their outputs, for the end of their `--help`.
pub const OUTPUTS: &str = "
OUTPUTS:
    Every output is checked before anything is rendered: its extension, its directory, no
    two outputs on one file (whatever the spelling), none on an input of the run (a scene
    file, a texture). An existing output is replaced only if it is a regular file with write
    permission and one hard link (like cp without -f; the new file keeps its permissions);
    a symbolic link is followed (the file it names is replaced, the link stays), and a link
    to a missing file is refused. Every file is written under a temporary name and all are
    renamed into place together once all are complete, missing directories made then: a
    run that fails, at any step, leaves every existing file as it was and creates nothing.

WORK:
    Before anything is prepared or rendered, each scene's work is estimated (ray-object
    tests, shadow rays, colour evaluations, exposure scans, colour tables; --dry-run prints
    it) and a scene estimated above the budget (120 s of one core, a minute on two; --budget
    sets it) is refused, naming the largest part and the options or scene fields that reduce
    it (tools/render/common/budget.rs). The estimate is within 5x of the CPU time measured for
    every shipped scene (docs/work_budget.md).
";

/// The largest `--budget`, seconds of one core (about four months).
pub const MAX_BUDGET_S: u64 = 10_000_000;

/// The options of a render that both renderers take.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    /// The scenes named (none: every shipped scene the renderer takes).
    pub scenes: Vec<String>,
    /// `--width` (this and the next three replace the scene's `[render]` values).
    pub width: Option<u32>,
    /// `--height`.
    pub height: Option<u32>,
    /// `--spp`.
    pub spp: Option<u32>,
    /// `--seed`.
    pub seed: Option<u64>,
    /// `--strategy`: the default strategy of the scene's gratings replaced.
    pub strategy: Option<Colour>,
    /// `--clip`: the gamut clipping of the PNG.
    pub clip: Option<Clip>,
    /// `--max-depth`: the scene's `render.max_depth` replaced.
    pub max_depth: Option<u32>,
    /// `--out`: the output file of one scene, or the output directory.
    pub out: Option<PathBuf>,
    /// `--pfm`: a linear PFM besides the PNG (one scene).
    pub pfm: Option<PathBuf>,
    /// `--frames`: an orbit of this many frames instead of a still.
    pub frames: Option<u32>,
    /// `--compare-clip`: one picture of the three clipping schemes.
    pub compare_clip: bool,
    /// `--quiet`: no progress bar, no messages.
    pub quiet: bool,
    /// `--dry-run`: check and estimate only.
    pub dry_run: bool,
    /// `--budget`: the work budget, seconds of one core (default [`crate::budget::BUDGET_S`]).
    pub budget: Option<u64>,
}

/// A renderer's own arguments.
pub trait Extra: Default {
    /// Takes `arg` if it is this renderer's (`value` reads the flag's value), with the scenes
    /// named so far: `Ok(true)` when taken, `Ok(false)` to leave it to the common options.
    fn take(
        &mut self,
        arg: &str,
        value: &mut dyn FnMut() -> Result<String, String>,
        opts: &Options,
    ) -> Result<bool, String>;
}

/// What to do: print the help, or render with these options.
#[derive(Debug, Clone, PartialEq)]
pub enum Command<X> {
    /// `-h`, `--help`.
    Help,
    /// Render with the common options and the renderer's own.
    Render(Options, X),
}

/// `v` as an integer in [min, max], or an error naming the flag and the range.
pub fn int<T: std::str::FromStr + PartialOrd + std::fmt::Display>(
    flag: &str,
    v: &str,
    min: T,
    max: T,
) -> Result<T, String> {
    match v.parse::<T>() {
        Ok(n) if n >= min && n <= max => Ok(n),
        _ => Err(format!(
            "{flag}: expected an integer in [{min}, {max}], got \"{v}\""
        )),
    }
}

/// Parses the arguments (without the program name).
pub fn parse<X: Extra>(args: &[String]) -> Result<Command<X>, String> {
    let mut opts = Options::default();
    let mut extra = X::default();
    let mut i = 0;
    while i < args.len() {
        let arg = &args[i];
        i += 1;
        // --flag=value or --flag value.
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f, Some(v.to_string())),
            _ => (arg.as_str(), None),
        };
        let mut value = || -> Result<String, String> {
            if let Some(v) = inline.clone() {
                return Ok(v);
            }
            let v = args
                .get(i)
                .cloned()
                .ok_or_else(|| format!("{flag}: expected a value"))?;
            i += 1;
            Ok(v)
        };
        if extra.take(flag, &mut value, &opts)? {
            continue;
        }
        match flag {
            "-h" | "--help" => return Ok(Command::Help),
            "--quiet" | "-q" => opts.quiet = true,
            "--compare-clip" => opts.compare_clip = true,
            "--dry-run" => opts.dry_run = true,
            "--width" => opts.width = Some(int(flag, &value()?, 1, MAX_SIZE)?),
            "--height" => opts.height = Some(int(flag, &value()?, 1, MAX_SIZE)?),
            "--spp" => opts.spp = Some(int(flag, &value()?, 1, MAX_SPP)?),
            "--frames" => opts.frames = Some(int(flag, &value()?, 1, MAX_FRAMES)?),
            "--seed" => opts.seed = Some(int(flag, &value()?, 0, u64::MAX)?),
            "--budget" => opts.budget = Some(int(flag, &value()?, 1, MAX_BUDGET_S)?),
            "--max-depth" => opts.max_depth = Some(int(flag, &value()?, 0, MAX_DEPTH)?),
            "--strategy" => {
                let v = value()?;
                opts.strategy = Some(
                    limits::parse_strategy(&v)
                        .map_err(|e| format!("--strategy: {e}, got \"{v}\""))?,
                );
            }
            "--clip" => {
                let v = value()?;
                opts.clip = Some(v.parse().map_err(|e| format!("--clip: {e}, got \"{v}\""))?);
            }
            "--out" | "-o" => opts.out = Some(PathBuf::from(value()?)),
            "--pfm" => opts.pfm = Some(PathBuf::from(value()?)),
            f if f.starts_with('-') => return Err(format!("unknown option {f}")),
            scene => opts.scenes.push(scene.to_string()),
        }
    }
    if opts.frames.is_some() && opts.compare_clip {
        return Err("--frames and --compare-clip cannot be combined".into());
    }
    if opts.pfm.is_some() && (opts.scenes.len() != 1 || opts.frames.is_some()) {
        return Err("--pfm needs exactly one scene and no --frames".into());
    }
    Ok(Command::Render(opts, extra))
}
