//! Procedural wood and image textures.

use std::path::Path;

use glam::{DVec2, DVec3};

use crate::sampling::{hash64, hash_unit};

/// 3-D gradient noise (Perlin's improved noise, with gradients picked by hashing the lattice
/// point), in about [-1, 1].
pub fn gradient_noise(p: DVec3) -> f64 {
    let cell = p.floor();
    let f = p - cell;
    let (i, j, k) = (cell.x as i64, cell.y as i64, cell.z as i64);
    let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (u, v, w) = (fade(f.x), fade(f.y), fade(f.z));
    let grad = |di: i64, dj: i64, dk: i64| {
        let h = hash64(
            (i.wrapping_add(di) as u64)
                ^ (j.wrapping_add(dj) as u64).wrapping_mul(0x632B_E59B_D9B4_E019)
                ^ (k.wrapping_add(dk) as u64).wrapping_mul(0x8CB9_2BA7_2F3D_8DD7),
        );
        // One of the 12 edge directions of a cube.
        let g = match h % 12 {
            0 => DVec3::new(1.0, 1.0, 0.0),
            1 => DVec3::new(-1.0, 1.0, 0.0),
            2 => DVec3::new(1.0, -1.0, 0.0),
            3 => DVec3::new(-1.0, -1.0, 0.0),
            4 => DVec3::new(1.0, 0.0, 1.0),
            5 => DVec3::new(-1.0, 0.0, 1.0),
            6 => DVec3::new(1.0, 0.0, -1.0),
            7 => DVec3::new(-1.0, 0.0, -1.0),
            8 => DVec3::new(0.0, 1.0, 1.0),
            9 => DVec3::new(0.0, -1.0, 1.0),
            10 => DVec3::new(0.0, 1.0, -1.0),
            _ => DVec3::new(0.0, -1.0, -1.0),
        };
        g.dot(f - DVec3::new(di as f64, dj as f64, dk as f64))
    };
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let x00 = lerp(grad(0, 0, 0), grad(1, 0, 0), u);
    let x10 = lerp(grad(0, 1, 0), grad(1, 1, 0), u);
    let x01 = lerp(grad(0, 0, 1), grad(1, 0, 1), u);
    let x11 = lerp(grad(0, 1, 1), grad(1, 1, 1), u);
    lerp(lerp(x00, x10, v), lerp(x01, x11, v), w)
}

/// Fractal sum of `octaves` octaves of gradient noise.
pub fn fbm(p: DVec3, octaves: u32) -> f64 {
    let (mut sum, mut amp, mut q) = (0.0, 0.5, p);
    for _ in 0..octaves {
        sum += amp * gradient_noise(q);
        q = q * 2.03 + DVec3::splat(17.0);
        amp *= 0.5;
    }
    sum
}

/// Planks of wood with growth rings: the trunk axis runs along x, the rings are cylinders about
/// it, distorted by gradient noise, and a fine grain and per-plank tint are added.
#[derive(Debug, Clone, Copy)]
pub struct Wood {
    /// The colour of early wood (linear sRGB).
    pub light: DVec3,
    /// The colour of late wood, the dark edge of each ring.
    pub dark: DVec3,
    /// Distance between growth rings, world units.
    pub ring_spacing: f64,
    /// Ring distortion, in ring spacings.
    pub turbulence: f64,
    /// Width of one plank (across the grain, along z), world units; 0 for one solid block.
    pub plank_width: f64,
    /// Length of one plank (along the grain), world units; 0 for endless planks.
    pub plank_length: f64,
}

