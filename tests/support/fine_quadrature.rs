//! An independent reference for the colour of any model: composite 8-point Gauss-Legendre on
//! pieces of 1/`PIECES_PER_NM` nm aligned with the 1 nm rows of the CIE tables (so no piece
//! straddles a kink of their linear interpolation), each piece further split where a narrow
//! peak lies near it. Written here from the definition of the reference colour
//! (`∫E·r·cmf dλ / ∫E·ȳ dλ` over 360-830 nm, r the model's `response`),
//! not from the crate's integrators.
#![allow(dead_code)]

use diffraction::cie::{cmf, Illuminant};
use diffraction::{Band, SpectralResponse};
use glam::DVec3;

#[path = "quadrature.rs"]
mod quadrature;
pub use quadrature::{W8, X8};

/// Pieces per nanometre of the base grid: 0.01 nm pieces.
pub const PIECES_PER_NM: u32 = 100;

fn gl8(a: f64, b: f64, f: &dyn Fn(f64) -> DVec3) -> DVec3 {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    let mut acc = DVec3::ZERO;
    for (x, w) in X8.iter().zip(W8) {
        acc += f(mid + half * x) * (w * half);
    }
    acc
}

/// ∫ g over the band, split at every 1/`per_nm` nm and, within 200 equivalent widths of each
/// (wavelength, equivalent width) in `peaks`, into pieces of a tenth of that width.
fn integrate(g: &dyn Fn(f64) -> DVec3, peaks: &[(f64, f64)], per_nm: u32) -> DVec3 {
    let mut acc = DVec3::ZERO;
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
                acc += gl8(s, e, g);
            }
        }
    }
    acc
}

/// ∫E·ȳ dλ of the linearly interpolated tables (a quadratic on every 1 nm row: GL8 is exact).
pub fn normalisation(illuminant: Illuminant) -> f64 {
    let mut y = 0.0;
    for row in 360..830 {
        let a = row as f64;
        y += gl8(a, a + 1.0, &|l| {
            DVec3::new(0.0, illuminant.power(l) * cmf(l)[1], 0.0)
        })
        .y;
    }
    y
}

/// The reference colour of `model` at (wo, wi) under `illuminant`.
pub fn reference_xyz(
    model: &dyn SpectralResponse,
    wo: DVec3,
    wi: DVec3,
    illuminant: Illuminant,
) -> DVec3 {
    reference_xyz_with(model, wo, wi, illuminant, PIECES_PER_NM)
}

/// [`reference_xyz`] on a base grid of `per_nm` pieces per nanometre (to check its convergence).
pub fn reference_xyz_with(
    model: &dyn SpectralResponse,
    wo: DVec3,
    wi: DVec3,
    illuminant: Illuminant,
    per_nm: u32,
) -> DVec3 {
    let norm = 1.0 / normalisation(illuminant);
    let mut peaks = vec![];
    model.peaks(wo, wi, Band::VISIBLE, &mut |p| {
        peaks.push((p.wavelength_nm, p.equivalent_width_nm))
    });
    let g = |l: f64| DVec3::from(cmf(l)) * (illuminant.power(l) * model.response(wo, wi, l) * norm);
    integrate(&g, &peaks, per_nm)
}
