//! `Strategy::ASYMPTOTIC`: the peak search with its leading correction (the derivation, the
//! treatment of the kinks, the band ends and order 0, and the measured bound are in the
//! `spectrum` module docs).
//!
//! The band [d·|u|/830, d·|u|/360] in x is walked from left to right: windows integrated lobe
//! by lobe (`Lobes::lobes_by` with `window_rule`) around every integer, at both band ends and
//! over the lobes wider than LOBE_NM, merged where they overlap; between them the envelope
//! G = h/(2N² sin²πx) with its end corrections (`Walk::envelope`); faint orders by their peak
//! value over their whole period (`Walk::plain_period`). The work is O(visible orders), as for
//! the peak search. The weight h comes from `Lobes::envelope_at` and `Lobes::integrand_at` (and
//! order 0's product rule, `order0`, from the same spectral weight and envelope), so a further
//! smooth per-wavelength factor multiplies in there. At the extremes of d·|u| (the band inside
//! order 0's central lobe, or more than `DENSE_ORDERS` orders) it is `Exact`, whose closed forms
//! bound the work there. Up to `small_n::MAX_SLITS` slits it is `small_n`'s rule (F_N as its N
//! cosines), whose fixed work is below the walk's there.

use glam::DVec3;

use super::bounds;
use super::lobes::Lobes;
use super::order0;
use super::rules::{gl2, gl3, gl4, gl6};
use super::small_n;
use super::smooth_band::Limits;
use super::{Spectral, BAND};
use crate::data::cie::Illuminant;
use crate::num::kernel::{single_slit_cycles, sinpi};
use crate::num::math::{ceil, floor, ln, rint, sqrt};
use crate::num::quadrature::GL8;
use crate::{Grating, Slits};
use core::f64::consts::PI;

/// Lobes on each side of every integer x integrated lobe by lobe.
const PEAK_LOBES: f64 = 2.0;
/// Whole lobes after the partial lobe at each band end integrated lobe by lobe: none, the
/// envelope's expansion holds from the first zero on there (h is below 10⁻⁴ of its peak at the
/// band ends, where the colour-matching functions vanish; measured: no change of the sweep's
/// worst error against one lobe).
const END_LOBES: f64 = 0.0;
/// Largest span in wavelength of one 3-point piece of order 0's envelope where the pieces are
/// not split at the illuminant's nodes, and the least span next to the orders m ≠ 0
/// (`order_span_nm`). 32 nm left 2.1·10⁻⁴ of order 0's light; 16 nm 6.8·10⁻⁵, 8 nm no less.
const ENVELOPE_SPAN_NM: f64 = 16.0;
/// The product rule for order 0 (`order0`) is taken where the spectral envelope's sinc² factor
/// stays below this argument over the band (no zero in it: as smooth as λ⁻ᵖ).
const ORDER0_SINC_CYCLES: f64 = 0.5;
/// The widest window (in wavelength) of an order's peak that takes `PeakRule`: there h's
/// interpolant at 5 points is within about 2·10⁻⁶ of it (h varies on the 20-40 nm scale of the
/// colour-matching functions).
const PEAK_WINDOW_NM: f64 = 4.0;
/// Relative tolerance when recognising a window's computed edges.
const EDGE: f64 = 1e-12;
/// The largest span of an envelope piece next to an order m ≠ 0 (see `order_span_nm`).
const MAX_ORDER_SPAN_NM: f64 = 64.0;
/// Lobes wider than this, in wavelength, or than the illuminant's node spacing, are
/// integrated lobe by lobe.
const LOBE_NM: f64 = 8.0;
/// Largest span in wavelength of one 4-point Gauss-Legendre piece.
const SPAN_NM: f64 = 16.0;
/// An order treated by the plain peak search contributes less than this, relative to the
/// brightest order's floor, to the error.
const FAINT: f64 = 1e-7;

/// The spacing of the illuminant's own rows, nm, where its linear interpolation has large kinks
/// (D65 is tabulated at 5 nm and interpolated linearly to the 1 nm table, see `cie`); 0 when it
/// has none (E is flat; A is Planck's law at every 1 nm row, as smooth as the observer).
fn node_spacing_nm(illuminant: Illuminant) -> f64 {
    match illuminant {
        Illuminant::D65 => 5.0,
        Illuminant::E | Illuminant::A => 0.0,
    }
}

