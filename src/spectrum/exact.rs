//! `Exact`: quadrature of the reference colour, the crate's reference.
//!
//! The integrand in the phase x = d·|u|/λ is sin²(πNx)·R(x), R = E·S·cmf·norm·|dλ/dx| /
//! (N·sin πx)², with kinks where λ crosses a 1 nm row of the tables. `filon_walk` integrates it
//! piece by piece: within WINDOW_LOBES lobes of every integer x (where R has its double pole)
//! lobe by lobe, each piece of a lobe (split at the rows) by the Gauss-Legendre rule its width
//! allows (8 points down to 3); elsewhere on pieces graded by the distance ε to the nearest
//! integer (w ≤ ε), at most SLIT_SPAN periods of S and of the envelope, across the rows, by
//! `levin::piece`: R's smooth factor interpolated at 16 Chebyshev nodes a piece, the tables'
//! piecewise quadratic weight and both halves of sin² = ½ − ½·cos(2πNx) integrated exactly row by
//! row, so a piece costs 16 evaluations of the envelope and of the pole however many rows and
//! lobes it holds, and a row one evaluation of nine polynomials. Against an independent
//! composite rule (8-point Gauss-Legendre on every eighth of a lobe between the rows) it agrees
//! to 1.8·10⁻¹¹ relative, against the walk of every lobe to 6.6·10⁻¹¹ (the walk's own error,
//! 6.3·10⁻¹¹ there), against the python oracle as `tests/spectral_reference.rs` states.

use glam::DVec3;

use super::levin;
use super::lobes::Lobes;
use super::smooth_band::Limits;
use super::{Spectral, BAND};
use crate::num::math::floor;
use crate::{Grating, Slits};

impl Spectral {
    pub(super) fn exact(&self, grating: &Grating, u: f64) -> DVec3 {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return DVec3::ZERO,
        };
        let q = grating.period_nm() * u;
        if Self::order0_everywhere(grating, q) {
            return self.flat_dvec3();
        }
        if let Some(c) = self.smooth_band(grating, q, n, Limits::EXACT) {
            // N·q up to about 29,000 nm (at most about 45 lobes over the band): the product rule
            // against the tables (`smooth_band`, within 3.5·10⁻¹¹ of the lobe walk).
            return c;
        }
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobes = Lobes::new(self, grating, q, n);
        if Self::is_dense(q) {
            // Too many orders to walk (see `dense`): closed form for the whole periods.
            let n_int = n as u32;
            return self.dense_exact(grating, &lobes, q, n_int, &|l, a, b| filon_walk(l, a, b));
        }
        filon_walk(&lobes, x_lo, x_hi)
    }
}

/// Lobes on each side of every integer x integrated lobe by lobe by `filon_walk`.
/// (The pieces beyond need at least `levin::MIN_LOBES` lobes each: the first is as wide as its
/// distance, WINDOW_LOBES.)
const WINDOW_LOBES: f64 = 4.0;
/// A piece outside the windows spans at most this fraction of its distance to the integer it
/// leaves (or of its end's distance to the integer it approaches): the double pole of R is then
/// at least one width away from it, which the interpolant of `levin::piece` resolves.
const GROWTH: f64 = 1.0;
/// GROWTH for the pieces leaving x = 0, where |dλ/dx| = q/x² makes R's pole of order four:
/// the pole two widths away keeps its interpolant within about 16³·ρ⁻¹⁶ = 5·10⁻¹³ (ρ = 5 + √24).
const GROWTH_ORDER0: f64 = 0.5;
/// Relative tolerance on the window edges.
const EDGE: f64 = 1e-9;
/// A piece spans at most this many periods of the single-slit factor (1/duty in x) and of the
/// envelope's sinc² (q/L in x, L its length).
const SLIT_SPAN: f64 = 0.2;
/// The most pieces the envelope's sinc² asks for over the band: its periods are resolved
/// (`SLIT_SPAN` a piece) up to MAX_ENVELOPE_PIECES·SLIT_SPAN = 51 periods over the band, and
/// beyond that the pieces span more of them, so that the work stays bounded whatever L (a
/// coherence length of N·d with N = 2³² − 1 has 10⁸ periods). The envelope is then at most
/// (360/(π·L))²·λ⁻ᵖ (L > 3.3·10⁴ nm: below 10⁻⁵ of its peak) and is interpolated, not
/// resolved (docs/spectral_strategies.md).
const MAX_ENVELOPE_PIECES: f64 = 256.0;

