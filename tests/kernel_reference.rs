//! The kernels against 100-digit mpmath values of the exact functions at the same
//! floating-point arguments (`tests/data/kernels.csv`, made by `python_ref/generate.py`).
//!
//! The crate documents 1e-12 (f64, N ≤ 10⁷, |α| ≤ 10⁵) and 1e-5 (f32, N ≤ 10⁶, |α| ≤ 10⁴, the
//! argument exactly the f32 in the file) absolute, see `diffraction::kernel`; the test asserts
//! the measured worst errors with their margins (`tests/support/tolerance.rs`).

#[path = "support/tolerance.rs"]
mod tolerance;

use diffraction::kernel::{n_slit, n_slit_cycles, single_slit, single_slit_cycles};
use std::fs;

struct Row {
    function: String,
    precision: String,
    n: u32,
    arg: f64,
    value: f64,
}

fn rows() -> Vec<Row> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/kernels.csv");
    let text = fs::read_to_string(path).expect("tests/data/kernels.csv (python_ref/generate.py)");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(lines.next(), Some("function,precision,n,arg,value"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            Row {
                function: f[0].to_string(),
                precision: f[1].to_string(),
                n: f[2].parse().unwrap(),
                arg: f[3].parse().unwrap(),
                value: f[4].parse().unwrap(),
            }
        })
        .collect()
}

fn eval(r: &Row) -> f64 {
    match (r.function.as_str(), r.precision.as_str()) {
        ("n_slit_cycles", "f64") => n_slit_cycles(r.arg, r.n),
        ("n_slit", "f64") => n_slit(r.arg, r.n),
        ("single_slit_cycles", "f64") => single_slit_cycles(r.arg),
        ("single_slit", "f64") => single_slit(r.arg),
        ("n_slit_cycles", "f32") => n_slit_cycles(to_f32(r.arg), r.n) as f64,
        ("n_slit", "f32") => n_slit(to_f32(r.arg), r.n) as f64,
        ("single_slit_cycles", "f32") => single_slit_cycles(to_f32(r.arg)) as f64,
        ("single_slit", "f32") => single_slit(to_f32(r.arg)) as f64,
        other => panic!("unknown row kind {other:?}"),
    }
}

fn to_f32(x: f64) -> f32 {
    let y = x as f32;
    assert_eq!(y as f64, x, "f32 row argument {x} is not an f32");
    y
}

#[test]
fn kernels_match_mpmath_within_measured_bounds() {
    let rows = rows();
    assert!(rows.len() > 1000);
    let mut worst = [(0.0f64, String::new()), (0.0f64, String::new())];
    for r in &rows {
        let got = eval(r);
        let (slot, bound) = if r.precision == "f64" {
            (0, tolerance::KERNEL_F64)
        } else {
            (1, tolerance::KERNEL_F32)
        };
        let err = (got - r.value).abs();
        assert!(
            err <= bound && (0.0..=1.0).contains(&got),
            "{}({}, n={}) [{}]: got {got}, exact {} (error {err:e})",
            r.function,
            r.arg,
            r.n,
            r.precision,
            r.value
        );
        if err > worst[slot].0 {
            worst[slot] = (err, format!("{}({}, n={})", r.function, r.arg, r.n));
        }
    }
    println!("worst f64 error {:e} at {}", worst[0].0, worst[0].1);
    println!("worst f32 error {:e} at {}", worst[1].0, worst[1].1);
}
