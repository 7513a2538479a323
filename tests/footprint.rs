//! `footprint::u_interval` against a brute-force evaluation of u = (wi + wo)·t over the pixel:
//! a pinhole (or orthographic) camera, the pixel's square sampled on 33 × 33 points (its edges
//! and corners included), each intersected with the surface plane, and the light's cone of
//! directions from each point sampled on 512 directions of its rim and its axis.

#[path = "support/render_tolerance.rs"]
mod render_tolerance;

use diffraction::footprint::{u_interval, u_range_at, LightExtent, PixelFootprint, PixelRay};
use diffraction::frame::ShadingFrame;
use glam::DVec3;
use render_tolerance::*;

/// The light of a case, for the brute force.
#[derive(Clone, Copy)]
enum Lamp {
    Sphere(DVec3, f64),
    Distant(DVec3, f64),
}

impl Lamp {
    fn extent(self) -> LightExtent {
        match self {
            Lamp::Sphere(c, r) => LightExtent::sphere(c, r).unwrap(),
            Lamp::Distant(d, a) => LightExtent::distant(d, a).unwrap(),
        }
    }
    /// (axis, half-angle) seen from `p`.
    fn cone(self, p: DVec3) -> (DVec3, f64) {
        match self {
            Lamp::Sphere(c, r) => {
                let to = c - p;
                (to.normalize(), (r / to.length()).asin())
            }
            Lamp::Distant(d, a) => (d.normalize(), a),
        }
    }
}

/// One case: a camera (an origin per pixel point, or one eye), the pixel's centre direction
/// and its two one-pixel steps, the plane (a point and its normal), the grating vector.
struct Case {
    name: &'static str,
    eye: DVec3,
    /// Orthographic: the origin moves by the steps and the direction stays `dir`.
    ortho: bool,
    dir: DVec3,
    ex: DVec3,
    ey: DVec3,
    plane: (DVec3, DVec3),
    t: DVec3,
    lamp: Lamp,
}

impl Case {
    /// The camera ray through the pixel point (a, b), in pixels from the centre.
    fn ray(&self, a: f64, b: f64) -> PixelRay {
        if self.ortho {
            PixelRay::new(self.eye + self.ex * a + self.ey * b, self.dir)
        } else {
            PixelRay::new(self.eye, self.dir + self.ex * a + self.ey * b)
        }
    }
    fn hit(&self, r: PixelRay) -> DVec3 {
        let (p, n) = self.plane;
        let t = (p - r.origin).dot(n) / r.direction.dot(n);
        assert!(t > 0.0);
        r.origin + r.direction * t
    }
    fn frame(&self) -> ShadingFrame {
        ShadingFrame::new(self.plane.1, self.t).unwrap()
    }
    /// The brute-force range of u over the pixel.
    fn brute(&self) -> (f64, f64) {
        let frame = self.frame();
        let t = frame.grating;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let grid = 33;
        for i in 0..grid {
            for j in 0..grid {
                let a = -0.5 + i as f64 / (grid - 1) as f64;
                let b = -0.5 + j as f64 / (grid - 1) as f64;
                let r = self.ray(a, b);
                let p = self.hit(r);
                let wo = -r.direction.normalize();
                let (axis, alpha) = self.lamp.cone(p);
                // An orthonormal pair around the axis for the rim.
                let e1 = axis.any_orthonormal_vector();
                let e2 = axis.cross(e1);
                let mut consider = |wi: DVec3| {
                    let u = (wi + wo).dot(t);
                    lo = lo.min(u);
                    hi = hi.max(u);
                };
                consider(axis);
                for k in 0..512 {
                    let phi = std::f64::consts::TAU * k as f64 / 512.0;
                    let rim = axis * alpha.cos() + (e1 * phi.cos() + e2 * phi.sin()) * alpha.sin();
                    consider(rim);
                }
            }
        }
        (lo, hi)
    }
    fn differentials(&self) -> PixelFootprint<'static> {
        PixelFootprint::Differentials {
            dx: self.ray(1.0, 0.0),
            dy: self.ray(0.0, 1.0),
        }
    }
}

