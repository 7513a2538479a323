//! `diffraction::color` against colour-science fixtures in `tests/data/` (made by
//! `python_ref/generate.py`; each file's `#` header names its source).
//!
//! A missing or malformed fixture makes the test **fail**, never skip.

use std::path::PathBuf;

use diffraction::color::{srgb_decode, srgb_encode, Lab, LinearSrgb, WhitePoint, Xyz};

/// Tolerances, each with its reason and measurement.
#[path = "support/color_tolerance.rs"]
mod tol;

/// One fixture: `#` comment lines, a header row, data rows (empty field → `None`).
struct Csv {
    name: String,
    comments: Vec<String>,
    header: Vec<String>,
    rows: Vec<Vec<Option<f64>>>,
}

impl Csv {
    fn load(file: &str) -> Csv {
        let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests", "data", file]
            .iter()
            .collect();
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!(
                "fixture {} is missing or unreadable ({e}); generate it with \
                 `python3 python_ref/generate.py`",
                path.display()
            )
        });
        let mut comments = Vec::new();
        let mut header = None;
        let mut rows = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let line = line.trim_end_matches('\r');
            if let Some(c) = line.strip_prefix('#') {
                comments.push(c.trim().to_string());
                continue;
            }
            if line.trim().is_empty() {
                continue;
            }
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            match &header {
                None => header = Some(fields.iter().map(|s| s.to_string()).collect::<Vec<_>>()),
                Some(h) => {
                    assert_eq!(
                        fields.len(),
                        h.len(),
                        "{file}:{}: {} fields, header has {}",
                        i + 1,
                        fields.len(),
                        h.len()
                    );
                    rows.push(
                        fields
                            .iter()
                            .map(|f| {
                                if f.is_empty() {
                                    None
                                } else {
                                    Some(f.parse::<f64>().unwrap_or_else(|e| {
                                        panic!("{file}:{}: bad number {f:?}: {e}", i + 1)
                                    }))
                                }
                            })
                            .collect(),
                    );
                }
            }
        }
        let header = header.unwrap_or_else(|| panic!("{file}: no header row"));
        assert!(!rows.is_empty(), "{file}: no data rows");
        Csv {
            name: file.to_string(),
            comments,
            header,
            rows,
        }
    }

    fn col(&self, name: &str) -> usize {
        self.header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{}: no column {name:?} in {:?}", self.name, self.header))
    }

    /// The named columns of one row, all present, or `None` when all are empty. Partly empty is
    /// a malformed fixture.
    fn get<const N: usize>(&self, row: usize, cols: [usize; N]) -> Option<[f64; N]> {
        let r = &self.rows[row];
        let present = cols.iter().filter(|&&c| r[c].is_some()).count();
        if present == 0 {
            return None;
        }
        assert_eq!(
            present,
            N,
            "{} row {}: columns {:?} partly empty",
            self.name,
            row + 1,
            cols.map(|c| &self.header[c])
        );
        Some(cols.map(|c| r[c].unwrap()))
    }
}

/// Tracks the largest error of a comparison, and fails with all offending rows.
struct Check {
    what: &'static str,
    tol: f64,
    max_err: f64,
    count: usize,
    failures: Vec<String>,
}

impl Check {
    fn new(what: &'static str, tol: f64) -> Check {
        Check {
            what,
            tol,
            max_err: 0.0,
            count: 0,
            failures: Vec::new(),
        }
    }

    fn close(&mut self, row: usize, label: &str, got: f64, want: f64) {
        let err = (got - want).abs();
        self.count += 1;
        if err.is_nan() || err > self.tol {
            self.failures.push(format!(
                "row {}: {label}: got {got:e}, want {want:e}, error {err:e}",
                row + 1
            ));
        }
        if err > self.max_err {
            self.max_err = err;
        }
    }

    fn finish(self) {
        println!(
            "{}: {} values, max error {:e} (tolerance {:e})",
            self.what, self.count, self.max_err, self.tol
        );
        assert!(self.count > 0, "{}: nothing compared", self.what);
        assert!(
            self.failures.is_empty(),
            "{}: {} of {} values off by more than {:e}:\n{}",
            self.what,
            self.failures.len(),
            self.count,
            self.tol,
            self.failures.join("\n")
        );
    }
}

