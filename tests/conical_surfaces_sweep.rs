//! The sweep of the conical input surfaces: random and adversarial inputs to
//! `EfficiencyTable::new_conical` (version 2) and `new_reduced` (version 3), their JSON reader,
//! their queries (`efficiencies_conical`, `efficiency_conical`, `plane_efficiencies`) at every
//! extreme direction (grazing, |β| → 1, exactly on nodes, α² + β² ≥ 1, subnormals), the
//! tabulated `GratingBsdf` built on them (`eval`, `eval4`, `pdf`, `pdf4`, `sample`, `sample4`,
//! `albedo`), and the classical table's fast reading through the same BSDF at its own extremes
//! (exactly on cell boundaries, on Rayleigh lines, at and past the table's edges), and that
//! table read reduced (`reduced_from_classical`, random planes and covers) through the same
//! queries and BSDF.
//!
//! Every accepted input must give finite, non-negative outputs with Σ η ≤ 1, sample weights
//! within `sample_weight_bound`, f reciprocal and `eval4`/`pdf4` equal to `eval`/`pdf` at each
//! wavelength; every refused one a short message starting with the field it names. Work is
//! bounded by the tables' documented caps (a hostile JSON array is refused as soon as it
//! passes them, which the huge-array cases check by their refusals' messages).
//!
//! `sweep` (CI: about a second in release) draws [`QUICK_CASES`] cases; `sweep_long` (ignored:
//! `cargo test --release --all-features --test conical_surfaces_sweep -- --ignored`) draws a
//! hundred times as many from another seed. Each prints its tally: calls per surface, accepted
//! and refused.
#![cfg(feature = "serde")]

use std::sync::Arc;

use diffraction::glam::DVec3;
use diffraction::grating_bsdf::{OrderEfficiency, MAX_TABULATED_ORDERS};
use diffraction::relief::{
    EfficiencyTable, Polarised, Preset, ReducedGrid, MAX_TABLE_ABS_BETA, MAX_TABLE_NODES,
};
use diffraction::{Bsdf, DiffractionBrdf, Grating, GratingBsdf, SampledWavelengths};

#[path = "support/rng.rs"]
mod rng;
use rng::Rng;
#[path = "support/sweep.rs"]
mod sweep;
use sweep::{MAX_MESSAGE, SUM_ROUNDING};

/// Cases drawn by the quick sweep.
const QUICK_CASES: usize = 300;
/// How far a sample's weight may exceed `sample_weight_bound`, relative: the rounding of the
/// weight's and the bound's products (as in tests/surfaces_sweep.rs).
const WEIGHT_ROUNDING: f64 = 1e-9;
/// How far a weight may exceed a bound of 0, absolute: with a subnormal efficiency in a table
/// (10⁻³¹⁰ at a node) the bound's product underflows to 0 while the sample's own weight keeps
/// 7·10⁻³⁰⁷ (measured in the long sweep); far below any weight that carries light.
const WEIGHT_UNDERFLOW: f64 = 1e-290;
/// `eval4`/`pdf4` against `eval`/`pdf` at each wavelength, relative: the same arithmetic,
/// shared between wavelengths (a few ulps).
const FOUR_ROUNDING: f64 = 1e-12;

/// Values that break arithmetic: subnormals, the ends of the range, exact grid values.
const EXTREMES: [f64; 16] = [
    0.0,
    -0.0,
    5e-324,
    1e-310,
    f64::MIN_POSITIVE,
    1e-300,
    1e-17,
    0.5,
    1.0,
    -1.0,
    1e300,
    f64::MAX,
    0.9999,
    MAX_TABLE_ABS_BETA,
    0.999_999_999_999_999_9,
    999.9995,
];

#[derive(Debug, Default)]
struct Tally {
    conical_built: u64,
    conical_refused: u64,
    reduced_built: u64,
    reduced_refused: u64,
    queries: u64,
    plane_queries: u64,
    json_accepted: u64,
    json_refused: u64,
    bsdf_calls: u64,
    bsdf_refused: u64,
    classical_bsdf_calls: u64,
    from_classical_built: u64,
    from_classical_refused: u64,
}

/// A number from [`EXTREMES`], or random in a range, or a random bit pattern's float.
fn value(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    sweep::value(r, &EXTREMES, lo, hi)
}

/// A strictly increasing axis in [lo, hi] most of the time (sometimes not, or with a node
/// replaced by an extreme value: the checks must refuse it).
fn axis(r: &mut Rng, lo: f64, hi: f64, ends: bool) -> Vec<f64> {
    let n = 2 + (r.next_u64() % 4) as usize;
    let mut v: Vec<f64> = (0..n).map(|_| lo + (hi - lo) * r.next_f64()).collect();
    if ends {
        v[0] = lo;
        v[n - 1] = hi;
    }
    if r.next_u64() % 6 != 0 {
        v.sort_by(f64::total_cmp);
        v.dedup();
    }
    if r.next_u64() % 10 == 0 {
        let k = (r.next_u64() % v.len() as u64) as usize;
        v[k] = value(r, lo, hi);
    }
    v
}