fn cases() -> Vec<Case> {
    let pixel = 1e-3;
    let eye = DVec3::new(0.2, -1.5, 1.2);
    let target = DVec3::new(0.1, 0.05, 0.0);
    let dir = target - eye;
    let right = dir.cross(DVec3::Z).normalize() * pixel * dir.length();
    let down = dir.cross(right).normalize() * pixel * dir.length();
    let plane = (DVec3::ZERO, DVec3::Z);
    let t = DVec3::new(0.8, 0.6, 0.0);
    let grazing_eye = DVec3::new(0.0, -6.0, 0.9);
    let gdir = target - grazing_eye;
    let gright = gdir.cross(DVec3::Z).normalize() * pixel * gdir.length();
    let gdown = gdir.cross(gright).normalize() * pixel * gdir.length();
    let tilted = (
        DVec3::new(0.0, 0.0, 0.1),
        DVec3::new(0.2, -0.3, 1.0).normalize(),
    );
    vec![
        Case {
            name: "pinhole, point light",
            eye,
            ortho: false,
            dir,
            ex: right,
            ey: down,
            plane,
            t,
            lamp: Lamp::Sphere(DVec3::new(-0.5, 0.4, 2.0), 0.0),
        },
        Case {
            name: "pinhole, sphere light",
            eye,
            ortho: false,
            dir,
            ex: right,
            ey: down,
            plane,
            t,
            lamp: Lamp::Sphere(DVec3::new(-0.5, 0.4, 2.0), 0.1),
        },
        Case {
            name: "pinhole, distant light, tilted plane",
            eye,
            ortho: false,
            dir,
            ex: right,
            ey: down,
            plane: tilted,
            t: DVec3::new(0.0, 1.0, 0.3),
            lamp: Lamp::Distant(DVec3::new(0.3, 0.2, 1.0), 0.05),
        },
        Case {
            name: "pinhole, grazing view (81°), 4-pixel steps",
            eye: grazing_eye,
            ortho: false,
            dir: gdir,
            ex: gright * 4.0,
            ey: gdown * 4.0,
            plane,
            t: DVec3::Y,
            lamp: Lamp::Sphere(DVec3::new(0.0, 3.0, 2.0), 0.2),
        },
        Case {
            name: "orthographic, point light",
            eye,
            ortho: true,
            dir,
            ex: right * 3.0,
            ey: down * 3.0,
            plane,
            t,
            lamp: Lamp::Sphere(DVec3::new(0.5, 0.2, 0.6), 0.0),
        },
    ]
}

/// |interval − brute| at each end, relative to the brute width.
fn discrepancy(got: (f64, f64), want: (f64, f64)) -> f64 {
    let width = want.1 - want.0;
    (got.0 - want.0).abs().max((got.1 - want.1).abs()) / width
}

#[test]
fn the_interval_from_differentials_is_the_range_over_the_pixel() {
    for c in cases() {
        let centre = c.ray(0.0, 0.0);
        let hit = c.hit(centre);
        let got = u_interval(centre, hit, &c.frame(), c.differentials(), c.lamp.extent()).unwrap();
        let want = c.brute();
        let d = discrepancy(got, want);
        println!("{}: width {:e}, discrepancy {d:e}", c.name, want.1 - want.0);
        assert!(
            d <= FOOTPRINT_RELATIVE,
            "{}: interval {got:?}, brute force {want:?} ({d:e} of the width)",
            c.name
        );
        assert!(got.0 <= got.1 && got.0 >= -2.0 && got.1 <= 2.0);
    }
}

#[test]
fn the_interval_from_corner_rays_is_the_range_over_the_pixel() {
    for c in cases() {
        let centre = c.ray(0.0, 0.0);
        let hit = c.hit(centre);
        let corners =
            [(-0.5, -0.5), (0.5, -0.5), (-0.5, 0.5), (0.5, 0.5)].map(|(a, b)| c.ray(a, b));
        let fp = PixelFootprint::Rays(&corners);
        let got = u_interval(centre, hit, &c.frame(), fp, c.lamp.extent()).unwrap();
        let want = c.brute();
        let d = discrepancy(got, want);
        println!("corners, {}: discrepancy {d:e}", c.name);
        assert!(
            d <= FOOTPRINT_RELATIVE,
            "{}: {got:?} vs {want:?} ({d:e})",
            c.name
        );
    }
}

#[test]
fn the_light_cone_range_is_the_closed_form() {
    // At one point: u_range_at against the brute force of the light's cone alone.
    let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
    let wo = DVec3::new(-0.3, 0.1, 0.9).normalize();
    for lamp in [
        Lamp::Sphere(DVec3::new(1.0, 0.5, 1.0), 0.3),
        Lamp::Sphere(DVec3::new(0.0, 0.0, 3.0), 0.2), // axis ⟂ t
        Lamp::Distant(DVec3::new(1.0, 0.0, 0.05), 0.2), // the cone reaches t
        Lamp::Distant(DVec3::new(-1.0, 0.0, 0.0), 0.3), // and −t
    ] {
        let got = u_range_at(DVec3::ZERO, wo, &frame, lamp.extent()).unwrap();
        let (axis, alpha) = lamp.cone(DVec3::ZERO);
        let mut lo: f64 = 1.0;
        let mut hi: f64 = -1.0;
        let e1 = axis.any_orthonormal_vector();
        let e2 = axis.cross(e1);
        for k in 0..100_000 {
            let phi = std::f64::consts::TAU * k as f64 / 100_000.0;
            let w = axis * alpha.cos() + (e1 * phi.cos() + e2 * phi.sin()) * alpha.sin();
            lo = lo.min(w.x);
            hi = hi.max(w.x);
        }
        // Where the cone contains ±t the extreme is ±1 (inside the cone, not on its rim).
        if axis.x >= alpha.cos() {
            hi = 1.0;
        }
        if axis.x <= -alpha.cos() {
            lo = -1.0;
        }
        let want = ((wo.x + lo).clamp(-2.0, 2.0), (wo.x + hi).clamp(-2.0, 2.0));
        println!(
            "cone: {:e}",
            (got.0 - want.0).abs().max((got.1 - want.1).abs())
        );
        assert!(
            (got.0 - want.0).abs() <= CONE_ABSOLUTE && (got.1 - want.1).abs() <= CONE_ABSOLUTE,
            "{got:?} vs {want:?}"
        );
    }
}

