#!/usr/bin/env python3
"""Regenerate every reference output of the `diffraction` crate, or check the committed ones.

    python3 python_ref/generate.py            # write all outputs into the repository
    python3 python_ref/generate.py --check    # regenerate into a temporary folder, compare, exit 1 on any difference
                                              # (the slow parts only where their inputs changed: see below)
    python3 python_ref/generate.py --check --full   # regenerate and compare every part, the slow ones too
    python3 python_ref/generate.py --only tables kernels   # restrict to some parts (for development)

Parts: tables (src/data/cie_data.rs), kernels (tests/data/kernels.csv), colour (cmf_interp.csv,
xyz_to_srgb.csv, srgb_transfer.csv, lab_de2000.csv), spectral (spectral_xyz.csv; the slow one),
stam (stam_orders.csv), metals (src/data/metals_data.rs, tests/data/metals.csv), rigorous
(tests/data/rigorous_orders.csv, tests/data/rigorous_conical.csv and data/efficiencies/*.json: hours of solves, needs
requirements-rigorous.txt; `--check` only verifies their hashes and validates the tables), presets
(src/data/efficiency_presets_data.rs from data/efficiencies/*.json).

The slow parts (spectral, about 290 s on 2 cores, and stam, about 28 s) carry a fingerprint line
in their files' comment header: `# Inputs sha256: A; data sha256: B`, where A hashes what the
part's output depends on (the source of the part's module and of every python_ref module it
imports, transitively; the versions of Python, colour-science, numpy, scipy and mpmath; neither
part reads a file of the repository) and B hashes the file without that line. `--check` reads the
committed file's fingerprint and recomputes A and B: if both match, the file is what that very
code made with these very libraries and has not been edited since, and the part is not rerun
(reported as "inputs unchanged"); if either differs the part is regenerated and compared as
every other part is. What this fast check does not verify: that the computation still gives the
same numbers on this machine (another CPU's last bits, a broken library install) — `--full`
regenerates every part and compares it, as CI did before; run it after changing a machine or a
library build, and before a release.
"""

from __future__ import annotations

import argparse
import ast
import csv
import hashlib
import math
import platform
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


# Parts whose `--check` reruns only when their inputs changed (see the module docs); their
# outputs are CSV files.
FINGERPRINTED = {"spectral", "stam"}
FINGERPRINT_PREFIX = "# Inputs sha256: "
HERE = Path(__file__).resolve().parent


