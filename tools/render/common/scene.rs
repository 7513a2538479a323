//! Scene files (TOML) and the scene they describe.
//!
//! A scene file has the tables `[render]`, `[camera]`, `[environment]` (or, for the path tracer,
//! `[radiometry]`), an array `[[lights]]` and an array `[[objects]]`, each object with a
//! `[objects.material]` (and, for gratings, a `[objects.material.field]`). See
//! `tools/render/scenes/fig4a.toml` for a commented example, `tools/render/scenes/baselines/compare.toml`
//! for the grating `model` key (Agu-Hill, Thorman, Stam) and `tools/render/scenes/cd_area_light.toml`
//! for physical units.
//!
//! Loading has two stages: serde checks the keys and types ([`crate::schema`]; unknown keys are
//! errors), then [`build`] checks every value against the documented ranges of
//! [`crate::limits`] and builds the scene. Either stage's error names the file, the line and
//! the field path, and says what is expected. The file's size and its numbers of objects and
//! lights are checked before it is deserialised, a texture's size before it is decoded.
//!
//! The format is one; what a grating is and what the light units mean is the renderer's
//! [`Physics`]: the paper's models and eq. 12 for `raytrace`, the energy-normalised grating in
//! physical units for `pathtrace`.

use std::io::Read;
use std::path::Path;

use diffraction::cie::Illuminant;
use diffraction::color::Clip;
use diffraction::spectrum::Spectral;
use glam::DVec3;
use toml::de::{DeTable, DeValue};

use crate::camera::Camera;
use crate::colour::Colour;
use crate::diagnostics::{
    line_of, locate, path_at, plain_message, value_at, Check, FieldError, SceneError,
};
use crate::files::Input;
use crate::geometry::{Primitive, Shape, Transform};
use crate::limits::{self, check, count, zero_or, Range};
use crate::material::{Loader, Material};
use crate::schema::{culprit, RawGrating, RawScene, Scale, COMMON_KEYS};

/// Render settings (the scene's `[render]` table, overridable from the command line).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// The picture's width in pixels.
    pub width: u32,
    /// The picture's height in pixels.
    pub height: u32,
    /// Camera samples per pixel.
    pub spp: u32,
    /// Bounces: mirror recursion (Whitted) or path length (path tracing).
    pub max_depth: u32,
    /// The seed of the random numbers (the same seed gives the same bytes).
    pub seed: u64,
    /// The gamut clipping of the PNG.
    pub clip: Clip,
    /// The default spectral strategy of the gratings.
    pub strategy: Colour,
}

/// A point light, or with `radius` > 0 a spherical light sampled `samples` times for shadows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// The light's centre.
    pub position: DVec3,
    /// Colour times intensity, linear sRGB.
    pub color: DVec3,
    /// 0 for a point light.
    pub radius: f64,
    /// Shadow rays per hit (1 for a point light).
    pub samples: u32,
}

/// What a renderer makes of a scene file: its model of a grating and its light units.
pub trait Physics {
    /// A grating material's model.
    type Grating: std::fmt::Debug + Clone + Send + Sync;
    /// The scene's light units (the paper's environment, or radiometry).
    type Units: std::fmt::Debug + Clone + Send + Sync;
    /// Checked first: `Err` at the field that makes the scene another renderer's, saying which.
    fn accepts(raw: &RawScene) -> Check<()>;
    /// The grating model `name` of the material at `path` (its keys are those the model takes,
    /// `period` in nm is checked).
    fn grating(name: &str, raw: &RawGrating, period: f64, path: &str) -> Check<Self::Grating>;
    /// The light units, once the lights and the materials are built.
    fn units(
        raw: &RawScene,
        lights: &[Light],
        materials: &[Material<Self::Grating>],
        spectral: &Spectral,
    ) -> Check<Self::Units>;
}

/// A loaded scene.
#[derive(Debug, Clone)]
pub struct Scene<P: Physics> {
    /// The file name without `.toml`.
    pub name: String,
    /// The file's `description` (may be empty).
    pub description: String,
    /// `[render]`, after the command line's overrides.
    pub settings: Settings,
    /// `[camera]`.
    pub camera: Camera,
    /// `[[lights]]`.
    pub lights: Vec<Light>,
    /// `[[objects]]`.
    pub objects: Vec<Primitive>,
    /// One material per object (`objects[i].material` is an index into it).
    pub materials: Vec<Material<P::Grating>>,
    /// The colour integrator of the scene's illuminant (`render.illuminant`).
    pub spectral: Spectral,
    /// What the renderer's [`Physics`] makes of the light units.
    pub units: P::Units,
    /// The files read: the scene file (when loaded from one) and its textures.
    pub inputs: Vec<Input>,
}

