//! Physical units for the reference ray tracer: the scene's `[radiometry]` table, spectral
//! emitters (spherical area lights, point lights, a sky), the energy-normalised grating
//! (`model = "radiometric"`, the crate's `GratingBsdf`), and the Whitted-style renderer of
//! such scenes (direct light integrated over each area light, mirror recursion).
//!
//! # Units
//!
//! * Every emitter has the spectrum s(λ) = E(λ)/E(560 nm) of the scene's illuminant
//!   (`render.illuminant`: D65, E or A), scaled by one number: a spherical light's `intensity`
//!   is its spectral **radiance** at 560 nm, W·sr⁻¹·m⁻²·nm⁻¹; a point light's (radius 0) is its
//!   spectral **radiant intensity** at 560 nm, W·sr⁻¹·nm⁻¹ (lengths in the scene's units are
//!   read as metres); the sky's `sky_horizon` and `sky_zenith` are radiances like a spherical
//!   light's. A light's `color` must be white: its colour is its spectrum.
//! * The camera's `exposure` (sr·m²/W) turns radiance into the film's tristimulus values:
//!   XYZ = exposure · ∫ L(λ)·cmf(λ) dλ over 360-830 nm, then the crate's pipeline (XYZ → linear
//!   sRGB → Hall clipping → sRGB). There is no per-material exposure: a grating is as bright
//!   as the light it diffracts.
//! * Diffuse colours (linear sRGB) become reflectance spectra by a box upsampling: the red
//!   value above 585 nm, green on 490-585 nm, blue below 490 nm. White stays white (ρ = 1 at
//!   every λ) and greys stay flat; saturated colours are approximations.
//! * A material is `mirror·tint·δ + (1 − mirror)·(diffuse·colour/π + grating)`, the grating
//!   the crate's radiometric BSDF (`f` in 1/sr). The scene is refused if some material could
//!   reflect more than it receives (mirror + (1 − mirror)·(diffuse·max colour + w/d) > 1).

use diffraction::cie::{cmf, Illuminant};
use diffraction::color::Xyz;
use diffraction::frame::ShadingFrame;
use diffraction::spectrum::Strategy;
use diffraction::{Band, Grating, GratingBsdf, GrooveSpread};
use glam::{DVec2, DVec3};
use serde::Deserialize;

use crate::diagnostics::FieldError;
use crate::geometry::{Hit, Ray};
use crate::material::{Material, Model};
use crate::render::Rng;
use crate::scene::{Light, Scene};

/// The largest accepted camera exposure, sr·m²/W.
pub const MAX_EXPOSURE: f64 = 1e12;
/// The largest accepted radiance or intensity at 560 nm (W·sr⁻¹·m⁻²·nm⁻¹ or W·sr⁻¹·nm⁻¹).
pub const MAX_RADIANCE: f64 = 1e12;

/// The `[radiometry]` table of a scene file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRadiometry {
    /// The camera's exposure, sr·m²/W.
    pub exposure: f64,
    /// The sky's radiance at 560 nm at and below the horizon.
    pub sky_horizon: Option<f64>,
    /// The sky's radiance at 560 nm straight up (default: `sky_horizon`).
    pub sky_zenith: Option<f64>,
}

/// One emitter of a radiometric scene, in the order of the scene's `[[lights]]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Emitter {
    pub center: DVec3,
    /// 0 for a point light.
    pub radius: f64,
    /// Radiance (sphere) or intensity (point) at 560 nm.
    pub scale: f64,
    /// Stratified directions per hit of the Whitted renderer.
    pub samples: u32,
}

/// The physical units of a radiometric scene (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Radiometry {
    pub exposure: f64,
    /// Sky radiance at 560 nm at the horizon and straight up.
    pub sky: [f64; 2],
    pub spectrum: Illuminant,
    pub emitters: Vec<Emitter>,
    /// ∫ s·cmf dλ: the XYZ of a unit-radiance emitter.
    pub white: Xyz,
    /// ∫ s·ȳ dλ (= `white.y`).
    pub ys: f64,
    /// ∫ s·B_c·cmf dλ for the box basis of red, green and blue.
    pub basis: [Xyz; 3],
}

/// The box upsampling's channel at λ: 0 red (≥ 585 nm), 1 green (490-585 nm), 2 blue.
fn channel(lambda_nm: f64) -> usize {
    if lambda_nm >= 585.0 {
        0
    } else if lambda_nm >= 490.0 {
        1
    } else {
        2
    }
}

