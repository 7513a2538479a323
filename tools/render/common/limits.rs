//! The tracer's documented limits: every size, count and scene value is checked against these
//! before anything is allocated or rendered, so that a run's memory and work are bounded and
//! every accepted value renders finite colours.
//!
//! Work: a run traces at most [`MAX_SAMPLES`] camera samples per scene (width × height × spp ×
//! frames); each sample follows at most [`MAX_DEPTH`] mirror bounces and casts at most
//! [`MAX_SHADOW_RAYS`] shadow rays per hit, each tested against at most [`MAX_OBJECTS`] objects.
//! Loading a scene reads at most [`MAX_SCENE_BYTES`] and decodes at most [`MAX_TEXTURE_PIXELS`];
//! the exposure scan of each distinct grating costs `EXPOSURE_SCAN` colour evaluations, each
//! bounded by the period limit [`PERIOD_NM`].
//!
//! Memory: the linear image takes 24 bytes a pixel and the 8-bit picture 3 (9 for
//! `--compare-clip`), at most [`MAX_PIXELS`] pixels: about 0.5 GB at the limit. An animation keeps
//! one frame at a time (the GIF is streamed). Textures take 24 bytes a texel.

use std::fmt::Display;

use diffraction::spectrum::StrategyKind;

use crate::colour::Colour;

use crate::diagnostics::FieldError;

/// Largest image width or height, pixels.
pub const MAX_SIZE: u32 = 16384;
/// Largest number of pixels of one image (width × height): 4096 × 4096.
pub const MAX_PIXELS: u64 = 1 << 24;
/// Largest number of samples per pixel.
pub const MAX_SPP: u32 = 4096;
/// Largest number of camera samples of one scene's run: width × height × spp × frames
/// (4.3·10⁹, e.g. 1920 × 1080 at 2048 spp).
pub const MAX_SAMPLES: u64 = 1 << 32;
/// Largest number of animation frames.
pub const MAX_FRAMES: u32 = 10_000;
/// Largest recursion depth of mirror reflection.
pub const MAX_DEPTH: u32 = 64;
/// Largest number of shadow samples of one light.
pub const MAX_LIGHT_SAMPLES: u32 = 1024;
/// Largest number of shadow rays from one hit: the sum of every light's samples.
pub const MAX_SHADOW_RAYS: u64 = 4096;
/// Largest number of objects, and of lights.
pub const MAX_OBJECTS: usize = 10_000;
/// Largest number of distinct grating materials (each costs one exposure scan to load).
pub const MAX_GRATINGS: usize = 256;
/// Largest scene file, bytes (4 MiB: about 20 000 commented objects).
pub const MAX_SCENE_BYTES: u64 = 4 << 20;
/// Largest efficiency table file a grating's `efficiency` reads, bytes (the shipped presets'
/// JSON are 31-124 kB; the library's reader keeps its memory within the table's bounds
/// whatever the file). Its type and size are checked before it is opened.
pub const MAX_TABLE_BYTES: u64 = 16 << 20;
/// Largest number of texels of all of a scene's image textures together (4096 × 4096),
/// checked from each PNG's header before it is decoded.
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 24;
/// Largest number of wavelengths of `uniform:K`.
pub const MAX_UNIFORM_SAMPLES: u32 = 4096;
/// Largest number of sub-intervals of `gauss:K` (8 wavelengths each).
pub const MAX_GAUSS_INTERVALS: u32 = 512;
/// The accuracies `auto:ACCURACY` accepts (relative): finer requests can cost unbounded
/// work in the peak search, coarser ones mean nothing.
pub const AUTO_ACCURACY: Range = Range::new(1e-6, 1.0);

/// A closed range of accepted values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The smallest accepted value.
    pub min: f64,
    /// The largest accepted value.
    pub max: f64,
}

impl Range {
    /// The range [min, max].
    pub const fn new(min: f64, max: f64) -> Range {
        Range { min, max }
    }

    /// Whether `v` lies in the range (false for NaN).
    pub fn contains(&self, v: f64) -> bool {
        v >= self.min && v <= self.max // false for NaN
    }
}

