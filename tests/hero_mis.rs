//! Furnace tests of the documented hero-wavelength MIS recipe (`HeroMis`, `docs/radiometry.md`):
//! under a uniform white sky (radiance 1 relative to the film's illuminant) a surface returns
//! its albedo weighted by the film, E·ȳ/∫E·ȳ. The recipe is run exactly as documented:
//! `SampledWavelengths::sample_visible` (or `sample_uniform`), `Bsdf::sample4`,
//! `HeroMis::{bsdf_sample, emitter_weight, light_sample_weight}`, each contribution converted by
//! `SampledSpectrum::to_xyz` when it is found. The expected values are closed forms (a white
//! Lambertian: Y = 1) or a quadrature over λ of `GratingBsdf::albedo` (itself checked against an
//! independent quadrature in `tests/bsdf_grating.rs`).
//!
//! `cargo test --release --test hero_mis -- --ignored --nocapture` prints the table of measured
//! values (and the old recipe's, f_j·cos/Σ pdf4, for comparison).

#[path = "support/quadrature.rs"]
mod quadrature;
#[path = "support/render_tolerance.rs"]
mod render_tolerance;
#[path = "support/rng.rs"]
mod rng;

use std::f64::consts::{FRAC_1_PI, PI};

use diffraction::bsdf::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use diffraction::cie::Illuminant;
use diffraction::color::Xyz;
use diffraction::{
    Band, Bsdf, BsdfFlags, BsdfSample, DiffractionBrdf, Grating, GratingBsdf, GrooveSpread,
    HeroMis, SampledSpectrum, SampledWavelengths, SpectralFilm,
};
use glam::{DVec2, DVec3};
use render_tolerance::*;
use rng::Rng;

/// A CD-like grating: d = 1.6 µm, half open.
const PERIOD: f64 = 1600.0;
const WIDTH: f64 = 800.0;
/// Samples per furnace estimate.
const SAMPLES: usize = 40_000;
/// The sky as a light: directions uniform on the sphere.
const SKY_PDF: f64 = 1.0 / (4.0 * PI);

/// A white Lambertian reflector with the cosine sampler: the test's own `Bsdf`.
struct Lambert;

impl DiffractionBrdf for Lambert {
    fn eval(&self, wo: DVec3, wi: DVec3, _lambda_nm: f64) -> f64 {
        if wo.z > 0.0 && wi.z > 0.0 {
            FRAC_1_PI
        } else {
            0.0
        }
    }
}

impl Bsdf for Lambert {
    fn sample(&self, wo: DVec3, lambda_nm: f64, _uc: f64, u2: DVec2) -> Option<BsdfSample> {
        let wi = sample_cosine_hemisphere(u2);
        (wo.z > 0.0 && wi.z > 0.0).then(|| {
            BsdfSample::new(
                wi,
                self.eval(wo, wi, lambda_nm),
                cosine_hemisphere_pdf(wi.z),
                BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE,
            )
        })
    }
    fn pdf(&self, wo: DVec3, wi: DVec3, _lambda_nm: f64) -> f64 {
        if wo.z > 0.0 {
            cosine_hemisphere_pdf(wi.z)
        } else {
            0.0
        }
    }
    fn flags(&self) -> BsdfFlags {
        BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE
    }
    fn regularize(&mut self) {}
}

/// How the wavelengths are drawn and which film weighs them.
#[derive(Clone, Copy, Debug)]
enum Spectrum {
    /// `sample_visible` with a D65 film.
    VisibleD65,
    /// `sample_uniform` over the visible band with an equal-energy film.
    UniformE,
}

impl Spectrum {
    fn film(self) -> SpectralFilm {
        match self {
            Spectrum::VisibleD65 => SpectralFilm::new(Illuminant::D65),
            Spectrum::UniformE => SpectralFilm::new(Illuminant::E),
        }
    }
    fn wavelengths(self, u: f64) -> SampledWavelengths {
        match self {
            Spectrum::VisibleD65 => SampledWavelengths::sample_visible(u),
            Spectrum::UniformE => SampledWavelengths::sample_uniform(u, Band::VISIBLE),
        }
    }
}

