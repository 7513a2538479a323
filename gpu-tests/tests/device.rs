//! The WGSL shaders of `diffraction::gpu` on a real device against the CPU crate: 10⁶ inputs of
//! each kernel (the stiff cases included) and 10⁶ colour-table lookups, with the tolerances
//! derived from the WGSL accuracy rules (tests/support/gpu_tolerance.rs, docs/gpu.md), never
//! from the device at hand. In CI (the `CI` variable set) a missing adapter fails; elsewhere
//! the tests skip with a message. `NODEVICE_SELECT=1` silences a harmless Mesa warning.

#[path = "common/colour.rs"]
mod colour;
#[path = "../../tests/support/gpu_cases.rs"]
mod gpu_cases;
#[path = "../../tests/support/gpu_tolerance.rs"]
mod gpu_tolerance;

use std::time::Instant;

use colour::{cell_scale, plane_bound, sigma_of};
use diffraction::glam::DVec3;
use diffraction::gpu::{shading_source, GpuColorTable, KERNEL_WGSL};
use diffraction::kernel::{n_slit_cycles, single_slit_cycles};
use diffraction::spectrum::{Illuminant, Spectral};
use diffraction::{ColorTable, Grating};
use gpu_cases::{stiff_phases, Mix, SLITS};
use gpu_tolerance::*;
use wgpu::util::DeviceExt;

const COUNT: usize = 1_000_000;

struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
}

/// The default adapter, or None outside CI (a panic in CI).
fn gpu() -> Option<Gpu> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = match pollster::block_on(instance.request_adapter(&Default::default())) {
        Ok(a) => a,
        Err(e) => {
            if std::env::var_os("CI").is_some() {
                panic!("no GPU adapter in CI ({e}): install mesa-vulkan-drivers (lavapipe)");
            }
            eprintln!("skipped: no GPU adapter ({e}); apt-get install mesa-vulkan-drivers");
            return None;
        }
    };
    eprintln!("adapter: {:?}", adapter.get_info().name);
    let (device, queue) =
        pollster::block_on(adapter.request_device(&Default::default())).expect("device");
    Some(Gpu { device, queue })
}

impl Gpu {
    /// Runs `entry` of `source` over `count` invocations (workgroups of 256) with the storage
    /// buffers `inputs` (read-only, bindings 0..) and one output (the next binding) of
    /// `out_bytes`, and `extra` at group 1 if given (bindings 0.., the first a uniform, the others
    /// read-only storage).
    /// Returns the output and the seconds of the dispatch (submit to read-back).
    fn run(
        &self,
        source: &str,
        entry: &str,
        inputs: &[&[u8]],
        out_bytes: usize,
        count: usize,
        extra: Option<&[&[u8]]>,
    ) -> (Vec<u8>, f64) {
        let d = &self.device;
        let module = d.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(entry),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = d.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(entry),
            layout: None,
            module: &module,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        });
        let storage = |bytes: &[u8], usage| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: bytes,
                usage,
            })
        };
        let ins: Vec<wgpu::Buffer> = inputs
            .iter()
            .map(|b| storage(b, wgpu::BufferUsages::STORAGE))
            .collect();
        let out = d.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: out_bytes as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read = d.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: out_bytes as u64,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut entries: Vec<wgpu::BindGroupEntry> = ins
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        entries.push(wgpu::BindGroupEntry {
            binding: ins.len() as u32,
            resource: out.as_entire_binding(),
        });
        let group0 = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let table_buffers: Option<Vec<wgpu::Buffer>> = extra.map(|bufs| {
            bufs.iter()
                .enumerate()
                .map(|(i, b)| {
                    let usage = if i == 0 {
                        wgpu::BufferUsages::UNIFORM
                    } else {
                        wgpu::BufferUsages::STORAGE
                    };
                    storage(b, usage)
                })
                .collect()
        });
        let group1 = table_buffers.as_ref().map(|bufs| {
            d.create_bind_group(&wgpu::BindGroupDescriptor {
                label: None,
                layout: &pipeline.get_bind_group_layout(1),
                entries: &bufs
                    .iter()
                    .enumerate()
                    .map(|(i, b)| wgpu::BindGroupEntry {
                        binding: i as u32,
                        resource: b.as_entire_binding(),
                    })
                    .collect::<Vec<_>>(),
            })
        });
        let start = Instant::now();
        let mut enc = d.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group0, &[]);
            if let Some(g) = &group1 {
                pass.set_bind_group(1, g, &[]);
            }
            pass.dispatch_workgroups(count.div_ceil(256) as u32, 1, 1);
        }
        enc.copy_buffer_to_buffer(&out, 0, &read, 0, out_bytes as u64);
        self.queue.submit([enc.finish()]);
        read.slice(..)
            .map_async(wgpu::MapMode::Read, |r| r.expect("map"));
        d.poll(wgpu::PollType::wait_indefinitely()).expect("poll");
        let bytes = read.slice(..).get_mapped_range().expect("mapped").to_vec();
        (bytes, start.elapsed().as_secs_f64())
    }
}

