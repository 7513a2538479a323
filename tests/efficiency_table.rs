//! The tabulated efficiency model: the presets' static data against the JSON tables at every
//! node, the interpolation against the Python reference (`tests/data/efficiency_interp.csv`),
//! the orders' appearance on their Rayleigh lines, Σ η ≤ 1 everywhere, the checks on load, and
//! the scalar model baked into a table.

#[path = "support/efficiency_tolerance.rs"]
mod efficiency_tolerance;

use diffraction::relief::{
    EfficiencyTable, Metal, Polarised, Preset, Relief, ScalarRelief, MAX_TABLE_NODES,
};
use efficiency_tolerance as tol;
use serde_json::Value;

fn json(preset: Preset) -> Value {
    let path = format!(
        "{}/data/efficiencies/{}.json",
        env!("CARGO_MANIFEST_DIR"),
        preset.name()
    );
    let text = std::fs::read_to_string(&path).expect(&path);
    serde_json::from_str(&text).expect("a JSON table")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn presets_match_their_json_tables_at_every_node() {
    let mut worst = 0.0f64;
    let mut worst_grazing = 0.0f64;
    for preset in Preset::ALL {
        let t = preset.table();
        let j = json(preset);
        let d = j["grating"]["period_nm"].as_f64().unwrap();
        assert_eq!(t.period_nm(), d);
        let (om, ox) = (
            j["order_min"].as_i64().unwrap() as i32,
            j["order_max"].as_i64().unwrap() as i32,
        );
        assert_eq!(t.orders(), om..=ox);
        // The shipped nodes are the JSON's, as f32.
        let s: Vec<f64> = floats(&j["sin_theta_i"]);
        let l: Vec<f64> = floats(&j["lambda_nm"]);
        let ts: Vec<f64> = t.sin_theta_i().collect();
        let tl: Vec<f64> = t.lambda_nm().collect();
        assert_eq!(
            ts,
            s.iter().map(|&x| f64::from(x as f32)).collect::<Vec<_>>()
        );
        assert_eq!(
            tl,
            l.iter().map(|&x| f64::from(x as f32)).collect::<Vec<_>>()
        );
        let mut out = vec![Polarised::default(); t.order_count()];
        for (jj, &lam) in tl.iter().enumerate() {
            for (ii, &sn) in ts.iter().enumerate() {
                t.efficiencies(sn, lam, &mut out);
                for (k, e) in out.iter().enumerate() {
                    let m = om + k as i32;
                    let sm = sn + f64::from(m) * lam / d;
                    for (pol, got) in [("te", e.te), ("tm", e.tm)] {
                        let want = j[pol][k][jj][ii].as_f64().unwrap();
                        if 1.0 - sm * sm <= tol::GRAZING_CORNER {
                            // A corner on its Rayleigh line counts as evanescent (the rule's
                            // step 4): the table gives 0 there.
                            assert_eq!(got, 0.0, "{preset} {pol} m={m} s={sn} l={lam}");
                            worst_grazing = worst_grazing.max(want);
                        } else {
                            let err = (got - want).abs();
                            worst = worst.max(err);
                            assert!(
                                err <= tol::NODE + tol::F32 * want,
                                "{preset} {pol} m={m} s={sn} l={lam}: {got} vs {want}"
                            );
                        }
                    }
                }
            }
        }
    }
    println!("nodes: max |table - JSON| = {worst:.3e}; largest JSON eta zeroed on a Rayleigh line {worst_grazing:.3e}");
    assert!(worst_grazing <= tol::GRAZING_NODE_ETA);
}

#[test]
fn interpolation_matches_the_python_reference() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/efficiency_interp.csv"
    );
    let text = std::fs::read_to_string(path).expect(path);
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("preset,order,sin_theta_i,lambda_nm,te,tm")
    );
    let (mut worst, mut rows, mut nonzero) = (0.0f64, 0, 0);
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let preset: Preset = f[0].parse().unwrap();
        let m: i32 = f[1].parse().unwrap();
        let v: Vec<f64> = f[2..].iter().map(|x| x.parse().unwrap()).collect();
        let e = preset.table().efficiency(m, v[0], v[1]);
        for (got, want) in [(e.te, v[2]), (e.tm, v[3])] {
            worst = worst.max((got - want).abs());
            nonzero += usize::from(want > 0.0);
        }
        rows += 1;
    }
    println!("interpolation: {rows} points ({nonzero} nonzero values), max |Rust - Python| = {worst:.3e}");
    assert_eq!(rows, 2000);
    assert!(nonzero > 3000);
    assert!(worst <= tol::INTERPOLATION, "{worst:e}");
}

