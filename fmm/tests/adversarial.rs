//! The sweep of the solver crate's public surfaces with random and adversarial inputs:
//! `Incidence` (`new`, `classical`, `from_cosines`), `Metal::custom` (n + ik), `Grating`
//! (every profile, covers), `Options`/`Solver::new`, `Solver::solve_at` and `Solver::solve`
//! (classical and conical incidence, the C method, the Fourier modal method, covers, metals by
//! n + ik), and `table::build_table` with hostile `TableSpec`s and a hostile `OrderSolver`.
//!
//! Every call either succeeds with finite, non-negative efficiencies whose sum is at most 1,
//! or returns a typed error whose message names its parameter. Work is bounded: the quick
//! sweep's solves use a small harmonic count (what the cap bounds is measured by the ignored
//! `solves_at_the_cap`, which prints the time of a solve at `MAX_HARMONICS`; speed is never
//! asserted).
//!
//! `sweep` (CI: a few seconds in release) draws [`QUICK_CASES`] cases; `sweep_long` (ignored:
//! `cargo test --release -p diffraction-fmm --test adversarial -- --ignored`) draws twenty
//! times as many from another seed. Each prints its tally.

use std::time::Instant;

mod support;
use support::SHALLOW_LAMELLAR;

use diffraction::relief::Metal;
use diffraction_fmm::table::{build_table, OrderSolver, Orders, TableError, TableSpec};
use diffraction_fmm::{
    Cover, CoverIndex, Error, Grating, Incidence, Level, Method, Options, Profile, Solver,
    MAX_HARMONICS,
};

/// Cases drawn by the quick sweep.
const QUICK_CASES: usize = 150;
/// The largest harmonic count of the quick sweep's solves (each a few milliseconds).
const QUICK_HARMONICS: u64 = 25;
/// How far a solve's Σ η may exceed 1: measured 1.5e-14 over the long sweep's accepted solves
/// (the reflection matrices' rounding, energy being conserved by the method for a lossless
/// metal and below 1 for a lossy one); margin 70×.
const SUM_ROUNDING: f64 = 1e-12;
/// How far below 0 an efficiency may be: the rounding of |r|²·Re(k_z)/k_z,i of an order at
/// the edge of propagation. Measured 0 over the long sweep; asserted at rounding.
const NEGATIVE_ROUNDING: f64 = 1e-15;
/// The longest error message accepted.
const MAX_MESSAGE: usize = 400;

/// SplitMix64 (as the library's tests), and whether the current case draws hostile values.
struct Rng(u64, bool);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

/// Values that break arithmetic.
const EXTREMES: [f64; 16] = [
    0.0,
    -0.0,
    5e-324,
    f64::MIN_POSITIVE,
    1e-300,
    0.5,
    1.0,
    -1.0,
    1e300,
    f64::MAX,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.999_999_999_999_999_9,
    1e5,
    20_000.0,
];

/// A number from the extremes, random in [lo, hi], or a random bit pattern's float (in a
/// hostile case; else random in [lo, hi]).
fn value(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    if !r.1 {
        return lo + (hi - lo) * r.next_f64();
    }
    match r.below(6) {
        0 => EXTREMES[r.below(EXTREMES.len() as u64) as usize],
        1 => f64::from_bits(r.next_u64()),
        _ => lo + (hi - lo) * r.next_f64(),
    }
}

#[derive(Debug, Default)]
struct Tally {
    incidences: u64,
    incidences_refused: u64,
    metals_refused: u64,
    gratings_refused: u64,
    solvers_refused: u64,
    solves: u64,
    solves_refused: u64,
    numerical: u64,
    not_converged: u64,
    specs_refused: u64,
    builds: u64,
    builds_refused: u64,
}

/// The parameters an error may name.
const PARAMETERS: [&str; 24] = [
    "theta",
    "phi",
    "wavelength_nm",
    "alpha",
    "beta",
    "period_nm",
    "depth_nm",
    "duty",
    "blaze",
    "levels",
    "ridges",
    "samples",
    "cover.index",
    "cover.index.b",
    "cover.index.c_um2",
    "cover.thickness_nm",
    "tolerance",
    "max_harmonics",
    "slabs",
    "harmonics",
    "numerics",
    "metal",
    "n",
    "k",
];

