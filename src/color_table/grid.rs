//! The graded grid every colour table holds: its blocks, its refinement against a node
//! evaluator (with the tolerance of a node), the O(1) lookup and the O(1) mean over an interval.
//!
//! The grid is cut into block 0 = [0, u_lo) and then 2^`SUB_BITS` blocks per octave of u up to
//! 2; each block is uniform with a power-of-two number of intervals. Node positions follow
//! from (u_lo, the intervals of every block) alone, so that is all a stored table keeps besides
//! the node values (see `stored.rs`); derivatives and cumulative integrals are recomputed.

use alloc::vec::Vec;

use super::interpolant::{cell_integral, derivatives, hermite, Node};
use super::layout::{bounds, work_units, MAX_BLOCK_INTERVALS, SHIFT, TINY_FRACTION, U_MAX};
use crate::color::Xyz;
use crate::error::{Error, Requirement};
use crate::num::math::cbrt;

/// One uniform block of the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Block {
    /// First u of the block.
    pub u0: f64,
    /// Node spacing.
    pub h: f64,
    /// 1 / spacing.
    pub inv_h: f64,
    /// Index of the block's first node.
    pub first: u32,
    /// Number of intervals (≥ 1).
    pub n: u32,
}

/// A block while the grid is refined.
struct Work {
    pub u0: f64,
    pub h: f64,
    pub n: usize,
    /// Values at the n + 1 nodes.
    pub vals: Vec<[f64; 3]>,
    /// Values at the n midpoints (empty until computed).
    pub mids: Vec<[f64; 3]>,
    /// Refinement stopped by the node budget.
    pub capped: bool,
    /// The worst midpoint error at the last check.
    pub err: f64,
}

/// What a build needs besides the node evaluator.
pub(super) struct Plan {
    /// The requested accuracy (units of [`tolerance`]).
    pub accuracy: f64,
    /// The illuminant's white (the tolerance's chromatic reference).
    pub white: [f64; 3],
    /// The least error scale Y_b (in the table's units).
    pub floor: f64,
    /// From this u on a node's Y counts towards the scale (an order m ≠ 0 can reach the band).
    pub diffracted_from: f64,
    /// End of block 0.
    pub u_lo: f64,
    /// Block 0 is neither refined nor checked (its lookups are computed directly).
    pub skip_first: bool,
    /// The grating's period (nm), for the work units of an evaluation.
    pub period_nm: f64,
    /// The caps: nodes and work units.
    pub max_nodes: usize,
    pub max_work: usize,
}

/// The tabulated function: blocks, nodes with derivatives, cumulative integrals, the error
/// scale and the worst midpoint error of the build.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Grid {
    pub scale: f64,
    pub error: f64,
    /// End of block 0, and the key (bits >> SHIFT) of block 1.
    pub u_lo: f64,
    base_key: u64,
    blocks: Vec<Block>,
    nodes: Vec<Node>,
    /// ∫₀^{u_i} of the interpolant at every node.
    cumulative: Vec<[f64; 3]>,
}

/// The error allowed in channel `c` of `exact`, over the accuracy: the change of that channel
/// that moves CIELAB's f(t) = t^(1/3) (linear below t = (6/29)³) by 1/3, at the exposure
/// Y' = max(`scale`, Y) (t = channel / (white · Y')). So it is white_c·Y'·max(t, (6/29)³)^(2/3):
/// at most white_c·Y' for channels up to the white, 0.043·white_c·Y_b where the colour is dark.
pub(super) fn tolerance(exact: &[f64; 3], c: usize, scale: f64, white: [f64; 3]) -> f64 {
    const DARK: f64 = (6.0 / 29.0) * (6.0 / 29.0) * (6.0 / 29.0);
    let exposure = scale.max(exact[1]);
    let t = (exact[c] / (white[c] * exposure)).max(DARK);
    let r = cbrt(t);
    white[c] * exposure * r * r
}

