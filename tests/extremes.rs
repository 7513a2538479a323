//! Extreme finite inputs through every public non-colour function: the output is finite and
//! non-negative (or a typed error), and the work of each call is bounded, counted as the
//! evaluations and peak visits of a model implemented here (not as wall time).
//!
//! `sweep` (a few seconds in release) draws a fixed number of cases from a seeded generator
//! over pools of extreme values; `sweep_long` (ignored) draws fifty times as many.
//!
//! It covers the `stam` models too, so it is built with that feature (the README's test command
//! enables every feature).
#![cfg(feature = "stam")]

use std::cell::Cell;

use diffraction::frame::{phase_projection, GratingField, ShadingFrame, Tile};
use diffraction::kernel::{n_slit, n_slit_cycles, single_slit, single_slit_cycles};
use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
use diffraction::stam::bessel_j;
use diffraction::{
    AguHill, Band, Grating, GratingEquation, Illumination, Peak, PeakSummary, Profile, Slits,
    SpectralResponse, Stam, Thorman, MAX_ORDERS,
};
use glam::{DVec2, DVec3};

#[path = "support/generic_models.rs"]
mod generic_models;
#[path = "support/rng.rs"]
mod rng;
use generic_models::Model;

/// The most `response` calls one `Spectral::xyz_brdf` call may make on the generic path.
/// `WINDOWS` is the largest: 470·8 for the 1 nm rule, plus per refined window 16 per nm it spans + 16 +
/// 128 pieces × 2 rows × 8; the windows never overlap and each spans whole nanometres, so at
/// most 470 of them: 3760 + 16·470 + 470·2064 < 10⁶. Measured maximum over the quick sweep:
/// 496 320 (a 2× margin).
const MAX_EVALS_PER_CALL: u64 = 1_000_000;

/// The most peaks one `peaks` call may visit: the documented cap.
const MAX_VISITS_PER_CALL: u64 = MAX_ORDERS as u64;
/// The most `peaks` passes one colour call makes on the generic path: `auto` reads the peaks'
/// sharpness first, then runs its rule, whose peak search may hand over to `WINDOWS`, each
/// one pass.
const MAX_PASSES_PER_CALL: u64 = 3;

/// Cases drawn by the quick sweep.
const QUICK_CASES: usize = 300;

/// Inputs drawn from the tests' seeded generator, so that every run tries the same ones.
struct Rng(rng::Rng);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    fn pick<T: Copy>(&mut self, pool: &[T]) -> T {
        pool[(self.next() % pool.len() as u64) as usize]
    }
    /// A value from the pool of extremes, or (one time in four) a log-uniform one in
    /// [1e-320, 1e308] with a random sign.
    fn real(&mut self) -> f64 {
        if self.next() % 4 == 0 {
            let e = -320.0 + 628.0 * (self.next() as f64 / u64::MAX as f64);
            let v = 10f64.powf(e);
            if self.next() % 2 == 0 {
                v
            } else {
                -v
            }
        } else {
            self.pick(EXTREMES)
        }
    }
    fn positive(&mut self) -> f64 {
        self.real().abs()
    }
    fn direction(&mut self) -> DVec3 {
        // Mostly unit directions, sometimes wild ones.
        if self.next() % 3 == 0 {
            DVec3::new(self.real(), self.real(), self.real())
        } else {
            let (a, b) = (
                self.next() as f64 / u64::MAX as f64,
                self.next() as f64 / u64::MAX as f64,
            );
            let (z, phi) = (a, std::f64::consts::TAU * b);
            let r = (1.0 - z * z).max(0.0).sqrt();
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        }
    }
}

const EXTREMES: &[f64] = &[
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1e-310,
    f64::MIN_POSITIVE,
    1e-300,
    1e-23,
    1e-12,
    1e-9,
    1e-6,
    0.3,
    0.5,
    1.0,
    -1.0,
    1.999,
    2.0,
    -2.0,
    360.0,
    550.0,
    830.0,
    1600.0,
    1e6,
    1e9,
    1.7824e12,
    1e12,
    1e19,
    1e300,
    -1e300,
    f64::MAX,
    -f64::MAX,
];

const COUNTS: &[u32] = &[0, 1, 2, 3, 7, 1000, 1_000_000, 10_000_000, u32::MAX];

/// A model that counts what the colour integrator asks of it, delegating to `inner`.
struct Counting<'a> {
    inner: &'a dyn Model,
    evals: Cell<u64>,
    visits: Cell<u64>,
}

impl SpectralResponse for Counting<'_> {
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.evals.set(self.evals.get() + 1);
        self.inner.response(wo, wi, lambda_nm)
    }
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        self.inner.peaks(wo, wi, band, &mut |p| {
            self.visits.set(self.visits.get() + 1);
            visit(p)
        })
    }
}

