//! The albedo of the grating: the part of every lobe inside the disk D of directions above the
//! surface, in closed form for delta lobes and by quadrature matched to F_N otherwise.

use glam::DVec3;

use super::order_weights::OrderSource;
use super::GratingBsdf;
use crate::model::MIN_COS_THETA;
use crate::num::kernel::single_slit_cycles;
use crate::num::math;
use crate::num::quadrature::{gl8, Value};
use crate::optics::groove::GrooveKind;
use crate::{GrooveSpread, Slits};
use core::f64::consts::PI;

/// [`GratingBsdf::albedo`] returns `None` above this many candidate orders.
pub(crate) const MAX_ALBEDO_ORDERS: i64 = 512;

/// A period whose centre is within this many periods of a cut (the disk's edge, or the step of
/// the chord's mass where its end crosses v = 0) is integrated lobe by lobe; farther ones by
/// the moment rule ([`GratingBsdf::albedo`]). At 2.5 periods the nearest singularity of the
/// integrand is 5 half-periods from the period's centre, where degree-15 interpolation
/// converges like 10⁻¹⁵.
pub(crate) const ALBEDO_CUT_MARGIN: f64 = 2.5;

/// The step of the chord's mass is that many groove widths (the Cauchy proxy's scale) wide in
/// v: beyond this many widths of it the mass is smooth on the scale of a period.
const GROOVE_WIDTHS: f64 = 8.0;

/// The largest ripple of the chord's mass (relative to the albedo) left to the moment rule.
const RIPPLE: f64 = 1e-10;

/// Points of the moment rule.
const MOMENT_POINTS: usize = 16;

/// The width, in v, of one piece of a conical table's albedo integrand across the groove
/// lobe's proxy scale: the lobe is cut into ⌈s/this⌉ pieces of equal proxy mass (one where
/// s ≤ this: the lobe's centre). The CD at N = 1 (s = 0.107 at 450 nm) then takes 64 pieces:
/// its albedo 0.7419 against 0.7415 with 256 and 0.731 with 16 ([`GratingBsdf::albedo`]).
const V_PIECE_SCALE: f64 = 1.6e-3;
/// The most pieces across the groove lobe (N = 1: s = 1.2·λ/(π·d)).
const MAX_V_PIECES: f64 = 64.0;

