//! The colour tables as caches (feature `serde`): a round trip through serde_json gives a table
//! equal to the saved one with bit-identical lookups and means, and every corruption of the
//! stored form is refused with an error naming its field.
#![cfg(feature = "serde")]

use diffraction::spectrum::{Illuminant, Spectral};
use diffraction::{ColorTable, Grating, GratingBsdf, GrooveSpread, TableSource};
use serde_json::{json, Value};

/// Values of u that reach every kind of cell: order 0's lobe and tail, orders, the ends, and
/// inputs outside [−2, 2].
fn probes() -> Vec<f64> {
    let mut v = vec![0.0, -0.0, 1e-300, 2.0, -2.0, 3.0, f64::NAN, f64::INFINITY];
    let mut x = 1e-22;
    while x < 2.0 {
        v.push(x);
        v.push(-x * 1.37);
        x *= 1.9;
    }
    v.extend((0..200).map(|k| -2.0 + 0.02 * k as f64 + 1.3e-4));
    v
}

fn same(a: diffraction::color::Xyz, b: diffraction::color::Xyz) -> bool {
    a.x.to_bits() == b.x.to_bits()
        && a.y.to_bits() == b.y.to_bits()
        && a.z.to_bits() == b.z.to_bits()
}

/// lookups and means of `a` and `b` are bit-identical at every probe.
fn identical(
    lookup: &dyn Fn(f64) -> [diffraction::color::Xyz; 2],
    mean: &dyn Fn(f64, f64) -> [diffraction::color::Xyz; 2],
) {
    let us = probes();
    for &u in &us {
        let [a, b] = lookup(u);
        assert!(same(a, b), "lookup at {u}: {a:?} {b:?}");
    }
    for w in us.windows(2) {
        let [a, b] = mean(w[0], w[1]);
        assert!(same(a, b), "mean over [{}, {}]", w[0], w[1]);
    }
}

fn color_tables() -> Vec<ColorTable> {
    let s = Spectral::new(Illuminant::D65);
    [
        (Grating::new(1600.0, 800.0, 1000).unwrap(), 1e-3),
        (Grating::new(400.0, 200.0, 5).unwrap(), 1e-3),
        // N·d > 3.3·10²⁰ nm: the first block is left to `Exact`.
        (Grating::new(1e12, 5e11, u32::MAX).unwrap(), 1e-2),
    ]
    .iter()
    .map(|(g, a)| ColorTable::new(&s, g, *a).unwrap())
    .collect()
}

fn radiometric_tables() -> Vec<ColorTable> {
    let s = Spectral::new(Illuminant::E);
    let rough = GrooveSpread::gaussian(0.01).unwrap();
    [
        GratingBsdf::new(Grating::new(1600.0, 800.0, 300).unwrap()).with_groove(rough),
        GratingBsdf::new(Grating::new(740.0, 370.0, 30).unwrap()).with_groove(GrooveSpread::IDEAL),
        GratingBsdf::new(Grating::infinite(1600.0, 800.0).unwrap()),
    ]
    .iter()
    .map(|b| ColorTable::new(&s, b, 1e-3).unwrap())
    .collect()
}

#[test]
fn color_tables_round_trip_bit_identically() {
    for t in color_tables() {
        let json = serde_json::to_string(&t).unwrap();
        let back: ColorTable = serde_json::from_str(&json).unwrap();
        assert_eq!(back, t);
        assert_eq!(serde_json::to_string(&back).unwrap(), json);
        identical(&|u| [t.lookup(u), back.lookup(u)], &|a, b| {
            [t.mean(a, b), back.mean(a, b)]
        });
        assert_eq!(
            (
                back.scale(),
                back.error_estimate(),
                back.evaluations(),
                back.node_count()
            ),
            (
                t.scale(),
                t.error_estimate(),
                t.evaluations(),
                t.node_count()
            )
        );
    }
}

#[test]
fn radiometric_tables_round_trip_bit_identically() {
    for t in radiometric_tables() {
        let json = serde_json::to_string(&t).unwrap();
        let back: ColorTable = serde_json::from_str(&json).unwrap();
        assert_eq!(back, t);
        identical(&|u| [t.lookup(u), back.lookup(u)], &|a, b| {
            [t.mean(a, b), back.mean(a, b)]
        });
        assert!(same(back.specular(), t.specular()));
    }
}

/// The error of loading `v` as a `T` names `field`.
fn refused<T: serde::de::DeserializeOwned>(v: &Value, field: &str) {
    let e = match serde_json::from_value::<T>(v.clone()) {
        Ok(_) => panic!("accepted a corrupted table (expected an error naming {field})"),
        Err(e) => e.to_string(),
    };
    assert!(e.contains(field), "expected {field} in: {e}");
}

