//! The band inside order 0's half period (d·|u| ≤ 180 nm, so x = d·|u|/λ ≤ ½ at every λ) by
//! product integration against the tables: ∫ W(λ)·K(λ) dλ with W = E·cmf the tables' weight
//! (quadratic between the 1 nm rows, kinks included) and K = S(ρ·q/λ)·F_N(q/λ)·env(λ)·norm,
//! analytic on the band. On each 30 nm piece of `order0`, K is replaced by its interpolant at 16
//! or 32 Chebyshev points (by K's largest local frequency on the piece, 2π·N·q/λ² radians per nm
//! at its short end) and the product with W integrated exactly, with weights computed from the
//! tables at compile time. Where a piece would need more than 32 points (about 80 lobes of F_N
//! over the band) the caller walks the lobes instead.
//!
//! Chebyshev interpolation of e^{iωt} with n points on [−1, 1] is off by about
//! (ω/2)ⁿ/(n!·2ⁿ⁻¹): with ω·(half width) ≤ 0.5 for 8 points, ≤ 5 for 16 and ≤ 21 for 32 that
//! is below 4·10⁻¹² of K's largest value on the piece; `tests` checks the rule against the lobe walk.

use glam::DVec3;

use super::order0::{piece_bounds, PIECES};
use super::{Spectral, BAND};
use crate::cie::Illuminant;
use crate::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};
use crate::kernel::intensity_ratio_flat;
use crate::Grating;

/// Rows of the tables.
const ROWS: usize = (LAST_NM - FIRST_NM) as usize + 1;
/// The largest ω·(half width) of a piece for 8 points (see the module docs: 3·10⁻¹²).
const LIMIT_8: f64 = 0.5;
/// The largest ω·(half width) of a piece for 16 points (see the module docs).
const LIMIT_16: f64 = 5.0;
/// The largest ω·(half width) of a piece for 32 points.
const LIMIT_32: f64 = 21.0;
/// The rule is taken where the spectral envelope's sinc² argument stays below this over the band
/// (no zero in it).
const SINC_CYCLES: f64 = 0.5;

/// The 8 Chebyshev points of the first kind on [−1, 1], cos(π(i + ½)/8), ascending (mpmath).
const T8: [f64; 8] = [
    -0.9807852804032304,
    -0.8314696123025452,
    -0.5555702330196022,
    -0.19509032201612828,
    0.19509032201612828,
    0.5555702330196022,
    0.8314696123025452,
    0.9807852804032304,
];

/// The 16 Chebyshev points of the first kind on [−1, 1], cos(π(i + ½)/16), ascending (mpmath).
const T16: [f64; 16] = [
    -0.9951847266721969,
    -0.9569403357322088,
    -0.881921264348355,
    -0.773010453362737,
    -0.6343932841636455,
    -0.47139673682599764,
    -0.2902846772544624,
    -0.0980171403295606,
    0.0980171403295606,
    0.2902846772544624,
    0.47139673682599764,
    0.6343932841636455,
    0.773010453362737,
    0.881921264348355,
    0.9569403357322088,
    0.9951847266721969,
];

/// The 32 Chebyshev points of the first kind, cos(π(i + ½)/32), ascending (mpmath).
const T32: [f64; 32] = [
    -0.9987954562051724,
    -0.989176509964781,
    -0.970031253194544,
    -0.9415440651830208,
    -0.9039892931234433,
    -0.8577286100002721,
    -0.8032075314806449,
    -0.7409511253549591,
    -0.6715589548470184,
    -0.5956993044924334,
    -0.5141027441932218,
    -0.4275550934302821,
    -0.33688985339222005,
    -0.2429801799032639,
    -0.14673047445536175,
    -0.049067674327418015,
    0.049067674327418015,
    0.14673047445536175,
    0.2429801799032639,
    0.33688985339222005,
    0.4275550934302821,
    0.5141027441932218,
    0.5956993044924334,
    0.6715589548470184,
    0.7409511253549591,
    0.8032075314806449,
    0.8577286100002721,
    0.9039892931234433,
    0.9415440651830208,
    0.970031253194544,
    0.989176509964781,
    0.9987954562051724,
];

