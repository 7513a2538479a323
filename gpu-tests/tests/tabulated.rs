//! Tabulated efficiencies in WGSL (`TABULATED_WGSL`, the tables packed by
//! `GpuEfficiencyTables`) on a device against the CPU, for every preset's classical table and
//! its conical one (`Preset::conical_table`, a reduced table: what `GratingBsdf::preset`
//! reads), and a version-2 tensor grid (the CD's conical reading on one): the interpolation `diffraction_eta` against `EfficiencyTable::efficiency` and
//! `diffraction_eta_conical` against `efficiency_conical` at 10⁵ queries per table (every
//! stored order, incidences and wavelengths beyond the grid included), and the tabulated BSDF's
//! f, pdf and sampler against `GratingBsdf::eval`, `pdf` and `sample` (same random numbers in,
//! same order, direction within its bound, the sample weight), with bounds derived from the
//! WGSL accuracy rules (`common/eta.rs`; docs/gpu.md, "Tabulated efficiencies"); the mean
//! weight of 2¹⁸ device samples of the CD, read classically and conically, is the CPU's albedo.
//! In CI (`CI` set) a missing adapter fails.

mod common;
#[path = "../../tests/support/tensor_cd.rs"]
mod tensor_cd;

use std::sync::OnceLock;

use common::gpu_cases::Mix;
use common::gpu_tolerance::*;
use common::*;
use diffraction::glam::DVec2;
use diffraction::gpu::{
    bsdf_bindings, efficiency_table_bindings, GpuBsdf, GpuEfficiencyTables, BSDF_WGSL, KERNEL_WGSL,
    TABULATED_WGSL, TYPES_WGSL,
};
use diffraction::grating_bsdf::OrderEfficiency;
use diffraction::relief::{EfficiencyTable, Preset};
use diffraction::{Bsdf, DiffractionBrdf, GratingBsdf, GrooveSpread};

const ETA_MAIN: &str = "
struct Query { m: i32, alpha: f32, beta: f32, lambda_nm: f32, table: u32, conical: u32, pad: vec2<u32> }
@group(0) @binding(0) var<storage, read> queries: array<Query>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(256)
fn eta_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i < arrayLength(&queries) {
        let q = queries[i];
        if q.conical != 0u {
            out[i] = diffraction_eta_conical(q.table, q.m, q.alpha, q.beta, q.lambda_nm);
        } else {
            out[i] = diffraction_eta(q.table, q.m, q.alpha, q.lambda_nm);
        }
    }
}
";

/// One packed table: its name, whether it is read conically (a preset's conical table,
/// `Preset::conical_table`, what `GratingBsdf::preset` reads, or the CD's version-2 tensor
/// grid), the table and its word offset.
struct Packed {
    name: String,
    conical: bool,
    table: &'static EfficiencyTable,
    offset: u32,
}

/// The CD's version-2 tensor grid (`tensor_cd`), built once.
fn tensor() -> &'static EfficiencyTable {
    static T: OnceLock<EfficiencyTable> = OnceLock::new();
    T.get_or_init(tensor_cd::tensor_cd)
}

/// Every preset's classical table ("Cd", …), every preset's conical one ("Cd conical", …) and
/// the CD's version-2 tensor grid ("Cd tensor"), in one buffer.
fn tables() -> (GpuEfficiencyTables, Vec<Packed>) {
    let mut t = GpuEfficiencyTables::default();
    let mut at = Vec::new();
    let mut add = |name: String, conical: bool, table: &'static EfficiencyTable| {
        let offset = t.push(table).expect("the table packs");
        at.push(Packed {
            name,
            conical,
            table,
            offset,
        });
    };
    for &p in &Preset::ALL {
        add(format!("{p:?}"), false, p.table());
    }
    for &p in &Preset::ALL {
        add(format!("{p:?} conical"), true, p.conical_table());
    }
    add("Cd tensor".into(), true, tensor());
    (t, at)
}

