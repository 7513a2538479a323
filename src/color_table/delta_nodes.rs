//! The node values of an N = ∞ radiometric table: the areas of the delta orders, summed over
//! the orders in the band, and the nodes that are provably dark.

use glam::DVec3;

use super::layout::{work_units, DARK_SHARE, LAMBDA_MAX_NM, LAMBDA_MIN_NM};
use crate::color::Xyz;
use crate::spectrum::{saturate, Spectral};
use crate::{Band, GratingBsdf, MAX_ORDERS};

/// The nodes of an N = ∞ table: Σ_m η_m·(d/|m|)·weight(λ_m) over the orders of
/// `Grating::peaks` (at most [`MAX_ORDERS`]), black without evaluation where provably below the
/// tolerance.
pub(super) struct DeltaNodes<'a> {
    spectral: &'a Spectral,
    bsdf: &'a GratingBsdf,
    /// An upper bound of weight(λ) per channel over the band, over the white.
    peak_weight: [f64; 3],
    white: [f64; 3],
    /// DARK_SHARE·accuracy·floor.
    dark: f64,
    pub evaluations: core::cell::Cell<usize>,
    pub work_done: core::cell::Cell<usize>,
}

impl<'a> DeltaNodes<'a> {
    pub(super) fn new(
        spectral: &'a Spectral,
        bsdf: &'a GratingBsdf,
        accuracy: f64,
        white: [f64; 3],
        floor: f64,
    ) -> DeltaNodes<'a> {
        DeltaNodes {
            spectral,
            bsdf,
            peak_weight: peak_weight(spectral),
            white,
            dark: accuracy * DARK_SHARE * floor,
            evaluations: core::cell::Cell::new(0),
            work_done: core::cell::Cell::new(0),
        }
    }

    /// Σ_m η_m·(d/|m|) ≤ d·Σ_{m ≥ a} 1/(π²·m³) ≤ d·(1/a³ + 1/(2a²))/π² with a the lowest order
    /// in the band (η_m = ρ²·S(π·ρ·m) ≤ 1/(π·m)²): where that times the peak weight is below
    /// the tolerance in every channel the node is black.
    fn provably_dark(&self, u: f64) -> bool {
        let d = self.bsdf.grating().period_nm();
        let a = (d * u / LAMBDA_MAX_NM).max(1.0);
        let pi2 = core::f64::consts::PI * core::f64::consts::PI;
        let bound = d * (1.0 / (a * a * a) + 0.5 / (a * a)) / pi2;
        a > 1.0 && (0..3).all(|c| bound * self.peak_weight[c] <= self.dark * self.white[c])
    }

    pub(super) fn eval(&self, u: f64) -> [f64; 3] {
        if self.provably_dark(u) {
            return [0.0; 3];
        }
        let g = self.bsdf.grating();
        let d = g.period_nm();
        self.evaluations.set(self.evaluations.get() + 1);
        self.work_done.set(self.work_done.get() + work_units(d * u));
        let mut acc = DVec3::ZERO;
        for p in g.peaks(u, Band::VISIBLE).take(MAX_ORDERS as usize) {
            let area = self.bsdf.efficiency(p.order) * d / p.order.unsigned_abs() as f64;
            acc += self.spectral.weight(p.wavelength_nm) * area;
        }
        let c = saturate(Xyz::new(acc.x, acc.y, acc.z));
        [c.x, c.y, c.z]
    }
}

/// An upper bound of `spectral.weight(λ)` per channel over the band: E and the observer are
/// linear between their 1 nm rows, so each is largest at a row, and the product of their
/// largest values bounds the weight.
pub(super) fn peak_weight(spectral: &Spectral) -> [f64; 3] {
    let (mut e_max, mut c_max) = (0.0f64, [0.0f64; 3]);
    let mut l = LAMBDA_MIN_NM;
    while l <= LAMBDA_MAX_NM {
        let w = spectral.weight(l);
        let e = spectral.illuminant().power(l);
        e_max = e_max.max(e);
        if e > 0.0 {
            c_max = [
                c_max[0].max(w.x / e),
                c_max[1].max(w.y / e),
                c_max[2].max(w.z / e),
            ];
        }
        l += 1.0;
    }
    [e_max * c_max[0], e_max * c_max[1], e_max * c_max[2]]
}
