//! `Strategy::ASYMPTOTIC` for N ≤ 7 slits: the Fejér kernel as its few cosines.
//!
//! For N slits F_N(x) = (1/N)·Σ_{|j|<N} (1 − |j|/N)·cos(2πjx) (x = d·|u|/λ), so the colour
//! is a short sum of cosine-weighted smooth integrals. Where the single-slit factor has more
//! than one lobe over the band it is split the same way, S(ρx) = (1 − cos 2πρx)/(2π²ρ²x²), so
//! every term is c·a(λ)·cos(2πfx) with a smooth amplitude a (S·env or λ²·env/(2π²ρ²q²)) and a
//! frequency f ∈ {j, j ± ρ}. On each 30 nm piece of `smooth_band` the terms whose local
//! frequency 2π|f|·q/λ² the product rule resolves (32 points, the limits of `Limits::FAST`) are
//! summed into one kernel and integrated against the tables by that rule (the sum of cosines
//! by Horner's rule in e^{2πix}, `cosine_sum`: two complex exponentials a point whatever the
//! number of terms); each remaining term is
//! high-frequency on a run of pieces from 360 nm up to some λ_t, and there it takes the
//! first two terms of its expansion by parts,
//!
//! ```text
//! ∫ G·cos φ dλ = [G·sin φ/φ' + (G' + 2G/λ)·cos φ/φ'²] − Σ_k ΔG'_k·cos φ_k/φ'_k² + O(G''/φ'³),
//! ```
//!
//! G = W·c·a (W = E·cmf the tables' weight, its slope one-sided at the ends), φ = 2πf·q/λ,
//! ΔG'_k the jump of G's slope at the illuminant's nodes λ_k inside (D65's 5 nm nodes, where
//! its linear interpolation has slope jumps up to 8 %/nm). The observer's 1 nm rows, whose
//! slope jumps are a second difference of the curves (below 5·10⁻⁴ of each maximum), are not
//! summed: at the threshold |φ'| ≥ 2.3 rad/nm each leaves below 10⁻⁴ of its row's light, with
//! phases that do not add up (measured bound in `bounds::ASYMPTOTIC_SMALL_N`). The work is
//! fixed: at most 16 pieces × 32 kernel points and, per high-frequency term, two end terms, and
//! at each of D65's 93 nodes one `cosine_sum` of the terms whose run holds it, whatever the
//! period. It grows by about 5 % a slit (instructions per colour at the slowest directions of
//! d = 30-100 µm), which is why the rule stops at `MAX_SLITS`.

use glam::DVec3;

use super::order0::{piece_bounds, PIECES};
use super::smooth_band::{piece_points, piece_rule, Limits};
use super::Spectral;
use crate::data::cie::Illuminant;
use crate::data::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};
use crate::num::kernel::{cis_turn, intensity_ratio_flat, single_slit_cycles};
use crate::{Grating, Slits};
use core::f64::consts::PI;

/// Where ρ·x stays below this over the band (at most one lobe of S), S is kept whole in the
/// amplitude; above, it is split into its cosines.
const WHOLE_SINC_CYCLES: f64 = 1.0;
/// The spacing of D65's own nodes, nm (see `asymptotic::node_spacing_nm`).
const D65_NODE_NM: usize = 5;
/// The step of the central difference for the amplitude's slope, nm (a is a power of λ times
/// the smooth envelope: the difference is exact to about 10⁻¹⁰ relative).
const SLOPE_STEP_NM: f64 = 1e-2;
/// The most slits this rule takes: up to here its fixed work (2 + 3·(N − 1) terms) is below the
/// lobe walk's at the slowest directions of coarse gratings (d = 30 and 100 µm, measured in
/// instructions per colour: 0.77-0.93× for N = 5-7); at 8 slits it is 1.00-1.09× the walk.
pub(super) const MAX_SLITS: usize = 7;
/// The most terms: 2 + 3·(N − 1) for N = MAX_SLITS.
const MAX_TERMS: usize = 2 + 3 * (MAX_SLITS - 1);