fn f32s(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

const KERNEL_MAIN: &str = "
struct Case { x: f32, n: u32 }
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read_write> out: array<f32>;
@compute @workgroup_size(256)
fn n_slit_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) { out[id.x] = diffraction_n_slit_cycles(cases[id.x].x, cases[id.x].n); }
}
@compute @workgroup_size(256)
fn single_slit_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) { out[id.x] = diffraction_single_slit_cycles(cases[id.x].x); }
}
";

/// 10⁶ (x, N) cases: the stiff phases for every N of the checks.
fn cases() -> (Vec<(f32, u32)>, Vec<u8>) {
    let mut rng = Mix(11);
    let per = COUNT / SLITS.len();
    let mut cases = Vec::with_capacity(COUNT);
    for n in SLITS {
        cases.extend(stiff_phases(n, per, &mut rng).into_iter().map(|x| (x, n)));
    }
    let mut bytes = Vec::with_capacity(8 * cases.len());
    for (x, n) in &cases {
        bytes.extend_from_slice(&x.to_le_bytes());
        bytes.extend_from_slice(&n.to_le_bytes());
    }
    (cases, bytes)
}

#[test]
fn kernels_match_the_cpu_within_the_spec_bound() {
    let Some(gpu) = gpu() else { return };
    let source = format!("{KERNEL_WGSL}\n{KERNEL_MAIN}");
    let (cases, bytes) = cases();
    for (entry, bound) in [
        ("n_slit_main", N_SLIT_SPEC),
        ("single_slit_main", SINGLE_SLIT_SPEC),
    ] {
        let (out, secs) = gpu.run(
            &source,
            entry,
            &[&bytes],
            4 * cases.len(),
            cases.len(),
            None,
        );
        let out = f32s(&out);
        let mut worst = (0.0f64, 0.0f32, 0u32);
        for (&(x, n), &g) in cases.iter().zip(&out) {
            let want = if entry == "n_slit_main" {
                n_slit_cycles(x as f64, n)
            } else {
                single_slit_cycles(x as f64)
            };
            let e = (g as f64 - want).abs();
            assert!(
                e.is_finite() && e <= bound,
                "{entry} x={x} n={n}: {g} vs {want}"
            );
            if e > worst.0 {
                worst = (e, x, n);
            }
        }
        println!(
            "{entry}: {} inputs in {:.1} ms, worst |GPU - CPU f64| = {:.2e} at x = {}, N = {} \
             (spec bound {bound:.2e})",
            cases.len(),
            secs * 1e3,
            worst.0,
            worst.1,
            worst.2
        );
    }
}

const TABLE_MAIN: &str = "
@group(0) @binding(0) var<storage, read> us: array<f32>;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
@compute @workgroup_size(256)
fn lookup_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) { out[id.x] = vec4<f32>(diffraction_table_lookup(us[id.x]), 0.0); }
}
";

