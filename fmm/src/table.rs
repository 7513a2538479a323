//! Error-controlled efficiency tables: a grid in (sin θi, λ) refined until the interpolation
//! error, measured against held-out rigorous solves, is below a tolerance.
//!
//! The table is the crate's `diffraction::relief::EfficiencyTable` (the JSON format of
//! `docs/efficiency_tables.md`), read back by the library's own interpolation rule, so the error
//! measured here is the error a renderer sees. The solver is anything that implements
//! [`OrderSolver`]: the reflected orders' TE and TM efficiencies at one (s, λ).
//!
//! How the grid is made ([`build_table`]):
//!
//! 1. Start: s from the range's low end to its high end in steps of at most
//!    [`TableSpec::initial_sin_step`] (with ±0.98 added near grazing, where order 0 changes
//!    fastest), λ in steps of at most [`TableSpec::initial_lambda_step_nm`]; plus breakpoints on
//!    the Rayleigh lines s + m·λ/d = ±1 where orders appear: the wavelengths d/|m| (order m
//!    at grazing exit for normal incidence) and 2d/|m| (its onset at grazing incidence), and
//!    the s values where each line crosses the shortest and the longest wavelength. Breakpoints
//!    closer than a tenth of a step to a node are merged into it.
//! 2. Solve every node; build the table.
//! 3. Held-out checks: solve at the midpoint of every s interval on every λ row, and at the
//!    midpoint of every λ interval on every s column; compare every order of both
//!    polarisations with the table's interpolation. An interval whose largest error exceeds the
//!    tolerance is bisected (its midpoints, already solved, become nodes), unless it is already
//!    narrower than [`TableSpec::min_sin_step`] / [`TableSpec::min_lambda_step_nm`]. Repeat from 2
//!    until no interval is bisected.
//! 4. Validation: solve at [`TableSpec::validation_points`] random points (seeded) and compare;
//!    a point above the tolerance bisects both intervals of its cell and the loop goes on.
//!
//! 5. Conical ([`TableSpec::abs_beta`] not empty): the error is the unpolarised efficiency's
//!    per order (a conical solve's s and p split swaps between β = 0 and β > 0 at α = 0; their
//!    mean is what the BSDF reads). By default ([`TableSpec::reduced`]) the table is the
//!    reduced format (JSON version 3): |β| planes with their own wavelength nodes, refined along
//!    s′, along each plane's λ and between planes (`table/reduced.rs` says how); otherwise the
//!    version-2 tensor grid in (s′, |β|, λ), refined as steps 1-4 along its three axes.
//!
//! The achieved error stored with the table is the largest absolute error over the held-out
//! points of the final grid (the last round's midpoints, which are not nodes, and the random
//! points). Work is bounded: more than [`TableSpec::max_solves`] solves, or a grid beyond the
//! loader's [`MAX_TABLE_NODES`] per axis, stops the build with [`TableError::Budget`], which
//! says the error reached so far.

use std::collections::HashMap;
use std::fmt;
use std::time::Instant;

use diffraction::relief::{EfficiencyTable, MAX_TABLE_NODES};
use diffraction::Error;

mod cache;
mod json;
mod reduced;
mod rigorous;
mod spec;

use cache::{assemble, point_error, Cache, Point};
use spec::check_spec;

pub use json::TableMeta;
pub use rigorous::{Mapped, Rigorous};

/// The most random held-out points a build checks ([`TableSpec::validation_points`]): the
/// points are made before their solves are counted against [`TableSpec::max_solves`], so their
/// number is bounded on its own.
pub const MAX_VALIDATION_POINTS: usize = 100_000;

/// The reflected orders of one solve: `te[k]`, `tm[k]` are the efficiencies of order
/// `order_min + k`. Orders not listed, and evanescent ones, count as 0.
#[derive(Debug, Clone, PartialEq)]
pub struct Orders {
    /// The first order listed.
    pub order_min: i32,
    /// TE (E along the grooves) efficiencies, consecutive orders from `order_min`.
    pub te: Vec<f64>,
    /// TM (H along the grooves) efficiencies, as long as `te`.
    pub tm: Vec<f64>,
}