impl<P: Physics> Scene<P> {
    /// Switches every grating that uses the default strategy to `strategy`.
    pub fn set_strategy(&mut self, strategy: Colour) {
        self.settings.strategy = strategy;
        for g in self.materials.iter_mut().filter_map(|m| m.grating.as_mut()) {
            if g.follows_default {
                g.strategy = strategy;
            }
        }
    }
}

fn file_error(file: &str, message: String) -> SceneError {
    SceneError::new(file, None, None, message)
}

/// Loads and checks a scene file of at most [`limits::MAX_SCENE_BYTES`].
pub fn load<P: Physics>(path: &Path) -> Result<Scene<P>, SceneError> {
    let file = path.display().to_string();
    let cannot = |e: std::io::Error| file_error(&file, format!("cannot read the scene file: {e}"));
    let too_big = || {
        file_error(
            &file,
            format!(
                "the scene file is larger than the limit of {} bytes",
                limits::MAX_SCENE_BYTES
            ),
        )
    };
    // A FIFO would block the open and a device never ends: only regular files are read.
    if !std::fs::metadata(path).map_err(cannot)?.is_file() {
        return Err(file_error(
            &file,
            "the scene file is not a regular file (a directory, a device or a FIFO)".into(),
        ));
    }
    let f = std::fs::File::open(path).map_err(cannot)?;
    if f.metadata()
        .is_ok_and(|m| m.len() > limits::MAX_SCENE_BYTES)
    {
        return Err(too_big());
    }
    // Devices and pipes have no length: read one byte past the limit at most.
    let mut bytes = Vec::new();
    f.take(limits::MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() as u64 > limits::MAX_SCENE_BYTES {
        return Err(too_big());
    }
    let src = String::from_utf8(bytes)
        .map_err(|e| file_error(&file, format!("the scene file is not UTF-8 text: {e}")))?;
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    let base = path.parent().unwrap_or(Path::new("."));
    let mut scene = parse::<P>(&src, &file, &name, base)?;
    scene.inputs.insert(0, Input::new("the scene file", path));
    Ok(scene)
}

/// Parses and checks scene text; `file` names it in errors, `base` resolves image paths.
pub fn parse<P: Physics>(
    src: &str,
    file: &str,
    name: &str,
    base: &Path,
) -> Result<Scene<P>, SceneError> {
    let err = |line, field, message| SceneError::new(file, line, field, message);
    if src.len() as u64 > limits::MAX_SCENE_BYTES {
        return Err(err(
            None,
            None,
            format!(
                "the scene is larger than the limit of {} bytes",
                limits::MAX_SCENE_BYTES
            ),
        ));
    }
    // Syntax.
    let doc = DeTable::parse(src).map_err(|e| {
        let line = e.span().map(|s| line_of(src, s.start));
        err(line, None, format!("invalid TOML: {}", e.message().trim()))
    })?;
    // Counts, before anything is deserialised.
    for key in ["objects", "lights"] {
        let n = doc
            .get_ref()
            .iter()
            .find(|(k, _)| k.get_ref() == key)
            .and_then(|(_, v)| match v.get_ref() {
                DeValue::Array(a) => Some(a.len()),
                _ => None,
            })
            .unwrap_or(0);
        if n > limits::MAX_OBJECTS {
            let line = line_of(src, locate(&doc, key).start);
            return Err(err(
                Some(line),
                Some(key.to_string()),
                format!("expected at most {} {key}, got {n}", limits::MAX_OBJECTS),
            ));
        }
    }
    // Keys and types.
    let raw: RawScene = toml::from_str(src).map_err(|e| {
        let mut offset = e.span().filter(|s| !s.is_empty()).map(|s| s.start);
        let mut field = e.span().and_then(|s| path_at(&doc, s));
        let mut message = plain_message(e.message());
        let material = field.clone().filter(|f| f.ends_with(".material"));
        let key = material.as_ref().and_then(|m| {
            let table: toml::Table = toml::from_str(src).ok()?;
            culprit(value_at(&table, m)?.as_table()?)
        });
        if let (Some(m), Some(key)) = (material, key) {
            // A tagged material reports the whole table: name the key that fails.
            if message.starts_with("unknown field") && !key.contains('.') {
                message = format!("{message} (or one of {COMMON_KEYS})");
            }
            let path = format!("{m}.{key}");
            offset = Some(locate(&doc, &path).start);
            field = Some(path);
        } else if let Some(missing) = message
            .strip_prefix("missing field `")
            .and_then(|m| m.split('`').next())
        {
            // "missing field `x`" is reported at the table that lacks it.
            field = Some(match field {
                Some(f) => format!("{f}.{missing}"),
                None => missing.to_string(),
            });
        }
        // An integer field's value that is no integer of its type names the field's range.
        // (The document may hold no toml::Value of the number: the model is read as written.)
        let range = field.as_deref().and_then(|f| {
            let model = f.strip_suffix(".slits").and_then(|m| {
                let text = src.get(locate(&doc, &format!("{m}.model")))?.trim();
                text.strip_prefix('"')?.strip_suffix('"')
            });
            limits::integer_range(f, model)
        });
        if let (Some((min, max)), Some(f)) = (range, &field) {
            let got = src.get(locate(&doc, f)).unwrap_or("").trim();
            message = format!("expected an integer in [{min}, {max}], got {got}");
        }
        err(offset.map(|o| line_of(src, o)), field, message)
    })?;
    // Values.
    let other_renderer = P::accepts(&raw).err();
    let built = match other_renderer.clone() {
        Some(e) => Err(e),
        None => build::<P>(raw, name, base),
    };
    built.map_err(|e| {
        // A field not in the file at all (a missing table) has no line.
        let span = locate(&doc, &e.path);
        let line = (span != doc.span()).then(|| line_of(src, span.start));
        let mut error = err(line, Some(e.path), e.message);
        error.other_renderer = other_renderer.is_some();
        error
    })
}

fn expect(path: &str, ok: bool, what: &str, got: impl std::fmt::Display) -> Check<()> {
    if ok {
        Ok(())
    } else {
        Err(FieldError::new(path, format!("expected {what}, got {got}")))
    }
}

/// Three numbers, each in `range`.
pub fn vec3(path: &str, v: [f64; 3], range: Range) -> Check<DVec3> {
    for (i, c) in v.iter().enumerate() {
        check(&format!("{path}[{i}]"), *c, range)?;
    }
    Ok(DVec3::from_array(v))
}

/// The strategy named `s` at `path`, within the work limits.
pub fn parse_strategy(path: &str, s: &str) -> Check<Colour> {
    limits::parse_strategy(s).map_err(|e| FieldError::new(path, format!("{e}, got \"{s}\"")))
}

fn build<P: Physics>(raw: RawScene, name: &str, base: &Path) -> Check<Scene<P>> {
    let r = &raw.render;
    let illuminant = match r.illuminant.as_deref() {
        None => Illuminant::D65,
        Some(s) => s.parse().map_err(|e: diffraction::ParseError| {
            FieldError::new("render.illuminant", format!("{e}, got \"{s}\""))
        })?,
    };
    let settings = Settings {
        width: count("render.width", r.width.unwrap_or(480), 1, limits::MAX_SIZE)?,
        height: count(
            "render.height",
            r.height.unwrap_or(360),
            1,
            limits::MAX_SIZE,
        )?,
        spp: count("render.spp", r.spp.unwrap_or(4), 1, limits::MAX_SPP)?,
        max_depth: count(
            "render.max_depth",
            r.max_depth.unwrap_or(5),
            0,
            limits::MAX_DEPTH,
        )?,
        seed: r.seed.unwrap_or(1),
        clip: match r.clip.as_deref() {
            None => Clip::Intensity,
            Some(s) => s.parse().map_err(|e: diffraction::ParseError| {
                FieldError::new("render.clip", format!("{e}, got \"{s}\""))
            })?,
        },
        strategy: match r.strategy.as_deref() {
            None => Colour::DEFAULT,
            Some(s) => parse_strategy("render.strategy", s)?,
        },
    };
    let size = if r.height.is_some() {
        "render.height"
    } else {
        "render.width"
    };
    limits::pixels(settings.width, settings.height).map_err(|e| FieldError::new(size, e))?;
    limits::work(settings.width, settings.height, settings.spp, 1)
        .map_err(|e| FieldError::new("render.spp", e))?;

    let c = &raw.camera;
    let up = c.up.unwrap_or([0.0, 1.0, 0.0]);
    let camera = Camera {
        position: vec3("camera.position", c.position, limits::COORDINATE)?,
        look_at: vec3("camera.look_at", c.look_at, limits::COORDINATE)?,
        up: vec3("camera.up", up, limits::COORDINATE)?.normalize_or_zero(),
        fov_deg: check("camera.fov_deg", c.fov_deg.unwrap_or(40.0), limits::FOV_DEG)?,
    };
    let forward = camera.look_at - camera.position;
    expect(
        "camera.look_at",
        forward.length() > 1e-9,
        "a point different from camera.position",
        "the same point",
    )?;
    expect(
        "camera.up",
        forward.normalize().cross(camera.up).length() > 1e-9,
        "a non-zero direction not parallel to the view direction",
        format!("{up:?}"),
    )?;

    let color = |path: &str, v: [f64; 3]| vec3(path, v, limits::COLOR);
    let mut lights = Vec::new();
    let mut shadow_rays = 0u64;
    for (i, l) in raw.lights.iter().enumerate() {
        let p = format!("lights[{i}]");
        let color = color(&format!("{p}.color"), l.color.unwrap_or([1.0, 1.0, 1.0]))?;
        let intensity = check(
            &format!("{p}.intensity"),
            l.intensity.unwrap_or(1.0),
            limits::COLOR,
        )?;
        let radius = zero_or(
            &format!("{p}.radius"),
            l.radius.unwrap_or(0.0),
            limits::LENGTH,
        )?;
        let samples = count(
            &format!("{p}.samples"),
            l.samples.unwrap_or(if radius > 0.0 { 8 } else { 1 }),
            1,
            limits::MAX_LIGHT_SAMPLES,
        )?;
        let samples = if radius > 0.0 { samples } else { 1 };
        shadow_rays += samples as u64;
        if shadow_rays > limits::MAX_SHADOW_RAYS {
            // The default count is not in the file: then the light is named.
            return Err(FieldError::new(
                if l.samples.is_some() {
                    format!("{p}.samples")
                } else {
                    p
                },
                format!(
                    "the lights' shadow samples add up to {shadow_rays}, more than the limit of \
                     {} rays from each hit",
                    limits::MAX_SHADOW_RAYS
                ),
            ));
        }
        lights.push(Light {
            position: vec3(&format!("{p}.position"), l.position, limits::COORDINATE)?,
            color: color * intensity,
            radius,
            samples,
        });
    }

    let spectral = Spectral::new(illuminant);
    let mut loader = Loader::new(settings.strategy, base, name);
    let mut objects = Vec::new();
    let mut materials = Vec::new();
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
        let translate = vec3(
            &format!("{p}.translate"),
            o.translate.unwrap_or([0.0; 3]),
            limits::COORDINATE,
        )?;
        let rotate = vec3(
            &format!("{p}.rotate_deg"),
            o.rotate_deg.unwrap_or([0.0; 3]),
            limits::ANGLE_DEG,
        )?;
        let scale = match o.scale {
            None => DVec3::ONE,
            Some(Scale::Uniform(s)) => {
                DVec3::splat(check(&format!("{p}.scale"), s, limits::SCALE)?)
            }
            Some(Scale::Axes(a)) => vec3(&format!("{p}.scale"), a, limits::SCALE)?,
        };
        let transform = Transform::new(translate, rotate, scale).ok_or_else(|| {
            FieldError::new(format!("{p}.scale"), "expected an invertible transform")
        })?;
        let material = loader.material::<P>(&o.material, &format!("{p}.material"))?;
        objects.push(Primitive {
            shape,
            transform,
            material: materials.len(),
        });
        materials.push(material);
    }

    let units = P::units(&raw, &lights, &materials, &spectral)?;
    Ok(Scene {
        name: name.to_string(),
        description: raw.description.unwrap_or_default(),
        settings,
        camera,
        lights,
        objects,
        materials,
        spectral,
        units,
        inputs: loader.inputs,
    })
}