#[test]
fn table_lookup_matches_the_cpu_table() {
    let Some(gpu) = gpu() else { return };
    let g = Grating::new(1600.0, 800.0, 300).unwrap();
    let table = ColorTable::new(&Spectral::new(Illuminant::D65), &g, 1e-3).unwrap();
    let t = GpuColorTable::new(&table);
    let mut rng = Mix(5);
    // Uniform in [-2.2, 2.2] (beyond 2 is clamped), and log-uniform near 0 (order 0's lobe).
    let us: Vec<f32> = (0..COUNT)
        .map(|i| {
            if i % 2 == 0 {
                (4.4 * rng.next() - 2.2) as f32
            } else {
                (10f64.powf(-6.0 * rng.next())) as f32
            }
        })
        .collect();
    let bytes: Vec<u8> = us.iter().flat_map(|u| u.to_le_bytes()).collect();
    let source = format!("{}\n{TABLE_MAIN}", shading_source(1, 0));
    let (h, b, n) = (t.header_bytes(), t.blocks_bytes(), t.nodes_bytes());
    let (out, secs) = gpu.run(
        &source,
        "lookup_main",
        &[&bytes],
        16 * COUNT,
        COUNT,
        Some(&[&h, &b, &n]),
    );
    let out = f32s(&out);
    let (mut worst, mut worst_abs) = (0.0f64, 0.0f64);
    for (i, &u) in us.iter().enumerate() {
        let cpu = table.lookup(u as f64);
        let cpu = [cpu.x, cpu.y, cpu.z];
        let (m, dmax) = cell_scale(&t, u);
        for c in 0..3 {
            let e = (out[4 * i + c] as f64 - cpu[c]).abs();
            let tol = TABLE_ROUNDINGS * U * m[c] + 2.0 * U * (u.abs().min(2.0) as f64) * dmax[c];
            assert!(
                e <= tol,
                "u={u} channel {c}: {} vs {} (tol {tol:e})",
                out[4 * i + c],
                cpu[c]
            );
            worst = worst.max(e / tol);
            worst_abs = worst_abs.max(e);
        }
    }
    println!(
        "table lookup: {COUNT} lookups in {:.1} ms, worst error {:.2e} of the table's scale, \
         {worst:.3} of its bound",
        secs * 1e3,
        worst_abs / table.scale()
    );
}

const COLOUR_MAIN: &str = "
struct Query { u: f32, s: f32 }
@group(0) @binding(0) var<storage, read> queries: array<Query>;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
@compute @workgroup_size(256)
fn colour_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) {
        let q = queries[id.x];
        out[id.x] = vec4<f32>(diffraction_table_colour(q.u, q.s), 0.0);
    }
}
";

/// The colours of `queries` queries (`bytes`) by the entry `entry` of `main` on the device,
/// with the colour table `t` and its incidence bound at group 1, and the dispatch's seconds.
fn colours(
    gpu: &Gpu,
    t: &GpuColorTable,
    main: &str,
    entry: &str,
    bytes: &[u8],
    queries: usize,
) -> (Vec<f32>, f64) {
    let source = [
        diffraction::gpu::TYPES_WGSL,
        &diffraction::gpu::color_table_bindings(1, 0),
        &diffraction::gpu::incidence_bindings(1, 3),
        diffraction::gpu::COLOR_TABLE_WGSL,
        diffraction::gpu::INCIDENCE_WGSL,
        main,
    ]
    .join("\n");
    let (h, bl, n, inc) = (
        t.header_bytes(),
        t.blocks_bytes(),
        t.nodes_bytes(),
        t.incidence_bytes(),
    );
    let (out, secs) = gpu.run(
        &source,
        entry,
        &[bytes],
        16 * queries,
        queries,
        Some(&[&h, &bl, &n, &inc]),
    );
    (f32s(&out), secs)
}

