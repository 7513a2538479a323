//! Order 0's envelope by product integration against the tables: ∫ h/(2 sin²πx) dx over a
//! range of order 0's half period (0 < x ≤ ½), the whole colour of order 0's tail in
//! `Asymptotic`.
//!
//! In the wavelength λ = q/x the integral is ∫ W(λ)·K(λ) dλ with W = E·cmf (the tables' weight,
//! quadratic between the 1 nm rows: a product of two linear interpolants, with kinks at every row
//! and D65's larger ones at its 5 nm nodes) and K(λ) = S(ρ·q/λ)·env(λ)/(2 sin²(π·q/λ)), smooth on
//! the band: its nearest poles are at λ = q/k ≤ q, at least 415 nm from any piece when
//! x ≤ ½ (λ ≥ 2q). The band is cut into fixed pieces of PIECE_NM; on each, K is replaced by its
//! cubic interpolant at the 4 Gauss-Legendre nodes and the product with W integrated exactly, row
//! by row, once per illuminant at compile time (`WEIGHTS`): the rule is Σᵢ K(λᵢ)·Ωᵢ, four
//! evaluations of K per 30 nm and no table look-up, where quadrature in x needs three
//! evaluations of h per 5 nm between D65's nodes. Pieces the range covers only in part are left
//! to the caller.

use glam::DVec3;

use crate::data::cie::Illuminant;
use crate::data::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};

/// Width of a fixed piece, nm (a multiple of D65's 5 nm nodes; the band is 16 pieces, the last
/// one 20 nm).
pub(super) const PIECE_NM: f64 = 30.0;
/// Pieces over the band.
pub(super) const PIECES: usize = 16;
/// Rows of the tables.
const ROWS: usize = (LAST_NM - FIRST_NM) as usize + 1;

/// The 4-point Gauss-Legendre nodes on [−1, 1] (as in `crate::num::quadrature::GL4`).
const T: [f64; 4] = [
    -0.8611363115940526,
    -0.33998104358485626,
    0.33998104358485626,
    0.8611363115940526,
];
/// The 3-point rule that integrates each row's product exactly (degree 2 + 3 ≤ 5).
const T3: [f64; 3] = [-0.7745966692414834, 0.0, 0.7745966692414834];
/// See `T3`.
const W3: [f64; 3] = [0.5555555555555556, 0.8888888888888888, 0.5555555555555556];

/// Product weights Ω[p][i] = ∫_piece W(λ)·ℓᵢ(t(λ)) dλ per channel, ℓᵢ the Lagrange basis
/// polynomial of node i of piece p (t the piece's coordinate on [−1, 1]).
type Weights = [[[f64; 3]; 4]; PIECES];

/// The pieces' bounds: [360 + 30p, min(830, 390 + 30p)].
pub(super) const fn piece_bounds(p: usize) -> (f64, f64) {
    let lo = FIRST_NM as f64 + PIECE_NM * p as f64;
    let hi = lo + PIECE_NM;
    (
        lo,
        if hi > LAST_NM as f64 {
            LAST_NM as f64
        } else {
            hi
        },
    )
}

/// E at row `j` of the illuminant (`None`: E, 1 everywhere).
const fn power_row(table: Option<&[f64; ROWS]>, j: usize) -> f64 {
    match table {
        Some(t) => t[j],
        None => 1.0,
    }
}

/// ℓᵢ(t) for the 4 nodes `T`.
const fn lagrange(i: usize, t: f64) -> f64 {
    let mut v = 1.0;
    let mut j = 0;
    while j < 4 {
        if j != i {
            v *= (t - T[j]) / (T[i] - T[j]);
        }
        j += 1;
    }
    v
}

/// Ω for one illuminant: every row of every piece integrated exactly (the rows are whole nm and
/// the pieces start on them).
const fn weights(table: Option<&[f64; ROWS]>) -> Weights {
    let mut out = [[[0.0; 3]; 4]; PIECES];
    let mut p = 0;
    while p < PIECES {
        let (lo, hi) = piece_bounds(p);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let mut j = (lo - FIRST_NM as f64) as usize;
        let end = (hi - FIRST_NM as f64) as usize;
        while j < end {
            let (e0, e1) = (power_row(table, j), power_row(table, j + 1));
            let (a, b) = (CIE1931_2DEG[j], CIE1931_2DEG[j + 1]);
            let mut k = 0;
            while k < 3 {
                // The row [j, j + 1] in nm: s = ½ + ½·T3[k].
                let s = 0.5 + 0.5 * T3[k];
                let lambda = FIRST_NM as f64 + j as f64 + s;
                let e = e0 + s * (e1 - e0);
                let t = (lambda - mid) / half;
                let mut i = 0;
                while i < 4 {
                    let l = lagrange(i, t) * e * 0.5 * W3[k];
                    let mut c = 0;
                    while c < 3 {
                        out[p][i][c] += l * (a[c] + s * (b[c] - a[c]));
                        c += 1;
                    }
                    i += 1;
                }
                k += 1;
            }
            j += 1;
        }
        p += 1;
    }
    out
}

