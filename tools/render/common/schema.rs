//! The scene file's schema: the first of the two stages of loading (serde checks the keys and
//! the types, [`crate::scene`] the values).
//!
//! Materials, grating fields and tiles are internally tagged by their `type` key, so that each
//! type accepts exactly its own keys. Two details of serde shape it:
//!
//! - A unit variant of an internally tagged enum ignores `deny_unknown_fields` (serde issue
//!   2294), so the variants without keys are written as empty struct variants (`Plain {}`).
//! - A tagged enum is buffered before it is deserialised, so its errors carry the span of the
//!   whole material table, not of the offending key. [`culprit`] finds that key again by
//!   deserialising the table one key at a time.

use serde::de::DeserializeOwned;
use serde::Deserialize;
use toml::{Table, Value};

/// A scene file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    /// A line shown before the scene renders.
    pub description: Option<String>,
    /// `[render]`: size, samples, seed, clipping, strategy, illuminant.
    #[serde(default)]
    pub render: RawRender,
    /// `[camera]` (required).
    pub camera: RawCamera,
    /// `[environment]`: the sky and the ambient light of the paper's renderer.
    #[serde(default)]
    pub environment: RawEnvironment,
    /// `[[lights]]`.
    #[serde(default)]
    pub lights: Vec<RawLight>,
    /// `[[objects]]`.
    #[serde(default)]
    pub objects: Vec<RawObject>,
    /// `[radiometry]`: physical units (the path tracer's scenes).
    pub radiometry: Option<RawRadiometry>,
}

/// The `[radiometry]` table: the physical units of a scene for the path tracer (its docs say
/// what they mean).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRadiometry {
    /// The camera's exposure, sr·m²/W.
    pub exposure: f64,
    /// The sky's radiance at 560 nm at and below the horizon.
    pub sky_horizon: Option<f64>,
    /// The sky's radiance at 560 nm straight up (default: `sky_horizon`).
    pub sky_zenith: Option<f64>,
}

/// `[render]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRender {
    /// Picture width in pixels (default 480).
    pub width: Option<u32>,
    /// Picture height in pixels (default 360).
    pub height: Option<u32>,
    /// Camera samples per pixel (default 4).
    pub spp: Option<u32>,
    /// Bounces (default 5).
    pub max_depth: Option<u32>,
    /// Seed of the random numbers (default 1).
    pub seed: Option<u64>,
    /// The gratings' default spectral strategy (default "peaks").
    pub strategy: Option<String>,
    /// Gamut clipping: "clamp", "intensity" (default), "constant".
    pub clip: Option<String>,
    /// The light's spectrum: "D65" (default), "E", "A".
    pub illuminant: Option<String>,
}

/// `[camera]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    /// Where the camera is.
    pub position: [f64; 3],
    /// The point at the centre of the picture.
    pub look_at: [f64; 3],
    /// Up in the picture (default +y).
    pub up: Option<[f64; 3]>,
    /// Vertical field of view, degrees (default 40).
    pub fov_deg: Option<f64>,
}

/// `[environment]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnvironment {
    /// Sky colour at the horizon and below (linear sRGB).
    pub background: Option<[f64; 3]>,
    /// Sky colour straight up (default: the background).
    pub zenith: Option<[f64; 3]>,
    /// Ambient light of eq. 12 (linear sRGB).
    pub ambient: Option<[f64; 3]>,
}

/// One of `[[lights]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    /// The light's centre.
    pub position: [f64; 3],
    /// Its colour (linear sRGB, default white; white in physical units).
    pub color: Option<[f64; 3]>,
    /// Its intensity (default 1; in physical units a radiance or radiant intensity).
    pub intensity: Option<f64>,
    /// 0 (default) for a point light, else a spherical light of this radius.
    pub radius: Option<f64>,
    /// Shadow rays per hit of a spherical light (default 8).
    pub samples: Option<u32>,
}

/// An object's `scale`.
#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    /// One factor for every axis.
    Uniform(f64),
    /// One factor per axis.
    Axes([f64; 3]),
}

/// One of `[[objects]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObject {
    /// "quad", "cube", "cylinder" or "disc".
    pub shape: String,
    /// A disc's inner radius (before scaling; the disc's radius is ½).
    pub hole: Option<f64>,
    /// Where the object is moved (after scaling and rotating).
    pub translate: Option<[f64; 3]>,
    /// Rotations about x, then y, then z, degrees.
    pub rotate_deg: Option<[f64; 3]>,
    /// One factor or one per axis.
    pub scale: Option<Scale>,
    /// `[objects.material]`.
    pub material: RawMaterial,
}

