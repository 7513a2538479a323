//! End-to-end tests of the tracer: determinism, the grating equation on screen, the mirror,
//! the CD's hues and scene-file errors. Small renders only (`cargo test --release`).

use std::path::Path;

use diffraction::color::{Clip, LinearSrgb};
use glam::DVec3;

use crate::geometry::Ray;
use crate::output;
use crate::render::{render, trace, Rng, Strata, MAX_STRATA_SAMPLES};
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
pub(crate) fn grating_scene() -> Scene {
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
        "test.toml: line 9, field objects[0].material.period_nm: expected a number in [10, 1e5], got -3"
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
    assert_eq!(
        e,
        "test.toml: line 8, field objects[0].material.period_nm: unknown field `period_nm`, \
         expected `color` (or one of ambient, diffuse, mirror, mirror_color)"
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
        "test.toml: line 11, field objects[0].material.lobe_width: expected a number in \
         [1e-6, 1], got 3"
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

/// Every cell of the stratification grid is reached, for every count, with the same
/// probability n / (cols·rows): no part of the pixel or of a disc light is skipped (the first-n
/// cells of a ⌈√n⌉ grid used to leave the last cells empty, e.g. one sector of the outer ring
/// of a disc light for the default 8 shadow samples).
#[test]
fn strata_reach_every_cell_with_equal_probability() {
    /// Sets drawn per count.
    const TRIALS: u32 = 4000;
    /// Allowed deviation of a cell's count from its binomial mean, in standard deviations:
    /// over the ~35000 cells checked, a fair sampler exceeds 5.5σ with probability ~1e-3.
    const SIGMAS: f64 = 5.5;
    let mut rng = Rng::new(11);
    for n in (1..=100).chain([255, 1000, 4095, MAX_STRATA_SAMPLES]) {
        let (cols, rows) = Strata::new(n, &mut rng).grid();
        let cells = (cols * rows) as usize;
        assert!(
            cells >= n as usize && cells - (n as usize) < cols as usize,
            "{n}"
        );
        let trials = if n > 100 { 200 } else { TRIALS };
        let mut counts = vec![0u32; cells];
        for _ in 0..trials {
            let mut strata = Strata::new(n, &mut rng);
            let mut seen = vec![false; cells];
            let mut k = 0;
            while let Some((cx, cy)) = strata.next_cell() {
                assert!(cx < cols && cy < rows, "{n}: cell ({cx}, {cy})");
                let c = (cy * cols + cx) as usize;
                assert!(!seen[c], "{n}: cell ({cx}, {cy}) twice in one set");
                seen[c] = true;
                counts[c] += 1;
                k += 1;
            }
            assert_eq!(k, n, "{n} samples");
        }
        let p = n as f64 / cells as f64;
        let (mean, sd) = (trials as f64 * p, (trials as f64 * p * (1.0 - p)).sqrt());
        for (c, &k) in counts.iter().enumerate() {
            assert!(k > 0, "{n}: cell {c} never sampled");
            assert!(
                (k as f64 - mean).abs() <= SIGMAS * sd.max(0.5),
                "{n}: cell {c} sampled {k} times, expected {mean} ± {sd}"
            );
        }
    }
    // The default 8 shadow samples: a 3 × 3 grid in (angle, r²); the outer ring's third sector
    // (column 2, row 2) is among the reached cells.
    let mut rng = Rng::new(3);
    let reached = (0..100).any(|_| {
        let mut s = Strata::new(8, &mut rng);
        std::iter::from_fn(|| s.next_cell()).any(|c| c == (2, 2))
    });
    assert!(reached);
}

// ------------------------------------------------------------------------------------------
// Bad input: values at the edges of their ranges render, values beyond them are refused with
// the field named, the loader's work and memory are bounded, and no output is lost.

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
        let img = render(&scene, &scene.camera, false, "");
        for p in &img.pixels {
            for v in p.to_array() {
                assert!(v.is_finite() && (v as f32).is_finite(), "{what}: {p:?}");
            }
        }
    }
}

