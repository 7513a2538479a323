//! The JSON table of `docs/efficiency_tables.md` (features `serde` and `alloc`), read field by
//! field so that every refusal names its field, and with bounded memory whatever the input.
//!
//! Each value is first read in a loosely typed form ([`Loose`]: what kind of value it was,
//! never more than a short quote of a string), then converted with a message naming the field
//! (`version: expected 1, 2 or 3, got 1.0`, `lambda_nm[1]: expected a number, got null`). Errors the
//! parser itself raises (`1e400`: number out of range; a truncated file) are prefixed with the
//! field they occurred in. The arrays are read straight into flat vectors and refused as soon
//! as they exceed the table's bounds ([`MAX_TABLE_NODES`] per axis and per row,
//! [`MAX_TABLE_ORDERS`] orders, [`MAX_TABLE_VALUES`] values), or stop being rectangular; no
//! nested vectors are built. The fields the crate does not use are skipped without being
//! stored ([`IgnoredAny`]).

use alloc::format;
use alloc::string::{String, ToString};
use alloc::vec;
use alloc::vec::Vec;
use core::fmt;

use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::{check_axis, check_period, EfficiencyTable};
use super::{MAX_TABLE_NODES, MAX_TABLE_ORDERS, MAX_TABLE_VALUES};
use crate::error::{Error, Requirement};
use crate::relief::{ReducedGrid, MAX_TABLE_ABS_BETA};

/// The `format` field's one accepted value.
const FORMAT: &str = "diffraction-efficiency-table";
/// The `version` field's accepted values: 1 (classical, `[order][λ][s]`), 2 (conical, with
/// `abs_beta` and `[order][|β|][λ][s]`) and 3 (reduced conical, with `abs_beta`,
/// `lambda_range_nm`, one wavelength array per plane and `[order][plane][λ of the plane][s]`).
const VERSIONS: [i128; 3] = [1, 2, 3];
/// The most characters of a string quoted in a message (a longer one is described by its
/// length).
const QUOTE_CHARS: usize = 40;

/// A message for a string where something else belongs: a short quote, or its length.
fn quoted(v: &str) -> String {
    if v.chars().count() <= QUOTE_CHARS {
        format!("{v:?}")
    } else {
        format!("a string of {} bytes", v.len())
    }
}

/// One JSON value as the reader first sees it: its kind, a number's value, a short quote of a
/// string. Arrays and objects are skipped (their contents are not stored).
#[derive(Debug, Clone, PartialEq)]
enum Loose {
    Bool(bool),
    Int(i128),
    Float(f64),
    /// A quote (or a length) for messages, and whether it is the `format` value.
    Str {
        quote: String,
        is_format: bool,
    },
    Null,
    Array,
    Object,
}

impl fmt::Display for Loose {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loose::Bool(b) => write!(f, "{b}"),
            Loose::Int(i) => write!(f, "{i}"),
            // `{:?}` keeps the decimal point: `1.0`, not `1`.
            Loose::Float(x) => write!(f, "{x:?}"),
            Loose::Str { quote, .. } => f.write_str(quote),
            Loose::Null => f.write_str("null"),
            Loose::Array => f.write_str("an array"),
            Loose::Object => f.write_str("an object"),
        }
    }
}

struct LooseVisitor;

