//! Writing pictures: PNG (clipped, sRGB-encoded), PFM (linear floats), animated GIF, and the
//! side-by-side comparison of the clipping schemes.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use diffraction::color::{Clip, LinearSrgb};
use image::{ImageEncoder, Rgb, RgbImage};

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

/// The kinds of output file, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// An 8-bit sRGB picture.
    Png,
    /// The linear image in 32-bit floats.
    Pfm,
    /// An animation.
    Gif,
}

impl Kind {
    /// The file name's extension.
    pub fn extension(self) -> &'static str {
        match self {
            Kind::Png => "png",
            Kind::Pfm => "pfm",
            Kind::Gif => "gif",
        }
    }
}

/// An output file checked before rendering: its extension fits its kind, its directory exists
/// (created if missing) and takes new files, and it is not something other than a regular
/// file. `path` is where it goes after normalisation (absolute, symbolic links resolved), so
/// that two names of one file compare equal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    /// The name the user gave.
    pub shown: PathBuf,
    /// Where it is written (normalised).
    pub path: PathBuf,
    /// What it holds.
    pub kind: Kind,
}

/// Checks an output file before anything is rendered (see [`Target`]).
pub fn target(path: &Path, kind: Kind) -> Result<Target, String> {
    let shown = path.display();
    if !path
        .extension()
        .is_some_and(|x| x.eq_ignore_ascii_case(kind.extension()))
    {
        return Err(format!(
            "{shown}: expected a file name ending in .{}",
            kind.extension()
        ));
    }
    let name = path
        .file_name()
        .ok_or_else(|| format!("{shown}: expected a file name"))?;
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| {
        format!(
            "{shown}: cannot create the directory {}: {e}",
            dir.display()
        )
    })?;
    let mut resolved = dir
        .canonicalize()
        .map_err(|e| {
            format!(
                "{shown}: cannot resolve the directory {}: {e}",
                dir.display()
            )
        })?
        .join(name);
    if let Ok(meta) = std::fs::metadata(&resolved) {
        if !meta.is_file() {
            return Err(format!(
                "{shown}: exists and is not a regular file, so it is not replaced"
            ));
        }
        // A symbolic link: the file it names is replaced, the link stays.
        resolved = resolved
            .canonicalize()
            .map_err(|e| format!("{shown}: cannot resolve: {e}"))?;
    }
    // Writable: a temporary file can be made beside it (and is removed at once).
    drop(AtomicFile::create(&resolved).map_err(|e| format!("{shown}: {e}"))?);
    Ok(Target {
        shown: path.to_path_buf(),
        path: resolved,
        kind,
    })
}

/// An output directory (of frames, or of several scenes' pictures): created if missing; an
/// existing path must be a directory.
pub fn directory(dir: &Path) -> Result<PathBuf, String> {
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "{}: not a directory (give a directory, or one scene and a file name ending in \
             .png or .pfm)",
            dir.display()
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    Ok(dir.to_path_buf())
}

/// Refuses two outputs on one file, after normalisation.
pub fn distinct(targets: &[Target]) -> Result<(), String> {
    let mut seen: std::collections::HashMap<&Path, &Target> = std::collections::HashMap::new();
    for a in targets {
        if let Some(b) = seen.insert(&a.path, a) {
            return Err(format!(
                "{} and {} are the same file ({}): refusing to write two outputs on it",
                b.shown.display(),
                a.shown.display(),
                a.path.display()
            ));
        }
    }
    Ok(())
}

/// A file written beside its destination under a temporary name and renamed into place by
/// [`AtomicFile::commit`] once complete and synced: a failed or interrupted write leaves the
/// destination as it was. Dropped without a commit, the temporary file is removed.
#[derive(Debug)]
pub struct AtomicFile {
    target: PathBuf,
    tmp: PathBuf,
    writer: Option<BufWriter<File>>,
}

/// A writer that keeps its first error where its owner can read it after the writer is gone
/// (the GIF encoder writes its trailer when dropped and drops the error).
#[derive(Debug)]
struct Shared {
    file: File,
    error: std::sync::Arc<std::sync::Mutex<Option<String>>>,
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
        let r = self.file.write(buf);
        self.keep(r)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let r = self.file.flush();
        self.keep(r)
    }
}

