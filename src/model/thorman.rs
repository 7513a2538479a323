//! Thorman's model (1996) as Agu & Hill describe it: the directions of the peaks from the grating
//! equation, every order equally bright, nothing between the peaks.

use glam::DVec3;

use crate::error::{positive, Error, Requirement};
use crate::model::{both_above, DiffractionBrdf, PeakSummary, SpectralResponse};
use crate::num::math;
use crate::{Band, Grating, GratingEquation, Peak, MAX_ORDERS};

/// Lobes are summed out to this many widths σ from their centre: exp(−8.5²/2) = 2·10⁻¹⁶.
const CUTOFF: f64 = 8.5;
/// √(2π).
const SQRT_TAU: f64 = 2.5066282746310002;
/// At most this many lobes are summed directly (more only when they overlap, see `eval`).
const MAX_TERMS: f64 = 64.0;

/// Thorman's grating model: peak directions only, every order equally bright.
///
/// Agu & Hill describe Thorman (1996) as using only the grating equation d·u = m·λ: the model
/// knows where the peaks are but nothing of the light between them, and takes every peak to be
/// equally bright. Taken literally that is a sum of delta functions, which a renderer cannot
/// show; this implementation gives every order m (order 0, the mirror direction, included) the
/// same Gaussian lobe in the phase projection u = (wi + wo)·t = `wi.x + wo.x`:
///
/// ```text
/// eval(wo, wi, λ) = brightness · Σ_m g((u − m·λ/d) / σ),   g(t) = exp(−t²/2),
/// ```
///
/// with σ = [`lobe_width`](Self::lobe_width), in units of u. Each lobe peaks at `brightness`
/// (g(0) = 1), the convention of the paper's own model whose peaks are S(β_m) ≤ 1; it is not an
/// energy normalisation. The choices, as documented assumptions:
///
/// * **order 0 is included** with the same brightness: it is a peak of the grating equation
///   (u = 0, the mirror direction, white), and Thorman knows nothing that would make it different;
/// * **the lobe width is constant in u**, the same for every order and wavelength. Seen at fixed
///   directions as a function of λ, the lobe of order m ≠ 0 is an exact Gaussian around
///   λ_m = d·u/m with standard deviation σ·d/|m| and **equivalent width** (area over peak)
///   √(2π)·σ·d/|m|, which is what [`peaks`](SpectralResponse::peaks) reports;
/// * the value depends on u only, like the paper's model: nothing confines the light to the
///   plane of the diffracted cone (compare `Stam`, feature `stam`).
///
/// [`Thorman::matching`] picks σ so that the equivalent widths equal those of an Agu-Hill
/// grating of N slits at one wavelength: the N-slit lobe has equivalent width λ/(N·d) in u, so
/// σ = λ/(√(2π)·N·d).
///
/// Reciprocal (u is symmetric in wi and wo). Like the paper's [`AguHill`](crate::AguHill) the
/// value is a unitless diffraction term that the light multiplies with no cosine (its
/// [`response`](SpectralResponse::response) is its value), not a BRDF in 1/sr: Thorman's model
/// has no radiometric normalisation, so it is not a [`Bsdf`](crate::Bsdf).
///
/// ```
/// use diffraction::{Band, DiffractionBrdf, SpectralResponse, Thorman};
/// use glam::DVec3;
/// let t = Thorman::new(1600.0, 0.01)?;
/// let wi = DVec3::Z;
/// let wo = DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt()); // u = 0.3: order 1 at 480 nm
/// assert!((t.eval(wo, wi, 480.0) - 1.0).abs() < 1e-12);
/// // One lobe width away from the peak in u: exp(−½).
/// let off = 480.0 + 0.01 * 1600.0; // λ = (u + σ)·d
/// assert!((t.eval(wo, wi, off) - (-0.5f64).exp()).abs() < 1e-12);
/// let mut widths = vec![];
/// t.peaks(wo, wi, Band::VISIBLE, &mut |p| widths.push(p.equivalent_width_nm));
/// assert!((widths[0] - (2.0 * std::f64::consts::PI).sqrt() * 0.01 * 1600.0).abs() < 1e-9);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thorman {
    /// The grating equation of the period.
    equation: GratingEquation,
    lobe_width: f64,
    brightness: f64,
}

