//! The builder's solves (cached, in parallel, mirrored for symmetric profiles), the error of
//! a table at a held-out point, and the assembly of the solved nodes into a table.

use std::collections::HashMap;
use std::sync::mpsc;
use std::time::Instant;

use diffraction::relief::{EfficiencyTable, MAX_TABLE_ORDERS};

use super::{OrderSolver, Orders, Progress, TableError};

/// A point of the grid: (s, |β|, λ), s′ = α/√(1 − β²) where β ≠ 0.
pub(super) type Point = (f64, f64, f64);

/// Solves with a cache (keyed on the exact floats; mirrored for symmetric profiles).
pub(super) struct Cache<'a, S: OrderSolver> {
    pub(super) solver: &'a S,
    pub(super) map: HashMap<(u64, u64, u64), Orders>,
    /// The points whose solve was marked unconverged, with the last change.
    pub(super) marked: HashMap<(u64, u64, u64), f64>,
    pub(super) solves: usize,
    pub(super) threads: usize,
    pub(super) start: Instant,
}

/// A solver's answer as the builder keeps it: TE and TM lists of one length, order numbers
/// (and their mirror images) within ±`MAX_TABLE_ORDERS` (a table holds at most that many; an
/// `i32` overflowed past them), every efficiency finite. Else the message of a solver failure.
fn checked(o: &Orders) -> Result<(), String> {
    let n = o.te.len();
    if o.tm.len() != n {
        return Err(format!("te lists {n} orders and tm {}", o.tm.len()));
    }
    let bound = MAX_TABLE_ORDERS as i64;
    let (first, last) = (
        i64::from(o.order_min),
        i64::from(o.order_min) + n as i64 - 1,
    );
    if n > MAX_TABLE_ORDERS || first < -bound || last > bound {
        return Err(format!(
            "orders {first}..={last}: must be at most {MAX_TABLE_ORDERS}, numbered within \
             ±{MAX_TABLE_ORDERS}"
        ));
    }
    if let Some(x) = o.te.iter().chain(&o.tm).find(|x| !x.is_finite()) {
        return Err(format!("an efficiency of {x}: must be finite"));
    }
    Ok(())
}

fn key((s, b, l): Point, symmetric: bool) -> (u64, u64, u64) {
    let s = if symmetric { s.abs() } else { s };
    ((s + 0.0).to_bits(), (b + 0.0).to_bits(), l.to_bits())
}

/// α of the point (s′·√(1 − β²); s itself at β = 0).
pub(super) fn alpha_of((s, b, _): Point) -> f64 {
    if b == 0.0 {
        s
    } else {
        s * (1.0 - b * b).sqrt()
    }
}

impl<'a, S: OrderSolver> Cache<'a, S> {
    /// Solves every point not yet known, in parallel, reporting progress.
    pub(super) fn solve_all(
        &mut self,
        points: &[Point],
        max_solves: usize,
        round: usize,
        error: f64,
        progress: &mut dyn FnMut(&Progress),
    ) -> Result<(), TableError> {
        let sym = self.solver.mirror_symmetric();
        let mut todo: Vec<Point> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        for &(s, b, l) in points {
            let k = key((s, b, l), sym);
            if !self.map.contains_key(&k) && seen.insert(k) {
                todo.push((if sym { s.abs() } else { s }, b, l));
            }
        }
        if self.solves + todo.len() > max_solves {
            return Err(TableError::Budget {
                limit: "max_solves",
                solves: self.solves,
                grid: (0, 0),
                achieved: error,
                tolerance: f64::NAN,
                best: None,
            });
        }
        let planned = todo.len();
        let threads = self.threads.max(1).min(planned.max(1));
        let solver = self.solver;
        let (tx, rx) = mpsc::channel();
        let mut failure = None;
        std::thread::scope(|scope| {
            for t in 0..threads {
                let tx = tx.clone();
                let mine: Vec<Point> = todo.iter().copied().skip(t).step_by(threads).collect();
                scope.spawn(move || {
                    for p in mine {
                        let r = solver.solve_marked(alpha_of(p), p.1, p.2);
                        let stop = r.is_err();
                        if tx.send((p, r)).is_err() || stop {
                            return;
                        }
                    }
                });
            }
            drop(tx);
            let mut done = 0;
            for (p, r) in rx {
                match r.and_then(|(o, mark)| checked(&o).map(|()| (o, mark))) {
                    Ok((o, mark)) => {
                        self.map.insert(key(p, sym), o);
                        if let Some(change) = mark {
                            self.marked.insert(key(p, sym), change);
                        }
                        self.solves += 1;
                        done += 1;
                        let elapsed = self.start.elapsed().as_secs_f64();
                        progress(&Progress {
                            round,
                            done,
                            planned,
                            total_solves: self.solves,
                            error,
                            seconds_per_solve: elapsed / self.solves as f64,
                        });
                    }
                    Err(message) => {
                        failure.get_or_insert(TableError::Solver {
                            sin_theta_i: alpha_of(p),
                            lambda_nm: p.2,
                            message,
                        });
                    }
                }
            }
        });
        failure.map_or(Ok(()), Err)
    }

