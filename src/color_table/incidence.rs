//! The table of a tabulated grating (feature `relief`): its colour C(u, s) depends on the
//! incidence s = wi.x as well as on u, so the table holds one pair of graded grids over u (one
//! for u ≥ 0, one for u ≤ 0, each by [`Grid::build`]) per incidence node, and interpolates
//! linearly between the two nodes around a lookup.
//!
//! The incidence is parametrised by τ ∈ [0, 1], its place between the two grazing directions
//! at that u: s = max(−1, u − 1) + τ·(2 − |u|) (τ = 0 where wo grazes, 1 where wi does). So a
//! node's grid follows the directions above the surface, and no interval of nodes straddles
//! the horizon of wo (at fixed s, interpolation would cross the line |u − s| = 1 where the
//! colour falls to 0). Near either end the efficiencies of the grazing direction rise as the
//! square root of its cosine², so the nodes are uniform in σ with τ = σ²/(σ² + (1 − σ)²),
//! which makes that square root linear in σ at both ends.
//!
//! The nodes start every 1/[`BASE_INTERVALS`] of σ and are refined by
//! bisection: an interval's midpoint node is built and compared, at every node of its grids,
//! with the interpolation of the interval's ends (by the grids' own tolerance, at the table's
//! error scale); where it misses the table's accuracy the midpoint is kept and both halves are
//! checked in turn, down to [`depth`] halvings ([`MAX_DEPTH`] at 10⁻³ and coarser, up to
//! [`FINE_DEPTH`] for finer accuracies). The nodes after the first take the first nodes'
//! layout over u (per block their most intervals, at most `ColorTable::MAX_NODES` nodes in
//! all), so that they cost one evaluation a node and no midpoint checks; the inner first nodes
//! are then rebuilt on that layout too, so that every node but the two grazing ends is on it.
//! A lookup locates its interval in O(1) from the bins of the finest level, and between two
//! nodes on the layout locates |u| once for both grids.
//!
//! A conical table's colour has one such table per plane |wi.y| = β (`source::COLOUR_PLANES`),
//! whose incidences run between the grazing directions |wi.x|, |wo.x| < r = √(1 − β²): the
//! place σ of (u, s) there is the place of (u/r, s/r) on the plane β = 0 (`r` is 1 there, and
//! every formula then the plane's own).

use alloc::vec::Vec;

use super::grid::{tolerance, Grid, Locator, Plan};
use super::tabulated_nodes::TabulatedNodes;
use crate::color::Xyz;
use crate::num::math::sqrt;

/// Intervals of the first incidence nodes over [−1, 1].
pub(super) const BASE_INTERVALS: usize = 8;
/// The most halvings of a first interval at accuracies of 10⁻³ and coarser.
pub(super) const MAX_DEPTH: u32 = 4;
/// The most halvings of a first interval at any accuracy: one more per halving of the
/// accuracy below 10⁻³, up to this (at most 513 incidence nodes).
pub(super) const FINE_DEPTH: u32 = 6;

/// The most halvings of a first interval at `accuracy` (the table's, not the grids'):
/// [`MAX_DEPTH`] at 10⁻³ and coarser, one more per factor 2 below it, at most [`FINE_DEPTH`].
pub(super) fn depth(accuracy: f64) -> u32 {
    let mut depth = MAX_DEPTH;
    let mut a = 1e-3;
    while depth < FINE_DEPTH && accuracy < a {
        depth += 1;
        a *= 0.5;
    }
    depth
}

/// The grids over u ≤ 0 are those over u ≥ 0 where the efficiencies are mirror symmetric
/// (`TabulatedNodes::mirror_symmetric`) to within this fraction of the table's accuracy: an
/// efficiency off by δ moves the colour by at most δ times that of an order of efficiency 1,
/// which the error scale is at least.
const MIRROR_SHARE: f64 = 16.0;

