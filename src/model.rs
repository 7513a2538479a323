//! The interface every diffraction model of the crate implements, and the models: the paper's
//! Agu-Hill grating ([`AguHill`]), the energy-normalised grating for path tracers
//! ([`GratingBsdf`]) and, with the feature `baselines`, the related work the paper argues
//! against (`Thorman`, `Stam`).
//!
//! Three traits, each a capability of its own:
//!
//! * [`DiffractionBrdf`]: the model's value at one wavelength, `eval(wo, wi, λ)`. Every model
//!   has it, with pbrt's argument order (`wo` toward the viewer first).
//! * [`Bsdf`]: what a Monte-Carlo integrator needs besides the value (sampling with an exact
//!   density, flags, regularisation); radiometric models only.
//! * [`SpectralResponse`]: what the colour integrator ([`spectrum`](crate::spectrum)) needs (the
//!   light reflected per unit light, the peaks in wavelength, and whether the model is a
//!   multiple of a grating's intensity); a model opts into it.
//!
//! One file per model; add a model by adding a file here that implements [`DiffractionBrdf`]
//! (and [`Bsdf`] if it is radiometric and samplable, [`SpectralResponse`] if it should have a
//! colour).

use glam::{DVec3, Vec3};

use crate::path::wavelengths::SampledWavelengths;

mod agu_hill;
pub mod bsdf;
pub mod grating_bsdf;
mod hero_mis;
#[cfg(feature = "baselines")]
pub(crate) mod profile;
mod response;
#[cfg(feature = "baselines")]
pub mod stam;
#[cfg(feature = "baselines")]
mod thorman;

pub use agu_hill::AguHill;
pub use bsdf::{Bsdf, BsdfFlags, BsdfSample, BsdfSample4};
pub use grating_bsdf::{GratingBsdf, WavelengthSample};
pub use hero_mis::HeroMis;
#[cfg(feature = "baselines")]
pub use profile::Profile;
pub use response::{Envelope, GratingResponse, PeakSummary, SpectralResponse};
#[cfg(feature = "baselines")]
pub use stam::Stam;
#[cfg(feature = "baselines")]
pub use thorman::Thorman;

/// Directions with cos θ below this count as below the horizon for every model of the crate:
/// their value, density and colour are 0 and no sampler returns them. It keeps f/pdf finite
/// (densities in solid angle carry a factor cos θ) at the cost of a solid angle of 2π·10⁻¹⁰⁰.
///
/// ```
/// use diffraction::{AguHill, DiffractionBrdf, Grating, MIN_COS_THETA};
/// use glam::DVec3;
/// let m = AguHill::new(Grating::new(1600.0, 800.0, 100)?);
/// let grazing = DVec3::new((1.0f64 - 1e-202).sqrt(), 0.0, 1e-101); // below MIN_COS_THETA
/// assert_eq!(m.eval(DVec3::Z, grazing, 550.0), 0.0);
/// assert!(MIN_COS_THETA > 0.0);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub const MIN_COS_THETA: f64 = 1e-100;

