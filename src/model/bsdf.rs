//! The radiometric, samplable BSDF interface for path tracers, shaped like pbrt-v4's `BxDF`.
//!
//! A model's value is [`DiffractionBrdf::eval`]`(wo, wi, λ)`, the one value interface of the
//! crate; [`Bsdf`] **extends** it with what a Monte-Carlo integrator needs: importance sampling
//! with an exact density, densities at four wavelengths, flags and regularisation. The colour
//! integrator's needs are a separate capability ([`SpectralResponse`](crate::SpectralResponse)).
//!
//! # Conventions (pbrt-v4's)
//!
//! * Directions are unit vectors in the local frame: `z` the normal, `x` the grating vector,
//!   `y` along the grooves. **`wo` points toward the viewer** (the camera side of the path) and
//!   comes first, **`wi` toward the light**; both above the surface (cos θ ≥
//!   [`MIN_COS_THETA`](crate::MIN_COS_THETA)) for a reflection, otherwise `eval` and `pdf` are 0.
//! * [`eval`](DiffractionBrdf::eval) is the BRDF in 1/sr, **cosine excluded**: reflected
//!   radiance is `∫ eval(wo, wi, λ)·L(wi, λ)·cos θi dωi` (pbrt's `f`).
//! * [`sample`](Bsdf::sample) returns wi with the value f and the density `pdf` in **solid
//!   angle** (1/sr) of the procedure that produced it. The Monte-Carlo weight is
//!   `f·cos θi / pdf`. A sample flagged [`BsdfFlags::SPECULAR`] comes from a lobe that is a
//!   Dirac delta in at least one dimension: then `f` and `pdf` both omit the same delta factor
//!   and only the weight `f·cos θi / pdf` is meaningful (for a pure delta lobe `pdf` is the
//!   discrete probability of choosing it), exactly as pbrt's specular BxDFs do; `eval` and
//!   `pdf` of the traits return 0 for such lobes.
//!
//! # Why the paper's model is not a `Bsdf`
//!
//! [`AguHill`](crate::AguHill) is the paper's unitless intensity S·F_N with every maximum at 1:
//! the area of each order falls as 1/N, so the light it reflects depends on N and the paper
//! needs an exposure per material; it includes no cos θi and has no unit. Reading it as 1/sr
//! would make a grating almost black for large N and brighter than a mirror for small N. It is
//! kept exactly as it is (for the paper's pictures) and is not a `Bsdf`. The energy-normalised
//! reading of the same optics is [`GratingBsdf`](crate::GratingBsdf).
//!
//! # Mapping to pbrt-v4 and Mitsuba 3
//!
//! pbrt-v4's `BxDF` has the same argument order and the same cosine convention:
//! `f(wo, wi)` is [`eval`](DiffractionBrdf::eval), `Sample_f(wo, uc, u)` is
//! [`sample`](Bsdf::sample), `PDF(wo, wi)` is [`pdf`](Bsdf::pdf), `Flags()` is
//! [`flags`](Bsdf::flags), `Regularize()` is [`regularize`](Bsdf::regularize).
//! [`sample4`](Bsdf::sample4) has no pbrt counterpart: it returns the values and densities of a
//! path's four wavelengths for the hero's direction, what hero-wavelength MIS
//! ([`HeroMis`](crate::HeroMis)) needs, in one call.
//! Mitsuba's `BSDF` calls the direction toward the camera `si.wi` and the sampled one `wo`,
//! and includes the cosine in its values:
//!
//! | Mitsuba 3 | this crate |
//! |---|---|
//! | `si.wi` | `wo` |
//! | `wo` (argument / sampled) | `wi` |
//! | `eval(ctx, si, wo)` | `eval(wo, wi, λ) · wi.z` |
//! | `pdf(ctx, si, wo)` | `pdf(wo, wi, λ)` |
//! | `sample(ctx, si, sample1, sample2)` → (bs, weight) | `sample(wo, λ, uc, u2)` → bs, weight = `f·wi.z/pdf` |
//! | `eval_pdf(ctx, si, wo)` | `eval4` and `pdf4` (the four-wavelength calls share their work); `sample4` for a sample and both |
//! | `BSDFSample3f.sampled_type` | `flags` |
//!
//! ```
//! use diffraction::{Bsdf, DiffractionBrdf, Grating, GratingBsdf};
//! use glam::{DVec2, DVec3};
//! let bsdf = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
//! let wo = DVec3::new(0.2, 0.1, (1.0f64 - 0.05).sqrt());
//! let s = bsdf.sample(wo, 550.0, 0.3, DVec2::new(0.4, 0.6)).unwrap();
//! // The sample's value and density are those of `eval` and `pdf` at its direction.
//! assert!((s.f - bsdf.eval(wo, s.wi, 550.0)).abs() <= 1e-9 * s.f);
//! assert!((s.pdf - bsdf.pdf(wo, s.wi, 550.0)).abs() <= 1e-9 * s.pdf);
//! # Ok::<(), diffraction::Error>(())
//! ```