/// The end nodes are evaluated this far (in τ) inside the grazing directions, where the colour
/// has its limit (exactly at grazing the BSDF is 0).
const GRAZING: f64 = 1e-6;

/// The incidence s = wi.x at u of the node σ: s runs over the directions above the surface at
/// u, from max(−1, u − 1) (σ = 0) to min(1, u + 1) (σ = 1), where wo or wi grazes, as
/// τ = σ²/(σ² + (1 − σ)²) (see the module docs).
#[inline]
fn incidence(u: f64, sigma: f64) -> f64 {
    let (a, b) = (sigma * sigma, (1.0 - sigma) * (1.0 - sigma));
    let tau = (a / (a + b)).clamp(GRAZING, 1.0 - GRAZING);
    u.max(0.0) - 1.0 + tau * (2.0 - u.abs())
}

/// The node coordinate σ of (u, s) (the inverse of [`incidence`]): σ = √τ/(√τ + √(1 − τ))
/// with τ = p/w, p = s − max(−1, u − 1) and w = 2 − |u|, computed as √p/(√p + √(w − p)) (one
/// division, after two independent square roots); `None` outside 0 ≤ p ≤ w (a direction below
/// the surface) and where w is not positive.
#[inline]
pub(super) fn coordinate(u: f64, s: f64) -> Option<f64> {
    let width = 2.0 - u.abs();
    let p = s - u.max(0.0) + 1.0;
    if !(width > 0.0 && (0.0..=width).contains(&p)) {
        return None;
    }
    Some(place(p, width))
}

/// σ = √p/(√p + √(w − p)) for 0 ≤ p ≤ w, w > 0 (see [`coordinate`]).
#[inline]
pub(super) fn place(p: f64, width: f64) -> f64 {
    let (a, b) = (sqrt(p), sqrt(width - p));
    a / (a + b)
}

/// One incidence node: σ (its field `s`) and its grids over u ≥ 0 and u ≤ 0 (the latter in
/// |u|; `None` where it is the former, see [`mirror_symmetric`]).
#[derive(Debug, Clone, PartialEq)]
struct Node {
    s: f64,
    /// 1/(s of the next node − s), 0 on the last node (set once the nodes are placed).
    inv_next: f64,
    pos: Grid,
    neg: Option<Grid>,
    /// Both grids are on the table's layouts (`Incidence::locators`).
    shared: bool,
}

impl Node {
    /// The grid over u ≤ 0 (in |u|).
    #[inline]
    fn neg(&self) -> &Grid {
        self.neg.as_ref().unwrap_or(&self.pos)
    }

    /// The grids over u ≥ 0 and, where it is its own, over u ≤ 0.
    fn grids(&self) -> impl Iterator<Item = &Grid> {
        core::iter::once(&self.pos).chain(self.neg.as_ref())
    }
}

/// The grids of every incidence node and the O(1) location of an incidence.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Incidence {
    nodes: Vec<Node>,
    /// The layouts over u ≥ 0 and u ≤ 0 of the nodes marked `shared`: an interval between
    /// two such nodes locates |u| once for both.
    locators: [Locator; 2],
    /// For each bin of the finest level over [−1, 1], the node starting its interval.
    bins: Vec<u32>,
    /// Bins per unit of s.
    inv_bin: f64,
    /// The plane's r = √(1 − β²) (1 on the plane across the grooves): its incidences run
    /// between the grazing directions of |wi.x|, |wo.x| < r, at r times the places of the
    /// plane β = 0 (`incidence(u/r, σ)·r`).
    r: f64,
    /// The error scale (the largest Y of a diffracted colour) and the worst error found.
    pub scale: f64,
    pub error: f64,
}

