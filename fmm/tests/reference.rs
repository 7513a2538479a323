//! Against the committed rigorous cases (tests/data/rigorous_orders.csv, python_ref): every
//! lamellar case (nannos, Li's rule) at the reference's own harmonic count, a sample of them
//! converged, and a sample of the C method's sinusoid and sawtooth cases with the staircase.

mod support;

use diffraction_fmm::{Error, Extrapolation, Incidence, Method, Options, Solver};
use support::{rigorous_cases, Case, REFERENCE_TOLERANCE};

/// The same method at the same truncation: the only difference is nannos's ε sampled on 2¹⁴
/// points before its FFT against the exact Fourier coefficients here. Measured worst 1.28e-5
/// over all 259 lamellar cases (TM, Ag, d = 2500 nm, 279 harmonics); asserted at 5e-5.
const EQUAL_TRUNCATION_TOLERANCE: f64 = 5e-5;

fn incidence(c: &Case) -> Incidence {
    let r = c.first();
    Incidence::classical(r.theta_deg.to_radians().sin(), r.lambda_nm).unwrap()
}

/// (worst TE, worst TM) of a solution against a case's rows.
fn worst(c: &Case, sol: &diffraction_fmm::Solution) -> (f64, f64) {
    let mut w = (0.0f64, 0.0f64);
    for row in &c.rows {
        let o = sol
            .order(row.order)
            .expect("the reference's orders propagate here too");
        if row.te {
            w.0 = w.0.max((o.te - row.efficiency).abs());
        } else {
            w.1 = w.1.max((o.tm - row.efficiency).abs());
        }
    }
    w
}

#[test]
fn every_lamellar_case_at_the_reference_truncation() {
    let solver = Solver::default();
    let cases: Vec<Case> = rigorous_cases()
        .into_iter()
        .filter(|c| c.first().profile == "lamellar")
        .collect();
    assert_eq!(cases.len(), 259, "lamellar cases in the data file");
    let mut all: f64 = 0.0;
    for c in &cases {
        let sol = solver
            .solve_at(&c.grating(), incidence(c), c.harmonics())
            .unwrap();
        let (te, tm) = worst(c, &sol);
        if te.max(tm) > all {
            all = te.max(tm);
            println!("{:?}: TE {te:.2e}, TM {tm:.2e}", c.first());
        }
    }
    println!(
        "{} lamellar cases at equal truncation: worst {all:.2e}",
        cases.len()
    );
    assert!(all < EQUAL_TRUNCATION_TOLERANCE);
}

/// Converged against the reference, both ways. The reference's TM values are themselves
/// converged to 1e-3 only between two counts ×1.5 apart, and lamellar TM converges like 1/N, so
/// they sit up to ~2e-3 from the limit (measured against 801/1201-harmonic extrapolations).
/// Plain convergence (the reference's own procedure) is asserted within 1e-3 for TE and for ≥ 90 %
/// of the cases in TM; the Richardson figures are printed (every 8th lamellar case).
#[test]
fn converged_lamellar_sample() {
    let cases: Vec<Case> = rigorous_cases()
        .into_iter()
        .filter(|c| c.first().profile == "lamellar")
        .step_by(8)
        .collect();
    for extrapolation in [Extrapolation::Off, Extrapolation::Richardson] {
        let solver = Solver::new(Options {
            extrapolation,
            ..Options::default()
        })
        .unwrap();
        let (mut te_worst, mut tm_worst, mut tm_within, mut capped) =
            (0.0f64, 0.0f64, 0usize, 0usize);
        for c in &cases {
            let sol = match solver.solve(&c.grating(), incidence(c)) {
                Ok(sol) => sol,
                Err(Error::NotConverged { .. }) => {
                    capped += 1;
                    continue;
                }
                Err(e) => panic!("{e}"),
            };
            let (te, tm) = worst(c, &sol);
            te_worst = te_worst.max(te);
            tm_worst = tm_worst.max(tm);
            tm_within += usize::from(tm < REFERENCE_TOLERANCE);
        }
        let solved = cases.len() - capped;
        println!(
            "converged lamellar, {extrapolation:?}: {} cases, {capped} not converged, TE worst {te_worst:.2e}, TM worst {tm_worst:.2e}, TM within 1e-3: {tm_within}/{solved}",
            cases.len()
        );
        assert_eq!(capped, 0);
        if extrapolation == Extrapolation::Off {
            assert!(te_worst < REFERENCE_TOLERANCE);
            assert!(tm_worst < 3.0 * REFERENCE_TOLERANCE);
            assert!(tm_within * 10 >= solved * 9);
        }
    }
}