use core::ops::BitOr;

use glam::{DVec2, DVec3};

use crate::num::math;
use crate::path::sampled_spectrum::SampledSpectrum;
use crate::path::wavelengths::SampledWavelengths;
use crate::DiffractionBrdf;

/// What kind of scattering a lobe or a sample is (pbrt-v4's `BxDFFlags`, reflection only).
///
/// ```
/// use diffraction::BsdfFlags;
/// let glossy = BsdfFlags::REFLECTION | BsdfFlags::GLOSSY;
/// assert!(glossy.contains(BsdfFlags::GLOSSY) && !glossy.is_specular());
/// assert!((BsdfFlags::REFLECTION | BsdfFlags::SPECULAR).is_specular());
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct BsdfFlags(u8);

impl BsdfFlags {
    /// No scattering.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(!BsdfFlags::NONE.contains(BsdfFlags::REFLECTION));
    /// ```
    pub const NONE: BsdfFlags = BsdfFlags(0);
    /// Light leaves on the side it arrived.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(BsdfFlags::REFLECTION.is_reflective());
    /// ```
    pub const REFLECTION: BsdfFlags = BsdfFlags(1);
    /// A lobe spread over the whole hemisphere.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(!BsdfFlags::DIFFUSE.is_specular());
    /// ```
    pub const DIFFUSE: BsdfFlags = BsdfFlags(2);
    /// A lobe with a density (however narrow): `f` and `pdf` are finite functions.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(BsdfFlags::GLOSSY.contains(BsdfFlags::GLOSSY));
    /// ```
    pub const GLOSSY: BsdfFlags = BsdfFlags(4);
    /// A lobe that is a Dirac delta in at least one dimension: `f` and `pdf` return 0 for it,
    /// and only `sample` reaches it (see the [module docs](self)).
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(BsdfFlags::SPECULAR.is_specular());
    /// ```
    pub const SPECULAR: BsdfFlags = BsdfFlags(8);

    /// Whether every flag of `other` is set in `self`.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// let f = BsdfFlags::REFLECTION | BsdfFlags::GLOSSY;
    /// assert!(f.contains(BsdfFlags::REFLECTION | BsdfFlags::GLOSSY));
    /// assert!(!f.contains(BsdfFlags::SPECULAR));
    /// ```
    #[must_use]
    pub fn contains(self, other: BsdfFlags) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether [`SPECULAR`](Self::SPECULAR) is set.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(!(BsdfFlags::REFLECTION | BsdfFlags::GLOSSY).is_specular());
    /// ```
    #[must_use]
    pub fn is_specular(self) -> bool {
        self.contains(BsdfFlags::SPECULAR)
    }

    /// Whether [`REFLECTION`](Self::REFLECTION) is set.
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert!(!BsdfFlags::NONE.is_reflective());
    /// ```
    #[must_use]
    pub fn is_reflective(self) -> bool {
        self.contains(BsdfFlags::REFLECTION)
    }

    /// The raw bits (REFLECTION 1, DIFFUSE 2, GLOSSY 4, SPECULAR 8).
    ///
    /// ```
    /// # use diffraction::BsdfFlags;
    /// assert_eq!((BsdfFlags::REFLECTION | BsdfFlags::SPECULAR).bits(), 9);
    /// ```
    #[must_use]
    pub fn bits(self) -> u8 {
        self.0
    }
}

impl BitOr for BsdfFlags {
    type Output = BsdfFlags;
    fn bitor(self, rhs: BsdfFlags) -> BsdfFlags {
        BsdfFlags(self.0 | rhs.0)
    }
}

