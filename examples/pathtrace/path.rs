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

use std::f64::consts::FRAC_1_PI;
use std::str::FromStr;

use diffraction::bsdf::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use diffraction::cie::cmf;
use diffraction::color::Xyz;
use diffraction::{Band, Bsdf, SampledWavelengths};
use glam::{DVec2, DVec3};
use indicatif::ProgressBar;
use rayon::prelude::*;

use crate::geometry::Ray;
use crate::radiometric::{
    nearest, nearest_emitter, occluded, offset, reflectance, sample_sphere, sphere_pdf, Emitter,
    Radiometry, Surface,
};
use crate::render::{CameraRays, Image, Rng};
use crate::scene::{Camera, Scene};
use crate::texture::hash64;

/// The integrator of a render (`--integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Integrator {
    /// The paper's Whitted-style tracer (for radiometric scenes: direct light from the
    /// emitters, integrated over each area light by its light samples).
    #[default]
    Whitted,
    /// The spectral path tracer of this module.
    Path,
}

impl FromStr for Integrator {
    type Err = String;
    fn from_str(s: &str) -> Result<Integrator, String> {
        match s {
            "whitted" => Ok(Integrator::Whitted),
            "path" => Ok(Integrator::Path),
            _ => Err("expected whitted or path".into()),
        }
    }
}

impl std::fmt::Display for Integrator {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Integrator::Whitted => "whitted",
            Integrator::Path => "path",
        })
    }
}

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

/// Renders with `integrator`: the Whitted renderer of `render`, or this module's path tracer
/// (which needs a radiometric scene).
pub fn render_with(
    integrator: Integrator,
    scene: &Scene,
    camera: &Camera,
    progress: bool,
    label: &str,
) -> Result<Image, String> {
    match integrator {
        Integrator::Whitted => Ok(crate::render::render(scene, camera, progress, label)),
        Integrator::Path => {
            let options = PathOptions {
                grating_sampler: true,
                max_depth: scene.settings.max_depth,
            };
            render(scene, camera, options, progress)
        }
    }
}