/// The envelope's largest piece span next to an order m ≠ 0 for N slits: ENVELOPE_SPAN_NM at
/// N = 5, growing as N^(1/6) to MAX_ORDER_SPAN_NM. There the envelope's share of the colour is
/// divided by N relative to the order's peak h(m)/N, while the 3-point rule's relative error
/// grows as span⁶: the product stays that of N = 5.
fn order_span_nm(n: f64) -> f64 {
    let grow = crate::num::math::powf(n / bounds::ASYMPTOTIC_MIN_SLITS as f64, 1.0 / 6.0);
    (ENVELOPE_SPAN_NM * grow).clamp(ENVELOPE_SPAN_NM, MAX_ORDER_SPAN_NM)
}

impl Spectral {
    /// Lobes wider than this (nm) are integrated lobe by lobe: LOBE_NM, or the illuminant's
    /// node spacing where that is smaller.
    fn lobe_nm(&self) -> f64 {
        let node = node_spacing_nm(self.illuminant);
        if node > 0.0 {
            LOBE_NM.min(node)
        } else {
            LOBE_NM
        }
    }
}

/// cos(π·r) for |r| ≤ ½.
#[inline]
fn cospi(r: f64) -> f64 {
    sinpi(0.5 - r.abs())
}

impl Spectral {
    /// The corrected peak search (see the module docs).
    pub(super) fn asymptotic(&self, grating: &Grating, u: f64) -> DVec3 {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return DVec3::ZERO,
        };
        let q = grating.period_nm() * u;
        if Self::order0_everywhere(grating, q) || Self::is_dense(q) {
            // The white, or a comb of more than `DENSE_ORDERS` orders: `Exact`'s closed forms
            // (bounded work, see `dense`).
            return self.exact(grating, u);
        }
        if n <= small_n::MAX_SLITS as f64 {
            // A few slits: F_N as its cosines (`small_n`), cheaper than the walk below up to
            // MAX_SLITS.
            return self
                .small_n(grating, q)
                .unwrap_or_else(|| self.exact(grating, u));
        }
        if let Some(c) = self.smooth_band(grating, q, n, Limits::FAST) {
            // N·q up to about 47,000 nm (at most about 74 lobes over the band): the product
            // rule against the tables, within 4.3·10⁻⁶ of the lobe walk (`smooth_band`).
            return c;
        }
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobe_nm = self.lobe_nm();
        // Lobes wider than lobe_nm at the band's long end: the fixed pieces from the one where a
        // lobe is lobe_nm wide (λ² = lobe_nm·N·q) on by the same product rule (there ω·h is at
        // most 30π/lobe_nm·(390/360)², inside its limits), the rest walked.
        let (mut long_end, mut x_lo) = (DVec3::ZERO, x_lo);
        if q / (n * x_lo * x_lo) > lobe_nm {
            let at = (sqrt(lobe_nm * n * q) - BAND.min_nm()) / order0::PIECE_NM;
            let first = floor(at.max(0.0)) as usize;
            if first < order0::PIECES {
                if let Some(c) = self.smooth_pieces(grating, q, n, Limits::FAST, first) {
                    long_end = c;
                    x_lo = q / order0::piece_bounds(first).0;
                }
            }
        }
        let lobes = Lobes::new(self, grating, q, n);
        let mut walk = Walk {
            lobes: &lobes,
            start: x_lo,
            end: x_hi,
            cursor: x_lo,
            cursor_on_zero: false,
            pending: None,
            acc: DVec3::ZERO,
            order_span_nm: order_span_nm(n),
            order0_pieces: self.envelope.band_sinc_cycles() <= ORDER0_SINC_CYCLES,
            peak_rule: None,
        };
        if x_lo.is_nan() || x_hi.is_nan() || x_lo >= x_hi {
            return long_end;
        }
        let t = PEAK_LOBES / n;
        // The band end, and every lobe wider than LOBE_NM (the envelope's expansion needs h
        // smooth on the scale of a lobe, q/(N·x²) nm wide).
        let wide = ceil(sqrt(q / (n * lobe_nm)) * n);
        let left = (floor(x_lo * n) + 1.0 + END_LOBES).max(wide) / n;
        walk.exact_window(x_lo, left);
        let right = (ceil(x_hi * n) - 1.0 - END_LOBES) / n;
        // An order whose whole period lies between the end windows and whose peak value is
        // below this gets the plain peak-search weight h(m)/N (its error, under 8/N of it, is
        // below FAINT of the accuracy unit's floor).
        let faint = FAINT * bounds::accuracy_floor(n) * n * n / bounds::PEAK_SEARCH_PER_SLIT;
        let mut right_done = false;
        // Every integer whose window reaches into the band, order 0 (x = 0) included.
        let mut m = ceil(x_lo - t).max(0.0);
        while m - t <= x_hi {
            if !right_done && m - t >= right {
                walk.exact_window(right, x_hi);
                right_done = true;
            }
            let h = if m >= 1.0 && m - 0.5 >= left && m + 0.5 <= right {
                let h = lobes.envelope_at(m);
                (h.abs().max_element() <= faint).then_some(h)
            } else {
                None
            };
            match h {
                Some(h) => walk.plain_period(m, h),
                None => walk.exact_window(m - t, m + t),
            }
            m += 1.0;
        }
        if !right_done {
            walk.exact_window(right, x_hi);
        }
        walk.finish();
        // The integral is non-negative; the corrections can undershoot a vanishing channel by
        // rounding.
        (long_end + walk.acc).max(DVec3::ZERO)
    }
}

