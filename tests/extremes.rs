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
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::stam::bessel_j;
use diffraction::{
    AguHill, Band, DiffractionBrdf, Grating, GratingEquation, Illumination, Peak, PeakSummary,
    Profile, Slits, Stam, Thorman, MAX_ORDERS,
};
use glam::{DVec2, DVec3};

/// The most `eval` calls one `Spectral::xyz_brdf` call may make on the generic path. `Exact`
/// is the largest: 470·8 for the 1 nm rule, plus per refined window 16 per nm it spans + 16 +
/// 128 pieces × 2 rows × 8; the windows never overlap and each spans whole nanometres, so at
/// most 470 of them: 3760 + 16·470 + 470·2064 < 10⁶. Measured maximum over the quick sweep:
/// 496 320 (a 2× margin).
const MAX_EVALS_PER_CALL: u64 = 1_000_000;

/// The most peaks one `peaks` call may visit: the documented cap.
const MAX_VISITS_PER_CALL: u64 = MAX_ORDERS as u64;

/// Cases drawn by the quick sweep.
const QUICK_CASES: usize = 300;

/// SplitMix64: a seeded generator, so that every run tries the same inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
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

/// A model that counts what the integrator asks of it, delegating to `inner` but without a
/// grating response, so that `Spectral::xyz_brdf` takes the generic path.
struct Counting<'a> {
    inner: &'a dyn DiffractionBrdf,
    evals: Cell<u64>,
    visits: Cell<u64>,
}

impl DiffractionBrdf for Counting<'_> {
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        self.evals.set(self.evals.get() + 1);
        self.inner.eval(wi, wo, lambda_nm)
    }
    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        self.inner.peaks(wi, wo, band, &mut |p| {
            self.visits.set(self.visits.get() + 1);
            visit(p)
        })
    }
    fn cosine_included(&self) -> bool {
        self.inner.cosine_included()
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

const STRATEGIES: &[Strategy] = &[
    Strategy::Uniform { samples: 0 },
    Strategy::Uniform { samples: 7 },
    Strategy::Uniform { samples: u32::MAX },
    Strategy::GaussLegendre { intervals: 0 },
    Strategy::GaussLegendre { intervals: 16 },
    Strategy::GaussLegendre {
        intervals: u32::MAX,
    },
    Strategy::PeakSearch { refine: false },
    Strategy::PeakSearch { refine: true },
    Strategy::PaperPeaks,
    Strategy::Asymptotic,
    Strategy::Exact,
    Strategy::Auto { accuracy: 1e-3 },
    Strategy::Auto { accuracy: 1e-12 },
    Strategy::Auto { accuracy: 5e-324 },
    Strategy::Auto { accuracy: f64::MAX },
    Strategy::Auto { accuracy: -1.0 },
];

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
    let (wi, wo) = (rng.direction(), rng.direction());
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
    let mut models: Vec<&dyn DiffractionBrdf> = vec![&agu];
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
        finite_nonneg(m.eval(wi, wo, lambda), "eval");
        let clamp3 = |v: DVec3| {
            v.as_vec3()
                .clamp(glam::Vec3::splat(f32::MIN), glam::Vec3::splat(f32::MAX))
        };
        let l32 = (lambda as f32).clamp(f32::MIN, f32::MAX);
        finite_nonneg(m.eval_f32(clamp3(wi), clamp3(wo), l32) as f64, "eval_f32");
        finite_nonneg(
            shading.eval(m, wi, wo, lambda, light, light),
            "Illumination::eval",
        );
        let counting = Counting {
            inner: m,
            evals: Cell::new(0),
            visits: Cell::new(0),
        };
        let summary = counting.peaks(wi, wo, band, &mut |p| {
            assert!(
                p.intensity.is_finite() && p.intensity >= 0.0,
                "peak of a model"
            );
        });
        assert!(u64::from(summary.orders) <= MAX_VISITS_PER_CALL);
        tally.max_visits = tally.max_visits.max(counting.visits.get());
        let strategy = rng.pick(STRATEGIES);
        counting.visits.set(0);
        let c = spectral.xyz_brdf(&counting, wi, wo, strategy);
        for v in [c.x, c.y, c.z] {
            finite_nonneg(v, "xyz_brdf");
        }
        assert!(
            counting.evals.get() <= MAX_EVALS_PER_CALL,
            "{} evals",
            counting.evals.get()
        );
        assert!(
            counting.visits.get() <= MAX_VISITS_PER_CALL,
            "{} visits",
            counting.visits.get()
        );
        tally.max_evals = tally.max_evals.max(counting.evals.get());
        tally.max_visits = tally.max_visits.max(counting.visits.get());
        tally.calls += 1;
    }
    // The grating paths of every strategy, and the Monte-Carlo estimators.
    let strategy = rng.pick(STRATEGIES);
    let c = spectral.xyz(&g, u, strategy);
    for v in [c.x, c.y, c.z] {
        finite_nonneg(
            v,
            &format!("xyz(d = {d:e}, w = {w:e}, {slits:?}, u = {u:e}, {strategy})"),
        );
    }
    let _ = spectral.choose(&g, u, rng.real());
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
    let mut rng = Rng(seed);
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
            Strategy::Exact,
            Strategy::PeakSearch { refine: false },
            Strategy::PeakSearch { refine: true },
            Strategy::Auto { accuracy: 1e-12 },
        ] {
            assert_eq!(s.xyz(&g, u, st), s.white(), "u = {u}, {st}");
        }
    }
    let fine = Grating::new(200.0, 100.0, 1000).unwrap();
    assert_eq!(
        s.xyz(&fine, 5e-324, Strategy::PeakSearch { refine: false }),
        s.white()
    );
    // Periods of 10¹⁹ and 10³⁰⁰ nm: finite, and the dense comb scales as 1/(d·u)² (its mean
    // intensity is λ²/(2π²·N·w²·u²)), so 1e9 → 1e19 divides the colour by 1e20.
    let y = |d: f64, st| s.xyz(&Grating::new(d, d / 2.0, 1000).unwrap(), 1.0, st).y;
    for st in [
        Strategy::Exact,
        Strategy::Auto { accuracy: 1e-3 },
        Strategy::PeakSearch { refine: false },
    ] {
        let (a, b) = (y(1e9, st), y(1e19, st));
        assert!(
            a > 0.0 && (b / a * 1e20 - 1.0).abs() < 1e-6,
            "{st}: {a} {b}"
        );
        assert!(y(1e300, st).is_finite());
    }
}
