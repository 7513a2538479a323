//! The `te` and `tm` arrays of a JSON table, read straight into a flat vector with bounded
//! memory: 3 levels (`[order][λ][s]`, version 1) or 4 (`[order][|β|][λ][s]`, version 2, and
//! `[order][plane][λ of the plane][s]`, version 3, whose planes may have different row counts).

use alloc::string::ToString;
use core::fmt;

use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::{number, quoted, within, Expecting, Loose, Path};
use super::{MAX_TABLE_NODES, MAX_TABLE_ORDERS, MAX_TABLE_VALUES};
use alloc::vec::Vec;

/// One polarisation's `[order][λ][s]` (version 1) or `[order][|β|][λ][s]` (version 2) array,
/// flattened as it is read. Which one is decided by the first element at depth 3 (a number: 3
/// levels; an array: 4); every later one must agree.
#[derive(Default)]
pub(super) struct Cube {
    pub(super) values: Vec<f64>,
    /// Elements per level (of the first array read at that level; every other is checked
    /// against it).
    pub(super) shape: [usize; 4],
    /// The depth of the numbers, 3 or 4, once the first is read (0 before).
    pub(super) leaf: usize,
    /// A 4-level array's rows per plane, as the first order has them (every other order is
    /// checked against them; `shape[2]` is the first plane's).
    pub(super) plane_rows: Vec<usize>,
}

/// One level of a [`Cube`]: depth 0 the orders, 1 an order's rows (or |β| planes), 2 and 3
/// the deeper arrays.
struct Level<'a> {
    name: &'a str,
    cube: &'a mut Cube,
    index: [usize; 4],
    depth: usize,
    /// Whether a first element of this level was read before (the shape is then fixed).
    fixed: [bool; 4],
}

impl Level<'_> {
    fn path(&self, depth: usize) -> Path<'_> {
        Path {
            name: self.name,
            index: self.index,
            depth,
        }
    }

    /// What the array at `depth` holds, and the most elements it may hold.
    fn level(&self, depth: usize) -> (usize, &'static str) {
        match (depth, self.cube.leaf) {
            (0, _) => (MAX_TABLE_ORDERS, "orders"),
            (1, 4) => (MAX_TABLE_NODES, "|beta| planes"),
            (1, _) => (MAX_TABLE_NODES, "wavelength rows"),
            (2, 4) => (MAX_TABLE_NODES, "wavelength rows"),
            _ => (MAX_TABLE_NODES, "values"),
        }
    }

    /// A number read at depth `self.depth`.
    fn push<E: de::Error>(&mut self, v: Loose) -> Result<(), E> {
        let here = self.path(self.depth).to_string();
        if self.cube.values.len() >= MAX_TABLE_VALUES {
            return Err(E::custom(format_args!(
                "{}: has more than {MAX_TABLE_VALUES} values (MAX_TABLE_VALUES)",
                self.name
            )));
        }
        let x = number(&here, v).map_err(E::custom)?;
        self.cube.values.push(x);
        Ok(())
    }
}

