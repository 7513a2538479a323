//! Scene files (TOML) and the scene they describe.
//!
//! A scene file has the tables `[render]`, `[camera]`, `[environment]`, an array `[[lights]]`
//! and an array `[[objects]]`, each object with a `[objects.material]` (and, for gratings, a
//! `[objects.material.field]`). See `examples/scenes/fig4a.toml` for a commented example, and
//! `examples/scenes/baselines/compare.toml` for the grating `model` key (Agu-Hill, Thorman, Stam).
//!
//! Loading has two stages: serde checks the keys and types ([`crate::schema`]; unknown keys are
//! errors), then [`build`] checks every value against the documented ranges of
//! [`crate::limits`] and builds the scene. Either stage's error names the file, the line and
//! the field path, and says what is expected. The file's size and its numbers of objects and
//! lights are checked before it is deserialised, a texture's size before it is decoded.

use std::collections::HashMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use diffraction::cie::Illuminant;
use diffraction::color::Clip;
use diffraction::frame::{GratingField, Tile};
use diffraction::spectrum::{Spectral, Strategy};
use diffraction::{AguHill, Grating, Illumination, Thorman};
use glam::DVec3;
use toml::de::{DeTable, DeValue};

use crate::diagnostics::{
    line_of, locate, path_at, plain_message, value_at, FieldError, SceneError,
};
use crate::geometry::{Primitive, Shape, Transform};
use crate::limits::{self, check, count, zero_or, Range};
use crate::material::{model_exposure, Albedo, GratingMaterial, Material, Model};
use crate::schema::{
    culprit, RawField, RawGrating, RawKind, RawMaterial, RawScene, RawTile, Scale, COMMON_KEYS,
};
use crate::texture::{ImageTexture, Wood};

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
    /// Which materials' strategy came from the scene's `[render]` default (and follows
    /// [`Scene::set_strategy`]).
    follows_default: Vec<bool>,
    /// The physical units of a radiometric scene (its `[radiometry]` table).
    pub radiometry: Option<crate::radiometric::Radiometry>,
    /// How the diffraction colour is filtered (`--filter`, [`crate::footprint::prepare`]).
    pub filter: crate::footprint::Filter,
    /// The colour table of each material, where [`filter`](Self::filter) uses one (empty or
    /// `None` otherwise).
    pub tables: Vec<Option<std::sync::Arc<diffraction::ColorTable>>>,
}

impl Scene {
    /// Switches every grating that uses the default strategy to `strategy` (and recomputes its
    /// exposure).
    pub fn set_strategy(&mut self, strategy: Strategy) {
        self.settings.strategy = strategy;
        let mut exposures = Exposures::default();
        for (m, follows) in self.materials.iter_mut().zip(&self.follows_default) {
            if let (Some(g), true) = (&mut m.grating, *follows) {
                g.strategy = strategy;
                g.exposure = exposures.get(&self.spectral, &g.model, strategy);
            }
        }
    }
}

/// The exposures of the distinct (model, strategy) pairs of a scene, each scanned once.
#[derive(Debug, Default)]
struct Exposures(HashMap<String, f64>);

impl Exposures {
    fn get(&mut self, spectral: &Spectral, model: &Model, strategy: Strategy) -> f64 {
        // Debug prints every parameter exactly (shortest round-trip floats).
        let key = format!("{model:?} {strategy:?}");
        *self
            .0
            .entry(key)
            .or_insert_with(|| model_exposure(spectral, model, strategy))
    }

    fn len(&self) -> usize {
        self.0.len()
    }
}

fn file_error(file: &str, message: String) -> SceneError {
    SceneError {
        file: file.to_string(),
        line: None,
        field: None,
        message,
    }
}

