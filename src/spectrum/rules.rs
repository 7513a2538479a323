//! Quadrature rules over wavelength or phase: the midpoint rule, Gauss-Legendre with 4 and 8
//! points, on XYZ-valued integrands.

use glam::DVec3;

use super::{BAND, MAX_WAVELENGTHS};

/// Gauss-Legendre 8-point nodes and weights on [−1, 1] (numpy.polynomial.legendre.leggauss(8)).
pub(super) const GL_X: [f64; 8] = [
    -0.9602898564975362,
    -0.7966664774136267,
    -0.525532409916329,
    -0.18343464249564978,
    0.18343464249564978,
    0.525532409916329,
    0.7966664774136267,
    0.9602898564975362,
];
pub(super) const GL_W: [f64; 8] = [
    0.10122853629037706,
    0.22238103445337443,
    0.3137066458778869,
    0.36268378337836166,
    0.36268378337836166,
    0.3137066458778869,
    0.22238103445337443,
    0.10122853629037706,
];

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

/// 4-point Gauss-Legendre over [a, b] (numpy.polynomial.legendre.leggauss(4)).
#[inline]
pub(super) fn gl4(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    const X: [f64; 2] = [0.33998104358485626, 0.8611363115940526];
    const W: [f64; 2] = [0.6521451548625464, 0.34785484513745357];
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    for (x, w) in X.iter().zip(W) {
        *acc += f(mid - half * x) * w * half;
        *acc += f(mid + half * x) * w * half;
    }
}

#[inline]
pub(super) fn gl8(a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    for (xi, wi) in GL_X.iter().zip(GL_W) {
        *acc += f(mid + half * xi) * wi * half;
    }
}