/// The 8-point Gauss-Legendre rule (as `crate::quadrature::GL8`) on each half of a row for the
/// weights: a row's quadratic W times a Chebyshev polynomial of degree ≤ 31 over 1/15 of the
/// piece is integrated to rounding (checked in `tests` against the rule on each quarter; on
/// whole rows it left 3·10⁻¹¹).
const G8: [(f64, f64); 8] = [
    (-0.9602898564975363, 0.10122853629037626),
    (-0.7966664774136267, 0.22238103445337448),
    (-0.525532409916329, 0.31370664587788727),
    (-0.1834346424956498, 0.362683783378362),
    (0.1834346424956498, 0.362683783378362),
    (0.525532409916329, 0.31370664587788727),
    (0.7966664774136267, 0.22238103445337448),
    (0.9602898564975363, 0.10122853629037626),
];

/// Product weights of one point set: Ω[p][i] per channel.
type Weights<const K: usize> = [[[f64; 3]; K]; PIECES];

/// Ω[p][i] = ∫_piece W(λ)·ℓᵢ(t(λ)) dλ per channel, ℓᵢ the Lagrange basis polynomial of
/// Chebyshev point i, t the piece's coordinate on [−1, 1]: ℓᵢ = (2/K)·(½ + Σ_{k≥1} T_k(tᵢ)·T_k),
/// so Ωᵢ = (2/K)·(½·M₀ + Σ_{k≥1} T_k(tᵢ)·M_k) with the Chebyshev moments M_k = ∫ W·T_k.
const fn weights<const K: usize>(table: Option<&[f64; ROWS]>, t: &[f64; K]) -> Weights<K> {
    let mut out = [[[0.0; 3]; K]; PIECES];
    let mut p = 0;
    while p < PIECES {
        let (lo, hi) = piece_bounds(p);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        let mut m = [[0.0; 3]; K];
        let mut j = (lo - FIRST_NM as f64) as usize;
        let end = (hi - FIRST_NM as f64) as usize;
        while j < end {
            let (e0, e1) = match table {
                Some(tab) => (tab[j], tab[j + 1]),
                None => (1.0, 1.0),
            };
            let (a, b) = (CIE1931_2DEG[j], CIE1931_2DEG[j + 1]);
            // Each half of the row by the 8-point rule.
            let mut g = 0;
            while g < 16 {
                let s = 0.25 + 0.5 * (g / 8) as f64 + 0.25 * G8[g % 8].0;
                let w = 0.25 * G8[g % 8].1 * (e0 + s * (e1 - e0));
                let x = (FIRST_NM as f64 + j as f64 + s - mid) / half;
                // T_k(x) by the recurrence.
                let (mut t0, mut t1) = (1.0, x);
                let mut k = 0;
                while k < K {
                    let tk = if k == 0 { t0 } else { t1 };
                    let mut c = 0;
                    while c < 3 {
                        m[k][c] += w * tk * (a[c] + s * (b[c] - a[c]));
                        c += 1;
                    }
                    if k >= 1 {
                        let t2 = 2.0 * x * t1 - t0;
                        t0 = t1;
                        t1 = t2;
                    }
                    k += 1;
                }
                g += 1;
            }
            j += 1;
        }
        let mut i = 0;
        while i < K {
            let ti = t[i];
            let (mut t0, mut t1) = (1.0, ti);
            let mut c = 0;
            while c < 3 {
                out[p][i][c] = 0.5 * m[0][c];
                c += 1;
            }
            let mut k = 1;
            while k < K {
                let mut c = 0;
                while c < 3 {
                    out[p][i][c] += t1 * m[k][c];
                    c += 1;
                }
                let t2 = 2.0 * ti * t1 - t0;
                t0 = t1;
                t1 = t2;
                k += 1;
            }
            let mut c = 0;
            while c < 3 {
                out[p][i][c] *= 2.0 / K as f64;
                c += 1;
            }
            i += 1;
        }
        p += 1;
    }
    out
}