/// Left-to-right integration over [start, end]: lobe by lobe inside the windows handed to
/// `exact_window` (in order of their starts), the mean-½ envelope with its end corrections in
/// the gaps between them.
struct Walk<'s, 'a> {
    lobes: &'s Lobes<'a>,
    start: f64,
    end: f64,
    /// Everything below is integrated.
    cursor: f64,
    /// Whether the cursor is on a zero of sin(πNx) (a window's edge).
    cursor_on_zero: bool,
    /// A window not yet integrated (it may still grow).
    pending: Option<(f64, f64)>,
    acc: DVec3,
    /// The envelope's piece span next to the orders m ≠ 0 (`order_span_nm`).
    order_span_nm: f64,
    /// Whether order 0's half period takes the product rule on the fixed pieces (`order0`):
    /// where the spectral envelope is smooth over the band.
    order0_pieces: bool,
    /// The window rule of the orders' peaks, made at the first window that takes it.
    peak_rule: Option<PeakRule>,
}

/// ∫ F_N(x)·h(x) over an order's window [m − t, m + t] (t = PEAK_LOBES/N) where h is smooth on
/// the window (at most PEAK_WINDOW_NM wide, no node of the illuminant inside): h is replaced by
/// its interpolant at the 5 Gauss-Legendre nodes of the window and the product with F_N (the
/// same on every window: F_N has period 1) integrated once, so a window costs 5 evaluations of
/// h without F_N instead of 24 of h·F_N.
#[derive(Clone, Copy)]
struct PeakRule {
    /// The nodes' offsets r from m.
    r: [f64; 5],
    /// ∫ ℓᵢ(r)·F_N(r) dr over [−t, t], ℓᵢ the Lagrange basis polynomial of node i.
    w: [f64; 5],
}

impl PeakRule {
    fn new(l: &Lobes<'_>) -> PeakRule {
        let t = PEAK_LOBES / l.n;
        let r = GL5.map(|s| s * t);
        let mut w = [0.0; 5];
        // F_N is even: ∫ over [−t, t] as twice [0, t], lobe by lobe with 8 points each.
        let lobes = PEAK_LOBES as u32;
        let width = 1.0 / l.n;
        for j in 0..lobes {
            let (mid, half) = ((j as f64 + 0.5) * width, 0.5 * width);
            for (xi, wi) in GL8.nodes.iter().zip(GL8.weights) {
                let x = mid + half * xi;
                let f = wi * half * l.n_slit(x);
                for (k, wk) in w.iter_mut().enumerate() {
                    *wk += f * (lagrange(&GL5, k, x / t) + lagrange(&GL5, k, -x / t));
                }
            }
        }
        PeakRule { r, w }
    }

    fn integrate(&self, l: &Lobes<'_>, m: f64) -> DVec3 {
        let mut acc = DVec3::ZERO;
        for (r, w) in self.r.iter().zip(self.w) {
            acc += l.envelope_at(m + r) * w;
        }
        acc
    }
}

/// The 5 Gauss-Legendre nodes on [−1, 1] (mpmath, 40 digits).
const GL5: [f64; 5] = [
    -0.906_179_845_938_664,
    -0.538_469_310_105_683_1,
    0.0,
    0.538_469_310_105_683_1,
    0.906_179_845_938_664,
];

