//! The example gpu's renderer on a paper scene: fig. 6 at 96×72 (the scene's 4 spp) rendered
//! with the G-buffer on the CPU and the WGSL shading on the device, against the reference
//! tracer's picture of the same samples with the same colour rule (`--filter point`); the mean
//! ΔE2000 over the picture is bounded by `gpu_tolerance::SCENE_MEAN_DELTA_E`.
//!
//! `harness = false` (Cargo.toml): the included modules' own unit tests are the root crate's
//! and are not run again here.
#![allow(dead_code, unused_imports)] // the included modules' test-only items

#[path = "../../tools/render/common/budget.rs"]
pub mod budget;
#[path = "../../tools/render/common/camera.rs"]
pub mod camera;
#[path = "../examples/gpu/cd.rs"]
pub mod cd;
#[path = "../../tools/render/common/cli.rs"]
pub mod cli;
#[path = "../../tools/render/common/colour.rs"]
pub mod colour;
#[path = "../examples/gpu/compare.rs"]
pub mod compare;
#[path = "../examples/gpu/device.rs"]
pub mod device;
#[path = "../../tools/render/common/diagnostics.rs"]
pub mod diagnostics;
#[path = "../../tools/render/common/files.rs"]
pub mod files;
#[path = "../../tools/render/common/font.rs"]
pub mod font;
#[path = "../../tools/render/raytrace/footprint.rs"]
pub mod footprint;
#[path = "../examples/gpu/gbuffer.rs"]
pub mod gbuffer;
#[path = "../../tools/render/common/geometry.rs"]
pub mod geometry;
#[path = "../../tests/support/gpu_tolerance.rs"]
mod gpu_tolerance;
#[path = "../../tools/render/common/limits.rs"]
pub mod limits;
#[path = "../../tools/render/common/material.rs"]
pub mod material;
#[path = "../../tools/render/raytrace/model.rs"]
pub mod model;
#[path = "../../tools/render/common/output.rs"]
pub mod output;
#[path = "../examples/gpu/renderer.rs"]
pub mod renderer;
#[path = "../../tools/render/common/run.rs"]
pub mod run;
#[path = "../../tools/render/common/sampling.rs"]
pub mod sampling;
#[path = "../../tools/render/common/scene.rs"]
pub mod scene;
#[path = "../../tools/render/common/schema.rs"]
pub mod schema;
#[path = "../../tools/render/common/texture.rs"]
pub mod texture;
#[path = "../../tools/render/raytrace/whitted.rs"]
pub mod whitted;

use run::Renderer;

fn main() {
    fig6_on_the_gpu_matches_the_reference_tracer();
    println!("test fig6_on_the_gpu_matches_the_reference_tracer ... ok");
    the_cd_preset_on_the_gpu_matches_the_cpu();
    println!("test the_cd_preset_on_the_gpu_matches_the_cpu ... ok");
}

/// The example's `gpu cd` (the CD preset with the tabulated BSDF in WGSL: f at stratified
/// wavelengths for a disk light, one BSDF sample toward the sky) against the same estimator on
/// the CPU with the same random numbers, at 48×36 and 4 spp.
fn the_cd_preset_on_the_gpu_matches_the_cpu() {
    let st = cd::Settings {
        width: 48,
        height: 36,
        spp: 4,
        lambdas: 8,
        out: None,
        reference: true,
    };
    let r = match cd::render(&st) {
        Ok(r) => r,
        Err(e) if std::env::var_os("CI").is_none() => {
            eprintln!("skipped: {e}");
            return;
        }
        Err(e) => panic!("{e}"),
    };
    let d = r.difference.expect("compared");
    eprintln!(
        "cd 48x36: {} BSDF calls, GPU {:.1} ms, CPU {:.1} ms, mean ΔE2000 {:.2e}, max {:.3}",
        r.calls,
        r.gpu_s * 1e3,
        r.cpu_s * 1e3,
        d.mean,
        d.max
    );
    let cpu = r.cpu.expect("rendered");
    assert_ne!(r.gpu.pixels, cpu.pixels);
    let bright = r
        .gpu
        .pixels
        .iter()
        .filter(|c| c.max_element() > 0.05)
        .count();
    assert!(bright > r.gpu.pixels.len() / 4, "{bright} bright pixels");
    assert!(r.calls > 10_000, "{} BSDF calls", r.calls);
    assert!(
        d.mean <= gpu_tolerance::CD_MEAN_DELTA_E,
        "mean ΔE2000 {:.2e} above {:.2e}",
        d.mean,
        gpu_tolerance::CD_MEAN_DELTA_E
    );
    assert!(
        d.max <= gpu_tolerance::CD_MAX_DELTA_E,
        "max ΔE2000 {}",
        d.max
    );
}

fn fig6_on_the_gpu_matches_the_reference_tracer() {
    if let Err(e) = device::Gpu::new() {
        if std::env::var_os("CI").is_some() {
            panic!("{e}");
        }
        eprintln!("skipped: {e}");
        return;
    }
    let mut scene = scene::load::<model::Paper>(&run::scenes_dir().join("fig6.toml"))
        .expect("the shipped fig6 loads");
    (scene.settings.width, scene.settings.height) = (96, 72);
    let r = renderer::GpuRenderer::new(true, true);
    let p = r.prepare(scene, &|_| {}).expect("prepared");
    let camera = p.scene.scene.camera;
    let (image, reference, frame) = r.frame(&p, &camera, None);
    let d = frame.difference.expect("compared");
    eprintln!(
        "fig6 96x72: {} records, GPU {:.1} ms, mean ΔE2000 {:.2e}, max {:.3}",
        frame.records,
        frame.gpu_s * 1e3,
        d.mean,
        d.max
    );
    // Not trivially equal: the GPU's f32 shading differs from the f64 reference somewhere,
    // and the picture is not black.
    let reference = reference.expect("rendered");
    assert_ne!(image.pixels, reference.pixels);
    let bright = image
        .pixels
        .iter()
        .filter(|c| c.max_element() > 0.2)
        .count();
    assert!(bright > image.pixels.len() / 4, "{bright} bright pixels");
    assert!(
        d.mean <= gpu_tolerance::SCENE_MEAN_DELTA_E,
        "mean ΔE2000 {:.2e} above {:.2e}",
        d.mean,
        gpu_tolerance::SCENE_MEAN_DELTA_E
    );
    assert!(
        d.max <= gpu_tolerance::SCENE_MAX_DELTA_E,
        "max ΔE2000 {}",
        d.max
    );
}
