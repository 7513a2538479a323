//! A conical table's parts for the GPU's packed table (`gpu/tabulated.rs`): its axes, the
//! nodes' q's with the corner formulas of [`Reduced::find`](super::Reduced::find) (a reduced
//! table, version 3) or `Cell3::find` (a tensor grid, version 2: every plane on the same
//! wavelength nodes), the stored unpolarised values the proposal reads, and the single-order
//! marks in the table's cell numbering.

use alloc::vec::Vec;

use super::super::nodes_q::NOT_PROPAGATING;
use super::super::{EfficiencyTable, Storage};
use super::cb;

/// What the GPU's packed table holds of a conical table (feature `gpu`).
pub(crate) struct ReducedParts {
    /// A version-2 tensor grid (blended linearly in |β|, every plane read at the query's λ,
    /// cells numbered (k·(n_λ − 1) + j)·(n_s − 1) + i), not a reduced table.
    pub tensor: bool,
    /// The planes' |β| and c = √(1 − β²).
    pub abs_beta: Vec<f64>,
    pub c: Vec<f64>,
    /// rows\[p\]: the first wavelength row of plane p (rows\[n_β\]: every plane's rows).
    pub rows: Vec<usize>,
    /// Every plane's wavelength nodes, plane after plane.
    pub lambda_nm: Vec<f64>,
    /// The band of physical wavelengths a query is clamped to.
    pub band: (f64, f64),
    /// Per order k, row r, s′ node i (at (k·rows + r)·n_s + i): (q_TE, q_TM) = η·cos θi/cos θm
    /// of the stored values, `None` where the order does not propagate at the node.
    pub q: Vec<Option<[f64; 2]>>,
    /// The stored unpolarised (TE + TM)/2, flattened as `q`.
    pub unpolarised: Vec<f64>,
    /// Per reduced cell: no query in it needs the normalisation (always `false` without
    /// `std`).
    pub marks: Vec<bool>,
}

impl EfficiencyTable {
    /// The parts of a conical table for the GPU (reduced or a version-2 tensor grid); `None`
    /// for a classical table.
    pub(crate) fn reduced_parts(&self) -> Option<ReducedParts> {
        let Some(r) = self.reduced() else {
            return self.tensor_parts();
        };
        let slice = r.slice();
        let mut q = Vec::with_capacity(slice * self.order_count);
        self.each_node_q(&r, |v| q.push((v[0] != NOT_PROPAGATING).then_some(v)));
        let unpolarised = (0..slice * self.order_count)
            .map(|at| 0.5 * (r.te[at] + r.tm[at]))
            .collect();
        let cells = r.slab_offset(r.bet.len() - 1);
        let marks = (0..cells)
            .map(|c| self.unit.is_unit(c, || self.reduced_marks(&r)))
            .collect();
        Some(ReducedParts {
            tensor: false,
            abs_beta: r.bet.to_vec(),
            c: r.loc.c.clone(),
            rows: r.rows.to_vec(),
            lambda_nm: r.lam.to_vec(),
            band: r.band,
            q,
            unpolarised,
            marks,
        })
    }

    /// The parts of a version-2 conical table: its planes as rows of the shared wavelength
    /// nodes, the q's with `Cell3::find`'s corner formulas, its own cells' marks.
    fn tensor_parts(&self) -> Option<ReducedParts> {
        let Storage::Owned {
            sin_theta_i: sin,
            abs_beta: bet,
            lambda_nm: lam,
            te,
            tm,
        } = &self.storage
        else {
            return None;
        };
        if bet.is_empty() {
            return None;
        }
        let (n_s, n_b, n_l) = (sin.len(), bet.len(), lam.len());
        let slice = n_s * n_b * n_l;
        let mut q = Vec::with_capacity(slice * self.order_count);
        self.each_node_q_in(&sin[..], &bet[..], &lam[..], &te[..], &tm[..], |v| {
            q.push((v[0] != NOT_PROPAGATING).then_some(v));
        });
        let cells = (n_b - 1) * (n_l - 1) * (n_s - 1);
        Some(ReducedParts {
            tensor: true,
            abs_beta: bet.clone(),
            c: bet.iter().map(|&b| cb(b)).collect(),
            rows: (0..=n_b).map(|p| p * n_l).collect(),
            lambda_nm: (0..n_b).flat_map(|_| lam.iter().copied()).collect(),
            band: (lam[0], lam[n_l - 1]),
            q,
            unpolarised: (0..slice * self.order_count)
                .map(|at| 0.5 * (te[at] + tm[at]))
                .collect(),
            marks: (0..cells)
                .map(|c| self.cell_needs_no_normalisation(c))
                .collect(),
        })
    }
}
