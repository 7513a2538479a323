//! The pinhole camera, its orbit for animations, and the film loop every integrator renders
//! through: stratified camera samples per pixel (one [`Strata`] set each), in parallel rows.

use std::io::IsTerminal;

use glam::{DVec2, DVec3};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::geometry::Ray;
use crate::output::Image;
use crate::sampling::{hash64, Rng, Strata};
use crate::scene::Settings;

/// A pinhole camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Where the camera is.
    pub position: DVec3,
    /// The point at the centre of the picture.
    pub look_at: DVec3,
    /// The direction that is up in the picture (unit).
    pub up: DVec3,
    /// The vertical field of view, degrees.
    pub fov_deg: f64,
}

impl Camera {
    /// The camera moved `angle` radians around the vertical axis (`up`) through its target.
    pub fn orbit(&self, angle: f64) -> Camera {
        let axis = self.up.normalize();
        let rotation = glam::DQuat::from_axis_angle(axis, angle);
        Camera {
            position: self.look_at + rotation * (self.position - self.look_at),
            ..*self
        }
    }
}

/// The pinhole camera's ray through a point of the image plane.
#[derive(Debug, Clone, Copy)]
pub struct CameraRays {
    origin: DVec3,
    right: DVec3,
    up: DVec3,
    forward: DVec3,
    width: f64,
    height: f64,
}

impl CameraRays {
    /// The rays of `camera` for a picture of width × height pixels.
    pub fn new(camera: &Camera, width: u32, height: u32) -> CameraRays {
        let forward = (camera.look_at - camera.position).normalize();
        let right = forward.cross(camera.up).normalize();
        let up = right.cross(forward);
        let half_h = (camera.fov_deg.to_radians() / 2.0).tan();
        let half_w = half_h * width as f64 / height as f64;
        CameraRays {
            origin: camera.position,
            right: right * half_w,
            up: up * half_h,
            forward,
            width: width as f64,
            height: height as f64,
        }
    }

    /// The ray through image point (x, y) in pixels, (0, 0) the top-left corner.
    pub fn ray(&self, x: f64, y: f64) -> Ray {
        let sx = 2.0 * x / self.width - 1.0;
        let sy = 1.0 - 2.0 * y / self.height;
        Ray::new(self.origin, self.forward + self.right * sx + self.up * sy)
    }
}

/// Whether to draw a progress bar: stderr is a terminal and the user did not ask for quiet.
pub fn progress_wanted(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// One camera sample of a pixel.
#[derive(Debug, Clone, Copy)]
pub struct CameraSample {
    /// Its index in the pixel's set, 0..spp.
    pub index: u32,
    /// The pixel (column, row from the top).
    pub pixel: (u32, u32),
    /// Its stratum cell (column, row) ...
    pub cell: (u32, u32),
    /// ... of a grid of this many columns and rows ([`Strata`]).
    pub grid: (u32, u32),
    /// The jittered image point, in pixels.
    pub point: DVec2,
}

/// Renders `settings.width × settings.height` pixels: for each pixel, `settings.spp` stratified
/// samples (their cells jittered x first), each traced by `sample` with the pixel's generator
/// (seeded by the settings' seed, the pixel and `salt`, so the bytes do not depend on the
/// threads), summed, and the sum turned into the pixel's linear sRGB by `finish`. `progress`:
/// the label of a progress bar, or `None` for none.
pub fn render<F, G>(
    settings: &Settings,
    salt: u64,
    progress: Option<&str>,
    sample: F,
    finish: G,
) -> Image
where
    F: Fn(&CameraSample, &mut Rng) -> DVec3 + Sync,
    G: Fn(DVec3) -> DVec3 + Sync,
{
    let (w, h) = (settings.width, settings.height);
    let bar = match progress {
        Some(label) => {
            let bar = ProgressBar::with_draw_target(Some(h as u64), ProgressDrawTarget::stderr());
            if let Ok(style) =
                ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} rows, {elapsed}")
            {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_message(label.to_string());
            bar
        }
        None => ProgressBar::hidden(),
    };
    let mut pixels = vec![DVec3::ZERO; (w as usize) * (h as usize)];
    pixels
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                let key = ((y as u64) << 32) | x as u64;
                let mut rng = Rng::new(settings.seed ^ hash64(key) ^ salt);
                let mut strata = Strata::new(settings.spp, &mut rng);
                let grid = strata.grid();
                let mut sum = DVec3::ZERO;
                let mut index = 0;
                while let Some((cell, jitter)) = strata.next_sample(&mut rng) {
                    let s = CameraSample {
                        index,
                        pixel: (x as u32, y as u32),
                        cell,
                        grid,
                        point: DVec2::new(x as f64 + jitter.x, y as f64 + jitter.y),
                    };
                    sum += sample(&s, &mut rng);
                    index += 1;
                }
                *out = finish(sum);
            }
            bar.inc(1);
        });
    bar.finish_and_clear();
    Image {
        width: w,
        height: h,
        pixels,
    }
}
