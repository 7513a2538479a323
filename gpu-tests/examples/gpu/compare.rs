//! The GPU's picture against the reference tracer's: CIEDE2000 per pixel (the crate's
//! `color::Lab::delta_e2000`) between the two linear images as the PNG shows them (clipped with the
//! scene's rule), in CIELAB relative to the sRGB white.

use diffraction::color::{Clip, Lab, LinearSrgb, WhitePoint};

use crate::output::Image;

/// ΔE2000 over an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Difference {
    /// The mean over the pixels.
    pub mean: f64,
    /// The largest.
    pub max: f64,
    /// The fraction of pixels above 1.
    pub above_one: f64,
}

/// ΔE2000 between `a` and `b` (of the same size) clipped with `clip`.
pub fn difference(a: &Image, b: &Image, clip: Clip) -> Difference {
    assert_eq!((a.width, a.height), (b.width, b.height), "image sizes");
    let white = WhitePoint::new(LinearSrgb::new(1.0, 1.0, 1.0).to_xyz())
        .expect("the sRGB white is a white point");
    let lab = |c: glam::DVec3| -> Lab {
        LinearSrgb::new(c.x, c.y, c.z)
            .clip(clip)
            .to_xyz()
            .to_lab(white)
    };
    let (mut sum, mut max, mut above) = (0.0, 0.0f64, 0usize);
    for (p, q) in a.pixels.iter().zip(&b.pixels) {
        let e = lab(*p).delta_e2000(lab(*q));
        sum += e;
        max = max.max(e);
        above += (e > 1.0) as usize;
    }
    let n = a.pixels.len().max(1) as f64;
    Difference {
        mean: sum / n,
        max,
        above_one: above as f64 / n,
    }
}