/// One sampled direction (pbrt-v4's `BSDFSample`).
///
/// ```
/// use diffraction::{BsdfFlags, BsdfSample};
/// use glam::DVec3;
/// let s = BsdfSample::new(DVec3::Z, 0.5, 2.0, BsdfFlags::REFLECTION | BsdfFlags::GLOSSY);
/// assert_eq!(s.weight(), 0.25); // f·cos θi/pdf
/// assert_eq!(s.order, None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct BsdfSample {
    /// The sampled direction toward the light, unit, local frame, z > 0.
    pub wi: DVec3,
    /// The BSDF value f(wo, wi, λ), 1/sr, cosine excluded (for a SPECULAR sample: without the
    /// delta factor, see the [module docs](self)).
    pub f: f64,
    /// The density of the sampling procedure at `wi`, in solid angle, > 0 (for a SPECULAR
    /// sample: without the delta factor; a discrete probability for a pure delta lobe).
    pub pdf: f64,
    /// What was sampled.
    pub flags: BsdfFlags,
    /// The diffraction order whose lobe (period) was sampled, for models that have orders.
    pub order: Option<i32>,
}

impl BsdfSample {
    /// A sample without an order.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample};
    /// use glam::DVec3;
    /// let s = BsdfSample::new(DVec3::Z, 1.0, 1.0, BsdfFlags::REFLECTION | BsdfFlags::DIFFUSE);
    /// assert_eq!((s.f, s.pdf), (1.0, 1.0));
    /// ```
    #[must_use]
    pub fn new(wi: DVec3, f: f64, pdf: f64, flags: BsdfFlags) -> BsdfSample {
        BsdfSample {
            wi,
            f,
            pdf,
            flags,
            order: None,
        }
    }

    /// The same sample tagged with its diffraction order.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample};
    /// use glam::DVec3;
    /// let s = BsdfSample::new(DVec3::Z, 1.0, 1.0, BsdfFlags::GLOSSY).with_order(-2);
    /// assert_eq!(s.order, Some(-2));
    /// ```
    #[must_use]
    pub fn with_order(self, order: i32) -> BsdfSample {
        BsdfSample {
            order: Some(order),
            ..self
        }
    }

    /// The Monte-Carlo weight f·cos θi/pdf (0 when pdf is 0), saturating at ±`f64::MAX` (a
    /// caller's subnormal pdf such as 5·10⁻³²⁴ would make it infinite).
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample};
    /// use glam::DVec3;
    /// let wi = DVec3::new(0.6, 0.0, 0.8);
    /// assert!((BsdfSample::new(wi, 1.0, 0.4, BsdfFlags::GLOSSY).weight() - 2.0).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn weight(&self) -> f64 {
        if self.pdf > 0.0 {
            (self.f * self.wi.z / self.pdf).clamp(-f64::MAX, f64::MAX)
        } else {
            0.0
        }
    }
}

/// One direction sampled at a path's hero wavelength, with the BSDF's values and densities at
/// all four wavelengths ([`Bsdf::sample4`]).
///
/// Index 0 is the hero's sample: `f[0]` and `pdf[0]` are [`BsdfSample::f`] and
/// [`BsdfSample::pdf`], the density the direction was drawn with. For j ≥ 1, `f[j]` is
/// `eval(wo, wi, λ_j)` and `pdf[j]` is `pdf(wo, wi, λ_j)`: the density with which the sampler
/// would have produced `wi` had λ_j been the hero (the densities of hero-wavelength MIS,
/// [`HeroMis`](crate::HeroMis)). For a SPECULAR sample the secondaries' values and densities
/// are 0 (a delta lobe has no density, and the direction belongs to the hero): terminate the
/// secondaries ([`HeroMis::bsdf_sample`](crate::HeroMis::bsdf_sample) does).
///
/// ```
/// use diffraction::{BsdfFlags, BsdfSample4, SampledSpectrum};
/// use glam::DVec3;
/// let wi = DVec3::new(0.6, 0.0, 0.8);
/// let f = SampledSpectrum::new([1.0, 0.5, 0.0, 2.0]);
/// let pdf = SampledSpectrum::new([0.4, 0.2, 0.0, 0.1]);
/// let s = BsdfSample4::new(wi, f, pdf, BsdfFlags::REFLECTION | BsdfFlags::GLOSSY);
/// // f_j·cos θi over the hero's density, at every wavelength:
/// let w = s.weight().values();
/// assert!((w[0] - 2.0).abs() < 1e-15 && (w[3] - 4.0).abs() < 1e-15);
/// assert_eq!(s.hero().pdf, 0.4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct BsdfSample4 {
    /// The sampled direction toward the light, unit, local frame, z > 0.
    pub wi: DVec3,
    /// f(wo, wi, λ_j), 1/sr, cosine excluded (index 0: the hero's sample value).
    pub f: SampledSpectrum,
    /// The sampler's density at `wi` with λ_j as the hero, in solid angle (index 0: the density
    /// the direction was drawn with, > 0).
    pub pdf: SampledSpectrum,
    /// What was sampled (at the hero wavelength).
    pub flags: BsdfFlags,
    /// The diffraction order whose lobe was sampled, for models that have orders.
    pub order: Option<i32>,
}