#[test]
fn xyz_to_linear_and_encoded_srgb() {
    let csv = Csv::load("xyz_to_srgb.csv");
    let xyz_cols = [csv.col("X"), csv.col("Y"), csv.col("Z")];
    let lin_cols = [
        csv.col("R_linear"),
        csv.col("G_linear"),
        csv.col("B_linear"),
    ];
    let enc_cols = [
        csv.col("R_encoded"),
        csv.col("G_encoded"),
        csv.col("B_encoded"),
    ];
    let mut linear = Check::new("XYZ -> linear sRGB", tol::LINEAR);
    let mut encoded = Check::new("linear -> encoded sRGB", tol::ENCODED);
    let mut out_of_gamut = 0;
    for i in 0..csv.rows.len() {
        let [x, y, z] = csv.get(i, xyz_cols).expect("XYZ present in every row");
        let want = csv
            .get(i, lin_cols)
            .expect("linear sRGB present in every row");
        let got = Xyz::new(x, y, z).to_linear_srgb();
        for (k, (g, w)) in [got.r, got.g, got.b].into_iter().zip(want).enumerate() {
            linear.close(i, ["R", "G", "B"][k], g, w);
        }
        let fixture_linear = LinearSrgb::new(want[0], want[1], want[2]);
        match csv.get(i, enc_cols) {
            Some(want_enc) => {
                assert!(
                    fixture_linear.is_in_gamut(),
                    "row {}: encoded values given for an out-of-gamut colour",
                    i + 1
                );
                let e = got.encode();
                for (k, (g, w)) in [e.r, e.g, e.b].into_iter().zip(want_enc).enumerate() {
                    encoded.close(i, ["R", "G", "B"][k], g, w);
                }
            }
            None => {
                assert!(
                    !fixture_linear.is_in_gamut(),
                    "row {}: in-gamut colour without encoded values",
                    i + 1
                );
                out_of_gamut += 1;
            }
        }
    }
    println!("{out_of_gamut} out-of-gamut rows (no encoded values)");
    linear.finish();
    encoded.finish();
}

#[test]
fn srgb_transfer_function() {
    let csv = Csv::load("srgb_transfer.csv");
    let cols = [csv.col("linear"), csv.col("encoded")];
    let mut forward = Check::new("srgb_encode", tol::ENCODED);
    let mut inverse = Check::new("srgb_decode", tol::DECODED);
    let mut window = Check::new(
        "srgb_decode just above the breakpoint",
        tol::DECODE_BREAKPOINT_WINDOW,
    );
    for i in 0..csv.rows.len() {
        let [linear, encoded] = csv.get(i, cols).expect("both columns present");
        forward.close(i, "encode", srgb_encode(linear), encoded);
        let a = linear.abs();
        if a > 0.0031308 && encoded.abs() <= 0.04045 {
            window.close(i, "decode", srgb_decode(encoded), linear);
        } else {
            inverse.close(i, "decode", srgb_decode(encoded), linear);
        }
    }
    forward.finish();
    inverse.finish();
    if window.count > 0 {
        window.finish();
    }
}

/// The white point from the `# white: Xn Yn Zn` comment.
fn white_point(csv: &Csv) -> Xyz {
    let line = csv
        .comments
        .iter()
        .find_map(|c| c.strip_prefix("white:"))
        .unwrap_or_else(|| panic!("{}: no `# white: Xn Yn Zn` line", csv.name));
    let v: Vec<f64> = line
        .split_whitespace()
        .map(|s| {
            s.parse()
                .unwrap_or_else(|e| panic!("white point {s:?}: {e}"))
        })
        .collect();
    assert_eq!(v.len(), 3, "white point needs three numbers: {line:?}");
    Xyz::new(v[0], v[1], v[2])
}

/// Whether the hues of two Lab colours differ by 180° to within the discontinuity tolerance.
fn opposite_hues(p: Lab, q: Lab) -> bool {
    if (p.a == 0.0 && p.b == 0.0) || (q.a == 0.0 && q.b == 0.0) {
        return false;
    }
    let d = (p.b.atan2(p.a) - q.b.atan2(q.a)).to_degrees().abs();
    (d - 180.0).abs() < tol::HUE_DISCONTINUITY_DEG
}