/// A direction uniform on the unit sphere.
fn sphere(u: DVec2) -> DVec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// One pixel sample of the documented recipe at one surface under the sky: Y of the XYZ the
/// film gets. `light` adds light sampling of the sky, combined with BSDF sampling by MIS.
fn recipe_sample<B: Bsdf>(b: &B, wo: DVec3, spectrum: Spectrum, light: bool, rng: &mut Rng) -> f64 {
    let film = spectrum.film();
    let mut lambdas = spectrum.wavelengths(rng.next_f64());
    let mut mis = HeroMis::new();
    let beta = SampledSpectrum::ONE;
    let sky = SampledSpectrum::ONE;
    let mut pixel = Xyz::default();
    let (u_light, uc, u2) = (rng.u2(), rng.next_f64(), rng.u2());
    if light {
        let wl = sphere(u_light);
        if wl.z > 0.0 {
            let f = SampledSpectrum::new(b.eval4(wo, wl, &lambdas));
            let w = mis.light_sample_weight(SKY_PDF, b.pdf4(wo, wl, &lambdas), &lambdas);
            pixel += (beta * f * sky * (wl.z / SKY_PDF * w)).to_xyz(&lambdas, &film);
        }
    }
    if let Some(s) = b.sample4(wo, &lambdas, uc, u2) {
        mis.bsdf_sample(&s, &mut lambdas);
        let beta = beta * s.weight();
        let light_pdf = if light { SKY_PDF } else { 0.0 };
        pixel += (beta * sky * mis.emitter_weight(light_pdf, &lambdas)).to_xyz(&lambdas, &film);
    }
    pixel.y
}

/// The recipe the crate documented before: weight wavelength j by p_j/Σp, i.e. f_j·cos/Σ pdf4
/// (BSDF sampling alone), for the report.
fn old_recipe_sample<B: Bsdf>(b: &B, wo: DVec3, spectrum: Spectrum, rng: &mut Rng) -> f64 {
    let film = spectrum.film();
    let lambdas = spectrum.wavelengths(rng.next_f64());
    let (_, uc, u2) = (rng.u2(), rng.next_f64(), rng.u2());
    let Some(s) = b.sample4(wo, &lambdas, uc, u2) else {
        return 0.0;
    };
    if s.flags.is_specular() {
        return 0.0;
    }
    let sum: f64 = s.pdf.values().iter().sum();
    (s.f * (s.wi.z / sum)).to_xyz(&lambdas, &film).y
}

/// Mean and standard error of `samples` draws of `f`.
fn estimate(samples: usize, mut f: impl FnMut() -> f64) -> (f64, f64) {
    let (mut s1, mut s2) = (0.0, 0.0);
    for _ in 0..samples {
        let y = f();
        s1 += y;
        s2 += y * y;
    }
    let n = samples as f64;
    let mean = s1 / n;
    (mean, ((s2 / n - mean * mean).max(0.0) / n).sqrt())
}

