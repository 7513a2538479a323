//! One-wavelength BRDF evaluation against the naive formula, and its stiff cases.

use super::*;

/// One-wavelength inputs: local directions and a wavelength, half of them near a peak.
struct Sample {
    wi: DVec3,
    wo: DVec3,
    lambda: f64,
}

fn eval_samples(period: f64, n: u32, count: usize) -> Vec<Sample> {
    rng::near_peak_samples(period, n, count)
        .into_iter()
        .map(|(wi, wo, lambda)| Sample { wi, wo, lambda })
        .collect()
}

pub(super) fn print_eval(budget: Duration) {
    println!("## One wavelength: DiffractionBrdf::eval (f64), eval_f32 and the naive formula");
    println!(
        "{:>7} {:>7} | {:>8} {:>8} {:>9} {:>9} | {:>9} {:>9} {:>9} {:>9}",
        "N",
        "d",
        "f64 ns",
        "f32 ns",
        "naive32",
        "naive64",
        "err f32",
        "err nv32",
        "err nv64",
        "f32 input"
    );
    for n in [1u32, 30, 1000, 1_000_000] {
        for period in [740.0, 1600.0, 100_000.0] {
            let w = period / 2.0;
            let brdf = AguHill::new(Grating::new(period, w, n).expect("valid grating"));
            let s = eval_samples(period, n, 1024);
            let s32: Vec<(Vec3, Vec3, f32)> = s
                .iter()
                .map(|s| (s.wi.as_vec3(), s.wo.as_vec3(), s.lambda as f32))
                .collect();
            let s64: Vec<(DVec3, DVec3, f64)> = s.iter().map(|s| (s.wi, s.wo, s.lambda)).collect();
            let t64 = time_ns(&s64, budget, |(a, b, l)| brdf.eval(a, b, l));
            let t32 = time_ns(&s32, budget, |(a, b, l)| brdf.eval_f32(a, b, l) as f64);
            let (d32, w32) = (period as f32, w as f32);
            let tn32 = time_ns(&s32, budget, |(a, b, l)| {
                naive_f32(d32, w32, n, a, b, l) as f64
            });
            let tn64 = time_ns(&s64, budget, |(a, b, l)| naive_f64(period, w, n, a, b, l));
            // Errors against eval in f64 at the same (f32) inputs; NaN counts as an error of 1.
            let (mut e32, mut en32, mut en64, mut einput) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
            for (&(a, b, l), &(a64, b64, l64)) in s32.iter().zip(&s64) {
                let want = brdf.eval(a.as_dvec3(), b.as_dvec3(), l as f64);
                let err = |v: f64| if v.is_finite() { (v - want).abs() } else { 1.0 };
                e32 = e32.max(err(brdf.eval_f32(a, b, l) as f64));
                en32 = en32.max(err(naive_f32(d32, w32, n, a, b, l) as f64));
                let want64 = brdf.eval(a64, b64, l64);
                let v = naive_f64(period, w, n, a64, b64, l64);
                en64 = en64.max(if v.is_finite() {
                    (v - want64).abs()
                } else {
                    1.0
                });
                einput = einput.max((want - want64).abs());
            }
            println!(
                "{n:>7} {period:>7} | {t64:>8.1} {t32:>8.1} {tn32:>9.1} {tn64:>9.1} | {e32:>9.1e} \
                 {en32:>9.1e} {en64:>9.1e} {einput:>9.1e}"
            );
        }
    }
    println!(
        "(err: max |value − eval in f64 at the same f32 inputs| over 1024 samples, half near a \
         peak; NaN counts as 1; f32 input: eval at the f32-rounded inputs against the f64 inputs)"
    );
    println!();
}

/// The naive formula's worst errors at the inputs of DESIGN.md's stiff cases, against the stable
/// kernel in f64 at the very same argument (within 1e-12 of 100-digit values).
pub(super) fn print_stiff() {
    println!("## Stiff cases: the naive N-slit formula against the stable kernel");
    // f32, N = 5000, orders 1-8 and 40, steps of 1e-6 cycles around each order.
    let (mut worst, mut at, mut max_value) = (0.0f64, 0.0f64, 0.0f32);
    for m in (1..=8).chain([40]) {
        for k in -2000..=2000 {
            let x = m as f32 + k as f32 * 1e-6;
            let a = std::f32::consts::PI * x;
            let v = naive::n_slit(a, 5000);
            let exact = n_slit(a as f64, 5000);
            if v.is_finite() {
                max_value = max_value.max(v);
                if (v as f64 - exact).abs() > worst {
                    worst = (v as f64 - exact).abs();
                    at = x as f64;
                }
            }
        }
    }
    println!(
        "f32, N = 5000, orders 1-8 and 40: naive reaches {max_value:.3} (worst error {worst:.3} at \
         x = {at:.6}); stable stays in [0, 1]"
    );
    // f64, N = 10⁷: orders up to 10⁴, offsets of a small fraction of a lobe.
    let n = 10_000_000u32;
    let (mut worst, mut at) = (0.0f64, 0.0f64);
    for m in 1..=10_000 {
        for t in [1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 1e-2] {
            for sign in [-1.0, 1.0] {
                let x = m as f64 + sign * t / n as f64;
                let a = std::f64::consts::PI * x;
                let v = naive::n_slit(a, n);
                let exact = n_slit(a, n);
                let e = if v.is_finite() {
                    (v - exact).abs()
                } else {
                    1.0
                };
                if e > worst {
                    worst = e;
                    at = x;
                }
            }
        }
    }
    println!(
        "f64, N = 10^7, orders 1-10^4: naive worst error {worst:.3} at x = {at:.9} (order {:.0})",
        at.round()
    );
    println!();
}
