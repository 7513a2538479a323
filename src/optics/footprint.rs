//! The interval of u = (wi + wo)·t that one pixel sees at a grating hit: from the pixel's ray
//! differentials (or the rays through its corners), the shading frame and the light's angular
//! size. Averaging a grating's colour over it ([`ColorTable::mean`](crate::ColorTable)) is a box
//! filter one pixel wide in u, which removes the aliasing of the narrow spectral bands at low
//! sample counts.
//!
//! # What it computes
//!
//! The pixel's rays are intersected with the **tangent plane** of the hit (pbrt's use of ray
//! differentials); at each of those points P, with wo = −(ray direction), u ranges over
//!
//! ```text
//! wo·t + [min, max] of wi·t over the cone of directions from P to the light,
//! ```
//!
//! and the interval is the hull over the points (the hit itself included). The cone of a
//! sphere of radius R at distance D has half-angle α = asin(R/D) (a point light: α = 0); a
//! distant light has its own angular radius. With θ the angle between the cone's axis and t,
//! wi·t ranges over [cos(min(θ + α, π)), cos(max(θ − α, 0))].
//!
//! From ray differentials (the rays one pixel to the right and one pixel down, pbrt's
//! `rxOrigin`/`rxDirection`, `ryOrigin`/`ryDirection`) the pixel is the box of ±½ pixel around
//! the camera ray: its four corner rays are interpolated from the three. Over a box smaller than
//! the scale on which u bends, u is monotone along each side, so its range over the pixel is
//! reached at the corners: the tests compare the interval with a brute-force evaluation of u
//! over 33 × 33 points of the pixel and 512 directions of the light's cone.
//!
//! **Approximations** (stated, not hidden): one shading frame for the whole pixel (a radial
//! CD field turns t by about footprint/radius across it; pass each point's own frame to
//! [`u_range_at`] and take the hull yourself where that matters) and the tangent plane for the
//! surface; a corner ray that misses the plane (grazing views) contributes its wo at the hit.
//!
//! ```
//! use diffraction::footprint::{u_interval, LightExtent, PixelFootprint, PixelRay};
//! use diffraction::frame::ShadingFrame;
//! use glam::DVec3;
//!
//! // A grating in the plane z = 0 (grating vector x), seen from (0, −1, 1) by a pinhole camera
//! // whose pixels are 10⁻³ apart on an image plane at distance 1; a lamp of radius 0.05.
//! let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
//! let eye = DVec3::new(0.0, -1.0, 1.0);
//! let hit = DVec3::ZERO;
//! let (right, down) = (DVec3::X * 1e-3, DVec3::new(0.0, 1.0, 1.0).normalize() * 1e-3);
//! let ray = PixelRay::new(eye, hit - eye);
//! let dx = PixelRay::new(eye, hit - eye + right * 2f64.sqrt());
//! let dy = PixelRay::new(eye, hit - eye + down * 2f64.sqrt());
//! let lamp = LightExtent::sphere(DVec3::new(0.5, 0.0, 2.0), 0.05)?;
//! let (u0, u1) = u_interval(ray, hit, &frame, PixelFootprint::Differentials { dx, dy }, lamp)?;
//! // The lamp alone spans about 2·sin α·|sin θ| ≈ 0.047 in u; the pixel adds about 10⁻³.
//! assert!(u1 - u0 > 0.045 && u1 - u0 < 0.052);
//! # Ok::<(), diffraction::Error>(())
//! ```

use glam::DVec3;

use crate::error::{Error, Requirement};
use crate::num::math;
use crate::optics::frame::ShadingFrame;

/// The largest |u|: |wi·t| and |wo·t| are at most 1.
pub const U_MAX: f64 = 2.0;

/// One ray of a pixel, in world space: an origin and a direction (any non-zero length).
///
/// ```
/// use diffraction::footprint::PixelRay;
/// use glam::DVec3;
/// let r = PixelRay::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -2.0));
/// assert_eq!(r.direction.z, -2.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRay {
    /// Where the ray starts.
    pub origin: DVec3,
    /// Where it goes (not necessarily unit).
    pub direction: DVec3,
}

