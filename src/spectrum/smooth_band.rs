//! The band by product integration against the tables, where K = S·F_N oscillates slowly
//! enough: ∫ W(λ)·K(λ) dλ with W = E·cmf the tables' weight (quadratic between the 1 nm rows,
//! kinks included) and K = S(ρ·q/λ)·F_N(q/λ)·env(λ)·norm, analytic on the band (S·F_N is a
//! trigonometric polynomial of frequency at most N − 1 + ρ ≤ N in x times a power of x, so its
//! local frequency in λ is at most 2π·N·q/λ² radians per nm, largest at the band's short end).
//! On each 30 nm piece of `order0`, K is replaced by its interpolant at 8, 16 or 32 Chebyshev
//! points, or at `order0`'s 4 Gauss-Legendre points (by ω·h, that frequency at the piece's short
//! end times its half width, against the [`Limits`]), and the product with W integrated
//! exactly, with weights computed from the tables at compile time. Where the first piece would
//! need more than 32 points (N·q above about 29,000 nm for `Exact`, 47,000 nm for
//! `Asymptotic`) the caller walks the lobes instead.
//!
//! Chebyshev interpolation of e^{iωt} at n points on [−1, 1] is off by about 2·J_n(ω) of its
//! amplitude (7.5·10⁻¹⁰ for n = 8, ω = ½; 1.1·10⁻⁴ for n = 32, ω = 21), but the error
//! oscillates as fast as K and integrates against the smooth W to far less: at the limits of
//! [`Limits::EXACT`] the rule is within 3.5·10⁻¹¹ of the lobe walk, at those of
//! [`Limits::FAST`] within 4.3·10⁻⁶ (`tests`, which put the band's first piece at each limit).

use glam::DVec3;

use super::order0::{self, piece_bounds, PIECES};
use super::Spectral;
use crate::data::cie::Illuminant;
use crate::data::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};
use crate::num::kernel::intensity_ratio_flat;
use crate::Grating;

/// Rows of the tables.
const ROWS: usize = (LAST_NM - FIRST_NM) as usize + 1;

/// The largest ω·h of a piece (its largest local frequency times its half width) for 8, 16 and
/// 32 points (see the module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct Limits {
    l4: f64,
    l8: f64,
    l16: f64,
    l32: f64,
}

impl Limits {
    /// `Exact`'s: within 3.5·10⁻¹¹ of the lobe walk (measured at each limit, `tests`).
    pub(super) const EXACT: Limits = Limits {
        l4: L4_EXACT,
        l8: 0.5,
        l16: 5.0,
        l32: 21.0,
    };
    /// `Asymptotic`'s, far inside its own bound (`bounds::ASYMPTOTIC_ORDER0`, 2·10⁻⁴): measured
    /// at each limit 4.7·10⁻⁸ (4 points), 7.6·10⁻⁸ (8), 2.7·10⁻⁷ (16) and 4.3·10⁻⁶ (32) of the
    /// lobe walk.
    pub(super) const FAST: Limits = Limits {
        l4: L4_FAST,
        l8: 3.0,
        l16: 12.0,
        l32: 34.0,
    };
}

/// ω·h up to which `order0`'s cubic rule (4 Gauss-Legendre points) takes a piece: none for
/// `Exact` (there the cubic rule would leave 3·10⁻¹¹ at ω·h = 0.02, and 5·10⁻¹³ of one slit's
/// colour, which `Exact` gives to rounding); 0.5 for `Asymptotic` (measured 4.7·10⁻⁸ at it).
const L4_EXACT: f64 = 0.0;
/// See L4_EXACT.
const L4_FAST: f64 = 0.5;
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

/// The 8-point Gauss-Legendre rule (as `crate::num::quadrature::GL8`) on each half of a row for the
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

/// Σᵢ K(mid + half·tᵢ)·Ωᵢ for one piece, four points side by side (K is a chain of dependent
/// operations: four independent chains keep the processor busy).
#[inline(always)]
fn piece_sum<const K: usize, F: Fn(f64) -> f64>(
    t: &[f64; K],
    w: &[[f64; 3]; K],
    mid: f64,
    half: f64,
    k: &F,
) -> DVec3 {
    let mut acc = [DVec3::ZERO; 4];
    for (t, w) in t.chunks_exact(4).zip(w.chunks_exact(4)) {
        let v = [0, 1, 2, 3].map(|i| k(mid + half * t[i]));
        for i in 0..4 {
            acc[i] += DVec3::from_array(w[i]) * v[i];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3])
}

