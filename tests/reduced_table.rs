//! Reduced conical tables (version 3, `docs/efficiency_tables.md`, "Reduced conical tables"):
//! the rule reproduces a q affine in (s′, λ′, √(1 − β²)) exactly (its closed form), a table
//! whose planes hold one classical table at the same reduced nodes reads as that table at
//! (s′, λ′) whatever β (the conical-to-classical mapping of a perfect conductor), one order read
//! alone equals its entry of the normalised set to the bit, and the JSON file (version 3) loads
//! with every refusal naming the field and the element.

#[path = "support/efficiency_tolerance.rs"]
mod efficiency_tolerance;

use diffraction::relief::{EfficiencyTable, Polarised, Preset, ReducedGrid};
use efficiency_tolerance as tol;

fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn cb(b: f64) -> f64 {
    (1.0 - b * b).sqrt()
}

/// The wavelengths plane `p` must reach (the loader's rule, written out).
fn reach(b: &[f64], band: (f64, f64), p: usize) -> (f64, f64) {
    let lo = if p > 0 {
        band.0 * cb(b[p]) / cb(b[p - 1])
    } else {
        band.0
    };
    let hi = if p + 1 < b.len() {
        band.1 * cb(b[p]) / cb(b[p + 1])
    } else {
        band.1
    };
    (lo, hi)
}

/// Random ragged planes: `n` nodes per plane reaching a little past what each must.
fn ragged(next: &mut impl FnMut() -> f64, b: &[f64], band: (f64, f64)) -> Vec<Vec<f64>> {
    (0..b.len())
        .map(|p| {
            let (lo, hi) = reach(b, band, p);
            let (lo, hi) = (lo * (1.0 - 0.05 * next()), hi * (1.0 + 0.05 * next()));
            let n = 3 + (5.0 * next()) as usize;
            (0..n)
                .map(|j| {
                    let jitter = if j == 0 || j == n - 1 {
                        0.0
                    } else {
                        0.4 * next()
                    };
                    lo + (hi - lo) * (j as f64 + jitter) / (n - 1) as f64
                })
                .collect()
        })
        .collect()
}

/// A reduced table of order 0 alone (which propagates wherever the incidence is real, with
/// cos θ0 = cos θi, so η0 = q) holding q = 0.3 + 0.1·s′ + 2·10⁻⁴·λ′ + 0.2·c at its nodes,
/// c = √(1 − β²): bilinear interpolation on each plane reproduces an affine function of
/// (s′, λ′) exactly, and the blend linear in c its c term, so every query in the band reads
/// q itself at the query's (s′, λ′ = λ/c, c).
#[test]
fn an_affine_q_is_read_exactly() {
    let mut next = rng(3);
    let q = |s: f64, lp: f64, c: f64| 0.3 + 0.1 * s + 2e-4 * lp + 0.2 * c;
    let mut worst = 0.0f64;
    for _ in 0..20 {
        let b = [0.0, 0.35 + 0.1 * next(), 0.7 + 0.1 * next(), 0.9];
        let band = (380.0 + 20.0 * next(), 700.0 + 100.0 * next());
        let s: Vec<f64> = vec![-0.95, -0.4 + 0.2 * next(), 0.3, 0.95];
        let planes = ragged(&mut next, &b, band);
        let (mut te, mut tm) = (Vec::new(), Vec::new());
        for (p, nodes) in planes.iter().enumerate() {
            for &l in nodes {
                for &x in &s {
                    let v = q(x, l / cb(b[p]), cb(b[p]));
                    te.push(v);
                    tm.push(0.5 * v);
                }
            }
        }
        let grid = ReducedGrid {
            sin_theta_i: s,
            abs_beta: b.to_vec(),
            lambda_range_nm: band,
            lambda_nm: planes,
        };
        let t = EfficiencyTable::new_reduced(1000.0, 0, grid, te, tm).unwrap();
        for _ in 0..500 {
            let beta = 0.9 * next();
            let c = cb(beta);
            let sp = -0.95 + 1.9 * next();
            let lam = band.0 + (band.1 - band.0) * next();
            let e = t.efficiency_conical(0, sp * c, beta, lam);
            let want = q(sp, lam / c, c);
            worst = worst
                .max((e.te - want).abs())
                .max((e.tm - 0.5 * want).abs());
        }
    }
    println!("affine q: worst {worst:.2e}");
    assert!(worst < tol::REDUCED_AFFINE, "{worst}");
}

