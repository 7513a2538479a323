//! Scene-file errors that name the file, the line and the field.
//!
//! The TOML document is parsed once more into `toml::de::DeTable`, which keeps the byte span of
//! every key and value, to turn a field path (`objects[2].material.period_nm`) into a line, and
//! a span reported by the deserialiser back into a field path.

use std::fmt;
use std::ops::Range;

use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// An error in a scene file.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError {
    /// The file, as the user named it.
    pub file: String,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// The field path, e.g. `objects[2].material.period_nm`, when known.
    pub field: Option<String>,
    /// What is wrong and what is expected.
    pub message: String,
    /// Whether the scene is valid but another renderer's (see `Physics::accepts`).
    pub other_renderer: bool,
}

impl SceneError {
    /// An error in `file`, at a line and a field when known.
    pub fn new(
        file: &str,
        line: Option<usize>,
        field: Option<String>,
        message: String,
    ) -> SceneError {
        SceneError {
            file: file.to_string(),
            line,
            field,
            message,
            other_renderer: false,
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.file)?;
        if let Some(line) = self.line {
            write!(f, "line {line}, ")?;
        }
        if let Some(field) = &self.field {
            write!(f, "field {field}: ")?;
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for SceneError {}

/// A failed check: the field path and the message.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldError {
    /// The field path, e.g. `objects[2].material.period_nm`.
    pub path: String,
    /// What is wrong and what is expected.
    pub message: String,
}

impl FieldError {
    /// The error `message` at the field `path`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> FieldError {
        FieldError {
            path: path.into(),
            message: message.into(),
        }
    }
}

/// The result of a check of a scene value.
pub type Check<T> = Result<T, FieldError>;

/// 1-based line of a byte offset.
pub fn line_of(src: &str, offset: usize) -> usize {
    let end = offset.min(src.len());
    1 + src.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
}

/// One step of a field path.
#[derive(Debug, Clone, PartialEq)]
enum Seg {
    Key(String),
    Index(usize),
}

/// Splits `a.b[2].c` into its steps.
fn segments(path: &str) -> Vec<Seg> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !key.is_empty() {
            out.push(Seg::Key(key.to_string()));
        }
        while let Some(close) = rest.find(']') {
            if let Ok(i) = rest[1..close].parse() {
                out.push(Seg::Index(i));
            }
            rest = &rest[close + 1..];
        }
    }
    out
}

/// The value at `path` in a parsed document, if it is there.
pub fn value_at<'a>(root: &'a toml::Table, path: &str) -> Option<&'a toml::Value> {
    let mut segs = segments(path).into_iter();
    let Some(Seg::Key(first)) = segs.next() else {
        return None;
    };
    let mut v = root.get(&first)?;
    for seg in segs {
        v = match seg {
            Seg::Key(k) => v.get(k.as_str())?,
            Seg::Index(i) => v.get(i)?,
        };
    }
    Some(v)
}

/// The span of the deepest part of `path` present in the document (the whole document if
/// nothing matches).
pub fn locate(doc: &Spanned<DeTable<'_>>, path: &str) -> Range<usize> {
    let mut span = doc.span();
    let mut table: Option<&DeTable<'_>> = Some(doc.get_ref());
    let mut value: Option<&Spanned<DeValue<'_>>> = None;
    for seg in segments(path) {
        let next = match (&seg, table, value) {
            (Seg::Key(k), Some(t), _) => {
                t.iter().find(|(key, _)| key.get_ref() == k).map(|(_, v)| v)
            }
            (Seg::Index(i), _, Some(v)) => v.get_ref().as_array().and_then(|a| a.get(*i)),
            _ => None,
        };
        let Some(v) = next else { break };
        span = v.span();
        value = Some(v);
        table = v.get_ref().as_table();
    }
    span
}

/// The field path of the smallest key or value whose span contains `target`; `None` for the
/// whole document.
pub fn path_at(doc: &Spanned<DeTable<'_>>, target: Range<usize>) -> Option<String> {
    if target.is_empty() {
        return None; // the deserialiser's span for the document itself
    }
    let mut best: Option<(usize, String)> = None;
    let inside = move |span: &Range<usize>| span.start <= target.start && target.end <= span.end;
    type Best = Option<(usize, String)>;
    fn visit(
        v: &Spanned<DeValue<'_>>,
        path: String,
        inside: &dyn Fn(&Range<usize>) -> bool,
        best: &mut Best,
    ) {
        let span = v.span();
        if inside(&span) && best.as_ref().is_none_or(|(len, _)| span.len() <= *len) {
            *best = Some((span.len(), path.clone()));
        }
        match v.get_ref() {
            DeValue::Table(t) => visit_table(t, &path, inside, best),
            DeValue::Array(a) => {
                for (i, e) in a.iter().enumerate() {
                    visit(e, format!("{path}[{i}]"), inside, best);
                }
            }
            _ => {}
        }
    }
    fn visit_table(
        t: &DeTable<'_>,
        prefix: &str,
        inside: &dyn Fn(&Range<usize>) -> bool,
        best: &mut Best,
    ) {
        for (k, v) in t.iter() {
            let path = if prefix.is_empty() {
                k.get_ref().to_string()
            } else {
                format!("{prefix}.{}", k.get_ref())
            };
            // An unknown or mistyped key is reported at the key itself.
            let ks = k.span();
            if inside(&ks) && best.as_ref().is_none_or(|(len, _)| ks.len() <= *len) {
                *best = Some((ks.len(), path.clone()));
            }
            visit(v, path, inside, best);
        }
    }
    visit_table(doc.get_ref(), "", &inside, &mut best);
    best.map(|(_, p)| p).filter(|p| !p.is_empty())
}

/// Rewrites serde's Rust-flavoured expectations into plain words.
pub fn plain_message(message: &str) -> String {
    message
        .trim()
        .replace("expected f64", "expected a number")
        .replace("expected u32", "expected a non-negative integer")
        .replace("expected u64", "expected a non-negative integer")
        .replace(
            "data did not match any variant of untagged enum Scale",
            "expected a number or an array of 3 numbers",
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_and_spans_round_trip() {
        let src = "[camera]\nposition = [0, 1, 2]\n\n[[objects]]\nshape = \"quad\"\n\n[[objects]]\nshape = \"cube\"\n[objects.material]\nperiod_nm = -3\n";
        let doc = DeTable::parse(src).unwrap();
        let span = locate(&doc, "objects[1].material.period_nm");
        assert_eq!(line_of(src, span.start), 10);
        assert_eq!(
            path_at(&doc, span).as_deref(),
            Some("objects[1].material.period_nm")
        );
        assert_eq!(path_at(&doc, 0..src.len()), None);
        assert_eq!(line_of(src, locate(&doc, "camera.position").start), 2);
        // A missing leaf is reported at its deepest existing parent.
        assert_eq!(
            line_of(src, locate(&doc, "objects[0].material.type").start),
            4
        );
    }
}
