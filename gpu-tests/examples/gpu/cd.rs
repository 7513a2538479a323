//! `gpu cd`: the CD preset (`GratingBsdf::preset(Preset::Cd, 34)`: the rigorous efficiencies
//! of aluminium pits under polycarbonate, read conically from the preset's reduced table)
//! rendered with the library's tabulated BSDF in WGSL
//! (`cd.wgsl`: the table as a storage buffer, `diffraction_bsdf_tabulated_f` for a disk light
//! at K stratified wavelengths and `diffraction_bsdf_tabulated_sample` toward a sky), and the
//! same estimator on the CPU (`GratingBsdf::eval` and `Bsdf::sample` in f64, the same random
//! numbers), with the frame times, the time per million BSDF calls of each and the ΔE2000
//! between the two pictures.
//!
//! ```text
//! cargo run --release -p gpu-tests --example gpu -- cd --width 320 --height 240 --spp 16 --out cd.png
//! ```

use std::time::Instant;

use diffraction::color::{Clip, Xyz};
use diffraction::glam::{DVec2, DVec3};
use diffraction::gpu::{
    bsdf_bindings, GpuEfficiencyTables, BSDF_WGSL, KERNEL_WGSL, TABULATED_WGSL, TYPES_WGSL,
};
use diffraction::relief::Preset;
use diffraction::spectrum::Illuminant;
use diffraction::{Bsdf, DiffractionBrdf, GratingBsdf, GrooveSpread};
use rayon::prelude::*;
use wgpu::util::DeviceExt;

use crate::compare::difference;
use crate::output::{png_to, to_rgb8, Image};

const USAGE: &str = "\
gpu cd: the CD preset (rigorous efficiencies) with the library's tabulated BSDF in WGSL, and the
same estimator on the CPU

USAGE:
    gpu cd [--width W] [--height H] [--spp S] [--lambdas K] [--out FILE] [--no-reference]
";

/// The demo's settings.
#[derive(Debug, Clone)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub lambdas: u32,
    pub out: Option<String>,
    pub reference: bool,
}

impl Default for Settings {
    fn default() -> Settings {
        Settings {
            width: 320,
            height: 240,
            spp: 32,
            lambdas: 16,
            out: Some("cd.png".into()),
            reference: true,
        }
    }
}

