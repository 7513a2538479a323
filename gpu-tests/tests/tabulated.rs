//! Tabulated efficiencies in WGSL (`TABULATED_WGSL`, the tables packed by
//! `GpuEfficiencyTables`) on a device against the CPU, for every preset: the interpolation
//! `diffraction_eta` against `EfficiencyTable::efficiency` at 10⁵ queries per preset (every
//! stored order, incidences and wavelengths beyond the grid included), and the tabulated BSDF's
//! f, pdf and sampler against `GratingBsdf::eval`, `pdf` and `sample` (same random numbers in,
//! same order, direction within its bound, the sample weight), with bounds derived from the
//! WGSL accuracy rules (docs/gpu.md, "Tabulated efficiencies"); the mean weight of 2¹⁸ device
//! samples of the CD is the CPU's albedo. In CI (`CI` set) a missing adapter fails.

mod common;

use common::gpu_cases::Mix;
use common::gpu_tolerance::*;
use common::*;
use diffraction::glam::{DVec2, DVec3};
use diffraction::gpu::{
    bsdf_bindings, efficiency_table_bindings, GpuBsdf, GpuEfficiencyTables, BSDF_WGSL, KERNEL_WGSL,
    TABULATED_WGSL, TYPES_WGSL,
};
use diffraction::grating_bsdf::OrderEfficiency;
use diffraction::relief::{EfficiencyTable, Preset};
use diffraction::{Bsdf, DiffractionBrdf, GratingBsdf, GrooveSpread};

const ETA_MAIN: &str = "
struct Query { m: i32, s: f32, lambda_nm: f32, table: u32 }
@group(0) @binding(0) var<storage, read> queries: array<Query>;
@group(0) @binding(2) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(256)
fn eta_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if i < arrayLength(&queries) {
        let q = queries[i];
        out[i] = diffraction_eta(q.table, q.m, q.s, q.lambda_nm);
    }
}
";

