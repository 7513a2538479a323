//! The checks of a [`TableSpec`]: every field out of range is refused, named.

use diffraction::relief::MAX_TABLE_NODES;
use diffraction::{Error, Requirement};

use super::{TableError, TableSpec};

pub(super) fn invalid(name: &'static str, value: f64, requirement: Requirement) -> TableError {
    TableError::Invalid(Error::InvalidParameter {
        name,
        value,
        requirement,
    })
}

// The negated comparisons reject NaN with the out-of-range values.
#[allow(clippy::neg_cmp_op_on_partial_ord)]
pub(super) fn check_spec(spec: &TableSpec, period_nm: f64) -> Result<(), TableError> {
    if !(period_nm.is_finite() && period_nm > 0.0) {
        return Err(invalid("period_nm", period_nm, Requirement::Positive));
    }
    let (s0, s1) = spec.sin_theta_range;
    let open = Requirement::Within {
        min: -0.99999,
        max: 0.99999,
    };
    for (name, v) in [("sin_theta_range.0", s0), ("sin_theta_range.1", s1)] {
        if !(v.abs() <= 0.99999) {
            return Err(invalid(name, v, open));
        }
    }
    if !(s1 > s0) {
        let r = Requirement::GreaterThan {
            bound_name: "sin_theta_range.0",
            bound: s0,
        };
        return Err(invalid("sin_theta_range.1", s1, r));
    }
    let (l0, l1) = spec.lambda_range_nm;
    let lam = Requirement::Within {
        min: 100.0,
        max: 20_000.0,
    };
    for (name, v) in [("lambda_range_nm.0", l0), ("lambda_range_nm.1", l1)] {
        if !(100.0..=20_000.0).contains(&v) {
            return Err(invalid(name, v, lam));
        }
    }
    if !(l1 > l0) {
        let r = Requirement::GreaterThan {
            bound_name: "lambda_range_nm.0",
            bound: l0,
        };
        return Err(invalid("lambda_range_nm.1", l1, r));
    }
    let positive = [
        ("tolerance", spec.tolerance),
        ("initial_sin_step", spec.initial_sin_step),
        ("initial_lambda_step_nm", spec.initial_lambda_step_nm),
        ("min_sin_step", spec.min_sin_step),
        ("min_lambda_step_nm", spec.min_lambda_step_nm),
    ];
    for (name, v) in positive {
        if !(v.is_finite() && v > 0.0) {
            return Err(invalid(name, v, Requirement::Positive));
        }
    }
    if spec.validation_points > super::MAX_VALIDATION_POINTS {
        let r = Requirement::Within {
            min: 0.0,
            max: super::MAX_VALIDATION_POINTS as f64,
        };
        return Err(invalid(
            "validation_points",
            spec.validation_points as f64,
            r,
        ));
    }
    if spec.max_solves == 0 {
        return Err(invalid("max_solves", 0.0, Requirement::AtLeastOne));
    }
    if !(spec.max_plane_ratio >= 1.01 && spec.max_plane_ratio <= 10.0) {
        let r = Requirement::Within {
            min: 1.01,
            max: 10.0,
        };
        return Err(invalid("max_plane_ratio", spec.max_plane_ratio, r));
    }
    if !(spec.min_beta_step.is_finite() && spec.min_beta_step > 0.0) {
        return Err(invalid(
            "min_beta_step",
            spec.min_beta_step,
            Requirement::Positive,
        ));
    }
    if let Some((s, l)) = &spec.fixed_nodes {
        // The random points are a fixed grid's only held-out check.
        if spec.validation_points == 0 {
            return Err(invalid("validation_points", 0.0, Requirement::AtLeastOne));
        }
        if !spec.abs_beta.is_empty() {
            return Err(invalid(
                "abs_beta",
                spec.abs_beta.len() as f64,
                Requirement::Count { min: 0, max: 0 },
            ));
        }
        let count = Requirement::Count {
            min: 2,
            max: MAX_TABLE_NODES,
        };
        for (name, nodes, lo, hi) in [
            ("fixed_nodes.0", s, -0.99999, 0.99999),
            ("fixed_nodes.1", l, 100.0, 20_000.0),
        ] {
            if !(2..=MAX_TABLE_NODES).contains(&nodes.len()) {
                return Err(invalid(name, nodes.len() as f64, count));
            }
            for (i, &x) in nodes.iter().enumerate() {
                if !(lo..=hi).contains(&x) {
                    return Err(invalid(name, x, Requirement::Within { min: lo, max: hi }));
                }
                if i > 0 && x <= nodes[i - 1] {
                    return Err(invalid(name, x, Requirement::StrictlyIncreasing));
                }
            }
        }
    }
    if !spec.abs_beta.is_empty() {
        let within = Requirement::Within {
            min: 0.0,
            max: diffraction::relief::MAX_TABLE_ABS_BETA,
        };
        if spec.abs_beta.len() < 2 {
            let r = Requirement::Count {
                min: 2,
                max: MAX_TABLE_NODES,
            };
            return Err(invalid("abs_beta", spec.abs_beta.len() as f64, r));
        }
        for (i, &b) in spec.abs_beta.iter().enumerate() {
            if !(0.0..=diffraction::relief::MAX_TABLE_ABS_BETA).contains(&b) {
                return Err(invalid("abs_beta", b, within));
            }
            if i > 0 && b <= spec.abs_beta[i - 1] {
                return Err(invalid("abs_beta", b, Requirement::StrictlyIncreasing));
            }
        }
    }
    Ok(())
}
