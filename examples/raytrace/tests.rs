//! End-to-end tests of the tracer: determinism, the grating equation on screen, the mirror,
//! the CD's hues and scene-file errors. Small renders only (`cargo test --release`).

use std::path::Path;

use diffraction::color::{Clip, LinearSrgb};
use glam::DVec3;

use crate::geometry::Ray;
use crate::output;
use crate::render::{render, trace, Rng};
use crate::scene::{self, Scene};

fn parse(src: &str) -> Result<Scene, crate::diagnostics::SceneError> {
    scene::parse(src, "test.toml", "test", Path::new("."))
}

/// The clipped colour seen along the ray from `from` to `to`.
fn look(scene: &Scene, from: DVec3, to: DVec3) -> LinearSrgb {
    let c = trace(scene, &Ray::new(from, to - from), 0, &mut Rng::new(7));
    LinearSrgb::new(c.x, c.y, c.z).clip(Clip::Intensity)
}

fn shipped(name: &str) -> Scene {
    scene::load(&crate::scenes_dir().join(format!("{name}.toml"))).unwrap()
}

#[test]
fn a_fixed_seed_renders_the_same_bytes() {
    let mut scene = shipped("fig6"); // area light samples, an image texture, a CD and mirrors
    scene.settings.width = 48;
    scene.settings.height = 36;
    scene.settings.spp = 3;
    let a = render(&scene, &scene.camera, false, "");
    let b = render(&scene, &scene.camera, false, "");
    assert_eq!(a, b);
    assert_eq!(output::pfm_bytes(&a), output::pfm_bytes(&b));
    let png = |img| {
        let mut bytes = std::io::Cursor::new(Vec::new());
        output::to_rgb8(img, Clip::Intensity)
            .write_to(&mut bytes, image::ImageFormat::Png)
            .unwrap();
        bytes.into_inner()
    };
    assert_eq!(png(&a), png(&b));
    scene.settings.seed += 1;
    assert_ne!(
        render(&scene, &scene.camera, false, ""),
        a,
        "the seed changes the jitter"
    );
}

/// A 1000 lines/mm grating lying at the origin (normal +y, grating vector +x), lit from
/// straight above, nothing else lit.
fn grating_scene() -> Scene {
    parse(
        r#"
[camera]
position = [0.0, 10.0, 1.0]
look_at = [0.0, 0.0, 0.0]
[environment]
background = [0.0, 0.0, 0.0]
ambient = [0.0, 0.0, 0.0]
[[lights]]
position = [0.0, 100.0, 0.0]
[[objects]]
shape = "quad"
scale = 2.0
[objects.material]
type = "grating"
period_nm = 1000.0
slits = 1000
color = [0.0, 0.0, 0.0]
[objects.material.field]
type = "constant"
angle_deg = 0.0
"#,
    )
    .unwrap()
}

#[test]
fn the_first_order_lands_where_the_grating_equation_puts_it() {
    let scene = grating_scene();
    // wi = +y, so u = wo.x; d·u = λ puts the first order of λ at wo.x = λ/d.
    let seen = |lambda: f64| {
        let x = lambda / 1000.0;
        look(
            &scene,
            DVec3::new(x, (1.0 - x * x).sqrt(), 0.0) * 10.0,
            DVec3::ZERO,
        )
    };
    let green = seen(550.0);
    assert!(
        green.g > 2.0 * green.r && green.g > 2.0 * green.b,
        "{green:?}"
    );
    let red = seen(650.0);
    assert!(red.r > 2.0 * red.g && red.r > 2.0 * red.b, "{red:?}");
    let blue = seen(460.0);
    assert!(blue.b > blue.r && blue.b > blue.g, "{blue:?}");
    // Between the orders (u = 0.2: λ₁ = 200 nm, ultraviolet) the black plate stays dark.
    let dark = look(&scene, DVec3::new(0.2, 0.98, 0.0) * 10.0, DVec3::ZERO);
    assert!(dark.luminance() < 1e-3, "{dark:?}");
}

