//! Materials: a diffuse colour source (solid, wood, image), optional mirror reflection, the
//! coefficients of the paper's eq. 12, and for diffraction gratings a grating-direction field
//! with the renderer's model of the grating (see [`crate::scene::Physics`]).
//!
//! [`Loader`] builds them from the scene file's `[objects.material]` tables, checking every value
//! against [`crate::limits`], loading each texture once.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use diffraction::frame::{GratingField, Tile};
use diffraction::relief::{EfficiencyTable, Preset};
use diffraction::Illumination;
use glam::DVec3;

use crate::colour::Colour;
use crate::diagnostics::{Check, FieldError};
use crate::files::Input;
use crate::geometry::{Hit, Part};
use crate::limits::{self, check, zero_or};
use crate::scene::{parse_strategy, vec3, Physics};
use crate::schema::{RawField, RawGrating, RawKind, RawMaterial, RawTile, MODELS};
use crate::texture::{ImageTexture, Wood};

/// Where the diffuse colour of a surface comes from.
#[derive(Debug, Clone)]
pub enum Albedo {
    /// One colour (linear sRGB).
    Solid(DVec3),
    /// Procedural wood.
    Wood(Wood),
    /// An image on the side of a cylinder (a can's label); `other` colours the caps and any
    /// other part.
    Image {
        /// The image.
        texture: Arc<ImageTexture>,
        /// The colour of the caps and other parts.
        other: DVec3,
    },
}

impl Albedo {
    /// The colour at a hit (linear sRGB).
    pub fn at(&self, hit: &Hit) -> DVec3 {
        match self {
            Albedo::Solid(c) => *c,
            Albedo::Wood(w) => w.albedo(hit.object_point),
            Albedo::Image { texture, other } => match hit.part {
                Part::Side | Part::Face => texture.sample(hit.uv),
                Part::Cap => *other,
            },
        }
    }

    /// An upper bound of the colour's components (textures: their brightest parameter; image
    /// texels are in [0, 1]).
    pub fn max_component(&self) -> f64 {
        match self {
            Albedo::Solid(c) => c.max_element(),
            Albedo::Wood(w) => w.light.max_element().max(w.dark.max_element()),
            Albedo::Image { other, .. } => other.max_element().max(1.0),
        }
    }
}

/// A surface material; `G` is the renderer's grating model.
#[derive(Debug, Clone)]
pub struct Material<G> {
    /// The diffuse colour.
    pub albedo: Albedo,
    /// The coefficients of the paper's eq. 12 (k_a, k_d, k_diffraction), validated by the
    /// crate: the only place they are kept.
    pub shading: Illumination,
    /// Fraction of perfect mirror reflection (0: none), tinted by `mirror_tint`.
    pub mirror: f64,
    /// The mirror reflection's colour (linear sRGB).
    pub mirror_tint: DVec3,
    /// The diffraction grating, for diffractive materials; `None` costs nothing spectral.
    pub grating: Option<GratingMaterial<G>>,
}

/// A diffraction grating material: the renderer's model of the grating over a field of
/// grating directions.
#[derive(Debug, Clone)]
pub struct GratingMaterial<G> {
    /// The diffraction model.
    pub model: G,
    /// The grating vector across the surface (constant, twisted, radial, checkerboard).
    pub field: GratingField,
    /// How the spectral integral is evaluated.
    pub strategy: Colour,
    /// Whether `strategy` is the scene's default (and follows `--strategy`).
    pub follows_default: bool,
    /// The diffuse colour of the plain (non-grating) squares of a checkerboard.
    pub plain_albedo: DVec3,
    /// The preset whose efficiencies the model reads (`efficiency` naming one); `None` for a
    /// table file, the amplitude reading and the models without efficiencies.
    pub preset: Option<Preset>,
}

impl<G> GratingMaterial<G> {
    /// Whether the field has a grating at the tangent point `p` (not a plain square).
    pub fn is_plain_at(&self, p: glam::DVec2) -> bool {
        matches!(self.field.tile_at(p), Tile::Plain)
    }
}

/// What building the materials shares: the default strategy, the textures loaded so far (one
/// per file, whatever its spelling, and their texels, against [`limits::MAX_TEXTURE_PIXELS`])
/// and the distinct gratings so far (against [`limits::MAX_GRATINGS`]).
pub struct Loader<'a> {
    /// The scene's default strategy.
    pub strategy: Colour,
    /// The directory that texture paths are relative to.
    pub base: &'a Path,
    /// The scene's name, for the inputs' descriptions.
    pub scene: &'a str,
    images: HashMap<PathBuf, Arc<ImageTexture>>,
    tables: HashMap<PathBuf, TableFile>,
    texels: u64,
    gratings: std::collections::HashSet<String>,
    /// The texture and table files read (inputs of the run, never written over).
    pub inputs: Vec<Input>,
}

