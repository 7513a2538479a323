#!/usr/bin/env python3
"""Rigorous order efficiencies of metal relief gratings (Fourier modal method, nannos, Li's rule).

    python3 python_ref/rigorous.py --validate        # the solver's checks; exit 1 on any failure (~1 min)
    python3 python_ref/rigorous.py --orders          # tests/data/rigorous_orders.csv (long: see its header)
    python3 python_ref/rigorous.py --presets         # data/efficiencies/*.json and src/data/efficiency_presets_data.rs
    python3 python_ref/rigorous.py --all             # all three, in this order
    python3 python_ref/rigorous.py --check           # cheap: the committed files' hashes and headers

Needs `pip install -r python_ref/requirements-rigorous.txt` (nannos and its dependencies); the cheap
`--check` (run by `generate.py --check`) needs only the standard library.

The solver and its conventions are in fmm.py; the table format in docs/efficiency_tables.md.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True
# One BLAS thread per process: the runs use their own process pool.
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))

REPO = Path(__file__).resolve().parent.parent
ORDERS_OUTPUT = Path("tests/data/rigorous_orders.csv")
ORDERS_CMD = "python3 python_ref/rigorous.py --orders"
HASH_PREFIX = "# sha256 of the lines below the comments: "
WORKERS = int(os.environ.get("RIGOROUS_WORKERS", "2"))


def _versions() -> str:
    import nannos
    import numpy as np
    import scipy

    return f"nannos {nannos.__version__}, numpy {np.__version__}, scipy {scipy.__version__}"


def _fmt(v: float) -> str:
    v = float(v)
    if not math.isfinite(v):
        raise ValueError(f"non-finite value {v!r}")
    return repr(v)


# ---------------------------------------------------------------- validation


# Reciprocity holds for the exact efficiencies; each side is converged to this, so they may differ by twice it.
RECIPROCITY_TOL = 5e-4


class Failed(AssertionError):
    pass


def _expect(ok: bool, what: str, failures: list[str]) -> None:
    if not ok:
        failures.append(what)
        print("  FAILED: " + what, flush=True)


def validate() -> dict:
    """The solver's checks. Raises Failed (exit 1) if any fails; returns the measured numbers."""
    import numpy as np

    import fmm
    import metals

    failures: list[str] = []
    report: dict = {}
    t0 = time.perf_counter()

    # 1. Flat metal against the Fresnel equations (this also fixes nannos's polarisation labels),
    #    through nannos (a flat stack) and through the C method (a sinusoid of zero depth).
    import cmethod

    worst = 0.0
    for metal in metals.METALS:
        for lam in (380.0, 550.0, 800.0):
            for s in (0.0, 0.5, 0.866, -0.95):
                g = fmm.Grating("lamellar", 1000.0, 0.0, metal, duty=0.5)
                r = fmm.solve_once(g, lam, s, 21)
                n_m = fmm.metal_index(metal, lam)
                rs, rp = fmm.fresnel_rs_rp(1.0, n_m, s)
                worst = max(worst, abs(float(r.te[r.orders == 0][0]) - rs), abs(float(r.tm[r.orders == 0][0]) - rp))
                flat = cmethod.Profile("sinusoid", 1000.0, 0.0)
                for pol, ref in (("TE", rs), ("TM", rp)):
                    c = cmethod.solve(flat, lam, s, 1.0, n_m**2, pol, 11)
                    worst = max(worst, abs(float(c.r_eff[c.orders == 0][0]) - ref), float(np.sum(c.r_eff[c.orders != 0])))
    report["flat_fresnel_max_abs_error"] = worst
    print(f"flat metal vs Fresnel (5 metals x 3 wavelengths x 4 angles x TE/TM, nannos and C method): max |dR| = {worst:.2e}")
    _expect(worst < 1e-6, f"flat metal vs Fresnel: {worst:.3g} >= 1e-6", failures)

    # 2. Lossless dielectric gratings: sum R + sum T = 1.
    # The sawtooth's C method conserves energy only as it converges (its transmitted Rayleigh
    # vectors see the slope's jumps): measured 1e-4 at 271 harmonics, so it has its own bound and
    # count; its reflected orders are converged to 1e-5 there.
    for g, counts, bound in (
        (fmm.Grating("lamellar", 1000.0, 300.0, "1.5+0i", duty=0.4), (21, 41), 1e-6),
        (fmm.Grating("sinusoid", 800.0, 400.0, "1.5+0i"), (21, 41), 1e-6),
        (fmm.sawtooth(1600.0, 20.0, "1.5+0i"), (181, 271), 3e-4),
    ):
        worst = 0.0
        for lam in (450.0, 650.0):
            for s in (0.0, 0.3, -0.7):
                for nh in counts:
                    r = fmm.solve_once(g, lam, s, nh, want_transmission=True)
                    for pol in ("te", "tm"):
                        tot = r.extra[f"R_{pol}_all"] + r.extra[f"T_{pol}"]
                        worst = max(worst, abs(tot - 1.0))
        report[f"lossless_energy_max_error_{g.profile}"] = worst
        print(f"lossless dielectric {g.profile} (n = 1.5; 450, 650 nm; s = 0, 0.3, -0.7; {counts} harmonics; TE/TM): max |R+T-1| = {worst:.2e}")
        _expect(worst < bound, f"lossless {g.profile} R+T: {worst:.3g} >= {bound}", failures)

    # 3. Mirror symmetry of a symmetric profile: eta_m(s) = eta_-m(-s).
    worst = 0.0
    for g in (fmm.Grating("sinusoid", 1600.0, 120.0, "Ag"), fmm.Grating("lamellar", 1600.0, 110.0, "Al", duty=0.3)):
        a = fmm.solve_once(g, 550.0, 0.4, 61)
        b = fmm.solve_once(g, 550.0, -0.4, 61)
        da = {int(m): (te, tm) for m, te, tm in zip(a.orders, a.te, a.tm)}
        db = {int(m): (te, tm) for m, te, tm in zip(b.orders, b.te, b.tm)}
        worst = max(worst, max(max(abs(da[m][0] - db[-m][0]), abs(da[m][1] - db[-m][1])) for m in da))
    report["mirror_symmetry_max_error"] = worst
    print(f"mirror symmetry of a sinusoid and a lamellar profile (eta_m(s) = eta_-m(-s)): max difference {worst:.2e}")
    _expect(worst < 1e-6, f"mirror symmetry: {worst:.3g}", failures)

    # 4. Reciprocity on asymmetric profiles: eta_m(s) = eta_m(-s - m*lambda/d).
    worst = 0.0
    for g, lam, s in ((fmm.sawtooth(1600.0, 10.0, "Al"), 550.0, 0.3), (fmm.sawtooth(1000.0, 20.0, "Ag"), 450.0, -0.2)):
        a = fmm.solve_converged(g, lam, s, tol=RECIPROCITY_TOL)
        for m, te, tm in zip(a.result.orders, a.result.te, a.result.tm):
            s2 = -s - m * lam / g.period_nm
            b = fmm.solve_converged(g, lam, s2, tol=RECIPROCITY_TOL, nh_start=a.nh_sequence[0])
            j = list(b.result.orders).index(m)
            worst = max(worst, abs(te - b.result.te[j]), abs(tm - b.result.tm[j]))
    report["reciprocity_max_error"] = worst
    print(f"reciprocity of two sawtooth gratings (eta_m(s) = eta_m(-s - m*lambda/d), solves converged to {RECIPROCITY_TOL}): max difference {worst:.2e}")
    _expect(worst < 2 * RECIPROCITY_TOL, f"reciprocity: {worst:.3g} >= {2 * RECIPROCITY_TOL}", failures)

    # 5. Blaze: an Al sawtooth of 600 lines/mm blazed for 500 nm in Littrow puts most of the light into +1 there.
    d = 1e6 / 600.0
    blaze = math.degrees(math.asin(500.0 / (2 * d)))
    g = fmm.sawtooth(d, blaze, "Al")
    c = fmm.solve_converged(g, 500.0, -500.0 / (2 * d))
    j = list(c.result.orders).index(1)
    report["blaze_littrow_te_tm_order1"] = [float(c.result.te[j]), float(c.result.tm[j])]
    print(f"600 l/mm Al sawtooth, blaze {blaze:.3f} deg, Littrow at 500 nm: eta_+1 TE {c.result.te[j]:.4f}, TM {c.result.tm[j]:.4f} ({c.nh_sequence[-1]} harmonics)")
    _expect(min(c.result.te[j], c.result.tm[j]) > 0.75, "blazed grating's +1 order in Littrow below 0.75", failures)

    # 6. The C method against an independent staircase in nannos, where the staircase converges:
    #    dielectric profiles (TE and TM) and TE on metal; 32 and 64 slabs (error ~1/L^2).
    worst = 0.0
    rows = []
    for g, lam, s, pols in (
        (fmm.Grating("sinusoid", 1000.0, 300.0, "1.5+0i"), 550.0, 0.3, ("te", "tm")),
        (fmm.sawtooth(1600.0, 15.0, "1.5+0i"), 500.0, -0.2, ("te", "tm")),
        (fmm.Grating("sinusoid", 1000.0, 120.0, "Al"), 550.0, 0.5, ("te",)),
        (fmm.sawtooth(1e6 / 600.0, blaze, "Al"), 500.0, -500.0 / (2 * d), ("te",)),
    ):
        c = fmm.solve_converged(g, lam, s).result
        st = {L: fmm.solve_staircase(g, lam, s, 81, slabs=L) for L in (32, 64)}
        for pol in pols:
            e_c = getattr(c, pol)
            e32, e64 = getattr(st[32], pol), getattr(st[64], pol)
            # Richardson: the midpoint staircase's error falls as 1/L^2.
            e_inf = e64 + (e64 - e32) / 3.0
            dev = float(np.max(np.abs(e_c - e_inf)))
            rows.append(f"  {g.profile} {g.metal} d={g.period_nm:.6g} h={g.depth_nm:.4g} {lam:g} nm s={s:.3g} {pol.upper()}: "
                        f"|C - staircase(64)| max {np.max(np.abs(e_c - e64)):.1e}, |C - extrapolated| max {dev:.1e}")
            worst = max(worst, dev)
    print("C method against the nannos staircase (32 and 64 slabs, 81 harmonics, extrapolated in 1/L^2):")
    print("\n".join(rows))
    report["cmethod_vs_staircase_max_difference"] = worst
    _expect(worst < 2e-3, f"C method vs staircase: {worst:.3g} >= 2e-3", failures)

    report["seconds"] = round(time.perf_counter() - t0, 1)
    print(f"validation took {report['seconds']} s")
    if failures:
        raise Failed("; ".join(failures))
    return report


