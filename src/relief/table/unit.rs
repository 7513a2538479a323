//! Cells without the normalisation: for each interpolation cell of a table, whether every query
//! inside it has Σ_m η_m ≤ 1 for TE and for TM before the normalisation, so that one order's
//! efficiency is that order's interpolation alone (the normalisation's factor is exactly 1
//! there) and a query need not interpolate every stored order for the sum.
//!
//! The bound of a cell, per polarisation, with the interpolation rule of the parent module:
//! order m's value at a query is a convex combination of q_c = η_c·cos θi,c/cos θm,c over the
//! cell's corners where it propagates (cos² θm,c > [`GRAZING_CORNER`]), times
//! cos θm/cos θi ≤ R_m at the query. An order propagating at every corner uses the bilinear
//! weights themselves, the same for every such order; any other order uses weights
//! renormalised over its corners. So
//!
//! ```text
//! Σ_m η_m(query) ≤ max_c Σ_{m full} q_m,c·R_m + Σ_{m partial} max_c q_m,c·R_m
//! ```
//!
//! with R_m the largest, over a few sub-boxes of the cell, of the sub-box's sup cos θm over
//! its inf cos θi ([`ratio_bound`]). A cell is marked when that bound is at most 1 − 10⁻⁹ for
//! both polarisations (the margin covers the query's rounding, ~10⁻¹⁵). Measured
//! (`tests` below): 92 % of the CD preset's cells are marked, 81 % of the DVD's, 48 % of the
//! foil's and 4.5 % of the blazed grating's (its coarse grid is crossed by Rayleigh lines
//! almost everywhere), and no query's sum exceeds its cell's bound. The marks are computed
//! once per table, on the first query that needs them (feature `std`: a `OnceLock`), for
//! tables of at most [`MAX_MARKED_VALUES`] values; without `std`, or for a larger table, every
//! query takes the full sum.

#[cfg(feature = "std")]
use std::{sync::OnceLock, vec::Vec};

use super::{EfficiencyTable, Storage, Values, GRAZING_CORNER};
use crate::num::math;

/// The largest table (values per polarisation) whose cells are marked: 2²⁰ (measured: the
/// first query of a table of 1.04·10⁶ values takes 0.37 s for the marks and the kept q's, the CD
/// preset's 10,625 values 1.5 ms); a larger table is read with the full sum everywhere.
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(super) const MAX_MARKED_VALUES: usize = 1 << 20;

/// A cell is marked when its bound is at most this (per polarisation).
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(super) const UNIT_BOUND: f64 = 1.0 - 1e-9;

/// The cells' marks of one table, a bit per cell, computed on first use.
#[derive(Debug, Clone, Default)]
pub(super) struct UnitCells {
    #[cfg(feature = "std")]
    bits: OnceLock<Vec<u64>>,
}

impl PartialEq for UnitCells {
    /// Derived data: equal tables have equal marks, computed or not.
    fn eq(&self, _other: &UnitCells) -> bool {
        true
    }
}

impl UnitCells {
    // Every table is built by a constructor (feature `alloc`) or is a preset.
    #[cfg_attr(not(any(feature = "alloc", feature = "presets")), allow(dead_code))]
    pub(super) const fn new() -> UnitCells {
        UnitCells {
            #[cfg(feature = "std")]
            bits: OnceLock::new(),
        }
    }

    /// Whether cell `cell` needs no normalisation; `marks` computes every cell's mark (called
    /// once). Always `false` without `std`.
    #[inline]
    pub(super) fn is_unit(&self, cell: usize, marks: impl FnOnce() -> Bits) -> bool {
        #[cfg(feature = "std")]
        {
            let bits = self.bits.get_or_init(|| marks().0);
            bits.get(cell / 64)
                .is_some_and(|w| (w >> (cell % 64)) & 1 == 1)
        }
        #[cfg(not(feature = "std"))]
        {
            let _ = (cell, marks);
            false
        }
    }
}

