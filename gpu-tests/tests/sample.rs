//! `diffraction_bsdf_sample` (the amplitude model's sampler in WGSL) on a device against the
//! CPU's `GratingBsdf::sample`, per sample: the same random numbers in (f32, read by both),
//! the same order, and the same direction within the bound derived from the WGSL accuracy rules
//! (docs/gpu.md, "The sampler"); f and pdf of the sample equal the shader's own
//! `diffraction_bsdf_f`/`_pdf` at its direction and the CPU's `eval`/`pdf` there within their
//! bounds; the sample weight f·cos θi/pdf agrees with the CPU's. Statistically, the mean
//! weight of 2¹⁸ device samples is the CPU's albedo (the identity E[f·cos/pdf] = ∫f·cos dω
//! holds only if pdf is the density of the samples). In CI (`CI` set) a missing adapter fails.

mod common;

use common::gpu_cases::Mix;
use common::gpu_tolerance::*;
use common::*;
use diffraction::glam::{DVec2, DVec3};
use diffraction::gpu::{order_rows_bytes, GpuBsdf, BSDF_WGSL, KERNEL_WGSL, TYPES_WGSL};
use diffraction::kernel::single_slit_cycles;
use diffraction::{Bsdf, DiffractionBrdf, Grating, GratingBsdf, GrooveSpread};

const SAMPLE_MAIN: &str = "
struct Case { wo: vec4<f32>, xi: vec4<f32> }
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read> model: array<DiffractionBsdf>;
@group(0) @binding(2) var<storage, read> diffraction_bsdf_orders: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out: array<vec4<f32>>;
@compute @workgroup_size(256)
fn sample_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i < arrayLength(&cases) {
        let c = cases[i];
        let b = model[0];
        let s = diffraction_bsdf_sample(b, c.wo.xyz, c.wo.w, c.xi.xyz);
        out[3u * i] = vec4<f32>(s.wi, s.f);
        out[3u * i + 1u] = vec4<f32>(s.pdf, f32(s.order), f32(s.valid), 0.0);
        out[3u * i + 2u] = vec4<f32>(diffraction_bsdf_f(b, c.wo.xyz, s.wi, c.wo.w),
                                     diffraction_bsdf_pdf(b, c.wo.xyz, s.wi, c.wo.w), 0.0, 0.0);
    }
}
";

/// One device sample: wi, f, pdf, order, valid, and the shader's f and pdf at wi.
#[derive(Debug, Clone, Copy)]
struct DeviceSample {
    wi: [f32; 3],
    f: f32,
    pdf: f32,
    order: i64,
    valid: bool,
    f_at: f32,
    pdf_at: f32,
}

fn models() -> Vec<GratingBsdf> {
    vec![
        GratingBsdf::new(Grating::new(1600.0, 800.0, 1).unwrap()),
        GratingBsdf::new(Grating::new(1600.0, 800.0, 10).unwrap()),
        GratingBsdf::new(Grating::new(1600.0, 800.0, 1000).unwrap()),
        GratingBsdf::new(Grating::new(740.0, 370.0, 1000).unwrap())
            .with_groove(GrooveSpread::gaussian(0.05).unwrap()),
        GratingBsdf::new(Grating::new(10_000.0, 3000.0, 100).unwrap()),
        // More than 256 candidates: the uniform order choice.
        GratingBsdf::new(Grating::new(100_000.0, 30_000.0, 10).unwrap()),
    ]
}

/// Runs the sampler on `cases` (wo, λ, ξ) for `b`.
fn device_samples(
    gpu: &Gpu,
    b: &GratingBsdf,
    cases: &[([f32; 3], f32, [f32; 3])],
) -> (Vec<DeviceSample>, f64) {
    let source = [TYPES_WGSL, KERNEL_WGSL, BSDF_WGSL, SAMPLE_MAIN].join("\n");
    let mut input = Vec::with_capacity(8 * cases.len());
    for (wo, l, xi) in cases {
        input.extend_from_slice(&[wo[0], wo[1], wo[2], *l, xi[0], xi[1], xi[2], 0.0]);
    }
    let g = GpuBsdf::new(b, 0);
    let rows = order_rows_bytes(&GpuBsdf::order_rows(b));
    let (out, secs) = gpu.run(
        &source,
        "sample_main",
        &[&bytes_of(&input), &g.to_bytes(), &rows],
        48 * cases.len(),
        cases.len(),
    );
    let o = f32s(&out);
    let samples = (0..cases.len())
        .map(|i| {
            let r = &o[12 * i..12 * i + 12];
            DeviceSample {
                wi: [r[0], r[1], r[2]],
                f: r[3],
                pdf: r[4],
                order: r[5] as i64,
                valid: r[6] != 0.0,
                f_at: r[8],
                pdf_at: r[9],
            }
        })
        .collect();
    (samples, secs)
}

