//! End-to-end tests of the paper's renderer: determinism, the grating equation on screen, the
//! mirror, the CD's hues, the models' scene errors and every value at the edge of its range.
//! Small renders only (`cargo test --release`).

use std::path::Path;

use diffraction::color::{Clip, LinearSrgb};
use glam::DVec3;

use crate::geometry::Ray;
use crate::model::Paper;
use crate::output;
use crate::run::{scene_names, scenes_dir, Renderer};
use crate::sampling::Rng;
use crate::scene::{self, Scene};
use crate::whitted::{trace, PaperScene};
use crate::Raytracer;

fn parse(src: &str) -> Result<Scene<Paper>, crate::diagnostics::SceneError> {
    scene::parse::<Paper>(src, "test.toml", "test", Path::new("."))
}

/// The scene prepared for rendering (exposures, no filter).
pub(crate) fn prepared(scene: Scene<Paper>) -> PaperScene {
    Raytracer::default().prepare(scene, &|_| ()).unwrap()
}

fn render(p: &PaperScene) -> output::Image {
    crate::whitted::render(p, &p.scene.camera, None)
}

/// The clipped colour seen along the ray from `from` to `to`.
fn look(p: &PaperScene, from: DVec3, to: DVec3) -> LinearSrgb {
    let c = trace(p, &Ray::new(from, to - from), None, 0, &mut Rng::new(7));
    LinearSrgb::new(c.x, c.y, c.z).clip(Clip::Intensity)
}

pub(crate) fn shipped(name: &str) -> Scene<Paper> {
    scene::load::<Paper>(&scenes_dir().join(format!("{name}.toml"))).unwrap()
}

#[test]
fn a_fixed_seed_renders_the_same_bytes() {
    let mut scene = shipped("fig6"); // area light samples, an image texture, a CD and mirrors
    scene.settings.width = 48;
    scene.settings.height = 36;
    scene.settings.spp = 3;
    let mut p = prepared(scene);
    let a = render(&p);
    let b = render(&p);
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
    p.scene.settings.seed += 1;
    assert_ne!(render(&p), a, "the seed changes the jitter");
}