#[test]
fn orders_appear_exactly_on_their_rayleigh_lines() {
    let (mut checked, mut worst_ratio) = (0, 0.0f64);
    for preset in Preset::ALL {
        let t = preset.table();
        let d = t.period_nm();
        let nodes: Vec<f64> = t.sin_theta_i().collect();
        for lam in [400.0, 455.5, 550.0, 613.25, 700.0, 790.0] {
            for m in t.orders().filter(|&m| m != 0) {
                for side in [-1.0f64, 1.0] {
                    // The line s + m·λ/d = side; the order propagates on the side of s − side.
                    let line = side - f64::from(m) * lam / d;
                    if !(line > nodes[0] + 1e-3 && line < nodes[nodes.len() - 1] - 1e-3)
                        || nodes.iter().any(|&n| (n - line).abs() < 1e-5)
                    {
                        continue;
                    }
                    let at = |delta: f64| t.efficiency(m, line - side * delta, lam);
                    // Just beyond the line: evanescent, exactly 0.
                    let beyond = t.efficiency(m, line + side * 1e-12, lam);
                    assert_eq!(beyond, Polarised::default(), "{preset} m={m} l={lam}");
                    let (near, far) = (at(1e-8), at(4e-8));
                    for (a, b) in [(near.te, far.te), (near.tm, far.tm)] {
                        if b == 0.0 {
                            continue; // the order carries nothing at the cell's corners
                        }
                        assert!(a > 0.0, "{preset} m={m} l={lam}");
                        // √ onset: η(4δ)/η(δ) = 2.
                        worst_ratio = worst_ratio.max((b / a - 2.0).abs());
                        checked += 1;
                    }
                }
            }
        }
    }
    println!("Rayleigh lines: {checked} onsets, max |eta(4d)/eta(d) - 2| = {worst_ratio:.3e}");
    assert!(checked > 100, "{checked}");
    assert!(worst_ratio <= tol::SQRT_ONSET, "{worst_ratio:e}");
}

#[test]
fn sums_stay_at_most_one_everywhere() {
    let (mut worst, mut scaled, mut queries) = (0.0f64, 0usize, 0usize);
    for preset in Preset::ALL {
        let before = scaled;
        let t = preset.table();
        let mut out = vec![Polarised::default(); t.order_count()];
        for i in 0..=800 {
            let s = -1.0 + f64::from(i) * 2.5e-3;
            for l in 0..=245 {
                let lam = 350.0 + 2.0 * f64::from(l);
                let total = t.efficiencies(s, lam, &mut out);
                let te: f64 = out.iter().map(|e| e.te).sum();
                let tm: f64 = out.iter().map(|e| e.tm).sum();
                assert!(
                    out.iter().all(|e| e.te >= 0.0 && e.tm >= 0.0),
                    "{preset} s={s} l={lam}"
                );
                assert!((total - 0.5 * (te + tm)).abs() <= efficiency_tolerance::UNPOLARISED_MEAN);
                worst = worst.max(te).max(tm);
                scaled += usize::from(te > 1.0 - 1e-12 || tm > 1.0 - 1e-12);
                queries += 1;
            }
        }
        println!("sums: {preset}: {} queries scaled", scaled - before);
    }
    println!("sums: {queries} queries, max sum {worst:.17}, {scaled} scaled down to 1");
    assert!(worst <= 1.0 + tol::SUM_ROUNDING, "{worst}");
}

