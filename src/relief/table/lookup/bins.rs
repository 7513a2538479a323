//! A table axis binned uniformly, for the cell search in O(1) of the parent module: each bin
//! keeps the count of the inner nodes below it, the node inside it and, for the two intervals
//! its values can fall in, the interval's first node and reciprocal width.

use std::vec::Vec;

/// One bin of an axis: the count `start` of inner nodes (after the first, before the last)
/// whose bin is below it, the
/// node inside it (`split`: +∞ where there is none, NaN where there are several), and for the
/// two intervals a value of the bin can be in (i = start, below the split, and start + 1, at
/// or above it; each at most n − 2) the interval's first node and 1/(its width).
#[derive(Debug, Clone, Copy)]
struct Bin {
    split: f64,
    start: u32,
    node: [f64; 2],
    inv: [f64; 2],
}

/// A table's axis binned uniformly: the bin of x is ⌊(x − x₀)·scale⌋; the axis's first and
/// last nodes (the clamp).
#[derive(Debug, Clone)]
pub(super) struct Bins {
    x0: f64,
    x1: f64,
    scale: f64,
    /// count + 1 bins: the last one pads the axis's end.
    bins: Vec<Bin>,
}

/// One value located on an axis: the interval i, its first node and 1/(its width).
#[derive(Debug, Clone, Copy)]
pub(super) struct Located {
    pub i: usize,
    pub node: f64,
    pub inv: f64,
}

/// The most bins per node interval (a grid whose smallest spacing is far below its mean one
/// gets this many, and a bin may then hold several nodes).
const MAX_BINS_PER_INTERVAL: usize = 8;

impl Bins {
    /// The binning of the strictly increasing `nodes` (at least 2, at most
    /// `MAX_TABLE_NODES`); `None` where the bins' scale count/span overflows (a span below
    /// about 10⁻³⁰⁸: a bin index would saturate past the bins).
    pub(super) fn new(nodes: &[f64]) -> Option<Bins> {
        let n = nodes.len();
        let span = nodes[n - 1] - nodes[0];
        let gap = nodes
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        // span/gap ≥ n − 1; an overflow saturates to the cap.
        let count = ((span / gap).ceil() as usize).clamp(1, MAX_BINS_PER_INTERVAL * (n - 1));
        let empty = Bin {
            split: f64::INFINITY,
            start: 0,
            node: [0.0; 2],
            inv: [0.0; 2],
        };
        let scale = count as f64 / span;
        if !scale.is_finite() {
            return None;
        }
        let mut b = Bins {
            x0: nodes[0],
            x1: nodes[n - 1],
            scale,
            bins: std::vec![empty; count + 1],
        };
        // Per bin (0..=count), the inner nodes inside it; the last node is left out (the
        // interval is at most n − 2 whatever x is).
        let mut inside = std::vec![0u32; count + 1];
        for &x in &nodes[1..n - 1] {
            let k = b.bin(x);
            inside[k] += 1;
            b.bins[k].split = if inside[k] == 1 { x } else { f64::NAN };
        }
        let mut below = 0;
        for (bin, &here) in b.bins.iter_mut().zip(&inside) {
            bin.start = below;
            below += here;
        }
        for bin in &mut b.bins {
            for up in 0..2 {
                let i = (bin.start as usize + up).min(n - 2);
                bin.node[up] = nodes[i];
                bin.inv[up] = 1.0 / (nodes[i + 1] - nodes[i]);
            }
        }
        Some(b)
    }

    /// How many bins hold several nodes (searched at a query).
    #[cfg(test)]
    pub(super) fn crowded(&self) -> usize {
        self.bins.iter().filter(|b| b.split.is_nan()).count()
    }

    /// The bin of x ≥ x₀ (monotone in x: a difference, a product by a positive constant and
    /// a truncation are).
    #[inline(always)]
    fn bin(&self, x: f64) -> usize {
        // `as` saturates: a value below x₀ is bin 0. On the axis (x ≤ x_{n−1}) the product is
        // at most count·(1 + 2⁻⁵¹): bin `count` at most, the padding bin.
        ((x - self.x0) * self.scale) as u32 as usize
    }

    /// x clamped to the axis (x finite).
    #[inline(always)]
    pub(super) fn clamp(&self, x: f64) -> f64 {
        if x < self.x0 {
            self.x0
        } else if x > self.x1 {
            self.x1
        } else {
            x
        }
    }

    /// The interval i of `nodes` (this binning's) holding x ∈ [x₀, x_{n−1}]: the count of
    /// nodes after the first at or below x, at most n − 2 (the parent module's binary search,
    /// `interval`). Nodes of the bins below x's are at or below x and those of the bins above
    /// it above x, so the count is the bin's `start` plus its nodes at or below x.
    #[inline(always)]
    pub(super) fn locate(&self, nodes: &[f64], inv: &[f64], x: f64) -> Located {
        let bin = self.bins[self.bin(x)];
        if bin.split.is_nan() {
            return Bins::several(bin, nodes, inv, x);
        }
        let up = usize::from(x >= bin.split);
        Located {
            i: (bin.start as usize + up).min(nodes.len() - 2),
            node: bin.node[up],
            inv: bin.inv[up],
        }
    }

    /// [`locate`](Self::locate) in a bin holding several nodes.
    #[inline(never)]
    fn several(bin: Bin, nodes: &[f64], inv: &[f64], x: f64) -> Located {
        let start = bin.start as usize;
        // The bin's nodes are the next ones; those at or below x a prefix of them.
        let end = nodes[start + 1..].partition_point(|&v| v <= x);
        let i = (start + end).min(nodes.len() - 2);
        Located {
            i,
            node: nodes[i],
            inv: inv[i],
        }
    }
}