/// A refusal: a known parameter, named in a short message.
fn check_error(e: &Error, what: &dyn std::fmt::Debug) {
    let msg = e.to_string();
    assert!(msg.len() < MAX_MESSAGE, "{msg}");
    assert!(
        PARAMETERS.contains(&e.parameter()),
        "{}: {msg} ({what:?})",
        e.parameter()
    );
    assert!(msg.starts_with(e.parameter()), "{msg}");
}

fn incidence(r: &mut Rng, tally: &mut Tally) -> Option<Incidence> {
    let lambda = value(r, 300.0, 1200.0);
    let made = match r.below(3) {
        0 => Incidence::new(value(r, 0.0, 1.5), value(r, -7.0, 7.0), lambda),
        1 => Incidence::classical(value(r, -1.0, 1.0), lambda),
        _ => Incidence::from_cosines(value(r, -1.0, 1.0), value(r, -1.0, 1.0), lambda),
    };
    tally.incidences += 1;
    match made {
        Ok(i) => {
            let (a, b) = (i.alpha(), i.beta());
            assert!(
                a.is_finite() && b.is_finite() && a * a + b * b < 1.0,
                "{i:?}"
            );
            assert!(i.phi().is_finite() && i.wavelength_nm().is_finite());
            Some(i)
        }
        Err(e) => {
            tally.incidences_refused += 1;
            check_error(&e, &"incidence");
            None
        }
    }
}

fn metal(r: &mut Rng, tally: &mut Tally) -> Metal {
    match r.below(6) {
        0 => Metal::AL,
        1 => Metal::AG,
        2 => Metal::AU,
        _ => match Metal::custom(value(r, 0.05, 3.0), value(r, 0.0, 10.0)) {
            Ok(m) => m,
            Err(e) => {
                tally.metals_refused += 1;
                assert!(["n", "k"].contains(&e.parameter()), "{e}");
                Metal::CR
            }
        },
    }
}

fn profile(r: &mut Rng) -> Profile {
    let depth = value(r, 0.0, 300.0);
    match r.below(8) {
        0 => Profile::Flat,
        1 => Profile::Lamellar {
            duty: value(r, 0.0, 1.0),
            depth_nm: depth,
        },
        2 => Profile::Sinusoid { depth_nm: depth },
        3 => Profile::Sawtooth {
            blaze: value(r, 0.0, 0.8),
        },
        4 => Profile::Fourier {
            cos: vec![value(r, 0.0, 100.0); r.below(4) as usize],
            sin: vec![value(r, 0.0, 100.0); r.below(3) as usize],
        },
        5 => Profile::Sampled(
            (0..r.below(6))
                .map(|_| value(r, 0.0, 200.0))
                .collect::<Vec<_>>(),
        ),
        _ => Profile::Multilevel(
            (0..r.below(4))
                .map(|_| Level {
                    thickness_nm: value(r, 0.0, 80.0),
                    ridges: vec![(value(r, 0.0, 0.5), value(r, 0.5, 1.0))],
                })
                .collect(),
        ),
    }
}

fn grating(r: &mut Rng, tally: &mut Tally) -> Grating {
    let cover = match r.below(5) {
        0 => Some(Cover {
            index: CoverIndex::Constant(value(r, 1.0, 2.0)),
            thickness_nm: value(r, 1e4, 1e7),
        }),
        1 => Some(Cover {
            index: CoverIndex::Sellmeier {
                b: value(r, 0.5, 2.0),
                c_um2: value(r, 0.0, 0.05),
            },
            thickness_nm: 1.2e6,
        }),
        _ => None,
    };
    Grating {
        period_nm: value(r, 200.0, 2000.0),
        profile: profile(r),
        metal: metal(r, tally),
        cover,
    }
}

fn options(r: &mut Rng) -> Options {
    Options {
        tolerance: if r.below(3) == 0 {
            value(r, 1e-9, 0.5)
        } else {
            0.5
        },
        max_harmonics: match r.below(8) {
            0 => [0, 1, 2, usize::MAX, MAX_HARMONICS + 1][r.below(5) as usize],
            1 => MAX_HARMONICS,
            _ => 3 + r.below(QUICK_HARMONICS) as usize,
        },
        slabs: match r.below(4) {
            0 => Some([0, 1, 401, usize::MAX][r.below(4) as usize]),
            1 => Some(1 + r.below(6) as usize),
            _ => Some(4),
        },
        method: [Method::Auto, Method::Fmm, Method::CMethod][r.below(3) as usize],
        always_conical: r.below(4) == 0,
        ..Options::default()
    }
}