/// The bound of |η_GPU − η_CPU| (unpolarised, normalised) for order m at (s, λ) of the table
/// packed at `words` (docs/gpu.md, "Tabulated efficiencies"): the cell's weights (the position
/// in the cell, 8u relative for t and u + 8u·t for 1 − t), the weighted mean of the corners' q
/// (≤ Q, the largest) and its roundings, cos θm/cos θi at the query (the conditioning of
/// √(1 − sin² θm) near the order's Rayleigh line), and the normalisation over every order.
pub fn eta_bound(words: &[f32], m: i32, s: f64, l: f64) -> f64 {
    let w = |i: usize| words[i] as f64;
    let (d, n_s, n_l) = (w(0), w(1) as usize, w(2) as usize);
    let (first, count, v) = (w(3) as i32, w(4) as usize, w(5) as usize);
    let sin: Vec<f64> = (0..n_s).map(|i| w(8 + i)).collect();
    let lam: Vec<f64> = (0..n_l).map(|j| w(8 + n_s + j)).collect();
    let s = s.clamp(sin[0], sin[n_s - 1]);
    let l = l.clamp(lam[0], lam[n_l - 1]);
    let cos_i = (1.0 - s * s).max(0.0).sqrt();
    if cos_i <= 0.0 {
        return 0.0;
    }
    let interval = |nodes: &[f64], x: f64| {
        let k = nodes.partition_point(|&n| n <= x);
        k.saturating_sub(1).min(nodes.len() - 2)
    };
    let (i, j) = (interval(&sin, s), interval(&lam, l));
    let tx = (s - sin[i]) / (sin[i + 1] - sin[i]);
    let ty = (l - lam[j]) / (lam[j + 1] - lam[j]);
    // The relative error of 1 − t (t itself: 8u).
    let e1 = |t: f64| {
        if t < 1.0 {
            (U + 8.0 * U * t) / (1.0 - t)
        } else {
            f64::INFINITY
        }
    };
    let wts = [
        ((1.0 - tx) * (1.0 - ty), e1(tx) + e1(ty) + U),
        (tx * (1.0 - ty), 8.0 * U + e1(ty) + U),
        ((1.0 - tx) * ty, e1(tx) + 8.0 * U + U),
        (tx * ty, 16.0 * U + U),
    ];
    let corner = [0, 1, n_s, n_s + 1];
    let ci_rel = (2.0 * U * s * s + U) / (2.0 * cos_i * cos_i) + U;
    // (raw η, its bound) of order mm, the larger polarisation's.
    let raw = |mm: i32| -> (f64, f64) {
        let k = (mm - first) as usize;
        let base = v + 2 * ((k * n_l + j) * n_s + i);
        let (mut num, mut den, mut q_max, mut werr) = (0.0, 0.0, 0.0f64, 0.0);
        for c in 0..4 {
            let (wc, ec) = wts[c];
            let at = base + 2 * corner[c];
            let q = w(at).max(w(at + 1));
            if wc > 0.0 && w(at) >= 0.0 {
                num += wc * q;
                den += wc;
                q_max = q_max.max(q);
                werr += wc * ec.min(1.0);
            }
        }
        let sm = s + mm as f64 * l / d;
        let dsm = (mm as f64 * l / d).abs() * 7.0 * U + U * sm.abs() + U;
        let a = 1.0 - sm * sm;
        let da = 2.0 * sm.abs() * dsm + dsm * dsm + 2.0 * U;
        if den <= 0.0 {
            return (0.0, 0.0);
        }
        let r = num / den;
        let dr = q_max * (2.0 * werr / den + 15.0 * U);
        let (root, droot) = if a > 0.0 {
            let root = a.sqrt();
            (root, (da / root).min(da.sqrt()) + U * root)
        } else {
            (0.0, (a + da).max(0.0).sqrt())
        };
        let k = root / cos_i;
        (
            r * k,
            (dr + r) * droot / cos_i + dr * k + r * k * (ci_rel + 6.0 * U),
        )
    };
    let (eta, deta) = raw(m);
    let (mut sum, mut dsum) = (0.0, 0.0);
    for k in 0..count {
        let (a, b) = raw(first + k as i32);
        sum += a;
        dsum += b;
    }
    let norm = if sum + dsum >= 1.0 {
        eta * (dsum + count as f64 * U * sum) / sum.max(1.0)
    } else {
        0.0
    };
    deta + norm + 2.0 * U * eta
}

fn tables() -> (GpuEfficiencyTables, Vec<(Preset, u32)>) {
    let mut t = GpuEfficiencyTables::default();
    let at = Preset::ALL
        .iter()
        .map(|&p| (p, t.push(p.table())))
        .collect();
    (t, at)
}