/// Parses the command line after `cd`; `Ok(None)` for `--help`.
pub fn parse(args: &[String]) -> Result<Option<Settings>, String> {
    let mut s = Settings::default();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| -> Result<u32, String> {
            let v = it.next().ok_or(format!("{name} needs a value"))?;
            match v.parse::<u32>() {
                Ok(n) if (1..=4096).contains(&n) => Ok(n),
                _ => Err(format!("{name} {v}: must be an integer in 1..=4096")),
            }
        };
        match a.as_str() {
            "--width" => s.width = value("--width")?,
            "--height" => s.height = value("--height")?,
            "--spp" => s.spp = value("--spp")?,
            "--lambdas" => s.lambdas = value("--lambdas")?,
            "--out" => s.out = Some(it.next().ok_or("--out needs a value")?.clone()),
            "--no-reference" => s.reference = false,
            "--help" | "-h" => {
                print!("{USAGE}");
                return Ok(None);
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    Ok(Some(s))
}

/// The scene (centimetres): camera, disk light, sky, the disc's radii, albedos.
struct Scene {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    light: DVec3,
    light_radius: f64,
    intensity: f64,
    sky: (f64, f64),
    disc: [f64; 4],
    albedo: [f64; 2],
}

fn scene(s: &Settings) -> Scene {
    let eye = DVec3::new(0.0, 9.0, 14.0);
    let forward = (DVec3::new(0.0, 0.0, -0.5) - eye).normalize();
    let tan = (20.0f64).to_radians().tan();
    let right = forward.cross(DVec3::Y).normalize() * tan * s.width as f64 / s.height as f64;
    let up = right.cross(forward).normalize() * tan;
    Scene {
        eye,
        forward,
        right,
        up,
        light: DVec3::new(0.0, 12.0, -10.0),
        light_radius: 3.0,
        intensity: 250.0,
        sky: (0.05, 0.01),
        disc: [0.75, 2.3, 5.8, 6.0],
        albedo: [0.12, 0.35],
    }
}

/// The CMFs times D65 at 360..830 nm (1 nm), Y summing to 1, as f32 rows (x, y, z, 0).
fn cmf_rows() -> Vec<[f32; 4]> {
    let rows: Vec<[f64; 3]> = (0..471)
        .map(|i| {
            let l = 360.0 + i as f64;
            let c = diffraction::cie::cmf(l);
            let p = Illuminant::D65.power(l);
            [c[0] * p, c[1] * p, c[2] * p]
        })
        .collect();
    let y: f64 = rows.iter().map(|r| r[1]).sum();
    rows.iter()
        .map(|r| [(r[0] / y) as f32, (r[1] / y) as f32, (r[2] / y) as f32, 0.0])
        .collect()
}

/// The model: the CD preset read conically (`GratingBsdf::preset`'s default, its table
/// `Preset::conical_table`), 34 coherent grooves, a Gaussian groove spread σ = 0.02.
pub fn model() -> GratingBsdf {
    GratingBsdf::preset(Preset::Cd, 34)
        .expect("the preset builds")
        .with_groove(GrooveSpread::gaussian(0.02).expect("σ = 0.02 is valid"))
}

fn hash(x: u32) -> u32 {
    let v = x.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let w = ((v >> ((v >> 28) + 4)) ^ v).wrapping_mul(277_803_737);
    (w >> 22) ^ w
}

/// cd.wgsl's `cd_rand`.
fn rand(seed: u32, pixel: u32, s: u32, d: u32) -> f64 {
    let h = hash(
        pixel
            ^ hash(
                s.wrapping_mul(2_654_435_769)
                    .wrapping_add(d.wrapping_mul(2_246_822_519))
                    .wrapping_add(seed),
            ),
    );
    ((h >> 8) as f32 / 16_777_216.0) as f64
}

const SEED: u32 = 7;

/// The CPU twin of `cd_main`: XYZ per pixel, and the number of BSDF calls.
fn render_cpu(st: &Settings, sc: &Scene, b: &GratingBsdf, rows: &[[f32; 4]]) -> (Vec<DVec3>, u64) {
    let row = |l: f64| {
        let r = rows[((l - 360.0) as usize).min(470)];
        DVec3::new(r[0] as f64, r[1] as f64, r[2] as f64)
    };
    let white: DVec3 = rows
        .iter()
        .map(|r| DVec3::new(r[0] as f64, r[1] as f64, r[2] as f64))
        .sum();
    let sky = |d: DVec3| {
        let y = d.y.max(0.0);
        sc.sky.1 + (sc.sky.0 - sc.sky.1) * y * y
    };
    let k_count = st.lambdas;
    let (w, h) = (st.width, st.height);
    let results: Vec<(DVec3, u64)> = (0..w * h)
        .into_par_iter()
        .map(|pixel| {
            let (px, py) = ((pixel % w) as f64, (pixel / w) as f64);
            let mut sum = DVec3::ZERO;
            let mut calls = 0u64;
            for s in 0..st.spp {
                let r = |d: u32| rand(SEED, pixel, s, d);
                let sx = 2.0 * (px + r(0)) / w as f64 - 1.0;
                let sy = 1.0 - 2.0 * (py + r(1)) / h as f64;
                let dir = (sc.forward + sx * sc.right + sy * sc.up).normalize();
                if dir.y >= 0.0 {
                    sum += sky(dir) * white;
                    continue;
                }
                let p = sc.eye + (-sc.eye.y / dir.y) * dir;
                let rad = DVec2::new(p.x, p.z).length();
                let wo_w = -dir;
                let axis = (sc.light - p).normalize();
                let pick = if axis.x.abs() > 0.9 {
                    DVec3::Z
                } else {
                    DVec3::X
                };
                let e1 = axis.cross(pick).normalize();
                let e2 = axis.cross(e1);
                let (lr, lphi) = (sc.light_radius * r(2).sqrt(), std::f64::consts::TAU * r(3));
                let q = sc.light + lr * (lphi.cos() * e1 + lphi.sin() * e2);
                let dl = q - p;
                let dist2 = dl.length_squared();
                let wi_w = dl / dist2.sqrt();
                let irradiance = sc.intensity * wi_w.y.max(0.0) / dist2;
                if rad < sc.disc[1] || rad > sc.disc[2] {
                    let on_disc = rad > sc.disc[0] && rad <= sc.disc[3];
                    let albedo = if on_disc { sc.albedo[1] } else { sc.albedo[0] };
                    sum += (albedo / std::f64::consts::PI) * irradiance * white;
                    continue;
                }
                let tx = DVec3::new(p.x / rad, 0.0, p.z / rad);
                let ty = DVec3::Y.cross(tx);
                let local = |v: DVec3| DVec3::new(v.dot(tx), v.dot(ty), v.y);
                let (wo, wi) = (local(wo_w), local(wi_w));
                let xi_l = r(4);
                for k in 0..k_count {
                    let l = 360.0 + 470.0 * (k as f64 + xi_l) / k_count as f64;
                    let f = b.eval(wo, wi, l);
                    sum += (f * irradiance * 470.0 / k_count as f64) * row(l);
                }
                let lh = 360.0 + 470.0 * r(5);
                if let Some(smp) = b.sample(wo, lh, r(6), DVec2::new(r(7), r(8))) {
                    let d = smp.wi.x * tx + smp.wi.y * ty + smp.wi.z * DVec3::Y;
                    let weight = smp.f * smp.wi.z / smp.pdf;
                    sum += (weight * sky(d) * 470.0) * row(lh);
                }
                calls += k_count as u64 + 1;
            }
            (sum / st.spp as f64, calls)
        })
        .collect();
    let calls = results.iter().map(|r| r.1).sum();
    (results.into_iter().map(|r| r.0).collect(), calls)
}

/// Renders on the first adapter.
fn render_gpu(
    st: &Settings,
    sc: &Scene,
    b: &GratingBsdf,
    rows: &[[f32; 4]],
) -> Result<GpuFrame, String> {
    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .map_err(|e| format!("no GPU adapter ({e}); apt-get install mesa-vulkan-drivers"))?;
    let name = adapter.get_info().name;
    let (device, queue) = pollster::block_on(adapter.request_device(&Default::default()))
        .map_err(|e| format!("GPU device: {e}"))?;
    let source = [
        TYPES_WGSL,
        KERNEL_WGSL,
        &bsdf_bindings(0, 5),
        BSDF_WGSL,
        TABULATED_WGSL,
        include_str!("cd.wgsl"),
    ]
    .join("\n");
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("cd"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("cd"),
        layout: None,
        module: &module,
        entry_point: Some("cd_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let start = Instant::now();
    // The table the model reads (the preset's conical one), packed, and the model's constants.
    let mut tables = GpuEfficiencyTables::default();
    let g = tables.push_bsdf(b, 0).map_err(|e| e.to_string())?;
    let v4 = |v: DVec3, w: f64| [v.x as f32, v.y as f32, v.z as f32, w as f32];
    let mut params: Vec<u8> = Vec::new();
    for w in [st.width, st.height, st.spp, st.lambdas] {
        params.extend_from_slice(&w.to_le_bytes());
    }
    for v in [
        v4(sc.eye, 0.0),
        v4(sc.forward, 0.0),
        v4(sc.right, 0.0),
        v4(sc.up, 0.0),
        v4(sc.light, sc.light_radius),
        [sc.intensity as f32, sc.sky.0 as f32, sc.sky.1 as f32, 0.0],
        sc.disc.map(|x| x as f32),
        [sc.albedo[0] as f32, sc.albedo[1] as f32, 0.0, 0.0],
    ] {
        for x in v {
            params.extend_from_slice(&x.to_le_bytes());
        }
    }
    for w in [SEED, 0, 0, 0] {
        params.extend_from_slice(&w.to_le_bytes());
    }
    let cmf: Vec<u8> = rows
        .iter()
        .flatten()
        .flat_map(|x| x.to_le_bytes())
        .collect();
    let init = |bytes: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes,
            usage: wgpu::BufferUsages::STORAGE,
        })
    };
    let inputs = [
        init(&params),
        init(&g.to_bytes()),
        init(&tables.to_bytes()),
        init(&cmf),
    ];
    let pixels = (st.width * st.height) as u64;
    let out = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 16 * pixels,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: 16 * pixels,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut entries: Vec<wgpu::BindGroupEntry> = inputs
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    entries.push(wgpu::BindGroupEntry {
        binding: 4,
        resource: out.as_entire_binding(),
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: None,
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let upload_s = start.elapsed().as_secs_f64();
    // Twice: the first dispatch includes the driver's compilation (lavapipe compiles lazily).
    let mut secs = [0.0f64; 2];
    let mut bytes = Vec::new();
    for t in &mut secs {
        let start = Instant::now();
        let mut enc = device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, &group, &[]);
            pass.dispatch_workgroups(pixels.div_ceil(64) as u32, 1, 1);
        }
        enc.copy_buffer_to_buffer(&out, 0, &read, 0, 16 * pixels);
        queue.submit([enc.finish()]);
        read.slice(..)
            .map_async(wgpu::MapMode::Read, |r| r.expect("map"));
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| format!("GPU poll: {e}"))?;
        bytes = read
            .slice(..)
            .get_mapped_range()
            .map_err(|e| format!("GPU read-back: {e:?}"))?
            .to_vec();
        read.unmap();
        *t = start.elapsed().as_secs_f64() + upload_s;
    }
    let f: Vec<f32> = bytes
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let xyz = f
        .chunks_exact(4)
        .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
        .collect();
    Ok(GpuFrame {
        xyz,
        first_s: secs[0],
        s: secs[1],
        adapter: name,
    })
}