fn packed<'a>(at: &'a [Packed], name: &str) -> &'a Packed {
    at.iter().find(|x| x.name == name).expect("packed")
}

/// `diffraction_eta` at (m, s, λ) against `EfficiencyTable::efficiency` for the classical
/// tables (s on [−1, 1], λ on 340-850 nm: beyond the grid included), and
/// `diffraction_eta_conical` at (m, α, β, λ) against `efficiency_conical` for the conical ones
/// (α = −w.x, β = −w.y of a direction uniform on the hemisphere with w.z ≥ 0.05), each within
/// its bound (`common::eta::eta_bound`), except where f32 may take the neighbouring cell of a
/// reduced table (a position within its rounding of a node line: at most 1 in 2000 queries).
/// `diffraction_eta` (`conical` false) or `diffraction_eta_conical` of the packed table at
/// word `offset` of `tables` at each (m, α, β, λ) of `queries` on the device, and the seconds
/// of the dispatch.
fn device_etas(
    gpu: &Gpu,
    tables: &GpuEfficiencyTables,
    offset: u32,
    conical: bool,
    queries: &[(i32, f32, f32, f32)],
) -> (Vec<f32>, f64) {
    let source = [
        TYPES_WGSL,
        KERNEL_WGSL,
        &bsdf_bindings(0, 3),
        BSDF_WGSL,
        &efficiency_table_bindings(0, 1),
        TABULATED_WGSL,
        ETA_MAIN,
    ]
    .join("\n");
    let mut bytes = Vec::with_capacity(32 * queries.len());
    for &(m, alpha, beta, l) in queries {
        bytes.extend_from_slice(&m.to_le_bytes());
        for v in [alpha, beta, l] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        for v in [offset, u32::from(conical), 0, 0] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
    }
    let (out, secs) = gpu.run(
        &source,
        "eta_main",
        &[&bytes, &tables.to_bytes()],
        4 * queries.len(),
        queries.len(),
    );
    (f32s(&out), secs)
}

#[test]
fn eta_matches_the_cpu_table() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
    let per = 100_000;
    let mut rng = Mix(31);
    for packed in &at {
        let (p, offset, conical) = (&packed.name, packed.offset, packed.conical);
        let t = packed.table;
        let (first, count) = (*t.orders().start(), t.order_count() as i32);
        let queries: Vec<(i32, f32, f32, f32)> = (0..per)
            .map(|_| {
                let m = first + ((rng.next() * count as f64) as i32).min(count - 1);
                let (alpha, beta) = if conical {
                    let w = hemisphere_f32(&mut rng);
                    (-w[0], -w[1])
                } else {
                    ((2.1 * rng.next() - 1.05).clamp(-1.0, 1.0) as f32, 0.0)
                };
                let l = (340.0 + 510.0 * rng.next()) as f32;
                (m, alpha, beta, l)
            })
            .collect();
        let (out, secs) = device_etas(&gpu, &tables, offset, conical, &queries);
        let words = &tables.words()[offset as usize..];
        let (mut worst, mut worst_rel, mut nonzero, mut skipped) = (0.0f64, 0.0f64, 0usize, 0);
        for (&(m, alpha, beta, l), &g) in queries.iter().zip(&out) {
            let (a, b, l) = (alpha as f64, beta as f64, l as f64);
            let cpu = if conical {
                t.efficiency_conical(m, a, b, l).unpolarised()
            } else {
                t.efficiency(m, a, l).unpolarised()
            };
            let Some(tol) = eta::eta_bound(words, m, a, b, l) else {
                skipped += 1;
                continue;
            };
            let e = (g as f64 - cpu).abs();
            assert!(
                e <= tol,
                "{p} m={m} α={alpha} β={beta} λ={l}: {g} vs {cpu} (tol {tol:e})"
            );
            if cpu > 0.0 {
                nonzero += 1;
            }
            worst = worst.max(e);
            if tol > 0.0 {
                worst_rel = worst_rel.max(e / tol);
            }
        }
        assert!(nonzero > per / 4, "{nonzero}");
        assert!(skipped * 2000 <= per, "{skipped} near node lines");
        assert!(worst <= ETA_WORST_MEASURED, "{p}: worst |Δη| {worst:e}");
        println!(
            "eta {p}: {per} queries in {:.1} ms, {nonzero} non-zero, worst |Δη| = {worst:.2e} \
             ({worst_rel:.3} of its bound), {skipped} skipped near node lines",
            secs * 1e3
        );
    }
}

