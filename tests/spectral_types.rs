//! The path tracer's spectral types: `SampledSpectrum::to_xyz` is an unbiased estimate of the
//! crate's reference colour (`Spectral`), the visible-wavelength sampler's density integrates to
//! 1 and its CDF inverts exactly, and `Bsdf::sample4` is `sample` + `eval4` + `pdf4`.

#[path = "support/quadrature.rs"]
mod quadrature;
#[path = "support/render_tolerance.rs"]
mod render_tolerance;
#[path = "support/rng.rs"]
mod rng;

use diffraction::cie::Illuminant;
use diffraction::color::Xyz;
use diffraction::spectrum::{Spectral, Strategy};
use diffraction::{
    visible, Band, Bsdf, BsdfFlags, BsdfSample, DiffractionBrdf, Grating, GratingBsdf,
    GrooveSpread, SampledSpectrum, SampledWavelengths, SpectralFilm,
};
use glam::{DVec2, DVec3};
use render_tolerance::*;
use rng::Rng;

/// Monte-Carlo mean and standard error per channel of `to_xyz` of `value(λ)`.
fn film_estimate(
    film: &SpectralFilm,
    visible_sampler: bool,
    samples: usize,
    seed: u64,
    value: impl Fn(f64) -> f64,
) -> ([f64; 3], [f64; 3]) {
    let mut rng = Rng::new(seed);
    let (mut s1, mut s2) = ([0.0; 3], [0.0; 3]);
    for _ in 0..samples {
        let u = rng.next_f64();
        let l = if visible_sampler {
            SampledWavelengths::sample_visible(u)
        } else {
            SampledWavelengths::sample_uniform(u, Band::VISIBLE)
        };
        let s = SampledSpectrum::new(l.lambda().map(&value));
        let Xyz { x, y, z } = s.to_xyz(&l, film);
        for (c, v) in [x, y, z].into_iter().enumerate() {
            s1[c] += v;
            s2[c] += v * v;
        }
    }
    let n = samples as f64;
    let mean = s1.map(|s| s / n);
    let se = [0, 1, 2].map(|c| ((s2[c] / n - mean[c] * mean[c]).max(0.0) / n).sqrt());
    (mean, se)
}

fn assert_unbiased(name: &str, (mean, se): ([f64; 3], [f64; 3]), want: Xyz) {
    for (c, w) in [want.x, want.y, want.z].into_iter().enumerate() {
        println!("{name}, channel {c}: z = {:.2}", (mean[c] - w) / se[c]);
        assert!(
            (mean[c] - w).abs() <= FILM_SIGMAS * se[c] + FILM_ROUNDING * w.abs(),
            "{name}, channel {c}: {} ± {}, reference {w}",
            mean[c],
            se[c]
        );
    }
}

#[test]
fn a_flat_spectrum_averages_to_the_illuminant_white() {
    for (k, ill) in [Illuminant::E, Illuminant::D65, Illuminant::A]
        .into_iter()
        .enumerate()
    {
        let film = SpectralFilm::new(ill);
        let want = Spectral::new(ill).white();
        assert_eq!(want.y, 1.0);
        for visible in [false, true] {
            let est = film_estimate(&film, visible, FILM_SAMPLES, 10 + k as u64, |_| 1.0);
            assert_unbiased(&format!("{ill}, visible {visible}"), est, want);
        }
    }
}

#[test]
fn a_grating_colour_by_monte_carlo_is_the_reference_colour() {
    // The paper's intensity I(u, λ) of a 5-slit grating (a smooth spectrum with several orders)
    // and of a 30-slit one (narrower peaks), against `Spectral::xyz` with `Exact`.
    for (n, u) in [(5, 0.4), (5, 0.9), (30, 0.6)] {
        let g = Grating::new(1600.0, 800.0, n).unwrap();
        for (k, ill) in [Illuminant::D65, Illuminant::A].into_iter().enumerate() {
            let film = SpectralFilm::new(ill);
            let want = Spectral::new(ill).xyz(&g, u, Strategy::EXACT);
            for visible in [false, true] {
                let est = film_estimate(
                    &film,
                    visible,
                    FILM_SAMPLES,
                    20 + k as u64 + n as u64,
                    |l| g.intensity(u, l),
                );
                assert_unbiased(&format!("N={n} u={u} {ill} visible {visible}"), est, want);
            }
        }
    }
}

