//! The paper's scenes (tools/render/scenes/*.toml: fig4a, fig4b, fig6, ...) with the library's WGSL
//! shading: the geometry on the CPU by the reference tracer's own code (`tools/render/common`, the
//! scene loader, the camera, ray casting, shadow rays and mirror recursion of
//! `tools/render/raytrace`), a G-buffer of every hit ([`gbuffer`]), and eq. 12 with each grating's
//! colour table on the GPU in one compute pass ([`device`], `shade.wgsl`). Each picture is
//! compared with the reference tracer's at the same size, samples and seed with the same
//! colour rule (`raytrace --filter point`: the colour table's lookup at each sample's u), and
//! the mean ΔE2000 printed with the frame time.
//!
//! ```text
//! cargo run --release -p gpu-tests --example gpu -- fig6 --width 480 --height 360 --out gpu.png
//! cargo run --release -p gpu-tests --example gpu -- --help
//! ```
//!
//! Any wgpu adapter works, Mesa lavapipe included (`NODEVICE_SELECT=1` silences its warning).

#[path = "../../../tools/render/common/budget.rs"]
pub mod budget;
#[path = "../../../tools/render/common/camera.rs"]
pub mod camera;
#[path = "../../../tools/render/common/cli.rs"]
pub mod cli;
#[path = "../../../tools/render/common/colour.rs"]
pub mod colour;
#[path = "../../../tools/render/common/diagnostics.rs"]
pub mod diagnostics;
#[path = "../../../tools/render/common/files.rs"]
pub mod files;
#[path = "../../../tools/render/common/font.rs"]
pub mod font;
#[path = "../../../tools/render/raytrace/footprint.rs"]
pub mod footprint;
#[path = "../../../tools/render/common/geometry.rs"]
pub mod geometry;
#[path = "../../../tools/render/common/limits.rs"]
pub mod limits;
#[path = "../../../tools/render/common/material.rs"]
pub mod material;
#[path = "../../../tools/render/raytrace/model.rs"]
pub mod model;
#[path = "../../../tools/render/common/output.rs"]
pub mod output;
#[path = "../../../tools/render/common/run.rs"]
pub mod run;
#[path = "../../../tools/render/common/sampling.rs"]
pub mod sampling;
#[path = "../../../tools/render/common/scene.rs"]
pub mod scene;
#[path = "../../../tools/render/common/schema.rs"]
pub mod schema;
#[path = "../../../tools/render/common/texture.rs"]
pub mod texture;
#[path = "../../../tools/render/raytrace/whitted.rs"]
pub mod whitted;

pub mod cd;
pub mod compare;
pub mod device;
pub mod gbuffer;
pub mod renderer;

use std::process::ExitCode;

use cli::{Command, Options};
use renderer::{Args, GpuRenderer};

const USAGE: &str = "\
gpu: the paper's scenes with the diffraction crate's WGSL shading (geometry on the CPU, by the
reference tracer's code; eq. 12 and the colour tables on the GPU), compared with the reference
tracer (raytrace --filter point) by the mean CIEDE2000 over the picture

USAGE:
    gpu [SCENE...] [OPTIONS]

    gpu cd [OPTIONS]     the CD preset with the tabulated BSDF in WGSL (gpu cd --help)

With no SCENE, renders every paper scene of tools/render/scenes into out/. SCENE is a shipped
scene's name (fig4a, fig4b, fig6, ...) or a path to a .toml scene file; its gratings must be
the paper's model with a spectral strategy (a colour table is built for each).

";

const OWN_OPTIONS: &str = "\
    --max-depth D      mirror recursion, 0-64
    --no-reference     do not render the reference picture (no ΔE2000)
";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("cd") {
        return match cd::main(&args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("error: {e}\n\nRun `gpu cd --help` for usage.");
                ExitCode::from(2)
            }
        };
    }
    let result = match cli::parse::<Args>(&args) {
        Err(e) => {
            eprintln!("error: {e}\n\nRun with --help for usage.");
            return ExitCode::from(2);
        }
        Ok(Command::Help) => {
            print!("{USAGE}{}{OWN_OPTIONS}{}", cli::OPTIONS, cli::OUTPUTS);
            Ok(())
        }
        Ok(Command::Render(opts, extra)) => {
            // An unknown scene is a usage error, like a bad option.
            if let Some(e) = opts.scenes.iter().find_map(|s| run::scene_path(s).err()) {
                eprintln!("error: {e}\n\nRun with --help for usage.");
                return ExitCode::from(2);
            }
            render(&opts, &extra)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

fn render(opts: &Options, extra: &Args) -> Result<(), String> {
    let r = GpuRenderer::new(extra.reference, opts.quiet);
    run::run(&r, opts)
}
