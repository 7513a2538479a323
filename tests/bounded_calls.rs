//! The bounded-work and finite-output cases of the grating BSDF and the colour table found by
//! the sweeps of issue 18, each as an exact test: the work is counted where the API counts it
//! (colour evaluations of a table build), never timed.

use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
use diffraction::{Bsdf, ColorTable, DiffractionBrdf, Grating, GratingBsdf, GrooveSpread};
use diffraction::{SpectralResponse, MAX_ORDERS};
use glam::{DVec2, DVec3};

#[path = "support/rng.rs"]
mod rng;

/// `peaks` visits at most `MAX_ORDERS` peaks, and the generic colour of an infinite grating
/// (delta lobes: `eval` is 0), of an ideal groove and of a grazing wi is black.
#[test]
fn generic_colour_of_delta_lobes_is_black_and_bounded() {
    let s = Spectral::new(Illuminant::D65);
    let wo = DVec3::new(0.5, 0.0, 0.75f64.sqrt());
    let infinite = GratingBsdf::new(Grating::infinite(1e12, 5e11).unwrap());
    let mut visits = 0u32;
    let summary = infinite.peaks(wo, wo, diffraction::Band::VISIBLE, &mut |_| visits += 1);
    assert_eq!((visits, summary.orders), (MAX_ORDERS, MAX_ORDERS));
    let finite = GratingBsdf::new(Grating::new(1e12, 5e11, 1000).unwrap());
    let ideal = finite.with_groove(GrooveSpread::IDEAL);
    let grazing = DVec3::new((1.0f64 - 1e-202).sqrt(), 0.0, 1e-101);
    for st in [
        GenericStrategy::WINDOWS,
        GenericStrategy::PEAK_SEARCH,
        GenericStrategy::auto(1e-3).unwrap(),
    ] {
        let black = diffraction::color::Xyz::default();
        assert_eq!(s.xyz_brdf(&infinite, wo, wo, st), black, "{st}");
        assert_eq!(s.xyz_brdf(&ideal, wo, wo, st), black, "{st}");
        assert_eq!(s.xyz_brdf(&finite, wo, grazing, st), black, "{st}");
    }
}

/// The albedo at the most candidate orders it accepts (512) is a number within its Parseval
/// bound, for every groove; one more order is `None`.
#[test]
fn albedo_at_the_order_cap() {
    let grooves = [
        None,
        Some(GrooveSpread::gaussian(0.02).unwrap()),
        Some(GrooveSpread::IDEAL),
        Some(GrooveSpread::coherence_length(1e3).unwrap()),
    ];
    // 2·d/λ + 1 candidates: 511 at d = 102 µm, λ = 400 nm.
    for n in [1u32, 129, 1_000_000] {
        for groove in grooves {
            let mut b = GratingBsdf::new(Grating::new(102_000.0, 51_000.0, n).unwrap());
            if let Some(g) = groove {
                b = b.with_groove(g);
            }
            for wo in [DVec3::Z, DVec3::new(0.3, 0.5, (1.0f64 - 0.34).sqrt())] {
                let a = b.albedo(wo, 400.0).expect("within the cap");
                assert!(a > 0.4 && a <= 0.5, "N={n} {groove:?}: {a}");
            }
        }
    }
    let b = GratingBsdf::new(Grating::new(103_000.0, 51_500.0, 1000).unwrap());
    assert_eq!(b.albedo(DVec3::Z, 400.0), None);
}

