//! The error-controlled table builder (`diffraction_fmm::table`): a table built to a tolerance
//! is within it of direct solves at held-out points it never saw, reads back through the
//! library's JSON loader, and bad specs or exhausted budgets give typed errors.
//!
//! The solver here is synthetic and cheap, with what makes tables hard: every order appears on
//! its Rayleigh line with a square-root onset (η_m = |r_m|²·cos θm/cos θi, |r_m|² smooth), and the specular order has a kink
//! there (it loses power as √cos θm of each new order), as a rigorous solution does; it is
//! continuous, mirror-symmetric (η_m(s) = η₋m(−s)) and Σ η < 1. (The crate's scalar relief model
//! is not a fit: its renormalisation makes the other orders jump where an order appears.)

use diffraction::relief::EfficiencyTable;
use diffraction_fmm::table::{build_table, OrderSolver, Orders, TableError, TableMeta, TableSpec};

struct Scalar {
    period_nm: f64,
}

impl OrderSolver for Scalar {
    fn period_nm(&self) -> f64 {
        self.period_nm
    }
    fn mirror_symmetric(&self) -> bool {
        true
    }
    fn solve(&self, s: f64, lambda_nm: f64) -> Result<Orders, String> {
        let r = lambda_nm / self.period_nm;
        let lo = (-(1.0 + s) / r).floor() as i32 - 1;
        let hi = ((1.0 - s) / r).ceil() as i32 + 1;
        let ci = (1.0 - s * s).sqrt();
        let mut te = Vec::new();
        let mut tm = Vec::new();
        let mut kink = 0.0;
        for m in lo..=hi {
            let sm = s + f64::from(m) * r;
            let c = 1.0 - sm * sm;
            if c <= 0.0 || m == 0 {
                te.push(0.0);
                tm.push(0.0);
                continue;
            }
            let cm = c.sqrt();
            kink += cm.sqrt();
            let a = 0.08 / (1.0 + f64::from(m * m))
                * (1.0 + 0.3 * (3.0 * sm).cos() * (lambda_nm / 90.0).sin());
            te.push(a * cm * ci);
            tm.push(0.7 * a * cm * ci);
        }
        let spec = 0.6 + 0.1 * (lambda_nm / 70.0 + s * s).cos() - 0.03 * kink;
        let k = (-lo) as usize;
        te[k] = spec;
        tm[k] = 0.9 * spec;
        Ok(Orders {
            order_min: lo,
            te,
            tm,
        })
    }
}

fn foil() -> Scalar {
    Scalar { period_nm: 1000.0 }
}

fn build(solver: &Scalar, spec: &TableSpec) -> diffraction_fmm::table::BuiltTable {
    match build_table(solver, spec, &mut |_| {}) {
        Ok(b) => b,
        Err(TableError::Budget {
            best: Some(b),
            limit,
            ..
        }) => panic!("{limit}: {:?}", b.report),
        Err(e) => panic!("{e}"),
    }
}

/// The descriptive fields of a synthetic table file.
fn meta(name: &str) -> TableMeta {
    TableMeta {
        name: name.into(),
        description: "synthetic".into(),
        profile: "sinusoid".into(),
        period_nm: 1000.0,
        depth_nm: 100.0,
        duty: None,
        blaze_deg: None,
        metal: "Al".into(),
        cover: "none".into(),
        symmetric: true,
        method: "synthetic".into(),
        harmonics: None,
        convergence: "closed form".into(),
        cover_model: None,
        command: "cargo test".into(),
    }
}

fn spec(tolerance: f64) -> TableSpec {
    TableSpec {
        lambda_range_nm: (400.0, 700.0),
        tolerance,
        threads: 2,
        ..TableSpec::default()
    }
}

