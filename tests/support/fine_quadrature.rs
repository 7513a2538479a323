//! An independent reference for the colour of any model: composite 8-point Gauss-Legendre on
//! pieces of 1/`PIECES_PER_NM` nm aligned with the 1 nm rows of the CIE tables (so no piece
//! straddles a kink of their linear interpolation), each piece further split where a narrow
//! peak lies near it. Written here from the definition of the reference colour
//! (`∫E·f·cmf dλ / ∫E·ȳ dλ` over 360-830 nm, f times cos θi when the model does not include it),
//! not from the crate's integrators.
#![allow(dead_code)]

use diffraction::cie::{cmf, Illuminant};
use diffraction::{Band, DiffractionBrdf};
use glam::DVec3;

/// Pieces per nanometre of the base grid: 0.01 nm pieces.
pub const PIECES_PER_NM: u32 = 100;

/// numpy.polynomial.legendre.leggauss(8), nodes on [−1, 1] and weights.
pub const X: [f64; 8] = [
    -0.9602898564975362,
    -0.7966664774136267,
    -0.525532409916329,
    -0.18343464249564978,
    0.18343464249564978,
    0.525532409916329,
    0.7966664774136267,
    0.9602898564975362,
];
pub const W: [f64; 8] = [
    0.10122853629037706,
    0.22238103445337443,
    0.3137066458778869,
    0.36268378337836166,
    0.36268378337836166,
    0.3137066458778869,
    0.22238103445337443,
    0.10122853629037706,
];

fn gl8(a: f64, b: f64, f: &dyn Fn(f64) -> [f64; 3], acc: &mut [f64; 3]) {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    for (x, w) in X.iter().zip(W) {
        let v = f(mid + half * x);
        for c in 0..3 {
            acc[c] += v[c] * w * half;
        }
    }
}

/// ∫ g over the band, split at every 1/`PIECES_PER_NM` nm and, within `reach` equivalent
/// widths of each (wavelength, equivalent width) in `peaks`, into pieces of a tenth of that
/// width.
fn integrate(g: &dyn Fn(f64) -> [f64; 3], peaks: &[(f64, f64)], per_nm: u32) -> [f64; 3] {
    let mut acc = [0.0; 3];
    let h = 1.0 / per_nm as f64;
    for row in 360..830 {
        for k in 0..per_nm {
            let a = row as f64 + k as f64 * h;
            let b = if k + 1 == per_nm {
                row as f64 + 1.0
            } else {
                a + h
            };
            // The narrowest peak reaching this piece sets its subdivision.
            let width = peaks
                .iter()
                .filter(|(l, w)| a < l + 200.0 * w && b > l - 200.0 * w)
                .map(|&(_, w)| w)
                .fold(f64::INFINITY, f64::min);
            let parts = ((b - a) / (0.1 * width)).ceil().clamp(1.0, 1e5) as u32;
            let step = (b - a) / parts as f64;
            for j in 0..parts {
                let s = a + j as f64 * step;
                let e = if j + 1 == parts { b } else { s + step };
                gl8(s, e, g, &mut acc);
            }
        }
    }
    acc
}

/// ∫E·ȳ dλ of the linearly interpolated tables (a quadratic on every 1 nm row: GL8 is exact).
pub fn normalisation(illuminant: Illuminant) -> f64 {
    let mut acc = [0.0; 3];
    for row in 360..830 {
        let a = row as f64;
        gl8(
            a,
            a + 1.0,
            &|l| [0.0, illuminant.power(l) * cmf(l)[1], 0.0],
            &mut acc,
        );
    }
    acc[1]
}

/// The reference colour of `model` at (wi, wo) under `illuminant`.
pub fn reference_xyz(
    model: &dyn DiffractionBrdf,
    wi: DVec3,
    wo: DVec3,
    illuminant: Illuminant,
) -> [f64; 3] {
    reference_xyz_with(model, wi, wo, illuminant, PIECES_PER_NM)
}

/// [`reference_xyz`] on a base grid of `per_nm` pieces per nanometre (to check its convergence).
pub fn reference_xyz_with(
    model: &dyn DiffractionBrdf,
    wi: DVec3,
    wo: DVec3,
    illuminant: Illuminant,
    per_nm: u32,
) -> [f64; 3] {
    let cos = if model.cosine_included() {
        1.0
    } else {
        wi.z.max(0.0)
    };
    let norm = 1.0 / normalisation(illuminant);
    let mut peaks = vec![];
    model.peaks(wi, wo, Band::VISIBLE, &mut |p| {
        peaks.push((p.wavelength_nm, p.equivalent_width_nm))
    });
    let g = |l: f64| {
        let e = illuminant.power(l) * model.eval(wi, wo, l) * cos * norm;
        let c = cmf(l);
        [e * c[0], e * c[1], e * c[2]]
    };
    integrate(&g, &peaks, per_nm)
}
