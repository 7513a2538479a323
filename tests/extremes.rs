//! Extreme finite inputs through every public non-colour function: the output is finite and
//! non-negative (or a typed error), and the work of each call is bounded, counted as the
//! evaluations and peak visits of a model implemented here (not as wall time), or as what the
//! call reports of its own work (orders, nodes). The colour types have their own sweep
//! (`tests/color_extremes.rs`).
//!
//! `sweep` (a few seconds in release) draws a fixed number of cases from a seeded generator
//! over pools of extreme values; `sweep_long` (ignored) draws fifty times as many.
//!
//! Every public function is called: the kernels, `Grating` and its iterators, `GratingEquation`,
//! `Band`, the models (`AguHill`, `Thorman`, `Stam`, `GratingBsdf`) through `eval`, `eval_f32`,
//! `eval4`, `response`, `peaks` and `grating_response`, the samplers (`sample`, `pdf`, `pdf4`,
//! `sample_weight_bound`, `albedo`, `sample_wavelength`, `wavelength_pdf`, `regularize`),
//! `GrooveSpread`, `SampledWavelengths`, `Illumination`, the strategies (built and parsed),
//! `Spectral` (`xyz`, `xyz_response`, `xyz_brdf`, `paper_peaks`, `paper_peaks_brdf`, `choose`,
//! the Monte-Carlo estimators), `ColorTable` (`new`, `lookup`, `mean`, with small inputs: see
//! [`TABLE_MAX_SLITS`]) and the frames and fields.
//!
//! Every property fails the sweep at its first failure, printing a reproducer; the cases that
//! failed once have reproducers of their own in `tests/extremes_handover.rs`.
//!
//! It covers the baselines (Thorman, Stam) too, so it needs the feature `baselines` (Cargo.toml's
//! `required-features`; the README's test command enables every feature).

use std::cell::Cell;

use diffraction::frame::{phase_projection, GratingField, ShadingFrame, Tile};
use diffraction::kernel::{n_slit, n_slit_cycles, single_slit, single_slit_cycles};
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::stam::bessel_j;
use diffraction::{
    AguHill, Band, Bsdf, ColorTable, DiffractionBrdf, Grating, GratingBsdf, GratingEquation,
    GrooveSpread, Illumination, Peak, PeakSummary, Profile, SampledWavelengths, Slits,
    SpectralResponse, Stam, Thorman, MAX_ORDERS,
};
use glam::{DVec2, DVec3};

#[path = "support/extreme_inputs.rs"]
mod extreme_inputs;
#[path = "support/generic_models.rs"]
mod generic_models;
#[path = "support/groove_proxy.rs"]
mod groove_proxy;
#[path = "support/rng.rs"]
mod rng;
use extreme_inputs::{generic_strategies, strategies, Rng, COUNTS};
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

/// `ColorTable::new` is bounded in memory (`ColorTable::MAX_NODES`) but not in time: measured
/// on a loaded 2-core machine, 70.6 s for `Grating::new(2537826.6745452136,
/// 1.3211993091378478, 2218803829)` at accuracy 10⁻⁶, 46.5 s for `(1e9, 5e-324, u32::MAX)` at
/// 10⁻⁶ and 5.2 s for `(1e300, 5e299, 1000)` at 10⁻³. The sweep builds tables only for N up
/// to this, periods from 100 nm to 10⁶ nm and accuracies of 10⁻³ and above.
const TABLE_MAX_SLITS: u32 = 10_000;
/// A table is built in one case in this many (each costs milliseconds).
const TABLE_EVERY: u64 = 16;
/// `GratingBsdf::albedo` is known to take seconds at hundreds of candidate orders (up to
/// 10.7 s at 300-512 of them, by the measurement); the sweep calls it where 2·d/λ is
/// at most this.
const ALBEDO_MAX_ORDERS: f64 = 64.0;

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
    bsdf_calls: u64,
    max_bsdf_visits: u64,
    tables: u64,
    max_table_nodes: usize,
}

