//! The energy-normalised grating's colour through its grating response (the lobe-exact paths
//! with an envelope of wavelength) against a direct quadrature of f·cos θi.

#[path = "support/tolerance.rs"]
mod tol;

use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
use diffraction::{Grating, GratingBsdf, GrooveSpread, SpectralResponse};
use glam::DVec3;

#[test]
fn envelope_path_matches_direct_quadrature() {
    let s = Spectral::new(Illuminant::D65);
    let mut worst = 0.0f64;
    for (n, groove) in [
        (3u32, GrooveSpread::coherence_length(4800.0).unwrap()),
        (5, GrooveSpread::gaussian(0.01).unwrap()),
        (8, GrooveSpread::coherence_length(20_000.0).unwrap()),
    ] {
        let b = GratingBsdf::new(Grating::new(1600.0, 640.0, n).unwrap()).with_groove(groove);
        for (u, v) in [
            (0.0, 0.0),
            (0.12, 0.0),
            (0.34, 0.01),
            (0.8, -0.02),
            (-0.5, 0.005),
        ] {
            let wi = DVec3::new(-0.1, -0.03, (1.0f64 - 0.01 - 0.0009).sqrt());
            let (ox, oy) = (u - wi.x, v - wi.y);
            let wo = DVec3::new(ox, oy, (1.0 - ox * ox - oy * oy).sqrt());
            let r = b.grating_response(wo, wi).unwrap();
            let fast = s.xyz_response(&r, Strategy::EXACT);
            // The generic path through `response` only.
            let direct = s.xyz_brdf(&b, wo, wi, GenericStrategy::gauss_legendre(8192).unwrap());
            let size = direct.x.max(direct.y).max(direct.z);
            assert!(size > 0.0, "n = {n} u = {u}");
            for (a, d) in [(fast.x, direct.x), (fast.y, direct.y), (fast.z, direct.z)] {
                worst = worst.max((a - d).abs() / size);
            }
        }
    }
    println!("envelope path against direct quadrature: {worst:.2e} relative");
    assert!(worst <= tol::ENVELOPE_PATH, "{worst:e}");
}