/// Each channel of the device's colour `got` within `tol` (plus 10⁻¹² relative: the CPU's own
/// rounding) of the CPU's `c`; `worst` keeps the largest error over its bound and in absolute.
fn check(got: &[f32], c: [f64; 3], tol: [f64; 3], at: &str, worst: (&mut f64, &mut f64)) {
    for ch in 0..3 {
        let tol = tol[ch] + 1e-12 * c[ch].abs();
        let e = (got[ch] as f64 - c[ch]).abs();
        assert!(
            e <= tol,
            "{at} channel {ch}: {} vs {} (tol {tol:e})",
            got[ch],
            c[ch]
        );
        *worst.0 = worst.0.max(e / tol);
        *worst.1 = worst.1.max(e);
    }
}

/// The colour table of `b` (D65, 10⁻¹: seconds to a minute unoptimised), its GPU form and the
/// seconds of its build.
fn colour_tables(b: &diffraction::GratingBsdf) -> (ColorTable, GpuColorTable, f64) {
    let start = Instant::now();
    let table = ColorTable::new(&Spectral::new(Illuminant::D65), b, 1e-1).unwrap();
    let build = start.elapsed().as_secs_f64();
    let t = GpuColorTable::new(&table);
    (table, t, build)
}

#[test]
fn table_colour_at_an_incidence_matches_the_cpu_table() {
    use diffraction::grating_bsdf::OrderEfficiency;
    use diffraction::relief::Preset;
    use diffraction::{GratingBsdf, GrooveSpread};
    let Some(gpu) = gpu() else { return };
    // The blazed grating (its colour is not even in u: a symmetric profile's grids over u ≥ 0
    // and u ≤ 0 are the same by reciprocity and mirror symmetry) with 8 grooves lit, at 10⁻¹
    // (a build of seconds unoptimised), read classically: `diffraction_table_colour` reads a
    // table's plane β = 0, which is the classical reading's table (tests/gpu_wgsl.rs); the
    // conical reading's planes of |wi.y| are the next test's (the CD's: a blazed600 read
    // conically would take minutes unoptimised).
    let classical = OrderEfficiency::from_static(Preset::Blazed600.table()).unwrap();
    let b = GratingBsdf::preset(Preset::Blazed600, 8)
        .and_then(|b| b.with_efficiency(classical))
        .unwrap()
        .with_groove(GrooveSpread::gaussian(0.02).unwrap());
    let (table, t, build) = colour_tables(&b);
    let words = &t.incidence;
    let (k, bins) = (words[0] as usize, words[1] as usize);
    assert!(k >= 9 && bins >= 8, "{k} nodes, {bins} bins");
    const QUERIES: usize = 1 << 18;
    let mut rng = Mix(11);
    // wi.x and wo.x uniform in (−0.99, 0.99), u = wi.x + wo.x rounded to f32.
    let queries: Vec<(f32, f32)> = (0..QUERIES)
        .map(|_| {
            let s = (1.98 * rng.next() - 0.99) as f32;
            let u = (s as f64 + 1.98 * rng.next() - 0.99) as f32;
            (u, s)
        })
        .collect();
    let bytes: Vec<u8> = queries
        .iter()
        .flat_map(|&(u, s)| [u.to_le_bytes(), s.to_le_bytes()])
        .flatten()
        .collect();
    let (out, secs) = colours(&gpu, &t, COLOUR_MAIN, "colour_main", &bytes, QUERIES);
    let g0 = b.groove().value(0.0, 550.0);
    let (mut worst, mut worst_abs, mut checked) = (0.0f64, 0.0f64, 0usize);
    for (q, &(u, s)) in queries.iter().enumerate() {
        let (uf, sf) = (u as f64, s as f64);
        let wi = DVec3::new(sf, 0.0, (1.0 - sf * sf).sqrt());
        let ox = uf - sf;
        if ox.abs() >= 0.995 {
            continue;
        }
        let wo = DVec3::new(ox, 0.0, (1.0 - ox * ox).sqrt());
        let xyz = table.xyz(wo, wi);
        let c = [xyz.x, xyz.y, xyz.z].map(|v| v / (wi.z * g0));
        // The place σ and its f32 rounding: τ's (three roundings of |s| + |u| + 1 over the
        // width), carried exactly through σ(τ), plus the square roots, sum and quotient.
        let a = u.abs();
        let width = 2.0 - a as f64;
        let tau = (sf - uf.max(0.0) + 1.0) / width;
        let dtau = 16.0 * U * (1.0 + sf.abs() + uf.abs()) / width + 2.0 * U * tau;
        let sigma = sigma_of(tau);
        let dsigma = sigma_of(tau + dtau) - sigma_of(tau - dtau) + 24.0 * U * sigma;
        let bound = plane_bound(&t, (0, 1), a, u >= 0.0, sigma, dsigma);
        let tol = [0, 1, 2].map(|ch| bound[ch].0);
        let got = &out[4 * q..4 * q + 3];
        check(
            got,
            c,
            tol,
            &format!("u={u} s={s}"),
            (&mut worst, &mut worst_abs),
        );
        checked += 1;
    }
    assert!(checked > QUERIES / 2, "{checked} checked");
    println!(
        "table colour at an incidence: {k} incidence nodes ({build:.1} s to build), \
         {checked} queries in {:.1} ms, worst error {:.2e} of the table's scale, {worst:.3} of \
         its bound",
        secs * 1e3,
        worst_abs / table.scale()
    );
}