/// Renders a radiometric scene by path tracing, `settings.spp` paths per pixel (stratified
/// over the pixel, four wavelengths each), in linear sRGB.
pub fn render(
    scene: &Scene,
    camera: &Camera,
    options: PathOptions,
    progress: bool,
) -> Result<Image, String> {
    let Some(r) = &scene.radiometry else {
        return Err(format!(
            "{}: the path integrator needs a radiometric scene (a [radiometry] table with the \
             camera's exposure, gratings of model \"radiometric\")",
            scene.name
        ));
    };
    let s = &scene.settings;
    let (w, h) = (s.width, s.height);
    let rays = CameraRays::new(camera, w, h);
    let bar = if progress {
        ProgressBar::new(h as u64)
    } else {
        ProgressBar::hidden()
    };
    let cols = (s.spp as f64).sqrt().ceil() as u32;
    let rows = s.spp.div_ceil(cols);
    let mut pixels = vec![DVec3::ZERO; (w as usize) * (h as usize)];
    pixels
        .par_chunks_mut(w as usize)
        .enumerate()
        .for_each(|(y, row)| {
            for (x, out) in row.iter_mut().enumerate() {
                let mut rng = Rng::new(s.seed ^ hash64(((y as u64) << 32) | x as u64) ^ 0x9a7);
                let mut sum = Xyz::default();
                for i in 0..s.spp {
                    let (cx, cy) = ((i % cols) as f64, (i / cols) as f64);
                    let jx = (cx + rng.next_f64()) / cols as f64;
                    let jy = (cy + rng.next_f64()) / rows as f64;
                    let ray = rays.ray(x as f64 + jx, y as f64 + jy);
                    // The hero stratified over the pixel's samples too.
                    let u = (i as f64 + rng.next_f64()) / s.spp as f64;
                    let lambdas = SampledWavelengths::sample_uniform(u, Band::VISIBLE);
                    let l = li(scene, r, &ray, lambdas, &mut rng, options);
                    sum += film_xyz(&lambdas, l);
                }
                let c = (sum * (r.exposure / s.spp as f64)).to_linear_srgb();
                *out = DVec3::new(c.r, c.g, c.b);
            }
            bar.inc(1);
        });
    bar.finish_and_clear();
    Ok(Image {
        width: w,
        height: h,
        pixels,
    })
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

/// One BSDF sample of a [`Surface`].
struct SurfaceSample {
    /// Local direction toward the light.
    wi: DVec3,
    /// f·cos θi / p(hero) per wavelength.
    weight: [f64; 4],
    /// Densities under each wavelength (for MIS; unused for delta samples).
    pdf4: [f64; 4],
    /// The hero's density.
    pdf: f64,
    /// A delta lobe (no MIS) ...
    specular: bool,
    /// ... that disperses (the secondaries end).
    dispersive: bool,
}

impl Surface<'_> {
    /// f (1/sr, cosine excluded) of the lobes with a density, per wavelength.
    fn f4(&self, wo: DVec3, wi: DVec3, l: &SampledWavelengths) -> [f64; 4] {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return [0.0; 4];
        }
        let g = self.grating.map_or([0.0; 4], |b| b.f4(wo, wi, l));
        let lam = l.lambda();
        std::array::from_fn(|j| {
            reflectance(self.diffuse, lam[j]) * FRAC_1_PI + self.grating_weight * g[j]
        })
    }

    /// The density of [`sample`](Self::sample) at wi (its part with a density), per
    /// wavelength as hero.
    fn pdf4(&self, wo: DVec3, wi: DVec3, l: &SampledWavelengths, sampler: bool) -> [f64; 4] {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return [0.0; 4];
        }
        let [_, p_l, p_g] = self.lobe_probabilities();
        let cos = cosine_hemisphere_pdf(wi.z);
        let g = match self.grating {
            Some(b) if sampler && p_g > 0.0 => b.pdf4(wo, wi, l),
            _ => [cos; 4],
        };
        std::array::from_fn(|k| p_l * cos + p_g * g[k])
    }

    fn sample(
        &self,
        wo: DVec3,
        l: &SampledWavelengths,
        rng: &mut Rng,
        sampler: bool,
    ) -> Option<SurfaceSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let [p_s, p_l, _] = self.lobe_probabilities();
        let uc = rng.next_f64();
        let u2 = DVec2::new(rng.next_f64(), rng.next_f64());
        if uc < p_s {
            let wi = DVec3::new(-wo.x, -wo.y, wo.z);
            let lam = l.lambda();
            let k = self.mirror / p_s;
            return Some(SurfaceSample {
                wi,
                weight: std::array::from_fn(|j| reflectance(self.tint, lam[j]) * k),
                pdf4: [0.0; 4],
                pdf: p_s,
                specular: true,
                dispersive: false,
            });
        }
        let wi = match self.grating {
            Some(b) if sampler && uc >= p_s + p_l => {
                // Reuse uc's remaining randomness for the order choice.
                let uo = ((uc - p_s - p_l) / (1.0 - p_s - p_l)).clamp(0.0, 1.0 - f64::EPSILON);
                let s = b.sample(wo, l.hero(), uo, u2)?;
                if s.flags.is_specular() {
                    let p_g = 1.0 - p_s - p_l;
                    let w = self.grating_weight * s.weight() / p_g;
                    return Some(SurfaceSample {
                        wi: s.wi,
                        weight: [w, 0.0, 0.0, 0.0],
                        pdf4: [0.0; 4],
                        pdf: s.pdf * p_g,
                        specular: true,
                        dispersive: true,
                    });
                }
                s.wi
            }
            _ => sample_cosine_hemisphere(u2),
        };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf4 = self.pdf4(wo, wi, l, sampler);
        let pdf = pdf4[0];
        if !(pdf > 0.0 && pdf.is_finite()) {
            return None;
        }
        let f = self.f4(wo, wi, l);
        Some(SurfaceSample {
            wi,
            weight: std::array::from_fn(|j| f[j] * wi.z / pdf),
            pdf4,
            pdf,
            specular: false,
            dispersive: false,
        })
    }
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
    scene: &Scene,
    r: &Radiometry,
    camera_ray: &Ray,
    mut lambdas: SampledWavelengths,
    rng: &mut Rng,
    options: PathOptions,
) -> [f64; 4] {
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
        let hit = nearest(scene, &ray, f64::INFINITY);
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
        let wo = surface.frame.to_local(-ray.dir);
        let origin = offset(&hit);

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
                if wi.z > 0.0
                    && wo.z > 0.0
                    && !occluded(scene, &Ray::new(origin, dir), dist * (1.0 - 1e-9))
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
