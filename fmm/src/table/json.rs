//! The JSON file of `docs/efficiency_tables.md`, written so that `python_ref`'s reader accepts
//! it byte for byte: keys sorted, compact separators, floats as Python's `repr` writes them, and
//! the `sha256` field over `json.dumps(body, sort_keys=True, separators=(",", ":"))`.

use std::fmt::Write as _;

use super::BuiltTable;

/// The descriptive fields of a table file.
#[derive(Debug, Clone, PartialEq)]
pub struct TableMeta {
    /// `name`.
    pub name: String,
    /// `description`.
    pub description: String,
    /// `grating.profile`: `"sinusoid"`, `"lamellar"` or `"sawtooth"`.
    pub profile: String,
    /// `grating.period_nm`.
    pub period_nm: f64,
    /// `grating.depth_nm`.
    pub depth_nm: f64,
    /// `grating.duty` (lamellar).
    pub duty: Option<f64>,
    /// `grating.blaze_deg` (sawtooth).
    pub blaze_deg: Option<f64>,
    /// `grating.metal`: `"Al"`, … or `"N+Ki"`.
    pub metal: String,
    /// `grating.cover`: `"none"` or `"polycarbonate"`.
    pub cover: String,
    /// `symmetric`.
    pub symmetric: bool,
    /// `solver.method`.
    pub method: String,
    /// `solver.harmonics`: the largest count used, if known.
    pub harmonics: Option<usize>,
    /// `solver.convergence`: how each node was converged.
    pub convergence: String,
    /// `solver.cover_model`, if there is a cover.
    pub cover_model: Option<String>,
    /// `command`.
    pub command: String,
}

/// A JSON value, enough for the table file.
enum Value {
    Null,
    Bool(bool),
    Int(i64),
    Float(f64),
    Str(String),
    Array(Vec<Value>),
    /// Keys are sorted when written.
    Object(Vec<(&'static str, Value)>),
}

/// Python's `repr(float)`: the shortest round-trip digits, fixed notation for decimal
/// exponents −4 ≤ e < 16 (with `.0` on integers), else `d.ddde±XX`.
fn py_float(out: &mut String, x: f64) {
    if x == 0.0 {
        out.push_str(if x.is_sign_negative() { "-0.0" } else { "0.0" });
        return;
    }
    let sci = format!("{:e}", x);
    let (mant, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let (neg, mant) = match mant.strip_prefix('-') {
        Some(m) => (true, m),
        None => (false, mant),
    };
    let digits: String = mant.chars().filter(char::is_ascii_digit).collect();
    if neg {
        out.push('-');
    }
    if !(-4..16).contains(&exp) {
        out.push_str(&digits[..1]);
        if digits.len() > 1 {
            out.push('.');
            out.push_str(&digits[1..]);
        }
        let _ = write!(out, "e{}{:02}", if exp < 0 { '-' } else { '+' }, exp.abs());
        return;
    }
    // Fixed: the decimal point after digit index exp + 1.
    let point = exp + 1;
    if point <= 0 {
        out.push_str("0.");
        for _ in 0..(-point) {
            out.push('0');
        }
        out.push_str(&digits);
    } else {
        let p = point as usize;
        if digits.len() <= p {
            out.push_str(&digits);
            for _ in digits.len()..p {
                out.push('0');
            }
            out.push_str(".0");
        } else {
            out.push_str(&digits[..p]);
            out.push('.');
            out.push_str(&digits[p..]);
        }
    }
}

/// Python's `json.dumps` string (ensure_ascii).
fn py_str(out: &mut String, s: &str) {
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            '\u{8}' => out.push_str("\\b"),
            '\u{c}' => out.push_str("\\f"),
            c if (c as u32) < 0x20 || (c as u32) > 0x7e => {
                let mut buf = [0u16; 2];
                for unit in c.encode_utf16(&mut buf) {
                    let _ = write!(out, "\\u{unit:04x}");
                }
            }
            c => out.push(c),
        }
    }
    out.push('"');
}

fn write_value(out: &mut String, v: &Value) {
    match v {
        Value::Null => out.push_str("null"),
        Value::Bool(b) => out.push_str(if *b { "true" } else { "false" }),
        Value::Int(i) => {
            let _ = write!(out, "{i}");
        }
        Value::Float(x) => py_float(out, *x),
        Value::Str(s) => py_str(out, s),
        Value::Array(a) => {
            out.push('[');
            for (i, x) in a.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_value(out, x);
            }
            out.push(']');
        }
        Value::Object(fields) => {
            let mut sorted: Vec<&(&str, Value)> = fields.iter().collect();
            sorted.sort_by(|a, b| a.0.cmp(b.0));
            out.push('{');
            for (i, (k, x)) in sorted.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                py_str(out, k);
                out.push(':');
                write_value(out, x);
            }
            out.push('}');
        }
    }
}

