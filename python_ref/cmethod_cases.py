"""Fixed-truncation C-method cases for the Rust C method's tests (fmm/tests/cmethod.rs).

Each case is solved by python_ref/cmethod.py at the harmonic counts listed, both polarisations,
with the substrate's n + ik written into the file (so that the Rust side solves with exactly the
same permittivity, `Metal::custom(n, k)`, and the comparison tests the method, not the tables).
Lossless substrates also get the transmitted totals (order = "T").

Regenerate: `/work/venv-rig/bin/python python_ref/cmethod_cases.py` (numpy + scipy only, about a
minute) -> fmm/tests/data/cmethod_fixed.csv.

`--time`: instead, times the solves of fmm/benches/solve.rs's `cmethod` group (foil at 41 and 81
harmonics, blazed600 at 81; TE and TM; sin(theta) = 0.5, 550 nm), best of 5, for the ratio to
`cargo bench -p diffraction-fmm --bench solve -- cmethod`.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402
import scipy  # noqa: E402

import cmethod  # noqa: E402
import fmm  # noqa: E402

OUT = Path(__file__).resolve().parent.parent / "fmm" / "tests" / "data" / "cmethod_fixed.csv"
BLAZE_600 = math.degrees(math.asin(500.0 / (2 * (1e6 / 600.0))))

# (profile kind, period nm, depth nm, blaze deg, substrate: metal name or "n+ki", lambda nm, sin theta, harmonics)
CASES = [
    ("sinusoid", 1000.0, 100.0, None, "Al", 450.0, 0.0, (41, 61)),  # the foil preset
    ("sinusoid", 1000.0, 100.0, None, "Al", 550.0, 0.5, (41, 61)),
    ("sinusoid", 1000.0, 100.0, None, "Al", 650.0, -0.25, (41,)),
    ("sinusoid", 1e6 / 1200.0, 150.0, None, "Ag", 550.0, math.sin(math.radians(20.0)), (41, 61)),
    ("sinusoid", 500.0, 250.0, None, "Ag", 450.0, 0.0, (31, 47)),
    ("sinusoid", 5000.0, 250.0, None, "Al", 650.0, 0.5, (61,)),
    ("sinusoid", 800.0, 400.0, None, "1.5+0i", 550.0, 0.3, (41,)),  # lossless: R + T
    ("triangle", 1e6 / 600.0, None, BLAZE_600, "Al", 500.0, -0.15, (41, 81)),  # blazed600 near Littrow
    ("triangle", 1000.0, None, 24.0, "Ag", 550.0, 0.5, (41, 81)),
    ("triangle", 740.0, None, 10.0, "Al", 450.0, 0.0, (61,)),
    ("triangle", 1600.0, None, 20.0, "1.5+0i", 500.0, -0.2, (81,)),  # lossless: R + T
]


def timing() -> int:
    nk = fmm.metal_index("Al", 550.0)
    cases = [
        ("foil_41", cmethod.Profile("sinusoid", 1000.0, 100.0), 41),
        ("foil_81", cmethod.Profile("sinusoid", 1000.0, 100.0), 81),
        ("blazed600_81", cmethod.Profile("triangle", 1e6 / 600.0, fmm.sawtooth_depth(1e6 / 600.0, BLAZE_600), BLAZE_600), 81),
    ]
    for name, prof, nh in cases:
        best = float("inf")
        for _ in range(5):
            t = time.perf_counter()
            for pol in ("TE", "TM"):
                cmethod.solve(prof, 550.0, 0.5, 1.0, complex(nk) ** 2, pol, nh)
            best = min(best, time.perf_counter() - t)
        print(f"cmethod/{name}: {best * 1e3:.1f} ms (TE + TM, best of 5)")
    return 0


def main() -> int:
    if "--time" in sys.argv[1:]:
        return timing()
    rows = []
    t0 = time.time()
    for kind, d, h, blaze, sub, lam, s, counts in CASES:
        if kind == "triangle":
            h = fmm.sawtooth_depth(d, blaze)
        prof = cmethod.Profile(kind, d, h, blaze)
        nk = fmm.metal_index(sub, lam)
        for nh in counts:
            for pol in ("TE", "TM"):
                r = cmethod.solve(prof, lam, s, 1.0, complex(nk) ** 2, pol, nh)
                for m, e in zip(r.orders, r.r_eff):
                    rows.append((kind, d, h, blaze, nk, lam, s, nh, pol, str(int(m)), float(e)))
                if not math.isnan(r.t_total):
                    rows.append((kind, d, h, blaze, nk, lam, s, nh, pol, "T", r.t_total))
    with OUT.open("w") as f:
        f.write("# C-method efficiencies at fixed harmonic counts (orders -M..M, M = harmonics // 2), one row per\n")
        f.write("# propagating reflected order (order = T: total transmitted into a lossless substrate).\n")
        f.write(f"# Made by python_ref/cmethod_cases.py with python_ref/cmethod.py, numpy {np.__version__}, scipy {scipy.__version__}.\n")
        f.write("# Regenerate: `/work/venv-rig/bin/python python_ref/cmethod_cases.py` (numpy + scipy only).\n")
        f.write("# Profiles: sinusoid z = (h/2) sin(2 pi x/d); triangle = the 90-degree-apex sawtooth of blaze_deg\n")
        f.write("# (depth d sin(blaze) cos(blaze)). Air above; substrate n + ik as written (metals from python_ref/data/metals).\n")
        f.write("# sin_theta: x component of the incident direction of travel; polarisation TE = E along the grooves.\n")
        f.write("profile,period_nm,depth_nm,blaze_deg,n,k,lambda_nm,sin_theta,harmonics,polarisation,order,efficiency\n")
        for kind, d, h, blaze, nk, lam, s, nh, pol, m, e in rows:
            b = "" if blaze is None else repr(blaze)
            f.write(f"{kind},{d!r},{h!r},{b},{nk.real!r},{nk.imag!r},{lam!r},{s!r},{nh},{pol},{m},{e!r}\n")
    print(f"{len(rows)} rows -> {OUT} ({time.time() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