/// A solution's orders: finite, ≥ 0, Σ ≤ 1 per polarisation, each order listed once.
fn check_solution(orders: &[diffraction_fmm::Order], what: &dyn std::fmt::Debug) {
    let (mut te, mut tm) = (0.0, 0.0);
    for o in orders {
        assert!(
            o.te.is_finite()
                && o.tm.is_finite()
                && o.te >= -NEGATIVE_ROUNDING
                && o.tm >= -NEGATIVE_ROUNDING
                && o.alpha.is_finite(),
            "{o:?}: {what:?}"
        );
        te += o.te;
        tm += o.tm;
    }
    assert!(
        te <= 1.0 + SUM_ROUNDING && tm <= 1.0 + SUM_ROUNDING,
        "Σ {te} {tm}: {what:?}"
    );
    for w in orders.windows(2) {
        assert!(w[0].m < w[1].m, "{what:?}");
    }
}

/// One solve at a small harmonic count (or, when the options cap it low enough, the
/// convergence loop), checked.
fn solve_case(r: &mut Rng, tally: &mut Tally) {
    let g = grating(r, tally);
    let Some(inc) = incidence(r, tally) else {
        return;
    };
    if let Err(e) = g.validate() {
        tally.gratings_refused += 1;
        check_error(&e, &g);
    }
    let opts = options(r);
    let solver = match Solver::new(opts) {
        Ok(s) => s,
        Err(e) => {
            tally.solvers_refused += 1;
            check_error(&e, &opts);
            return;
        }
    };
    let what = (&g, inc, opts);
    let result = if r.below(3) == 0 && opts.max_harmonics <= QUICK_HARMONICS as usize + 3 {
        solver.solve(&g, inc)
    } else {
        let n = match r.below(5) {
            0 => [0, 1, 2, usize::MAX][r.below(4) as usize],
            _ => 3 + r.below(QUICK_HARMONICS) as usize,
        };
        solver.solve_at(&g, inc, n)
    };
    tally.solves += 1;
    match result {
        Ok(sol) => {
            check_solution(&sol.orders, &what);
            if let Some((t_te, t_tm)) = sol.transmitted {
                assert!(t_te.is_finite() && t_tm.is_finite(), "{what:?}");
            }
        }
        Err(e) => {
            tally.solves_refused += 1;
            match e {
                Error::Numerical(_) => tally.numerical += 1,
                Error::NotConverged { .. } => tally.not_converged += 1,
                Error::Invalid { .. } => {}
            }
            check_error(&e, &what);
        }
    }
}

/// A solver for the table builder whose answers are hostile: NaN, negative, sums above 1,
/// extreme first orders, empty or mismatched lists, or (most of the time) a plausible one.
struct Hostile {
    period_nm: f64,
    kind: u64,
}

impl OrderSolver for Hostile {
    fn period_nm(&self) -> f64 {
        self.period_nm
    }
    fn solve(&self, s: f64, lambda_nm: f64) -> Result<Orders, String> {
        let plausible = Orders {
            order_min: 0,
            te: vec![0.5 + 0.1 * s * (lambda_nm / 1000.0)],
            tm: vec![0.4],
        };
        Ok(match self.kind {
            0 => plausible,
            1 => Orders {
                te: vec![f64::NAN],
                ..plausible
            },
            2 => Orders {
                te: vec![-0.5],
                ..plausible
            },
            3 => Orders {
                te: vec![0.9, 0.9],
                tm: vec![0.9, 0.9],
                ..plausible
            },
            4 => Orders {
                order_min: i32::MAX,
                te: vec![0.1, 0.1],
                tm: vec![0.1, 0.1],
            },
            5 => Orders {
                order_min: i32::MIN,
                te: vec![0.1],
                tm: vec![0.1],
            },
            6 => Orders {
                te: vec![],
                tm: vec![],
                ..plausible
            },
            7 => Orders {
                tm: vec![],
                ..plausible
            },
            8 => Orders {
                order_min: -5,
                te: vec![1e-3; 100_000],
                tm: vec![1e-3; 100_000],
            },
            9 => return Err("no answer here".to_string()),
            _ => Orders {
                te: vec![f64::INFINITY],
                ..plausible
            },
        })
    }
}

