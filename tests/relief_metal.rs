//! The metals of the relief model against the Python oracle: n + ik linearly interpolated in λ
//! (numpy.interp on the same source rows) and the normal-incidence reflectance, at every source
//! wavelength, every midpoint and the band edges (`tests/data/metals.csv`); the Fresnel equations
//! against their closed-form limits.

#[path = "support/relief_tolerance.rs"]
mod relief_tolerance;

use diffraction::relief::Metal;
use relief_tolerance as tol;

struct Row {
    metal: Metal,
    lambda_nm: f64,
    n: f64,
    k: f64,
    reflectance: f64,
}

fn rows() -> Vec<Row> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/metals.csv");
    let text = std::fs::read_to_string(path).expect("tests/data/metals.csv");
    let mut out = vec![];
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().expect("a number");
        out.push(Row {
            metal: f[0].parse().expect("a metal name"),
            lambda_nm: num(1),
            n: num(3),
            k: num(4),
            reflectance: num(5),
        });
    }
    out
}

#[test]
fn index_and_normal_reflectance_match_the_oracle() {
    let rows = rows();
    assert_eq!(rows.len(), 164, "every row of metals.csv");
    let (mut worst_index, mut worst_r) = (0.0f64, 0.0f64);
    for r in &rows {
        let (n, k) = r.metal.index(r.lambda_nm);
        let e = ((n - r.n) / r.n).abs().max(((k - r.k) / r.k).abs());
        worst_index = worst_index.max(e);
        let (rs, rp) = r.metal.reflectance(r.lambda_nm, 1.0);
        assert!(
            (rs - rp).abs() <= relief_tolerance::NORMAL_INCIDENCE_S_P,
            "s and p agree at normal incidence"
        );
        worst_r = worst_r.max((rs - r.reflectance).abs());
    }
    println!(
        "metals.csv: index relative error {worst_index:.3e}, reflectance abs error {worst_r:.3e}"
    );
    assert!(worst_index <= tol::METAL_INDEX_REL, "{worst_index:e}");
    assert!(worst_r <= tol::METAL_REFLECTANCE, "{worst_r:e}");
}

#[test]
fn every_metal_covers_the_visible_band_with_physical_values() {
    for m in Metal::TABULATED {
        let mut lambda = 360.0;
        while lambda <= 830.0 {
            let (n, k) = m.index(lambda);
            assert!(n > 0.0 && k > 1.0, "{m} at {lambda}: {n} + {k}i is a metal");
            for i in 0..=20 {
                let c = f64::from(i) / 20.0;
                let (rs, rp) = m.reflectance(lambda, c);
                assert!((0.0..=1.0).contains(&rs) && (0.0..=1.0).contains(&rp));
                assert!(
                    rp <= rs + relief_tolerance::RP_ABOVE_RS,
                    "{m} {lambda} {c}: R_p {rp} > R_s {rs}"
                );
            }
            lambda += 5.0;
        }
    }
}

/// Oblique incidence against the Fresnel equations written with the angle itself (the complex
/// Snell's law cos θt = √(1 − sin²θ/N²), r_s = (cos θ − N cos θt)/(cos θ + N cos θt),
/// r_p = (N cos θ − cos θt)/(N cos θ + cos θt)): an independent form of the same physics.
#[test]
fn oblique_incidence_matches_the_snell_form() {
    #[derive(Clone, Copy)]
    struct C(f64, f64);
    let mul = |a: C, b: C| C(a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0);
    let div = |a: C, b: C| {
        let d = b.0 * b.0 + b.1 * b.1;
        C((a.0 * b.0 + a.1 * b.1) / d, (a.1 * b.0 - a.0 * b.1) / d)
    };
    let sqrt = |a: C| {
        let r = (a.0 * a.0 + a.1 * a.1).sqrt();
        let re = ((r + a.0) / 2.0).sqrt();
        let im = ((r - a.0) / 2.0).sqrt().copysign(a.1);
        C(re, im)
    };
    let mut worst = 0.0f64;
    for m in Metal::TABULATED {
        for &lambda in &[400.0, 550.0, 700.0] {
            let (n, k) = m.index(lambda);
            let nn = C(n, k);
            for i in 1..20 {
                let c = f64::from(i) / 20.0;
                let s2 = 1.0 - c * c;
                let n2 = mul(nn, nn);
                let t = div(C(s2, 0.0), n2);
                let ct = sqrt(C(1.0 - t.0, -t.1));
                let nct = mul(nn, ct);
                let rs = div(C(c - nct.0, -nct.1), C(c + nct.0, nct.1));
                let nc = C(n * c, k * c);
                let rp = div(C(nc.0 - ct.0, nc.1 - ct.1), C(nc.0 + ct.0, nc.1 + ct.1));
                let (ours_s, ours_p) = m.reflectance(lambda, c);
                worst = worst
                    .max((ours_s - (rs.0 * rs.0 + rs.1 * rs.1)).abs())
                    .max((ours_p - (rp.0 * rp.0 + rp.1 * rp.1)).abs());
            }
        }
    }
    println!("Fresnel against the Snell form: {worst:.3e}");
    assert!(worst <= tol::FRESNEL_FORMS, "{worst:e}");
}
