//! The tests of `examples/efficiencies.rs` (run by `cargo test`: the example has `test = true`).
use super::*;

fn args(s: &str) -> Vec<String> {
    s.split_whitespace().map(str::to_string).collect()
}

fn error(s: &str) -> String {
    parse(&args(s)).and_then(|o| run(&o)).unwrap_err()
}

fn lines(s: &str) -> Vec<serde_json::Value> {
    let (l, _) = run(&parse(&args(s)).unwrap()).unwrap();
    l.iter().map(|x| serde_json::from_str(x).unwrap()).collect()
}

const FOIL: &str = "--profile sinusoid --period 1000 --depth 100 --metal Al --lambda 550 --theta 0";

#[test]
fn prints_every_propagating_order_with_the_grating_equation() {
    let out = lines(FOIL);
    let orders: Vec<i64> = out.iter().map(|v| v["order"].as_i64().unwrap()).collect();
    assert_eq!(orders, [-1, 0, 1]);
    for v in &out {
        let m = v["order"].as_f64().unwrap();
        assert!((v["sin_theta"].as_f64().unwrap() - m * 0.55).abs() < 1e-15);
        let (te, tm) = (v["te"].as_f64().unwrap(), v["tm"].as_f64().unwrap());
        assert_eq!(v["efficiency"].as_f64().unwrap(), 0.5 * (te + tm));
    }
    // The same numbers as the library's.
    let g = ScalarRelief::new(Relief::sinusoid(100.0).unwrap(), Metal::AL, 1000.0).unwrap();
    let e = g.order(1, 0.0, 550.0).unwrap();
    assert_eq!(out[2]["te"].as_f64().unwrap(), e.te);
    let te = lines(&format!("{FOIL} --polarisation te"));
    assert_eq!(te[2]["efficiency"].as_f64().unwrap(), e.te);
}

#[test]
fn every_profile_and_metal_prints() {
    for metal in ["Al", "Ag", "Au", "Cu", "Cr", "1.5+7i"] {
        for profile in [
            "--profile sinusoid --depth 80",
            "--profile lamellar --depth 110 --duty 0.3125",
            "--profile sawtooth --blaze 8.627",
            "--profile sawtooth --depth 200",
            "--profile amplitude --duty 0.4",
        ] {
            let out = lines(&format!(
                "{profile} --period 1600 --metal {metal} --lambda 500 --theta 20"
            ));
            assert!(!out.is_empty(), "{profile} {metal}");
            let total: f64 = out.iter().map(|v| v["efficiency"].as_f64().unwrap()).sum();
            assert!(total > 0.0 && total <= 1.0, "{profile} {metal}: {total}");
        }
    }
    // The amplitude model has no polarisation.
    let amp = lines("--profile amplitude --period 1600 --lambda 500 --theta 0");
    assert!(amp[0].get("te").is_none());
    assert_eq!(amp.len(), 7); // |m·500/1600| < 1: m = −3 … 3
}