/// The reflectance spectrum of a linear-sRGB colour at λ (box upsampling, clamped to [0, 1]).
pub fn reflectance(rgb: DVec3, lambda_nm: f64) -> f64 {
    rgb.to_array()[channel(lambda_nm)].clamp(0.0, 1.0)
}

impl Radiometry {
    /// Builds the units from the table, the scene's lights and illuminant.
    pub fn new(
        raw: &RawRadiometry,
        lights: &[Light],
        intensities: &[(DVec3, f64)],
        spectrum: Illuminant,
    ) -> Result<Radiometry, FieldError> {
        let range = |path: &str, v: f64, max: f64| -> Result<f64, FieldError> {
            if v.is_finite() && v >= 0.0 && v <= max {
                Ok(v)
            } else {
                Err(FieldError::new(
                    path,
                    format!("expected a number in [0, {max:e}], got {v}"),
                ))
            }
        };
        let exposure = range("radiometry.exposure", raw.exposure, MAX_EXPOSURE)?;
        let horizon = range(
            "radiometry.sky_horizon",
            raw.sky_horizon.unwrap_or(0.0),
            MAX_RADIANCE,
        )?;
        let zenith = range(
            "radiometry.sky_zenith",
            raw.sky_zenith.unwrap_or(horizon),
            MAX_RADIANCE,
        )?;
        let mut emitters = Vec::with_capacity(lights.len());
        for (i, (l, &(color, intensity))) in lights.iter().zip(intensities).enumerate() {
            if color != DVec3::ONE {
                return Err(FieldError::new(
                    format!("lights[{i}].color"),
                    "expected [1, 1, 1] or nothing: in a radiometric scene a light's colour is \
                     its spectrum, the scene's illuminant",
                ));
            }
            emitters.push(Emitter {
                center: l.position,
                radius: l.radius,
                scale: range(&format!("lights[{i}].intensity"), intensity, MAX_RADIANCE)?,
                samples: l.samples,
            });
        }
        let s560 = spectrum.power(560.0);
        let s = |l: f64| spectrum.power(l) / s560;
        // Simpson on every 1 nm row: exact for the products of the linearly interpolated
        // tables, which are quadratic between rows (the box edges are on rows).
        let mut white = [0.0; 3];
        let mut basis = [[0.0; 3]; 3];
        let band = Band::VISIBLE;
        let rows = band.width_nm().round() as usize;
        for i in 0..rows {
            let a = band.min_nm() + i as f64;
            for (x, w) in [(a, 1.0 / 6.0), (a + 0.5, 4.0 / 6.0), (a + 1.0, 1.0 / 6.0)] {
                let c = cmf(x);
                // At a box edge the row belongs to the channel of its midpoint.
                let ch = channel(a + 0.5);
                for k in 0..3 {
                    white[k] += w * s(x) * c[k];
                    basis[ch][k] += w * s(x) * c[k];
                }
            }
        }
        let xyz = |v: [f64; 3]| Xyz::new(v[0], v[1], v[2]);
        Ok(Radiometry {
            exposure,
            sky: [horizon, zenith],
            spectrum,
            emitters,
            white: xyz(white),
            ys: white[1],
            basis: [xyz(basis[0]), xyz(basis[1]), xyz(basis[2])],
        })
    }

    /// The relative spectrum s(λ) = E(λ)/E(560).
    pub fn s(&self, lambda_nm: f64) -> f64 {
        self.spectrum.power(lambda_nm) / self.spectrum.power(560.0)
    }

    /// The sky's radiance scale (at 560 nm) along `dir`: horizon below, linear in dir.y above.
    pub fn sky_scale(&self, dir: DVec3) -> f64 {
        let t = dir.y.clamp(0.0, 1.0);
        self.sky[0] + (self.sky[1] - self.sky[0]) * t
    }

    /// The film XYZ of a diffuse reflection of unit-radiance light by `rgb` (box upsampling).
    pub fn diffuse_xyz(&self, rgb: DVec3) -> Xyz {
        let c = rgb.clamp(DVec3::ZERO, DVec3::ONE);
        self.basis[0] * c.x + self.basis[1] * c.y + self.basis[2] * c.z
    }
}

