//! The builder of a reduced conical table (JSON version 3, the module docs' step 5): |β| planes,
//! each with its own wavelength nodes, read by the library at fixed reduced coordinates
//! (s′, λ′) = (α, λ)/c, c = √(1 − β²) (`docs/efficiency_tables.md`, "Reduced conical tables").
//!
//! 1. Planes: the starting |β| nodes, with planes added (bisecting c) until neighbours differ
//!    by at most [`TableSpec::max_plane_ratio`] in c, lowered where the solver's
//!    [`OrderSolver::wavelength_range_nm`] needs it: plane p is read at λ·c_p/c for the band's
//!    queries beside it, so it must reach from λ0·c_p/c_{p−1} to λ1·c_p/c_{p+1}.
//! 2. Nodes: the s′ axis of a classical table of the band (shared by every plane); each
//!    plane's wavelengths in steps of at most the starting λ step over its reach, plus the
//!    Rayleigh breakpoints c_p·d/m and c_p·2d/m (the classical ones in λ′).
//! 3. Held-out midpoints: along s′ on every plane's rows, along each plane's λ on every s′
//!    column, and between neighbouring planes at the mean of their c, on every s′ column, at
//!    the lower plane's nodes' reduced wavelengths that fall inside the band there. An interval
//!    (of s′, of a plane's λ, or a slab) above the tolerance is bisected; its midpoints,
//!    already solved, become nodes (an inserted plane gets both planes' nodes' reduced
//!    wavelengths inside the slab's queries, and its ends, solved in the next round).
//! 4. Random points in the box (s′, |β| and λ uniform); one above the tolerance bisects its s′
//!    interval, its slab and both planes' λ intervals.
//!
//! The error is the unpolarised efficiency's, per order (`cache::point_error`).

use diffraction::relief::{ReducedGrid, MAX_TABLE_NODES};
use diffraction::Requirement;

use super::cache::{plane_error, point_error, Cache, Point};
use super::spec::invalid;
use super::{
    cell, even_steps, initial_grid, merge, round_report, splitmix, BuiltTable, OrderSolver,
    Progress, TableError, TableSpec,
};

/// The factor a plane's wavelengths may reach inside the solver's range at least (a band closer
/// to the ends of the range would need planes without end).
const MIN_RATIO: f64 = 1.02;

/// c = √(1 − β²).
fn cb(b: f64) -> f64 {
    (1.0 - b * b).sqrt()
}

/// One |β| plane: its |β| and its own wavelength nodes.
#[derive(Debug, Clone)]
struct Plane {
    beta: f64,
    lam: Vec<f64>,
}

/// What a held-out point checks.
#[derive(Debug, Clone, Copy)]
enum Axis {
    /// The s′ interval i.
    S(usize),
    /// Plane p's wavelength interval j.
    L(usize, usize),
    /// The slab between planes k and k + 1.
    B(usize),
}

/// The wavelengths plane `p` must reach (the library's rule, `ReducedGrid::plane_reach_nm`).
fn reach(planes: &[Plane], band: (f64, f64), p: usize) -> (f64, f64) {
    let grid = ReducedGrid {
        sin_theta_i: Vec::new(),
        abs_beta: planes.iter().map(|q| q.beta).collect(),
        lambda_range_nm: band,
        lambda_nm: Vec::new(),
    };
    grid.plane_reach_nm(p).unwrap_or(band)
}

/// The |β| of the plane between planes with c = `c0` and `c1` (the mean of their c), and the
/// physical wavelengths it needs: both planes' nodes in reduced wavelengths inside the slab's
/// queries [λ0/c0, λ1/c1], its ends included, times its c; nodes closer than half the
/// smallest λ step merged.
fn between(a: &Plane, b: &Plane, band: (f64, f64), min_step: f64) -> (f64, Vec<f64>) {
    let (c0, c1) = (cb(a.beta), cb(b.beta));
    let cm = 0.5 * (c0 + c1);
    let beta = (1.0 - cm * cm).sqrt();
    let (lo, hi) = (band.0 / c0, band.1 / c1);
    let mut reduced: Vec<f64> = a.lam.iter().map(|&l| l / c0).collect();
    reduced.extend(b.lam.iter().map(|&l| l / c1));
    reduced.retain(|&x| x > lo && x < hi);
    reduced.sort_by(f64::total_cmp);
    let mut out = vec![band.0 * (cm / c0)];
    for x in reduced {
        let l = x * cm;
        if l - out[out.len() - 1] >= 0.5 * min_step {
            out.push(l);
        }
    }
    let end = band.1 * (cm / c1);
    if end - out[out.len() - 1] < 0.5 * min_step && out.len() > 1 {
        out.pop();
    }
    out.push(end);
    (beta, out)
}

