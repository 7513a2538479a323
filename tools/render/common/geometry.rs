//! Rays, transforms and the four primitives (quad, cube, capped cylinder, disc with a hole).
//!
//! Every primitive is defined once in its own local space at unit size and placed in the scene
//! by a [`Transform`] (scale, then rotation, then translation). Besides the hit distance and the
//! normal, every hit reports the surface's **tangent coordinates**: a 2-D point `p` on the
//! surface and the world tangent vectors along its two axes. The diffraction shading needs them
//! to turn a [`GratingField`](diffraction::frame::GratingField) (defined in `p` coordinates)
//! into a world grating vector.

use glam::{DAffine3, DMat3, DVec2, DVec3};

/// Distance below which a hit is ignored (self-intersection guard), in world units.
pub const EPSILON: f64 = 1e-7;

/// The fraction of the distance to a light a shadow ray tests: the point sampled on the light
/// itself never counts as an occluder.
pub const SHADOW_REACH: f64 = 1.0 - 1e-9;

/// The nearest hit of any of `objects` along `ray` before `t_max` (its `object` the index).
pub fn nearest(objects: &[Primitive], ray: &Ray, t_max: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (i, obj) in objects.iter().enumerate() {
        let t = best.map_or(t_max, |b| b.t);
        if let Some(hit) = obj.intersect(ray, t, i) {
            best = Some(hit);
        }
    }
    best
}

/// Whether any of `objects` lies on `ray` in (EPSILON, t_max).
pub fn occluded(objects: &[Primitive], ray: &Ray, t_max: f64) -> bool {
    objects.iter().any(|o| o.occludes(ray, t_max))
}

/// A ray `origin + t·dir`; `dir` is unit length.
#[derive(Debug, Clone, Copy)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: DVec3,
    /// Its unit direction.
    pub dir: DVec3,
}

impl Ray {
    /// The ray from `origin` along `dir` (normalised here).
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray {
            origin,
            dir: dir.normalize(),
        }
    }

    /// The point at distance `t` along the ray.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.dir * t
    }
}

/// Scale, then rotate (about x, then y, then z), then translate.
#[derive(Debug, Clone, Copy)]
pub struct Transform {
    to_world: DAffine3,
    to_local: DAffine3,
    /// Inverse transpose of the linear part (for normals).
    normal_matrix: DMat3,
    /// The rotation alone (for solid textures in object space at world scale).
    rotation: DMat3,
    translation: DVec3,
}

impl Transform {
    /// `None` when a scale component is zero or the matrix is not invertible.
    pub fn new(translate: DVec3, rotate_deg: DVec3, scale: DVec3) -> Option<Transform> {
        if !(translate.is_finite() && rotate_deg.is_finite() && scale.is_finite()) {
            return None;
        }
        if scale.abs().min_element() < 1e-12 {
            return None;
        }
        let r = rotate_deg * (std::f64::consts::PI / 180.0);
        let rotation =
            DMat3::from_rotation_z(r.z) * DMat3::from_rotation_y(r.y) * DMat3::from_rotation_x(r.x);
        let linear = rotation * DMat3::from_diagonal(scale);
        let to_world = DAffine3::from_mat3_translation(linear, translate);
        let to_local = to_world.inverse();
        if !to_local.is_finite() {
            return None;
        }
        Some(Transform {
            to_world,
            to_local,
            normal_matrix: linear.inverse().transpose(),
            rotation,
            translation: translate,
        })
    }

    /// A world point in the object's frame without the scale (world units, object orientation):
    /// where solid textures (wood) are evaluated, so they move with the object.
    pub fn object_point(&self, world: DVec3) -> DVec3 {
        self.rotation.transpose() * (world - self.translation)
    }
}

/// The shape of a primitive, in its local space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// The square |x|, |z| ≤ ½ in the plane y = 0, normal +y (two-sided).
    Quad,
    /// The cube |x|, |y|, |z| ≤ ½.
    Cube,
    /// The cylinder of radius ½ about the y axis, |y| ≤ ½, with both caps.
    Cylinder,
    /// The annulus `hole` ≤ r ≤ ½ in the plane y = 0 (two-sided); `hole` is the inner radius.
    Disc {
        /// The inner radius, in [0, ½).
        hole: f64,
    },
}