/// SHA-256 (FIPS 180-4) of `data`, lower-case hex.
fn sha256_hex(data: &[u8]) -> String {
    const K: [u32; 64] = [
        0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4,
        0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe,
        0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f,
        0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7,
        0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc,
        0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b,
        0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116,
        0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
        0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
        0xc67178f2,
    ];
    let mut h: [u32; 8] = [
        0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab,
        0x5be0cd19,
    ];
    let mut msg = data.to_vec();
    let bits = (data.len() as u64).wrapping_mul(8);
    msg.push(0x80);
    while msg.len() % 64 != 56 {
        msg.push(0);
    }
    msg.extend_from_slice(&bits.to_be_bytes());
    for block in msg.chunks_exact(64) {
        let mut w = [0u32; 64];
        for (i, c) in block.chunks_exact(4).enumerate() {
            w[i] = u32::from_be_bytes([c[0], c[1], c[2], c[3]]);
        }
        for i in 16..64 {
            let s0 = w[i - 15].rotate_right(7) ^ w[i - 15].rotate_right(18) ^ (w[i - 15] >> 3);
            let s1 = w[i - 2].rotate_right(17) ^ w[i - 2].rotate_right(19) ^ (w[i - 2] >> 10);
            w[i] = w[i - 16]
                .wrapping_add(s0)
                .wrapping_add(w[i - 7])
                .wrapping_add(s1);
        }
        let mut v = h;
        for i in 0..64 {
            let s1 = v[4].rotate_right(6) ^ v[4].rotate_right(11) ^ v[4].rotate_right(25);
            let ch = (v[4] & v[5]) ^ (!v[4] & v[6]);
            let t1 = v[7]
                .wrapping_add(s1)
                .wrapping_add(ch)
                .wrapping_add(K[i])
                .wrapping_add(w[i]);
            let s0 = v[0].rotate_right(2) ^ v[0].rotate_right(13) ^ v[0].rotate_right(22);
            let maj = (v[0] & v[1]) ^ (v[0] & v[2]) ^ (v[1] & v[2]);
            let t2 = s0.wrapping_add(maj);
            v = [
                t1.wrapping_add(t2),
                v[0],
                v[1],
                v[2],
                v[3].wrapping_add(t1),
                v[4],
                v[5],
                v[6],
            ];
        }
        for (a, b) in h.iter_mut().zip(v) {
            *a = a.wrapping_add(b);
        }
    }
    h.iter().fold(String::with_capacity(64), |mut s, x| {
        let _ = write!(s, "{x:08x}");
        s
    })
}

