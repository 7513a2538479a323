//! The geometry half of the GPU renderer, on the CPU: the reference tracer's camera samples,
//! nearest hits, shadow rays and mirror recursion (`tools/render/common`, `whitted::visibility`,
//! `whitted::sky`), recording what eq. 12 needs at every surface hit instead of shading it.
//!
//! A pixel's colour in the Whitted tracer is linear in its hits' local shades: a hit of a
//! material with mirror coefficient m shades as (1 − m)·local + m·tint·(what the reflected ray
//! sees), and the pixel is the mean of its samples. So every hit becomes one [`Record`] with the
//! product of those factors as its weight, and the sky seen by a ray (no shading) is summed into
//! the pixel's base colour here. The random numbers are drawn in the reference's order (the
//! lights' shadow rays, then the reflection), so the visibilities are the reference's own.

use std::sync::Mutex;

use diffraction::frame::ShadingFrame;
use glam::DVec3;

use crate::camera::{self, Camera, CameraRays};
use crate::geometry::{nearest, Hit, Ray};
use crate::output::Image;
use crate::sampling::Rng;
use crate::whitted::{sky, visibility, PaperScene};

/// One surface hit of a camera or mirror ray: what its shading on the GPU needs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Record {
    /// The hit point (the lights' directions are taken from it).
    pub point: DVec3,
    /// The unit shading normal.
    pub normal: DVec3,
    /// Toward the viewer (unit).
    pub wo: DVec3,
    /// The unit grating vector in the tangent plane (the shading frame's x), or `None` where
    /// the surface is no grating there.
    pub grating: Option<DVec3>,
    /// The diffuse albedo at the hit (textures evaluated).
    pub albedo: DVec3,
    /// The factor of this hit's shade in its pixel: 1/spp times the mirror factors.
    pub weight: DVec3,
    /// The scene's material index.
    pub material: u32,
}

/// The G-buffer of a frame: per pixel a run of records and the sky it sees.
#[derive(Debug, Clone)]
pub struct GBuffer {
    /// The sky's share of each pixel (linear sRGB).
    pub base: Image,
    /// Pixel i's records are `records[offsets[i]..offsets[i + 1]]`.
    pub offsets: Vec<usize>,
    /// Every pixel's records, pixel by pixel.
    pub records: Vec<Record>,
    /// The visible fraction of each light from each record (records × lights, 0 where the
    /// light is below the surface).
    pub visibility: Vec<f32>,
}

/// One pixel's records and visibilities while they are traced.
type Pixel = (Vec<Record>, Vec<f32>);

/// Traces the G-buffer of `p`'s scene from `camera` with the scene's settings (the reference's
/// samples, seeds and rays, `--filter point`: no footprint rays).
pub fn trace(p: &PaperScene, camera: &Camera, progress: Option<&str>) -> GBuffer {
    let s = &p.scene.settings;
    let rays = CameraRays::new(camera, s.width, s.height);
    let pixels: Vec<Mutex<Pixel>> = (0..s.width as usize * s.height as usize)
        .map(|_| Mutex::new((Vec::new(), Vec::new())))
        .collect();
    let weight = DVec3::splat(1.0 / s.spp as f64);
    let sample = |c: &camera::CameraSample, rng: &mut Rng| {
        let ray = rays.ray(c.point.x, c.point.y);
        let index = c.pixel.1 as usize * s.width as usize + c.pixel.0 as usize;
        // Only this pixel's thread ever locks it.
        let mut pixel = pixels[index].lock().unwrap_or_else(|e| e.into_inner());
        let (records, vis) = &mut *pixel;
        ray_records(p, &ray, 0, weight, rng, records, vis)
    };
    // The samples' weights hold 1/spp already.
    let base = camera::render(s, 0, progress, sample, |sum| sum);
    let (mut offsets, mut records, mut visibility) = (vec![0], Vec::new(), Vec::new());
    for pixel in pixels {
        let (r, v) = pixel.into_inner().unwrap_or_else(|e| e.into_inner());
        records.extend(r);
        visibility.extend(v);
        offsets.push(records.len());
    }
    GBuffer {
        base,
        offsets,
        records,
        visibility,
    }
}

/// Records the hits along `ray` with factor `weight`; returns the sky's share.
fn ray_records(
    p: &PaperScene,
    ray: &Ray,
    depth: u32,
    weight: DVec3,
    rng: &mut Rng,
    records: &mut Vec<Record>,
    vis: &mut Vec<f32>,
) -> DVec3 {
    match nearest(&p.scene.objects, ray, f64::INFINITY) {
        None => weight * sky(&p.scene, ray.dir),
        Some(hit) => hit_records(p, ray, &hit, depth, weight, rng, records, vis),
    }
}

/// The reference's `shade` without the shading: the hit's record, then its reflection's.
#[allow(clippy::too_many_arguments)]
fn hit_records(
    p: &PaperScene,
    ray: &Ray,
    hit: &Hit,
    depth: u32,
    weight: DVec3,
    rng: &mut Rng,
    records: &mut Vec<Record>,
    vis: &mut Vec<f32>,
) -> DVec3 {
    let scene = &p.scene;
    let index = scene.objects[hit.object].material;
    let material = &scene.materials[index];
    let n = hit.normal;
    let origin = hit.spawn_point();
    let mut albedo = None;
    let grating = material.grating.as_ref().and_then(|g| {
        if g.is_plain_at(hit.p) {
            albedo = Some(g.plain_albedo);
            return None;
        }
        let t = g.field.world_direction(hit.p, hit.tangent, hit.bitangent)?;
        ShadingFrame::new(n, t).map(|frame| frame.grating)
    });
    let albedo = albedo.unwrap_or_else(|| material.albedo.at(hit));
    for light in &scene.lights {
        let wi = (light.position - hit.point).normalize();
        let v = match n.dot(wi) > 0.0 {
            true => visibility(scene, origin, light, rng),
            false => 0.0,
        };
        vis.push(v as f32);
    }
    let mirrors = material.mirror > 0.0 && depth < scene.settings.max_depth;
    let local = match mirrors {
        true => weight * (1.0 - material.mirror),
        false => weight,
    };
    records.push(Record {
        point: hit.point,
        normal: n,
        wo: -ray.dir,
        grating,
        albedo,
        weight: local,
        material: index as u32,
    });
    if !mirrors {
        return DVec3::ZERO;
    }
    let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
    let next = Ray::new(origin, dir);
    let reflected = weight * material.mirror_tint * material.mirror;
    ray_records(p, &next, depth + 1, reflected, rng, records, vis)
}