impl Orders {
    /// (TE, TM) of order `m`, 0 where not listed.
    #[must_use]
    pub fn get(&self, m: i32) -> (f64, f64) {
        let k = i64::from(m) - i64::from(self.order_min);
        if k < 0 || k as usize >= self.te.len() {
            return (0.0, 0.0);
        }
        let k = k as usize;
        (self.te[k], self.tm.get(k).copied().unwrap_or(0.0))
    }

    /// The last order listed.
    #[must_use]
    pub fn order_max(&self) -> i32 {
        self.order_min + self.te.len() as i32 - 1
    }

    /// The same orders for the mirrored grating (m → −m).
    fn mirrored(&self) -> Orders {
        let mut te = self.te.clone();
        let mut tm = self.tm.clone();
        te.reverse();
        tm.reverse();
        Orders {
            order_min: -self.order_max(),
            te,
            tm,
        }
    }
}

/// A rigorous solver of a grating's reflected orders in the classical mount.
pub trait OrderSolver: Sync {
    /// The grating period d in nm (the orders leave at s + m·λ/d).
    fn period_nm(&self) -> f64;

    /// Whether the profile is mirror-symmetric, so that η_m(s) = η₋m(−s): the builder then
    /// solves only s ≥ 0 and mirrors.
    fn mirror_symmetric(&self) -> bool {
        false
    }

    /// The efficiencies of the propagating reflected orders at s = sin θi (the x component of
    /// the incident direction of travel) and λ in nm, converged to the solver's own tolerance
    /// (well below the table's).
    fn solve(&self, sin_theta_i: f64, lambda_nm: f64) -> Result<Orders, String>;

    /// The efficiencies in a conical mount: the incident direction of travel has direction
    /// cosines α = `alpha` across and β = `beta` ≥ 0 along the grooves (order m leaves with
    /// α + m·λ/d, β). TE and TM are then the incident s and p polarisations (only their mean,
    /// the unpolarised efficiency, is independent of that choice). The default solves the
    /// classical mount at β = 0 and refuses any other β.
    fn solve_conical(&self, alpha: f64, beta: f64, lambda_nm: f64) -> Result<Orders, String> {
        if beta == 0.0 {
            self.solve(alpha, lambda_nm)
        } else {
            Err("this solver has no conical mount".to_string())
        }
    }

    /// The wavelengths (nm) the solver can solve at (its materials' tabulated range), `None`
    /// (the default) for any: a reduced conical table's planes reach beyond its band, and the
    /// builder keeps them inside this range or refuses the band by name.
    fn wavelength_range_nm(&self) -> Option<(f64, f64)> {
        None
    }

    /// [`solve_conical`](Self::solve_conical), with the node marked where the solver did not
    /// converge to its tolerance but returned its best value: `Some(the last change)`. The
    /// default marks nothing.
    fn solve_marked(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
    ) -> Result<(Orders, Option<f64>), String> {
        self.solve_conical(alpha, beta, lambda_nm)
            .map(|o| (o, None))
    }
}

