//! The stored form of a colour table (feature `serde`): a cache a renderer writes once and
//! loads instead of rebuilding, validated on load.
//!
//! A table stores its format version, what it tabulates (`grating` for the paper's source,
//! `bsdf` for the radiometric one: exactly one of them), the illuminant, the accuracy, its
//! error scale and estimate, its evaluation count, the end u_lo of its first block, the
//! interval count of every block and the node values. Node positions follow from u_lo and the
//! interval counts (blocks of 1/8 octave, each uniform), so they are increasing by
//! construction; derivatives and cumulative integrals are recomputed by the same code as a
//! build, so a loaded table's lookups and means are bit-identical to the saved one's (given a
//! format that keeps `f64` exactly: serde_json needs its `float_roundtrip` feature). The form is
//! the one `ColorTable` and the former `RadiometricTable` wrote (version 1), so their caches load.
//!
//! Checked on load, each error naming its field: `format_version` (= [`ColorTable::FORMAT_VERSION`]), the
//! grating or BSDF (their own validation; the paper's grating with N = ∞ names `slits`, a
//! coherence length for the BSDF names `groove`; both or neither name `grating`), `accuracy`
//! (as in a build), `u_lo` (the value the source implies), `intervals` (one per block, powers
//! of two in [2, 1024], at most `MAX_NODES` nodes in all), `values` (one per node, every
//! channel finite, ≥ 0 and at most twice what a build of the source can produce: the white for
//! the paper's grating, k·white/360 nm with k = ρ²·N·d for the BSDF of finite N, d times the
//! largest film weight for N = ∞), `scale` (from the build's floor to twice the largest Y a
//! build can produce), `error` (≥ 0 and at most 2·10⁴·(largest value over the white)/scale)
//! and `evaluations` (at most 2 per node: each node and each final interval's midpoint once).

use alloc::vec::Vec;

use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::grid::{Grid, Limits, Stored};
use super::source::{Source, TableSource};
use super::{check_accuracy, ColorTable};
use crate::error::{Error, Requirement};
use crate::spectrum::{Illuminant, Spectral};
use crate::{Grating, GratingBsdf};

/// The version of the stored form this crate writes and reads.
const FORMAT_VERSION: u32 = ColorTable::FORMAT_VERSION;

/// The grid's stored fields.
#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct StoredGrid {
    scale: f64,
    error: f64,
    evaluations: u64,
    u_lo: f64,
    intervals: Vec<u32>,
    values: Vec<[f64; 3]>,
}

impl StoredGrid {
    fn of(t: &Grid, evaluations: usize) -> StoredGrid {
        let (intervals, values) = t.parts();
        StoredGrid {
            scale: t.scale,
            error: t.error,
            evaluations: evaluations as u64,
            u_lo: t.u_lo,
            intervals,
            values,
        }
    }

    fn load(&self, expected_u_lo: f64, max_nodes: usize, limits: &Limits) -> Result<Grid, Error> {
        let grid = Grid::from_parts(
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
        Ok(grid)
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

#[derive(Serialize)]
struct TableOut<'a> {
    format_version: u32,
    #[serde(skip_serializing_if = "Option::is_none")]
    grating: Option<&'a Grating>,
    #[serde(skip_serializing_if = "Option::is_none")]
    bsdf: Option<&'a GratingBsdf>,
    illuminant: Illuminant,
    accuracy: f64,
    grid: StoredGrid,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TableIn {
    format_version: u32,
    #[serde(default)]
    grating: Option<Grating>,
    #[serde(default)]
    bsdf: Option<GratingBsdf>,
    illuminant: Illuminant,
    accuracy: f64,
    grid: StoredGrid,
}

impl Serialize for ColorTable {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        if self.incidence_count().is_some() {
            return Err(serde::ser::Error::custom(
                "a colour table of tabulated order efficiencies has no stored form: rebuild it",
            ));
        }
        let (grating, bsdf) = match self.source() {
            TableSource::Paper(g) => (Some(g), None),
            TableSource::Radiometric(b) => (None, Some(b)),
        };
        TableOut {
            format_version: FORMAT_VERSION,
            grating,
            bsdf,
            illuminant: self.illuminant,
            accuracy: self.accuracy,
            grid: StoredGrid::of(&self.grid, self.evaluations),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for ColorTable {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let r = TableIn::deserialize(d)?;
        let source = match (&r.grating, &r.bsdf) {
            (Some(g), None) => TableSource::Paper(g),
            (None, Some(b)) => TableSource::Radiometric(b),
            (None, None) => return Err(D::Error::missing_field("grating")),
            (Some(_), Some(_)) => {
                return Err(D::Error::custom(
                    "both `grating` and `bsdf`: a table stores one source",
                ))
            }
        };
        let load = || -> Result<ColorTable, Error> {
            check_version(r.format_version)?;
            check_accuracy(r.accuracy)?;
            let (source, nodes) = Source::new(source, &Spectral::new(r.illuminant))?;
            #[cfg(feature = "relief")]
            if let Source::Tabulated { bsdf, .. } = &source {
                let orders = bsdf
                    .order_efficiency()
                    .table()
                    .map_or(0, |t| t.orders().count());
                return Err(Error::invalid(
                    "efficiency",
                    orders as f64,
                    Requirement::NotTabulated,
                ));
            }
            let (u_lo, _) = source.first_block();
            let limits = source.stored_limits(r.illuminant);
            let grid = r.grid.load(u_lo, ColorTable::MAX_NODES, &limits)?;
            let evaluations = usize::try_from(r.grid.evaluations).unwrap_or(usize::MAX);
            Ok(ColorTable::with_grid(
                source,
                nodes,
                r.illuminant,
                r.accuracy,
                grid,
                evaluations,
            ))
        };
        load().map_err(D::Error::custom)
    }
}
