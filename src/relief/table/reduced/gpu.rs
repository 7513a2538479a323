//! A reduced conical table's parts for the GPU's packed table (`gpu/tabulated.rs`): its axes,
//! the nodes' q's with the corner formulas of [`Reduced::find`](super::Reduced::find), the
//! stored unpolarised values the proposal reads, and the single-order marks in the reduced
//! cells' numbering.

use alloc::vec::Vec;

use super::super::nodes_q::NOT_PROPAGATING;
use super::super::EfficiencyTable;

/// What the GPU's packed table holds of a reduced conical table (feature `gpu`).
pub(crate) struct ReducedParts {
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
    /// The parts of a reduced conical table for the GPU; `None` for any other table.
    pub(crate) fn reduced_parts(&self) -> Option<ReducedParts> {
        let r = self.reduced()?;
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
}
