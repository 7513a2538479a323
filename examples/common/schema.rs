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

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub description: Option<String>,
    #[serde(default)]
    pub render: RawRender,
    pub camera: RawCamera,
    #[serde(default)]
    pub environment: RawEnvironment,
    #[serde(default)]
    pub lights: Vec<RawLight>,
    #[serde(default)]
    pub objects: Vec<RawObject>,
    pub radiometry: Option<crate::radiometric::RawRadiometry>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawRender {
    pub width: Option<u32>,
    pub height: Option<u32>,
    pub spp: Option<u32>,
    pub max_depth: Option<u32>,
    pub seed: Option<u64>,
    pub strategy: Option<String>,
    pub clip: Option<String>,
    pub illuminant: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawCamera {
    pub position: [f64; 3],
    pub look_at: [f64; 3],
    pub up: Option<[f64; 3]>,
    pub fov_deg: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawEnvironment {
    pub background: Option<[f64; 3]>,
    pub zenith: Option<[f64; 3]>,
    pub ambient: Option<[f64; 3]>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLight {
    pub position: [f64; 3],
    pub color: Option<[f64; 3]>,
    pub intensity: Option<f64>,
    pub radius: Option<f64>,
    pub samples: Option<u32>,
}

#[derive(Debug, Deserialize)]
#[serde(untagged)]
pub enum Scale {
    Uniform(f64),
    Axes([f64; 3]),
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawObject {
    pub shape: String,
    pub hole: Option<f64>,
    pub translate: Option<[f64; 3]>,
    pub rotate_deg: Option<[f64; 3]>,
    pub scale: Option<Scale>,
    pub material: RawMaterial,
}

/// A material: the keys every type takes, and the type's own (unknown keys are rejected by
/// the flattened, tagged [`RawKind`], which receives every key not consumed here).
#[derive(Debug, Deserialize)]
pub struct RawMaterial {
    pub ambient: Option<f64>,
    pub diffuse: Option<f64>,
    pub mirror: Option<f64>,
    pub mirror_color: Option<[f64; 3]>,
    #[serde(flatten)]
    pub kind: RawKind,
}

/// The keys every material type takes besides its own (named in unknown-key messages).
pub const COMMON_KEYS: &str = "ambient, diffuse, mirror, mirror_color";

#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawKind {
    Diffuse {
        color: Option<[f64; 3]>,
    },
    Mirror {
        color: Option<[f64; 3]>,
    },
    Wood {
        light: Option<[f64; 3]>,
        dark: Option<[f64; 3]>,
        ring_spacing: Option<f64>,
        turbulence: Option<f64>,
        plank_width: Option<f64>,
        plank_length: Option<f64>,
    },
    Image {
        image: Option<String>,
        color: Option<[f64; 3]>,
    },
    Grating(Box<RawGrating>),
}

/// A grating: its geometry, the model (`model`, default "agu-hill") and the model's
/// parameters (checked against the model in the second stage).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawGrating {
    pub color: Option<[f64; 3]>,
    pub period_nm: Option<f64>,
    pub lines_per_mm: Option<f64>,
    pub diffraction: Option<f64>,
    pub strategy: Option<String>,
    pub field: Option<RawField>,
    pub model: Option<String>,
    pub slit_width_nm: Option<f64>,
    pub slits: Option<u64>,
    pub lobe_width: Option<f64>,
    pub depth_nm: Option<f64>,
    pub fraction: Option<f64>,
    pub coherence_nm: Option<f64>,
    pub reflectance: Option<f64>,
    pub groove_sigma: Option<f64>,
}

impl RawGrating {
    /// The model parameters present, by key.
    pub fn parameters(&self) -> [(&'static str, bool); 8] {
        [
            ("slit_width_nm", self.slit_width_nm.is_some()),
            ("slits", self.slits.is_some()),
            ("lobe_width", self.lobe_width.is_some()),
            ("depth_nm", self.depth_nm.is_some()),
            ("fraction", self.fraction.is_some()),
            ("coherence_nm", self.coherence_nm.is_some()),
            ("reflectance", self.reflectance.is_some()),
            ("groove_sigma", self.groove_sigma.is_some()),
        ]
    }
}

/// The grating direction across the surface.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawField {
    Constant {
        angle_deg: Option<f64>,
        twist_deg: Option<f64>,
    },
    Radial {
        center: Option<[f64; 2]>,
        twist_deg: Option<f64>,
    },
    Checkerboard {
        cell_size: Option<f64>,
        even: Option<RawTile>,
        odd: Option<RawTile>,
        plain_color: Option<[f64; 3]>,
        twist_deg: Option<f64>,
    },
}

/// One kind of square of a checkerboard.
#[derive(Debug, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase", deny_unknown_fields)]
pub enum RawTile {
    /// No grating (an empty struct variant: a unit variant would accept any key).
    Plain {},
    Constant {
        angle_deg: Option<f64>,
        twist_deg: Option<f64>,
    },
    Radial {
        center: Option<[f64; 2]>,
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