#[test]
fn errors_name_the_flag() {
    let base = "--period 1000 --metal Al --lambda 550 --theta 0";
    let cases = [
        (format!("--profile sine --depth 10 {base}"), "--profile"),
        (format!("--profile sinusoid {base}"), "--depth"),
        (format!("--profile sinusoid --depth -5 {base}"), "--depth"),
        (format!("--profile sinusoid --depth abc {base}"), "--depth"),
        (
            format!("--profile lamellar --depth 50 --duty 1.5 {base}"),
            "--duty",
        ),
        (
            format!("--profile sinusoid --depth 50 --duty 0.5 {base}"),
            "--duty",
        ),
        (format!("--profile sawtooth {base}"), "--blaze"),
        (format!("--profile sawtooth --blaze 120 {base}"), "--blaze"),
        (
            format!("--profile sawtooth --blaze 10 --depth 5 {base}"),
            "--depth",
        ),
        (format!("--profile sawtooth --depth 900 {base}"), "--depth"),
        (
            format!("--profile sinusoid --depth 50 --blaze 10 {base}"),
            "--blaze",
        ),
        (
            "--profile sinusoid --depth 50 --period 0 --metal Al --lambda 550 --theta 0".into(),
            "--period",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --metal gold --lambda 550 --theta 0"
                .into(),
            "--metal",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --metal 0+1i --lambda 550 --theta 0"
                .into(),
            "--metal",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --lambda 550 --theta 0".into(),
            "--metal",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --metal Al --lambda -1 --theta 0".into(),
            "--lambda",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --metal Al --lambda 550 --theta 95".into(),
            "--theta",
        ),
        (
            "--profile sinusoid --depth 50 --period 1000 --metal Al --lambda 550".into(),
            "--theta",
        ),
        (
            format!("--profile sinusoid --depth 50 {base} --polarisation s"),
            "--polarisation",
        ),
        (
            format!("--profile sinusoid --depth 50 {base} --table cd.json"),
            "--table",
        ),
        (
            format!("--profile sinusoid --depth 50 --depth 60 {base}"),
            "--depth",
        ),
        (
            format!("--profile sinusoid --depth 50 {base} --bogus 1"),
            "--bogus",
        ),
        (
            format!("--profile sinusoid --depth 50 {base} --period"),
            "--period",
        ),
        (format!("--profile amplitude --duty 0 {base}"), "--duty"),
    ];
    for (line, flag) in cases {
        let e = error(&line);
        assert!(e.starts_with(flag), "{line}: {e}");
    }
}

#[test]
fn tables_and_presets_print_their_interpolated_orders() {
    let q = "--lambda 550 --theta 20";
    let preset = lines(&format!("--preset cd {q}"));
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/data/efficiencies/cd.json");
    // Read by the library's `Deserialize` with feature `serde`, by the example's own reader
    // without it.
    let table = lines(&format!("--table {file} {q}"));
    assert_eq!(preset.len(), table.len());
    let cd = Preset::Cd.table();
    let s = 20f64.to_radians().sin();
    for (p, t) in preset.iter().zip(&table) {
        let m = p["order"].as_i64().unwrap() as i32;
        assert_eq!(m, t["order"].as_i64().unwrap() as i32);
        let sm = p["sin_theta"].as_f64().unwrap();
        assert!((sm - (s + f64::from(m) * 550.0 / 1600.0)).abs() < 1e-15 && sm.abs() < 1.0);
        let e = cd.efficiency(m, s, 550.0);
        // serde_json's default float parsing may be one unit in the last place off.
        let close = |key: &str, want: f64| (p[key].as_f64().unwrap() - want).abs() <= 1e-15;
        assert!(close("te", e.te) && close("tm", e.tm), "{m}");
        assert!(close("efficiency", e.unpolarised()), "{m}");
        // The JSON file's 6 decimals against the preset's 5 (and f32).
        assert!((t["te"].as_f64().unwrap() - e.te).abs() < 2e-5, "{m}");
    }
    let te = lines(&format!("--preset foil {q} --polarisation tm"));
    assert_eq!(te[0]["efficiency"], te[0]["tm"]);
    let q = "--lambda 550 --theta 0";
    for (line, flag) in [
        (format!("--preset bluray {q}"), "--preset"),
        (format!("--table /nonexistent/t.json {q}"), "--table"),
        (
            format!("--table {} {q}", env!("CARGO_MANIFEST_DIR")),
            "--table",
        ),
        (
            format!("--table {}/Cargo.toml {q}", env!("CARGO_MANIFEST_DIR")),
            "--table",
        ),
        (format!("--preset cd --table {file} {q}"), "--table"),
        (format!("--preset cd --metal Al {q}"), "--preset"),
        ("--preset cd --theta 0".to_string(), "--lambda"),
        ("--preset cd --lambda 550 --theta 90".to_string(), "--theta"),
    ] {
        let e = error(&line);
        assert!(e.starts_with(flag), "{line}: {e}");
    }
    assert!(error(&format!("--table /nonexistent/t.json {q}")).contains("/nonexistent/t.json"));
}