/// The 2 × 2-node table of orders −1, 0, 1 (d = 1000 nm) with the given TE, and TM = TE.
fn small(te: Vec<f64>) -> Result<EfficiencyTable, diffraction::Error> {
    let tm = te.clone();
    EfficiencyTable::new(1000.0, -1, vec![0.0, 0.5], vec![500.0, 600.0], te, tm)
}

const GOOD: [f64; 12] = [0.1, 0.2, 0.1, 0.3, 0.5, 0.5, 0.5, 0.5, 0.1, 0.0, 0.1, 0.0];

#[test]
fn bad_tables_are_rejected_naming_the_field() {
    assert!(small(GOOD.to_vec()).is_ok());
    let err = |r: Result<EfficiencyTable, diffraction::Error>| r.unwrap_err().to_string();
    let new = EfficiencyTable::new;
    let (s, l) = (vec![0.0, 0.5], vec![500.0, 600.0]);
    let g = GOOD.to_vec();
    let cases: Vec<(String, &str)> = vec![
        (
            err(new(0.0, -1, s.clone(), l.clone(), g.clone(), g.clone())),
            "invalid period_nm = 0: must be finite and > 0",
        ),
        (
            err(new(2e6, -1, s.clone(), l.clone(), g.clone(), g.clone())),
            "invalid period_nm = 2000000: must satisfy 0 < period_nm <= MAX_PERIOD_NM (1000000)",
        ),
        (
            err(new(1000.0, -1, vec![0.0], l.clone(), g.clone(), g.clone())),
            "invalid sin_theta_i: has 1 values, must have 2 to 4096",
        ),
        (
            err(new(1000.0, -1, vec![0.5, 0.0], l.clone(), g.clone(), g.clone())),
            "invalid sin_theta_i = 0: must be strictly increasing (above the value before it)",
        ),
        (
            err(new(1000.0, -1, vec![0.0, 1.5], l.clone(), g.clone(), g.clone())),
            "invalid sin_theta_i = 1.5: must lie in [-1, 1]",
        ),
        (
            err(new(1000.0, -1, vec![f64::NAN, 0.5], l.clone(), g.clone(), g.clone())),
            "invalid sin_theta_i = NaN: must lie in [-1, 1]",
        ),
        (
            err(new(1000.0, -1, s.clone(), vec![0.0, 600.0], g.clone(), g.clone())),
            "invalid lambda_nm = 0: must be finite and > 0",
        ),
        (
            err(new(1000.0, -1, s.clone(), vec![600.0, 600.0], g.clone(), g.clone())),
            "invalid lambda_nm = 600: must be strictly increasing (above the value before it)",
        ),
        (
            err(new(1000.0, -1, s.clone(), l.clone(), g[..11].to_vec(), g.clone())),
            "invalid te: has 11 values, must have a multiple of 4 (one [lambda][sin_theta_i] slice per order), 1 to 4097 slices",
        ),
        (
            err(new(1000.0, -1, s.clone(), l.clone(), vec![], vec![])),
            "invalid te: has 0 values, must have a multiple of 4 (one [lambda][sin_theta_i] slice per order), 1 to 4097 slices",
        ),
        (
            err(new(1000.0, -1, s.clone(), l.clone(), g.clone(), g[..8].to_vec())),
            "invalid tm: has 8 values, must have 12",
        ),
        (
            err(new(1000.0, i32::MAX - 1, s.clone(), l.clone(), g.clone(), g.clone())),
            "invalid order_min = 2147483646: must lie in [-2147483648, 2147483645]",
        ),
        (
            err(small({
                let mut v = g.clone();
                v[4] = -0.1;
                v
            })),
            "invalid te = -0.1: must be finite and >= 0",
        ),
        (
            err(small({
                let mut v = g.clone();
                v[5] = f64::INFINITY;
                v
            })),
            "invalid te = inf: must be finite and >= 0",
        ),
        (
            err(small({
                let mut v = g.clone();
                v[4] = 0.9;
                v
            })),
            "invalid te = 1.1: must be a sum over orders <= 1.000001",
        ),
        (
            err(small({
                let mut v = g.clone();
                v[9] = 0.02;
                v
            })),
            "invalid te = 0.02: must be 0: order 1 is evanescent there (|sin_theta_i + m lambda/d| >= 1)",
        ),
        (
            err(new(1000.0, -1, s.clone(), l.clone(), g.clone(), {
                let mut v = g.clone();
                v[11] = 0.5;
                v
            })),
            "invalid tm = 0.5: must be 0: order 1 is evanescent there (|sin_theta_i + m lambda/d| >= 1)",
        ),
    ];
    for (got, want) in cases {
        assert_eq!(got, want);
    }
    // Bounded: no more than MAX_TABLE_NODES nodes per axis.
    let many: Vec<f64> = (0..=MAX_TABLE_NODES).map(|i| 400.0 + i as f64).collect();
    assert_eq!(
        err(new(1000.0, -1, s, many, g.clone(), g)),
        "invalid lambda_nm: has 4097 values, must have 2 to 4096"
    );
}