/// The next float above x (finite x; `f64::next_up` needs Rust 1.86, above the MSRV).
fn up(x: f64) -> f64 {
    if x == 0.0 {
        return 5e-324;
    }
    let b = x.to_bits();
    f64::from_bits(if x > 0.0 { b + 1 } else { b - 1 })
}

/// The next float below x (finite x).
fn down(x: f64) -> f64 {
    -up(-x)
}

/// c = √(1 − β²).
fn cb(b: f64) -> f64 {
    (1.0 - b * b).sqrt()
}

/// Values of `orders` orders for nodes (s′, |β|, λ) listed by `nodes`: below 1/orders where
/// the order propagates at the node, 0 where it does not; sometimes one value corrupted.
fn values(
    r: &mut Rng,
    period: f64,
    order_min: i32,
    orders: usize,
    nodes: &[(f64, f64, f64)],
) -> Vec<f64> {
    let mut v = Vec::with_capacity(orders * nodes.len());
    for k in 0..orders {
        let m = f64::from(order_min) + k as f64;
        for &(s, b, l) in nodes {
            let am = s * cb(b) + m * l / period;
            v.push(if 1.0 - am * am - b * b > 0.0 {
                r.next_f64() / orders as f64
            } else {
                0.0
            });
        }
    }
    if r.next_u64() % 10 == 0 {
        let k = (r.next_u64() % v.len() as u64) as usize;
        v[k] = value(r, 0.0, 1.0);
    }
    v
}

/// Checks a refusal: it names a parameter, and its message is short.
fn check_refusal(e: &diffraction::Error) {
    assert!(!e.parameter().is_empty(), "{e}");
    assert!(e.to_string().len() < MAX_MESSAGE, "{e}");
    assert!(e.to_string().contains(e.parameter()), "{e}");
}

fn period(r: &mut Rng) -> f64 {
    if r.next_u64() % 5 == 0 {
        value(r, 100.0, 1e5)
    } else {
        300.0 + 3000.0 * r.next_f64()
    }
}

/// A random version-2 table: mostly accepted, sometimes corrupted.
fn random_conical(r: &mut Rng, tally: &mut Tally) -> Option<EfficiencyTable> {
    let d = period(r);
    let s = axis(r, -1.0, 1.0, false);
    let ends = r.next_u64() % 3 == 0;
    let b = axis(r, 0.0, MAX_TABLE_ABS_BETA, ends);
    let l = axis(r, 300.0, 1200.0, false);
    let orders = 1 + (r.next_u64() % 7) as usize;
    let order_min = -((r.next_u64() % 5) as i32);
    let mut nodes = vec![];
    for &bb in &b {
        for &ll in &l {
            for &ss in &s {
                nodes.push((ss, bb, ll));
            }
        }
    }
    let te = values(r, d, order_min, orders, &nodes);
    let mut tm: Vec<f64> = te.iter().map(|x| 0.9 * x).collect();
    if r.next_u64() % 20 == 0 {
        tm.pop();
    }
    match EfficiencyTable::new_conical(d, order_min, s, b, l, te, tm) {
        Ok(t) => {
            tally.conical_built += 1;
            assert!(t.is_conical() && !t.is_reduced());
            Some(t)
        }
        Err(e) => {
            tally.conical_refused += 1;
            check_refusal(&e);
            None
        }
    }
}

/// A random version-3 grid: each plane reaching what it must (sometimes short of it, empty,
/// or one plane too few).
fn random_grid(r: &mut Rng) -> ReducedGrid {
    let sin_theta_i = axis(r, -1.0, 1.0, false);
    let ends = r.next_u64() % 3 == 0;
    let abs_beta = axis(r, 0.0, MAX_TABLE_ABS_BETA, ends);
    let l0 = 300.0 + 300.0 * r.next_f64();
    let band = if r.next_u64() % 12 == 0 {
        (value(r, 0.0, 1000.0), value(r, 0.0, 1000.0))
    } else {
        (l0, l0 + 1.0 + 600.0 * r.next_f64())
    };
    let mut grid = ReducedGrid {
        sin_theta_i,
        abs_beta,
        lambda_range_nm: band,
        lambda_nm: vec![],
    };
    for p in 0..grid.abs_beta.len() {
        let (lo, hi) = grid.plane_reach_nm(p).unwrap();
        let mut nodes = if lo.is_finite() && hi.is_finite() && lo < hi {
            axis(r, lo, hi, true)
        } else {
            vec![lo, hi]
        };
        match r.next_u64() % 30 {
            0 => nodes.clear(),
            1 => nodes.truncate(1),
            2 => *nodes.last_mut().unwrap() *= 0.99,
            _ => {}
        }
        grid.lambda_nm.push(nodes);
    }
    if r.next_u64() % 30 == 0 {
        grid.lambda_nm.pop();
    }
    grid
}