/// One term c·a(λ)·cos(2π(j + σρ)·x).
#[derive(Clone, Copy, Default)]
struct Term {
    j: usize,
    sigma: f64,
    coef: f64,
    /// The first piece whose product rule resolves the term (`PIECES` if none).
    first_low: usize,
}

/// cos and sin of 2π·(j + σρ)·x for the terms, from e^{2πix} and e^{2πiρx}.
struct Phases {
    powers: [(f64, f64); MAX_SLITS],
    slit: (f64, f64),
}

impl Phases {
    fn new(x: f64, rho: f64, n: usize) -> Phases {
        let mul = |a: (f64, f64), b: (f64, f64)| (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
        let turn = cis_turn;
        let e1 = turn(x);
        let mut powers = [(1.0, 0.0); MAX_SLITS];
        for j in 1..n {
            powers[j] = mul(powers[j - 1], e1);
        }
        Phases {
            powers,
            slit: turn(rho * x),
        }
    }

    /// (cos φ, sin φ) for the term.
    #[inline]
    fn of(&self, t: &Term) -> (f64, f64) {
        let a = self.powers[t.j];
        if t.sigma == 0.0 {
            return a;
        }
        let (c, s) = (self.slit.0, t.sigma * self.slit.1);
        (a.0 * c - a.1 * s, a.0 * s + a.1 * c)
    }
}

/// Adds c·cos 2π(j + σρ)x to the rows of `cosine_sum`: row j holds (c_j,0, c_j,+ + c_j,−,
/// c_j,+ − c_j,−), the coefficients of cos 2πjx, cos 2π(j + ρ)x and cos 2π(j − ρ)x combined.
fn add_term(rows: &mut [[f64; 3]], j: usize, sigma: f64, c: f64) {
    let row = &mut rows[j];
    if sigma == 0.0 {
        row[0] += c;
    } else {
        row[1] += c;
        row[2] += sigma.signum() * c;
    }
}

/// Σ_j [c_j,0·cos 2πjx + c_j,+·cos 2π(j + ρ)x + c_j,−·cos 2π(j − ρ)x] for the rows of
/// `add_term`: the real part of Σ_j e^{2πijx}·(c_j,0 + (c_j,+ + c_j,−)·cos θ +
/// i·(c_j,+ − c_j,−)·sin θ), θ = 2πρx, by Horner's rule in e^{2πix} (two complex exponentials,
/// then a complex product and sum per row).
fn cosine_sum(rows: &[[f64; 3]], x: f64, rho: f64) -> f64 {
    let (c1, s1) = cis_turn(x);
    let (cs, sn) = cis_turn(rho * x);
    let (mut re, mut im) = (0.0, 0.0);
    for r in rows.iter().rev() {
        let (a, b) = (r[0] + r[1] * cs, r[2] * sn);
        (re, im) = (re * c1 - im * s1 + a, re * s1 + im * c1 + b);
    }
    re
}

/// E(λ) on row i of `illuminant`.
#[inline]
fn power_row(illuminant: Illuminant, i: usize) -> f64 {
    match illuminant {
        Illuminant::E => 1.0,
        Illuminant::D65 => D65[i],
        Illuminant::A => ILLUMINANT_A[i],
    }
}

/// W = E·cmf and its slope dW/dλ at fraction s ∈ [0, 1] of row i (between rows i and i + 1).
fn weight_and_slope(illuminant: Illuminant, i: usize, s: f64) -> (DVec3, DVec3) {
    let (e0, e1) = (power_row(illuminant, i), power_row(illuminant, i + 1));
    let (c0, c1) = (
        DVec3::from_array(CIE1931_2DEG[i]),
        DVec3::from_array(CIE1931_2DEG[i + 1]),
    );
    let (e, c) = (e0 + s * (e1 - e0), c0 + s * (c1 - c0));
    (c * e, c * (e1 - e0) + (c1 - c0) * e)
}

impl Spectral {
    /// The colour for N ≤ `MAX_SLITS` slits (module docs); `None` where the spectral envelope is not
    /// smooth over the band (the caller takes `Exact`).
    pub(super) fn small_n(&self, grating: &Grating, q: f64) -> Option<DVec3> {
        let n = match grating.slits() {
            Slits::Finite(n) if (1..=MAX_SLITS as u32).contains(&n) => n as usize,
            _ => return None,
        };
        if self.envelope.band_sinc_cycles() > 0.5 || !q.is_finite() {
            return None;
        }
        if let Some(c) = self.smooth_band(grating, q, n as f64, Limits::FAST) {
            return Some(c);
        }
        let rho = grating.slit_width_nm() / grating.period_nm();
        let whole = rho * q / (FIRST_NM as f64) <= WHOLE_SINC_CYCLES;
        // The terms: c_j = (2 − δ_j0)(1 − j/N)/N, each times S or split with S's cosines.
        let mut terms = [Term::default(); MAX_TERMS];
        let mut count = 0;
        let mut push = |j: usize, sigma: f64, coef: f64| {
            terms[count] = Term {
                j,
                sigma,
                coef,
                first_low: PIECES,
            };
            count += 1;
        };
        for j in 0..n {
            let c = if j == 0 { 1.0 } else { 2.0 } * (1.0 - j as f64 / n as f64) / n as f64;
            if whole {
                push(j, 0.0, c);
            } else if j == 0 {
                push(0, 0.0, c);
                push(0, 1.0, -c);
            } else {
                push(j, 0.0, c);
                push(j, 1.0, -0.5 * c);
                push(j, -1.0, -0.5 * c);
            }
        }
        let terms = &mut terms[..count];
        let frequency =
            |t: &Term, l: f64| 2.0 * PI * (t.j as f64 + t.sigma * rho).abs() * q / (l * l);
        for t in terms.iter_mut() {
            t.first_low = (0..PIECES)
                .find(|&p| {
                    let (lo, hi) = piece_bounds(p);
                    piece_points(Limits::FAST, frequency(t, lo), 0.5 * (hi - lo)).is_some()
                })
                .unwrap_or(PIECES);
        }
        let k_split = 1.0 / (2.0 * PI * PI * rho * rho * q * q);
        let amplitude = |l: f64| {
            if whole {
                single_slit_cycles(rho * q / l) * self.envelope_norm(l)
            } else {
                l * l * k_split * self.envelope_norm(l)
            }
        };
        let mut acc = DVec3::ZERO;
        // The pieces that resolve every term: the whole kernel S·F_N·env, one evaluation a
        // point (as `smooth_band`).
        let all_low = terms.iter().map(|t| t.first_low).max().unwrap_or(0);
        let n_int = n as u32;
        let whole_kernel = |l: f64| {
            let x = q / l;
            let (num, den) = intensity_ratio_flat(x, rho * x, n_int);
            let r = num / den;
            (r * r).min(1.0) * self.envelope_norm(l)
        };
        let top_frequency = (n as f64 - 1.0 + rho) * 2.0 * PI * q;
        for p in all_low..PIECES {
            let (lo, hi) = piece_bounds(p);
            let points = piece_points(Limits::FAST, top_frequency / (lo * lo), 0.5 * (hi - lo))?;
            acc += piece_rule(self.illuminant, p, points, &whole_kernel);
        }
        // The resolved terms of the other pieces by the product rule.
        for p in 0..all_low {
            let (lo, hi) = piece_bounds(p);
            let top = terms
                .iter()
                .filter(|t| t.first_low <= p)
                .map(|t| frequency(t, lo))
                .fold(-1.0f64, f64::max);
            if top < 0.0 {
                continue;
            }
            let points = piece_points(Limits::FAST, top, 0.5 * (hi - lo))?;
            // The resolved terms' coefficients by j and σ, summed by `cosine_sum`.
            let mut low = [[0.0; 3]; MAX_SLITS];
            let mut top_j = 0;
            for t in terms.iter().filter(|t| t.first_low <= p) {
                add_term(&mut low, t.j, t.sigma, t.coef);
                top_j = top_j.max(t.j);
            }
            let low = &low[..=top_j];
            let k = |l: f64| cosine_sum(low, q / l, rho) * amplitude(l);
            acc += piece_rule(self.illuminant, p, points, &k);
        }
        // The high-frequency runs [360, λ_t] by parts.
        if terms.iter().any(|t| t.first_low > 0) {
            acc += self.by_parts(terms, q, rho, &amplitude);
        }
        Some(acc.max(DVec3::ZERO))
    }

