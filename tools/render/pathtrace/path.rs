//! The spectral path tracer of radiometric scenes (`--integrator path`).
//!
//! Unidirectional, after pbrt-v4's `PathIntegrator`, with four wavelengths per path
//! (`SampledWavelengths`, stratified, the hero at index 0):
//!
//! * **Next-event estimation** at every vertex with a density: one emitter chosen uniformly, a
//!   direction uniform in the solid angle of a spherical emitter's cone (point lights: their
//!   centre), a shadow ray.
//! * **BSDF sampling**: the mirror share as a delta, the Lambertian by the cosine, the grating
//!   by `Bsdf::sample` at the hero wavelength (or, with `grating_sampler = false`, by the
//!   cosine: the comparison of the docs).
//! * **MIS**: the balance heuristic over eight techniques, {light, BSDF} × {the four
//!   wavelengths as hero} (Veach's balance heuristic with Wilkie et al.'s hero-wavelength
//!   MIS), kept as pbrt-v4 keeps it: the throughput `beta` divided by the hero's densities, and
//!   the ratios `r_u[k]` (BSDF path density under wavelength k over the sampling density) and
//!   `r_l[k]` (the same with light sampling at the last vertex). A contribution is
//!   `beta·L / mean_k(r_u[k] + r_l[k])`. This is the crate's recommendation for glossy
//!   grating lobes (`diffraction::SampledWavelengths`): for large N the secondaries' densities
//!   at the hero's direction are tiny and their weight goes to 0 by itself; a specular
//!   (delta) dispersive sample terminates the secondaries instead.
//! * The sky is reached by BSDF sampling only (weight 1). Russian roulette from the fourth
//!   vertex on, at most `max_depth` bounces (`max_depth = 1`: direct light only).
//! * The film: XYZ = exposure · mean_j cmf(λ_j)·L(λ_j)/p(λ_j), `diffraction::cie::cmf`, then
//!   the crate's colour pipeline (linear sRGB here, Hall clipping and encoding in `output`).

use diffraction::cie::cmf;
use diffraction::color::Xyz;
use diffraction::{Band, SampledWavelengths};
use glam::{DVec2, DVec3};

use crate::budget;
use crate::camera::{self, Camera, CameraRays};
use crate::geometry::{nearest, occluded, Ray, SHADOW_REACH};
use crate::output::Image;
use crate::radiometry::{Emitter, Radiometric, Radiometry};
use crate::sampling::Rng;
use crate::scene::Scene;
use crate::surface::{nearest_emitter, sample_sphere, sphere_pdf, Surface};

/// Options of the path tracer beyond the scene's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathOptions {
    /// Sample gratings with `Bsdf::sample` (else with the cosine, for comparison).
    pub grating_sampler: bool,
    /// Bounces after which a path ends (the scene's `max_depth` by default).
    pub max_depth: u32,
}

/// Vertices after which Russian roulette may end a path (pbrt-v4 starts after the second).
pub const ROULETTE_DEPTH: u32 = 3;

/// The seed salt of the path tracer's pixel generators (its random numbers differ from the
/// Whitted renderer's at the same seed).
const SALT: u64 = 0x9a7;

/// Renders a radiometric scene by path tracing, `settings.spp` paths per pixel (stratified
/// over the pixel, four wavelengths each, the heroes stratified over the pixel's paths), in
/// linear sRGB.
pub fn render(
    scene: &Scene<Radiometric>,
    camera: &Camera,
    options: PathOptions,
    progress: Option<&str>,
) -> Image {
    let r = &scene.units;
    let s = &scene.settings;
    let rays = CameraRays::new(camera, s.width, s.height);
    let spp = s.spp as f64;
    let path = |c: &camera::CameraSample, rng: &mut Rng| {
        let ray = rays.ray(c.point.x, c.point.y);
        // The hero stratified over the pixel's samples too.
        let u = (c.index as f64 + rng.next_f64()) / spp;
        let lambdas = SampledWavelengths::sample_uniform(u, Band::VISIBLE);
        let l = li(scene, &ray, lambdas, rng, options);
        let xyz = film_xyz(&lambdas, l);
        DVec3::new(xyz.x, xyz.y, xyz.z)
    };
    let film = |sum: DVec3| {
        let c = (Xyz::new(sum.x, sum.y, sum.z) * (r.exposure / spp)).to_linear_srgb();
        DVec3::new(c.r, c.g, c.b)
    };
    camera::render(s, SALT, progress, path, film)
}