/// Each class of bad value is refused with the file, the line and the field the user wrote.
#[test]
fn values_beyond_their_ranges_name_the_field() {
    let cases: [(&str, &str, &str, &str, &str, &str); 12] = [
        // Accepted before and rendered NaN.
        ("", "", "", "", "type = \"wood\"\nring_spacing = 5e-324",
         "line 19, field objects[0].material.ring_spacing: expected a number in [1e-6, 1e6], got 5e-324"),
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1600.0\ndiffraction = 1.7976931348623157e308",
         "line 20, field objects[0].material.diffraction: expected a number in [0, 1000], got 1.7976931348623157e308"),
        // Blamed another field.
        ("", "", "", "", "type = \"grating\"\nlines_per_mm = 1e-310",
         "line 19, field objects[0].material.lines_per_mm: expected a number in [10, 1e5], got 1e-310"),
        ("", "position = [1e308, 1e308, 1e308]\nlook_at = [0.0, 0.0, 0.0]", "", "", "type = \"diffuse\"",
         "line 7, field camera.position[0]: expected a number in [-1e6, 1e6], got 1e308"),
        ("", "up = [5e-324, 0.0, 0.0]", "", "", "type = \"diffuse\"",
         "line 9, field camera.up: expected a non-zero direction not parallel to the view direction, got [5e-324, 0.0, 0.0]"),
        // Hung the loader.
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1e12",
         "line 19, field objects[0].material.period_nm: expected a number in [10, 1e5], got 1e12"),
        ("", "", "", "", "type = \"grating\"\nlines_per_mm = 1e-6",
         "line 19, field objects[0].material.lines_per_mm: expected a number in [10, 1e5], got 1e-6"),
        // Unbounded work.
        ("strategy = \"uniform:4294967295\"", "", "", "", "type = \"diffuse\"",
         "line 5, field render.strategy: uniform:K takes at most 4096 wavelengths, got \"uniform:4294967295\""),
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1600.0\nstrategy = \"gauss:10000000\"",
         "line 20, field objects[0].material.strategy: gauss:K takes at most 512 intervals, got \"gauss:10000000\""),
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1600.0\nstrategy = \"auto:1e-12\"",
         "line 20, field objects[0].material.strategy: auto:ACCURACY takes an accuracy in [1e-6, 1], got \"auto:1e-12\""),
        ("", "", "samples = 1024\nradius = 1.0\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [1.0, 3.0, 2.0]\nradius = 1.0", "", "type = \"diffuse\"",
         "line 26, field lights[4]: the lights' shadow samples add up to 4104, more than the limit of 4096 rays from each hit"),
        ("width = 16384\nheight = 16384\nspp = 1", "", "", "", "type = \"diffuse\"",
         "line 3, field render.height: 16384 x 16384 = 268435456 pixels, more than the limit of 16777216"),
    ];
    for (render_, camera, light, object, material, expected) in cases {
        let src = one_object(render_, camera, light, object, material);
        assert_eq!(error_of(&src), format!("test.toml: {expected}"), "{src}");
    }
}