/// Loads and checks a scene file of at most [`limits::MAX_SCENE_BYTES`].
pub fn load(path: &Path) -> Result<Scene, SceneError> {
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

/// Three numbers, each in `range`.
fn vec3(path: &str, v: [f64; 3], range: Range) -> Check<DVec3> {
    for (i, c) in v.iter().enumerate() {
        check(&format!("{path}[{i}]"), *c, range)?;
    }
    Ok(DVec3::from_array(v))
}

fn parse_strategy(path: &str, s: &str) -> Check<Strategy> {
    limits::parse_strategy(s).map_err(|e| FieldError::new(path, format!("{e}, got \"{s}\"")))
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
            Some(s) => s.parse().map_err(|e: diffraction::color::ParseClipError| {
                FieldError::new("render.clip", format!("{e}, got \"{s}\""))
            })?,
        },
        strategy: match r.strategy.as_deref() {
            None => Strategy::PeakSearch { refine: false },
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

    let env = &raw.environment;
    let color = |path: &str, v: [f64; 3]| vec3(path, v, limits::COLOR);
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

    let mut loader = Loader {
        settings: &settings,
        spectral: Spectral::new(illuminant),
        base,
        images: HashMap::new(),
        texels: 0,
        exposures: Exposures::default(),
    };
    let mut objects = Vec::new();
    let mut materials = Vec::new();
    let mut follows_default = Vec::new();
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
        let (material, follows) = loader.material(&o.material, &format!("{p}.material"))?;
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
        spectral: loader.spectral,
        follows_default,
        radiometry,
        filter: crate::footprint::Filter::None,
        tables: Vec::new(),
    })
}

/// What building the materials shares: the settings, the colour integrator, the textures
/// loaded so far (and their texels, against [`limits::MAX_TEXTURE_PIXELS`]) and the exposures
/// measured so far.
struct Loader<'a> {
    settings: &'a Settings,
    spectral: Spectral,
    base: &'a Path,
    images: HashMap<PathBuf, Arc<ImageTexture>>,
    texels: u64,
    exposures: Exposures,
}

impl Loader<'_> {
    /// The material at `path`, and whether its strategy follows the scene default.
    fn material(&mut self, m: &RawMaterial, path: &str) -> Check<(Material, bool)> {
        let f = |name: &str| format!("{path}.{name}");
        let color = |name: &str, v: Option<[f64; 3]>, default: [f64; 3]| {
            vec3(&f(name), v.unwrap_or(default), limits::COLOR)
        };
        let is_mirror = matches!(m.kind, RawKind::Mirror { .. });
        let ka = check(&f("ambient"), m.ambient.unwrap_or(1.0), limits::COEFFICIENT)?;
        let kd = check(
            &f("diffuse"),
            m.diffuse.unwrap_or(if is_mirror { 0.1 } else { 1.0 }),
            limits::COEFFICIENT,
        )?;
        let mirror = check(
            &f("mirror"),
            m.mirror.unwrap_or(if is_mirror { 0.9 } else { 0.0 }),
            limits::FRACTION,
        )?;
        let mirror_tint = color("mirror_color", m.mirror_color, [1.0; 3])?;
        let (albedo, grating) = match &m.kind {
            RawKind::Diffuse { color: c } => (Albedo::Solid(color("color", *c, [0.7; 3])?), None),
            RawKind::Mirror { color: c } => (Albedo::Solid(color("color", *c, [0.05; 3])?), None),
            RawKind::Wood {
                light,
                dark,
                ring_spacing,
                turbulence,
                plank_width,
                plank_length,
            } => {
                let wood = Wood {
                    light: color("light", *light, [0.62, 0.40, 0.20])?,
                    dark: color("dark", *dark, [0.30, 0.16, 0.07])?,
                    ring_spacing: check(
                        &f("ring_spacing"),
                        ring_spacing.unwrap_or(0.05),
                        limits::LENGTH,
                    )?,
                    turbulence: check(
                        &f("turbulence"),
                        turbulence.unwrap_or(1.5),
                        limits::COEFFICIENT,
                    )?,
                    plank_width: zero_or(
                        &f("plank_width"),
                        plank_width.unwrap_or(0.0),
                        limits::LENGTH,
                    )?,
                    plank_length: zero_or(
                        &f("plank_length"),
                        plank_length.unwrap_or(0.0),
                        limits::LENGTH,
                    )?,
                };
                (Albedo::Wood(wood), None)
            }
            RawKind::Image { image, color: c } => {
                let texture = self.texture(image.as_deref(), &f("image"))?;
                let other = color("color", *c, [0.7; 3])?;
                (Albedo::Image { texture, other }, None)
            }
            RawKind::Grating(g) => {
                let base_color = color("color", g.color, [0.7; 3])?;
                let (grating, shading, follows) = self.grating(g, path, (ka, kd), base_color)?;
                return Ok((
                    Material {
                        albedo: Albedo::Solid(base_color),
                        shading,
                        mirror,
                        mirror_tint,
                        grating: Some(grating),
                    },
                    follows,
                ));
            }
        };
        Ok((
            Material {
                albedo,
                shading: Illumination::new(ka, kd, 0.0)
                    .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?,
                mirror,
                mirror_tint,
                grating,
            },
            true,
        ))
    }

    /// The image texture named `name` (relative to the scene file), loaded once per file.
    fn texture(&mut self, name: Option<&str>, path: &str) -> Check<Arc<ImageTexture>> {
        let Some(name) = name else {
            return Err(FieldError::new(
                path,
                "expected the path of a PNG image (relative to the scene file)",
            ));
        };
        let file = self.base.join(name);
        if let Some(t) = self.images.get(&file) {
            return Ok(t.clone());
        }
        let budget = limits::MAX_TEXTURE_PIXELS - self.texels;
        let t = Arc::new(ImageTexture::load(&file, budget).map_err(|e| {
            FieldError::new(
                path,
                format!("{e} (the can label is made by `raytrace make-label`)"),
            )
        })?);
        self.texels += t.texels();
        self.images.insert(file, t.clone());
        Ok(t)
    }

    /// The grating of a grating material, and whether its strategy follows the scene default.
    fn grating(
        &mut self,
        g: &RawGrating,
        path: &str,
        (ka, kd): (f64, f64),
        base_color: DVec3,
    ) -> Check<(GratingMaterial, Illumination, bool)> {
        let f = |name: &str| format!("{path}.{name}");
        let period = match (g.period_nm, g.lines_per_mm) {
            (Some(_), Some(_)) => {
                return Err(FieldError::new(
                    f("lines_per_mm"),
                    "give either period_nm or lines_per_mm, not both",
                ))
            }
            (Some(d), None) => check(&f("period_nm"), d, limits::PERIOD_NM)?,
            (None, Some(l)) => 1.0e6 / check(&f("lines_per_mm"), l, limits::LINES_PER_MM)?,
            (None, None) => {
                return Err(FieldError::new(
                    f("period_nm"),
                    "missing: a grating needs period_nm (or lines_per_mm)",
                ))
            }
        };
        let kdiff = check(
            &f("diffraction"),
            g.diffraction.unwrap_or(1.0),
            limits::COEFFICIENT,
        )?;
        let shading = Illumination::new(ka, kd, kdiff)
            .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?;
        let model = build_model(g, path, period)?;
        let (strategy, follows) = match &g.strategy {
            Some(s) => (parse_strategy(&f("strategy"), s)?, false),
            None => (self.settings.strategy, true),
        };
        let (field, plain_albedo) = match &g.field {
            None => (GratingField::constant(0.0), base_color),
            Some(field) => build_field(field, &f("field"), base_color)?,
        };
        let exposure = self.exposures.get(&self.spectral, &model, strategy);
        if self.exposures.len() > limits::MAX_GRATINGS {
            return Err(FieldError::new(
                path,
                format!(
                    "more than {} distinct gratings (each needs an exposure scan)",
                    limits::MAX_GRATINGS
                ),
            ));
        }
        Ok((
            GratingMaterial {
                exposure,
                model,
                field,
                strategy,
                plain_albedo,
            },
            shading,
            follows,
        ))
    }
}

