//! [`Bsdf`] for the related-work baselines, [`Thorman`] and `Stam` (feature `stam`).
//!
//! Neither model has a sampler of its own here: both use the crate's documented default, a
//! **cosine-weighted hemisphere** ([`sample_cosine_hemisphere`], density cos θi/π), which is
//! exact and positive wherever f is, so every generic test (furnace, reciprocity, χ²,
//! finite values) runs on them as on [`GratingBsdf`](crate::GratingBsdf); its weight
//! f·cos θi/pdf = π·f is bounded by π·max f. It finds narrow lobes only by chance: for
//! those, a renderer should prefer light sampling (MIS does this automatically).
//!
//! * **Thorman**: its value (brightness · Σ Gaussian lobes in u) is read as a BRDF in 1/sr
//!   with the cosine applied by the integrator, `f(wo, wi, λ) = eval(wi, wo, λ)`: reciprocal,
//!   but with no radiometric normalisation (the model has none: every peak is as bright as the
//!   brightness says), so its albedo is not bounded by 1 in general. Its `DiffractionBrdf`
//!   reports `cosine_included() == true` (the paper's convention for the colour interface);
//!   as a `Bsdf` the renderer multiplies `f` by cos θi.
//! * **Stam**: already a BRDF (cosine excluded), `f(wo, wi, λ) = eval(wi, wo, λ)`;
//!   reciprocal; not energy conserving (its geometry factor exceeds 1 off the mirror
//!   direction, see its docs).
//!
//! Both answer for wavelengths in [`BASELINE_WAVELENGTHS_NM`] only. Both are GLOSSY and [`regularize`](Bsdf::regularize) leaves them unchanged (their lobe
//! widths are parameters of the published models).
//!
//! ```
//! use diffraction::{Bsdf, DiffractionBrdf, Thorman};
//! use glam::{DVec2, DVec3};
//! let t = Thorman::new(1600.0, 0.02)?;
//! let wo = DVec3::new(0.3, 0.0, 0.91f64.sqrt());
//! let s = t.sample(wo, 480.0, 0.0, DVec2::new(0.3, 0.8)).unwrap();
//! assert!((s.pdf - s.wi.z / std::f64::consts::PI).abs() < 1e-15);
//! assert_eq!(s.f, t.eval(s.wi, wo, 480.0));
//! # Ok::<(), diffraction::Error>(())
//! ```

use glam::{DVec2, DVec3};

use crate::bxdf::bsdf::{
    cosine_hemisphere_pdf, sample_cosine_hemisphere, Bsdf, BsdfFlags, BsdfSample,
};
use crate::bxdf::grating_bsdf::MIN_COS_THETA;
use crate::DiffractionBrdf;
use crate::Thorman;

/// As a `Bsdf` the baselines answer for wavelengths in [1 nm, 1 mm] only (outside optics, and
/// where Thorman's overlapping lobes would make f/pdf overflow); elsewhere f = pdf = 0.
pub const BASELINE_WAVELENGTHS_NM: (f64, f64) = (1.0, 1e6);

fn in_range(lambda_nm: f64) -> bool {
    (BASELINE_WAVELENGTHS_NM.0..=BASELINE_WAVELENGTHS_NM.1).contains(&lambda_nm)
}

/// The default sampler's sample for a model whose value is `f`.
fn cosine_sample(
    wo: DVec3,
    lambda_nm: f64,
    u2: DVec2,
    f: impl Fn(DVec3) -> f64,
) -> Option<BsdfSample> {
    if !(wo.z > 0.0 && wo.is_finite() && in_range(lambda_nm) && u2.is_finite()) {
        return None;
    }
    let wi = sample_cosine_hemisphere(u2);
    let pdf = cosine_hemisphere_pdf(wi.z);
    if !(wi.z >= MIN_COS_THETA && pdf > 0.0) {
        return None;
    }
    Some(BsdfSample::new(
        wi,
        f(wi),
        pdf,
        BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
    ))
}

/// The default density: cos θi/π for both directions above the surface (cos θi at least
/// [`MIN_COS_THETA`], so that f/pdf stays finite).
fn cosine_pdf(wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
    if wo.z > 0.0
        && wi.z >= MIN_COS_THETA
        && wo.is_finite()
        && wi.is_finite()
        && in_range(lambda_nm)
    {
        cosine_hemisphere_pdf(wi.z)
    } else {
        0.0
    }
}

/// `Bsdf` for a model whose `eval` is read as f in 1/sr, sampled by the cosine-weighted default.
macro_rules! cosine_sampled_bsdf {
    ($model:ty, $f_doc:literal) => {
        impl Bsdf for $model {
            #[doc = $f_doc]
            fn f(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
                if in_range(lambda_nm) {
                    self.eval(wi, wo, lambda_nm)
                } else {
                    0.0
                }
            }

            /// Cosine-weighted hemisphere.
            fn sample(&self, wo: DVec3, lambda_nm: f64, _uc: f64, u2: DVec2) -> Option<BsdfSample> {
                cosine_sample(wo, lambda_nm, u2, |wi| self.eval(wi, wo, lambda_nm))
            }

            /// cos θi/π.
            fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
                cosine_pdf(wo, wi, lambda_nm)
            }

            /// REFLECTION | GLOSSY.
            fn flags(&self) -> BsdfFlags {
                BsdfFlags::REFLECTION | BsdfFlags::GLOSSY
            }

            /// No change: the lobe widths are the published model's parameters.
            fn regularize(&mut self) {}
        }
    };
}

cosine_sampled_bsdf!(
    Thorman,
    "`eval(wi, wo, λ)`, read as 1/sr (see the [module docs](crate::baselines))."
);
#[cfg(feature = "stam")]
cosine_sampled_bsdf!(
    crate::Stam,
    "`eval(wi, wo, λ)`: Stam's BRDF, cosine excluded."
);