impl<'de> Visitor<'de> for LooseVisitor {
    type Value = Loose;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Loose, E> {
        Ok(Loose::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Loose, E> {
        Ok(Loose::Int(v.into()))
    }
    fn visit_u64<E>(self, v: u64) -> Result<Loose, E> {
        Ok(Loose::Int(v.into()))
    }
    fn visit_i128<E>(self, v: i128) -> Result<Loose, E> {
        Ok(Loose::Int(v))
    }
    fn visit_f64<E>(self, v: f64) -> Result<Loose, E> {
        Ok(Loose::Float(v))
    }
    fn visit_str<E>(self, v: &str) -> Result<Loose, E> {
        Ok(Loose::Str {
            quote: quoted(v),
            is_format: v == FORMAT,
        })
    }
    fn visit_bytes<E>(self, v: &[u8]) -> Result<Loose, E> {
        Ok(Loose::Str {
            quote: format!("{} bytes", v.len()),
            is_format: false,
        })
    }
    fn visit_unit<E>(self) -> Result<Loose, E> {
        Ok(Loose::Null)
    }
    fn visit_none<E>(self) -> Result<Loose, E> {
        Ok(Loose::Null)
    }
    fn visit_some<D: de::Deserializer<'de>>(self, d: D) -> Result<Loose, D::Error> {
        d.deserialize_any(LooseVisitor)
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Loose, A::Error> {
        while seq.next_element::<IgnoredAny>()?.is_some() {}
        Ok(Loose::Array)
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Loose, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(Loose::Object)
    }
}

impl<'de> de::Deserialize<'de> for Loose {
    fn deserialize<D: de::Deserializer<'de>>(d: D) -> Result<Loose, D::Error> {
        d.deserialize_any(LooseVisitor)
    }
}

/// `msg` without the position a parser appends (serde_json's ` at line L column C`), which the
/// parser adds again where the error leaves it.
fn without_position(msg: &str) -> &str {
    if let Some(i) = msg.rfind(" at line ") {
        let mut parts = msg[i + " at line ".len()..].splitn(2, " column ");
        if let (Some(l), Some(c)) = (parts.next(), parts.next()) {
            let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
            if digits(l) && digits(c) {
                return &msg[..i];
            }
        }
    }
    msg
}

/// The error `e` raised inside field `name`, prefixed with it (unless it names a part of it
/// already: `te[0][1]: …`).
fn within<E: de::Error>(name: &str, e: E) -> E {
    let msg = e.to_string();
    let msg = without_position(&msg);
    let named = msg
        .strip_prefix(name)
        .is_some_and(|rest| rest.starts_with(['[', '.', ':']));
    if named {
        E::custom(msg)
    } else {
        E::custom(format_args!("{name}: {msg}"))
    }
}

/// A number where `name` needs one (an integer is taken as its nearest f64).
fn number(name: &dyn fmt::Display, v: Loose) -> Result<f64, String> {
    match v {
        Loose::Int(i) => Ok(i as f64),
        Loose::Float(x) => Ok(x),
        other => Err(format!("{name}: expected a number, got {other}")),
    }
}

/// An integer where `name` needs one (a number with a fractional part or an exponent is not).
fn integer(name: &str, v: Loose) -> Result<i128, String> {
    match v {
        Loose::Int(i) => Ok(i),
        other => Err(format!("{name}: expected an integer, got {other}")),
    }
}

/// The name of an element: `te[2][0][1]`.
struct Path<'a> {
    name: &'a str,
    index: [usize; 4],
    depth: usize,
}

impl fmt::Display for Path<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name)?;
        for i in &self.index[..self.depth] {
            write!(f, "[{i}]")?;
        }
        Ok(())
    }
}

/// A visitor's answer to a string where an array or an object belongs: a short quote.
macro_rules! refuse_long_strings {
    () => {
        fn visit_str<E: de::Error>(self, v: &str) -> Result<Self::Value, E> {
            Err(E::custom(format_args!(
                "invalid type: {}, expected {}",
                quoted(v),
                Expecting(&self)
            )))
        }
    };
}

/// A visitor's `expecting` as a `Display`.
struct Expecting<'a, V>(&'a V);

impl<'de, V: Visitor<'de>> fmt::Display for Expecting<'_, V> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.expecting(f)
    }
}

/// An axis: 2 to [`MAX_TABLE_NODES`] numbers (the rest of the checks by `check_axis`).
struct Axis<'a>(&'a str);

impl<'de> Visitor<'de> for Axis<'_> {
    type Value = Vec<f64>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an array of numbers")
    }
    refuse_long_strings!();
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<f64>, A::Error> {
        let name = self.0;
        let mut out = Vec::new();
        loop {
            let path = Path {
                name,
                index: [out.len(), 0, 0, 0],
                depth: 1,
            };
            let Some(v) = seq
                .next_element::<Loose>()
                .map_err(|e| within(&path.to_string(), e))?
            else {
                return Ok(out);
            };
            if out.len() == MAX_TABLE_NODES {
                return Err(de::Error::custom(format_args!(
                    "{name}: has more than {MAX_TABLE_NODES} values, must have 2 to \
                     {MAX_TABLE_NODES}"
                )));
            }
            out.push(number(&path, v).map_err(de::Error::custom)?);
        }
    }
}