/// A spec with one hostile field (or none).
fn spec(r: &mut Rng) -> TableSpec {
    let mut s = TableSpec {
        sin_theta_range: (-0.5, 0.5),
        lambda_range_nm: (500.0, 600.0),
        max_solves: 2000,
        validation_points: 4,
        threads: 1,
        initial_sin_step: 0.5,
        initial_lambda_step_nm: 100.0,
        min_sin_step: 0.1,
        min_lambda_step_nm: 50.0,
        tolerance: 0.5,
        ..TableSpec::default()
    };
    let x = value(r, -1.0, 1.0);
    match r.below(14) {
        0 => s.sin_theta_range = (x, value(r, -1.0, 1.0)),
        1 => s.lambda_range_nm = (value(r, 100.0, 1000.0), value(r, 100.0, 1000.0)),
        2 => s.tolerance = x,
        3 => s.initial_sin_step = value(r, 0.0, 1.0),
        4 => s.initial_lambda_step_nm = value(r, 0.0, 100.0),
        5 => s.min_sin_step = value(r, 0.0, 0.1),
        6 => s.min_lambda_step_nm = value(r, 0.0, 10.0),
        7 => s.max_solves = [0, 1, 5][r.below(3) as usize],
        8 => s.validation_points = [0, 1, 100_001, usize::MAX][r.below(4) as usize],
        9 => s.abs_beta = vec![value(r, 0.0, 0.5), value(r, 0.0, 1.0)],
        10 => s.max_plane_ratio = value(r, 1.0, 10.0),
        11 => s.min_beta_step = value(r, 0.0, 0.1),
        12 => s.threads = [0, 1000, usize::MAX][r.below(3) as usize],
        _ => {}
    }
    s
}

fn build_case(r: &mut Rng, tally: &mut Tally) {
    let solver = Hostile {
        period_nm: if r.below(8) == 0 {
            value(r, 100.0, 2000.0)
        } else {
            1000.0
        },
        kind: if r.below(2) == 0 { 0 } else { r.below(11) },
    };
    let spec = spec(r);
    let what = (solver.period_nm, solver.kind, spec.clone());
    let t0 = Instant::now();
    let result = build_table(&solver, &spec, &mut |_| {});
    tally.builds += 1;
    if let Err(e) = result {
        tally.builds_refused += 1;
        let msg = e.to_string();
        assert!(msg.len() < 2 * MAX_MESSAGE, "{msg}: {what:?}");
        if let TableError::Invalid(inner) | TableError::Table(inner) = &e {
            tally.specs_refused += u64::from(matches!(e, TableError::Invalid(_)));
            assert!(!inner.parameter().is_empty() && msg.contains(inner.parameter()));
        }
    }
    // A bound on the work, not a speed assertion: a hostile spec must stop at its caps (the
    // plausible builds here take milliseconds; a minute means the caps did not hold).
    assert!(t0.elapsed().as_secs() < 60, "{what:?}");
}

fn sweep_with(cases: usize, seed: u64) {
    let mut r = Rng(seed, true);
    let mut tally = Tally::default();
    for _ in 0..cases {
        // Half the cases hostile, half in range (so that the solver's work is swept too).
        r.1 = r.below(2) == 0;
        solve_case(&mut r, &mut tally);
        build_case(&mut r, &mut tally);
    }
    println!("{cases} cases (seed {seed:#x}): {tally:?}");
    assert!(
        tally.solves > tally.solves_refused && tally.solves_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.incidences_refused > 0 && tally.solvers_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.builds > tally.builds_refused && tally.specs_refused > 0,
        "{tally:?}"
    );
}

#[test]
fn sweep() {
    sweep_with(QUICK_CASES, 0xad5e);
}

#[test]
#[ignore = "twenty times the quick sweep"]
fn sweep_long() {
    sweep_with(20 * QUICK_CASES, 0xad5e_7777);
}