/// A reduced table whose planes all hold the CD preset's values at the preset's own nodes in
/// reduced coordinates (plane p's wavelengths c_p·λ_j): every plane is the same function of
/// (s′, λ′), which the rule then reads at (s′, λ′) = (α, λ)/c for every β — what a perfect
/// conductor's exact conical-to-classical mapping gives.
fn cd_planes(betas: &[f64], band: (f64, f64)) -> EfficiencyTable {
    let cd = Preset::Cd.table();
    let s: Vec<f64> = cd.sin_theta_i().collect();
    let l: Vec<f64> = cd.lambda_nm().collect();
    let (lo, n_o, d) = (*cd.orders().start(), cd.order_count(), cd.period_nm());
    let slice = s.len() * l.len() * betas.len();
    let (mut te, mut tm) = (vec![0.0; n_o * slice], vec![0.0; n_o * slice]);
    let mut out = vec![Polarised::default(); n_o];
    for (p, &b) in betas.iter().enumerate() {
        let c = cb(b);
        for (j, &lam) in l.iter().enumerate() {
            for (i, &x) in s.iter().enumerate() {
                cd.efficiencies(x, lam, &mut out);
                for (k, e) in out.iter().enumerate() {
                    // The loader's test of evanescence at the node (physical λ = c·λ′).
                    let am = x * c + f64::from(lo + k as i32) * (c * lam) / d;
                    if 1.0 - am * am - b * b > 0.0 {
                        let at = k * slice + (p * l.len() + j) * s.len() + i;
                        te[at] = e.te;
                        tm[at] = e.tm;
                    }
                }
            }
        }
    }
    let grid = ReducedGrid {
        sin_theta_i: s,
        abs_beta: betas.to_vec(),
        lambda_range_nm: band,
        lambda_nm: betas
            .iter()
            .map(|&b| l.iter().map(|&x| cb(b) * x).collect())
            .collect(),
    };
    EfficiencyTable::new_reduced(d, lo, grid, te, tm).unwrap()
}

#[test]
fn planes_of_one_classical_table_read_it_in_reduced_coordinates() {
    let cd = Preset::Cd.table();
    let betas = [0.0, 0.3, 0.5];
    // The band the planes' nodes c_p·(360..830) cover: up to 830·c(0.5).
    let band = (360.0, 830.0 * cb(0.5));
    let t = cd_planes(&betas, band);
    assert!(t.is_reduced() && t.is_conical());
    let n = cd.order_count();
    let (mut a, mut r) = (vec![Polarised::default(); n], vec![Polarised::default(); n]);
    let mut next = rng(9);
    let mut worst = 0.0f64;
    for _ in 0..3000 {
        let beta = 0.5 * next();
        let c = cb(beta);
        let sp = -0.999 + 1.998 * next();
        let lam = band.0 + (band.1 - band.0) * next();
        cd.efficiencies(sp, lam / c, &mut a);
        let total = t.efficiencies_conical(sp * c, beta, lam, &mut r);
        assert!(total <= 1.0);
        for (x, y) in a.iter().zip(&r) {
            worst = worst.max((x.te - y.te).abs()).max((x.tm - y.tm).abs());
        }
        // |β| only.
        let mut m = vec![Polarised::default(); n];
        t.efficiencies_conical(sp * c, -beta, lam, &mut m);
        assert_eq!(m, r);
    }
    println!("reduced CD against the CD at (s', lambda'): worst {worst:.2e}");
    assert!(worst < tol::REDUCED_MAPPING, "{worst}");
    // An order appears exactly where α_m² + β² = 1: order 1 at β = 0.4, λ = 600 nm.
    let (beta, lam) = (0.4, 600.0);
    let edge = cb(beta) - lam / 1600.0;
    assert_eq!(t.efficiency_conical(1, edge + 1e-9, beta, lam).te, 0.0);
    assert!(t.efficiency_conical(1, edge - 1e-3, beta, lam).te > 0.0);
    // Beyond the incidence, and non-finite queries: nothing.
    assert_eq!(t.efficiency_conical(0, 0.8, 0.6, lam), Polarised::default());
    assert_eq!(
        t.efficiency_conical(0, f64::NAN, 0.1, lam),
        Polarised::default()
    );
    assert_eq!(t.efficiencies_conical(0.1, f64::INFINITY, lam, &mut r), 0.0);
}