/// Which part of a primitive was hit (for materials that differ per part, e.g. a can's label).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Part {
    /// A flat face (quad, disc, a cube face).
    Face,
    /// The curved side of a cylinder.
    Side,
    /// A cap of a cylinder.
    Cap,
}

/// A hit in local space, before the transform.
#[derive(Debug, Clone, Copy)]
struct LocalHit {
    t: f64,
    normal: DVec3,
    /// Tangent coordinates on the surface.
    p: DVec2,
    /// ∂P/∂p.x and ∂P/∂p.y in local space.
    dpdx: DVec3,
    dpdy: DVec3,
    /// Texture coordinates in [0, 1]².
    uv: DVec2,
    part: Part,
}

/// A ray-surface intersection in world space.
#[derive(Debug, Clone, Copy)]
pub struct Hit {
    /// The distance along the ray.
    pub t: f64,
    /// The point hit, world coordinates.
    pub point: DVec3,
    /// Unit normal, turned to face the incoming ray.
    pub normal: DVec3,
    /// Tangent coordinates of the hit in world units (the domain of a grating field).
    pub p: DVec2,
    /// World vectors to pass to `GratingField::world_direction`: the dual basis of
    /// (∂P/∂p.x, ∂P/∂p.y), so that a direction `d` in `p` coordinates maps to the world
    /// direction across the grooves even under non-uniform scaling (the grating vector is a
    /// gradient, perpendicular to the grooves, and transforms like one).
    pub tangent: DVec3,
    /// The second vector of that dual basis.
    pub bitangent: DVec3,
    /// Texture coordinates in [0, 1]².
    pub uv: DVec2,
    /// Which part of the primitive was hit.
    pub part: Part,
    /// The hit in the object's unscaled frame (for solid textures).
    pub object_point: DVec3,
    /// The index of the object hit (see [`nearest`]).
    pub object: usize,
}

impl Hit {
    /// The origin of secondary rays (shadow rays, reflections): the hit point moved off the
    /// surface along its normal by a distance relative to the point's magnitude.
    pub fn spawn_point(&self) -> DVec3 {
        self.point + self.normal * (1e-7 * (1.0 + self.point.abs().max_element()))
    }
}

/// A primitive placed in the scene.
#[derive(Debug, Clone)]
pub struct Primitive {
    /// The shape in its local space.
    pub shape: Shape,
    /// Where it is placed.
    pub transform: Transform,
    /// Its material: an index into the scene's materials.
    pub material: usize,
}

impl Primitive {
    /// The nearest intersection with `t` in (EPSILON, t_max).
    pub fn intersect(&self, ray: &Ray, t_max: f64, index: usize) -> Option<Hit> {
        let tf = &self.transform;
        // The local direction is not normalised, so t means the same in both spaces.
        let o = tf.to_local.transform_point3(ray.origin);
        let d = tf.to_local.transform_vector3(ray.dir);
        let local = match self.shape {
            Shape::Quad => quad(o, d, t_max),
            Shape::Cube => cube(o, d, t_max),
            Shape::Cylinder => cylinder(o, d, t_max),
            Shape::Disc { hole } => disc(o, d, t_max, hole),
        }?;
        let point = ray.at(local.t);
        let mut normal = (tf.normal_matrix * local.normal).normalize();
        if normal.dot(ray.dir) > 0.0 {
            normal = -normal;
        }
        // Tangent coordinates in world units: scale p by the lengths of the world tangents
        // (constant over each face, and over a cylinder's side when its x and z scales agree).
        let dpdx = tf.to_world.transform_vector3(local.dpdx);
        let dpdy = tf.to_world.transform_vector3(local.dpdy);
        let (a, b) = (dpdx.length(), dpdy.length());
        let (tangent, bitangent) = dual_basis(dpdx / a, dpdy / b);
        Some(Hit {
            t: local.t,
            point,
            normal,
            p: DVec2::new(local.p.x * a, local.p.y * b),
            tangent,
            bitangent,
            uv: local.uv,
            part: local.part,
            object_point: tf.object_point(point),
            object: index,
        })
    }

    /// Whether anything of this primitive lies on the ray in (EPSILON, t_max).
    pub fn occludes(&self, ray: &Ray, t_max: f64) -> bool {
        self.intersect(ray, t_max, 0).is_some()
    }
}

