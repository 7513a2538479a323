//! One-sample hero-wavelength MIS along a path: the weights a spectral path tracer multiplies
//! its four wavelengths' contributions by, for BSDF samples and for light samples. The recipe
//! and why it is right are in the docs of [`HeroMis`].

use crate::model::bsdf::BsdfSample4;
use crate::path::wavelengths::SampledWavelengths;

/// The MIS state of one path for hero-wavelength sampling: the weights a spectral path tracer
/// multiplies its four wavelengths' contributions by (the reasoning and the recipe are below).
/// It holds the ratios r_k of the prefix's density with λ_k as hero to its density with the
/// actual hero,
/// and the last BSDF sample's densities. Create one per camera ray with [`HeroMis::new`],
/// record every BSDF sample with [`bsdf_sample`](Self::bsdf_sample), and multiply light
/// found along the path by [`emitter_weight`](Self::emitter_weight) (after a BSDF sample) or
/// [`light_sample_weight`](Self::light_sample_weight) (next-event estimation).
///
/// Every weight is finite and in [0, 4] for finite input, the same for the four wavelengths
/// (the technique is which wavelength leads, not the wavelength that is weighted), and 0 for
/// non-finite or negative densities.
///
/// ```
/// use diffraction::{Band, BsdfFlags, BsdfSample4, HeroMis, SampledSpectrum, SampledWavelengths};
/// use glam::DVec3;
/// let mut l = SampledWavelengths::sample_uniform(0.1, Band::VISIBLE);
/// let mut mis = HeroMis::new();
/// assert_eq!(mis.emitter_weight(0.0, &l), 1.0); // the camera ray sees emitters unweighted
/// // A glossy sample whose secondaries have half the hero's density there:
/// let pdf = SampledSpectrum::new([2.0, 1.0, 1.0, 1.0]);
/// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::ONE, pdf, BsdfFlags::GLOSSY);
/// mis.bsdf_sample(&s, &mut l);
/// // BSDF sampling alone: p_0/mean(p) = 2/1.25.
/// assert!((mis.emitter_weight(0.0, &l) - 1.6).abs() < 1e-15);
/// ```
///
/// # Why the weight is not p_j/Σp
///
/// The four wavelengths of [`SampledWavelengths`] are stratified copies of one random number,
/// so each is equally likely to be the hero: a path the hero sampled is one sample of the
/// one-sample MIS (Veach 1997, §9.2.4) of four techniques, "wavelength k leads the path", each
/// chosen with probability c_k = ¼. The balance-heuristic estimator of wavelength j is
/// w_0·F_j/(c_0·p_0) = F_j/(Σ_k c_k·p_k) = F_j/**mean**_k(p_k), with F_j the path's
/// contribution at λ_j and p_k its density under technique k. Dividing by Σ_k p_k instead
/// drops the 1/c and gives images 4× too dark.
///
/// A technique is a whole path: its density is the product of the densities of every bounce,
/// p_k = Π_b pdf(wo_b, wi_b, λ_k). [`HeroMis`] keeps the prefix's ratios r_k = Π_b p_k,b/p_0,b
/// (pbrt-v4 keeps the same `r_u`); weights taken per bounce from that bounce's `pdf4` alone are
/// unbiased for one bounce only.
///
/// With light sampling as well (next-event estimation, multi-sample MIS of the light's density
/// p_L in solid angle against the BSDF's), the techniques are {BSDF, light} × {hero k}, and
/// the weights of the last vertex are, with p_k the BSDF's densities `pdf4` there:
///
/// ```text
/// BSDF sample reaching an emitter:  w = p_0 / mean_k(r_k·(p_k + p_L))   times β_j·Le_j
/// light sample:                     w = p_L / mean_k(r_k·(p_k + p_L))   times β_j·f_j·cos·Le_j/p_L
/// delta light (p_L = ∞):            w = 1 / mean_k(r_k)                  times β_j·f_j·cos·I_j/d²
/// ```
///
/// where β_j is the throughput up to that vertex (each BSDF sample multiplies it by
/// [`BsdfSample4::weight`], f_j·cos θ/p_0). Without light sampling p_L = 0 and the first line
/// is p_0/mean_k(r_k·p_k). After a SPECULAR sample the secondaries are terminated (the delta's
/// direction belongs to the hero) and every weight is the hero's alone.
///
/// **Convert light to XYZ when it is found** ([`SampledSpectrum::to_xyz`](crate::SampledSpectrum::to_xyz)
/// with the wavelengths as they are at that moment) and add the XYZ to the pixel. Termination
/// changes the wavelengths' densities; radiance gathered before it was weighted for four
/// techniques and must be divided by the densities it was found with (summing all of a path's
/// radiance and converting it once at the end is biased for paths that terminate late).
///
/// # The recipe
///
/// ```
/// use diffraction::cie::Illuminant;
/// use diffraction::color::Xyz;
/// use diffraction::{Bsdf, DiffractionBrdf, Grating, GratingBsdf, HeroMis, SampledSpectrum};
/// use diffraction::{SampledWavelengths, SpectralFilm};
/// use glam::{DVec2, DVec3};
///
/// // One pixel sample of a grating under a white sky of radiance 1 (relative to the film's
/// // illuminant), with BSDF sampling and light sampling of the sky (uniform on the sphere).
/// let bsdf = GratingBsdf::new(Grating::new(1600.0, 800.0, 30)?);
/// let film = SpectralFilm::new(Illuminant::D65);
/// let wo = DVec3::new(0.2, 0.1, 0.95f64.sqrt());
/// let sky_pdf = 1.0 / (4.0 * std::f64::consts::PI);
/// let (u_lambda, u_light, uc, u2) = (0.3, DVec2::new(0.2, 0.9), 0.6, DVec2::new(0.4, 0.7));
///
/// let mut lambdas = SampledWavelengths::sample_visible(u_lambda);
/// let mut mis = HeroMis::new();
/// let beta = SampledSpectrum::ONE;
/// let mut pixel = Xyz::default();
///
/// // Light sample: a direction toward the sky with density sky_pdf.
/// let z = 1.0 - 2.0 * u_light.x;
/// let r = (1.0 - z * z).max(0.0).sqrt();
/// let phi = std::f64::consts::TAU * u_light.y;
/// let wl = DVec3::new(r * phi.cos(), r * phi.sin(), z);
/// if wl.z > 0.0 {
///     let f = SampledSpectrum::new(bsdf.eval4(wo, wl, &lambdas));
///     let w = mis.light_sample_weight(sky_pdf, bsdf.pdf4(wo, wl, &lambdas), &lambdas);
///     let le = SampledSpectrum::ONE;
///     pixel += (beta * f * le * (wl.z / sky_pdf * w)).to_xyz(&lambdas, &film);
/// }
/// // BSDF sample: the same call gives the four wavelengths' values and densities.
/// if let Some(s) = bsdf.sample4(wo, &lambdas, uc, u2) {
///     mis.bsdf_sample(&s, &mut lambdas);
///     let beta = beta * s.weight();
///     // The direction reaches the sky, which light sampling produces with density sky_pdf.
///     let le = SampledSpectrum::ONE;
///     pixel += (beta * le * mis.emitter_weight(sky_pdf, &lambdas)).to_xyz(&lambdas, &film);
/// }
/// assert!(pixel.y >= 0.0 && pixel.y.is_finite());
/// # Ok::<(), diffraction::Error>(())
/// ```
///
/// Averaged over many such samples Y is the grating's albedo weighted by D65·ȳ (the furnace
/// tests in `tests/hero_mis.rs` check it for several N and groove spreads, and a white
/// Lambertian's 1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeroMis {
    /// r_k = Π p_k/p_0 over the BSDF samples so far (1 at the camera).
    ratio: [f64; 4],
    /// The ratios before the last BSDF sample and that sample's densities (hero first);
    /// `None` for the camera ray and after a SPECULAR sample (no other technique reaches a
    /// delta's direction).
    last: Option<([f64; 4], [f64; 4])>,
}