/// A random version-3 table: mostly accepted, sometimes corrupted.
fn random_reduced(r: &mut Rng, tally: &mut Tally) -> Option<EfficiencyTable> {
    let d = period(r);
    let grid = random_grid(r);
    let orders = 1 + (r.next_u64() % 7) as usize;
    let order_min = -((r.next_u64() % 5) as i32);
    let mut nodes = vec![];
    for (&b, plane) in grid.abs_beta.iter().zip(&grid.lambda_nm) {
        for &l in plane {
            for &s in &grid.sin_theta_i {
                nodes.push((s, b, l));
            }
        }
    }
    let te = if nodes.is_empty() {
        vec![0.5; orders]
    } else {
        values(r, d, order_min, orders, &nodes)
    };
    let tm: Vec<f64> = te.iter().map(|x| 0.8 * x).collect();
    match EfficiencyTable::new_reduced(d, order_min, grid, te, tm) {
        Ok(t) => {
            tally.reduced_built += 1;
            assert!(t.is_conical() && t.is_reduced());
            Some(t)
        }
        Err(e) => {
            tally.reduced_refused += 1;
            check_refusal(&e);
            None
        }
    }
}

/// The extreme incidences of a conical table: on its nodes (α = s′·√(1 − β²) exactly as the
/// table computes it, a subnormal step off), grazing, |β| → 1, α² + β² ≥ 1, and random ones.
fn directions(r: &mut Rng, t: &EfficiencyTable) -> Vec<(f64, f64)> {
    let s: Vec<f64> = t.sin_theta_i().collect();
    let b: Vec<f64> = t.abs_beta().collect();
    let pick = |r: &mut Rng, v: &[f64]| v[(r.next_u64() % v.len() as u64) as usize];
    let (sn, bn) = (pick(r, &s), pick(r, &b));
    let on = sn * cb(bn);
    let sign = if r.next_u64() % 2 == 0 { 1.0 } else { -1.0 };
    let b_rand = value(r, -1.0, 1.0);
    vec![
        (on, sign * bn),
        (on + 5e-324, bn),
        (up(on), down(bn)),
        (cb(bn), bn),
        (down(cb(bn)), bn),
        (0.0, 1.0),
        (0.0, down(1.0)),
        (0.0, -(down(1.0))),
        (1e-300, 0.999_999_999),
        (0.8, 0.6),
        (up(0.6), 0.8),
        (5e-324, 5e-324),
        (-1.0, 0.0),
        (value(r, -1.0, 1.0), b_rand),
        (value(r, -1.0, 1.0), sign * bn),
        (f64::MAX, 0.0),
    ]
}

/// The wavelengths of a query: a node, the band's ends and a step past them, extremes.
fn wavelengths(r: &mut Rng, t: &EfficiencyTable) -> [f64; 5] {
    let (l0, l1) = t.lambda_range_nm();
    [
        l0,
        up(l1),
        l0 * 0.5,
        value(r, l0, l1),
        value(r, 100.0, 2000.0),
    ]
}

/// One query of a conical table: every order finite and ≥ 0, Σ ≤ 1, each single order as its
/// entry's bounds.
fn check_query(t: &EfficiencyTable, alpha: f64, beta: f64, lambda: f64, tally: &mut Tally) {
    let mut out = vec![Polarised::default(); t.order_count()];
    let total = t.efficiencies_conical(alpha, beta, lambda, &mut out);
    tally.queries += 1;
    let repro = || format!("{t:?} at α = {alpha:e}, β = {beta:e}, λ = {lambda:e}");
    assert!(
        total.is_finite() && (0.0..=1.0 + SUM_ROUNDING).contains(&total),
        "{total}: {}",
        repro()
    );
    let te: f64 = out.iter().map(|e| e.te).sum();
    let tm: f64 = out.iter().map(|e| e.tm).sum();
    assert!(
        te <= 1.0 + SUM_ROUNDING && tm <= 1.0 + SUM_ROUNDING,
        "{te} {tm}: {}",
        repro()
    );
    for e in &out {
        assert!(
            e.te.is_finite() && e.te >= 0.0 && e.tm.is_finite() && e.tm >= 0.0,
            "{e:?}: {}",
            repro()
        );
    }
    if alpha * alpha + beta * beta >= 1.0 || !(alpha.is_finite() && beta.is_finite()) {
        assert_eq!(total, 0.0, "{}", repro());
    }
    let m = t.orders().start() + (alpha.to_bits() % t.order_count() as u64) as i32;
    let one = t.efficiency_conical(m, alpha, beta, lambda);
    assert!(
        one.te.is_finite() && one.te >= 0.0 && one.tm.is_finite() && one.tm >= 0.0,
        "{one:?}: {}",
        repro()
    );
    assert!(
        one.te <= 1.0 + SUM_ROUNDING && one.tm <= 1.0 + SUM_ROUNDING,
        "{one:?}: {}",
        repro()
    );
}

/// One plane of a reduced table read alone.
fn check_plane(t: &EfficiencyTable, plane: usize, s: f64, lambda: f64, tally: &mut Tally) {
    let mut out = vec![Polarised::default(); t.order_count()];
    let total = t.plane_efficiencies(plane, s, lambda, &mut out);
    tally.plane_queries += 1;
    assert!(
        total.is_finite() && (0.0..=1.0 + SUM_ROUNDING).contains(&total),
        "{total}: {t:?} plane {plane} at {s:e}, {lambda:e}"
    );
    for e in &out {
        assert!(e.te.is_finite() && e.te >= 0.0 && e.tm.is_finite() && e.tm >= 0.0);
    }
}

