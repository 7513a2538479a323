//! The work estimate against measured time, without timing anything: every row of
//! `tools/render/budget_calibration.csv` (a command, its estimate and its measured CPU time,
//! written by `tools/render/calibrate.sh`) is estimated again by the current cost model, and
//! the new estimate must stay within [`FACTOR`] of the measured time, both ways
//! (docs/work_budget.md). A change of the cost model that breaks the calibration fails here;
//! one that keeps it needs no new measurement.

use std::path::Path;

use crate::cli::Options;
use crate::run::{self, Renderer};

/// How far an estimate may be from the measured CPU time, either way (the budget's promise).
pub(crate) const FACTOR: f64 = 5.0;

/// One row of the calibration table.
pub(crate) struct Row {
    pub binary: String,
    pub args: Vec<String>,
    pub cpu_s: f64,
}

/// The rows of the calibration table, scene paths made absolute (they are relative to the
/// repository's root).
pub(crate) fn rows() -> Vec<Row> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let root = dir.join("../..");
    let text = std::fs::read_to_string(dir.join("budget_calibration.csv")).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("binary,arguments,estimate_s,cpu_s,ratio")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            assert_eq!(f.len(), 5, "{l}");
            let args = f[1]
                .split_whitespace()
                .map(|a| match a.contains('/') && !a.starts_with('-') {
                    true => root.join(a).display().to_string(),
                    false => a.to_string(),
                })
                .collect();
            Row {
                binary: f[0].to_string(),
                args,
                cpu_s: f[3].parse().unwrap(),
            }
        })
        .collect()
}

/// Checks every row of `binary` whose scene `skip` does not exclude: `renderer` parses its
/// arguments. Returns the (estimate, measured) pairs checked.
pub(crate) fn check<R: Renderer>(
    binary: &str,
    renderer: impl Fn(&[String]) -> (R, Options),
    skip: impl Fn(&Row) -> bool,
) -> Vec<(f64, f64)> {
    let mut checked = Vec::new();
    for row in rows().iter().filter(|r| r.binary == binary && !skip(r)) {
        let (r, opts) = renderer(&row.args);
        assert_eq!(opts.scenes.len(), 1, "{:?}", row.args);
        let scene = run::load::<R>(&opts.scenes[0], &opts, false)
            .unwrap()
            .unwrap();
        let estimate = r.estimate(&scene, 1).seconds();
        let ratio = estimate / row.cpu_s;
        assert!(
            (1.0 / FACTOR..=FACTOR).contains(&ratio),
            "{binary} {}: estimated {estimate} s, measured {} s: {ratio:.2} times",
            row.args.join(" "),
            row.cpu_s
        );
        checked.push((estimate, row.cpu_s));
    }
    // Commands whose measured times differ by more than the factor keep their order.
    for &(e1, m1) in &checked {
        for &(e2, m2) in &checked {
            if m1 > FACTOR * m2 {
                assert!(
                    e1 > e2,
                    "measured {m1} s > {FACTOR} × {m2} s, estimated {e1} s <= {e2} s"
                );
            }
        }
    }
    checked
}