/// A JSON table as a string: `edit` changes the object first.
#[cfg(feature = "serde")]
fn json_table(edit: impl FnOnce(&mut Value)) -> String {
    let mut v: Value = serde_json::json!({
        "format": "diffraction-efficiency-table", "version": 1, "name": "t", "description": "",
        "grating": {"profile": "sinusoid", "period_nm": 1000.0, "depth_nm": 100.0, "duty": null,
                    "blaze_deg": null, "metal": "Al", "cover": "none"},
        "symmetric": true, "sin_theta_i": [0.0, 0.5], "lambda_nm": [500.0, 600.0],
        "order_min": -1, "order_max": 1,
        "te": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],
        "tm": [[[0.1, 0.2], [0.1, 0.3]], [[0.5, 0.5], [0.5, 0.5]], [[0.1, 0.0], [0.1, 0.0]]],
        "solver": {"method": "x"}, "validation": {}, "command": "", "sha256": "0"
    });
    edit(&mut v);
    v.to_string()
}

/// A change to a JSON table.
#[cfg(feature = "serde")]
type Edit = fn(&mut Value);

#[cfg(feature = "serde")]
#[test]
fn json_tables_load_and_bad_ones_name_the_field() {
    let t: EfficiencyTable = serde_json::from_str(&json_table(|_| {})).unwrap();
    assert_eq!(t, small(GOOD.to_vec()).unwrap());
    let err = |edit: fn(&mut Value)| {
        let e = serde_json::from_str::<EfficiencyTable>(&json_table(edit)).unwrap_err();
        e.to_string()
    };
    let cases: [(Edit, &str); 8] = [
        (
            |v| v["format"] = "other".into(),
            "format: expected \"diffraction-efficiency-table\", got \"other\"",
        ),
        (
            |v| v["version"] = 4.into(),
            "version: expected 1, 2 or 3, got 4",
        ),
        (
            |v| v["grating"]["period_nm"] = (-1.0).into(),
            "invalid grating.period_nm = -1: must be finite and > 0",
        ),
        (
            |v| v["order_max"] = (-2).into(),
            "invalid order_max = -2: must satisfy order_max >= order_min (-1)",
        ),
        (
            |v| v["order_max"] = 2.into(),
            "te: has shape [3][2][2], expected [4][2][2] ([order][lambda][sin])",
        ),
        (
            |v| v["tm"][1] = serde_json::json!([[0.5, 0.5]]),
            "tm[1]: has 1 wavelength rows, expected 2 (as the first)",
        ),
        (
            |v| v["te"][2][1] = serde_json::json!([0.1]),
            "te[2][1]: has 1 values, expected 2 (as the first)",
        ),
        (
            |v| v["lambda_nm"] = serde_json::json!([600.0, 500.0]),
            "invalid lambda_nm = 500: must be strictly increasing (above the value before it)",
        ),
    ];
    for (edit, want) in cases {
        let got = err(edit);
        assert!(got.starts_with(want), "{got}\n  expected: {want}");
    }
    // A field the reader needs is missing.
    let got = err(|v| {
        v.as_object_mut().unwrap().remove("tm");
    });
    assert!(got.starts_with("missing field `tm`"), "{got}");
    // The shipped files load and equal the presets at the nodes (to the f32 rounding).
    for p in Preset::ALL {
        let t: EfficiencyTable = serde_json::from_value(json(p)).unwrap();
        assert_eq!(t.orders(), p.table().orders());
        let e = (
            t.efficiency(1, 0.2, 550.0),
            p.table().efficiency(1, 0.2, 550.0),
        );
        assert!(
            (e.0.te - e.1.te).abs() < efficiency_tolerance::JSON_AGAINST_PRESET,
            "{p}: {e:?}"
        );
    }
}