/// What the refinement needs.
struct Build<'a> {
    nodes: &'a TabulatedNodes,
    plan: Plan,
    /// The layouts of the refined nodes over u ≥ 0 and u ≤ 0: per block the most intervals
    /// of the first nodes' grids.
    layouts: [Vec<u32>; 2],
    scale: f64,
    error: f64,
    /// The bisection's accuracy (the table's own, finer than the grids' where asked) and its
    /// most halvings.
    accuracy: f64,
    max_depth: u32,
    /// Whether the grids over u ≤ 0 are those over u ≥ 0 ([`mirror_symmetric`]).
    mirrored: bool,
    /// The plane's r (`TabulatedNodes::r`).
    r: f64,
}

impl Build<'_> {
    /// The grids at σ, refined in u (the first nodes).
    fn refined(&mut self, s: f64) -> Node {
        let n = self.nodes;
        // Each grid has its own budget.
        let start = n.work_done.get();
        let r = self.r;
        let pos = Grid::build(
            &self.plan,
            &|a, _| n.eval(a, r * incidence(a / r, s)),
            &|| n.work_done.get() - start,
        );
        let neg = (!self.mirrored).then(|| {
            let start = n.work_done.get();
            Grid::build(
                &self.plan,
                &|a, _| n.eval(-a, r * incidence(-a / r, s)),
                &|| n.work_done.get() - start,
            )
        });
        for g in core::iter::once(&pos).chain(neg.as_ref()) {
            self.scale = self.scale.max(g.scale);
            self.error = self.error.max(g.error);
        }
        Node {
            s,
            inv_next: 0.0,
            pos,
            neg,
            shared: false,
        }
    }

    /// The grids at σ on the layouts.
    fn node(&mut self, s: f64) -> Node {
        let (n, u_lo, r) = (self.nodes, self.plan.u_lo, self.r);
        let pos = Grid::on_layout(u_lo, &self.layouts[0], self.scale, &|a| {
            n.eval(a, r * incidence(a / r, s))
        });
        let neg = (!self.mirrored).then(|| {
            Grid::on_layout(u_lo, &self.layouts[1], self.scale, &|a| {
                n.eval(-a, r * incidence(-a / r, s))
            })
        });
        Node {
            s,
            inv_next: 0.0,
            pos,
            neg,
            shared: true,
        }
    }

    /// The worst error of the interpolation of `a` and `b` at the nodes of `mid`'s grids.
    fn error(&self, a: &Node, b: &Node, mid: &Node) -> f64 {
        let white = self.plan.white;
        let mut worst = 0.0f64;
        for ((ga, gb), gm) in a.grids().zip(b.grids()).zip(mid.grids()) {
            for u in gm.positions() {
                let exact = gm.value(u);
                let (x, y) = (ga.value(u), gb.value(u));
                let exact = [exact.x, exact.y, exact.z];
                let interp = [0.5 * (x.x + y.x), 0.5 * (x.y + y.y), 0.5 * (x.z + y.z)];
                for c in 0..3 {
                    let tol = tolerance(&exact, c, self.scale, white);
                    worst = worst.max((interp[c] - exact[c]).abs() / tol);
                }
            }
        }
        worst
    }

    /// Appends the nodes between the last of `out` and `right` (bisected while the midpoint
    /// misses the accuracy), then `right`.
    fn refine(&mut self, out: &mut Vec<(Node, u32)>, right: Node, depth: u32) {
        if depth < self.max_depth {
            let left = &out[out.len() - 1].0;
            let mid = self.node(0.5 * (left.s + right.s));
            let err = self.error(left, &right, &mid);
            if err > self.accuracy {
                self.refine(out, mid, depth + 1);
                self.refine(out, right, depth + 1);
                return;
            }
            self.error = self.error.max(err);
        }
        out.push((right, depth));
    }
}