const CONICAL_MAIN: &str = "
struct Query { u: f32, s: f32, b: f32, pad: f32 }
@group(0) @binding(0) var<storage, read> queries: array<Query>;
@group(0) @binding(1) var<storage, read_write> out: array<vec4<f32>>;
@compute @workgroup_size(256)
fn conical_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) {
        let q = queries[id.x];
        out[id.x] = vec4<f32>(diffraction_table_colour_conical(q.u, q.s, q.b), 0.0);
    }
}
";

/// A conical table's colour on its planes of |wi.y| (the CD as `GratingBsdf::preset` reads it)
/// against `ColorTable::xyz`: b = min(|wi.y|, |wo.y|) from 0 to past the last plane, each
/// plane's bound (`plane_bound`, with σ's rounding through r = √(1 − b²) and the divisions by
/// it) blended as the planes are, plus the blend's rounding times the larger plane's colour.
/// Queries within 10⁻⁶ of a plane's |wi.y| are left out: there the f32 and f64 comparisons may
/// pick the neighbouring pair of planes, whose blend is the same plane's colour only to within
/// the rounding of t.
#[test]
fn conical_table_colour_matches_the_cpu_table() {
    use diffraction::relief::Preset;
    use diffraction::{GratingBsdf, GrooveSpread};
    let Some(gpu) = gpu() else { return };
    let b = GratingBsdf::preset(Preset::Cd, 8)
        .unwrap()
        .with_groove(GrooveSpread::gaussian(0.02).unwrap());
    let (table, t, build) = colour_tables(&b);
    let words = &t.incidence;
    let head = 2 + words[1] as usize + 2 * words[0] as usize;
    let planes = words[head] as usize;
    // (|wi.y|, c, first word, first grid) of each plane, the plane across the grooves first.
    let mut plane = vec![(0.0f64, 1.0f64, 0usize, 1usize)];
    for p in 0..planes {
        let e = &words[head + 1 + 4 * p..head + 5 + 4 * p];
        plane.push((
            f32::from_bits(e[0]) as f64,
            f32::from_bits(e[1]) as f64,
            e[2] as usize,
            e[3] as usize,
        ));
    }
    assert_eq!(planes, 8);
    const QUERIES: usize = 1 << 16;
    let mut rng = Mix(12);
    // (u, s, b, wo.y): b uniform in [0, 0.97], wi.y = b, wo.y in [b, b + 0.02].
    let mut cases = Vec::with_capacity(QUERIES);
    while cases.len() < QUERIES {
        let bq = (0.97 * rng.next()) as f32;
        let (bf, oy) = (bq as f64, bq as f64 + 0.02 * rng.next());
        if plane.iter().any(|p| (bf - p.0).abs() < 1e-6 && p.0 > 0.0) || oy >= 0.999 {
            continue;
        }
        let (ri, ro) = ((1.0 - bf * bf).sqrt(), (1.0 - oy * oy).sqrt());
        let s = (ri * (1.98 * rng.next() - 0.99)) as f32;
        let u = (s as f64 + ro * (1.98 * rng.next() - 0.99)) as f32;
        cases.push((u, s, bq, oy));
    }
    let bytes: Vec<u8> = cases
        .iter()
        .flat_map(|&(u, s, bq, _)| [u, s, bq, 0.0].map(f32::to_le_bytes))
        .flatten()
        .collect();
    let (out, secs) = colours(&gpu, &t, CONICAL_MAIN, "conical_main", &bytes, QUERIES);
    let (mut worst, mut worst_abs, mut checked, mut off_plane) = (0.0f64, 0.0f64, 0usize, 0usize);
    for (q, &(u, s, bq, oy)) in cases.iter().enumerate() {
        let (uf, sf, bf) = (u as f64, s as f64, bq as f64);
        let ox = uf - sf;
        let (wiz2, woz2) = (1.0 - sf * sf - bf * bf, 1.0 - ox * ox - oy * oy);
        if wiz2 <= 1e-4 || woz2 <= 1e-4 {
            continue;
        }
        let wi = DVec3::new(sf, bf, wiz2.sqrt());
        let wo = DVec3::new(ox, -oy, woz2.sqrt());
        let g = b.groove().value(wi.y + wo.y, 550.0);
        let xyz = table.xyz(wo, wi);
        let c = [xyz.x, xyz.y, xyz.z].map(|v| v / (wi.z * g));
        // σ on the planes: r and the divisions by it (relative dr), then p, the width and τ
        // (as the plane across the grooves, `table_colour_at_an_incidence_matches_the_cpu_table`).
        let a = u.abs();
        let r = (1.0 - bf * bf).sqrt();
        let dr = U * (2.0 + bf * bf / (1.0 - bf * bf));
        let (ur, sr) = (uf / r, sf / r);
        let width = 2.0 - ur.abs();
        let p = (sr - ur.max(0.0) + 1.0).clamp(0.0, width);
        let tau = p / width;
        let dw = ur.abs() * (dr + U) + 4.0 * U;
        let dp = 16.0 * U * (1.0 + sr.abs() + ur.abs()) + 2.0 * (sr.abs() + ur.abs()) * dr;
        let dtau = (dp + tau * dw) / width + 2.0 * U * tau;
        let sigma = sigma_of(tau);
        let dsigma = sigma_of(tau + dtau) - sigma_of(tau - dtau) + 24.0 * U * sigma;
        // The planes around b and the blend between them (the last plane alone past it).
        let k = plane.iter().rposition(|p| p.0 <= bf).unwrap();
        let read = |k: usize| plane_bound(&t, (plane[k].2, plane[k].3), a, u >= 0.0, sigma, dsigma);
        let x = read(k);
        let (y, tb, dt) = if k + 1 < plane.len() {
            let (c0, c1) = (plane[k].1, plane[k + 1].1);
            let tb = ((c0 - r) / (c0 - c1)).clamp(0.0, 1.0);
            (read(k + 1), tb, (8.0 * U + r * dr) / (c0 - c1) + 4.0 * U)
        } else {
            (x, 0.0, 0.0)
        };
        off_plane += usize::from(k > 0 || tb > 0.0);
        let tol = [0, 1, 2]
            .map(|ch| (1.0 - tb) * x[ch].0 + tb * y[ch].0 + x[ch].1.max(y[ch].1) * (dt + 4.0 * U));
        let got = &out[4 * q..4 * q + 3];
        let at = format!("u={u} s={s} b={bq}");
        check(got, c, tol, &at, (&mut worst, &mut worst_abs));
        checked += 1;
    }
    assert!(
        checked > QUERIES / 2 && off_plane > QUERIES / 2,
        "{checked} checked"
    );
    let relative = worst_abs / table.scale();
    assert!(relative <= CONICAL_COLOUR_WORST_MEASURED, "{relative:e}");
    println!(
        "conical table colour: {} planes ({build:.1} s to build), {checked} queries in {:.1} ms, \
         worst error {relative:.2e} of the table's scale, {worst:.3} of its bound",
        planes + 1,
        secs * 1e3,
    );
}

