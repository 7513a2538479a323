//! Hand-written command-line parsing.

use std::path::PathBuf;

use diffraction::color::Clip;
use diffraction::spectrum::Strategy;

use crate::limits::{self, MAX_FRAMES, MAX_SIZE, MAX_SPP};

pub const USAGE: &str = "\
raytrace: the diffraction crate's reference ray tracer (Agu & Hill, figures 4-6)

USAGE:
    raytrace [SCENE...] [OPTIONS]
    raytrace make-label [--out FILE]

With no SCENE, renders every scene of examples/scenes into out/ (NAME.png and the linear
NAME.pfm). SCENE is a shipped scene's name (fig4a, fig4b, fig5a, fig5b, fig6) or a path to a
.toml scene file.

OPTIONS:
    --width W          image width in pixels (1-16384; alone, keeps the scene's aspect ratio)
    --height H         image height in pixels (1-16384; width x height at most 16777216)
    --spp S            samples per pixel, stratified (1-4096; width x height x spp x frames
                       at most 4294967296 camera samples)
    --seed N           seed of the jitter (the same seed gives the same bytes)
    --strategy NAME    spectral evaluation: peaks (default), peaks-refined, paper, exact,
                       uniform:K (K <= 4096), gauss:K (K <= 512), auto or auto:ACCURACY
                       (ACCURACY in [1e-6, 1])
    --filter NAME      diffraction colour of the paper's model: none (default, at each
                       sample's u), footprint (the mean over the pixel footprint's u and the
                       light's size, from a colour table per grating built at load) or point
                       (the table at each sample's u)
    --clip SCHEME      gamut clipping: clamp, intensity (default), constant
    --integrator NAME  whitted (default) or path (spectral path tracing with MIS; needs a
                       scene with a [radiometry] table, e.g. cd_area_light)
    --max-depth D      bounces: mirror recursion (whitted) or path length (path; 1 = direct
                       light only), 0-64
    --out PATH         one scene: the output file (.png, or .pfm for linear floats);
                       several scenes or --frames: the output directory (default out/)
    --pfm FILE         also write the linear, unclipped image as a PFM (one scene)
    --frames N         an animation of N frames (1-10000) orbiting the camera once around
                       its target: PATH/NAME_0000.png ... and PATH/NAME.gif
    --compare-clip     one picture of three panels: the render clipped with clamp,
                       intensity and constant (default file out/NAME-clipping.png)
    --quiet            no progress bar and no messages
    -h, --help         this text

Every output path is checked before rendering (extension, directory, writable, no two
outputs on one file). Each file is written under a temporary name beside it and renamed into
place when complete, so a failed run leaves existing files as they were.

make-label writes the can label (default examples/assets/label.png).
";

/// What to do.
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Help,
    MakeLabel { out: Option<PathBuf> },
    Render(Options),
}

/// The options of a render.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Options {
    pub scenes: Vec<String>,
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    pub seed: Option<u64>,
    pub strategy: Option<Strategy>,
    pub clip: Option<Clip>,
    pub integrator: crate::path::Integrator,
    pub max_depth: Option<u32>,
    pub out: Option<PathBuf>,
    pub pfm: Option<PathBuf>,
    pub frames: Option<u32>,
    pub compare_clip: bool,
    pub filter: crate::footprint::Filter,
    pub quiet: bool,
}

fn int<T: std::str::FromStr + PartialOrd + std::fmt::Display>(
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
pub fn parse(args: &[String]) -> Result<Command, String> {
    let mut opts = Options::default();
    let mut make_label = false;
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
        match flag {
            "-h" | "--help" => return Ok(Command::Help),
            "--quiet" | "-q" => opts.quiet = true,
            "--compare-clip" => opts.compare_clip = true,
            "--width" => opts.width = Some(int(flag, &value()?, 1, MAX_SIZE)?),
            "--height" => opts.height = Some(int(flag, &value()?, 1, MAX_SIZE)?),
            "--spp" => opts.spp = Some(int(flag, &value()?, 1, MAX_SPP)?),
            "--frames" => opts.frames = Some(int(flag, &value()?, 1, MAX_FRAMES)?),
            "--seed" => opts.seed = Some(int(flag, &value()?, 0, u64::MAX)?),
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
            "--filter" => {
                let v = value()?;
                opts.filter = v
                    .parse()
                    .map_err(|e| format!("--filter: {e}, got \"{v}\""))?;
            }
            "--integrator" => {
                let v = value()?;
                opts.integrator = v
                    .parse()
                    .map_err(|e| format!("--integrator: {e}, got \"{v}\""))?;
            }
            "--max-depth" => {
                opts.max_depth = Some(int(flag, &value()?, 0, crate::limits::MAX_DEPTH)?)
            }
            "--out" | "-o" => opts.out = Some(PathBuf::from(value()?)),
            "--pfm" => opts.pfm = Some(PathBuf::from(value()?)),
            "make-label" if opts.scenes.is_empty() && !make_label => make_label = true,
            f if f.starts_with('-') => return Err(format!("unknown option {f}")),
            scene => opts.scenes.push(scene.to_string()),
        }
    }
    if make_label {
        if !opts.scenes.is_empty() {
            return Err("make-label takes no scene".into());
        }
        return Ok(Command::MakeLabel { out: opts.out });
    }
    if opts.frames.is_some() && opts.compare_clip {
        return Err("--frames and --compare-clip cannot be combined".into());
    }
    if opts.pfm.is_some() && (opts.scenes.len() != 1 || opts.frames.is_some()) {
        return Err("--pfm needs exactly one scene and no --frames".into());
    }
    Ok(Command::Render(opts))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(s: &str) -> Vec<String> {
        s.split_whitespace().map(String::from).collect()
    }

    #[test]
    fn options_parse() {
        let Command::Render(o) = parse(&args(
            "fig4a --width 64 --spp=2 --strategy paper --clip constant --out a.png",
        ))
        .unwrap() else {
            panic!()
        };
        assert_eq!(o.scenes, ["fig4a"]);
        assert_eq!((o.width, o.spp), (Some(64), Some(2)));
        assert_eq!(o.strategy, Some(Strategy::PaperPeaks));
        assert_eq!(o.clip, Some(Clip::ConstantIntensity));
        assert_eq!(o.filter, crate::footprint::Filter::None);
        let Command::Render(o) = parse(&args("fig6 --filter footprint")).unwrap() else {
            panic!()
        };
        assert_eq!(o.filter, crate::footprint::Filter::Footprint);
        assert_eq!(parse(&args("--help")).unwrap(), Command::Help);
        assert_eq!(
            parse(&args("make-label")).unwrap(),
            Command::MakeLabel { out: None }
        );
    }

    #[test]
    fn absurd_values_are_refused() {
        for bad in [
            "--width 20000",
            "--height 0",
            "--spp 5000",
            "--frames 10001",
            "--width -3",
            "--strategy uniform:0",
            "--clip gamma",
            "--filter box",
            "--bogus",
            "--width",
        ] {
            let e = parse(&args(bad)).unwrap_err();
            assert!(
                e.starts_with(bad.split_whitespace().next().unwrap())
                    || e.contains("unknown option"),
                "{bad}: {e}"
            );
        }
    }
}