impl BsdfSample4 {
    /// A sample without an order.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample4, SampledSpectrum};
    /// use glam::DVec3;
    /// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::ONE, SampledSpectrum::ONE, BsdfFlags::DIFFUSE);
    /// assert_eq!(s.order, None);
    /// ```
    #[must_use]
    pub fn new(
        wi: DVec3,
        f: SampledSpectrum,
        pdf: SampledSpectrum,
        flags: BsdfFlags,
    ) -> BsdfSample4 {
        BsdfSample4 {
            wi,
            f,
            pdf,
            flags,
            order: None,
        }
    }

    /// The same sample tagged with its diffraction order.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample4, SampledSpectrum};
    /// use glam::DVec3;
    /// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::ONE, SampledSpectrum::ONE, BsdfFlags::GLOSSY);
    /// assert_eq!(s.with_order(3).order, Some(3));
    /// ```
    #[must_use]
    pub fn with_order(self, order: i32) -> BsdfSample4 {
        BsdfSample4 {
            order: Some(order),
            ..self
        }
    }

    /// The throughput factor of each wavelength, f_j·cos θi/pdf\[0\] (the direction was drawn
    /// with the hero's density); 0 everywhere when that density is not positive; each value
    /// saturates at ±`f64::MAX` (a subnormal density would make it infinite). A path tracer
    /// multiplies its throughput by it and applies the MIS weight of
    /// [`HeroMis`](crate::HeroMis) where the path meets light.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample4, SampledSpectrum};
    /// use glam::DVec3;
    /// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::splat(2.0), SampledSpectrum::ZERO, BsdfFlags::GLOSSY);
    /// assert!(s.weight().is_zero());
    /// ```
    #[must_use]
    pub fn weight(&self) -> SampledSpectrum {
        let p = self.pdf[0];
        if p > 0.0 {
            let k = (self.wi.z / p).clamp(-f64::MAX, f64::MAX);
            let v = self.f.values();
            SampledSpectrum::new(core::array::from_fn(|j| {
                (v[j] * k).clamp(-f64::MAX, f64::MAX)
            }))
        } else {
            SampledSpectrum::ZERO
        }
    }

    /// The hero wavelength's sample alone.
    ///
    /// ```
    /// use diffraction::{BsdfFlags, BsdfSample4, SampledSpectrum};
    /// use glam::DVec3;
    /// let s = BsdfSample4::new(DVec3::Z, SampledSpectrum::splat(2.0), SampledSpectrum::ONE, BsdfFlags::GLOSSY);
    /// assert_eq!((s.hero().f, s.hero().pdf, s.hero().wi), (2.0, 1.0, DVec3::Z));
    /// ```
    #[must_use]
    pub fn hero(&self) -> BsdfSample {
        BsdfSample {
            wi: self.wi,
            f: self.f[0],
            pdf: self.pdf[0],
            flags: self.flags,
            order: self.order,
        }
    }