    pub(super) fn get(&self, p: Point) -> Orders {
        let sym = self.solver.mirror_symmetric();
        let o = &self.map[&key(p, sym)];
        if sym && p.0 < 0.0 {
            o.mirrored()
        } else {
            o.clone()
        }
    }
}

/// The table's largest absolute error at one point against a solve there: per order and
/// polarisation, or (`unpolarised`, conical tables) per order of the mean of TE and TM, the
/// only part of a conical solve that does not depend on the choice of the incident s and p
/// (which swap between β = 0 and β > 0 at α = 0).
pub(super) fn point_error(
    table: &EfficiencyTable,
    solve: &Orders,
    p: Point,
    unpolarised: bool,
) -> f64 {
    let mut out = vec![diffraction::relief::Polarised::default(); table.order_count()];
    table.efficiencies_conical(alpha_of(p), p.1, p.2, &mut out);
    let first = *table.orders().start();
    let mut worst: f64 = 0.0;
    for (k, t) in out.iter().enumerate() {
        let (te, tm) = solve.get(first + k as i32);
        worst = if unpolarised {
            worst.max((t.unpolarised() - 0.5 * (te + tm)).abs())
        } else {
            worst.max((t.te - te).abs()).max((t.tm - tm).abs())
        };
    }
    // Orders the solve has and the table does not store.
    for (k, (&te, &tm)) in solve.te.iter().zip(&solve.tm).enumerate() {
        if !table.orders().contains(&(solve.order_min + k as i32)) {
            worst = if unpolarised {
                worst.max(0.5 * (te + tm).abs())
            } else {
                worst.max(te.abs()).max(tm.abs())
            };
        }
    }
    worst
}

/// [`point_error`] of plane `plane` of a reduced table read alone
/// (`EfficiencyTable::plane_efficiencies`) at the point's s′ and physical λ: a plane's own
/// interpolation, also at the wavelengths past the band that only its neighbours' queries
/// read.
pub(super) fn plane_error(table: &EfficiencyTable, plane: usize, solve: &Orders, p: Point) -> f64 {
    let mut out = vec![diffraction::relief::Polarised::default(); table.order_count()];
    table.plane_efficiencies(plane, p.0, p.2, &mut out);
    let first = *table.orders().start();
    let mut worst: f64 = 0.0;
    for (k, t) in out.iter().enumerate() {
        let (te, tm) = solve.get(first + k as i32);
        worst = worst.max((t.unpolarised() - 0.5 * (te + tm)).abs());
    }
    for (k, (&te, &tm)) in solve.te.iter().zip(&solve.tm).enumerate() {
        if !table.orders().contains(&(solve.order_min + k as i32)) {
            worst = worst.max(0.5 * (te + tm).abs());
        }
    }
    worst
}

/// (order_min, order_max, TE, TM flattened `[order][|β|][λ][s]`, the library's table).
pub(super) type Assembled = (i32, i32, Vec<f64>, Vec<f64>, EfficiencyTable);

/// Assembles the flattened arrays and the library's table from the solved nodes; `b` is
/// `[0.0]` for a classical table (`conical` false).
pub(super) fn assemble(
    cache: &Cache<'_, impl OrderSolver>,
    axes: (&[f64], &[f64], &[f64]),
    conical: bool,
    d: f64,
) -> Result<Assembled, TableError> {
    let (s, b, l) = axes;
    let mut lo = i32::MAX;
    let mut hi = i32::MIN;
    for &beta in b {
        for &lam in l {
            for &x in s {
                let o = cache.get((x, beta, lam));
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
        lo = 0;
        hi = 0;
    }
    let n = (hi - lo + 1) as usize * s.len() * b.len() * l.len();
    let mut te = vec![0.0; n];
    let mut tm = vec![0.0; n];
    for (kb, &beta) in b.iter().enumerate() {
        let cb = (1.0 - beta * beta).sqrt();
        for (j, &lam) in l.iter().enumerate() {
            for (i, &x) in s.iter().enumerate() {
                let o = cache.get((x, beta, lam));
                for m in lo..=hi {
                    // The loader's own test of evanescence: exactly 0 there.
                    let am = if conical { x * cb } else { x } + f64::from(m) * lam / d;
                    if 1.0 - am * am - beta * beta <= 0.0 {
                        continue;
                    }
                    let (a, t) = o.get(m);
                    let at = ((((m - lo) as usize * b.len() + kb) * l.len()) + j) * s.len() + i;
                    te[at] = a.max(0.0);
                    tm[at] = t.max(0.0);
                }
            }
        }
    }
    let table = if conical {
        EfficiencyTable::new_conical(
            d,
            lo,
            s.to_vec(),
            b.to_vec(),
            l.to_vec(),
            te.clone(),
            tm.clone(),
        )
    } else {
        EfficiencyTable::new(d, lo, s.to_vec(), l.to_vec(), te.clone(), tm.clone())
    }
    .map_err(TableError::Table)?;
    Ok((lo, hi, te, tm, table))
}