impl<'a> Loader<'a> {
    /// A loader with the scene's default strategy, resolving textures in `base`.
    pub fn new(strategy: Colour, base: &'a Path, scene: &'a str) -> Loader<'a> {
        Loader {
            strategy,
            base,
            scene,
            images: HashMap::new(),
            tables: HashMap::new(),
            texels: 0,
            gratings: Default::default(),
            inputs: Vec::new(),
        }
    }

    /// The material at `path`.
    pub fn material<P: Physics>(
        &mut self,
        m: &RawMaterial,
        path: &str,
    ) -> Check<Material<P::Grating>> {
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
        let mut kdiff = 0.0;
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
                let (grating, k) = self.grating::<P>(g, path, base_color)?;
                kdiff = k;
                (Albedo::Solid(base_color), Some(grating))
            }
        };
        Ok(Material {
            albedo,
            shading: Illumination::new(ka, kd, kdiff)
                .map_err(|e| FieldError::new(f(e.parameter()), e.to_string()))?,
            mirror,
            mirror_tint,
            grating,
        })
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
        // One file under two spellings (`a.png`, `./a.png`, links) is loaded and counted once.
        let key = file.canonicalize().unwrap_or_else(|_| file.clone());
        if let Some(t) = self.images.get(&key) {
            return Ok(t.clone());
        }
        let budget = limits::MAX_TEXTURE_PIXELS - self.texels;
        let t = Arc::new(ImageTexture::load(&file, budget).map_err(|e| {
            let hint = if is_the_label(&file) {
                " (the can label is made by `raytrace make-label`)"
            } else {
                ""
            };
            FieldError::new(path, format!("{e}{hint}"))
        })?);
        self.texels += t.texels();
        self.images.insert(key, t.clone());
        self.inputs
            .push(Input::new(format!("a texture of {}", self.scene), &file));
        Ok(t)
    }

    /// The efficiency table of file `name` (relative to the scene file), for the field at
    /// `path`: a regular file of at most [`limits::MAX_TABLE_BYTES`] (its type and size checked
    /// before it is opened, so a FIFO or a device is refused without blocking, and read
    /// through a `take`), UTF-8, the JSON of docs/efficiency_tables.md read by the library's
    /// bounded reader, and its `grating.cover`. One file is read once however many materials
    /// name it.
    fn table(&mut self, name: &str, path: &str) -> Check<TableFile> {
        use std::io::Read;
        let file = self.base.join(name);
        let key = file.canonicalize().unwrap_or_else(|_| file.clone());
        if let Some(t) = self.tables.get(&key) {
            return Ok(t.clone());
        }
        let err = |msg: String| FieldError::new(path, msg);
        let cannot = |e: std::io::Error| err(format!("the table {name:?} cannot be read: {e}"));
        let meta = std::fs::metadata(&file).map_err(cannot)?;
        let not_regular = || {
            err(format!(
                "the table {name:?} is not a regular file (a directory, a device or a FIFO)"
            ))
        };
        if !meta.is_file() {
            return Err(not_regular());
        }
        let max = limits::MAX_TABLE_BYTES;
        let too_big = |size: u64| {
            err(format!(
                "the table {name:?} has {size} bytes, more than the {max} read"
            ))
        };
        if meta.len() > max {
            return Err(too_big(meta.len()));
        }
        let f = std::fs::File::open(&file).map_err(cannot)?;
        if !f.metadata().map_err(cannot)?.is_file() {
            return Err(not_regular());
        }
        let mut bytes = Vec::new();
        f.take(max + 1).read_to_end(&mut bytes).map_err(cannot)?;
        if bytes.len() as u64 > max {
            return Err(too_big(bytes.len() as u64));
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            let at = e.utf8_error().valid_up_to();
            err(format!("the table {name:?} is not UTF-8 (at byte {at})"))
        })?;
        let table = serde_json::from_str::<EfficiencyTable>(&text)
            .map_err(|e| err(format!("the table {name:?}: {e}")))?;
        // The cover (`grating.cover`, which the library's reader does not keep); the file
        // parsed as a table above, so this reading of it cannot fail on its syntax.
        let cover = serde_json::from_str::<Head>(&text)
            .ok()
            .and_then(|h| h.grating)
            .and_then(|g| g.cover);
        let t = TableFile {
            table: Arc::new(table),
            cover,
        };
        self.tables.insert(key, t.clone());
        self.inputs.push(Input::new(
            format!("an efficiency table of {}", self.scene),
            &file,
        ));
        Ok(t)
    }

    /// The grating of a grating material: its period, the model (`model`, default
    /// "agu-hill", built by the renderer's [`Physics`]), the strategy and the field; and the
    /// material's k_diffraction.
    fn grating<P: Physics>(
        &mut self,
        g: &RawGrating,
        path: &str,
        base_color: DVec3,
    ) -> Check<(GratingMaterial<P::Grating>, f64)> {
        let f = |name: &str| format!("{path}.{name}");
        let name = g.model.as_deref().unwrap_or("agu-hill");
        let Some((_, takes)) = MODELS.iter().find(|(m, _)| *m == name) else {
            let names: Vec<String> = MODELS.iter().map(|(m, _)| format!("\"{m}\"")).collect();
            return Err(FieldError::new(
                f("model"),
                format!("expected one of {}, got \"{name}\"", names.join(", ")),
            ));
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
        // A table file (the model takes `efficiency`: checked above).
        let table = match g.efficiency.as_deref() {
            Some(name) if name.ends_with(".json") => Some(self.table(name, &f("efficiency"))?),
            _ => None,
        };
        let period = match (g.period_nm, g.lines_per_mm) {
            (Some(_), Some(_)) => {
                return Err(FieldError::new(
                    f("lines_per_mm"),
                    "give either period_nm or lines_per_mm, not both",
                ))
            }
            (Some(d), None) => check(&f("period_nm"), d, limits::PERIOD_NM)?,
            (None, Some(l)) => 1.0e6 / check(&f("lines_per_mm"), l, limits::LINES_PER_MM)?,
            // A table's period.
            (None, None) if table.is_some() => table.as_ref().map_or(0.0, |t| t.table.period_nm()),
            (None, None) => match g.efficiency.as_deref().map(str::parse::<Preset>) {
                // A preset's table fixes the period.
                Some(Ok(preset)) => preset.period_nm(),
                // A name that is neither a preset nor the amplitude reading: that field is wrong,
                // not the missing period (the names are case-sensitive, as `Preset`'s).
                Some(Err(e)) if g.efficiency.as_deref() != Some("amplitude") => {
                    let name = g.efficiency.as_deref().unwrap_or_default();
                    return Err(FieldError::new(
                        f("efficiency"),
                        format!("{e} or amplitude, got {name:?}"),
                    ));
                }
                _ => {
                    return Err(FieldError::new(
                        f("period_nm"),
                        "missing: a grating needs period_nm (or lines_per_mm)",
                    ))
                }
            },
        };
        let kdiff = check(
            &f("diffraction"),
            g.diffraction.unwrap_or(1.0),
            limits::COEFFICIENT,
        )?;
        let model = match table {
            Some(file) => {
                let mut with = g.clone();
                (with.table, with.table_cover) = (Some(file.table), file.cover);
                P::grating(name, &with, period, path)?
            }
            None => P::grating(name, g, period, path)?,
        };
        let (strategy, follows_default) = match &g.strategy {
            Some(s) => (parse_strategy(&f("strategy"), s)?, false),
            None => (self.strategy, true),
        };
        let (field, plain_albedo) = match &g.field {
            None => (GratingField::constant(0.0), base_color),
            Some(field) => build_field(field, &f("field"), base_color)?,
        };
        // Debug prints every parameter exactly (shortest round-trip floats). A tabulated
        // model's Debug would print its whole table: its parameters (the preset's name or the
        // table's file as written) stand for it.
        let key = match g.efficiency.as_deref() {
            Some(e) if e != "amplitude" => {
                let mut raw = g.clone();
                (raw.table, raw.field, raw.color) = (None, None, None);
                format!("{raw:?} {period:?} {strategy:?}")
            }
            _ => format!("{model:?} {strategy:?}"),
        };
        self.gratings.insert(key);
        if self.gratings.len() > limits::MAX_GRATINGS {
            return Err(FieldError::new(
                path,
                format!(
                    "more than {} distinct gratings (each needs an exposure scan)",
                    limits::MAX_GRATINGS
                ),
            ));
        }
        let preset = g
            .efficiency
            .as_deref()
            .and_then(|e| e.parse::<Preset>().ok());
        let grating = GratingMaterial {
            model,
            field,
            strategy,
            follows_default,
            plain_albedo,
            preset,
        };
        Ok((grating, kdiff))
    }
}