/// Largest |table − solve| over every order and both polarisations at one point.
fn error_at(table: &EfficiencyTable, solver: &Scalar, s: f64, l: f64) -> f64 {
    let o = solver.solve(s, l).unwrap();
    let mut worst: f64 = 0.0;
    for m in -6..=6 {
        let t = table.efficiency(m, s, l);
        let (te, tm) = o.get(m);
        worst = worst.max((t.te - te).abs()).max((t.tm - tm).abs());
    }
    worst
}

/// Fresh random points (another generator than the builder's) may find a larger error than the
/// builder's held-out set did, which is a sample too: allowed up to this factor of the tolerance.
/// Measured: the largest over 2000 fresh points is 1.33 times the tolerance at 1e-2 (p95 0.77 times).
const FRESH_POINTS_MARGIN: f64 = 1.5;

#[test]
fn built_table_is_within_its_claimed_error_at_fresh_points() {
    let solver = foil();
    for tolerance in [2e-2, 1e-2] {
        let built = build(&solver, &spec(tolerance));
        let r = &built.report;
        assert!(r.achieved_abs_error <= tolerance, "{r:?}");
        assert!(r.held_out_points > built.sin_theta_i.len() * built.lambda_nm.len());
        let mut state = 12345u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut worst: f64 = 0.0;
        let mut errs = Vec::new();
        for _ in 0..2000 {
            let s = -0.9999 + 1.9998 * next();
            let l = 400.0 + 300.0 * next();
            let e = error_at(&built.table, &solver, s, l);
            worst = worst.max(e);
            errs.push(e);
        }
        errs.sort_by(f64::total_cmp);
        let p95 = errs[1900];
        eprintln!(
            "tolerance {tolerance:e}: grid {} x {}, {} solves, achieved {:.3e}, fresh max {worst:.3e}, p95 {p95:.3e}",
            built.sin_theta_i.len(),
            built.lambda_nm.len(),
            r.solves,
            r.achieved_abs_error
        );
        assert!(
            worst <= FRESH_POINTS_MARGIN * tolerance,
            "fresh max {worst}"
        );
        assert!(p95 <= tolerance, "fresh p95 {p95}");
    }
}

#[test]
fn json_reads_back_through_the_library_loader() {
    let solver = foil();
    let built = build(&solver, &spec(1e-2));
    let meta = TableMeta {
        description: "scalar model of the foil, for the test".into(),
        method: "scalar relief model".into(),
        ..meta("foil-scalar")
    };
    let text = built.to_json(&meta);
    // For checking the file with python_ref/efficiency_table.py::read_json (its sha256 too).
    if let Ok(path) = std::env::var("TABLE_JSON_OUT") {
        std::fs::write(path, &text).unwrap();
    }
    let read: EfficiencyTable = serde_json::from_str(&text).unwrap();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["validation"]["tolerance"], 1e-2);
    let claimed = v["validation"]["achieved_abs_error"].as_f64().unwrap();
    assert_eq!(claimed, built.report.achieved_abs_error);
    // The file's values are rounded to 6 decimals.
    for (k, m) in (built.order_min..=built.order_max).enumerate() {
        for (j, &l) in built.lambda_nm.iter().enumerate() {
            for (i, &s) in built.sin_theta_i.iter().enumerate() {
                let at = (k * built.lambda_nm.len() + j) * built.sin_theta_i.len() + i;
                let e = read.efficiency(m, s, l);
                let f = built.table.efficiency(m, s, l);
                assert!((e.te - f.te).abs() <= 6e-7 && (e.tm - f.tm).abs() <= 6e-7);
                assert!((built.te[at] - f.te).abs() <= 1e-12 || f.te < built.te[at]);
            }
        }
    }
}