def _local_modules(name: str, seen: set[str] | None = None) -> set[str]:
    """The python_ref module `name` and every python_ref module it imports, transitively."""
    seen = set() if seen is None else seen
    if name in seen or not (HERE / f"{name}.py").exists():
        return seen
    seen.add(name)
    tree = ast.parse((HERE / f"{name}.py").read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names = [a.name.split(".")[0] for a in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names = [node.module.split(".")[0]]
        else:
            continue
        for n in names:
            _local_modules(n, seen)
    return seen


def inputs_hash(part: str) -> str:
    """The sha256 of what a fingerprinted part's output depends on: its modules' sources and
    the interpreter's and libraries' versions."""
    from common import versions

    h = hashlib.sha256()
    module = PARTS[part].__module__
    for name in sorted(_local_modules(module)):
        h.update(f"{name}.py\0".encode())
        h.update((HERE / f"{name}.py").read_bytes())
    h.update(f"python {platform.python_version()}; {versions()}".encode())
    return h.hexdigest()


def _split_fingerprint(text: str) -> tuple[str | None, str | None, str]:
    """(inputs hash, data hash, the text without the fingerprint line)."""
    lines = text.splitlines(keepends=True)
    for i, line in enumerate(lines):
        if line.startswith(FINGERPRINT_PREFIX):
            rest = line[len(FINGERPRINT_PREFIX):].strip()
            inputs, _, data = rest.partition("; data sha256: ")
            return inputs, data, "".join(lines[:i] + lines[i + 1:])
    return None, None, text


def add_fingerprint(path: Path, inputs: str) -> None:
    """Inserts the fingerprint line after the comment header of the CSV at `path`."""
    text = path.read_text(encoding="utf-8")
    _, _, body = _split_fingerprint(text)
    data = hashlib.sha256(body.encode("utf-8")).hexdigest()
    lines = body.splitlines(keepends=True)
    at = next(i for i, line in enumerate(lines) if not line.startswith("#"))
    line = f"{FINGERPRINT_PREFIX}{inputs}; data sha256: {data}\n"
    path.write_text("".join(lines[:at] + [line] + lines[at:]), encoding="utf-8")


def fingerprint_current(path: Path, inputs: str) -> str | None:
    """None if the committed file at `path` carries the fingerprint of `inputs` and its data
    are unchanged since; else why not."""
    if not path.exists():
        return "missing"
    stored, data, body = _split_fingerprint(path.read_text(encoding="utf-8"))
    if stored is None:
        return "no fingerprint line"
    if stored != inputs:
        return "inputs changed"
    if data != hashlib.sha256(body.encode("utf-8")).hexdigest():
        return "edited since it was generated"
    return None


def run_part(name: str, root: Path) -> list[Path]:
    """Runs a part into `root`, adding the fingerprint line to a fingerprinted part's files."""
    written = PARTS[name](root)
    if name in FINGERPRINTED:
        inputs = inputs_hash(name)
        for rel in written:
            add_fingerprint(root / rel, inputs)
    return written


# The files of each fingerprinted part.
FINGERPRINTED_OUTPUTS = {"spectral": [spectral.OUTPUT], "stam": [stam.OUTPUT, stam.LARGE_OUTPUT]}


# numpy's vectorised sin/pow/atan2 and LAPACK's inverse may differ in the last bit between CPUs
# (SIMD code paths); a fixture whose comment lines are identical and whose numbers agree to this
# tolerance, relative to the largest number of their row, is the same fixture. Anything larger
# is a real change.
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
        # Relative to the row's largest number: a cell that is a linear image of the row's
        # inputs (XYZ -> RGB of a white, say) can be a rounding residue near 0 whose own relative
        # change is large while its error against the row's magnitude is a last bit.
        row_scale = 0.0
        for p in x + y:
            try:
                row_scale = max(row_scale, abs(float(p)))
            except ValueError:
                pass
        for p, q in zip(x, y):
            if p == q:
                continue
            cells += 1
            try:
                fp, fq = float(p), float(q)
            except ValueError:
                return f" (text cell differs: {p!r} vs {q!r})", False
            scale = max(abs(fp), abs(fq), row_scale if math.isfinite(row_scale) else 0.0)
            worst = max(worst, abs(fp - fq) / scale if scale > 0 else math.inf)
    return f" ({cells} data cells differ, max relative difference {worst:.3g})", worst <= LAST_BIT_TOLERANCE


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="regenerate into a temp folder and compare with the committed files")
    ap.add_argument("--full", action="store_true",
                    help="with --check: rerun the fingerprinted (slow) parts even where their inputs are unchanged")
    ap.add_argument("--only", nargs="+", choices=sorted(PARTS), help="only these parts")
    args = ap.parse_args()
    parts = args.only or list(PARTS)

    if not args.check:
        for name in parts:
            t0 = time.perf_counter()
            written = run_part(name, REPO)
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
            if name in FINGERPRINTED and not args.full:
                inputs = inputs_hash(name)
                outputs = FINGERPRINTED_OUTPUTS[name]
                why = [w for w in (fingerprint_current(REPO / rel, inputs) for rel in outputs) if w]
                if not why:
                    print(f"{name}: inputs unchanged, data as generated: {', '.join(map(str, outputs))} "
                          f"not recomputed (--full does) in {time.perf_counter() - t0:.1f} s")
                    continue
                print(f"{name}: {', '.join(why)}: regenerating")
            written = run_part(name, tmp)
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