impl<'de> DeserializeSeed<'de> for Axis<'_> {
    type Value = Vec<f64>;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Vec<f64>, D::Error> {
        d.deserialize_any(self)
    }
}

mod cube;
mod lambda;
use cube::{Cube, CubeSeed};
use lambda::{Lambda, LambdaSeed};

/// The `grating` object: its `period_nm` (the other fields are skipped).
struct GratingVisitor;

impl<'de> Visitor<'de> for GratingVisitor {
    type Value = Option<f64>;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object with period_nm")
    }
    refuse_long_strings!();
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Option<f64>, A::Error> {
        let mut period = None;
        while let Some(key) = map.next_key::<Key>()? {
            if key == Key::PeriodNm {
                if period.is_some() {
                    return Err(de::Error::custom("grating.period_nm: given twice"));
                }
                let name = "grating.period_nm";
                let v = map.next_value::<Loose>().map_err(|e| within(name, e))?;
                period = Some(number(&name, v).map_err(de::Error::custom)?);
            } else {
                map.next_value::<IgnoredAny>()?;
            }
        }
        Ok(period)
    }
}

impl<'de> DeserializeSeed<'de> for GratingVisitor {
    type Value = Option<f64>;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Option<f64>, D::Error> {
        d.deserialize_any(self)
    }
}

/// The keys the reader uses; any other is skipped.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Key {
    Format,
    Version,
    Grating,
    PeriodNm,
    SinThetaI,
    AbsBeta,
    LambdaNm,
    LambdaRangeNm,
    OrderMin,
    OrderMax,
    Te,
    Tm,
    Other,
}

impl Key {
    const ALL: [(Key, &'static str); 12] = [
        (Key::Format, "format"),
        (Key::Version, "version"),
        (Key::Grating, "grating"),
        (Key::PeriodNm, "period_nm"),
        (Key::SinThetaI, "sin_theta_i"),
        (Key::AbsBeta, "abs_beta"),
        (Key::LambdaNm, "lambda_nm"),
        (Key::LambdaRangeNm, "lambda_range_nm"),
        (Key::OrderMin, "order_min"),
        (Key::OrderMax, "order_max"),
        (Key::Te, "te"),
        (Key::Tm, "tm"),
    ];

    fn name(self) -> &'static str {
        Key::ALL
            .iter()
            .find(|(k, _)| *k == self)
            .map_or("", |(_, n)| n)
    }
}

struct KeyVisitor;

impl Visitor<'_> for KeyVisitor {
    type Value = Key;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a field name")
    }
    fn visit_str<E>(self, v: &str) -> Result<Key, E> {
        Ok(Key::ALL
            .iter()
            .find(|(_, n)| *n == v)
            .map_or(Key::Other, |(k, _)| *k))
    }
}

impl<'de> de::Deserialize<'de> for Key {
    fn deserialize<D: de::Deserializer<'de>>(d: D) -> Result<Key, D::Error> {
        d.deserialize_identifier(KeyVisitor)
    }
}

/// The fields read, before their checks.
#[derive(Default)]
struct Fields {
    format: Option<Loose>,
    version: Option<Loose>,
    period_nm: Option<Option<f64>>,
    sin_theta_i: Option<Vec<f64>>,
    abs_beta: Option<Vec<f64>>,
    lambda_nm: Option<Lambda>,
    lambda_range_nm: Option<Vec<f64>>,
    order_min: Option<Loose>,
    order_max: Option<Loose>,
    te: Option<Cube>,
    tm: Option<Cube>,
}

struct FileVisitor;

