//! The grating's wavelength sampler: a wavelength for a fixed pair of directions, drawn from the
//! grating's own spectral response (its peaks at λ_m = d·|u|/|m|), with its exact density.

use glam::DVec3;

use super::lobe::{lorentz_q, lorentz_r};
use super::GratingBsdf;
use crate::model::both_above;
use crate::num::math;
use crate::num::random::unit_random;
use crate::{Band, Peak, Slits};

/// The uniform share of [`GratingBsdf::sample_wavelength`].
#[doc(hidden)]
pub const DEFENSIVE_WAVELENGTH_SHARE: f64 = 0.1;
/// [`GratingBsdf::sample_wavelength`] follows at most this many peaks (in order of |m|); the
/// uniform share covers the rest.
pub(crate) const MAX_WAVELENGTH_PEAKS: usize = 64;

/// One sampled wavelength (see [`GratingBsdf::sample_wavelength`]).
///
/// ```
/// use diffraction::{Band, Grating, GratingBsdf};
/// use glam::DVec3;
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
/// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
/// let s = b.sample_wavelength(wo, wi, Band::VISIBLE, 0.5).unwrap();
/// assert!((s.lambda_nm - 480.0).abs() < 1.0); // near the first-order peak
/// assert!((s.pdf - b.wavelength_pdf(wo, wi, Band::VISIBLE, s.lambda_nm)).abs() < 1e-9 * s.pdf);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WavelengthSample {
    /// The wavelength, nm, inside the band.
    pub lambda_nm: f64,
    /// Its density, 1/nm.
    pub pdf: f64,
}

impl GratingBsdf {
    /// Samples a wavelength in `band` for the fixed pair (wo, wi) from the grating's own
    /// spectral response, from one uniform `xi` in [0, 1) (other values by the crate's rule,
    /// [`unit_random`](crate::unit_random)).
    ///
    /// At fixed directions f is a sum of peaks at λ_m = d·|u|/|m| of width about λ_m/(|m|·N).
    /// The sampler is a mixture: with probability [`DEFENSIVE_WAVELENGTH_SHARE`] uniform over
    /// the band; otherwise peak m (the first `MAX_WAVELENGTH_PEAKS` orders m ≠ 0 with λ_m in
    /// the band, [`Grating::peaks`](crate::Grating::peaks)) with probability ∝ its area η_m·(d/|m|)·g(v; λ_m), or
    /// order 0 (when its period, λ > 2·d·|u|, reaches the band) with probability ∝ f at the
    /// middle of that range times its length. Inside peak m the phase x = d·|u|/λ is drawn
    /// from the Lorentzian proxy of its period (x = |m| + r as in `sample`) and λ = d·|u|/x, so
    /// the density is q(r)·d·|u|/λ²; inside order 0's range λ is uniform. Samples outside the
    /// band are rejected (`None`); [`wavelength_pdf`](Self::wavelength_pdf) is the exact
    /// density and integrates to the probability of `Some`. For N = ∞ (delta peaks, no
    /// spectral density) only the uniform part is used.
    ///
    /// ```
    /// use diffraction::{Band, Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1_000_000)?);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// let s = b.sample_wavelength(wo, wi, Band::VISIBLE, 0.7).unwrap();
    /// assert!((s.lambda_nm - 480.0).abs() < 0.01); // inside the peak, 5·10⁻⁴ nm wide
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn sample_wavelength(
        &self,
        wo: DVec3,
        wi: DVec3,
        band: Band,
        xi: f64,
    ) -> Option<WavelengthSample> {
        let xi = unit_random(xi);
        let mix = self.wavelength_mixture(wo, wi, band);
        let b = band.width_nm();
        let lambda = if mix.total <= 0.0 || xi < DEFENSIVE_WAVELENGTH_SHARE {
            let t = if mix.total <= 0.0 {
                xi
            } else {
                xi / DEFENSIVE_WAVELENGTH_SHARE
            };
            (band.min_nm() + t * b).min(band.max_nm())
        } else {
            let target =
                (xi - DEFENSIVE_WAVELENGTH_SHARE) / (1.0 - DEFENSIVE_WAVELENGTH_SHARE) * mix.total;
            let mut acc = mix.zero_weight;
            if target < acc {
                let t = target / mix.zero_weight;
                mix.zero_lo + t * (band.max_nm() - mix.zero_lo)
            } else {
                let n = mix.n;
                let mut chosen = None;
                let mut last = None;
                for p in self.grating.peaks(mix.u, band).take(MAX_WAVELENGTH_PEAKS) {
                    let w = self.peak_weight(&p, &mix);
                    if w > 0.0 {
                        last = Some((p, w, acc));
                        if target < acc + w {
                            chosen = Some((p, w, acc));
                            break;
                        }
                        acc += w;
                    }
                }
                let (p, w, start) = chosen.or(last)?;
                let t = ((target - start) / w).clamp(0.0, 1.0);
                let r = lorentz_r(n, self.atan_n, t);
                let x = (p.order.unsigned_abs() as f64) + r;
                mix.q / x
            }
        };
        if !band.contains(lambda) {
            return None;
        }
        let pdf = self.wavelength_pdf_mix(&mix, band, lambda);
        (pdf > 0.0 && pdf.is_finite()).then_some(WavelengthSample {
            lambda_nm: lambda,
            pdf,
        })
    }