impl Tally {
    /// Checks `ok`; a failure panics with the case's reproducer.
    fn expect(&mut self, ok: bool, what: &str, repro: impl FnOnce() -> String) {
        assert!(ok, "{what}: {}", repro());
    }
}

fn is_ok(v: f64) -> bool {
    v.is_finite() && v >= 0.0
}

fn finite_nonneg(v: f64, what: &str) {
    assert!(v.is_finite() && v >= 0.0, "{what}: {v}");
}

fn finite(v: f64, what: &str) {
    assert!(v.is_finite(), "{what}: {v}");
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
    // The run of propagating orders is found in bounded work (34 evaluations per end) and
    // its length is known.
    let orders = g.diffracted_orders(wi, lambda);
    assert!(orders.len() as u64 <= 1 << 32);
    for o in orders.take(8) {
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
        finite(s.phase(wo, wi, lambda), "Stam phase");
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
        if let Some(r) = m.grating_response(wo, wi) {
            assert!(r.u.is_finite() && is_ok(r.scale), "grating_response: {r:?}");
        }
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
            assert!(
                is_ok(p.equivalent_width_nm) && band.contains(p.wavelength_nm),
                "peak of a model: {p:?} in {band:?}"
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
    if let Some(s) = &stam {
        stam_sampler(rng, s, wo, wi, lambda);
    }
    radiometric(rng, &g, band, wo, wi, lambda, spectral, tally);
    wavelengths_and_grooves(rng, band, lambda, tally);
    if rng.next() % TABLE_EVERY == 0 {
        table(rng, spectral, tally);
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
        phase_projection(unit(wo), unit(wi), unit(t)),
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

/// Stam's sampler (the cosine hemisphere) and its densities.
fn stam_sampler(rng: &mut Rng, s: &Stam, wo: DVec3, wi: DVec3, lambda: f64) {
    let l4 = SampledWavelengths::sample_uniform(rng.real(), Band::VISIBLE);
    for v in s.eval4(wo, wi, &l4).into_iter().chain(s.pdf4(wo, wi, &l4)) {
        finite_nonneg(v, "Stam eval4/pdf4");
    }
    finite_nonneg(s.pdf(wo, wi, lambda), "Stam pdf");
    if let Some(x) = s.sample(wo, lambda, rng.real(), DVec2::new(rng.real(), rng.real())) {
        assert!(x.wi.is_finite() && x.wi.z > 0.0, "Stam sample direction");
        finite_nonneg(x.f, "Stam sample f");
        assert!(
            x.pdf > 0.0 && x.pdf.is_finite(),
            "Stam sample pdf {}",
            x.pdf
        );
        finite_nonneg(x.weight(), "Stam sample weight");
    }
    let mut r = *s;
    r.regularize();
    assert_eq!(r, *s, "Stam::regularize changes nothing");
}

/// The radiometric grating BSDF through every method, for one groove spread drawn from the
/// pools, and its colour through the counting wrapper.
#[allow(clippy::too_many_arguments)]
fn radiometric(
    rng: &mut Rng,
    g: &Grating,
    band: Band,
    wo: DVec3,
    wi: DVec3,
    lambda: f64,
    spectral: &Spectral,
    tally: &mut Tally,
) {
    let base = GratingBsdf::new(*g);
    let groove = match rng.next() % 4 {
        0 => GrooveSpread::gaussian(rng.positive()).ok(),
        1 => GrooveSpread::coherence_length(rng.positive()).ok(),
        2 => Some(GrooveSpread::IDEAL),
        _ => None,
    };
    let regularized = rng.next() % 4 == 0;
    let mut b = match groove {
        Some(gr) => base.with_groove(gr),
        None => base,
    };
    let model = format!(
        "GratingBsdf::new({:?}).with_groove({:?}){}",
        b.grating(),
        b.groove(),
        if regularized { ", regularized" } else { "" },
    );
    if regularized {
        b.regularize();
    }
    let repro =
        |what: &str| format!("{what} of {model} at wo = {wo:?}, wi = {wi:?}, λ = {lambda:e}");
    let l4 = SampledWavelengths::sample_uniform(rng.real(), band);
    let f = b.eval(wo, wi, lambda);
    tally.expect(is_ok(f), "GratingBsdf::eval finite", || repro("eval"));
    for v in b.eval4(wo, wi, &l4).into_iter().chain(b.pdf4(wo, wi, &l4)) {
        tally.expect(is_ok(v), "GratingBsdf::eval4/pdf4 finite", || {
            repro("eval4/pdf4")
        });
    }
    let p = b.pdf(wo, wi, lambda);
    tally.expect(is_ok(p), "GratingBsdf::pdf finite", || repro("pdf"));
    tally.expect(
        is_ok(b.response(wo, wi, lambda)),
        "GratingBsdf::response finite",
        || repro("response"),
    );
    let bound = b.sample_weight_bound(wo, lambda);
    tally.expect(is_ok(bound), "sample_weight_bound finite", || {
        repro("sample_weight_bound")
    });
    let (uc, u2) = (rng.real(), DVec2::new(rng.real(), rng.real()));
    if let Some(x) = b.sample(wo, lambda, uc, u2) {
        let ok = x.wi.is_finite() && x.wi.z > 0.0 && is_ok(x.f) && x.pdf > 0.0 && x.pdf.is_finite();
        tally.expect(ok, "GratingBsdf::sample finite", || {
            format!("{} with uc = {uc:e}, u2 = {u2:?}: {x:?}", repro("sample"))
        });
        let w = x.weight();
        tally.expect(
            is_ok(w) && w <= bound * (1.0 + 1e-9),
            "GratingBsdf::sample weight within sample_weight_bound",
            || {
                format!(
                    "{}, uc = {uc:e}, u2 = {u2:?}: weight {w:e}, bound {bound:e}",
                    repro("sample")
                )
            },
        );
    }
    if lambda > 0.0 && 2.0 * g.period_nm() / lambda <= ALBEDO_MAX_ORDERS {
        if let Some(a) = b.albedo(wo, lambda) {
            tally.expect(
                is_ok(a) && a <= 1.0 + 1e-6,
                "GratingBsdf::albedo in [0, 1]",
                || format!("{}: {a:e}", repro("albedo")),
            );
        }
    }
    let xi = rng.real();
    if let Some(ws) = b.sample_wavelength(wo, wi, band, xi) {
        let ok = band.contains(ws.lambda_nm) && ws.pdf > 0.0 && ws.pdf.is_finite();
        tally.expect(ok, "sample_wavelength in the band, finite pdf", || {
            format!(
                "{} in {band:?}, xi = {xi:e}: {ws:?}",
                repro("sample_wavelength")
            )
        });
    }
    let wp = b.wavelength_pdf(wo, wi, band, lambda);
    tally.expect(is_ok(wp), "wavelength_pdf finite", || {
        format!("{} in {band:?}: {wp:e}", repro("wavelength_pdf"))
    });
    for v in [
        b.efficiency(rng.pick(&[0, 1, -1, 7, i32::MAX, i32::MIN])),
        b.lobe_half_width(lambda),
    ] {
        tally.expect(is_ok(v), "efficiency/lobe_half_width finite", || {
            repro("efficiency/lobe_half_width")
        });
    }
    let _ = (
        b.is_near_specular(),
        b.flags(),
        b.groove(),
        b.order_efficiency(),
    );
    if let Some(r) = b.grating_response(wo, wi) {
        tally.expect(
            r.u.is_finite() && is_ok(r.scale),
            "GratingBsdf::grating_response finite",
            || format!("{}: {r:?}", repro("grating_response")),
        );
        let c = spectral.xyz_response(&r, rng.pick(&strategies()));
        tally.expect(
            is_ok(c.x) && is_ok(c.y) && is_ok(c.z),
            "xyz_response finite",
            || format!("{}: {c:?}", repro("xyz_response")),
        );
    }
    // Peaks (visits counted) and the generic colour path (evaluations counted).
    let counting = Counting {
        inner: &b,
        evals: Cell::new(0),
        visits: Cell::new(0),
    };
    let mut bad_peak = None;
    let summary = counting.peaks(wo, wi, band, &mut |p| {
        let ok =
            is_ok(p.intensity) && is_ok(p.equivalent_width_nm) && band.contains(p.wavelength_nm);
        if !ok && bad_peak.is_none() {
            bad_peak = Some(p);
        }
    });
    tally.expect(bad_peak.is_none(), "GratingBsdf::peaks finite", || {
        format!("{}: {bad_peak:?}", repro("peaks"))
    });
    let visits = counting.visits.get();
    tally.expect(
        visits <= MAX_VISITS_PER_CALL && u64::from(summary.orders) == visits,
        "GratingBsdf::peaks within MAX_ORDERS",
        || format!("{}: {visits} visits", repro("peaks")),
    );
    tally.max_bsdf_visits = tally.max_bsdf_visits.max(visits);
    counting.visits.set(0);
    let strategy = rng.pick(&generic_strategies());
    let c = spectral.xyz_brdf(&counting, wo, wi, strategy);
    let (evals, visits) = (counting.evals.get(), counting.visits.get());
    tally.expect(
        is_ok(c.x) && is_ok(c.y) && is_ok(c.z),
        "xyz_brdf of GratingBsdf finite",
        || format!("{} with {strategy}: {c:?}", repro("xyz_brdf")),
    );
    tally.expect(
        evals <= MAX_EVALS_PER_CALL && visits <= MAX_PASSES_PER_CALL * MAX_VISITS_PER_CALL,
        "xyz_brdf of GratingBsdf within its work caps",
        || {
            format!(
                "{} with {strategy}: {evals} evals, {visits} visits",
                repro("xyz_brdf")
            )
        },
    );
    tally.max_evals = tally.max_evals.max(evals);
    tally.bsdf_calls += 1;
}

/// `SampledWavelengths`, `Band` and `GrooveSpread` at the ends of their ranges.
fn wavelengths_and_grooves(rng: &mut Rng, band: Band, lambda: f64, tally: &mut Tally) {
    let u = rng.real();
    let mut l = SampledWavelengths::sample_uniform(u, band);
    for (&x, &p) in l.lambda().iter().zip(l.pdf().iter()) {
        assert!(band.contains(x), "sample_uniform({u:e}, {band:?}) = {l:?}");
        assert!(
            p.is_finite() && p > 0.0,
            "sample_uniform({u:e}, {band:?}) = {l:?}"
        );
    }
    // What sample_uniform returns, SampledWavelengths::new accepts.
    assert_eq!(SampledWavelengths::new(l.lambda(), l.pdf()), Ok(l));
    assert!(band.width_nm() >= Band::MIN_WIDTH_NM * (1.0 - f64::EPSILON));
    let _ = (l.hero(), band.contains(lambda));
    l.terminate_secondary();
    assert!(l.secondary_terminated() && l.pdf()[0].is_finite());
    // The hero MIS weights of a light sample and of an emitter hit: finite and ≥ 0 for any
    // densities.
    let pdf4 = [rng.real(), rng.real(), rng.real(), rng.real()];
    let mis = diffraction::HeroMis::new();
    for w in [
        mis.light_sample_weight(rng.real(), pdf4, &l),
        mis.emitter_weight(rng.real(), &l),
    ] {
        assert!(
            w.is_finite() && w >= 0.0,
            "hero MIS weight of {pdf4:?}: {w}"
        );
    }
    let _ = SampledWavelengths::new(
        [rng.real(), rng.real(), rng.real(), rng.real()],
        [rng.real(), rng.real(), rng.real(), rng.real()],
    );
    for groove in [
        GrooveSpread::gaussian(rng.positive()),
        GrooveSpread::coherence_length(rng.positive()),
        Ok(GrooveSpread::IDEAL),
    ]
    .into_iter()
    .flatten()
    {
        let (v, v1) = (rng.real(), rng.real());
        let repro = || format!("{groove:?} at v = {v:e}, v1 = {v1:e}, λ = {lambda:e}");
        for (what, x) in [
            ("value", groove.value(v, lambda)),
            ("width", groove.width(lambda)),
            ("pdf", groove.pdf(v, lambda)),
            ("mean", groove.mean(v, v1, lambda)),
            ("proxy_bound", groove.proxy_bound()),
        ] {
            assert!(is_ok(x), "GrooveSpread::{what}: {x:e}, {}", repro());
        }
        let m = groove.mass(v, v1, lambda);
        assert!(
            (0.0..=1.0).contains(&m),
            "GrooveSpread::mass: {m:e}, {}",
            repro()
        );
        let x = groove.sample(rng.real(), lambda);
        assert!(x.is_finite(), "GrooveSpread::sample: {x:e}, {}", repro());
        // A sampled v has a positive density wherever that density, s/(π·(s² + v²)) (here
        // in logarithms, which cannot overflow), is between 10⁻³⁰⁰ and f64::MAX (beyond it,
        // at λ below 10⁻³⁰⁹·L, the documented 0).
        let pdf = groove.pdf(x, lambda);
        let sc = groove_proxy::proxy_scale(groove, lambda);
        let (big, small) = (sc.max(x.abs()), sc.min(x.abs()));
        let ln_pdf = sc.ln()
            - std::f64::consts::PI.ln()
            - 2.0 * big.ln()
            - (1.0 + (small / big).powi(2)).ln();
        tally.expect(
            groove.is_delta()
                || sc == 0.0
                || pdf > 0.0
                || !(-300.0 * 10f64.ln()..f64::MAX.ln()).contains(&ln_pdf),
            "GrooveSpread::pdf of its own sample is positive",
            || format!("{}: sample {x:e}, pdf {pdf:e}", repro()),
        );
        let _ = (groove.kind(), GrooveSpread::new(groove.kind()));
    }
}

/// A colour table over small inputs (see [`TABLE_MAX_SLITS`]): bounded in nodes, finite
/// lookups and means.
fn table(rng: &mut Rng, spectral: &Spectral, tally: &mut Tally) {
    let d = rng.pick(&[100.0, 740.0, 1600.0, 1e4, 1e6]);
    let n = rng.pick(&[1, 2, 5, 30, 1000, TABLE_MAX_SLITS]);
    let accuracy = rng.pick(&[1e-3, 1e-2, 1.0]);
    let g = Grating::new(d, d * rng.pick(&[0.5, 1.0, 1e-3]), n).unwrap();
    let t = ColorTable::new(spectral, &g, accuracy).unwrap();
    tally.expect(
        t.node_count() <= ColorTable::MAX_NODES,
        "ColorTable node budget",
        || format!("{g:?} at {accuracy}: {} nodes", t.node_count()),
    );
    tally.max_table_nodes = tally.max_table_nodes.max(t.node_count());
    tally.tables += 1;
    for _ in 0..8 {
        let (u0, u1) = (rng.real(), rng.real());
        let (a, m) = (t.lookup(u0), t.mean(u0, u1));
        let ok = [a.x, a.y, a.z, m.x, m.y, m.z].into_iter().all(is_ok);
        tally.expect(ok, "ColorTable lookup/mean finite", || {
            format!("{g:?} at {accuracy}, u0 = {u0:e}, u1 = {u1:e}: {a:?} {m:?}")
        });
    }
    let _ = (t.scale(), t.error_estimate(), t.accuracy(), t.size_bytes());
}

fn sweep_with(cases: usize, seed: u64) {
    let spectral = Spectral::new(Illuminant::D65);
    let mut rng = Rng(rng::Rng(seed));
    let mut tally = Tally::default();
    for _ in 0..cases {
        one_case(&mut rng, &spectral, &mut tally);
    }
    println!(
        "{cases} cases, {} generic-path calls, at most {} evaluations and {} peak visits per call; \
         {} GratingBsdf cases, at most {} peak visits; {} colour tables, at most {} nodes",
        tally.calls,
        tally.max_evals,
        tally.max_visits,
        tally.bsdf_calls,
        tally.max_bsdf_visits,
        tally.tables,
        tally.max_table_nodes,
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

/// Stam's peaks over Band(1 nm, 10⁶ nm) for a deep sine (d = 38 888 nm, h₀ = 10 µm): 38 888
/// orders, which took 8.5 s when each order's J_m(φ)² ran the full recurrence (up to 10⁵
/// steps). Each peak is still Stam's own value at its wavelength (`response` there, which
/// takes J² from the full recurrence): to 10⁻⁸ relative away from the zeros of J.
#[test]
fn stam_peaks_over_a_huge_band() {
    let s = Stam::new(Profile::Sine, 38888.0, 1e4, 38888.0).unwrap();
    let band = Band::new(1.0, 1e6).unwrap();
    let w = DVec3::new(0.5, 0.0, 0.75f64.sqrt());
    let mut peaks = vec![];
    let summary = s.peaks(w, w, band, &mut |p| peaks.push(p));
    assert_eq!((summary.orders, peaks.len()), (38888, 38888));
    let brightest = peaks.iter().map(|p| p.intensity).fold(0.0, f64::max);
    let mut compared = 0;
    for p in peaks.iter().step_by(97) {
        assert!(p.equivalent_width_nm.is_finite() && p.equivalent_width_nm > 0.0);
        let want = s.response(w, w, p.wavelength_nm);
        if want > 1e-3 * brightest {
            let rel = (p.intensity - want).abs() / want;
            assert!(
                rel < 1e-8,
                "order {}: {} against {want}",
                p.order,
                p.intensity
            );
            compared += 1;
        }
    }
    assert!(compared > 50, "{compared}");
}

/// λ/d = 10⁻²³: the first propagating order comes without walking the empty ones, at every
/// incidence of the class (grazing, conical), and the run's length is known.
#[test]
fn diffracted_orders_at_tiny_wavelength_over_period() {
    let g = Grating::new(1e23, 5e22, 10).unwrap();
    for wi in [
        DVec3::Z,
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.6, 0.8, 0.0),
        DVec3::new(-1.0, 0.0, 0.0),
        DVec3::new(1e-8, (1.0f64 - 2.2e-16).sqrt(), 1e-8),
    ] {
        let orders = g.diffracted_orders(wi, 1.0);
        let n = orders.len();
        assert!(n > 0 && n as u64 <= 1 << 32, "{wi}: {n}");
        let first = orders.clone().next().unwrap();
        assert!(first.direction.is_finite() && first.direction.z > 0.0);
        assert!(first.intensity.is_finite());
    }
}

/// The weight-bound case (a lobe narrower than f64's phase resolution): the weight was
/// 8.8·10⁻⁹ against a bound of 1.96·10⁻¹³; it is within the bound on this base.
#[test]
fn sample_weight_within_its_bound_for_a_sub_resolution_lobe() {
    let b = GratingBsdf::new(Grating::new(1e12, 3.0, 1379100723).unwrap());
    let wo = DVec3::new(0.39996, 0.17600, 0.8995);
    let bound = b.sample_weight_bound(wo, 417.473);
    if let Some(x) = b.sample(wo, 417.473, 0.1, DVec2::new(0.8662, 0.3)) {
        assert!(x.weight() <= bound, "{} > {bound}", x.weight());
    }
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