/// The grating's diffraction model (`model`, default "agu-hill") and its parameters; a
/// parameter of another model is an error, and so is a Stam model in a build without the
/// `stam` feature.
fn build_model(g: &RawGrating, path: &str, period: f64) -> Check<Model> {
    let f = |name: &str| format!("{path}.{name}");
    let name = g.model.as_deref().unwrap_or("agu-hill");
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
    for (key, is_set) in g.parameters() {
        if is_set && !takes.contains(&key) {
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
            "period_nm" if g.period_nm.is_none() => "lines_per_mm",
            p => p,
        };
        FieldError::new(f(field), e.to_string())
    };
    match name {
        "agu-hill" => {
            let width = check(
                &f("slit_width_nm"),
                g.slit_width_nm.unwrap_or(period / 2.0),
                limits::SLIT_WIDTH_NM,
            )?;
            let slits = g.slits.unwrap_or(1000);
            count(&f("slits"), slits, 1, limits::SLITS.max as u64)?;
            let grating = Grating::new(period, width, slits as u32).map_err(crate_error)?;
            Ok(Model::AguHill(AguHill::new(grating)))
        }
        "thorman" => {
            let lobe = check(
                &f("lobe_width"),
                g.lobe_width.unwrap_or(0.005),
                limits::LOBE_WIDTH,
            )?;
            Ok(Model::Thorman(
                Thorman::new(period, lobe).map_err(crate_error)?,
            ))
        }
        "radiometric" => crate::radiometric::grating_model(
            period,
            g.slit_width_nm,
            g.slits,
            g.coherence_nm,
            g.groove_sigma,
            path,
        ),
        _ => {
            for (key, v, range) in [
                ("depth_nm", g.depth_nm, limits::DEPTH_NM),
                ("fraction", g.fraction, limits::FRACTION),
                ("coherence_nm", g.coherence_nm, limits::COHERENCE_NM),
                ("reflectance", g.reflectance, limits::FRACTION),
            ] {
                if let Some(v) = v {
                    check(&f(key), v, range)?;
                }
            }
            stam_model(g, path, name, period, &crate_error)
        }
    }
}