/// The dual basis (a*, b*) of two tangent vectors: a*·a = b*·b = 1, a*·b = b*·a = 0, both in
/// their plane. For orthogonal a, b it is (a/|a|², b/|b|²).
fn dual_basis(a: DVec3, b: DVec3) -> (DVec3, DVec3) {
    let (aa, ab, bb) = (a.dot(a), a.dot(b), b.dot(b));
    let det = aa * bb - ab * ab;
    if det.abs() <= 1e-300 || det.is_nan() {
        return (a, b);
    }
    let inv = 1.0 / det;
    ((a * bb - b * ab) * inv, (b * aa - a * ab) * inv)
}

fn in_range(t: f64, t_max: f64) -> bool {
    t > EPSILON && t < t_max
}

/// The hit of the plane y = 0 at a point `inside` accepts, with tangent coordinates p = (x, z).
fn y_plane(o: DVec3, d: DVec3, t_max: f64, inside: impl Fn(DVec3) -> bool) -> Option<LocalHit> {
    if d.y.abs() < 1e-300 {
        return None;
    }
    let t = -o.y / d.y;
    if !in_range(t, t_max) {
        return None;
    }
    let q = o + d * t;
    if !inside(q) {
        return None;
    }
    Some(LocalHit {
        t,
        normal: DVec3::Y,
        p: DVec2::new(q.x, q.z),
        dpdx: DVec3::X,
        dpdy: DVec3::Z,
        uv: DVec2::new(q.x + 0.5, q.z + 0.5),
        part: Part::Face,
    })
}

/// The plane y = 0, |x|, |z| ≤ ½. Tangent coordinates p = (x, z).
fn quad(o: DVec3, d: DVec3, t_max: f64) -> Option<LocalHit> {
    y_plane(o, d, t_max, |q| q.x.abs() <= 0.5 && q.z.abs() <= 0.5)
}

/// The annulus hole ≤ r ≤ ½ in y = 0. Tangent coordinates p = (x, z), so a radial field
/// centred at (0, 0) follows the tracks.
fn disc(o: DVec3, d: DVec3, t_max: f64, hole: f64) -> Option<LocalHit> {
    y_plane(o, d, t_max, |q| {
        let r2 = q.x * q.x + q.z * q.z;
        r2 <= 0.25 && r2 >= hole * hole
    })
}

/// The cube |x|, |y|, |z| ≤ ½ (slab method). Each face's tangent coordinates are its two
/// in-plane coordinates, ordered so that the first tangent is horizontal on the side faces.
fn cube(o: DVec3, d: DVec3, t_max: f64) -> Option<LocalHit> {
    let inv = d.recip();
    let t0 = (DVec3::splat(-0.5) - o) * inv;
    let t1 = (DVec3::splat(0.5) - o) * inv;
    let near = t0.min(t1);
    let far = t0.max(t1);
    let t_near = near.max_element();
    let t_far = far.min_element();
    if t_near > t_far {
        return None;
    }
    let t = if in_range(t_near, t_max) {
        t_near
    } else if in_range(t_far, t_max) {
        t_far
    } else {
        return None;
    };
    let q = o + d * t;
    // The face is the axis where |q| is largest.
    let a = q.abs();
    let (normal, p, dpdx, dpdy) = if a.x >= a.y && a.x >= a.z {
        let s = q.x.signum();
        (
            DVec3::X * s,
            DVec2::new(-s * q.z, q.y),
            DVec3::Z * -s,
            DVec3::Y,
        )
    } else if a.y >= a.z {
        let s = q.y.signum();
        (DVec3::Y * s, DVec2::new(q.x, q.z), DVec3::X, DVec3::Z)
    } else {
        let s = q.z.signum();
        (
            DVec3::Z * s,
            DVec2::new(s * q.x, q.y),
            DVec3::X * s,
            DVec3::Y,
        )
    };
    Some(LocalHit {
        t,
        normal,
        p,
        dpdx,
        dpdy,
        uv: p + DVec2::splat(0.5),
        part: Part::Face,
    })
}