const BSDF_MAIN: &str = "
struct Case { wo: vec4<f32>, wi: vec4<f32> }
@group(0) @binding(0) var<storage, read> cases: array<Case>;
@group(0) @binding(1) var<storage, read> model: array<DiffractionBsdf>;
@group(0) @binding(2) var<storage, read> diffraction_bsdf_orders: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> out: array<vec2<f32>>;
@compute @workgroup_size(256)
fn bsdf_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x < arrayLength(&out) {
        let c = cases[id.x];
        let b = model[0];
        out[id.x] = vec2<f32>(diffraction_bsdf_f(b, c.wo.xyz, c.wi.xyz, c.wo.w),
                              diffraction_bsdf_pdf(b, c.wo.xyz, c.wi.xyz, c.wo.w));
    }
}
";

#[test]
fn bsdf_matches_the_cpu_within_the_spec_bound() {
    use diffraction::glam::{DVec2, DVec3};
    use diffraction::gpu::{order_rows_bytes, GpuBsdf, BSDF_WGSL, TYPES_WGSL};
    use diffraction::{Bsdf, DiffractionBrdf, GratingBsdf, GrooveSpread};
    let Some(gpu) = gpu() else { return };
    let source = [TYPES_WGSL, KERNEL_WGSL, BSDF_WGSL, BSDF_MAIN].join("\n");
    let models = [
        GratingBsdf::new(Grating::new(1600.0, 800.0, 1).unwrap()),
        GratingBsdf::new(Grating::new(1600.0, 800.0, 10).unwrap()),
        GratingBsdf::new(Grating::new(1600.0, 800.0, 1000).unwrap()),
        GratingBsdf::new(Grating::new(740.0, 370.0, 1000).unwrap())
            .with_groove(GrooveSpread::gaussian(0.05).unwrap()),
        GratingBsdf::new(Grating::new(10_000.0, 3000.0, 100).unwrap()),
    ];
    let per = 40_000;
    let mut rng = Mix(3);
    for b in &models {
        // wo uniform on the hemisphere, λ uniform in the band, wi from the model's own sampler
        // (so that the lobes are hit), all rounded to f32; the CPU reads the same f32 values.
        let mut cases: Vec<([f32; 3], [f32; 3], f32)> = Vec::with_capacity(per);
        while cases.len() < per {
            let (z, phi) = (rng.next(), 2.0 * std::f64::consts::PI * rng.next());
            let s = (1.0 - z * z).sqrt();
            let wo = DVec3::new(s * phi.cos(), s * phi.sin(), z.max(0.05));
            let wo = wo.normalize();
            let lambda = (360.0 + 470.0 * rng.next()) as f32;
            let Some(smp) = b.sample(
                wo,
                lambda as f64,
                rng.next(),
                DVec2::new(rng.next(), rng.next()),
            ) else {
                continue;
            };
            let f = |v: DVec3| [v.x as f32, v.y as f32, v.z as f32];
            cases.push((f(wo), f(smp.wi), lambda));
        }
        let mut bytes = Vec::with_capacity(32 * per);
        for (wo, wi, l) in &cases {
            for v in [wo[0], wo[1], wo[2], *l, wi[0], wi[1], wi[2], 0.0] {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
        // The grating's rows after 65 rows of another grating's, as in a shared buffer.
        let g = GpuBsdf::new(b, 65);
        let mut rows = GpuBsdf::order_rows(&models[0]).to_vec();
        rows.extend_from_slice(&GpuBsdf::order_rows(b));
        let (out, secs) = gpu.run(
            &source,
            "bsdf_main",
            &[&bytes, &g.to_bytes(), &order_rows_bytes(&rows)],
            8 * per,
            per,
            None,
        );
        let out = f32s(&out);
        let (n, d, rho) = (g.slits as f64, g.period_nm as f64, g.rho as f64);
        let (mut worst_f, mut worst_p, mut skipped) = (0.0f64, 0.0f64, 0usize);
        for (i, (wo, wi, l)) in cases.iter().enumerate() {
            let dv = |v: &[f32; 3]| DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64);
            let (wo64, wi64, l64) = (dv(wo), dv(wi), *l as f64);
            let (f_cpu, p_cpu) = (b.eval(wo64, wi64, l64), b.pdf(wo64, wi64, l64));
            let (f_gpu, p_gpu) = (out[2 * i] as f64, out[2 * i + 1] as f64);
            let x = d * (wi64.x + wo64.x) / l64;
            let v = wi64.y + wo64.y;
            // The phases' own f32 rounding (u, u/λ, d·q): 7u relative.
            let dx = 7.0 * U * x.abs();
            // Where the order owning u or the candidate orders are decided within that
            // rounding (|r| near ½, the candidates' ends near an integer), GPU and CPU may
            // differ by a whole order: skipped and counted.
            let near_half = |t: f64| ((t - t.round()).abs() - 0.5).abs() <= dx + 16.0 * U;
            let step = l64 / d;
            let ends = [(wo64.x - 1.0) / step - 0.5, (wo64.x + 1.0) / step + 0.5];
            let near_int = |t: f64| (t - t.round()).abs() <= 16.0 * U * (t.abs() + 1.0);
            if near_half(x) || ends.iter().any(|&t| near_int(t)) {
                skipped += 1;
                continue;
            }
            // f: the kernels' spec bounds and the phases' conditioning, times the lobe's scale.
            let (gmax, groove_term) = if g.groove == 0 {
                let k = g.groove_param as f64 / l64;
                let t = k * v;
                (
                    k,
                    SINGLE_SLIT_SPEC + 14.0 * std::f64::consts::PI * U * t.abs(),
                )
            } else {
                let sigma = g.groove_param as f64;
                let t = v / sigma;
                (
                    1.0 / ((2.0 * std::f64::consts::PI).sqrt() * sigma),
                    U * (6.0 + 9.0 * t * t),
                )
            };
            let scale = rho * rho * n * d / l64 * gmax;
            let tol_f = scale
                * (INTENSITY_SPEC
                    + groove_term
                    + 20.0 * U
                    + 2.0 * std::f64::consts::PI * (n + 1.0) * dx);
            let e_f = (f_gpu - f_cpu).abs();
            assert!(
                e_f <= tol_f,
                "f: wo={wo:?} wi={wi:?} λ={l}: {f_gpu} vs {f_cpu} (tol {tol_f:e})"
            );
            worst_f = worst_f.max(e_f / scale);
            // pdf: relative, the roundings of its products and quotients (2.5 ulp each
            // division), the sum of up to 256 weights, and t = 2N·r's conditioning.
            let tol_p = p_cpu * (40.0 * U + 256.0 * U + 2.0 * n * dx);
            let e_p = (p_gpu - p_cpu).abs();
            assert!(
                e_p <= tol_p,
                "pdf: wo={wo:?} wi={wi:?} λ={l}: {p_gpu} vs {p_cpu} (tol {tol_p:e})"
            );
            if p_cpu > 0.0 {
                worst_p = worst_p.max(e_p / p_cpu);
            }
        }
        println!(
            "bsdf d={d} N={n} groove={}: {per} cases in {:.1} ms, worst |Δf| = {worst_f:.2e} of \
             the lobe's scale, worst |Δpdf|/pdf = {worst_p:.2e}, {skipped} skipped at order \
             boundaries",
            g.groove,
            secs * 1e3
        );
    }
}
