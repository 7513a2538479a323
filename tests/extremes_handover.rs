//! Regression tests of failures that the extremes sweep (`tests/extremes.rs`) found in the
//! radiometric grating BSDF and the strategy parser, on the exact inputs that failed: each
//! asserts what the fixed function does. (`ColorTable::new`'s run time on huge inputs, the
//! other known case, is a matter of time, which tests do not assert: its reproducers are in the
//! docs of `TABLE_MAX_SLITS` in `tests/extremes.rs`.)

#[path = "support/tolerance.rs"]
mod tolerance;

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
    let r = b.grating_response(w, w);
    assert!(r.is_none(), "u = wi.x + wo.x overflows: {r:?}");
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

/// At N = ∞ `sample` read the efficiency of the order clamped to i32 while the order's sampling
/// weight used the true order: beyond 2³¹ (here wo far from unit, m ≈ 2·10¹²; with unit
/// directions d/λ > 10⁹ does the same) the weight was 4.4e-20 against a bound of 5.0e-37.
#[test]
fn sample_weight_bound_beyond_i32_orders() {
    use diffraction::Bsdf;
    use glam::DVec2;
    let b =
        GratingBsdf::new(Grating::infinite(1.0, 1e-6).unwrap()).with_groove(GrooveSpread::IDEAL);
    let wo = DVec3::new(1e12, -4.770228783212094e-226, 1.0);
    let bound = b.sample_weight_bound(wo, 0.5);
    let x = b
        .sample(wo, 0.5, 2.2250738585072014e-308, DVec2::new(1e-9, 1e-12))
        .expect("the sweep's case samples a direction");
    assert!(
        x.weight() <= bound * (1.0 + tolerance::WEIGHT_BOUND_ROUNDING),
        "{} > {bound:e}",
        x.weight()
    );
    // Unit directions: d/λ = 2·10⁹, orders up to 4·10⁹.
    let b =
        GratingBsdf::new(Grating::infinite(1e12, 3e11).unwrap()).with_groove(GrooveSpread::IDEAL);
    let wo = DVec3::new(0.6, 0.0, 0.8);
    let mut sampled = 0;
    for k in 0..64 {
        let uc = (k as f64 + 0.5) / 64.0;
        let bound = b.sample_weight_bound(wo, 500.0);
        if let Some(x) = b.sample(wo, 500.0, uc, DVec2::new(0.5, 0.5)) {
            sampled += 1;
            assert!(
                x.weight() <= bound * (1.0 + tolerance::WEIGHT_BOUND_ROUNDING),
                "uc {uc}: {} > {bound:e}",
                x.weight()
            );
        }
    }
    println!("{sampled} of 64 choices sampled an order");
    // Measured 64 of 64.
    assert!(
        2 * sampled >= 64,
        "only {sampled} of 64 choices sampled an order"
    );
}