impl Incidence {
    /// The table of `nodes` with the grids' `plan`: the first nodes refined in u (normal
    /// incidence first, whose error scale becomes the floor of the others, so that every node
    /// is refined at the table's one scale), the others on the layouts of the first ones.
    /// The incidence nodes are bisected to `accuracy` (which may be finer than the plan's, the
    /// grids'), at most [`depth`]`(accuracy)` times. Returns the grid of normal incidence over
    /// u ≥ 0 too.
    pub(super) fn build(
        nodes: &TabulatedNodes,
        mut plan: Plan,
        accuracy: f64,
    ) -> (Incidence, Grid) {
        let r = nodes.r();
        let normal = Grid::build(&plan, &|u, _| nodes.eval(u, 0.0), &|| nodes.work_done.get());
        plan.floor = plan.floor.max(normal.scale);
        let mut b = Build {
            nodes,
            scale: plan.floor,
            plan,
            layouts: [Vec::new(), Vec::new()],
            error: 0.0,
            accuracy,
            max_depth: depth(accuracy),
            mirrored: nodes.mirror_symmetric(accuracy / MIRROR_SHARE),
            r,
        };
        let base = |k: usize| k as f64 / BASE_INTERVALS as f64;
        let first: Vec<Node> = (0..=BASE_INTERVALS).map(|k| b.refined(base(k))).collect();
        for (side, layout) in b.layouts.iter_mut().enumerate() {
            // The grazing ends' grids resolve their square-root edges, which no inner node needs.
            for n in &first[1..BASE_INTERVALS] {
                let grid = if side == 0 { &n.pos } else { n.neg() };
                let intervals = grid.intervals();
                if layout.is_empty() {
                    *layout = intervals;
                } else {
                    for (l, i) in layout.iter_mut().zip(intervals) {
                        *l = (*l).max(i);
                    }
                }
            }
        }
        // At most `max_nodes` nodes a grid, as a refined one: the largest blocks halved.
        for layout in &mut b.layouts {
            while 1 + layout.iter().map(|&n| n as usize).sum::<usize>() > b.plan.max_nodes {
                match layout.iter_mut().filter(|n| **n > 2).max_by_key(|n| **n) {
                    Some(n) => *n /= 2,
                    None => break,
                }
            }
        }
        // The inner first nodes again on the layouts (at least their own intervals in every
        // block the cap left alone), so that every interval away from the grazing ends locates
        // |u| once for both of its nodes.
        let first: Vec<Node> = first
            .into_iter()
            .enumerate()
            .map(|(k, n)| match k {
                0 | BASE_INTERVALS => n,
                _ => b.node(n.s),
            })
            .collect();
        let mut first = first.into_iter();
        let mut out: Vec<(Node, u32)> = Vec::new();
        if let Some(n) = first.next() {
            out.push((n, 0));
        }
        for right in first {
            b.refine(&mut out, right, 0);
        }
        // Each node after the first closes an interval of 2^(max_depth − depth) finest bins.
        let max_depth = b.max_depth;
        let mut bins = Vec::with_capacity(BASE_INTERVALS << max_depth);
        for (i, (_, depth)) in out.iter().enumerate().skip(1) {
            for _ in 0..1usize << (max_depth - depth) {
                bins.push((i - 1) as u32);
            }
        }
        let inv_bin = bins.len() as f64;
        let mut nodes: Vec<Node> = out.into_iter().map(|(n, _)| n).collect();
        for i in 1..nodes.len() {
            nodes[i - 1].inv_next = 1.0 / (nodes[i].s - nodes[i - 1].s);
        }
        let locators = match nodes.iter().find(|n| n.shared) {
            Some(first) => {
                debug_assert!(nodes.iter().filter(|n| n.shared).all(|n| {
                    n.pos.same_layout(&first.pos) && n.neg().same_layout(first.neg())
                }));
                [first.pos.locator(), first.neg().locator()]
            }
            None => Default::default(),
        };
        let table = Incidence {
            nodes,
            locators,
            bins,
            inv_bin,
            r,
            scale: b.scale,
            error: b.error,
        };
        (table, normal)
    }

