//! The round-3 reproducers of the new input surfaces (efficiency tables in memory and from
//! JSON, the colour tables' stored form, sampled wavelengths, the grating BSDF with tabulated
//! efficiencies), each as an exact test: finite results where the input is accepted, and for
//! the refused ones the exact message, which names the field.

use diffraction::relief::{EfficiencyTable, Polarised};

/// Two orders of a 1000 nm grating on a 2 × 2 grid whose corner (s = 0, λ = 999.9995 nm) is
/// within 10⁻³ of order −1's Rayleigh line (c_m = 10⁻⁶ − 2.5·10⁻¹³: counted as evanescent).
/// At s = 5·10⁻³²⁴ the only other weighted corner, (0.5, 999.9995), has the bilinear weight
/// 10⁻³²³: the normalisation by that weight overflowed to ∞ and gave 0·∞ = NaN.
fn grazing_corner_table() -> EfficiencyTable {
    let (s, l) = (vec![0.0, 0.5], vec![999.9995, 1200.0]);
    // [order][λ][s]: order −1, then order 0; order −1 is evanescent at (0, 1200).
    let te = vec![0.01, 0.3, 0.0, 0.2, 0.9, 0.6, 0.9, 0.7];
    EfficiencyTable::new(1000.0, -1, s, l, te.clone(), te).unwrap()
}

#[test]
fn a_corner_of_subnormal_weight_gives_finite_efficiencies() {
    let t = grazing_corner_table();
    let mut out = [Polarised::default(); 2];
    for s in [5e-324, 1e-320, 1e-310, 1e-300, 0.0, 1e-17] {
        let total = t.efficiencies(s, 999.9995, &mut out);
        assert!(
            total.is_finite() && (0.0..=1.0).contains(&total),
            "s = {s:e}: {total}"
        );
        let (te, tm): (f64, f64) = (
            out.iter().map(|e| e.te).sum(),
            out.iter().map(|e| e.tm).sum(),
        );
        assert!(te <= 1.0 && tm <= 1.0, "s = {s:e}: {out:?}");
        for m in [-1, 0] {
            let e = t.efficiency(m, s, 999.9995);
            assert!(
                e.te.is_finite() && e.te >= 0.0 && e.tm.is_finite(),
                "{m} {s:e}: {e:?}"
            );
        }
    }
    // At s = 5e-324 order −1 takes the one propagating corner's q (0.3 at s = 0.5, cos θi,c =
    // √0.75, cos θm,c = √(1 − 0.4999995²)) times the query's cos θm / cos θi: the closed form
    // within rounding.
    let e = t.efficiency(-1, 5e-324, 999.9995);
    let sm: f64 = 5e-324 - 0.9999995;
    let q = 0.3 * 0.75f64.sqrt() / (1.0 - 0.4999995f64 * 0.4999995).sqrt();
    let want = q * (1.0 - sm * sm).sqrt();
    assert!((e.te - want).abs() <= 1e-12 * want, "{} vs {want}", e.te);
}

/// A small valid JSON table (orders −1..=1 of a 1000 nm grating on a 2 × 2 grid) with
/// `edit` applied to its text.
#[cfg(feature = "serde")]
fn json_with(edit: impl Fn(&str) -> String) -> String {
    edit(concat!(
        r#"{"format": "diffraction-efficiency-table", "version": 1, "name": "t","#,
        r#" "grating": {"profile": "sinusoid", "period_nm": 1000.0, "metal": "Al"},"#,
        r#" "sin_theta_i": [0.0, 0.5], "lambda_nm": [500.0, 600.0],"#,
        r#" "order_min": -1, "order_max": 1,"#,
        r#" "te": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],"#,
        r#" "tm": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],"#,
        r#" "solver": {"method": "x"}, "sha256": "0"}"#
    ))
}

/// serde_json's message for a refused table, split into the text and whether it ends with
/// exactly one position (` at line L column C`).
#[cfg(feature = "serde")]
fn refusal(text: &str) -> (String, bool) {
    let e = serde_json::from_str::<EfficiencyTable>(text)
        .unwrap_err()
        .to_string();
    match e.rfind(" at line ") {
        Some(i) => (e[..i].to_string(), !e[..i].contains(" at line ")),
        None => (e, false),
    }
}