/// Hostile `--table` files are refused quickly with bounded memory: devices and FIFOs
/// before they are opened, a file over the cap by its size, an array of empty arrays by
/// the reader's bounds (with feature `serde`).
#[test]
fn hostile_table_files_are_refused_quickly() {
    let q = "--lambda 550 --theta 0";
    let dir = std::env::temp_dir().join(format!("efficiencies-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let not_regular =
        |f: &str| format!("--table: {f:?} is not a regular file (a directory, a device or a FIFO)");
    assert_eq!(
        error(&format!("--table /dev/zero {q}")),
        not_regular("/dev/zero")
    );
    let fifo = dir.join("fifo.json");
    let _ = std::fs::remove_file(&fifo);
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if made.is_ok_and(|s| s.success()) {
        let f = fifo.to_str().unwrap();
        assert_eq!(error(&format!("--table {f} {q}")), not_regular(f));
    }
    // A sparse file one byte over the cap: refused by its size, never read.
    let big = dir.join("big.json");
    std::fs::File::create(&big)
        .unwrap()
        .set_len(MAX_TABLE_BYTES + 1)
        .unwrap();
    let f = big.to_str().unwrap();
    assert_eq!(
        error(&format!("--table {f} {q}")),
        format!(
            "--table: {f:?} has {} bytes, more than the {MAX_TABLE_BYTES} this reads",
            MAX_TABLE_BYTES + 1
        )
    );
    // Orders of nested empty arrays (1 MB), and bytes that are not UTF-8.
    let nested = dir.join("nested.json");
    let empties = vec!["[[]]"; 200_000].join(",");
    std::fs::write(&nested, format!("{{\"te\": [{empties}]}}")).unwrap();
    let e = error(&format!("--table {} {q}", nested.to_str().unwrap()));
    assert!(e.starts_with("--table: "), "{e}");
    #[cfg(feature = "serde")]
    assert!(e.contains("te: has more than 4097 orders"), "{e}");
    let binary = dir.join("binary.json");
    std::fs::write(&binary, [b'{', 0xff, b'}']).unwrap();
    let f = binary.to_str().unwrap();
    assert_eq!(
        error(&format!("--table {f} {q}")),
        format!("--table: {f:?} is not UTF-8 (at byte 1)")
    );
    // The table whose one weighted propagating corner has a subnormal weight at
    // s = sin(3e-322°) = 5e-324 (its normalisation gave NaN): finite lines, Σ η ≤ 1.
    let grazing = dir.join("grazing.json");
    std::fs::write(
        &grazing,
        r#"{"format": "diffraction-efficiency-table", "version": 1,
            "grating": {"period_nm": 1000.0}, "sin_theta_i": [0.0, 0.5],
            "lambda_nm": [999.9995, 1200.0], "order_min": -1, "order_max": 0,
            "te": [[[0.01, 0.3], [0.0, 0.2]], [[0.9, 0.6], [0.9, 0.7]]],
            "tm": [[[0.01, 0.3], [0.0, 0.2]], [[0.9, 0.6], [0.9, 0.7]]]}"#,
    )
    .unwrap();
    let out = lines(&format!(
        "--table {} --lambda 999.9995 --theta 3e-322",
        grazing.to_str().unwrap()
    ));
    let total: f64 = out.iter().map(|v| v["efficiency"].as_f64().unwrap()).sum();
    assert!(
        out.len() == 2 && total.is_finite() && total <= 1.0,
        "{out:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn notes_queries_outside_the_valid_region() {
    let (_, note) = run(&parse(&args(FOIL)).unwrap()).unwrap();
    assert!(note.is_some()); // the foil is too deep for its period
    let shallow = "--profile sinusoid --period 5000 --depth 120 --metal Al --lambda 550 --theta 30";
    let (_, note) = run(&parse(&args(shallow)).unwrap()).unwrap();
    assert!(note.is_none());
}