/// ℓ_k(s) for the nodes `nodes`.
fn lagrange(nodes: &[f64; 5], k: usize, s: f64) -> f64 {
    let mut v = 1.0;
    for (j, &sj) in nodes.iter().enumerate() {
        if j != k {
            v *= (s - sj) / (nodes[k] - sj);
        }
    }
    v
}

impl Walk<'_, '_> {
    fn exact_window(&mut self, a: f64, b: f64) {
        let (a, b) = (a.max(self.start), b.min(self.end));
        if a.is_nan() || b.is_nan() || b <= a {
            return;
        }
        match self.pending {
            Some((pa, pb)) if a <= pb => self.pending = Some((pa, pb.max(b))),
            Some((pa, pb)) => {
                self.flush(pa, pb);
                self.envelope(pb, a, true);
                self.pending = Some((a, b));
            }
            None => {
                if a > self.cursor {
                    self.envelope(self.cursor, a, true);
                }
                self.pending = Some((a.max(self.cursor), b));
            }
        }
    }

    /// The period [m − ½, m + ½] by the peak search: h(m)/N.
    fn plain_period(&mut self, m: f64, h: DVec3) {
        let a = m - 0.5;
        match self.pending.take() {
            Some((pa, pb)) => {
                self.flush(pa, pb);
                self.envelope(pb, a, false);
            }
            None => self.envelope(self.cursor, a, false),
        }
        self.acc += h / self.lobes.n;
        self.cursor = m + 0.5;
        self.cursor_on_zero = false;
    }

    fn finish(&mut self) {
        if let Some((pa, pb)) = self.pending.take() {
            self.flush(pa, pb);
            if pb < self.end {
                self.envelope(pb, self.end, false);
            }
        } else if self.cursor < self.end {
            self.envelope(self.cursor, self.end, false);
        }
    }

    fn flush(&mut self, a: f64, b: f64) {
        match self.peak_window(a, b) {
            Some(m) => {
                let rule = *self
                    .peak_rule
                    .get_or_insert_with(|| PeakRule::new(self.lobes));
                self.acc += rule.integrate(self.lobes, m);
            }
            None => self.acc += self.lobes.lobes_by(a, b, window_rule),
        }
        self.cursor = b;
        self.cursor_on_zero = true;
    }

    /// The order m when [a, b] is exactly its window [m − t, m + t] (t = PEAK_LOBES/N), m ≥ 1,
    /// at most PEAK_WINDOW_NM wide in wavelength and free of the illuminant's nodes: there h is
    /// smooth across the window and `PeakRule` applies.
    fn peak_window(&self, a: f64, b: f64) -> Option<f64> {
        let l = self.lobes;
        let m = rint(0.5 * (a + b));
        let t = PEAK_LOBES / l.n;
        let tol = EDGE * m.max(1.0);
        let exact = (a - (m - t)).abs() <= tol && (b - (m + t)).abs() <= tol;
        let (l_hi, l_lo) = (l.q / a, l.q / b);
        if !(m >= 1.0 && exact && l_hi - l_lo <= PEAK_WINDOW_NM) {
            return None;
        }
        let node = node_spacing_nm(l.s.illuminant);
        let crosses = node > 0.0 && floor(l_hi / node) != floor(l_lo / node);
        (!crosses).then_some(m)
    }