impl Thorman {
    /// The model for period d = `period_nm` and lobe width σ = `lobe_width` (in u), with
    /// brightness 1. Rejects d ≤ 0, σ ≤ 0, σ > 1 (u spans [−2, 2]) and non-finite values.
    ///
    /// ```
    /// use diffraction::Thorman;
    /// let t = Thorman::new(1600.0, 0.005)?;
    /// assert_eq!((t.period_nm(), t.lobe_width(), t.brightness()), (1600.0, 0.005, 1.0));
    /// assert_eq!(Thorman::new(0.0, 0.005).unwrap_err().parameter(), "period_nm");
    /// assert_eq!(Thorman::new(1600.0, 0.0).unwrap_err().parameter(), "lobe_width");
    /// assert_eq!(Thorman::new(1600.0, f64::NAN).unwrap_err().parameter(), "lobe_width");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(period_nm: f64, lobe_width: f64) -> Result<Thorman, Error> {
        let d = positive("period_nm", period_nm)?;
        let equation = GratingEquation::new(d)?;
        let sigma = positive("lobe_width", lobe_width)?;
        if sigma > 1.0 {
            return Err(Error::invalid(
                "lobe_width",
                sigma,
                Requirement::AtMost {
                    bound_name: "1",
                    bound: 1.0,
                },
            ));
        }
        Ok(Thorman {
            equation,
            lobe_width: sigma,
            brightness: 1.0,
        })
    }

    /// The model with the period of `grating` and the lobe width that gives its peaks the
    /// equivalent widths of the grating's N-slit peaks at `lambda_nm`: σ = λ/(√(2π)·N·d).
    ///
    /// Fails for N = ∞ (σ would be 0; reported as `slits`), for a non-positive `lambda_nm`,
    /// and where σ would exceed 1 or underflow (reported as `lambda_nm`, with the range
    /// that gives 0 < σ ≤ 1 for this grating).
    ///
    /// ```
    /// use diffraction::{Grating, Thorman};
    /// let ideal = Grating::infinite(1600.0, 800.0)?;
    /// let err = Thorman::matching(&ideal, 550.0).unwrap_err();
    /// assert_eq!(err.to_string(), "invalid slits = inf: must be finite");
    /// let one = Grating::new(100.0, 50.0, 1)?; // σ = λ/(√(2π)·100 nm) > 1 for λ > 250.7 nm
    /// assert_eq!(Thorman::matching(&one, 550.0).unwrap_err().parameter(), "lambda_nm");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    ///
    /// ```
    /// use diffraction::{Band, Grating, SpectralResponse, Thorman};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// let t = Thorman::matching(&g, 550.0)?;
    /// // Order 1 at 550 nm: the same equivalent width as the N-slit peak, λ/(|m|·N).
    /// let u = 550.0 / 1600.0;
    /// let (wo, wi) = (DVec3::new(u, 0.0, (1.0 - u * u).sqrt()), DVec3::Z);
    /// t.peaks(wo, wi, Band::VISIBLE, &mut |p| {
    ///     assert!((p.equivalent_width_nm - 550.0 / 100.0).abs() < 1e-9);
    /// });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn matching(grating: &Grating, lambda_nm: f64) -> Result<Thorman, Error> {
        let lambda = positive("lambda_nm", lambda_nm)?;
        let n = grating.slits().as_f64();
        if !n.is_finite() {
            return Err(Error::invalid("slits", n, Requirement::Finite));
        }
        // σ = λ/(√(2π)·N·d) must be a normal number in (0, 1]: λ in [√(2π)·N·d·MIN_POSITIVE,
        // √(2π)·N·d].
        let scale = SQRT_TAU * n * grating.period_nm();
        let sigma = lambda / scale;
        if !(f64::MIN_POSITIVE..=1.0).contains(&sigma) {
            return Err(Error::invalid(
                "lambda_nm",
                lambda,
                Requirement::Within {
                    min: scale * f64::MIN_POSITIVE,
                    max: scale,
                },
            ));
        }
        Thorman::new(grating.period_nm(), sigma)
    }

    /// Sets the brightness of every peak (finite, ≥ 0).
    ///
    /// ```
    /// use diffraction::{DiffractionBrdf, Thorman};
    /// use glam::DVec3;
    /// let t = Thorman::new(1600.0, 0.01)?.with_brightness(0.25)?;
    /// assert_eq!(t.eval(DVec3::Z, DVec3::Z, 550.0), 0.25); // u = 0: order 0
    /// assert_eq!(Thorman::new(1600.0, 0.01)?.with_brightness(-1.0).unwrap_err().parameter(), "brightness");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_brightness(self, brightness: f64) -> Result<Thorman, Error> {
        if brightness.is_finite() && brightness >= 0.0 {
            Ok(Thorman { brightness, ..self })
        } else {
            Err(Error::invalid(
                "brightness",
                brightness,
                Requirement::NonNegative,
            ))
        }
    }

    /// The period d, nm.
    ///
    /// ```
    /// # use diffraction::Thorman;
    /// assert_eq!(Thorman::new(740.0, 0.01)?.period_nm(), 740.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.equation.period_nm()
    }

    /// The lobe width σ, in units of u.
    ///
    /// ```
    /// # use diffraction::Thorman;
    /// assert_eq!(Thorman::new(740.0, 0.01)?.lobe_width(), 0.01);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn lobe_width(&self) -> f64 {
        self.lobe_width
    }

    /// The peak value of every lobe.
    ///
    /// ```
    /// # use diffraction::Thorman;
    /// assert_eq!(Thorman::new(740.0, 0.01)?.brightness(), 1.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn brightness(&self) -> f64 {
        self.brightness
    }

    /// Σ_m g((u − m·step)/σ) over every integer m.
    fn lobes(&self, u: f64, step: f64) -> f64 {
        let sigma = self.lobe_width;
        if step < 0.5 * sigma {
            // The lobes overlap: by Poisson summation the sum is σ√(2π)/step times
            // 1 + 2·Σ_k exp(−2π²k²σ²/step²)·cos(2πku/step), and exp(−8π²) < 10⁻³⁴.
            return SQRT_TAU * sigma / step;
        }
        let lo = math::ceil((u - CUTOFF * sigma) / step);
        let hi = math::floor((u + CUTOFF * sigma) / step);
        if lo > hi {
            return 0.0;
        }
        // At most 2·8.5·σ/step + 1 ≤ 35 terms here; the cap guards rounding at huge |u|.
        let count = (hi - lo + 1.0).min(MAX_TERMS) as u32;
        let mut sum = 0.0;
        for j in 0..count {
            let t = (u - (lo + j as f64) * step) / sigma;
            sum += math::exp(-0.5 * t * t);
        }
        sum
    }
}