impl GratingBsdf {
    /// The albedo ∫ f·cos θi dωi for light leaving toward `wo` at λ: the part of every lobe
    /// inside the disk D (see the [module docs](super)); at most ρ = w/d. `None` when more than
    /// `MAX_ALBEDO_ORDERS` orders are candidates; 0 below the surface.
    ///
    /// N = ∞: the closed form Σ_m η_m·∫ g over the chord of D at u = m·λ/d (by
    /// [`GrooveSpread::mass`](crate::GrooveSpread::mass)). Finite N: the periods within
    /// `ALBEDO_CUT_MARGIN` periods (or 8 groove widths) of a place where the chord starts,
    /// stops or steps are integrated lobe by lobe: Gauss-Legendre (8 points) on every side lobe
    /// of F_N out to 64 lobes from the peak (all of them for N ≤ 128), and beyond them F_N
    /// replaced by its local mean 1/(2N²·sin²(π·r)) on 24 geometric pieces (the error of that
    /// average is below 1/(2π²·64³) of the lobe's area), the pieces split where the chord
    /// meets the edge of D; so are the periods where a coherence length's rippling sinc² tails
    /// make the chord's mass ripple by more than 10⁻¹⁰ (λ/(π²·L·h_v) for a chord of half-length
    /// h_v: L beyond about 10¹⁰·λ). Every other period, where the integrand without F_N is smooth, by a
    /// 16-point rule exact for N·F_N times polynomials of degree 15 (the kernel's Legendre
    /// moments, integrated once per call by the lobe-by-lobe rule): 16 evaluations per order
    /// instead of about 1400, so 512 orders cost a few tens of milliseconds. Relative accuracy
    /// about 10⁻⁶ (tests compare with an independent quadrature of `f`, and the 16-point rule
    /// with the lobe-by-lobe rule on every period).
    ///
    /// A tabulated model (`OrderEfficiency::Tabulated`, feature `relief`): the same
    /// rules with ρ²·S replaced by η̃_m(u, v) = min(η_m(wo.x − u, wo.y − v, λ),
    /// η_m(−wo.x, −wo.y, λ)), every period lobe by lobe (η̃ has the table's kinks). A classical
    /// table ignores v; a conical one is integrated across the groove lobe too: the chord is cut
    /// into ⌈s/(1.6·10⁻³)⌉ pieces (at most 64) of equal mass of the groove's Cauchy proxy of
    /// scale s, each piece's mass of g times η̃ at the proxy's median in it (one piece, the
    /// lobe's centre v = 0, for narrow lobes: s ≤ 1.6·10⁻³). For N = 1, whose lobe is about
    /// λ/d wide in v, the lobe's centre alone was 1-5 % off (the conical test table 0.890
    /// against a furnace of 0.846 ± 0.002, the CD as `GratingBsdf::preset` reads it 0.751
    /// against 0.742 ± 0.002 at normal incidence and 450 nm), 16 pieces 1.4 % (0.731); 64
    /// pieces give 0.7419 and 256 give 0.7415. That costs about 0.26 s an albedo for the CD at
    /// N = 1 (5 ms at N = 30, 3 pieces). At most Σ_m η_m(−wo.x, −wo.y, λ) ≤ 1. For N = ∞:
    /// Σ_m η̃_m·∫ g over the chord (the ideal groove: its centre). Measured against the
    /// Monte-Carlo furnace within 1.75
    /// standard errors (`tests/bsdf_efficiency.rs`).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// // Normal incidence at 550 nm: orders −2 … 2 propagate (|m|·λ/d < 1); 0 and ±1 carry light.
    /// let want = b.efficiency(0) + 2.0 * b.efficiency(1) + 2.0 * b.efficiency(2);
    /// assert!((b.albedo(DVec3::Z, 550.0).unwrap() - want).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn albedo(&self, wo: DVec3, lambda_nm: f64) -> Option<f64> {
        self.albedo_by(wo, lambda_nm, true)
    }

    /// [`albedo`](Self::albedo), with the moment rule on the periods far from the cuts
    /// (`moments`) or the lobe-by-lobe rule on every period.
    fn albedo_by(&self, wo: DVec3, lambda_nm: f64, moments: bool) -> Option<f64> {
        if !(wo.z >= MIN_COS_THETA && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return Some(0.0);
        }
        let step = lambda_nm / self.grating.period_nm();
        let Some((lo, hi)) = OrderSource::range(
            self.grating.slits(),
            wo,
            self.grating.period_nm() / lambda_nm,
        ) else {
            return Some(0.0);
        };
        if hi - lo + 1 > MAX_ALBEDO_ORDERS {
            return None;
        }
        let rho = self.grating.open_fraction();
        // A tabulated model: the order weights η_m(−wo.x, λ) of the candidates, and η̃_m at u
        // (the min with η_m(−wi.x, λ), wi.x = u − wo.x); every period lobe by lobe (η̃ has the
        // table's kinks).
        let tab = match self.orders {
            OrderSource::Amplitude(_) => None,
            OrderSource::Tabulated { .. } => match self.tabulated_etas(wo, lambda_nm) {
                Some(o) => Some(o),
                None => return Some(0.0),
            },
        };
        let moments = moments && tab.is_none();
        // A conical table's η̃ depends on wi.y = v − wo.y: the chord is cut into pieces of
        // equal mass of the groove's Cauchy proxy (scale s), each read at its proxy median;
        // one piece (the lobe's centre v = 0) where the lobe is narrow.
        let scale = self.groove.proxy_scale(lambda_nm);
        let pieces = match &tab {
            Some(o) if o.conical() && scale > 0.0 => {
                math::ceil(scale / V_PIECE_SCALE).clamp(1.0, MAX_V_PIECES)
            }
            _ => 1.0,
        };
        // ∫ g·η̃_m over the chord of D at u (tabulated), or ∫ g (the amplitude reading).
        let chord = |m: i64, u: f64| {
            let a = u - wo.x;
            let h2 = 1.0 - a * a;
            if h2 <= 0.0 {
                return 0.0;
            }
            let h = math::sqrt(h2);
            let (v0, v1) = (wo.y - h, wo.y + h);
            let Some(o) = &tab else {
                return self.groove.mass(v0, v1, lambda_nm);
            };
            if pieces == 1.0 {
                return o.eta_at(m, u, 0.0, wo, lambda_nm) * self.groove.mass(v0, v1, lambda_nm);
            }
            let quantile = |t: f64| GrooveSpread::sample_scaled(t, scale).clamp(v0, v1);
            let (mut sum, mut lo, mut j) = (0.0, v0, 1.0);
            while j <= pieces {
                let hi = if j == pieces {
                    v1
                } else {
                    quantile(j / pieces)
                };
                if hi > lo {
                    let mass = self.groove.mass(lo, hi, lambda_nm);
                    if mass > 0.0 {
                        let at = quantile((j - 0.5) / pieces).clamp(lo, hi);
                        sum += mass * o.eta_at(m, u, at, wo, lambda_nm);
                    }
                    lo = hi;
                }
                j += 1.0;
            }
            sum
        };
        let mut sum = 0.0;
        match self.grating.slits() {
            Slits::Infinite => {
                for m in lo..=hi {
                    let u = m as f64 * step;
                    let e = if tab.is_some() {
                        1.0
                    } else {
                        rho * rho * single_slit_cycles(rho * m as f64)
                    };
                    sum += e * chord(m, u);
                }
            }
            Slits::Finite(n) => {
                // Where the chord starts or stops: |u − wo.x| = 1, and for an ideal groove
                // |u − wo.x| = √(1 − wo.y²) (the step of C).
                // Where the chord's end crosses v = 0 (the centre of g): a step for an ideal
                // groove, a steep rise of width about the groove's width otherwise.
                let e = math::sqrt((1.0 - wo.y * wo.y).max(0.0));
                let edges = [wo.x - 1.0, wo.x + 1.0, wo.x - e, wo.x + e];
                let nf = n as f64;
                // The step at the chord's v = 0 crossing is a few groove widths wide in v,
                // dv/du = |u − wo.x|/√(1 − (u − wo.x)²) = e/|wo.y| there.
                let groove_du = match self.groove.proxy_scale(lambda_nm) {
                    s if s > 0.0 && wo.y != 0.0 => GROOVE_WIDTHS * s * wo.y.abs() / e.max(1e-300),
                    _ => 0.0,
                };
                let margin = [
                    ALBEDO_CUT_MARGIN,
                    ALBEDO_CUT_MARGIN,
                    ALBEDO_CUT_MARGIN + groove_du / step,
                    ALBEDO_CUT_MARGIN + groove_du / step,
                ];
                let mut rule: Option<MomentRule> = None;
                for m in lo..=hi {
                    if tab.as_ref().is_some_and(|o| o.eta_wo(m) == 0.0) {
                        // f = 0 on the period (η̃ ≤ η_m(−wo.x) = 0).
                        continue;
                    }
                    let h = |r: f64| {
                        let x = m as f64 + r;
                        if tab.is_some() {
                            chord(m, x * step)
                        } else {
                            rho * rho * single_slit_cycles(rho * x) * chord(m, x * step)
                        }
                    };
                    let mut cuts = [f64::NAN; 4];
                    let mut near = false;
                    for (k, e) in edges.iter().enumerate() {
                        let r = e / step - m as f64;
                        if r > -0.5 && r < 0.5 {
                            cuts[k] = r;
                        }
                        // NaN (an edge beyond f64) counts as near.
                        near |= !moments || r.abs() < margin[k] || r.is_nan();
                    }
                    // A coherence length's sinc² has rippling tails, so the chord's mass
                    // ripples in u with amplitude about λ/(π²·L·h_v) (h_v the chord's half-length
                    // in v), up to 2·N·|u − wo.x|/h_v times per period: the moment rule only where
                    // that amplitude is negligible.
                    if let GrooveKind::CoherenceLength { length_nm } = self.groove.kind() {
                        let a = m as f64 * step - wo.x;
                        let hv = math::sqrt((1.0 - a * a).max(0.0));
                        near |= lambda_nm > RIPPLE * PI * PI * length_nm * hv || hv.is_nan();
                    }
                    sum += if near {
                        period_integral(nf, &cuts, &h)
                    } else {
                        rule.get_or_insert_with(|| MomentRule::new(nf)).apply(&h)
                    };
                }
            }
        }
        let cap = match &tab {
            Some(o) => o.total.min(1.0),
            None => rho,
        };
        Some(sum.clamp(0.0, cap))
    }
}