#[test]
fn the_visible_density_integrates_to_one_and_its_cdf_is_its_integral() {
    // The test's own 8-point Gauss-Legendre on every 1 nm.
    let integral = |a: f64, b: f64| {
        let pieces = ((b - a).ceil() as usize).max(1);
        let h = (b - a) / pieces as f64;
        let mut sum = 0.0;
        for k in 0..pieces {
            let (p, q) = (a + k as f64 * h, a + (k + 1) as f64 * h);
            for (x, w) in quadrature::X8.iter().zip(quadrature::W8) {
                sum += 0.5 * (q - p) * w * visible::pdf(0.5 * (p + q) + 0.5 * (q - p) * x);
            }
        }
        sum
    };
    let total = integral(360.0, 830.0);
    println!("∫p − 1 = {:e}", total - 1.0);
    assert!((total - 1.0).abs() <= VISIBLE_PDF_INTEGRAL, "∫p = {total}");
    for l in [400.0, 538.0, 611.3, 700.0, 829.0] {
        let c = integral(360.0, l);
        println!("P({l}) − ∫p = {:e}", visible::cdf(l) - c);
        assert!(
            (visible::cdf(l) - c).abs() <= VISIBLE_PDF_INTEGRAL,
            "P({l}) = {} vs ∫p = {c}",
            visible::cdf(l)
        );
    }
    assert_eq!(visible::pdf(359.9), 0.0);
    assert_eq!(visible::pdf(830.1), 0.0);
}

#[test]
fn the_visible_sampler_is_the_exact_inverse_cdf() {
    let mut worst_u: f64 = 0.0;
    let mut worst_l: f64 = 0.0;
    let n = 100_000;
    for i in 0..n {
        let u = (i as f64 + 0.5) / n as f64;
        let l = visible::sample(u);
        assert!((360.0..=830.0).contains(&l));
        worst_u = worst_u.max((visible::cdf(l) - u).abs());
        let back = visible::sample(visible::cdf(l));
        worst_l = worst_l.max((back - l).abs() / l);
    }
    println!("round trips: u {worst_u:e}, λ {worst_l:e}");
    assert!(
        worst_u <= VISIBLE_CDF_ROUND_TRIP,
        "|P(P⁻¹(u)) − u| up to {worst_u:e}"
    );
    assert!(
        worst_l <= VISIBLE_LAMBDA_ROUND_TRIP,
        "|P⁻¹(P(λ)) − λ|/λ up to {worst_l:e}"
    );
    // Monotone, and the ends.
    assert_eq!(visible::sample(0.0), 360.0);
    assert!(visible::sample(1.0 - f64::EPSILON) <= 830.0);
    let mut prev = 0.0;
    for i in 0..1000 {
        let l = visible::sample(i as f64 / 1000.0);
        assert!(l >= prev);
        prev = l;
    }
}

#[test]
fn stratified_visible_wavelengths_carry_their_densities() {
    let mut rng = Rng::new(3);
    for _ in 0..1000 {
        let u = rng.next_f64();
        let l = SampledWavelengths::sample_visible(u);
        for j in 0..4 {
            let t = (u + 0.25 * j as f64).fract();
            assert_eq!(l.lambda()[j], visible::sample(t));
            assert_eq!(l.pdf()[j], visible::pdf(l.lambda()[j]));
        }
    }
}

/// Gratings for the `sample4` checks: glossy and specular, several N and grooves.
fn gratings() -> Vec<GratingBsdf> {
    let mut v = Vec::new();
    for n in [1, 5, 30, 1000, 1_000_000] {
        let b = GratingBsdf::new(Grating::new(1600.0, 800.0, n).unwrap());
        v.push(b.with_groove(GrooveSpread::gaussian(0.03).unwrap()));
        v.push(b.with_groove(GrooveSpread::IDEAL));
        v.push(b);
    }
    v.push(GratingBsdf::new(Grating::infinite(1600.0, 800.0).unwrap()));
    v.push(
        GratingBsdf::new(Grating::infinite(740.0, 300.0).unwrap())
            .with_groove(GrooveSpread::gaussian(0.02).unwrap()),
    );
    v
}