/// A unit direction with x = `x`, y = `y` above the surface (z from the rest), or `None`.
fn dir(x: f64, y: f64) -> Option<DVec3> {
    let z2 = 1.0 - x * x - y * y;
    (x.is_finite() && y.is_finite() && z2 >= 0.0).then(|| DVec3::new(x, y, z2.sqrt()))
}

/// Every BSDF method at (wo, wi, λ): finite and ≥ 0, f reciprocal, `eval4`/`pdf4` equal to
/// `eval`/`pdf` at each wavelength, sample weights within the bound, albedo ≤ 1.
fn check_bsdf(b: &GratingBsdf, wo: DVec3, wi: DVec3, r: &mut Rng, albedo: bool) -> u64 {
    let ls = SampledWavelengths::sample_visible(r.next_f64());
    let lambda = [ls.hero(), value(r, 360.0, 830.0)][(r.next_u64() % 2) as usize];
    let repro = || format!("{b:?} wo = {wo:?}, wi = {wi:?}, λ = {lambda:e}");
    let f = b.eval(wo, wi, lambda);
    let p = b.pdf(wo, wi, lambda);
    assert!(
        f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
        "{f} {p}: {}",
        repro()
    );
    let back = b.eval(wi, wo, lambda);
    assert!(
        (f - back).abs() <= FOUR_ROUNDING * f.max(back),
        "f = {f}, reversed {back}: {}",
        repro()
    );
    let (f4, p4) = (b.eval4(wo, wi, &ls), b.pdf4(wo, wi, &ls));
    for (k, &l) in ls.lambda().iter().enumerate() {
        let (f1, p1) = (b.eval(wo, wi, l), b.pdf(wo, wi, l));
        assert!(
            (f4[k] - f1).abs() <= FOUR_ROUNDING * f1.max(f4[k])
                && (p4[k] - p1).abs() <= FOUR_ROUNDING * p1.max(p4[k]),
            "eval4 {f4:?} pdf4 {p4:?} at {:?} against {f1} {p1}: {}",
            ls.lambda(),
            repro()
        );
    }
    let bound = b.sample_weight_bound(wo, lambda);
    assert!(bound.is_finite() && bound >= 0.0, "{bound}: {}", repro());
    if let Some(x) = b.sample(wo, lambda, r.next_f64(), r.u2()) {
        let w = x.weight();
        assert!(
            w.is_finite() && w >= 0.0 && w <= bound * (1.0 + WEIGHT_ROUNDING) + WEIGHT_UNDERFLOW,
            "{w} > {bound}: {}",
            repro()
        );
        assert!(x.pdf.is_finite() && x.pdf >= 0.0 && x.f.is_finite() && x.f >= 0.0);
    }
    // The tabulated albedo integrates every order lobe by lobe: once per table.
    if albedo {
        if let Some(a) = b.albedo(wo, lambda) {
            assert!(
                a.is_finite() && (0.0..=1.0 + SUM_ROUNDING).contains(&a),
                "albedo {a}: {}",
                repro()
            );
        }
    }
    let hero_bound = b.sample_weight_bound(wo, ls.hero());
    if let Some(x) = b.sample4(wo, &ls, r.next_f64(), r.u2()) {
        for (k, w) in x.weight().values().into_iter().enumerate() {
            assert!(w.is_finite() && w >= 0.0, "sample4 weight {w}: {}", repro());
            if k == 0 {
                assert!(
                    w <= hero_bound * (1.0 + WEIGHT_ROUNDING) + WEIGHT_UNDERFLOW,
                    "{w} > {hero_bound}: {}",
                    repro()
                );
            }
        }
        for v in x.f.values().into_iter().chain(x.pdf.values()) {
            assert!(v.is_finite() && v >= 0.0, "sample4 {x:?}: {}", repro());
        }
    }
    7
}

/// The BSDF on a table, and its methods at extreme pairs of directions (the table's nodes as
/// incidences, grazing, the pole of |β| → 1) and random ones.
fn sweep_bsdf(t: &Arc<EfficiencyTable>, r: &mut Rng, case: usize, tally: &mut Tally) {
    if t.order_count() > MAX_TABULATED_ORDERS {
        return;
    }
    let slits = [1u32, 34, 1000, u32::MAX][case % 4];
    let g = Grating::new(1600.0, 800.0, slits).unwrap();
    let e = OrderEfficiency::from_table(t.clone()).unwrap();
    let b = match GratingBsdf::new(g).with_efficiency(e) {
        Ok(b) => b,
        Err(e) => {
            assert_eq!(e.parameter(), "slit_width_nm", "{t:?}");
            tally.bsdf_refused += 1;
            return;
        }
    };
    let mut cases: Vec<(DVec3, DVec3)> = vec![(r.direction(1e-3), r.direction(1e-3))];
    for (a, beta) in directions(r, t).into_iter().take(12) {
        // The incident direction of travel (α, β) is −wi's tangent part.
        if let Some(wi) = dir(-a, -beta) {
            cases.push((r.direction(1e-6), wi));
        }
    }
    cases.push((DVec3::Z, DVec3::new(1.0, 0.0, 0.0)));
    cases.push((DVec3::new(0.0, down(1.0), 2e-8), DVec3::Z));
    for (k, (wo, wi)) in cases.into_iter().enumerate() {
        tally.bsdf_calls += check_bsdf(&b, wo, wi, r, k == 0);
    }
}

