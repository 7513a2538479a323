//! The `lambda_nm` field of a JSON table: one axis of wavelengths (versions 1 and 2) or one per
//! |β| plane (version 3), told apart by the first element, read with bounded memory and every
//! element named (`lambda_nm[2][5]: expected a number, got null`).

use alloc::format;
use alloc::string::ToString;
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::{number, quoted, within, Expecting, Loose, LooseVisitor, Path, MAX_TABLE_NODES};

/// The `lambda_nm` field: an array of numbers (versions 1 and 2) or one array of numbers per
/// |β| plane (version 3), told apart by its first element; bounded as the axes are
/// ([`MAX_TABLE_NODES`] planes, and values per plane).
pub(super) enum Lambda {
    Flat(Vec<f64>),
    Planes(Vec<Vec<f64>>),
}

/// The first element of `lambda_nm`: a number, or a whole plane.
enum FirstLambda {
    Number(Loose),
    Plane(Vec<f64>),
}

struct FirstLambdaSeed;

impl<'de> Visitor<'de> for FirstLambdaSeed {
    type Value = FirstLambda;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a number or an array of numbers")
    }
    fn visit_bool<E>(self, v: bool) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Bool(v)))
    }
    fn visit_i64<E>(self, v: i64) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Int(v.into())))
    }
    fn visit_u64<E>(self, v: u64) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Int(v.into())))
    }
    fn visit_i128<E>(self, v: i128) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Int(v)))
    }
    fn visit_f64<E>(self, v: f64) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Float(v)))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(LooseVisitor.visit_str(v)?))
    }
    fn visit_unit<E>(self) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Null))
    }
    fn visit_none<E>(self) -> Result<FirstLambda, E> {
        Ok(FirstLambda::Number(Loose::Null))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<FirstLambda, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(FirstLambda::Number(Loose::Object))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<FirstLambda, A::Error> {
        PlaneAxis(0).visit_seq(seq).map(FirstLambda::Plane)
    }
}

impl<'de> DeserializeSeed<'de> for FirstLambdaSeed {
    type Value = FirstLambda;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<FirstLambda, D::Error> {
        d.deserialize_any(self)
    }
}

/// Plane `.0`'s wavelengths in a version-3 `lambda_nm`: elements named `lambda_nm[p][j]`.
struct PlaneAxis(usize);

impl<'de> Visitor<'de> for PlaneAxis {
    type Value = Vec<f64>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an array of numbers")
    }
    refuse_long_strings!();
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<f64>, A::Error> {
        let mut out = Vec::new();
        loop {
            let path = Path {
                name: "lambda_nm",
                index: [self.0, out.len(), 0, 0],
                depth: 2,
            };
            let Some(v) = seq
                .next_element::<Loose>()
                .map_err(|e| within(&path.to_string(), e))?
            else {
                return Ok(out);
            };
            if out.len() == MAX_TABLE_NODES {
                return Err(de::Error::custom(format_args!(
                    "lambda_nm[{}]: has more than {MAX_TABLE_NODES} values, must have 2 to \
                     {MAX_TABLE_NODES}",
                    self.0
                )));
            }
            out.push(number(&path, v).map_err(de::Error::custom)?);
        }
    }
}

impl<'de> DeserializeSeed<'de> for PlaneAxis {
    type Value = Vec<f64>;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Vec<f64>, D::Error> {
        d.deserialize_any(self)
    }
}

/// The whole `lambda_nm` field.
pub(super) struct LambdaSeed;

impl<'de> Visitor<'de> for LambdaSeed {
    type Value = Lambda;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an array of numbers, or of arrays of numbers (one per |beta| plane)")
    }
    refuse_long_strings!();
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Lambda, A::Error> {
        let first = seq
            .next_element_seed(FirstLambdaSeed)
            .map_err(|e| within("lambda_nm[0]", e))?;
        match first {
            None => Ok(Lambda::Flat(Vec::new())),
            Some(FirstLambda::Number(v)) => {
                let mut out = vec![number(&"lambda_nm[0]", v).map_err(de::Error::custom)?];
                // The rest as an axis, its elements named from 1.
                loop {
                    let path = Path {
                        name: "lambda_nm",
                        index: [out.len(), 0, 0, 0],
                        depth: 1,
                    };
                    let Some(v) = seq
                        .next_element::<Loose>()
                        .map_err(|e| within(&path.to_string(), e))?
                    else {
                        return Ok(Lambda::Flat(out));
                    };
                    if out.len() == MAX_TABLE_NODES {
                        return Err(de::Error::custom(format_args!(
                            "lambda_nm: has more than {MAX_TABLE_NODES} values, must have 2 to \
                             {MAX_TABLE_NODES}"
                        )));
                    }
                    out.push(number(&path, v).map_err(de::Error::custom)?);
                }
            }
            Some(FirstLambda::Plane(p)) => {
                let mut planes = vec![p];
                loop {
                    let at = planes.len();
                    let name = format!("lambda_nm[{at}]");
                    let Some(p) = seq
                        .next_element_seed(PlaneAxis(at))
                        .map_err(|e| within(&name, e))?
                    else {
                        return Ok(Lambda::Planes(planes));
                    };
                    if planes.len() == MAX_TABLE_NODES {
                        return Err(de::Error::custom(format_args!(
                            "lambda_nm: has more than {MAX_TABLE_NODES} planes"
                        )));
                    }
                    planes.push(p);
                }
            }
        }
    }
}

impl<'de> DeserializeSeed<'de> for LambdaSeed {
    type Value = Lambda;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Lambda, D::Error> {
        d.deserialize_any(self)
    }
}