/// What to build: the grid's range, the tolerance and the work allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct TableSpec {
    /// The s range, inside (−1, 1) (the solvers need cos θi > 0); default ±0.9999 as the presets.
    pub sin_theta_range: (f64, f64),
    /// The wavelength range in nm; default 360-830 nm.
    pub lambda_range_nm: (f64, f64),
    /// The largest absolute interpolation error allowed, per order and polarisation; default 10⁻².
    pub tolerance: f64,
    /// The most solves the build may make (nodes and checks, mirrored solves not counted);
    /// default 20,000.
    pub max_solves: usize,
    /// The starting s step; default 0.2.
    pub initial_sin_step: f64,
    /// The starting λ step in nm; default 50.
    pub initial_lambda_step_nm: f64,
    /// Intervals narrower than this in s are not bisected; default 2·10⁻³.
    pub min_sin_step: f64,
    /// Intervals narrower than this in λ (nm) are not bisected; default 1 nm.
    pub min_lambda_step_nm: f64,
    /// Random held-out points checked after the midpoints pass, at most
    /// [`MAX_VALIDATION_POINTS`]; default 64.
    pub validation_points: usize,
    /// The seed of those points.
    pub seed: u64,
    /// Worker threads (0: the machine's parallelism).
    pub threads: usize,
    /// The starting |β| nodes of a conical table, strictly increasing in [0, 0.99999]
    /// (β: the incident direction cosine along the grooves); empty (the default): a classical
    /// table. A conical table's s axis is s′ = α/√(1 − β²) (`docs/efficiency_tables.md`).
    pub abs_beta: Vec<f64>,
    /// Intervals narrower than this in |β| (in √(1 − β²) for a reduced table, whose planes are
    /// bisected in it) are not bisected; default 0.02.
    pub min_beta_step: f64,
    /// A conical table (`abs_beta` not empty) in the reduced format (JSON version 3, the
    /// default: |β| planes with their own wavelength nodes, read at fixed (s′, λ′); the module
    /// docs, step 5), or, `false`, the version-2 tensor grid in (s′, |β|, λ).
    pub reduced: bool,
    /// A reduced table's largest ratio c_p/c_{p+1} between neighbouring planes, c = √(1 − β²)
    /// (default 2.5): planes are added (bisecting c) until every pair meets it, so that each
    /// plane's wavelengths reach at most this factor beyond the band (and within the solver's
    /// [`OrderSolver::wavelength_range_nm`]: the ratio is lowered to fit it).
    pub max_plane_ratio: f64,
    /// A classical table on these nodes, (s, λ nm), each axis strictly increasing with 2 to
    /// [`MAX_TABLE_NODES`] nodes: no refinement (steps 1 and 3 of the module docs are skipped,
    /// `tolerance` is not enforced) and the held-out error is measured at the random
    /// validation points inside the nodes' span (e.g. to re-solve a shipped table on its own
    /// grid); `validation_points` must then be at least 1. `None` (the default): the grid is
    /// made and refined.
    pub fixed_nodes: Option<(Vec<f64>, Vec<f64>)>,
}

impl Default for TableSpec {
    fn default() -> Self {
        TableSpec {
            sin_theta_range: (-0.9999, 0.9999),
            lambda_range_nm: (360.0, 830.0),
            tolerance: 1e-2,
            max_solves: 20_000,
            initial_sin_step: 0.2,
            initial_lambda_step_nm: 50.0,
            min_sin_step: 2e-3,
            min_lambda_step_nm: 1.0,
            validation_points: 64,
            seed: 0x5eed_7ab1e,
            threads: 0,
            abs_beta: Vec::new(),
            min_beta_step: 0.02,
            reduced: true,
            max_plane_ratio: 2.5,
            fixed_nodes: None,
        }
    }
}

/// Why a build stopped.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum TableError {
    /// A field of [`TableSpec`] (or the solver's period) out of range, named by the error.
    Invalid(Error),
    /// The solver failed at a point.
    Solver {
        /// s of the failed solve.
        sin_theta_i: f64,
        /// λ of the failed solve, nm.
        lambda_nm: f64,
        /// The solver's message.
        message: String,
    },
    /// The solver's values do not make a valid table (e.g. a node's sum above 1).
    Table(Error),
    /// The tolerance was not reached within the work allowed.
    Budget {
        /// What ran out: `"max_solves"`, `"nodes"` (the loader's per-axis limit) or
        /// `"min_step"` (the intervals above the tolerance are at the minimum width).
        limit: &'static str,
        /// Solves made.
        solves: usize,
        /// The grid reached (s nodes, λ nodes).
        grid: (usize, usize),
        /// The largest held-out error of the last round; NaN when no round finished (the
        /// budget ran out inside the first), which the message says in words.
        achieved: f64,
        /// The tolerance asked for.
        tolerance: f64,
        /// The last complete table (nodes solved, held-out error measured), if a round
        /// finished: a table claiming its achieved error, for a caller that accepts it.
        best: Option<Box<BuiltTable>>,
    },
}