/// Builds a reduced conical table (the module docs say how).
pub(super) fn build<S: OrderSolver>(
    solver: &S,
    spec: &TableSpec,
    progress: &mut dyn FnMut(&Progress),
) -> Result<BuiltTable, TableError> {
    let d = solver.period_nm();
    let band = spec.lambda_range_nm;
    let mut ratio = spec.max_plane_ratio;
    if let Some((lo, hi)) = solver.wavelength_range_nm() {
        let within = Requirement::Within {
            min: lo * MIN_RATIO,
            max: hi / MIN_RATIO,
        };
        if band.0 < lo * MIN_RATIO {
            return Err(invalid("lambda_range_nm.0", band.0, within));
        }
        if band.1 > hi / MIN_RATIO {
            return Err(invalid("lambda_range_nm.1", band.1, within));
        }
        ratio = ratio.min(band.0 / lo).min(hi / band.1);
    }
    let threads = if spec.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        spec.threads
    };
    let mut cache = Cache {
        solver,
        map: std::collections::HashMap::new(),
        marked: std::collections::HashMap::new(),
        solves: 0,
        threads,
        start: std::time::Instant::now(),
    };
    // Step 1: the planes.
    let mut planes: Vec<Plane> = spec
        .abs_beta
        .iter()
        .map(|&beta| Plane {
            beta,
            lam: Vec::new(),
        })
        .collect();
    loop {
        let mut added = false;
        let mut out = Vec::with_capacity(2 * planes.len());
        for k in 0..planes.len() {
            out.push(planes[k].clone());
            if k + 1 < planes.len() && cb(planes[k].beta) > ratio * cb(planes[k + 1].beta) {
                let cm = 0.5 * (cb(planes[k].beta) + cb(planes[k + 1].beta));
                out.push(Plane {
                    beta: (1.0 - cm * cm).sqrt(),
                    lam: Vec::new(),
                });
                added = true;
            }
        }
        planes = out;
        if planes.len() > MAX_TABLE_NODES {
            return Err(TableError::Budget {
                limit: "nodes",
                solves: 0,
                grid: (0, 0),
                achieved: f64::NAN,
                tolerance: spec.tolerance,
                best: None,
            });
        }
        if !added {
            break;
        }
    }
    // Step 2: the nodes.
    let (mut s, _) = initial_grid(spec, d);
    for p in 0..planes.len() {
        let (lo, hi) = reach(&planes, band, p);
        let c = cb(planes[p].beta);
        let mut l = even_steps(lo, hi, spec.initial_lambda_step_nm);
        let max_m = (2.0 * d / lo).floor().min(4096.0) as i32;
        let breaks = (1..=max_m).flat_map(|m| [c * d / f64::from(m), 2.0 * c * d / f64::from(m)]);
        merge(&mut l, breaks, 0.1 * spec.initial_lambda_step_nm);
        planes[p].lam = l;
    }
    let mut rng = spec.seed;
    let mut error = f64::NAN;
    let mut round = 0;
    let mut last: Option<BuiltTable> = None;
    let budget = |cache: &Cache<'_, S>, last: &Option<BuiltTable>, limit| {
        let best = last.clone().map(Box::new);
        let (grid, achieved) = best.as_ref().map_or(((0, 0), f64::NAN), |t| {
            let rows = t.plane_lambda_nm.iter().map(Vec::len).max().unwrap_or(0);
            ((t.sin_theta_i.len(), rows), t.report.achieved_abs_error)
        });
        TableError::Budget {
            limit,
            solves: cache.solves,
            grid,
            achieved,
            tolerance: spec.tolerance,
            best,
        }
    };
    let mid = |v: &[f64], i: usize| 0.5 * (v[i] + v[i + 1]);
    loop {
        round += 1;
        let too_many = planes.iter().any(|p| p.lam.len() > MAX_TABLE_NODES);
        if s.len() > MAX_TABLE_NODES || planes.len() > MAX_TABLE_NODES || too_many {
            return Err(budget(&cache, &last, "nodes"));
        }
        // Step 3: the held-out midpoints.
        let mut checks: Vec<(Point, Axis)> = Vec::new();
        for (p, plane) in planes.iter().enumerate() {
            for &lam in &plane.lam {
                for i in 0..s.len() - 1 {
                    checks.push(((mid(&s, i), plane.beta, lam), Axis::S(i)));
                }
            }
            for j in 0..plane.lam.len() - 1 {
                for &x in &s {
                    checks.push(((x, plane.beta, mid(&plane.lam, j)), Axis::L(p, j)));
                }
            }
        }
        let inserts: Vec<(f64, Vec<f64>)> = (0..planes.len() - 1)
            .map(|k| between(&planes[k], &planes[k + 1], band, spec.min_lambda_step_nm))
            .collect();
        // Between planes: the blend at the band's queries, at the lower plane's reduced
        // wavelengths (a plane inserted there gets both planes', solved once it is).
        for (k, (beta, lams)) in inserts.iter().enumerate() {
            let (c0, cm) = (cb(planes[k].beta), cb(*beta));
            let at_lower = |l: f64| {
                let lp = l / cm * c0;
                planes[k].lam.iter().any(|&x| (x - lp).abs() <= 1e-9 * x)
            };
            let in_band = |l: f64| l >= band.0 && l <= band.1;
            for &lam in lams.iter().filter(|&&l| in_band(l) && at_lower(l)) {
                for &x in &s {
                    checks.push(((x, *beta, lam), Axis::B(k)));
                }
            }
        }
        let mut points: Vec<Point> = Vec::new();
        for plane in &planes {
            for &lam in &plane.lam {
                for &x in &s {
                    points.push((x, plane.beta, lam));
                }
            }
        }
        points.extend(checks.iter().map(|c| c.0));
        cache
            .solve_all(&points, spec.max_solves, round, error, progress)
            .map_err(|e| match e {
                TableError::Budget { .. } => budget(&cache, &last, "max_solves"),
                e => e,
            })?;
        let (lo, hi, te, tm, table) = assemble(&cache, &s, &planes, band, d)?;
        let mut errs = Vec::new();
        let mut at: Vec<Point> = Vec::new();
        let mut split_s = vec![false; s.len() - 1];
        let mut split_l: Vec<Vec<bool>> = planes
            .iter()
            .map(|p| vec![false; p.lam.len() - 1])
            .collect();
        let mut split_b = vec![false; planes.len() - 1];
        for &(p, axis) in &checks {
            let solve = cache.get(p);
            let e = match axis {
                // A plane's own interpolation, past the band too.
                Axis::S(_) | Axis::L(..) => {
                    let q = planes.iter().position(|q| q.beta == p.1).unwrap_or(0);
                    plane_error(&table, q, &solve, p)
                }
                // The blend between planes, at the band's queries.
                Axis::B(_) => point_error(&table, &solve, p, true),
            };
            errs.push(e);
            at.push(p);
            if e > spec.tolerance {
                match axis {
                    Axis::S(i) => split_s[i] = true,
                    Axis::L(q, j) => split_l[q][j] = true,
                    Axis::B(k) => split_b[k] = true,
                }
            }
        }
        let any_split =
            split_s.iter().chain(&split_b).any(|&x| x) || split_l.iter().flatten().any(|&x| x);
        let mut random_max: f64 = 0.0;
        if !any_split {
            // Step 4: the random points.
            let (s0, s1) = spec.sin_theta_range;
            let (b0, b1) = (planes[0].beta, planes[planes.len() - 1].beta);
            let betas: Vec<f64> = planes.iter().map(|p| p.beta).collect();
            let pts: Vec<Point> = (0..spec.validation_points)
                .map(|_| {
                    let x = s0 + (s1 - s0) * splitmix(&mut rng);
                    let beta = b0 + (b1 - b0) * splitmix(&mut rng);
                    (x, beta, band.0 + (band.1 - band.0) * splitmix(&mut rng))
                })
                .collect();
            cache
                .solve_all(&pts, spec.max_solves, round, error, progress)
                .map_err(|e| match e {
                    TableError::Budget { .. } => budget(&cache, &last, "max_solves"),
                    e => e,
                })?;
            for &p in &pts {
                let e = point_error(&table, &cache.get(p), p, true);
                errs.push(e);
                at.push(p);
                random_max = random_max.max(e);
                if e > spec.tolerance {
                    split_s[cell(&s, p.0)] = true;
                    let k = cell(&betas, p.1);
                    split_b[k] = true;
                    for q in [k, k + 1] {
                        let l = p.2 * cb(planes[q].beta) / cb(p.1);
                        split_l[q][cell(&planes[q].lam, l)] = true;
                    }
                }
            }
        }
        let mut unresolved = 0;
        let mut refinable = |split: &mut [bool], width: &dyn Fn(usize) -> f64, min: f64| {
            for (i, x) in split.iter_mut().enumerate() {
                if *x && width(i) < 2.0 * min {
                    *x = false;
                    unresolved += 1;
                }
            }
        };
        refinable(&mut split_s, &|i| s[i + 1] - s[i], spec.min_sin_step);
        for (plane, split) in planes.iter().zip(&mut split_l) {
            let w = |j: usize| plane.lam[j + 1] - plane.lam[j];
            refinable(split, &w, spec.min_lambda_step_nm);
        }
        // Slabs are bisected in c = √(1 − β²), the blend's variable: their width too.
        let w = |k: usize| cb(planes[k].beta) - cb(planes[k + 1].beta);
        refinable(&mut split_b, &w, spec.min_beta_step);
        let report = round_report(
            spec, &cache, &errs, &at, random_max, unresolved, round, false,
        );
        error = report.achieved_abs_error;
        let candidate = BuiltTable {
            sin_theta_i: s.clone(),
            abs_beta: planes.iter().map(|p| p.beta).collect(),
            lambda_nm: planes[0].lam.clone(),
            plane_lambda_nm: planes.iter().map(|p| p.lam.clone()).collect(),
            lambda_range_nm: band,
            order_min: lo,
            order_max: hi,
            te,
            tm,
            table,
            report,
        };
        let any =
            split_s.iter().chain(&split_b).any(|&x| x) || split_l.iter().flatten().any(|&x| x);
        if !any {
            if error > spec.tolerance {
                return Err(budget(&cache, &Some(candidate), "min_step"));
            }
            return Ok(candidate);
        }
        last = Some(candidate);
        let bisect = |nodes: &[f64], split: &[bool]| {
            let mut out = Vec::with_capacity(nodes.len() * 2);
            for i in 0..nodes.len() {
                out.push(nodes[i]);
                if i < split.len() && split[i] {
                    out.push(0.5 * (nodes[i] + nodes[i + 1]));
                }
            }
            out
        };
        s = bisect(&s, &split_s);
        for (plane, split) in planes.iter_mut().zip(&split_l) {
            plane.lam = bisect(&plane.lam, split);
        }
        let mut next = Vec::with_capacity(2 * planes.len());
        for (k, plane) in planes.into_iter().enumerate() {
            next.push(plane);
            if split_b.get(k).copied().unwrap_or(false) {
                let (beta, lam) = inserts[k].clone();
                next.push(Plane { beta, lam });
            }
        }
        planes = next;
    }
}