static WEIGHTS_E: Weights = weights(None);
static WEIGHTS_D65: Weights = weights(Some(&D65));
static WEIGHTS_A: Weights = weights(Some(&ILLUMINANT_A));

fn weights_of(illuminant: Illuminant) -> &'static Weights {
    match illuminant {
        Illuminant::E => &WEIGHTS_E,
        Illuminant::D65 => &WEIGHTS_D65,
        Illuminant::A => &WEIGHTS_A,
    }
}

/// The whole pieces inside [l0, l1] (nm): the first index and one past the last (empty when
/// none).
pub(super) fn whole_pieces(l0: f64, l1: f64) -> (usize, usize) {
    let first = crate::num::math::ceil((l0 - FIRST_NM as f64) / PIECE_NM).max(0.0);
    // A piece p is whole when its upper bound is at most l1.
    let mut last = crate::num::math::floor((l1 - FIRST_NM as f64) / PIECE_NM).max(0.0);
    if l1 >= LAST_NM as f64 {
        last = PIECES as f64;
    }
    let (first, last) = (
        first.min(PIECES as f64) as usize,
        last.min(PIECES as f64) as usize,
    );
    (first, last.max(first))
}

/// Σ over pieces [first, last) of Σᵢ K(λᵢ)·Ωᵢ: ∫ W·K over those pieces for `illuminant`, to
/// the cubic interpolation of K on each.
pub(super) fn integrate<F: Fn(f64) -> f64 + ?Sized>(
    illuminant: Illuminant,
    first: usize,
    last: usize,
    k: &F,
) -> DVec3 {
    let w = weights_of(illuminant);
    let mut acc = DVec3::ZERO;
    for (p, wp) in w.iter().enumerate().take(last).skip(first) {
        let (lo, hi) = piece_bounds(p);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        for (t, wi) in T.iter().zip(wp) {
            acc += DVec3::from_array(*wi) * k(mid + half * t);
        }
    }
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::cie;

    /// The weights integrate W·K exactly for cubic K: against a row-by-row 8-point rule of the
    /// tables' own interpolation (`cie::power_and_cmf`), for K = 1, λ and (λ − 500)³, every
    /// illuminant. Measured 2.4e-15 relative; margin 4×.
    const CUBIC_EXACT: f64 = 1e-14;

    #[test]
    fn weights_integrate_cubics_exactly() {
        use crate::num::quadrature::GL8;
        let mut worst = 0.0f64;
        for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
            let ks: [&dyn Fn(f64) -> f64; 3] = [&|_| 1.0, &|l| l, &|l| {
                (l - 500.0) * (l - 500.0) * (l - 500.0)
            }];
            for k in ks {
                let got = integrate(ill, 0, PIECES, k);
                let mut want = DVec3::ZERO;
                for j in 0..ROWS - 1 {
                    let a = FIRST_NM as f64 + j as f64;
                    for (t, w) in GL8.nodes.iter().zip(GL8.weights) {
                        let l = a + 0.5 + 0.5 * t;
                        let (e, c) = cie::power_and_cmf(ill, l);
                        want += DVec3::from_array(c) * (e * k(l) * 0.5 * w);
                    }
                }
                let scale = want.abs().max_element();
                let rel = (got - want).abs().max_element() / scale;
                assert!(rel <= CUBIC_EXACT, "{ill:?}: {got} vs {want}");
                worst = worst.max(rel);
            }
        }
        std::println!("product weights against the row rule: worst {worst:.2e}");
    }

    #[test]
    fn whole_pieces_cover_exactly_the_inner_pieces() {
        assert_eq!(whole_pieces(360.0, 830.0), (0, PIECES));
        assert_eq!(whole_pieces(361.0, 830.0), (1, PIECES));
        assert_eq!(whole_pieces(360.0, 829.0), (0, PIECES - 1));
        assert_eq!(whole_pieces(400.0, 430.0), (2, 2)); // [390, 420] and [420, 450] are partial
        assert_eq!(whole_pieces(390.0, 450.0), (1, 3));
        assert_eq!(whole_pieces(900.0, 1000.0).0, whole_pieces(900.0, 1000.0).1);
        assert_eq!(piece_bounds(PIECES - 1), (810.0, 830.0));
    }
}
