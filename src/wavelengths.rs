//! The wavelengths a spectral path carries: a hero wavelength and three companions with their
//! sampling densities (pbrt-v4's `SampledWavelengths`).

use crate::error::{Error, Requirement};
use crate::random::unit_random;
use crate::Band;

/// Four wavelengths carried by one path, with the densities they were sampled with
/// (pbrt-v4's `SampledWavelengths`). Index 0 is the **hero** wavelength: the one
/// [`Bsdf::sample`](crate::Bsdf::sample) follows.
///
/// Two ways to use the four with a dispersive BSDF (the sampled direction depends on λ):
///
/// * **Hero-wavelength MIS** (Wilkie et al., "Hero Wavelength Spectral Sampling", EGSR 2014):
///   the direction was sampled for the hero; weight wavelength j's contribution by the balance
///   heuristic over the four, `p_j / Σ_k p_k` with `p_k = pdf4(wo, wi)[k]` (and the
///   wavelength densities), see [`balance_heuristic`](Self::balance_heuristic). Unbiased, and
///   where the lobes of the four overlap (small N) all four contribute.
/// * **Terminate the secondaries** (pbrt-v4's `TerminateSecondary`): keep the hero only and
///   divide by its density alone ([`terminate_secondary`](Self::terminate_secondary)).
///
/// For gratings the crate recommends **hero MIS with [`Bsdf::pdf4`](crate::Bsdf::pdf4)** for glossy samples: the
/// lobes of order m sit at u = m·λ/d, so for large N the secondaries' pdfs at the hero's
/// direction are tiny and the balance heuristic gives them weight ≈ 0 by itself (it degrades
/// gracefully into termination, with no bias and no branch), while for small N, where the
/// lobes overlap, it keeps their contribution. For **SPECULAR** samples (N = ∞ or an ideal
/// groove) the secondaries' densities are exactly 0 and `pdf4` cannot express the delta: there
/// terminate the secondaries, as pbrt does for dispersive specular surfaces.
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
    /// Stratified uniform wavelengths: the hero at `band.min + u·B`, the others B/4 apart
    /// (wrapping around the band), each with density 1/B. `u` by the crate's rule for random
    /// numbers ([`unit_random`](crate::unit_random)). Every wavelength is in the band and every
    /// density finite and at most 10⁶ per nm ([`Band::MIN_WIDTH_NM`]), so the result is one that
    /// [`new`](Self::new) accepts.
    ///
    /// ```
    /// use diffraction::{Band, SampledWavelengths};
    /// let l = SampledWavelengths::sample_uniform(0.5, Band::new(400.0, 800.0)?);
    /// assert_eq!(l.lambda(), [600.0, 700.0, 400.0, 500.0]);
    /// assert_eq!(l.hero(), 600.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn sample_uniform(u: f64, band: Band) -> SampledWavelengths {
        let u = unit_random(u);
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
            pdf: [1.0 / b; 4],
        }
    }

    /// Four wavelengths (finite, > 0) with their densities (finite, ≥ 0), for example from a
    /// grating's own wavelength sampler. Errors name `lambda_nm` or `pdf`.
    ///
    /// ```
    /// use diffraction::SampledWavelengths;
    /// let l = SampledWavelengths::new([500.0, 510.0, 520.0, 530.0], [0.01; 4])?;
    /// assert_eq!(l.lambda()[3], 530.0);
    /// assert_eq!(SampledWavelengths::new([0.0; 4], [0.01; 4]).unwrap_err().parameter(), "lambda_nm");
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

    /// The balance-heuristic weight of wavelength `index` for a direction whose sampling
    /// densities under the four wavelengths are `pdf4`: `pdf4[index] / Σ pdf4` (0 when the sum
    /// is 0 or `index` > 3). Multiply wavelength j's contribution f_j·cos/pdf4\[j\] by it, or
    /// equivalently use f_j·cos/Σ pdf4 for every j (Wilkie et al. 2014).
    ///
    /// Always in [0, 1]: a density that is not a number ≥ 0 (negative, NaN) counts as 0, and
    /// the sum is taken relative to the largest density, so huge finite densities (whose sum
    /// would overflow) and infinite ones (each infinite density gets an equal share) still give
    /// weights that add up to 1.
    ///
    /// ```
    /// use diffraction::SampledWavelengths;
    /// let w = SampledWavelengths::balance_heuristic([3.0, 1.0, 0.0, 0.0], 0);
    /// assert_eq!(w, 0.75);
    /// assert_eq!(SampledWavelengths::balance_heuristic([0.0; 4], 0), 0.0);
    /// assert_eq!(SampledWavelengths::balance_heuristic([f64::MAX; 4], 2), 0.25);
    /// assert_eq!(SampledWavelengths::balance_heuristic([f64::NAN, 1.0, -1.0, 0.0], 1), 1.0);
    /// ```
    #[must_use]
    pub fn balance_heuristic(pdf4: [f64; 4], index: usize) -> f64 {
        if index > 3 {
            return 0.0;
        }
        // NaN and negative densities count as 0; ∞ as the largest value, shared equally.
        let p = pdf4.map(|p| if p > 0.0 { p } else { 0.0 });
        let top = p.iter().fold(0.0f64, |a, &b| a.max(b));
        if top == 0.0 {
            return 0.0;
        }
        let rel = if top.is_finite() {
            p.map(|x| x / top)
        } else {
            p.map(|x| if x == top { 1.0 } else { 0.0 })
        };
        // Each term ≤ 1, so the sum is in [1, 4]: no overflow, no 0/0.
        let sum: f64 = rel.iter().sum();
        rel[index] / sum
    }
}
