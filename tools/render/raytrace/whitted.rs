//! The Whitted-style tracer of the paper: nearest hits, hard (or softly sampled) shadows,
//! mirror recursion, and the paper's illumination model (eq. 12, the crate's `Illumination`)
//! with the crate's diffraction colours.

use std::sync::Arc;

use diffraction::frame::ShadingFrame;
use diffraction::ColorTable;
use glam::DVec3;

use crate::camera::{self, Camera, CameraRays};
use crate::footprint::{self, Filter, Footprint};
use crate::geometry::{nearest, occluded, Hit, Ray, SHADOW_REACH};
use crate::model::Paper;
use crate::output::Image;
use crate::sampling::{Rng, Strata};
use crate::scene::{Light, Scene};

/// A scene ready for the paper's renderer: the scene, each material's exposure, and the
/// colour tables of `--filter`.
#[derive(Debug, Clone)]
pub struct PaperScene {
    pub scene: Scene<Paper>,
    /// Per material: the scale of its diffraction XYZ ([`crate::model::exposure`]).
    pub exposures: Vec<f64>,
    /// How the diffraction colour is filtered (`--filter`).
    pub filter: Filter,
    /// The colour table of each material, where `filter` uses one (`None` otherwise).
    pub tables: Vec<Option<Arc<ColorTable>>>,
}

/// Renders the scene from `camera` with the scene's settings.
pub fn render(p: &PaperScene, camera: &Camera, progress: Option<&str>) -> Image {
    let s = &p.scene.settings;
    let rays = CameraRays::new(camera, s.width, s.height);
    let trace_sample = |c: &camera::CameraSample, rng: &mut Rng| {
        let ray = rays.ray(c.point.x, c.point.y);
        if p.filter != Filter::Footprint {
            return trace(p, &ray, None, 0, rng);
        }
        // The footprint is the sample's stratum cell (the pixel at 1 spp): the rays through
        // the midpoints of its edges, whatever the jitter.
        let (x, y) = (c.pixel.0 as f64, c.pixel.1 as f64);
        let (cw, ch) = (1.0 / c.grid.0 as f64, 1.0 / c.grid.1 as f64);
        let (mx, my) = (
            x + (c.cell.0 as f64 + 0.5) * cw,
            y + (c.cell.1 as f64 + 0.5) * ch,
        );
        let fp = [
            rays.ray(mx - 0.5 * cw, my),
            rays.ray(mx + 0.5 * cw, my),
            rays.ray(mx, my - 0.5 * ch),
            rays.ray(mx, my + 0.5 * ch),
        ];
        trace(p, &ray, Some(&fp), 0, rng)
    };
    camera::render(s, 0, progress, trace_sample, |sum| sum / s.spp as f64)
}

/// The sky seen along `dir`: `background` at the horizon and below, `zenith` straight up.
pub fn sky(scene: &Scene<Paper>, dir: DVec3) -> DVec3 {
    let env = &scene.units;
    let t = dir.y.clamp(0.0, 1.0);
    env.background + (env.zenith - env.background) * t
}