/// Hostile queries (non-finite, huge, tiny or negative α, β and λ, orders outside the stored
/// ones and at the ends of i32) of every packed table give a finite η in [0, 1] on the device,
/// as on the CPU (no hang: every loop of the WGSL is bounded by the table's counts).
#[test]
fn hostile_eta_queries_give_finite_efficiencies() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
    let xs = [
        f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        1e30,
        -1e30,
        1.0,
        -1.0,
        0.999_999_9,
        1e-30,
        0.0,
        -0.0,
        0.3,
    ];
    let ls = [
        f32::NAN,
        f32::INFINITY,
        -1.0,
        0.0,
        1e-30,
        1e30,
        359.0,
        550.0,
        2000.0,
    ];
    for packed in &at {
        let t = packed.table;
        let (first, last) = (*t.orders().start(), *t.orders().end());
        let orders = [i32::MIN, first - 1, first, 0, last, last + 1, i32::MAX];
        let mut queries = Vec::new();
        for &m in &orders {
            for &a in &xs {
                for &b in &xs {
                    for &l in &ls {
                        queries.push((m, a, b, l));
                    }
                }
            }
        }
        let (out, _) = device_etas(&gpu, &tables, packed.offset, packed.conical, &queries);
        for (q, &g) in queries.iter().zip(&out) {
            assert!(
                g.is_finite() && (0.0..=1.0 + 1e-5).contains(&g),
                "{} {q:?}: {g}",
                packed.name
            );
            let (m, a, b, l) = (q.0, q.1 as f64, q.2 as f64, q.3 as f64);
            let cpu = if packed.conical {
                t.efficiency_conical(m, a, b, l)
            } else {
                t.efficiency(m, a, l)
            };
            assert!(cpu.te.is_finite() && cpu.tm.is_finite(), "{q:?}: {cpu:?}");
        }
        println!(
            "{}: {} hostile queries, every η finite in [0, 1]",
            packed.name,
            queries.len()
        );
    }
}

const TAB_MAIN: &str = "
struct Case { wo: vec4<f32>, xi: vec4<f32> }
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read> model: array<DiffractionBsdf>;
@group(0) @binding(2) var<storage, read> diffraction_efficiency_tables: array<f32>;
@group(0) @binding(3) var<storage, read_write> out: array<vec4<f32>>;
@compute @workgroup_size(256)
fn tab_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i < arrayLength(&cases) {
        let c = cases[i];
        let b = model[0];
        let s = diffraction_bsdf_tabulated_sample(b, c.wo.xyz, c.wo.w, c.xi.xyz);
        out[3u * i] = vec4<f32>(s.wi, s.f);
        out[3u * i + 1u] = vec4<f32>(s.pdf, f32(s.order), f32(s.valid), 0.0);
        out[3u * i + 2u] = vec4<f32>(diffraction_bsdf_tabulated_f(b, c.wo.xyz, s.wi, c.wo.w),
                                     diffraction_bsdf_tabulated_pdf(b, c.wo.xyz, s.wi, c.wo.w),
                                     0.0, 0.0);
    }
}
";

struct DeviceSample {
    wi: [f32; 3],
    f: f32,
    pdf: f32,
    order: i64,
    valid: bool,
    f_at: f32,
    pdf_at: f32,
}

