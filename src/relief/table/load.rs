//! User tables: the checks on load (`docs/efficiency_tables.md`, "Checks on load"), the scalar
//! model baked into a table, and the JSON file (feature `serde`).

use alloc::vec;
use alloc::vec::Vec;

use super::{EfficiencyTable, Lookup, NodeQ, Storage, UnitCells};
use crate::error::{positive, Error, Requirement};
use crate::num::math;
use crate::relief::scalar::{ScalarRelief, MAX_PERIOD_NM, MAX_RELIEF_ORDER};

/// The most nodes of one axis (sin θi or λ) a table may have.
///
/// ```
/// use diffraction::relief::{EfficiencyTable, MAX_TABLE_NODES};
/// let s: Vec<f64> = (0..=MAX_TABLE_NODES).map(|i| -0.5 + i as f64 * 1e-4).collect();
/// let e = EfficiencyTable::new(1000.0, 0, s, vec![500.0, 600.0], vec![], vec![]).unwrap_err();
/// assert_eq!(e.parameter(), "sin_theta_i");
/// ```
pub const MAX_TABLE_NODES: usize = 4096;
/// The most orders a table may store (the scalar model's 2·2048 + 1).
pub const MAX_TABLE_ORDERS: usize = 2 * MAX_RELIEF_ORDER as usize + 1;
/// The most efficiencies a table may hold per polarisation (orders × λ nodes × sin θi nodes),
/// 2²⁴ (128 MiB of f64 for TE and TM together).
pub const MAX_TABLE_VALUES: usize = 1 << 24;
/// How far a node's sum over orders may exceed 1 (solver round-off;
/// `python_ref/efficiency_table.py`'s `SUM_TOLERANCE`).
pub(crate) const SUM_TOLERANCE: f64 = 1e-6;

/// The presets' sin θi nodes: steps of 0.1, plus ±0.95, ±0.98 and the grazing ends ±0.9999.
const DEFAULT_SIN_THETA_I: [f64; 25] = [
    -0.9999, -0.98, -0.95, -0.9, -0.8, -0.7, -0.6, -0.5, -0.4, -0.3, -0.2, -0.1, 0.0, 0.1, 0.2,
    0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98, 0.9999,
];
/// The presets' wavelength nodes, nm: 360 to 820 in steps of 20, and 830.
const DEFAULT_LAMBDA_NM: [f64; 25] = [
    360.0, 380.0, 400.0, 420.0, 440.0, 460.0, 480.0, 500.0, 520.0, 540.0, 560.0, 580.0, 600.0,
    620.0, 640.0, 660.0, 680.0, 700.0, 720.0, 740.0, 760.0, 780.0, 800.0, 820.0, 830.0,
];

/// Checks a period: finite, > 0 and at most [`MAX_PERIOD_NM`].
pub(super) fn check_period(name: &'static str, period_nm: f64) -> Result<(), Error> {
    positive(name, period_nm)?;
    if period_nm > MAX_PERIOD_NM {
        let requirement = Requirement::AtMost {
            bound_name: "MAX_PERIOD_NM",
            bound: MAX_PERIOD_NM,
        };
        return Err(Error::invalid(name, period_nm, requirement));
    }
    Ok(())
}