#[test]
fn scalar_model_baked_into_a_table_matches_it_at_the_nodes() {
    let (s, l) = EfficiencyTable::default_grid();
    let reliefs = [
        ScalarRelief::new(Relief::sinusoid(100.0).unwrap(), Metal::AL, 1000.0).unwrap(),
        ScalarRelief::new(Relief::lamellar(110.0, 0.3125).unwrap(), Metal::AG, 1600.0).unwrap(),
        ScalarRelief::new(Relief::sawtooth(0.15).unwrap(), Metal::AU, 1666.67).unwrap(),
    ];
    let mut worst = 0.0f64;
    let mut worst_sum = 0.0f64;
    for r in &reliefs {
        let t = EfficiencyTable::from_scalar(r, s, l).unwrap();
        let mut out = vec![Polarised::default(); t.order_count()];
        for &lam in l {
            for &sn in s {
                t.efficiencies(sn, lam, &mut out);
                for (k, e) in out.iter().enumerate() {
                    let m = t.orders().start() + k as i32;
                    let sm = sn + f64::from(m) * lam / r.period_nm();
                    if 1.0 - sm * sm <= tol::GRAZING_CORNER {
                        continue;
                    }
                    let want = r.order(m, sn, lam).unwrap_or_default();
                    worst = worst
                        .max((e.te - want.te).abs())
                        .max((e.tm - want.tm).abs());
                }
                // Every order the model gives at the node is stored.
                for o in r.orders(sn, lam) {
                    assert!(t.orders().contains(&o.order));
                }
            }
        }
        for i in 0..=200 {
            for j in 0..=100 {
                let (sn, lam) = (-1.0 + 0.01 * f64::from(i), 355.0 + 4.8 * f64::from(j));
                t.efficiencies(sn, lam, &mut out);
                let te: f64 = out.iter().map(|e| e.te).sum();
                let tm: f64 = out.iter().map(|e| e.tm).sum();
                worst_sum = worst_sum.max(te).max(tm);
            }
        }
    }
    println!("from_scalar: max |table - model| at the nodes {worst:.3e}; max sum {worst_sum:.6}");
    assert!(worst <= tol::SCALAR_NODES, "{worst:e}");
    assert!(worst_sum <= 1.0 + tol::SUM_ROUNDING);
    // Its errors name the axis.
    let e = EfficiencyTable::from_scalar(&reliefs[0], &[0.0], l).unwrap_err();
    assert_eq!(e.parameter(), "sin_theta_i");
    let fine: Vec<f64> = (0..4096).map(|i| -0.99 + f64::from(i) * 4e-4).collect();
    let e = EfficiencyTable::from_scalar(&reliefs[0], &fine, &fine[..4000]).unwrap_err();
    assert_eq!(e.parameter(), "lambda_nm"); // negative wavelengths
    let lam: Vec<f64> = (0..4096).map(|i| 300.0 + f64::from(i) * 0.1).collect();
    let e = EfficiencyTable::from_scalar(&reliefs[0], &fine, &lam).unwrap_err();
    assert_eq!(e.parameter(), "sin_theta_i"); // more than MAX_TABLE_VALUES values
}