/// The film's estimate of ∫ L·cmf dλ from four wavelengths: mean_j cmf(λ_j)·L_j/p(λ_j)
/// (terminated secondaries have density 0 and contribute nothing).
pub fn film_xyz(lambdas: &SampledWavelengths, l: [f64; 4]) -> Xyz {
    let mut acc = [0.0; 3];
    for ((&lambda, &p), &v) in lambdas.lambda().iter().zip(&lambdas.pdf()).zip(&l) {
        if p > 0.0 && v != 0.0 {
            let c = cmf(lambda);
            for k in 0..3 {
                acc[k] += c[k] * v / p;
            }
        }
    }
    Xyz::new(acc[0] / 4.0, acc[1] / 4.0, acc[2] / 4.0)
}

/// The balance-heuristic weights of the eight techniques {light, BSDF} × {wavelength k as
/// hero} for one path: `r_u[k]` is the prefix's density ratio under wavelength k, `p_light`
/// the light-sampling density of the last direction and `pdf4[k]` its BSDF density under
/// wavelength k. Returns (light weights, BSDF weights); they sum to 1 when any density is
/// positive (all 0 otherwise).
pub fn mis_weights(r_u: [f64; 4], p_light: f64, pdf4: [f64; 4]) -> ([f64; 4], [f64; 4]) {
    let mut wl = [0.0; 4];
    let mut wb = [0.0; 4];
    let mut sum = 0.0;
    for k in 0..4 {
        wl[k] = r_u[k] * p_light;
        wb[k] = r_u[k] * pdf4[k];
        sum += wl[k] + wb[k];
    }
    if !(sum > 0.0 && sum.is_finite()) {
        return ([0.0; 4], [0.0; 4]);
    }
    for k in 0..4 {
        wl[k] /= sum;
        wb[k] /= sum;
    }
    (wl, wb)
}

fn mean(v: [f64; 4]) -> f64 {
    v.iter().sum::<f64>() / 4.0
}

/// The emitted spectral radiance of an emitter (or a point light's intensity) at the four
/// wavelengths.
fn emitted(r: &Radiometry, e: &Emitter, l: &SampledWavelengths) -> [f64; 4] {
    let lam = l.lambda();
    std::array::from_fn(|j| e.scale * r.s(lam[j]))
}

/// The radiance along a camera ray at the four wavelengths (relative to the sampling of the
/// wavelengths: the film divides by their densities).
pub fn li(
    scene: &Scene<Radiometric>,
    camera_ray: &Ray,
    lambdas: SampledWavelengths,
    rng: &mut Rng,
    options: PathOptions,
) -> [f64; 4] {
    li_counted(
        scene,
        camera_ray,
        lambdas,
        rng,
        options,
        &mut Counts::default(),
    )
}

/// What one path did, for the work estimate's pilot ([`pilot`]).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counts {
    /// Rays tested against every object (the camera ray and one per bounce).
    pub rays: u64,
    /// Vertices shaded (a surface, its light sample and its BSDF sample).
    pub vertices: u64,
    /// Shadow rays (each tested against every object).
    pub shadow_rays: u64,
    /// Vertices on a grating (its BSDF evaluated and sampled).
    pub grating_vertices: u64,
}