/// The time of one solve at the harmonic cap, for each kind of solve, with the largest work
/// cap: the time per unit of `diffraction_fmm::work` that `DEFAULT_MAX_WORK` stands for.
/// Printed, not asserted (speed is measured, never asserted).
#[test]
#[ignore = "measures solves at MAX_HARMONICS: minutes"]
fn solves_at_the_cap() {
    let g = |profile: Profile| Grating {
        period_nm: 1000.0,
        profile,
        metal: Metal::AL,
        cover: None,
    };
    let cases: Vec<(&str, Grating, Incidence, Options)> = vec![
        (
            "lamellar, classical",
            g(Profile::Lamellar {
                duty: 0.5,
                depth_nm: 100.0,
            }),
            Incidence::classical(0.3, 550.0).unwrap(),
            Options::default(),
        ),
        (
            "lamellar, conical",
            g(Profile::Lamellar {
                duty: 0.5,
                depth_nm: 100.0,
            }),
            Incidence::from_cosines(0.3, 0.4, 550.0).unwrap(),
            Options::default(),
        ),
        (
            "sinusoid, C method, classical",
            g(Profile::Sinusoid { depth_nm: 200.0 }),
            Incidence::classical(0.3, 550.0).unwrap(),
            Options::default(),
        ),
        (
            "sinusoid, C method, conical",
            g(Profile::Sinusoid { depth_nm: 200.0 }),
            Incidence::from_cosines(0.3, 0.4, 550.0).unwrap(),
            Options::default(),
        ),
        (
            "sinusoid, FMM staircase of 8 slabs, classical",
            g(Profile::Sinusoid { depth_nm: 200.0 }),
            Incidence::classical(0.3, 550.0).unwrap(),
            Options {
                method: Method::Fmm,
                slabs: Some(8),
                ..Options::default()
            },
        ),
    ];
    for (name, g, inc, opts) in cases {
        // The largest work cap: the default (`DEFAULT_MAX_WORK`) refuses some of these.
        let s = Solver::new(Options {
            max_work: diffraction_fmm::MAX_WORK,
            ..opts
        })
        .unwrap();
        let t0 = Instant::now();
        let r = s.solve_at(&g, inc, MAX_HARMONICS);
        let dt = t0.elapsed().as_secs_f64();
        println!(
            "{name}: {:.1} s at {MAX_HARMONICS} harmonics ({})",
            dt,
            r.as_ref()
                .map_or_else(|e| e.to_string(), |s| format!("{} orders", s.orders.len()))
        );
        if let Ok(sol) = r {
            check_solution(&sol.orders, &name);
        }
    }
}

/// An error's value prints in its shortest form: a subnormal or huge value was printed with
/// every decimal digit (`period_nm = 0.000…0049…`, 750 characters for 5e-324; 309 digits for
/// `f64::MAX`).
#[test]
fn error_values_print_short() {
    let g = |period_nm: f64| Grating {
        period_nm,
        profile: Profile::Flat,
        metal: Metal::AL,
        cover: None,
    };
    let s = Solver::default();
    let inc = Incidence::classical(0.2, 550.0).unwrap();
    let msg = |d: f64| s.solve(&g(d), inc).unwrap_err().to_string();
    assert_eq!(
        msg(f64::MAX),
        "period_nm = 1.7976931348623157e308: must be finite, in [1, 1e5] nm"
    );
    assert_eq!(
        msg(5e-324),
        "period_nm = 5e-324: must be finite, in [1, 1e5] nm"
    );
    assert_eq!(
        Incidence::classical(0.2, 1e-300).unwrap_err().to_string(),
        "wavelength_nm = 1e-300: must be in [100, 20000] nm"
    );
    // Ordinary values keep their plain form.
    assert_eq!(msg(-5.0), "period_nm = -5: must be finite, in [1, 1e5] nm");
}

