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
//!
//! A grating with tabulated order efficiencies (a preset) and a Gaussian groove spread is
//! coloured from its `ColorTable` over (u, incidence), built once per material before the
//! render ([`Tables`]): a lookup of about 0.1 µs where the generic path took 0.3-1 ms a colour
//! (docs/color_table.md, "Tabulated efficiencies").

use diffraction::color::Xyz;
use diffraction::relief::Preset;
use diffraction::spectrum::GenericStrategy;
use diffraction::{ColorTable, GratingBsdf, GrooveKind, SpectralResponse};
use glam::DVec3;

use crate::camera::{self, Camera, CameraRays};
use crate::colour::Colour;
use crate::geometry::{nearest, occluded, Ray, SHADOW_REACH};
use crate::material::GratingMaterial;
use crate::output::Image;
use crate::radiometry::{Radiometric, Radiometry};
use crate::sampling::{Rng, Strata};
use crate::scene::Scene;
use crate::surface::{nearest_emitter, sample_sphere, Surface};

/// The accuracy of the colour tables of tabulated gratings: 10⁻³, whose table of the CD
/// preset (N = 34, σ = 0.02, D65) read classically builds in about 5 s and stays within 0.071
/// ΔE2000 of the generic colour, read conically in about 20 s within a mean of 0.07-0.15 for
/// |wi.y| up to 0.6 (tests/tabulated_color_table.rs).
const TABLE_ACCURACY: f64 = 1e-3;

/// The cost of a table's `xyz`, ns: measured 53-55 ns (the CD preset, benches/color_table.rs;
/// 86-106 ns before its lookup located the incidence with one division), counted with a margin.
pub const TABLE_LOOKUP_NS: f64 = 100.0;
/// The cost of building one table at [`TABLE_ACCURACY`], ns, per preset: the measured builds
/// (one core of the shared 2-core machine, D65, N = 34, Gaussian σ = 0.02; docs/color_table.md)
/// with a margin. Read classically: the CD 4.3 s, the foil 4.2 s, the DVD 35 s (the
/// mirror-symmetric presets build one grid per incidence node), `blazed600` 60-66 s; with 8
/// grooves the CD 1.7 s, the foil 3.1 s and the DVD 26 s, so the N = 34 figures stand for any
/// N. Read conically (the presets' default: 9 planes of |wi.y|; `conical_presets_build_times`
/// in tests/tabulated_color_table.rs, beside another build): the CD 20 s, the foil 32 s, the
/// DVD 44 s, `blazed600` 211 s. A table file's cost is not known before its table is built:
/// it counts as the dearest preset's.
pub fn table_build_ns(g: &GratingMaterial<GratingBsdf>) -> f64 {
    let conical = g
        .model
        .order_efficiency()
        .table()
        .is_some_and(|t| t.is_conical());
    match (g.preset, conical) {
        (Some(Preset::Cd), true) => 4e10,
        (Some(Preset::Foil), true) => 6e10,
        (Some(Preset::Dvd), true) => 9e10,
        (_, true) => 4e11,
        (Some(Preset::Cd | Preset::Foil), false) => 8e9,
        (Some(Preset::Dvd), false) => 6e10,
        // `blazed600`, a table file (and any preset added later).
        (_, false) => 7.5e10,
    }
}

/// Whether the Whitted renderer colours grating material `g` from a colour table: tabulated
/// efficiencies (a conical table's on its planes of |wi.y|, as `ColorTable` takes it), finite
/// N, a groove spread that does not depend on λ, and a colour that is an integral
/// (`Colour::Integral`).
pub fn tabled(g: &GratingMaterial<GratingBsdf>) -> bool {
    let b = &g.model;
    let tabulated = b.order_efficiency().is_tabulated();
    let groove = !matches!(b.groove().kind(), GrooveKind::CoherenceLength { .. });
    let finite = b.grating().slits().as_f64().is_finite();
    tabulated && groove && finite && matches!(g.strategy, Colour::Integral(_))
}

/// The colour tables of the scene's tabulated gratings, one per material (`None` where the
/// material has no grating, an amplitude one, or one no table takes: a coherence-length
/// groove, whose colour the generic path integrates).
#[derive(Default)]
pub struct Tables(Vec<Option<ColorTable>>);

impl Tables {
    /// The tables of every tabulated grating of `scene` whose colour is an integral
    /// (`Colour::Integral`), built under its illuminant.
    pub fn new(scene: &Scene<Radiometric>) -> Tables {
        let table = |g: &GratingMaterial<GratingBsdf>| {
            tabled(g)
                .then(|| ColorTable::new(&scene.spectral, &g.model, TABLE_ACCURACY).ok())
                .flatten()
        };
        Tables(
            scene
                .materials
                .iter()
                .map(|m| m.grating.as_ref().and_then(table))
                .collect(),
        )
    }

    /// The table of material `m`.
    fn get(&self, m: usize) -> Option<&ColorTable> {
        self.0.get(m).and_then(Option::as_ref)
    }
}

/// Renders a radiometric scene Whitted-style, `settings.spp` stratified samples per pixel.
pub fn render(scene: &Scene<Radiometric>, camera: &Camera, progress: Option<&str>) -> Image {
    let s = &scene.settings;
    let tables = Tables::new(scene);
    let rays = CameraRays::new(camera, s.width, s.height);
    let sample = |c: &camera::CameraSample, rng: &mut Rng| {
        trace_with(scene, &tables, &rays.ray(c.point.x, c.point.y), 0, rng)
    };
    camera::render(s, 0, progress, sample, |sum| sum / s.spp as f64)
}

/// The linear sRGB radiance along `ray` (film units: times the exposure), Whitted-style: the
/// emitters and the sky seen directly, direct light from every emitter (point lights by one
/// shadow ray, spherical ones by `samples` stratified directions uniform in their cone, each
/// with its shadow ray), mirror recursion up to `max_depth`. Diffuse interreflection and the
/// sky's light on surfaces are left out (the path integrator has them).
#[cfg(test)]
pub fn trace(scene: &Scene<Radiometric>, ray: &Ray, depth: u32, rng: &mut Rng) -> DVec3 {
    trace_with(scene, &Tables::default(), ray, depth, rng)
}

/// [`trace`] with the colour tables of the scene's tabulated gratings.
pub fn trace_with(
    scene: &Scene<Radiometric>,
    tables: &Tables,
    ray: &Ray,
    depth: u32,
    rng: &mut Rng,
) -> DVec3 {
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
    let table = tables.get(scene.objects[hit.object].material);
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
                        // Tabulated efficiencies (η depends on λ and the incidence): the
                        // material's table, else the generic rule of the same name
                        // (`Colour::generic`).
                        None => match table {
                            Some(t) => t.xyz(wo_l, wi_l),
                            None => {
                                let rule = Colour::Integral(s)
                                    .generic()
                                    .unwrap_or(GenericStrategy::WINDOWS);
                                scene.spectral.xyz_brdf(b, wo_l, wi_l, rule)
                            }
                        },
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
        let reflected = trace_with(scene, tables, &Ray::new(origin, dir), depth + 1, rng);
        rgb += surface.tint * reflected * surface.mirror;
    }
    rgb
}

/// XYZ of radiance to the film's linear sRGB (times the exposure).
pub fn film(r: &Radiometry, xyz: Xyz) -> DVec3 {
    let c = (xyz * r.exposure).to_linear_srgb();
    DVec3::new(c.r, c.g, c.b)
}