impl AtomicFile {
    /// A new temporary file in the directory of `target` (the name starts with a dot and ends
    /// in `.tmp`).
    pub fn create(target: &Path) -> Result<AtomicFile, String> {
        static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let dir = target.parent().unwrap_or(Path::new("."));
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let tmp = dir.join(format!(".{name}.{}-{n}.tmp", std::process::id()));
        let file = File::options()
            .write(true)
            .create_new(true)
            .open(&tmp)
            .map_err(|e| format!("cannot create a file in {}: {e}", dir.display()))?;
        Ok(AtomicFile {
            target: target.to_path_buf(),
            tmp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// Where the content goes.
    pub fn writer(&mut self) -> &mut BufWriter<File> {
        self.writer.as_mut().expect("written before commit")
    }

    /// Flushes, syncs and renames the file into place.
    pub fn commit(mut self) -> Result<(), String> {
        let shown = self.target.display().to_string();
        let mut w = self.writer.take().expect("committed once");
        let fail = |e: std::io::Error| format!("cannot write {shown}: {e}");
        w.flush().map_err(fail)?;
        let file = w.into_inner().map_err(|e| fail(e.into_error()))?;
        file.sync_all().map_err(fail)?;
        drop(file);
        std::fs::rename(&self.tmp, &self.target).map_err(fail)?;
        self.tmp = PathBuf::new();
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if !self.tmp.as_os_str().is_empty() {
            self.writer = None;
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Writes a file with `write` through an [`AtomicFile`]: on any error the destination keeps
/// its old content.
pub fn write_atomic(
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), String>,
) -> Result<(), String> {
    let mut file = AtomicFile::create(target)?;
    write(file.writer()).map_err(|e| format!("cannot write {}: {e}", target.display()))?;
    file.commit()
}

fn png_to(w: &mut dyn Write, img: &RgbImage) -> Result<(), String> {
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

/// Writes an 8-bit sRGB picture as a PNG, atomically.
pub fn write_png(path: &Path, img: &RgbImage) -> Result<(), String> {
    write_atomic(path, |w| png_to(w, img))
}

/// The PFM header of an image.
fn pfm_header(image: &Image) -> String {
    format!("PF\n{} {}\n-1.0\n", image.width, image.height)
}

/// Writes the PFM rows (bottom first) without building the whole file in memory.
fn pfm_to(w: &mut dyn Write, image: &Image) -> std::io::Result<()> {
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

/// The linear, unclipped image as a little-endian colour PFM (rows from the bottom, as the
/// format wants). Negative components (out-of-gamut spectral colours) are kept.
#[cfg(test)]
pub fn pfm_bytes(image: &Image) -> Vec<u8> {
    let mut out = Vec::new();
    pfm_to(&mut out, image).expect("writing to memory");
    out
}

/// Writes the linear image as a PFM, atomically.
pub fn write_pfm(path: &Path, image: &Image) -> Result<(), String> {
    write_atomic(path, |w| pfm_to(w, image).map_err(|e| e.to_string()))
}

/// An animated GIF, looping forever, written one frame at a time (no frame is kept) into an
/// [`AtomicFile`] that [`Gif::finish`] renames into place.
pub struct Gif {
    encoder: Option<image::codecs::gif::GifEncoder<BufWriter<Shared>>>,
    error: std::sync::Arc<std::sync::Mutex<Option<String>>>,
    file: AtomicFile,
    delay_ms: u32,
}

impl Gif {
    /// A GIF at `path` (written under a temporary name), `delay_ms` between frames.
    pub fn create(path: &Path, delay_ms: u32) -> Result<Gif, String> {
        use image::codecs::gif::{GifEncoder, Repeat};
        let fail = |e: &dyn std::fmt::Display| format!("cannot write {}: {e}", path.display());
        let mut file = AtomicFile::create(path)?;
        // The encoder writes through a second handle on the temporary file.
        let handle = file.writer().get_ref().try_clone().map_err(|e| fail(&e))?;
        let error = std::sync::Arc::new(std::sync::Mutex::new(None));
        let shared = Shared {
            file: handle,
            error: error.clone(),
        };
        let mut encoder = GifEncoder::new_with_speed(BufWriter::new(shared), 10);
        encoder.set_repeat(Repeat::Infinite).map_err(|e| fail(&e))?;
        Ok(Gif {
            encoder: Some(encoder),
            error,
            file,
            delay_ms,
        })
    }

    /// Appends a frame.
    pub fn add(&mut self, frame: &RgbImage) -> Result<(), String> {
        let rgba = image::DynamicImage::ImageRgb8(frame.clone()).to_rgba8();
        let delay = image::Delay::from_numer_denom_ms(self.delay_ms, 1);
        let frame = image::Frame::from_parts(rgba, 0, 0, delay);
        let encoder = self.encoder.as_mut().expect("not finished");
        encoder
            .encode_frame(frame)
            .map_err(|e| format!("cannot write {}: {e}", self.file.target.display()))
    }

    /// Writes the trailer, checks that every byte reached the file, and renames it into place.
    pub fn finish(mut self) -> Result<(), String> {
        drop(self.encoder.take()); // writes the trailer and flushes
        let error = self.error.lock().ok().and_then(|mut e| e.take());
        if let Some(e) = error {
            return Err(format!("cannot write {}: {e}", self.file.target.display()));
        }
        self.file.commit()
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
