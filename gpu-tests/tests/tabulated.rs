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
        (r * k, (dr + r) * droot / cos_i + dr * k + r * k * (ci_rel + 6.0 * U))
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
    let at = Preset::ALL.iter().map(|&p| (p, t.push(p.table()))).collect();
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
        let (out, secs) = gpu.run(&source, "eta_main", &[&bytes, &tables.to_bytes()], 4 * per, per);
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