/// A fresh directory under the system's temporary directory.
fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("raytrace-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// CRC-32 (ISO-HDLC, as PNG uses), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// The loader reads, parses and decodes only bounded amounts: the file size before parsing,
/// the counts of objects and lights before deserialising, a texture's size from its header.
#[test]
fn scene_files_and_textures_are_bounded_before_they_are_read() {
    #[cfg(unix)]
    assert_eq!(
        scene::load(Path::new("/dev/zero")).unwrap_err().to_string(),
        "/dev/zero: the scene file is larger than the limit of 4194304 bytes"
    );
    let dir = scratch("bounded");
    let big = dir.join("big.toml");
    let mut src = String::from(MINIMAL);
    while src.len() <= 4 << 20 {
        src.push_str("# padding padding padding padding padding padding padding padding\n");
    }
    std::fs::write(&big, &src).unwrap();
    assert_eq!(
        scene::load(&big).unwrap_err().to_string(),
        format!(
            "{}: the scene file is larger than the limit of 4194304 bytes",
            big.display()
        )
    );
    let many = format!(
        "{MINIMAL}{}",
        "[[objects]]\nshape = \"cube\"\nmaterial = { type = \"diffuse\" }\n".repeat(10_001)
    );
    assert_eq!(
        error_of(&many),
        "test.toml: line 4, field objects: expected at most 10000 objects, got 10001"
    );
    // A 22000 x 22000 PNG header (the file itself is tiny): refused before decoding.
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend_from_slice(&22000u32.to_be_bytes());
    ihdr.extend_from_slice(&22000u32.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]); // 8-bit RGB
    png.extend_from_slice(&13u32.to_be_bytes());
    png.extend_from_slice(&ihdr);
    png.extend_from_slice(&crc32(&ihdr).to_be_bytes());
    for chunk in [&b"IDAT"[..], &b"IEND"[..]] {
        png.extend_from_slice(&0u32.to_be_bytes());
        png.extend_from_slice(chunk);
        png.extend_from_slice(&crc32(chunk).to_be_bytes());
    }
    std::fs::write(dir.join("huge.png"), &png).unwrap();
    let scene = format!(
        "{MINIMAL}[[objects]]\nshape = \"cylinder\"\n[objects.material]\ntype = \"image\"\nimage = \"huge.png\"\n"
    );
    let e = scene::parse(&scene, "test.toml", "test", &dir)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!(
            "test.toml: line 8, field objects[0].material.image: {}: 22000 x 22000 = 484000000 \
             pixels, more than the 16777216 left of the limit on texture pixels (the can label \
             is made by `raytrace make-label`)",
            dir.join("huge.png").display()
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// serde issue 2294: a unit variant of an internally tagged enum ignores
/// `deny_unknown_fields`. An unknown key is refused in every variant of every tagged table,
/// named with its path and line; a wrong type inside a tagged table names its key too.
#[test]
fn an_unknown_key_is_refused_in_every_variant() {
    let object = |material: &str| {
        format!("{MINIMAL}[[objects]]\nshape = \"quad\"\n[objects.material]\n{material}\n")
    };
    for kind in ["diffuse", "mirror", "wood", "image", "grating"] {
        let e = error_of(&object(&format!("type = \"{kind}\"\nbogus = 1")));
        assert!(
            e.starts_with(
                "test.toml: line 8, field objects[0].material.bogus: unknown field `bogus`, expected"
            ),
            "{kind}: {e}"
        );
    }
    for field in ["constant", "radial", "checkerboard"] {
        let e = error_of(&object(&format!(
            "{GRATING}[objects.material.field]\ntype = \"{field}\"\nbogus = 1"
        )));
        assert!(
            e.starts_with(
                "test.toml: line 11, field objects[0].material.field.bogus: unknown field `bogus`"
            ),
            "{field}: {e}"
        );
    }
    for tile in ["plain", "constant", "radial"] {
        let e = error_of(&object(&format!(
            "{GRATING}[objects.material.field]\ntype = \"checkerboard\"\nodd = {{ type = \"{tile}\", bogus = 1 }}"
        )));
        assert!(
            e.starts_with(
                "test.toml: line 11, field objects[0].material.field.odd.bogus: unknown field `bogus`"
            ),
            "{tile}: {e}"
        );
    }
    assert_eq!(
        error_of(&object("type = \"wood\"\nring_spacing = \"big\"")),
        "test.toml: line 8, field objects[0].material.ring_spacing: invalid type: string \"big\", \
         expected a number"
    );
    assert_eq!(
        error_of(&object(&format!(
            "{GRATING}[objects.material.field]\ntype = \"checkerboard\"\neven = {{ type = \"constant\", angle_deg = [1.0] }}"
        ))),
        "test.toml: line 11, field objects[0].material.field.even.angle_deg: invalid type: \
         sequence, expected a number"
    );
    assert_eq!(
        error_of(&object("type = \"glass\"")),
        "test.toml: line 7, field objects[0].material.type: unknown variant `glass`, expected one \
         of `diffuse`, `mirror`, `wood`, `image`, `grating`"
    );
    assert_eq!(
        error_of(&object("color = [1.0, 1.0, 1.0]")),
        "test.toml: line 6, field objects[0].material.type: missing field `type`"
    );
}

fn render_args(args: &str) -> crate::cli::Options {
    let args: Vec<String> = args.split_whitespace().map(String::from).collect();
    match crate::cli::parse(&args).unwrap() {
        crate::cli::Command::Render(o) => o,
        other => panic!("{other:?}"),
    }
}

/// The files of `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// No run destroys a file: two outputs on one file (also by two names) and unwritable paths are
/// refused before rendering, a failed write leaves the old file and no temporary, and a
/// successful one replaces it whole.
#[test]
fn an_existing_file_survives_a_failed_render() {
    let dir = scratch("outputs");
    let tiny = dir.join("tiny.toml");
    std::fs::write(&tiny, one_object("", "", "", "", GRATING)).unwrap();
    let old = b"an existing, valid file".to_vec();
    for name in ["a.png", "a.pfm"] {
        std::fs::write(dir.join(name), &old).unwrap();
    }
    let d = dir.display();
    let t = tiny.display();
    for (args, expected) in [
        (format!("{t} --out {d}/a.png --pfm {d}/a.png"), format!("{d}/a.png: expected a file name ending in .pfm")),
        (format!("{t} --out {d}/a.pfm --pfm {d}/sub/../a.pfm"), format!("{d}/a.pfm and {d}/sub/../a.pfm are the same file ({}): refusing to write two outputs on it", dir.canonicalize().unwrap().join("a.pfm").display())),
        (format!("{t} {t} --out {d}"), format!("{d}/tiny.png and {d}/tiny.png are the same file ({}): refusing to write two outputs on it", dir.canonicalize().unwrap().join("tiny.png").display())),
        (format!("{t} --out {d}/a.jpg"), format!("--out {d}/a.jpg: expected a file name ending in .png or .pfm, or a directory")),
        (format!("{t} --out {d}/a.png/b.png"), format!("{d}/a.png/b.png: cannot create the directory {d}/a.png: File exists (os error 17)")),
    ] {
        assert_eq!(crate::run(&render_args(&format!("{args} --quiet"))), Err(expected), "{args}");
    }
    #[cfg(target_os = "linux")]
    assert_eq!(
        crate::run(&render_args(&format!("{t} --out /dev/full --quiet"))),
        Err(
            "/dev/full: not a directory (give a directory, or one scene and a file name ending \
             in .png or .pfm)"
                .into()
        )
    );
    // A write that fails half-way keeps the old file and removes its temporary.
    let target = dir.join("a.png");
    let e = output::write_atomic(&target, |w| {
        w.write_all(b"partial").map_err(|e| e.to_string())?;
        Err("disk full".into())
    });
    assert_eq!(
        e,
        Err(format!("cannot write {}: disk full", target.display()))
    );
    assert_eq!(std::fs::read(&target).unwrap(), old);
    assert_eq!(listing(&dir), ["a.pfm", "a.png", "sub", "tiny.toml"]);
    // A run that succeeds replaces both files whole.
    let args = format!("{t} --out {d}/a.png --pfm {d}/a.pfm --quiet");
    assert_eq!(crate::run(&render_args(&args)), Ok(()));
    assert_eq!(image::open(&target).unwrap().to_rgb8().dimensions(), (8, 6));
    assert!(std::fs::read(dir.join("a.pfm"))
        .unwrap()
        .starts_with(b"PF\n8 6\n"));
    assert_eq!(listing(&dir), ["a.pfm", "a.png", "sub", "tiny.toml"]);
    let _ = std::fs::remove_dir_all(&dir);
}

/// An animation streams its frames into the GIF: every frame is in it, and each is written.
#[test]
fn an_animation_writes_every_frame_and_the_gif() {
    use image::AnimationDecoder;
    let dir = scratch("frames");
    let tiny = dir.join("tiny.toml");
    std::fs::write(&tiny, one_object("", "", "", "", GRATING)).unwrap();
    let out = dir.join("anim");
    let args = format!(
        "{} --frames 3 --out {} --quiet",
        tiny.display(),
        out.display()
    );
    assert_eq!(crate::run(&render_args(&args)), Ok(()));
    assert_eq!(
        listing(&out),
        [
            "tiny.gif",
            "tiny_0000.png",
            "tiny_0001.png",
            "tiny_0002.png"
        ]
    );
    let gif = std::io::BufReader::new(std::fs::File::open(out.join("tiny.gif")).unwrap());
    let frames = image::codecs::gif::GifDecoder::new(gif)
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 3);
    assert_eq!(frames[0].buffer().dimensions(), (8, 6));
    let _ = std::fs::remove_dir_all(&dir);
}