/// The staircased smooth profiles against the C method, at 81 harmonics and the default slab
/// count (λ/40 per slab): a staircase on a metal converges slowly and erratically in TM (every
/// step is a pair of metal corners), so no case of this sample converges to 1e-3 within 401
/// harmonics; the fixed-truncation agreement is measured here and printed (every 40th sinusoid
/// or sawtooth case).
#[test]
fn staircase_sample_against_the_c_method() {
    let solver = Solver::new(Options {
        method: Method::Fmm,
        ..Options::default()
    })
    .unwrap();
    let cases: Vec<Case> = rigorous_cases()
        .into_iter()
        .filter(|c| c.first().profile != "lamellar")
        .step_by(40)
        .collect();
    let (mut te_within, mut tm_within, mut te_worst, mut tm_worst) =
        (0usize, 0usize, 0.0f64, 0.0f64);
    for c in &cases {
        let sol = solver.solve_at(&c.grating(), incidence(c), 81).unwrap();
        let (te, tm) = worst(c, &sol);
        te_within += usize::from(te < REFERENCE_TOLERANCE);
        tm_within += usize::from(tm < REFERENCE_TOLERANCE);
        te_worst = te_worst.max(te);
        tm_worst = tm_worst.max(tm);
    }
    println!(
        "staircase vs C method at 81 harmonics: {} cases, TE within 1e-3 {te_within} (worst {te_worst:.2e}), TM within 1e-3 {tm_within} (worst {tm_worst:.2e})",
        cases.len()
    );
    // Measured: TE 7 of 15 within 1e-3 (worst 1.0e-2), TM 0 of 15 (worst 0.21).
    assert!(te_within >= 5);
}

/// Every lamellar case solved with the default options (ignored: 32 minutes on two cores; `cargo test --release -p diffraction-fmm --test reference -- --ignored
/// --nocapture`). At the default cap (1601) at most `CAPPED_BY_DEFAULT` cases stop unconverged
/// (at 801 harmonics 12 did); TE agrees with the reference everywhere; TM, whose reference sits
/// up to ~2e-3 from the limit (`converged_lamellar_sample`), is within 1e-3 for all but the
/// counted rows.
#[test]
#[ignore]
fn every_lamellar_case_with_the_default_options() {
    // Measured: 1 (Ag, d = 2500 nm, 50 nm deep, 450 nm, θ = 30°: last change 6.9e-3 at 1419).
    const CAPPED_BY_DEFAULT: usize = 1;
    // Measured: 175 of the 1990 TM rows off by more than 1e-3 (145 at 801 harmonics, 247
    // cases solved: the values nearer the limit are further from the reference); asserted with
    // a margin of 1.5.
    const TM_ROWS_OFF: usize = 175;
    let cases: Vec<Case> = rigorous_cases()
        .into_iter()
        .filter(|c| c.first().profile == "lamellar")
        .collect();
    let solver = Solver::new(Options::default()).unwrap();
    let (mut capped, mut te_worst, mut tm_off, mut tm_rows) = (0usize, 0.0f64, 0usize, 0usize);
    for c in &cases {
        let sol = match solver.solve(&c.grating(), incidence(c)) {
            Ok(sol) => sol,
            Err(Error::NotConverged {
                harmonics, change, ..
            }) => {
                let r = c.first();
                println!(
                    "not converged: {} d = {} nm, {} nm deep, {} nm, θ = {}°: {change:.1e} at {harmonics}",
                    r.metal, c.grating().period_nm, r.depth_nm, r.lambda_nm, r.theta_deg
                );
                capped += 1;
                continue;
            }
            Err(e) => panic!("{e}"),
        };
        for row in &c.rows {
            let o = sol
                .order(row.order)
                .expect("the reference's orders propagate");
            if row.te {
                te_worst = te_worst.max((o.te - row.efficiency).abs());
            } else {
                tm_rows += 1;
                tm_off += usize::from((o.tm - row.efficiency).abs() > REFERENCE_TOLERANCE);
            }
        }
    }
    println!(
        "{} lamellar cases: {capped} not converged; TE worst {te_worst:.2e}; TM rows off by more than 1e-3: {tm_off} of {tm_rows}",
        cases.len()
    );
    assert!(capped <= CAPPED_BY_DEFAULT, "{capped}");
    assert!(te_worst < REFERENCE_TOLERANCE, "{te_worst:e}");
    assert!(2 * tm_off <= 3 * TM_ROWS_OFF, "{tm_off}");
}
