#!/usr/bin/env python3
"""Regenerate every reference output of the `diffraction` crate, or check the committed ones.

    python3 python_ref/generate.py            # write all outputs into the repository
    python3 python_ref/generate.py --check    # regenerate into a temporary folder, compare, exit 1 on any difference
    python3 python_ref/generate.py --only tables kernels   # restrict to some parts (for development)

Parts: tables (src/cie_data.rs), kernels (tests/data/kernels.csv), colour (cmf_interp.csv,
xyz_to_srgb.csv, srgb_transfer.csv, lab_de2000.csv), spectral (spectral_xyz.csv; the slow one),
stam (stam_orders.csv), metals (src/metals_data.rs, tests/data/metals.csv), rigorous
(tests/data/rigorous_orders.csv and data/efficiencies/*.json: hours of solves, needs
requirements-rigorous.txt; `--check` only verifies their hashes and validates the tables), presets
(src/efficiency_presets_data.rs from data/efficiencies/*.json).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
import tempfile
import time
from pathlib import Path

sys.dont_write_bytecode = True  # keep python_ref/ free of __pycache__
sys.path.insert(0, str(Path(__file__).resolve().parent))

import colour_fixtures  # noqa: E402
import efficiency_interp  # noqa: E402
import kernels  # noqa: E402
import metals  # noqa: E402
import presets  # noqa: E402
import rigorous  # noqa: E402
import spectral  # noqa: E402
import stam  # noqa: E402
import tables  # noqa: E402
from common import REPO  # noqa: E402

PARTS = {
    "tables": tables.generate,
    "kernels": kernels.generate,
    "colour": colour_fixtures.generate,
    "spectral": spectral.generate,
    "stam": stam.generate,
    "metals": metals.generate,
    "rigorous": rigorous.generate,
    "presets": presets.generate,
    "efficiency_interp": efficiency_interp.generate,
}

# Parts too expensive to regenerate in `--check`: a cheap check of the committed files instead
# (returns a list of problems).
CHECK_ONLY = {
    "rigorous": rigorous.check,
}


# numpy's vectorised sin/pow/atan2 may differ in the last bit between CPUs (SIMD code paths);
# a fixture whose comment lines are identical and whose numbers agree to this relative
# tolerance is the same fixture. Anything larger is a real change.
LAST_BIT_TOLERANCE = 1e-12


def _numeric_diff(a: Path, b: Path) -> tuple[str, bool]:
    """For a differing CSV: a description of the difference, and whether it is last-bit noise only."""
    if a.suffix != ".csv":
        return "", False
    la, lb = a.read_text().splitlines(), b.read_text().splitlines()
    if [l for l in la if l.startswith("#")] != [l for l in lb if l.startswith("#")]:
        return " (comment lines differ)", False
    ra = [r for r in csv.reader(la) if r and not r[0].startswith("#")]
    rb = [r for r in csv.reader(lb) if r and not r[0].startswith("#")]
    if len(ra) != len(rb):
        return f" (row count {len(ra)} vs {len(rb)})", False
    worst, cells = 0.0, 0
    for x, y in zip(ra, rb):
        if len(x) != len(y):
            return " (column count differs)", False
        for p, q in zip(x, y):
            if p == q:
                continue
            cells += 1
            try:
                fp, fq = float(p), float(q)
            except ValueError:
                return f" (text cell differs: {p!r} vs {q!r})", False
            scale = max(abs(fp), abs(fq))
            worst = max(worst, abs(fp - fq) / scale if scale > 0 else math.inf)
    return f" ({cells} data cells differ, max relative difference {worst:.3g})", worst <= LAST_BIT_TOLERANCE


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="regenerate into a temp folder and compare with the committed files")
    ap.add_argument("--only", nargs="+", choices=sorted(PARTS), help="only these parts")
    args = ap.parse_args()
    parts = args.only or list(PARTS)

    if not args.check:
        for name in parts:
            t0 = time.perf_counter()
            written = PARTS[name](REPO)
            print(f"{name}: wrote {', '.join(map(str, written))} in {time.perf_counter() - t0:.1f} s")
        return 0

    bad = []
    with tempfile.TemporaryDirectory(prefix="diffraction_ref_") as tmp:
        tmp = Path(tmp)
        for name in parts:
            t0 = time.perf_counter()
            if name in CHECK_ONLY:
                problems = CHECK_ONLY[name](REPO)
                bad += problems
                print(f"{name}: checked hashes and tables of the committed files in {time.perf_counter() - t0:.1f} s"
                      + ("" if not problems else f" ({len(problems)} problems)"))
                continue
            written = PARTS[name](tmp)
            for rel in written:
                new, old = tmp / rel, REPO / rel
                if not old.exists():
                    bad.append(f"{rel}: missing from the repository")
                elif new.read_bytes() != old.read_bytes():
                    what, noise = _numeric_diff(old, new)
                    if noise:
                        print(f"  {rel}: last-bit differences only{what}")
                    else:
                        bad.append(f"{rel}: differs from a fresh regeneration{what}")
            print(f"{name}: checked {', '.join(map(str, written))} in {time.perf_counter() - t0:.1f} s")
    if bad:
        print("\nOUT OF DATE (run `python3 python_ref/generate.py` and review the diff):")
        for b in bad:
            print("  " + b)
        return 1
    print("all generated files are up to date")
    return 0


if __name__ == "__main__":
    sys.exit(main())