impl fmt::Display for TableError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TableError::Invalid(e) | TableError::Table(e) => write!(f, "{e}"),
            TableError::Solver {
                sin_theta_i,
                lambda_nm,
                message,
            } => write!(
                f,
                "solver failed at sin_theta_i = {sin_theta_i}, lambda_nm = {lambda_nm}: {message}"
            ),
            TableError::Budget {
                limit,
                solves,
                grid,
                achieved,
                tolerance,
                ..
            } => {
                write!(
                    f,
                    "tolerance {tolerance:e} not reached: {limit} exhausted after {solves} \
                     solves on a {} x {} grid, ",
                    grid.0, grid.1
                )?;
                if achieved.is_nan() {
                    write!(f, "no held-out error measured (no round finished)")
                } else {
                    write!(f, "held-out error {achieved:.3e}")
                }
            }
        }
    }
}

impl std::error::Error for TableError {}

/// Progress of a build, reported after every solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Progress {
    /// Refinement round (1 = the starting grid).
    pub round: usize,
    /// Solves done in this round and planned for it.
    pub done: usize,
    /// Solves planned for this round.
    pub planned: usize,
    /// Solves made in the whole build so far.
    pub total_solves: usize,
    /// The largest held-out error of the previous round (NaN in round 1).
    pub error: f64,
    /// Seconds per solve so far (wall time over solves).
    pub seconds_per_solve: f64,
}

/// The error statistics of a built table.
#[derive(Debug, Clone, PartialEq)]
pub struct BuildReport {
    /// The tolerance asked for.
    pub tolerance: f64,
    /// The largest absolute error over the held-out points of the final grid (per order and
    /// polarisation): the table's achieved error.
    pub achieved_abs_error: f64,
    /// 95th percentile of the per-point largest errors.
    pub abs_error_p95: f64,
    /// Median of the per-point largest errors.
    pub abs_error_median: f64,
    /// Held-out points compared (midpoints of the final grid and random points).
    pub held_out_points: usize,
    /// The largest error at the random points alone.
    pub random_points_max: f64,
    /// Where the largest error is: (s, λ nm); s′ = α/√(1 − β²) for a conical table (its
    /// |β| is `worst_beta`).
    pub worst_point: (f64, f64),
    /// |β| of the worst point (0 for a classical table).
    pub worst_beta: f64,
    /// Nodes and held-out points whose solve reached the solver's harmonic cap without
    /// converging to its tolerance, taken at the cap's count (see [`Rigorous`]): how many, and
    /// the largest last change among them (0 if none).
    pub unconverged: (usize, f64),
    /// Intervals that exceeded the tolerance but were at the minimum width (not bisected).
    pub unresolved_intervals: usize,
    /// Solves made (nodes and checks; mirrored values not counted).
    pub solves: usize,
    /// Refinement rounds.
    pub rounds: usize,
    /// Whether the nodes were given ([`TableSpec::fixed_nodes`]): no refinement, `tolerance`
    /// not enforced.
    pub fixed_grid: bool,
    /// Wall time of the build, seconds.
    pub seconds: f64,
}