/// The two one-sided limits of ΔE2000 at a hue discontinuity: turn q's hue a little each way.
fn one_sided_limits(p: Lab, q: Lab) -> [f64; 2] {
    [tol::LIMIT_STEP_RAD, -tol::LIMIT_STEP_RAD].map(|t| {
        let (s, c) = t.sin_cos();
        p.delta_e2000(Lab::new(q.l, c * q.a - s * q.b, s * q.a + c * q.b))
    })
}

#[test]
fn xyz_to_lab_and_delta_e2000() {
    let csv = Csv::load("lab_de2000.csv");
    let white = white_point(&csv);
    let lab_white = WhitePoint::new(white).unwrap();
    let xyz1 = [csv.col("X1"), csv.col("Y1"), csv.col("Z1")];
    let xyz2 = [csv.col("X2"), csv.col("Y2"), csv.col("Z2")];
    let lab1 = [csv.col("L1"), csv.col("a1"), csv.col("b1")];
    let lab2 = [csv.col("L2"), csv.col("a2"), csv.col("b2")];
    let de = csv.col("dE2000");

    let mut lab = Check::new("XYZ -> Lab", tol::LAB);
    let mut de_fixture_lab = Check::new("dE2000 of the fixture's Lab", tol::DE2000);
    let mut de_our_lab = Check::new("dE2000 of our Lab", tol::DE2000_FROM_XYZ);
    let mut one_sided = Check::new("dE2000 at a 180 degree hue difference", tol::ONE_SIDED);
    let (mut from_xyz, mut from_lab) = (0, 0);
    for i in 0..csv.rows.len() {
        let [l1, a1, b1] = csv.get(i, lab1).expect("Lab1 present in every row");
        let [l2, a2, b2] = csv.get(i, lab2).expect("Lab2 present in every row");
        let want_de = csv.rows[i][de].expect("dE2000 present in every row");
        let (p, q) = (Lab::new(l1, a1, b1), Lab::new(l2, a2, b2));

        let ours = match (csv.get(i, xyz1), csv.get(i, xyz2)) {
            (Some([x1, y1, z1]), Some([x2, y2, z2])) => {
                from_xyz += 1;
                let (op, oq) = (
                    Xyz::new(x1, y1, z1).to_lab(lab_white),
                    Xyz::new(x2, y2, z2).to_lab(lab_white),
                );
                for (label, g, w) in [
                    ("L1", op.l, l1),
                    ("a1", op.a, a1),
                    ("b1", op.b, b1),
                    ("L2", oq.l, l2),
                    ("a2", oq.a, a2),
                    ("b2", oq.b, b2),
                ] {
                    lab.close(i, label, g, w);
                }
                Some((op, oq))
            }
            (None, None) => {
                from_lab += 1;
                None
            }
            _ => panic!("row {}: only one of the two XYZ triples given", i + 1),
        };

        if opposite_hues(p, q) && (p.delta_e2000(q) - want_de).abs() > tol::DE2000 {
            // On the discontinuity, and the two libraries picked different sides: both our
            // value and colour-science's must be one of the one-sided limits.
            let limits = one_sided_limits(p, q);
            let mut check_side = |label: &str, got: f64| {
                let nearest = if (got - limits[0]).abs() < (got - limits[1]).abs() {
                    limits[0]
                } else {
                    limits[1]
                };
                one_sided.close(i, label, got, nearest);
            };
            check_side("ours", p.delta_e2000(q));
            check_side("colour-science", want_de);
            println!(
                "row {}: hue difference 180 degrees: ours {}, colour-science {}, limits {:?}",
                i + 1,
                p.delta_e2000(q),
                want_de,
                limits
            );
            continue;
        }
        de_fixture_lab.close(i, "dE2000", p.delta_e2000(q), want_de);
        de_fixture_lab.close(i, "dE2000 swapped", q.delta_e2000(p), want_de);
        if let Some((op, oq)) = ours {
            de_our_lab.close(i, "dE2000", op.delta_e2000(oq), want_de);
        }
    }
    println!("{from_xyz} rows from XYZ, {from_lab} given as Lab");
    assert!(from_xyz > 0 && from_lab > 0, "expected both kinds of rows");
    lab.finish();
    de_fixture_lab.finish();
    de_our_lab.finish();
    if one_sided.count > 0 {
        one_sided.finish();
    }
}