/// Checks the `[radiometry]` table against the scene's materials: every grating radiometric,
/// every material passive, and a radiometric grating only in a scene with the table.
pub fn check_materials(materials: &[Material], radiometric: bool) -> Result<(), FieldError> {
    for (i, m) in materials.iter().enumerate() {
        let path = format!("objects[{i}].material");
        let grating = m.grating.as_ref();
        let is_radiometric = grating.is_some_and(|g| matches!(g.model, Model::Radiometric(_)));
        if !radiometric {
            if is_radiometric {
                return Err(FieldError::new(
                    format!("{path}.model"),
                    "model \"radiometric\" needs a [radiometry] table (the camera's exposure)",
                ));
            }
            continue;
        }
        if grating.is_some() && !is_radiometric {
            return Err(FieldError::new(
                format!("{path}.model"),
                "a scene with a [radiometry] table takes gratings of model \"radiometric\" \
                 only (the other models have no physical units)",
            ));
        }
        let duty = match grating.map(|g| &g.model) {
            Some(Model::Radiometric(b)) => b.grating().slit_width_nm() / b.grating().period_nm(),
            _ => 0.0,
        };
        let diffuse = m.shading.coefficients().1 * max_albedo(m);
        let total = m.mirror * m.mirror_tint.max_element() + (1.0 - m.mirror) * (diffuse + duty);
        if total > 1.0 + 1e-12 {
            return Err(FieldError::new(
                format!("{path}.diffuse"),
                format!(
                    "expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color \
                     + slit_width/period) is {total:.3}, above 1"
                ),
            ));
        }
    }
    Ok(())
}

/// An upper bound of a material's diffuse colour (textures: their brightest parameter).
fn max_albedo(m: &Material) -> f64 {
    use crate::material::Albedo;
    match &m.albedo {
        Albedo::Solid(c) => c.max_element(),
        Albedo::Wood(w) => w.light.max_element().max(w.dark.max_element()),
        // Image texels are in [0, 1].
        Albedo::Image { other, .. } => other.max_element().max(1.0),
    }
}

/// The radiometric grating of a scene's grating material: `slit_width_nm` (default d/2),
/// `slits` (default 1000), and the spread along the grooves, either `coherence_nm` (a
/// coherence length, default N·d) or `groove_sigma` (a Gaussian, groove roughness).
pub fn grating_model(
    period: f64,
    slit_width: Option<f64>,
    slits: Option<u64>,
    coherence_nm: Option<f64>,
    groove_sigma: Option<f64>,
    path: &str,
) -> Result<Model, FieldError> {
    let f = |name: &str| format!("{path}.{name}");
    let slits = slits.unwrap_or(1000);
    if !(1..=u32::MAX as u64).contains(&slits) {
        return Err(FieldError::new(
            f("slits"),
            format!("expected an integer in [1, {}], got {slits}", u32::MAX),
        ));
    }
    let grating = Grating::new(period, slit_width.unwrap_or(period / 2.0), slits as u32)
        .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?;
    let groove = match (coherence_nm, groove_sigma) {
        (Some(_), Some(_)) => {
            return Err(FieldError::new(
                f("groove_sigma"),
                "give either coherence_nm or groove_sigma, not both",
            ))
        }
        (Some(l), None) => Some((
            GrooveSpread::CoherenceLength { length_nm: l },
            "coherence_nm",
        )),
        (None, Some(s)) => Some((GrooveSpread::Gaussian { sigma: s }, "groove_sigma")),
        (None, None) => None,
    };
    let bsdf = match groove {
        None => GratingBsdf::new(grating),
        Some((g, key)) => GratingBsdf::new(grating)
            .with_groove(g)
            .map_err(|e| FieldError::new(f(key), e.to_string()))?,
    };
    Ok(Model::Radiometric(Box::new(bsdf)))
}

// ------------------------------------------------------------------------------------------
// Geometry of the emitters, shared by both integrators.

/// The nearest scene hit along `ray` before `t_max`.
pub fn nearest(scene: &Scene, ray: &Ray, t_max: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, obj) in scene.objects.iter().enumerate() {
        let t = best.map_or(t_max, |b| b.t);
        if let Some(hit) = obj.intersect(ray, t, i) {
            best = Some(hit);
        }
    }
    best
}

