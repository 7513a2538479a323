//! The paper's own colours (its rendering steps 6-8): eq. 13 at the peak wavelengths only.

use glam::DVec3;

use super::{Spectral, BAND};
use crate::color::Xyz;
use crate::data::cie;
use crate::Grating;

impl Spectral {
    /// The paper's own colour of `grating` at u (its rendering steps 6-8): eq. 13 at the peak
    /// wavelengths λ_m only, each with its peak intensity S(β_m) whatever N is, converted to
    /// colour: XYZ = Σ_m S(β_m)·(E(λ_m)/Ē)·cmf(λ_m), with Ē = ∫E·ȳ/∫ȳ the mean power of the
    /// illuminant, so a unit peak at 555 nm under E has Y ≈ 1; inside the order-0 lobe the
    /// colour is the illuminant's white (Y = 1) plus the peaks.
    ///
    /// It reproduces the paper's pictures but is **not the integral** (not a
    /// [`Strategy`](super::Strategy)): it is N·|m|/λ_m·(∫Eȳ/Ē) times brighter per order than the
    /// peak-search estimate of the integral, so the relative brightness of orders differs
    /// (higher orders are relatively brighter in the paper's mode). Finite and ≥ 0; bounded
    /// work for every period (more than 4096 orders in the band are summed in closed form).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let s = Spectral::new(Illuminant::E);
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// // u = 0.3: order 1 at 480 nm with S(β₁) = 4/π², the paper's colour of that wavelength.
    /// let paper = s.paper_peaks(&g, 0.3);
    /// let cmf = diffraction::cie::cmf(480.0);
    /// let mean = 1.0; // E is flat: Ē = 1
    /// assert!((paper.y - 4.0 / std::f64::consts::PI.powi(2) * cmf[1] / mean).abs() < 1e-12);
    /// // The integral is far darker: about 1/N of the light.
    /// assert!(s.xyz(&g, 0.3, Strategy::EXACT).y < 1e-2 * paper.y);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn paper_peaks(&self, grating: &Grating, u: f64) -> Xyz {
        let u = u.abs();
        if !u.is_finite() {
            return Xyz::default();
        }
        let v = self.paper_peaks_sum(grating, u);
        super::saturate(Xyz::new(v.x, v.y, v.z))
    }

    fn paper_peaks_sum(&self, grating: &Grating, u: f64) -> DVec3 {
        if u == 0.0 {
            return self.flat_dvec3();
        }
        if Self::is_dense(grating.period_nm() * u) {
            // Too many orders to walk one by one: the same sum in closed form (see `dense`).
            return self.dense_paper_peaks(grating, grating.period_nm() * u);
        }
        let peaks = grating.peaks(u, BAND);
        let mut acc = DVec3::ZERO;
        if peaks.specular() {
            acc = self.flat_dvec3();
        }
        let scale = 1.0 / self.mean_power;
        for p in peaks {
            let e = self.illuminant.power(p.wavelength_nm) * scale * p.intensity;
            acc += DVec3::from(cie::cmf(p.wavelength_nm)) * e;
        }
        acc
    }
}