#[test]
fn the_mirror_shows_what_it_faces() {
    let scene = parse(
        r#"
[camera]
position = [0.0, 1.0, -3.0]
look_at = [0.0, 0.0, 0.0]
[environment]
background = [0.0, 0.0, 0.0]
ambient = [0.1, 0.1, 0.1]
[[lights]]
position = [0.0, 1.0, -2.0]
[[objects]]
shape = "quad"
scale = 4.0
[objects.material]
type = "mirror"
color = [0.0, 0.0, 0.0]
mirror = 1.0
[[objects]]
shape = "cube"
translate = [0.0, 1.0, 3.0]
[objects.material]
type = "diffuse"
color = [0.8, 0.05, 0.05]
"#,
    )
    .unwrap();
    // The reflected ray leaves the origin toward (0, 1/3, 1) and meets the red cube.
    let c = look(&scene, scene.camera.position, DVec3::ZERO);
    assert!(c.r > 0.2 && c.r > 5.0 * c.g && c.r > 5.0 * c.b, "{c:?}");
    // Beside the cube, the mirror shows the black sky.
    let c = look(&scene, scene.camera.position, DVec3::new(1.5, 0.0, 0.0));
    assert!(c.luminance() < 1e-6, "{c:?}");
}

fn hue_deg(c: LinearSrgb) -> Option<f64> {
    let max = c.r.max(c.g).max(c.b);
    let min = c.r.min(c.g).min(c.b);
    if max - min < 0.05 {
        return None;
    }
    let h = if max == c.r {
        (c.g - c.b) / (max - min)
    } else if max == c.g {
        2.0 + (c.b - c.r) / (max - min)
    } else {
        4.0 + (c.r - c.g) / (max - min)
    };
    Some((h * 60.0).rem_euclid(360.0))
}

#[test]
fn the_cd_shows_different_hues_around_its_centre() {
    let scene = parse(
        r#"
[camera]
position = [0.0, 1.7, 2.9]
look_at = [0.0, 0.0, 0.0]
[environment]
background = [0.0, 0.0, 0.0]
ambient = [0.0, 0.0, 0.0]
[[lights]]
position = [0.0, 3.0, -2.0]
[[objects]]
shape = "disc"
hole = 0.19
scale = 1.2
[objects.material]
type = "grating"
period_nm = 1600.0
slits = 1000
color = [0.0, 0.0, 0.0]
[objects.material.field]
type = "radial"
"#,
    )
    .unwrap();
    let hues: Vec<f64> = (0..180)
        .filter_map(|i| {
            let a = (i as f64 * 2.0).to_radians();
            // Between the hole and the rim (radius 0.6), at radius 0.45.
            let p = DVec3::new(0.45 * a.cos(), 0.0, 0.45 * a.sin());
            hue_deg(look(&scene, scene.camera.position, p))
        })
        .collect();
    let has = |lo: f64, hi: f64| hues.iter().any(|&h| h >= lo && h < hi);
    assert!(has(0.0, 30.0) || has(330.0, 360.0), "no red in {hues:?}");
    assert!(has(90.0, 150.0), "no green in {hues:?}");
    assert!(has(210.0, 270.0), "no blue in {hues:?}");
}

#[test]
fn every_shipped_scene_loads_and_renders() {
    for name in crate::scene_names() {
        let mut scene = shipped(&name);
        assert!(
            scene.materials.iter().any(|m| m.grating.is_some()),
            "{name} shows no grating"
        );
        for m in &scene.materials {
            if let (Some(g), None) = (&m.grating, &scene.radiometry) {
                assert!(g.exposure > 1.0, "{name}: exposure {}", g.exposure);
            }
        }
        scene.settings.width = 24;
        scene.settings.height = 18;
        scene.settings.spp = 1;
        let img = render(&scene, &scene.camera, false, "");
        assert!(img.pixels.iter().all(|p| p.is_finite()), "{name}");
    }
    assert_eq!(
        crate::scene_names(),
        ["cd_area_light", "fig4a", "fig4b", "fig5a", "fig5b", "fig6"]
    );
}

const MINIMAL: &str = "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";