impl DiffractionBrdf for Thorman {
    /// `brightness · Σ_m exp(−½((u − m·λ/d)/σ)²)`, u = `wi.x + wo.x`; 0 below the surface,
    /// for λ ≤ 0 and for non-finite input. Where the lobes overlap so densely that the sum
    /// exceeds `f64::MAX` (λ/d below about 10⁻³⁰⁸·σ) it saturates there.
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(both_above(wo, wi) && lambda_nm > 0.0) {
            return 0.0;
        }
        let u = wi.x + wo.x;
        let step = lambda_nm / self.equation.period_nm();
        if !(u.is_finite() && step.is_finite() && step > 0.0) {
            return 0.0;
        }
        let v = self.brightness * self.lobes(u, step);
        if v.is_nan() {
            // brightness 0 times an overflowing sum: no light.
            0.0
        } else {
            v.min(f64::MAX)
        }
    }
}

impl SpectralResponse for Thorman {
    /// The paper's convention, as for [`AguHill`](crate::AguHill): the value itself, no cosine.
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eval(wo, wi, lambda_nm)
    }

    /// Every order m ≠ 0 with λ_m = d·|u|/|m| in `band`, each with intensity `brightness` (its
    /// own lobe's peak; `eval` there also holds the far tails of the other lobes) and equivalent
    /// width √(2π)·σ·d/|m| (saturating at `f64::MAX` where it overflows, for periods near
    /// `f64::MAX`), at most [`MAX_ORDERS`] of them (the lowest |m|).
    /// Order 0's lobe is seen where |u| < 8.5·σ.
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !both_above(wo, wi) {
            return PeakSummary::default();
        }
        let u = wi.x + wo.x;
        // σ·√(2π) ≤ 2.51 and d/|m| ≤ d: the product overflows only for d near f64::MAX.
        let scale = SQRT_TAU * self.lobe_width;
        let d = self.equation.period_nm();
        let mut orders = 0;
        for p in self.equation.orders(u, band).take(MAX_ORDERS as usize) {
            visit(Peak {
                order: p.order,
                wavelength_nm: p.wavelength_nm,
                intensity: self.brightness,
                equivalent_width_nm: (scale * (d / (p.order as f64).abs())).min(f64::MAX),
            });
            orders += 1;
        }
        PeakSummary {
            orders,
            specular: u.abs() < CUTOFF * self.lobe_width,
        }
    }
}