/// ∫ over [x_lo, x_hi] of the full integrand: lobe by lobe (split at the 1 nm rows, each piece by
/// the rule its width allows) within WINDOW_LOBES lobes of every integer x; elsewhere on pieces
/// graded by the distance to the nearest integer and at most SLIT_SPAN periods of S and of the
/// envelope, across the rows, by `levin::piece` (lobe by lobe where a piece holds fewer than
/// `levin::MIN_LOBES` lobes).
pub(super) fn filon_walk(l: &Lobes<'_>, x_lo: f64, x_hi: f64) -> DVec3 {
    let mut acc = DVec3::ZERO;
    if x_lo.is_nan() || x_hi.is_nan() || x_hi <= x_lo {
        return acc;
    }
    let n = l.n;
    let t = WINDOW_LOBES / n;
    // Cycles per unit x of S and of the envelope's sinc² (sinc²(π·L/λ) = sinc²(π·(L/q)·x)),
    // the latter at most MAX_ENVELOPE_PIECES pieces' worth over the band.
    let envelope = l.s.envelope.band_sinc_cycles() * BAND.min_nm() / l.q;
    let cap = MAX_ENVELOPE_PIECES * SLIT_SPAN / (x_hi - x_lo);
    let cycles = l.duty + envelope.min(cap);
    let slit_span = SLIT_SPAN / cycles.max(1e-300);
    let mut cursor = x_lo;
    while cursor < x_hi {
        let m = floor(cursor);
        let (r_lo, r_hi) = (cursor - m, m + 1.0 - cursor);
        // The window edges m ± t are computed, so compare with a relative tolerance: a cursor
        // left on an edge by rounding must not re-enter the window it has just finished.
        let window_end = if r_lo < t * (1.0 - EDGE) {
            Some(m + t)
        } else if r_hi <= t * (1.0 + EDGE) {
            Some(m + 1.0 + t)
        } else {
            None
        };
        let until = match window_end {
            Some(end) => end,
            None => {
                let graded = if r_lo < 0.5 {
                    let growth = if m == 0.0 { GROWTH_ORDER0 } else { GROWTH };
                    (cursor + growth * r_lo).min(m + 0.5)
                } else {
                    (m + 1.0 - r_hi / (1.0 + GROWTH)).min(m + 1.0 - t)
                };
                graded.min(cursor + slit_span)
            }
        };
        let until = until.min(x_hi);
        // Progress is guaranteed: a piece that would not advance (rounding) is one lobe.
        let (until, lobewise) = if until > cursor {
            (until, window_end.is_some())
        } else {
            ((cursor + 1.0 / n).min(x_hi), true)
        };
        if lobewise || n * (until - cursor) < levin::MIN_LOBES {
            acc += l.graded_lobes(cursor, until);
        } else {
            acc += levin::piece(l, cursor, until);
        }
        cursor = until;
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::Illuminant;

    /// `filon_walk` against the walk of every lobe (8-point rule on each piece between the
    /// zeros of sin(πNx) and the rows, `Lobes::lobes`), relative to each component. Measured
    /// 6.6e-11 (d=740 w=370 N=1000 u=0.9 E, where the lobe walk itself is 6.3e-11 off the
    /// composite rule of `COMPOSITE`); margin 10×.
    const FILON_WALK: f64 = 7e-10;

    #[test]
    fn filon_walk_matches_the_lobe_walk() {
        let mut worst = 0.0f64;
        for ill in [Illuminant::E, Illuminant::D65] {
            let s = Spectral::new(ill);
            for (d, w, n, u) in [
                (400.0, 40.0, 1_000_000u32, 3e-7),
                (400.0, 200.0, 5, 1.9),
                (740.0, 370.0, 1000, 0.9),
                (740.0, 74.0, 30_000, 0.63),
                (1600.0, 800.0, 1000, 1.0),
                (1600.0, 160.0, 30, 1.3),
                (1600.0, 160.0, 1, 0.4),
                (10000.0, 5000.0, 300, 0.7),
                (100000.0, 50000.0, 30, 1.7),
                (100000.0, 10000.0, 3, 0.05),
            ] {
                let g = Grating::new(d, w, n).unwrap();
                let q = d * u;
                let l = Lobes::new(&s, &g, q, n as f64);
                let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
                let want = l.lobes(x_lo, x_hi);
                let got = filon_walk(&l, x_lo, x_hi);
                let rel = ((got - want).abs() / want.abs()).max_element();
                assert!(
                    rel <= FILON_WALK,
                    "{d} {w} {n} {u} {ill:?}: {got} vs {want}"
                );
                worst = worst.max(rel);
            }
        }
        std::println!("filon walk against the lobe walk: worst {worst:.3e}");
    }

    /// `Exact` against an independent composite rule in wavelength: I(u, λ) from
    /// `Grating::intensity`, the weight E·cmf·norm from `Spectral::weight`, 8-point
    /// Gauss-Legendre on equal pieces of each 1 nm row of at most an eighth of a lobe of F_N
    /// (λ²/(8·q·N) at the row's short end), relative to each component. Measured 2.6e-11
    /// (d=100000 w=50000 N=10⁶ u=3e-7 D65); margin 7.7×.
    const COMPOSITE: f64 = 2e-10;

    /// The composite rule of `COMPOSITE` over the band.
    fn composite(s: &Spectral, g: &Grating, u: f64) -> DVec3 {
        use crate::num::quadrature::GL8;
        let q = g.period_nm() * u;
        let n = g.slits().as_f64();
        let mut acc = DVec3::ZERO;
        let (first, last) = (BAND.min_nm() as u32, BAND.max_nm() as u32);
        for row in first..last {
            let lambda = row as f64;
            let pieces = (8.0 * q * n / (lambda * lambda)).ceil().max(1.0) as u32;
            let step = 1.0 / pieces as f64;
            for p in 0..pieces {
                let a = lambda + p as f64 * step;
                let (mid, half) = (a + 0.5 * step, 0.5 * step);
                for (t, w) in GL8.nodes.iter().zip(GL8.weights) {
                    let l = mid + half * t;
                    acc += s.weight(l) * (g.intensity(u, l) * w * half);
                }
            }
        }
        acc
    }

    /// Envelopes of more periods than `MAX_ENVELOPE_PIECES` pieces resolve (51 over the band),
    /// against the composite rule (which resolves every period), relative to the colour itself
    /// up to 200 periods (L = 1.3·10⁵ nm: pieces of 0.8 periods), measured 1.3·10⁻¹¹, and at
    /// 1570 periods (L = 10⁶ nm: 6 periods a piece) relative to the colour without the sinc²
    /// (λ⁻² alone, which the envelope's bound (360/(π·L))² multiplies), measured 9.0·10⁻¹³
    /// (3.0·10⁻⁵ of the colour itself, 3.0·10⁻⁸ of that scale). Margins about 8×. A coherence
    /// length of 10¹² nm (10⁹ periods, which before the cap took hours) returns a colour below
    /// the envelope's bound.
    #[test]
    fn envelopes_of_many_periods() {
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        let with = |length: f64| {
            Spectral::new(Illuminant::D65).with_envelope(crate::Envelope::new(2, length).unwrap())
        };
        for u in [0.37, 1.21] {
            let scale = with(0.0).exact(&g, u).max_element();
            for length in [3.0e4, 4.0e4, 1.3e5, 1e6] {
                let s = with(length);
                let want = composite(&s, &g, u);
                let err = (s.exact(&g, u) - want).abs().max_element();
                let (of_itself, of_plain) = (err / want.max_element(), err / scale);
                std::println!(
                    "u {u} L {length:e}: {of_itself:.2e} of itself, {of_plain:.2e} of λ⁻²'s"
                );
                if length <= 1.3e5 {
                    assert!(of_itself <= 1e-10, "u {u} L {length}: {of_itself:e}");
                } else {
                    assert!(of_plain <= 1e-11, "u {u} L {length}: {of_plain:e}");
                }
            }
        }
        let g = Grating::new(1600.0, 800.0, 1_000_000).unwrap();
        for u in [0.1, 0.9] {
            let scale = with(0.0).exact(&g, u).max_element();
            let got = with(1e12).exact(&g, u).max_element();
            let bound = (830.0 / (core::f64::consts::PI * 1e12)).powi(2) * scale;
            assert!(
                got.is_finite() && got >= 0.0 && got <= bound,
                "{got:e} vs {bound:e}"
            );
        }
    }

    #[test]
    fn exact_matches_a_fine_composite_rule() {
        let mut worst = 0.0f64;
        // D65 with an envelope λ⁻²·sinc²(π·5 µm/λ) too: its 14 periods over the band bound the
        // pieces like S's.
        let enveloped =
            Spectral::new(Illuminant::D65).with_envelope(crate::Envelope::new(2, 5000.0).unwrap());
        for s in [
            Spectral::new(Illuminant::E),
            Spectral::new(Illuminant::D65),
            enveloped,
        ] {
            let ill = (s.illuminant(), s.envelope());
            for (d, w, n, u) in [
                (1600.0, 800.0, 1000u32, 0.37),
                (740.0, 370.0, 1000, 0.9),
                (1600.0, 800.0, 1000, 1.21),
                (1600.0, 800.0, 1000, 1.93),
                (740.0, 370.0, 3000, 0.8),
                (1600.0, 160.0, 100, 1.3),
                (10000.0, 5000.0, 300, 0.7),
                // Order 0's half period only, where |dλ/dx| adds to R's pole at x = 0.
                (1600.0, 1600.0, 30_000, 0.001),
                (100_000.0, 50_000.0, 1_000_000, 3e-7),
            ] {
                let g = Grating::new(d, w, n).unwrap();
                let want = composite(&s, &g, u);
                let got = s.exact(&g, u);
                let rel = ((got - want).abs() / want.abs()).max_element();
                std::println!("{d} {w} {n} {u} {ill:?}: {rel:.2e}");
                assert!(rel <= COMPOSITE, "{d} {w} {n} {u} {ill:?}: {got} vs {want}");
                worst = worst.max(rel);
            }
        }
        std::println!("exact against the composite rule: worst {worst:.3e}");
    }
}