static W8_E: Weights<8> = weights(None, &T8);
static W8_D65: Weights<8> = weights(Some(&D65), &T8);
static W8_A: Weights<8> = weights(Some(&ILLUMINANT_A), &T8);
static W16_E: Weights<16> = weights(None, &T16);
static W16_D65: Weights<16> = weights(Some(&D65), &T16);
static W16_A: Weights<16> = weights(Some(&ILLUMINANT_A), &T16);
static W32_E: Weights<32> = weights(None, &T32);
static W32_D65: Weights<32> = weights(Some(&D65), &T32);
static W32_A: Weights<32> = weights(Some(&ILLUMINANT_A), &T32);

/// The weights of the three point sets for `illuminant`.
struct Sets {
    w8: &'static Weights<8>,
    w16: &'static Weights<16>,
    w32: &'static Weights<32>,
}

fn weights_of(illuminant: Illuminant) -> Sets {
    match illuminant {
        Illuminant::E => Sets {
            w8: &W8_E,
            w16: &W16_E,
            w32: &W32_E,
        },
        Illuminant::D65 => Sets {
            w8: &W8_D65,
            w16: &W16_D65,
            w32: &W32_D65,
        },
        Illuminant::A => Sets {
            w8: &W8_A,
            w16: &W16_A,
            w32: &W32_A,
        },
    }
}

/// Σᵢ K(mid + half·tᵢ)·Ωᵢ for one piece.
fn piece_sum<const K: usize>(
    t: &[f64; K],
    w: &[[f64; 3]; K],
    mid: f64,
    half: f64,
    k: &dyn Fn(f64) -> f64,
) -> DVec3 {
    let mut acc = DVec3::ZERO;
    for (t, w) in t.iter().zip(w) {
        acc += DVec3::from_array(*w) * k(mid + half * t);
    }
    acc
}

/// Σ over the pieces of Σᵢ K(λᵢ)·Ωᵢ for K of largest local frequency `frequency`(λ) radians
/// per nm at λ and above; `None` where a piece would need more than 32 points.
fn integrate(
    illuminant: Illuminant,
    frequency: &dyn Fn(f64) -> f64,
    k: &dyn Fn(f64) -> f64,
) -> Option<DVec3> {
    let sets = weights_of(illuminant);
    let mut count = [0usize; PIECES];
    for (p, c) in count.iter_mut().enumerate() {
        let (lo, hi) = piece_bounds(p);
        let wh = frequency(lo) * 0.5 * (hi - lo);
        *c = if wh <= LIMIT_8 {
            8
        } else if wh <= LIMIT_16 {
            16
        } else if wh <= LIMIT_32 {
            32
        } else {
            return None;
        };
    }
    let mut acc = DVec3::ZERO;
    for (p, &c) in count.iter().enumerate() {
        let (lo, hi) = piece_bounds(p);
        let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
        acc += match c {
            8 => piece_sum(&T8, &sets.w8[p], mid, half, k),
            16 => piece_sum(&T16, &sets.w16[p], mid, half, k),
            _ => piece_sum(&T32, &sets.w32[p], mid, half, k),
        };
    }
    Some(acc)
}

