//! Fig. 6 of Agu & Hill rendered headless on the GPU with the library's WGSL shading: the CD's
//! data area is shaded by `diffraction_shade_grating` (eq. 12 with the grating's colour table,
//! built on the CPU and uploaded as three buffers), everything else by `diffraction_shade`.
//! A simplified fig6 (examples/scenes/fig6.toml): no mirror reflections, a striped can instead
//! of the label image, hard shadows of the can only, one sample per pixel.
//!
//! `cargo run -p gpu-tests --example gpu -- [out.png]` (default `target/gpu_fig6.png`); any
//! wgpu adapter works, Mesa lavapipe included (`NODEVICE_SELECT=1` silences its warning).

use std::time::Instant;

use diffraction::gpu::{shading_source, GpuColorTable, GpuIllumination};
use diffraction::spectrum::{Illuminant, Spectral};
use diffraction::{ColorTable, Grating, Illumination};
use wgpu::util::DeviceExt;

const WIDTH: u32 = 480;
const HEIGHT: u32 = 360;

fn main() {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "target/gpu_fig6.png".to_string());

    // The CD's grating (fig6.toml: d = 1600 nm, w = 800 nm, N = 1000) under D65, its table, and
    // the exposure that makes its brightest diffracted colour Y = 1 (the CPU ray tracer's).
    let start = Instant::now();
    let grating = Grating::new(1600.0, 800.0, 1000).expect("grating");
    let spectral = Spectral::new(Illuminant::D65);
    let table = ColorTable::new(&spectral, &grating, 1e-3).expect("table");
    let from = 360.0 / grating.period_nm();
    let brightest = (0..4000)
        .map(|i| table.lookup(from + (2.0 - from) * i as f64 / 3999.0).y)
        .fold(0.0f64, f64::max);
    let exposure = if brightest > 0.0 {
        1.0 / brightest
    } else {
        1.0
    };
    let gpu_table = GpuColorTable::new(&table);
    println!(
        "table: {} nodes in {:.0} ms, exposure {exposure:.1}",
        table.node_count(),
        start.elapsed().as_secs_f64() * 1e3
    );

    let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
    let adapter = pollster::block_on(instance.request_adapter(&Default::default()))
        .expect("no GPU adapter (on Linux without a GPU: apt-get install mesa-vulkan-drivers)");
    println!("adapter: {}", adapter.get_info().name);
    let (device, queue) =
        pollster::block_on(adapter.request_device(&Default::default())).expect("device");

    let source = format!("{}\n{}", shading_source(1, 0), include_str!("scene.wgsl"));
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("fig6"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("fig6"),
        layout: None,
        module: &module,
        entry_point: Some("render"),
        compilation_options: Default::default(),
        cache: None,
    });

    // Params: width, height, exposure, pad, then the grating's eq. 12 coefficients (fig6's
    // grating material: k_a = k_d = 1 and the diffraction term 1).
    let k = GpuIllumination::from(&Illumination::new(1.0, 1.0, 1.0).expect("coefficients"));
    let mut params = Vec::with_capacity(32);
    params.extend_from_slice(&WIDTH.to_le_bytes());
    params.extend_from_slice(&HEIGHT.to_le_bytes());
    params.extend_from_slice(&(exposure as f32).to_le_bytes());
    params.extend_from_slice(&0f32.to_le_bytes());
    params.extend_from_slice(&k.to_bytes());
    let init = |bytes: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents: bytes,
            usage,
        })
    };
    let params = init(&params, wgpu::BufferUsages::UNIFORM);
    let size = (4 * WIDTH * HEIGHT) as u64;
    let pixels = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("pixels"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let read = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("read"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let header = init(&gpu_table.header_bytes(), wgpu::BufferUsages::UNIFORM);
    let blocks = init(&gpu_table.blocks_bytes(), wgpu::BufferUsages::STORAGE);
    let nodes = init(&gpu_table.nodes_bytes(), wgpu::BufferUsages::STORAGE);
    let group = |index: u32, buffers: &[&wgpu::Buffer]| {
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(index),
            entries: &buffers
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: b.as_entire_binding(),
                })
                .collect::<Vec<_>>(),
        })
    };
    let group0 = group(0, &[&params, &pixels]);
    let group1 = group(1, &[&header, &blocks, &nodes]);

    let start = Instant::now();
    let mut enc = device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group0, &[]);
        pass.set_bind_group(1, &group1, &[]);
        pass.dispatch_workgroups(WIDTH.div_ceil(8), HEIGHT.div_ceil(8), 1);
    }
    enc.copy_buffer_to_buffer(&pixels, 0, &read, 0, size);
    queue.submit([enc.finish()]);
    read.slice(..)
        .map_async(wgpu::MapMode::Read, |r| r.expect("map"));
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .expect("poll");
    let rgba = read.slice(..).get_mapped_range().expect("mapped").to_vec();
    println!(
        "rendered {WIDTH}x{HEIGHT} in {:.1} ms",
        start.elapsed().as_secs_f64() * 1e3
    );
    image::save_buffer(&out, &rgba, WIDTH, HEIGHT, image::ExtendedColorType::Rgba8)
        .expect("write the PNG");
    println!("wrote {out}");
}
