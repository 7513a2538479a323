//! Encoding pictures: PNG (clipped, sRGB-encoded), PFM (linear floats), animated GIF, and the
//! side-by-side comparison of the clipping schemes. Where they are written is
//! [`crate::files`]'s.

use std::io::{BufWriter, Write};
use std::sync::{Arc, Mutex};

use diffraction::color::{Clip, LinearSrgb};
use image::{ImageEncoder, Rgb, RgbImage};

use crate::files::{Sink, Staged};
use crate::font;

/// A rendered image in linear sRGB (unclipped: spectral colours have negative components and
/// highlights exceed 1), rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// width × height colours, row by row.
    pub pixels: Vec<glam::DVec3>,
}

/// Clips every pixel with `clip` and encodes it to 8-bit sRGB.
pub fn to_rgb8(image: &Image, clip: Clip) -> RgbImage {
    let mut out = RgbImage::new(image.width, image.height);
    for (px, c) in out.pixels_mut().zip(&image.pixels) {
        let linear = LinearSrgb::new(c.x, c.y, c.z);
        *px = Rgb(linear.clip(clip).encode().to_rgb8());
    }
    out
}

/// A writer that keeps its first error where its owner can read it after the writer is gone
/// (the GIF encoder writes its trailer when dropped and drops the error).
#[derive(Debug)]
struct Shared {
    sink: Sink,
    error: Arc<Mutex<Option<String>>>,
}

impl Shared {
    fn keep<T>(&self, r: std::io::Result<T>) -> std::io::Result<T> {
        if let Err(e) = &r {
            if let Ok(mut slot) = self.error.lock() {
                slot.get_or_insert_with(|| e.to_string());
            }
        }
        r
    }
}

impl Write for Shared {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let r = self.sink.write(buf);
        self.keep(r)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let r = self.sink.flush();
        self.keep(r)
    }
}

/// Encodes an 8-bit sRGB picture as PNG into `w`.
pub fn png_to(w: &mut dyn Write, img: &RgbImage) -> Result<(), String> {
    let mut w = std::io::BufWriter::new(w);
    image::codecs::png::PngEncoder::new(&mut w)
        .write_image(
            img.as_raw(),
            img.width(),
            img.height(),
            image::ExtendedColorType::Rgb8,
        )
        .map_err(|e| e.to_string())?;
    w.flush().map_err(|e| e.to_string())
}

/// The PFM header of an image.
fn pfm_header(image: &Image) -> String {
    format!("PF\n{} {}\n-1.0\n", image.width, image.height)
}

/// Writes the linear, unclipped image as a little-endian colour PFM into `w`, rows from the
/// bottom (as the format wants), without building the whole file in memory. Negative
/// components (out-of-gamut spectral colours) are kept.
pub fn pfm_to(w: &mut dyn Write, image: &Image) -> std::io::Result<()> {
    w.write_all(pfm_header(image).as_bytes())?;
    let mut row_bytes = Vec::with_capacity(image.width as usize * 12);
    for row in image.pixels.chunks(image.width as usize).rev() {
        row_bytes.clear();
        for c in row {
            for v in [c.x, c.y, c.z] {
                row_bytes.extend_from_slice(&(v as f32).to_le_bytes());
            }
        }
        w.write_all(&row_bytes)?;
    }
    Ok(())
}

/// The PFM of an image, in memory.
#[cfg(test)]
pub fn pfm_bytes(image: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    pfm_to(&mut out, image).expect("writing to memory");
    out
}

/// An animated GIF, looping forever, encoded one frame at a time (no frame is kept) into a
/// staged file of a [`Transaction`](crate::files::Transaction).
pub struct Gif {
    encoder: Option<image::codecs::gif::GifEncoder<BufWriter<Shared>>>,
    error: Arc<Mutex<Option<String>>>,
    delay_ms: u32,
}

impl Gif {
    /// A GIF written into `staged`, `delay_ms` between frames.
    pub fn new(staged: &mut Staged, delay_ms: u32) -> Result<Gif, String> {
        use image::codecs::gif::{GifEncoder, Repeat};
        // The encoder writes through a second handle on the staged file.
        let sink = staged
            .writer()
            .get_ref()
            .try_clone()
            .map_err(|e| e.to_string())?;
        let error = Arc::new(Mutex::new(None));
        let shared = Shared {
            sink,
            error: error.clone(),
        };
        let mut encoder = GifEncoder::new_with_speed(BufWriter::new(shared), 10);
        encoder
            .set_repeat(Repeat::Infinite)
            .map_err(|e| e.to_string())?;
        Ok(Gif {
            encoder: Some(encoder),
            error,
            delay_ms,
        })
    }

    /// Appends a frame.
    pub fn add(&mut self, frame: &RgbImage) -> Result<(), String> {
        let rgba = image::DynamicImage::ImageRgb8(frame.clone()).to_rgba8();
        let delay = image::Delay::from_numer_denom_ms(self.delay_ms, 1);
        let frame = image::Frame::from_parts(rgba, 0, 0, delay);
        let encoder = self.encoder.as_mut().expect("not finished");
        encoder.encode_frame(frame).map_err(|e| e.to_string())
    }

    /// Writes the trailer and checks that every byte reached the file.
    pub fn finish(mut self) -> Result<(), String> {
        drop(self.encoder.take()); // writes the trailer and flushes
        match self.error.lock().ok().and_then(|mut e| e.take()) {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
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
