//! Writing pictures: PNG (clipped, sRGB-encoded), PFM (linear floats), animated GIF, and the
//! side-by-side comparison of the clipping schemes.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

use diffraction::color::{Clip, LinearSrgb};
use image::{Rgb, RgbImage};

use crate::font;
use crate::render::Image;

/// Clips every pixel with `clip` and encodes it to 8-bit sRGB.
pub fn to_rgb8(image: &Image, clip: Clip) -> RgbImage {
    let mut out = RgbImage::new(image.width, image.height);
    for (px, c) in out.pixels_mut().zip(&image.pixels) {
        let linear = LinearSrgb::new(c.x, c.y, c.z);
        *px = Rgb(linear.clip(clip).encode().to_rgb8());
    }
    out
}

fn create(path: &Path) -> Result<BufWriter<File>, String> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    }
    File::create(path)
        .map(BufWriter::new)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

pub fn write_png(path: &Path, img: &RgbImage) -> Result<(), String> {
    let mut w = create(path)?;
    img.write_to(&mut w, image::ImageFormat::Png)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// The linear, unclipped image as a little-endian colour PFM (rows from the bottom, as the
/// format wants). Negative components (out-of-gamut spectral colours) are kept.
pub fn pfm_bytes(image: &Image) -> Vec<u8> {
    let mut out = format!("PF\n{} {}\n-1.0\n", image.width, image.height).into_bytes();
    out.reserve(image.pixels.len() * 12);
    for row in image.pixels.chunks(image.width as usize).rev() {
        for c in row {
            for v in [c.x, c.y, c.z] {
                out.extend_from_slice(&(v as f32).to_le_bytes());
            }
        }
    }
    out
}

pub fn write_pfm(path: &Path, image: &Image) -> Result<(), String> {
    let mut w = create(path)?;
    w.write_all(&pfm_bytes(image))
        .and_then(|()| w.flush())
        .map_err(|e| format!("cannot write {}: {e}", path.display()))
}

/// An animated GIF, looping forever, `delay_ms` per frame.
pub fn write_gif(path: &Path, frames: &[RgbImage], delay_ms: u32) -> Result<(), String> {
    use image::codecs::gif::{GifEncoder, Repeat};
    let w = create(path)?;
    let mut enc = GifEncoder::new_with_speed(w, 10);
    let err = |e: image::ImageError| format!("cannot write {}: {e}", path.display());
    enc.set_repeat(Repeat::Infinite).map_err(err)?;
    for f in frames {
        let rgba = image::DynamicImage::ImageRgb8(f.clone()).to_rgba8();
        let frame =
            image::Frame::from_parts(rgba, 0, 0, image::Delay::from_numer_denom_ms(delay_ms, 1));
        enc.encode_frame(frame).map_err(err)?;
    }
    Ok(())
}

/// The same linear image clipped with each scheme, side by side, each panel captioned with the
/// scheme's name.
pub fn clip_panels(image: &Image) -> RgbImage {
    let (w, h) = (image.width, image.height);
    let caption = 20;
    let gap = 4;
    let n = Clip::ALL.len() as u32;
    let mut out = RgbImage::from_pixel(n * w + (n - 1) * gap, h + caption, Rgb([24, 24, 24]));
    for (i, clip) in Clip::ALL.into_iter().enumerate() {
        let x0 = i as u32 * (w + gap);
        let panel = to_rgb8(image, clip);
        image::imageops::replace(&mut out, &panel, x0 as i64, caption as i64);
        let label = match clip {
            Clip::Clamp => "CLAMP",
            Clip::Intensity => "INTENSITY SCALING",
            _ => "CONSTANT INTENSITY",
        };
        let scale = 2;
        let tw = font::text_width(label, scale);
        font::draw_text(
            &mut out,
            label,
            x0 + w.saturating_sub(tw) / 2,
            3,
            scale,
            [235, 235, 235],
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn pfm_has_header_and_bottom_up_rows() {
        let img = Image {
            width: 2,
            height: 2,
            pixels: vec![
                DVec3::splat(1.0),
                DVec3::splat(2.0),
                DVec3::splat(-3.0),
                DVec3::splat(4.0),
            ],
        };
        let bytes = pfm_bytes(&img);
        let header = b"PF\n2 2\n-1.0\n";
        assert_eq!(&bytes[..header.len()], header);
        assert_eq!(bytes.len(), header.len() + 4 * 12);
        let first = f32::from_le_bytes(bytes[header.len()..header.len() + 4].try_into().unwrap());
        assert_eq!(first, -3.0); // the bottom row comes first
    }
}
