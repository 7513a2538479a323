//! The GPU renderer as a `run::Renderer`: the reference tracer's scene preparation with a
//! colour table per grating (`--filter point`), the G-buffer on the CPU, the shading on the
//! GPU, and the comparison with the reference tracer's picture.

use std::sync::OnceLock;
use std::time::Instant;

use crate::budget::{self, Estimate};
use crate::camera::Camera;
use crate::cli::{self, Options};
use crate::compare::{difference, Difference};
use crate::device::{Gpu, Uploaded};
use crate::footprint::{self, Filter};
use crate::model::{self, Paper};
use crate::output::Image;
use crate::scene::Scene;
use crate::whitted::{self, PaperScene};
use crate::{gbuffer, run};

/// The example's own arguments.
#[derive(Debug, Clone, PartialEq)]
pub struct Args {
    /// Render the reference picture and print ΔE2000 (not `--no-reference`).
    pub reference: bool,
}

impl Default for Args {
    fn default() -> Args {
        Args { reference: true }
    }
}

impl cli::Extra for Args {
    fn take(
        &mut self,
        arg: &str,
        _value: &mut dyn FnMut() -> Result<String, String>,
        _opts: &Options,
    ) -> Result<bool, String> {
        match arg {
            "--no-reference" => self.reference = false,
            _ => return Ok(false),
        }
        Ok(true)
    }
}

/// One frame's measurements.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// Seconds of the G-buffer on the CPU.
    pub gbuffer_s: f64,
    /// Records in it.
    pub records: usize,
    /// Seconds of the GPU: upload, shading, read-back.
    pub gpu_s: f64,
    /// Seconds of the reference tracer's picture, if rendered.
    pub reference_s: Option<f64>,
    /// ΔE2000 against it.
    pub difference: Option<Difference>,
}

/// The renderer: its device, made at the first scene prepared.
#[derive(Debug)]
pub struct GpuRenderer {
    gpu: OnceLock<Result<Gpu, String>>,
    reference: bool,
    quiet: bool,
    /// The last frame's measurements.
    pub last: std::sync::Mutex<Option<Frame>>,
}

impl GpuRenderer {
    /// A renderer comparing with the reference tracer when `reference`; `quiet`: no messages.
    pub fn new(reference: bool, quiet: bool) -> GpuRenderer {
        GpuRenderer {
            gpu: OnceLock::new(),
            reference,
            quiet,
            last: std::sync::Mutex::new(None),
        }
    }

    fn gpu(&self) -> Result<&Gpu, String> {
        self.gpu
            .get_or_init(Gpu::new)
            .as_ref()
            .map_err(Clone::clone)
    }

    /// Renders `p` from `camera`: the GPU's picture, the reference's if asked, the measurements.
    pub fn frame(
        &self,
        p: &Prepared,
        camera: &Camera,
        progress: Option<&str>,
    ) -> (Image, Option<Image>, Frame) {
        let gpu = self.gpu().expect("the device was made by prepare");
        let start = Instant::now();
        let g = gbuffer::trace(&p.scene, camera, progress);
        let gbuffer_s = start.elapsed().as_secs_f64();
        let (image, gpu_time) = gpu.shade(&p.uploaded, &g);
        let mut frame = Frame {
            gbuffer_s,
            records: g.records.len(),
            gpu_s: gpu_time.as_secs_f64(),
            reference_s: None,
            difference: None,
        };
        let reference = self.reference.then(|| {
            let start = Instant::now();
            let reference = whitted::render(&p.scene, camera, None);
            frame.reference_s = Some(start.elapsed().as_secs_f64());
            let clip = p.scene.scene.settings.clip;
            frame.difference = Some(difference(&image, &reference, clip));
            reference
        });
        (image, reference, frame)
    }
}

/// A scene prepared for the GPU: the reference tracer's preparation and the uploads.
#[derive(Debug)]
pub struct Prepared {
    /// The scene, exposures and colour tables.
    pub scene: PaperScene,
    uploaded: Uploaded,
}

impl run::Renderer for GpuRenderer {
    type Physics = Paper;
    type Prepared = Prepared;
    const OTHER: &'static str = "pathtrace";

    /// The reference tracer's preparation with `--filter point` (a colour table per distinct
    /// grating); a grating the tables do not cover is refused.
    fn prepare(&self, scene: Scene<Paper>, note: &dyn Fn(&str)) -> Result<Prepared, String> {
        for o in &scene.objects {
            if let Some(g) = &scene.materials[o.material].grating {
                if !footprint::tabulable(g) {
                    return Err(format!(
                        "{}: a grating of model {:?} with strategy {}: the GPU shades the \
                         paper's model from its colour table (a spectral --strategy, not paper)",
                        scene.name, g.model, g.strategy
                    ));
                }
            }
        }
        let gpu = self.gpu()?;
        let exposures = model::exposures(&scene.spectral, &scene.materials);
        let mut p = PaperScene {
            scene,
            exposures,
            filter: Filter::None,
            tables: Vec::new(),
        };
        let (n, took) = footprint::prepare(&mut p, Filter::Point)?;
        note(&format!(
            "{}: {n} colour table(s) built in {:.2} s; GPU: {}",
            p.scene.name,
            took.as_secs_f64(),
            gpu.name
        ));
        let uploaded = gpu.upload(&p);
        Ok(Prepared { scene: p, uploaded })
    }

    /// The reference tracer's rays twice (the G-buffer and the reference picture), the tables.
    fn estimate(&self, scene: &Scene<Paper>, frames: u32) -> Estimate {
        let s = &scene.settings;
        let samples = s.width as f64 * s.height as f64 * s.spp as f64 * frames as f64;
        let pilot = budget::pilot(scene, &scene.camera, true);
        let mut est = Estimate::default();
        let passes = if self.reference { 2.0 } else { 1.0 };
        budget::tracing(&mut est, samples * passes, &pilot, scene.objects.len());
        let mut tables = Vec::new();
        for g in scene.materials.iter().filter_map(|m| m.grating.as_ref()) {
            if !tables.contains(&g.model.integrand()) {
                tables.push(g.model.integrand());
            }
        }
        est.add(
            format!("{} colour tables", tables.len()),
            tables.len() as f64 * budget::TABLE_NS,
            "the number of distinct gratings",
        );
        est
    }

    fn scene<'a>(&self, p: &'a Prepared) -> &'a Scene<Paper> {
        &p.scene.scene
    }

    fn render(&self, p: &Prepared, camera: &Camera, progress: Option<&str>) -> Image {
        let (image, _, f) = self.frame(p, camera, progress);
        if !self.quiet {
            let s = &p.scene.scene.settings;
            let mut msg = format!(
                "{}: {}x{}, {} spp: G-buffer {:.3} s on the CPU ({} records), GPU shading \
                 {:.1} ms (upload, dispatch, read-back)",
                p.scene.scene.name,
                s.width,
                s.height,
                s.spp,
                f.gbuffer_s,
                f.records,
                f.gpu_s * 1e3
            );
            if let (Some(d), Some(t)) = (f.difference, f.reference_s) {
                msg += &format!(
                    "\n{}: mean ΔE2000 {:.2e} against the reference tracer (--filter point, \
                     {t:.2} s), max {:.3}, {:.2}% of pixels above 1",
                    p.scene.scene.name,
                    d.mean,
                    d.max,
                    d.above_one * 100.0
                );
            }
            println!("{msg}");
        }
        *self.last.lock().unwrap_or_else(|e| e.into_inner()) = Some(f);
        image
    }

    fn integrator(&self) -> &'static str {
        "whitted G-buffer + WGSL shading"
    }
}
