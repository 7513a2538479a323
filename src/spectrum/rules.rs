//! Quadrature rules over wavelength or phase on XYZ-valued integrands: the midpoint rule and the
//! crate's Gauss-Legendre rules ([`crate::num::quadrature`]) in the accumulating form the spectral
//! integrators use.

use glam::DVec3;

use super::{BAND, MAX_WAVELENGTHS};
use crate::num::quadrature;

/// The midpoint rule with `k` (at least 1) wavelengths over the band.
pub(super) fn midpoint_rule(k: u32, f: &dyn Fn(f64) -> DVec3) -> DVec3 {
    let k = k.clamp(1, MAX_WAVELENGTHS);
    let step = BAND.width_nm() / k as f64;
    let mut acc = DVec3::ZERO;
    for j in 0..k {
        acc += f(BAND.min_nm() + (j as f64 + 0.5) * step) * step;
    }
    acc
}

/// 8-point Gauss-Legendre on each of `k` (at least 1) equal intervals of the band.
pub(super) fn gauss_legendre_rule(k: u32, f: &dyn Fn(f64) -> DVec3) -> DVec3 {
    let k = k.clamp(1, MAX_WAVELENGTHS / 8);
    let step = BAND.width_nm() / k as f64;
    let mut acc = DVec3::ZERO;
    for j in 0..k {
        let a = BAND.min_nm() + j as f64 * step;
        gl8(a, a + step, &mut acc, f);
    }
    acc
}

/// The crate's Gauss-Legendre rules ([`crate::num::quadrature`]) accumulating into `acc`, the form
/// the spectral integrators pass around as piece rules.
#[inline]
pub(super) fn gl8(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    *acc += quadrature::gl8(a, b, f);
}

/// See [`gl8`].
#[inline]
pub(super) fn gl6(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    *acc += quadrature::gl6(a, b, f);
}

/// See [`gl8`].
#[inline]
pub(super) fn gl4(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    *acc += quadrature::gl4(a, b, f);
}

/// See [`gl8`].
#[inline]
pub(super) fn gl3(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    *acc += quadrature::gl3(a, b, f);
}

/// See [`gl8`].
#[inline]
pub(super) fn gl2(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    *acc += quadrature::gl2(a, b, f);
}