    /// Σ over the terms of their expansion by parts over [360, λ_t] (module docs).
    fn by_parts(&self, terms: &[Term], q: f64, rho: f64, amplitude: &dyn Fn(f64) -> f64) -> DVec3 {
        let ill = self.illuminant;
        let n = terms.iter().map(|t| t.j + 1).max().unwrap_or(1);
        let last_row = (LAST_NM - FIRST_NM) as usize;
        // [G·sin φ/φ' + (G' + 2G/λ)·cos φ/φ'²] at λ (row i, fraction s), times `sign`.
        let end = |t: &Term, l: f64, i: usize, s: f64, ph: &Phases| {
            let (w, dw) = weight_and_slope(ill, i, s);
            let a = amplitude(l);
            let da = (amplitude(l + SLOPE_STEP_NM) - amplitude(l - SLOPE_STEP_NM))
                / (2.0 * SLOPE_STEP_NM);
            let g = w * (t.coef * a);
            let dg = (w * da + dw * a) * t.coef;
            let f = t.j as f64 + t.sigma * rho;
            let dphi = -2.0 * PI * f * q / (l * l);
            let (c, sn) = ph.of(t);
            g * (sn / dphi) + (dg + g * (2.0 / l)) * (c / (dphi * dphi))
        };
        let mut acc = DVec3::ZERO;
        let first = FIRST_NM as f64;
        let ph0 = Phases::new(q / first, rho, n);
        for t in terms.iter().filter(|t| t.first_low > 0) {
            let l_t = if t.first_low < PIECES {
                piece_bounds(t.first_low).0
            } else {
                LAST_NM as f64
            };
            let row = (l_t - first) as usize;
            let ph = Phases::new(q / l_t, rho, n);
            acc += end(t, l_t, row.min(last_row) - 1, 1.0, &ph);
            acc -= end(t, first, 0, 0.0, &ph0);
        }
        if ill != Illuminant::D65 {
            return acc;
        }
        // The slope jumps at D65's nodes inside each run.
        let top = terms.iter().map(|t| t.first_low).max().map_or(0.0, |p| {
            if p < PIECES {
                piece_bounds(p).0
            } else {
                LAST_NM as f64
            }
        });
        // Σ_t c_t·cos φ_t/φ'_t² = l⁴/(2πq)²·Σ_t (c_t/f_t²)·cos 2πf_t·x over the terms whose run
        // holds the node (l < λ_t), as one cosine sum; a term leaves it at its λ_t.
        let mut runs = [(f64::INFINITY, 0usize, 0.0, 0.0); MAX_TERMS];
        let mut count = 0;
        let mut sums = [[0.0; 3]; MAX_SLITS];
        for t in terms.iter().filter(|t| t.first_low > 0) {
            let l_t = if t.first_low < PIECES {
                piece_bounds(t.first_low).0
            } else {
                LAST_NM as f64
            };
            let f = t.j as f64 + t.sigma * rho;
            let c = t.coef / (f * f);
            add_term(&mut sums, t.j, t.sigma, c);
            runs[count] = (l_t, t.j, t.sigma, c);
            count += 1;
        }
        let runs = &mut runs[..count];
        let scale = 1.0 / (4.0 * PI * PI * q * q);
        let mut i = D65_NODE_NM;
        while (first + i as f64) < top {
            let l = first + i as f64;
            for (l_t, j, sigma, c) in runs.iter_mut() {
                if *l_t <= l {
                    add_term(&mut sums, *j, *sigma, -*c);
                    *l_t = f64::INFINITY;
                }
            }
            let (_, right) = weight_and_slope(ill, i, 0.0);
            let (_, left) = weight_and_slope(ill, i - 1, 1.0);
            let jump = (right - left) * amplitude(l);
            let l2 = l * l;
            acc -= jump * (cosine_sum(&sums[..n], q / l, rho) * l2 * l2 * scale);
            i += D65_NODE_NM;
        }
        acc
    }
}