/// The cylinder of radius ½ about y, |y| ≤ ½, capped.
///
/// Side: p = (arc length ½·φ, y) with φ = atan2(x, z) (so φ = 0 faces +z), uv = (φ/2π + ½, y + ½).
/// Caps: p = (x, z).
fn cylinder(o: DVec3, d: DVec3, t_max: f64) -> Option<LocalHit> {
    let mut best: Option<LocalHit> = None;
    let mut consider = |h: LocalHit| {
        if best.is_none_or(|b| h.t < b.t) {
            best = Some(h);
        }
    };
    // Side: (ox + t dx)² + (oz + t dz)² = ¼.
    let a = d.x * d.x + d.z * d.z;
    if a > 1e-300 {
        let b = o.x * d.x + o.z * d.z;
        let c = o.x * o.x + o.z * o.z - 0.25;
        let disc = b * b - a * c;
        if disc >= 0.0 {
            let s = disc.sqrt();
            for t in [(-b - s) / a, (-b + s) / a] {
                if in_range(t, t_max) {
                    let q = o + d * t;
                    if q.y.abs() <= 0.5 {
                        let phi = q.x.atan2(q.z);
                        consider(LocalHit {
                            t,
                            normal: DVec3::new(q.x, 0.0, q.z) * 2.0,
                            p: DVec2::new(0.5 * phi, q.y),
                            // ∂P/∂(arc length) = (cos φ, 0, −sin φ) with x = ½ sin φ, z = ½ cos φ.
                            dpdx: DVec3::new(phi.cos(), 0.0, -phi.sin()),
                            dpdy: DVec3::Y,
                            uv: DVec2::new(phi / std::f64::consts::TAU + 0.5, q.y + 0.5),
                            part: Part::Side,
                        });
                        break;
                    }
                }
            }
        }
    }
    // Caps y = ±½.
    if d.y.abs() > 1e-300 {
        for y in [-0.5, 0.5] {
            let t = (y - o.y) / d.y;
            if in_range(t, t_max) {
                let q = o + d * t;
                if q.x * q.x + q.z * q.z <= 0.25 {
                    consider(LocalHit {
                        t,
                        normal: DVec3::Y * y.signum(),
                        p: DVec2::new(q.x, q.z),
                        dpdx: DVec3::X,
                        dpdy: DVec3::Z,
                        uv: DVec2::new(q.x + 0.5, q.z + 0.5),
                        part: Part::Cap,
                    });
                }
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity() -> Transform {
        Transform::new(DVec3::ZERO, DVec3::ZERO, DVec3::ONE).unwrap()
    }

    #[test]
    fn primitives_are_hit_where_expected() {
        let ray = Ray::new(DVec3::new(0.0, 5.0, 0.1), -DVec3::Y);
        for (shape, t) in [
            (Shape::Quad, 5.0),
            (Shape::Cube, 4.5),
            (Shape::Cylinder, 4.5),
            (Shape::Disc { hole: 0.0 }, 5.0),
        ] {
            let prim = Primitive {
                shape,
                transform: identity(),
                material: 0,
            };
            let hit = prim.intersect(&ray, f64::INFINITY, 0).unwrap();
            assert!((hit.t - t).abs() < 1e-12, "{shape:?}");
            assert!((hit.normal - DVec3::Y).length() < 1e-12);
        }
        // The hole of the disc lets the ray through.
        let cd = Primitive {
            shape: Shape::Disc { hole: 0.2 },
            transform: identity(),
            material: 0,
        };
        assert!(cd.intersect(&ray, f64::INFINITY, 0).is_none());
    }

    #[test]
    fn transforms_move_scale_and_rotate() {
        let tf = Transform::new(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(0.0, 90.0, 0.0),
            DVec3::splat(2.0),
        )
        .unwrap();
        let prim = Primitive {
            shape: Shape::Cube,
            transform: tf,
            material: 0,
        };
        let ray = Ray::new(DVec3::new(1.0, 2.0, 10.0), -DVec3::Z);
        let hit = prim.intersect(&ray, f64::INFINITY, 0).unwrap();
        assert!((hit.point.z - 4.0).abs() < 1e-12);
        assert!((hit.normal - DVec3::Z).length() < 1e-12);
        assert!(Transform::new(DVec3::ZERO, DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0)).is_none());
    }

    #[test]
    fn dual_basis_inverts_the_tangents() {
        let (a, b) = (DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 3.0, 0.0));
        let (da, db) = dual_basis(a, b);
        assert!((da.dot(a) - 1.0).abs() < 1e-12 && da.dot(b).abs() < 1e-12);
        assert!((db.dot(b) - 1.0).abs() < 1e-12 && db.dot(a).abs() < 1e-12);
    }
}