/// A frame from the device: XYZ per pixel, the seconds of the first dispatch (with the
/// driver's compilation) and of the second (each with the upload and the read-back).
struct GpuFrame {
    xyz: Vec<DVec3>,
    first_s: f64,
    s: f64,
    adapter: String,
}

/// XYZ to the linear sRGB image, times the exposure.
fn image(st: &Settings, xyz: &[DVec3], exposure: f64) -> Image {
    Image {
        width: st.width,
        height: st.height,
        pixels: xyz
            .iter()
            .map(|c| {
                let s = Xyz::new(c.x, c.y, c.z).to_linear_srgb();
                DVec3::new(s.r, s.g, s.b) * exposure
            })
            .collect(),
    }
}

/// The exposure of the pictures.
const EXPOSURE: f64 = 1.5;

/// What `render` measured.
pub struct Report {
    /// The GPU's picture (linear sRGB, exposed).
    pub gpu: Image,
    /// The CPU's, with `--no-reference` none.
    pub cpu: Option<Image>,
    /// The adapter's name.
    pub adapter: String,
    /// Seconds of the GPU frame (upload, dispatch, read-back): the first (with the driver's
    /// compilation) and the second.
    pub gpu_first_s: f64,
    pub gpu_s: f64,
    /// Seconds of the CPU frame (rayon on every core).
    pub cpu_s: f64,
    /// BSDF calls of the frame (f at each wavelength and one sample per grating hit).
    pub calls: u64,
    /// ΔE2000 between the two pictures.
    pub difference: Option<crate::compare::Difference>,
}