/// An efficiency table file as read: the table and its `grating.cover` (`"none"`,
/// `"polycarbonate"`, or absent).
#[derive(Clone)]
struct TableFile {
    table: Arc<EfficiencyTable>,
    cover: Option<String>,
}

/// The part of a table file the library's reader skips: `grating.cover`.
#[derive(serde::Deserialize)]
struct Head {
    grating: Option<HeadGrating>,
}

#[derive(serde::Deserialize)]
struct HeadGrating {
    cover: Option<String>,
}

/// Whether `file` is the shipped can label (`tools/render/assets/label.png`), compared after
/// removing `.` and `..`.
pub fn is_the_label(file: &Path) -> bool {
    let clean = |p: &Path| -> PathBuf {
        let p = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        let mut out = PathBuf::new();
        for c in p.components() {
            match c {
                std::path::Component::CurDir => {}
                std::path::Component::ParentDir => {
                    out.pop();
                }
                c => out.push(c),
            }
        }
        out
    };
    let label = Path::new(crate::run::ROOT).join("assets/label.png");
    clean(file) == clean(&label)
}

/// The crate's error building a grating model at `path`, at the field the user wrote (the
/// period given as `lines_per_mm` is named so).
pub fn model_error(g: &RawGrating, path: &str, e: diffraction::Error) -> FieldError {
    let field = match e.parameter() {
        "period_nm" if g.period_nm.is_none() => "lines_per_mm",
        p => p,
    };
    FieldError::new(format!("{path}.{field}"), e.to_string())
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
            GratingField::uniform(Tile::Radial {
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