impl Default for HeroMis {
    fn default() -> HeroMis {
        HeroMis::new()
    }
}

impl HeroMis {
    /// The state at the camera: every ratio 1, and the camera ray a delta (emitters it reaches
    /// have weight 1).
    ///
    /// ```
    /// use diffraction::{Band, HeroMis, SampledWavelengths};
    /// let l = SampledWavelengths::sample_uniform(0.5, Band::VISIBLE);
    /// assert_eq!(HeroMis::new().light_sample_weight(f64::INFINITY, [0.0; 4], &l), 1.0);
    /// ```
    #[must_use]
    pub fn new() -> HeroMis {
        HeroMis {
            ratio: [1.0; 4],
            last: None,
        }
    }

    /// Records a BSDF sample taken at the path's current vertex (the path tracer multiplies its
    /// throughput by [`sample.weight()`](BsdfSample4::weight) and follows `sample.wi`). A
    /// SPECULAR sample terminates the secondaries of `lambdas`
    /// ([`SampledWavelengths::terminate_secondary`]): a delta lobe's direction is the hero's
    /// alone, so from here on the hero stands for all four wavelengths.
    ///
    /// ```
    /// use diffraction::{Band, BsdfFlags, BsdfSample4, HeroMis, SampledSpectrum, SampledWavelengths};
    /// use glam::DVec3;
    /// let mut l = SampledWavelengths::sample_uniform(0.1, Band::VISIBLE);
    /// let mut mis = HeroMis::new();
    /// let delta = BsdfSample4::new(DVec3::Z, SampledSpectrum::ONE, SampledSpectrum::ONE, BsdfFlags::SPECULAR);
    /// mis.bsdf_sample(&delta, &mut l);
    /// assert!(l.secondary_terminated());
    /// assert_eq!(mis.emitter_weight(0.5, &l), 1.0); // light sampling cannot reach a delta
    /// ```
    pub fn bsdf_sample(&mut self, sample: &BsdfSample4, lambdas: &mut SampledWavelengths) {
        if sample.flags.is_specular() {
            lambdas.terminate_secondary();
            self.last = None;
            return;
        }
        let pdf = sample.pdf.values().map(clean);
        self.last = Some((self.ratio, pdf));
        let p0 = pdf[0];
        for (r, p) in self.ratio.iter_mut().zip(pdf) {
            *r = if p0 > 0.0 { clean(*r * (p / p0)) } else { 0.0 };
        }
    }