/// ∫_{−½}^{½} N·F_N(π·r)·h(r) dr for a smooth h, with the pieces also split at `cuts`
/// (NaN entries ignored). See [`GratingBsdf::albedo`].
fn period_integral<T: Value>(n: f64, cuts: &[f64; 4], h: &dyn Fn(f64) -> T) -> T {
    const RESOLVED: f64 = 64.0;
    const FULL: f64 = 128.0;
    const TAIL_PIECES: u32 = 24;
    let fejer = |r: f64| {
        // N·F_N(π r): exact F_N through the kernel, in cycles.
        n * crate::num::kernel::n_slit_cycles(r, n as u32)
    };
    let tail = |r: f64| {
        let s = crate::num::kernel::sinpi(r);
        1.0 / (2.0 * n * s * s)
    };
    let mut sum = T::ZERO;
    // Resolved zone: every side lobe [k/N, (k+1)/N] out to `RESOLVED` lobes (or all).
    let lobes = if n <= FULL {
        math::floor(n / 2.0)
    } else {
        RESOLVED
    };
    let edge = if n <= FULL { 0.5 } else { RESOLVED / n };
    let mut piece = |a: f64, b: f64, w: &dyn Fn(f64) -> f64| {
        // Split [a, b] at the cuts, then 8-point Gauss-Legendre on each part.
        let mut pts = [a, b, f64::NAN, f64::NAN, f64::NAN, f64::NAN];
        let mut k = 2;
        for &c in cuts {
            if c > a && c < b {
                pts[k] = c;
                k += 1;
            }
        }
        let pts = &mut pts[..k];
        pts.sort_unstable_by(|x, y| x.partial_cmp(y).unwrap_or(core::cmp::Ordering::Equal));
        for j in 0..k - 1 {
            let (p0, p1) = (pts[j], pts[j + 1]);
            let f = |r: f64| h(r) * w(r);
            let at_cut = |p: f64| cuts.contains(&p);
            sum = sum
                + match (at_cut(p0), at_cut(p1)) {
                    (true, false) => graded(p0, p1, &f),
                    (false, true) => graded(p1, p0, &f),
                    (true, true) => {
                        let mid = 0.5 * (p0 + p1);
                        graded(p0, mid, &f) + graded(p1, mid, &f)
                    }
                    (false, false) => {
                        // Pieces longer than 1/64 of a period (small N) are split.
                        let k = math::ceil((p1 - p0) * 64.0).max(1.0);
                        let h = (p1 - p0) / k;
                        let mut acc = T::ZERO;
                        let mut j = 0.0;
                        while j < k {
                            acc = acc + gl8(p0 + j * h, p0 + (j + 1.0) * h, &f);
                            j += 1.0;
                        }
                        acc
                    }
                };
        }
    };
    let nl = lobes as u32;
    for side in [-1.0, 1.0] {
        for k in 0..nl {
            let (a, b) = (k as f64 / n, ((k + 1) as f64 / n).min(0.5));
            if side > 0.0 {
                piece(a, b, &fejer);
            } else {
                piece(-b, -a, &fejer);
            }
        }
        // For even N ≤ 128 the last lobe ends at ½ exactly; odd N leaves [⌊N/2⌋/N, ½].
        let resolved_end = (lobes / n).min(0.5);
        if n <= FULL {
            if resolved_end < 0.5 {
                if side > 0.0 {
                    piece(resolved_end, 0.5, &fejer);
                } else {
                    piece(-0.5, -resolved_end, &fejer);
                }
            }
        } else {
            // Averaged tail on geometric pieces from edge to ½.
            let ratio = math::powf(0.5 / edge, 1.0 / TAIL_PIECES as f64);
            let mut a = edge;
            for j in 0..TAIL_PIECES {
                let b = if j + 1 == TAIL_PIECES { 0.5 } else { a * ratio };
                if side > 0.0 {
                    piece(a, b, &tail);
                } else {
                    piece(-b, -a, &tail);
                }
                a = b;
            }
        }
    }
    sum
}