fn corruptions(base: &Value) -> Vec<(Value, &'static str)> {
    let mut out = Vec::new();
    let mut edit = |field: &'static str, f: &dyn Fn(&mut Value)| {
        let mut v = base.clone();
        f(&mut v);
        out.push((v, field));
    };
    edit("format_version", &|v| v["format_version"] = json!(2));
    edit("format_version", &|v| v["format_version"] = json!(0));
    edit("accuracy", &|v| v["accuracy"] = json!(0.0));
    edit("accuracy", &|v| v["accuracy"] = json!(5.0));
    edit("u_lo", &|v| {
        let u = v["grid"]["u_lo"].as_f64().unwrap();
        v["grid"]["u_lo"] = json!(2.0 * u);
    });
    edit("u_lo", &|v| v["grid"]["u_lo"] = json!(-1.0));
    edit("intervals", &|v| {
        v["grid"]["intervals"].as_array_mut().unwrap().pop();
    });
    edit("intervals", &|v| v["grid"]["intervals"][3] = json!(3));
    edit("intervals", &|v| v["grid"]["intervals"][3] = json!(0));
    edit("intervals", &|v| v["grid"]["intervals"][3] = json!(2048));
    edit("intervals", &|v| {
        for n in v["grid"]["intervals"].as_array_mut().unwrap() {
            *n = json!(1024);
        }
    });
    edit("values", &|v| {
        v["grid"]["values"].as_array_mut().unwrap().pop();
    });
    edit("values", &|v| v["grid"]["values"][7][1] = json!(-1e-9));
    edit("values", &|v| v["grid"]["values"][0][2] = json!(-0.5));
    edit("scale", &|v| v["grid"]["scale"] = json!(0.0));
    edit("scale", &|v| v["grid"]["scale"] = json!(-1.0));
    edit("error", &|v| v["grid"]["error"] = json!(-1.0));
    // Values, scale and error at 1e308, evaluations at u64::MAX: finite, but no build makes
    // them.
    edit("values", &|v| v["grid"]["values"][7][1] = json!(1e308));
    edit("scale", &|v| v["grid"]["scale"] = json!(1e308));
    edit("scale", &|v| v["grid"]["scale"] = json!(1e-300));
    edit("error", &|v| v["grid"]["error"] = json!(1e308));
    edit("evaluations", &|v| {
        v["grid"]["evaluations"] = json!(u64::MAX)
    });
    edit("unknown field", &|v| v["extra"] = json!(1));
    edit("unknown field", &|v| v["grid"]["derivatives"] = json!([]));
    edit("missing field", &|v| {
        v.as_object_mut().unwrap().remove("illuminant");
    });
    edit("missing field", &|v| {
        v["grid"].as_object_mut().unwrap().remove("values");
    });
    out
}

#[test]
fn corrupted_color_tables_are_refused_naming_the_field() {
    let t = &color_tables()[0];
    let base = serde_json::to_value(t).unwrap();
    for (v, field) in corruptions(&base) {
        refused::<ColorTable>(&v, field);
    }
    let mut v = base.clone();
    v["grating"]["slits"] = json!("Infinite");
    refused::<ColorTable>(&v, "slits");
    let mut v = base.clone();
    v["grating"]["slit_width_nm"] = json!(5000.0);
    refused::<ColorTable>(&v, "slit_width_nm");
    // Another grating's grid: its u_lo is not this grating's.
    let mut v = base;
    v["grating"]["slits"] = json!({"Finite": 10});
    refused::<ColorTable>(&v, "u_lo");
}

#[test]
fn corrupted_radiometric_tables_are_refused_naming_the_field() {
    for t in radiometric_tables() {
        let base = serde_json::to_value(&t).unwrap();
        for (v, field) in corruptions(&base) {
            refused::<ColorTable>(&v, field);
        }
    }
    let base = serde_json::to_value(&radiometric_tables()[0]).unwrap();
    let mut v = base.clone();
    v["bsdf"]["groove"] = json!({"CoherenceLength": {"length_nm": 480000.0}});
    refused::<ColorTable>(&v, "groove");
    let mut v = base;
    v["bsdf"]["groove"] = json!({"Gaussian": {"sigma": -1.0}});
    refused::<ColorTable>(&v, "sigma");
}

/// One stored form for both sources: the paper's writes `grating`, the radiometric one `bsdf`
/// (the fields `ColorTable` and the former `RadiometricTable` wrote, version 1), each loads
/// back with its source, and a form with both or neither is refused naming `grating`.
#[test]
fn the_stored_form_names_its_source() {
    let paper = &color_tables()[0];
    let v = serde_json::to_value(paper).unwrap();
    assert!(v.get("grating").is_some() && v.get("bsdf").is_none());
    assert_eq!(v["format_version"], json!(1));
    let radiometric = &radiometric_tables()[0];
    let w = serde_json::to_value(radiometric).unwrap();
    assert!(w.get("bsdf").is_some() && w.get("grating").is_none());
    let back: ColorTable = serde_json::from_value(w.clone()).unwrap();
    assert!(matches!(back.source(), TableSource::Radiometric(b) if Some(b) == radiometric.bsdf()));
    // The deprecated name still loads the same form.
    #[allow(deprecated)]
    let old: diffraction::RadiometricTable = serde_json::from_value(w.clone()).unwrap();
    assert_eq!(&old, radiometric);
    let mut both = w.clone();
    both["grating"] = v["grating"].clone();
    refused::<ColorTable>(&both, "grating");
    let mut neither = w;
    neither.as_object_mut().unwrap().remove("bsdf");
    refused::<ColorTable>(&neither, "grating");
}