/// The classical table's fast reading through the BSDF: incidences exactly on the table's
/// nodes and a subnormal step off them, on the Rayleigh lines of its orders at a node
/// wavelength, at and past its edges, and wavelengths at the nodes and past the ends.
fn sweep_classical(t: &Arc<EfficiencyTable>, r: &mut Rng, tally: &mut Tally) {
    let e = OrderEfficiency::from_table(t.clone()).unwrap();
    let g = Grating::new(1600.0, 800.0, [30, 1000][(r.next_u64() % 2) as usize]).unwrap();
    let Ok(b) = GratingBsdf::new(g).with_efficiency(e) else {
        return;
    };
    let s: Vec<f64> = t.sin_theta_i().collect();
    let l: Vec<f64> = t.lambda_nm().collect();
    let d = t.period_nm();
    let pick = |r: &mut Rng, v: &[f64]| v[(r.next_u64() % v.len() as u64) as usize];
    let (sn, ln) = (pick(r, &s), pick(r, &l));
    let m = f64::from(*t.orders().start()) + (r.next_u64() % t.order_count() as u64) as f64;
    // α on order m's Rayleigh lines at λ = ln: α + m·λ/d = ±1.
    let rayleigh = [1.0 - m * ln / d, -1.0 - m * ln / d];
    let mut alphas = vec![
        sn,
        up(sn),
        sn + 5e-324,
        s[0],
        s[s.len() - 1],
        down(s[0]),
        up(s[s.len() - 1]),
        rayleigh[0],
        rayleigh[1],
        down(rayleigh[0]),
        value(r, -1.0, 1.0),
    ];
    alphas.retain(|a| a.abs() < 1.0);
    let lambdas = [ln, l[0], l[l.len() - 1], down(l[0]), up(l[l.len() - 1])];
    for &a in &alphas {
        let Some(wi) = dir(-a, 0.0) else { continue };
        let wo = match r.next_u64() % 3 {
            // The specular pair: u = 0 (order 0's peak).
            0 => DVec3::new(a, 0.0, wi.z),
            1 => dir(pick(r, &alphas), 0.0).unwrap_or(DVec3::Z),
            _ => r.direction(1e-3),
        };
        let lambda = pick(r, &lambdas);
        let f = b.eval(wo, wi, lambda);
        let p = b.pdf(wo, wi, lambda);
        assert!(
            f.is_finite() && f >= 0.0 && p.is_finite() && p >= 0.0,
            "{t:?} {wo} {wi} {lambda}"
        );
        assert_eq!(f, b.eval(wi, wo, lambda), "{t:?} {wo} {wi} {lambda}");
        let bound = b.sample_weight_bound(wo, lambda);
        if let Some(x) = b.sample(wo, lambda, r.next_f64(), r.u2()) {
            let w = x.weight();
            assert!(
                w.is_finite()
                    && w >= 0.0
                    && w <= bound * (1.0 + WEIGHT_ROUNDING) + WEIGHT_UNDERFLOW,
                "{w} > {bound}: {t:?} {wo} {lambda}"
            );
        }
        tally.classical_bsdf_calls += 4;
        tally.bsdf_calls += check_bsdf(&b, wo, wi, r, a == alphas[0]);
    }
}

/// A random classical table (values below 1/orders where the order propagates).
fn random_classical(r: &mut Rng) -> Option<EfficiencyTable> {
    let d = 300.0 + 3000.0 * r.next_f64();
    let mut s = axis(r, -1.0, 1.0, false);
    let mut l = axis(r, 300.0, 1200.0, false);
    // Subnormal node spacings (the fast reading's bins would overflow).
    match r.next_u64() % 12 {
        0 => s = vec![0.0, 1e-310],
        1 => s = vec![-0.5, 0.0, 5e-324, 0.5],
        2 => l = vec![5e-324, 1e-323],
        3 => l = vec![1e-310, 2e-310, 600.0],
        _ => {}
    }
    let orders = 1 + (r.next_u64() % 7) as usize;
    let order_min = -((r.next_u64() % 5) as i32);
    let mut nodes = vec![];
    for &ll in &l {
        for &ss in &s {
            nodes.push((ss, 0.0, ll));
        }
    }
    let te = values(r, d, order_min, orders, &nodes);
    let tm: Vec<f64> = te.iter().map(|x| 0.9 * x).collect();
    EfficiencyTable::new(d, order_min, s, l, te, tm).ok()
}