/// The nodes of all blocks in order (shared ends once), their values, and each block's first
/// node index.
fn assemble(work: &[Work]) -> (Vec<f64>, Vec<[f64; 3]>, Vec<usize>) {
    let total = 1 + work.iter().map(|w| w.n).sum::<usize>();
    let (mut xs, mut fs, mut starts) = (
        Vec::with_capacity(total),
        Vec::with_capacity(total),
        Vec::with_capacity(work.len()),
    );
    for (k, w) in work.iter().enumerate() {
        starts.push(if k == 0 { 0 } else { xs.len() - 1 });
        let skip = (k > 0) as usize;
        for j in skip..=w.n {
            xs.push(w.u0 + j as f64 * w.h);
            fs.push(w.vals[j]);
        }
    }
    (xs, fs, starts)
}

/// The place of `a` ∈ [0, 2] in the blocks: (cell, fraction in it, spacing).
#[inline(always)]
fn locate(blocks: &[Block], u_lo: f64, base_key: u64, a: f64) -> (usize, f64, f64) {
    let k = if a < u_lo {
        0
    } else {
        // a ≥ u_lo, so its key is at least base_key.
        ((a.to_bits() >> SHIFT) - base_key + 1) as usize
    };
    let b = &blocks[k.min(blocks.len() - 1)];
    let t = (a - b.u0) * b.inv_h;
    // t ≥ 0 (a ≥ u0); `as` truncates toward 0, which is floor here, and saturates.
    let j = (t as u32).min(b.n - 1);
    ((b.first + j) as usize, t - j as f64, b.h)
}

/// A layout of blocks without node values: locates a point once for every grid on it.
#[cfg(feature = "relief")]
#[derive(Debug, Clone, PartialEq, Default)]
pub(super) struct Locator {
    u_lo: f64,
    base_key: u64,
    blocks: Vec<Block>,
}

#[cfg(feature = "relief")]
impl Locator {
    /// The place of `a` ∈ [0, 2] (as [`Grid::cell_value`] takes it); a locator without blocks
    /// is never asked.
    #[inline]
    pub(super) fn locate(&self, a: f64) -> (usize, f64, f64) {
        locate(&self.blocks, self.u_lo, self.base_key, a)
    }

    /// Heap memory, bytes.
    pub(super) fn heap_bytes(&self) -> usize {
        self.blocks.capacity() * core::mem::size_of::<Block>()
    }
}

impl Grid {
    /// Every block's (u0, h, first node, intervals) and every node's (value, derivative), for
    /// the GPU's upload structs.
    #[cfg(feature = "gpu")]
    #[allow(clippy::type_complexity)]
    pub fn gpu_parts(
        &self,
    ) -> (
        impl Iterator<Item = (f64, f64, u32, u32)> + '_,
        impl Iterator<Item = ([f64; 3], [f64; 3])> + '_,
    ) {
        (
            self.blocks.iter().map(|b| (b.u0, b.h, b.first, b.n)),
            self.nodes.iter().map(|n| (n.f, n.d)),
        )
    }