/// Renders the CD on the GPU and (unless `--no-reference`) on the CPU.
pub fn render(st: &Settings) -> Result<Report, String> {
    let sc = scene(st);
    let b = model();
    let rows = cmf_rows();
    let g = render_gpu(st, &sc, &b, &rows)?;
    let gpu = image(st, &g.xyz, EXPOSURE);
    let mut report = Report {
        gpu,
        cpu: None,
        adapter: g.adapter,
        gpu_first_s: g.first_s,
        gpu_s: g.s,
        cpu_s: 0.0,
        calls: 0,
        difference: None,
    };
    if st.reference {
        let start = Instant::now();
        let (cpu_xyz, calls) = render_cpu(st, &sc, &b, &rows);
        report.cpu_s = start.elapsed().as_secs_f64();
        report.calls = calls;
        let cpu = image(st, &cpu_xyz, EXPOSURE);
        report.difference = Some(difference(&report.gpu, &cpu, Clip::Clamp));
        report.cpu = Some(cpu);
    }
    Ok(report)
}

/// Renders and reports; the PNG of the GPU picture to `--out`.
pub fn run(st: &Settings) -> Result<(), String> {
    let r = render(st)?;
    if let Some(path) = &st.out {
        let mut file = std::fs::File::create(path).map_err(|e| format!("{path}: {e}"))?;
        png_to(&mut file, &to_rgb8(&r.gpu, Clip::Clamp))?;
    }
    println!(
        "cd: {}x{}, {} spp, {} wavelengths per light sample, on {}: GPU frame {:.1} ms \
         (upload, dispatch, read-back; the first {:.1} ms with the driver's compilation)",
        st.width,
        st.height,
        st.spp,
        st.lambdas,
        r.adapter,
        r.gpu_s * 1e3,
        r.gpu_first_s * 1e3
    );
    if let Some(d) = r.difference {
        let per = |s: f64| s / (r.calls as f64 / 1e6) * 1e3;
        println!(
            "cd: {} BSDF calls (f at each wavelength, one sample per grating hit); GPU {:.1} ms \
             per million, CPU {:.1} ms per million ({} threads, frame {:.2} s); mean ΔE2000 \
             {:.2e}, max {:.3}, {:.3}% of pixels above 1",
            r.calls,
            per(r.gpu_s),
            per(r.cpu_s),
            rayon::current_num_threads(),
            r.cpu_s,
            d.mean,
            d.max,
            d.above_one * 100.0
        );
    }
    Ok(())
}

/// `gpu cd ARGS`.
pub fn main(args: &[String]) -> Result<(), String> {
    match parse(args)? {
        Some(st) => run(&st),
        None => Ok(()),
    }
}