    /// The weight of light reached by the last BSDF sample (or by the camera ray, before any):
    /// multiply the path's contribution β_j·Le_j (β including that sample's
    /// [`weight`](BsdfSample4::weight)) by it. `light_pdf` is the density in solid angle with
    /// which the path tracer's light sampling at the previous vertex produces this direction
    /// (0 when the emitter is not light-sampled, or without next-event estimation).
    ///
    /// p_0/mean_k(r_k·(p_k + p_L)) with the ratios before the sample; 1/mean_k(r_k) after a
    /// SPECULAR sample or at the camera (see [`HeroMis`]).
    ///
    /// ```
    /// use diffraction::{Band, BsdfFlags, BsdfSample4, HeroMis, SampledSpectrum, SampledWavelengths};
    /// use glam::DVec3;
    /// let mut l = SampledWavelengths::sample_uniform(0.1, Band::VISIBLE);
    /// let mut mis = HeroMis::new();
    /// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::ONE, SampledSpectrum::splat(3.0), BsdfFlags::GLOSSY);
    /// mis.bsdf_sample(&s, &mut l);
    /// // Equal densities: the classic balance heuristic of BSDF against light, 3/(3 + 1).
    /// assert_eq!(mis.emitter_weight(1.0, &l), 0.75);
    /// ```
    #[must_use]
    pub fn emitter_weight(&self, light_pdf: f64, lambdas: &SampledWavelengths) -> f64 {
        let light_pdf = clean(light_pdf);
        match self.last {
            None => prefix_weight(&self.ratio, lambdas),
            Some((ratio, pdf)) => {
                if light_pdf == f64::INFINITY {
                    return 0.0;
                }
                weight(pdf[0], &ratio, &pdf, light_pdf, lambdas)
            }
        }
    }