/// A material: the keys every type takes, and the type's own (unknown keys are rejected by
/// the flattened, tagged [`RawKind`], which receives every key not consumed here).
#[derive(Debug, Deserialize)]
pub struct RawMaterial {
    /// k_a of eq. 12 (default 1).
    pub ambient: Option<f64>,
    /// k_d of eq. 12 (default 1; 0.1 for a mirror).
    pub diffuse: Option<f64>,
    /// The fraction of mirror reflection (default 0; 0.9 for a mirror).
    pub mirror: Option<f64>,
    /// The mirror reflection's colour (default white).
    pub mirror_color: Option<[f64; 3]>,
    /// `type` and the type's own keys.
    #[serde(flatten)]
    pub kind: RawKind,
}

/// The keys every material type takes besides its own (named in unknown-key messages).
pub const COMMON_KEYS: &str = "ambient, diffuse, mirror, mirror_color";

/// A material's `type` and its own keys.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawKind {
    /// `type = "diffuse"`: a Lambertian colour.
    Diffuse {
        /// Colour (linear sRGB).
        color: Option<[f64; 3]>,
    },
    /// `type = "mirror"`: mostly mirror reflection.
    Mirror {
        /// Colour (linear sRGB).
        color: Option<[f64; 3]>,
    },
    /// `type = "wood"`: procedural planks.
    Wood {
        /// Early wood's colour.
        light: Option<[f64; 3]>,
        /// Late wood's colour.
        dark: Option<[f64; 3]>,
        /// Distance between growth rings.
        ring_spacing: Option<f64>,
        /// Ring distortion, in ring spacings.
        turbulence: Option<f64>,
        /// Plank width (0: one block).
        plank_width: Option<f64>,
        /// Plank length (0: endless).
        plank_length: Option<f64>,
    },
    /// `type = "image"`: a PNG on a cylinder's side (a can's label).
    Image {
        /// The PNG, relative to the scene file.
        image: Option<String>,
        /// Colour (linear sRGB).
        color: Option<[f64; 3]>,
    },
    /// `type = "grating"`: a diffraction grating.
    Grating(Box<RawGrating>),
}

/// A grating: its geometry, the model (`model`, default "agu-hill") and the model's
/// parameters (checked against the model in the second stage).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGrating {
    /// The diffuse colour under the grating (default 0.7 grey).
    pub color: Option<[f64; 3]>,
    /// The period d, nm (or `lines_per_mm`).
    pub period_nm: Option<f64>,
    /// The line density (10⁶/d).
    pub lines_per_mm: Option<f64>,
    /// k_diffraction of eq. 12 (default 1).
    pub diffraction: Option<f64>,
    /// This grating's spectral strategy (default the scene's).
    pub strategy: Option<String>,
    /// The grating direction across the surface (default constant, along x).
    pub field: Option<RawField>,
    /// The diffraction model (see [`MODELS`]; default "agu-hill").
    pub model: Option<String>,
    /// The slit width w, nm (default d/2).
    pub slit_width_nm: Option<f64>,
    /// The number of coherently lit slits N (default 1000).
    pub slits: Option<u64>,
    /// Thorman's lobe width in u.
    pub lobe_width: Option<f64>,
    /// Stam's groove depth, nm.
    pub depth_nm: Option<f64>,
    /// Stam's binary profile: the grooved fraction.
    pub fraction: Option<f64>,
    /// Stam's coherence width, or the radiometric grating's coherence length, nm.
    pub coherence_nm: Option<f64>,
    /// Stam's reflectance.
    pub reflectance: Option<f64>,
    /// The radiometric grating's Gaussian spread along the grooves.
    pub groove_sigma: Option<f64>,
    /// The radiometric grating's order efficiencies: "amplitude" (default), a rigorous preset
    /// of `diffraction::relief::Preset` ("cd", "dvd", "blazed600", "foil"), or the path of a
    /// JSON efficiency table (a name ending in `.json`, relative to the scene file: the format
    /// of docs/efficiency_tables.md, as `diffraction-fmm`'s `grating-table` writes it; at most
    /// `limits::MAX_TABLE_BYTES`, a regular file). A preset's or a table's period is then the
    /// default `period_nm`.
    pub efficiency: Option<String>,
    /// How a classical table (a preset, or a version-1 table file) is read off the plane across
    /// the grooves: "reduced" (the default for a preset, as the library's
    /// `OrderEfficiency::preset`; `EfficiencyTable::reduced_from_classical` for a file: in
    /// reduced coordinates in the cover's medium, the file's `grating.cover`, "none" or
    /// "polycarbonate"; a conical table the path tracer reads at the full incident direction)
    /// or "classical" (the default for a file: the classical mount). The Whitted integrator's
    /// colour tables follow the reading (a conical one on planes of |wi.y|).
    pub reading: Option<String>,
    /// The table `efficiency` names, read by the loader (not a key of the file).
    #[serde(skip)]
    pub table: Option<std::sync::Arc<diffraction::relief::EfficiencyTable>>,
    /// The `grating.cover` of that table's file (`"none"`, `"polycarbonate"`), read by the
    /// loader (not a key of the file).
    #[serde(skip)]
    pub table_cover: Option<String>,
}