    /// Refines the grid until every interval's midpoint meets `plan.accuracy` (or a cap is
    /// reached, worst blocks first). `eval(u, scale)` is a node's value; `work_done` the work
    /// units it has spent so far (for the budget).
    pub(super) fn build(
        plan: &Plan,
        eval: &dyn Fn(f64, f64) -> [f64; 3],
        work_done: &dyn Fn() -> usize,
    ) -> Grid {
        let (accuracy, white, d) = (plan.accuracy, plan.white, plan.period_nm);
        let mut scale = plan.floor;
        let bounds = bounds(plan.u_lo);
        // Every block starts with two intervals, so that it is checked at two points.
        let values: Vec<[f64; 3]> = bounds.iter().map(|&u| eval(u, scale)).collect();
        let mut work: Vec<Work> = bounds
            .windows(2)
            .zip(values.windows(2))
            .map(|(b, v)| {
                let h = 0.5 * (b[1] - b[0]);
                Work {
                    u0: b[0],
                    h,
                    n: 2,
                    vals: alloc::vec![v[0], eval(b[0] + h, scale), v[1]],
                    mids: Vec::new(),
                    capped: false,
                    err: 0.0,
                }
            })
            .collect();
        if plan.skip_first {
            work[0].capped = true;
        }
        let mut nodes_used = 2 * bounds.len() - 1;
        for w in &work {
            for (j, v) in w.vals.iter().enumerate() {
                if w.u0 + j as f64 * w.h >= plan.diffracted_from {
                    scale = scale.max(v[1]);
                }
            }
        }

        loop {
            let (xs, fs, starts) = assemble(&work);
            let ds = derivatives(&xs, &fs);
            // Every block is checked against the current derivatives (a neighbour's refinement
            // changes them); only new midpoints cost an evaluation.
            let mut failing: Vec<(usize, f64)> = Vec::new();
            for (k, w) in work.iter_mut().enumerate() {
                if w.mids.is_empty() {
                    w.mids = (0..w.n)
                        .map(|j| eval(w.u0 + (j as f64 + 0.5) * w.h, scale))
                        .collect();
                    for (j, m) in w.mids.iter().enumerate() {
                        if w.u0 + (j as f64 + 0.5) * w.h >= plan.diffracted_from {
                            scale = scale.max(m[1]);
                        }
                    }
                }
                let mut err = 0.0f64;
                for (j, exact) in w.mids.iter().enumerate() {
                    let i = starts[k] + j;
                    for c in 0..3 {
                        let interp = 0.5 * (fs[i][c] + fs[i + 1][c])
                            + 0.125 * w.h * (ds[i][c] - ds[i + 1][c]);
                        let tol = tolerance(exact, c, scale, white);
                        err = err.max((interp - exact[c]).abs() / tol);
                    }
                }
                w.err = err;
                if err > accuracy && !w.capped {
                    failing.push((k, err));
                }
            }
            if failing.is_empty() {
                break;
            }
            failing.sort_unstable_by(|a, b| b.1.total_cmp(&a.1));
            // The evaluations spent and planned for the next round's midpoint checks.
            let mut planned = work_done();
            for (k, _) in failing {
                let w = &mut work[k];
                // Doubling adds w.n nodes (already evaluated as midpoints) and costs 2·w.n
                // new midpoint checks.
                let cost = 2 * w.n * work_units(d * (w.u0 + w.n as f64 * w.h));
                let over_budget = planned + cost > plan.max_work;
                if nodes_used + w.n > plan.max_nodes || w.n >= MAX_BLOCK_INTERVALS || over_budget {
                    w.capped = true;
                    continue;
                }
                planned += cost;
                nodes_used += w.n;
                let mut vals = Vec::with_capacity(2 * w.n + 1);
                for (j, m) in w.mids.iter().enumerate() {
                    vals.push(w.vals[j]);
                    vals.push(*m);
                }
                vals.push(w.vals[w.n]);
                w.vals = vals;
                w.mids = Vec::new();
                w.n *= 2;
                w.h *= 0.5;
            }
        }

        let skip = plan.skip_first as usize;
        let error = work.iter().skip(skip).fold(0.0f64, |m, w| m.max(w.err));
        Grid::assembled(&work, plan.u_lo, scale, error)
    }

    /// The table of the blocks `work` (their values set): derivatives, cumulative integrals.
    fn assembled(work: &[Work], u_lo: f64, scale: f64, error: f64) -> Grid {
        let (xs, fs, starts) = assemble(work);
        let ds = derivatives(&xs, &fs);
        let blocks: Vec<Block> = work
            .iter()
            .zip(&starts)
            .map(|(w, &first)| Block {
                u0: w.u0,
                h: w.h,
                inv_h: 1.0 / w.h,
                first: first as u32,
                n: w.n as u32,
            })
            .collect();
        let nodes: Vec<Node> = fs.iter().zip(&ds).map(|(&f, &d)| Node { f, d }).collect();
        let mut cumulative = Vec::with_capacity(nodes.len());
        let mut acc = [0.0; 3];
        cumulative.push(acc);
        for b in &blocks {
            for j in 0..b.n as usize {
                let i = b.first as usize + j;
                let cell = cell_integral(&nodes[i], &nodes[i + 1], b.h, 1.0);
                for c in 0..3 {
                    acc[c] += cell[c];
                }
                cumulative.push(acc);
            }
        }
        Grid {
            scale,
            error,
            u_lo,
            base_key: u_lo.to_bits() >> SHIFT,
            blocks,
            nodes,
            cumulative,
        }
    }

