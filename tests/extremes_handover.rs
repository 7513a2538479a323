//! Reproducers of failures that the extremes sweep (`tests/extremes.rs`) found in parts of the
//! crate it does not vouch for yet: the radiometric grating BSDF, the colour table and the
//! strategy parser. Each is ignored until its part is fixed; each asserts what the fixed
//! function must do, on the exact input that fails today.

use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{ColorTable, Grating, GratingBsdf, GrooveSpread, SpectralResponse};
use glam::DVec3;

/// `grating_response` returns u = wi.x + wo.x = ∞ where the sum overflows (directions far from
/// unit, finite); `AguHill` returns `None` there.
#[test]
#[ignore = "GratingBsdf::grating_response: u = inf where wi.x + wo.x overflows"]
fn grating_response_u_is_finite() {
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100).unwrap())
        .with_groove(GrooveSpread::gaussian(0.05).unwrap());
    let w = DVec3::new(f64::MAX, 0.0, 1.0);
    if let Some(r) = b.grating_response(w, w) {
        assert!(r.u.is_finite() && r.scale.is_finite(), "{r:?}");
    }
}

/// `ColorTable::new` is bounded in nodes but not in time: these take 37-40 s today (issue's
/// measurement; the node budget holds). Each must finish in well under a second, or be
/// refused with an error naming the parameter.
#[test]
#[ignore = "ColorTable::new takes about 40 s (no work bound besides the node budget)"]
fn color_table_is_bounded_in_time() {
    let s = Spectral::new(Illuminant::D65);
    for (g, accuracy) in [
        (
            Grating::new(2537826.6745452136, 1.3211993091378478, 2218803829),
            1e-6,
        ),
        (Grating::new(1e9, 5e-324, u32::MAX), 1e-6),
        (Grating::new(1e300, 5e299, 1000), 1e-3),
    ] {
        let g = g.unwrap();
        let start = std::time::Instant::now();
        if let Ok(t) = ColorTable::new(&s, &g, accuracy) {
            assert!(t.node_count() <= ColorTable::MAX_NODES);
        }
        println!("{g:?} at {accuracy}: {:?}", start.elapsed());
    }
}

/// For d ≥ 10¹⁵ nm the table's `error_estimate` reports 1.88 (up to 1.1·10¹⁰) while its
/// lookups equal `Exact`: the estimate must not exceed the error it estimates by that much.
#[test]
#[ignore = "ColorTable::error_estimate is far above the real error for d >= 1e15 nm"]
fn color_table_error_estimate_is_honest_for_huge_periods() {
    let s = Spectral::new(Illuminant::D65);
    let g = Grating::new(1e15, 5e14, 1000).unwrap();
    let t = ColorTable::new(&s, &g, 1e-3).unwrap();
    let mut worst = 0.0f64;
    for k in 0..=200 {
        let u = -2.0 + 4.0 * k as f64 / 200.0;
        let (a, b) = (t.lookup(u), s.xyz(&g, u, Strategy::EXACT));
        worst = worst.max(
            (a.x - b.x)
                .abs()
                .max((a.y - b.y).abs())
                .max((a.z - b.z).abs()),
        );
    }
    let worst = worst / t.scale();
    assert!(
        t.error_estimate() <= 100.0 * worst.max(t.accuracy()),
        "estimate {} for a measured error of {worst:e}",
        t.error_estimate()
    );
}

/// A strategy name with a count outside its range says "unknown strategy", as for a misspelt
/// name, although the name is known and only the count is out of range: the message should say
/// which count and which range (`uniform: K = 99999999999 is outside 1 to 65536`).
#[test]
#[ignore = "Strategy's parse error does not say that the count, not the name, is wrong"]
fn an_out_of_range_count_is_named() {
    let e = "uniform:99999999999"
        .parse::<Strategy>()
        .unwrap_err()
        .to_string();
    assert!(!e.starts_with("unknown"), "{e}");
    assert!(e.contains("99999999999") && e.contains("65536"), "{e}");
}
