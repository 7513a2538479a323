#!/usr/bin/env python3
"""Rigorous reflection efficiencies of 1-D lamellar gratings in conical mounts (nannos, Li's rule).

    python3 python_ref/conical.py            # tests/data/rigorous_conical.csv and tests/data/nannos_timing.csv
    python3 python_ref/conical.py --timing   # only the timing file
    python3 python_ref/conical.py --check    # cheap: the committed CSV's data hash

Needs `pip install -r python_ref/requirements-rigorous.txt`; `--check` (run by `generate.py --check`
through part `rigorous`) needs only the standard library. Resumable: finished cases are cached in
python_ref/.cache/conical.jsonl.

Conventions (docs/efficiency_tables.md, DESIGN.md "Conical incidence and covers"): x across the
grooves (the grating vector), y along them, z the normal, light from z > 0. The incident direction
of travel has polar angle theta from the normal and azimuth phi from the grating vector, so its
direction cosines are alpha = sin(theta) cos(phi) across and beta = sin(theta) sin(phi) along the
grooves; order m leaves with alpha_m = alpha + m lambda/d, beta_m = beta and propagates iff
alpha_m^2 + beta^2 < 1. nannos's PlaneWave(angles=(theta, phi, psi)) has this wave vector; its
field amplitude is E = cos(psi) p_hat + sin(psi) s_hat with s_hat = (-sin phi, cos phi, 0) (normal
to the plane of incidence) and p_hat = (cos theta cos phi, cos theta sin phi, -sin theta) (in it):
psi = 90 deg is s, psi = 0 is p. At phi = 0 s is TE (E along the grooves) and p is TM. Checked
below against the Fresnel equations on a flat metal at oblique azimuths (`_check_fresnel`).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("NANNOS_LOGLEVEL", "WARNING")
sys.path.insert(0, str(Path(__file__).resolve().parent))

import rigorous  # noqa: E402  (hash helpers, versions; imports nothing heavy)

REPO = Path(__file__).resolve().parent.parent
OUTPUT = Path("tests/data/rigorous_conical.csv")
TIMING_OUTPUT = Path("tests/data/nannos_timing.csv")
CMD = "python3 python_ref/conical.py"
WORKERS = int(os.environ.get("RIGOROUS_WORKERS", "2"))
CACHE = REPO / "python_ref" / ".cache" / "conical.jsonl"

# Convergence: counts nh_0 = first_nh (fmm.py), nh_{k+1} = odd(1.5 nh_k). Lamellar TM-like fields
# converge like 1/N and not monotonically, so one small step is not enough: a case is converged at
# nh_k when the last two steps both changed no order (s or p) by TOL or more and nh_k >= NH_FLOOR.
TOL = 1e-3
NH_FLOOR = 161
NH_CAP = 361

# The grid. theta = 0 has no azimuth (alpha = beta = 0): only phi = 0 there.
METALS = ["Al", "Ag"]
GEOMETRIES = [(d, h, 0.5) for d in (500.0, 1000.0, 1600.0) for h in (50.0, 120.0)] + [(1000.0, h, 0.25) for h in (50.0, 120.0)]
LAMBDAS = [450.0, 550.0, 650.0]
ANGLES = [(0.0, 0.0)] + [(t, p) for t in (30.0, 60.0) for p in (0.0, 30.0, 60.0, 80.0)]
# Lossless dielectric gratings (n = 1.5 ridges on an n = 1.5 substrate): the transmitted power is
# written too, so R + T = 1 can be checked.
DIELECTRIC = "1.5+0i"
DIELECTRIC_CASES = [((1000.0, 300.0, 0.5), lam, t, p) for lam in (450.0, 650.0) for t, p in ((30.0, 0.0), (30.0, 60.0), (60.0, 30.0), (60.0, 80.0))]

POLS = (("s", 90.0), ("p", 0.0))


def cases():
    out = []
    for metal in METALS:
        for geo in GEOMETRIES:
            for lam in LAMBDAS:
                for t, p in ANGLES:
                    out.append((geo, metal, lam, t, p))
    for geo, lam, t, p in DIELECTRIC_CASES:
        out.append((geo, DIELECTRIC, lam, t, p))
    return out


def _key(case) -> str:
    (d, h, duty), metal, lam, t, p = case
    return json.dumps([d, h, duty, metal, lam, t, p])


def solve_once(case, nh: int, want_transmission: bool = False) -> dict:
    """One solve at `nh` harmonics: {order: (eta_s, eta_p)} of the propagating reflected orders,
    plus the transmitted totals when asked."""
    import nannos as nn
    import numpy as np

    import fmm

    (d, h, duty), metal, lam, t, p = case
    g = fmm.Grating("lamellar", d, h, metal, duty=duty)
    layers, _ = fmm._layers(g, lam, 1)
    pw_p = nn.PlaneWave(wavelength=float(lam), angles=(t, p, 0.0))
    sim = nn.Simulation(layers, pw_p, nh=int(nh), formulation=fmm.FORMULATION)
    r_p, t_p = sim.diffraction_efficiencies(orders=True)
    # The S-matrix does not depend on the incident polarisation: the s solve reuses the layers'
    # eigenmodes and only changes the incident amplitude vector (as fmm.solve_staircase does).
    pw_s = nn.PlaneWave(wavelength=float(lam), angles=(t, p, 90.0))
    sim.excitation = pw_s
    a0 = np.zeros(2 * sim.nh, dtype=complex)
    a0[sim.index_zeroth_order] = complex(pw_s.a0[0])
    a0[sim.nh + sim.index_zeroth_order] = complex(pw_s.a0[1])
    sim.a0 = a0
    r_s, t_s = sim.diffraction_efficiencies(orders=True)
    harm = np.asarray(sim.harmonics[0]).astype(int)
    alpha = math.sin(math.radians(t)) * math.cos(math.radians(p))
    beta = math.sin(math.radians(t)) * math.sin(math.radians(p))
    out = {}
    for i, m in enumerate(harm.tolist()):
        q = (alpha + m * lam / d) ** 2 + beta**2
        if abs(q - 1.0) < 1e-9:
            raise ValueError(f"{case}: order {m} is on its Rayleigh line")
        if q < 1.0:
            out[m] = (float(np.real(r_s[i])), float(np.real(r_p[i])))
    res = {"orders": out, "nh": int(sim.nh)}
    if want_transmission:
        res["t"] = (float(np.sum(np.real(np.asarray(t_s)))), float(np.sum(np.real(np.asarray(t_p)))))
        res["r_all"] = (float(np.sum(np.real(np.asarray(r_s)))), float(np.sum(np.real(np.asarray(r_p)))))
    return res


def _change(a: dict, b: dict) -> float:
    assert a.keys() == b.keys()
    return max(max(abs(a[m][0] - b[m][0]), abs(a[m][1] - b[m][1])) for m in a)


def run_case(case):
    import fmm

    (d, h, duty), metal, lam, t, p = case
    g = fmm.Grating("lamellar", d, h, metal, duty=duty)
    dielectric = metal == DIELECTRIC
    t0 = time.perf_counter()
    nh = fmm.first_nh(g, lam, 1.0)
    prev = solve_once(case, nh, dielectric)
    changes: list[float] = []
    while True:
        nh = fmm._odd(nh * fmm.NH_GROWTH)
        if nh > NH_CAP:
            return {"key": _key(case), "error": f"not converged by {prev['nh']} harmonics (last two changes "
                    + ", ".join(f"{c:.2g}" for c in changes[-2:]) + ")", "seconds": time.perf_counter() - t0}
        cur = solve_once(case, nh, dielectric)
        changes.append(_change(prev["orders"], cur["orders"]))
        if len(changes) >= 2 and max(changes[-2:]) < TOL and cur["nh"] >= NH_FLOOR:
            rec = {"key": _key(case), "error": None, "seconds": time.perf_counter() - t0, "nh": cur["nh"],
                   "nh_prev": prev["nh"], "change": changes[-1], "change_before": changes[-2],
                   "orders": {str(m): [v[0], v[1], v[0] - prev["orders"][m][0], v[1] - prev["orders"][m][1]]
                              for m, v in sorted(cur["orders"].items())}}
            if dielectric:
                rec["t"], rec["r_all"] = cur["t"], cur["r_all"]
            return rec
        prev = cur


def _load_cache() -> dict:
    out = {}
    if CACHE.exists():
        for line in CACHE.read_text().splitlines():
            rec = json.loads(line)
            out[rec["key"]] = rec
    return out


def _order(case) -> str:
    # Every case costs about the same (the count floor dominates), so they run in a fixed shuffled
    # order: an interrupted run's cached cases (--from-cache) cover the whole grid.
    import hashlib

    return hashlib.sha256(_key(case).encode()).hexdigest()


def _check_fresnel() -> float:
    """Flat Al: R_s, R_p from nannos at oblique azimuths against Fresnel; the largest difference."""
    import fmm

    worst = 0.0
    n = fmm.metal_index("Al", 550.0)
    for t, p in ((30.0, 60.0), (60.0, 80.0), (45.0, 30.0)):
        r = solve_once(((1000.0, 0.0, 0.5), "Al", 550.0, t, p), 21)["orders"][0]
        rs, rp = fmm.fresnel_rs_rp(1.0, n, math.sin(math.radians(t)))
        worst = max(worst, abs(r[0] - rs), abs(r[1] - rp))
    if worst > 1e-9:
        raise SystemExit(f"polarisation labels: flat Al differs from Fresnel by {worst:.3g}")
    return worst


def _classical_crosscheck(results: dict) -> tuple[float, int, int]:
    """phi = 0 rows against tests/data/rigorous_orders.csv (TE = s, TM = p) where both have the case:
    the largest difference, the number of order values compared and how many differ by more than 1e-3."""
    import csv

    ref = {}
    lines = [l for l in (REPO / rigorous.ORDERS_OUTPUT).read_text().splitlines() if not l.startswith("#")]
    for r in csv.DictReader(lines):
        if r["profile"] != "lamellar":
            continue
        k = (float(r["period_nm"]), float(r["depth_nm"]), float(r["duty"]), r["metal"], float(r["lambda_nm"]),
             float(r["theta_deg"]), "s" if r["polarisation"] == "TE" else "p", int(r["order"]))
        ref[k] = float(r["efficiency"])
    worst, n, over = 0.0, 0, 0
    for case, rec in results.items():
        (d, h, duty), metal, lam, t, p = case
        if p != 0.0:
            continue
        for m, v in rec["orders"].items():
            for j, pol in enumerate("sp"):
                k = (d, h, duty, metal, lam, t, pol, int(m))
                if k in ref:
                    worst = max(worst, abs(ref[k] - v[j]))
                    n += 1
                    over += abs(ref[k] - v[j]) > 1e-3
    return worst, n, over


def timing() -> Path:
    """nannos wall time per solve at fixed truncations (median of 3), both polarisations from one
    set of eigenmodes as above, and one polarisation alone."""
    import statistics

    import nannos as nn

    import fmm

    rows = ["case,metal,period_nm,depth_nm,duty,lambda_nm,theta_deg,phi_deg,harmonics,seconds_one_polarisation,seconds_both"]
    for (d, h, duty), metal, lam, t, p in (((1000.0, 120.0, 0.5), "Al", 550.0, 30.0, 0.0),
                                           ((1000.0, 120.0, 0.5), "Al", 550.0, 30.0, 60.0),
                                           ((1600.0, 50.0, 0.5), "Ag", 450.0, 60.0, 30.0)):
        case = ((d, h, duty), metal, lam, t, p)
        g = fmm.Grating("lamellar", d, h, metal, duty=duty)
        for nh in (41, 81, 121, 201):
            one, both = [], []
            for _ in range(3):
                t0 = time.perf_counter()
                layers, _ = fmm._layers(g, lam, 1)
                sim = nn.Simulation(layers, nn.PlaneWave(wavelength=lam, angles=(t, p, 0.0)), nh=nh, formulation=fmm.FORMULATION)
                sim.diffraction_efficiencies(orders=True)
                one.append(time.perf_counter() - t0)
                t0 = time.perf_counter()
                solve_once(case, nh)
                both.append(time.perf_counter() - t0)
            kind = "classical" if p == 0 else "conical"
            rows.append(f"{kind},{metal},{d:g},{h:g},{duty:g},{lam:g},{t:g},{p:g},{nh},"
                        f"{statistics.median(one):.4g},{statistics.median(both):.4g}")
            print(rows[-1], flush=True)
    head = [
        "# nannos wall time per solve of a lamellar grating at fixed harmonic counts (median of 3 runs).",
        f"# Made by `{CMD} --timing` with {rigorous._versions()}, formulation=\"{fmm.FORMULATION}\", "
        f"epsilon on {fmm.DISCRETIZATION} points, one BLAS thread (OMP_NUM_THREADS=1), on a shared 2-core machine",
        f"# (other processes running; load averages {', '.join(f'{x:.1f}' for x in os.getloadavg())} (1, 5, 15 min) when written).",
        "# Compare ratios measured in one run, not these absolute times.",
        "# seconds_one_polarisation: layers, eigenmodes, S-matrix and the efficiencies of one incident polarisation;",
        "# seconds_both: the same plus the second polarisation from the same eigenmodes (conical.py's solve_once).",
        "# nannos solves the vector (2N x 2N) eigenproblem in every mount, classical included; `harmonics` is N.",
    ]
    (REPO / TIMING_OUTPUT).write_text("\n".join(head + rows) + "\n", encoding="utf-8")
    return TIMING_OUTPUT


def build(from_cache: bool = False) -> Path:
    import multiprocessing as mp

    import fmm

    _check_fresnel()
    all_cases = cases()
    cache = _load_cache()
    todo = [] if from_cache else sorted((c for c in all_cases if _key(c) not in cache), key=_order)
    CACHE.parent.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    print(f"  {len(all_cases)} cases, {len(all_cases) - len(todo)} from the cache", flush=True)
    with mp.get_context("fork").Pool(WORKERS) as pool, CACHE.open("a") as fh:
        for n, rec in enumerate(pool.imap_unordered(run_case, todo)):
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            cache[rec["key"]] = rec
            if n % 20 == 0:
                print(f"  {n + 1}/{len(todo)} cases, {time.perf_counter() - t0:.0f} s", flush=True)
    results, failed, missing, cpu = {}, [], [], 0.0
    for case in all_cases:
        rec = cache.get(_key(case))
        if rec is None:
            missing.append(case)
            continue
        cpu += rec["seconds"]
        if rec["error"]:
            failed.append((case, rec["error"]))
        else:
            results[case] = rec
    cols = ["profile", "metal", "period_nm", "depth_nm", "duty", "lambda_nm", "theta_deg", "phi_deg", "polarisation",
            "order", "alpha_m", "beta", "efficiency", "harmonics", "nh_change", "transmitted"]
    lines = [",".join(cols)]
    f = rigorous._fmt
    worst_change, worst_sum, worst_energy, max_nh = 0.0, 0.0, 0.0, 0
    for case in all_cases:
        rec = results.get(case)
        if rec is None:
            continue
        (d, h, duty), metal, lam, t, p = case
        alpha = math.sin(math.radians(t)) * math.cos(math.radians(p))
        beta = math.sin(math.radians(t)) * math.sin(math.radians(p))
        max_nh = max(max_nh, rec["nh"])
        for j, pol in enumerate("sp"):
            total = sum(v[j] for v in rec["orders"].values())
            worst_sum = max(worst_sum, total)
            if total > 1.0 + 1e-9 or min(v[j] for v in rec["orders"].values()) < -1e-9:
                raise SystemExit(f"{case} {pol}: efficiencies {rec['orders']}")
            trans = ""
            if "t" in rec:
                trans = f(rec["t"][j])
                worst_energy = max(worst_energy, abs(rec["r_all"][j] + rec["t"][j] - 1.0))
            for m, v in rec["orders"].items():
                worst_change = max(worst_change, abs(v[2 + j]))
                lines.append(",".join([
                    "lamellar", metal, f(d), f(h), f(duty), f(lam), f(t), f(p), pol, m,
                    f(alpha + int(m) * lam / d), f(beta), f(max(v[j], 0.0)), str(rec["nh"]), f"{v[2 + j]:.3g}", trans,
                ]))
    cross, ncross, nover = _classical_crosscheck(results)
    wall = time.perf_counter() - t0
    comments = [
        "Rigorous reflection efficiencies of 1-D lamellar gratings in conical mounts, one row per propagating reflected order",
        "and incident polarisation.",
        f"Made by python_ref/conical.py (geometry and metals from python_ref/fmm.py) with {rigorous._versions()}:",
        f"Fourier modal method, formulation=\"{fmm.FORMULATION}\" (Li's factorisation rule), epsilon sampled on {fmm.DISCRETIZATION} points",
        "per period (cell centres; nannos's Toeplitz matrices come from the FFT of these samples).",
        f"Regenerate with `{CMD}` ({WORKERS} processes; {cpu / 60:.0f} min of solves in all, on a shared 2-core machine).",
        "Frame: x across the grooves (the grating vector), y along them, z the normal; the light comes from z > 0 in air.",
        "Grating: raised metal ridges of width duty*d (0 <= x < duty*d) and height depth_nm on the same metal, filling z < 0.",
        "Metal: n + ik from python_ref/data/metals (Al: Rakic 1995, Ag: Johnson & Christy 1972), linear in wavelength;",
        f"metal {DIELECTRIC}: a lossless dielectric (ridges and substrate), for the energy balance.",
        "Incidence: the direction of travel has polar angle theta_deg and azimuth phi_deg (from +x, in the surface plane):",
        "alpha = sin(theta) cos(phi) across and beta = sin(theta) sin(phi) along the grooves (so wi = (-alpha, -beta, cos theta)).",
        "Order m leaves with alpha_m = alpha + m lambda/d, beta_m = beta (columns alpha_m, beta); it propagates iff",
        "alpha_m^2 + beta^2 < 1; only those are listed (the others carry 0). phi = 0 is the classical mount.",
        "polarisation: s = E normal to the plane of incidence, along (-sin phi, cos phi, 0); p = E in it (nannos psi = 90 and",
        "0 deg; checked against Fresnel on flat Al at oblique azimuths). At phi = 0, s = TE and p = TM; unpolarised = (s + p)/2.",
        "efficiency: the order's reflected z-flux (both output polarisations) over the incident z-flux.",
        "transmitted (dielectric rows only): the total transmitted efficiency of the case and polarisation.",
        f"harmonics: the Fourier harmonic count of the values; counts start at fmm.first_nh and grow by x{fmm.NH_GROWTH};",
        f"a case is converged when the last two steps both changed no order (s or p) by {TOL} or more and harmonics >= {NH_FLOOR}",
        f"(lamellar p/TM converges like 1/N, not monotonically); cap {NH_CAP} (the last count tried is the sequence's last below it, 267-323; Ag, with its",
        "surface plasmons, converges slowest). nh_change: this order's signed change",
        "between the last two counts (value at the previous count = efficiency - nh_change; its harmonic count is the",
        "previous odd(count/1.5) step of the sequence). The error left is of the order of 2 |nh_change| for 1/N convergence.",
        "Grid: lamellar duty 0.5 at d = 500, 1000, 1600 nm and duty 0.25 at d = 1000 nm; depths 50, 120 nm; metals "
        + ", ".join(METALS) + ";",
        "lambda " + ", ".join(f"{v:g}" for v in LAMBDAS) + " nm; (theta, phi) = " + ", ".join(f"({a:g}, {b:g})" for a, b in ANGLES)
        + " deg; dielectric d = 1000 nm,",
        "depth 300 nm, duty 0.5 at lambda 450, 650 nm and (theta, phi) = (30, 0), (30, 60), (60, 30), (60, 80) deg.",
        f"Checks: phi = 0 rows against tests/data/rigorous_orders.csv (same cases, TE = s, TM = p): max difference {cross:.3g}",
        f"over {ncross} order values, {nover} of them above 1e-3 (that file stopped at one step below 1e-3, this one",
        f"at two and a higher count); dielectric cases: max |sum R + sum T - 1| = {worst_energy:.3g}.",
        f"Cases: {len(all_cases)}, {len(results)} converged, {len(failed)} not converged by {NH_CAP} harmonics (left out):",
    ]
    for (geo, metal, lam, t, p), err in failed:
        comments.append(f"  {metal} d = {geo[0]:g} nm, depth {geo[1]:g} nm, duty {geo[2]:g}, {lam:g} nm, theta {t:g}, phi {p:g}: {err}")
    if missing:
        comments.append(f"Not computed in this run ({len(missing)} cases; `{CMD}` computes them):")
        for (geo, metal, lam, t, p) in missing:
            comments.append(f"  {metal} d = {geo[0]:g} nm, depth {geo[1]:g} nm, duty {geo[2]:g}, {lam:g} nm, theta {t:g}, phi {p:g}")
    comments.append(f"Rows: {len(lines) - 1}; largest harmonic count {max_nh}; largest |nh_change| {worst_change:.3g}; "
                    f"largest sum over orders {worst_sum:.6f}.")
    rigorous.write_with_hash(REPO / OUTPUT, comments, lines)
    print(f"wrote {OUTPUT}: {len(lines) - 1} rows, {len(results)} cases, {len(failed)} not converged, "
          f"{len(missing)} missing, {wall / 60:.1f} min wall, {cpu / 60:.1f} min of solves; cross-check {cross:.3g}")
    return OUTPUT


def check(root: Path = REPO) -> list[str]:
    e = rigorous.check_hashed(root / OUTPUT)
    return [e] if e else []


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--timing", action="store_true")
    ap.add_argument("--from-cache", action="store_true", help="write the CSV from the cached cases only")
    args = ap.parse_args()
    if args.check:
        errs = check()
        for e in errs:
            print(e)
        return 1 if errs else 0
    if args.timing:
        timing()
        return 0
    build(args.from_cache)
    if not args.from_cache:
        timing()
    return 0


if __name__ == "__main__":
    sys.exit(main())