/// Efficiencies are written rounded to 6 decimals, as `python_ref` writes them.
fn round6(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

fn opt(x: Option<f64>) -> Value {
    x.map_or(Value::Null, Value::Float)
}

fn floats(v: &[f64]) -> Value {
    Value::Array(v.iter().map(|&x| Value::Float(x)).collect())
}

/// `[order][λ][s]` (or `[order][|β|][λ][s]`, or `[order][plane][λ of the plane][s]`) nested
/// arrays of one polarisation.
fn nested(t: &BuiltTable, flat: &[f64]) -> Value {
    if !t.plane_lambda_nm.is_empty() {
        let n_s = t.sin_theta_i.len();
        let total: usize = t.plane_lambda_nm.iter().map(Vec::len).sum();
        let n_o = (t.order_max - t.order_min + 1) as usize;
        let row = |at: usize| {
            let r = &flat[at * n_s..(at + 1) * n_s];
            Value::Array(r.iter().map(|&x| Value::Float(round6(x))).collect())
        };
        return Value::Array(
            (0..n_o)
                .map(|k| {
                    let mut first = k * total;
                    Value::Array(
                        t.plane_lambda_nm
                            .iter()
                            .map(|plane| {
                                let rows = (first..first + plane.len()).map(row).collect();
                                first += plane.len();
                                Value::Array(rows)
                            })
                            .collect(),
                    )
                })
                .collect(),
        );
    }
    let (n_s, n_l) = (t.sin_theta_i.len(), t.lambda_nm.len());
    let n_b = t.abs_beta.len().max(1);
    let n_o = (t.order_max - t.order_min + 1) as usize;
    let rows = |plane: usize| {
        Value::Array(
            (0..n_l)
                .map(|j| {
                    let at = (plane * n_l + j) * n_s;
                    let row = &flat[at..at + n_s];
                    Value::Array(row.iter().map(|&x| Value::Float(round6(x))).collect())
                })
                .collect(),
        )
    };
    Value::Array(
        (0..n_o)
            .map(|k| {
                if t.abs_beta.is_empty() {
                    rows(k)
                } else {
                    Value::Array((0..n_b).map(|b| rows(k * n_b + b)).collect())
                }
            })
            .collect(),
    )
}

impl BuiltTable {
    /// The table as the JSON file of `docs/efficiency_tables.md` (one line), with the build's
    /// error in `validation` (`tolerance`, `achieved_abs_error`, …) and the `sha256` field
    /// `python_ref/efficiency_table.py::read_json` checks.
    #[must_use]
    pub fn to_json(&self, meta: &TableMeta) -> String {
        let r = &self.report;
        let reduced = !self.plane_lambda_nm.is_empty();
        let conical = !self.abs_beta.is_empty();
        let max_sum = |flat: &[f64]| {
            let rows = if reduced {
                self.plane_lambda_nm.iter().map(Vec::len).sum()
            } else {
                self.lambda_nm.len() * self.abs_beta.len().max(1)
            };
            let slice = self.sin_theta_i.len() * rows;
            let mut sums = vec![0.0; slice];
            for (i, &x) in flat.iter().enumerate() {
                sums[i % slice] += round6(x);
            }
            sums.iter().fold(0.0f64, |a, &b| a.max(b))
        };
        let mut solver = vec![
            ("method", Value::Str(meta.method.clone())),
            (
                "harmonics",
                meta.harmonics.map_or(Value::Null, |h| Value::Int(h as i64)),
            ),
            ("convergence", Value::Str(meta.convergence.clone())),
            ("seconds", Value::Float((r.seconds * 10.0).round() / 10.0)),
            ("solves", Value::Int(r.solves as i64)),
        ];
        if let Some(c) = &meta.cover_model {
            solver.push(("cover_model", Value::Str(c.clone())));
        }
        let validation = vec![
            ("sum_tolerance", Value::Float(1e-6)),
            (
                "max_sum",
                Value::Object(vec![
                    ("te", Value::Float(max_sum(&self.te))),
                    ("tm", Value::Float(max_sum(&self.tm))),
                ]),
            ),
            (
                "method",
                Value::Str(format!(
                    "{}, against the library's interpolation (relief::EfficiencyTable); largest absolute error over \
                     every order {}",
                    if r.fixed_grid {
                        "held-out rigorous solves at random points inside the given grid (fixed nodes, not refined)"
                    } else if reduced {
                        "held-out rigorous solves at the midpoints of every interval of the final grid (along s', along \
                         each plane's wavelengths, and between planes at the mean of their sqrt(1 - beta^2)) and at \
                         random points"
                    } else {
                        "held-out rigorous solves at the midpoints of every interval of the final grid and at random points"
                    },
                    if conical {
                        "of the unpolarised efficiency (the mean of TE and TM: a conical solve's s and p split depends \
                         on the azimuth, their mean does not)"
                    } else {
                        "and both polarisations"
                    }
                )),
            ),
            (
                "tolerance",
                if r.fixed_grid {
                    Value::Null
                } else {
                    Value::Float(r.tolerance)
                },
            ),
            ("achieved_abs_error", Value::Float(r.achieved_abs_error)),
            (
                "interpolation_abs_error_max",
                Value::Float(r.achieved_abs_error),
            ),
            ("interpolation_abs_error_p95", Value::Float(r.abs_error_p95)),
            (
                "interpolation_abs_error_median",
                Value::Float(r.abs_error_median),
            ),
            ("interpolation_points", Value::Int(r.held_out_points as i64)),
            (
                "random_points_abs_error_max",
                Value::Float(r.random_points_max),
            ),
            (
                "unresolved_intervals",
                Value::Int(r.unresolved_intervals as i64),
            ),
            ("unconverged_points", Value::Int(r.unconverged.0 as i64)),
            ("unconverged_max_change", Value::Float(r.unconverged.1)),
            ("rounds", Value::Int(r.rounds as i64)),
        ];
        let mut body = vec![
            ("format", Value::Str("diffraction-efficiency-table".into())),
            (
                "version",
                Value::Int(match (conical, reduced) {
                    (_, true) => 3,
                    (true, false) => 2,
                    _ => 1,
                }),
            ),
            ("name", Value::Str(meta.name.clone())),
            ("description", Value::Str(meta.description.clone())),
            (
                "grating",
                Value::Object(vec![
                    ("profile", Value::Str(meta.profile.clone())),
                    ("period_nm", Value::Float(meta.period_nm)),
                    ("depth_nm", Value::Float(meta.depth_nm)),
                    ("duty", opt(meta.duty)),
                    ("blaze_deg", opt(meta.blaze_deg)),
                    ("metal", Value::Str(meta.metal.clone())),
                    ("cover", Value::Str(meta.cover.clone())),
                ]),
            ),
            ("symmetric", Value::Bool(meta.symmetric)),
            ("sin_theta_i", floats(&self.sin_theta_i)),
            (
                "lambda_nm",
                if reduced {
                    Value::Array(self.plane_lambda_nm.iter().map(|p| floats(p)).collect())
                } else {
                    floats(&self.lambda_nm)
                },
            ),
            ("order_min", Value::Int(i64::from(self.order_min))),
            ("order_max", Value::Int(i64::from(self.order_max))),
            ("te", nested(self, &self.te)),
            ("tm", nested(self, &self.tm)),
            ("solver", Value::Object(solver)),
            ("validation", Value::Object(validation)),
            ("command", Value::Str(meta.command.clone())),
        ];
        if conical {
            body.push(("abs_beta", floats(&self.abs_beta)));
        }
        if reduced {
            let (l0, l1) = self.lambda_range_nm;
            body.push(("lambda_range_nm", floats(&[l0, l1])));
        }
        let body = Value::Object(body);
        let mut text = String::new();
        write_value(&mut text, &body);
        let hash = sha256_hex(text.as_bytes());
        let Value::Object(mut fields) = body else {
            unreachable!()
        };
        fields.push(("sha256", Value::Str(hash)));
        let mut out = String::with_capacity(text.len() + 80);
        write_value(&mut out, &Value::Object(fields));
        out.push('\n');
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_as_python_repr() {
        // Python 3: repr() of each value.
        let cases = [
            (0.1, "0.1"),
            (1.0, "1.0"),
            (-2.5, "-2.5"),
            (1e-4, "0.0001"),
            (1e-5, "1e-05"),
            (1.5e-7, "1.5e-07"),
            (123456.0, "123456.0"),
            (1e16, "1e+16"),
            (1234567890123456.0, "1234567890123456.0"),
            (0.9999, "0.9999"),
            (-0.0, "-0.0"),
            (2.0f64.sqrt(), "1.4142135623730951"),
        ];
        for (x, want) in cases {
            let mut s = String::new();
            py_float(&mut s, x);
            assert_eq!(s, want, "{x:e}");
        }
    }

    #[test]
    fn sha256_known_answers() {
        // FIPS 180-4 examples.
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
        assert_eq!(
            sha256_hex(b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1"
        );
    }

    #[test]
    fn strings_as_python_json() {
        let mut s = String::new();
        py_str(&mut s, "a\"b\\c\n\u{e9}\u{1f600}");
        assert_eq!(s, r#""a\"b\\c\n\u00e9\ud83d\ude00""#);
    }
}
