//! Visible-wavelength importance sampling (pbrt-v4's `SampleVisibleWavelengths`): wavelengths
//! drawn with a density close to the luminance response, so that the four wavelengths of a
//! path land where the eye sees them.
//!
//! The density over the crate's band B = [360, 830] nm ([`Band::VISIBLE`](crate::Band::VISIBLE))
//! is
//!
//! ```text
//! p(λ) = b / ((t₁ − t₀) · cosh²(b·(λ − c))),   b = 0.0072 /nm,  c = 538 nm,
//! t₀ = tanh(b·(360 − c)),  t₁ = tanh(b·(830 − c)),
//! ```
//!
//! pbrt-v4's shape (fitted by Radziszewski et al. to the CIE ȳ under D65) with the exact
//! normalisation over B (pbrt rounds it to 0.0039398042; here it is computed from the tanh
//! values). Its CDF is P(λ) = (tanh(b·(λ − c)) − t₀)/(t₁ − t₀) and the sampler is its exact
//! inverse, λ = c + atanh(t₀ + u·(t₁ − t₀))/b: no rejection, no table.
//!
//! ```
//! use diffraction::visible;
//! let l = visible::sample(0.5);
//! assert!((visible::cdf(l) - 0.5).abs() < 1e-15); // the exact inverse
//! assert!(visible::pdf(550.0) > 2.0 * visible::pdf(400.0)); // green likelier than violet
//! assert_eq!(visible::pdf(900.0), 0.0); // outside the band
//! ```

use crate::data::cie::{TABLE_FIRST_NM, TABLE_LAST_NM};
use crate::num::math;
use crate::num::random::unit_random;

/// The centre c of the density, nm (pbrt-v4's 538 nm).
///
/// ```
/// use diffraction::visible::{pdf, CENTER_NM};
/// assert!(pdf(CENTER_NM) > pdf(CENTER_NM - 1.0) && pdf(CENTER_NM) > pdf(CENTER_NM + 1.0));
/// ```
pub const CENTER_NM: f64 = 538.0;

/// The sharpness b of the density, 1/nm (pbrt-v4's 0.0072): the density falls to half its peak
/// at |λ − c| = acosh(√2)/b ≈ 122 nm.
///
/// ```
/// use diffraction::visible::{pdf, CENTER_NM, SHARPNESS_PER_NM};
/// let half = (2f64.sqrt()).acosh() / SHARPNESS_PER_NM;
/// assert!((pdf(CENTER_NM + half) / pdf(CENTER_NM) - 0.5).abs() < 1e-12);
/// ```
pub const SHARPNESS_PER_NM: f64 = 0.0072;

/// tanh(b·(λ − c)) at the band's ends: (t₀, t₁).
#[inline]
fn ends() -> (f64, f64) {
    (
        math::tanh(SHARPNESS_PER_NM * (TABLE_FIRST_NM - CENTER_NM)),
        math::tanh(SHARPNESS_PER_NM * (TABLE_LAST_NM - CENTER_NM)),
    )
}

/// The density p(λ), 1/nm, of [`sample`]: 0 outside 360-830 nm and for NaN; it integrates to
/// exactly 1 over the band (see the [module docs](self)).
///
/// ```
/// use diffraction::visible::pdf;
/// // The trapezoid rule on 0.01 nm steps: 1 to its error.
/// let h = 0.01;
/// let sum: f64 = (0..=47_000)
///     .map(|i| if i == 0 || i == 47_000 { 0.5 } else { 1.0 } * pdf(360.0 + i as f64 * h))
///     .sum();
/// assert!((sum * h - 1.0).abs() < 1e-9);
/// ```
#[must_use]
pub fn pdf(lambda_nm: f64) -> f64 {
    if !(TABLE_FIRST_NM..=TABLE_LAST_NM).contains(&lambda_nm) {
        return 0.0;
    }
    let (t0, t1) = ends();
    let c = math::cosh(SHARPNESS_PER_NM * (lambda_nm - CENTER_NM));
    SHARPNESS_PER_NM / ((t1 - t0) * c * c)
}

/// The CDF P(λ) of [`pdf`]: 0 below 360 nm, 1 above 830 nm (and 0 for NaN).
///
/// ```
/// use diffraction::visible::cdf;
/// assert_eq!(cdf(360.0), 0.0);
/// assert_eq!(cdf(830.0), 1.0);
/// assert!(cdf(538.0) > 0.4 && cdf(538.0) < 0.5); // the density is skewed toward the blue end
/// ```
#[must_use]
pub fn cdf(lambda_nm: f64) -> f64 {
    if lambda_nm.is_nan() || lambda_nm <= TABLE_FIRST_NM {
        return 0.0;
    }
    if lambda_nm >= TABLE_LAST_NM {
        return 1.0;
    }
    let (t0, t1) = ends();
    let t = math::tanh(SHARPNESS_PER_NM * (lambda_nm - CENTER_NM));
    ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
}

/// The wavelength with CDF `uc` (the exact inverse of [`cdf`]), nm, in [360, 830]; `uc` by the
/// crate's rule for random numbers ([`unit_random`](crate::unit_random())).
///
/// ```
/// use diffraction::visible::{cdf, sample};
/// assert_eq!(sample(0.0), 360.0);
/// for uc in [0.1, 0.37, 0.9] {
///     assert!((cdf(sample(uc)) - uc).abs() < 1e-15);
/// }
/// assert_eq!(sample(f64::NAN), 360.0); // non-finite input counts as 0
/// ```
#[must_use]
pub fn sample(uc: f64) -> f64 {
    let u = unit_random(uc);
    let (t0, t1) = ends();
    let l = CENTER_NM + math::atanh(t0 + u * (t1 - t0)) / SHARPNESS_PER_NM;
    l.clamp(TABLE_FIRST_NM, TABLE_LAST_NM)
}