#[derive(Default)]
struct Tally {
    calls: u64,
    max_evals: u64,
    max_visits: u64,
}

fn finite_nonneg(v: f64, what: &str) {
    assert!(v.is_finite() && v >= 0.0, "{what}: {v}");
}

fn finite(v: f64, what: &str) {
    assert!(v.is_finite(), "{what}: {v}");
}

/// Every grating strategy at the ends of its accepted range.
fn strategies() -> Vec<Strategy> {
    vec![
        Strategy::uniform(1).unwrap(),
        Strategy::uniform(7).unwrap(),
        Strategy::uniform(diffraction::spectrum::MAX_WAVELENGTHS).unwrap(),
        Strategy::gauss_legendre(1).unwrap(),
        Strategy::gauss_legendre(16).unwrap(),
        Strategy::gauss_legendre(diffraction::spectrum::MAX_WAVELENGTHS / 8).unwrap(),
        Strategy::PEAK_SEARCH,
        Strategy::PEAK_SEARCH_REFINED,
        Strategy::ASYMPTOTIC,
        Strategy::EXACT,
        Strategy::auto(1e-3).unwrap(),
        Strategy::auto(diffraction::spectrum::MIN_ACCURACY).unwrap(),
        Strategy::auto(diffraction::spectrum::MAX_ACCURACY).unwrap(),
    ]
}

/// Every generic rule at the ends of its accepted range.
fn generic_strategies() -> Vec<GenericStrategy> {
    vec![
        GenericStrategy::uniform(1).unwrap(),
        GenericStrategy::uniform(diffraction::spectrum::MAX_WAVELENGTHS).unwrap(),
        GenericStrategy::gauss_legendre(16).unwrap(),
        GenericStrategy::gauss_legendre(diffraction::spectrum::MAX_WAVELENGTHS / 8).unwrap(),
        GenericStrategy::PEAK_SEARCH,
        GenericStrategy::WINDOWS,
        GenericStrategy::auto(1e-3).unwrap(),
        GenericStrategy::auto(diffraction::spectrum::MIN_ACCURACY).unwrap(),
    ]
}

/// Counts and accuracies outside the accepted ranges are refused where the strategy is built,
/// with the parameter's name.
#[test]
fn strategies_outside_their_range_are_refused() {
    for k in [0, diffraction::spectrum::MAX_WAVELENGTHS + 1, u32::MAX] {
        assert_eq!(Strategy::uniform(k).unwrap_err().parameter(), "samples");
        assert_eq!(
            GenericStrategy::uniform(k).unwrap_err().parameter(),
            "samples"
        );
    }
    for k in [0, diffraction::spectrum::MAX_WAVELENGTHS, u32::MAX] {
        assert_eq!(
            Strategy::gauss_legendre(k).unwrap_err().parameter(),
            "intervals"
        );
    }
    for a in [
        0.0,
        -1.0,
        5e-324,
        1e-12,
        2.0,
        f64::MAX,
        f64::NAN,
        f64::INFINITY,
    ] {
        assert_eq!(
            Strategy::auto(a).unwrap_err().parameter(),
            "accuracy",
            "{a}"
        );
        assert_eq!(
            GenericStrategy::auto(a).unwrap_err().parameter(),
            "accuracy",
            "{a}"
        );
    }
}