#[test]
fn bad_specs_name_the_field() {
    let solver = foil();
    let cases: [(&str, TableSpec); 11] = [
        (
            "validation_points",
            TableSpec {
                fixed_nodes: Some((vec![-0.5, 0.5], vec![400.0, 500.0])),
                validation_points: 0,
                ..spec(1e-2)
            },
        ),
        (
            "fixed_nodes.0",
            TableSpec {
                fixed_nodes: Some((vec![0.1, 0.1], vec![400.0, 500.0])),
                ..spec(1e-2)
            },
        ),
        (
            "fixed_nodes.1",
            TableSpec {
                fixed_nodes: Some((vec![-0.5, 0.5], vec![400.0])),
                ..spec(1e-2)
            },
        ),
        (
            "abs_beta",
            TableSpec {
                fixed_nodes: Some((vec![-0.5, 0.5], vec![400.0, 500.0])),
                abs_beta: vec![0.0, 0.5],
                ..spec(1e-2)
            },
        ),
        (
            "tolerance",
            TableSpec {
                tolerance: -1.0,
                ..spec(1e-2)
            },
        ),
        (
            "max_plane_ratio",
            TableSpec {
                max_plane_ratio: 1.0,
                ..spec(1e-2)
            },
        ),
        (
            "max_plane_ratio",
            TableSpec {
                max_plane_ratio: f64::NAN,
                ..spec(1e-2)
            },
        ),
        (
            "tolerance",
            TableSpec {
                tolerance: f64::NAN,
                ..spec(1e-2)
            },
        ),
        (
            "sin_theta_range.1",
            TableSpec {
                sin_theta_range: (-0.5, 1.0),
                ..spec(1e-2)
            },
        ),
        (
            "lambda_range_nm.1",
            TableSpec {
                lambda_range_nm: (700.0, 400.0),
                ..spec(1e-2)
            },
        ),
        (
            "max_solves",
            TableSpec {
                max_solves: 0,
                ..spec(1e-2)
            },
        ),
    ];
    for (name, s) in cases {
        match build_table(&solver, &s, &mut |_| {}) {
            Err(TableError::Invalid(e)) => assert_eq!(e.parameter(), name, "{e}"),
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn work_is_bounded_with_a_typed_error_and_the_best_table() {
    let solver = foil();
    let s = TableSpec {
        max_solves: 300,
        ..spec(1e-4)
    };
    match build_table(&solver, &s, &mut |_| {}) {
        Err(TableError::Budget {
            limit,
            solves,
            achieved,
            best,
            ..
        }) => {
            assert_eq!(limit, "max_solves");
            assert!(solves <= 300);
            let best = best.expect("a first round fits in 300 solves");
            assert_eq!(best.report.achieved_abs_error, achieved);
            assert!(achieved > 1e-4);
        }
        other => panic!("{other:?}"),
    }
    // A tolerance below what the minimum steps can resolve stops at them, not at the cap.
    let s = TableSpec {
        min_sin_step: 0.05,
        min_lambda_step_nm: 20.0,
        ..spec(1e-6)
    };
    match build_table(&solver, &s, &mut |_| {}) {
        Err(TableError::Budget { limit, .. }) => assert_eq!(limit, "min_step"),
        other => panic!("{other:?}"),
    }
}

#[test]
fn progress_is_reported_and_symmetry_halves_the_solves() {
    let solver = foil();
    let mut calls = 0;
    let mut last = None;
    let built = build_table(&solver, &spec(1e-2), &mut |p| {
        calls += 1;
        assert!(p.done <= p.planned && p.total_solves >= p.done);
        last = Some(*p);
    })
    .unwrap();
    assert_eq!(calls, built.report.solves);
    assert_eq!(last.unwrap().total_solves, built.report.solves);
    // Every node and held-out point with s < 0 is the mirror of one with s > 0.
    let nodes = built.sin_theta_i.len() * built.lambda_nm.len();
    assert!(built.report.solves < nodes + built.report.held_out_points);
    assert!(built
        .sin_theta_i
        .iter()
        .zip(built.sin_theta_i.iter().rev())
        .all(|(a, b)| *a == -*b));
}

/// The synthetic solver in a conical mount: orders propagate iff α_m² + β² < 1, with their
/// square-root onsets (cos θm = √(1 − α_m² − β²)) and the specular kink, and a smooth
/// dependence on β² (mirror-symmetric in β, as a 1-D grating's unpolarised efficiencies).
struct Conical {
    period_nm: f64,
}

impl OrderSolver for Conical {
    fn period_nm(&self) -> f64 {
        self.period_nm
    }
    fn mirror_symmetric(&self) -> bool {
        true
    }
    fn solve(&self, s: f64, lambda_nm: f64) -> Result<Orders, String> {
        self.solve_conical(s, 0.0, lambda_nm)
    }
    fn solve_conical(&self, a: f64, b: f64, lambda_nm: f64) -> Result<Orders, String> {
        let r = lambda_nm / self.period_nm;
        let lo = (-(1.0 + a) / r).floor() as i32 - 1;
        let hi = ((1.0 - a) / r).ceil() as i32 + 1;
        let ci = (1.0 - a * a - b * b).sqrt();
        let (mut te, mut tm, mut kink) = (Vec::new(), Vec::new(), 0.0);
        for m in lo..=hi {
            let am = a + f64::from(m) * r;
            let c = 1.0 - am * am - b * b;
            if c <= 0.0 || m == 0 {
                te.push(0.0);
                tm.push(0.0);
                continue;
            }
            let cm = c.sqrt();
            kink += cm.sqrt();
            let amp = 0.08 / (1.0 + f64::from(m * m))
                * (1.0 + 0.3 * (3.0 * am).cos())
                * (1.0 + 0.5 * b * b);
            te.push(amp * cm * ci);
            tm.push(0.7 * amp * cm * ci);
        }
        let spec = 0.6 + 0.1 * (lambda_nm / 70.0 + a * a).cos() - 0.03 * kink - 0.1 * b * b;
        let k = (-lo) as usize;
        te[k] = spec;
        tm[k] = 0.9 * spec;
        Ok(Orders {
            order_min: lo,
            te,
            tm,
        })
    }
}

/// A conical table of the synthetic conical solver built to 2·10⁻² in the format `reduced`
/// (version 3) or not (version 2): within its claimed error (unpolarised, what a conical build
/// controls; with the fresh-points margin) at fresh random (α, β, λ) inside its box, read back
/// through the library's loader as a file of that version. Returns the solves and the fresh
/// error.
fn conical_build(reduced: bool) -> (usize, f64) {
    let solver = Conical { period_nm: 1000.0 };
    let tolerance = 2e-2;
    let spec = TableSpec {
        abs_beta: vec![0.0, 0.45, 0.9],
        reduced,
        ..spec(tolerance)
    };
    let built = match build_table(&solver, &spec, &mut |_| {}) {
        Ok(b) => b,
        Err(e) => panic!("{e}"),
    };
    let r = &built.report;
    assert!(r.achieved_abs_error <= tolerance, "{r:?}");
    assert!(built.table.is_conical() && built.table.is_reduced() == reduced);
    let mut state = 999u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut worst: f64 = 0.0;
    for _ in 0..1000 {
        let b = 0.9 * next();
        let a = (1.0 - b * b).sqrt() * (-0.9999 + 1.9998 * next());
        let l = 400.0 + 300.0 * next();
        let o = solver.solve_conical(a, b, l).unwrap();
        for m in -6..=6 {
            let t = built.table.efficiency_conical(m, a, -b, l);
            let (te, tm) = o.get(m);
            worst = worst.max((t.unpolarised() - 0.5 * (te + tm)).abs());
        }
    }
    let rows: Vec<usize> = built.plane_lambda_nm.iter().map(Vec::len).collect();
    eprintln!(
        "conical (reduced {reduced}): grid {} x {:?} x {} {rows:?}, {} solves, achieved {:.3e}, \
         fresh max {worst:.3e}",
        built.sin_theta_i.len(),
        built.abs_beta,
        built.lambda_nm.len(),
        r.solves,
        r.achieved_abs_error
    );
    assert!(
        worst <= FRESH_POINTS_MARGIN * tolerance,
        "fresh max {worst}"
    );
    let text = built.to_json(&meta("conical"));
    let read: EfficiencyTable = serde_json::from_str(&text).unwrap();
    assert!(read.is_conical() && read.is_reduced() == reduced);
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["version"], if reduced { 3 } else { 2 });
    for &(a, b, l) in &[(0.1, 0.3, 450.0), (-0.5, 0.7, 620.0), (0.0, 0.0, 500.0)] {
        for m in -3..=3 {
            let (e, f) = (
                read.efficiency_conical(m, a, b, l),
                built.table.efficiency_conical(m, a, b, l),
            );
            assert!((e.te - f.te).abs() <= 1e-6 && (e.tm - f.tm).abs() <= 1e-6);
        }
    }
    (r.solves, worst)
}

#[test]
fn a_conical_table_is_within_its_error_and_reads_back() {
    conical_build(false);
}

/// The reduced format (version 3) of the same: every plane with its own wavelengths, planes
/// added until neighbours' √(1 − β²) differ by at most 2.5.
#[test]
fn a_reduced_conical_table_is_within_its_error_and_reads_back() {
    conical_build(true);
}

/// A band that the solver's materials do not cover (with the room a plane needs beyond it) is
/// refused by name before any solve.
#[test]
fn a_reduced_table_beyond_the_metals_data_is_refused_by_name() {
    use diffraction_fmm::table::Rigorous;
    use diffraction_fmm::{Grating, Profile, Solver};
    let rig = Rigorous {
        grating: Grating {
            period_nm: 1000.0,
            profile: Profile::Lamellar {
                duty: 0.5,
                depth_nm: 50.0,
            },
            metal: diffraction::relief::Metal::AG,
            cover: None,
        },
        solver: Solver::default(),
        accept_unconverged: 1e-3,
    };
    let spec = TableSpec {
        abs_beta: vec![0.0, 0.5],
        lambda_range_nm: (200.0, 700.0),
        ..spec(1e-2)
    };
    let e = build_table(&rig, &spec, &mut |_| {}).unwrap_err();
    assert_eq!(
        e.to_string(),
        "invalid lambda_range_nm.0 = 200: must lie in [203.286, 1899.0196078431372]"
    );
}

/// Given nodes are kept as they are (no refinement, whatever the tolerance), solved once each
/// (the mirror symmetry halving them), and the held-out error is measured at the random points
/// alone, inside the nodes' span: exactly the largest error there, as a direct check finds.
#[test]
fn fixed_nodes_are_solved_as_given_and_their_error_measured() {
    let solver = foil();
    let s_nodes = vec![
        -0.9, -0.72, -0.54, -0.36, -0.18, 0.0, 0.18, 0.36, 0.54, 0.72, 0.9,
    ];
    let l_nodes = vec![400.0, 475.0, 550.0, 625.0, 700.0];
    let spec = TableSpec {
        tolerance: 1e-6,
        validation_points: 40,
        fixed_nodes: Some((s_nodes.clone(), l_nodes.clone())),
        ..spec(1e-6)
    };
    let built = build_table(&solver, &spec, &mut |_| {}).expect("a fixed grid is not refined");
    let r = &built.report;
    assert_eq!(
        (built.sin_theta_i.clone(), built.lambda_nm.clone()),
        (s_nodes, l_nodes)
    );
    assert!(r.fixed_grid);
    assert_eq!(r.rounds, 1);
    assert_eq!(r.held_out_points, 40);
    // 55 nodes, 5 of them on s = 0 (their own mirror): 30 solved; and the 40 random points.
    assert_eq!(r.solves, 30 + 40, "{r:?}");
    assert!(r.achieved_abs_error > spec.tolerance, "{r:?}");
    assert_eq!(r.achieved_abs_error, r.random_points_max);
    let json = built.to_json(&meta("fixed"));
    assert!(json.contains(r#""tolerance":null"#), "{json}");
    assert!(json.contains("fixed nodes, not refined"));
}