/// Coordinates of points and components of directions, world units: |x| ≤ 10⁶, so that
/// distances, products and the image's colours stay far from overflow.
pub const COORDINATE: Range = Range::new(-1e6, 1e6);
/// Scale factors of an object, per axis.
pub const SCALE: Range = Range::new(1e-6, 1e6);
/// Lengths of textures and fields (ring spacing, plank sizes, cell size, light radius), world
/// units; plank sizes and the light radius may also be 0 (none).
pub const LENGTH: Range = Range::new(1e-6, 1e6);
/// Angles in degrees (rotations, grating angles and twists).
pub const ANGLE_DEG: Range = Range::new(-360.0, 360.0);
/// The camera's vertical field of view, degrees.
pub const FOV_DEG: Range = Range::new(0.01, 179.0);
/// Colour components and light intensities (linear sRGB).
pub const COLOR: Range = Range::new(0.0, 1e6);
/// The coefficients of eq. 12 (k_a, k_d, k_diffraction) and the wood's turbulence.
pub const COEFFICIENT: Range = Range::new(0.0, 1e3);
/// Fractions: mirror reflection, reflectance, the binary profile's grooved fraction.
pub const FRACTION: Range = Range::new(0.0, 1.0);
/// The grating period, nm: from 10 nm (no order propagates below λ_min/2 = 180 nm, so finer
/// gratings only show the mirror) to 0.1 mm, where about 300 orders lie in the visible band
/// at grazing angles and each colour evaluation still takes microseconds.
pub const PERIOD_NM: Range = Range::new(10.0, 1e5);
/// The line density, lines per mm (10⁶ / [`PERIOD_NM`]).
pub const LINES_PER_MM: Range = Range::new(10.0, 1e5);
/// The slit width, nm (and at most the period).
pub const SLIT_WIDTH_NM: Range = Range::new(1e-3, 1e5);
/// The number of coherently lit slits N of the paper's model.
pub const SLITS: Range = Range::new(1.0, 1e9);
/// The number of coherently lit slits N of the radiometric grating (the crate's `u32`).
pub const RADIOMETRIC_SLITS: u64 = u32::MAX as u64;
/// Thorman's lobe width, in u.
pub const LOBE_WIDTH: Range = Range::new(1e-6, 1.0);
/// Stam's groove depth (or sine amplitude), nm.
pub const DEPTH_NM: Range = Range::new(0.0, 1e4);
/// Stam's coherence width, nm (and at least the period).
pub const COHERENCE_NM: Range = Range::new(10.0, 1e8);
/// The largest exposure (the scale that brings a grating's brightest diffracted colour to
/// Y = 1): about 2·N for the Agu-Hill model, so 10¹² leaves room for N = 10⁹; a grating with
/// (almost) no visible diffracted light is not amplified beyond it.
pub const MAX_EXPOSURE: f64 = 1e12;

