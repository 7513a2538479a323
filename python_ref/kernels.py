"""`tests/data/kernels.csv`: exact values of the two diffraction factors at floating-point arguments.

Functions (exact mathematics, evaluated with mpmath at 100 significant digits, then rounded once
to the nearest f64 by `float(mpf)`):

* n_slit_cycles(N, x) = sin²(πNx) / (N² sin²(πx)), 1 at integer x (phase in cycles);
* n_slit(N, α)        = sin²(Nα) / (N² sin²α), 1 at α = 0 (phase in radians);
* single_slit_cycles(y) = (sin(πy) / (πy))², 1 at y = 0;
* single_slit(β)        = (sin β / β)², 1 at β = 0.

The argument written in the file is the exact binary value used (mpmath.mpf(float) is exact);
for `f32` rows it is an f32 value (rounded with numpy.float32 first), written as the f64 repr of
that value, so parsing it as f64 and casting to f32 is exact.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
import numpy as np
from mpmath import mp

from common import REGEN_CMD, f, randint, rng, uniform, versions, write_csv

OUTPUT = Path("tests/data/kernels.csv")
DPS = 100

NS = {"f64": [1, 2, 10, 5000, 1_000_000, 10_000_000], "f32": [1, 2, 10, 5000, 1_000_000]}
# Largest |x| (cycles) and |alpha|, |beta| (radians) per precision.
X_MAX = {"f64": 1e4, "f32": 1e4 / math.pi}
A_MAX = {"f64": 1e5, "f32": 1e4}


def exact_n_slit_cycles(n: int, x: float) -> float:
    with mp.workdps(DPS):
        X = mpmath.mpf(x)
        if X == mpmath.floor(X):
            return 1.0
        v = (mpmath.sinpi(n * X) / (n * mpmath.sinpi(X))) ** 2
        return float(v)


def exact_n_slit(n: int, a: float) -> float:
    with mp.workdps(DPS):
        A = mpmath.mpf(a)
        if A == 0:
            return 1.0
        v = (mpmath.sin(n * A) / (n * mpmath.sin(A))) ** 2
        return float(v)


def exact_single_slit_cycles(y: float) -> float:
    with mp.workdps(DPS):
        Y = mpmath.mpf(y)
        if Y == 0:
            return 1.0
        return float((mpmath.sinpi(Y) / (mp.pi * Y)) ** 2)


def exact_single_slit(b: float) -> float:
    with mp.workdps(DPS):
        B = mpmath.mpf(b)
        if B == 0:
            return 1.0
        return float((mpmath.sin(B) / B) ** 2)


def _to(prec: str, v: float) -> float:
    v = float(v)
    return float(np.float32(v)) if prec == "f32" else v


def _neighbours(prec: str, v: float) -> list[float]:
    """The two representable neighbours of v in the given precision."""
    if prec == "f32":
        s = np.float32(v)
        return [float(np.nextafter(s, np.float32(-np.inf))), float(np.nextafter(s, np.float32(np.inf)))]
    return [math.nextafter(v, -math.inf), math.nextafter(v, math.inf)]


def _dedup_in_range(prec: str, vals, limit: float) -> list[float]:
    out, seen = [], set()
    for v in vals:
        v = _to(prec, v)
        if not math.isfinite(v) or abs(v) > limit:
            continue
        key = v.hex()
        if key not in seen:
            seen.add(key)
            out.append(v)
    return out


def cases_n_slit_cycles(prec: str, n: int, seed: int) -> list[float]:
    xmax = X_MAX[prec]
    r = rng(seed)
    ints = [0, 1, 40, 3183, 9999, -1, -40]
    xs: list[float] = []
    xs += ints
    # neighbours of integers in the working precision
    for m in (0, 1, 40, 3183):
        xs += _neighbours(prec, float(m))
    if prec == "f64":
        xs += [40 + 1e-12, 3 - 3e-13, 1 - 1e-12, 1e-12, -1e-12, 9999 + 1e-12, 3183 - 5e-13, -40 - 1e-12]
    # zeros x = k/N
    for k in (1, 2, 7, n - 1, n + 1, 3 * n - 1, 40 * n + 3, 3183 * n + 1, 9999 * n - 1, -(n + 1)):
        if k % n != 0:
            xs.append(k / n)
    # just off the peaks, half-integers
    for m in (0, 1, 40, 3183, 9999, -40):
        for d in (0.3 / n, 1.7 / n, -0.3 / n, 0.5):
            xs.append(m + d)
    xs += [0.5, 1.5, 40.5, -2.5, 3182.5, 9998.5, 0.25, 0.75]
    # coarse gratings, high orders
    xs += [xmax, -xmax, 0.99 * xmax, 1234.5678, 9876.54321, -5000.0 + 0.3 / n]
    # random x in [-xmax, xmax]
    xs += [uniform(r, -xmax, xmax) for _ in range(30)]
    # random near-peak x = m + delta with delta*N in [-3, 3]
    for _ in range(12):
        m = randint(r, -int(xmax), int(xmax))
        xs.append(m + uniform(r, -3.0, 3.0) / n)
    return _dedup_in_range(prec, xs, xmax)


def cases_n_slit(prec: str, n: int, seed: int) -> list[float]:
    amax = A_MAX[prec]
    r = rng(seed)
    a: list[float] = [0.0]
    for k in (1, 7, 1000, 3183, 31830, -7):
        a.append(k * math.pi)
        a += _neighbours(prec, _to(prec, k * math.pi))
        for d in (0.3 * math.pi / n, -1.7 * math.pi / n, 0.5 * math.pi):
            a.append(k * math.pi + d)
    # zeros alpha = k*pi/N
    for k in (1, n + 1, 40 * n + 3):
        if k % n != 0:
            a.append(k * math.pi / n)
    a += [1e-12, -1e-9, 0.5, 1.0, 3.0, amax, -amax]
    a += [uniform(r, -amax, amax) for _ in range(10)]
    for _ in range(6):
        k = randint(r, -int(amax / math.pi), int(amax / math.pi))
        a.append(k * math.pi + uniform(r, -3.0, 3.0) * math.pi / n)
    return _dedup_in_range(prec, a, amax)


def cases_single_slit(prec: str, seed: int) -> list[float]:
    amax = A_MAX[prec]
    r = rng(seed)
    tiny = [1e-300, 5e-324] if prec == "f64" else [1e-38, 1e-45]
    b = [0.0]
    for v in tiny + [1e-9, 1e-4, math.pi, 2 * math.pi, 1e4, 1e5, 1.0]:
        b += [v, -v]
    b += [0.5, 1e-8, 3e-5, 0.01, 0.1, 100 * math.pi, 31830 * math.pi]
    b += _neighbours(prec, _to(prec, math.pi))
    b += [uniform(r, -amax, amax) for _ in range(10)]
    b += [uniform(r, -10.0, 10.0) for _ in range(10)]
    return _dedup_in_range(prec, b, amax)


def cases_single_slit_cycles(prec: str, seed: int) -> list[float]:
    ymax = X_MAX[prec]
    r = rng(seed)
    tiny = [1e-300, 5e-324] if prec == "f64" else [1e-38, 1e-45]
    y = [0.0]
    for v in tiny + [1e-12, 1e-6, 0.5, 1.0, 2.0, 3.0, 40.0, 1e4, 3183.0, 1.5]:
        y += [v, -v]
    y += _neighbours(prec, 1.0) + _neighbours(prec, 40.0)
    y += [1 + 1e-12, 40 - 1e-12, 0.3, 1e-4]
    y += [uniform(r, -ymax, ymax) for _ in range(10)]
    y += [uniform(r, -5.0, 5.0) for _ in range(10)]
    return _dedup_in_range(prec, y, ymax)


def rows() -> list[list[str]]:
    out = []
    seed = 1000
    for prec in ("f64", "f32"):
        for n in NS[prec]:
            seed += 1
            for x in cases_n_slit_cycles(prec, n, seed):
                out.append(["n_slit_cycles", prec, str(n), f(x), f(exact_n_slit_cycles(n, x))])
        for n in NS[prec]:
            seed += 1
            for a in cases_n_slit(prec, n, seed):
                out.append(["n_slit", prec, str(n), f(a), f(exact_n_slit(n, a))])
        seed += 1
        for y in cases_single_slit_cycles(prec, seed):
            out.append(["single_slit_cycles", prec, "1", f(y), f(exact_single_slit_cycles(y))])
        seed += 1
        for b in cases_single_slit(prec, seed):
            out.append(["single_slit", prec, "1", f(b), f(exact_single_slit(b))])
    return out


def generate(out_root: Path) -> list[Path]:
    data = rows()
    counts = {}
    for r in data:
        counts[(r[0], r[1])] = counts.get((r[0], r[1]), 0) + 1
    summary = ", ".join(f"{k[0]}/{k[1]}: {v}" for k, v in counts.items())
    comments = [
        "kernels.csv: reference values of the EXACT diffraction factors at floating-point arguments.",
        "  n_slit_cycles: sin^2(pi*N*x) / (N^2 sin^2(pi*x)), = 1 at integer x (x = phase in cycles)",
        "  n_slit:        sin^2(N*a) / (N^2 sin^2(a)),       = 1 at a = 0 (a = phase in radians)",
        "  single_slit_cycles: (sin(pi*y) / (pi*y))^2, = 1 at y = 0",
        "  single_slit:        (sin(b) / b)^2,         = 1 at b = 0   (n is 1 on single-slit rows)",
        f"Made with mpmath at mp.dps = {DPS} ({versions()}): the float argument is converted to mpf",
        "exactly, the function is evaluated (mpmath.sinpi for the cycle forms), and the result is",
        "rounded once to the nearest f64 (float(mpf)); written with Python repr() (round-trip exact).",
        "precision = f32: arg is exactly an f32 (rounded with numpy.float32), written as the f64 repr of",
        "that value; value is the exact function at that f32 argument, still as an f64.",
        "Ranges: f64 rows N <= 1e7, |x| <= 1e4, |a|,|b| <= 1e5; f32 rows N <= 1e6, |x|,|y| <= 1e4/pi, |a|,|b| <= 1e4.",
        "Cases: integers and their neighbours, x within 1e-12 of integers (f64), zeros k/N, m + 0.3/N,",
        "m + 1.7/N, half-integers, |x| up to the range limit, seeded random x (Python random.Random) and",
        "random near-peak x = m + delta with delta*N in [-3, 3]; radians: a near k*pi incl. fl(k*pi).",
        f"Rows: {len(data)} ({summary}).",
        f"Regenerate: {REGEN_CMD}",
    ]
    write_csv(out_root / OUTPUT, comments, ["function", "precision", "n", "arg", "value"], data)
    return [OUTPUT]