/// The number of orders of `te` and `tm` (arrays of `slice` values an order), checked: a
/// whole number from 1 to the most the value cap admits (`slices(slice, max_slices)` names
/// the requirement otherwise), `tm` as long as `te`, and the last order
/// `order_min + orders − 1` within i32.
pub(super) fn order_count(
    te: &[f64],
    tm: &[f64],
    slice: usize,
    order_min: i32,
    slices: impl FnOnce(usize, usize) -> Requirement,
) -> Result<usize, Error> {
    let max_slices = MAX_TABLE_ORDERS.min(MAX_TABLE_VALUES / slice);
    let orders = te.len() / slice;
    if te.len() % slice != 0 || orders == 0 || orders > max_slices {
        return Err(Error::invalid(
            "te",
            te.len() as f64,
            slices(slice, max_slices),
        ));
    }
    if tm.len() != te.len() {
        let requirement = Requirement::Count {
            min: te.len(),
            max: te.len(),
        };
        return Err(Error::invalid("tm", tm.len() as f64, requirement));
    }
    // orders ≤ 4097, so the sum cannot overflow an i64.
    let last = i64::from(order_min) + orders as i64 - 1;
    if last > i64::from(i32::MAX) {
        let requirement = Requirement::Within {
            min: f64::from(i32::MIN),
            max: (i64::from(i32::MAX) - orders as i64 + 1) as f64,
        };
        return Err(Error::invalid(
            "order_min",
            f64::from(order_min),
            requirement,
        ));
    }
    Ok(orders)
}

/// Checks one axis: 2 to [`MAX_TABLE_NODES`] finite values, strictly increasing, inside
/// [lo, hi] (`lo = None`: positive).
pub(super) fn check_axis(
    name: &'static str,
    v: &[f64],
    range: Option<(f64, f64)>,
) -> Result<(), Error> {
    if v.len() < 2 || v.len() > MAX_TABLE_NODES {
        let requirement = Requirement::Count {
            min: 2,
            max: MAX_TABLE_NODES,
        };
        return Err(Error::invalid(name, v.len() as f64, requirement));
    }
    for (i, &x) in v.iter().enumerate() {
        match range {
            Some((min, max)) if !(x >= min && x <= max) => {
                return Err(Error::invalid(name, x, Requirement::Within { min, max }));
            }
            None => {
                positive(name, x)?;
            }
            _ => {}
        }
        // Both finite here (checked above).
        if i > 0 && x <= v[i - 1] {
            return Err(Error::invalid(name, x, Requirement::StrictlyIncreasing));
        }
    }
    Ok(())
}