/// [`li`], counting its work into `counts`.
pub fn li_counted(
    scene: &Scene<Radiometric>,
    camera_ray: &Ray,
    mut lambdas: SampledWavelengths,
    rng: &mut Rng,
    options: PathOptions,
    counts: &mut Counts,
) -> [f64; 4] {
    let r = &scene.units;
    let mut l = [0.0; 4];
    let mut beta = [1.0; 4];
    let mut r_u = [1.0; 4];
    // The last BSDF sample's prefix ratios and densities (for the MIS weight of an emitter
    // it reaches).
    let mut last = ([1.0; 4], [0.0; 4]);
    let mut specular = true; // the camera ray counts as a delta
    let mut prev = camera_ray.origin;
    let mut ray = *camera_ray;
    let n_lights = r.emitters.len();
    let mut depth = 0u32;
    loop {
        counts.rays += 1;
        let hit = nearest(&scene.objects, &ray, f64::INFINITY);
        let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
        if let Some((i, _)) = nearest_emitter(r, &ray, t_hit) {
            let le = emitted(r, &r.emitters[i], &lambdas);
            // beta holds 1/p_hero of the last direction; the balance weight of the hero's BSDF
            // technique is w = r_u[0]·p_hero/Σ (over the eight techniques), so the balanced
            // contribution beta·p_hero·Le/(Σ/4) is beta·Le·4·w/r_u[0].
            let k = if specular {
                1.0 / mean(r_u)
            } else {
                let p_light = sphere_pdf(prev, &r.emitters[i]) / n_lights as f64;
                4.0 * mis_weights(last.0, p_light, last.1).1[0] / last.0[0]
            };
            if k > 0.0 && k.is_finite() {
                for j in 0..4 {
                    l[j] += beta[j] * le[j] * k;
                }
            }
            break;
        }
        let Some(hit) = hit else {
            let sky = r.sky_scale(ray.dir);
            let lam = lambdas.lambda();
            let denom = mean(r_u);
            if sky > 0.0 && denom > 0.0 {
                for j in 0..4 {
                    l[j] += beta[j] * sky * r.s(lam[j]) / denom;
                }
            }
            break;
        };
        if depth >= options.max_depth {
            break;
        }
        let surface = Surface::at(scene, &hit);
        counts.vertices += 1;
        counts.grating_vertices += surface.grating.is_some() as u64;
        let wo = surface.frame.to_local(-ray.dir);
        let origin = hit.spawn_point();

        // Next-event estimation.
        if surface.has_density() && n_lights > 0 {
            let i = ((rng.next_f64() * n_lights as f64) as usize).min(n_lights - 1);
            let e = &r.emitters[i];
            let u = DVec2::new(rng.next_f64(), rng.next_f64());
            let sampled = if e.radius <= 0.0 {
                let to = e.center - origin;
                let dist = to.length();
                // A delta light: its "density" 1 with the intensity over dist² as radiance.
                (dist > 0.0).then(|| (to / dist, dist, 0.0))
            } else {
                sample_sphere(origin, e, u)
            };
            if let Some((dir, dist, pdf)) = sampled {
                let wi = surface.frame.to_local(dir);
                counts.shadow_rays += (wi.z > 0.0 && wo.z > 0.0) as u64;
                if wi.z > 0.0
                    && wo.z > 0.0
                    && !occluded(&scene.objects, &Ray::new(origin, dir), dist * SHADOW_REACH)
                {
                    let f = surface.f4(wo, wi, &lambdas);
                    let le = emitted(r, e, &lambdas);
                    let pmf = 1.0 / n_lights as f64;
                    let k = if e.radius <= 0.0 {
                        // A delta light: no MIS, its intensity over dist² as radiance.
                        1.0 / (pmf * dist * dist * mean(r_u))
                    } else {
                        let mut pdf4 = surface.pdf4(wo, wi, &lambdas, options.grating_sampler);
                        if lambdas.secondary_terminated() {
                            pdf4 = [pdf4[0]; 4];
                        }
                        // The hero's light technique: beta·f·Le/(Σ/4) = beta·f·Le·4·w/(r_u[0]·p).
                        let p = pdf * pmf;
                        4.0 * mis_weights(r_u, p, pdf4).0[0] / (r_u[0] * p)
                    };
                    if k > 0.0 && k.is_finite() {
                        for j in 0..4 {
                            l[j] += beta[j] * f[j] * wi.z * le[j] * k;
                        }
                    }
                }
            }
        }

        // BSDF sampling.
        let Some(s) = surface.sample(wo, &lambdas, rng, options.grating_sampler) else {
            break;
        };
        for (b, w) in beta.iter_mut().zip(s.weight) {
            *b *= w;
        }
        if s.specular {
            specular = true;
            if s.dispersive && !lambdas.secondary_terminated() {
                lambdas.terminate_secondary();
                beta = [beta[0] * 4.0, 0.0, 0.0, 0.0];
                r_u = [r_u[0]; 4];
            }
        } else {
            specular = false;
            let pdf4 = if lambdas.secondary_terminated() {
                [s.pdf; 4]
            } else {
                s.pdf4
            };
            last = (r_u, pdf4);
            for k in 0..4 {
                r_u[k] *= pdf4[k] / s.pdf;
            }
        }
        if beta.iter().all(|&b| b == 0.0) {
            break;
        }
        prev = origin;
        ray = Ray::new(origin, surface.frame.to_world(s.wi));
        depth += 1;
        // Russian roulette on the MIS-weighted throughput.
        if depth >= ROULETTE_DEPTH {
            let m = beta.iter().cloned().fold(0.0, f64::max) / mean(r_u).max(1e-300);
            if m < 1.0 {
                let q = (1.0 - m).max(0.0);
                if rng.next_f64() < q {
                    break;
                }
                for b in &mut beta {
                    *b /= 1.0 - q;
                }
            }
        }
    }
    // Guard the film against a non-finite value from a degenerate configuration.
    l.map(|v| if v.is_finite() { v.max(0.0) } else { 0.0 })
}