    /// The weight of a light sample taken at the path's current vertex: multiply its
    /// contribution β_j·f_j·cos θ·Le_j/p_L by it. `light_pdf` is the light sampler's density p_L
    /// of the direction, in solid angle (`f64::INFINITY` for a delta light: a point or a
    /// directional light, whose contribution is β_j·f_j·cos θ·I_j/d²); `bsdf_pdf4` is
    /// [`Bsdf::pdf4`](crate::Bsdf::pdf4) of the BSDF at the vertex for that direction (the
    /// densities of BSDF sampling, 0 for a delta lobe).
    ///
    /// p_L/mean_k(r_k·(p_k + p_L)); 1/mean_k(r_k) for a delta light (see the
    /// [`HeroMis`] docs).
    ///
    /// ```
    /// use diffraction::{Band, HeroMis, SampledWavelengths};
    /// let l = SampledWavelengths::sample_uniform(0.1, Band::VISIBLE);
    /// let mis = HeroMis::new();
    /// // At the first vertex, against the mean of the BSDF's four densities:
    /// let w = mis.light_sample_weight(1.0, [2.0, 0.0, 1.0, 1.0], &l);
    /// assert_eq!(w, 0.5); // 1/(mean(2, 0, 1, 1) + 1)
    /// ```
    #[must_use]
    pub fn light_sample_weight(
        &self,
        light_pdf: f64,
        bsdf_pdf4: [f64; 4],
        lambdas: &SampledWavelengths,
    ) -> f64 {
        let light_pdf = clean(light_pdf);
        if light_pdf == f64::INFINITY {
            return prefix_weight(&self.ratio, lambdas);
        }
        weight(
            light_pdf,
            &self.ratio,
            &bsdf_pdf4.map(clean),
            light_pdf,
            lambdas,
        )
    }
}

/// A density or ratio as the weights use it: non-negative, NaN as 0, +∞ kept.
#[inline]
fn clean(p: f64) -> f64 {
    if p > 0.0 {
        p
    } else {
        0.0
    }
}

/// The wavelengths whose techniques take part: all four, or the hero alone once the
/// secondaries are terminated.
#[inline]
fn techniques(lambdas: &SampledWavelengths) -> usize {
    if lambdas.secondary_terminated() {
        1
    } else {
        4
    }
}

/// 1/mean_k(r_k) over the techniques (r_0 = 1, so it is at most 4).
fn prefix_weight(ratio: &[f64; 4], lambdas: &SampledWavelengths) -> f64 {
    let n = techniques(lambdas);
    let mean = ratio[..n].iter().sum::<f64>() / n as f64;
    finite_quotient(1.0, mean)
}

/// numerator/mean_k(r_k·(p_k + p_L)) over the techniques.
fn weight(
    numerator: f64,
    ratio: &[f64; 4],
    pdf: &[f64; 4],
    light_pdf: f64,
    lambdas: &SampledWavelengths,
) -> f64 {
    let n = techniques(lambdas);
    // After termination only the hero takes part, with r_0 = 1.
    let mut sum = 0.0;
    for k in 0..n {
        let r = if n == 1 { 1.0 } else { ratio[k] };
        sum += r * (pdf[k] + light_pdf);
    }
    finite_quotient(numerator, sum / n as f64)
}

/// a/b for a ≥ 0, b ≥ 0, clamped into [0, 4] (the largest weight: a technique's share of 1
/// over its selection probability ¼); 0 when b is 0 or the quotient is not finite.
#[inline]
fn finite_quotient(a: f64, b: f64) -> f64 {
    let q = a / b;
    if q.is_finite() && q >= 0.0 {
        q.min(MAX_WEIGHT)
    } else {
        0.0
    }
}

/// The largest weight a technique chosen with probability ¼ can have (1/¼).
const MAX_WEIGHT: f64 = 4.0;