#[test]
fn odd_queries_are_finite_and_zero_where_they_should_be() {
    for p in Preset::ALL {
        let t = p.table();
        let mut out = vec![Polarised::default(); t.order_count() + 3];
        for (s, lam) in [
            (f64::NAN, 500.0),
            (0.0, f64::NAN),
            (f64::INFINITY, 500.0),
            (0.0, f64::NEG_INFINITY),
        ] {
            assert_eq!(t.efficiencies(s, lam, &mut out), 0.0);
            assert!(out.iter().all(|e| *e == Polarised::default()));
        }
        for (s, lam) in [(1e300, 1e300), (-5.0, 1e-300), (0.3, 0.0), (-0.3, -7.0)] {
            let total = t.efficiencies(s, lam, &mut out);
            assert!(total.is_finite() && (0.0..=1.0).contains(&total));
            // The extra slots beyond the stored orders stay 0.
            assert!(out[t.order_count()..]
                .iter()
                .all(|e| *e == Polarised::default()));
        }
        // A short buffer gets the first orders, with the same normalisation.
        let mut short = vec![Polarised::default(); 2];
        t.efficiencies(0.1, 500.0, &mut short);
        t.efficiencies(0.1, 500.0, &mut out);
        assert_eq!(short[..], out[..2]);
        assert_eq!(
            t.efficiency(t.orders().end() + 1, 0.1, 500.0),
            Polarised::default()
        );
    }
}

/// A conical table whose |β| planes all hold the classical table `t`'s values (0 where the
/// order is evanescent conically).
#[cfg(feature = "alloc")]
fn planes_of(t: &EfficiencyTable, betas: &[f64]) -> EfficiencyTable {
    use diffraction::relief::Polarised;
    let s: Vec<f64> = t.sin_theta_i().collect();
    let l: Vec<f64> = t.lambda_nm().collect();
    let (lo, n_o) = (*t.orders().start(), t.order_count());
    let d = t.period_nm();
    let n = n_o * s.len() * betas.len() * l.len();
    let (mut te, mut tm) = (vec![0.0; n], vec![0.0; n]);
    let mut out = vec![Polarised::default(); n_o];
    for (kb, &b) in betas.iter().enumerate() {
        let cb = (1.0 - b * b).sqrt();
        for (j, &lam) in l.iter().enumerate() {
            for (i, &x) in s.iter().enumerate() {
                t.efficiencies(x, lam, &mut out);
                for (k, e) in out.iter().enumerate() {
                    let am = x * cb + f64::from(lo + k as i32) * lam / d;
                    if 1.0 - am * am - b * b > 0.0 {
                        let at = ((k * betas.len() + kb) * l.len() + j) * s.len() + i;
                        te[at] = e.te;
                        tm[at] = e.tm;
                    }
                }
            }
        }
    }
    EfficiencyTable::new_conical(d, lo, s, betas.to_vec(), l, te, tm).unwrap()
}

