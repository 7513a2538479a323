#!/usr/bin/env python3
"""Write a tabulated order-efficiency file (JSON, docs/efficiency_tables.md) for any 1-D grating.

    python3 python_ref/efficiencies.py --profile lamellar --period 1600 --depth 110 --duty 0.5 --metal Al --out cd.json
    python3 python_ref/efficiencies.py --profile sinusoid --period 1000 --depth 100 --metal Ag --out foil.json
    python3 python_ref/efficiencies.py --profile sawtooth --period 1666.667 --blaze 8.63 --metal Al --out b.json
    python3 python_ref/efficiencies.py ... --metal 1.2+7.0i --cover polycarbonate --sin-step 0.05 --lambda-step 10

Rigorous solvers (fmm.py): nannos (Fourier modal method, Li's rule) for lamellar profiles, the C
method with Li's factorisation (cmethod.py) for sinusoids and sawtooths. Every node is converged
on its own (the harmonic count raised x1.5 until no order changes by 1e-3); the interpolation error
is measured against fresh solves at random points inside cells and stored in the file. Needs `pip install -r python_ref/requirements-rigorous.txt`. A failed run leaves an existing
--out file as it was.

Cost: one solve per node (TE and TM together; half the s nodes for symmetric profiles), from
0.01 s (shallow sinusoid) to a few seconds (deep lamellar at d/lambda ~ 20) per solve.
"""

from __future__ import annotations

import argparse
import math
import os
import shlex
import sys
from pathlib import Path

sys.dont_write_bytecode = True
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
sys.path.insert(0, str(Path(__file__).resolve().parent))

import efficiency_table as et  # noqa: E402
import fmm  # noqa: E402


def _positive(flag):
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{flag}: {text!r} is not a number") from None
        if not (v > 0 and math.isfinite(v)):
            raise argparse.ArgumentTypeError(f"{flag}: {text!r} must be a positive number")
        return v

    return conv


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--profile", required=True, choices=["sinusoid", "lamellar", "sawtooth"])
    ap.add_argument("--period", required=True, type=_positive("--period"), help="grating period d, nm")
    ap.add_argument("--depth", type=float, help="nm: peak-to-valley (sinusoid), ridge height (lamellar); not for sawtooth")
    ap.add_argument("--duty", type=float, help="lamellar: the raised ridge's share of the period, in (0, 1)")
    ap.add_argument("--blaze", type=float, help="sawtooth: blaze angle (facet slope), degrees, in (0, 45)")
    ap.add_argument("--metal", required=True, help="Al, Ag, Au, Cu, Cr or a complex index N+Ki (e.g. 1.2+7.0i)")
    ap.add_argument("--cover", default="none", choices=["none", "polycarbonate"])
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--name", help="the table's name (default: the file's stem)")
    ap.add_argument("--description", default="")
    ap.add_argument("--sin-step", type=_positive("--sin-step"), default=0.1, help="sin(theta_i) step; divides 1 (default 0.1)")
    ap.add_argument("--lambda-min", type=_positive("--lambda-min"), default=360.0)
    ap.add_argument("--lambda-max", type=_positive("--lambda-max"), default=830.0)
    ap.add_argument("--lambda-step", type=_positive("--lambda-step"), default=20.0, help="nm (default 20; the last node is lambda-max)")
    ap.add_argument("--nh", type=int, help="starting harmonic count of each node's convergence (default: from d/lambda)")
    ap.add_argument("--workers", type=int, default=2, help="processes (default 2)")
    ap.add_argument("--interp-points", type=int, default=32, help="random in-cell points solved to measure the interpolation error (default 32)")
    a = ap.parse_args(argv)

    try:
        if a.profile == "sawtooth":
            if a.blaze is None:
                ap.error("--blaze: required for a sawtooth")
            if a.depth is not None:
                ap.error("--depth: a sawtooth's depth follows from --period and --blaze (d sin(2 blaze)/2)")
            g = fmm.sawtooth(a.period, a.blaze, a.metal, cover=a.cover)
        else:
            if a.depth is None:
                ap.error("--depth: required for a sinusoid or a lamellar profile")
            if a.blaze is not None:
                ap.error("--blaze: only for a sawtooth")
            if a.profile == "lamellar" and a.duty is None:
                ap.error("--duty: required for a lamellar profile")
            if a.profile != "lamellar" and a.duty is not None:
                ap.error("--duty: only for a lamellar profile")
            g = fmm.Grating(a.profile, a.period, a.depth, a.metal, duty=a.duty, cover=a.cover)
        grid = et.Grid(a.sin_step, a.lambda_min, a.lambda_max, a.lambda_step)
        if not (a.lambda_min >= 360.0 and a.lambda_max <= 830.0) and a.metal in fmm.metals.METALS:
            ap.error("--lambda-min/--lambda-max: the metal tables cover 360-830 nm")
        et.s_grid(a.sin_step)
        if a.nh is not None and not (3 <= a.nh <= fmm.NH_CAP):
            ap.error(f"--nh: must be in 3..{fmm.NH_CAP}")
        if a.workers < 1:
            ap.error("--workers: must be >= 1")
        if a.interp_points < 1:
            ap.error("--interp-points: must be >= 1")
    except ValueError as e:
        ap.error(str(e))

    cmd = "python3 python_ref/efficiencies.py " + " ".join(shlex.quote(x) for x in (argv if argv is not None else sys.argv[1:]))
    t = et.build(g, grid, a.name or a.out.stem, a.description, cmd, workers=a.workers, nh=a.nh,
                 interp_points=a.interp_points)
    et.write_json(t, a.out)
    print(f"wrote {a.out} ({a.out.stat().st_size / 1e3:.0f} kB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