/// Checks one polarisation's values (`docs/efficiency_tables.md`, check 4): finite and ≥ 0,
/// each node's sum over orders ≤ 1 + `SUM_TOLERANCE`, 0 where the order is evanescent.
fn check_values(
    name: &'static str,
    period_nm: f64,
    order_min: i32,
    sin: &[f64],
    lam: &[f64],
    v: &[f64],
) -> Result<(), Error> {
    if let Some(&bad) = v.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
        return Err(Error::invalid(name, bad, Requirement::NonNegative));
    }
    let slice = sin.len() * lam.len();
    let orders = v.len() / slice;
    let mut sums = vec![0.0; slice];
    for k in 0..orders {
        let m = f64::from(order_min) + k as f64;
        for (j, &l) in lam.iter().enumerate() {
            for (i, &s) in sin.iter().enumerate() {
                let x = v[k * slice + j * sin.len() + i];
                sums[j * sin.len() + i] += x;
                let sm = s + m * l / period_nm;
                if x != 0.0 && 1.0 - sm * sm <= 0.0 {
                    let requirement = Requirement::ZeroWhereEvanescent {
                        order: order_min + k as i32,
                    };
                    return Err(Error::invalid(name, x, requirement));
                }
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

impl EfficiencyTable {
    /// A table of order efficiencies (feature `alloc`): the grating period `period_nm`, the
    /// first stored order `order_min`, the strictly increasing nodes `sin_theta_i` (inside
    /// [−1, 1]) and `lambda_nm` (positive, nm), and the TE and TM efficiencies, each flattened
    /// `[order][λ][sin θi]`: `te[(k·n_λ + j)·n_s + i]` is order `order_min + k` at λ =
    /// `lambda_nm[j]`, s = `sin_theta_i[i]`. The number of orders is `te.len() / (n_λ·n_s)`.
    ///
    /// Checked as `docs/efficiency_tables.md` ("Checks on load") says, each error naming the
    /// field: `period_nm` finite, > 0 and at most [`MAX_PERIOD_NM`]; each axis 2 to
    /// [`MAX_TABLE_NODES`] finite nodes, strictly increasing, s in [−1, 1], λ > 0; `te` a whole
    /// number (1 to [`MAX_TABLE_ORDERS`], at most [`MAX_TABLE_VALUES`] values) of
    /// `[λ][sin θi]` slices and `tm` as long; the last order fits an `i32`; every η finite and
    /// ≥ 0, each node's sum over orders at most 1 + `SUM_TOLERANCE`, and η = 0 wherever the
    /// order is evanescent at the node (|s + m·λ/d| ≥ 1).
    ///
    /// ```
    /// use diffraction::relief::EfficiencyTable;
    /// // Orders −1, 0, 1 of a 1000 nm grating on a 2 × 2 grid: at s = 0.5, λ = 600 nm order 1
    /// // is evanescent (0.5 + 0.6 ≥ 1) and must be 0.
    /// let (s, l) = (vec![0.0, 0.5], vec![500.0, 600.0]);
    /// let te = vec![0.1, 0.2, 0.1, 0.3, /* order 0 */ 0.5, 0.5, 0.5, 0.5, /* order 1 */ 0.1, 0.0, 0.1, 0.0];
    /// let t = EfficiencyTable::new(1000.0, -1, s.clone(), l.clone(), te.clone(), te.clone())?;
    /// assert_eq!(t.orders(), -1..=1);
    /// assert!((t.efficiency(0, 0.0, 500.0).te - 0.5).abs() < 1e-15);
    /// let mut bad = te.clone();
    /// bad[11] = 0.01;
    /// let e = EfficiencyTable::new(1000.0, -1, s, l, bad, te).unwrap_err();
    /// assert_eq!(
    ///     e.to_string(),
    ///     "invalid te = 0.01: must be 0: order 1 is evanescent there (|sin_theta_i + m lambda/d| >= 1)"
    /// );
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(
        period_nm: f64,
        order_min: i32,
        sin_theta_i: Vec<f64>,
        lambda_nm: Vec<f64>,
        te: Vec<f64>,
        tm: Vec<f64>,
    ) -> Result<EfficiencyTable, Error> {
        check_period("period_nm", period_nm)?;
        check_axis("sin_theta_i", &sin_theta_i, Some((-1.0, 1.0)))?;
        check_axis("lambda_nm", &lambda_nm, None)?;
        let slice = sin_theta_i.len() * lambda_nm.len();
        let orders = order_count(&te, &tm, slice, order_min, |slice, max_slices| {
            Requirement::Slices { slice, max_slices }
        })?;
        check_values("te", period_nm, order_min, &sin_theta_i, &lambda_nm, &te)?;
        check_values("tm", period_nm, order_min, &sin_theta_i, &lambda_nm, &tm)?;
        Ok(EfficiencyTable {
            period_nm,
            order_min,
            order_count: orders,
            storage: Storage::Owned {
                sin_theta_i,
                abs_beta: Vec::new(),
                lambda_nm,
                te,
                tm,
            },
            unit: UnitCells::new(),
            q: NodeQ::new(),
            lookup: Lookup::new(),
        })
    }

    /// The presets' grid (feature `alloc`), for [`from_scalar`](Self::from_scalar): 25 sin θi
    /// nodes (steps of 0.1, plus ±0.95, ±0.98 and the grazing ends ±0.9999, where order 0
    /// changes fastest) and 25 wavelengths (360 to 820 nm in steps of 20, and 830).
    ///
    /// ```
    /// use diffraction::relief::EfficiencyTable;
    /// let (s, l) = EfficiencyTable::default_grid();
    /// assert_eq!((s.len(), l.len()), (25, 25));
    /// assert_eq!((s[0], s[24], l[0], l[24]), (-0.9999, 0.9999, 360.0, 830.0));
    /// ```
    #[must_use]
    pub fn default_grid() -> (&'static [f64], &'static [f64]) {
        (&DEFAULT_SIN_THETA_I, &DEFAULT_LAMBDA_NM)
    }

    /// The scalar relief model baked into a table on the grid `sin_theta_i` × `lambda_nm`
    /// (feature `alloc`): at every node each order's [`ScalarRelief::order`] (0 where it is
    /// evanescent, and at |s| = 1), for every order that propagates at some node (at most
    /// |m| ≤ [`MAX_RELIEF_ORDER`], as the model computes). Between the nodes the table follows
    /// the interpolation rule, so a BSDF has one fast path for the scalar and the rigorous
    /// models; a finer grid follows the model more closely.
    ///
    /// Errors: an axis as in [`new`](Self::new), and `sin_theta_i` when the table would hold
    /// more than [`MAX_TABLE_VALUES`] values per polarisation.
    ///
    /// ```
    /// use diffraction::relief::{EfficiencyTable, Metal, Relief, ScalarRelief};
    /// let foil = ScalarRelief::new(Relief::sinusoid(100.0)?, Metal::AL, 1000.0)?;
    /// let (s, l) = EfficiencyTable::default_grid();
    /// let t = EfficiencyTable::from_scalar(&foil, s, l)?;
    /// assert_eq!(t.orders(), -5..=5);
    /// let exact = foil.order(1, 0.1, 500.0).unwrap();
    /// assert!((t.efficiency(1, 0.1, 500.0).te - exact.te).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn from_scalar(
        relief: &ScalarRelief,
        sin_theta_i: &[f64],
        lambda_nm: &[f64],
    ) -> Result<EfficiencyTable, Error> {
        check_axis("sin_theta_i", sin_theta_i, Some((-1.0, 1.0)))?;
        check_axis("lambda_nm", lambda_nm, None)?;
        let d = relief.period_nm();
        let (s_min, s_max) = (sin_theta_i[0], sin_theta_i[sin_theta_i.len() - 1]);
        let step = lambda_nm[0] / d;
        let cap = f64::from(MAX_RELIEF_ORDER);
        // The largest m with s_min + m·λ_min/d < 1, and the smallest with s_max + m·λ_min/d > −1.
        let hi = (math::ceil((1.0 - s_min) / step) - 1.0).clamp(0.0, cap) as i32;
        let lo = -((math::ceil((1.0 + s_max) / step) - 1.0).clamp(0.0, cap) as i32);
        let orders = (hi - lo + 1) as usize;
        let (n_s, n_l) = (sin_theta_i.len(), lambda_nm.len());
        if orders * n_l * n_s > MAX_TABLE_VALUES {
            let requirement = Requirement::Count {
                min: 2,
                max: (MAX_TABLE_VALUES / (orders * n_l)).max(2),
            };
            return Err(Error::invalid("sin_theta_i", n_s as f64, requirement));
        }
        let mut te = vec![0.0; orders * n_l * n_s];
        let mut tm = te.clone();
        for (j, &l) in lambda_nm.iter().enumerate() {
            for (i, &s) in sin_theta_i.iter().enumerate() {
                for o in relief.orders(s, l) {
                    // The check on load's own test of evanescence (the model's may round the
                    // other way on a Rayleigh line).
                    let sm = s + f64::from(o.order) * l / d;
                    if (lo..=hi).contains(&o.order) && 1.0 - sm * sm > 0.0 {
                        let at = ((o.order - lo) as usize * n_l + j) * n_s + i;
                        te[at] = o.efficiency.te;
                        tm[at] = o.efficiency.tm;
                    }
                }
            }
        }
        EfficiencyTable::new(d, lo, sin_theta_i.to_vec(), lambda_nm.to_vec(), te, tm)
    }
}

#[cfg(feature = "serde")]
mod json;
