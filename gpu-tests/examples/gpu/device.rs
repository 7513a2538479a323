//! The shading half on the GPU: the G-buffer uploaded in chunks of whole pixels (each within
//! the device's storage binding limit), one compute dispatch per colour table over each chunk,
//! the pixels read back.

use std::sync::Arc;
use std::time::{Duration, Instant};

use diffraction::gpu::{shading_source, GpuColorTable, GpuIllumination};
use diffraction::ColorTable;
use wgpu::util::DeviceExt;

use crate::gbuffer::GBuffer;
use crate::output::Image;
use crate::whitted::PaperScene;

/// Bytes of one record in `shade.wgsl`.
const RECORD_BYTES: usize = 96;
/// Pixels of one dispatch: 65535 workgroups of 64.
const MAX_PIXELS: usize = 65535 * 64;

/// The device and the shading pipeline.
#[derive(Debug)]
pub struct Gpu {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::ComputePipeline,
    /// The adapter's name.
    pub name: String,
}

/// What a scene uploads once: its distinct colour tables, its materials and lights.
#[derive(Debug)]
pub struct Uploaded {
    /// Bind group 1 of each table.
    tables: Vec<wgpu::BindGroup>,
    materials: wgpu::Buffer,
    lights: wgpu::Buffer,
    light_count: u32,
    ambient: [f32; 3],
}

/// The distinct colour tables of `p` and each material's index among them (0 for materials
/// without one).
pub fn distinct_tables(p: &PaperScene) -> (Vec<Arc<ColorTable>>, Vec<u32>) {
    let mut tables: Vec<Arc<ColorTable>> = Vec::new();
    let index = p
        .tables
        .iter()
        .map(|t| match t {
            None => 0,
            Some(t) => match tables.iter().position(|u| Arc::ptr_eq(u, t)) {
                Some(i) => i as u32,
                None => {
                    tables.push(t.clone());
                    tables.len() as u32 - 1
                }
            },
        })
        .collect();
    (tables, index)
}