/// (order_min, order_max, TE, TM flattened `[order][plane][λ of the plane][s′]`, the library's
/// table) from the solved nodes.
type Assembled = (
    i32,
    i32,
    Vec<f64>,
    Vec<f64>,
    diffraction::relief::EfficiencyTable,
);

fn assemble(
    cache: &Cache<'_, impl OrderSolver>,
    s: &[f64],
    planes: &[Plane],
    band: (f64, f64),
    d: f64,
) -> Result<Assembled, TableError> {
    let (mut lo, mut hi) = (i32::MAX, i32::MIN);
    for plane in planes {
        for &lam in &plane.lam {
            for &x in s {
                let o = cache.get((x, plane.beta, lam));
                for (k, (&a, &t)) in o.te.iter().zip(&o.tm).enumerate() {
                    if a > 0.0 || t > 0.0 {
                        lo = lo.min(o.order_min + k as i32);
                        hi = hi.max(o.order_min + k as i32);
                    }
                }
            }
        }
    }
    if lo > hi {
        (lo, hi) = (0, 0);
    }
    let rows: usize = planes.iter().map(|p| p.lam.len()).sum();
    let slice = rows * s.len();
    let n = (hi - lo + 1) as usize * slice;
    let (mut te, mut tm) = (vec![0.0; n], vec![0.0; n]);
    let mut row = 0;
    for plane in planes {
        let c = cb(plane.beta);
        for &lam in &plane.lam {
            for (i, &x) in s.iter().enumerate() {
                let o = cache.get((x, plane.beta, lam));
                for m in lo..=hi {
                    // The loader's own test of evanescence: exactly 0 there.
                    let am = x * c + f64::from(m) * lam / d;
                    if 1.0 - am * am - plane.beta * plane.beta <= 0.0 {
                        continue;
                    }
                    let (a, t) = o.get(m);
                    let at = (m - lo) as usize * slice + row * s.len() + i;
                    te[at] = a.max(0.0);
                    tm[at] = t.max(0.0);
                }
            }
            row += 1;
        }
    }
    let grid = ReducedGrid {
        sin_theta_i: s.to_vec(),
        abs_beta: planes.iter().map(|p| p.beta).collect(),
        lambda_range_nm: band,
        lambda_nm: planes.iter().map(|p| p.lam.clone()).collect(),
    };
    let table =
        diffraction::relief::EfficiencyTable::new_reduced(d, lo, grid, te.clone(), tm.clone())
            .map_err(TableError::Table)?;
    Ok((lo, hi, te, tm, table))
}
