//! A grating's `efficiency` naming a JSON efficiency table (docs/efficiency_tables.md), relative
//! to the scene file: read with bounded work and memory, its period the default, and every
//! refusal naming the scene file, the line, the field and the cause.

use diffraction::grating_bsdf::OrderEfficiency;
use diffraction::relief::Preset;
use std::path::{Path, PathBuf};

use crate::radiometry::Radiometric;
use crate::run::Renderer;
use crate::scene;
use crate::Integrator;

/// A valid table of three orders over two wavelengths and two incidences (d = 1000 nm), as
/// the library's JSON tests write it.
const TABLE: &str = r#"{"format": "diffraction-efficiency-table", "version": 1, "name": "t",
"description": "", "grating": {"profile": "sinusoid", "period_nm": 1000.0, "depth_nm": 100.0,
"duty": null, "blaze_deg": null, "metal": "Al", "cover": "none"}, "symmetric": true,
"sin_theta_i": [0.0, 0.5], "lambda_nm": [500.0, 600.0], "order_min": -1, "order_max": 1,
"te": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],
"tm": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],
"solver": {"method": "x"}, "validation": {}, "command": "", "sha256": "0"}"#;

/// A scene whose one grating (line 12) has `efficiency = "{efficiency}"` and `extra` after it.
fn scene_src(efficiency: &str, extra: &str) -> String {
    format!(
        "[radiometry]\nexposure = 1.0\n[camera]\nposition = [0.0, 1.0, 0.0]\n\
         look_at = [0.0, 0.0, 0.3]\n[[objects]]\nshape = \"quad\"\n[objects.material]\n\
         type = \"grating\"\nmodel = \"radiometric\"\ndiffuse = 0.0\n\
         efficiency = \"{efficiency}\"\n{extra}"
    )
}

/// A fresh directory with `tables/` in it.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pathtrace-table-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("tables")).unwrap();
    dir
}

fn load(dir: &Path, src: &str) -> Result<scene::Scene<Radiometric>, String> {
    let file = dir.join("t.toml");
    std::fs::write(&file, src).unwrap();
    scene::load::<Radiometric>(&file).map_err(|e| e.to_string())
}

/// Renders `scene` at 8 × 6 pixels and 2 samples a pixel with both integrators: every pixel
/// finite.
fn renders_finite(scene: &mut scene::Scene<Radiometric>) {
    scene.settings.width = 8;
    scene.settings.height = 6;
    scene.settings.spp = 2;
    for integrator in [Integrator::Path, Integrator::Whitted] {
        let img = integrator.render(scene, &scene.camera, None);
        assert!(img.pixels.iter().all(|p| p.is_finite()), "{integrator:?}");
    }
}

#[test]
fn a_table_file_is_the_gratings_efficiencies_and_period() {
    let dir = scratch("ok");
    std::fs::write(dir.join("tables/t.json"), TABLE).unwrap();
    let mut scene = load(&dir, &scene_src("tables/t.json", "")).unwrap();
    let g = scene.materials[0].grating.as_ref().unwrap();
    assert_eq!(g.model.grating().period_nm(), 1000.0);
    assert!(g.model.order_efficiency().is_tabulated());
    // The table is an input of the run (never written over).
    let table = dir.join("tables/t.json");
    let table = table.canonicalize().unwrap();
    assert!(
        scene.inputs.iter().any(|i| i.path == table),
        "{:?}",
        scene.inputs
    );
    // The same period given is taken; another is refused, naming both.
    assert!(load(&dir, &scene_src("tables/t.json", "period_nm = 1000.0\n")).is_ok());
    assert_eq!(
        load(&dir, &scene_src("tables/t.json", "period_nm = 1600.0\n")).unwrap_err(),
        format!(
            "{}: line 13, field objects[0].material.period_nm: the table \"tables/t.json\" is \
             tabulated for a period of 1000 nm, got 1600 (leave period_nm out to take the \
             table's)",
            dir.join("t.toml").display()
        )
    );
    // Both integrators render it, finite.
    renders_finite(&mut scene);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A reduced conical table (version 3): two |β| planes of one order, each with its own
/// wavelengths (docs/efficiency_tables.md, "Reduced conical tables").
const TABLE_V3: &str = r#"{"format": "diffraction-efficiency-table", "version": 3, "name": "t",
"grating": {"profile": "lamellar", "period_nm": 1000.0}, "sin_theta_i": [-0.5, 0.5],
"abs_beta": [0.0, 0.6], "lambda_range_nm": [400.0, 700.0],
"lambda_nm": [[400.0, 600.0, 875.0], [320.0, 700.0]], "order_min": 0, "order_max": 0,
"te": [[[[0.9, 0.9], [0.9, 0.9], [0.9, 0.9]], [[0.9, 0.9], [0.9, 0.9]]]],
"tm": [[[[0.8, 0.8], [0.8, 0.8], [0.8, 0.8]], [[0.8, 0.8], [0.8, 0.8]]]],
"solver": {}, "validation": {}, "sha256": "0"}"#;