impl PixelRay {
    /// The ray from `origin` along `direction`.
    ///
    /// ```
    /// use diffraction::footprint::PixelRay;
    /// use glam::DVec3;
    /// assert_eq!(PixelRay::new(DVec3::X, DVec3::Z).origin, DVec3::X);
    /// ```
    #[must_use]
    pub fn new(origin: DVec3, direction: DVec3) -> PixelRay {
        PixelRay { origin, direction }
    }
}

/// The rays that say which part of the surface a pixel covers.
///
/// ```
/// use diffraction::footprint::{PixelFootprint, PixelRay};
/// use glam::DVec3;
/// let r = PixelRay::new(DVec3::ZERO, DVec3::NEG_Z);
/// let corners = [r; 4];
/// let fp = PixelFootprint::Rays(&corners);
/// assert!(matches!(fp, PixelFootprint::Rays(c) if c.len() == 4));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PixelFootprint<'a> {
    /// Ray differentials (pbrt's): the camera rays of the pixels one to the right (`dx`) and one
    /// below (`dy`). The pixel is the box of ±½ pixel around the camera ray; its corner rays are
    /// interpolated (origins and unit directions).
    Differentials {
        /// The ray one pixel over in x.
        dx: PixelRay,
        /// The ray one pixel over in y.
        dy: PixelRay,
    },
    /// Rays through points of the pixel's boundary (its corners, say): the hull is taken over
    /// them as given. Any number, including none (then only the hit counts).
    Rays(&'a [PixelRay]),
}

/// The light as the footprint sees it: its direction from each point and its angular radius.
/// Built by [`sphere`](Self::sphere) or [`distant`](Self::distant), which check their input.
///
/// ```
/// use diffraction::footprint::LightExtent;
/// use glam::DVec3;
/// assert!(LightExtent::sphere(DVec3::Y, 0.1).is_ok());
/// assert_eq!(LightExtent::sphere(DVec3::Y, -0.1).unwrap_err().parameter(), "radius");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightExtent(Light);

#[derive(Debug, Clone, Copy, PartialEq)]
enum Light {
    Sphere { center: DVec3, radius: f64 },
    Distant { axis: DVec3, sin: f64, cos: f64 },
}

impl LightExtent {
    /// A spherical light of `radius` ≥ 0 around `center` (world space; radius 0: a point light).
    /// Errors name `center` (a non-finite coordinate) or `radius`.
    ///
    /// ```
    /// use diffraction::footprint::LightExtent;
    /// use glam::DVec3;
    /// let e = LightExtent::sphere(DVec3::new(0.0, f64::NAN, 0.0), 1.0).unwrap_err();
    /// assert_eq!(e.parameter(), "center");
    /// ```
    pub fn sphere(center: DVec3, radius: f64) -> Result<LightExtent, Error> {
        finite_vector("center", center)?;
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(Error::invalid("radius", radius, Requirement::NonNegative));
        }
        Ok(LightExtent(Light::Sphere { center, radius }))
    }

    /// A distant light (the sun, a window far away) in the world direction `direction` (toward
    /// the light, any non-zero length) with angular radius `half_angle` in radians, within
    /// [0, π/2]. Errors name `direction` or `half_angle`.
    ///
    /// ```
    /// use diffraction::footprint::LightExtent;
    /// use glam::DVec3;
    /// let sun = LightExtent::distant(DVec3::new(0.3, 1.0, 0.2), 0.0047)?; // 0.27°
    /// assert_eq!(LightExtent::distant(DVec3::ZERO, 0.1).unwrap_err().parameter(), "direction");
    /// assert_eq!(LightExtent::distant(DVec3::Y, 2.0).unwrap_err().parameter(), "half_angle");
    /// # let _ = sun;
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn distant(direction: DVec3, half_angle: f64) -> Result<LightExtent, Error> {
        let axis = unit("direction", direction)?;
        let max = core::f64::consts::FRAC_PI_2;
        if !(0.0..=max).contains(&half_angle) {
            return Err(Error::invalid(
                "half_angle",
                half_angle,
                Requirement::Within { min: 0.0, max },
            ));
        }
        Ok(LightExtent(Light::Distant {
            axis,
            sin: math::sin(half_angle),
            cos: math::cos(half_angle),
        }))
    }
}