fn one_case(rng: &mut Rng, spectral: &Spectral, tally: &mut Tally) {
    // Gratings: d from the pools (1e-6 to 1e12 nm and beyond), w ≤ d, N from the counts.
    let d = rng.positive();
    let w = d * rng.pick(&[1.0, 0.5, 0.3, 1e-6, 1e-300]);
    let slits = if rng.next() % 5 == 0 {
        Slits::Infinite
    } else {
        Slits::Finite(rng.pick(COUNTS))
    };
    let (u, lambda) = (rng.real(), rng.real());
    let band = match Band::new(rng.positive(), rng.positive()) {
        Ok(b) => b,
        Err(_) => Band::VISIBLE,
    };
    // Kernels.
    let n = rng.pick(COUNTS);
    let x = rng.real();
    for v in [
        n_slit(x, n),
        n_slit_cycles(x, n),
        single_slit(x),
        single_slit_cycles(x),
    ] {
        assert!((0.0..=1.0).contains(&v), "kernel at x = {x}, N = {n}: {v}");
    }
    let xf = (x as f32).clamp(f32::MIN, f32::MAX); // finite f32 input only
    for v in [
        n_slit(xf, n),
        n_slit_cycles(xf, n),
        single_slit(xf),
        single_slit_cycles(xf),
    ] {
        assert!(
            (0.0..=1.0).contains(&v),
            "f32 kernel at x = {xf}, N = {n}: {v}"
        );
    }
    let _ = Grating::from_lines_per_mm(rng.real(), rng.real(), slits);
    let _ = GratingEquation::new(rng.real());
    let Ok(g) = Grating::with_slits(d, w, slits) else {
        return;
    };
    finite_nonneg(g.intensity(u, lambda), "intensity");
    let f32_of = |v: f64| (v as f32).clamp(f32::MIN, f32::MAX);
    finite_nonneg(
        g.intensity(f32_of(u), f32_of(lambda)) as f64,
        "intensity f32",
    );
    finite_nonneg(g.single_slit(u, lambda), "single_slit");
    finite_nonneg(g.n_slit(u, lambda), "n_slit");
    finite(g.phase_cycles(u, lambda), "phase_cycles");
    finite_nonneg(g.specular_half_width(lambda.abs()), "specular_half_width");
    if let Some(l) = g.peak_wavelength(u, rng.pick(&[1, -1, 2, i32::MAX, i32::MIN])) {
        finite_nonneg(l, "peak_wavelength");
    }
    let peaks = g.peaks(u, band);
    let _ = peaks.len();
    for p in peaks.take(8) {
        finite_nonneg(p.wavelength_nm, "peak λ");
        finite_nonneg(p.intensity, "peak intensity");
        finite_nonneg(p.equivalent_width_nm, "peak width");
    }
    let (wo, wi) = (rng.direction(), rng.direction());
    for o in g.diffracted_orders(wi, lambda).take(8) {
        assert!(
            o.direction.is_finite() && o.intensity.is_finite(),
            "diffracted order"
        );
    }
    // Models, their peaks (visits counted) and the generic path (evaluations counted).
    let agu = AguHill::new(g);
    let thorman = Thorman::new(d, rng.positive().min(1.0)).ok();
    let stam = Stam::new(
        rng.pick(&[Profile::Sine, Profile::Binary { fraction: 0.3 }]),
        d,
        rng.pick(&[0.0, 90.0, 1e4]),
        d * rng.pick(&[1.0, 20.0, 1e6]),
    )
    .ok();
    let _ = Thorman::matching(&g, lambda);
    let mut models: Vec<&dyn Model> = vec![&agu];
    if let Some(t) = &thorman {
        models.push(t);
    }
    if let Some(s) = &stam {
        finite(s.phase(wi, wo, lambda), "Stam phase");
        models.push(s);
    }
    let light = rng.positive().min(1e6);
    let shading = Illumination::new(0.1, 0.5, 1.0).unwrap();
    for &m in &models {
        finite_nonneg(m.eval(wo, wi, lambda), "eval");
        let clamp3 = |v: DVec3| {
            v.as_vec3()
                .clamp(glam::Vec3::splat(f32::MIN), glam::Vec3::splat(f32::MAX))
        };
        let l32 = (lambda as f32).clamp(f32::MIN, f32::MAX);
        finite_nonneg(m.eval_f32(clamp3(wo), clamp3(wi), l32) as f64, "eval_f32");
        finite_nonneg(m.response(wo, wi, lambda), "response");
        finite_nonneg(
            shading.eval(m, wo, wi, lambda, light, light),
            "Illumination::eval",
        );
        let counting = Counting {
            inner: m,
            evals: Cell::new(0),
            visits: Cell::new(0),
        };
        let summary = counting.peaks(wo, wi, band, &mut |p| {
            assert!(
                p.intensity.is_finite() && p.intensity >= 0.0,
                "peak of a model"
            );
        });
        assert!(u64::from(summary.orders) <= MAX_VISITS_PER_CALL);
        tally.max_visits = tally.max_visits.max(counting.visits.get());
        let strategy = rng.pick(&generic_strategies());
        for paper in [false, true] {
            counting.visits.set(0);
            counting.evals.set(0);
            let c = if paper {
                spectral.paper_peaks_brdf(&counting, wo, wi)
            } else {
                spectral.xyz_brdf(&counting, wo, wi, strategy)
            };
            for v in [c.x, c.y, c.z] {
                finite_nonneg(
                    v,
                    if paper {
                        "paper_peaks_brdf"
                    } else {
                        "xyz_brdf"
                    },
                );
            }
            assert!(
                counting.evals.get() <= MAX_EVALS_PER_CALL,
                "{} evals",
                counting.evals.get()
            );
            assert!(
                counting.visits.get() <= MAX_PASSES_PER_CALL * MAX_VISITS_PER_CALL,
                "{} visits",
                counting.visits.get()
            );
            tally.max_evals = tally.max_evals.max(counting.evals.get());
            tally.max_visits = tally.max_visits.max(counting.visits.get());
            tally.calls += 1;
        }
    }
    // The grating paths of every strategy, and the Monte-Carlo estimators.
    let strategy = rng.pick(&strategies());
    let c = spectral.xyz(&g, u, strategy);
    let p = spectral.paper_peaks(&g, u);
    for v in [c.x, c.y, c.z, p.x, p.y, p.z] {
        finite_nonneg(
            v,
            &format!("xyz(d = {d:e}, w = {w:e}, {slits:?}, u = {u:e}, {strategy})"),
        );
    }
    let _ = spectral.choose(&g, u, strategy);
    let h = spectral.xyz_hero(&g, u, rng.real(), rng.pick(COUNTS));
    let st = spectral.xyz_stratified(&g, u, &[rng.real(), rng.real(), rng.real()]);
    for v in [h.x, h.y, h.z, st.x, st.y, st.z] {
        finite_nonneg(v, "Monte-Carlo estimate");
    }
    // Frames and fields.
    let t = rng.direction();
    // Unit vectors (overflow of the caller's own huge vectors is documented).
    let unit = |v: DVec3| v.try_normalize().unwrap_or(DVec3::Z);
    finite(
        phase_projection(unit(wi), unit(wo), unit(t)),
        "phase_projection",
    );
    if let Some(f) = ShadingFrame::new(rng.direction(), rng.direction()) {
        let l = f.to_local(wi.normalize_or_zero());
        assert!(l.is_finite(), "to_local");
    }
    let p = DVec2::new(rng.real(), rng.real());
    for field in [
        GratingField::radial(DVec2::new(rng.real(), rng.real())),
        GratingField::constant(rng.real()),
    ] {
        if let Some(dir) = field.direction_at(p) {
            assert!(dir.is_finite(), "direction_at");
        }
    }
    if let Ok(field) =
        GratingField::checkerboard(rng.real(), Tile::Plain, Tile::Constant { angle: 1.0 })
    {
        if let Some(dir) = field.world_direction(p, DVec3::X, DVec3::Z) {
            assert!(dir.is_finite(), "world_direction");
        }
    }
    // Stam's coefficients within the model's own domain (phase ≤ 4π·10⁴, the deepest profile
    // at 1 nm): bounded work and finite values.
    let phase = rng.real().clamp(-1.3e5, 1.3e5);
    finite(
        bessel_j(
            rng.pick(&[0, 1, -1, 7, 1000, 200_000, i32::MAX, i32::MIN]),
            phase,
        ),
        "J_n",
    );
}

