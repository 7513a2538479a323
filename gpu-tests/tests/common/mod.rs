//! The device harness of the BSDF tests (`sample.rs`, `tabulated.rs`): one compute dispatch
//! over read-only storage inputs at group 0, and the error bounds of `diffraction_bsdf_f` and
//! `diffraction_bsdf_pdf` at a given direction (docs/gpu.md, "The radiometric BSDF").
#![allow(dead_code)]

use std::time::Instant;

use diffraction::glam::DVec3;
use diffraction::gpu::GpuBsdf;
use wgpu::util::DeviceExt;

pub mod eta;
#[path = "../../../tests/support/gpu_cases.rs"]
pub mod gpu_cases;
#[path = "../../../tests/support/gpu_tolerance.rs"]
pub mod gpu_tolerance;

use gpu_tolerance::*;

pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
}

/// The default adapter, or None outside CI (a panic in CI).
pub fn gpu() -> Option<Gpu> {
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
    /// buffers `inputs` (read-only, group 0, bindings 0..) and one output (the next binding) of
    /// `out_bytes`. Returns the output and the seconds of the dispatch (submit to read-back).
    pub fn run(
        &self,
        source: &str,
        entry: &str,
        inputs: &[&[u8]],
        out_bytes: usize,
        count: usize,
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
        let ins: Vec<wgpu::Buffer> = inputs
            .iter()
            .map(|b| {
                d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: None,
                    contents: b,
                    usage: wgpu::BufferUsages::STORAGE,
                })
            })
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
        let start = Instant::now();
        let mut enc = d.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group0, &[]);
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

pub fn f32s(bytes: &[u8]) -> Vec<f32> {
    bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}