/// A random reduced table with node sums close to 1 (TE in [0.9, 1], TM in [0.97, 1]), where
/// the interpolation overshoots 1 between nodes and the normalisation acts.
fn near_unit_reduced(next: &mut impl FnMut() -> f64) -> EfficiencyTable {
    let d = 900.0 + 800.0 * next();
    let (orders, first) = (5usize, -2i32);
    let n_s = 4 + (4.0 * next()) as usize;
    let s: Vec<f64> = (0..n_s)
        .map(|i| (-0.99 + 1.98 * (i as f64 + 0.3 * next()) / (n_s - 1) as f64).min(0.999))
        .collect();
    let b0 = if next() < 0.5 { 0.0 } else { 0.3 * next() };
    let b: Vec<f64> = vec![b0, b0 + 0.15 + 0.2 * next(), 0.8 + 0.1 * next()];
    let band = (380.0 + 30.0 * next(), 650.0 + 150.0 * next());
    let planes = ragged(next, &b, band);
    let rows: usize = planes.iter().map(Vec::len).sum();
    let slice = n_s * rows;
    let (mut te, mut tm) = (vec![0.0; orders * slice], vec![0.0; orders * slice]);
    let mut row = 0;
    for (&beta, nodes) in b.iter().zip(&planes) {
        let c = cb(beta);
        for &lam in nodes {
            for (i, &x) in s.iter().enumerate() {
                let at = row * n_s + i;
                let mut raw = vec![(0.0, 0.0); orders];
                let (mut st, mut sm) = (0.0, 0.0);
                for (k, r) in raw.iter_mut().enumerate() {
                    let am = x * c + f64::from(first + k as i32) * lam / d;
                    if 1.0 - am * am - beta * beta > 0.0 {
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
            row += 1;
        }
    }
    let grid = ReducedGrid {
        sin_theta_i: s,
        abs_beta: b,
        lambda_range_nm: band,
        lambda_nm: planes,
    };
    EfficiencyTable::new_reduced(d, first, grid, te, tm).unwrap()
}

/// One order's efficiency (read alone in the cells whose bound needs no normalisation) equals
/// its entry of the full normalised set to the bit, on reduced tables: the CD's planes and
/// random tables with sums close to 1, at queries over the band and beyond it (clamped).
#[test]
fn one_order_equals_its_entry_of_the_normalised_set() {
    let mut next = rng(13);
    let mut tables = vec![cd_planes(&[0.0, 0.3, 0.5], (360.0, 830.0 * cb(0.5)))];
    for _ in 0..40 {
        tables.push(near_unit_reduced(&mut next));
    }
    let (mut checked, mut normalised) = (0usize, 0usize);
    for t in &tables {
        let mut all = vec![Polarised::default(); t.order_count()];
        let (l0, l1) = t.lambda_range_nm();
        for q in 0..3000 {
            let wide = if q % 10 == 0 { 50.0 } else { 0.0 };
            let lam = l0 - wide + (l1 - l0 + 2.0 * wide) * next();
            let beta = 0.95 * next();
            let alpha = cb(beta) * (-1.0 + 2.0 * next());
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
                    one.te.to_bits() == all[k].te.to_bits()
                        && one.tm.to_bits() == all[k].tm.to_bits(),
                    "order {m} at α = {alpha}, β = {beta}, λ = {lam}: {one:?} alone, {:?} in the set",
                    all[k]
                );
                checked += 1;
            }
        }
    }
    println!("{checked} orders checked, {normalised} normalised queries");
    assert!(normalised > 1000, "{normalised} normalised queries");
    assert!(checked > 500_000, "{checked}");
}

/// A version-3 JSON table: two planes (|β| = 0 and 0.6) of one order over 400-700 nm.
#[cfg(feature = "serde")]
fn v3(edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let mut v = serde_json::json!({
        "format": "diffraction-efficiency-table", "version": 3, "name": "t", "description": "",
        "grating": {"profile": "lamellar", "period_nm": 1000.0},
        "sin_theta_i": [-0.5, 0.5], "abs_beta": [0.0, 0.6], "lambda_range_nm": [400.0, 700.0],
        "lambda_nm": [[400.0, 600.0, 875.0], [320.0, 700.0]],
        "order_min": 0, "order_max": 0,
        "te": [[[[0.9, 0.9], [0.9, 0.9], [0.9, 0.9]], [[0.9, 0.9], [0.9, 0.9]]]],
        "tm": [[[[0.8, 0.8], [0.8, 0.8], [0.8, 0.8]], [[0.8, 0.8], [0.8, 0.8]]]],
        "solver": {}, "validation": {}, "sha256": "0"
    });
    edit(&mut v);
    v.to_string()
}

#[cfg(feature = "serde")]
#[test]
fn version_3_files_load_and_bad_ones_name_the_field_and_element() {
    let t: EfficiencyTable = serde_json::from_str(&v3(|_| {})).unwrap();
    assert!(t.is_reduced());
    assert_eq!(
        t.plane_lambda_nm(0).collect::<Vec<_>>(),
        [400.0, 600.0, 875.0]
    );
    assert!((t.efficiency_conical(0, 0.1, 0.3, 550.0).te - 0.9).abs() < 1e-15);
    let err = |edit: fn(&mut serde_json::Value)| {
        serde_json::from_str::<EfficiencyTable>(&v3(edit))
            .unwrap_err()
            .to_string()
    };
    type Edit = fn(&mut serde_json::Value);
    let cases: [(Edit, &str); 10] = [
        (
            |v| v["lambda_nm"][1][1] = serde_json::Value::Null,
            "lambda_nm[1][1]: expected a number, got null",
        ),
        (
            |v| v["version"] = 4.into(),
            "version: expected 1, 2 or 3, got 4",
        ),
        (
            |v| v["version"] = 2.into(),
            "lambda_nm: one array of wavelengths per |beta| plane needs version 3, got version 2",
        ),
        (
            |v| v["lambda_nm"] = serde_json::json!([400.0, 875.0]),
            "lambda_nm: version 3 holds one array of wavelengths per |beta| plane",
        ),
        (
            |v| {
                v.as_object_mut().unwrap().remove("lambda_range_nm");
            },
            "missing field `lambda_range_nm`",
        ),
        (
            |v| v["lambda_range_nm"] = serde_json::json!([400.0]),
            "lambda_range_nm: expected [min, max], got 1 values",
        ),
        (
            |v| v["lambda_nm"][0][2] = 800.0.into(),
            "invalid lambda_nm = 800: must let plane 0 (lambda_nm[0]) reach from 400 to 875 nm",
        ),
        (
            |v| v["lambda_nm"][1] = serde_json::json!([700.0, 320.0]),
            "invalid lambda_nm = 320: must be in plane 1 (lambda_nm[1]): 2 to 4096 finite \
             wavelengths > 0, strictly increasing",
        ),
        (
            |v| v["te"][0][1] = serde_json::json!([[0.9, 0.9]]),
            "te: has shape [1][2][3,1][2], expected [1][2][3,2][2] ([order][plane][lambda of \
             the plane][sin])",
        ),
        (
            |v| v["tm"][0][0][2][1] = serde_json::json!("x"),
            "tm[0][0][2][1]: expected a number, got \"x\"",
        ),
    ];
    for (edit, want) in cases {
        let got = err(edit);
        assert!(got.starts_with(want), "{got}\n  expected: {want}");
    }
    // The planes' rows must match lambda_nm's.
    let got = err(|v| {
        v["lambda_nm"][0] = serde_json::json!([400.0, 875.0]);
    });
    assert!(
        got.starts_with(
            "te: has shape [1][2][3,2][2], expected [1][2][2,2][2] ([order][plane][lambda of the plane][sin])"
        ),
        "{got}"
    );
}

/// The GPU packs a reduced table's first plane as a classical table: the same words as the
/// classical table of that plane's own nodes and values (to one f32 rounding of the q's), but
/// no cell marked (a conical table's marks hold for its own reading), and header words 8 and 9
/// naming its planes and the section of them that follows (tests/gpu_wgsl.rs checks that).
#[cfg(feature = "gpu")]
#[test]
fn the_gpu_packs_the_first_plane() {
    use diffraction::gpu::pack_efficiency_table;
    let t = cd_planes(&[0.0, 0.3, 0.5], (360.0, 830.0 * cb(0.5)));
    let s: Vec<f64> = t.sin_theta_i().collect();
    let l: Vec<f64> = t.plane_lambda_nm(0).collect();
    assert_eq!(l, t.lambda_nm().collect::<Vec<_>>());
    // The first plane's values: the CD's at its own nodes (the planes were made of them).
    let cd = Preset::Cd.table();
    let n = cd.order_count() * s.len() * l.len();
    let (mut te, mut tm) = (vec![0.0; n], vec![0.0; n]);
    for (k, m) in cd.orders().enumerate() {
        for (j, &lam) in l.iter().enumerate() {
            for (i, &x) in s.iter().enumerate() {
                let e = cd.efficiency(m, x, lam);
                te[(k * l.len() + j) * s.len() + i] = e.te;
                tm[(k * l.len() + j) * s.len() + i] = e.tm;
            }
        }
    }
    let classical =
        EfficiencyTable::new(cd.period_nm(), *cd.orders().start(), s, l, te, tm).unwrap();
    let (a, b) = (
        pack_efficiency_table(&t).unwrap(),
        pack_efficiency_table(&classical).unwrap(),
    );
    assert_eq!((a[8], a[9], b[8], b[9]), (3.0, b.len() as f32, 0.0, 0.0));
    assert!(a.len() > b.len());
    let marks = b[6] as usize;
    let mut worst = 0.0f32;
    for (i, (x, y)) in a[..marks].iter().zip(&b[..marks]).enumerate() {
        if i != 8 && i != 9 {
            worst = worst.max((x - y).abs() / y.abs().max(1e-30));
        }
    }
    println!("first plane packed against its classical table: worst relative {worst:.2e}");
    assert!(worst <= 2.0 * f32::EPSILON, "{worst}");
    assert!(a[marks..b.len()].iter().all(|&w| w == 0.0));
}

/// `reduced_from_classical` of a bare grating (the foil): its planes map onto the classical
/// nodes, so wherever λ″ = λ/c stays in the band the table reads the classical table at
/// (α, λ)/c whatever β, to rounding; beyond the band (the extrapolation) and at any β its sums
/// stay in [0, 1], and at its nodes past the band they are the band edge's.
#[test]
fn a_bare_table_read_from_its_classical_one_is_the_reduced_reading() {
    use diffraction::relief::REDUCED_PLANES;
    let foil = Preset::Foil.table();
    let t = foil
        .reduced_from_classical(&REDUCED_PLANES, |_| 1.0)
        .unwrap();
    assert!(t.is_reduced());
    assert_eq!(t.abs_beta().collect::<Vec<_>>(), REDUCED_PLANES.to_vec());
    let n = foil.order_count();
    let (mut a, mut r) = (vec![Polarised::default(); n], vec![Polarised::default(); n]);
    let mut next = rng(31);
    let (mut worst, mut inside) = (0.0f64, 0);
    for _ in 0..20_000 {
        let beta = 0.99999 * next();
        let c = cb(beta);
        let sp = -0.999 + 1.998 * next();
        let lam = 300.0 + 600.0 * next();
        let total = t.efficiencies_conical(sp * c, beta, lam, &mut r);
        assert!(total.is_finite() && (0.0..=1.0).contains(&total), "{total}");
        if (360.0..=830.0).contains(&lam) && lam / c <= 830.0 {
            inside += 1;
            foil.efficiencies(sp, lam / c, &mut a);
            for (x, y) in a.iter().zip(&r) {
                worst = worst.max((x.te - y.te).abs()).max((x.tm - y.tm).abs());
            }
        }
    }
    println!("foil read from its classical table: worst {worst:.2e} over {inside} queries");
    assert!(inside > 5000);
    assert!(worst < tol::REDUCED_MAPPING, "{worst}");
    // Past the band a node holds the band edge's sums (the power of the orders cut off at its
    // own λ″ goes to the others) wherever an order propagates there. Planes up to |β| = 0.95:
    // nearer 1 every order leaves within cos θm = c·√(1 − (s′ + m·λ′/d)²) ≤ 10⁻³ of grazing
    // at some nodes, where the reading's rule counts it evanescent.
    let s: Vec<f64> = t.sin_theta_i().collect();
    let (mut nodes, mut worst) = (0, 0.0f64);
    for p in (0..REDUCED_PLANES.len()).filter(|&p| REDUCED_PLANES[p] <= 0.95) {
        let c = cb(REDUCED_PLANES[p]);
        for l in t
            .plane_lambda_nm(p)
            .filter(|&l| l / c > 830.0 * (1.0 + 1e-9))
        {
            for &sp in &s {
                let total = t.plane_efficiencies(p, sp, l, &mut r);
                if total == 0.0 {
                    continue;
                }
                nodes += 1;
                let edge = foil.efficiencies(sp, 830.0, &mut a);
                worst = worst.max((total - edge).abs());
            }
        }
    }
    println!("foil past its band: {nodes} nodes, sums within {worst:.2e} of the edge's");
    assert!(nodes > 100);
    assert!(worst < tol::REDUCED_MAPPING, "{worst}");
}

/// Under a cover the reduction is in the cover's medium, c = √(1 − β²/n²): on the plane
/// β = 0 the CD's reduced table is its classical table; off it, it reads the direct reduced
/// reading (the classical table at (α, λ)/c) within the second interpolation's error (the
/// planes' s′ nodes map onto s″ = s′·√(1 − β²)/c between the classical nodes).
/// Fresnel's power transmittances (TE, TM) from a medium of index `n` into air, for light
/// leaving at squared sine `sin2` in air.
fn transmittance(n: f64, sin2: f64) -> (f64, f64) {
    let ca = (1.0 - sin2).sqrt();
    let cn = (1.0 - sin2 / (n * n)).sqrt();
    let (ts, tp) = (2.0 * n * cn / (n * cn + ca), 2.0 * n * cn / (cn + n * ca));
    // T = |t|²·(cos θ in air)/(n·cos θ in the medium).
    (ts * ts * ca / (n * cn), tp * tp * ca / (n * cn))
}

/// The real path's unpolarised transmittance over the reduced problem's (index `n2` at λ″,
/// sine `red`), for TE and TM alike.
fn interfaces(n: f64, n2: f64, real2: f64, red: f64) -> (f64, f64) {
    let (a, b) = (transmittance(n, real2), transmittance(n2, red * red));
    let ratio = (a.0 + a.1) / (b.0 + b.1);
    (ratio, ratio)
}

#[test]
fn a_covered_table_reads_the_reduction_in_the_cover() {
    let cd = Preset::Cd.table();
    let t = Preset::Cd.reduced_table().unwrap();
    let n = cd.order_count();
    let (mut a, mut r) = (vec![Polarised::default(); n], vec![Polarised::default(); n]);
    let mut next = rng(32);
    let (mut on_plane, mut off_plane, mut count) = (0.0f64, 0.0f64, 0);
    let (mut sum, mut terms) = (0.0f64, 0usize);
    for k in 0..20_000 {
        let beta = if k % 4 == 0 { 0.0 } else { 0.95 * next() };
        let sp = -0.999 + 1.998 * next();
        let lam = 360.0 + 470.0 * next();
        let idx = Preset::Cd.cover_index(lam);
        let cc = (1.0 - (beta / idx) * (beta / idx)).sqrt();
        let alpha = sp * cb(beta);
        if lam / cc > 830.0 {
            continue;
        }
        count += 1;
        cd.efficiencies(alpha / cc, lam / cc, &mut a);
        // Trapped in the cover (propagating there, evanescent in air): 0. The others pass
        // the cover-air interface at their real direction instead of the reduced one.
        let n2 = Preset::Cd.cover_index(lam / cc);
        let into = interfaces(idx, n2, alpha * alpha + beta * beta, alpha / cc);
        for (m, x) in cd.orders().zip(a.iter_mut()) {
            let am = alpha + f64::from(m) * lam / cd.period_nm();
            if am * am + beta * beta >= 1.0 {
                *x = Polarised::default();
            } else {
                let out = interfaces(idx, n2, am * am + beta * beta, am / cc);
                x.te *= into.0 * out.0;
                x.tm *= into.1 * out.1;
            }
        }
        t.efficiencies_conical(alpha, beta, lam, &mut r);
        // Orders at least 0.2 in cos θm from their cut-off in air: nearer, the table's rule
        // (η/cos θm interpolated, then times the query's cos θm) and the direct reading part.
        let mut worst = 0.0f64;
        for (m, (x, y)) in cd.orders().zip(a.iter().zip(&r)) {
            let am = alpha + f64::from(m) * lam / cd.period_nm();
            if 1.0 - am * am - beta * beta > 0.04 {
                worst = worst.max((x.te - y.te).abs()).max((x.tm - y.tm).abs());
                if beta > 0.0 {
                    sum += (x.te - y.te).abs() + (x.tm - y.tm).abs();
                    terms += 2;
                }
            }
        }
        if beta == 0.0 {
            on_plane = on_plane.max(worst);
        } else {
            off_plane = off_plane.max(worst);
        }
    }
    let mean = sum / terms as f64;
    println!(
        "CD reduced in its cover: worst on the plane {on_plane:.2e}, off it {off_plane:.2e}, \
         mean {mean:.2e} ({count} queries)"
    );
    assert!(on_plane < tol::REDUCED_MAPPING, "{on_plane}");
    assert!(off_plane < tol::REDUCED_IN_THE_COVER, "{off_plane}");
    assert!(mean < tol::REDUCED_IN_THE_COVER_MEAN, "{mean}");
    // An order that propagates in the cover but not in air is 0: order 1 at β = 0.6,
    // λ = 600 nm leaves the air's circle at α = 0.8 − 600/1600 = 0.425.
    let (beta, lam) = (0.6, 600.0);
    assert_eq!(t.efficiency_conical(1, 0.43, beta, lam).te, 0.0);
    assert!(t.efficiency_conical(1, 0.40, beta, lam).te > 0.0);
}

#[test]
fn reading_a_table_reduced_refuses_bad_input_naming_it() {
    use diffraction::relief::REDUCED_PLANES;
    let foil = Preset::Foil.table();
    let conical = foil
        .reduced_from_classical(&REDUCED_PLANES, |_| 1.0)
        .unwrap();
    let e = conical
        .reduced_from_classical(&REDUCED_PLANES, |_| 1.0)
        .unwrap_err();
    assert_eq!(e.parameter(), "table");
    for bad in [f64::NAN, 0.5, f64::INFINITY] {
        let e = foil
            .reduced_from_classical(&REDUCED_PLANES, |_| bad)
            .unwrap_err();
        assert_eq!(e.parameter(), "cover_index", "{bad}");
    }
    for planes in [&[0.0][..], &[0.0, 1.0], &[0.5, 0.3], &[0.0, f64::NAN], &[]] {
        let e = foil.reduced_from_classical(planes, |_| 1.0).unwrap_err();
        assert_eq!(e.parameter(), "abs_beta", "{planes:?}");
    }
    // Too many planes for MAX_TABLE_VALUES: refused before any work (4000 planes of the CD,
    // 17 orders × 25 s′ × about 27 rows each).
    let many: Vec<f64> = (0..4000).map(|i| 0.9 * f64::from(i) / 4000.0).collect();
    let e = Preset::Cd
        .table()
        .reduced_from_classical(&many, |_| 1.0)
        .unwrap_err();
    assert_eq!(e.parameter(), "abs_beta");
    assert!(e.to_string().contains("MAX_TABLE_VALUES"), "{e}");
    // Two planes are enough; so is one starting above 0 (queries below it read it).
    assert!(foil
        .reduced_from_classical(&[0.0, 0.99999], |_| 1.0)
        .is_ok());
    assert!(foil.reduced_from_classical(&[0.4, 0.8], |_| 1.0).is_ok());
    for p in Preset::ALL {
        assert!(p.reduced_table().is_ok(), "{p}");
    }
}

/// A reduced table whose node spacings are subnormal (as tests/conical_surfaces_sweep.rs
/// checks for classical tables): an inner s′ interval of 10⁻³¹⁰, whose reciprocal width (the
/// locator's) overflows, and two planes 10⁻³¹⁰ apart in |β| (coincident in c). At s′ = 0
/// exactly the rule reads node 1's value (one order, no normalisation, order 0 at normal
/// incidence), not the next node's; every read is finite.
#[test]
fn reduced_tables_with_subnormal_spacings_are_read_by_the_rule() {
    let sin = vec![-0.5, 0.0, 1e-310, 0.5];
    let row = [0.5, 0.2, 0.6, 0.5];
    let grid = |abs_beta: Vec<f64>| ReducedGrid {
        sin_theta_i: sin.clone(),
        lambda_nm: vec![vec![400.0, 700.0]; abs_beta.len()],
        abs_beta,
        lambda_range_nm: (400.0, 700.0),
    };
    for planes in [vec![0.0, 1e-310], vec![0.0, 1e-310, 0.3]] {
        // With a third plane at |β| = 0.3 (flat 0.5), the second must reach 700 nm/c there
        // and the third down to 400 nm·c.
        let mut g = grid(planes.clone());
        if planes.len() == 3 {
            let c = (1.0f64 - 0.09).sqrt();
            g.lambda_nm[1] = vec![400.0, 700.0 / c];
            g.lambda_nm[2] = vec![400.0 * c, 700.0];
        }
        let mut te = Vec::new();
        for p in 0..planes.len() {
            for _ in 0..2 {
                if p < 2 {
                    te.extend(row);
                } else {
                    te.extend([0.5; 4]);
                }
            }
        }
        let t = EfficiencyTable::new_reduced(1000.0, 0, g, te.clone(), te).unwrap();
        for beta in [0.0, 1e-311, 1e-310, 0.1] {
            let e = t.efficiency_conical(0, 0.0, beta, 550.0).unpolarised();
            assert!(e.is_finite() && e > 0.0, "{planes:?} {beta}: {e}");
            if beta <= 1e-310 {
                assert!(
                    (e - 0.2).abs() < tol::INTERPOLATION,
                    "{planes:?} {beta}: {e}"
                );
            }
        }
        for alpha in [1e-311, 5e-311, 1e-310, 2e-310, -1e-311] {
            let e = t.efficiency_conical(0, alpha, 0.0, 550.0).unpolarised();
            assert!((0.2..=0.6).contains(&e), "{planes:?} {alpha}: {e}");
        }
    }
}