/// Every cell's mark, a bit per cell.
pub(super) struct Bits(#[cfg(feature = "std")] pub(super) Vec<u64>);

/// One corner of a cell: its node's s (s′ of a conical table) and |β| (0 for a classical
/// one), α, β² and λ of the node, cos θi there, and the node's flat index in an order's slice.
#[derive(Clone, Copy, Default)]
pub(super) struct Corner {
    pub s: f64,
    pub b: f64,
    pub alpha: f64,
    pub beta2: f64,
    pub lambda_nm: f64,
    pub cos_i: f64,
    pub index: usize,
}

/// The marks of `cells` cells, cell c's corners from `corners(c, &mut buf)` (which fills
/// `buf` and returns their count, 4 or 8).
#[allow(clippy::too_many_arguments)]
pub(super) fn marks<T: Values + ?Sized>(
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    slice: usize,
    cells: usize,
    te: &T,
    tm: &T,
    mut corners: impl FnMut(usize, &mut [Corner; 8]) -> usize,
) -> Bits {
    #[cfg(feature = "std")]
    {
        let mut bits = std::vec![0u64; cells.div_ceil(64)];
        if slice * order_count > MAX_MARKED_VALUES {
            // No cell marked: every query sums all orders, as without `std`.
            return Bits(bits);
        }
        let mut buf = [Corner::default(); 8];
        for cell in 0..cells {
            let n = corners(cell, &mut buf);
            let (b_te, b_tm) = bound(period_nm, order_min, order_count, slice, &buf[..n], te, tm);
            if b_te <= UNIT_BOUND && b_tm <= UNIT_BOUND {
                bits[cell / 64] |= 1 << (cell % 64);
            }
        }
        Bits(bits)
    }
    #[cfg(not(feature = "std"))]
    {
        let _ = (
            period_nm,
            order_min,
            order_count,
            slice,
            cells,
            te,
            tm,
            &mut corners,
        );
        Bits()
    }
}

/// The bound of Σ_m η_m over the cell of corners `c`, (TE, TM): ∞ where a corner is at
/// grazing incidence. An order propagating at every corner (a *full* order) is a convex
/// combination with the bilinear weights themselves, the same for every full order, so the full
/// orders together give at most max_c Σ_m q_m,c·R_m; every other order (its weights
/// renormalised over fewer corners) gives at most max_c q_m,c·R_m. R_m bounds
/// cos θm/cos θi over the cell: the largest, over [`PIECES`] sub-boxes, of the sub-box's sup
/// cos θm over its inf cos θi.
#[allow(clippy::too_many_arguments)]
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(super) fn bound<T: Values + ?Sized>(
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    slice: usize,
    c: &[Corner],
    te: &T,
    tm: &T,
) -> (f64, f64) {
    let ratio = |mf: f64| ratio_bound(period_nm, mf, c);
    bound_with(period_nm, order_min, order_count, slice, c, (te, tm), ratio)
}

/// [`bound`] with R_m from `ratio(m)`: a bound of cos θm/cos θi over every query of the cell
/// (a reduced conical table's cell takes it over its box in (s′, λ′), `reduced.rs`).
#[cfg_attr(not(feature = "std"), allow(dead_code))]
pub(super) fn bound_with<T: Values + ?Sized>(
    period_nm: f64,
    order_min: i32,
    order_count: usize,
    slice: usize,
    c: &[Corner],
    (te, tm): (&T, &T),
    ratio: impl Fn(f64) -> f64,
) -> (f64, f64) {
    if c.iter().any(|k| k.cos_i.is_nan() || k.cos_i <= 0.0) {
        return (f64::INFINITY, f64::INFINITY);
    }
    let mut full = [(0.0f64, 0.0f64); 8];
    let (mut part_te, mut part_tm) = (0.0, 0.0);
    for k in 0..order_count {
        let mf = f64::from(order_min) + k as f64;
        let mut q = [(0.0f64, 0.0f64); 8];
        let mut live = 0;
        for (n, corner) in c.iter().enumerate() {
            // The query's formula for α_m at a node (conical.rs, table.rs).
            let am = corner.alpha + mf * corner.lambda_nm / period_nm;
            let cm2 = 1.0 - am * am - corner.beta2;
            if cm2 > GRAZING_CORNER {
                let g = corner.cos_i / math::sqrt(cm2);
                let at = k * slice + corner.index;
                q[n] = (g * te.at(at), g * tm.at(at));
                live += 1;
            }
        }
        if q.iter().all(|&(a, b)| a == 0.0 && b == 0.0) {
            continue;
        }
        let r = ratio(mf);
        if live == c.len() {
            for (f, q) in full.iter_mut().zip(&q) {
                f.0 += q.0 * r;
                f.1 += q.1 * r;
            }
        } else {
            part_te += q.iter().fold(0.0f64, |a, q| a.max(q.0)) * r;
            part_tm += q.iter().fold(0.0f64, |a, q| a.max(q.1)) * r;
        }
    }
    let full = &full[..c.len()];
    (
        full.iter().fold(0.0f64, |a, f| a.max(f.0)) + part_te,
        full.iter().fold(0.0f64, |a, f| a.max(f.1)) + part_tm,
    )
}

/// Sub-boxes per cell axis for [`ratio_bound`]: sin θi (or s′), λ and |β|.
const PIECES: [usize; 3] = [8, 4, 4];

/// A bound of cos θm/cos θi over the cell of corners `c` for order m = `mf`: on each sub-box,
/// sup cos θm = √(1 − a² − β₀²) (a the sub-box's smallest |α_m|, 0 where its corners' α_m
/// straddle 0: α_m is monotone along each axis, so its range is the corners'; β₀ its
/// smallest |β|) over inf cos θi (the smallest corner's: cos θi is concave in s′ and falls
/// with |β|).
pub(super) fn ratio_bound(period_nm: f64, mf: f64, c: &[Corner]) -> f64 {
    // The cell's axes from its corners: corner 1 is the next s node, corner 2 the next |β|
    // node (conical) or λ node (classical), corner 4 the next λ node (conical).
    let conical = c.len() == 8;
    let cb = |b2: f64| math::sqrt(1.0 - b2);
    let (s0, s1) = (c[0].s, c[1].s);
    let (l0, l1) = (c[0].lambda_nm, c[if conical { 4 } else { 2 }].lambda_nm);
    let (b0, b1) = if conical {
        (c[0].b, c[2].b)
    } else {
        (0.0, 0.0)
    };
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let pb = if conical { PIECES[2] } else { 1 };
    let mut worst = 0.0f64;
    for ib in 0..pb {
        let (ba, bb) = (
            lerp(b0, b1, ib as f64 / pb as f64),
            lerp(b0, b1, (ib + 1) as f64 / pb as f64),
        );
        let (ca, cbb) = (cb(ba * ba), cb(bb * bb));
        for is in 0..PIECES[0] {
            let (sa, sb) = (
                lerp(s0, s1, is as f64 / PIECES[0] as f64),
                lerp(s0, s1, (is + 1) as f64 / PIECES[0] as f64),
            );
            let inf_cos_i = cbb * math::sqrt(1.0 - sa * sa).min(math::sqrt(1.0 - sb * sb));
            if inf_cos_i.is_nan() || inf_cos_i <= 0.0 {
                return f64::INFINITY;
            }
            for il in 0..PIECES[1] {
                let (la, lb) = (
                    lerp(l0, l1, il as f64 / PIECES[1] as f64),
                    lerp(l0, l1, (il + 1) as f64 / PIECES[1] as f64),
                );
                let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                for s in [sa, sb] {
                    for cbv in [ca, cbb] {
                        for l in [la, lb] {
                            let am = s * cbv + mf * l / period_nm;
                            lo = lo.min(am);
                            hi = hi.max(am);
                        }
                    }
                }
                let a = if lo <= 0.0 && hi >= 0.0 {
                    0.0
                } else {
                    lo.abs().min(hi.abs())
                };
                let sup2 = 1.0 - a * a - ba * ba;
                if sup2 > 0.0 {
                    worst = worst.max(math::sqrt(sup2) / inf_cos_i);
                }
            }
        }
    }
    // The rounding of the sub-boxes' edges and of the quotients: a relative 10⁻¹² on top, far
    // below the marks' margin.
    worst * (1.0 + 1e-12)
}

impl EfficiencyTable {
    /// Whether interpolation cell `cell` (numbered as `Cell` and `Cell3` number theirs) needs no
    /// normalisation: every query in it has Σ_m η_m ≤ 1 per polarisation (`unit.rs`; always
    /// `false` without `std`). For the GPU's packed table.
    #[cfg_attr(not(feature = "gpu"), allow(dead_code))]
    pub(crate) fn cell_needs_no_normalisation(&self, cell: usize) -> bool {
        with_arrays!(self, |sin, bet, lam, te, tm| self
            .unit
            .is_unit(cell, || self.marks_in(sin, bet, lam, te, tm)))
    }

    /// The marks of every cell of the table (`unit.rs`).
    pub(super) fn marks_in<T: Values + ?Sized>(
        &self,
        sin: &T,
        bet: &T,
        lam: &T,
        te: &T,
        tm: &T,
    ) -> Bits {
        let slice = sin.count() * bet.count().max(1) * lam.count();
        let (period, first, count) = (self.period_nm, self.order_min, self.order_count);
        let cells = cell_count(sin, bet, lam);
        marks(period, first, count, slice, cells, te, tm, |c, buf| {
            corners_of(sin, bet, lam, c, buf)
        })
    }
}

/// The number of interpolation cells of a grid (`bet` empty: classical).
pub(super) fn cell_count<T: Values + ?Sized>(sin: &T, bet: &T, lam: &T) -> usize {
    (sin.count() - 1) * bet.count().saturating_sub(1).max(1) * (lam.count() - 1)
}

/// The corners of cell `c` (numbered as [`Cell`] and `Cell3` number theirs) with the formulas
/// of their `find`, written to `buf`: their count (4 or 8).
pub(super) fn corners_of<T: Values + ?Sized>(
    sin: &T,
    bet: &T,
    lam: &T,
    c: usize,
    buf: &mut [Corner; 8],
) -> usize {
    let (n_s, n_b, n_l) = (sin.count(), bet.count(), lam.count());
    let i = c % (n_s - 1);
    let j = (c / (n_s - 1)) % (n_l - 1);
    if n_b == 0 {
        for (n, corner) in buf.iter_mut().take(4).enumerate() {
            let (di, dj) = (n & 1, n >> 1);
            let s = sin.at(i + di);
            *corner = Corner {
                s,
                b: 0.0,
                alpha: s,
                beta2: 0.0,
                lambda_nm: lam.at(j + dj),
                cos_i: math::sqrt(1.0 - s * s),
                index: (j + dj) * n_s + i + di,
            };
        }
        return 4;
    }
    let k = c / ((n_s - 1) * (n_l - 1));
    for (n, corner) in buf.iter_mut().enumerate() {
        let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
        let (s, b) = (sin.at(i + di), bet.at(k + dk));
        let cb = math::sqrt(1.0 - b * b);
        *corner = Corner {
            s,
            b,
            alpha: s * cb,
            beta2: b * b,
            lambda_nm: lam.at(j + dj),
            cos_i: cb * math::sqrt(1.0 - s * s),
            index: ((k + dk) * n_l + (j + dj)) * n_s + (i + di),
        };
    }
    8
}

#[cfg(all(test, feature = "std"))]
mod tests {
    use std::vec::Vec;

    use super::super::{EfficiencyTable, Storage};
    use super::{bound, Corner, UNIT_BOUND};
    use super::{cell_count, corners_of};

    /// The table's axes and values as f64 (the presets' f32 widened exactly).
    fn arrays(t: &EfficiencyTable) -> [Vec<f64>; 5] {
        let w = |v: &[f32]| v.iter().map(|&x| f64::from(x)).collect::<Vec<f64>>();
        match &t.storage {
            Storage::Static {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                te,
                tm,
            } => [w(sin_theta_i), w(abs_beta), w(lambda_nm), w(te), w(tm)],
            Storage::Owned {
                sin_theta_i,
                abs_beta,
                lambda_nm,
                te,
                tm,
            } => [
                sin_theta_i.clone(),
                abs_beta.clone(),
                lambda_nm.clone(),
                te.clone(),
                tm.clone(),
            ],
            Storage::Reduced { .. } => unreachable!("the classical and conical tables only"),
        }
    }

    /// Every cell's bound against the sums of `per_cell` random queries inside it: returns the
    /// share of marked cells and the largest sum/bound ratio seen.
    fn check(t: &EfficiencyTable, per_cell: usize, next: &mut impl FnMut() -> f64) -> (f64, f64) {
        let [sin, bet, lam, te, tm] = arrays(t);
        let (sin, bet, lam) = (sin.as_slice(), bet.as_slice(), lam.as_slice());
        let slice = sin.len() * bet.len().max(1) * lam.len();
        let cells = cell_count(sin, bet, lam);
        let (mut marked, mut worst) = (0usize, 0.0f64);
        let mut buf = [Corner::default(); 8];
        for c in 0..cells {
            let n = corners_of(sin, bet, lam, c, &mut buf);
            let (first, count) = (t.order_min, t.order_count);
            let (b_te, b_tm) = bound(t.period_nm, first, count, slice, &buf[..n], &*te, &*tm);
            if b_te <= UNIT_BOUND && b_tm <= UNIT_BOUND {
                marked += 1;
            }
            let i = c % (sin.len() - 1);
            let j = (c / (sin.len() - 1)) % (lam.len() - 1);
            let k = c / ((sin.len() - 1) * (lam.len() - 1));
            let within = |x: &[f64], at: usize, u: f64| x[at] + (x[at + 1] - x[at]) * u;
            for q in 0..per_cell {
                // Corners and edges exactly, then inside.
                let u = |next: &mut dyn FnMut() -> f64, e: usize| match q {
                    0..=3 => ((q >> e) & 1) as f64,
                    _ => next(),
                };
                let s = within(sin, i, u(next, 0));
                let l = within(lam, j, u(next, 1));
                let (alpha, beta) = if bet.is_empty() {
                    (s, 0.0)
                } else {
                    let b = within(bet, k, next());
                    (s * (1.0 - b * b).sqrt(), b)
                };
                let (st, sm) = t.each(alpha, beta, l, |_, _| {});
                for (sum, b) in [(st, b_te), (sm, b_tm)] {
                    if sum > 0.0 {
                        worst = worst.max(sum / b);
                    }
                }
            }
        }
        (marked as f64 / cells as f64, worst)
    }

    fn rng(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A random table with node sums in [0.5, 1] (TE) and [0.8, 1] (TM), `betas` empty for a
    /// classical one.
    fn random_table(next: &mut impl FnMut() -> f64, betas: &[f64]) -> EfficiencyTable {
        let d = 700.0 + 1500.0 * next();
        let (orders, first) = (7usize, -3i32);
        let n_s = 3 + (6.0 * next()) as usize;
        let n_l = 2 + (5.0 * next()) as usize;
        let s: Vec<f64> = (0..n_s)
            .map(|i| -0.995 + 1.99 * i as f64 / (n_s - 1) as f64)
            .collect();
        let l: Vec<f64> = (0..n_l)
            .map(|j| 360.0 + 470.0 * j as f64 / (n_l - 1) as f64)
            .collect();
        let planes = betas.len().max(1);
        let slice = n_s * planes * n_l;
        let (mut te, mut tm) = (vec![0.0; orders * slice], vec![0.0; orders * slice]);
        for kb in 0..planes {
            let b = betas.get(kb).copied().unwrap_or(0.0);
            for (j, &lj) in l.iter().enumerate() {
                for (i, &si) in s.iter().enumerate() {
                    let at = (kb * n_l + j) * n_s + i;
                    let live: Vec<usize> = (0..orders)
                        .filter(|&k| {
                            let am =
                                si * (1.0 - b * b).sqrt() + f64::from(first + k as i32) * lj / d;
                            1.0 - am * am - b * b > 0.0
                        })
                        .collect();
                    let raw: Vec<(f64, f64)> = live.iter().map(|_| (next(), next())).collect();
                    let (st, sm) = raw.iter().fold((0.0, 0.0), |(p, q), r| (p + r.0, q + r.1));
                    let (gt, gm) = (0.5 + 0.5 * next(), 0.8 + 0.2 * next());
                    for (&k, r) in live.iter().zip(&raw) {
                        te[k * slice + at] = r.0 / st * gt;
                        tm[k * slice + at] = r.1 / sm * gm;
                    }
                }
            }
        }
        if betas.is_empty() {
            EfficiencyTable::new(d, first, s, l, te, tm).unwrap()
        } else {
            EfficiencyTable::new_conical(d, first, s, betas.to_vec(), l, te, tm).unwrap()
        }
    }

    /// No query's sum (before the normalisation) exceeds its cell's bound, on the presets and
    /// on random classical and conical tables; the presets' marked shares are what was
    /// measured.
    #[test]
    fn cell_bounds_hold_and_mark_most_preset_cells() {
        let mut next = rng(3);
        let mut worst = 0.0f64;
        for _ in 0..30 {
            let t = random_table(&mut next, &[]);
            worst = worst.max(check(&t, 60, &mut next).1);
            let b0 = 0.6 * next();
            let b1 = b0 + 0.05 + 0.3 * next();
            let t = random_table(&mut next, &[b0, b1, b1 + 0.05]);
            worst = worst.max(check(&t, 60, &mut next).1);
        }
        #[cfg(feature = "presets")]
        for (p, least) in [
            // The measured shares (0.917, 0.806, 0.045, 0.479), less 0.02.
            (crate::relief::Preset::Cd, 0.897),
            (crate::relief::Preset::Dvd, 0.786),
            (crate::relief::Preset::Blazed600, 0.025),
            (crate::relief::Preset::Foil, 0.459),
        ] {
            let (share, w) = check(p.table(), 40, &mut next);
            std::println!("{p}: {share:.3} of the cells marked, sum/bound ≤ {w:.3}");
            assert!(share >= least, "{p}: {share}");
            worst = worst.max(w);
        }
        std::println!("largest sum/bound {worst}");
        assert!(worst <= 1.0 + 1e-12, "{worst}");
    }
}