#[test]
fn sample4_is_sample_eval4_and_pdf4() {
    let mut rng = Rng::new(17);
    let mut glossy = 0;
    let mut specular = 0;
    for b in gratings() {
        for _ in 0..2000 {
            let wo = rng.direction(1e-3);
            let lambdas = SampledWavelengths::sample_visible(rng.next_f64());
            let (uc, u2) = (rng.next_f64(), rng.u2());
            let four = b.sample4(wo, &lambdas, uc, u2);
            let hero = b.sample(wo, lambdas.hero(), uc, u2);
            let (Some(four), Some(hero)) = (four, hero) else {
                assert_eq!(four.is_none(), hero.is_none());
                continue;
            };
            assert_eq!(
                (four.wi, four.flags, four.order),
                (hero.wi, hero.flags, hero.order)
            );
            assert_eq!((four.f[0], four.pdf[0]), (hero.f, hero.pdf));
            if hero.flags.is_specular() {
                specular += 1;
                assert_eq!(&four.f.values()[1..], &[0.0; 3]);
                assert_eq!(&four.pdf.values()[1..], &[0.0; 3]);
            } else {
                glossy += 1;
                // Bit-identical: the same operations as eval and pdf.
                assert_eq!(four.f.values(), b.eval4(wo, four.wi, &lambdas));
                assert_eq!(four.pdf.values(), b.pdf4(wo, four.wi, &lambdas));
                for j in 0..4 {
                    assert_eq!(four.f[j], b.eval(wo, four.wi, lambdas.lambda()[j]));
                }
            }
            let w = four.weight();
            assert!(w.values().iter().all(|x| x.is_finite() && *x >= 0.0));
        }
    }
    assert!(
        glossy > 10_000 && specular > 5_000,
        "{glossy} glossy, {specular} specular"
    );
}

/// A grating behind the trait's default `sample4` (everything else delegated).
struct DefaultFour(GratingBsdf);

impl DiffractionBrdf for DefaultFour {
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.0.eval(wo, wi, lambda_nm)
    }
    fn eval4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        self.0.eval4(wo, wi, lambdas)
    }
}

impl Bsdf for DefaultFour {
    fn sample(&self, wo: DVec3, lambda_nm: f64, uc: f64, u2: DVec2) -> Option<BsdfSample> {
        self.0.sample(wo, lambda_nm, uc, u2)
    }
    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.0.pdf(wo, wi, lambda_nm)
    }
    fn flags(&self) -> BsdfFlags {
        self.0.flags()
    }
    fn regularize(&mut self) {
        self.0.regularize();
    }
}

#[test]
fn the_default_sample4_equals_the_gratings_own() {
    let mut rng = Rng::new(23);
    for b in gratings() {
        let d = DefaultFour(b.clone());
        for _ in 0..500 {
            let wo = rng.direction(1e-3);
            let lambdas = SampledWavelengths::sample_uniform(rng.next_f64(), Band::VISIBLE);
            let (uc, u2) = (rng.next_f64(), rng.u2());
            assert_eq!(
                d.sample4(wo, &lambdas, uc, u2),
                b.sample4(wo, &lambdas, uc, u2)
            );
        }
    }
}

#[test]
fn sample4_rejects_what_sample_rejects() {
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100).unwrap());
    let l = SampledWavelengths::sample_visible(0.5);
    assert!(b.sample4(-DVec3::Z, &l, 0.5, DVec2::splat(0.5)).is_none());
    let nan = DVec3::new(f64::NAN, 0.0, 1.0);
    assert!(b.sample4(nan, &l, 0.5, DVec2::splat(0.5)).is_none());
    // Non-finite random numbers follow the crate's rule (taken as 0), never NaN out.
    let zero = b.sample4(DVec3::Z, &l, 0.0, DVec2::ZERO);
    assert_eq!(
        b.sample4(DVec3::Z, &l, f64::NAN, DVec2::splat(f64::INFINITY)),
        zero
    );
    // u2 = (0, 0.5) at the choice 0.5: order 0 at the lobe's edge in u, a direction.
    let s = b
        .sample4(DVec3::Z, &l, 0.5, DVec2::new(f64::NAN, 0.5))
        .expect("u2 = (0, 0.5) at the choice 0.5 samples order 0");
    assert_eq!(Some(s), b.sample4(DVec3::Z, &l, 0.5, DVec2::new(0.0, 0.5)));
    assert!(s
        .f
        .values()
        .iter()
        .chain(&s.pdf.values())
        .all(|x| x.is_finite()));
}

#[test]
fn spectrum_arithmetic_never_makes_nan_from_finite_values() {
    let mut rng = Rng::new(9);
    let pick = |rng: &mut Rng| {
        let choices = [0.0, -0.0, 1.0, 1e-300, 1e300, -2.5, f64::MIN_POSITIVE];
        choices[(rng.next_u64() % choices.len() as u64) as usize]
    };
    for _ in 0..10_000 {
        let a = SampledSpectrum::from_fn(|_| pick(&mut rng));
        let b = SampledSpectrum::from_fn(|_| pick(&mut rng));
        let k = pick(&mut rng);
        for s in [
            a + b,
            a - b,
            a * b,
            a / b,
            a * k,
            a / k,
            a.safe_div(b),
            a.max(b),
            a.min(b),
        ] {
            assert!(s.values().iter().all(|v| !v.is_nan()), "{a:?} {b:?} {k}");
        }
        assert!(!a.average().is_nan() && !a.max_value().is_nan());
    }
}