/// ∫ w_Y(λ)·a(λ) dλ over the band, w_Y the film's Y weight and a the grating's albedo toward
/// `wo`: 8-point Gauss-Legendre (the test's own nodes) on pieces of at most
/// [`QUADRATURE_PIECE_NM`], split where an order's lobe crosses the edge of the disk of
/// directions (|m·λ/d − wo.x| = 1 or √(1 − wo.y²), where the albedo has a kink or, for delta
/// lobes, a step) and cut into [`QUADRATURE_EDGE_NM`] pieces within 1 nm of such a crossing
/// (finite-N ramps of width about λ²/(N·d·|u|)). Its error is measured against a finer rule in
/// `quadrature_of_the_expected_value_is_converged`.
fn expected_y(b: &GratingBsdf, wo: DVec3, film: &SpectralFilm, piece: f64, edge: f64) -> f64 {
    let e = (1.0 - wo.y * wo.y).max(0.0).sqrt();
    let mut kinks = Vec::new();
    for m in 1..=20i32 {
        for edge in [wo.x - 1.0, wo.x + 1.0, wo.x - e, wo.x + e] {
            let l = PERIOD * edge.abs() / m as f64;
            if l > 360.0 && l < 830.0 {
                kinks.push(l);
            }
        }
    }
    let mut cuts = vec![360.0, 830.0];
    let steps = (470.0 / piece).ceil() as usize;
    cuts.extend((1..steps).map(|k| 360.0 + 470.0 * k as f64 / steps as f64));
    for &k in &kinks {
        let near = (1.0 / edge).round() as i32;
        cuts.extend(
            (-near..=near)
                .map(|i| k + i as f64 * edge)
                .filter(|l| *l > 360.0 && *l < 830.0),
        );
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let mut total = 0.0;
    for w in cuts.windows(2) {
        let (p, q) = (w[0], w[1]);
        for (x, wt) in quadrature::X8.iter().zip(quadrature::W8) {
            let l = 0.5 * (p + q) + 0.5 * (q - p) * x;
            total += 0.5 * (q - p) * wt * film.weight(l)[1] * b.albedo(wo, l).unwrap();
        }
    }
    total
}

/// The expected value's quadrature: pieces of at most 20 nm, 0.5 nm within 1 nm of the
/// albedo's kinks.
const QUADRATURE_PIECE_NM: f64 = 20.0;
/// See [`QUADRATURE_PIECE_NM`].
const QUADRATURE_EDGE_NM: f64 = 0.5;

/// The coarse rule of the furnaces against one with 1 nm pieces (the tables' kinks) and
/// 0.1 nm pieces within 1 nm of the albedo's kinks, on the stiffest gratings (N = 1000, ideal groove:
/// steep ramps; N = ∞: steps).
#[test]
fn quadrature_of_the_expected_value_is_converged() {
    let film = Spectrum::VisibleD65.film();
    let cases = [
        GratingBsdf::new(Grating::new(PERIOD, WIDTH, 1000).unwrap())
            .with_groove(GrooveSpread::IDEAL),
        GratingBsdf::new(Grating::infinite(PERIOD, WIDTH).unwrap()),
        GratingBsdf::new(Grating::new(PERIOD, WIDTH, 5).unwrap()),
    ];
    for b in &cases {
        for wo in views() {
            let coarse = expected_y(b, wo, &film, QUADRATURE_PIECE_NM, QUADRATURE_EDGE_NM);
            let fine = expected_y(b, wo, &film, 1.0, 0.1);
            println!(
                "quadrature: {coarse} vs {fine}: {:e}",
                (coarse - fine).abs() / fine
            );
            assert!(
                (coarse - fine).abs() <= QUADRATURE_AGREEMENT * fine,
                "{coarse} vs {fine}"
            );
        }
    }
}

/// The gratings of the tests: several N and groove spreads.
fn gratings() -> Vec<(String, GratingBsdf)> {
    let finite = |n| GratingBsdf::new(Grating::new(PERIOD, WIDTH, n).unwrap());
    let mut out = Vec::new();
    for n in [1, 5, 30, 1000] {
        out.push((format!("N={n}, L=N·d"), finite(n)));
    }
    // (The albedo of a wide Gaussian groove at large N is the slowest to integrate over λ.)
    for n in [5, 30] {
        let g = GrooveSpread::gaussian(0.05).unwrap();
        out.push((format!("N={n}, Gaussian σ=0.05"), finite(n).with_groove(g)));
    }
    for n in [5, 1000] {
        out.push((
            format!("N={n}, ideal groove"),
            finite(n).with_groove(GrooveSpread::IDEAL),
        ));
    }
    out.push((
        "N=∞, ideal groove".into(),
        GratingBsdf::new(Grating::infinite(PERIOD, WIDTH).unwrap()),
    ));
    out
}

fn views() -> [DVec3; 2] {
    [DVec3::Z, DVec3::new(0.3, 0.2, (1.0f64 - 0.13).sqrt())]
}

/// One furnace row: (name, expected, (mean, se) with BSDF sampling, (mean, se) with light +
/// BSDF sampling).
type Row = (String, f64, (f64, f64), (f64, f64));

fn grating_rows() -> Vec<Row> {
    let film = Spectrum::VisibleD65.film();
    let mut rows = Vec::new();
    for (k, (name, b)) in gratings().iter().enumerate() {
        for (j, wo) in views().iter().enumerate() {
            let want = expected_y(b, *wo, &film, QUADRATURE_PIECE_NM, QUADRATURE_EDGE_NM);
            let mut rng = Rng::new(100 + 10 * k as u64 + j as u64);
            let bsdf_only = estimate(SAMPLES, || {
                recipe_sample(b, *wo, Spectrum::VisibleD65, false, &mut rng)
            });
            let both = estimate(SAMPLES, || {
                recipe_sample(b, *wo, Spectrum::VisibleD65, true, &mut rng)
            });
            rows.push((format!("{name}, wo={wo:.2}"), want, bsdf_only, both));
        }
    }
    rows
}

fn lambert_rows() -> Vec<Row> {
    let mut rows = Vec::new();
    for (k, spectrum) in [Spectrum::VisibleD65, Spectrum::UniformE]
        .iter()
        .enumerate()
    {
        for (j, wo) in views().iter().enumerate() {
            let mut rng = Rng::new(7 + 10 * k as u64 + j as u64);
            let bsdf_only = estimate(SAMPLES, || {
                recipe_sample(&Lambert, *wo, *spectrum, false, &mut rng)
            });
            let both = estimate(SAMPLES, || {
                recipe_sample(&Lambert, *wo, *spectrum, true, &mut rng)
            });
            rows.push((
                format!("Lambert, {spectrum:?}, wo={wo:.2}"),
                1.0,
                bsdf_only,
                both,
            ));
        }
    }
    rows
}

fn check(rows: &[Row]) {
    for (name, want, a, b) in rows {
        for (label, (mean, se)) in [("BSDF", a), ("light + BSDF", b)] {
            println!(
                "{name}, {label}: z = {:.2}, se/expected = {:.2e}",
                (mean - want) / se,
                se / want
            );
            assert!(
                (mean - want).abs() <= FURNACE_SIGMAS * se,
                "{name}, {label}: {mean} ± {se}, expected {want}"
            );
            assert!(
                *se <= FURNACE_MAX_RELATIVE_SE * want,
                "{name}, {label}: se {se}"
            );
        }
    }
}

#[test]
fn a_white_lambertian_under_the_sky_is_white() {
    check(&lambert_rows());
}

#[test]
fn a_grating_under_the_sky_returns_its_albedo() {
    check(&grating_rows());
}

/// Two glossy bounces with wavelength-dependent densities (N = 5: the four wavelengths' lobes
/// overlap, so every technique matters): the path-level weights of `HeroMis` against an
/// independent estimator, single-wavelength BSDF sampling of the first bounce times the exact
/// albedo of the second (`GratingBsdf::albedo`).
#[test]
fn two_bounces_match_a_single_wavelength_reference() {
    for (n, seed) in [(5, 11), (30, 12)] {
        let (want, got, _) = two_bounce(n, seed);
        let se = (want.1 * want.1 + got.1 * got.1).sqrt();
        assert!(
            (want.0 - got.0).abs() <= FURNACE_SIGMAS * se,
            "N={n}: hero MIS {got:?}, reference {want:?}"
        );
    }
}

/// The second surface sees the first one's outgoing direction mirrored across its grooves.
fn second_view(w: DVec3) -> DVec3 {
    DVec3::new(-w.x, w.y, w.z)
}

/// (reference, hero MIS with path-level ratios, hero MIS with per-bounce weights), each
/// (mean, se), Y under D65 with visible wavelengths.
fn two_bounce(n: u32, seed: u64) -> ((f64, f64), (f64, f64), (f64, f64)) {
    let b = GratingBsdf::new(Grating::new(PERIOD, WIDTH, n).unwrap());
    let wo = DVec3::new(0.3, 0.2, (1.0f64 - 0.13).sqrt());
    let film = SpectralFilm::new(Illuminant::D65);
    let mut rng = Rng::new(seed);
    let reference = estimate(SAMPLES / 2, || {
        let u = rng.next_f64();
        let l = diffraction::visible::sample(u);
        let p_l = diffraction::visible::pdf(l);
        let Some(s) = b.sample(wo, l, rng.next_f64(), rng.u2()) else {
            return 0.0;
        };
        let a = b.albedo(second_view(s.wi), l).unwrap();
        s.weight() * a * film.weight(l)[1] / p_l
    });
    let mut rng = Rng::new(seed + 1000);
    let mut per_bounce_rng = rng.clone();
    let hero = estimate(SAMPLES, || {
        let mut lambdas = SampledWavelengths::sample_visible(rng.next_f64());
        let mut mis = HeroMis::new();
        let mut beta = SampledSpectrum::ONE;
        let mut w = wo;
        for _ in 0..2 {
            let Some(s) = b.sample4(w, &lambdas, rng.next_f64(), rng.u2()) else {
                return 0.0;
            };
            mis.bsdf_sample(&s, &mut lambdas);
            beta *= s.weight();
            w = second_view(s.wi);
        }
        (beta * mis.emitter_weight(0.0, &lambdas))
            .to_xyz(&lambdas, &film)
            .y
    });
    let per_bounce = estimate(SAMPLES, || {
        let rng = &mut per_bounce_rng;
        let lambdas = SampledWavelengths::sample_visible(rng.next_f64());
        let mut beta = SampledSpectrum::ONE;
        let mut w = wo;
        for _ in 0..2 {
            let Some(s) = b.sample4(w, &lambdas, rng.next_f64(), rng.u2()) else {
                return 0.0;
            };
            beta *= s.weight() * (s.pdf[0] / s.pdf.average());
            w = second_view(s.wi);
        }
        beta.to_xyz(&lambdas, &film).y
    });
    (reference, hero, per_bounce)
}

#[test]
#[ignore = "report: prints the furnace table"]
fn report() {
    println!("| case | expected Y | BSDF (± 1σ) | light + BSDF (± 1σ) | old recipe |");
    println!("|---|---|---|---|---|");
    let mut worst: f64 = 0.0;
    for (rows, old) in [(lambert_rows(), true), (grating_rows(), true)] {
        for (name, want, a, b) in rows {
            worst = worst
                .max(((a.0 - want) / a.1).abs())
                .max(((b.0 - want) / b.1).abs());
            let old_value = if old {
                let mut rng = Rng::new(5);
                let wo = if name.contains("wo=[0.00") {
                    views()[0]
                } else {
                    views()[1]
                };
                let value = if name.starts_with("Lambert") {
                    let spectrum = if name.contains("UniformE") {
                        Spectrum::UniformE
                    } else {
                        Spectrum::VisibleD65
                    };
                    estimate(SAMPLES, || {
                        old_recipe_sample(&Lambert, wo, spectrum, &mut rng)
                    })
                    .0
                } else {
                    let b = gratings()
                        .into_iter()
                        .find(|(n, _)| name.starts_with(n.as_str()))
                        .unwrap()
                        .1;
                    estimate(SAMPLES, || {
                        old_recipe_sample(&b, wo, Spectrum::VisibleD65, &mut rng)
                    })
                    .0
                };
                format!("{:.4}", value / want)
            } else {
                String::new()
            };
            println!(
                "| {name} | {want:.6} | {:.5} ± {:.5} | {:.5} ± {:.5} | {old_value} × |",
                a.0, a.1, b.0, b.1
            );
        }
    }
    println!("largest |z| = {worst:.2}");
    for (n, seed) in [(5, 11), (30, 12)] {
        let (r, h, p) = two_bounce(n, seed);
        println!(
            "two bounces N={n}: reference {:.5} ± {:.5}, HeroMis {:.5} ± {:.5}, per-bounce weights {:.5} ± {:.5}",
            r.0, r.1, h.0, h.1, p.0, p.1
        );
    }
}