/// The good version-2 and version-3 files the hostile ones are made from.
const V2: &str = r#"{"format": "diffraction-efficiency-table", "version": 2, "grating": {"period_nm": 1000.0}, "sin_theta_i": [-0.5, 0.5], "abs_beta": [0.0, 0.6], "lambda_nm": [500.0, 600.0], "order_min": 0, "order_max": 0, "te": [[[[0.9, 0.9], [0.9, 0.9]], [[0.5, 0.5], [0.5, 0.25]]]], "tm": [[[[0.8, 0.8], [0.8, 0.8]], [[0.5, 0.5], [0.5, 0.5]]]]}"#;
const V3: &str = r#"{"format": "diffraction-efficiency-table", "version": 3, "grating": {"period_nm": 1000.0}, "sin_theta_i": [-0.5, 0.5], "abs_beta": [0.0, 0.6], "lambda_range_nm": [400.0, 700.0], "lambda_nm": [[400.0, 875.0], [320.0, 500.0, 700.0]], "order_min": 0, "order_max": 0, "te": [[[[0.9, 0.9], [0.9, 0.9]], [[0.5, 0.5], [0.5, 0.5], [0.5, 0.25]]]], "tm": [[[[0.8, 0.8], [0.8, 0.8]], [[0.5, 0.5], [0.5, 0.5], [0.5, 0.5]]]]}"#;

/// Structural edits of a good file: wrong versions, β outside [0, 1), unsorted or duplicate
/// axes, planes of mismatched sizes, empty planes.
const EDITS: [(&str, &str); 22] = [
    ("\"version\": 2", "\"version\": 3"),
    ("\"version\": 3", "\"version\": 2"),
    ("\"version\": 2", "\"version\": 1"),
    ("\"version\": 3", "\"version\": 1"),
    ("\"version\": 2", "\"version\": 4"),
    ("\"version\": 3", "\"version\": \"3\""),
    ("[0.0, 0.6]", "[0.0, 1.0]"),
    ("[0.0, 0.6]", "[-0.1, 0.6]"),
    ("[0.0, 0.6]", "[0.6, 0.0]"),
    ("[0.0, 0.6]", "[0.6, 0.6]"),
    ("[0.0, 0.6]", "[0.0]"),
    ("[0.0, 0.6]", "[]"),
    ("[0.0, 0.6]", "[0.0, 0.6, 0.8]"),
    ("[[400.0, 875.0], ", "[[], "),
    ("[[400.0, 875.0], ", ""),
    ("[[400.0, 875.0], ", "[[400.0, 875.0], [400.0, 875.0], "),
    ("[320.0, 500.0, 700.0]", "[320.0, 700.0]"),
    ("[[0.9, 0.9], [0.9, 0.9]]", "[[0.9, 0.9], [0.9]]"),
    ("[[0.9, 0.9], [0.9, 0.9]]", "[]"),
    ("[500.0, 600.0]", "[[500.0, 600.0], [500.0, 600.0]]"),
    ("[400.0, 700.0]", "[700.0, 400.0]"),
    ("[400.0, 700.0]", "[400.0, 700.0, 800.0]"),
];

/// Tokens put in place of one number.
const TOKENS: [&str; 16] = [
    "null",
    "1e400",
    "-0",
    "[]",
    "{}",
    "\"NaN\"",
    "\"inf\"",
    "NaN",
    "9223372036854775807",
    "-9223372036854775809",
    "[[[]]]",
    "true",
    "5e-324",
    "0.99999",
    "1.0",
    "[0.5, 0.5]",
];

/// A hostile file: a good one with a structural edit, or a number replaced by a hostile
/// token, or cut.
fn hostile_json(r: &mut Rng) -> String {
    let good = [V2, V3][(r.next_u64() % 2) as usize];
    match r.next_u64() % 4 {
        0 => good[..(r.next_u64() % good.len() as u64) as usize].to_string(),
        1 => {
            let (a, b) = EDITS[(r.next_u64() % EDITS.len() as u64) as usize];
            good.replacen(a, b, 1)
        }
        _ => {
            let bytes = good.as_bytes();
            let mut numbers = vec![];
            let mut i = 0;
            while i < bytes.len() {
                if bytes[i].is_ascii_digit() || bytes[i] == b'-' {
                    let start = i;
                    while i < bytes.len()
                        && (bytes[i].is_ascii_digit() || b"-.e".contains(&bytes[i]))
                    {
                        i += 1;
                    }
                    numbers.push((start, i));
                }
                i += 1;
            }
            let (a, b) = numbers[(r.next_u64() % numbers.len() as u64) as usize];
            let t = TOKENS[(r.next_u64() % TOKENS.len() as u64) as usize];
            format!("{}{t}{}", &good[..a], &good[b..])
        }
    }
}

/// The field names a refusal may start with (or serde's own words for a whole-file problem,
/// or the typed error's `invalid <field>`).
const FIELDS: [&str; 17] = [
    "format",
    "version",
    "grating",
    "sin_theta_i",
    "abs_beta",
    "lambda_nm",
    "lambda_range_nm",
    "order_min",
    "order_max",
    "te",
    "tm",
    "invalid ",
    "missing field",
    "duplicate field",
    "EOF",
    "expected",
    "trailing",
];