# ---------------------------------------------------------------- the test grid

PERIODS = [500.0, 740.0, 1000.0, 1600.0, 2500.0, 5000.0, 10000.0]
DEPTHS = [15.0, 50.0, 120.0, 250.0]
LAMBDAS = [450.0, 550.0, 650.0]
THETAS = [0.0, 30.0, 60.0]
GRID_METALS = ["Al", "Ag"]
# (profile, duty, periods): the lamellar profiles and the sawtooth get fewer periods (their cases
# take 10-30 s each on the shared machine, the sinusoid's about 1 s).
PROFILES = [("sinusoid", None, PERIODS), ("lamellar", 0.5, PERIODS[:-1]), ("lamellar", 0.25, [1000.0]),
            ("sawtooth", None, [740.0, 1000.0, 1600.0])]
# The sawtooth is set by its blaze angle (depth d*sin(2*blaze)/2: 126-275 nm at 740 nm, 272-595 nm
# at 1600 nm; at 2500 nm most cases did not converge by 401 harmonics). Small blaze angles make the
# short facet nearly vertical, where the C method converges slowly (at 3 degrees TM still changed
# by 2e-3 between 161 and 241 harmonics); the preset at 8.6 degrees converges (203 harmonics).
BLAZES = [10.0, 24.0]


