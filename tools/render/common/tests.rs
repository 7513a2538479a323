//! Tests of the code both renderers share: scene files (keys, types, values, bounded loading),
//! the command line and the outputs of a run, through a renderer of flat colours (no
//! diffraction: `Flat` builds every grating model as its name and renders each pixel's
//! albedo), so that they test the shared code alone. Run by `raytrace`'s tests.

use std::path::Path;

use diffraction::spectrum::Spectral;
use glam::DVec3;

use crate::budget::{self, Estimate};
use crate::camera::{self, Camera, CameraRays};
use crate::cli::{self, Command, Options};
use crate::diagnostics::{Check, SceneError};
use crate::geometry::nearest;
use crate::material::Material;
use crate::output::Image;
use crate::run::Renderer;
use crate::scene::{self, Light, Physics, Scene};
use crate::schema::{RawGrating, RawScene};

/// Every grating model is its name; no units; every scene is taken.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Flat;

impl Physics for Flat {
    type Grating = String;
    type Units = ();
    fn accepts(_: &RawScene) -> Check<()> {
        Ok(())
    }
    fn grating(name: &str, _: &RawGrating, _: f64, _: &str) -> Check<String> {
        Ok(name.to_string())
    }
    fn units(_: &RawScene, _: &[Light], _: &[Material<String>], _: &Spectral) -> Check<()> {
        Ok(())
    }
}

impl Renderer for Flat {
    type Physics = Flat;
    type Prepared = Scene<Flat>;
    const OTHER: &'static str = "nothing";
    fn prepare(&self, scene: Scene<Flat>, _: &dyn Fn(&str)) -> Result<Scene<Flat>, String> {
        Ok(scene)
    }
    /// As a Whitted renderer: the pilot's rays and every light sample at every hit.
    fn estimate(&self, scene: &Scene<Flat>, frames: u32) -> Estimate {
        let s = &scene.settings;
        let samples = s.width as f64 * s.height as f64 * s.spp as f64 * frames as f64;
        let pilot = budget::pilot(scene, &scene.camera, true);
        let mut est = Estimate::default();
        budget::tracing(&mut est, samples, &pilot, scene.objects.len());
        est
    }

    fn scene<'a>(&self, scene: &'a Scene<Flat>) -> &'a Scene<Flat> {
        scene
    }
    /// The albedo of the nearest hit at each sample (black where nothing is hit).
    fn render(&self, scene: &Scene<Flat>, camera: &Camera, _: Option<&str>) -> Image {
        let s = &scene.settings;
        let rays = CameraRays::new(camera, s.width, s.height);
        let albedo = |c: &camera::CameraSample, _: &mut crate::sampling::Rng| {
            let ray = rays.ray(c.point.x, c.point.y);
            nearest(&scene.objects, &ray, f64::INFINITY).map_or(DVec3::ZERO, |h| {
                scene.materials[scene.objects[h.object].material]
                    .albedo
                    .at(&h)
            })
        };
        camera::render(s, 0, None, albedo, |sum| sum / s.spp as f64)
    }
    fn integrator(&self) -> &'static str {
        "flat"
    }
}

impl cli::Extra for () {
    fn take(
        &mut self,
        _: &str,
        _: &mut dyn FnMut() -> Result<String, String>,
        _: &Options,
    ) -> Result<bool, String> {
        Ok(false)
    }
}

fn parse(src: &str) -> Result<Scene<Flat>, SceneError> {
    scene::parse::<Flat>(src, "test.toml", "test", Path::new("."))
}

const MINIMAL: &str = "[camera]\nposition = [0.0, 1.0, 5.0]\nlook_at = [0.0, 0.0, 0.0]\n";

fn error_of(src: &str) -> String {
    parse(src).unwrap_err().to_string()
}