impl<'de> Visitor<'de> for FileVisitor {
    type Value = EfficiencyTable;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("an object (a diffraction-efficiency-table)")
    }
    refuse_long_strings!();
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<EfficiencyTable, A::Error> {
        let mut f = Fields::default();
        while let Some(key) = map.next_key::<Key>()? {
            let name = key.name();
            let twice = || de::Error::duplicate_field(name);
            macro_rules! once {
                ($slot:expr, $seed:expr) => {{
                    if $slot.is_some() {
                        return Err(twice());
                    }
                    $slot = Some(map.next_value_seed($seed).map_err(|e| within(name, e))?);
                }};
            }
            match key {
                Key::Format => once!(f.format, core::marker::PhantomData::<Loose>),
                Key::Version => once!(f.version, core::marker::PhantomData::<Loose>),
                Key::Grating => once!(f.period_nm, GratingVisitor),
                Key::SinThetaI => once!(f.sin_theta_i, Axis(name)),
                Key::AbsBeta => once!(f.abs_beta, Axis(name)),
                Key::LambdaNm => once!(f.lambda_nm, LambdaSeed),
                Key::LambdaRangeNm => once!(f.lambda_range_nm, Axis(name)),
                Key::OrderMin => once!(f.order_min, core::marker::PhantomData::<Loose>),
                Key::OrderMax => once!(f.order_max, core::marker::PhantomData::<Loose>),
                Key::Te => once!(f.te, CubeSeed(name)),
                Key::Tm => once!(f.tm, CubeSeed(name)),
                Key::PeriodNm | Key::Other => {
                    map.next_value::<IgnoredAny>()?;
                }
            }
        }
        f.into_table()
    }
}