/// ∫ between `at` (a cut: the disk's edge, where the integrand behaves like a square root, or
/// the steep rise of the chord's mass) and `to` on 16 pieces graded geometrically (ratio ½)
/// toward `at`, the innermost with the substitution r = at + (to − at)·s² that makes a
/// square-root end smooth.
fn graded<T: Value>(at: f64, to: f64, f: &dyn Fn(f64) -> T) -> T {
    const LEVELS: i32 = 16;
    let len = to - at;
    let mut sum = T::ZERO;
    let mut outer = 1.0;
    for _ in 0..LEVELS {
        let inner = 0.5 * outer;
        let (a, b) = (at + inner * len, at + outer * len);
        sum = sum
            + if len > 0.0 {
                gl8(a, b, f)
            } else {
                gl8(b, a, f)
            };
        outer = inner;
    }
    let e = outer * len;
    sum + gl8(0.0, 1.0, &|s| f(at + e * s * s) * (2.0 * e.abs() * s))
}

/// The Legendre polynomials P_0 … P_15 at t.
fn legendre(t: f64) -> [f64; MOMENT_POINTS] {
    let mut p = [0.0; MOMENT_POINTS];
    p[0] = 1.0;
    p[1] = t;
    for k in 1..MOMENT_POINTS - 1 {
        let kf = k as f64;
        p[k + 1] = ((2.0 * kf + 1.0) * t * p[k] - kf * p[k - 1]) / (kf + 1.0);
    }
    p
}