pub(crate) const GRATING: &str = "type = \"grating\"\nperiod_nm = 1600.0\n";

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
    // An integer field names its range whatever the value: beyond the type, negative, not an
    // integer.
    for (key, value, range) in [
        ("width", "\"big\"", "[1, 16384]"),
        ("width", "4294967296", "[1, 16384]"),
        ("height", "-1", "[1, 16384]"),
        ("spp", "1e3", "[1, 4096]"),
        ("max_depth", "18446744073709551616", "[0, 64]"),
        ("seed", "18446744073709551616", "[0, 18446744073709551615]"),
        ("seed", "-1", "[0, 18446744073709551615]"),
    ] {
        assert_eq!(
            error_of(&format!("[render]\n{key} = {value}\n{MINIMAL}")),
            format!("test.toml: line 2, field render.{key}: expected an integer in {range}, got {value}")
        );
    }
    assert_eq!(
        error_of(&format!("{MINIMAL}[[lights]]\nposition = [0.0, 1.0, 0.0]\nsamples = 4294967296\n")),
        "test.toml: line 6, field lights[0].samples: expected an integer in [1, 1024], got 4294967296"
    );
    for slits in [
        "18446744073709551616",
        "340282366920938463463374607431768211456",
        "-5",
        "2.5",
    ] {
        assert_eq!(
            error_of(&grating(&format!("period_nm = 1600\nslits = {slits}"))),
            format!("test.toml: line 10, field objects[0].material.slits: expected an integer in [1, 1000000000], got {slits}")
        );
    }
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
    // A field the material type does not use, a model that does not exist, a parameter of
    // another model.
    let e = error_of(&format!("{MINIMAL}[[objects]]\nshape = \"cube\"\n[objects.material]\ntype = \"diffuse\"\nperiod_nm = 1600\n"));
    assert_eq!(
        e,
        "test.toml: line 8, field objects[0].material.period_nm: unknown field `period_nm`, \
         expected `color` (or one of ambient, diffuse, mirror, mirror_color)"
    );
    assert_eq!(
        error_of(&grating("period_nm = 1600\nmodel = \"fourier\"")),
        "test.toml: line 10, field objects[0].material.model: expected one of \"agu-hill\", \
         \"thorman\", \"stam-sine\", \"stam-binary\", \"radiometric\", got \"fourier\""
    );
    assert_eq!(
        error_of(&grating(
            "period_nm = 1600\nmodel = \"thorman\"\nslits = 100"
        )),
        "test.toml: line 11, field objects[0].material.slits: not used by model \"thorman\" \
         (it takes lobe_width)"
    );
    assert_eq!(
        error_of(&grating("period_nm = 1600\ndepth_nm = 100")),
        "test.toml: line 10, field objects[0].material.depth_nm: not used by model \"agu-hill\" \
         (it takes slit_width_nm, slits)"
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
    let e = scene::load::<Flat>(Path::new("no/such/scene.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("no/such/scene.toml: cannot read the scene file"),
        "{e}"
    );
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
        ("strategy = \"uniform:99999999999999999999999\"", "", "", "", "type = \"diffuse\"",
         "line 5, field render.strategy: uniform:K takes at most 4096 wavelengths, got \"uniform:99999999999999999999999\""),
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1600.0\nstrategy = \"gauss:10000000\"",
         "line 20, field objects[0].material.strategy: gauss:K takes at most 512 intervals, got \"gauss:10000000\""),
        ("", "", "", "", "type = \"grating\"\nperiod_nm = 1600.0\nstrategy = \"auto:1e-12\"",
         "line 20, field objects[0].material.strategy: auto accuracy 1e-12 is out of range: expected 1e-6 to 1, got \"auto:1e-12\""),
        ("", "", "samples = 1024\nradius = 1.0\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [0.0, 3.0, 2.0]\nradius = 1.0\nsamples = 1024\n[[lights]]\nposition = [1.0, 3.0, 2.0]\nradius = 1.0", "", "type = \"diffuse\"",
         "line 26, field lights[4]: the lights' shadow samples add up to 4104, more than the limit of 4096 rays from each hit"),
    ];
    for (render_, camera, light, object, material, expected) in cases {
        let src = one_object(render_, camera, light, object, material);
        assert_eq!(error_of(&src), format!("test.toml: {expected}"), "{src}");
    }
    let src = one_object(
        "width = 16384\nheight = 16384\nspp = 1",
        "",
        "",
        "",
        "type = \"diffuse\"",
    );
    assert_eq!(
        error_of(&src),
        "test.toml: line 3, field render.height: 16384 x 16384 = 268435456 pixels, more than \
         the limit of 16777216"
    );
}