fn error_of(src: &str) -> String {
    parse(src).unwrap_err().to_string()
}

#[test]
fn scene_errors_name_file_line_and_field() {
    let grating = |field: &str| {
        format!("{MINIMAL}\n[[objects]]\nshape = \"quad\"\n[objects.material]\ntype = \"grating\"\n{field}\n")
    };
    // Line 9 is the field's line in the text below.
    assert_eq!(
        error_of(&grating("period_nm = -3")),
        "test.toml: line 9, field objects[0].material.period_nm: expected a positive number, got -3"
    );
    // The crate's own validation, wrapped with the field path.
    assert_eq!(
        error_of(&grating("period_nm = 1600\nslit_width_nm = 2000")),
        "test.toml: line 10, field objects[0].material.slit_width_nm: invalid slit_width_nm = 2000: \
         must satisfy 0 < slit_width_nm <= period_nm (1600)"
    );
    assert_eq!(
        error_of(&grating("period_nm = 1600\nslits = 2000000000")),
        "test.toml: line 10, field objects[0].material.slits: expected an integer in [1, 1000000000], got 2000000000"
    );
    let e = error_of(&grating("period_nm = 1600\nstrategy = \"magic\""));
    assert!(
        e.starts_with("test.toml: line 10, field objects[0].material.strategy: unknown strategy"),
        "{e}"
    );
    // Typos and types are caught by the first stage, with the same details.
    let e = error_of(&grating("perod_nm = 1600"));
    assert!(
        e.starts_with(
            "test.toml: line 9, field objects[0].material.perod_nm: unknown field `perod_nm`"
        ),
        "{e}"
    );
    let e = error_of(&format!("[render]\nwidth = \"big\"\n{MINIMAL}"));
    assert!(e.starts_with("test.toml: line 2, field render.width: invalid type: string \"big\", expected a non-negative integer"), "{e}");
    assert_eq!(
        error_of(&format!("[render]\nwidth = 20000\n{MINIMAL}")),
        "test.toml: line 2, field render.width: expected an integer in [1, 16384], got 20000"
    );
    assert_eq!(
        error_of(&format!("[render]\nspp = 5000\n{MINIMAL}")),
        "test.toml: line 2, field render.spp: expected an integer in [1, 4096], got 5000"
    );
    let e = error_of(&format!("{MINIMAL}[[objects]]\nshape = \"cube\"\nscale = [1.0, 2.0]\n[objects.material]\ntype = \"diffuse\"\n"));
    assert!(
        e.starts_with(
            "test.toml: line 6, field objects[0].scale: expected a number or an array of 3 numbers"
        ),
        "{e}"
    );
    let e = error_of(&format!(
        "{MINIMAL}[[objects]]\nshape = \"sphere\"\n[objects.material]\ntype = \"diffuse\"\n"
    ));
    assert!(
        e.starts_with("test.toml: line 5, field objects[0].shape: expected one of"),
        "{e}"
    );
    // A field the material type does not use.
    let e = error_of(&format!("{MINIMAL}[[objects]]\nshape = \"cube\"\n[objects.material]\ntype = \"diffuse\"\nperiod_nm = 1600\n"));
    assert!(
        e.starts_with(
            "test.toml: line 8, field objects[0].material.period_nm: not used by type \"diffuse\""
        ),
        "{e}"
    );
    // A missing table and a syntax error.
    let e = error_of("[render]\nwidth = 10\n");
    assert_eq!(e, "test.toml: field camera: missing field `camera`");
    let e = error_of(&format!("{MINIMAL}[[lights]]\ncolor = [1.0, 1.0, 1.0]\n"));
    assert!(
        e.starts_with("test.toml: line 4, field lights[0].position: missing field `position`"),
        "{e}"
    );
    let e = error_of(&format!("{MINIMAL}[[lights]]\nposition = [1, 2\n"));
    assert!(e.starts_with("test.toml: line 5, invalid TOML"), "{e}");
    // A file that is not there.
    let e = scene::load(Path::new("no/such/scene.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("no/such/scene.toml: cannot read the scene file"),
        "{e}"
    );
}

/// The comparison of the models (examples/scenes/baselines/compare.toml): with the `stam`
/// feature it loads, every plate has its model, and each bay's plate shows its spectrum; without
/// it, the error names the feature.
#[test]
fn the_model_comparison_scene() {
    let path = crate::scenes_dir().join("baselines/compare.toml");
    #[cfg(feature = "stam")]
    {
        use crate::material::Model;
        let mut scene = scene::load(&path).unwrap();
        let models: Vec<&str> = scene
            .materials
            .iter()
            .filter_map(|m| m.grating.as_ref())
            .map(|g| match g.model {
                Model::AguHill(_) => "agu-hill",
                Model::Thorman(_) => "thorman",
                Model::Stam(_) => "stam",
                Model::Radiometric(_) => "radiometric",
            })
            .collect();
        assert_eq!(models, ["agu-hill", "thorman", "stam", "stam"]);
        scene.settings.width = 160;
        scene.settings.height = 60;
        scene.settings.spp = 1;
        let img = render(&scene, &scene.camera, false, "");
        assert!(img.pixels.iter().all(|p| p.is_finite()));
        // Every quarter of the picture (one bay each) holds a saturated diffracted colour.
        for bay in 0..4 {
            let brightest = (0..60)
                .flat_map(|y| (bay * 40..bay * 40 + 40).map(move |x| (x, y)))
                .map(|(x, y)| img.pixels[y * 160 + x])
                .map(|c| c.max_element())
                .fold(0.0, f64::max);
            assert!(brightest > 0.3, "bay {bay}: {brightest}");
        }
    }
    #[cfg(not(feature = "stam"))]
    {
        let e = scene::load(&path).unwrap_err().to_string();
        assert!(
            e.contains("model \"stam-sine\" needs the crate feature `stam`"),
            "{e}"
        );
    }
}

#[test]
fn grating_models_are_checked() {
    let grating = |fields: &str| {
        format!("{MINIMAL}\n[[objects]]\nshape = \"quad\"\n[objects.material]\ntype = \"grating\"\nperiod_nm = 1600\n{fields}\n")
    };
    assert_eq!(
        error_of(&grating("model = \"fourier\"")),
        "test.toml: line 10, field objects[0].material.model: expected one of \"agu-hill\", \
         \"thorman\", \"stam-sine\", \"stam-binary\", \"radiometric\", got \"fourier\""
    );
    assert_eq!(
        error_of(&grating("model = \"thorman\"\nslits = 100")),
        "test.toml: line 11, field objects[0].material.slits: not used by model \"thorman\" \
         (it takes lobe_width)"
    );
    assert_eq!(
        error_of(&grating("model = \"thorman\"\nlobe_width = 3.0")),
        "test.toml: line 11, field objects[0].material.lobe_width: invalid lobe_width = 3: \
         must satisfy 0 < lobe_width <= 1 (1)"
    );
    assert_eq!(
        error_of(&grating("depth_nm = 100")),
        "test.toml: line 10, field objects[0].material.depth_nm: not used by model \"agu-hill\" \
         (it takes slit_width_nm, slits)"
    );
    assert!(parse(&grating("model = \"thorman\"\nlobe_width = 0.01")).is_ok());
    #[cfg(feature = "stam")]
    {
        assert!(parse(&grating(
            "model = \"stam-binary\"\ndepth_nm = 120\nfraction = 0.3\ncoherence_nm = 9000"
        ))
        .is_ok());
        assert_eq!(
            error_of(&grating("model = \"stam-sine\"\ncoherence_nm = 100")),
            "test.toml: line 11, field objects[0].material.coherence_nm: invalid coherence_nm = \
             100: must satisfy coherence_nm >= period_nm (1600)"
        );
        assert_eq!(
            error_of(&grating("model = \"stam-sine\"\nfraction = 0.5")),
            "test.toml: line 11, field objects[0].material.fraction: not used by model \
             \"stam-sine\" (it takes depth_nm, coherence_nm, reflectance)"
        );
    }
}