/// The range of u at one surface point: wo·t plus the range of wi·t over the light's cone seen
/// from `point` (see the [module docs](self)). `wo` is the world direction toward the viewer
/// (any non-zero length), `frame` the shading frame at the point. Within [−2, 2]. A point
/// inside a spherical light sees it everywhere: wi·t spans [−1, 1]. Errors name `point` or
/// `wo`.
///
/// ```
/// use diffraction::footprint::{u_range_at, LightExtent};
/// use diffraction::frame::ShadingFrame;
/// use glam::DVec3;
/// let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
/// let point_light = LightExtent::sphere(DVec3::new(0.0, 0.0, 1.0), 0.0)?;
/// let wo = DVec3::new(0.6, 0.0, 0.8);
/// let (u0, u1) = u_range_at(DVec3::ZERO, wo, &frame, point_light)?;
/// assert!((u0 - 0.6).abs() < 1e-15 && u0 == u1); // u = wo·t + wi·t = 0.6 + 0
/// # Ok::<(), diffraction::Error>(())
/// ```
pub fn u_range_at(
    point: DVec3,
    wo: DVec3,
    frame: &ShadingFrame,
    light: LightExtent,
) -> Result<(f64, f64), Error> {
    finite_vector("point", point)?;
    let wo = unit("wo", wo)?;
    Ok(range_at(point, wo, frame, light))
}

/// The interval [u0, u1] of u that a pixel sees at a hit (see the [module docs](self)):
/// `camera_ray` is the pixel sample's ray, `hit` where it meets the surface, `frame` the
/// shading frame there, `footprint` the pixel's other rays and `light` the light's extent.
/// Within [−2, 2], u0 ≤ u1. Errors name `camera_ray`, `hit` or `footprint` (a ray with a
/// non-finite or zero vector).
///
/// ```
/// use diffraction::footprint::{u_interval, LightExtent, PixelFootprint, PixelRay};
/// use diffraction::frame::ShadingFrame;
/// use glam::DVec3;
/// let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
/// let eye = DVec3::new(1.0, 0.0, 1.0);
/// let ray = PixelRay::new(eye, -eye);
/// let light = LightExtent::distant(DVec3::Z, 0.0)?;
/// // No footprint, a point-like light: the sample's own u = wo·t = 1/√2.
/// let (u0, u1) = u_interval(ray, DVec3::ZERO, &frame, PixelFootprint::Rays(&[]), light)?;
/// assert!((u0 - 0.5f64.sqrt()).abs() < 1e-15 && u0 == u1);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub fn u_interval(
    camera_ray: PixelRay,
    hit: DVec3,
    frame: &ShadingFrame,
    footprint: PixelFootprint<'_>,
    light: LightExtent,
) -> Result<(f64, f64), Error> {
    finite_vector("camera_ray", camera_ray.origin)?;
    let d0 = unit("camera_ray", camera_ray.direction)?;
    finite_vector("hit", hit)?;
    let (mut lo, mut hi) = range_at(hit, -d0, frame, light);
    let mut widen = |ray: PixelRay| {
        let Ok(d) = unit("footprint", ray.direction) else {
            return;
        };
        let p = tangent_hit(ray.origin, d, hit, frame.normal).unwrap_or(hit);
        let (a, b) = range_at(p, -d, frame, light);
        lo = lo.min(a);
        hi = hi.max(b);
    };
    match footprint {
        PixelFootprint::Differentials { dx, dy } => {
            for r in [dx, dy] {
                finite_vector("footprint", r.origin)?;
                unit("footprint", r.direction)?;
            }
            let (ddx, ddy) = (dx.direction.normalize() - d0, dy.direction.normalize() - d0);
            let (odx, ody) = (dx.origin - camera_ray.origin, dy.origin - camera_ray.origin);
            for (sx, sy) in [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)] {
                let direction = d0 + ddx * sx + ddy * sy;
                let origin = camera_ray.origin + odx * sx + ody * sy;
                if direction.length_squared() > 0.0 {
                    widen(PixelRay { origin, direction });
                }
            }
        }
        PixelFootprint::Rays(rays) => {
            for r in rays {
                finite_vector("footprint", r.origin)?;
                unit("footprint", r.direction)?;
            }
            for &r in rays {
                widen(r);
            }
        }
    }
    Ok((lo.clamp(-U_MAX, U_MAX), hi.clamp(-U_MAX, U_MAX)))
}