impl Fields {
    fn into_table<E: de::Error>(self) -> Result<EfficiencyTable, E> {
        let missing = |name: &'static str| E::missing_field(name);
        let text = |msg: String| E::custom(msg);
        let typed = |e: Error| E::custom(e);
        match self.format.ok_or_else(|| missing("format"))? {
            Loose::Str {
                is_format: true, ..
            } => {}
            other => return Err(text(format!("format: expected {FORMAT:?}, got {other}"))),
        }
        let version = match self.version.ok_or_else(|| missing("version"))? {
            Loose::Int(v) if VERSIONS.contains(&v) => v,
            other => return Err(text(format!("version: expected 1, 2 or 3, got {other}"))),
        };
        let period = self
            .period_nm
            .ok_or_else(|| missing("grating"))?
            .ok_or_else(|| text("grating.period_nm: missing".to_string()))?;
        check_period("grating.period_nm", period).map_err(typed)?;
        let sin = self.sin_theta_i.ok_or_else(|| missing("sin_theta_i"))?;
        check_axis("sin_theta_i", &sin, Some((-1.0, 1.0))).map_err(typed)?;
        let beta = match (version, self.abs_beta) {
            (1, None) => None,
            (1, Some(_)) => {
                return Err(text(
                    "abs_beta: a conical axis needs version 2 (version 1 is classical)".to_string(),
                ))
            }
            (_, None) => return Err(missing("abs_beta")),
            (_, Some(b)) => {
                check_axis("abs_beta", &b, Some((0.0, MAX_TABLE_ABS_BETA))).map_err(typed)?;
                Some(b)
            }
        };
        let (lam, planes) =
            match (version, self.lambda_nm.ok_or_else(|| missing("lambda_nm"))?) {
                (3, Lambda::Planes(p)) => (Vec::new(), Some(p)),
                (3, Lambda::Flat(_)) => return Err(text(
                    "lambda_nm: version 3 holds one array of wavelengths per |beta| plane, got \
                     an array of numbers"
                        .to_string(),
                )),
                (_, Lambda::Planes(_)) => {
                    return Err(text(format!(
                    "lambda_nm: one array of wavelengths per |beta| plane needs version 3, got \
                     version {version}"
                )))
                }
                (_, Lambda::Flat(l)) => {
                    check_axis("lambda_nm", &l, None).map_err(typed)?;
                    (l, None)
                }
            };
        let band = match (version, self.lambda_range_nm) {
            (3, Some(r)) if r.len() == 2 => Some((r[0], r[1])),
            (3, Some(r)) => {
                return Err(text(format!(
                    "lambda_range_nm: expected [min, max], got {} values",
                    r.len()
                )))
            }
            (3, None) => return Err(missing("lambda_range_nm")),
            (_, Some(_)) => {
                return Err(text(format!(
                    "lambda_range_nm: a band of a reduced conical table (version 3), got \
                     version {version}"
                )))
            }
            (_, None) => None,
        };
        if let (Some(p), Some(b)) = (&planes, &beta) {
            if p.len() != b.len() {
                let requirement = Requirement::Count {
                    min: b.len(),
                    max: b.len(),
                };
                return Err(typed(Error::invalid(
                    "lambda_nm",
                    p.len() as f64,
                    requirement,
                )));
            }
        }
        let order_min = self.order_min.ok_or_else(|| missing("order_min"))?;
        let order_min = integer("order_min", order_min).map_err(text)?;
        let order_max = self.order_max.ok_or_else(|| missing("order_max"))?;
        let order_max = integer("order_max", order_max).map_err(text)?;
        let i32_range = Requirement::Within {
            min: f64::from(i32::MIN),
            max: f64::from(i32::MAX),
        };
        let Ok(first) = i32::try_from(order_min) else {
            return Err(typed(Error::invalid(
                "order_min",
                order_min as f64,
                i32_range,
            )));
        };
        // i128: no difference of two i64 (or u64) overflows.
        if order_max < order_min {
            let requirement = Requirement::AtLeast {
                bound_name: "order_min",
                bound: order_min as f64,
            };
            return Err(typed(Error::invalid(
                "order_max",
                order_max as f64,
                requirement,
            )));
        }
        let n_o = order_max - order_min + 1;
        if n_o > MAX_TABLE_ORDERS as i128 {
            let requirement = Requirement::Within {
                min: order_min as f64,
                max: (order_min + MAX_TABLE_ORDERS as i128 - 1) as f64,
            };
            return Err(typed(Error::invalid(
                "order_max",
                order_max as f64,
                requirement,
            )));
        }
        // The expected shape, outermost first: [order][λ][s] or [order][|β|][λ][s] (version
        // 3: [order][plane][λ of the plane][s], the first plane's rows in `want`).
        let mut want = vec![n_o as usize];
        want.extend(beta.as_ref().map(Vec::len));
        let plane_rows: Vec<usize> = planes.iter().flatten().map(Vec::len).collect();
        want.extend([plane_rows.first().copied().unwrap_or(lam.len()), sin.len()]);
        let mut flat = [Vec::new(), Vec::new()];
        for (k, (name, cube)) in [("te", self.te), ("tm", self.tm)].into_iter().enumerate() {
            let cube = cube.ok_or_else(|| missing(name))?;
            if planes.is_some() {
                let rows = |r: &[usize]| r.iter().map(|n| n.to_string()).collect::<Vec<_>>();
                let got = if cube.leaf == 4 {
                    rows(&cube.plane_rows)
                } else {
                    Vec::new()
                };
                let total: usize = plane_rows.iter().sum();
                let values = n_o as usize * total * sin.len();
                let same = cube.leaf == 4
                    && cube.shape[0] == n_o as usize
                    && cube.plane_rows == plane_rows
                    && cube.shape[3] == sin.len()
                    && cube.values.len() == values;
                if !same {
                    let dims = |d: &[usize], r: &[String]| {
                        format!("[{}][{}][{}][{}]", d[0], d[1], r.join(","), d[3])
                    };
                    let mut shape = cube.shape;
                    if cube.leaf != 4 {
                        shape = [cube.shape[0], cube.shape[1], 0, 0];
                    }
                    let wanted = [n_o as usize, plane_rows.len(), 0, sin.len()];
                    return Err(text(format!(
                        "{name}: has shape {}, expected {} ([order][plane][lambda of the \
                         plane][sin])",
                        dims(&shape, &got),
                        dims(&wanted, &rows(&plane_rows))
                    )));
                }
                flat[k] = cube.values;
                continue;
            }
            // An empty level leaves the levels inside it unread (0); a 4-level array in a
            // version-1 file (or a 3-level one in version 2) has the wrong shape.
            let depth = if cube.leaf == 0 {
                want.len()
            } else {
                cube.leaf
            };
            let got = &cube.shape[..depth];
            let mut same = got.len() == want.len();
            let mut outer = 1;
            for (g, w) in got.iter().zip(&want) {
                same &= outer == 0 || g == w;
                outer *= g;
            }
            if !same || cube.values.len() != want.iter().product::<usize>() {
                let dims = |v: &[usize]| v.iter().map(|n| format!("[{n}]")).collect::<String>();
                let axes = if beta.is_some() {
                    "[order][abs_beta][lambda][sin]"
                } else {
                    "[order][lambda][sin]"
                };
                return Err(text(format!(
                    "{name}: has shape {}, expected {} ({axes})",
                    dims(got),
                    dims(&want)
                )));
            }
            flat[k] = cube.values;
        }
        let [te, tm] = flat;
        match (beta, planes, band) {
            (Some(b), Some(p), Some(band)) => {
                let grid = ReducedGrid {
                    sin_theta_i: sin,
                    abs_beta: b,
                    lambda_range_nm: band,
                    lambda_nm: p,
                };
                EfficiencyTable::new_reduced(period, first, grid, te, tm)
            }
            (Some(b), _, _) => EfficiencyTable::new_conical(period, first, sin, b, lam, te, tm),
            (None, _, _) => EfficiencyTable::new(period, first, sin, lam, te, tm),
        }
        .map_err(typed)
    }
}