/// A table and how it was made.
#[derive(Debug, Clone, PartialEq)]
pub struct BuiltTable {
    /// The s nodes (s′ = α/√(1 − β²) for a conical table).
    pub sin_theta_i: Vec<f64>,
    /// The |β| nodes of a conical table; empty for a classical one.
    pub abs_beta: Vec<f64>,
    /// The λ nodes, nm (of a reduced conical table its first plane's).
    pub lambda_nm: Vec<f64>,
    /// A reduced conical table's wavelength nodes, one list per |β| plane (empty otherwise).
    pub plane_lambda_nm: Vec<Vec<f64>>,
    /// The band of physical wavelengths the table answers for, nm.
    pub lambda_range_nm: (f64, f64),
    /// The first order stored.
    pub order_min: i32,
    /// The last order stored.
    pub order_max: i32,
    /// TE efficiencies flattened `[order][λ][s]` (`[order][|β|][λ][s]` for a conical table,
    /// `[order][plane][λ of the plane][s]` for a reduced one).
    pub te: Vec<f64>,
    /// TM efficiencies, flattened as `te`.
    pub tm: Vec<f64>,
    /// The table as the library reads it.
    pub table: EfficiencyTable,
    /// The error statistics.
    pub report: BuildReport,
}

/// Even steps of at most `step` from `a` to `b`, both ends included.
fn even_steps(a: f64, b: f64, step: f64) -> Vec<f64> {
    let n = ((b - a) / step).ceil().clamp(1.0, 4096.0) as usize;
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// Adds `extra` points inside (a, b) to the sorted `nodes`, skipping any within `gap` of a node.
fn merge(nodes: &mut Vec<f64>, extra: impl IntoIterator<Item = f64>, gap: f64) {
    let (a, b) = (nodes[0], nodes[nodes.len() - 1]);
    for x in extra {
        if x > a && x < b && nodes.iter().all(|&n| (n - x).abs() >= gap) {
            nodes.push(x);
            nodes.sort_by(f64::total_cmp);
        }
    }
}

/// The starting grid (step 1 of the module docs). A range symmetric about s = 0 gets a mirror-
/// symmetric s axis (exact negatives), so a symmetric profile's mirrored solves are cache hits.
fn initial_grid(spec: &TableSpec, d: f64) -> (Vec<f64>, Vec<f64>) {
    let (s0, s1) = spec.sin_theta_range;
    let (l0, l1) = spec.lambda_range_nm;
    let max_m = (2.0 * d / l0).floor().min(4096.0) as i32;
    let mut sb = vec![-0.98, 0.98];
    for m in -max_m..=max_m {
        for lam in [l0, l1] {
            let shift = f64::from(m) * lam / d;
            sb.push(1.0 - shift);
            sb.push(-1.0 - shift);
        }
    }
    let gap = 0.1 * spec.initial_sin_step;
    let s = if s0 == -s1 {
        let mut half = even_steps(0.0, s1, spec.initial_sin_step);
        merge(&mut half, sb.iter().map(|x| x.abs()), gap);
        let mut full: Vec<f64> = half.iter().rev().map(|&x| -x).collect();
        full.pop(); // -0.0: the 0 of `half` stays
        full.extend(half);
        full
    } else {
        let mut s = even_steps(s0, s1, spec.initial_sin_step);
        merge(&mut s, sb, gap);
        s
    };
    let mut l = even_steps(l0, l1, spec.initial_lambda_step_nm);
    let mut breaks = Vec::new();
    for m in 1..=max_m {
        breaks.push(d / f64::from(m));
        breaks.push(2.0 * d / f64::from(m));
    }
    merge(&mut l, breaks, 0.1 * spec.initial_lambda_step_nm);
    (s, l)
}

/// A small seeded generator (SplitMix64) for the validation points.
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// A round's held-out errors `errs` at their points `at` (s, |β|, λ) and its other counts, as
/// the report of the table it built.
#[allow(clippy::too_many_arguments)]
fn round_report<S: OrderSolver>(
    spec: &TableSpec,
    cache: &Cache<'_, S>,
    errs: &[f64],
    at: &[(f64, f64, f64)],
    random_max: f64,
    unresolved: usize,
    round: usize,
    fixed: bool,
) -> BuildReport {
    let worst = (0..errs.len()).fold(0, |w, i| if errs[i] > errs[w] { i } else { w });
    let worst_at = at
        .get(worst)
        .copied()
        .unwrap_or((f64::NAN, f64::NAN, f64::NAN));
    let mut sorted = errs.to_vec();
    sorted.sort_by(f64::total_cmp);
    let marked = cache
        .marked
        .values()
        .fold((0usize, 0.0f64), |(n, w), &c| (n + 1, w.max(c)));
    BuildReport {
        tolerance: spec.tolerance,
        achieved_abs_error: errs.get(worst).copied().unwrap_or(0.0),
        abs_error_p95: percentile(&sorted, 0.95),
        abs_error_median: percentile(&sorted, 0.5),
        held_out_points: errs.len(),
        random_points_max: random_max,
        worst_point: (worst_at.0, worst_at.2),
        worst_beta: worst_at.1,
        unconverged: marked,
        unresolved_intervals: unresolved,
        solves: cache.solves,
        rounds: round,
        fixed_grid: fixed,
        seconds: cache.start.elapsed().as_secs_f64(),
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let i = ((sorted.len() - 1) as f64 * p).round() as usize;
    sorted[i]
}

fn cell(nodes: &[f64], x: f64) -> usize {
    let i = nodes.partition_point(|&n| n <= x);
    i.clamp(1, nodes.len() - 1) - 1
}

/// Builds a table of `solver`'s efficiencies to `spec` (the module docs say how), calling
/// `progress` after every solve.
///
/// # Errors
/// [`TableError::Invalid`] for a field of `spec` out of range (named), [`TableError::Solver`]
/// if a solve fails, [`TableError::Table`] if the solver's values break the table's checks,
/// [`TableError::Budget`] if the tolerance is not reached within `spec.max_solves` solves or
/// the loader's node limit.
pub fn build_table<S: OrderSolver>(
    solver: &S,
    spec: &TableSpec,
    progress: &mut dyn FnMut(&Progress),
) -> Result<BuiltTable, TableError> {
    let d = solver.period_nm();
    check_spec(spec, d)?;
    if spec.reduced && !spec.abs_beta.is_empty() {
        return reduced::build(solver, spec, progress);
    }
    let threads = if spec.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        spec.threads
    };
    let mut cache = Cache {
        solver,
        map: HashMap::new(),
        marked: HashMap::new(),
        solves: 0,
        threads,
        start: Instant::now(),
    };
    let conical = !spec.abs_beta.is_empty();
    let fixed = spec.fixed_nodes.is_some();
    let (mut s, mut l) = match &spec.fixed_nodes {
        Some((s, l)) => (s.clone(), l.clone()),
        None => initial_grid(spec, d),
    };
    let mut b = if conical {
        spec.abs_beta.clone()
    } else {
        vec![0.0]
    };
    let mut rng = spec.seed;
    let mut error = f64::NAN;
    let mut round = 0;
    let mut last: Option<BuiltTable> = None;
    let budget = |cache: &Cache<'_, S>, last: &Option<BuiltTable>, limit| {
        let best = last.clone().map(Box::new);
        let (grid, achieved) = best.as_ref().map_or(((0, 0), f64::NAN), |t| {
            (
                (t.sin_theta_i.len(), t.lambda_nm.len()),
                t.report.achieved_abs_error,
            )
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
        if s.len() > MAX_TABLE_NODES || l.len() > MAX_TABLE_NODES || b.len() > MAX_TABLE_NODES {
            return Err(budget(&cache, &last, "nodes"));
        }
        // The held-out midpoints of this grid: along s on every (|β|, λ) line, along λ on
        // every (s, |β|) line, along |β| on every (s, λ) line; with the axis and interval
        // each one checks.
        let mut checks: Vec<(Point, usize, usize)> = Vec::new();
        for &beta in if fixed { &[][..] } else { &b[..] } {
            for &lam in &l {
                for i in 0..s.len() - 1 {
                    checks.push(((mid(&s, i), beta, lam), 0, i));
                }
            }
            for j in 0..l.len() - 1 {
                for &x in &s {
                    checks.push(((x, beta, mid(&l, j)), 2, j));
                }
            }
        }
        if conical {
            for k in 0..b.len() - 1 {
                for &lam in &l {
                    for &x in &s {
                        checks.push(((x, mid(&b, k), lam), 1, k));
                    }
                }
            }
        }
        let mut points: Vec<Point> = Vec::new();
        for &beta in &b {
            for &lam in &l {
                for &x in &s {
                    points.push((x, beta, lam));
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
        let (lo, hi, te, tm, table) = assemble(&cache, (&s, &b, &l), conical, d)?;
        let mut errs = Vec::new();
        let mut at: Vec<Point> = Vec::new();
        let mut split = [
            vec![false; s.len() - 1],
            vec![false; b.len().max(2) - 1],
            vec![false; l.len() - 1],
        ];
        let mut unresolved = 0;
        for &(p, axis, i) in &checks {
            let e = point_error(&table, &cache.get(p), p, conical);
            errs.push(e);
            at.push(p);
            if e > spec.tolerance {
                split[axis][i] = true;
            }
        }
        let mut random_max: f64 = 0.0;
        let any_split = split.iter().flatten().any(|&x| x);
        let refinable = |split: &mut [bool], nodes: &[f64], min: f64, unresolved: &mut usize| {
            for (i, x) in split.iter_mut().enumerate() {
                if *x && nodes[i + 1] - nodes[i] < 2.0 * min {
                    *x = false;
                    *unresolved += 1;
                }
            }
        };
        if !any_split {
            // The random validation points (step 4).
            let (s0, s1, l0, l1) = if fixed {
                (s[0], s[s.len() - 1], l[0], l[l.len() - 1])
            } else {
                let ((s0, s1), (l0, l1)) = (spec.sin_theta_range, spec.lambda_range_nm);
                (s0, s1, l0, l1)
            };
            let (b0, b1) = (b[0], b[b.len() - 1]);
            let pts: Vec<Point> = (0..spec.validation_points)
                .map(|_| {
                    let x = s0 + (s1 - s0) * splitmix(&mut rng);
                    let beta = if conical {
                        b0 + (b1 - b0) * splitmix(&mut rng)
                    } else {
                        0.0
                    };
                    (x, beta, l0 + (l1 - l0) * splitmix(&mut rng))
                })
                .collect();
            cache
                .solve_all(&pts, spec.max_solves, round, error, progress)
                .map_err(|e| match e {
                    TableError::Budget { .. } => budget(&cache, &last, "max_solves"),
                    e => e,
                })?;
            for &p in &pts {
                let e = point_error(&table, &cache.get(p), p, conical);
                errs.push(e);
                at.push(p);
                random_max = random_max.max(e);
                if e > spec.tolerance {
                    split[0][cell(&s, p.0)] = true;
                    if conical {
                        split[1][cell(&b, p.1)] = true;
                    }
                    split[2][cell(&l, p.2)] = true;
                }
            }
        }
        refinable(&mut split[0], &s, spec.min_sin_step, &mut unresolved);
        if conical {
            refinable(&mut split[1], &b, spec.min_beta_step, &mut unresolved);
        }
        refinable(&mut split[2], &l, spec.min_lambda_step_nm, &mut unresolved);
        let report = round_report(
            spec, &cache, &errs, &at, random_max, unresolved, round, fixed,
        );
        error = report.achieved_abs_error;
        let candidate = BuiltTable {
            sin_theta_i: s.clone(),
            abs_beta: if conical { b.clone() } else { Vec::new() },
            lambda_nm: l.clone(),
            plane_lambda_nm: Vec::new(),
            lambda_range_nm: (l[0], l[l.len() - 1]),
            order_min: lo,
            order_max: hi,
            te,
            tm,
            table,
            report,
        };
        if fixed {
            return Ok(candidate);
        }
        if !split.iter().flatten().any(|&x| x) {
            if error > spec.tolerance {
                // Only intervals at the minimum width are left: not reachable on this grid.
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
        s = bisect(&s, &split[0]);
        if conical {
            b = bisect(&b, &split[1]);
        }
        l = bisect(&l, &split[2]);
    }
}
