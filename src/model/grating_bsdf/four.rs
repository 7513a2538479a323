//! The grating's four-wavelength sample ([`Bsdf::sample4`](crate::Bsdf::sample4)): the hero's
//! direction, value and density from one [`sample`](crate::Bsdf::sample), and the three
//! secondaries' values and densities at that direction with the checks and (u, v) shared (and a
//! table's location of wo and wi).

use glam::{DVec2, DVec3};

use super::order_weights::OrderSource;
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
            if let OrderSource::Tabulated { .. } = self.orders {
                self.secondaries_tabulated(wo, wi, lambdas, &mut f, &mut pdf);
            } else {
                let l = lambdas.lambda();
                for k in 1..4 {
                    if l[k] > 0.0 && l[k].is_finite() {
                        f[k] = self.value(wo, wi, l[k]);
                        pdf[k] = self.pdf_finite(wo, wi, l[k]);
                    }
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

impl GratingBsdf {
    /// `eval4` of a tabulated model (after the checks): the pair (wo, wi) located once in the
    /// table, each λ read as `eval` reads it, so equal to four `eval` calls to the bit. Not
    /// inlined, like the other tabulated paths.
    #[inline(never)]
    pub(super) fn eval4_tabulated(
        &self,
        wo: DVec3,
        wi: DVec3,
        lambdas: &SampledWavelengths,
    ) -> [f64; 4] {
        #[cfg(feature = "relief")]
        if let Some(pair) = self.orders.incidences(wo, wi) {
            return lambdas.lambda().map(|l| {
                if l > 0.0 && l.is_finite() {
                    self.value_at(&pair, wo, wi, l)
                } else {
                    0.0
                }
            });
        }
        lambdas.lambda().map(|l| {
            if l > 0.0 && l.is_finite() {
                self.value(wo, wi, l)
            } else {
                0.0
            }
        })
    }

    /// `pdf4` of a tabulated model (after the checks): wo located once, each λ's density as
    /// `pdf`'s.
    #[inline(never)]
    pub(super) fn pdf4_tabulated(
        &self,
        wo: DVec3,
        wi: DVec3,
        lambdas: &SampledWavelengths,
    ) -> [f64; 4] {
        #[cfg(feature = "relief")]
        let pair = self.orders.incidences(wo, wi);
        lambdas.lambda().map(|l| {
            if !(l > 0.0 && l.is_finite()) {
                return 0.0;
            }
            #[cfg(feature = "relief")]
            if let Some(pair) = &pair {
                return self.pdf_at(pair, wo, wi, l);
            }
            self.pdf_finite(wo, wi, l)
        })
    }

    /// The secondaries of `sample4` for a tabulated model: the pair (wo, wi) located once for
    /// the three, each value and density as `eval`'s and `pdf`'s.
    #[inline(never)]
    fn secondaries_tabulated(
        &self,
        wo: DVec3,
        wi: DVec3,
        lambdas: &SampledWavelengths,
        f: &mut [f64; 4],
        pdf: &mut [f64; 4],
    ) {
        let l = lambdas.lambda();
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
}