/// The seed of the pilot's paths (any fixed value: the estimate is deterministic).
const PILOT_SEED: u64 = 0x9110;

/// What a path does per camera sample, from the integrator's own paths through a grid of
/// pixel centres (fixed seeds, so the same scene gives the same numbers; at most
/// [`budget::PILOT_TESTS`] ray-object tests): its rays, vertices, shadow rays and grating
/// vertices, Russian roulette and the sky included. The estimate of `--integrator path`
/// multiplies them by the camera samples ([`crate::Integrator::estimate`]).
pub fn pilot(scene: &Scene<Radiometric>, camera: &Camera, options: PathOptions) -> Counts64 {
    let s = &scene.settings;
    let objects = scene.objects.len().max(1) as f64;
    let per_path = 2.0 * (1.0 + options.max_depth as f64);
    let n = (budget::PILOT_TESTS / (objects * per_path)).clamp(16.0, 1024.0);
    let aspect = s.width as f64 / s.height as f64;
    let cols = ((n * aspect).sqrt().round() as u32).clamp(1, s.width);
    let rows = ((n / aspect).sqrt().round() as u32).clamp(1, s.height);
    let rays = CameraRays::new(camera, s.width, s.height);
    let mut counts = Counts::default();
    let paths = cols as u64 * rows as u64;
    for k in 0..paths {
        let (i, j) = (k % cols as u64, k / cols as u64);
        let x = (i as f64 + 0.5) / cols as f64 * s.width as f64;
        let y = (j as f64 + 0.5) / rows as f64 * s.height as f64;
        let mut rng = Rng::new(PILOT_SEED ^ k);
        let u = (k as f64 + 0.5) / paths as f64;
        let lambdas = SampledWavelengths::sample_uniform(u, Band::VISIBLE);
        li_counted(
            scene,
            &rays.ray(x, y),
            lambdas,
            &mut rng,
            options,
            &mut counts,
        );
    }
    let per = 1.0 / paths as f64;
    Counts64 {
        rays: counts.rays as f64 * per,
        vertices: counts.vertices as f64 * per,
        shadow_rays: counts.shadow_rays as f64 * per,
        grating_vertices: counts.grating_vertices as f64 * per,
    }
}

/// [`Counts`] per camera sample (means over the pilot's paths).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Counts64 {
    /// Rays tested against every object.
    pub rays: f64,
    /// Vertices shaded.
    pub vertices: f64,
    /// Shadow rays.
    pub shadow_rays: f64,
    /// Vertices on a grating.
    pub grating_vertices: f64,
}