/// Reads a JSON text: an accepted table is queried at its extremes, a refusal must name a
/// field.
fn check_json(text: &str, r: &mut Rng, tally: &mut Tally) {
    match serde_json::from_str::<EfficiencyTable>(text) {
        Ok(t) => {
            tally.json_accepted += 1;
            for (a, b) in directions(r, &t) {
                check_query(&t, a, b, 550.0, tally);
            }
        }
        Err(e) => {
            tally.json_refused += 1;
            let e = e.to_string();
            assert!(e.len() < MAX_MESSAGE, "{text}: {e}");
            assert!(FIELDS.iter().any(|f| e.starts_with(f)), "{text}: {e}");
        }
    }
}

fn sweep_with(cases: usize, seed: u64) {
    let mut r = Rng::new(seed);
    let mut tally = Tally::default();
    // Both good files load.
    for good in [V2, V3] {
        let t: EfficiencyTable = serde_json::from_str(good).unwrap();
        assert!(t.is_conical());
    }
    let presets: Vec<Arc<EfficiencyTable>> = Preset::ALL
        .iter()
        .map(|p| Arc::new(p.table().clone()))
        .collect();
    for case in 0..cases {
        let tables = [
            random_conical(&mut r, &mut tally),
            random_reduced(&mut r, &mut tally),
        ];
        for t in tables.into_iter().flatten() {
            let t = Arc::new(t);
            for lambda in wavelengths(&mut r, &t) {
                for (a, b) in directions(&mut r, &t) {
                    check_query(&t, a, b, lambda, &mut tally);
                }
            }
            if t.is_reduced() {
                let planes = t.abs_beta().len();
                for p in [0, planes - 1, planes, usize::MAX] {
                    let l: Vec<f64> = t.plane_lambda_nm(p).collect();
                    let lam = l.first().copied().unwrap_or(500.0);
                    for s in [-1.0, 1.0, 5e-324, value(&mut r, -1.0, 1.0)] {
                        check_plane(&t, p, s, lam, &mut tally);
                        check_plane(&t, p, s, value(&mut r, 100.0, 2000.0), &mut tally);
                    }
                }
            }
            sweep_bsdf(&t, &mut r, case, &mut tally);
        }
        let text = hostile_json(&mut r);
        check_json(&text, &mut r, &mut tally);
        // The classical fast reading: a preset or a random classical table.
        let classical = match random_classical(&mut r) {
            Some(t) if case % 2 == 0 => Arc::new(t),
            _ => presets[case % presets.len()].clone(),
        };
        sweep_classical(&classical, &mut r, &mut tally);
        // The same table read reduced, with random planes and a random cover.
        if let Some(t) = from_classical(&classical, &mut r, &mut tally) {
            let t = Arc::new(t);
            for lambda in wavelengths(&mut r, &t) {
                for (a, b) in directions(&mut r, &t) {
                    check_query(&t, a, b, lambda, &mut tally);
                }
            }
            sweep_bsdf(&t, &mut r, case, &mut tally);
        }
    }
    println!("{cases} cases (seed {seed:#x}): {tally:?}");
    assert!(
        tally.conical_built > 0 && tally.conical_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.reduced_built > 0 && tally.reduced_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.json_accepted > 0 && tally.json_refused > 0,
        "{tally:?}"
    );
    assert!(
        tally.bsdf_calls > 0 && tally.classical_bsdf_calls > 0,
        "{tally:?}"
    );
    assert!(
        tally.from_classical_built > 0 && tally.from_classical_refused > 0,
        "{tally:?}"
    );
}

/// `reduced_from_classical` of `t` at random planes (the default ones, a random axis, or one
/// with extreme values) and a random cover index (1, polycarbonate, a constant up to 4, or a
/// bad one: NaN, below 1, infinite): a table, or a refusal naming its field.
fn from_classical(t: &EfficiencyTable, r: &mut Rng, tally: &mut Tally) -> Option<EfficiencyTable> {
    let planes = match r.next_u64() % 3 {
        0 => diffraction::relief::REDUCED_PLANES.to_vec(),
        1 => axis(r, 0.0, MAX_TABLE_ABS_BETA, false),
        _ => vec![0.0, value(r, 0.0, 1.0)],
    };
    let constant = 1.0 + 3.0 * r.next_f64();
    let bad = [f64::NAN, 0.5, f64::INFINITY][(r.next_u64() % 3) as usize];
    let kind = r.next_u64() % 8;
    let index = move |l: f64| match kind {
        0..=2 => 1.0,
        3..=4 => diffraction::relief::polycarbonate_index(l),
        5..=6 => constant,
        _ => bad,
    };
    match t.reduced_from_classical(&planes, index) {
        Ok(reduced) => {
            assert!(reduced.is_reduced());
            tally.from_classical_built += 1;
            Some(reduced)
        }
        Err(e) => {
            check_refusal(&e);
            let named = ["abs_beta", "cover_index", "lambda_nm", "te", "tm", "table"];
            assert!(named.contains(&e.parameter()), "{e}");
            tally.from_classical_refused += 1;
            None
        }
    }
}

