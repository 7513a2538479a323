//! Scene files (TOML) and the scene they describe.
//!
//! A scene file has the tables `[render]`, `[camera]`, `[environment]`, an array `[[lights]]`
//! and an array `[[objects]]`, each object with a `[objects.material]` (and, for gratings, a
//! `[objects.material.field]`). See `examples/scenes/fig4a.toml` for a commented example, and
//! `examples/scenes/baselines/compare.toml` for the grating `model` key (Agu-Hill, Thorman, Stam).
//!
//! Parsing has two stages: serde checks the types (unknown keys are errors), then
//! [`build`] checks the values and builds the scene. Either stage's error names the file, the
//! line and the field path, and says what is expected.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use diffraction::cie::Illuminant;
use diffraction::color::Clip;
use diffraction::frame::{GratingField, Tile};
use diffraction::spectrum::{Spectral, Strategy};
use diffraction::{AguHill, Grating, Thorman};
use glam::DVec3;
use serde::Deserialize;
use toml::de::DeTable;

use crate::diagnostics::{line_of, locate, path_at, plain_message, FieldError, SceneError};
use crate::geometry::{Primitive, Shape, Transform};
use crate::material::{model_exposure, Albedo, GratingMaterial, Material, Model};
use crate::texture::{ImageTexture, Wood};

/// Largest accepted image width or height.
pub const MAX_SIZE: u32 = 16384;
/// Largest accepted number of samples per pixel.
pub const MAX_SPP: u32 = 4096;
/// Largest accepted number of coherent slits N.
pub const MAX_SLITS: u64 = 1_000_000_000;
/// Largest accepted recursion depth of mirror reflection.
pub const MAX_DEPTH: u32 = 64;
/// Largest accepted number of shadow samples of one light.
pub const MAX_LIGHT_SAMPLES: u32 = 1024;
/// Largest accepted number of objects and of lights.
pub const MAX_OBJECTS: usize = 10_000;