/// A scene of one lit object, with `extra` lines in `[render]`, `[camera]`, `[[lights]]`, the
/// object and its material.
/// A `camera` or `light` that starts with its own `position` replaces the default one.
pub(crate) fn one_object(
    render: &str,
    camera: &str,
    light: &str,
    object: &str,
    material: &str,
) -> String {
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

/// A fresh directory under the system's temporary directory.
pub(crate) fn scratch(name: &str) -> std::path::PathBuf {
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
        scene::load::<Flat>(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string(),
        "/dev/zero: the scene file is not a regular file (a directory, a device or a FIFO)"
    );
    let dir = scratch("bounded");
    // A FIFO without a writer would block the open: refused by its type first.
    #[cfg(unix)]
    {
        let fifo = dir.join("fifo.toml");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            assert_eq!(
                scene::load::<Flat>(&fifo).unwrap_err().to_string(),
                format!(
                    "{}: the scene file is not a regular file (a directory, a device or a FIFO)",
                    fifo.display()
                )
            );
        }
    }
    // Truncated, deeply nested, a very long string, NaN and ∞: each refused with a line or a
    // field, none takes more than the file's length to find.
    let truncated = &MINIMAL[..MINIMAL.len() / 2];
    assert!(
        error_of(truncated).starts_with("test.toml: "),
        "{}",
        error_of(truncated)
    );
    let deep = format!(
        "{MINIMAL}x = {}{}\n",
        "[".repeat(100_000),
        "]".repeat(100_000)
    );
    assert!(
        error_of(&deep).starts_with("test.toml: line "),
        "{}",
        error_of(&deep)
    );
    let long = format!("{MINIMAL}name = \"{}\"\n", "x".repeat(1 << 20));
    assert!(error_of(&long).len() < 400, "{}", &error_of(&long)[..400]);
    let big = dir.join("big.toml");
    let mut src = String::from(MINIMAL);
    while src.len() <= 4 << 20 {
        src.push_str("# padding padding padding padding padding padding padding padding\n");
    }
    std::fs::write(&big, &src).unwrap();
    assert_eq!(
        scene::load::<Flat>(&big).unwrap_err().to_string(),
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
    let e = scene::parse::<Flat>(&scene, "test.toml", "test", &dir)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!(
            "test.toml: line 8, field objects[0].material.image: {}: 22000 x 22000 = 484000000 \
             pixels, more than the 16777216 left of the limit on texture pixels",
            dir.join("huge.png").display()
        )
    );
    // The hint about `raytrace make-label` is for the shipped label's own errors only.
    let label = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/label.png");
    assert!(crate::material::is_the_label(&label));
    assert!(crate::material::is_the_label(
        &label.join("../../assets/./label.png")
    ));
    assert!(!crate::material::is_the_label(&dir.join("huge.png")));
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

#[test]
fn options_parse() {
    let args = |s: &str| -> Vec<String> { s.split_whitespace().map(String::from).collect() };
    let Command::Render(o, ()) = cli::parse::<()>(&args(
        "fig4a --width 64 --spp=2 --strategy paper --clip constant --out a.png",
    ))
    .unwrap() else {
        panic!()
    };
    assert_eq!(o.scenes, ["fig4a"]);
    assert_eq!((o.width, o.spp), (Some(64), Some(2)));
    assert_eq!(o.strategy, Some(crate::colour::Colour::Paper));
    assert_eq!(o.clip, Some(diffraction::color::Clip::ConstantIntensity));
    assert_eq!(cli::parse::<()>(&args("--help")).unwrap(), Command::Help);
    for bad in [
        "--width 20000",
        "--height 0",
        "--spp 5000",
        "--frames 10001",
        "--width -3",
        "--strategy uniform:0",
        "--clip gamma",
        "--bogus",
        "--width",
    ] {
        let e = cli::parse::<()>(&args(bad)).unwrap_err();
        assert!(
            e.starts_with(bad.split_whitespace().next().unwrap()) || e.contains("unknown option"),
            "{bad}: {e}"
        );
    }
}
