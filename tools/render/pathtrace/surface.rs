//! The surface at a hit of a radiometric scene, as both integrators see it (a mirror share, a
//! Lambertian and the crate's grating BSDF, with its sampling), and the geometry of the
//! spherical emitters.

use std::f64::consts::FRAC_1_PI;

use crate::colour::Colour;
use diffraction::bsdf::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use diffraction::frame::ShadingFrame;
use diffraction::{Bsdf, DiffractionBrdf, GratingBsdf, SampledWavelengths};
use glam::{DVec2, DVec3};

use crate::geometry::{Hit, Ray};
use crate::radiometry::{reflectance, Emitter, Radiometric, Radiometry};
use crate::sampling::Rng;
use crate::scene::Scene;

/// The radiometric BSDF at a hit: a mirror share, a Lambertian and the grating, in the local
/// frame (z the normal, x the grating vector).
pub struct Surface<'a> {
    pub frame: ShadingFrame,
    /// The mirror share m and its tint.
    pub mirror: f64,
    pub tint: DVec3,
    /// (1 − m)·diffuse·colour, linear sRGB (box-upsampled per wavelength).
    pub diffuse: DVec3,
    /// The grating and its weight (1 − m).
    pub grating: Option<&'a GratingBsdf>,
    pub grating_weight: f64,
    pub strategy: Colour,
}