// ------------------------------------------------------------------------------------------
// The file's schema (stage 1: types).

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScene {
    description: Option<String>,
    #[serde(default)]
    render: RawRender,
    camera: RawCamera,
    #[serde(default)]
    environment: RawEnvironment,
    #[serde(default)]
    lights: Vec<RawLight>,
    #[serde(default)]
    objects: Vec<RawObject>,
    radiometry: Option<crate::radiometric::RawRadiometry>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRender {
    width: Option<u32>,
    height: Option<u32>,
    spp: Option<u32>,
    max_depth: Option<u32>,
    seed: Option<u64>,
    strategy: Option<String>,
    clip: Option<String>,
    illuminant: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCamera {
    position: [f64; 3],
    look_at: [f64; 3],
    up: Option<[f64; 3]>,
    fov_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawEnvironment {
    background: Option<[f64; 3]>,
    zenith: Option<[f64; 3]>,
    ambient: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLight {
    position: [f64; 3],
    color: Option<[f64; 3]>,
    intensity: Option<f64>,
    radius: Option<f64>,
    samples: Option<u32>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
enum Scale {
    Uniform(f64),
    Axes([f64; 3]),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawObject {
    shape: String,
    hole: Option<f64>,
    translate: Option<[f64; 3]>,
    rotate_deg: Option<[f64; 3]>,
    scale: Option<Scale>,
    material: RawMaterial,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    #[serde(rename = "type")]
    kind: String,
    color: Option<[f64; 3]>,
    ambient: Option<f64>,
    diffuse: Option<f64>,
    mirror: Option<f64>,
    mirror_color: Option<[f64; 3]>,
    // wood
    light: Option<[f64; 3]>,
    dark: Option<[f64; 3]>,
    ring_spacing: Option<f64>,
    turbulence: Option<f64>,
    plank_width: Option<f64>,
    plank_length: Option<f64>,
    // image
    image: Option<String>,
    // grating
    period_nm: Option<f64>,
    lines_per_mm: Option<f64>,
    slit_width_nm: Option<f64>,
    slits: Option<u64>,
    diffraction: Option<f64>,
    strategy: Option<String>,
    field: Option<RawField>,
    // grating model and its parameters
    model: Option<String>,
    lobe_width: Option<f64>,
    depth_nm: Option<f64>,
    fraction: Option<f64>,
    coherence_nm: Option<f64>,
    reflectance: Option<f64>,
    groove_sigma: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawField {
    #[serde(rename = "type")]
    kind: String,
    angle_deg: Option<f64>,
    twist_deg: Option<f64>,
    center: Option<[f64; 2]>,
    cell_size: Option<f64>,
    even: Option<RawTile>,
    odd: Option<RawTile>,
    plain_color: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTile {
    #[serde(rename = "type")]
    kind: String,
    angle_deg: Option<f64>,
    twist_deg: Option<f64>,
    center: Option<[f64; 2]>,
}

// ------------------------------------------------------------------------------------------
// The scene (stage 2: values).

/// Render settings (the scene's `[render]` table, overridable from the command line).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub max_depth: u32,
    pub seed: u64,
    pub clip: Clip,
    pub strategy: Strategy,
}

/// A pinhole camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    pub position: DVec3,
    pub look_at: DVec3,
    pub up: DVec3,
    pub fov_deg: f64,
}

/// A point light, or with `radius` > 0 a spherical light sampled `samples` times for shadows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    pub position: DVec3,
    /// Colour times intensity, linear sRGB.
    pub color: DVec3,
    pub radius: f64,
    pub samples: u32,
}

/// A loaded scene.
#[derive(Debug, Clone)]
pub struct Scene {
    pub name: String,
    pub description: String,
    pub settings: Settings,
    pub camera: Camera,
    /// Sky colour at the horizon and straight up (linear sRGB).
    pub background: DVec3,
    pub zenith: DVec3,
    /// Ambient light (linear sRGB).
    pub ambient: DVec3,
    pub lights: Vec<Light>,
    pub objects: Vec<Primitive>,
    pub materials: Vec<Material>,
    pub spectral: Spectral,
    /// The physical units of a radiometric scene (its `[radiometry]` table).
    pub radiometry: Option<crate::radiometric::Radiometry>,
    /// Which materials' strategy came from the scene's `[render]` default (and follows
    /// [`Scene::set_strategy`]).
    follows_default: Vec<bool>,
}

impl Scene {
    /// Switches every grating that uses the default strategy to `strategy` (and recomputes its
    /// exposure).
    pub fn set_strategy(&mut self, strategy: Strategy) {
        self.settings.strategy = strategy;
        for (m, follows) in self.materials.iter_mut().zip(&self.follows_default) {
            if let (Some(g), true) = (&mut m.grating, *follows) {
                g.strategy = strategy;
                g.exposure = model_exposure(&self.spectral, &g.model, strategy);
            }
        }
    }
}

/// Loads and checks a scene file.
pub fn load(path: &Path) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let src = std::fs::read_to_string(path).map_err(|e| SceneError {
        file: file.clone(),
        line: None,
        field: None,
        message: format!("cannot read the scene file: {e}"),
    })?;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let base = path.parent().unwrap_or(Path::new("."));
    parse(&src, &file, &name, base)
}

/// Parses and checks scene text; `file` names it in errors, `base` resolves image paths.
pub fn parse(src: &str, file: &str, name: &str, base: &Path) -> Result<Scene, SceneError> {
    let err = |line, field, message| SceneError {
        file: file.to_string(),
        line,
        field,
        message,
    };
    // Syntax.
    let doc = DeTable::parse(src).map_err(|e| {
        let line = e.span().map(|s| line_of(src, s.start));
        err(line, None, format!("invalid TOML: {}", e.message().trim()))
    })?;
    // Types.
    let raw: RawScene = toml::from_str(src).map_err(|e| {
        let offset = e.span().filter(|s| !s.is_empty()).map(|s| s.start);
        let mut field = e.span().and_then(|s| path_at(&doc, s));
        let message = plain_message(e.message());
        // "missing field `x`" is reported at the table that lacks it.
        if let Some(missing) = message
            .strip_prefix("missing field `")
            .and_then(|m| m.split('`').next())
        {
            field = Some(match field {
                Some(f) => format!("{f}.{missing}"),
                None => missing.to_string(),
            });
        }
        err(offset.map(|o| line_of(src, o)), field, message)
    })?;
    // Values.
    build(raw, name, base).map_err(|e| {
        let span = locate(&doc, &e.path);
        err(Some(line_of(src, span.start)), Some(e.path), e.message)
    })
}

type Check<T> = Result<T, FieldError>;

fn expect(path: &str, ok: bool, what: &str, got: impl std::fmt::Display) -> Check<()> {
    if ok {
        Ok(())
    } else {
        Err(FieldError::new(path, format!("expected {what}, got {got}")))
    }
}

fn positive(path: &str, v: f64) -> Check<f64> {
    expect(path, v.is_finite() && v > 0.0, "a positive number", v)?;
    Ok(v)
}

fn non_negative(path: &str, v: f64) -> Check<f64> {
    expect(path, v.is_finite() && v >= 0.0, "a number >= 0", v)?;
    Ok(v)
}

fn finite(path: &str, v: f64) -> Check<f64> {
    expect(path, v.is_finite(), "a finite number", v)?;
    Ok(v)
}

fn vec3(path: &str, v: [f64; 3]) -> Check<DVec3> {
    for (i, c) in v.iter().enumerate() {
        finite(&format!("{path}[{i}]"), *c)?;
    }
    Ok(DVec3::from_array(v))
}

fn color(path: &str, v: [f64; 3]) -> Check<DVec3> {
    for (i, c) in v.iter().enumerate() {
        non_negative(&format!("{path}[{i}]"), *c)?;
    }
    Ok(DVec3::from_array(v))
}

fn unit_interval(path: &str, v: f64) -> Check<f64> {
    expect(path, (0.0..=1.0).contains(&v), "a number in [0, 1]", v)?;
    Ok(v)
}

fn count(path: &str, v: u32, min: u32, max: u32) -> Check<u32> {
    expect(
        path,
        (min..=max).contains(&v),
        &format!("an integer in [{min}, {max}]"),
        v,
    )?;
    Ok(v)
}

fn parse_strategy(path: &str, s: &str) -> Check<Strategy> {
    s.parse()
        .map_err(|e: diffraction::spectrum::ParseStrategyError| {
            FieldError::new(path, format!("{e}, got \"{s}\""))
        })
}

/// Rejects fields that the chosen `type` does not use (they are most likely a mistake).
fn only(path: &str, kind: &str, present: &[(&str, bool)], allowed: &[&str]) -> Check<()> {
    for (name, is_set) in present {
        if *is_set && !allowed.contains(name) {
            return Err(FieldError::new(
                format!("{path}.{name}"),
                format!(
                    "not used by type \"{kind}\" (it takes {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    Ok(())
}

fn build(raw: RawScene, name: &str, base: &Path) -> Check<Scene> {
    let r = &raw.render;
    let illuminant = match r.illuminant.as_deref() {
        None => Illuminant::D65,
        Some(s) => s
            .parse()
            .map_err(|e: diffraction::cie::ParseIlluminantError| {
                FieldError::new("render.illuminant", format!("{e}, got \"{s}\""))
            })?,
    };
    let settings = Settings {
        width: count("render.width", r.width.unwrap_or(480), 1, MAX_SIZE)?,
        height: count("render.height", r.height.unwrap_or(360), 1, MAX_SIZE)?,
        spp: count("render.spp", r.spp.unwrap_or(4), 1, MAX_SPP)?,
        max_depth: count("render.max_depth", r.max_depth.unwrap_or(5), 0, MAX_DEPTH)?,
        seed: r.seed.unwrap_or(1),
        clip: match r.clip.as_deref() {
            None => Clip::Intensity,
            Some(s) => s.parse().map_err(|e: diffraction::color::ParseClipError| {
                FieldError::new("render.clip", format!("{e}, got \"{s}\""))
            })?,
        },
        strategy: match r.strategy.as_deref() {
            None => Strategy::PeakSearch { refine: false },
            Some(s) => parse_strategy("render.strategy", s)?,
        },
    };

    let c = &raw.camera;
    let camera = Camera {
        position: vec3("camera.position", c.position)?,
        look_at: vec3("camera.look_at", c.look_at)?,
        up: vec3("camera.up", c.up.unwrap_or([0.0, 1.0, 0.0]))?,
        fov_deg: c.fov_deg.unwrap_or(40.0),
    };
    expect(
        "camera.fov_deg",
        camera.fov_deg.is_finite() && camera.fov_deg > 0.0 && camera.fov_deg < 180.0,
        "an angle in (0, 180) degrees",
        camera.fov_deg,
    )?;
    let forward = camera.look_at - camera.position;
    expect(
        "camera.look_at",
        forward.length() > 1e-12,
        "a point different from camera.position",
        "the same point",
    )?;
    expect(
        "camera.up",
        forward.normalize().cross(camera.up).length() > 1e-9,
        "a direction not parallel to the view direction",
        format!("{:?}", c.up.unwrap_or([0.0, 1.0, 0.0])),
    )?;

    let env = &raw.environment;
    let background = color(
        "environment.background",
        env.background.unwrap_or([0.05, 0.05, 0.06]),
    )?;
    let zenith = match env.zenith {
        Some(z) => color("environment.zenith", z)?,
        None => background,
    };
    let ambient = color(
        "environment.ambient",
        env.ambient.unwrap_or([0.1, 0.1, 0.1]),
    )?;

    expect(
        "lights",
        raw.lights.len() <= MAX_OBJECTS,
        &format!("at most {MAX_OBJECTS} lights"),
        raw.lights.len(),
    )?;
    let mut lights = Vec::new();
    for (i, l) in raw.lights.iter().enumerate() {
        let p = format!("lights[{i}]");
        let color = color(&format!("{p}.color"), l.color.unwrap_or([1.0, 1.0, 1.0]))?;
        let intensity = non_negative(&format!("{p}.intensity"), l.intensity.unwrap_or(1.0))?;
        let radius = non_negative(&format!("{p}.radius"), l.radius.unwrap_or(0.0))?;
        let samples = count(
            &format!("{p}.samples"),
            l.samples.unwrap_or(if radius > 0.0 { 8 } else { 1 }),
            1,
            MAX_LIGHT_SAMPLES,
        )?;
        lights.push(Light {
            position: vec3(&format!("{p}.position"), l.position)?,
            color: color * intensity,
            radius,
            samples: if radius > 0.0 { samples } else { 1 },
        });
    }

    let spectral = Spectral::new(illuminant);
    expect(
        "objects",
        raw.objects.len() <= MAX_OBJECTS,
        &format!("at most {MAX_OBJECTS} objects"),
        raw.objects.len(),
    )?;
    let mut objects = Vec::new();
    let mut materials = Vec::new();
    let mut follows_default = Vec::new();
    let mut images: HashMap<PathBuf, Arc<ImageTexture>> = HashMap::new();
    for (i, o) in raw.objects.iter().enumerate() {
        let p = format!("objects[{i}]");
        let shape = match o.shape.as_str() {
            "quad" => Shape::Quad,
            "cube" => Shape::Cube,
            "cylinder" => Shape::Cylinder,
            "disc" => {
                let hole = o.hole.unwrap_or(0.0);
                expect(
                    &format!("{p}.hole"),
                    (0.0..0.5).contains(&hole),
                    "an inner radius in [0, 0.5) (the disc's radius is 0.5 before scaling)",
                    hole,
                )?;
                Shape::Disc { hole }
            }
            other => {
                return Err(FieldError::new(
                    format!("{p}.shape"),
                    format!(
                    "expected one of \"quad\", \"cube\", \"cylinder\", \"disc\", got \"{other}\""
                ),
                ))
            }
        };
        if o.hole.is_some() && !matches!(shape, Shape::Disc { .. }) {
            return Err(FieldError::new(
                format!("{p}.hole"),
                "only a \"disc\" has a hole",
            ));
        }
        let translate = vec3(&format!("{p}.translate"), o.translate.unwrap_or([0.0; 3]))?;
        let rotate = vec3(&format!("{p}.rotate_deg"), o.rotate_deg.unwrap_or([0.0; 3]))?;
        let scale = match o.scale {
            None => DVec3::ONE,
            Some(Scale::Uniform(s)) => DVec3::splat(positive(&format!("{p}.scale"), s)?),
            Some(Scale::Axes(a)) => {
                for (k, s) in a.iter().enumerate() {
                    positive(&format!("{p}.scale[{k}]"), *s)?;
                }
                DVec3::from_array(a)
            }
        };
        let transform = Transform::new(translate, rotate, scale).ok_or_else(|| {
            FieldError::new(format!("{p}.scale"), "expected an invertible transform")
        })?;
        let (material, follows) = build_material(
            &o.material,
            &format!("{p}.material"),
            &settings,
            &spectral,
            base,
            &mut images,
        )?;
        objects.push(Primitive {
            shape,
            transform,
            material: materials.len(),
        });
        materials.push(material);
        follows_default.push(follows);
    }

    let radiometry = crate::radiometric::build(
        raw.radiometry.as_ref(),
        (&lights, raw.lights.iter().map(|l| (l.color, l.intensity))),
        &materials,
        illuminant,
    )?;
    Ok(Scene {
        name: name.to_string(),
        description: raw.description.unwrap_or_default(),
        settings,
        camera,
        background,
        zenith,
        ambient,
        lights,
        objects,
        materials,
        spectral,
        radiometry,
        follows_default,
    })
}

/// The material at `path`, and whether its strategy follows the scene default.
fn build_material(
    m: &RawMaterial,
    path: &str,
    settings: &Settings,
    spectral: &Spectral,
    base: &Path,
    images: &mut HashMap<PathBuf, Arc<ImageTexture>>,
) -> Check<(Material, bool)> {
    let present = [
        ("color", m.color.is_some()),
        ("ambient", m.ambient.is_some()),
        ("diffuse", m.diffuse.is_some()),
        ("mirror", m.mirror.is_some()),
        ("mirror_color", m.mirror_color.is_some()),
        ("light", m.light.is_some()),
        ("dark", m.dark.is_some()),
        ("ring_spacing", m.ring_spacing.is_some()),
        ("turbulence", m.turbulence.is_some()),
        ("plank_width", m.plank_width.is_some()),
        ("plank_length", m.plank_length.is_some()),
        ("image", m.image.is_some()),
        ("period_nm", m.period_nm.is_some()),
        ("lines_per_mm", m.lines_per_mm.is_some()),
        ("slit_width_nm", m.slit_width_nm.is_some()),
        ("slits", m.slits.is_some()),
        ("diffraction", m.diffraction.is_some()),
        ("strategy", m.strategy.is_some()),
        ("field", m.field.is_some()),
        ("model", m.model.is_some()),
        ("lobe_width", m.lobe_width.is_some()),
        ("depth_nm", m.depth_nm.is_some()),
        ("fraction", m.fraction.is_some()),
        ("coherence_nm", m.coherence_nm.is_some()),
        ("reflectance", m.reflectance.is_some()),
        ("groove_sigma", m.groove_sigma.is_some()),
    ];
    const COMMON: [&str; 4] = ["ambient", "diffuse", "mirror", "mirror_color"];
    let allowed: Vec<&str> = match m.kind.as_str() {
        "diffuse" | "mirror" => vec!["color"],
        "wood" => vec!["light", "dark", "ring_spacing", "turbulence", "plank_width", "plank_length"],
        "image" => vec!["image", "color"],
        "grating" => vec![
            "color",
            "period_nm",
            "lines_per_mm",
            "slit_width_nm",
            "slits",
            "diffraction",
            "strategy",
            "field",
            "model",
            "lobe_width",
            "depth_nm",
            "fraction",
            "coherence_nm",
            "reflectance",
            "groove_sigma",
        ],
        other => {
            return Err(FieldError::new(
                format!("{path}.type"),
                format!("expected one of \"diffuse\", \"mirror\", \"wood\", \"image\", \"grating\", got \"{other}\""),
            ))
        }
    };
    let allowed: Vec<&str> = allowed.into_iter().chain(COMMON).collect();
    only(path, &m.kind, &present, &allowed)?;

    let f = |name: &str| format!("{path}.{name}");
    let is_mirror = m.kind == "mirror";
    let base_color = color(
        &f("color"),
        m.color
            .unwrap_or(if is_mirror { [0.05; 3] } else { [0.7; 3] }),
    )?;
    let ka = non_negative(&f("ambient"), m.ambient.unwrap_or(1.0))?;
    let kd = non_negative(
        &f("diffuse"),
        m.diffuse.unwrap_or(if is_mirror { 0.1 } else { 1.0 }),
    )?;
    let mirror = unit_interval(
        &f("mirror"),
        m.mirror.unwrap_or(if is_mirror { 0.9 } else { 0.0 }),
    )?;
    let mirror_tint = color(&f("mirror_color"), m.mirror_color.unwrap_or([1.0; 3]))?;

    let albedo = match m.kind.as_str() {
        "wood" => Albedo::Wood(Wood {
            light: color(&f("light"), m.light.unwrap_or([0.62, 0.40, 0.20]))?,
            dark: color(&f("dark"), m.dark.unwrap_or([0.30, 0.16, 0.07]))?,
            ring_spacing: positive(&f("ring_spacing"), m.ring_spacing.unwrap_or(0.05))?,
            turbulence: non_negative(&f("turbulence"), m.turbulence.unwrap_or(1.5))?,
            plank_width: non_negative(&f("plank_width"), m.plank_width.unwrap_or(0.0))?,
            plank_length: non_negative(&f("plank_length"), m.plank_length.unwrap_or(0.0))?,
        }),
        "image" => {
            let Some(name) = &m.image else {
                return Err(FieldError::new(
                    f("image"),
                    "expected the path of a PNG image (relative to the scene file)",
                ));
            };
            let file = base.join(name);
            let texture = match images.get(&file) {
                Some(t) => t.clone(),
                None => {
                    let t = Arc::new(ImageTexture::load(&file).map_err(|e| {
                        FieldError::new(
                            f("image"),
                            format!("{e} (the can label is made by `raytrace make-label`)"),
                        )
                    })?);
                    images.insert(file, t.clone());
                    t
                }
            };
            Albedo::Image {
                texture,
                other: base_color,
            }
        }
        _ => Albedo::Solid(base_color),
    };

    let mut follows = true;
    let grating = if m.kind == "grating" {
        let period = match (m.period_nm, m.lines_per_mm) {
            (Some(_), Some(_)) => {
                return Err(FieldError::new(
                    f("lines_per_mm"),
                    "give either period_nm or lines_per_mm, not both",
                ))
            }
            (Some(d), None) => positive(&f("period_nm"), d)?,
            (None, Some(l)) => 1.0e6 / positive(&f("lines_per_mm"), l)?,
            (None, None) => {
                return Err(FieldError::new(
                    f("period_nm"),
                    "missing: a grating needs period_nm (or lines_per_mm)",
                ))
            }
        };
        let kdiff = non_negative(&f("diffraction"), m.diffraction.unwrap_or(1.0))?;
        let model = build_model(m, path, period, (ka, kd, kdiff), &present)?;
        let strategy = match &m.strategy {
            Some(s) => {
                follows = false;
                parse_strategy(&f("strategy"), s)?
            }
            None => settings.strategy,
        };
        let (field, plain_albedo) = match &m.field {
            None => (GratingField::constant(0.0), base_color),
            Some(field) => build_field(field, &f("field"), base_color)?,
        };
        Some(GratingMaterial {
            exposure: model_exposure(spectral, &model, strategy),
            model,
            diffraction: kdiff,
            field,
            strategy,
            plain_albedo,
        })
    } else {
        None
    };

    Ok((
        Material {
            albedo,
            ambient: ka,
            diffuse: kd,
            mirror,
            mirror_tint,
            grating,
        },
        follows,
    ))
}

/// The grating's diffraction model (`model`, default "agu-hill") and its parameters; a
/// parameter of another model is an error, and so is a Stam model in a build without the
/// `stam` feature.
fn build_model(
    m: &RawMaterial,
    path: &str,
    period: f64,
    (ka, kd, kdiff): (f64, f64, f64),
    present: &[(&str, bool)],
) -> Check<Model> {
    let f = |name: &str| format!("{path}.{name}");
    let name = m.model.as_deref().unwrap_or("agu-hill");
    const PARAMETERS: [&str; 8] = [
        "slit_width_nm",
        "slits",
        "lobe_width",
        "depth_nm",
        "fraction",
        "coherence_nm",
        "reflectance",
        "groove_sigma",
    ];
    let takes: &[&str] = match name {
        "agu-hill" => &["slit_width_nm", "slits"],
        "thorman" => &["lobe_width"],
        "stam-sine" => &["depth_nm", "coherence_nm", "reflectance"],
        "stam-binary" => &["depth_nm", "fraction", "coherence_nm", "reflectance"],
        "radiometric" => &["slit_width_nm", "slits", "coherence_nm", "groove_sigma"],
        other => {
            return Err(FieldError::new(
                f("model"),
                format!("expected one of \"agu-hill\", \"thorman\", \"stam-sine\", \"stam-binary\", \"radiometric\", got \"{other}\""),
            ))
        }
    };
    for (key, is_set) in present {
        if *is_set && PARAMETERS.contains(key) && !takes.contains(key) {
            return Err(FieldError::new(
                f(key),
                format!(
                    "not used by model \"{name}\" (it takes {})",
                    takes.join(", ")
                ),
            ));
        }
    }
    let crate_error = |e: diffraction::Error| {
        let field = match e.parameter() {
            "period_nm" if m.period_nm.is_none() => "lines_per_mm",
            p => p,
        };
        FieldError::new(f(field), e.to_string())
    };
    match name {
        "agu-hill" => {
            let width = positive(&f("slit_width_nm"), m.slit_width_nm.unwrap_or(period / 2.0))?;
            let slits = m.slits.unwrap_or(1000);
            expect(
                &f("slits"),
                (1..=MAX_SLITS).contains(&slits),
                &format!("an integer in [1, {MAX_SLITS}]"),
                slits,
            )?;
            let grating = Grating::new(period, width, slits as u32).map_err(crate_error)?;
            let model = AguHill::new(grating)
                .with_coefficients(ka, kd, kdiff)
                .map_err(crate_error)?;
            Ok(Model::AguHill(model))
        }
        "radiometric" => crate::radiometric::grating_model(
            period,
            m.slit_width_nm,
            m.slits,
            m.coherence_nm,
            m.groove_sigma,
            path,
        ),
        "thorman" => Ok(Model::Thorman(
            Thorman::new(period, m.lobe_width.unwrap_or(0.005)).map_err(crate_error)?,
        )),
        _ => stam_model(m, path, name, period, &crate_error),
    }
}

/// `stam-sine` or `stam-binary`: depth_nm (default 100), coherence_nm (default 10 periods),
/// fraction (binary, default 0.5), reflectance (default 1).
#[cfg(feature = "stam")]
fn stam_model(
    m: &RawMaterial,
    _: &str,
    name: &str,
    period: f64,
    crate_error: &dyn Fn(diffraction::Error) -> FieldError,
) -> Check<Model> {
    use diffraction::{Profile, Stam};
    let profile = match name {
        "stam-sine" => Profile::Sine,
        _ => Profile::Binary {
            fraction: m.fraction.unwrap_or(0.5),
        },
    };
    let stam = Stam::new(
        profile,
        period,
        m.depth_nm.unwrap_or(100.0),
        m.coherence_nm.unwrap_or(10.0 * period),
    )
    .and_then(|s| s.with_reflectance(m.reflectance.unwrap_or(1.0)))
    .map_err(crate_error)?;
    Ok(Model::Stam(stam))
}

#[cfg(not(feature = "stam"))]
fn stam_model(
    _: &RawMaterial,
    path: &str,
    name: &str,
    _: f64,
    _: &dyn Fn(diffraction::Error) -> FieldError,
) -> Check<Model> {
    Err(FieldError::new(
        format!("{path}.model"),
        format!(
            "model \"{name}\" needs the crate feature `stam`: build with `--features stam` \
             (e.g. cargo run --release --features stam --example raytrace -- ...)"
        ),
    ))
}

fn degrees(path: &str, v: Option<f64>) -> Check<f64> {
    Ok(finite(path, v.unwrap_or(0.0))?.to_radians())
}

fn center(path: &str, v: Option<[f64; 2]>) -> Check<[f64; 2]> {
    let c = v.unwrap_or([0.0, 0.0]);
    finite(&format!("{path}[0]"), c[0])?;
    finite(&format!("{path}[1]"), c[1])?;
    Ok(c)
}

fn build_tile(t: &RawTile, path: &str) -> Check<Tile> {
    let present = [
        ("angle_deg", t.angle_deg.is_some()),
        ("twist_deg", t.twist_deg.is_some()),
        ("center", t.center.is_some()),
    ];
    let f = |name: &str| format!("{path}.{name}");
    match t.kind.as_str() {
        "plain" => {
            only(path, "plain", &present, &[])?;
            Ok(Tile::Plain)
        }
        "constant" => {
            only(path, "constant", &present, &["angle_deg", "twist_deg"])?;
            Ok(Tile::Constant {
                angle: degrees(&f("angle_deg"), t.angle_deg)?
                    + degrees(&f("twist_deg"), t.twist_deg)?,
            })
        }
        "radial" => {
            only(path, "radial", &present, &["center", "twist_deg"])?;
            Ok(Tile::Radial {
                center: center(&f("center"), t.center)?,
                twist: degrees(&f("twist_deg"), t.twist_deg)?,
            })
        }
        other => Err(FieldError::new(
            f("type"),
            format!("expected one of \"plain\", \"constant\", \"radial\", got \"{other}\""),
        )),
    }
}

/// The field and the albedo of its plain squares.
fn build_field(fd: &RawField, path: &str, base_color: DVec3) -> Check<(GratingField, DVec3)> {
    let present = [
        ("angle_deg", fd.angle_deg.is_some()),
        ("twist_deg", fd.twist_deg.is_some()),
        ("center", fd.center.is_some()),
        ("cell_size", fd.cell_size.is_some()),
        ("even", fd.even.is_some()),
        ("odd", fd.odd.is_some()),
        ("plain_color", fd.plain_color.is_some()),
    ];
    let f = |name: &str| format!("{path}.{name}");
    let twist = degrees(&f("twist_deg"), fd.twist_deg)?;
    let field = match fd.kind.as_str() {
        "constant" => {
            only(path, "constant", &present, &["angle_deg", "twist_deg"])?;
            GratingField::constant(degrees(&f("angle_deg"), fd.angle_deg)?)
        }
        "radial" => {
            only(path, "radial", &present, &["center", "twist_deg"])?;
            GratingField::Uniform(Tile::Radial {
                center: center(&f("center"), fd.center)?,
                twist: 0.0,
            })
        }
        "checkerboard" => {
            only(
                path,
                "checkerboard",
                &present,
                &["cell_size", "even", "odd", "plain_color", "twist_deg"],
            )?;
            let cell = positive(&f("cell_size"), fd.cell_size.unwrap_or(0.25))?;
            let even = match &fd.even {
                Some(t) => build_tile(t, &f("even"))?,
                None => Tile::Constant { angle: 0.0 },
            };
            let odd = match &fd.odd {
                Some(t) => build_tile(t, &f("odd"))?,
                None => Tile::Plain,
            };
            GratingField::checkerboard(cell, even, odd)
                .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?
        }
        other => {
            return Err(FieldError::new(
                f("type"),
                format!(
                    "expected one of \"constant\", \"radial\", \"checkerboard\", got \"{other}\""
                ),
            ))
        }
    };
    let field = field
        .twisted(twist)
        .map_err(|e| FieldError::new(f("twist_deg"), e.to_string()))?;
    let plain = match fd.plain_color {
        Some(c) => color(&f("plain_color"), c)?,
        None => base_color,
    };
    Ok((field, plain))
}