/// Conical tables: at β = 0 a conical table reads exactly as the classical table of its β = 0
/// plane; it depends on |β| only; an order appears exactly where α_m² + β² = 1; and each
/// polarisation's sum stays at most 1.
#[cfg(all(feature = "alloc", feature = "presets"))]
#[test]
fn conical_tables_follow_their_rule() {
    use diffraction::relief::{Polarised, Preset};
    let cd = Preset::Cd.table();
    let c = planes_of(cd, &[0.0, 0.4, 0.8, 0.95]);
    assert!(c.is_conical() && !cd.is_conical());
    let n = cd.order_count();
    let (mut a, mut b) = (vec![Polarised::default(); n], vec![Polarised::default(); n]);
    let mut state = 7u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..500 {
        let (s, lam) = (-0.999 + 1.998 * next(), 360.0 + 470.0 * next());
        let ta = cd.efficiencies(s, lam, &mut a);
        let tb = c.efficiencies_conical(s, 0.0, lam, &mut b);
        for (x, y) in a.iter().zip(&b) {
            // The same corners and weights: equal to rounding.
            assert!((x.te - y.te).abs() < 1e-12 && (x.tm - y.tm).abs() < 1e-12);
        }
        assert!((ta - tb).abs() < 1e-12);
        // |β| only, and the sums.
        let beta = 0.97 * next();
        let alpha = (1.0 - beta * beta).sqrt() * (-0.999 + 1.998 * next());
        let t1 = c.efficiencies_conical(alpha, beta, lam, &mut a);
        let t2 = c.efficiencies_conical(alpha, -beta, lam, &mut b);
        assert_eq!(a, b);
        assert_eq!(t1, t2);
        let (st, sm) = a.iter().fold((0.0, 0.0), |(p, q), e| (p + e.te, q + e.tm));
        assert!(st <= 1.0 + 1e-12 && sm <= 1.0 + 1e-12 && t1 <= 1.0);
    }
    // Order 1 at λ = 600 nm, β = 0.5: appears at α₁² + β² = 1, α = √0.75 − 600/1600.
    let (beta, lam) = (0.5, 600.0);
    let edge = 0.75f64.sqrt() - lam / 1600.0;
    assert_eq!(c.efficiency_conical(1, edge + 1e-9, beta, lam).te, 0.0);
    assert!(c.efficiency_conical(1, edge - 1e-3, beta, lam).te > 0.0);
    // A classical table ignores β (the classical-mount reading).
    assert_eq!(
        cd.efficiency_conical(1, 0.1, 0.6, lam),
        cd.efficiency(1, 0.1, lam)
    );
    // Beyond the incidence: nothing.
    assert_eq!(c.efficiency_conical(0, 0.8, 0.6, lam), Polarised::default());
}

/// A random table of `orders` orders from −orders/2 on a grid of the given axes (`betas` empty:
/// classical), each node's values random and scaled so that the node's sum over orders is
/// random in [0.9, 1] (TE) and [0.97, 1] (TM), 0 where the order is evanescent: sums close to 1,
/// where the bilinear interpolation overshoots 1 between nodes near Rayleigh lines.
fn near_unit_table(next: &mut impl FnMut() -> f64, betas: &[f64]) -> EfficiencyTable {
    let d = 900.0 + 800.0 * next();
    let orders = 5usize;
    let first = -(orders as i32) / 2;
    let n_s = 4 + (4.0 * next()) as usize;
    let n_l = 3 + (4.0 * next()) as usize;
    let mut s: Vec<f64> = (0..n_s)
        .map(|i| -0.99 + 1.98 * (i as f64 + 0.3 * next()) / (n_s - 1) as f64)
        .collect();
    s[n_s - 1] = s[n_s - 1].min(0.999);
    let l: Vec<f64> = (0..n_l)
        .map(|j| 380.0 + 420.0 * (j as f64 + 0.3 * next()) / (n_l - 1) as f64)
        .collect();
    let planes = betas.len().max(1);
    let slice = n_s * planes * n_l;
    let (mut te, mut tm) = (vec![0.0; orders * slice], vec![0.0; orders * slice]);
    for kb in 0..planes {
        let b = betas.get(kb).copied().unwrap_or(0.0);
        let cb = (1.0 - b * b).sqrt();
        for (j, &lam) in l.iter().enumerate() {
            for (i, &x) in s.iter().enumerate() {
                let at = (kb * n_l + j) * n_s + i;
                let mut raw = vec![(0.0, 0.0); orders];
                let (mut st, mut sm) = (0.0, 0.0);
                for (k, r) in raw.iter_mut().enumerate() {
                    let am = x * cb + f64::from(first + k as i32) * lam / d;
                    if 1.0 - am * am - b * b > 0.0 {
                        *r = (next(), next());
                        st += r.0;
                        sm += r.1;
                    }
                }
                let (gt, gm) = (0.9 + 0.1 * next(), 0.97 + 0.03 * next());
                for (k, r) in raw.iter().enumerate() {
                    if st > 0.0 {
                        te[k * slice + at] = r.0 / st * gt;
                    }
                    if sm > 0.0 {
                        tm[k * slice + at] = r.1 / sm * gm;
                    }
                }
            }
        }
    }
    if betas.is_empty() {
        EfficiencyTable::new(d, first, s, l, te, tm).unwrap()
    } else {
        EfficiencyTable::new_conical(d, first, s, betas.to_vec(), l, te, tm).unwrap()
    }
}