    /// The stored form: the intervals of every block and the node values (positions follow
    /// from `u_lo` and the intervals).
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(super) fn parts(&self) -> (Vec<u32>, Vec<[f64; 3]>) {
        (
            self.blocks.iter().map(|b| b.n).collect(),
            self.nodes.iter().map(|n| n.f).collect(),
        )
    }

    /// The table from its stored form, validated: `u_lo` a power of two in [`min_u_lo`, 1]
    /// (`expected_u_lo` where the table's model fixes it), one interval count per block of
    /// that layout, each a power of two in [2, 1024], 1 + Σ intervals values, at most
    /// `max_nodes`, every channel finite and in [0, `limits.value`]; `scale` in
    /// `limits.scale`, `error` in [0, `limits.error_times_scale`/scale]. The errors name the
    /// field.
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(super) fn from_parts(
        expected_u_lo: f64,
        stored: Stored<'_>,
        max_nodes: usize,
        limits: &Limits,
    ) -> Result<Grid, Error> {
        let Stored {
            u_lo,
            intervals,
            values,
            scale,
            error,
        } = stored;
        if u_lo.to_bits() != expected_u_lo.to_bits() {
            return Err(Error::invalid(
                "u_lo",
                u_lo,
                Requirement::Within {
                    min: expected_u_lo,
                    max: expected_u_lo,
                },
            ));
        }
        if !(scale > 0.0 && scale.is_finite()) {
            return Err(Error::invalid("scale", scale, Requirement::Positive));
        }
        let (min, max) = limits.scale;
        if !(scale >= min && scale <= max) {
            return Err(Error::invalid(
                "scale",
                scale,
                Requirement::Within { min, max },
            ));
        }
        if !(error >= 0.0 && error.is_finite()) {
            return Err(Error::invalid("error", error, Requirement::NonNegative));
        }
        let max = limits.error_times_scale / scale;
        if error > max {
            let requirement = Requirement::Within { min: 0.0, max };
            return Err(Error::invalid("error", error, requirement));
        }
        let bounds = bounds(u_lo);
        let blocks = bounds.len() - 1;
        if intervals.len() != blocks {
            let b = blocks as f64;
            return Err(Error::invalid(
                "intervals",
                intervals.len() as f64,
                Requirement::Within { min: b, max: b },
            ));
        }
        let mut total = 1usize;
        for &n in intervals {
            if !(2..=MAX_BLOCK_INTERVALS as u32).contains(&n) || !n.is_power_of_two() {
                return Err(Error::invalid(
                    "intervals",
                    n as f64,
                    Requirement::Within {
                        min: 2.0,
                        max: MAX_BLOCK_INTERVALS as f64,
                    },
                ));
            }
            total += n as usize;
        }
        if total > max_nodes {
            return Err(Error::invalid(
                "intervals",
                total as f64,
                Requirement::AtMost {
                    bound_name: "max_nodes",
                    bound: max_nodes as f64,
                },
            ));
        }
        if values.len() != total {
            let t = total as f64;
            return Err(Error::invalid(
                "values",
                values.len() as f64,
                Requirement::Within { min: t, max: t },
            ));
        }
        if let Some(bad) = values
            .iter()
            .flatten()
            .find(|v| !(**v >= 0.0 && v.is_finite()))
        {
            return Err(Error::invalid("values", *bad, Requirement::NonNegative));
        }
        for v in values {
            for (&x, &max) in v.iter().zip(&limits.value) {
                if x > max {
                    let requirement = Requirement::Within { min: 0.0, max };
                    return Err(Error::invalid("values", x, requirement));
                }
            }
        }
        let mut next = 0usize;
        let work: Vec<Work> = bounds
            .windows(2)
            .zip(intervals)
            .map(|(b, &n)| {
                let n = n as usize;
                let vals = values[next..=next + n].to_vec();
                next += n;
                Work {
                    u0: b[0],
                    // Exact: a halving per refinement of the block's width.
                    h: (b[1] - b[0]) / n as f64,
                    n,
                    vals,
                    mids: Vec::new(),
                    capped: false,
                    err: 0.0,
                }
            })
            .collect();
        Ok(Grid::assembled(&work, u_lo, scale, error))
    }