impl std::fmt::Debug for DeviceSample {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "wi={:?} f={} pdf={} m={} valid={} (f, pdf at wi: {}, {})",
            self.wi, self.f, self.pdf, self.order, self.valid, self.f_at, self.pdf_at
        )
    }
}

/// The tabulated sampler on `cases` (wo, λ, ξ) for `b`, its table at `offset` of `tables`.
fn device_samples(
    gpu: &Gpu,
    b: &GratingBsdf,
    tables: &GpuEfficiencyTables,
    offset: u32,
    cases: &[([f32; 3], f32, [f32; 3])],
) -> (Vec<DeviceSample>, f64) {
    let source = [
        TYPES_WGSL,
        KERNEL_WGSL,
        &bsdf_bindings(0, 5),
        BSDF_WGSL,
        TABULATED_WGSL,
        TAB_MAIN,
    ]
    .join("\n");
    let mut input = Vec::with_capacity(8 * cases.len());
    for (wo, l, xi) in cases {
        input.extend_from_slice(&[wo[0], wo[1], wo[2], *l, xi[0], xi[1], xi[2], 0.0]);
    }
    let g = GpuBsdf::new(b, 0).with_table(offset);
    let (out, secs) = gpu.run(
        &source,
        "tab_main",
        &[&bytes_of(&input), &g.to_bytes(), &tables.to_bytes()],
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

/// The preset with `n` grooves on its classical table (`Preset::table`; `GratingBsdf::preset`
/// reads its conical table).
fn classical(p: Preset, n: u32) -> GratingBsdf {
    GratingBsdf::preset(p, n)
        .unwrap()
        .with_efficiency(OrderEfficiency::from_static(p.table()).unwrap())
        .unwrap()
}

/// The models of the per-sample test: (the packed table's name, model), the classical
/// readings, the presets' default conical ones and the CD on its version-2 tensor grid.
fn preset_models() -> Vec<(&'static str, GratingBsdf)> {
    let conical = |p: Preset, n: u32| GratingBsdf::preset(p, n).unwrap();
    let gaussian = GrooveSpread::gaussian(0.02).unwrap();
    let tensor_cd = conical(Preset::Cd, 34)
        .with_efficiency(OrderEfficiency::from_static(tensor()).unwrap())
        .unwrap()
        .with_groove(gaussian);
    vec![
        ("Cd", classical(Preset::Cd, 34)),
        ("Cd", classical(Preset::Cd, 34).with_groove(gaussian)),
        ("Dvd", classical(Preset::Dvd, 300)),
        ("Blazed600", classical(Preset::Blazed600, 100)),
        ("Foil", classical(Preset::Foil, 10)),
        ("Cd conical", conical(Preset::Cd, 34).with_groove(gaussian)),
        ("Dvd conical", conical(Preset::Dvd, 300)),
        ("Blazed600 conical", conical(Preset::Blazed600, 100)),
        ("Foil conical", conical(Preset::Foil, 10)),
        ("Cd tensor", tensor_cd),
    ]
}

#[test]
fn tabulated_bsdf_matches_the_cpu_per_sample() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
    let per = 20_000;
    let mut rng = Mix(41);
    for (p, b) in preset_models() {
        let (offset, t) = (packed(&at, p).offset, packed(&at, p).table);
        let words = &tables.words()[offset as usize..];
        let g = GpuBsdf::new(&b, 0).with_table(offset);
        let lobe = Lobe::of(&g, true);
        let cases: Vec<([f32; 3], f32, [f32; 3])> = (0..per)
            .map(|_| {
                let wo = hemisphere_f32(&mut rng);
                let l = (360.0 + 470.0 * rng.next()) as f32;
                let xi = [unit_f32(&mut rng), unit_f32(&mut rng), unit_f32(&mut rng)];
                (wo, l, xi)
            })
            .collect();
        let (out, secs) = device_samples(&gpu, &b, &tables, offset, &cases);
        let (mut skipped, mut compared) = (0usize, 0usize);
        let (mut worst_dir, mut worst_f, mut worst_p, mut worst_w) =
            (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        for ((wo, l, xi), s) in cases.iter().zip(&out) {
            let (wo64, l64) = (widen(*wo), *l as f64);
            let xi64 = [xi[0] as f64, xi[1] as f64, xi[2] as f64];
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
            let Some(w) = eta::weights(words, wo64, l64) else {
                skipped += 1;
                continue;
            };
            let total: f64 = w.iter().map(|x| x.1).sum();
            let dtotal: f64 = w.iter().map(|x| x.2).sum();
            let ws: Vec<f64> = w.iter().map(|x| x.1).collect();
            let ambiguous = near_partial_sum(
                &ws,
                xi64[0] * total,
                dtotal + (ws.len() as f64 + 4.0) * U * total,
            );
            let c = match (&cpu, s.valid) {
                (None, false) => continue,
                (Some(c), true) if c.order.map(i64::from) == Some(s.order) => c,
                (Some(c), _) => {
                    let db = direction_bound(&g, wo64, l64, c.order.map_or(0, i64::from), xi64);
                    assert!(
                        ambiguous
                            || c.wi.z <= 2.0 * db[2].max(4.0 * U.sqrt())
                            || lobe.at_order_boundary(wo64, c.wi, l64),
                        "wo={wo:?} λ={l} ξ={xi:?}: CPU {c:?}, device {s:?}"
                    );
                    skipped += 1;
                    continue;
                }
                (None, true) => {
                    assert!(
                        ambiguous
                            || (s.wi[2] as f64) <= 1e-3
                            || lobe.at_order_boundary(wo64, widen(s.wi), l64),
                        "wo={wo:?} λ={l} ξ={xi:?}: no CPU sample, device {s:?}"
                    );
                    skipped += 1;
                    continue;
                }
            };
            let db = direction_bound(&g, wo64, l64, s.order, xi64);
            let wi = widen(s.wi);
            for k in 0..3 {
                let e = (wi[k] - c.wi[k]).abs();
                assert!(
                    e <= db[k],
                    "wi[{k}] wo={wo:?} λ={l} ξ={xi:?}: {wi} vs {}",
                    c.wi
                );
                worst_dir = worst_dir.max(e / db[k]);
            }
            if lobe.at_order_boundary(wo64, wi, l64) {
                skipped += 1;
                continue;
            }
            compared += 1;
            // f = η̃·L at the device's direction: the efficiencies' bounds at wo and wi times the
            // lobe's scale, plus η̃ times the lobe's bound.
            let m = s.order as i32;
            let (scale, tol_l) = lobe.f_bound(wo64, wi, l64);
            let e_wo = t.efficiency_conical(m, -wo64.x, -wo64.y, l64).unpolarised();
            let e_wi = t.efficiency_conical(m, -wi.x, -wi.y, l64).unpolarised();
            let bounds = (
                eta::eta_bound(words, m, -wo64.x, -wo64.y, l64),
                eta::eta_bound(words, m, -wi.x, -wi.y, l64),
            );
            let (Some(d_wo), Some(d_wi)) = bounds else {
                skipped += 1;
                continue;
            };
            let deta = d_wo.max(d_wi);
            let tol_f = deta * scale + e_wo.min(e_wi) * tol_l;
            let f_cpu = b.eval(wo64, wi, l64);
            let e_f = (s.f as f64 - f_cpu).abs();
            assert!(
                e_f <= tol_f,
                "f wo={wo:?} λ={l}: {s:?} vs {f_cpu} (tol {tol_f:e})"
            );
            worst_f = worst_f.max(e_f / scale);
            // pdf = P(m)·R: the proposal's bounds, and R's roundings.
            let wm = w
                .iter()
                .find(|x| x.0 == s.order)
                .map_or((0.0, 0.0), |x| (x.1, x.2));
            let p_cpu = b.pdf(wo64, wi, l64);
            let rel = if wm.0 > 0.0 { wm.1 / wm.0 } else { 0.0 };
            let tol_p = p_cpu * (rel + dtotal / total + lobe.pdf_relative_bound(wo64, wi, l64));
            let e_p = (s.pdf as f64 - p_cpu).abs();
            assert!(
                e_p <= tol_p,
                "pdf wo={wo:?} λ={l}: {s:?} vs {p_cpu} (tol {tol_p:e})"
            );
            if p_cpu > 0.0 {
                worst_p = worst_p.max(e_p / p_cpu);
            }
            // The weight: the amplitude model's terms (sample.rs) and the efficiencies'.
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
            // w = η̃·X/P ≤ bound: P's relative bound, and η̃'s bound relative to η̃.
            let eta_tilde = e_wo.min(e_wi);
            let eta_terms = if wm.0 > 0.0 && eta_tilde > 0.0 {
                dtotal / total + wm.1 / wm.0 + deta / eta_tilde
            } else {
                0.0
            };
            let tol_w = bound
                * (2.0 * std::f64::consts::PI * (lobe.n + 1.0) * d_phase
                    + groove_rate * db[1]
                    + tol_l / scale
                    + lobe.pdf_relative_bound(wo64, wi, l64)
                    + eta_terms);
            let e_w = (w_gpu - w_cpu).abs();
            assert!(
                e_w <= tol_w,
                "weight wo={wo:?} λ={l} ξ={xi:?}: {w_gpu} vs {w_cpu} (tol {tol_w:e})"
            );
            worst_w = worst_w.max(e_w / bound);
        }
        assert!(
            skipped * 200 <= per,
            "{skipped} of {per} at rounding boundaries"
        );
        println!(
            "tabulated {p} N={} groove={}: {per} samples in {:.1} ms, {compared} compared, worst \
             |Δwi| {worst_dir:.3} of its bound, |Δf| = {worst_f:.2e} of the lobe's scale, \
             |Δpdf|/pdf = {worst_p:.2e}, |Δweight| = {worst_w:.2e} of the weight bound, \
             {skipped} skipped at rounding boundaries",
            g.slits,
            g.groove,
            secs * 1e3
        );
    }
}

#[test]
fn tabulated_sample_weights_average_to_the_albedo() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
    let count = 1usize << 18;
    let mut rng = Mix(43);
    for conical in [false, true] {
        let b = if conical {
            GratingBsdf::preset(Preset::Cd, 34).unwrap()
        } else {
            classical(Preset::Cd, 34)
        };
        let offset = packed(&at, if conical { "Cd conical" } else { "Cd" }).offset;
        for (wo, l) in [
            ([0.0f32, 0.0], 550.0f32),
            ([0.6, 0.1], 420.0),
            ([-0.3, -0.5], 700.0),
        ] {
            let wo = [wo[0], wo[1], (1.0 - wo[0] * wo[0] - wo[1] * wo[1]).sqrt()];
            let cases: Vec<([f32; 3], f32, [f32; 3])> = (0..count)
                .map(|_| {
                    (
                        wo,
                        l,
                        [unit_f32(&mut rng), unit_f32(&mut rng), unit_f32(&mut rng)],
                    )
                })
                .collect();
            let (out, secs) = device_samples(&gpu, &b, &tables, offset, &cases);
            let (mean, se) = mean_weight(out.iter().map(|s| (s.valid, s.f, s.wi[2], s.pdf)));
            let albedo = b.albedo(widen(wo), l as f64).expect("albedo");
            let tol = 5.0 * se + SAMPLE_WEIGHT_F32 * b.sample_weight_bound(widen(wo), l as f64);
            println!(
            "albedo CD{} N=34 wo={wo:?} λ={l}: device mean weight {mean:.6} ± {se:.1e} ({count} \
             samples, {:.0} ms), CPU albedo {albedo:.6}: {:.2} standard errors",
            if conical { " conical" } else { "" },
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
