//! Footprint filtering of the Agu-Hill diffraction colour: one [`ColorTable`] per distinct
//! grating, built at scene load, and each hit's interval of u from the pixel's footprint (ray
//! differentials) and the light's angular size, averaged by [`ColorTable::mean`].
//!
//! A pixel sample carries four offset rays, through the midpoints of the edges of its stratum
//! cell (the pixel at 1 spp: ±½ pixel in x and in y around the pixel's centre), so that the
//! interval does not move with the jitter and the cells' means add up to the pixel's. At a grating hit each offset ray is intersected with the same object (or, where it
//! misses it, with the hit's tangent plane), and u = (wi + wo)·t is evaluated at the five points
//! with each point's own normal, grating vector and direction to the light; a spherical light
//! widens each by the range of wi·t over the cone of directions to its disc. The colour is the
//! table's mean over the hull of those intervals: a box filter one pixel wide in u. Mirror
//! reflections carry the offset rays on, each reflected at its own hit.

use std::str::FromStr;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::colour::Colour;
use diffraction::frame::ShadingFrame;
use diffraction::ColorTable;
use glam::{DVec2, DVec3};

use crate::geometry::{Hit, Ray};
use crate::material::GratingMaterial;
use crate::model::{Model, Paper};
use crate::scene::{Light, Scene};
use crate::whitted::PaperScene;

/// Relative accuracy of the colour tables (of the brightest diffracted order's Y; about
/// 0.1-0.3 ΔE2000 against `Exact`, docs/color_table.md), a build of 0.1-2 s per grating.
pub const TABLE_ACCURACY: f64 = 1e-3;

/// How the diffraction colour of a pixel sample is evaluated (`--filter`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Filter {
    /// At the sample's u alone, with the material's strategy (the paper's renders).
    #[default]
    None,
    /// The table's mean over the sample's footprint in u (and the light's extent).
    Footprint,
    /// The table's lookup at the sample's u: the footprint filter with zero width, for
    /// references and comparisons.
    Point,
}

impl FromStr for Filter {
    type Err = String;
    fn from_str(s: &str) -> Result<Filter, String> {
        match s {
            "none" => Ok(Filter::None),
            "footprint" => Ok(Filter::Footprint),
            "point" => Ok(Filter::Point),
            _ => Err("expected none, footprint or point".into()),
        }
    }
}

/// The four offset rays of a pixel sample: the image points (x ± w/2, y) and (x, y ± h/2) of its
/// stratum cell of centre (x, y) and size w × h.
pub type Footprint = [Ray; 4];

/// Whether a material's colour can come from a table: the paper's model with a finite slit
/// count, and a strategy that estimates the spectral integral (the paper's peak colours are
/// normalised differently and keep their own code).
pub fn tabulable(g: &GratingMaterial<Model>) -> bool {
    matches!(g.model, Model::AguHill(_)) && g.strategy != Colour::Paper
}

/// Builds one table per distinct grating among the materials the scene's objects use (for a
/// `filter` other than [`Filter::None`]), and sets the filter. Returns the number of tables
/// built and the time taken.
pub fn prepare(p: &mut PaperScene, filter: Filter) -> Result<(usize, Duration), String> {
    let start = Instant::now();
    let scene = &p.scene;
    let mut tables = vec![None; scene.materials.len()];
    if filter == Filter::None {
        (p.filter, p.tables) = (filter, tables);
        return Ok((0, start.elapsed()));
    }
    let mut used = vec![false; scene.materials.len()];
    for o in &scene.objects {
        used[o.material] = true;
    }
    let mut built: Vec<Arc<ColorTable>> = Vec::new();
    for (i, m) in scene.materials.iter().enumerate() {
        let Some(g) = m.grating.as_ref().filter(|g| used[i] && tabulable(g)) else {
            continue;
        };
        let Model::AguHill(model) = &g.model else {
            continue;
        };
        let grating = model.grating();
        let table = match built.iter().find(|t| t.grating() == grating) {
            Some(t) => t.clone(),
            None => {
                let t = ColorTable::new(&scene.spectral, grating, TABLE_ACCURACY)
                    .map_err(|e| format!("colour table of material {i}: {e}"))?;
                built.push(Arc::new(t));
                built[built.len() - 1].clone()
            }
        };
        tables[i] = Some(table);
    }
    (p.filter, p.tables) = (filter, tables);
    Ok((built.len(), start.elapsed()))
}