/// The grating models a scene names (`model`) and the parameters each takes; which of them a
/// renderer builds is its [`crate::scene::Physics`]'s choice.
pub const MODELS: [(&str, &[&str]); 5] = [
    ("agu-hill", &["slit_width_nm", "slits"]),
    ("thorman", &["lobe_width"]),
    ("stam-sine", &["depth_nm", "coherence_nm", "reflectance"]),
    (
        "stam-binary",
        &["depth_nm", "fraction", "coherence_nm", "reflectance"],
    ),
    (
        "radiometric",
        &[
            "slit_width_nm",
            "slits",
            "coherence_nm",
            "groove_sigma",
            "efficiency",
            "reading",
        ],
    ),
];

impl RawGrating {
    /// The model parameters present, by key.
    pub fn parameters(&self) -> [(&'static str, bool); 10] {
        [
            ("slit_width_nm", self.slit_width_nm.is_some()),
            ("slits", self.slits.is_some()),
            ("lobe_width", self.lobe_width.is_some()),
            ("depth_nm", self.depth_nm.is_some()),
            ("fraction", self.fraction.is_some()),
            ("coherence_nm", self.coherence_nm.is_some()),
            ("reflectance", self.reflectance.is_some()),
            ("groove_sigma", self.groove_sigma.is_some()),
            ("efficiency", self.efficiency.is_some()),
            ("reading", self.reading.is_some()),
        ]
    }
}

/// The grating direction across the surface.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawField {
    /// `type = "constant"`: one grating direction.
    Constant {
        /// The grating vector's angle in the surface, degrees.
        angle_deg: Option<f64>,
        /// A twist added to the direction, degrees.
        twist_deg: Option<f64>,
    },
    /// `type = "radial"`: grooves around a centre (a CD).
    Radial {
        /// The centre in the surface's coordinates.
        center: Option<[f64; 2]>,
        /// A twist added to the direction, degrees.
        twist_deg: Option<f64>,
    },
    /// `type = "checkerboard"`: two kinds of squares.
    Checkerboard {
        /// The side of a square.
        cell_size: Option<f64>,
        /// The even squares (default a constant grating).
        even: Option<RawTile>,
        /// The odd squares (default plain).
        odd: Option<RawTile>,
        /// The colour of plain squares (default the grating's colour).
        plain_color: Option<[f64; 3]>,
        /// A twist added to the direction, degrees.
        twist_deg: Option<f64>,
    },
}

/// One kind of square of a checkerboard.
#[derive(Debug, Clone, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawTile {
    /// No grating (an empty struct variant: a unit variant would accept any key).
    Plain {},
    /// A constant grating direction.
    Constant {
        /// The grating vector's angle in the surface, degrees.
        angle_deg: Option<f64>,
        /// A twist added to the direction, degrees.
        twist_deg: Option<f64>,
    },
    /// Grooves around a centre.
    Radial {
        /// The centre in the surface's coordinates.
        center: Option<[f64; 2]>,
        /// A twist added to the direction, degrees.
        twist_deg: Option<f64>,
    },
}

/// The tagged tables, outermost first.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Level {
    Material,
    Field,
    Tile,
}

impl Level {
    fn accepts(self, table: &Table) -> bool {
        fn ok<T: DeserializeOwned>(t: &Table) -> bool {
            Value::Table(t.clone()).try_into::<T>().is_ok()
        }
        match self {
            Level::Material => ok::<RawMaterial>(table),
            Level::Field => ok::<RawField>(table),
            Level::Tile => ok::<RawTile>(table),
        }
    }

    fn child(self, key: &str) -> Option<Level> {
        match (self, key) {
            (Level::Material, "field") => Some(Level::Field),
            (Level::Field, "even" | "odd") => Some(Level::Tile),
            _ => None,
        }
    }
}

/// The key (a path relative to `table`, e.g. `field.even.angle_deg`) that makes the material
/// `table` fail to deserialise: its own `type` when that is missing or unknown, else the first
/// key that fails alone beside the type, followed into nested fields and tiles.
pub fn culprit(material: &Table) -> Option<String> {
    fn find(table: &Table, level: Level) -> Option<String> {
        let Some(kind) = table.get("type") else {
            return Some("type".into());
        };
        let with = |key: Option<(&String, &Value)>| {
            let mut t = Table::new();
            t.insert("type".into(), kind.clone());
            if let Some((k, v)) = key {
                t.insert(k.clone(), v.clone());
            }
            t
        };
        if !level.accepts(&with(None)) {
            return Some("type".into());
        }
        for (k, v) in table.iter().filter(|(k, _)| *k != "type") {
            if level.accepts(&with(Some((k, v)))) {
                continue;
            }
            if let (Some(inner), Some(t)) = (level.child(k), v.as_table()) {
                if let Some(deeper) = find(t, inner) {
                    return Some(format!("{k}.{deeper}"));
                }
            }
            return Some(k.clone());
        }
        None
    }
    find(material, Level::Material)
}