def grid_cases():
    import fmm

    cases = []
    for profile, duty, periods in PROFILES:
        for metal in GRID_METALS:
            for d in periods:
                shapes = []
                if profile == "sawtooth":
                    shapes = [fmm.sawtooth(d, b, metal) for b in BLAZES]
                else:
                    shapes = [fmm.Grating(profile, d, h, metal, duty=duty) for h in DEPTHS]
                for g in shapes:
                    for lam in LAMBDAS:
                        for th in THETAS:
                            cases.append((g, lam, th))
    return cases


def _cost(case) -> float:
    g, lam, _ = case
    return (g.period_nm / lam) ** 2.5 * (3.0 if g.profile == "sawtooth" else 1.0)


CACHE = REPO / "python_ref" / ".cache" / "orders.jsonl"


def _key(case) -> str:
    g, lam, th = case
    return json.dumps([g.profile, g.metal, g.period_nm, g.depth_nm, g.duty, g.blaze_deg, g.cover, lam, th])


def _load_cache() -> dict:
    """Finished cases of an interrupted run (python_ref/.cache, not committed): resumable runs."""
    out = {}
    if CACHE.exists():
        for line in CACHE.read_text().splitlines():
            rec = json.loads(line)
            out[rec["key"]] = rec
    return out


def _run_case(case):
    import fmm

    g, lam, th = case
    s = math.sin(math.radians(th))
    t0 = time.perf_counter()
    try:
        c = fmm.solve_converged(g, lam, s)
    except fmm.NotConverged as e:
        return case, None, str(e), time.perf_counter() - t0
    return case, c, None, time.perf_counter() - t0