/// A short form of a limit for messages: `1e6`, `0.01`, `360`.
pub fn short(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// `v` if it lies in `range`, else an error at `path` that names the range and the value.
pub fn check(path: &str, v: f64, range: Range) -> Result<f64, FieldError> {
    if range.contains(v) {
        Ok(v)
    } else {
        Err(FieldError::new(
            path,
            format!(
                "expected a number in [{}, {}], got {}",
                short(range.min),
                short(range.max),
                short(v)
            ),
        ))
    }
}

/// `v` if it is 0 or lies in `range`.
pub fn zero_or(path: &str, v: f64, range: Range) -> Result<f64, FieldError> {
    if v == 0.0 {
        return Ok(v);
    }
    check(path, v, range).map_err(|e| FieldError::new(e.path, format!("{} (or 0)", e.message)))
}

/// The documented range of an integer field of a scene file (`objects[2].material.slits`),
/// for the messages of values that are not integers of its type at all (`-1`, 2³², 2⁶⁴,
/// `1e3`); `model` is the grating model of a `slits` field.
pub fn integer_range(field: &str, model: Option<&str>) -> Option<(u64, u64)> {
    let key = field.rsplit('.').next()?;
    let table = field.strip_suffix(key)?.trim_end_matches('.');
    let in_array = |name: &str| {
        table
            .strip_prefix(name)
            .and_then(|r| r.strip_prefix('['))
            .and_then(|r| r.split(']').next())
            .is_some_and(|i| i.bytes().all(|b| b.is_ascii_digit()))
    };
    Some(match (table, key) {
        ("render", "width" | "height") => (1, MAX_SIZE as u64),
        ("render", "spp") => (1, MAX_SPP as u64),
        ("render", "max_depth") => (0, MAX_DEPTH as u64),
        ("render", "seed") => (0, u64::MAX),
        (_, "samples") if in_array("lights") => (1, MAX_LIGHT_SAMPLES as u64),
        (_, "slits") if in_array("objects") && table.ends_with("].material") => match model {
            Some("radiometric") => (1, RADIOMETRIC_SLITS),
            _ => (1, SLITS.max as u64),
        },
        _ => return None,
    })
}

/// An integer count in [min, max].
pub fn count<T: PartialOrd + Display + Copy>(
    path: &str,
    v: T,
    min: T,
    max: T,
) -> Result<T, FieldError> {
    if v >= min && v <= max {
        Ok(v)
    } else {
        Err(FieldError::new(
            path,
            format!("expected an integer in [{min}, {max}], got {v}"),
        ))
    }
}

/// Parses a colour rule (`paper` or a strategy name) and checks it against the work limits,
/// naming the limit when a count or an accuracy is out of range.
pub fn parse_strategy(s: &str) -> Result<Colour, String> {
    // A count of any length: digits beyond u64 are above every limit too.
    let above = |k: &str, max: u32| {
        !k.is_empty()
            && k.bytes().all(|b| b.is_ascii_digit())
            && k.parse::<u64>().map_or(true, |k| k > max as u64)
    };
    match s.split_once(':') {
        Some(("uniform", k)) if above(k, MAX_UNIFORM_SAMPLES) => {
            return Err(format!(
                "uniform:K takes at most {MAX_UNIFORM_SAMPLES} wavelengths"
            ))
        }
        Some(("gauss", k)) if above(k, MAX_GAUSS_INTERVALS) => {
            return Err(format!(
                "gauss:K takes at most {MAX_GAUSS_INTERVALS} intervals"
            ))
        }
        _ => {}
    }
    s.parse::<Colour>()
        .map_err(|e| e.to_string())
        .and_then(strategy)
}

/// A colour rule within the work limits: `uniform:K` with K ≤ [`MAX_UNIFORM_SAMPLES`],
/// `gauss:K` with K ≤ [`MAX_GAUSS_INTERVALS`], `auto:ACCURACY` in [`AUTO_ACCURACY`].
pub fn strategy(c: Colour) -> Result<Colour, String> {
    let Colour::Integral(s) = c else {
        return Ok(c);
    };
    match s.kind() {
        StrategyKind::Uniform { samples } if samples > MAX_UNIFORM_SAMPLES => Err(format!(
            "uniform:K takes at most {MAX_UNIFORM_SAMPLES} wavelengths"
        )),
        StrategyKind::GaussLegendre { intervals } if intervals > MAX_GAUSS_INTERVALS => Err(
            format!("gauss:K takes at most {MAX_GAUSS_INTERVALS} intervals"),
        ),
        StrategyKind::Auto { accuracy } if !AUTO_ACCURACY.contains(accuracy) => Err(format!(
            "auto:ACCURACY takes an accuracy in [{}, {}]",
            short(AUTO_ACCURACY.min),
            short(AUTO_ACCURACY.max),
        )),
        _ => Ok(c),
    }
}

/// The pixels of an image, or an error when they pass [`MAX_PIXELS`].
pub fn pixels(width: u32, height: u32) -> Result<u64, String> {
    let pixels = width as u64 * height as u64;
    if pixels > MAX_PIXELS {
        return Err(format!(
            "{width} x {height} = {pixels} pixels, more than the limit of {MAX_PIXELS}"
        ));
    }
    Ok(pixels)
}

/// The camera samples of a run of `frames` images of width × height at spp samples, or an error
/// when they pass [`MAX_PIXELS`] or [`MAX_SAMPLES`].
pub fn work(width: u32, height: u32, spp: u32, frames: u32) -> Result<u64, String> {
    let pixels = pixels(width, height)?;
    let samples = pixels * spp as u64 * frames as u64; // < 2⁶⁴: 2²⁴ · 2¹² · 2¹⁴
    if samples > MAX_SAMPLES {
        return Err(format!(
            "{width} x {height} pixels x {spp} spp{} = {samples} camera samples, more than the \
             limit of {MAX_SAMPLES}",
            if frames > 1 {
                format!(" x {frames} frames")
            } else {
                String::new()
            }
        ));
    }
    Ok(samples)
}

// The stratification handles every count the limits let through.
const _: () = assert!(MAX_SPP <= crate::sampling::MAX_STRATA_SAMPLES);
const _: () = assert!(MAX_LIGHT_SAMPLES <= crate::sampling::MAX_STRATA_SAMPLES);
