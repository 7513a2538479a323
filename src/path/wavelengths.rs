//! The wavelengths a spectral path carries: a hero wavelength and three companions with their
//! sampling densities (pbrt-v4's `SampledWavelengths`).

use crate::error::{Error, Requirement};
use crate::num::random::unit_random;
use crate::path::visible;
use crate::Band;

/// Four wavelengths carried by one path, with the densities they were sampled with
/// (pbrt-v4's `SampledWavelengths`). Index 0 is the **hero** wavelength: the one
/// [`Bsdf::sample`](crate::Bsdf::sample) follows.
///
/// Two ways to use the four with a dispersive BSDF (the sampled direction depends on λ):
///
/// * **Hero-wavelength MIS** (Wilkie et al., "Hero Wavelength Spectral Sampling", EGSR 2014):
///   the four wavelengths are stratified copies of one random number, so each of them is
///   equally likely to be the hero, and a direction the hero sampled is a sample of the
///   one-sample MIS of four techniques (wavelength k's sampler, each chosen with probability
///   ¼). Wavelength j's estimate is f_j·cos θ/(¼·Σ_k p_k) = f_j·cos θ/mean(pdf4), **not**
///   f_j·cos θ/Σ_k p_k (which is 4× too dark). Along a path the techniques are whole paths,
///   so the densities multiply over the bounces: [`HeroMis`](crate::HeroMis) keeps that
///   state and gives the weights of BSDF samples and of light samples.
/// * **Terminate the secondaries** (pbrt-v4's `TerminateSecondary`): keep the hero only and
///   divide by its density alone ([`terminate_secondary`](Self::terminate_secondary)).
///
/// For gratings the crate recommends **hero MIS** for glossy samples: the lobes of order m sit
/// at u = m·λ/d, so for large N the secondaries' densities at the hero's direction are tiny
/// and the balance heuristic gives the hero's own estimate back (it degrades gracefully into
/// termination, with no bias and no branch), while for small N, where the lobes overlap, it
/// keeps their contribution. For **SPECULAR** samples (N = ∞ or an ideal groove) the
/// secondaries' densities are exactly 0 and `pdf4` cannot express the delta: there terminate
/// the secondaries, as pbrt does for dispersive specular surfaces ([`HeroMis`](crate::HeroMis)
/// does it for you).
///
/// ```
/// use diffraction::{Band, SampledWavelengths};
/// let mut l = SampledWavelengths::sample_uniform(0.0, Band::VISIBLE);
/// assert_eq!(l.lambda(), [360.0, 477.5, 595.0, 712.5]); // stratified: B/4 apart
/// assert_eq!(l.pdf(), [1.0 / 470.0; 4]);
/// l.terminate_secondary();
/// assert!(l.secondary_terminated());
/// assert_eq!(l.pdf(), [0.25 / 470.0, 0.0, 0.0, 0.0]); // the hero now stands for all four
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledWavelengths {
    lambda: [f64; 4],
    pdf: [f64; 4],
}

impl SampledWavelengths {
    /// The smallest nonzero density [`new`](Self::new) accepts, 1/nm: the smallest normal
    /// `f64` (2.2·10⁻³⁰⁸), so that 1/pdf is finite (a subnormal density such as 5·10⁻³²⁴ made
    /// [`SampledSpectrum::to_xyz`](crate::SampledSpectrum::to_xyz) infinite).
    ///
    /// ```
    /// assert_eq!(diffraction::SampledWavelengths::MIN_PDF, f64::MIN_POSITIVE);
    /// ```
    pub const MIN_PDF: f64 = f64::MIN_POSITIVE;