/// The amplitude model's order weights w_m = S(ρ·m) + ⅛·U_m (orders.rs) in f64.
fn weight(rho: f64, m: i64) -> f64 {
    let a = ((m.unsigned_abs() as f64) - 0.5).max(0.0) * rho * std::f64::consts::PI;
    single_slit_cycles(rho * m as f64) + 0.125 * 3.0 / (3.0 + a * a)
}

/// Whether the order choice from `uc` is decided within the rounding of the f32 running sum
/// (the target uc·Σw within (2K + 16)·u·Σw of a partial sum; the uniform choice within 4K·u of
/// an integer).
fn choice_ambiguous(b: &GratingBsdf, wo: DVec3, l: f64, uc: f64) -> bool {
    let g = b.grating();
    let (d, rho) = (g.period_nm(), g.open_fraction());
    let step = l / d;
    let lo = ((wo.x - 1.0) / step - 0.5).floor() as i64 + 1;
    let hi = ((wo.x + 1.0) / step + 0.5).ceil() as i64 - 1;
    let count = (hi - lo + 1) as f64;
    if hi - lo + 1 > 256 {
        let t = uc * count;
        return (t - t.round()).abs() <= 4.0 * count * U * (1.0 + t);
    }
    let w: Vec<f64> = (lo..=hi).map(|m| weight(rho, m)).collect();
    let total: f64 = w.iter().sum();
    near_partial_sum(&w, uc * total, (2.0 * count + 16.0) * U * total)
}

#[test]
fn sample_matches_the_cpu_per_sample() {
    let Some(gpu) = gpu() else { return };
    let per = 40_000;
    let mut rng = Mix(17);
    for b in &models() {
        let g = GpuBsdf::new(b, 0);
        let lobe = Lobe::of(&g, false);
        let cases: Vec<([f32; 3], f32, [f32; 3])> = (0..per)
            .map(|_| {
                let wo = hemisphere_f32(&mut rng);
                let l = (360.0 + 470.0 * rng.next()) as f32;
                let xi = [unit_f32(&mut rng), unit_f32(&mut rng), unit_f32(&mut rng)];
                (wo, l, xi)
            })
            .collect();
        let (out, secs) = device_samples(&gpu, b, &cases);
        let mut skipped = 0usize;
        let mut valid = 0usize;
        let mut worst_dir = 0.0f64; // of the bound
        let mut worst_dir_abs = 0.0f64;
        let (mut worst_f, mut worst_p, mut worst_w) = (0.0f64, 0.0f64, 0.0f64);
        for ((wo, l, xi), s) in cases.iter().zip(&out) {
            let (wo64, l64) = (widen(*wo), *l as f64);
            let xi64 = [xi[0] as f64, xi[1] as f64, xi[2] as f64];
            // The shader's sample carries its own f and pdf at its direction, bit for bit.
            assert_eq!(
                (s.f.to_bits(), s.pdf.to_bits()),
                if s.valid {
                    (s.f_at.to_bits(), s.pdf_at.to_bits())
                } else {
                    (0, 0)
                },
                "{s:?}"
            );
            let cpu = b.sample(wo64, l64, xi64[0], DVec2::new(xi64[1], xi64[2]));
            let ambiguous_order = choice_ambiguous(b, wo64, l64, xi64[0]);
            match (&cpu, s.valid) {
                (None, false) => continue,
                (Some(c), true) if c.order.map(i64::from) == Some(s.order) => {}
                (Some(c), _) => {
                    // A different order or no device sample: only where the choice, the
                    // candidates or the horizon are decided within rounding.
                    let db = direction_bound(&g, wo64, l64, c.order.map_or(0, i64::from), xi64);
                    let near_horizon = c.wi.z <= 2.0 * db[2].max(4.0 * U.sqrt());
                    assert!(
                        ambiguous_order || near_horizon || lobe.at_order_boundary(wo64, c.wi, l64),
                        "wo={wo:?} λ={l} ξ={xi:?}: CPU {c:?}, device {s:?}"
                    );
                    skipped += 1;
                    continue;
                }
                (None, true) => {
                    let near_horizon = (s.wi[2] as f64) <= 1e-3;
                    assert!(
                        ambiguous_order
                            || near_horizon
                            || lobe.at_order_boundary(wo64, widen(s.wi), l64),
                        "wo={wo:?} λ={l} ξ={xi:?}: no CPU sample, device {s:?}"
                    );
                    skipped += 1;
                    continue;
                }
            }
            let c = cpu.expect("matched above");
            valid += 1;
            // The direction.
            let db = direction_bound(&g, wo64, l64, s.order, xi64);
            let wi = widen(s.wi);
            for k in 0..3 {
                let e = (wi[k] - c.wi[k]).abs();
                assert!(
                    e <= db[k],
                    "wi[{k}] wo={wo:?} λ={l} ξ={xi:?}: {wi} vs {} (bound {:e})",
                    c.wi,
                    db[k]
                );
                worst_dir = worst_dir.max(e / db[k]);
                worst_dir_abs = worst_dir_abs.max(e);
            }
            if lobe.at_order_boundary(wo64, wi, l64) {
                skipped += 1;
                continue;
            }
            // f and pdf against the CPU's eval and pdf at the device's direction.
            let (f_cpu, p_cpu) = (b.eval(wo64, wi, l64), b.pdf(wo64, wi, l64));
            let (scale, tol_f) = lobe.f_bound(wo64, wi, l64);
            let e_f = (s.f as f64 - f_cpu).abs();
            assert!(e_f <= tol_f, "f {s:?} vs {f_cpu} (tol {tol_f:e})");
            worst_f = worst_f.max(e_f / scale);
            let tol_p = p_cpu * lobe.pdf_relative_bound(wo64, wi, l64);
            let e_p = (s.pdf as f64 - p_cpu).abs();
            assert!(e_p <= tol_p, "pdf {s:?} vs {p_cpu} (tol {tol_p:e})");
            worst_p = worst_p.max(e_p / p_cpu);
            // The sample weight against the CPU sample's: the direction's error moves the
            // phase by (d/λ)·Δu and v by Δv; N·F_N/q and g/q_v change by at most their bound
            // times 2π(N + 1) per unit of phase and 2π·L/λ (or 2/σ) per unit of v.
            let w_gpu = s.f as f64 * wi.z / s.pdf as f64;
            let w_cpu = c.f * c.wi.z / c.pdf;
            let bound = b.sample_weight_bound(wo64, l64);
            let (_, dx) = lobe.phase(wo64, wi, l64);
            let d_phase = lobe.d / l64 * db[0] + dx;
            let groove_rate = if g.groove == 0 {
                2.0 * std::f64::consts::PI * g.groove_param as f64 / l64
            } else {
                2.0 / g.groove_param as f64
            };
            let tol_w = bound
                * (2.0 * std::f64::consts::PI * (lobe.n + 1.0) * d_phase
                    + groove_rate * db[1]
                    + tol_f / scale
                    + lobe.pdf_relative_bound(wo64, wi, l64));
            let e_w = (w_gpu - w_cpu).abs();
            assert!(
                e_w <= tol_w,
                "weight wo={wo:?} λ={l} ξ={xi:?}: {w_gpu} vs {w_cpu} (tol {tol_w:e})"
            );
            worst_w = worst_w.max(e_w / bound);
        }
        assert!(
            skipped * 200 <= per,
            "{skipped} of {per} samples at a rounding boundary"
        );
        println!(
            "sample d={} N={} groove={}: {per} samples in {:.1} ms, {valid} compared, worst \
             |Δwi| = {worst_dir_abs:.2e} ({worst_dir:.3} of its bound), |Δf| = {worst_f:.2e} of \
             the lobe's scale, |Δpdf|/pdf = {worst_p:.2e}, |Δweight| = {worst_w:.2e} of the \
             weight bound, {skipped} skipped at rounding boundaries",
            g.period_nm,
            g.slits,
            g.groove,
            secs * 1e3
        );
    }
}

