//! The paper's own colours (its rendering steps 6-8): eq. 13 at the peak wavelengths only.

use glam::DVec3;

use super::{Spectral, BAND};
use crate::cie;
use crate::Grating;

impl Spectral {
    pub(super) fn paper_peaks(&self, grating: &Grating, u: f64) -> DVec3 {
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