pub fn bytes_of(values: &[f32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A uniform f32 in [0, 1) with 24 random bits (exact in f32, never rounds to 1).
pub fn unit_f32(rng: &mut gpu_cases::Mix) -> f32 {
    ((rng.next() * 16_777_216.0) as u32).min(16_777_215) as f32 / 16_777_216.0
}

/// A direction uniform on the hemisphere (z ≥ 0.05), rounded to f32.
pub fn hemisphere_f32(rng: &mut gpu_cases::Mix) -> [f32; 3] {
    let (z, phi) = (rng.next(), 2.0 * std::f64::consts::PI * rng.next());
    let s = (1.0 - z * z).sqrt();
    let w = DVec3::new(s * phi.cos(), s * phi.sin(), z.max(0.05)).normalize();
    [w.x as f32, w.y as f32, w.z as f32]
}

pub fn widen(v: [f32; 3]) -> DVec3 {
    DVec3::new(v[0] as f64, v[1] as f64, v[2] as f64)
}

/// What the f and pdf bounds need of a model: d, N, ρ² (1 for a tabulated model: its lobe
/// carries no single-slit factor), the groove (0 coherence length L, 1 Gaussian σ).
#[derive(Clone, Copy, Debug)]
pub struct Lobe {
    pub d: f64,
    pub n: f64,
    pub rho2: f64,
    pub groove: u32,
    pub groove_param: f64,
}

impl Lobe {
    pub fn of(g: &diffraction::gpu::GpuBsdf, tabulated: bool) -> Lobe {
        let rho = g.rho as f64;
        Lobe {
            d: g.period_nm as f64,
            n: g.slits as f64,
            rho2: if tabulated { 1.0 } else { rho * rho },
            groove: g.groove,
            groove_param: g.groove_param as f64,
        }
    }

    /// The phase x = d·(u/λ) and its f32 rounding (7u relative: one addition, a division,
    /// a product).
    pub fn phase(&self, wo: DVec3, wi: DVec3, l: f64) -> (f64, f64) {
        let x = self.d * (wi.x + wo.x) / l;
        (x, 7.0 * U * x.abs())
    }

    /// Whether GPU and CPU may assign a different owning order or candidate range (|r| within
    /// the phase's rounding of ½, a candidate range's end within rounding of an integer).
    pub fn at_order_boundary(&self, wo: DVec3, wi: DVec3, l: f64) -> bool {
        let (x, dx) = self.phase(wo, wi, l);
        let near_half = |t: f64| ((t - t.round()).abs() - 0.5).abs() <= dx + 16.0 * U;
        let step = l / self.d;
        let ends = [(wo.x - 1.0) / step - 0.5, (wo.x + 1.0) / step + 0.5];
        let near_int = |t: f64| (t - t.round()).abs() <= 16.0 * U * (t.abs() + 1.0);
        near_half(x) || ends.iter().any(|&t| near_int(t))
    }

    /// The lobe's scale ρ²·(N·d/λ)·g_max and the bound of |Δf| over it at (wo, wi): the
    /// kernels' spec bounds, the groove's, and the phase's conditioning (docs/gpu.md).
    pub fn f_bound(&self, wo: DVec3, wi: DVec3, l: f64) -> (f64, f64) {
        let (_, dx) = self.phase(wo, wi, l);
        let v = wi.y + wo.y;
        let (gmax, groove_term) = if self.groove == 0 {
            let k = self.groove_param / l;
            let t = k * v;
            (
                k,
                SINGLE_SLIT_SPEC + 14.0 * std::f64::consts::PI * U * t.abs(),
            )
        } else {
            let sigma = self.groove_param;
            let t = v / sigma;
            (
                1.0 / ((2.0 * std::f64::consts::PI).sqrt() * sigma),
                U * (6.0 + 9.0 * t * t),
            )
        };
        let scale = self.rho2 * self.n * self.d / l * gmax;
        let tol = scale
            * (INTENSITY_SPEC
                + groove_term
                + 20.0 * U
                + 2.0 * std::f64::consts::PI * (self.n + 1.0) * dx);
        (scale, tol)
    }

    /// The relative bound of |Δpdf| at (wo, wi) for exact order weights: the roundings of its
    /// products and quotients, the sum of up to 256 weights, t = 2N·r's conditioning.
    pub fn pdf_relative_bound(&self, wo: DVec3, wi: DVec3, l: f64) -> f64 {
        let (_, dx) = self.phase(wo, wi, l);
        40.0 * U + 256.0 * U + 2.0 * self.n * dx
    }
}

/// The bound of |wi_GPU − wi_CPU| per component for order m and ξ (docs/gpu.md, "The
/// sampler"): the proxy's inverse CDF, u = (m + r)·λ/d, v from the Cauchy proxy, and the
/// direction's z = √(1 − x² − y²).
pub fn direction_bound(g: &GpuBsdf, wo: DVec3, l: f64, m: i64, xi: [f64; 3]) -> [f64; 3] {
    let pi = std::f64::consts::PI;
    let (n, d) = (g.slits as f64, g.period_nm as f64);
    let (r, dr) = if g.slits <= 1 {
        (xi[1] - 0.5, U)
    } else {
        let r = ((2.0 * xi[1] - 1.0) * n.atan()).tan() / (2.0 * n);
        let r = r.clamp(-0.5, 0.5);
        let t = 2.0 * n * r;
        (
            r,
            pi * (1.0 + t * t) / (2.0 * n) * 3.0 * U + r.abs() * 85.0 * U,
        )
    };
    let step = l / d;
    let du = step * ((m as f64 + r).abs() * 8.0 * U + dr);
    let s = if g.groove == 0 {
        1.2 * l / (pi * g.groove_param as f64)
    } else {
        g.groove_param as f64
    };
    let v = s * (pi * (xi[2] - 0.5)).tan();
    let t = v / s;
    let dv = s * pi * (1.0 + t * t) * U + v.abs() * 93.0 * U;
    let (x, y) = ((m as f64 + r) * step - wo.x, v - wo.y);
    let (dx, dy) = (du + U * x.abs(), dv + U * y.abs());
    let dz2 = 2.0 * x.abs() * dx + dx * dx + 2.0 * y.abs() * dy + dy * dy + 4.0 * U;
    let z = (1.0 - x * x - y * y).max(0.0).sqrt();
    let dz = (dz2 / z).min(dz2.sqrt()) + U * z;
    [dx, dy, dz]
}

/// The mean of the sample weights f·cos θi/pdf of device samples given as (valid, f, wi.z,
/// pdf) (0 for an invalid one), and its standard error.
pub fn mean_weight(samples: impl Iterator<Item = (bool, f32, f32, f32)>) -> (f64, f64) {
    let w: Vec<f64> = samples
        .map(|(valid, f, z, pdf)| {
            if valid {
                f as f64 * z as f64 / pdf as f64
            } else {
                0.0
            }
        })
        .collect();
    let count = w.len() as f64;
    let mean = w.iter().sum::<f64>() / count;
    let var = w.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (count - 1.0);
    (mean, (var / count).sqrt())
}

/// Whether a running sum of `weights` comes within `delta` of `target` (the order choice is
/// decided within rounding there).
pub fn near_partial_sum(weights: &[f64], target: f64, delta: f64) -> bool {
    let mut acc = 0.0;
    weights.iter().any(|w| {
        acc += w;
        (acc - target).abs() <= delta
    })
}