/// A 1000 lines/mm grating lying at the origin (normal +y, grating vector +x), lit from
/// straight above, nothing else lit.
pub(crate) fn grating_scene() -> PaperScene {
    prepared(
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
        .unwrap(),
    )
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
    let scene = prepared(
        parse(
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
        .unwrap(),
    );
    // The reflected ray leaves the origin toward (0, 1/3, 1) and meets the red cube.
    let c = look(&scene, scene.scene.camera.position, DVec3::ZERO);
    assert!(c.r > 0.2 && c.r > 5.0 * c.g && c.r > 5.0 * c.b, "{c:?}");
    // Beside the cube, the mirror shows the black sky.
    let c = look(
        &scene,
        scene.scene.camera.position,
        DVec3::new(1.5, 0.0, 0.0),
    );
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
    let scene = prepared(
        parse(
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
        .unwrap(),
    );
    let hues: Vec<f64> = (0..180)
        .filter_map(|i| {
            let a = (i as f64 * 2.0).to_radians();
            // Between the hole and the rim (radius 0.6), at radius 0.45.
            let p = DVec3::new(0.45 * a.cos(), 0.0, 0.45 * a.sin());
            hue_deg(look(&scene, scene.scene.camera.position, p))
        })
        .collect();
    let has = |lo: f64, hi: f64| hues.iter().any(|&h| h >= lo && h < hi);
    assert!(has(0.0, 30.0) || has(330.0, 360.0), "no red in {hues:?}");
    assert!(has(90.0, 150.0), "no green in {hues:?}");
    assert!(has(210.0, 270.0), "no blue in {hues:?}");
}

#[test]
fn every_paper_scene_loads_and_renders() {
    let mut paper = Vec::new();
    for name in scene_names() {
        let path = scenes_dir().join(format!("{name}.toml"));
        let mut scene = match scene::load::<Paper>(&path) {
            Ok(scene) => scene,
            Err(e) => {
                // The scenes in physical units are the path tracer's, and say so.
                assert!(e.other_renderer, "{name}: {e}");
                assert_eq!(
                    e.to_string(),
                    format!(
                        "{}: line 28, field radiometry: a scene in physical units (a \
                         [radiometry] table) is the path tracer's",
                        path.display()
                    )
                );
                continue;
            }
        };
        assert!(
            scene.materials.iter().any(|m| m.grating.is_some()),
            "{name} shows no grating"
        );
        scene.settings.width = 24;
        scene.settings.height = 18;
        scene.settings.spp = 1;
        let p = prepared(scene);
        for (m, e) in p.scene.materials.iter().zip(&p.exposures) {
            if m.grating.is_some() {
                assert!(*e > 1.0, "{name}: exposure {e}");
            }
        }
        let img = render(&p);
        assert!(img.pixels.iter().all(|p| p.is_finite()), "{name}");
        paper.push(name);
    }
    assert_eq!(paper, ["fig4a", "fig4b", "fig5a", "fig5b", "fig6"]);
    // Rendering every shipped scene skips the path tracer's.
    let e = crate::run::run(
        &Raytracer::default(),
        &crate::cli::Options {
            scenes: vec!["cd_area_light".into()],
            quiet: true,
            ..Default::default()
        },
    )
    .unwrap_err();
    assert!(
        e.ends_with(
            "is the path tracer's: render it with `cargo run --release -p diffraction-render --bin pathtrace -- \
             cd_area_light`"
        ),
        "{e}"
    );
}

const MINIMAL: &str = "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";

fn error_of(src: &str) -> String {
    parse(src).unwrap_err().to_string()
}

/// The comparison of the models (tools/render/scenes/baselines/compare.toml): with the `stam`
/// feature it loads, every plate has its model, and each bay's plate shows its spectrum; without
/// it, the error names the feature.
#[test]
fn the_model_comparison_scene() {
    let path = scenes_dir().join("baselines/compare.toml");
    #[cfg(feature = "stam")]
    {
        use crate::model::Model;
        let mut scene = scene::load::<Paper>(&path).unwrap();
        let models: Vec<&str> = scene
            .materials
            .iter()
            .filter_map(|m| m.grating.as_ref())
            .map(|g| match g.model {
                Model::AguHill(_) => "agu-hill",
                Model::Thorman(_) => "thorman",
                Model::Stam(_) => "stam",
            })
            .collect();
        assert_eq!(models, ["agu-hill", "thorman", "stam", "stam"]);
        scene.settings.width = 160;
        scene.settings.height = 60;
        scene.settings.spp = 1;
        let img = render(&prepared(scene));
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
        let e = scene::load::<Paper>(&path).unwrap_err().to_string();
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
    // The crate's own validation, wrapped with the field path.
    assert_eq!(
        error_of(&grating("slit_width_nm = 2000")),
        "test.toml: line 10, field objects[0].material.slit_width_nm: invalid slit_width_nm = \
         2000: must satisfy 0 < slit_width_nm <= period_nm (1600)"
    );
    assert_eq!(
        error_of(&grating("slits = 2000000000")),
        "test.toml: line 10, field objects[0].material.slits: expected an integer in [1, \
         1000000000], got 2000000000"
    );
    assert_eq!(
        error_of(&grating("model = \"radiometric\"")),
        "test.toml: line 10, field objects[0].material.model: model \"radiometric\" needs a \
         [radiometry] table (the camera's exposure)"
    );
    assert_eq!(
        error_of(&grating("model = \"thorman\"\nlobe_width = 3.0")),
        "test.toml: line 11, field objects[0].material.lobe_width: expected a number in \
         [1e-6, 1], got 3"
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

// ------------------------------------------------------------------------------------------
// Bad input: values at the edges of their ranges render (the common tests refuse the values
// beyond them).

/// A scene of one lit object, with `extra` lines in `[render]`, `[camera]`, `[[lights]]`, the
/// object and its material.
/// A `camera` or `light` that starts with its own `position` replaces the default one.
fn one_object(render: &str, camera: &str, light: &str, object: &str, material: &str) -> String {
    let camera = if camera.starts_with("position") {
        camera.to_string()
    } else {
        format!("position = [0.0, 2.0, 3.0]\nlook_at = [0.0, 0.0, 0.0]\n{camera}")
    };
    let light = if light.starts_with("position") {
        light.to_string()
    } else {
        format!("position = [0.0, 3.0, -2.0]\n{light}")
    };
    let object = if object.contains("scale") {
        object.to_string()
    } else {
        format!("scale = 3.0\n{object}")
    };
    let render = if render.starts_with("width") {
        render.to_string()
    } else {
        format!("width = 8\nheight = 6\nspp = 1\n{render}")
    };
    format!(
        "[render]\n{render}\n\
         [camera]\n{camera}\n\
         [[lights]]\n{light}\n\
         [[objects]]\nshape = \"quad\"\n{object}\n\
         [objects.material]\n{material}\n"
    )
}

const GRATING: &str = "type = \"grating\"\nperiod_nm = 1600.0\n";

/// Every numeric value at both ends of its documented range loads and renders finite colours,
/// also as the 32-bit floats of the PFM.
#[test]
fn values_at_the_edges_of_their_ranges_render() {
    let g = |extra: &str| format!("{GRATING}{extra}");
    let field = |f: &str| format!("{GRATING}[objects.material.field]\n{f}");
    let m = |s: &str| s.to_string();
    let cases: Vec<(&str, String, String, String, String, String)> = vec![
        ("largest coordinates", m(""), m("position = [1e6, 1e6, 1e6]\nlook_at = [-1e6, -1e6, -1e6]\nup = [1e6, -1e6, 0.0]"), m("position = [-1e6, 1e6, 1e6]"), m("translate = [1e6, -1e6, 1e6]"), m("type = \"diffuse\"")),
        ("narrowest view", m(""), m("fov_deg = 0.01"), m(""), m(""), m(GRATING)),
        ("widest view", m(""), m("fov_deg = 179"), m(""), m(""), m(GRATING)),
        ("brightest light", m(""), m(""), m("color = [1e6, 1e6, 1e6]\nintensity = 1e6\nradius = 1e6\nsamples = 1024"), m(""), m(GRATING)),
        ("smallest light", m(""), m(""), m("radius = 1e-6\nsamples = 7"), m(""), m("type = \"diffuse\"")),
        ("extreme transform", m(""), m(""), m(""), m("rotate_deg = [360.0, -360.0, 360.0]\nscale = [1e-6, 1e6, 1e6]"), m("type = \"diffuse\"")),
        ("largest coefficients", m(""), m(""), m("intensity = 1e6"), m(""), g("color = [1e6, 1e6, 1e6]\nambient = 1e3\ndiffuse = 1e3\ndiffraction = 1e3\nmirror = 1.0\nmirror_color = [1e6, 1e6, 1e6]")),
        ("fine wood", m(""), m(""), m(""), m(""), m("type = \"wood\"\nring_spacing = 1e-6\nturbulence = 1e3\nplank_width = 1e-6\nplank_length = 1e-6\nlight = [1e6, 1e6, 1e6]")),
        ("coarse wood", m(""), m(""), m(""), m(""), m("type = \"wood\"\nring_spacing = 1e6\nturbulence = 0.0\nplank_width = 1e6\nplank_length = 1e6")),
        ("finest grating", m(""), m(""), m(""), m(""), m("type = \"grating\"\nperiod_nm = 10.0\nslit_width_nm = 1e-3\nslits = 1")),
        ("coarsest grating", m(""), m(""), m(""), m(""), m("type = \"grating\"\nperiod_nm = 1e5\nslits = 1000000000")),
        ("densest lines", m(""), m(""), m(""), m(""), m("type = \"grating\"\nlines_per_mm = 1e5")),
        ("sparsest lines", m(""), m(""), m(""), m(""), m("type = \"grating\"\nlines_per_mm = 10.0")),
        ("widest slits", m(""), m(""), m(""), m(""), g("slit_width_nm = 1600.0")),
        ("most wavelengths", m("strategy = \"uniform:4096\""), m(""), m(""), m(""), m(GRATING)),
        ("most intervals", m("strategy = \"gauss:512\""), m(""), m(""), m(""), m(GRATING)),
        ("finest auto", m(""), m(""), m(""), m(""), g("strategy = \"auto:1e-6\"")),
        ("turned field", m(""), m(""), m(""), m(""), field("type = \"constant\"\nangle_deg = -360.0\ntwist_deg = 360.0")),
        ("far radial centre", m(""), m(""), m(""), m(""), field("type = \"radial\"\ncenter = [1e6, -1e6]\ntwist_deg = -360.0")),
        ("finest checkerboard", m(""), m(""), m(""), m(""), field("type = \"checkerboard\"\ncell_size = 1e-6\nplain_color = [1e6, 0.0, 0.0]\neven = { type = \"radial\", center = [-1e6, 1e6], twist_deg = 360.0 }\nodd = { type = \"constant\", angle_deg = 360.0, twist_deg = -360.0 }")),
        ("coarsest checkerboard", m(""), m(""), m(""), m(""), field("type = \"checkerboard\"\ncell_size = 1e6\neven = { type = \"plain\" }")),
        ("narrowest Thorman lobe", m(""), m(""), m(""), m(""), g("model = \"thorman\"\nlobe_width = 1e-6")),
        ("widest Thorman lobe", m(""), m(""), m(""), m(""), g("model = \"thorman\"\nlobe_width = 1.0")),
    ];
    #[cfg(feature = "stam")]
    let cases = {
        let mut cases = cases;
        cases.push((
            "flat Stam",
            m(""),
            m(""),
            m(""),
            m(""),
            g("model = \"stam-sine\"\ndepth_nm = 0.0\nreflectance = 0.0"),
        ));
        cases.push(("deep Stam", m(""), m(""), m(""), m(""), g("model = \"stam-binary\"\ndepth_nm = 1e4\nfraction = 1.0\ncoherence_nm = 1e8\nreflectance = 1.0")));
        cases.push((
            "narrow Stam grooves",
            m(""),
            m(""),
            m(""),
            m(""),
            g("model = \"stam-binary\"\nfraction = 1e-6\ncoherence_nm = 1600.0"),
        ));
        cases
    };
    for (what, render_, camera, light, object, material) in &cases {
        let src = one_object(render_, camera, light, object, material);
        let scene = parse(&src).unwrap_or_else(|e| panic!("{what}: {e}"));
        let img = render(&prepared(scene));
        for p in &img.pixels {
            for v in p.to_array() {
                assert!(v.is_finite() && (v as f32).is_finite(), "{what}: {p:?}");
            }
        }
    }
}

#[test]
fn the_path_tracer_options_name_the_other_example() {
    let args = |s: &str| -> Vec<String> { s.split_whitespace().map(String::from).collect() };
    assert_eq!(
        crate::cli::parse::<crate::Args>(&args("cd_area_light --integrator path")),
        Err(
            "--integrator path: the path tracer is the binary pathtrace: cargo run --release \
             -p diffraction-render --bin pathtrace -- SCENE"
                .into()
        )
    );
    let Ok(crate::cli::Command::Render(o, a)) =
        crate::cli::parse::<crate::Args>(&args("fig6 --filter footprint --integrator whitted"))
    else {
        panic!()
    };
    assert_eq!(
        (o.scenes, a.filter),
        (
            vec!["fig6".to_string()],
            crate::footprint::Filter::Footprint
        )
    );
    let Ok(crate::cli::Command::Render(_, a)) =
        crate::cli::parse::<crate::Args>(&args("make-label"))
    else {
        panic!()
    };
    assert!(a.make_label);
}

/// At most 256 distinct gratings, each with its exposure scan: the 257th is refused where it
/// is written.
#[test]
fn at_most_256_distinct_gratings() {
    let mut src = String::from(MINIMAL);
    for i in 0..257 {
        src += &format!(
            "[[objects]]\nshape = \"quad\"\n[objects.material]\ntype = \"grating\"\nperiod_nm = {}\n",
            1000 + i
        );
    }
    assert_eq!(
        error_of(&src),
        "test.toml: line 1286, field objects[256].material: more than 256 distinct gratings (each \
         needs an exposure scan)"
    );
}
