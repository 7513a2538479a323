//! The constructor of a reduced conical table and its checks on load (`docs/efficiency_tables.md`,
//! "Reduced conical tables").

use alloc::boxed::Box;
use alloc::vec;
use alloc::vec::Vec;

use super::super::load::{check_axis, check_period, order_count, SUM_TOLERANCE};
use super::super::{
    EfficiencyTable, Lookup, NodeQ, Storage, UnitCells, MAX_TABLE_ABS_BETA, MAX_TABLE_NODES,
};
use super::{cb, Locator, ReducedGrid};
use crate::error::{positive, Error, Requirement};

impl EfficiencyTable {
    /// A reduced conical table (version 3, feature `alloc`; `docs/efficiency_tables.md`,
    /// "Reduced conical tables"): the grid `grid` ([`ReducedGrid`]: s′ nodes shared by every
    /// plane, each |β| plane's own wavelength nodes, the band) and the TE and TM values
    /// flattened `[order][plane][λ of the plane][s′]`: plane p's row j, node i of order k at
    /// `(k·R + r_p + j)·n_s + i`, with r_p the rows of the planes before p and R of all planes.
    ///
    /// Checked, each error naming the field: `period_nm` as [`new`](Self::new); `sin_theta_i`
    /// and `abs_beta` as [`new_conical`](Self::new_conical); `lambda_range_nm` finite with
    /// 0 < λ0 < λ1; `lambda_nm` one plane per |β| node, each 2 to `MAX_TABLE_NODES` finite
    /// wavelengths > 0, strictly increasing ([`Requirement::PlaneNodes`]), reaching from
    /// λ0·c_p/c_{p−1} to λ1·c_p/c_{p+1}, c = √(1 − β²), to a relative 10⁻⁹
    /// ([`Requirement::PlaneCovers`]); `te` a whole number of
    /// slices (1 to `MAX_TABLE_ORDERS`, at most `MAX_TABLE_VALUES` values), `tm` as long; the
    /// last order fits an `i32`; every η finite and ≥ 0, each node's sum over orders at most
    /// 1 + 10⁻⁶, and 0 where the order is evanescent at the node
    /// ((s′·c_p + m·λ/d)² + β_p² ≥ 1, λ the node's physical wavelength).
    ///
    /// ```
    /// use diffraction::relief::{EfficiencyTable, ReducedGrid};
    /// let grid = ReducedGrid {
    ///     sin_theta_i: vec![-0.5, 0.5],
    ///     abs_beta: vec![0.0, 0.6],
    ///     lambda_range_nm: (400.0, 700.0),
    ///     // The β = 0 plane stops at 800 nm: queries at β near 0.6 and 700 nm read it at 875.
    ///     lambda_nm: vec![vec![400.0, 800.0], vec![320.0, 700.0]],
    /// };
    /// let e = EfficiencyTable::new_reduced(1000.0, 0, grid, vec![0.9; 8], vec![0.8; 8])
    ///     .unwrap_err();
    /// assert_eq!(e.parameter(), "lambda_nm");
    /// assert_eq!(
    ///     e.to_string(),
    ///     "invalid lambda_nm = 800: must let plane 0 (lambda_nm[0]) reach from 400 to 875 nm, \
    ///      the wavelengths the band's queries in the cells beside it read there"
    /// );
    /// ```
    pub fn new_reduced(
        period_nm: f64,
        order_min: i32,
        grid: ReducedGrid,
        te: Vec<f64>,
        tm: Vec<f64>,
    ) -> Result<EfficiencyTable, Error> {
        check_period("period_nm", period_nm)?;
        check_axis("sin_theta_i", &grid.sin_theta_i, Some((-1.0, 1.0)))?;
        check_axis("abs_beta", &grid.abs_beta, Some((0.0, MAX_TABLE_ABS_BETA)))?;
        let (l0, l1) = grid.lambda_range_nm;
        positive("lambda_range_nm", l0)?;
        positive("lambda_range_nm", l1)?;
        if l1 <= l0 {
            let requirement = Requirement::GreaterThan {
                bound_name: "lambda_range_nm.0",
                bound: l0,
            };
            return Err(Error::invalid("lambda_range_nm", l1, requirement));
        }
        let n_b = grid.abs_beta.len();
        if grid.lambda_nm.len() != n_b {
            let requirement = Requirement::Count { min: n_b, max: n_b };
            return Err(Error::invalid(
                "lambda_nm",
                grid.lambda_nm.len() as f64,
                requirement,
            ));
        }
        for (p, nodes) in grid.lambda_nm.iter().enumerate() {
            let bad = |x: f64| Error::invalid("lambda_nm", x, Requirement::PlaneNodes { plane: p });
            if nodes.len() < 2 || nodes.len() > MAX_TABLE_NODES {
                return Err(bad(nodes.len() as f64));
            }
            for (j, &x) in nodes.iter().enumerate() {
                if !(x.is_finite() && x > 0.0) || (j > 0 && x <= nodes[j - 1]) {
                    return Err(bad(x));
                }
            }
            // Both ends exist (checked above) and reach is Some (p < n_b).
            let (lo, hi) = grid.plane_reach_nm(p).unwrap_or((l0, l1));
            let (first, last) = (nodes[0], nodes[nodes.len() - 1]);
            let covers = Requirement::PlaneCovers {
                plane: p,
                min: lo,
                max: hi,
            };
            if first > lo * (1.0 + 1e-9) {
                return Err(Error::invalid("lambda_nm", first, covers));
            }
            if last < hi * (1.0 - 1e-9) {
                return Err(Error::invalid("lambda_nm", last, covers));
            }
        }
        // At most 4096 × 4096 rows and 4096 nodes of s′: the product fits a 64-bit usize;
        // saturate elsewhere (the slice check then refuses the table).
        let slice = grid.sin_theta_i.len().saturating_mul(grid.rows());
        let orders = order_count(&te, &tm, slice, order_min, |slice, max_slices| {
            Requirement::PlaneSlices { slice, max_slices }
        })?;
        check_values("te", period_nm, order_min, &grid, &te)?;
        check_values("tm", period_nm, order_min, &grid, &tm)?;
        let mut rows = Vec::with_capacity(n_b + 1);
        let mut lambda_nm = Vec::with_capacity(grid.rows());
        for nodes in &grid.lambda_nm {
            rows.push(lambda_nm.len());
            lambda_nm.extend_from_slice(nodes);
        }
        rows.push(lambda_nm.len());
        let locator = Box::new(Locator::new(
            &grid.sin_theta_i,
            &grid.abs_beta,
            &lambda_nm,
            &rows,
        ));
        Ok(EfficiencyTable {
            period_nm,
            order_min,
            order_count: orders,
            storage: Storage::Reduced {
                sin_theta_i: grid.sin_theta_i,
                abs_beta: grid.abs_beta,
                lambda_nm,
                rows,
                band: grid.lambda_range_nm,
                te,
                tm,
                locator,
            },
            unit: UnitCells::new(),
            q: NodeQ::new(),
            lookup: Lookup::new(),
        })
    }
}