/// A spectral diffraction model in the local shading frame: its value at one wavelength.
///
/// Shaped like the BxDF interfaces of pbrt-v4 and Mitsuba 3: directions are unit vectors in the
/// local frame where `z` is the normal and `x` the grating vector t (`y` runs along the
/// grooves); **`wo` points toward the viewer and comes first, `wi` toward the light**, pbrt's
/// `f(wo, wi)`. Both must be above the surface (cos θ ≥ [`MIN_COS_THETA`]) and finite; otherwise
/// the value is 0. Every model of the crate depends on wo and wi through wi + wo, so it is
/// reciprocal: `eval(wo, wi, λ) == eval(wi, wo, λ)`.
///
/// What the value *is* belongs to the model, one meaning each:
///
/// * radiometric models ([`GratingBsdf`], `Thorman`, `Stam`): the BRDF in 1/sr, **cosine
///   excluded** (pbrt's convention): reflected radiance is ∫ eval·L·cos θi dωi;
/// * the paper's [`AguHill`]: its unitless intensity S(β)·F_N(α) (peak 1), which the paper
///   multiplies by the light with no cosine (its eq. 12).
///
/// The light a model reflects per unit light, the quantity a colour is made of, is
/// [`SpectralResponse::response`]: `eval·cos θi` for the radiometric models, `eval` for
/// `AguHill`.
///
/// ```
/// use diffraction::{AguHill, DiffractionBrdf, Grating};
/// use glam::DVec3;
/// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
/// let wo = DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt()); // toward the viewer
/// let wi = DVec3::Z; // toward the light
/// // u = wi.x + wo.x = 0.3: the first order at 480 nm, far brighter than 500 nm.
/// assert!(brdf.eval(wo, wi, 480.0) > 100.0 * brdf.eval(wo, wi, 500.0));
/// assert_eq!(brdf.eval(wo, wi, 480.0), brdf.eval(wi, wo, 480.0)); // reciprocal
/// # Ok::<(), diffraction::Error>(())
/// ```
pub trait DiffractionBrdf {
    /// The value at wavelength `lambda_nm` (nm) for the local directions `wo` (toward the
    /// viewer) and `wi` (toward the light). Finite and ≥ 0 for every input; 0 below the surface
    /// and for non-finite input.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wo, wi) = (DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.6, 0.0, 0.8));
    /// assert_eq!(brdf.eval(wo, wi, 550.0), 1.0); // the mirror direction: S(0)·F_N(0) = 1
    /// assert_eq!(brdf.eval(wo, -wi, 550.0), 0.0); // light below the surface
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64;

    /// [`eval`](Self::eval) for `f32` callers. Implementations may override it with a faster
    /// path; the default widens to `f64` and rounds back, saturating at `f32::MAX`.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::Vec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wo, wi) = (Vec3::new(0.3, 0.0, 0.91f32.sqrt()), Vec3::Z); // order 1 at 480 nm
    /// let wide = brdf.eval(wo.as_dvec3(), wi.as_dvec3(), 480.0);
    /// assert_eq!(brdf.eval_f32(wo, wi, 480.0), wide as f32); // the f64 value, rounded once
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn eval_f32(&self, wo: Vec3, wi: Vec3, lambda_nm: f32) -> f32 {
        // A finite f64 value beyond f32's range saturates instead of rounding to ∞.
        (self.eval(wo.as_dvec3(), wi.as_dvec3(), lambda_nm as f64) as f32).min(f32::MAX)
    }

    /// [`eval`](Self::eval) at the four wavelengths of `lambdas` (a path's hero wavelength and
    /// its three companions). Models override it to share the work that does not depend on λ;
    /// the default calls `eval` four times.
    ///
    /// ```
    /// use diffraction::{Band, DiffractionBrdf, Grating, GratingBsdf, SampledWavelengths};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// let l = SampledWavelengths::sample_uniform(0.3, Band::VISIBLE);
    /// let (wo, wi) = (DVec3::new(0.3, 0.0, 0.91f64.sqrt()), DVec3::Z);
    /// let four = b.eval4(wo, wi, &l);
    /// for i in 0..4 {
    ///     assert_eq!(four[i], b.eval(wo, wi, l.lambda()[i]));
    /// }
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn eval4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        lambdas.lambda().map(|l| self.eval(wo, wi, l))
    }
}

/// Whether both directions are finite and above the surface (cos θ ≥ [`MIN_COS_THETA`]): the
/// one hemisphere test every model of the crate applies before it reflects light (false for
/// NaN).
#[inline]
pub(crate) fn both_above(wo: DVec3, wi: DVec3) -> bool {
    wo.z >= MIN_COS_THETA && wi.z >= MIN_COS_THETA && wo.is_finite() && wi.is_finite()
}