/// One order's efficiency (which skips the sum over orders in cells where no query needs the
/// normalisation) equals, to the bit, that order's entry of the full, normalised set, for the
/// presets, a conical table made of the CD's, and random tables whose node sums are close to 1
/// (classical and conical); the queries cover whole grids, edges and clamped outskirts.
#[cfg(all(feature = "alloc", feature = "presets"))]
#[test]
fn one_order_equals_its_entry_of_the_normalised_set() {
    let mut state = 11u64;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut tables: Vec<EfficiencyTable> = Preset::ALL.iter().map(|p| p.table().clone()).collect();
    tables.push(planes_of(Preset::Cd.table(), &[0.0, 0.4, 0.8, 0.95]));
    for _ in 0..40 {
        tables.push(near_unit_table(&mut next, &[]));
        let b0 = 0.5 * next();
        let b1 = b0 + 0.2 + 0.2 * next();
        tables.push(near_unit_table(&mut next, &[b0, b1]));
    }
    let (mut checked, mut normalised) = (0usize, 0usize);
    for t in &tables {
        let n = t.order_count();
        let mut all = vec![Polarised::default(); n];
        let (smin, smax) = (
            t.sin_theta_i().next().unwrap(),
            t.sin_theta_i().last().unwrap(),
        );
        let (lmin, lmax) = (t.lambda_nm().next().unwrap(), t.lambda_nm().last().unwrap());
        for q in 0..3000 {
            // Mostly inside the grid, some beyond it (clamped).
            let wide = if q % 10 == 0 { 0.2 } else { 0.0 };
            let s = smin - wide + (smax - smin + 2.0 * wide) * next();
            let lam = lmin - 50.0 * wide + (lmax - lmin + 100.0 * wide) * next();
            let beta = if t.is_conical() { 0.9 * next() } else { 0.0 };
            let alpha = s * (1.0 - beta * beta).sqrt();
            t.efficiencies_conical(alpha, beta, lam, &mut all);
            let (st, sm) = all
                .iter()
                .fold((0.0, 0.0), |(p, r), e| (p + e.te, r + e.tm));
            if st > 1.0 - 1e-9 || sm > 1.0 - 1e-9 {
                normalised += 1;
            }
            for (k, m) in t.orders().enumerate() {
                let one = t.efficiency_conical(m, alpha, beta, lam);
                assert!(
                    one.te.to_bits() == all[k].te.to_bits() && one.tm.to_bits() == all[k].tm.to_bits(),
                    "order {m} at α = {alpha}, β = {beta}, λ = {lam}: {one:?} alone, {:?} in the set",
                    all[k]
                );
                checked += 1;
            }
        }
    }
    // The random tables reach the normalisation at some queries: the check covers both paths.
    assert!(normalised > 1000, "{normalised} normalised queries");
    assert!(checked > 1_000_000, "{checked}");
}
