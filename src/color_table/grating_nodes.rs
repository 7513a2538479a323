//! The node values of a finite grating's colour: which strategy computes each node, the nodes
//! that are provably dark, and the evaluation counters (the paper's source and the finite-N
//! radiometric source of [`ColorTable`](super::ColorTable)).

use core::cell::Cell;

use super::layout::{
    work_units, ASYMPTOTIC_ACCURACY, DARK_SHARE, LAMBDA_MAX_NM, ORDER0_HALF_PERIOD_NM,
};
use crate::error::Error;
use crate::spectrum::bounds::{self, accuracy_floor};
use crate::spectrum::{Spectral, Strategy, MIN_ACCURACY};
use crate::Grating;

/// `k · spectral.xyz(grating, u, ·)` at a node, by the cheapest strategy that keeps the node
/// inside the tolerance (see `ColorTable`'s Cost section), with its counters.
pub(super) struct GratingNodes<'a> {
    spectral: &'a Spectral,
    grating: &'a Grating,
    /// The factor of every value (1 for the paper's colour, ρ²·N·d for the radiometric one).
    k: f64,
    white: [f64; 3],
    fast: bool,
    order0_from: f64,
    dark_t: f64,
    careful: Strategy,
    /// k·(the colour of I ≡ 1), per channel.
    flat: [f64; 3],
    /// The tolerance's least value over the white: DARK_SHARE·accuracy·floor.
    dark: f64,
    /// π·ρ/λ_max: β at the band's longest wavelength per unit d·u.
    slit: f64,
    pub evaluations: Cell<usize>,
    pub work_done: Cell<usize>,
}

impl<'a> GratingNodes<'a> {
    /// The evaluator for a finite grating of N = `n` slits at `accuracy` (validated by the
    /// caller); `floor` is the table's least error scale (in units of k·colour).
    pub(super) fn new(
        spectral: &'a Spectral,
        grating: &'a Grating,
        n: f64,
        accuracy: f64,
        k: f64,
        white: [f64; 3],
        floor: f64,
    ) -> Result<GratingNodes<'a>, Error> {
        let dark_t = {
            let r = accuracy / bounds::ASYMPTOTIC_ORDER0;
            r * r * r
        };
        let flat = spectral.xyz(grating, 0.0, Strategy::EXACT);
        Ok(GratingNodes {
            spectral,
            grating,
            k,
            white,
            fast: n >= bounds::ASYMPTOTIC_MIN_SLITS as f64 && accuracy >= ASYMPTOTIC_ACCURACY,
            order0_from: ORDER0_HALF_PERIOD_NM / grating.period_nm(),
            // Where order 0's light reaches the band, `Asymptotic` is within ORDER0_BOUND of
            // that light: a relative error δ moves CIELAB's f(t) by δ·t^(1/3)/3, within the
            // tolerance (accuracy/3) while t ≤ (accuracy/ORDER0_BOUND)³; brighter nodes are
            // recomputed by `Exact`.
            dark_t,
            // Below the accuracy where `Asymptotic` is used, a node is the cheapest strategy
            // whose bound meets DARK_SHARE of the accuracy (the peak search for very fine
            // gratings, whose bound 8/N is far below it; otherwise `Exact`).
            careful: Strategy::auto((accuracy * DARK_SHARE).max(MIN_ACCURACY))?,
            flat: [k * flat.x, k * flat.y, k * flat.z],
            dark: accuracy * DARK_SHARE * floor,
            slit: core::f64::consts::PI * grating.open_fraction() / LAMBDA_MAX_NM,
            evaluations: Cell::new(0),
            work_done: Cell::new(0),
        })
    }

    /// The paper's error floor 555/(N·∫ȳ) (see [`accuracy_floor`]).
    pub(super) fn paper_floor(n: f64) -> f64 {
        accuracy_floor(n)
    }

    /// A colour is at most S_max·flat per channel (F_N ≤ 1, S(β) ≤ 1/β² with β ≥ π·ρ·x at the
    /// band's longest wavelength), and the tolerance at least DARK_SHARE·accuracy·white·floor:
    /// where that bound is below it the node is black without an evaluation (the dense combs of
    /// very coarse gratings, d·|u| in millimetres and more).
    fn provably_dark(&self, u: f64) -> bool {
        let beta = self.slit * self.grating.period_nm() * u;
        beta > 1.0 && (0..3).all(|c| self.flat[c] / (beta * beta) <= self.dark * self.white[c])
    }

    /// The node's value at u ≥ 0, with the table's current error scale `scale`.
    pub(super) fn eval(&self, u: f64, scale: f64) -> [f64; 3] {
        if self.provably_dark(u) {
            return [0.0; 3];
        }
        let (s, g, k) = (self.spectral, self.grating, self.k);
        self.evaluations.set(self.evaluations.get() + 1);
        self.work_done
            .set(self.work_done.get() + work_units(g.period_nm() * u));
        if self.fast {
            let c = s.xyz(g, u, Strategy::ASYMPTOTIC);
            let c = [k * c.x, k * c.y, k * c.z];
            if u >= self.order0_from {
                return c;
            }
            let exposure = scale.max(c[1]);
            if (0..3).all(|j| c[j] <= self.dark_t * self.white[j] * exposure) {
                return c;
            }
        }
        let strategy = if self.fast {
            Strategy::EXACT
        } else {
            s.choose(g, u, self.careful)
        };
        let c = s.xyz(g, u, strategy);
        [k * c.x, k * c.y, k * c.z]
    }
}