impl Spectral {
    /// The colour of `grating` (N = `n` slits) at q = d·|u| by the product rule (module docs)
    /// where the band lies inside order 0's half period and the rule's 32 points per piece
    /// suffice; `None` elsewhere.
    pub(super) fn smooth_band(&self, grating: &Grating, q: f64, n: f64) -> Option<DVec3> {
        if !(q / BAND.min_nm() <= 0.5 && self.envelope.band_sinc_cycles() <= SINC_CYCLES) {
            return None;
        }
        let duty = grating.slit_width_nm() / grating.period_nm();
        let n_int = n as u32;
        let frequency = |l: f64| 2.0 * core::f64::consts::PI * n * q / (l * l);
        let k = |l: f64| {
            let x = q / l;
            let (num, den) = intensity_ratio_flat(x, duty * x, n_int);
            let r = num / den;
            (r * r).min(1.0) * self.envelope_norm(l)
        };
        integrate(self.illuminant, &frequency, &k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::lobes::Lobes;

    /// The weights against a row-by-row 16-point rule of the tables' own interpolation for K =
    /// T_31 on every piece (the highest degree the 32 points integrate exactly), every
    /// illuminant, relative to Σ|Ωᵢ|. Measured 2.1e-14; margin 10×.
    const WEIGHTS_EXACT: f64 = 2e-13;
    /// The rule against the lobe walk of the same integrand (`Lobes::lobes`: 8 points on every
    /// piece between the zeros of sin(πNx) and the 1 nm rows), relative to each component.
    /// Measured 3.5e-11 (d = 10 µm, N = 300, u = 0.003, E); margin 9×.
    const AGAINST_LOBES: f64 = 3e-10;

    #[test]
    fn weights_integrate_the_highest_degree_exactly() {
        let gl8 = crate::quadrature::GL8; // on each quarter of a row
        let mut worst = 0.0f64;
        for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
            let w32 = weights_of(ill).w32;
            for (p, wp) in w32.iter().enumerate() {
                let (lo, hi) = piece_bounds(p);
                let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
                let cheb = |l: f64| {
                    let x = (l - mid) / half;
                    (31.0 * x.clamp(-1.0, 1.0).acos()).cos()
                };
                let got: DVec3 = T32
                    .iter()
                    .zip(wp)
                    .map(|(t, w)| DVec3::from_array(*w) * cheb(mid + half * t))
                    .sum();
                let mut want = DVec3::ZERO;
                let mut a = lo;
                while a < hi {
                    for (c, h) in [0.125, 0.375, 0.625, 0.875].map(|f| (a + f, 0.125)) {
                        for (t, w) in gl8.nodes.iter().zip(gl8.weights) {
                            let l = c + h * t;
                            let (e, cmf) = crate::cie::power_and_cmf(ill, l);
                            want += DVec3::from_array(cmf) * (e * cheb(l) * h * w);
                        }
                    }
                    a += 1.0;
                }
                let scale = wp
                    .iter()
                    .map(|w| DVec3::from_array(*w).abs().max_element())
                    .sum::<f64>();
                let rel = (got - want).abs().max_element() / scale;
                assert!(rel <= WEIGHTS_EXACT, "{ill:?} piece {p}: {got} vs {want}");
                worst = worst.max(rel);
            }
        }
        std::println!("Chebyshev product weights: worst {worst:.2e}");
    }

    #[test]
    fn the_rule_matches_the_lobe_walk() {
        let mut worst = 0.0f64;
        for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
            let s = Spectral::new(ill);
            for (d, w, n, u) in [
                (1600.0, 800.0, 1000u32, 1e-8),
                (1600.0, 800.0, 1000, 1e-4),
                (1600.0, 800.0, 1000, 2e-3),
                (1600.0, 800.0, 1000, 1.5e-2),
                (740.0, 74.0, 30, 0.2),
                (400.0, 200.0, 5, 0.44),
                (10_000.0, 5000.0, 300, 3e-3),
                (100_000.0, 10_000.0, 1_000_000, 1e-7),
            ] {
                let g = Grating::new(d, w, n).unwrap();
                let q = d * u;
                let Some(got) = s.smooth_band(&g, q, n as f64) else {
                    panic!("{d} {n} {u}: outside the rule");
                };
                let l = Lobes::new(&s, &g, q, n as f64);
                let want = l.lobes(q / BAND.max_nm(), q / BAND.min_nm());
                let rel = ((got - want).abs() / want.abs()).max_element();
                assert!(
                    rel <= AGAINST_LOBES,
                    "{ill:?} {d} {w} {n} {u}: {got} vs {want}"
                );
                worst = worst.max(rel);
            }
        }
        std::println!("smooth band against the lobe walk: worst {worst:.2e}");
    }

    #[test]
    fn the_rule_declines_beyond_its_points_and_order_0() {
        let s = Spectral::new(Illuminant::D65);
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        assert!(s.smooth_band(&g, 1600.0 * 0.05, 1000.0).is_none()); // ~130 lobes
        assert!(s.smooth_band(&g, 200.0, 1000.0).is_none()); // order 1 in the band
    }
}