impl<'de> Visitor<'de> for &mut Level<'_> {
    type Value = ();
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self.depth {
            0 => "an array of orders",
            1 => "an array of wavelength rows",
            2 if self.cube.leaf == 4 => "an array of wavelength rows",
            _ => "an array of numbers",
        })
    }
    refuse_long_strings!();
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        let depth = self.depth;
        let mut count = 0usize;
        loop {
            self.index[depth] = count;
            let here = self.path(depth + 1).to_string();
            // The elements at depth + 1: numbers at the leaf depth, arrays above it, and
            // either at depth 3 while the leaf is not known.
            let more = if self.cube.leaf == depth + 1 {
                match seq.next_element::<Loose>().map_err(|e| within(&here, e))? {
                    None => false,
                    Some(v) => {
                        self.depth = depth + 1;
                        let r = self.push(v);
                        self.depth = depth;
                        r?;
                        true
                    }
                }
            } else if depth + 1 == 3 && self.cube.leaf == 0 {
                self.depth = depth + 1;
                let got = seq
                    .next_element_seed(Either(&mut *self))
                    .map_err(|e| within(&here, e));
                self.depth = depth;
                got?.is_some()
            } else if depth + 1 >= 4 {
                // Deeper than any table: only a number belongs here.
                match seq.next_element::<Loose>().map_err(|e| within(&here, e))? {
                    None => false,
                    Some(v) => return Err(de::Error::custom(number(&here, v).unwrap_err())),
                }
            } else {
                self.depth = depth + 1;
                let got = seq
                    .next_element_seed(&mut *self)
                    .map_err(|e| within(&here, e));
                self.depth = depth;
                got?.is_some()
            };
            if !more {
                break;
            }
            count += 1;
            let (max, what) = self.level(depth);
            if count > max {
                let at = self.path(depth).to_string();
                return Err(de::Error::custom(format_args!(
                    "{at}: has more than {max} {what}"
                )));
            }
        }
        let (_, what) = self.level(depth);
        let at = self.path(depth).to_string();
        if depth == 2 && self.cube.leaf == 4 {
            // A plane's rows: each plane its own count, the same in every order.
            let (order, plane) = (self.index[0], self.index[1]);
            let rows = &mut self.cube.plane_rows;
            if order == 0 {
                if plane == 0 {
                    self.cube.shape[2] = count;
                }
                rows.push(count);
            } else if let Some(&want) = rows.get(plane) {
                if count != want {
                    return Err(de::Error::custom(format_args!(
                        "{at}: has {count} {what}, expected {want} (as the first order's plane \
                         {plane})"
                    )));
                }
            } else {
                let planes = rows.len();
                return Err(de::Error::custom(format_args!(
                    "{at}: beyond the first order's {planes} |beta| planes"
                )));
            }
            return Ok(());
        }
        if self.fixed[depth] {
            let want = self.cube.shape[depth];
            if count != want {
                return Err(de::Error::custom(format_args!(
                    "{at}: has {count} {what}, expected {want} (as the first)"
                )));
            }
        } else {
            self.fixed[depth] = true;
            self.cube.shape[depth] = count;
        }
        Ok(())
    }
}

impl<'de> DeserializeSeed<'de> for &mut Level<'_> {
    type Value = ();
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

/// The first element at depth 3: a number (the table has 3 levels) or an array (4 levels).
struct Either<'a, 'b>(&'a mut Level<'b>);

impl Either<'_, '_> {
    fn leaf<E: de::Error>(self, v: Loose) -> Result<(), E> {
        if let Loose::Int(_) | Loose::Float(_) = v {
            self.0.cube.leaf = 3;
        }
        self.0.push(v)
    }
}

impl<'de> Visitor<'de> for Either<'_, '_> {
    type Value = ();
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or an array of numbers")
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<(), E> {
        self.leaf(Loose::Bool(v))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<(), E> {
        self.leaf(Loose::Int(v.into()))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<(), E> {
        self.leaf(Loose::Int(v.into()))
    }
    fn visit_i128<E: de::Error>(self, v: i128) -> Result<(), E> {
        self.leaf(Loose::Int(v))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<(), E> {
        self.leaf(Loose::Float(v))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<(), E> {
        let quote = quoted(v);
        self.leaf(Loose::Str {
            quote,
            is_format: false,
        })
    }
    fn visit_unit<E: de::Error>(self) -> Result<(), E> {
        self.leaf(Loose::Null)
    }
    fn visit_none<E: de::Error>(self) -> Result<(), E> {
        self.leaf(Loose::Null)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        self.leaf(Loose::Object)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<(), A::Error> {
        self.0.cube.leaf = 4;
        self.0.visit_seq(seq)
    }
}

impl<'de> DeserializeSeed<'de> for Either<'_, '_> {
    type Value = ();
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_any(self)
    }
}

/// A whole [`Cube`] field.
pub(super) struct CubeSeed<'a>(pub(super) &'a str);

impl<'de> DeserializeSeed<'de> for CubeSeed<'_> {
    type Value = Cube;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Cube, D::Error> {
        let mut cube = Cube::default();
        let mut level = Level {
            name: self.0,
            cube: &mut cube,
            index: [0; 4],
            depth: 0,
            fixed: [false; 4],
        };
        d.deserialize_any(&mut level)?;
        // An order without rows, or rows without values, leave the inner levels unread.
        Ok(cube)
    }
}