    /// C(u, s) interpolated: Hermite in u on both nodes around τ(u, s), linear between them;
    /// `u` in [−2, 2] and `s` in [−1, 1] (the caller's ranges).
    #[inline]
    pub(super) fn value(&self, u: f64, s: f64) -> Xyz {
        match coordinate(u / self.r, s / self.r) {
            Some(sigma) => self.value_at(u, sigma),
            None => Xyz::default(),
        }
    }

    /// C at u and the node coordinate σ in [0, 1] (`coordinate`, of a plane of the caller's r).
    #[inline]
    pub(super) fn value_at(&self, u: f64, s: f64) -> Xyz {
        let t = s * self.inv_bin;
        // t ≥ 0; `as` truncates toward 0 and saturates.
        let bin = (t as usize).min(self.bins.len() - 1);
        let i = self.bins[bin] as usize;
        let (a, b) = (&self.nodes[i], &self.nodes[i + 1]);
        let w = ((s - a.s) * a.inv_next).clamp(0.0, 1.0);
        let m = u.abs();
        let (ga, gb) = if u >= 0.0 {
            (&a.pos, &b.pos)
        } else {
            (a.neg(), b.neg())
        };
        let (x, y) = if a.shared && b.shared {
            // One layout: |u| located once, both cells read side by side.
            let cell = self.locators[usize::from(u < 0.0)].locate(m);
            (ga.cell_value(cell), gb.cell_value(cell))
        } else {
            (ga.value(m), gb.value(m))
        };
        x.scale(1.0 - w) + y.scale(w)
    }

    /// The incidence nodes.
    pub(super) fn incidence_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nodes of all grids.
    pub(super) fn node_count(&self) -> usize {
        self.nodes
            .iter()
            .flat_map(Node::grids)
            .map(Grid::node_count)
            .sum()
    }

    /// Heap memory, bytes.
    pub(super) fn heap_bytes(&self) -> usize {
        self.bins.capacity() * core::mem::size_of::<u32>()
            + self.locators.iter().map(Locator::heap_bytes).sum::<usize>()
            + self.nodes.capacity() * core::mem::size_of::<Node>()
            + self
                .nodes
                .iter()
                .flat_map(Node::grids)
                .map(Grid::heap_bytes)
                .sum::<usize>()
    }
}

/// One grid for `gpu::GpuColorTable`: its blocks (u0, h, first node, intervals) and nodes
/// (value, derivative), as [`Grid::gpu_parts`].
#[cfg(feature = "gpu")]
pub(crate) type GpuGrid = (Vec<(f64, f64, u32, u32)>, Vec<([f64; 3], [f64; 3])>);

/// The incidence of a tabulated table for `gpu::GpuColorTable`: the bins (the node starting
/// each finest interval), per node σ and 1/(next σ − σ) (0 on the last), and per node its grids
/// over u ≥ 0 and u ≤ 0, in that order.
#[cfg(feature = "gpu")]
pub(crate) struct GpuIncidence<'a> {
    pub bins: &'a [u32],
    pub nodes: Vec<(f64, f64)>,
    pub grids: Vec<GpuGrid>,
}

#[cfg(feature = "gpu")]
impl Incidence {
    /// The nodes and their grids for the GPU.
    fn gpu(&self) -> GpuIncidence<'_> {
        let parts = |g: &Grid| {
            let (blocks, nodes) = g.gpu_parts();
            (blocks.collect(), nodes.collect())
        };
        GpuIncidence {
            bins: &self.bins,
            nodes: self.nodes.iter().map(|n| (n.s, n.inv_next)).collect(),
            grids: self
                .nodes
                .iter()
                .flat_map(|n| [parts(&n.pos), parts(n.neg())])
                .collect(),
        }
    }
}