#[test]
fn sweep() {
    sweep_with(QUICK_CASES, 0x2b);
}

#[test]
#[ignore = "a hundred times the quick sweep"]
fn sweep_long() {
    sweep_with(100 * QUICK_CASES, 0x2b2b_4444);
}

/// Huge arrays in a conical file are refused at the table's caps, naming the field, however
/// long they are (the reader stops at the cap: its work is the cap's, not the input's).
#[test]
fn huge_conical_arrays_are_refused_at_the_caps() {
    let long = |n: usize| {
        let v: Vec<String> = (0..n).map(|i| format!("{}", i as f64 / n as f64)).collect();
        format!("[{}]", v.join(", "))
    };
    let cases = [
        (
            V2.replacen("[0.0, 0.6]", &long(MAX_TABLE_NODES + 1), 1),
            "abs_beta",
        ),
        (
            V3.replacen("[0.0, 0.6]", &long(MAX_TABLE_NODES + 1), 1),
            "abs_beta",
        ),
        (
            V3.replacen("[320.0, 500.0, 700.0]", &long(MAX_TABLE_NODES + 1), 1),
            "lambda_nm",
        ),
        (
            V3.replacen(
                "\"lambda_nm\": [[400.0, 875.0], ",
                &format!(
                    "\"lambda_nm\": [{}",
                    "[400.0, 875.0], ".repeat(MAX_TABLE_NODES + 1)
                ),
                1,
            ),
            "lambda_nm",
        ),
    ];
    for (text, field) in cases {
        let e = serde_json::from_str::<EfficiencyTable>(&text)
            .unwrap_err()
            .to_string();
        assert!(e.len() < MAX_MESSAGE, "{e}");
        assert!(e.starts_with(field), "{field}: {e}");
    }
}

/// A BSDF on a one-order classical table with `te` = `tm` = `v` per node.
fn one_order_bsdf(sin: &[f64], lam: &[f64], v: &[f64]) -> GratingBsdf {
    let t = EfficiencyTable::new(
        1000.0,
        0,
        sin.to_vec(),
        lam.to_vec(),
        v.to_vec(),
        v.to_vec(),
    )
    .unwrap();
    GratingBsdf::new(Grating::new(1600.0, 800.0, 30).unwrap())
        .with_efficiency(OrderEfficiency::from_table(Arc::new(t)).unwrap())
        .unwrap()
}

/// Tables whose node spacing is subnormal (a span below 10⁻³⁰⁸): the fast reading's bins
/// and reciprocal widths overflowed, so that a query past the first node indexed a bin past
/// the last (a panic) and a query exactly on a node read the next one. Such tables are read by
/// the parent rule, whose divisions are exact there.
#[test]
fn subnormal_node_spacings_are_read_by_the_rule() {
    // Spans of 10⁻³¹⁰ nm in s and of 5·10⁻³²⁴ nm in λ: every method finite, none panics.
    let tiny = [
        (vec![0.0, 1e-310], vec![500.0, 600.0]),
        (vec![-0.5, 0.5], vec![5e-324, 1e-323]),
    ];
    for (sin, lam) in tiny {
        let b = one_order_bsdf(&sin, &lam, &vec![0.5; sin.len() * lam.len()]);
        for x in [1e-311, 0.3, -0.3, 0.0] {
            let wi = dir(x, 0.0).unwrap();
            let wo = DVec3::new(-x, 0.0, wi.z);
            let (f, p) = (b.eval(wo, wi, 550.0), b.pdf(wo, wi, 550.0));
            assert!(
                f.is_finite() && f > 0.0 && p.is_finite() && p > 0.0,
                "{sin:?} {lam:?} {x}"
            );
            let s = b.sample(wo, 550.0, 0.3, diffraction::glam::DVec2::new(0.5, 0.5));
            assert!(
                s.is_some_and(|s| s.weight().is_finite()),
                "{sin:?} {lam:?} {x}"
            );
        }
    }
    // An inner interval of 10⁻³¹⁰ in s: at s = 0 exactly (normal incidence, the specular
    // pair) the rule reads node 0's value 0.2 (one order, no normalisation; order 0's
    // cos θm/cos θi = 1), against a table of 0.5 everywhere: f in the ratio 0.2/0.5.
    let sin = [-0.5, 0.0, 1e-310, 0.5];
    let lam = [500.0, 600.0];
    let v = [0.5, 0.2, 0.6, 0.5, 0.5, 0.2, 0.6, 0.5];
    let (b, flat) = (
        one_order_bsdf(&sin, &lam, &v),
        one_order_bsdf(&sin, &lam, &[0.5; 8]),
    );
    let ratio = b.eval(DVec3::Z, DVec3::Z, 550.0) / flat.eval(DVec3::Z, DVec3::Z, 550.0);
    assert!((ratio - 0.4).abs() < FOUR_ROUNDING, "{ratio}");
}
