//! Regression tests of failures that the extremes sweep (`tests/extremes.rs`) found in the
//! radiometric grating BSDF and the strategy parser, on the exact inputs that failed: each
//! asserts what the fixed function does. (`ColorTable::new`'s run time on huge inputs, the
//! other known case, is a matter of time, which tests do not assert: its reproducers are in the
//! docs of `TABLE_MAX_SLITS` in `tests/extremes.rs`.)

use diffraction::spectrum::Strategy;
use diffraction::{Grating, GratingBsdf, GrooveSpread, SpectralResponse};
use glam::DVec3;

/// `grating_response` returned u = wi.x + wo.x = ∞ where the sum overflows (directions far
/// from unit, finite); it returns `None` there, as `AguHill` does.
#[test]
fn grating_response_u_is_finite() {
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100).unwrap())
        .with_groove(GrooveSpread::gaussian(0.05).unwrap());
    let w = DVec3::new(f64::MAX, 0.0, 1.0);
    if let Some(r) = b.grating_response(w, w) {
        assert!(r.u.is_finite() && r.scale.is_finite(), "{r:?}");
    }
}

/// A strategy name with a count outside its range says "unknown strategy", as for a misspelt
/// name, although the name is known and only the count is out of range: the message should say
/// which count and which range (`uniform: K = 99999999999 is outside 1 to 65536`).
#[test]
fn an_out_of_range_count_is_named() {
    let e = "uniform:99999999999"
        .parse::<Strategy>()
        .unwrap_err()
        .to_string();
    assert!(!e.starts_with("unknown"), "{e}");
    assert!(e.contains("99999999999") && e.contains("65536"), "{e}");
}