fn f32s(out: &mut Vec<u8>, v: &[f32]) {
    for x in v {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

fn vec4(out: &mut Vec<u8>, v: glam::DVec3, w: [u8; 4]) {
    f32s(out, &[v.x as f32, v.y as f32, v.z as f32]);
    out.extend_from_slice(&w);
}

impl Gpu {
    /// The first adapter wgpu finds and the pipeline compiled on it.
    pub fn new() -> Result<Gpu, String> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle());
        let adapter =
            pollster::block_on(instance.request_adapter(&Default::default())).map_err(|e| {
                format!(
                    "no GPU adapter ({e}); on Linux without a GPU: apt-get install \
                     mesa-vulkan-drivers (lavapipe)"
                )
            })?;
        let name = adapter.get_info().name;
        let (device, queue) = pollster::block_on(adapter.request_device(&Default::default()))
            .map_err(|e| format!("GPU device: {e}"))?;
        let source = format!("{}\n{}", shading_source(1, 0), include_str!("shade.wgsl"));
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("shade"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("shade"),
            layout: None,
            module: &module,
            entry_point: Some("shade"),
            compilation_options: Default::default(),
            cache: None,
        });
        Ok(Gpu {
            device,
            queue,
            pipeline,
            name,
        })
    }

    fn buffer(&self, bytes: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
        // wgpu refuses bindings shorter than one element (empty ones too): pad to 128 bytes.
        let mut padded = bytes.to_vec();
        padded.resize(bytes.len().max(128), 0);
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: None,
                contents: &padded,
                usage,
            })
    }

    fn group(&self, index: u32, buffers: &[&wgpu::Buffer]) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.pipeline.get_bind_group_layout(index),
            entries: &entries,
        })
    }

    /// Uploads `p`'s colour tables, materials (eq. 12's coefficients, exposure, table) and lights.
    pub fn upload(&self, p: &PaperScene) -> Uploaded {
        let (tables, index) = distinct_tables(p);
        let storage = wgpu::BufferUsages::STORAGE;
        let mut groups = Vec::new();
        for t in &tables {
            let g = GpuColorTable::new(t);
            let header = self.buffer(&g.header_bytes(), wgpu::BufferUsages::UNIFORM);
            let blocks = self.buffer(&g.blocks_bytes(), storage);
            let nodes = self.buffer(&g.nodes_bytes(), storage);
            groups.push(self.group(1, &[&header, &blocks, &nodes]));
        }
        if groups.is_empty() {
            // No grating: a one-node dummy table keeps the layout (never read).
            let header = self.buffer(&[0; 16], wgpu::BufferUsages::UNIFORM);
            let blocks = self.buffer(&[0; 32], storage);
            let nodes = self.buffer(&[0; 32], storage);
            groups.push(self.group(1, &[&header, &blocks, &nodes]));
        }
        let mut materials = Vec::new();
        for (i, m) in p.scene.materials.iter().enumerate() {
            materials.extend_from_slice(&GpuIllumination::from(&m.shading).to_bytes());
            f32s(&mut materials, &[p.exposures[i] as f32]);
            materials.extend_from_slice(&index[i].to_le_bytes());
            materials.extend_from_slice(&[0; 8]);
        }
        let mut lights = Vec::new();
        for l in &p.scene.lights {
            vec4(&mut lights, l.position, [0; 4]);
            vec4(&mut lights, l.color, [0; 4]);
        }
        let a = p.scene.units.ambient;
        Uploaded {
            tables: groups,
            materials: self.buffer(&materials, storage),
            lights: self.buffer(&lights, storage),
            light_count: p.scene.lights.len() as u32,
            ambient: [a.x as f32, a.y as f32, a.z as f32],
        }
    }

    /// Shades `g` with `scene`'s uploads: the linear image and the time from the first upload
    /// of the G-buffer to the last read-back.
    pub fn shade(&self, scene: &Uploaded, g: &GBuffer) -> (Image, Duration) {
        let start = Instant::now();
        let limit = (self.device.limits().max_storage_buffer_binding_size as usize)
            .min(self.device.limits().max_buffer_size as usize);
        let per_pixel_max = limit / RECORD_BYTES;
        let lights = scene.light_count as usize;
        let n = g.offsets.len() - 1;
        let mut pixels = Vec::with_capacity(n);
        let mut first = 0;
        while first < n {
            // Whole pixels while their records fit one binding (a pixel's own always do:
            // at most spp × (max_depth + 1) records).
            let mut last = first + 1;
            while last < n
                && g.offsets[last + 1] - g.offsets[first] <= per_pixel_max
                && last - first < MAX_PIXELS
            {
                last += 1;
            }
            pixels.extend(self.chunk(scene, g, first..last, lights));
            first = last;
        }
        let image = Image {
            width: g.base.width,
            height: g.base.height,
            pixels,
        };
        (image, start.elapsed())
    }

    /// Shades pixels `range` of `g`.
    fn chunk(
        &self,
        scene: &Uploaded,
        g: &GBuffer,
        range: std::ops::Range<usize>,
        lights: usize,
    ) -> Vec<glam::DVec3> {
        let (r0, r1) = (g.offsets[range.start], g.offsets[range.end]);
        let mut records = Vec::with_capacity((r1 - r0) * RECORD_BYTES);
        for r in &g.records[r0..r1] {
            vec4(&mut records, r.point, r.material.to_le_bytes());
            vec4(
                &mut records,
                r.normal,
                (r.grating.is_some() as u32).to_le_bytes(),
            );
            vec4(&mut records, r.wo, [0; 4]);
            vec4(&mut records, r.grating.unwrap_or_default(), [0; 4]);
            vec4(&mut records, r.albedo, [0; 4]);
            vec4(&mut records, r.weight, [0; 4]);
        }
        let mut offsets = Vec::new();
        for o in &g.offsets[range.start..=range.end] {
            offsets.extend_from_slice(&((o - r0) as u32).to_le_bytes());
        }
        let mut vis = Vec::new();
        f32s(&mut vis, &g.visibility[r0 * lights..r1 * lights]);
        let mut base = Vec::new();
        for c in &g.base.pixels[range.clone()] {
            vec4(&mut base, *c, [0; 4]);
        }
        let storage = wgpu::BufferUsages::STORAGE;
        let records = self.buffer(&records, storage);
        let offsets = self.buffer(&offsets, storage);
        let vis = self.buffer(&vis, storage);
        let size = base.len() as u64;
        let image = self.buffer(&base, storage | wgpu::BufferUsages::COPY_SRC);
        let read = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let count = range.len() as u32;
        let mut enc = self.device.create_command_encoder(&Default::default());
        let mut params = Vec::new();
        for (table, group1) in scene.tables.iter().enumerate() {
            params.clear();
            for x in [count, scene.light_count, table as u32, 0] {
                params.extend_from_slice(&x.to_le_bytes());
            }
            f32s(&mut params, &scene.ambient);
            params.extend_from_slice(&[0; 4]);
            let params = self.buffer(&params, wgpu::BufferUsages::UNIFORM);
            let group0 = self.group(
                0,
                &[
                    &params,
                    &records,
                    &offsets,
                    &vis,
                    &scene.materials,
                    &scene.lights,
                    &image,
                ],
            );
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &group0, &[]);
            pass.set_bind_group(1, group1, &[]);
            pass.dispatch_workgroups(count.div_ceil(64), 1, 1);
        }
        enc.copy_buffer_to_buffer(&image, 0, &read, 0, size);
        self.queue.submit([enc.finish()]);
        read.slice(..)
            .map_async(wgpu::MapMode::Read, |r| r.expect("map the pixels"));
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .expect("wait for the GPU");
        let bytes = read.slice(..).get_mapped_range().expect("mapped").to_vec();
        bytes
            .chunks_exact(16)
            .map(|c| {
                let f = |i: usize| f32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]) as f64;
                glam::DVec3::new(f(0), f(4), f(8))
            })
            .collect()
    }
}
