//! What the tests of the generic colour path share: a model trait object with both the value
//! and the colour capability, the directions that put a given phase projection u in front of a
//! model, and the sharpest visited peak.
//!
//! Each test binary that includes this file uses part of it.
#![allow(dead_code)]

use diffraction::{Band, DiffractionBrdf, SpectralResponse};
use glam::DVec3;

/// A model with its value and its colour (`dyn` needs one trait for both).
pub trait Model: DiffractionBrdf + SpectralResponse {}
impl<M: DiffractionBrdf + SpectralResponse> Model for M {}

/// wo = wi = (u/2, 0, √(1 − u²/4)): the retro-reflecting pair whose phase projection
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
/// `N_eff` of the `GenericStrategy` bounds. `None` where no peak is visited.
pub fn sharpest(model: &dyn SpectralResponse, wo: DVec3, wi: DVec3) -> Option<f64> {
    let mut n_eff: Option<f64> = None;
    model.peaks(wo, wi, Band::VISIBLE, &mut |p| {
        let n = p.wavelength_nm / (p.order.unsigned_abs() as f64 * p.equivalent_width_nm);
        n_eff = Some(n_eff.map_or(n, |m| m.min(n)));
    });
    n_eff
}