def _data_hash(lines: list[str]) -> str:
    return hashlib.sha256(("\n".join(lines) + "\n").encode("utf-8")).hexdigest()


def write_with_hash(path: Path, comments: list[str], data_lines: list[str]) -> None:
    out = ["# " + c if c else "#" for c in comments]
    out.append(HASH_PREFIX + _data_hash(data_lines))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(out + data_lines) + "\n", encoding="utf-8")


def orders(limit: int | None = None, from_cache: bool = False) -> Path:
    """The test grid. Cases run cheapest first and are cached as they finish (resumable);
    `from_cache` writes the CSV from the cached cases only, listing the others in the header as
    not computed."""
    import multiprocessing as mp

    import fmm

    cases = grid_cases()
    if limit:
        cases = cases[:: max(1, len(cases) // limit)]
    cache = _load_cache()
    todo = [] if from_cache else [c for c in cases if _key(c) not in cache]
    todo.sort(key=_cost)
    t0 = time.perf_counter()
    CACHE.parent.mkdir(parents=True, exist_ok=True)
    print(f"  {len(cases)} cases, {len(cases) - len(todo)} from {CACHE.relative_to(REPO)}", flush=True)
    with mp.get_context("fork").Pool(WORKERS) as pool, CACHE.open("a") as fh:
        for n, (case, c, err, dt) in enumerate(pool.imap_unordered(_run_case, todo)):
            rec = {"key": _key(case), "seconds": dt, "error": err}
            if c is not None:
                r = c.result
                rec.update(orders=r.orders.tolist(), te=r.te.tolist(), tm=r.tm.tolist(), nh=r.nh,
                           slabs=r.slabs, change=c.change)
            fh.write(json.dumps(rec) + "\n")
            fh.flush()
            cache[rec["key"]] = rec
            if n % 50 == 0:
                print(f"  {n + 1}/{len(todo)} cases, {time.perf_counter() - t0:.0f} s", flush=True)
    wall = time.perf_counter() - t0
    import numpy as np

    results, failed, cpu, missing = {}, [], 0.0, []
    for case in cases:
        rec = cache.get(_key(case))
        if rec is None:
            missing.append(case)
            continue
        cpu += rec["seconds"]
        if rec["error"]:
            failed.append(rec["error"])
            continue
        res = fmm.Solve(np.array(rec["orders"]), np.array(rec["te"]), np.array(rec["tm"]), rec["nh"], rec["slabs"], 1.0)
        results[(case[0], case[1], case[2])] = fmm.Converged(res, [rec["nh"]], rec["change"])
    cols = ["profile", "metal", "period_nm", "depth_nm", "duty", "blaze_deg", "lambda_nm", "theta_deg",
            "polarisation", "order", "sin_theta_m", "efficiency", "harmonics", "slabs", "nh_change"]
    lines = [",".join(cols)]
    worst_change, max_nh, rows, worst_sum = 0.0, 0, 0, 0.0
    for g, lam, th in cases:
        c = results.get((g, lam, th))
        if c is None:
            continue
        s = math.sin(math.radians(th))
        r = c.result
        worst_change = max(worst_change, c.change)
        max_nh = max(max_nh, r.nh)
        for pol in ("te", "tm"):
            eff = getattr(r, pol)
            worst_sum = max(worst_sum, float(eff.sum()))
            if eff.sum() > 1.0 + 1e-9 or eff.min() < -1e-9:
                raise Failed(f"{g} {lam} {th} {pol}: efficiencies {eff}")
            for m, e in zip(r.orders, eff):
                lines.append(",".join([
                    g.profile, g.metal, _fmt(g.period_nm), _fmt(g.depth_nm),
                    _fmt(g.duty) if g.duty is not None else "",
                    _fmt(g.blaze_deg) if g.blaze_deg is not None else "",
                    _fmt(lam), _fmt(th), pol.upper(), str(int(m)),
                    _fmt(s + m * lam / g.period_nm), _fmt(max(float(e), 0.0)), str(r.nh), str(r.slabs),
                    f"{c.change:.3g}",
                ]))
                rows += 1
    comments = [
        "Rigorous reflection efficiencies of 1-D metal relief gratings in air, one row per propagating reflected order.",
        f"Made by python_ref/rigorous.py (solver python_ref/fmm.py) with {_versions()}: Fourier modal method,",
        f"formulation=\"{fmm.FORMULATION}\" (Li's factorisation rule), epsilon sampled on {fmm.DISCRETIZATION} points per period.",
        f"Regenerate with `{ORDERS_CMD}` ({WORKERS} processes; {cpu / 60:.0f} min of solves in all, on a shared 2-core machine).",
        "Solvers: lamellar by nannos (slabs = 1); sinusoid and sawtooth by the C method with Li's factorisation",
        "(python_ref/cmethod.py; slabs = 0: no staircase). Both checked by `python3 python_ref/rigorous.py --validate`.",
        "Geometry (x across the grooves, classical mount): sinusoid z = (h/2) sin(2 pi x/d), h = depth_nm peak-to-valley;",
        "lamellar: raised metal ridges of width duty*d, height depth_nm; sawtooth: a 90-degree-apex triangle, long facet",
        "of slope blaze_deg falling from z = h at x = 0 to 0 at x = d cos^2(blaze), short facet rising back, depth_nm =",
        "d sin(blaze) cos(blaze); the long facet's normal leans toward +x, so it blazes into positive orders for theta < 0.",
        "Metal below the profile: n + ik from python_ref/data/metals (Al: Rakic 1995, Ag: Johnson & Christy 1972),",
        "linear in wavelength.",
        "theta_deg: incidence angle in air, sin(theta) = x component of the incident direction of travel (= -wi.x);",
        "order m leaves at sin_theta_m = sin(theta) + m lambda/d (= wo.x; the crate's u = wi.x + wo.x = m lambda/d).",
        "polarisation: TE = E along the grooves, TM = H along the grooves. efficiency: reflected z-flux of the order",
        "over the incident z-flux (evanescent orders are not listed; their efficiency is 0).",
        f"harmonics: the Fourier harmonic count of the reported values; the count was raised by x{fmm.NH_GROWTH} until no",
        f"order (TE or TM) changed by {fmm.CONVERGENCE_TOL} or more between the last two counts; nh_change = that change.",
        "Grid: " + "; ".join((p if d is None else f"{p} duty {d}") + f" at d = {', '.join(f'{x:g}' for x in ps)} nm" for p, d, ps in PROFILES) + ";",
        f"metals {', '.join(GRID_METALS)}; depths {', '.join(f'{h:g}' for h in DEPTHS)} nm",
        f"(sawtooth: blaze {', '.join(f'{b:g}' for b in BLAZES)} deg instead, depth = d sin(2 blaze)/2);",
        f"lambda {', '.join(f'{v:g}' for v in LAMBDAS)} nm; theta {', '.join(f'{v:g}' for v in THETAS)} deg; TE and TM.",
        f"Cases: {len(cases)} (geometry x lambda x theta), {len(results)} converged, {len(failed)} not converged by {fmm.NH_CAP} harmonics (left out):",
    ]
    comments += ["  " + e for e in failed[:40]]
    if len(failed) > 40:
        comments.append(f"  ... and {len(failed) - 40} more")
    if missing:
        comments.append(f"Not computed in this run ({len(missing)} cases; `{ORDERS_CMD}` computes them, cheapest first):")
        byclass: dict = {}
        for g, lam, th in missing:
            k = (g.profile, g.duty, g.metal, g.period_nm)
            byclass[k] = byclass.get(k, 0) + 1
        for (p, d, m, per), n in sorted(byclass.items(), key=str):
            comments.append(f"  {p}{'' if d is None else f' duty {d}'} {m} d = {per:g} nm: {n} of its (depth or blaze) x lambda x theta cases")
    comments += [
        f"Rows: {rows}; largest harmonic count {max_nh}; largest nh_change {worst_change:.3g}; largest sum over orders {worst_sum:.6f}.",
    ]
    write_with_hash(REPO / ORDERS_OUTPUT, comments, lines)
    print(f"wrote {ORDERS_OUTPUT}: {rows} rows, {len(failed)} cases not converged, {wall / 60:.1f} min (this run), {cpu / 60:.1f} min of solves")
    return ORDERS_OUTPUT


# ---------------------------------------------------------------- cheap check (generate.py --check)


def check_hashed(path: Path) -> str | None:
    """None if the file's data lines still have the hash its header records; else a description."""
    if not path.exists():
        return f"{path}: missing"
    lines = path.read_text(encoding="utf-8").splitlines()
    recorded = [l[len(HASH_PREFIX):] for l in lines if l.startswith(HASH_PREFIX)]
    if len(recorded) != 1:
        return f"{path}: no (or several) hash lines"
    data = [l for l in lines if not l.startswith("#")]
    if _data_hash(data) != recorded[0]:
        return f"{path}: data lines edited after generation (hash mismatch)"
    return None


def check(root: Path = REPO) -> list[str]:
    import presets

    import conical

    errs = []
    e = check_hashed(root / ORDERS_OUTPUT)
    if e:
        errs.append(e)
    errs += conical.check(root)
    errs += presets.check_json(root)
    return errs


def generate(out_root: Path) -> list[Path]:
    """generate.py's part `rigorous` (write mode only): validate, the test grid, the conical grid
    (conical.py), the presets' JSON.
    Always writes into the repository (the runs are resumable and far too long for a temp copy)."""
    try:
        import nannos  # noqa: F401
    except ImportError:
        raise SystemExit("part rigorous needs `pip install -r python_ref/requirements-rigorous.txt` "
                         "(or skip it: `--only tables kernels colour spectral stam metals presets`)") from None
    validate()
    written = [orders()]
    import conical

    written.append(conical.build())
    import presets

    for p in presets.build_all(json_only=True):
        written.append(p.relative_to(REPO))
    return written


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--validate", action="store_true")
    ap.add_argument("--orders", action="store_true")
    ap.add_argument("--presets", action="store_true")
    ap.add_argument("--all", action="store_true")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--preset", action="append", help="with --presets: only this preset (repeatable)")
    ap.add_argument("--reuse", action="store_true", help="with --presets: copy the nodes the committed JSON already has (same grating)")
    ap.add_argument("--from-cache", action="store_true", help="with --orders: write the CSV from the cached cases only")
    ap.add_argument("--limit", type=int, help="(development) only about this many grid cases")
    args = ap.parse_args()
    if args.check:
        errs = check()
        for e in errs:
            print(e)
        return 1 if errs else 0
    if not (args.validate or args.orders or args.presets or args.all):
        ap.print_help()
        return 2
    try:
        if args.validate or args.all:
            print(json.dumps(validate(), indent=1))
        if args.orders or args.all:
            orders(args.limit, args.from_cache)
        if args.presets or args.all:
            import presets

            presets.build_all(only=args.preset, reuse_existing=args.reuse)
    except Failed as e:
        print(f"\nVALIDATION FAILED: {e}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