/// Periods far below any grating's were accepted and solved to nonsense: a sinusoid of period
/// 10⁻¹⁰ nm (depth half of it) at λ = 20 µm, β = 0.4, gave Σ η = (202, 148) from the Fourier
/// modal method at 41 harmonics, and a flat one of 10⁻³⁰⁰ nm a numerical error that named no
/// parameter. Periods below `MIN_PERIOD_NM` are refused naming `period_nm`.
#[test]
fn periods_below_the_minimum_are_refused() {
    let inc = Incidence::from_cosines(0.3, 0.4, 20_000.0).unwrap();
    for (d, profile) in [
        (1e-10, Profile::Sinusoid { depth_nm: 0.5e-10 }),
        (1e-300, Profile::Flat),
        (
            f64::from_bits(diffraction_fmm::MIN_PERIOD_NM.to_bits() - 1),
            Profile::Flat,
        ),
    ] {
        let g = Grating {
            period_nm: d,
            profile,
            metal: Metal::AL,
            cover: None,
        };
        for method in [Method::Fmm, Method::Auto] {
            let s = Solver::new(Options {
                method,
                ..Options::default()
            })
            .unwrap();
            let e = s.solve_at(&g, inc, 41).unwrap_err();
            assert_eq!(e.parameter(), "period_nm", "{d:e}: {e}");
        }
    }
    // At the minimum a solve is accepted, and physical.
    let g = Grating {
        period_nm: diffraction_fmm::MIN_PERIOD_NM,
        profile: Profile::Sinusoid { depth_nm: 0.5 },
        metal: Metal::AL,
        cover: None,
    };
    let sol = Solver::default().solve_at(&g, inc, 41).unwrap();
    check_solution(&sol.orders, &g);
}

/// A fixed-count solve of a deep sinusoid by the C method was returned with more reflected than
/// incident power: d = 1000 nm, h = 2000 nm (aspect 2, inside `MAX_ASPECT`), Al, s = 0.3,
/// λ = 5 µm at 101 harmonics gave Σ TE = 1.17; aspect 10 at λ = 20 µm, Σ TM = 1.92. Such a
/// result is a numerical error now; the converged solve of the same grating is physical.
#[test]
fn solves_with_more_than_the_incident_power_are_refused() {
    let g = |h: f64| Grating {
        period_nm: 1000.0,
        profile: Profile::Sinusoid { depth_nm: h },
        metal: Metal::AL,
        cover: None,
    };
    for (h, lambda) in [(2000.0, 5000.0), (10_000.0, 20_000.0)] {
        let inc = Incidence::classical(0.3, lambda).unwrap();
        let e = Solver::default().solve_at(&g(h), inc, 101).unwrap_err();
        assert!(matches!(e, Error::Numerical(_)), "{h} {lambda}: {e}");
        assert!(
            e.to_string().starts_with("numerics: the reflected orders"),
            "{e}"
        );
    }
    let inc = Incidence::classical(0.3, 5000.0).unwrap();
    let sol = Solver::default().solve(&g(2000.0), inc).unwrap();
    check_solution(&sol.orders, &"converged");
}

/// `TableSpec::validation_points` had no bound: `usize::MAX` points were allocated at once
/// (a capacity overflow) before the budget counted their solves. Beyond
/// `MAX_VALIDATION_POINTS` a spec is refused, naming the field; at the bound it builds.
#[test]
fn validation_points_are_bounded() {
    let solver = Hostile {
        period_nm: 1000.0,
        kind: 0,
    };
    let base = TableSpec {
        sin_theta_range: (-0.5, 0.5),
        lambda_range_nm: (500.0, 600.0),
        max_solves: 5000,
        threads: 1,
        initial_sin_step: 0.5,
        initial_lambda_step_nm: 100.0,
        tolerance: 0.5,
        ..TableSpec::default()
    };
    for n in [
        usize::MAX,
        diffraction_fmm::table::MAX_VALIDATION_POINTS + 1,
    ] {
        let spec = TableSpec {
            validation_points: n,
            ..base.clone()
        };
        match build_table(&solver, &spec, &mut |_| {}) {
            Err(TableError::Invalid(e)) => assert_eq!(e.parameter(), "validation_points"),
            other => panic!("{n}: {other:?}"),
        }
    }
    // A plausible solver and a spec within every bound builds.
    let spec = TableSpec {
        validation_points: 8,
        ..base
    };
    assert!(build_table(&solver, &spec, &mut |_| {}).is_ok());
}