#[cfg(feature = "gpu")]
impl super::ColorTable {
    /// The incidence nodes and their grids (`None` for a table without incidence).
    pub(crate) fn gpu_incidence(&self) -> Option<GpuIncidence<'_>> {
        Some(self.tabulated()?.gpu())
    }

    /// A conical table's planes off the plane across the grooves: (|wi.y|, c = √(1 − wi.y²),
    /// the plane's incidence nodes and grids); empty for any other table.
    pub(crate) fn gpu_planes(&self) -> Vec<(f64, f64, GpuIncidence<'_>)> {
        self.planes().map(|(b, c, t)| (b, c, t.gpu())).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Incidence::value`] without the shared locators: both grids located on their own.
    fn value_by_grids(t: &Incidence, u: f64, s: f64) -> Option<Xyz> {
        let s = coordinate(u, s)?;
        let bin = ((s * t.inv_bin) as usize).min(t.bins.len() - 1);
        let i = t.bins[bin] as usize;
        let (a, b) = (&t.nodes[i], &t.nodes[i + 1]);
        let w = ((s - a.s) * a.inv_next).clamp(0.0, 1.0);
        let m = u.abs();
        let (x, y) = if u >= 0.0 {
            (a.pos.value(m), b.pos.value(m))
        } else {
            (a.neg().value(m), b.neg().value(m))
        };
        Some(x.scale(1.0 - w) + y.scale(w))
    }

    /// Locating |u| once for two nodes on the layouts gives each grid's own reading to the
    /// bit, over u ≥ 0 and u ≤ 0 of a grating with and without mirror symmetry; and every
    /// interval away from the two grazing ends takes that path.
    #[cfg(feature = "presets")]
    #[test]
    fn shared_locators_read_as_the_grids() {
        use crate::relief::Preset;
        use crate::spectrum::{Illuminant, Spectral};
        use crate::{ColorTable, GratingBsdf, GrooveSpread};
        let spectral = Spectral::new(Illuminant::D65);
        for preset in [Preset::Blazed600, Preset::Cd] {
            let b = GratingBsdf::preset(preset, 8)
                .unwrap()
                .with_groove(GrooveSpread::gaussian(0.02).unwrap());
            let table = ColorTable::new(&spectral, &b, 1e-1).unwrap();
            let t = table.tabulated().unwrap();
            let inner = &t.nodes[1..t.nodes.len() - 1];
            assert!(inner.iter().all(|n| n.shared), "{preset}");
            assert!(!t.nodes[0].shared && !t.nodes[t.nodes.len() - 1].shared);
            // The R₂ low-discrepancy sequence over (u, s) ∈ [−2, 2] × [−1, 1].
            let (a1, a2) = (0.754_877_666_246_692_7, 0.569_840_290_998_053_3);
            let frac = |x: f64| x - (x as u64) as f64;
            let mut lit = 0;
            for k in 0..20_000 {
                let k = f64::from(k);
                let (u, s) = (4.0 * frac(k * a1) - 2.0, 2.0 * frac(k * a2) - 1.0);
                let want = value_by_grids(t, u, s).unwrap_or_default();
                assert_eq!(t.value(u, s), want, "{preset}: u {u}, s {s}");
                lit += usize::from(want != Xyz::default());
            }
            // Half the rectangle has both directions above the surface (s spans 2 − |u|).
            assert!(lit > 9_000, "{preset}: {lit} lit");
        }
    }

    #[test]
    fn depth_grows_one_halving_per_halved_accuracy() {
        assert_eq!(depth(1.0), MAX_DEPTH);
        assert_eq!(depth(1e-3), MAX_DEPTH);
        assert_eq!(depth(7e-4), MAX_DEPTH + 1);
        assert_eq!(depth(5e-4), MAX_DEPTH + 1);
        assert_eq!(depth(2.5e-4), MAX_DEPTH + 2);
        assert_eq!(depth(1e-6), FINE_DEPTH);
        assert_eq!(depth(f64::MIN_POSITIVE), FINE_DEPTH);
    }
}
