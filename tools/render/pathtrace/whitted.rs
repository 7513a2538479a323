//! The Whitted-style renderer of radiometric scenes (`--integrator whitted`): direct light
//! integrated over each area light by its stratified light samples, mirror recursion; the
//! reference the path tracer's direct light is compared with.
//!
//! # Cost
//!
//! Every camera sample takes each spherical light's `samples` directions, each with a shadow ray
//! and, on a grating, the grating's colour over the whole visible band (the crate's peak search
//! and lobe integrals), where the path tracer takes one light sample and one BSDF sample per
//! vertex at four wavelengths. The time is proportional to the light samples: `cd_area_light`
//! at 160×120 and 16 spp took 0.22, 0.48 and 1.50 s of CPU with 1, 4 and 16 light samples (the
//! path tracer 0.25 s); at 16 (the scene's) about half of it is the grating's colours, 18 % the
//! light-direction sampling and 9 % the shadow rays (perf). That is the price of a low-noise
//! reference, 256 light directions per pixel, not waste: lower `samples` in the scene's light
//! for a faster, noisier picture.

use diffraction::color::Xyz;
use diffraction::spectrum::GenericStrategy;
use diffraction::SpectralResponse;
use glam::DVec3;

use crate::camera::{self, Camera, CameraRays};
use crate::colour::Colour;
use crate::geometry::{nearest, occluded, Ray, SHADOW_REACH};
use crate::output::Image;
use crate::radiometry::{Radiometric, Radiometry};
use crate::sampling::{Rng, Strata};
use crate::scene::Scene;
use crate::surface::{nearest_emitter, sample_sphere, Surface};

/// Renders a radiometric scene Whitted-style, `settings.spp` stratified samples per pixel.
pub fn render(scene: &Scene<Radiometric>, camera: &Camera, progress: Option<&str>) -> Image {
    let s = &scene.settings;
    let rays = CameraRays::new(camera, s.width, s.height);
    let sample = |c: &camera::CameraSample, rng: &mut Rng| {
        trace(scene, &rays.ray(c.point.x, c.point.y), 0, rng)
    };
    camera::render(s, 0, progress, sample, |sum| sum / s.spp as f64)
}

/// The linear sRGB radiance along `ray` (film units: times the exposure), Whitted-style: the
/// emitters and the sky seen directly, direct light from every emitter (point lights by one
/// shadow ray, spherical ones by `samples` stratified directions uniform in their cone, each
/// with its shadow ray), mirror recursion up to `max_depth`. Diffuse interreflection and the
/// sky's light on surfaces are left out (the path integrator has them).
pub fn trace(scene: &Scene<Radiometric>, ray: &Ray, depth: u32, rng: &mut Rng) -> DVec3 {
    let r = &scene.units;
    let hit = nearest(&scene.objects, ray, f64::INFINITY);
    let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
    if let Some((i, _)) = nearest_emitter(r, ray, t_hit) {
        return film(r, r.white * r.emitters[i].scale);
    }
    let Some(hit) = hit else {
        return film(r, r.white * r.sky_scale(ray.dir));
    };
    let surface = Surface::at(scene, &hit);
    let n = hit.normal;
    let wo = -ray.dir;
    let wo_l = surface.frame.to_local(wo);
    let origin = hit.spawn_point();
    let mut xyz = Xyz::default();
    for e in &r.emitters {
        let light = |wi: DVec3, weight: f64, xyz: &mut Xyz| {
            let wi_l = surface.frame.to_local(wi);
            if wi_l.z <= 0.0 || wo_l.z <= 0.0 {
                return;
            }
            // Lambertian: ∫ s·ρ·cmf dλ·cos/π.
            let mut c = r.diffuse_xyz(surface.diffuse) * (wi_l.z / std::f64::consts::PI);
            if let Some(b) = surface.grating {
                // ∫ s·f·cmf dλ·cos, from the crate's colour (relative to ∫ s·ȳ).
                let g = match surface.strategy {
                    Colour::Integral(s) => match b.grating_response(wo_l, wi_l) {
                        Some(r) => scene.spectral.xyz_response(&r, s),
                        // Tabulated efficiencies (η depends on λ): the generic rule of the
                        // same name (`Colour::generic`).
                        None => {
                            let rule = Colour::Integral(s)
                                .generic()
                                .unwrap_or(GenericStrategy::WINDOWS);
                            scene.spectral.xyz_brdf(b, wo_l, wi_l, rule)
                        }
                    },
                    Colour::Paper => scene.spectral.paper_peaks_brdf(b, wo_l, wi_l),
                };
                c += g * (r.ys * surface.grating_weight);
            }
            *xyz += c * weight;
        };
        if e.radius <= 0.0 {
            let to = e.center - hit.point;
            let dist = to.length();
            if n.dot(to) <= 0.0
                || occluded(&scene.objects, &Ray::new(origin, to), dist * SHADOW_REACH)
            {
                continue;
            }
            light(to / dist, e.scale / (dist * dist), &mut xyz);
            continue;
        }
        let k = e.samples.max(1);
        let mut strata = Strata::new(k, rng);
        while let Some((_, u)) = strata.next_sample(rng) {
            let Some((dir, dist, pdf)) = sample_sphere(origin, e, u) else {
                continue;
            };
            if n.dot(dir) <= 0.0
                || occluded(&scene.objects, &Ray::new(origin, dir), dist * SHADOW_REACH)
            {
                continue;
            }
            light(dir, e.scale / (pdf * k as f64), &mut xyz);
        }
    }
    let mut rgb = film(r, xyz);
    if surface.mirror > 0.0 && depth < scene.settings.max_depth {
        let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
        let reflected = trace(scene, &Ray::new(origin, dir), depth + 1, rng);
        rgb += surface.tint * reflected * surface.mirror;
    }
    rgb
}

/// XYZ of radiance to the film's linear sRGB (times the exposure).
pub fn film(r: &Radiometry, xyz: Xyz) -> DVec3 {
    let c = (xyz * r.exposure).to_linear_srgb();
    DVec3::new(c.r, c.g, c.b)
}
