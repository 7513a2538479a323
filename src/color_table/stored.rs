//! The stored form of the colour tables (feature `serde`): a cache a renderer writes once and
//! loads instead of rebuilding, validated on load.
//!
//! A table stores its format version, what it tabulates (the grating or the BSDF, the
//! illuminant, the accuracy), its error scale and estimate, its evaluation count, the end u_lo of
//! its first block, the interval count of every block and the node values. Node positions
//! follow from u_lo and the interval counts (blocks of 1/8 octave, each uniform), so they are
//! increasing by construction; derivatives and cumulative integrals are recomputed by the same
//! code as a build, so a loaded table's lookups and means are bit-identical to the saved one's
//! (given a format that keeps `f64` exactly: serde_json needs its `float_roundtrip` feature).
//!
//! Checked on load, each error naming its field: `format_version` (= [`ColorTable::FORMAT_VERSION`]), the
//! grating or BSDF (their own validation; N = ∞ for a `ColorTable` names `slits`, a coherence
//! length for a `RadiometricTable` names `groove`), `accuracy` (as in a build), `u_lo` (the
//! value the grating implies), `intervals` (one per block, powers of two in [2, 1024], at most
//! `MAX_NODES` nodes in all), `values` (one per node, every channel finite, ≥ 0 and at most
//! twice what a build of the model can produce: the white for a `ColorTable`, k·white/360 nm
//! with k = ρ²·N·d for a `RadiometricTable` of finite N, d times the largest film weight for
//! N = ∞), `scale` (from the build's floor to twice the largest Y a build can produce), `error`
//! (≥ 0 and at most 2·10⁴·(largest value over the white)/scale)
//! and `evaluations` (at most 2 per node: each node and each final interval's midpoint once).

use alloc::vec::Vec;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::nodes::GratingNodes;
use super::radiometric::{factorises, peak_weight, radiometric_first_block};
use super::tabulated::{Limits, Stored, Tabulated};
use super::LAMBDA_MIN_NM;
use super::{first_block, ColorTable, RadiometricTable};
use crate::error::{Error, Requirement};
use crate::spectrum::{Illuminant, Spectral, MAX_ACCURACY, MIN_ACCURACY};
use crate::{Grating, GratingBsdf, Slits};

/// The version of the stored form this crate writes and reads.
const FORMAT_VERSION: u32 = ColorTable::FORMAT_VERSION;

/// The fields both tables store beside what they tabulate.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Grid {
    scale: f64,
    error: f64,
    evaluations: u64,
    u_lo: f64,
    intervals: Vec<u32>,
    values: Vec<[f64; 3]>,
}

impl Grid {
    fn of(t: &Tabulated, evaluations: usize) -> Grid {
        let (intervals, values) = t.parts();
        Grid {
            scale: t.scale,
            error: t.error,
            evaluations: evaluations as u64,
            u_lo: t.u_lo,
            intervals,
            values,
        }
    }

    fn load(
        &self,
        expected_u_lo: f64,
        max_nodes: usize,
        limits: &Limits,
    ) -> Result<Tabulated, Error> {
        let t = Tabulated::from_parts(
            expected_u_lo,
            Stored {
                u_lo: self.u_lo,
                intervals: &self.intervals,
                values: &self.values,
                scale: self.scale,
                error: self.error,
            },
            max_nodes,
            limits,
        )?;
        // Every node is evaluated once (as a node or as a midpoint that became one), and so is
        // the midpoint of every final interval: at most 2 per node.
        let most = 2 * self.values.len() as u64;
        if self.evaluations > most {
            let requirement = Requirement::Within {
                min: 0.0,
                max: most as f64,
            };
            return Err(Error::invalid(
                "evaluations",
                self.evaluations as f64,
                requirement,
            ));
        }
        Ok(t)
    }
}

/// Headroom over the largest node value a build produces (a colour of an intensity at most 1:
/// at most the white for a `ColorTable`, k·white/360 nm for a `RadiometricTable` of finite N),
/// for the rounding of the strategies.
const VALUE_HEADROOM: f64 = 2.0;
/// A bound of error·scale per unit of (largest value)/white: the worst midpoint error is the
/// difference of the interpolant (within a small multiple of the largest value) and a node
/// value, over a tolerance of at least (6/29)²·white·scale = 0.043·white·scale; 10⁴ is ample.
const ERROR_FACTOR: f64 = 1e4;

/// What a build can produce for a table whose node values are at most `max_value` per
/// channel, with the error scale at least `floor`.
fn limits(max_value: [f64; 3], white: [f64; 3], floor: f64) -> Limits {
    let value = max_value.map(|v| VALUE_HEADROOM * v);
    let ratio = (0..3).map(|c| value[c] / white[c]).fold(0.0, f64::max);
    Limits {
        value,
        scale: (floor, floor.max(value[1])),
        error_times_scale: ERROR_FACTOR * ratio,
    }
}

