//! The groove spread g(v): unit integral, closed-form mass against quadrature of the value, the
//! proxy sampler against its density, the bound of g/q, and the four-wavelength calls against
//! the one-wavelength ones.

#[path = "support/bsdf_check.rs"]
mod bsdf_check;

use bsdf_check::*;
use diffraction::{
    Band, Bsdf, DiffractionBrdf, Grating, GratingBsdf, GrooveKind, GrooveSpread, SampledWavelengths,
};

fn spreads() -> [GrooveSpread; 3] {
    [
        GrooveSpread::coherence_length(20_000.0).unwrap(),
        GrooveSpread::coherence_length(1.6e9).unwrap(),
        GrooveSpread::gaussian(0.03).unwrap(),
    ]
}

#[test]
fn mass_is_the_integral_of_the_value() {
    for g in spreads() {
        for (a, b) in [(-0.2, 0.1), (0.05, 0.4), (-1e-6, 2e-6), (-2.0, -0.5)] {
            let l = 532.0;
            // Pieces fine enough for the lobe and every side lobe (period λ/L in v).
            let scale = match g.kind() {
                GrooveKind::CoherenceLength { length_nm } => l / length_nm,
                _ => proxy_scale(g, l),
            };
            let pieces = ((b - a) / scale * 4.0).clamp(4000.0, 2_000_000.0) as usize;
            let num = integrate(a, b, pieces, &|v| g.value(v, l));
            assert!(
                (g.mass(a, b, l) - num).abs()
                    <= MASS_AGREEMENT.max(MASS_AGREEMENT_NARROW_REL * num),
                "{g:?} [{a}, {b}]: {} vs {num}",
                g.mass(a, b, l)
            );
            assert!((g.mean(a, b, l) * (b - a) - g.mass(a, b, l)).abs() < MEAN_TIMES_WIDTH);
        }
    }
}

#[test]
fn proxy_bound_holds_and_the_proxy_is_a_density() {
    for g in spreads() {
        let l = 600.0;
        let s = proxy_scale(g, l);
        let bound = g.proxy_bound();
        let mut worst: f64 = 0.0;
        for i in 0..200_000 {
            let v = (i as f64 - 100_000.0) * s * 1e-4;
            worst = worst.max(g.value(v, l) / g.pdf(v, l));
        }
        assert!(worst <= bound, "{g:?}: {worst} > {bound}");
        // The bound is tight (it is a supremum, not a loose estimate).
        assert!(
            worst >= (1.0 - PROXY_BOUND_TIGHT) * bound,
            "{g:?}: {worst} ≪ {bound}"
        );
        // The proxy's CDF is the sampler's inverse: uc → v → uc.
        for k in 1..100 {
            let uc = k as f64 / 100.0;
            let v = g.sample(uc, l);
            let back = 0.5 + (v / s).atan() / std::f64::consts::PI;
            assert!((back - uc).abs() < PROXY_ROUND_TRIP);
        }
        // The density is the documented Cauchy proxy of that scale.
        for v in [0.0, 0.3 * s, -4.0 * s] {
            let q = s / (std::f64::consts::PI * (s * s + v * v));
            assert!((g.pdf(v, l) - q).abs() <= 1e-14 * q, "{g:?} at {v}");
        }
        assert!(bound < 1.521);
    }
}

#[test]
fn four_wavelengths_equal_four_calls() {
    let mut rng = Rng::new(4);
    for n in [1, 30, 1_000_000] {
        let b = GratingBsdf::new(Grating::new(1600.0, 800.0, n).unwrap());
        for _ in 0..500 {
            let (wo, wi) = (rng.direction(0.01), rng.direction(0.01));
            let l = SampledWavelengths::sample_uniform(rng.next_f64(), Band::VISIBLE);
            let (f4, p4) = (b.eval4(wo, wi, &l), b.pdf4(wo, wi, &l));
            for i in 0..4 {
                assert_eq!(f4[i], b.eval(wo, wi, l.lambda()[i]));
                assert_eq!(p4[i], b.pdf(wo, wi, l.lambda()[i]));
            }
        }
    }
}
