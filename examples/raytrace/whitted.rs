//! The Whitted-style tracer: camera rays with stratified supersampling, nearest hits, hard (or
//! softly sampled) shadows, mirror recursion, and the paper's illumination model (eq. 12) for
//! diffraction gratings.

use std::io::IsTerminal;

use diffraction::frame::ShadingFrame;
use glam::DVec3;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;

use crate::footprint::{self, Filter, Footprint};
use crate::geometry::{Hit, Ray};
use crate::scene::{Camera, Light, Scene};
use crate::texture::hash64;

/// A rendered image in linear sRGB (unclipped: spectral colours have negative components and
/// highlights exceed 1), rows from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<DVec3>,
}

/// A small deterministic generator (SplitMix64), seeded per pixel so that the picture does not
/// depend on how rayon splits the work.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(hash64(seed))
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        hash64(self.0)
    }

    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// An integer in [0, n), n ≥ 1, by the high half of a 64 × 64-bit product (Lemire's method
    /// without the rejection step: the bias is below n / 2⁶⁴, under 10⁻¹⁵ for the counts here).
    pub fn below(&mut self, n: u32) -> u32 {
        ((self.next_u64() as u128 * n as u128) >> 64) as u32
    }
}

/// Largest number of samples in one [`Strata`] set (larger counts are taken as this): the
/// scene loader's limits on samples per pixel and shadow samples are at most this.
pub const MAX_STRATA_SAMPLES: u32 = 4096;

/// Largest number of cells a [`Strata`] grid leaves empty: a grid of cols = ⌈√n⌉ columns and
/// rows = ⌈n / cols⌉ rows has fewer than cols cells over n, and cols ≤ 64 for n ≤
/// [`MAX_STRATA_SAMPLES`].
const MAX_EMPTY_CELLS: usize = 64;

/// `n` stratified samples of the unit square for any n ≥ 1: a grid of cols = ⌈√n⌉ by
/// rows = ⌈n / cols⌉ cells (cols·rows ≥ n, fewer than cols cells too many), one jittered sample
/// in each of n distinct cells. When the grid has more cells than samples, the cells left empty
/// are a uniformly random subset (Floyd's algorithm) drawn afresh for every set, so every cell
/// is sampled with the same probability n / (cols·rows) and every sample is uniform over the
/// square: the estimate is unbiased and no part of the domain is ever skipped. When n is a square
/// or the grid is full (cols·rows = n) no cell is left out and nothing extra is drawn.
#[derive(Debug, Clone)]
pub struct Strata {
    cols: u32,
    rows: u32,
    /// The cells left empty, sorted.
    empty: [u32; MAX_EMPTY_CELLS],
    n_empty: usize,
    /// The next cell to visit and the next empty cell to skip.
    cell: u32,
    skip: usize,
    left: u32,
}

impl Strata {
    /// The grid for `n` samples (0 is taken as 1, more than [`MAX_STRATA_SAMPLES`] as that),
    /// its empty cells drawn from `rng`.
    pub fn new(n: u32, rng: &mut Rng) -> Strata {
        let n = n.clamp(1, MAX_STRATA_SAMPLES);
        let cols = (n as f64).sqrt().ceil() as u32;
        let rows = n.div_ceil(cols);
        let cells = cols * rows;
        let n_empty = (cells - n) as usize; // < cols ≤ MAX_EMPTY_CELLS
        let mut empty = [0u32; MAX_EMPTY_CELLS];
        // Floyd's algorithm: a uniformly random n_empty-subset of 0..cells.
        for (k, j) in (cells - n_empty as u32..cells).enumerate() {
            let t = rng.below(j + 1);
            empty[k] = if empty[..k].contains(&t) { j } else { t };
        }
        empty[..n_empty].sort_unstable();
        Strata {
            cols,
            rows,
            empty,
            n_empty,
            cell: 0,
            skip: 0,
            left: n,
        }
    }

    /// The grid's columns and rows.
    pub fn grid(&self) -> (u32, u32) {
        (self.cols, self.rows)
    }