fn check_version(v: u32) -> Result<(), Error> {
    if v == FORMAT_VERSION {
        return Ok(());
    }
    let f = FORMAT_VERSION as f64;
    Err(Error::invalid(
        "format_version",
        v as f64,
        Requirement::Within { min: f, max: f },
    ))
}

fn check_accuracy(a: f64) -> Result<(), Error> {
    if (MIN_ACCURACY..=MAX_ACCURACY).contains(&a) {
        return Ok(());
    }
    Err(Error::invalid(
        "accuracy",
        a,
        Requirement::Within {
            min: MIN_ACCURACY,
            max: MAX_ACCURACY,
        },
    ))
}

#[derive(Serialize)]
struct ColorTableOut<'a> {
    format_version: u32,
    grating: &'a Grating,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Grid,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ColorTableIn {
    format_version: u32,
    grating: Grating,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Grid,
}

impl Serialize for ColorTable {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ColorTableOut {
            format_version: FORMAT_VERSION,
            grating: &self.grating,
            illuminant: self.illuminant,
            accuracy: self.accuracy,
            grid: Grid::of(&self.grid, self.evaluations),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for ColorTable {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = ColorTableIn::deserialize(d)?;
        let load = || -> Result<ColorTable, Error> {
            check_version(r.format_version)?;
            check_accuracy(r.accuracy)?;
            if r.grating.slits() == Slits::Infinite {
                return Err(Error::invalid("slits", f64::INFINITY, Requirement::Finite));
            }
            let (u_lo, unresolved) = first_block(&r.grating);
            let spectral = Spectral::new(r.illuminant);
            let w = spectral.white();
            let floor = GratingNodes::paper_floor(r.grating.slits().as_f64());
            let white = [w.x, w.y, w.z];
            let bounds = limits(white, white, floor);
            let grid = r.grid.load(u_lo, ColorTable::MAX_NODES, &bounds)?;
            Ok(ColorTable {
                grating: r.grating,
                illuminant: r.illuminant,
                accuracy: r.accuracy,
                grid,
                exact_below: if unresolved { u_lo } else { -1.0 },
                spectral,
                evaluations: usize::try_from(r.grid.evaluations).unwrap_or(usize::MAX),
            })
        };
        load().map_err(D::Error::custom)
    }
}

#[derive(Serialize)]
struct RadiometricOut<'a> {
    format_version: u32,
    bsdf: &'a GratingBsdf,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Grid,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RadiometricIn {
    format_version: u32,
    bsdf: GratingBsdf,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Grid,
}

impl Serialize for RadiometricTable {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        RadiometricOut {
            format_version: FORMAT_VERSION,
            bsdf: self.bsdf(),
            illuminant: self.illuminant(),
            accuracy: self.accuracy(),
            grid: Grid::of(self.grid(), self.evaluations()),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for RadiometricTable {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = RadiometricIn::deserialize(d)?;
        let load = || -> Result<RadiometricTable, Error> {
            check_version(r.format_version)?;
            check_accuracy(r.accuracy)?;
            factorises(&r.bsdf)?;
            let (u_lo, _) = radiometric_first_block(&r.bsdf);
            let plain = Spectral::new(r.illuminant);
            let w = plain.white();
            let white = [w.x, w.y, w.z];
            let g = r.bsdf.grating();
            let (d, rho) = (g.period_nm(), g.open_fraction());
            // As `RadiometricTable::new`'s.
            let floor =
                (rho * rho * d / crate::cie::cmf_areas()[1]).clamp(f64::MIN_POSITIVE, f64::MAX);
            let max_value = match g.slits() {
                // k·(the paper's colour, at most the white, with the envelope 1/λ ≤ 1/360 nm),
                // k = ρ²·N·d.
                Slits::Finite(n) => {
                    let k = (rho * rho * f64::from(n) * d).min(f64::MAX);
                    white.map(|c| k * c / LAMBDA_MIN_NM)
                }
                // Σ_m η_m·(d/|m|)·weight(λ_m) with Σ η ≤ 1.
                Slits::Infinite => peak_weight(&plain).map(|c| d * c),
            };
            let bounds = limits(max_value, white, floor);
            let grid = r.grid.load(u_lo, RadiometricTable::MAX_NODES, &bounds)?;
            let evaluations = usize::try_from(r.grid.evaluations).unwrap_or(usize::MAX);
            RadiometricTable::with_grid(&r.bsdf, r.illuminant, r.accuracy, grid, evaluations)
        };
        load().map_err(D::Error::custom)
    }
}