/// Checks one polarisation's values of a reduced table: finite and ≥ 0, each node's sum over
/// orders ≤ 1 + `SUM_TOLERANCE`, 0 where the order is evanescent at the node.
fn check_values(
    name: &'static str,
    period_nm: f64,
    order_min: i32,
    grid: &ReducedGrid,
    v: &[f64],
) -> Result<(), Error> {
    if let Some(&bad) = v.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
        return Err(Error::invalid(name, bad, Requirement::NonNegative));
    }
    let n_s = grid.sin_theta_i.len();
    let slice = n_s * grid.rows();
    let orders = v.len() / slice;
    let mut sums = vec![0.0; slice];
    for k in 0..orders {
        let m = f64::from(order_min) + k as f64;
        let mut row = 0;
        for (&b, nodes) in grid.abs_beta.iter().zip(&grid.lambda_nm) {
            let c = cb(b);
            for &l in nodes {
                for (i, &s) in grid.sin_theta_i.iter().enumerate() {
                    let at = row * n_s + i;
                    let x = v[k * slice + at];
                    sums[at] += x;
                    let am = s * c + m * l / period_nm;
                    if x != 0.0 && 1.0 - am * am - b * b <= 0.0 {
                        let requirement = Requirement::ZeroWhereEvanescentConical {
                            order: order_min + k as i32,
                        };
                        return Err(Error::invalid(name, x, requirement));
                    }
                }
                row += 1;
            }
        }
    }
    let bound = 1.0 + SUM_TOLERANCE;
    if let Some(&worst) = sums.iter().find(|&&t| t > bound) {
        let worst = sums.iter().fold(worst, |a, &b| a.max(b));
        return Err(Error::invalid(
            name,
            worst,
            Requirement::SumAtMost { bound },
        ));
    }
    Ok(())
}
