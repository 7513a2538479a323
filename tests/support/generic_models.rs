//! Models that take the generic colour path of `Spectral::xyz_brdf`, and the directions that
//! put a given phase projection u in front of them.
//!
//! Each test binary that includes this file uses part of it.
#![allow(dead_code)]

use diffraction::{Band, DiffractionBrdf, Peak, PeakSummary};
use glam::DVec3;

/// A model that hides that it is a grating's intensity (no `grating_response`), so that the
/// colour integrator takes its generic path through `eval` and `peaks`.
pub struct Opaque<B>(pub B);

impl<B: DiffractionBrdf> DiffractionBrdf for Opaque<B> {
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        self.0.eval(wi, wo, lambda_nm)
    }
    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        self.0.peaks(wi, wo, band, visit)
    }
    fn cosine_included(&self) -> bool {
        self.0.cosine_included()
    }
}

/// wi = wo = (u/2, 0, √(1 − u²/4)): the retro-reflecting pair whose phase projection
/// wi.x + wo.x is exactly u (halving and doubling are exact), for |u| < 2.
pub fn retro(u: f64) -> (DVec3, DVec3) {
    let h = 0.5 * u;
    let w = DVec3::new(h, 0.0, (1.0 - h * h).sqrt());
    (w, w)
}

/// A unit direction in the upper hemisphere from its polar and azimuthal angles.
pub fn unit_upper(theta: f64, phi: f64) -> DVec3 {
    DVec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

/// The sharpest visited peak's N_eff = λ_m/(|m|·Δλ_m) (Δλ_m its equivalent width): the
/// `N_eff` of the `Strategy` bounds. `None` where no peak is visited.
pub fn sharpest(model: &dyn DiffractionBrdf, wi: DVec3, wo: DVec3) -> Option<f64> {
    let mut n_eff: Option<f64> = None;
    model.peaks(wi, wo, Band::VISIBLE, &mut |p| {
        let n = p.wavelength_nm / (p.order.unsigned_abs() as f64 * p.equivalent_width_nm);
        n_eff = Some(n_eff.map_or(n, |m| m.min(n)));
    });
    n_eff
}