    /// Stratified uniform wavelengths: the hero at `band.min + uc·B`, the others B/4 apart
    /// (wrapping around the band), each with density 1/B. `uc` by the crate's rule for random
    /// numbers ([`unit_random`](crate::unit_random)). Every wavelength is in the band and every
    /// density finite and at most 10⁶ per nm ([`Band::MIN_WIDTH_NM`]), and at least
    /// [`MIN_PDF`](Self::MIN_PDF) (a band wider than 1/`MIN_PDF` = 4.5·10³⁰⁷ nm gets that
    /// density), so the result is one that [`new`](Self::new) accepts.
    ///
    /// ```
    /// use diffraction::{Band, SampledWavelengths};
    /// let l = SampledWavelengths::sample_uniform(0.5, Band::new(400.0, 800.0)?);
    /// assert_eq!(l.lambda(), [600.0, 700.0, 400.0, 500.0]);
    /// assert_eq!(l.hero(), 600.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn sample_uniform(uc: f64, band: Band) -> SampledWavelengths {
        let u = unit_random(uc);
        let b = band.width_nm();
        let mut lambda = [0.0; 4];
        for (i, l) in lambda.iter_mut().enumerate() {
            let mut t = u + 0.25 * i as f64;
            if t >= 1.0 {
                t -= 1.0;
            }
            *l = (band.min_nm() + t * b).min(band.max_nm());
        }
        SampledWavelengths {
            lambda,
            pdf: [(1.0 / b).max(Self::MIN_PDF); 4],
        }
    }

    /// Stratified wavelengths from the visible importance density of pbrt-v4
    /// ([`visible`](crate::path::visible): ∝ 1/cosh²(0.0072·(λ − 538)) over 360-830 nm): the hero
    /// at the inverse CDF of `uc`, the others at the inverse CDF of uc + ¼, uc + ½, uc + ¾
    /// (modulo 1), each with its density [`visible::pdf`](crate::path::visible::pdf). Fewer samples
    /// fall where the eye sees little (violet, deep red) than with
    /// [`sample_uniform`](Self::sample_uniform). `uc` by the crate's rule for random numbers.
    ///
    /// ```
    /// use diffraction::{visible, SampledWavelengths};
    /// let l = SampledWavelengths::sample_visible(0.2);
    /// assert_eq!(l.hero(), visible::sample(0.2));
    /// assert_eq!(l.lambda()[2], visible::sample(0.7));
    /// assert_eq!(l.pdf()[1], visible::pdf(l.lambda()[1]));
    /// ```
    #[must_use]
    pub fn sample_visible(uc: f64) -> SampledWavelengths {
        let u = unit_random(uc);
        let mut lambda = [0.0; 4];
        let mut pdf = [0.0; 4];
        for i in 0..4 {
            let mut t = u + 0.25 * i as f64;
            if t >= 1.0 {
                t -= 1.0;
            }
            lambda[i] = visible::sample(t);
            pdf[i] = visible::pdf(lambda[i]);
        }
        SampledWavelengths { lambda, pdf }
    }

    /// Four wavelengths (finite, > 0) with their densities: finite, and 0 (a terminated
    /// secondary) or at least [`MIN_PDF`](Self::MIN_PDF) per nm, so that 1/pdf is finite. For
    /// example from a grating's own wavelength sampler. Errors name `lambda_nm` or `pdf`.
    ///
    /// ```
    /// use diffraction::SampledWavelengths;
    /// let l = SampledWavelengths::new([500.0, 510.0, 520.0, 530.0], [0.01; 4])?;
    /// assert_eq!(l.lambda()[3], 530.0);
    /// assert_eq!(SampledWavelengths::new([0.0; 4], [0.01; 4]).unwrap_err().parameter(), "lambda_nm");
    /// // A subnormal density: 1/pdf would be infinite.
    /// assert_eq!(
    ///     SampledWavelengths::new([500.0; 4], [5e-324, 0.01, 0.01, 0.01]).unwrap_err().to_string(),
    ///     "invalid pdf = 5e-324: must satisfy pdf >= SampledWavelengths::MIN_PDF (2.2250738585072014e-308)"
    /// );
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(lambda: [f64; 4], pdf: [f64; 4]) -> Result<SampledWavelengths, Error> {
        for &l in &lambda {
            crate::error::positive("lambda_nm", l)?;
        }
        for &p in &pdf {
            if !(p.is_finite() && p >= 0.0) {
                return Err(Error::invalid("pdf", p, Requirement::NonNegative));
            }
            if p > 0.0 && p < Self::MIN_PDF {
                let requirement = Requirement::AtLeast {
                    bound_name: "SampledWavelengths::MIN_PDF",
                    bound: Self::MIN_PDF,
                };
                return Err(Error::invalid("pdf", p, requirement));
            }
        }
        Ok(SampledWavelengths { lambda, pdf })
    }

    /// The four wavelengths, nm (index 0 is the hero).
    ///
    /// ```
    /// # use diffraction::{Band, SampledWavelengths};
    /// assert_eq!(SampledWavelengths::sample_uniform(0.0, Band::VISIBLE).lambda()[0], 360.0);
    /// ```
    #[must_use]
    pub fn lambda(&self) -> [f64; 4] {
        self.lambda
    }

    /// The hero wavelength, nm.
    ///
    /// ```
    /// # use diffraction::{Band, SampledWavelengths};
    /// assert_eq!(SampledWavelengths::sample_uniform(0.25, Band::new(400.0, 800.0)?).hero(), 500.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn hero(&self) -> f64 {
        self.lambda[0]
    }

    /// The densities, 1/nm (0 for terminated secondaries).
    ///
    /// ```
    /// # use diffraction::{Band, SampledWavelengths};
    /// assert_eq!(SampledWavelengths::sample_uniform(0.0, Band::new(400.0, 800.0)?).pdf()[1], 1.0 / 400.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn pdf(&self) -> [f64; 4] {
        self.pdf
    }

    /// Keeps the hero only (pbrt-v4's `TerminateSecondary`): the secondaries' densities become
    /// 0 and the hero's is divided by 4, since it now stands for all four strata. Idempotent.
    ///
    /// ```
    /// # use diffraction::{Band, SampledWavelengths};
    /// let mut l = SampledWavelengths::sample_uniform(0.1, Band::new(400.0, 800.0)?);
    /// l.terminate_secondary();
    /// l.terminate_secondary();
    /// assert_eq!(l.pdf(), [1.0 / 1600.0, 0.0, 0.0, 0.0]);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn terminate_secondary(&mut self) {
        if self.secondary_terminated() {
            return;
        }
        for i in 1..4 {
            self.pdf[i] = 0.0;
        }
        self.pdf[0] *= 0.25;
    }

    /// Whether the secondaries were terminated.
    ///
    /// ```
    /// # use diffraction::{Band, SampledWavelengths};
    /// assert!(!SampledWavelengths::sample_uniform(0.1, Band::VISIBLE).secondary_terminated());
    /// ```
    #[must_use]
    pub fn secondary_terminated(&self) -> bool {
        self.pdf[1..].iter().all(|&p| p == 0.0)
    }
}