#[test]
fn a_reduced_conical_table_file_loads() {
    let dir = scratch("v3");
    std::fs::write(dir.join("tables/v3.json"), TABLE_V3).unwrap();
    let scene = load(&dir, &scene_src("tables/v3.json", "")).unwrap();
    let g = scene.materials[0].grating.as_ref().unwrap();
    assert_eq!(g.model.grating().period_nm(), 1000.0);
    assert!(g.model.order_efficiency().is_tabulated());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The order efficiencies of the first material's grating of `scene`.
fn efficiency(scene: &scene::Scene<Radiometric>) -> OrderEfficiency {
    scene.materials[0]
        .grating
        .as_ref()
        .unwrap()
        .model
        .order_efficiency()
}

/// `reading = "reduced"` reads a preset or a classical table file conically
/// (`reduced_from_classical`; the default for a preset, `Preset::conical_table`), and
/// "classical" in the classical mount (the default for a file); the amplitude reading, a
/// conical file, a cover it does not know or another reading is refused naming `reading`.
#[test]
fn a_classical_table_read_reduced_is_a_conical_table() {
    let dir = scratch("reading");
    let mut scene = load(&dir, &scene_src("cd", "reading = \"reduced\"\n")).unwrap();
    let g = scene.materials[0].grating.as_ref().unwrap();
    let e = g.model.order_efficiency();
    assert!(e.table().unwrap().is_reduced());
    assert_eq!(g.model.grating().period_nm(), 1600.0);
    // The default is the library's, the preset's conical table; "classical" reads the
    // preset's classical table.
    let s = load(&dir, &scene_src("cd", "")).unwrap();
    let e = efficiency(&s);
    assert!(std::ptr::eq(e.table().unwrap(), Preset::Cd.conical_table()));
    let s = load(&dir, &scene_src("cd", "reading = \"classical\"\n")).unwrap();
    let e = efficiency(&s);
    assert!(std::ptr::eq(e.table().unwrap(), Preset::Cd.table()));
    // A classical file is read classically by default, and reduced with its cover (none
    // here) when asked.
    std::fs::write(dir.join("tables/t.json"), TABLE).unwrap();
    let s = load(&dir, &scene_src("tables/t.json", "")).unwrap();
    let e = efficiency(&s);
    assert!(!e.table().unwrap().is_conical());
    let s = load(&dir, &scene_src("tables/t.json", "reading = \"reduced\"\n")).unwrap();
    let e = efficiency(&s);
    assert!(e.table().unwrap().is_reduced());
    std::fs::write(dir.join("tables/v3.json"), TABLE_V3).unwrap();
    let glass = TABLE.replace("\"cover\": \"none\"", "\"cover\": \"glass\"");
    assert!(glass.contains("glass"));
    std::fs::write(dir.join("tables/glass.json"), glass).unwrap();
    let field = "field objects[0].material.reading: ";
    for (efficiency, extra, why) in [
        (
            "amplitude",
            "period_nm = 1000.0\n",
            "\"reduced\" reads a table",
        ),
        (
            "cd",
            "",
            "expected \"classical\" or \"reduced\", got \"conical\"",
        ),
        (
            "tables/v3.json",
            "",
            "the table \"tables/v3.json\": invalid table = 1: must be a classical table",
        ),
        (
            "tables/glass.json",
            "",
            "the table \"tables/glass.json\" names the cover \"glass\"",
        ),
    ] {
        let reading = if efficiency == "cd" {
            "conical"
        } else {
            "reduced"
        };
        let extra = format!("{extra}reading = \"{reading}\"\n");
        let Err(e) = load(&dir, &scene_src(efficiency, &extra)) else {
            panic!("{efficiency} with {extra:?} loaded");
        };
        assert!(e.contains(&format!("{field}{why}")), "{e}");
    }
    // Both integrators render it, finite (the Whitted one from its colour table, on the plane
    // across the grooves).
    renders_finite(&mut scene);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_hostile_table_file_is_refused_naming_the_field() {
    let dir = scratch("hostile");
    std::fs::create_dir_all(dir.join("tables/dir.json")).unwrap();
    std::fs::write(dir.join("tables/bad.json"), "{\"format\": ").unwrap();
    std::fs::write(dir.join("tables/latin1.json"), b"{\"name\": \"\xe9\"}").unwrap();
    std::fs::write(
        dir.join("tables/v4.json"),
        TABLE.replace("\"version\": 1", "\"version\": 4"),
    )
    .unwrap();
    let big = std::fs::File::create(dir.join("tables/big.json")).unwrap();
    big.set_len(crate::limits::MAX_TABLE_BYTES + 1).unwrap();
    let fifo = dir.join("tables/fifo.json");
    let has_fifo = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    let at = format!(
        "{}: line 12, field objects[0].material.efficiency: the table",
        dir.join("t.toml").display()
    );
    let mut cases = vec![
        (
            "tables/missing.json",
            "\"tables/missing.json\" cannot be read: No such file or directory (os error 2)"
                .to_string(),
        ),
        (
            "tables/dir.json",
            "\"tables/dir.json\" is not a regular file (a directory, a device or a FIFO)".into(),
        ),
        (
            "tables/big.json",
            "\"tables/big.json\" has 16777217 bytes, more than the 16777216 read".into(),
        ),
        (
            "tables/latin1.json",
            "\"tables/latin1.json\" is not UTF-8 (at byte 10)".into(),
        ),
        (
            "tables/bad.json",
            "\"tables/bad.json\": format: EOF while parsing a value at line 1 column 11".into(),
        ),
        (
            "tables/v4.json",
            "\"tables/v4.json\": version: expected 1, 2 or 3, got 4 at line 7 column 74".into(),
        ),
    ];
    if has_fifo {
        cases.push((
            "tables/fifo.json",
            "\"tables/fifo.json\" is not a regular file (a directory, a device or a FIFO)".into(),
        ));
    }
    for (file, expected) in cases {
        let e = load(&dir, &scene_src(file, "")).unwrap_err();
        assert_eq!(e, format!("{at} {expected}"), "{file}");
    }
    // A model that takes no `efficiency` is refused by that rule, before any file is read.
    let paper = scene_src("tables/missing.json", "")
        .replace("model = \"radiometric\"", "model = \"agu-hill\"");
    assert_eq!(
        load(&dir, &paper).unwrap_err(),
        format!(
            "{}: line 12, field objects[0].material.efficiency: not used by model \"agu-hill\" \
             (it takes slit_width_nm, slits)",
            dir.join("t.toml").display()
        )
    );
    let _ = std::fs::remove_dir_all(&dir);
}