/// The `grating-table` flags that take a value, with hostile values for each.
const CLI_FLAGS: [&str; 22] = [
    "--lines-per-mm",
    "--period",
    "--profile",
    "--depth",
    "--duty",
    "--blaze",
    "--metal",
    "--nk",
    "--cover",
    "--cover-passes",
    "--tolerance",
    "--lambda",
    "--sin-max",
    "--abs-beta",
    "--conical-version",
    "--max-plane-ratio",
    "--threads",
    "--validation",
    "--solve-tolerance",
    "--max-harmonics",
    "--nodes-of",
    "--frobnicate",
];
const CLI_VALUES: [&str; 20] = [
    "nan",
    "inf",
    "-inf",
    "-0",
    "0",
    "1e400",
    "",
    "18446744073709551616",
    "-1",
    "5e-324",
    "1e300",
    "abc",
    "1,2,3",
    ",",
    "0.5,nan",
    "1000,1e400",
    "/",
    "/dev/zero",
    "/nonexistent/file.json",
    "\u{1F600}",
];

/// One `grating-table` run with a hostile value for one flag, on a cheap grating whose build
/// cannot finish (two solves allowed), writing over an existing file: the exit code is 2 (bad
/// input, the message naming the flag) or 1 (the build failed), and the file is untouched.
fn cli_case(flag: &str, value: &str, out: &std::path::Path) {
    std::fs::write(out, "previous").unwrap();
    let o = out.to_str().unwrap();
    let mut args = SHALLOW_LAMELLAR.to_vec();
    args.extend(["--lambda", "500,600"]);
    args.extend([flag, value, "--max-solves", "2", "--out", o]);
    let t0 = Instant::now();
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_grating-table"))
        .args(&args)
        .output()
        .expect("the binary runs");
    let code = run.status.code().unwrap_or(-1);
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        code == 1 || code == 2,
        "{flag} {value:?}: exit {code}: {err}"
    );
    if code == 2 {
        let named = err.contains(flag)
            || ["period_nm", "depth_nm", "duty", "blaze", "n =", "k ="]
                .iter()
                .any(|p| err.contains(p));
        assert!(named, "{flag} {value:?}: {err}");
    }
    assert!(!err.contains("panicked"), "{flag} {value:?}: {err}");
    assert_eq!(
        std::fs::read_to_string(out).unwrap(),
        "previous",
        "{flag} {value:?}"
    );
    assert!(t0.elapsed().as_secs() < 60, "{flag} {value:?}");
}

fn cli_sweep(draws: Option<usize>, seed: u64) {
    let out = std::env::temp_dir().join(format!("adversarial-{}-{seed}.json", std::process::id()));
    let mut r = Rng(seed, true);
    let mut runs = 0;
    match draws {
        Some(n) => {
            for _ in 0..n {
                let f = CLI_FLAGS[r.below(CLI_FLAGS.len() as u64) as usize];
                let v = CLI_VALUES[r.below(CLI_VALUES.len() as u64) as usize];
                cli_case(f, v, &out);
                runs += 1;
            }
        }
        None => {
            for f in CLI_FLAGS {
                for v in CLI_VALUES {
                    cli_case(f, v, &out);
                    runs += 1;
                }
            }
        }
    }
    let _ = std::fs::remove_file(&out);
    println!("grating-table: {runs} hostile runs");
}

#[test]
fn cli_sweep_quick() {
    cli_sweep(Some(40), 0xc11);
}

#[test]
#[ignore = "every flag with every hostile value"]
fn cli_sweep_long() {
    cli_sweep(None, 0xc12);
}

/// A solver's answers were kept as they came: order numbers past `i32::MAX` wrapped (an
/// index out of bounds in the assembly: a panic), a NaN or an infinite efficiency became 0,
/// a TM list shorter than TE was padded with zeros. Such an answer is a solver failure now,
/// with a message saying what was wrong.
#[test]
fn hostile_solver_answers_are_solver_errors() {
    let spec = TableSpec {
        sin_theta_range: (-0.5, 0.5),
        lambda_range_nm: (500.0, 600.0),
        max_solves: 2000,
        validation_points: 4,
        threads: 1,
        initial_sin_step: 0.5,
        initial_lambda_step_nm: 100.0,
        tolerance: 0.5,
        ..TableSpec::default()
    };
    for kind in [1, 4, 5, 7, 8, 10] {
        let solver = Hostile {
            period_nm: 1000.0,
            kind,
        };
        match build_table(&solver, &spec, &mut |_| {}) {
            Err(TableError::Solver { message, .. }) => {
                assert!(message.len() < MAX_MESSAGE, "{kind}: {message}");
            }
            other => panic!("{kind}: {other:?}"),
        }
    }
}