/// The weight bound holds where the lobe is narrower than the rounding of the phase
/// (issue 18's case: d = 10¹² nm, N = 1 379 100 723), and on a sweep of such gratings.
#[test]
fn weight_bound_holds_below_phase_resolution() {
    let b = GratingBsdf::new(Grating::new(1e12, 3.0, 1_379_100_723).unwrap());
    let wo = DVec3::new(0.39996, 0.17600, 0.8995);
    let bound = b.sample_weight_bound(wo, 417.473);
    let x = b.sample(wo, 417.473, 0.1, DVec2::new(0.8662, 0.3)).unwrap();
    let weight = x.f * x.wi.z / x.pdf;
    assert!(weight <= bound, "{weight} > {bound}");
    let mut r = rng::Rng(0x18);
    let mut worst = 0.0f64;
    for (d, w, n) in [
        (1e12, 3.0, 1_379_100_723u32),
        (1e12, 5e11, u32::MAX),
        (1e9, 1e8, 4_000_000_000),
        (3e7, 1.5e7, 1_000_000_000),
    ] {
        let b = GratingBsdf::new(Grating::new(d, w, n).unwrap());
        for _ in 0..2000 {
            let wo = r.direction(0.05);
            let l = 360.0 + 470.0 * r.next_f64();
            let bound = b.sample_weight_bound(wo, l);
            if let Some(x) = b.sample(wo, l, r.next_f64(), r.u2()) {
                let weight = x.f * x.wi.z / x.pdf;
                assert!(weight.is_finite() && weight >= 0.0);
                // The bound's own rounding: a few ulp.
                assert!(
                    weight <= bound * (1.0 + 1e-12),
                    "d={d} N={n}: {weight} > {bound}"
                );
                // f and pdf agree with eval and pdf at the returned direction.
                assert_eq!(x.f, b.eval(wo, x.wi, l));
                assert_eq!(x.pdf, b.pdf(wo, x.wi, l));
                worst = worst.max(weight / bound);
            }
        }
    }
    println!("largest weight / bound below phase resolution: {worst:.3}");
}

/// Finite outputs where wi.x + wo.x overflows, and at the smallest period.
#[test]
fn finite_where_the_phase_overflows() {
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 10).unwrap());
    let (wo, wi) = (
        DVec3::new(f64::MAX, 0.0, 1.0),
        DVec3::new(f64::MAX, 0.0, 1.0),
    );
    assert!(b.grating_response(wo, wi).is_none());
    assert_eq!(b.sample_weight_bound(wo, 500.0), 0.0);
    assert!(b.lobe_half_width(500.0).is_finite());
    let tiny = GratingBsdf::new(Grating::new(5e-324, 5e-324, 1).unwrap());
    assert!(tiny.lobe_half_width(500.0).is_finite());
    for l in [1e-300, 500.0, f64::MAX] {
        let bound = tiny.sample_weight_bound(DVec3::Z, l);
        assert!(bound.is_finite() && bound >= 0.0, "{l}: {bound}");
        let big = b.sample_weight_bound(DVec3::new(0.3, 0.0, 0.91f64.sqrt()), l);
        assert!(big.is_finite() && big >= 0.0, "{l}: {big}");
    }
}

/// Table builds of the cases stay within the evaluation budget, and where order 0's
/// lobe is narrower than any grid the estimate stays truthful: at the accuracy for d = 10²⁰
/// and 10³⁰⁰, N = 10⁶, with lookups within it of `Exact` everywhere (equal below 2⁻⁶⁴).
#[test]
fn table_builds_are_bounded() {
    let s = Spectral::new(Illuminant::D65);
    for (d, w, n, accuracy) in [
        (2537826.6745452136, 1.3211993091378478, 2218803829u32, 1e-6),
        (1e9, 5e-324, u32::MAX, 1e-6),
        (1e300, 5e299, 1000, 1e-3),
    ] {
        let g = Grating::new(d, w, n).unwrap();
        let t = ColorTable::new(&s, &g, accuracy).unwrap();
        // The initial grid (at most 2601 evaluations) and the refinement budget of 16384 units,
        // each evaluation at least one.
        assert!(t.evaluations() <= 2601 + ColorTable::MAX_WORK, "d={d}");
        assert!(t.error_estimate().is_finite(), "d={d}");
    }
    for d in [1e20, 1e300] {
        let g = Grating::new(d, d / 2.0, 1_000_000).unwrap();
        let t = ColorTable::new(&s, &g, 1e-3).unwrap();
        assert!(
            t.error_estimate() <= 2.0 * t.accuracy(),
            "d={d}: {}",
            t.error_estimate()
        );
        assert_eq!(t.lookup(0.0), s.white());
        for u in [1e-320, 1e-300, 1e-25, 5e-20] {
            assert_eq!(t.lookup(u), s.xyz(&g, u, Strategy::EXACT), "d={d} u={u}");
        }
        for k in 0..120 {
            let u = 2.0 * 10f64.powf(-0.2 * k as f64);
            let (e, l) = (s.xyz(&g, u, Strategy::EXACT), t.lookup(u));
            let err = (e.x - l.x)
                .abs()
                .max((e.y - l.y).abs())
                .max((e.z - l.z).abs());
            assert!(
                err <= 2e-3 * t.scale().max(e.y),
                "d={d} u={u}: {l:?} vs {e:?}"
            );
        }
    }
}