    /// The four-wavelength sample of `hero`, sampled at λ₀ of `lambdas`, with the secondaries
    /// from `eval4` and `pdf4` (0 for a SPECULAR sample): what [`Bsdf::sample4`] returns by
    /// default.
    ///
    /// ```
    /// use diffraction::{Band, Bsdf, BsdfSample4, Grating, GratingBsdf, SampledWavelengths};
    /// use glam::{DVec2, DVec3};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 30)?);
    /// let l = SampledWavelengths::sample_uniform(0.4, Band::VISIBLE);
    /// let wo = DVec3::new(0.3, 0.1, 0.9f64.sqrt());
    /// let s = b.sample(wo, l.hero(), 0.3, DVec2::new(0.6, 0.2)).unwrap();
    /// let four = BsdfSample4::from_hero(&b, wo, &l, s);
    /// assert_eq!(four.pdf[2], b.pdf(wo, s.wi, l.lambda()[2]));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn from_hero<B: Bsdf + ?Sized>(
        bsdf: &B,
        wo: DVec3,
        lambdas: &SampledWavelengths,
        hero: BsdfSample,
    ) -> BsdfSample4 {
        let (mut f, mut pdf) = if hero.flags.is_specular() {
            ([0.0; 4], [0.0; 4])
        } else {
            (
                bsdf.eval4(wo, hero.wi, lambdas),
                bsdf.pdf4(wo, hero.wi, lambdas),
            )
        };
        f[0] = hero.f;
        pdf[0] = hero.pdf;
        BsdfSample4 {
            wi: hero.wi,
            f: SampledSpectrum::new(f),
            pdf: SampledSpectrum::new(pdf),
            flags: hero.flags,
            order: hero.order,
        }
    }
}

/// A radiometric, samplable BSDF (pbrt-v4's `BxDF`): the value
/// [`eval`](DiffractionBrdf::eval) in 1/sr (cosine excluded) with an importance sampler of exact
/// density. See the [module docs](self) for conventions, the pbrt and Mitsuba mappings and why
/// [`AguHill`](crate::AguHill) does not implement it.
///
/// Every method returns finite, non-negative values for finite input, and 0 / `None` for
/// directions below the surface or a non-positive wavelength.
///
/// ```
/// use diffraction::{Bsdf, BsdfFlags, DiffractionBrdf, Grating, GratingBsdf};
/// use glam::DVec3;
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 30)?);
/// assert_eq!(b.flags(), BsdfFlags::REFLECTION | BsdfFlags::GLOSSY);
/// let (wo, wi) = (DVec3::new(0.3, 0.0, 0.91f64.sqrt()), DVec3::Z);
/// assert_eq!(b.eval(wo, wi, 480.0), b.eval(wi, wo, 480.0)); // reciprocal
/// # Ok::<(), diffraction::Error>(())
/// ```
pub trait Bsdf: DiffractionBrdf {
    /// Samples wi for `wo` at wavelength `lambda_nm` from the uniform numbers `uc` (lobe
    /// choice) and `u2` (position), each in [0, 1) (other values by the crate's rule,
    /// [`unit_random`](crate::unit_random)). `None` when the procedure produced no direction
    /// above the surface (its pdf then integrates to the probability of `Some`).
    ///
    /// ```
    /// use diffraction::{Bsdf, Grating, GratingBsdf};
    /// use glam::{DVec2, DVec3};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert!(b.sample(-DVec3::Z, 550.0, 0.5, DVec2::splat(0.5)).is_none()); // wo below
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn sample(&self, wo: DVec3, lambda_nm: f64, uc: f64, u2: DVec2) -> Option<BsdfSample>;

    /// The density in solid angle with which `sample(wo, λ, ..)` produces `wi` (0 for delta
    /// lobes).
    ///
    /// ```
    /// use diffraction::{Bsdf, Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert!(b.pdf(DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()), 480.0) > 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64;