#[test]
fn sample_weights_average_to_the_albedo() {
    let Some(gpu) = gpu() else { return };
    let count = 1usize << 18;
    let mut rng = Mix(23);
    let models = models();
    for b in &models[1..5] {
        for (wo, l) in [
            ([0.0f32, 0.0, 1.0], 550.0f32),
            ([0.6, 0.1, 0.0], 420.0),
            ([-0.3, -0.5, 0.0], 700.0),
        ] {
            let mut wo = wo;
            wo[2] = (1.0 - wo[0] * wo[0] - wo[1] * wo[1]).sqrt();
            let cases: Vec<([f32; 3], f32, [f32; 3])> = (0..count)
                .map(|_| {
                    let xi = [unit_f32(&mut rng), unit_f32(&mut rng), unit_f32(&mut rng)];
                    (wo, l, xi)
                })
                .collect();
            let (out, secs) = device_samples(&gpu, b, &cases);
            let (mean, se) = mean_weight(out.iter().map(|s| (s.valid, s.f, s.wi[2], s.pdf)));
            let albedo = b.albedo(widen(wo), l as f64).expect("albedo");
            // 5 standard errors, and a systematic f32 error (see SAMPLE_WEIGHT_F32).
            let bound = b.sample_weight_bound(widen(wo), l as f64);
            let tol = 5.0 * se + SAMPLE_WEIGHT_F32 * bound;
            let g = b.grating();
            println!(
                "albedo d={} N={:?} wo={wo:?} λ={l}: device mean weight {mean:.6} ± {se:.1e} \
                 ({count} samples, {:.0} ms), CPU albedo {albedo:.6}: {:.2} standard errors",
                g.period_nm(),
                g.slits(),
                secs * 1e3,
                (mean - albedo).abs() / se
            );
            assert!(
                (mean - albedo).abs() <= tol,
                "{mean} vs {albedo} (tol {tol:e})"
            );
        }
    }
}