    /// ∫ F_N·h over [a, b] for a, b zeros of sin(πNx) (or a = ½, the end of order 0's
    /// half period) at least PEAK_LOBES lobes from every integer: ∫ h/(2N² sin²πx) with
    /// −[G']/(4π²N²), G = h/(2N² sin²πx), from the oscillating part (two integrations by
    /// parts).
    ///
    /// The end corrections are taken at a when the cursor sits on a window's edge and at b when
    /// `b_on_zero`; elsewhere (half-integers, where sin(2πNx) = 0 and G' is of order h'/N²)
    /// they are negligible.
    fn envelope(&mut self, a: f64, b: f64, b_on_zero: bool) {
        if a.is_nan() || b.is_nan() || b <= a {
            return;
        }
        let n = self.lobes.n;
        let inv_n2 = 1.0 / (n * n);
        let k = inv_n2 * inv_n2 / (4.0 * PI * PI);
        let mut sum = DVec3::ZERO;
        // Pieces within one half period on either side of an integer m, each with the
        // tangent of h at its end nearer to m (a window's edge).
        let mut lo = a;
        while lo < b {
            let m = floor(lo + 0.5);
            let hi = if lo < m { m } else { m + 0.5 }.min(b);
            let hi = if hi > lo { hi } else { b };
            let (c, side) = if lo < m { (hi, -1.0) } else { (lo, 1.0) };
            let tangent = self.tangent(c, side);
            self.half_period(m, c, tangent, lo, hi, &mut sum);
            // End corrections at the window edges, with the same tangent where it is there.
            if lo == a && self.cursor_on_zero {
                let t = if c == a {
                    tangent
                } else {
                    self.tangent(a, 1.0)
                };
                self.acc += slope_of_g(a, t) * k;
            }
            if hi == b && b_on_zero {
                let t = if c == b {
                    tangent
                } else {
                    self.tangent(b, -1.0)
                };
                self.acc -= slope_of_g(b, t) * k;
            }
            lo = hi;
        }
        self.acc += sum * inv_n2;
        self.cursor = b;
    }

    /// h(c) and its one-sided slope toward `side` (±1), by a difference over a quarter lobe.
    fn tangent(&self, c: f64, side: f64) -> (DVec3, DVec3) {
        let step = side * 0.25 / self.lobes.n;
        let h = self.lobes.envelope_at(c);
        let h1 = self.lobes.envelope_at(c + step);
        (h, (h1 - h) / step)
    }

    /// ∫ h/(2 sin²πx) over [a, b], on one side of the integer m and within half a period of
    /// it: the tangent p of h at c analytically, h − p by Gauss-Legendre.
    fn half_period(
        &self,
        m: f64,
        c: f64,
        (hc, slope): (DVec3, DVec3),
        a: f64,
        b: f64,
        sum: &mut DVec3,
    ) {
        if m == 0.0 && self.order0_pieces {
            let q = self.lobes.q;
            let (first, last) = order0::whole_pieces(q / b, q / a);
            if first < last {
                // Whole pieces by the product rule, the rest of [a, b] as below.
                let (l0, l1) = (
                    order0::piece_bounds(first).0,
                    order0::piece_bounds(last - 1).1,
                );
                *sum += self.order0_whole(first, last);
                let (x0, x1) = (q / l1, q / l0);
                if x0 > a {
                    self.half_period_parts(m, c, (hc, slope), a, x0, sum);
                }
                if b > x1 {
                    self.half_period_parts(m, c, (hc, slope), x1, b, sum);
                }
                return;
            }
        }
        self.half_period_parts(m, c, (hc, slope), a, b, sum);
    }

    /// ∫ h/(2 sin²πx) over order 0's whole fixed pieces [first, last) (`order0`): K(λ) =
    /// S(ρ·q/λ)·env(λ)·norm/(2 sin²(π·q/λ)) against the tables' product weights.
    fn order0_whole(&self, first: usize, last: usize) -> DVec3 {
        let l = self.lobes;
        let s = l.s;
        let k = |lambda: f64| {
            let x = l.q / lambda;
            let sx = sinpi(x - rint(x));
            single_slit_cycles(l.duty * x) * s.envelope_norm(lambda) / (2.0 * sx * sx)
        };
        order0::integrate(s.illuminant, first, last, &k)
    }

    /// `half_period` on [a, b] by Gauss-Legendre pieces and the tangent's closed forms.
    fn half_period_parts(
        &self,
        m: f64,
        c: f64,
        (hc, slope): (DVec3, DVec3),
        a: f64,
        b: f64,
        sum: &mut DVec3,
    ) {
        // p(x) = value + slope·(x − m).
        let value = hc - slope * (c - m);
        let lobes = self.lobes;
        let rest = |x: f64| {
            let r = x - m;
            let s = sinpi(r);
            let w = 0.5 / (s * s);
            (lobes.envelope_at(x) - value - slope * r) * w
        };
        // Split at the illuminant's nodes only in order 0's half period, where the envelope is
        // the whole colour; next to the orders it is a correction of relative size 1/N.
        let node = if m == 0.0 {
            node_spacing_nm(lobes.s.illuminant)
        } else {
            0.0
        };
        let span = if m == 0.0 {
            ENVELOPE_SPAN_NM
        } else {
            self.order_span_nm
        };
        pieces(lobes.q, node, span, &gl3, a, b, sum, &rest);
        // ∫ dr/(2 sin²πr) = −cot(πr)/(2π); ∫ r dr/(2 sin²πr) = −r·cot(πr)/(2π) + ln|sin πr|/(2π²).
        let (r0, r1) = (a - m, b - m);
        let (s0, s1) = (sinpi(r0), sinpi(r1));
        let (c0, c1) = (cospi(r0) / s0, cospi(r1) / s1);
        let i0 = (c0 - c1) / (2.0 * PI);
        let i1 = (r0 * c0 - r1 * c1) / (2.0 * PI) + ln(s1 / s0) / (2.0 * PI * PI);
        *sum += value * i0 + slope * i1;
    }
}