#[cfg(feature = "serde")]
#[test]
fn json_refusals_name_the_field_and_the_element() {
    assert!(serde_json::from_str::<EfficiencyTable>(&json_with(str::to_string)).is_ok());
    let long = "x".repeat(100_000);
    let cases: Vec<(String, &str)> = vec![
        (
            json_with(|t| t.replace(r#""version": 1"#, r#""version": 1.0"#)),
            "version: expected 1, 2 or 3, got 1.0",
        ),
        (
            json_with(|t| t.replace(r#""version": 1"#, r#""version": "1""#)),
            "version: expected 1, 2 or 3, got \"1\"",
        ),
        (
            json_with(|t| t.replace(r#""version": 1"#, r#""version": null"#)),
            "version: expected 1, 2 or 3, got null",
        ),
        (
            json_with(|t| t.replace(r#""period_nm": 1000.0"#, r#""period_nm": null"#)),
            "grating.period_nm: expected a number, got null",
        ),
        (
            json_with(|t| t.replace(r#""period_nm": 1000.0"#, r#""period_nm": "1000""#)),
            "grating.period_nm: expected a number, got \"1000\"",
        ),
        (
            json_with(|t| t.replace(r#""period_nm": 1000.0"#, r#""period_nm": 1e400"#)),
            "grating.period_nm: number out of range",
        ),
        (
            json_with(|t| t.replace("[500.0, 600.0]", "[500.0, 1e400]")),
            "lambda_nm[1]: number out of range",
        ),
        (
            json_with(|t| t.replace("[500.0, 600.0]", "[500.0, null]")),
            "lambda_nm[1]: expected a number, got null",
        ),
        (
            json_with(|t| t.replace(r#""order_min": -1"#, r#""order_min": -1.5"#)),
            "order_min: expected an integer, got -1.5",
        ),
        (
            json_with(|t| t.replace(r#""order_max": 1"#, r#""order_max": 1.0"#)),
            "order_max: expected an integer, got 1.0",
        ),
        (
            json_with(|t| t.replace(r#""order_max": 1"#, r#""order_max": 9223372036854775807"#)),
            "invalid order_max = 9.223372036854776e18: must lie in [-1, 4095]",
        ),
        (
            json_with(|t| t.replace(r#""order_max": 1"#, r#""order_max": 18446744073709551615"#)),
            "invalid order_max = 1.8446744073709552e19: must lie in [-1, 4095]",
        ),
        (
            json_with(|t| t.replace(r#""order_min": -1"#, r#""order_min": -9223372036854775808"#)),
            "invalid order_min = -9.223372036854776e18: must lie in [-2147483648, 2147483647]",
        ),
        (
            json_with(|t| {
                t.replace(
                    "[[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0]",
                    "[[0.5, null], [0.5, 0.5]], [[0.1, 0.0]",
                )
            }),
            "te[1][0][1]: expected a number, got null",
        ),
        (
            json_with(|t| {
                t.replacen(
                    "[[0.5, 0.5], [0.5, 0.5]]",
                    "[[0.5, 0.5], [0.5, 0.5e999]]",
                    1,
                )
            }),
            "te[1][1][1]: number out of range",
        ),
        (
            json_with(|t| t.replacen("[[0.5, 0.5], [0.5, 0.5]]", "[[0.5, 0.5], [[0.5], 0.5]]", 1)),
            "te[1][1][0]: expected a number, got an array",
        ),
        (
            json_with(|t| {
                t.replace(
                    r#""format": "diffraction-efficiency-table""#,
                    &format!("\"format\": \"{long}\""),
                )
            }),
            "format: expected \"diffraction-efficiency-table\", got a string of 100000 bytes",
        ),
        (
            json_with(|t| t.replace("[0.0, 0.5]", &format!("\"{long}\""))),
            "sin_theta_i: invalid type: a string of 100000 bytes, expected an array of numbers",
        ),
        (
            json_with(|t| t.replace(r#""version": 1"#, r#""version": 1, "version": 1"#)),
            "duplicate field `version`",
        ),
        (
            json_with(|t| t.replace(r#""version": 1"#, r#""version": 2"#)),
            "missing field `abs_beta`",
        ),
    ];
    for (text, want) in cases {
        let (got, one_position) = refusal(&text);
        assert!(got.len() < 200, "a long message: {}…", &got[..200]);
        assert_eq!(got, want);
        assert!(one_position, "{want}");
    }
}

/// Every class of hostile file: refused with the field named, and at once where the input is
/// large (the reader stops at the first value past the table's bounds).
#[cfg(feature = "serde")]
#[test]
fn hostile_json_tables_are_refused_by_field() {
    use diffraction::relief::{MAX_TABLE_NODES, MAX_TABLE_ORDERS};
    let empties = |n: usize| vec!["[]"; n].join(",");
    let deep = format!("{}{}", "[".repeat(10_000), "]".repeat(10_000));
    let cases: Vec<(String, String)> = vec![
        // Truncated.
        (json_with(|t| t[..t.find("[0.5, 0.5]").unwrap() + 5].to_string()), "te[1][0][1]: EOF while parsing a value".into()),
        // NaN and ∞ are no JSON numbers; negative and > 1 efficiencies are refused by value.
        (json_with(|t| t.replace("[[0.1, 0.2], [0.1, 0.3]], [[0.5", "[[NaN, 0.2], [0.1, 0.3]], [[0.5")), "te[0][0][0]: expected value".into()),
        (json_with(|t| t.replacen("0.2]", "-0.2]", 1)), "invalid te = -0.2: must be finite and >= 0".into()),
        (json_with(|t| t.replacen("[[0.5, 0.5]", "[[1.5, 0.5]", 1)), "invalid te = 1.7000000000000002: must be a sum over orders <= 1.000001".into()),
        // Non-monotone and duplicate grids.
        (json_with(|t| t.replace("[0.0, 0.5]", "[0.5, 0.0]")), "invalid sin_theta_i = 0: must be strictly increasing (above the value before it)".into()),
        (json_with(|t| t.replace("[500.0, 600.0]", "[500.0, 500.0]")), "invalid lambda_nm = 500: must be strictly increasing (above the value before it)".into()),
        // Wrong version.
        (json_with(|t| t.replace(r#""version": 1"#, r#""version": 4"#)), "version: expected 1, 2 or 3, got 4".into()),
        // Claimed dimensions far beyond the data.
        (json_with(|t| t.replace(r#""order_max": 1"#, r#""order_max": 4000"#)), "te: has shape [3][2][2], expected [4002][2][2] ([order][lambda][sin])".into()),
        // An order whose rows disagree, a row longer than the grid.
        (json_with(|t| t.replacen("[[0.5, 0.5], [0.5, 0.5]]", "[[0.5, 0.5, 0.5], [0.5, 0.5, 0.5]]", 1)), "te[1][0]: has 3 values, expected 2 (as the first)".into()),
        // Too many values, orders, rows, before they are stored.
        (
            json_with(|t| t.replace("[0.0, 0.5]", &format!("[{}]", vec!["0.1"; MAX_TABLE_NODES + 1].join(",")))),
            format!("sin_theta_i: has more than {MAX_TABLE_NODES} values, must have 2 to {MAX_TABLE_NODES}"),
        ),
        (
            json_with(|t| t.replacen(r#""te": ["#, &format!(r#""te": [{},"#, empties(MAX_TABLE_ORDERS + 1)), 1)),
            format!("te: has more than {MAX_TABLE_ORDERS} orders"),
        ),
        (
            json_with(|t| t.replacen(r#""te": [["#, &format!(r#""te": [[{},"#, empties(MAX_TABLE_NODES + 1)), 1)),
            format!("te[0]: has more than {MAX_TABLE_NODES} wavelength rows"),
        ),
        // Deeply nested JSON, in a field the reader uses and in one it skips.
        (json_with(|t| t.replacen(r#""te": ["#, &format!(r#""te": [{deep},"#), 1)), "te[0][0][0][0]: expected a number, got an array".into()),
        (json_with(|t| t.replace(r#""version": 1"#, &format!(r#""version": {deep}"#))), "version: expected 1, 2 or 3, got an array".into()),
        // A table whose orders or grid disagree with its period: order 1 propagating at a
        // node where it is evanescent for d = 1000 nm; the same table on a 100 nm period.
        (json_with(|t| t.replace("[[0.1, 0.0], [0.1, 0.0]]]", "[[0.1, 0.01], [0.1, 0.0]]]")), "invalid te = 0.01: must be 0: order 1 is evanescent there (|sin_theta_i + m lambda/d| >= 1)".into()),
        (json_with(|t| t.replace(r#""period_nm": 1000.0"#, r#""period_nm": 100.0"#)), "invalid te = 0.1: must be 0: order -1 is evanescent there (|sin_theta_i + m lambda/d| >= 1)".into()),
    ];
    for (text, want) in cases {
        let (got, _) = refusal(&text);
        assert!(got.len() < 300, "a long message: {}…", &got[..300]);
        assert_eq!(got, want);
    }
    // A deep value in a field the reader skips is skipped without recursion.
    let skipped = json_with(|t| t.replace(r#""sha256": "0""#, &format!(r#""sha256": {deep}"#)));
    assert!(serde_json::from_str::<EfficiencyTable>(&skipped).is_ok());
}

/// A version-2 (conical) table: 2 |β| planes of the table of `json_with` (orders −1, 0, 1 of
/// d = 1000 nm; at |β| = 0.6 the s′ axis 0, 0.5 gives α = 0, 0.4).
#[cfg(feature = "serde")]
fn conical_json_with(edit: impl Fn(&str) -> String) -> String {
    edit(concat!(
        r#"{"format": "diffraction-efficiency-table", "version": 2, "name": "t","#,
        r#" "grating": {"profile": "sinusoid", "period_nm": 1000.0, "metal": "Al"},"#,
        r#" "sin_theta_i": [0.0, 0.5], "abs_beta": [0.0, 0.6], "lambda_nm": [500.0, 600.0],"#,
        r#" "order_min": -1, "order_max": 1,"#,
        r#" "te": [[[[0.1, 0.2], [0.1, 0.3]], [[0.1, 0.2], [0.1, 0.2]]], [[[0.5, 0.5], [0.5, 0.5]], [[0.5, 0.5], [0.5, 0.5]]], [[[0.1, 0.0], [0.1, 0.0]], [[0.1, 0.0], [0.0, 0.0]]]],"#,
        r#" "tm": [[[[0.1, 0.2], [0.1, 0.3]], [[0.1, 0.2], [0.1, 0.2]]], [[[0.5, 0.5], [0.5, 0.5]], [[0.5, 0.5], [0.5, 0.5]]], [[[0.1, 0.0], [0.1, 0.0]], [[0.1, 0.0], [0.0, 0.0]]]],"#,
        r#" "solver": {"method": "x"}, "sha256": "0"}"#
    ))
}

/// Conical tables: read, and every class of hostile file refused with the field named.
#[cfg(feature = "serde")]
#[test]
fn hostile_conical_tables_are_refused_by_field() {
    let t: EfficiencyTable = serde_json::from_str(&conical_json_with(str::to_string)).unwrap();
    assert!(t.is_conical());
    assert_eq!(t.abs_beta().collect::<Vec<_>>(), vec![0.0, 0.6]);
    let cases: Vec<(String, String)> = vec![
        // A version-1 file with a conical axis, a version-2 file without one.
        (json_with(|t| t.replace(r#""lambda_nm""#, r#""abs_beta": [0.0, 0.5], "lambda_nm""#)), "abs_beta: a conical axis needs version 2 (version 1 is classical)".into()),
        (conical_json_with(|t| t.replace(r#""abs_beta": [0.0, 0.6], "#, "")), "missing field `abs_beta`".into()),
        // Classical arrays in a conical file, and the reverse.
        (json_with(|t| t.replace(r#""version": 1"#, r#""version": 2, "abs_beta": [0.0, 0.6]"#)), "te: has shape [3][2][2], expected [3][2][2][2] ([order][abs_beta][lambda][sin])".into()),
        (conical_json_with(|t| t.replace(r#""version": 2"#, r#""version": 1"#).replace(r#""abs_beta": [0.0, 0.6], "#, "")), "te: has shape [3][2][2][2], expected [3][2][2] ([order][lambda][sin])".into()),
        // The |β| axis: out of range, not increasing, NaN-like, too short.
        (conical_json_with(|t| t.replace("[0.0, 0.6]", "[0.0, 1.0]")), "invalid abs_beta = 1: must lie in [0, 0.99999]".into()),
        (conical_json_with(|t| t.replace("[0.0, 0.6]", "[-0.1, 0.6]")), "invalid abs_beta = -0.1: must lie in [0, 0.99999]".into()),
        (conical_json_with(|t| t.replace("[0.0, 0.6]", "[0.6, 0.6]")), "invalid abs_beta = 0.6: must be strictly increasing (above the value before it)".into()),
        (conical_json_with(|t| t.replace("[0.0, 0.6]", "[0.6]")), "invalid abs_beta: has 1 values, must have 2 to 4096".into()),
        (conical_json_with(|t| t.replace("[0.0, 0.6]", "[0.0, null]")), "abs_beta[1]: expected a number, got null".into()),
        // A plane of another shape (each plane may have its own rows, version 3, but every
        // order the first's), a value of the wrong type, deeper than four levels.
        (conical_json_with(|t| t.replacen("[[0.1, 0.2], [0.1, 0.2]]]", "[[0.1, 0.2], [0.1, 0.2], [0.1, 0.2]]]", 1)), "te[1][1]: has 2 wavelength rows, expected 3 (as the first order's plane 1)".into()),
        (conical_json_with(|t| t.replacen("[[0.1, 0.2], [0.1, 0.2]]]", "[[0.1, \"x\"], [0.1, 0.2]]]", 1)), "te[0][1][0][1]: expected a number, got \"x\"".into()),
        (conical_json_with(|t| t.replacen("[[0.1, 0.2], [0.1, 0.2]]]", "[[0.1, [0.2]], [0.1, 0.2]]]", 1)), "te[0][1][0][1]: expected a number, got an array".into()),
        // Order 1 at s′ = 0.5, |β| = 0.6, λ = 600 nm: α₁ = 0.4 + 0.6, evanescent.
        (conical_json_with(|t| t.replacen("[[0.1, 0.0], [0.0, 0.0]]]]", "[[0.1, 0.0], [0.0, 0.01]]]]", 1)), "invalid te = 0.01: must be 0: order 1 is evanescent there ((sin_theta_i sqrt(1 - beta^2) + m lambda/d)^2 + beta^2 >= 1)".into()),
        // A node's sum above 1.
        (conical_json_with(|t| t.replacen("[[[0.5, 0.5], [0.5, 0.5]], [[0.5, 0.5]", "[[[0.5, 0.5], [0.5, 0.5]], [[0.9, 0.5]", 1)), "invalid te = 1.1: must be a sum over orders <= 1.000001".into()),
    ];
    for (text, want) in cases {
        let (got, _) = refusal(&text);
        assert!(got.len() < 300, "a long message: {}…", &got[..300]);
        assert_eq!(got, want);
    }
}

/// `SampledWavelengths::new` refuses a subnormal density (1/pdf infinite), and the film's
/// estimate and the sample weights saturate instead of overflowing for every density it
/// accepts.
#[test]
fn tiny_divisors_give_finite_results() {
    use diffraction::cie::Illuminant;
    use diffraction::{
        BsdfFlags, BsdfSample, BsdfSample4, SampledSpectrum, SampledWavelengths, SpectralFilm,
    };
    use glam::DVec3;
    assert_eq!(
        SampledWavelengths::new([500.0; 4], [0.01, 5e-324, 0.01, 0.01]).unwrap_err().to_string(),
        "invalid pdf = 5e-324: must satisfy pdf >= SampledWavelengths::MIN_PDF (2.2250738585072014e-308)"
    );
    let l = SampledWavelengths::new([500.0, 550.0, 600.0, 650.0], [f64::MIN_POSITIVE; 4]).unwrap();
    let film = SpectralFilm::new(Illuminant::E);
    for v in [1.0, f64::MAX, -f64::MAX, 1e-300] {
        let xyz = SampledSpectrum::new([v, -v, v, v]).to_xyz(&l, &film);
        assert!(
            xyz.x.is_finite() && xyz.y.is_finite() && xyz.z.is_finite(),
            "{v:e}: {xyz:?}"
        );
    }
    // The widest band's uniform density is clamped to MIN_PDF, which `new` accepts.
    let wide = diffraction::Band::new(1.0, f64::MAX).unwrap();
    let u = SampledWavelengths::sample_uniform(0.3, wide);
    assert_eq!(u.pdf(), [SampledWavelengths::MIN_PDF; 4]);
    assert_eq!(SampledWavelengths::new(u.lambda(), u.pdf()), Ok(u));
    let wi = DVec3::new(0.0, 0.6, 0.8);
    assert_eq!(
        BsdfSample::new(wi, 1.0, 5e-324, BsdfFlags::GLOSSY).weight(),
        f64::MAX
    );
    let s4 = BsdfSample4::new(
        wi,
        SampledSpectrum::splat(1.0),
        SampledSpectrum::splat(5e-324),
        BsdfFlags::GLOSSY,
    );
    assert_eq!(s4.weight(), SampledSpectrum::splat(f64::MAX));
}

/// `with_efficiency` returns the error of the grating it cannot rebuild at the table's period
/// (it kept the old period before: a DVD table on a 1600 nm grating).
#[test]
fn with_efficiency_reports_the_grating_it_cannot_build() {
    use diffraction::grating_bsdf::OrderEfficiency;
    use diffraction::relief::Preset;
    use diffraction::{Grating, GratingBsdf};
    let thin = GratingBsdf::new(Grating::new(1600.0, 5e-324, 30).unwrap());
    assert_eq!(
        thin.with_efficiency(OrderEfficiency::preset(Preset::Dvd))
            .unwrap_err()
            .to_string(),
        "invalid slit_width_nm = 0: must be finite and > 0"
    );
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 30).unwrap())
        .with_efficiency(OrderEfficiency::preset(Preset::Dvd))
        .unwrap();
    assert_eq!(b.grating().period_nm(), 740.0);
}

/// Stored colour tables with fields no build produces are refused with the field, its value
/// and the range a build can produce.
#[cfg(feature = "serde")]
#[test]
fn corrupted_stored_colour_tables_name_the_field_and_the_range() {
    use diffraction::spectrum::{Illuminant, Spectral};
    use diffraction::{ColorTable, Grating};
    let s = Spectral::new(Illuminant::E);
    let t = ColorTable::new(&s, &Grating::new(1600.0, 800.0, 100).unwrap(), 1e-3).unwrap();
    let base = serde_json::to_value(&t).unwrap();
    let back: ColorTable = serde_json::from_value(base.clone()).unwrap();
    assert_eq!(back, t);
    let nodes = t.node_count();
    let white = s.white();
    // Closed forms: the paper's floor 555/(N·∫ȳ) for N = 100, twice the white.
    let floor = diffraction::spectrum::bounds::accuracy_floor(100.0);
    let err = |f: &dyn Fn(&mut serde_json::Value)| {
        let mut v = base.clone();
        f(&mut v);
        serde_json::from_value::<ColorTable>(v)
            .unwrap_err()
            .to_string()
    };
    let num = |x: f64| {
        if x.abs() >= 1e16 || x.abs() < 1e-4 {
            format!("{x:e}")
        } else {
            format!("{x}")
        }
    };
    assert_eq!(
        err(&|v| v["grid"]["values"][7][1] = 1e308.into()),
        format!(
            "invalid values = 1e308: must lie in [0, {}]",
            num(2.0 * white.y)
        )
    );
    assert_eq!(
        err(&|v| v["grid"]["scale"] = 1e308.into()),
        format!(
            "invalid scale = 1e308: must lie in [{}, {}]",
            num(floor),
            num(2.0 * white.y)
        )
    );
    assert_eq!(
        err(&|v| v["grid"]["error"] = 1e308.into()),
        format!(
            "invalid error = 1e308: must lie in [0, {}]",
            num(2e4 / t.scale())
        )
    );
    assert_eq!(
        err(&|v| v["grid"]["evaluations"] = u64::MAX.into()),
        format!(
            "invalid evaluations = 1.8446744073709552e19: must lie in [0, {}]",
            2 * nodes
        )
    );
}