    /// `pdf` at the four wavelengths of `lambdas` (the densities for hero-wavelength MIS);
    /// the default calls `pdf` four times.
    ///
    /// ```
    /// use diffraction::{Band, Bsdf, Grating, GratingBsdf, SampledWavelengths};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// let l = SampledWavelengths::sample_uniform(0.3, Band::VISIBLE);
    /// let (wo, wi) = (DVec3::new(0.3, 0.0, 0.91f64.sqrt()), DVec3::Z);
    /// assert_eq!(b.pdf4(wo, wi, &l)[2], b.pdf(wo, wi, l.lambda()[2]));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn pdf4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        lambdas.lambda().map(|l| self.pdf(wo, wi, l))
    }

    /// Samples wi at the hero wavelength of `lambdas` (as [`sample`](Self::sample) with
    /// λ₀, `uc`, `u2`) and returns the BSDF's values and densities at all four wavelengths for
    /// that direction ([`BsdfSample4`]): one call per bounce for a hero-wavelength path
    /// tracer. The default is [`BsdfSample4::from_hero`] (`sample`, then `eval4` and `pdf4`);
    /// models override it to share the work (the grating's costs about one `sample` + `eval4`).
    ///
    /// ```
    /// use diffraction::{Band, Bsdf, DiffractionBrdf, Grating, GratingBsdf, SampledWavelengths};
    /// use glam::{DVec2, DVec3};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 30)?);
    /// let l = SampledWavelengths::sample_uniform(0.4, Band::VISIBLE);
    /// let wo = DVec3::new(0.3, 0.1, 0.9f64.sqrt());
    /// let s = b.sample4(wo, &l, 0.3, DVec2::new(0.6, 0.2)).unwrap();
    /// let hero = b.sample(wo, l.hero(), 0.3, DVec2::new(0.6, 0.2)).unwrap();
    /// assert_eq!((s.wi, s.pdf[0]), (hero.wi, hero.pdf));
    /// assert_eq!(s.f.values(), b.eval4(wo, s.wi, &l));
    /// assert_eq!(s.pdf.values(), b.pdf4(wo, s.wi, &l));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn sample4(
        &self,
        wo: DVec3,
        lambdas: &SampledWavelengths,
        uc: f64,
        u2: DVec2,
    ) -> Option<BsdfSample4> {
        let hero = self.sample(wo, lambdas.hero(), uc, u2)?;
        Some(BsdfSample4::from_hero(self, wo, lambdas, hero))
    }

    /// The kinds of lobe the model has.
    ///
    /// ```
    /// use diffraction::{Bsdf, Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// assert!(b.flags().is_specular()); // N = ∞: delta orders
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn flags(&self) -> BsdfFlags;

    /// Widens near-delta lobes (pbrt-v4's `Regularize`), for the paths where a narrow lobe
    /// only adds noise (after a diffuse bounce, say). What "near-delta" means and how much the
    /// lobes widen is model-specific and documented by each implementation; models without
    /// such lobes leave themselves unchanged.
    ///
    /// ```
    /// use diffraction::{Bsdf, Grating, GratingBsdf, Slits};
    /// let mut b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// b.regularize();
    /// assert!(!b.flags().is_specular());
    /// assert!(matches!(b.grating().slits(), Slits::Finite(_)));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn regularize(&mut self);
}

/// The default sampler of models without their own: a cosine-weighted direction on the upper
/// hemisphere (Malley's method: a uniform point on the unit disk, concentric map, lifted).
/// Its density is [`cosine_hemisphere_pdf`]`(wi.z)` = cos θ/π. `u2` is clamped into [0, 1]
/// (a non-finite component taken as ½).
///
/// ```
/// use diffraction::bsdf::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
/// use glam::DVec2;
/// let w = sample_cosine_hemisphere(DVec2::new(0.5, 0.5));
/// assert_eq!(w, glam::DVec3::Z); // the disk's centre lifts to the normal
/// assert!((cosine_hemisphere_pdf(w.z) - 1.0 / std::f64::consts::PI).abs() < 1e-16);
/// ```
#[must_use]
pub fn sample_cosine_hemisphere(u2: DVec2) -> DVec3 {
    use core::f64::consts::FRAC_PI_4;
    let clamp = |x: f64| {
        if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            0.5
        }
    };
    let (a, b) = (2.0 * clamp(u2.x) - 1.0, 2.0 * clamp(u2.y) - 1.0);
    if a == 0.0 && b == 0.0 {
        return DVec3::Z;
    }
    let (r, phi) = if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, core::f64::consts::FRAC_PI_2 - FRAC_PI_4 * (a / b))
    };
    let (x, y) = (r * math::cos(phi), r * math::sin(phi));
    let z = math::sqrt((1.0 - x * x - y * y).max(0.0));
    DVec3::new(x, y, z)
}

/// The density cos θ/π of [`sample_cosine_hemisphere`] (0 for cos θ ≤ 0 or NaN).
///
/// ```
/// use diffraction::bsdf::cosine_hemisphere_pdf;
/// assert_eq!(cosine_hemisphere_pdf(-0.5), 0.0);
/// assert!((cosine_hemisphere_pdf(1.0) - std::f64::consts::FRAC_1_PI).abs() < 1e-17);
/// ```
#[must_use]
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    if cos_theta > 0.0 {
        cos_theta * core::f64::consts::FRAC_1_PI
    } else {
        0.0
    }
}
