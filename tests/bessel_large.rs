//! `stam::bessel_j` at large orders and arguments, where the recurrences would exceed their
//! cost limit of 10⁵ steps and Debye's expansions take over: the values against the mpmath
//! oracle of `tests/data/bessel_large.csv` (`python_ref/stam.py`), and bounded, finite output at
//! the extremes of the input range.

#[path = "support/tolerance.rs"]
mod tol;

use std::f64::consts::PI;

use diffraction::stam::bessel_j;

/// Debye's expansions are used where |n − x| ≥ 15·x^{1/3} + 2 (the crate's `DEBYE_WIDTH`);
/// inside, a short backward recurrence. The test sorts the rows by the same rule.
const DEBYE_WIDTH: f64 = 15.0;

/// One row of `tests/data/bessel_large.csv`.
struct Row {
    order: i32,
    x: f64,
    j: f64,
}

fn reference() -> Vec<Row> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/bessel_large.csv");
    let text = std::fs::read_to_string(path).expect("tests/data/bessel_large.csv");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(lines.next(), Some("order,x,bessel_j"));
    lines
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            Row {
                order: c[0].parse().unwrap(),
                x: c[1].parse().unwrap(),
                j: c[2].parse().unwrap(),
            }
        })
        .collect()
}

/// The local amplitude of J_n(x) for n < x: Debye's envelope √(2/(π√(x² − n²))), at most the
/// size x^{−1/3} of J near the turning point.
fn amplitude(n: f64, x: f64) -> f64 {
    (2.0 / (PI * ((x - n) * (x + n)).sqrt()))
        .sqrt()
        .min(x.powf(-1.0 / 3.0))
}

#[test]
fn large_orders_match_the_reference() {
    let rows = reference();
    assert!(rows.len() >= 80);
    let (mut decaying, mut turning, mut oscillating) = (0, 0, 0);
    for r in &rows {
        let got = bessel_j(r.order, r.x);
        let (n, x) = (r.order.unsigned_abs() as f64, r.x.abs());
        let width = DEBYE_WIDTH * x.cbrt() + 2.0;
        let err = (got - r.j).abs();
        let (bound, region) = if n >= x + width {
            decaying += 1;
            (tol::BESSEL_LARGE_DECAYING * r.j.abs(), "decaying")
        } else if n <= x - width {
            oscillating += 1;
            let units = 1e-12 + f64::EPSILON * n * n / x;
            (
                tol::BESSEL_OSCILLATING_UNITS * units * amplitude(n, x),
                "oscillating",
            )
        } else {
            turning += 1;
            (
                tol::BESSEL_TURNING * r.j.abs().max(amplitude(n, x)),
                "turning",
            )
        };
        assert!(
            err <= bound,
            "{region}: J_{}({}) = {got:e}, reference {:e}, error {err:.2e} > {bound:.2e}",
            r.order,
            r.x,
            r.j
        );
    }
    assert!(decaying >= 10 && turning >= 20 && oscillating >= 20);
}

/// The reproducer of the issue and the corners of the input range: every call takes at most
/// 10⁵ recurrence steps (Debye's expansions have no loop over n; the turning-point window is
/// at most 2·(15·x^{1/3} + 2) + 2 ≤ 38 800 steps for |n| ≤ 2³¹ − 1), so the whole grid runs in
/// well under a second, and every value is finite and at most 1 in magnitude.
#[test]
fn extreme_inputs_are_finite_and_bounded() {
    let orders = [
        i32::MAX,
        i32::MIN,
        i32::MAX - 1,
        1 << 30,
        123_456_789,
        10_000_000,
        1_000_001,
        100_001,
        99_999,
        -100_001,
        0,
        1,
        -7,
    ];
    let mut xs = vec![
        1e5,
        2.5e5,
        999_999.5,
        1e6,
        1.000_001e6,
        1e7,
        1e10,
        1e15,
        1e100,
        1e300,
        f64::MAX,
    ];
    // Around the turning point of the largest order.
    let n = i32::MAX as f64;
    let c = n.cbrt();
    for k in [-20.0, -15.0, -1.0, 0.0, 1.0, 15.0, 20.0] {
        xs.push(n + k * c);
    }
    for &m in &orders {
        for &x in &xs {
            for x in [x, -x] {
                let j = bessel_j(m, x);
                assert!(j.is_finite() && j.abs() <= 1.0, "J_{m}({x}) = {j}");
            }
        }
    }
    // The reproducer, against the oracle's value at x = 1e10 (tests/data).
    let j = bessel_j(i32::MAX, 1e10);
    let reference = reference()
        .into_iter()
        .find(|r| r.order == i32::MAX && r.x == 1e10)
        .expect("row (2^31 - 1, 1e10)")
        .j;
    let units = 1e-12 + f64::EPSILON * n * n / 1e10;
    assert!((j - reference).abs() <= tol::BESSEL_OSCILLATING_UNITS * units * amplitude(n, 1e10));
}

/// Where the recurrences stay within their cost limit the old paths are unchanged: the
/// forward recurrence at x > 10⁶, n ≤ 10⁵ agrees with the Debye path's neighbour to the
/// recurrence identity J_{n−1} + J_{n+1} = (2n/x)·J_n across the switch at n = 10⁵.
#[test]
fn recurrence_identity_across_the_switch() {
    let x = 2e6;
    for n in [99_999, 100_000, 100_001] {
        let lhs = bessel_j(n - 1, x) + bessel_j(n + 1, x);
        let rhs = 2.0 * f64::from(n) / x * bessel_j(n, x);
        // Each value within 10⁻¹¹ of the amplitude (about 6·10⁻⁴ here).
        assert!(
            (lhs - rhs).abs() <= tol::BESSEL_SWITCH_RECURRENCE * amplitude(f64::from(n), x),
            "n = {n}"
        );
    }
}