#[test]
fn eta_matches_the_cpu_table() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
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
    let per = 100_000;
    let mut rng = Mix(31);
    for &(p, offset) in &at {
        let t: &EfficiencyTable = p.table();
        let (first, count) = (*t.orders().start(), t.order_count() as i32);
        let queries: Vec<(i32, f32, f32)> = (0..per)
            .map(|_| {
                let m = first + ((rng.next() * count as f64) as i32).min(count - 1);
                let s = (2.1 * rng.next() - 1.05).clamp(-1.0, 1.0) as f32;
                let l = (340.0 + 510.0 * rng.next()) as f32;
                (m, s, l)
            })
            .collect();
        let mut bytes = Vec::with_capacity(16 * per);
        for &(m, s, l) in &queries {
            bytes.extend_from_slice(&m.to_le_bytes());
            bytes.extend_from_slice(&s.to_le_bytes());
            bytes.extend_from_slice(&l.to_le_bytes());
            bytes.extend_from_slice(&offset.to_le_bytes());
        }
        let (out, secs) = gpu.run(
            &source,
            "eta_main",
            &[&bytes, &tables.to_bytes()],
            4 * per,
            per,
        );
        let out = f32s(&out);
        let words = &tables.words()[offset as usize..];
        let (mut worst, mut worst_rel, mut nonzero) = (0.0f64, 0.0f64, 0usize);
        for (&(m, s, l), &g) in queries.iter().zip(&out) {
            let cpu = t.efficiency(m, s as f64, l as f64).unpolarised();
            let tol = eta_bound(words, m, s as f64, l as f64);
            let e = (g as f64 - cpu).abs();
            assert!(
                e <= tol,
                "{p:?} m={m} s={s} λ={l}: {g} vs {cpu} (tol {tol:e})"
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
        println!(
            "eta {p:?}: {per} queries in {:.1} ms, {nonzero} non-zero, worst |Δη| = {worst:.2e} \
             ({worst_rel:.3} of its bound)",
            secs * 1e3
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

/// The sampler's order proposal for wo at λ, recomputed from the table's public reading: the
/// candidates clipped to the stored orders and trimmed to those propagating at the clamped
/// query, P(m) = (1 − δ)·η̂_m/Σ η̂ + δ/K with η̂_m = Σ_c w_c·η_m,c the table's values at the
/// cell's corners with the query's bilinear weights, and each P's device bound: each weight
/// within 19u absolute (its two factors' errors, as in `eta_bound`, and the product), so
/// η̂_m within 76u·max_c η_m,c plus its own roundings (the node values' to f32, the products
/// and the sum: 6u·η̂_m); the total within the sum of those plus K·u of it; P through the
/// quotients, the product and the sum (8u). `None` where f32 may trim another order (the query
/// within 10⁻⁵ of an order's Rayleigh line).
fn weights(t: &EfficiencyTable, wo: DVec3, l: f64) -> Option<Vec<(i64, f64, f64)>> {
    let d = t.period_nm();
    let step = l / d;
    let lo = (((wo.x - 1.0) / step - 0.5).floor() as i64 + 1).max(*t.orders().start() as i64);
    let hi = (((wo.x + 1.0) / step + 0.5).ceil() as i64 - 1).min(*t.orders().end() as i64);
    let sin: Vec<f64> = t.sin_theta_i().collect();
    let lam: Vec<f64> = t.lambda_nm().collect();
    let s = (-wo.x).clamp(sin[0], sin[sin.len() - 1]);
    let lc = l.clamp(lam[0], lam[lam.len() - 1]);
    let interval = |nodes: &[f64], x: f64| {
        let k = nodes.partition_point(|&n| n <= x);
        k.saturating_sub(1).min(nodes.len() - 2)
    };
    let (i, j) = (interval(&sin, s), interval(&lam, lc));
    let tx = (s - sin[i]) / (sin[i + 1] - sin[i]);
    let ty = (lc - lam[j]) / (lam[j + 1] - lam[j]);
    if (1.0 - s * s).sqrt() <= 0.0 {
        return Some(Vec::new());
    }
    let propagates = |m: i64| (s + m as f64 * lc / d).abs() < 1.0;
    let edge = (lo..=hi).any(|m| ((s + m as f64 * lc / d).abs() - 1.0).abs() < 1e-5);
    if edge {
        return None;
    }
    let corners = [
        ((1.0 - tx) * (1.0 - ty), sin[i], lam[j]),
        (tx * (1.0 - ty), sin[i + 1], lam[j]),
        ((1.0 - tx) * ty, sin[i], lam[j + 1]),
        (tx * ty, sin[i + 1], lam[j + 1]),
    ];
    let orders: Vec<i64> = (lo..=hi).filter(|&m| propagates(m)).collect();
    // (η̂_m, its bound)
    let hat: Vec<(f64, f64)> = orders
        .iter()
        .map(|&m| {
            let (mut e, mut top) = (0.0, 0.0f64);
            for &(w, sn, ln) in &corners {
                let v = t.efficiency(m as i32, sn, ln).unpolarised();
                top = top.max(v);
                if w > 0.0 {
                    e += w * v;
                }
            }
            (e, 76.0 * U * top + 6.0 * U * e)
        })
        .collect();
    let total: f64 = hat.iter().map(|h| h.0).sum();
    let k = orders.len() as f64;
    let dtotal: f64 = hat.iter().map(|h| h.1).sum::<f64>() + k * U * total;
    let share = diffraction::grating_bsdf::TABULATED_DEFENSIVE_SHARE;
    Some(
        orders
            .iter()
            .zip(&hat)
            .map(|(&m, &(e, de))| {
                if total > 0.0 {
                    let p = (1.0 - share) * e / total + share / k;
                    let dp =
                        (1.0 - share) * (de / total + e * dtotal / (total * total)) + 8.0 * U * p;
                    (m, p, dp)
                } else {
                    (m, 1.0 / k, 8.0 * U / k)
                }
            })
            .collect(),
    )
}

/// The preset with `n` grooves on its classical table (`Preset::table`), the reading the
/// WGSL implements (`GratingBsdf::preset` reads it conically).
fn classical(p: Preset, n: u32) -> GratingBsdf {
    GratingBsdf::preset(p, n)
        .unwrap()
        .with_efficiency(OrderEfficiency::from_static(p.table()).unwrap())
        .unwrap()
}

fn preset_models() -> Vec<(Preset, GratingBsdf)> {
    vec![
        (Preset::Cd, classical(Preset::Cd, 34)),
        (
            Preset::Cd,
            classical(Preset::Cd, 34).with_groove(GrooveSpread::gaussian(0.02).unwrap()),
        ),
        (Preset::Dvd, classical(Preset::Dvd, 300)),
        (Preset::Blazed600, classical(Preset::Blazed600, 100)),
        (Preset::Foil, classical(Preset::Foil, 10)),
    ]
}

#[test]
fn tabulated_bsdf_matches_the_cpu_per_sample() {
    let Some(gpu) = gpu() else { return };
    let (tables, at) = tables();
    let per = 20_000;
    let mut rng = Mix(41);
    for (p, b) in preset_models() {
        let offset = at.iter().find(|(q, _)| *q == p).unwrap().1;
        let words = &tables.words()[offset as usize..];
        let t = p.table();
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
            let Some(w) = weights(t, wo64, l64) else {
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
            let e_wo = t.efficiency(m, -wo64.x, l64).unpolarised();
            let e_wi = t.efficiency(m, -wi.x, l64).unpolarised();
            let deta = eta_bound(words, m, -wo64.x, l64).max(eta_bound(words, m, -wi.x, l64));
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
            "tabulated {p:?} N={} groove={}: {per} samples in {:.1} ms, {compared} compared, worst \
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
    let b = classical(Preset::Cd, 34);
    let offset = at[0].1;
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
        let w: Vec<f64> = out
            .iter()
            .map(|s| {
                if s.valid {
                    s.f as f64 * s.wi[2] as f64 / s.pdf as f64
                } else {
                    0.0
                }
            })
            .collect();
        let mean = w.iter().sum::<f64>() / count as f64;
        let var = w.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (count - 1) as f64;
        let se = (var / count as f64).sqrt();
        let albedo = b.albedo(widen(wo), l as f64).expect("albedo");
        let tol = 5.0 * se + SAMPLE_WEIGHT_F32 * b.sample_weight_bound(widen(wo), l as f64);
        println!(
            "albedo CD N=34 wo={wo:?} λ={l}: device mean weight {mean:.6} ± {se:.1e} ({count} \
             samples, {:.0} ms), CPU albedo {albedo:.6}: {:.2} standard errors",
            secs * 1e3,
            (mean - albedo).abs() / se
        );
        assert!(
            (mean - albedo).abs() <= tol,
            "{mean} vs {albedo} (tol {tol:e})"
        );
    }
}