/// Whether anything lies on `ray` in (ε, t_max).
pub fn occluded(scene: &Scene, ray: &Ray, t_max: f64) -> bool {
    scene.objects.iter().any(|o| o.occludes(ray, t_max))
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

// ------------------------------------------------------------------------------------------
// The surface at a hit, shared by both integrators.

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
    pub strategy: Strategy,
}

impl<'a> Surface<'a> {
    /// The surface of `hit` (seen from direction `-ray_dir`).
    pub fn at(scene: &'a Scene, hit: &Hit) -> Surface<'a> {
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
            match &g.model {
                Model::Radiometric(b) => Some((b.as_ref(), frame)),
                _ => None,
            }
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

// ------------------------------------------------------------------------------------------
// The Whitted renderer of radiometric scenes.

/// The linear sRGB radiance along `ray` (film units: times the exposure), Whitted-style: the
/// emitters and the sky seen directly, direct light from every emitter (point lights by one
/// shadow ray, spherical ones by `samples` stratified directions uniform in their cone, each
/// with its shadow ray), mirror recursion up to `max_depth`. Diffuse interreflection and the
/// sky's light on surfaces are left out (the path integrator has them).
pub fn whitted(scene: &Scene, r: &Radiometry, ray: &Ray, depth: u32, rng: &mut Rng) -> DVec3 {
    let hit = nearest(scene, ray, f64::INFINITY);
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
    let origin = offset(&hit);
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
                let g = scene.spectral.xyz_brdf(b, wi_l, wo_l, surface.strategy);
                c += g * (r.ys * surface.grating_weight);
            }
            *xyz += c * weight;
        };
        if e.radius <= 0.0 {
            let to = e.center - hit.point;
            let dist = to.length();
            if n.dot(to) <= 0.0 || occluded(scene, &Ray::new(origin, to), dist * (1.0 - 1e-9)) {
                continue;
            }
            light(to / dist, e.scale / (dist * dist), &mut xyz);
            continue;
        }
        let k = e.samples.max(1);
        let cols = (k as f64).sqrt().ceil() as u32;
        let rows = k.div_ceil(cols);
        for i in 0..k {
            let u = DVec2::new(
                ((i % cols) as f64 + rng.next_f64()) / cols as f64,
                ((i / cols) as f64 + rng.next_f64()) / rows as f64,
            );
            let Some((dir, dist, pdf)) = sample_sphere(origin, e, u) else {
                continue;
            };
            if n.dot(dir) <= 0.0 || occluded(scene, &Ray::new(origin, dir), dist * (1.0 - 1e-9)) {
                continue;
            }
            light(dir, e.scale / (pdf * k as f64), &mut xyz);
        }
    }
    let mut rgb = film(r, xyz);
    if surface.mirror > 0.0 && depth < scene.settings.max_depth {
        let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
        let reflected = whitted(scene, r, &Ray::new(origin, dir), depth + 1, rng);
        rgb += surface.tint * reflected * surface.mirror;
    }
    rgb
}

/// XYZ of radiance to the film's linear sRGB (times the exposure).
pub fn film(r: &Radiometry, xyz: Xyz) -> DVec3 {
    let c = (xyz * r.exposure).to_linear_srgb();
    DVec3::new(c.r, c.g, c.b)
}

/// The origin of secondary rays from a hit, off the surface on the side of its normal.
pub fn offset(hit: &Hit) -> DVec3 {
    hit.point + hit.normal * (1e-7 * (1.0 + hit.point.abs().max_element()))
}

/// The scene's radiometry from its `[radiometry]` table (`None` without one), with the checks
/// of [`check_materials`]. `lights` pairs the built lights with each one's `color` and
/// `intensity` keys as written.
pub fn build(
    raw: Option<&RawRadiometry>,
    lights: (
        &[Light],
        impl Iterator<Item = (Option<[f64; 3]>, Option<f64>)>,
    ),
    materials: &[Material],
    spectrum: Illuminant,
) -> Result<Option<Radiometry>, FieldError> {
    check_materials(materials, raw.is_some())?;
    let Some(raw) = raw else {
        return Ok(None);
    };
    let keys: Vec<(DVec3, f64)> = lights
        .1
        .map(|(c, i)| (DVec3::from_array(c.unwrap_or([1.0; 3])), i.unwrap_or(1.0)))
        .collect();
    Radiometry::new(raw, lights.0, &keys, spectrum).map(Some)
}