impl Wood {
    /// The albedo at a point in the object's (unscaled) frame.
    pub fn albedo(&self, q: DVec3) -> DVec3 {
        let s = self.ring_spacing;
        let (plank, mut edge) = if self.plank_width > 0.0 {
            let j = (q.z / self.plank_width).floor();
            let f = q.z / self.plank_width - j;
            (j as i64, f.min(1.0 - f) * self.plank_width)
        } else {
            (0, f64::INFINITY)
        };
        // Planks are staggered: each row has its butt joints at a different offset.
        let mut board = plank as u64;
        if self.plank_length > 0.0 {
            let offset = hash_unit(plank as u64 ^ 0xA5A5) * self.plank_length;
            let x = q.x + offset;
            let k = (x / self.plank_length).floor();
            let f = x / self.plank_length - k;
            edge = edge.min(f.min(1.0 - f) * self.plank_length);
            board = board.wrapping_mul(131).wrapping_add(k as i64 as u64);
        }
        // Each board is cut from a different place of a log: axis offset below the surface.
        let cy = -(4.0 + 12.0 * hash_unit(board ^ 0x51)) * s;
        let cz = (hash_unit(board ^ 0x77) - 0.5) * 8.0 * s;
        let local = DVec3::new(q.x, q.y - cy, q.z - self.plank_width * plank as f64 - cz);
        // The noise is stretched along the grain, so the rings wander slowly along a board.
        let warp = DVec3::new(local.x * 0.08 / s, local.y * 0.5 / s, local.z * 0.5 / s);
        let offset = DVec3::new(
            hash_unit(board ^ 0x3),
            hash_unit(board ^ 0x4),
            hash_unit(board ^ 0x5),
        ) * 100.0;
        let distort = self.turbulence * fbm(warp + offset, 4);
        let r = (local.y * local.y + local.z * local.z).sqrt() / s + distort;
        let ring = r - r.floor();
        // Early wood light, late wood darker with a sharp edge at the ring boundary.
        let late = smoothstep(0.55, 0.95, ring) * (1.0 - smoothstep(0.95, 1.0, ring));
        let grain =
            0.5 + 0.5 * gradient_noise(DVec3::new(q.x * 3.0 / s, q.y * 80.0 / s, q.z * 80.0 / s));
        let t = (0.75 * late + 0.25 * grain).clamp(0.0, 1.0);
        let tint = 0.85 + 0.3 * hash_unit(board ^ 0x1234);
        let mut c = (self.light + (self.dark - self.light) * t) * tint;
        // A dark gap between boards.
        let gap = 0.04 * s;
        if edge < gap {
            c *= 0.35 + 0.65 * (edge / gap);
        }
        c
    }
}

fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// An 8-bit sRGB image decoded to linear RGB, sampled bilinearly with wrapping in u.
#[derive(Debug, Clone)]
pub struct ImageTexture {
    width: usize,
    height: usize,
    texels: Vec<DVec3>,
}

impl ImageTexture {
    /// Loads a PNG (or any format the `image` crate reads here) of at most `max_texels` pixels,
    /// checked from the file's header before anything is decoded.
    pub fn load(path: &Path, max_texels: u64) -> Result<ImageTexture, String> {
        let cannot = |e: &dyn std::fmt::Display| format!("cannot read {}: {e}", path.display());
        let reader = || {
            image::ImageReader::open(path)
                .map_err(|e| cannot(&e))?
                .with_guessed_format()
                .map_err(|e| cannot(&e))
        };
        let (w, h) = reader()?.into_dimensions().map_err(|e| cannot(&e))?;
        let texels = w as u64 * h as u64;
        if texels > max_texels {
            return Err(format!(
                "{}: {w} x {h} = {texels} pixels, more than the {max_texels} left of the limit on \
                 texture pixels",
                path.display()
            ));
        }
        let img = reader()?.decode().map_err(|e| cannot(&e))?;
        Ok(ImageTexture::from_rgb8(&img.to_rgb8()))
    }

    /// The number of texels.
    pub fn texels(&self) -> u64 {
        self.texels.len() as u64
    }

    /// The texture of an 8-bit sRGB image.
    pub fn from_rgb8(img: &image::RgbImage) -> ImageTexture {
        let decode = |c: u8| diffraction::color::srgb_decode(c as f64 / 255.0);
        let texels = img
            .pixels()
            .map(|p| DVec3::new(decode(p[0]), decode(p[1]), decode(p[2])))
            .collect();
        ImageTexture {
            width: img.width() as usize,
            height: img.height() as usize,
            texels,
        }
    }

    /// The colour at texture coordinates (u, v), v = 0 at the bottom of the image.
    pub fn sample(&self, uv: DVec2) -> DVec3 {
        let (w, h) = (self.width, self.height);
        if w == 0 || h == 0 {
            return DVec3::ZERO;
        }
        let x = uv.x.rem_euclid(1.0) * w as f64 - 0.5;
        let y = (1.0 - uv.y.clamp(0.0, 1.0)) * h as f64 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let at = |i: f64, j: f64| {
            let i = (i as i64).rem_euclid(w as i64) as usize;
            let j = (j as i64).clamp(0, h as i64 - 1) as usize;
            self.texels[j * w + i]
        };
        let top = at(x0, y0).lerp(at(x0 + 1.0, y0), fx);
        let bottom = at(x0, y0 + 1.0).lerp(at(x0 + 1.0, y0 + 1.0), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_bounded_and_deterministic() {
        for i in 0..1000 {
            let p = DVec3::new(i as f64 * 0.137, i as f64 * -0.071, i as f64 * 0.29);
            let n = gradient_noise(p);
            assert!(n.abs() <= 1.5, "{n}");
            assert_eq!(n, gradient_noise(p));
        }
        assert_eq!(gradient_noise(DVec3::new(3.0, 4.0, 5.0)), 0.0); // zero on the lattice
    }
}