    /// The density (1/nm) with which [`sample_wavelength`](Self::sample_wavelength) returns
    /// `lambda_nm` for (wo, wi); 0 outside the band.
    ///
    /// ```
    /// use diffraction::{Band, Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// // Far from every peak only the uniform share remains (and order 1's far tail).
    /// let p = b.wavelength_pdf(wo, wi, Band::VISIBLE, 700.0);
    /// assert!(p >= 0.1 / 470.0 && p < 0.11 / 470.0);
    /// assert_eq!(b.wavelength_pdf(wo, wi, Band::VISIBLE, 900.0), 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn wavelength_pdf(&self, wo: DVec3, wi: DVec3, band: Band, lambda_nm: f64) -> f64 {
        if !band.contains(lambda_nm) {
            return 0.0;
        }
        let mix = self.wavelength_mixture(wo, wi, band);
        self.wavelength_pdf_mix(&mix, band, lambda_nm)
    }

    /// The area-based weight of one peak in the wavelength mixture: η_m·(d/|m|)·g(v; λ_m), with
    /// a tabulated model's η̃_m at the peak's λ.
    fn peak_weight(&self, p: &Peak, mix: &WavelengthMixture) -> f64 {
        let l = p.wavelength_nm;
        let g = if self.groove.is_delta() {
            1.0
        } else {
            self.groove.value(mix.v, l)
        };
        let eta = self.efficiency_at(p.order, mix.wo, mix.wi, l);
        let w = eta * (self.grating.period_nm() / p.order.abs() as f64) * g;
        if w.is_finite() {
            w
        } else {
            0.0
        }
    }

    fn wavelength_mixture(&self, wo: DVec3, wi: DVec3, band: Band) -> WavelengthMixture {
        let mut mix = WavelengthMixture {
            u: 0.0,
            v: 0.0,
            q: 0.0,
            n: 1.0,
            total: 0.0,
            zero_weight: 0.0,
            zero_lo: band.max_nm(),
            wo,
            wi,
        };
        let Slits::Finite(n) = self.grating.slits() else {
            return mix;
        };
        if !both_above(wo, wi) {
            return mix;
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        mix.u = u;
        mix.v = v;
        mix.n = n as f64;
        mix.q = self.grating.period_nm() * u.abs();
        let mut total = 0.0;
        // Order 0's period: x = q/λ < ½, λ > 2q.
        let zero_lo = (2.0 * mix.q).max(band.min_nm());
        if zero_lo < band.max_nm() {
            let mid = 0.5 * (zero_lo + band.max_nm());
            let g = if self.groove.is_delta() {
                1.0
            } else {
                self.groove.value(v, mid)
            };
            let rho = self.grating.open_fraction();
            let f = if self.efficiency.is_tabulated() {
                // η̃_0(λ)·(N·d/λ)·F_N·g at the middle of the range.
                self.efficiency_at(0, wo, wi, mid)
                    * (mix.n * self.grating.period_nm() / mid)
                    * self.grating.n_slit(u, mid)
                    * g
            } else {
                rho * rho
                    * (mix.n * self.grating.period_nm() / mid)
                    * self.grating.intensity_f64(u, mid)
                    * g
            };
            let w = f * (band.max_nm() - zero_lo);
            if w.is_finite() && w > 0.0 {
                mix.zero_weight = w;
                mix.zero_lo = zero_lo;
                total += w;
            }
        }
        for p in self.grating.peaks(u, band).take(MAX_WAVELENGTH_PEAKS) {
            total += self.peak_weight(&p, &mix);
        }
        mix.total = if total.is_finite() { total } else { 0.0 };
        mix
    }

    fn wavelength_pdf_mix(&self, mix: &WavelengthMixture, band: Band, lambda: f64) -> f64 {
        if !band.contains(lambda) {
            return 0.0;
        }
        let b = band.width_nm();
        if mix.total <= 0.0 {
            return 1.0 / b;
        }
        let mut p = DEFENSIVE_WAVELENGTH_SHARE / b;
        let share = (1.0 - DEFENSIVE_WAVELENGTH_SHARE) / mix.total;
        if mix.zero_weight > 0.0 && lambda >= mix.zero_lo {
            p += share * mix.zero_weight / (band.max_nm() - mix.zero_lo);
        }
        if mix.q > 0.0 {
            let x = mix.q / lambda;
            let m = math::rint(x);
            if m >= 1.0 {
                let r = x - m;
                // Is order m among the peaks the sampler follows?
                let peaks = self.grating.peaks(mix.u, band);
                let mut found = None;
                for pk in peaks.take(MAX_WAVELENGTH_PEAKS) {
                    if pk.order.unsigned_abs() as f64 == m {
                        found = Some(pk);
                        break;
                    }
                    if pk.order.unsigned_abs() as f64 > m {
                        break;
                    }
                }
                if let Some(pk) = found {
                    let w = self.peak_weight(&pk, mix);
                    p += share * w * lorentz_q(mix.n, self.atan_n, r) * mix.q / (lambda * lambda);
                }
            }
        }
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }
}

/// The mixture of `sample_wavelength` for one (wo, wi).
struct WavelengthMixture {
    u: f64,
    v: f64,
    q: f64,
    n: f64,
    total: f64,
    zero_weight: f64,
    zero_lo: f64,
    wo: DVec3,
    wi: DVec3,
}