/// The range of w·x over the unit directions w within `half_angle` of the unit `axis`, for a
/// unit `x`: [cos(θ + α), cos(θ − α)] with θ the angle between axis and x, clamped to [−1, 1].
pub fn cone_range(axis: DVec3, x: DVec3, half_angle: f64) -> (f64, f64) {
    let theta = axis.dot(x).clamp(-1.0, 1.0).acos();
    let lo = (theta + half_angle).min(std::f64::consts::PI).cos();
    let hi = (theta - half_angle).max(0.0).cos();
    (lo, hi)
}

/// Where an offset ray meets the surface near `hit`: its hit on the same object, or its
/// intersection with the hit's tangent plane (with the hit's normal and tangent coordinates
/// moved along the plane), or `None` when it runs parallel to the plane or away from it.
fn offset_hit(scene: &Scene<Paper>, ray: &Ray, hit: &Hit) -> Option<Hit> {
    if let Some(h) = scene.objects[hit.object].intersect(ray, f64::INFINITY, hit.object) {
        return Some(h);
    }
    let denom = ray.dir.dot(hit.normal);
    if denom.abs() < 1e-12 {
        return None;
    }
    let t = (hit.point - ray.origin).dot(hit.normal) / denom;
    if !(t > 0.0 && t.is_finite()) {
        return None;
    }
    let point = ray.origin + ray.dir * t;
    let d = point - hit.point;
    Some(Hit {
        t,
        point,
        p: hit.p + DVec2::new(d.dot(hit.tangent), d.dot(hit.bitangent)),
        ..*hit
    })
}

/// The offset rays reflected at their own hits near `hit` (a mirror's ray differentials);
/// an offset ray that does not meet the surface is replaced by the reflected central ray.
pub fn reflect(scene: &Scene<Paper>, fp: &Footprint, hit: &Hit, central: &Ray) -> Footprint {
    fp.map(|r| match offset_hit(scene, &r, hit) {
        Some(h) => {
            let n = h.normal;
            Ray::new(h.spawn_point(), r.dir - n * (2.0 * r.dir.dot(n)))
        }
        None => *central,
    })
}

/// u = (wi + wo)·t at a surface point, and its range over the light's disc.
fn u_range(g: &GratingMaterial<Model>, h: &Hit, wo: DVec3, light: &Light) -> Option<(f64, f64)> {
    let t = g.field.world_direction(h.p, h.tangent, h.bitangent)?;
    let frame = ShadingFrame::new(h.normal, t)?;
    let x = frame.grating;
    let to = light.position - h.point;
    let dist = to.length();
    let wi = to / dist;
    let alpha = if light.radius > 0.0 {
        (light.radius / dist).min(1.0).asin()
    } else {
        0.0
    };
    let (lo, hi) = cone_range(wi, x, alpha);
    let ux = wo.dot(x);
    let r = (ux + lo, ux + hi);
    (r.0.is_finite() && r.1.is_finite()).then_some(r)
}

/// The footprint's interval of u for `light` at `hit` (seen along `ray`): the hull over the hit
/// and the offset rays' points, each widened by the light's angular size.
pub fn interval(
    scene: &Scene<Paper>,
    g: &GratingMaterial<Model>,
    ray: &Ray,
    hit: &Hit,
    fp: &Footprint,
    light: &Light,
) -> Option<(f64, f64)> {
    let (mut lo, mut hi) = u_range(g, hit, -ray.dir, light)?;
    for r in fp {
        if let Some((a, b)) = offset_hit(scene, r, hit).and_then(|h| u_range(g, &h, -r.dir, light))
        {
            lo = lo.min(a);
            hi = hi.max(b);
        }
    }
    Some((lo, hi))
}