impl<'a> Surface<'a> {
    /// The surface of `hit` (seen from direction `-ray_dir`).
    pub fn at(scene: &'a Scene<Radiometric>, hit: &Hit) -> Surface<'a> {
        let material = &scene.materials[scene.objects[hit.object].material];
        let n = hit.normal;
        let mut albedo = None;
        let mut strategy = scene.settings.strategy;
        let grating = material.grating.as_ref().and_then(|g| {
            if g.is_plain_at(hit.p) {
                albedo = Some(g.plain_albedo);
                return None;
            }
            let t = g.field.world_direction(hit.p, hit.tangent, hit.bitangent)?;
            let frame = ShadingFrame::new(n, t)?;
            strategy = g.strategy;
            Some((&g.model, frame))
        });
        let albedo = albedo.unwrap_or_else(|| material.albedo.at(hit));
        let m = material.mirror;
        let frame = match grating {
            Some((_, f)) => f,
            None => {
                let (a, _) = n.any_orthonormal_pair();
                ShadingFrame::new(n, a).unwrap_or(ShadingFrame {
                    grating: DVec3::X,
                    groove: DVec3::Y,
                    normal: DVec3::Z,
                })
            }
        };
        Surface {
            frame,
            mirror: m,
            tint: material.mirror_tint,
            diffuse: albedo * (material.shading.coefficients().1 * (1.0 - m)),
            grating: grating.map(|(b, _)| b),
            grating_weight: 1.0 - m,
            strategy,
        }
    }

    /// The probabilities of choosing the mirror, the Lambertian and the grating lobe.
    pub fn lobe_probabilities(&self) -> [f64; 3] {
        let a_l = self.diffuse.max_element().max(0.0);
        let a_g = self.grating.map_or(0.0, |b| {
            self.grating_weight * b.grating().slit_width_nm() / b.grating().period_nm()
        });
        let rest = 1.0 - self.mirror;
        if a_l + a_g <= 0.0 {
            return [if self.mirror > 0.0 { 1.0 } else { 0.0 }, 0.0, 0.0];
        }
        [
            self.mirror,
            rest * a_l / (a_l + a_g),
            rest * a_g / (a_l + a_g),
        ]
    }

    /// Whether the surface has a lobe with a density (light sampling can reach it).
    pub fn has_density(&self) -> bool {
        let p = self.lobe_probabilities();
        p[1] + p[2] > 0.0
    }
}

/// One BSDF sample of a [`Surface`].
pub struct SurfaceSample {
    /// Local direction toward the light.
    pub wi: DVec3,
    /// f·cos θi / p(hero) per wavelength.
    pub weight: [f64; 4],
    /// Densities under each wavelength (for MIS; unused for delta samples).
    pub pdf4: [f64; 4],
    /// The hero's density.
    pub pdf: f64,
    /// A delta lobe (no MIS) ...
    pub specular: bool,
    /// ... that disperses (the secondaries end).
    pub dispersive: bool,
}

impl Surface<'_> {
    /// f (1/sr, cosine excluded) of the lobes with a density, per wavelength.
    pub fn f4(&self, wo: DVec3, wi: DVec3, l: &SampledWavelengths) -> [f64; 4] {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return [0.0; 4];
        }
        let g = self.grating.map_or([0.0; 4], |b| b.eval4(wo, wi, l));
        let lam = l.lambda();
        std::array::from_fn(|j| {
            reflectance(self.diffuse, lam[j]) * FRAC_1_PI + self.grating_weight * g[j]
        })
    }

    /// The density of [`sample`](Self::sample) at wi (its part with a density), per
    /// wavelength as hero.
    pub fn pdf4(&self, wo: DVec3, wi: DVec3, l: &SampledWavelengths, sampler: bool) -> [f64; 4] {
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

    pub fn sample(
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

/// The nearest spherical emitter along `ray` before `t_max`: (index, distance).
pub fn nearest_emitter(r: &Radiometry, ray: &Ray, t_max: f64) -> Option<(usize, f64)> {
    let mut best = None;
    let mut t_best = t_max;
    for (i, e) in r.emitters.iter().enumerate() {
        if e.radius <= 0.0 {
            continue;
        }
        if let Some(t) = sphere_hit(ray, e.center, e.radius) {
            if t < t_best {
                t_best = t;
                best = Some((i, t));
            }
        }
    }
    best
}

/// The first intersection t > 0 of `ray` (unit direction) with a sphere, from outside.
fn sphere_hit(ray: &Ray, c: DVec3, r: f64) -> Option<f64> {
    let oc = ray.origin - c;
    let b = oc.dot(ray.dir);
    let cc = oc.length_squared() - r * r;
    if cc <= 0.0 {
        return None; // inside: the sphere emits outward only
    }
    let disc = b * b - cc;
    if disc < 0.0 {
        return None;
    }
    let t = -b - disc.sqrt();
    (t > 0.0).then_some(t)
}

/// 1 − cos θmax of the cone a sphere of radius r subtends at distance dc > r (stable for
/// small cones).
fn one_minus_cos_max(dc: f64, r: f64) -> f64 {
    let sin2 = (r / dc).powi(2);
    sin2 / (1.0 + (1.0 - sin2).max(0.0).sqrt())
}

/// The solid-angle density of [`sample_sphere`] toward a direction inside the cone of the
/// sphere seen from `p` (0 when `p` is inside it).
pub fn sphere_pdf(p: DVec3, e: &Emitter) -> f64 {
    let dc = (e.center - p).length();
    if dc <= e.radius {
        return 0.0;
    }
    1.0 / (std::f64::consts::TAU * one_minus_cos_max(dc, e.radius))
}

/// A direction toward the visible cap of a spherical emitter, uniform in the solid angle of its
/// cone: (direction, distance to the sphere, density in solid angle).
pub fn sample_sphere(p: DVec3, e: &Emitter, u: DVec2) -> Option<(DVec3, f64, f64)> {
    let axis = e.center - p;
    let dc = axis.length();
    if dc <= e.radius || e.radius <= 0.0 {
        return None;
    }
    let axis = axis / dc;
    let om = one_minus_cos_max(dc, e.radius);
    let t = u.x * om; // 1 − cos θ
    let cos = 1.0 - t;
    let sin = (t * (2.0 - t)).max(0.0).sqrt();
    let phi = std::f64::consts::TAU * u.y;
    let (a, b) = axis.any_orthonormal_pair();
    let dir = (axis * cos + (a * phi.cos() + b * phi.sin()) * sin).normalize();
    // The near intersection; at the rim rounding can miss it: the tangent point's distance.
    let dist = sphere_hit(&Ray { origin: p, dir }, e.center, e.radius)
        .unwrap_or_else(|| (dc * dc - e.radius * e.radius).max(0.0).sqrt());
    Some((dir, dist, 1.0 / (std::f64::consts::TAU * om)))
}