/// The fraction of `light` visible from `origin`: one shadow ray for a point light, `samples`
/// stratified rays ([`Strata`]) toward a disc of the light's radius facing the point for a
/// spherical one.
pub fn visibility(scene: &Scene<Paper>, origin: DVec3, light: &Light, rng: &mut Rng) -> f64 {
    let objects = &scene.objects;
    if light.radius <= 0.0 {
        let to = light.position - origin;
        let dist = to.length();
        return if occluded(objects, &Ray::new(origin, to), dist * SHADOW_REACH) {
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
        if !occluded(objects, &Ray::new(origin, to), dist * SHADOW_REACH) {
            seen += 1;
        }
    }
    seen as f64 / n as f64
}

/// The linear sRGB radiance along `ray`, with the offset rays of its pixel footprint for
/// [`Filter::Footprint`] (`None`: the colour at the ray's own u).
pub fn trace(
    p: &PaperScene,
    ray: &Ray,
    fp: Option<&Footprint>,
    depth: u32,
    rng: &mut Rng,
) -> DVec3 {
    match nearest(&p.scene.objects, ray, f64::INFINITY) {
        None => sky(&p.scene, ray.dir),
        Some(hit) => shade(p, ray, fp, &hit, depth, rng),
    }
}

/// The paper's illumination model at a hit (eq. 12, rendering steps 1-8), by the crate's
/// [`Illumination::shade`](diffraction::Illumination::shade): ambient + Σ_lights visibility ·
/// light · (k_d·albedo·cos θi + k_diffraction·diffraction), plus mirror reflection for
/// reflective materials.
///
/// For a diffraction grating (steps 3-5) the grating vector t at the hit comes from the
/// material's field in the surface's tangent coordinates, the frame (normal, t) gives local wi
/// and wo, and u = wi.x + wo.x = (wi + wo)·t. The diffraction colour (steps 6-8) is the crate's
/// spectral colour XYZ of the material's model at (wi, wo) (for Agu-Hill a function of u),
/// scaled by the material's exposure and converted to linear sRGB. Materials without a grating
/// never call the spectral code.
///
/// With a colour table for the material ([`crate::footprint`]) the diffraction XYZ is the
/// table's: its mean over the footprint's interval of u for [`Filter::Footprint`], its lookup
/// at u for [`Filter::Point`], scaled the same way.
fn shade(
    p: &PaperScene,
    ray: &Ray,
    fp: Option<&Footprint>,
    hit: &Hit,
    depth: u32,
    rng: &mut Rng,
) -> DVec3 {
    let scene = &p.scene;
    let index = scene.objects[hit.object].material;
    let material = &scene.materials[index];
    let table = p.tables.get(index).and_then(Option::as_deref);
    let exposure = p.exposures[index];
    let n = hit.normal;
    let wo = -ray.dir;
    let origin = hit.spawn_point();

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

    // Steps 2, 3 and 5-8 for each light: its visible part, its cosine and the diffraction
    // colour toward it; eq. 12 sums them with the ambient term.
    let lights = scene.lights.iter().filter_map(|light| {
        let wi = (light.position - hit.point).normalize();
        let cos = n.dot(wi);
        if cos <= 0.0 {
            return None;
        }
        let vis = visibility(scene, origin, light, rng);
        if vis == 0.0 {
            return None;
        }
        let mut diffracted = DVec3::ZERO;
        if let Some((g, frame)) = &grating {
            // Steps 3 and 5: local directions and the phase projection.
            let (wi_l, wo_l) = (frame.to_local(wi), frame.to_local(wo));
            if wi_l.z > 0.0 && wo_l.z > 0.0 {
                // Steps 6-8: the spectral colour of the diffraction term.
                let u = wi_l.x + wo_l.x;
                let xyz = match (table, p.filter, fp) {
                    (Some(table), Filter::Footprint, Some(fp)) => {
                        let range =
                            footprint::interval(scene, g, ray, hit, fp, light).unwrap_or((u, u));
                        table.mean(range.0, range.1).scale(exposure)
                    }
                    (Some(table), Filter::Point, _) => table.mean(u, u).scale(exposure),
                    _ => g
                        .model
                        .xyz(&scene.spectral, wo_l, wi_l, g.strategy, exposure),
                };
                let rgb = xyz.to_linear_srgb();
                diffracted = DVec3::new(rgb.r, rgb.g, rgb.b);
            }
        }
        Some((light.color * vis, cos, diffracted))
    });
    let mut color = material.shading.shade(scene.units.ambient, albedo, lights);

    if material.mirror > 0.0 && depth < scene.settings.max_depth {
        let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
        let next = Ray::new(origin, dir);
        let next_fp = fp.map(|fp| footprint::reflect(scene, fp, hit, &next));
        let reflected = trace(p, &next, next_fp.as_ref(), depth + 1, rng);
        color =
            color * (1.0 - material.mirror) + material.mirror_tint * reflected * material.mirror;
    }
    color
}