/// The range of u at `point` for the unit `wo`, after the checks.
fn range_at(point: DVec3, wo: DVec3, frame: &ShadingFrame, light: LightExtent) -> (f64, f64) {
    let t = frame.grating;
    let (axis, sin_a, cos_a) = match light.0 {
        Light::Distant { axis, sin, cos } => (axis, sin, cos),
        Light::Sphere { center, radius } => {
            let to = center - point;
            let dist = to.length();
            let outside = dist > radius && dist.is_finite();
            if !outside {
                // Inside (or on) the light: it fills every direction.
                let w = wo.dot(t);
                return (
                    (w - 1.0).clamp(-U_MAX, U_MAX),
                    (w + 1.0).clamp(-U_MAX, U_MAX),
                );
            }
            let s = radius / dist;
            (to / dist, s, math::sqrt((1.0 - s * s).max(0.0)))
        }
    };
    let (lo, hi) = cone_range(axis, t, sin_a, cos_a);
    let w = wo.dot(t);
    ((w + lo).clamp(-U_MAX, U_MAX), (w + hi).clamp(-U_MAX, U_MAX))
}

/// The range of w·x over the unit w within angle α of the unit `axis`, for a unit x:
/// [cos(min(θ + α, π)), cos(max(θ − α, 0))] with θ = ∠(axis, x), from sin α and cos α without
/// inverse trigonometry.
fn cone_range(axis: DVec3, x: DVec3, sin_a: f64, cos_a: f64) -> (f64, f64) {
    let c = axis.dot(x).clamp(-1.0, 1.0);
    let s = math::sqrt((1.0 - c * c).max(0.0));
    // θ ≤ α ⇔ cos θ ≥ cos α; θ + α ≥ π ⇔ cos θ ≤ −cos α.
    let hi = if c >= cos_a {
        1.0
    } else {
        c * cos_a + s * sin_a
    };
    let lo = if c <= -cos_a {
        -1.0
    } else {
        c * cos_a - s * sin_a
    };
    (lo.clamp(-1.0, 1.0), hi.clamp(-1.0, 1.0))
}

/// Where the ray (o, unit d) meets the plane through `p` with normal `n`, if ahead of it.
fn tangent_hit(o: DVec3, d: DVec3, p: DVec3, n: DVec3) -> Option<DVec3> {
    let denom = d.dot(n);
    let t = (p - o).dot(n) / denom;
    let q = o + d * t;
    (t > 0.0 && q.is_finite()).then_some(q)
}

/// Checks that every coordinate of `v` is finite.
fn finite_vector(name: &'static str, v: DVec3) -> Result<(), Error> {
    for c in v.to_array() {
        if !c.is_finite() {
            return Err(Error::invalid(name, c, Requirement::Finite));
        }
    }
    Ok(())
}

/// `v` normalised, after checking that it is finite and not zero (scaled by its largest
/// coordinate first, so that no finite vector overflows).
fn unit(name: &'static str, v: DVec3) -> Result<DVec3, Error> {
    finite_vector(name, v)?;
    let m = v.abs().max_element();
    if m <= 0.0 {
        return Err(Error::invalid(name, m, Requirement::Positive));
    }
    let w = v / m;
    Ok(w / w.length())
}