/// The 16 Gauss-Legendre nodes and weights on [−1, 1] (Newton's iteration on P_16 from
/// Tricomi's initial guesses, to rounding).
fn gauss_legendre_16() -> ([f64; MOMENT_POINTS], [f64; MOMENT_POINTS]) {
    let k = MOMENT_POINTS;
    let (mut t, mut w) = ([0.0; MOMENT_POINTS], [0.0; MOMENT_POINTS]);
    for i in 0..k {
        let mut x = math::cos(core::f64::consts::PI * (i as f64 + 0.75) / (k as f64 + 0.5));
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_k(x) and P_k'(x) by the recurrence.
            let (mut p0, mut p1) = (1.0, x);
            for j in 1..k {
                let jf = j as f64;
                let p2 = ((2.0 * jf + 1.0) * x * p1 - jf * p0) / (jf + 1.0);
                p0 = p1;
                p1 = p2;
            }
            dp = k as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() <= 1e-16 {
                break;
            }
        }
        t[i] = x;
        w[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    (t, w)
}

/// ∫_{−½}^{½} N·F_N(π·r)·h(r) dr for h smooth on the period: h interpolated at the 16
/// Gauss-Legendre nodes, its Legendre series integrated exactly against the kernel's moments
/// μ_k = ∫ N·F_N(π·r)·P_k(2r) dr (odd ones vanish), which `period_integral` computes once:
/// W_i = w_i·Σ_k (2k + 1)/2·P_k(t_i)·μ_k.
struct MomentRule {
    nodes: [f64; MOMENT_POINTS],
    weights: [f64; MOMENT_POINTS],
}

/// The 16 Legendre moments as one quadrature value.
#[derive(Clone, Copy)]
struct Moments([f64; MOMENT_POINTS]);

impl core::ops::Add for Moments {
    type Output = Moments;
    fn add(self, o: Moments) -> Moments {
        Moments(core::array::from_fn(|k| self.0[k] + o.0[k]))
    }
}

impl core::ops::Mul<f64> for Moments {
    type Output = Moments;
    fn mul(self, s: f64) -> Moments {
        Moments(self.0.map(|v| v * s))
    }
}

impl Value for Moments {
    const ZERO: Moments = Moments([0.0; MOMENT_POINTS]);
}

impl MomentRule {
    fn new(n: f64) -> MomentRule {
        let mu = period_integral(n, &[f64::NAN; 4], &|r| Moments(legendre(2.0 * r))).0;
        let (t, w) = gauss_legendre_16();
        let mut weights = [0.0; MOMENT_POINTS];
        for i in 0..MOMENT_POINTS {
            let p = legendre(t[i]);
            let s: f64 = (0..MOMENT_POINTS)
                .step_by(2)
                .map(|k| (k as f64 + 0.5) * p[k] * mu[k])
                .sum();
            weights[i] = w[i] * s;
        }
        MomentRule {
            nodes: t.map(|t| 0.5 * t),
            weights,
        }
    }

    fn apply(&self, h: &dyn Fn(f64) -> f64) -> f64 {
        self.nodes
            .iter()
            .zip(&self.weights)
            .map(|(&r, &w)| w * h(r))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optics::groove::GrooveSpread;
    use crate::Grating;

    /// The moment rule against the lobe-by-lobe rule on every period, relative to the albedo.
    /// Measured worst 2.65·10⁻¹⁴ (rounding of the two sums); the bound keeps a margin of 40.
    /// (Before the ripple test a coherence length of N·d reached 8.2·10⁻⁷ at N = 30.)
    const MOMENT_RULE: f64 = 1e-12;

    #[test]
    fn moment_rule_matches_the_lobe_walk() {
        let mut worst = 0.0f64;
        let grooves = [
            None,
            Some(GrooveSpread::gaussian(0.02).unwrap()),
            Some(GrooveSpread::gaussian(1e-4).unwrap()),
            Some(GrooveSpread::IDEAL),
            Some(GrooveSpread::coherence_length(1e3).unwrap()),
            Some(GrooveSpread::coherence_length(1e15).unwrap()),
        ];
        for n in [1u32, 7, 30, 128, 129, 1000, 1_000_000] {
            for groove in grooves {
                for (d, rho, l, wo) in [
                    (1600.0, 0.5, 450.0, DVec3::Z),
                    (20_000.0, 0.5, 400.0, DVec3::Z),
                    (
                        30_000.0,
                        0.1,
                        470.0,
                        DVec3::new(0.3, 0.5, (1.0f64 - 0.34).sqrt()),
                    ),
                    (
                        10_000.0,
                        0.9,
                        700.0,
                        DVec3::new(-0.6, 0.1, (1.0f64 - 0.37).sqrt()),
                    ),
                ] {
                    let mut b = GratingBsdf::new(Grating::new(d, rho * d, n).unwrap());
                    if let Some(g) = groove {
                        b = b.with_groove(g);
                    }
                    let fast = b.albedo_by(wo, l, true).unwrap();
                    let full = b.albedo_by(wo, l, false).unwrap();
                    let rel = (fast - full).abs() / full;
                    assert!(
                        rel <= MOMENT_RULE,
                        "N={n} {groove:?} d={d}: {fast} vs {full}"
                    );
                    worst = worst.max(rel);
                }
            }
        }
        std::println!("moment rule against the lobe walk: worst {worst:.2e}");
    }
}