/// The number of points the product rule takes on a piece of half width `half` nm whose
/// largest local frequency is `frequency` radians per nm (4, 8, 16 or 32); `None` where 32 do
/// not suffice under `limits`.
pub(super) fn piece_points(limits: Limits, frequency: f64, half: f64) -> Option<usize> {
    let wh = frequency * half;
    if wh <= limits.l4 {
        Some(4)
    } else if wh <= limits.l8 {
        Some(8)
    } else if wh <= limits.l16 {
        Some(16)
    } else if wh <= limits.l32 {
        Some(32)
    } else {
        None
    }
}

/// Σᵢ K(λᵢ)·Ωᵢ on piece `p` with `points` points (4, 8, 16 or 32, from `piece_points`): ∫ W·K
/// over the piece, to the interpolation of K.
pub(super) fn piece_rule<F: Fn(f64) -> f64>(
    illuminant: Illuminant,
    p: usize,
    points: usize,
    k: &F,
) -> DVec3 {
    let sets = weights_of(illuminant);
    let (lo, hi) = piece_bounds(p);
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    match points {
        4 => order0::integrate(illuminant, p, p + 1, k),
        8 => piece_sum(&T8, &sets.w8[p], mid, half, k),
        16 => piece_sum(&T16, &sets.w16[p], mid, half, k),
        _ => piece_sum(&T32, &sets.w32[p], mid, half, k),
    }
}

/// Σ over the pieces from `first` on of Σᵢ K(λᵢ)·Ωᵢ for K of largest local frequency
/// `frequency`(λ) radians per nm at λ and above; `None` where a piece would need more than 32
/// points under `limits`.
fn integrate<F: Fn(f64) -> f64>(
    illuminant: Illuminant,
    limits: Limits,
    first: usize,
    frequency: &dyn Fn(f64) -> f64,
    k: &F,
) -> Option<DVec3> {
    let mut count = [0usize; PIECES];
    for (p, c) in count.iter_mut().enumerate().skip(first) {
        let (lo, hi) = piece_bounds(p);
        *c = piece_points(limits, frequency(lo), 0.5 * (hi - lo))?;
    }
    let mut acc = DVec3::ZERO;
    for (p, &c) in count.iter().enumerate().skip(first) {
        acc += piece_rule(illuminant, p, c, k);
    }
    Some(acc)
}

impl Spectral {
    /// The colour of `grating` (N = `n` slits) at q = d·|u| by the product rule (module docs)
    /// where its 32 points per piece suffice under `limits` and the spectral envelope is smooth
    /// over the band; `None` elsewhere.
    pub(super) fn smooth_band(
        &self,
        grating: &Grating,
        q: f64,
        n: f64,
        limits: Limits,
    ) -> Option<DVec3> {
        self.smooth_pieces(grating, q, n, limits, 0)
    }