    /// The interpolated value at `a` ∈ [0, 2], each channel clamped at 0.
    #[inline]
    pub(super) fn value(&self, a: f64) -> Xyz {
        self.cell_value(self.locate(a))
    }

    /// The interpolated value at a place `(cell, fraction, spacing)` of this grid's layout
    /// (from [`locate`](Self::locate) or the [`Locator`] of a grid with the same layout), each
    /// channel clamped at 0.
    #[inline]
    pub(super) fn cell_value(&self, (i, s, h): (usize, f64, f64)) -> Xyz {
        let f = hermite(&self.nodes[i], &self.nodes[i + 1], h, s);
        Xyz::new(f[0].max(0.0), f[1].max(0.0), f[2].max(0.0))
    }

    /// Whether `other` has this grid's blocks, so that one [`Locator`] serves both.
    #[cfg(feature = "relief")]
    pub(super) fn same_layout(&self, other: &Grid) -> bool {
        self.u_lo == other.u_lo && self.blocks == other.blocks
    }

    /// The grid's layout alone, to locate points once for several grids of that layout.
    #[cfg(feature = "relief")]
    pub(super) fn locator(&self) -> Locator {
        Locator {
            u_lo: self.u_lo,
            base_key: self.base_key,
            blocks: self.blocks.clone(),
        }
    }

    /// The mean over [u0, u1] of the even function whose value at a point is `point(u)` and
    /// whose integral is the interpolant's (see `ColorTable::mean`).
    pub(super) fn mean(&self, u0: f64, u1: f64, point: &dyn Fn(f64) -> Xyz) -> Xyz {
        if !(u0.is_finite() && u1.is_finite()) {
            return Xyz::default();
        }
        let (a, b) = if u0 <= u1 { (u0, u1) } else { (u1, u0) };
        let len = b - a;
        let mid = 0.5 * a + 0.5 * b;
        let (_, _, h) = self.locate(mid.abs().min(U_MAX));
        // Finite ends: len is not NaN (it may overflow to +∞, handled below).
        if len <= TINY_FRACTION * h {
            return point(mid);
        }
        // ∫_a^b XYZ(|u|) du = F(b) − F(a) with F odd, F(v) = ∫₀^v for v ≥ 0; clamped to [−2, 2].
        let (ca, cb) = (a.clamp(-U_MAX, U_MAX), b.clamp(-U_MAX, U_MAX));
        let inside = if ca >= 0.0 {
            self.integral(ca, cb)
        } else if cb <= 0.0 {
            self.integral(-cb, -ca)
        } else {
            let (l, r) = (self.integral(0.0, -ca), self.integral(0.0, cb));
            [l[0] + r[0], l[1] + r[1], l[2] + r[2]]
        };
        let mut m = [inside[0] / len, inside[1] / len, inside[2] / len];
        let outside = 1.0 - (cb - ca) / len;
        if outside > 0.0 {
            let edge = point(U_MAX);
            m[0] += outside * edge.x;
            m[1] += outside * edge.y;
            m[2] += outside * edge.z;
        }
        Xyz::new(m[0].max(0.0), m[1].max(0.0), m[2].max(0.0))
    }