/// d/dx [h/(2 sin²πx)] = N²·G' at c, from h(c) and h'(c).
fn slope_of_g(c: f64, (h, slope): (DVec3, DVec3)) -> DVec3 {
    let r = c - rint(c);
    let s = sinpi(r);
    let a = 0.5 / (s * s);
    let b = PI * cospi(r) / (s * s * s);
    slope * a - h * b
}

/// The piece rule inside the windows: split at the illuminant's nodes and into pieces of at
/// most SPAN_NM.
fn window_rule(l: &Lobes<'_>, a: f64, b: f64, acc: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    let node = node_spacing_nm(l.s.illuminant);
    pieces(l.q, node, SPAN_NM, &lobe_rule(l.n, l.q), a, b, acc, f);
}

/// The Gauss-Legendre rule for a piece of a lobe: 6 points where the piece is more than half a
/// lobe (the error of 6 points on a whole lobe of sin² is 7e-7, of 4 points 7e-4), 4 points up
/// to half a lobe (3e-6), 2 points up to 0.15 lobe (2e-6) where the piece also spans at most
/// 6 nm (h, smooth between the illuminant's nodes, changes little over it).
fn lobe_rule(n: f64, q: f64) -> impl Fn(f64, f64, &mut DVec3, &dyn Fn(f64) -> DVec3) {
    move |a, b, acc, f| {
        let lobes = (b - a) * n;
        if lobes > 0.5 {
            gl6(a, b, acc, f);
        } else if lobes > 0.15 || q / a - q / b > 6.0 {
            gl4(a, b, acc, f);
        } else {
            gl2(a, b, acc, f);
        }
    }
}

/// 4-point Gauss-Legendre over [a, b] (in x) split where λ = q/x crosses a node of the
/// illuminant (every `node_nm`; none when 0) and into pieces spanning at most SPAN_NM.
#[allow(clippy::too_many_arguments)]
fn pieces(
    q: f64,
    node_nm: f64,
    max_nm: f64,
    gauss: Rule<'_>,
    a: f64,
    b: f64,
    acc: &mut DVec3,
    f: &dyn Fn(f64) -> DVec3,
) {
    let mut lo = a;
    let (l_hi, l_lo) = (q / a, q / b);
    // Nodes strictly between, from the long-wavelength end (small x) on.
    let mut node = if node_nm > 0.0 {
        ceil(l_hi / node_nm) * node_nm - node_nm
    } else {
        0.0
    };
    while lo < b {
        let next_node = if node > l_lo { q / node } else { b };
        let stop = next_node.min(b);
        span_pieces(q, max_nm, gauss, lo, stop, acc, f);
        lo = stop;
        node -= node_nm;
        if node_nm <= 0.0 {
            break;
        }
    }
}

/// A Gauss-Legendre rule on one piece.
type Rule<'r> = &'r dyn Fn(f64, f64, &mut DVec3, &dyn Fn(f64) -> DVec3);

/// Gauss-Legendre on equal pieces of [a, b] spanning at most SPAN_NM each.
fn span_pieces(
    q: f64,
    max_nm: f64,
    gauss: Rule<'_>,
    a: f64,
    b: f64,
    acc: &mut DVec3,
    f: &dyn Fn(f64) -> DVec3,
) {
    if a.is_nan() || b.is_nan() || b <= a {
        return;
    }
    let span = q / a - q / b;
    let count = ceil(span / max_nm).max(1.0);
    let step = (b - a) / count;
    let count = count as u32;
    let mut t = a;
    for j in 1..=count {
        let e = if j == count { b } else { a + j as f64 * step };
        gauss(t, e, acc, f);
        t = e;
    }
}