fn sweep_with(cases: usize, seed: u64) {
    let spectral = Spectral::new(Illuminant::D65);
    let mut rng = Rng(rng::Rng(seed));
    let mut tally = Tally::default();
    for _ in 0..cases {
        one_case(&mut rng, &spectral, &mut tally);
    }
    println!(
        "{cases} cases, {} generic-path calls, at most {} evaluations and {} peak visits per call",
        tally.calls, tally.max_evals, tally.max_visits
    );
}

#[test]
fn sweep() {
    sweep_with(QUICK_CASES, 0x5EED);
}

#[test]
#[ignore = "fifty times the quick sweep: about five minutes in release"]
fn sweep_long() {
    sweep_with(50 * QUICK_CASES, 0xD1FF_2AC7);
}

/// The reproducers of the issue, one per class, with the values each must give.
#[test]
fn reproducers() {
    let s = Spectral::new(Illuminant::D65);
    // Inside order 0's lobe at every wavelength: the white, for every strategy.
    let g = Grating::new(1600.0, 800.0, 1000).unwrap();
    for u in [1e-310, 5e-324, 1e-300] {
        for st in [
            Strategy::EXACT,
            Strategy::PEAK_SEARCH,
            Strategy::PEAK_SEARCH_REFINED,
            Strategy::auto(diffraction::spectrum::MIN_ACCURACY).unwrap(),
        ] {
            assert_eq!(s.xyz(&g, u, st), s.white(), "u = {u}, {st}");
        }
    }
    let fine = Grating::new(200.0, 100.0, 1000).unwrap();
    assert_eq!(s.xyz(&fine, 5e-324, Strategy::PEAK_SEARCH), s.white());
    // Periods of 10¹⁹ and 10³⁰⁰ nm: finite, and the dense comb scales as 1/(d·u)² (its mean
    // intensity is λ²/(2π²·N·w²·u²)), so 1e9 → 1e19 divides the colour by 1e20.
    let y = |d: f64, st| s.xyz(&Grating::new(d, d / 2.0, 1000).unwrap(), 1.0, st).y;
    for st in [
        Strategy::EXACT,
        Strategy::auto(1e-3).unwrap(),
        Strategy::PEAK_SEARCH,
    ] {
        let (a, b) = (y(1e9, st), y(1e19, st));
        assert!(
            a > 0.0 && (b / a * 1e20 - 1.0).abs() < 1e-6,
            "{st}: {a} {b}"
        );
        assert!(y(1e300, st).is_finite());
    }
}
