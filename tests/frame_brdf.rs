//! Grating-direction fields, the shading frame and the `DiffractionBrdf` implementation.

#[path = "support/fixed_seed.rs"]
mod fixed_seed;
#[path = "support/tolerance.rs"]
mod tolerance;

use diffraction::frame::{phase_projection, GratingField, ShadingFrame, Tile};
use diffraction::{AguHill, Band, DiffractionBrdf, Grating, Illumination, Peak, SpectralResponse};
use glam::{DVec2, DVec3, Vec3};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn unit_upper(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

proptest! {
    #![proptest_config(fixed_seed::config(500, 0x5EED_0006, "tests/frame_brdf.proptest-regressions"))]

    /// eval is the grating intensity at u = wi.x + wo.x, the illumination model's diffraction
    /// term scales it by its coefficient, and eval_f32 agrees with it to f32 precision of its
    /// inputs.
    #[test]
    fn eval_is_the_scaled_intensity(t1 in 0.0f64..1.5, p1 in 0.0f64..std::f64::consts::TAU, t2 in 0.0f64..1.5,
                                    p2 in 0.0f64..std::f64::consts::TAU, l in 360.0f64..830.0, k in 0.0f64..3.0) {
        let g = Grating::new(1600.0, 800.0, 300).unwrap();
        let m = AguHill::new(g);
        let shading = Illumination::new(0.0, 0.0, k).unwrap();
        let (wo, wi) = (unit_upper(t2, p2), unit_upper(t1, p1));
        let u = phase_projection(wo, wi, DVec3::X);
        let v = m.eval(wo, wi, l);
        prop_assert_eq!(v, g.intensity(u, l));
        prop_assert_eq!(shading.eval(&m, wo, wi, l, 1.0, 1.0), k * v);
        // f32 directions round to 6e-8; |dI/du| ≤ π·N·d/λ bounds the difference by
        // slope·2.5e-7 + 1e-6 (f32 rounding of the value); measured within a fraction of that.
        let v32 = m.eval_f32(wi.as_vec3(), wo.as_vec3(), l as f32) as f64;
        let slope = PI * 300.0 * 1600.0 / l;
        prop_assert!((v32 - v).abs() <= tolerance::EVAL_F32_FRACTION * (slope * 2.5e-7 + 1e-6));
    }

    /// Reciprocity: u is symmetric in (wi, wo), so eval(wi, wo) = eval(wo, wi).
    #[test]
    fn eval_is_reciprocal(t1 in 0.0f64..1.5, p1 in 0.0f64..std::f64::consts::TAU, t2 in 0.0f64..1.5,
                          p2 in 0.0f64..std::f64::consts::TAU, l in 360.0f64..830.0) {
        let m = AguHill::new(Grating::new(740.0, 370.0, 5000).unwrap());
        let (wo, wi) = (unit_upper(t2, p2), unit_upper(t1, p1));
        prop_assert_eq!(m.eval(wo, wi, l), m.eval(wi, wo, l));
    }

    /// The visited peaks are the grating's peaks, with eval at the peak wavelength equal to the
    /// reported intensity.
    #[test]
    fn visited_peaks_match_eval(t1 in 0.0f64..1.5, p1 in 0.0f64..std::f64::consts::TAU, t2 in 0.0f64..1.5,
                                p2 in 0.0f64..std::f64::consts::TAU) {
        let m = AguHill::new(Grating::new(1600.0, 640.0, 2000).unwrap());
        let (wo, wi) = (unit_upper(t2, p2), unit_upper(t1, p1));
        let mut seen: Vec<Peak> = vec![];
        let s = m.peaks(wo, wi, Band::VISIBLE, &mut |p| seen.push(p));
        prop_assert_eq!(s.orders as usize, seen.len());
        for p in &seen {
            let v = m.eval(wo, wi, p.wavelength_nm);
            prop_assert!((v - p.intensity).abs()
                <= tolerance::EVAL_AT_PEAK_REL * p.intensity + tolerance::INTENSITY_AT_PEAK_ABS);
        }
    }
}

#[test]
fn below_the_surface_is_dark() {
    let m = AguHill::new(Grating::new(1600.0, 800.0, 100).unwrap());
    let shading = Illumination::new(0.2, 0.5, 1.0).unwrap();
    let up = DVec3::new(0.0, 0.0, 1.0);
    let down = DVec3::new(0.0, 0.0, -1.0);
    assert_eq!(m.eval(up, down, 500.0), 0.0);
    assert_eq!(m.eval(down, up, 500.0), 0.0);
    assert_eq!(m.eval_f32(Vec3::Z, -Vec3::Z, 500.0), 0.0);
    let s = m.peaks(down, up, Band::VISIBLE, &mut |_| {
        panic!("no peak below the surface")
    });
    assert_eq!(s.orders, 0);
    // Only the ambient term remains.
    assert_eq!(shading.eval(&m, up, down, 500.0, 1.0, 1.0), 0.2);
    assert_eq!(m.response(up, down, 500.0), 0.0);
}

#[test]
fn order_zero_is_white_specular_in_the_illumination_model() {
    let m = AguHill::new(Grating::new(1600.0, 800.0, 1000).unwrap());
    let shading = Illumination::new(0.1, 0.4, 0.8).unwrap();
    let wi = unit_upper(0.5, 0.0);
    let wo = DVec3::new(-wi.x, -wi.y, wi.z); // mirror
    let s = m.peaks(wo, wi, Band::VISIBLE, &mut |_| {});
    assert!(s.specular && s.orders == 0);
    for l in [360.0, 450.0, 600.0, 830.0] {
        let want = 0.1 * 0.3 + 2.0 * (0.4 * wi.z + 0.8);
        assert!(
            (shading.eval(&m, wo, wi, l, 0.3, 2.0) - want).abs() < tolerance::SHADING_CLOSED_FORM
        );
    }
}

#[test]
fn bad_coefficients_are_named() {
    let bad = |a, d, k| Illumination::new(a, d, k).unwrap_err();
    assert_eq!(bad(-0.1, 0.0, 1.0).parameter(), "ambient");
    assert_eq!(bad(0.0, f64::NAN, 1.0).parameter(), "diffuse");
    assert_eq!(bad(0.0, 0.0, f64::INFINITY).parameter(), "diffraction");
    assert_eq!(
        bad(0.0, 0.0, -f64::MAX).to_string(),
        "invalid diffraction = -1.7976931348623157e308: must be finite and >= 0"
    );
}

#[test]
fn fields_give_unit_tangent_directions() {
    let twisted = GratingField::constant(0.3).twisted(0.4).unwrap();
    let d = twisted.direction_at(DVec2::new(5.0, -2.0)).unwrap();
    assert!((d - DVec2::new(0.7f64.cos(), 0.7f64.sin())).length() < tolerance::FIELD_DIRECTION);

    let cd = GratingField::radial(DVec2::new(1.0, 1.0));
    for p in [
        DVec2::new(3.0, 1.0),
        DVec2::new(1.0, -4.0),
        DVec2::new(-2.0, 5.0),
    ] {
        let d = cd.direction_at(p).unwrap();
        assert!((d.length() - 1.0).abs() < tolerance::FIELD_DIRECTION);
        // Radial: parallel to p − centre, so the grooves are circles around the centre.
        assert!(d.perp_dot(p - DVec2::new(1.0, 1.0)).abs() < tolerance::FIELD_RADIAL);
    }
    assert_eq!(cd.direction_at(DVec2::new(1.0, 1.0)), None);

    let board =
        GratingField::checkerboard(1.0, Tile::Constant { angle: 0.0 }, Tile::Plain).unwrap();
    assert!(board.direction_at(DVec2::new(0.5, 0.5)).is_some());
    assert!(board.direction_at(DVec2::new(1.5, 0.5)).is_none());
    assert!(board.direction_at(DVec2::new(-0.5, 0.5)).is_none());
    assert!(board.direction_at(DVec2::new(-0.5, -0.5)).is_some());
    assert!(board.direction_at(DVec2::new(f64::NAN, 0.0)).is_none());
    assert_eq!(
        GratingField::checkerboard(0.0, Tile::Plain, Tile::Plain)
            .unwrap_err()
            .parameter(),
        "cell_size"
    );
    assert_eq!(
        GratingField::constant(0.0)
            .twisted(f64::NAN)
            .unwrap_err()
            .parameter(),
        "twist"
    );

    // Alternating twist (Fig. 5b): neighbouring squares have perpendicular grating vectors.
    let alt = GratingField::checkerboard(
        0.5,
        Tile::Constant { angle: 0.0 },
        Tile::Constant { angle: FRAC_PI_2 },
    )
    .unwrap();
    let a = alt.direction_at(DVec2::new(0.25, 0.25)).unwrap();
    let b = alt.direction_at(DVec2::new(0.75, 0.25)).unwrap();
    assert!(a.dot(b).abs() < tolerance::FIELD_DIRECTION);
}

#[test]
fn world_direction_and_shading_frame_agree() {
    let field = GratingField::constant(FRAC_PI_2);
    let (tangent, bitangent, normal) = (DVec3::X, DVec3::NEG_Z, DVec3::Y);
    let t = field
        .world_direction(DVec2::ZERO, tangent, bitangent)
        .unwrap();
    assert!((t - DVec3::NEG_Z).length() < tolerance::FIELD_DIRECTION);
    let frame = ShadingFrame::new(normal, t).unwrap();
    // A light along the grating vector tilted up has local x > 0.
    let wi = (t + normal).normalize();
    let local = frame.to_local(wi);
    assert!(local.x > 0.0 && local.z > 0.0 && local.y.abs() < tolerance::FIELD_DIRECTION);
    assert!(ShadingFrame::new(DVec3::Y, DVec3::Y).is_none());
    assert!(ShadingFrame::new(DVec3::ZERO, DVec3::X).is_none());
}