/// The JSON table of `docs/efficiency_tables.md` (features `serde` and `alloc`; a
/// self-describing format such as JSON), checked as [`EfficiencyTable::new`] checks (and
/// `format` = `"diffraction-efficiency-table"`, `version` = the integer 1, 2 or 3, `order_min`
/// and `order_max` integers with `order_max` ≥ `order_min`, `te` and `tm` of shape
/// `[order_max − order_min + 1][n_λ][n_s]`, with `abs_beta` `[…][n_β][n_λ][n_s]` (version 2,
/// [`EfficiencyTable::new_conical`]'s checks), or `[…][n_β][rows of plane p][n_s]` with
/// `abs_beta`, `lambda_range_nm` and `lambda_nm` one array per plane (version 3,
/// [`EfficiencyTable::new_reduced`]'s checks)); each error names the field, and the element
/// (`te[2][0][1]: expected a number, got null`), also where the parser itself refuses a value
/// (`lambda_nm[1]: number out of range`). Fields the crate does not use (`name`,
/// `description`, `symmetric`, `solver`, `validation`, `command`, `sha256`, the grating's
/// other fields) are skipped without being stored. Memory is bounded by the table's limits,
/// whatever the input: an axis is refused past [`MAX_TABLE_NODES`] values, `te` or `tm` past
/// [`MAX_TABLE_ORDERS`] orders, [`MAX_TABLE_NODES`] rows or values per row,
/// [`MAX_TABLE_VALUES`] values or a first row of another length; a string in a message is
/// quoted to 40 characters. The input itself is the caller's: bound its size where it comes
/// from an untrusted source.
///
/// ```
/// use diffraction::relief::EfficiencyTable;
/// let json = r#"{"format": "diffraction-efficiency-table", "version": 1,
///     "grating": {"period_nm": 1000.0, "profile": "sinusoid"}, "solver": {},
///     "sin_theta_i": [0.0, 0.5], "lambda_nm": [500.0, 600.0], "order_min": 0, "order_max": 0,
///     "te": [[[0.9, 0.9], [0.9, 0.9]]], "tm": [[[0.8, 0.8], [0.8, 0.8]]]}"#;
/// let t: EfficiencyTable = serde_json::from_str(json).unwrap();
/// assert!((t.efficiency(0, 0.2, 550.0).tm - 0.8).abs() < 1e-15);
/// let bad = json.replace("\"version\": 1", "\"version\": 1.0");
/// let e = serde_json::from_str::<EfficiencyTable>(&bad).unwrap_err();
/// assert!(e.to_string().starts_with("version: expected 1, 2 or 3, got 1.0"));
/// let bad = json.replace("[500.0, 600.0]", "[500.0, 1e400]");
/// let e = serde_json::from_str::<EfficiencyTable>(&bad).unwrap_err();
/// assert!(e.to_string().starts_with("lambda_nm[1]: number out of range"));
/// ```
impl<'de> de::Deserialize<'de> for EfficiencyTable {
    fn deserialize<D: de::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(FileVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::without_position;

    #[test]
    fn positions_are_stripped_only_when_they_are_one() {
        assert_eq!(without_position("x at line 3 column 14"), "x");
        assert_eq!(without_position("x at line 3"), "x at line 3");
        assert_eq!(
            without_position("x at line a column 1"),
            "x at line a column 1"
        );
        assert_eq!(without_position("plain"), "plain");
    }
}