    /// The cell (column, row) of the next sample; the caller jitters inside it, at
    /// ((column + ξ₁) / cols, (row + ξ₂) / rows).
    pub fn next_cell(&mut self) -> Option<(u32, u32)> {
        if self.left == 0 {
            return None;
        }
        while self.skip < self.n_empty && self.empty[self.skip] == self.cell {
            self.skip += 1;
            self.cell += 1;
        }
        let cell = (self.cell % self.cols, self.cell / self.cols);
        self.cell += 1;
        self.left -= 1;
        Some(cell)
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

/// The camera moved `angle` radians around the vertical axis (`up`) through its target.
pub fn orbit(camera: &Camera, angle: f64) -> Camera {
    let axis = camera.up.normalize();
    let rotation = glam::DQuat::from_axis_angle(axis, angle);
    Camera {
        position: camera.look_at + rotation * (camera.position - camera.look_at),
        ..*camera
    }
}

/// Whether to draw a progress bar: stderr is a terminal and the user did not ask for quiet.
pub fn progress_wanted(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// Renders the scene from `camera` with the scene's settings.
pub fn render(scene: &Scene, camera: &Camera, progress: bool, label: &str) -> Image {
    let s = &scene.settings;
    let (w, h) = (s.width, s.height);
    let rays = CameraRays::new(camera, w, h);
    let bar = if progress {
        let bar = ProgressBar::with_draw_target(Some(h as u64), ProgressDrawTarget::stderr());
        if let Ok(style) =
            ProgressStyle::with_template("{msg:>12} [{bar:40}] {pos}/{len} rows, {elapsed}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(label.to_string());
        bar
    } else {
        ProgressBar::hidden()
    };
    let mut pixels = vec![DVec3::ZERO; (w as usize) * (h as usize)];
    pixels
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                let mut rng = Rng::new(s.seed ^ hash64(((y as u64) << 32) | x as u64));
                let mut sum = DVec3::ZERO;
                let mut strata = Strata::new(s.spp, &mut rng);
                let (cols, rows) = strata.grid();
                while let Some((cx, cy)) = strata.next_cell() {
                    let jx = (cx as f64 + rng.next_f64()) / cols as f64;
                    let jy = (cy as f64 + rng.next_f64()) / rows as f64;
                    let (px, py) = (x as f64 + jx, y as f64 + jy);
                    let ray = rays.ray(px, py);
                    sum += if scene.filter == Filter::Footprint {
                        // The footprint is the sample's stratum cell (the pixel at 1 spp):
                        // the rays through the midpoints of its edges, whatever the jitter.
                        let (cw, ch) = (1.0 / cols as f64, 1.0 / rows as f64);
                        let (mx, my) = (
                            x as f64 + (cx as f64 + 0.5) * cw,
                            y as f64 + (cy as f64 + 0.5) * ch,
                        );
                        let fp = [
                            rays.ray(mx - 0.5 * cw, my),
                            rays.ray(mx + 0.5 * cw, my),
                            rays.ray(mx, my - 0.5 * ch),
                            rays.ray(mx, my + 0.5 * ch),
                        ];
                        trace_with(scene, &ray, Some(&fp), 0, &mut rng)
                    } else {
                        trace(scene, &ray, 0, &mut rng)
                    };
                }
                *out = sum / s.spp as f64;
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

fn nearest(scene: &Scene, ray: &Ray) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, obj) in scene.objects.iter().enumerate() {
        let t_max = best.map_or(f64::INFINITY, |b| b.t);
        if let Some(hit) = obj.intersect(ray, t_max, i) {
            best = Some(hit);
        }
    }
    best
}

fn occluded(scene: &Scene, ray: &Ray, t_max: f64) -> bool {
    scene.objects.iter().any(|o| o.occludes(ray, t_max))
}

/// The sky seen along `dir`: `background` at the horizon and below, `zenith` straight up.
fn sky(scene: &Scene, dir: DVec3) -> DVec3 {
    let t = dir.y.clamp(0.0, 1.0);
    scene.background + (scene.zenith - scene.background) * t
}

/// The fraction of `light` visible from `origin`: one shadow ray for a point light, `samples`
/// stratified rays ([`Strata`]) toward a disc of the light's radius facing the point for a
/// spherical one.
fn visibility(scene: &Scene, origin: DVec3, light: &Light, rng: &mut Rng) -> f64 {
    if light.radius <= 0.0 {
        let to = light.position - origin;
        let dist = to.length();
        return if occluded(scene, &Ray::new(origin, to), dist * (1.0 - 1e-9)) {
            0.0
        } else {
            1.0
        };
    }
    let axis = (light.position - origin).normalize();
    let (a, b) = axis.any_orthonormal_pair();
    let n = light.samples;
    let mut seen = 0u32;
    let mut strata = Strata::new(n, rng);
    let (cols, rows) = strata.grid();
    while let Some((cx, cy)) = strata.next_cell() {
        // Stratified in (r², angle): uniform over the disc, rings by row, sectors by column.
        let r = ((cy as f64 + rng.next_f64()) / rows as f64).sqrt() * light.radius;
        let phi = (cx as f64 + rng.next_f64()) / cols as f64 * std::f64::consts::TAU;
        let target = light.position + (a * phi.cos() + b * phi.sin()) * r;
        let to = target - origin;
        let dist = to.length();
        if !occluded(scene, &Ray::new(origin, to), dist * (1.0 - 1e-9)) {
            seen += 1;
        }
    }
    seen as f64 / n as f64
}

/// The linear sRGB radiance along `ray`.
pub fn trace(scene: &Scene, ray: &Ray, depth: u32, rng: &mut Rng) -> DVec3 {
    trace_with(scene, ray, None, depth, rng)
}

/// The linear sRGB radiance along `ray`, with the offset rays of its pixel footprint for
/// [`Filter::Footprint`] (`None`: the colour at the ray's own u).
pub fn trace_with(
    scene: &Scene,
    ray: &Ray,
    fp: Option<&Footprint>,
    depth: u32,
    rng: &mut Rng,
) -> DVec3 {
    if let Some(r) = &scene.radiometry {
        return crate::radiometric::whitted(scene, r, ray, depth, rng);
    }
    match nearest(scene, ray) {
        None => sky(scene, ray.dir),
        Some(hit) => shade(scene, ray, fp, &hit, depth, rng),
    }
}

/// The paper's illumination model at a hit (eq. 12, rendering steps 1-8):
/// ambient + Σ_lights visibility · light · (k_d·albedo·cos θi + diffraction), plus mirror
/// reflection for reflective materials.
///
/// For a diffraction grating (steps 3-5) the grating vector t at the hit comes from the
/// material's field in the surface's tangent coordinates, the frame (normal, t) gives local wi
/// and wo, and u = wi.x + wo.x = (wi + wo)·t. The diffraction term (steps 6-8) is the crate's
/// spectral colour XYZ(u) of the Agu-Hill intensity (or of the material's other model at
/// (wi, wo)), scaled by k_diffraction and the material's exposure, converted to linear sRGB and
/// coloured by the light. Materials without a grating
/// never call the spectral code.
///
/// With a colour table for the material ([`crate::footprint`]) the diffraction XYZ is the
/// table's: its mean over the footprint's interval of u for [`Filter::Footprint`], its lookup
/// at u for [`Filter::Point`], scaled the same way.
fn shade(
    scene: &Scene,
    ray: &Ray,
    fp: Option<&Footprint>,
    hit: &Hit,
    depth: u32,
    rng: &mut Rng,
) -> DVec3 {
    let index = scene.objects[hit.object].material;
    let material = &scene.materials[index];
    let table = scene.tables.get(index).and_then(Option::as_deref);
    let n = hit.normal;
    let wo = -ray.dir;
    let origin = hit.point + n * (1e-7 * (1.0 + hit.point.abs().max_element()));

    // Step 4: the grating direction and the shading frame (None off the grating).
    let mut albedo = None;
    let grating = material.grating.as_ref().and_then(|g| {
        if g.is_plain_at(hit.p) {
            albedo = Some(g.plain_albedo);
            return None;
        }
        let t = g.field.world_direction(hit.p, hit.tangent, hit.bitangent)?;
        ShadingFrame::new(n, t).map(|frame| (g, frame))
    });
    let albedo = albedo.unwrap_or_else(|| material.albedo.at(hit));

    // Step 2: ambient and diffuse.
    // Eq. 12 in linear sRGB with the material's coefficients: the ambient and diffuse terms
    // coloured by the albedo, the diffraction term by the spectrum.
    let (k_ambient, k_diffuse, k_diffraction) = material.shading.coefficients();
    let mut color = scene.ambient * albedo * k_ambient;
    for light in &scene.lights {
        let to = light.position - hit.point;
        let wi = to.normalize();
        let cos = n.dot(wi);
        if cos <= 0.0 {
            continue;
        }
        let vis = visibility(scene, origin, light, rng);
        if vis == 0.0 {
            continue;
        }
        let mut reflected = albedo * (k_diffuse * cos);
        if let Some((g, frame)) = &grating {
            // Steps 3 and 5: local directions and the phase projection.
            let (wi_l, wo_l) = (frame.to_local(wi), frame.to_local(wo));
            if wi_l.z > 0.0 && wo_l.z > 0.0 {
                // Steps 6-8: the spectral colour of the diffraction term (for Agu-Hill, of
                // u = wi.x + wo.x).
                let xyz = match (table, scene.filter, fp) {
                    (Some(table), Filter::Footprint, Some(fp)) => {
                        let u = footprint::interval(scene, g, ray, hit, fp, light)
                            .unwrap_or((wi_l.x + wo_l.x, wi_l.x + wo_l.x));
                        footprint::filtered_xyz(table, g, u, k_diffraction)
                    }
                    (Some(table), Filter::Point, _) => {
                        let u = wi_l.x + wo_l.x;
                        footprint::filtered_xyz(table, g, (u, u), k_diffraction)
                    }
                    _ => g.xyz(&scene.spectral, wi_l, wo_l, k_diffraction),
                };
                let rgb = xyz.to_linear_srgb();
                reflected += DVec3::new(rgb.r, rgb.g, rgb.b);
            }
        }
        color += light.color * reflected * vis;
    }

    if material.mirror > 0.0 && depth < scene.settings.max_depth {
        let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
        let next = Ray::new(origin, dir);
        let next_fp = fp.map(|fp| footprint::reflect(scene, fp, hit, &next));
        let reflected = trace_with(scene, &next, next_fp.as_ref(), depth + 1, rng);
        color =
            color * (1.0 - material.mirror) + material.mirror_tint * reflected * material.mirror;
    }
    color
}
