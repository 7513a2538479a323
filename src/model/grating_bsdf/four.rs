//! The grating's four-wavelength sample ([`Bsdf::sample4`](crate::Bsdf::sample4)): the hero's
//! direction, value and density from one [`sample`](crate::Bsdf::sample), and the three
//! secondaries' values and densities at that direction with the checks and (u, v) shared (and a
//! table's location of wo and wi).

use glam::{DVec2, DVec3};

use super::GratingBsdf;
use crate::model::bsdf::{Bsdf, BsdfSample4};
use crate::path::sampled_spectrum::SampledSpectrum;
use crate::path::wavelengths::SampledWavelengths;

impl GratingBsdf {
    /// [`Bsdf::sample4`] for the grating: `sample` at the hero, then for each secondary λ_j the
    /// lobe's value and the density at the sampled direction, by the same operations as `eval`
    /// and `pdf` (so the result equals `sample` + `eval4` + `pdf4` to the bit), without their
    /// hemisphere checks (the sample is above the surface) and without the hero's lane. A
    /// SPECULAR sample has secondaries 0.
    pub(super) fn sample_four(
        &self,
        wo: DVec3,
        lambdas: &SampledWavelengths,
        uc: f64,
        u2: DVec2,
    ) -> Option<BsdfSample4> {
        let hero = self.sample(wo, lambdas.hero(), uc, u2)?;
        let mut f = [hero.f, 0.0, 0.0, 0.0];
        let mut pdf = [hero.pdf, 0.0, 0.0, 0.0];
        if !hero.flags.is_specular() {
            let wi = hero.wi;
            let l = lambdas.lambda();
            // A table: the pair (wo, wi) located once for the three.
            #[cfg(feature = "relief")]
            let pair = self.orders.incidences(wo, wi);
            for k in 1..4 {
                if l[k] > 0.0 && l[k].is_finite() {
                    #[cfg(feature = "relief")]
                    if let Some(pair) = &pair {
                        f[k] = self.value_at(pair, wo, wi, l[k]);
                        pdf[k] = self.pdf_at(pair, wo, wi, l[k]);
                        continue;
                    }
                    f[k] = self.value(wo, wi, l[k]);
                    pdf[k] = self.pdf_finite(wo, wi, l[k]);
                }
            }
        }
        let s = BsdfSample4::new(
            hero.wi,
            SampledSpectrum::new(f),
            SampledSpectrum::new(pdf),
            hero.flags,
        );
        Some(match hero.order {
            Some(m) => s.with_order(m),
            None => s,
        })
    }
}
