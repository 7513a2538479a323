"""Tabulated order efficiencies on a (sin theta_i, lambda) grid: build, validate, interpolate, write.

The format is documented in docs/efficiency_tables.md; this module is its reference implementation
(`interpolate` is the rule the crate follows). A table is a JSON object:

    format "diffraction-efficiency-table", version 1, name, description,
    grating {profile, period_nm, depth_nm, duty, blaze_deg, metal, cover},
    symmetric (bool: eta_m(s) = eta_-m(-s) holds; the table is stored whole anyway),
    sin_theta_i [n_s] (strictly increasing, inside [-1, 1]),
    lambda_nm [n_l] (strictly increasing),
    order_min, order_max (every integer in between has a slice),
    te, tm: [n_orders][n_l][n_s] efficiencies (0 where the order is evanescent at the node),
    solver {...}, validation {...}, command, sha256.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
from dataclasses import dataclass
from pathlib import Path

import numpy as np

FORMAT = "diffraction-efficiency-table"
VERSION = 1
# A table's sum over orders may exceed 1 by at most this (solver round-off; a metal absorbs, so the
# true sums are well below 1: largest measured 0.98 for Ag).
SUM_TOLERANCE = 1e-6
# Efficiencies are written rounded to this many decimals (absolute 5e-7): far below the solver's
# convergence (1e-3) and the interpolation error, and it keeps the files small.
DECIMALS = 6
# The grazing ends of the sin(theta_i) grid: the solvers need cos(theta_i) > 0.
S_EDGE = 0.9999


# Extra nodes near grazing incidence: there order 0 changes fastest (it tends to 1 at grazing,
# and under a cover the TM specular passes a Brewster-like minimum near |s| = 0.9).
EDGE_NODES = (0.95, 0.98)


def s_grid(step: float) -> np.ndarray:
    n = round(1.0 / step)
    if abs(n * step - 1.0) > 1e-12:
        raise ValueError(f"sin-step: {step} must divide 1")
    inner = {round(-1.0 + i * step, 12) for i in range(1, 2 * n)}
    inner |= {e for e in EDGE_NODES} | {-e for e in EDGE_NODES}
    return np.array([-S_EDGE] + sorted(inner) + [S_EDGE])


def l_grid(lmin: float, lmax: float, step: float) -> np.ndarray:
    """lmin, lmin + step, ... below lmax, then lmax."""
    if not (lmax > lmin and step > 0):
        raise ValueError("lambda grid: need lambda-max > lambda-min and lambda-step > 0")
    n = int(math.floor((lmax - lmin) / step + 1e-9))
    nodes = [round(lmin + j * step, 9) for j in range(n + 1)]
    if lmax - nodes[-1] > 1e-9:
        nodes.append(lmax)
    return np.array(nodes)


def order_range(period_nm: float, s: np.ndarray, lam: np.ndarray) -> tuple[int, int]:
    """Every order that propagates in air at some node (|s + m*lambda/d| < 1)."""
    mmax = int(math.ceil(2.0 * period_nm / lam.min())) + 1
    ms = [m for m in range(-mmax, mmax + 1)
          if np.any(np.abs(s[None, :] + m * lam[:, None] / period_nm) < 1.0)]
    return min(ms), max(ms)


def cos_theta_m(period_nm: float, m: int, s, lam):
    sm = np.asarray(s) + m * np.asarray(lam) / period_nm
    c = 1.0 - sm * sm
    return np.where(c > 0, np.sqrt(np.maximum(c, 0.0)), 0.0)


# ---------------------------------------------------------------- interpolation (the reference rule)

# A corner closer than this to the order's Rayleigh line (cos^2(theta_m) <= 1e-6, cos(theta_m) <=
# 1e-3) is treated as evanescent: its eta and cos(theta_m) are both tiny and their ratio is
# dominated by rounding (a node that lies on the line up to float rounding holds the efficiency of a
# solve nudged off the line, a few 1e-5, over a cos(theta_m) of 1e-8).
GRAZING_CORNER = 1e-6


def interpolate(table: dict, pol: str, m: int, s: float, lam: float) -> float:
    """eta_m(s, lambda) by the documented rule (docs/efficiency_tables.md):

    1. clamp s and lambda to the grid's range;
    2. 0 if the order is evanescent there (|s + m*lambda/d| >= 1);
    3. else, over the four corners of the grid cell holding (s, lambda), the corners where the order
       propagates (cos^2(theta_m) > GRAZING_CORNER) carry q = eta * cos(theta_i) / cos(theta_m) (= |r_m|^2, smooth through the order's
       Rayleigh line and through grazing incidence); bilinear weights, renormalised over those
       corners (0 if none), give q at (s, lambda), and eta = q * cos(theta_m) / cos(theta_i) there.

    The order so appears exactly on its Rayleigh line with its square-root onset."""
    d = table["grating"]["period_nm"]
    if not (table["order_min"] <= m <= table["order_max"]):
        return 0.0
    S = table["sin_theta_i"]
    L = table["lambda_nm"]
    s = min(max(s, S[0]), S[-1])
    lam = min(max(lam, L[0]), L[-1])
    sm = s + m * lam / d
    if abs(sm) >= 1.0:
        return 0.0
    eta = table[pol][m - table["order_min"]]
    i = min(max(int(np.searchsorted(S, s, side="right")) - 1, 0), len(S) - 2)
    j = min(max(int(np.searchsorted(L, lam, side="right")) - 1, 0), len(L) - 2)
    tx = (s - S[i]) / (S[i + 1] - S[i])
    ty = (lam - L[j]) / (L[j + 1] - L[j])
    num = den = 0.0
    for ii, jj, w in ((i, j, (1 - tx) * (1 - ty)), (i + 1, j, tx * (1 - ty)),
                      (i, j + 1, (1 - tx) * ty), (i + 1, j + 1, tx * ty)):
        c = 1.0 - (S[ii] + m * L[jj] / d) ** 2
        if c > GRAZING_CORNER and w > 0.0:
            num += w * eta[jj][ii] * math.sqrt(1.0 - S[ii] ** 2) / math.sqrt(c)
            den += w
    if den == 0.0:
        return 0.0
    return math.sqrt(1.0 - sm * sm) / math.sqrt(1.0 - s * s) * num / den


def interpolate_normalised(table: dict, m: int, s: float, lam: float) -> tuple[float, float]:
    """(TE, TM) of order m at (s, lambda) as the crate returns them: `interpolate` for every stored
    order, then, per polarisation, every order scaled by 1/sum where the sum over the stored orders
    exceeds 1 (bilinear interpolation can overshoot between nodes), so sum eta <= 1 at every query."""
    out = []
    for pol in ("te", "tm"):
        etas = {k: interpolate(table, pol, k, s, lam) for k in range(table["order_min"], table["order_max"] + 1)}
        total = sum(etas.values())
        eta = etas.get(m, 0.0)
        out.append(eta / total if total > 1.0 else eta)
    return out[0], out[1]


# ---------------------------------------------------------------- validation on load and write


class TableError(ValueError):
    pass


def validate_table(t: dict) -> None:
    """The checks a reader must make; raises TableError naming the field."""
    if t.get("format") != FORMAT or t.get("version") != VERSION:
        raise TableError(f"format/version: expected {FORMAT!r} version {VERSION}")
    g = t["grating"]
    if not (g["period_nm"] > 0):
        raise TableError("grating.period_nm must be > 0")
    S = np.asarray(t["sin_theta_i"], dtype=float)
    L = np.asarray(t["lambda_nm"], dtype=float)
    if S.ndim != 1 or S.size < 2 or not np.all(np.diff(S) > 0) or S[0] < -1 or S[-1] > 1:
        raise TableError("sin_theta_i must be strictly increasing inside [-1, 1], at least 2 values")
    if L.ndim != 1 or L.size < 2 or not np.all(np.diff(L) > 0) or L[0] <= 0:
        raise TableError("lambda_nm must be strictly increasing and positive, at least 2 values")
    n_o = t["order_max"] - t["order_min"] + 1
    if n_o < 1:
        raise TableError("order_max must be >= order_min")
    for pol in ("te", "tm"):
        a = np.asarray(t[pol], dtype=float)
        if a.shape != (n_o, L.size, S.size):
            raise TableError(f"{pol}: shape {a.shape}, expected {(n_o, L.size, S.size)} [order][lambda][sin]")
        if not np.all(np.isfinite(a)) or np.any(a < 0):
            raise TableError(f"{pol}: efficiencies must be finite and >= 0")
        tot = a.sum(axis=0)
        if np.any(tot > 1.0 + SUM_TOLERANCE):
            raise TableError(f"{pol}: sum over orders {tot.max()} > 1 + {SUM_TOLERANCE}")
        for k in range(n_o):
            m = t["order_min"] + k
            ev = cos_theta_m(g["period_nm"], m, S[None, :], L[:, None]) == 0
            if np.any(a[k][ev] != 0):
                raise TableError(f"{pol}: order {m} is nonzero where it is evanescent")


def data_hash(t: dict) -> str:
    body = {k: v for k, v in t.items() if k != "sha256"}
    return hashlib.sha256(json.dumps(body, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


def write_json(t: dict, path: Path) -> None:
    """Validate, then write atomically (a failed run leaves an existing file as it was)."""
    validate_table(t)
    t = dict(t)
    t["sha256"] = data_hash(t)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_suffix(path.suffix + ".tmp")
    text = json.dumps(t, indent=None, separators=(",", ":"))
    tmp.write_text(text + "\n", encoding="utf-8")
    os.replace(tmp, path)


def read_json(path: Path) -> dict:
    t = json.loads(path.read_text(encoding="utf-8"))
    if t.get("sha256") != data_hash(t):
        raise TableError(f"{path}: sha256 does not match the contents")
    validate_table(t)
    return t


# ---------------------------------------------------------------- building


@dataclass
class Grid:
    sin_step: float = 0.1
    lambda_min: float = 360.0
    lambda_max: float = 830.0
    lambda_step: float = 20.0


def _row(args):
    """All s nodes of one wavelength, each converged on its own (fmm.solve_converged: the count
    raised x1.5 until no order changes by 1e-3). Returns (j, te[n_o][n_s], tm, dropped [te, tm],
    largest efficiency zeroed on a Rayleigh node, largest count, largest last change)."""
    import fmm

    g, lam, s_nodes, nh0, order_min, n_o, j, known, fixed = args
    te = np.zeros((n_o, s_nodes.size))
    tm = np.zeros_like(te)
    dropped = [0.0, 0.0]
    zeroed, nh_max, change = 0.0, 0, 0.0
    unconverged = []
    for i, s in enumerate(s_nodes):
        if float(s) in known:  # a node of an earlier table of the same grating
            te[:, i], tm[:, i] = known[float(s)]
            continue
        try:
            if fixed:
                res, ch = fmm.solve_once(g, lam, float(s), nh0), 0.0
            else:
                c = fmm.solve_converged(g, lam, float(s), nh_start=nh0)
                res, ch = c.result, c.change
        except fmm.NotConverged as e:
            # Kept at the cap's count and listed in the table (solver.unconverged_nodes).
            res, ch = e.last, e.change
            unconverged.append({"lambda_nm": lam, "sin_theta_i": float(s), "harmonics": res.nh, "change": ch})
        nh_max, change = max(nh_max, res.nh), max(change, ch if ch == ch else 0.0)
        a = fmm.to_air(g, lam, float(s), res)
        dropped = [max(dropped[0], a.dropped_te), max(dropped[1], a.dropped_tm)]
        for m, e_te, e_tm in zip(a.orders, a.te, a.tm):
            nominal = s + m * lam / g.period_nm
            if abs(nominal) >= 1.0:  # a Rayleigh-nudged solve: the node itself is on the line
                zeroed = max(zeroed, e_te, e_tm)
                continue
            te[m - order_min, i] = max(e_te, 0.0)
            tm[m - order_min, i] = max(e_tm, 0.0)
    return j, te, tm, dropped, zeroed, nh_max, change, unconverged


def _pool_map(fn, tasks, workers):
    if workers <= 1:
        return [fn(t) for t in tasks]
    import multiprocessing as mp

    with mp.get_context("fork").Pool(workers) as pool:
        return list(pool.imap_unordered(fn, tasks))


def build(g, grid: Grid, name: str, description: str, command: str, workers: int = 2,
          nh: int | None = None, interp_points: int = 32, seed: int = 1,
          log=print, reuse: dict | None = None, fixed_nh: int | None = None, check_points: int = 8) -> dict:
    """The table of grating g on `grid`. `reuse`: an earlier table of the same grating (same
    geometry, metal, cover, orders) whose nodes are copied instead of solved again; its solver
    records (counts, unconverged nodes, dropped power) are carried over.

    `fixed_nh`: solve every node at this one count instead of converging each (for costly tables),
    then check `check_points` random nodes against NH_GROWTH times the count; the table records it."""
    import fmm

    t0 = time.perf_counter()
    S = s_grid(grid.sin_step)
    L = l_grid(grid.lambda_min, grid.lambda_max, grid.lambda_step)
    omin, omax = order_range(g.period_nm, S, L)
    n_o = omax - omin + 1
    # nh: the starting count of every node's convergence (default: fmm.first_nh).
    sym = g.symmetric
    s_solve = S[S >= 0] if sym else S
    known_rows = [{} for _ in L]
    nh_max, worst_conv, unconverged = 0, 0.0, []
    reused = 0
    if reuse is not None:
        rg = reuse["grating"]
        same = all(rg[k] == v for k, v in (("profile", g.profile), ("period_nm", g.period_nm), ("depth_nm", g.depth_nm),
                                              ("duty", g.duty), ("blaze_deg", g.blaze_deg), ("metal", g.metal), ("cover", g.cover)))
        if not same or (reuse["order_min"], reuse["order_max"]) != (omin, omax):
            raise ValueError("reuse: a table of another grating")
        for jj, lam in enumerate(reuse["lambda_nm"]):
            if lam in list(L):
                j = list(L).index(lam)
                for ii, s in enumerate(reuse["sin_theta_i"]):
                    known_rows[j][float(s)] = (np.array([reuse["te"][k][jj][ii] for k in range(n_o)]),
                                               np.array([reuse["tm"][k][jj][ii] for k in range(n_o)]))
                    reused += 1
        rs = reuse["solver"]
        nh_max, worst_conv = rs["harmonics"], rs["convergence_max_last_change"]
        unconverged = list(rs.get("unconverged_nodes", []))
    if fixed_nh is not None:
        nh = fixed_nh
    tasks = [(g, float(lam), s_solve, nh, omin, n_o, j, known_rows[j], fixed_nh is not None) for j, lam in enumerate(L)]
    te = np.zeros((n_o, L.size, S.size))
    tm = np.zeros_like(te)
    dropped = [0.0, 0.0] if reuse is None else [reuse["solver"]["cover_dropped_max"]["te"], reuse["solver"]["cover_dropped_max"]["tm"]]
    zeroed = 0.0 if reuse is None else reuse["validation"]["rayleigh_node_zeroed_max"]
    for j, a_te, a_tm, dr, z, nhj, chj, unc in _pool_map(_row, tasks, workers):
        nh_max, worst_conv = max(nh_max, nhj), max(worst_conv, chj)
        unconverged += unc
        dropped = [max(dropped[0], dr[0]), max(dropped[1], dr[1])]
        zeroed = max(zeroed, z)
        if sym:
            n_neg = int(np.sum(S < 0))
            te[:, j, n_neg:] = a_te
            tm[:, j, n_neg:] = a_tm
            # eta_m(-s) = eta_-m(s); the s grid is symmetric, so column n_neg - 1 - i mirrors n_neg + i + (0 is shared)
            for i in range(n_neg):
                src = S.size - 1 - i
                te[:, j, i] = te[::-1, j, src] if omin == -omax else _mirror(te[:, j, src], omin, omax)
                tm[:, j, i] = tm[::-1, j, src] if omin == -omax else _mirror(tm[:, j, src], omin, omax)
        else:
            te[:, j, :] = a_te
            tm[:, j, :] = a_tm
    solve_s = time.perf_counter() - t0
    te = np.round(te, DECIMALS)
    tm = np.round(tm, DECIMALS)
    for k in range(n_o):  # rounding cannot revive an evanescent order, but make it explicit
        ev = cos_theta_m(g.period_nm, omin + k, S[None, :], L[:, None]) == 0
        te[k][ev] = 0.0
        tm[k][ev] = 0.0

    table = {
        "format": FORMAT,
        "version": VERSION,
        "name": name,
        "description": description,
        "grating": {"profile": g.profile, "period_nm": g.period_nm, "depth_nm": g.depth_nm,
                    "duty": g.duty, "blaze_deg": g.blaze_deg, "metal": g.metal, "cover": g.cover},
        "symmetric": sym,
        "sin_theta_i": [float(v) for v in S],
        "lambda_nm": [float(v) for v in L],
        "order_min": omin,
        "order_max": omax,
        "te": te.tolist(),
        "tm": tm.tolist(),
    }

    fixed_check = None
    if fixed_nh is not None:
        rng0 = np.random.default_rng(seed + 1)
        nh_max, worst_conv = fixed_nh, 0.0
        for _ in range(check_points):
            lam, s = float(rng0.choice(L)), float(rng0.choice(S))
            a = fmm.solve_once(g, lam, s, fixed_nh)
            b = fmm.solve_once(g, lam, s, fmm._odd(fixed_nh * fmm.NH_GROWTH))
            worst_conv = max(worst_conv, fmm._max_change(a, b))
        fixed_check = {"harmonics": fixed_nh, "checked_against": fmm._odd(fixed_nh * fmm.NH_GROWTH),
                       "random_nodes": check_points, "max_change": worst_conv}
        log(f"  fixed count {fixed_nh}: max change against {fixed_check['checked_against']} at {check_points} random nodes {worst_conv:.2e}")
    unconverged.sort(key=lambda u: (u["lambda_nm"], u["sin_theta_i"]))
    log(f"  nodes converged: largest count {nh_max}, largest last change {worst_conv:.2e}; "
        f"{len(unconverged)} nodes not converged to 1e-3 by the cap (kept at the cap's count); {reused} nodes reused")

    check = interpolation_check(g, table, interp_points, seed, nh, fixed_nh is not None)
    total_s = time.perf_counter() - t0
    table["solver"] = {
        "method": "nannos Fourier modal method, Li's rule (formulation tangent)" if g.profile == "lamellar"
        else "C method with Li's factorisation (python_ref/cmethod.py)",
        "harmonics": nh_max,
        "convergence": ("every node: the harmonic count raised x1.5 until no order (TE or TM) changed by 1e-3"
                        if fixed_check is None else "one fixed harmonic count for every node, checked at random nodes (fixed_count)"),
        "fixed_count": fixed_check,
        "convergence_max_last_change": worst_conv,
        "unconverged_nodes": unconverged,
        "rayleigh_nudge": fmm.RAYLEIGH_NUDGE,
        "cover_model": "none" if g.cover == "none" else
        "single pass through a flat air-polycarbonate surface (Sultanova 2009 Sellmeier), Fresnel "
        "transmission in and out, the surface's own reflection added to order 0; totally reflected "
        "orders and second passes dropped",
        "cover_dropped_max": {"te": dropped[0], "tm": dropped[1]},
        "seconds": round(total_s, 1),
    }
    table["validation"] = {
        "sum_tolerance": SUM_TOLERANCE,
        "max_sum": {"te": float(te.sum(axis=0).max()), "tm": float(tm.sum(axis=0).max())},
        **check,
        "rayleigh_node_zeroed_max": zeroed,
    }
    table["command"] = command
    log(f"  {name}: {n_o} orders, {L.size} x {S.size} nodes, up to {nh_max} harmonics, solves {solve_s:.0f} s, total {total_s:.0f} s; "
        f"interpolation |error| max {table['validation']['interpolation_abs_error_max']:.2e}, p95 {table['validation']['interpolation_abs_error_p95']:.2e}")
    return table


def interpolation_check(g, table: dict, points: int, seed: int, nh: int | None, fixed: bool) -> dict:
    """Fresh solves at random points inside grid cells against the interpolation rule."""
    import fmm

    S, L = np.asarray(table["sin_theta_i"]), np.asarray(table["lambda_nm"])
    rng = np.random.default_rng(seed)
    err_all, err_big, n_cmp = [], [], 0
    for _ in range(points):
        i = int(rng.integers(0, S.size - 1))
        j = int(rng.integers(0, L.size - 1))
        s = float(S[i] + rng.uniform(0.2, 0.8) * (S[i + 1] - S[i]))
        lam = float(L[j] + rng.uniform(0.2, 0.8) * (L[j + 1] - L[j]))
        try:
            r = fmm.solve_once(g, lam, s, nh) if fixed else fmm.solve_converged(g, lam, s, nh_start=nh).result
        except fmm.NotConverged as e:
            r = e.last
        a = fmm.to_air(g, lam, s, r)
        for pol, eff in (("te", a.te), ("tm", a.tm)):
            for m, e in zip(a.orders, eff):
                if abs(s + m * lam / g.period_nm) >= 1:
                    continue
                d = abs(interpolate(table, pol, int(m), s, lam) - e)
                err_all.append(d)
                n_cmp += 1
                if e >= 0.01:
                    err_big.append(d / e)
    err_all = np.array(err_all) if err_all else np.zeros(1)
    err_big = np.array(err_big) if err_big else np.zeros(1)
    return {
        "interpolation_points": points,
        "interpolation_compared_orders": n_cmp,
        "interpolation_abs_error_max": float(err_all.max()),
        "interpolation_abs_error_p95": float(np.percentile(err_all, 95)),
        "interpolation_abs_error_median": float(np.median(err_all)),
        "interpolation_rel_error_p95_eta_ge_0.01": float(np.percentile(err_big, 95)),
        "interpolation_rel_error_max_eta_ge_0.01": float(err_big.max()),
    }


def _mirror(col: np.ndarray, omin: int, omax: int) -> np.ndarray:
    """eta_m at -s from eta at s: order m takes order -m's value (0 if -m is outside the range)."""
    out = np.zeros_like(col)
    for k in range(col.size):
        m = omin + k
        if omin <= -m <= omax:
            out[k] = col[-m - omin]
    return out