    /// ∫ over [a, b] of the interpolant, 0 ≤ a ≤ b ≤ 2: whole cells from the cumulative sums,
    /// the partial cells at each end directly, so that no digits are lost to large sums.
    fn integral(&self, a: f64, b: f64) -> [f64; 3] {
        let (ia, sa, ha) = self.locate(a);
        let (ib, sb, hb) = self.locate(b);
        if ia == ib {
            let lo = cell_integral(&self.nodes[ia], &self.nodes[ia + 1], ha, sa);
            let hi = cell_integral(&self.nodes[ib], &self.nodes[ib + 1], hb, sb);
            return [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
        }
        // [a, node ia + 1]: the cell's rest; whole cells ia + 1 .. ib; [node ib, b].
        let whole_a = cell_integral(&self.nodes[ia], &self.nodes[ia + 1], ha, 1.0);
        let part_a = cell_integral(&self.nodes[ia], &self.nodes[ia + 1], ha, sa);
        let part_b = cell_integral(&self.nodes[ib], &self.nodes[ib + 1], hb, sb);
        let (c0, c1) = (&self.cumulative[ia + 1], &self.cumulative[ib]);
        let mut out = [0.0; 3];
        for c in 0..3 {
            out[c] = (whole_a[c] - part_a[c]) + (c1[c] - c0[c]) + part_b[c];
        }
        out
    }

    /// The node index, the fraction in [0, 1] and the spacing of the cell holding `a` ∈ [0, 2].
    #[inline]
    fn locate(&self, a: f64) -> (usize, f64, f64) {
        locate(&self.blocks, self.u_lo, self.base_key, a)
    }

    /// The number of intervals of every block.
    #[cfg(feature = "relief")]
    pub(super) fn intervals(&self) -> Vec<u32> {
        self.blocks.iter().map(|b| b.n).collect()
    }

    /// The grid whose blocks after block 0 = [0, `u_lo`) have `intervals` (one per block of
    /// that layout, powers of two: the caller's), its node values from `eval`, its error scale
    /// `scale` and no error estimate (its nodes are not checked).
    #[cfg(feature = "relief")]
    pub(super) fn on_layout(
        u_lo: f64,
        intervals: &[u32],
        scale: f64,
        eval: &dyn Fn(f64) -> [f64; 3],
    ) -> Grid {
        let bounds = bounds(u_lo);
        let mut work: Vec<Work> = Vec::with_capacity(intervals.len());
        for (b, &n) in bounds.windows(2).zip(intervals) {
            let n = n.max(1) as usize;
            let h = (b[1] - b[0]) / n as f64;
            let mut vals = Vec::with_capacity(n + 1);
            // A block's first node is the last of the block before.
            match work.last() {
                Some(w) => vals.push(w.vals[w.n]),
                None => vals.push(eval(b[0])),
            }
            vals.extend((1..=n).map(|j| eval(b[0] + j as f64 * h)));
            work.push(Work {
                u0: b[0],
                h,
                n,
                vals,
                mids: Vec::new(),
                capped: false,
                err: 0.0,
            });
        }
        Grid::assembled(&work, u_lo, scale, 0.0)
    }

    /// The positions of the nodes.
    #[cfg(feature = "relief")]
    pub(super) fn positions(&self) -> impl Iterator<Item = f64> + '_ {
        let last = self.blocks.last().map(|b| b.u0 + b.n as f64 * b.h);
        self.blocks
            .iter()
            .flat_map(|b| (0..b.n).map(move |j| b.u0 + j as f64 * b.h))
            .chain(last)
    }

    /// The number of nodes.
    pub(super) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Heap memory, bytes.
    pub(super) fn heap_bytes(&self) -> usize {
        self.blocks.capacity() * core::mem::size_of::<Block>()
            + self.nodes.capacity() * core::mem::size_of::<Node>()
            + self.cumulative.capacity() * core::mem::size_of::<[f64; 3]>()
    }
}

/// What a build of the stored table's source can produce (see [`Grid::from_parts`]): the
/// largest node value per channel, the range of the error scale, and a bound of
/// error·scale (the worst midpoint error is a difference of bounded colours over a tolerance of
/// at least (6/29)²·white·scale).
#[cfg_attr(not(feature = "serde"), allow(dead_code))]
pub(super) struct Limits {
    pub value: [f64; 3],
    pub scale: (f64, f64),
    pub error_times_scale: f64,
}

/// A table's stored fields (see [`Grid::from_parts`]).
#[cfg_attr(not(feature = "serde"), allow(dead_code))]
pub(super) struct Stored<'a> {
    pub u_lo: f64,
    pub intervals: &'a [u32],
    pub values: &'a [[f64; 3]],
    pub scale: f64,
    pub error: f64,
}