#[test]
fn a_point_sample_with_a_point_light_is_its_own_u() {
    let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
    let eye = DVec3::new(-1.0, 0.2, 1.0);
    let light = DVec3::new(0.5, -0.2, 1.0);
    let ray = PixelRay::new(eye, -eye);
    let lamp = LightExtent::sphere(light, 0.0).unwrap();
    let (u0, u1) = u_interval(ray, DVec3::ZERO, &frame, PixelFootprint::Rays(&[]), lamp).unwrap();
    let u = (light.normalize() + eye.normalize()).x;
    assert!((u0 - u).abs() < POINT_FOOTPRINT && (u1 - u).abs() < POINT_FOOTPRINT);
    // Zero-length differentials (the same ray): the same.
    let same = PixelFootprint::Differentials { dx: ray, dy: ray };
    let (v0, v1) = u_interval(ray, DVec3::ZERO, &frame, same, lamp).unwrap();
    assert!((v0 - u).abs() < POINT_FOOTPRINT && (v1 - u).abs() < POINT_FOOTPRINT);
}

#[test]
fn bad_input_is_refused_by_name() {
    let frame = ShadingFrame::new(DVec3::Z, DVec3::X).unwrap();
    let lamp = LightExtent::sphere(DVec3::Z, 0.1).unwrap();
    let ray = PixelRay::new(DVec3::new(0.0, 0.0, 1.0), DVec3::NEG_Z);
    let none = PixelFootprint::Rays(&[]);
    let err = |r: PixelRay, hit: DVec3, fp| {
        u_interval(r, hit, &frame, fp, lamp)
            .unwrap_err()
            .parameter()
    };
    assert_eq!(
        err(PixelRay::new(DVec3::Z, DVec3::ZERO), DVec3::ZERO, none),
        "camera_ray"
    );
    assert_eq!(
        err(
            PixelRay::new(DVec3::splat(f64::NAN), DVec3::Z),
            DVec3::ZERO,
            none
        ),
        "camera_ray"
    );
    assert_eq!(err(ray, DVec3::new(f64::INFINITY, 0.0, 0.0), none), "hit");
    let bad = [PixelRay::new(DVec3::Z, DVec3::new(0.0, f64::NAN, 1.0))];
    assert_eq!(
        err(ray, DVec3::ZERO, PixelFootprint::Rays(&bad)),
        "footprint"
    );
    assert_eq!(
        LightExtent::sphere(DVec3::Z, f64::NAN)
            .unwrap_err()
            .parameter(),
        "radius"
    );
    assert_eq!(
        LightExtent::distant(DVec3::Z, -0.1)
            .unwrap_err()
            .parameter(),
        "half_angle"
    );
    // Huge but finite vectors are fine (no overflow in the normalisation).
    let far = PixelRay::new(DVec3::new(0.0, 0.0, 1e300), DVec3::new(0.0, 0.0, -1e300));
    let (a, b) = u_interval(far, DVec3::ZERO, &frame, none, lamp).unwrap();
    assert!(a.is_finite() && b.is_finite());
    // A ray parallel to the plane, and one pointing away: no NaN, the hit's own range.
    let parallel = [
        PixelRay::new(DVec3::Z, DVec3::X),
        PixelRay::new(DVec3::Z, DVec3::Z),
    ];
    let (a, b) = u_interval(
        ray,
        DVec3::ZERO,
        &frame,
        PixelFootprint::Rays(&parallel),
        lamp,
    )
    .unwrap();
    assert!(a.is_finite() && b.is_finite() && a <= b);
    // A point inside the light sees it everywhere.
    let inside = LightExtent::sphere(DVec3::ZERO, 1.0).unwrap();
    let (a, b) = u_range_at(DVec3::ZERO, DVec3::Z, &frame, inside).unwrap();
    assert_eq!((a, b), (-1.0, 1.0));
}