/// `stam-sine` or `stam-binary`: depth_nm (default 100), coherence_nm (default 10 periods),
/// fraction (binary, default 0.5), reflectance (default 1).
#[cfg(feature = "stam")]
fn stam_model(
    g: &RawGrating,
    _: &str,
    name: &str,
    period: f64,
    crate_error: &dyn Fn(diffraction::Error) -> FieldError,
) -> Check<Model> {
    use diffraction::{Profile, Stam};
    let profile = match name {
        "stam-sine" => Profile::Sine,
        _ => Profile::Binary {
            fraction: g.fraction.unwrap_or(0.5),
        },
    };
    let stam = Stam::new(
        profile,
        period,
        g.depth_nm.unwrap_or(100.0),
        g.coherence_nm.unwrap_or(10.0 * period),
    )
    .and_then(|s| s.with_reflectance(g.reflectance.unwrap_or(1.0)))
    .map_err(crate_error)?;
    Ok(Model::Stam(stam))
}

#[cfg(not(feature = "stam"))]
fn stam_model(
    _: &RawGrating,
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
    Ok(check(path, v.unwrap_or(0.0), limits::ANGLE_DEG)?.to_radians())
}

fn center(path: &str, v: Option<[f64; 2]>) -> Check<[f64; 2]> {
    let c = v.unwrap_or([0.0, 0.0]);
    check(&format!("{path}[0]"), c[0], limits::COORDINATE)?;
    check(&format!("{path}[1]"), c[1], limits::COORDINATE)?;
    Ok(c)
}

fn build_tile(t: &RawTile, path: &str) -> Check<Tile> {
    let f = |name: &str| format!("{path}.{name}");
    Ok(match t {
        RawTile::Plain {} => Tile::Plain,
        RawTile::Constant {
            angle_deg,
            twist_deg,
        } => Tile::Constant {
            angle: degrees(&f("angle_deg"), *angle_deg)? + degrees(&f("twist_deg"), *twist_deg)?,
        },
        RawTile::Radial {
            center: c,
            twist_deg,
        } => Tile::Radial {
            center: center(&f("center"), *c)?,
            twist: degrees(&f("twist_deg"), *twist_deg)?,
        },
    })
}

/// The field and the albedo of its plain squares.
fn build_field(fd: &RawField, path: &str, base_color: DVec3) -> Check<(GratingField, DVec3)> {
    let f = |name: &str| format!("{path}.{name}");
    let (field, twist, plain) = match fd {
        RawField::Constant {
            angle_deg,
            twist_deg,
        } => (
            GratingField::constant(degrees(&f("angle_deg"), *angle_deg)?),
            twist_deg,
            None,
        ),
        RawField::Radial {
            center: c,
            twist_deg,
        } => (
            GratingField::Uniform(Tile::Radial {
                center: center(&f("center"), *c)?,
                twist: 0.0,
            }),
            twist_deg,
            None,
        ),
        RawField::Checkerboard {
            cell_size,
            even,
            odd,
            plain_color,
            twist_deg,
        } => {
            let cell = check(&f("cell_size"), cell_size.unwrap_or(0.25), limits::LENGTH)?;
            let even = match even {
                Some(t) => build_tile(t, &f("even"))?,
                None => Tile::Constant { angle: 0.0 },
            };
            let odd = match odd {
                Some(t) => build_tile(t, &f("odd"))?,
                None => Tile::Plain,
            };
            let field = GratingField::checkerboard(cell, even, odd)
                .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?;
            (field, twist_deg, plain_color.as_ref())
        }
    };
    let field = field
        .twisted(degrees(&f("twist_deg"), *twist)?)
        .map_err(|e| FieldError::new(f("twist_deg"), e.to_string()))?;
    let plain = match plain {
        Some(c) => vec3(&f("plain_color"), *c, limits::COLOR)?,
        None => base_color,
    };
    Ok((field, plain))
}