    /// [`smooth_band`](Self::smooth_band) over the fixed pieces from `first` on (the band's
    /// long-wavelength end from `order0::piece_bounds(first).0` nm; nothing for `first` ≥
    /// `PIECES`).
    pub(super) fn smooth_pieces(
        &self,
        grating: &Grating,
        q: f64,
        n: f64,
        limits: Limits,
        first: usize,
    ) -> Option<DVec3> {
        if !(q.is_finite() && self.envelope.band_sinc_cycles() <= SINC_CYCLES) {
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
        integrate(self.illuminant, limits, first, &frequency, &k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::lobes::Lobes;
    use crate::spectrum::BAND;

    /// The weights against a row-by-row 16-point rule of the tables' own interpolation for K =
    /// T_31 on every piece (the highest degree the 32 points integrate exactly), every
    /// illuminant, relative to Σ|Ωᵢ|. Measured 2.1e-14; margin 10×.
    const WEIGHTS_EXACT: f64 = 2e-13;
    /// The rule against the lobe walk of the same integrand (`Lobes::lobes`: 8 points on every
    /// piece between the zeros of sin(πNx) and the 1 nm rows), relative to each component, for
    /// [`Limits::EXACT`]. Measured 3.5e-11 (d = 10 µm, N = 300, u = 0.003, E); margin 9×.
    const AGAINST_LOBES: f64 = 3e-10;
    /// The same for [`Limits::FAST`], with the band's first piece at each limit. Measured
    /// 4.3e-6 (32 points, d = 1600 nm, N = 1000); margin 7×.
    const FAST_AGAINST_LOBES: f64 = 3e-5;

    /// u that puts the band's first piece of a grating (d, N) at ω·h = `limit` (just inside).
    fn u_at_limit(d: f64, n: u32, limit: f64) -> f64 {
        let (lo, hi) = piece_bounds(0);
        let per_q = 2.0 * core::f64::consts::PI * n as f64 / (lo * lo) * 0.5 * (hi - lo);
        limit / per_q / d * (1.0 - 1e-9)
    }

    #[test]
    fn weights_integrate_the_highest_degree_exactly() {
        let gl8 = crate::num::quadrature::GL8; // on each quarter of a row
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
                            let (e, cmf) = crate::data::cie::power_and_cmf(ill, l);
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

    /// The rule against the lobe walk for `limits` on `cases` (d, w, N, u), every illuminant;
    /// the worst relative error.
    fn against_lobes(limits: Limits, cases: &[(f64, f64, u32, f64)], bound: f64) -> f64 {
        let mut worst = 0.0f64;
        for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
            let s = Spectral::new(ill);
            for &(d, w, n, u) in cases {
                let g = Grating::new(d, w, n).unwrap();
                let q = d * u;
                let Some(got) = s.smooth_band(&g, q, n as f64, limits) else {
                    panic!("{d} {n} {u}: outside the rule");
                };
                let l = Lobes::new(&s, &g, q, n as f64);
                let want = l.lobes(q / BAND.max_nm(), q / BAND.min_nm());
                let rel = ((got - want).abs() / want.abs()).max_element();
                assert!(rel <= bound, "{ill:?} {d} {w} {n} {u}: {got} vs {want}");
                worst = worst.max(rel);
            }
        }
        worst
    }

    #[test]
    fn the_rule_matches_the_lobe_walk() {
        let limits = Limits::EXACT;
        let cases = [
            (1600.0, 800.0, 1000u32, 1e-8),
            (1600.0, 800.0, 1000, 1e-4),
            (1600.0, 800.0, 1000, 2e-3),
            (1600.0, 800.0, 1000, 1.5e-2),
            (740.0, 74.0, 30, 0.2),
            (400.0, 200.0, 5, 0.44),
            (10_000.0, 5000.0, 300, 3e-3),
            (100_000.0, 10_000.0, 1_000_000, 1e-7),
            // Orders in the band (x > ½) and a single slit.
            (10_000.0, 5000.0, 5, 0.5),
            (10_000.0, 5000.0, 20, 0.12),
            (3000.0, 1000.0, 1, 1.9),
            (3000.0, 1000.0, 10, u_at_limit(3000.0, 10, limits.l32)),
            // Each limit.
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l8)),
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l16)),
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l32)),
        ];
        let worst = against_lobes(limits, &cases, AGAINST_LOBES);
        std::println!("smooth band against the lobe walk: worst {worst:.2e}");
    }

    #[test]
    fn the_fast_rule_matches_the_lobe_walk_at_its_limits() {
        let limits = Limits::FAST;
        let cases = [
            (1600.0, 800.0, 1000u32, u_at_limit(1600.0, 1000, limits.l4)),
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l8)),
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l16)),
            (1600.0, 800.0, 1000, u_at_limit(1600.0, 1000, limits.l32)),
            // Orders in the band (x > ½) and a single slit.
            (10_000.0, 5000.0, 5, u_at_limit(10_000.0, 5, limits.l32)),
            (3000.0, 1000.0, 10, u_at_limit(3000.0, 10, limits.l16)),
            (10_000.0, 5000.0, 5, 0.5),
            (10_000.0, 5000.0, 20, 0.15),
            (3000.0, 1000.0, 1, 1.9),
        ];
        let worst = against_lobes(limits, &cases, FAST_AGAINST_LOBES);
        std::println!("fast smooth band against the lobe walk: worst {worst:.2e}");
    }

    #[test]
    fn the_rule_declines_beyond_its_points() {
        let s = Spectral::new(Illuminant::D65);
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        assert!(s
            .smooth_band(&g, 1600.0 * 0.05, 1000.0, Limits::FAST)
            .is_none()); // ~130 lobes
        for limits in [Limits::EXACT, Limits::FAST] {
            let u = u_at_limit(1600.0, 1000, limits.l32);
            assert!(s.smooth_band(&g, 1600.0 * u, 1000.0, limits).is_some());
            let above = 1600.0 * u * (1.0 + 1e-6);
            assert!(s.smooth_band(&g, above, 1000.0, limits).is_none());
        }
    }
}
