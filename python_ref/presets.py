"""Rigorous efficiency tables of the crate's presets: a CD, a DVD, a ruled blazed grating, a foil.

    python3 python_ref/rigorous.py --presets    # solve and write data/efficiencies/*.json, then the Rust file
    python3 python_ref/presets.py --rust        # only src/data/efficiency_presets_data.rs from the committed JSON
    python3 python_ref/presets.py --rust-solve dvd  # re-solve one preset with the crate's own solver

The CD, the DVD and the blazed grating (RUST_SOLVED) are solved by the crate's Rust solver
(`grating-table` of diffraction-fmm, on the committed table's own grid, `--nodes-of`), each node
converged to 2.5e-4: their TM orders converge slowly (lamellar TM like 1/N), and python_ref's runs
(nannos stopping at one x1.5 step changing < 1e-3; the C method at one fixed count for the blazed
grating) left them up to 3.1-3.6e-3 off. The foil is python_ref's C method, within 5e-7 of the Rust
C method at its nodes (fmm/tests/cmethod.rs); fmm/tests/presets.rs checks the others reproduce.

`src/data/efficiency_presets_data.rs` is made from the JSON files alone (cheap; `generate.py` part
`presets` regenerates and compares it in `--check`), on the JSON tables' grid (COARSEN = 1: a larger value would
drop nodes in both axes, keeping the last); its header repeats the interpolation error the JSON
tables measured against fresh solves inside grid cells.

Literature values (from standard references, as commonly quoted; see docs/efficiency_tables.md):

* CD: track pitch 1.6 um (ECMA-130 / IEC 60908); pits about 0.5 um wide and 0.11 um deep
  (K. C. Pohlmann, The Compact Disc Handbook, 2nd ed., 1992). A pressed CD is read through its
  1.2 mm polycarbonate substrate; seen from there, the aluminium-coated pits are bumps. Modelled as a
  1-D lamellar grating of raised Al ridges 0.5 um wide (duty 0.5/1.6) and 110 nm high, continuous
  along the track, under polycarbonate (see fmm.py for the cover). The real pits cover roughly half
  of a track's length: the continuous ridge overstates the diffracted orders (and understates order 0).
* DVD: track pitch 0.74 um (ECMA-267); pits about 0.32 um wide (minimum length 0.4 um) and about
  lambda/(4 n) deep for its 650 nm laser, 105 nm; read through 0.6 mm of polycarbonate. Same model:
  ridges 0.32 um wide (duty 0.32/0.74), 105 nm high, under polycarbonate.
* Blazed: a ruled grating of 600 lines/mm (d = 1666.67 nm) blazed for 500 nm in the first order in
  Littrow: sin(theta_B) = lambda_B/(2d), theta_B = 8.627 deg; 90-degree-apex triangle, bare aluminium.
* Foil: an embossed holographic foil, a sinusoid of 1000 lines/mm, 100 nm peak-to-valley, bare
  aluminium (relief depths of embossed holograms are of order 0.1 um).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402

import efficiency_table as et  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
JSON_DIR = Path("data/efficiencies")
RUST_OUTPUT = Path("src/data/efficiency_presets_data.rs")
COARSEN = 1
RUST_DECIMALS = 5
PRESETS_CMD = "python3 python_ref/rigorous.py --presets"

BLAZE_600 = math.degrees(math.asin(500.0 / (2 * (1e6 / 600.0))))

# Presets solved by the crate's Rust solver: the grating-table flags of each (its grid: the
# committed JSON's nodes). One pass through the cover, as the nannos tables they replace (the
# multiple-pass sum is a choice of the solver, docs/efficiency_tables.md).
RUST_SOLVED = {
    "cd": ["--period", "1600", "--profile", "lamellar", "--depth", "110", "--duty", "0.3125",
           "--metal", "Al", "--cover", "polycarbonate", "--cover-passes", "single",
           "--solve-tolerance", "2.5e-4", "--max-harmonics", "1037", "--validation", "64", "--name", "cd"],
    "blazed600": ["--lines-per-mm", "600", "--profile", "sawtooth", "--blaze", repr(BLAZE_600), "--metal", "Al",
                  "--solve-tolerance", "2.5e-4", "--max-harmonics", "1037", "--validation", "16",
                  "--name", "blazed600"],
    "dvd": ["--period", "740", "--profile", "lamellar", "--depth", "105", "--duty", "0.43243243243243246",
            "--metal", "Al", "--cover", "polycarbonate", "--cover-passes", "single",
            "--solve-tolerance", "2.5e-4", "--max-harmonics", "1037", "--validation", "64", "--name", "dvd"],
}


def preset_gratings():
    import fmm

    return {
        "cd": (fmm.Grating("lamellar", 1600.0, 110.0, "Al", duty=0.5 / 1.6, cover="polycarbonate"),
               "Pressed CD read through its polycarbonate: track pitch 1.6 um, Al pits seen as ridges 0.5 um wide "
               "and 110 nm high (1-D lamellar, continuous along the track), polycarbonate cover"),
        "dvd": (fmm.Grating("lamellar", 740.0, 105.0, "Al", duty=0.32 / 0.74, cover="polycarbonate"),
                "DVD read through its polycarbonate: track pitch 0.74 um, pits seen as ridges 0.32 um wide and "
                "105 nm high (1-D lamellar), polycarbonate cover"),
        "blazed600": (fmm.sawtooth(1e6 / 600.0, BLAZE_600, "Al"),
                      "Ruled grating, 600 lines/mm, blazed for 500 nm in first-order Littrow "
                      f"(blaze {BLAZE_600:.3f} deg), 90-degree-apex triangle, aluminium"),
        "foil": (fmm.Grating("sinusoid", 1000.0, 100.0, "Al"),
                 "Embossed holographic foil: sinusoid of 1000 lines/mm, 100 nm peak-to-valley, aluminium"),
    }


# The blazed grating's C method needs 150-400 harmonics per node (its steep short facet), several
# seconds a node on a shared machine: a coarser grid and one fixed count, 243, checked at random
# nodes against 365 (161 was not enough: 1.6e-3 against 243).
PRESET_GRIDS = {
    "blazed600": (et.Grid(sin_step=0.2, lambda_step=60.0), {"fixed_nh": 243, "interp_points": 12, "check_points": 6}),
}


def build_all(workers: int = 2, json_only: bool = False, only: list[str] | None = None,
              reuse_existing: bool = False) -> list[Path]:
    written = []
    for name, (g, desc) in preset_gratings().items():
        if only and name not in only:
            continue
        if name in RUST_SOLVED:
            rust_solve(name)
            written.append(REPO / JSON_DIR / f"{name}.json")
            continue
        print(f"preset {name}: {desc}", flush=True)
        path = REPO / JSON_DIR / f"{name}.json"
        reuse = None
        if reuse_existing and path.exists():
            reuse = et.read_json(path)
            print(f"  reusing the nodes of the committed {path.relative_to(REPO)}", flush=True)
        grid, extra = PRESET_GRIDS.get(name, (et.Grid(), {}))
        t = et.build(g, grid, name, desc, PRESETS_CMD, workers=workers, reuse=reuse, **extra)
        et.write_json(t, path)
        print(f"wrote {path.relative_to(REPO)} ({path.stat().st_size / 1e6:.2f} MB)", flush=True)
        written.append(path)
    if not json_only:
        written += [REPO / p for p in generate(REPO)]
    return written


def rust_solve(name: str) -> None:
    """Re-solve a preset with the crate's Rust solver on the committed JSON's grid."""
    import subprocess

    _, desc = preset_gratings()[name]
    path = JSON_DIR / f"{name}.json"
    cmd = ["cargo", "run", "--release", "-q", "-p", "diffraction-fmm", "--bin", "grating-table", "--",
           *RUST_SOLVED[name], "--description", desc, "--nodes-of", str(path), "--out", str(path)]
    print("  " + " ".join(cmd), flush=True)
    subprocess.run(cmd, cwd=REPO, check=True)
    et.read_json(REPO / path)  # python_ref's reader accepts it


# ---------------------------------------------------------------- the Rust file


def _solver_text(t: dict) -> str:
    s = t["solver"]
    if s.get("fixed_count"):
        f = s["fixed_count"]
        return (f"{s['method']}, {f['harmonics']} harmonics at every node (against {f['checked_against']} at "
                f"{f['random_nodes']} random nodes: max change {f['max_change']:.1e})")
    if s["method"].startswith("diffraction-fmm"):
        return f"{s['method']}; {s['convergence']}"
    return f"{s['method']}, every node converged to 1e-3 (up to {s['harmonics']} harmonics)"


def _interp_text(t: dict) -> str:
    v = t["validation"]
    if "interpolation_compared_orders" in v:  # python_ref's check: over every compared order
        text = (f"Interpolation against fresh solves at {v['interpolation_points']} random points inside grid cells "
                f"({v['interpolation_compared_orders']} order efficiencies): |error| 95th percentile "
                f"{v['interpolation_abs_error_p95']:.1e}, max {v['interpolation_abs_error_max']:.1e}")
    else:  # the Rust builder's: each point's largest error over its orders and polarisations
        text = (f"Interpolation against fresh solves at {v['interpolation_points']} random points inside grid cells: "
                f"each point's largest |error| over its orders, 95th percentile {v['interpolation_abs_error_p95']:.1e}, "
                f"max {v['interpolation_abs_error_max']:.1e}")
    if "interpolation_rel_error_p95_eta_ge_0.01" in v:
        text += f"; relative error where eta >= 0.01: 95th percentile {v['interpolation_rel_error_p95_eta_ge_0.01']:.1%}"
    return text + "."


def _coarse_indices(n: int) -> list[int]:
    idx = list(range(0, n, COARSEN))
    if idx[-1] != n - 1:
        idx.append(n - 1)
    return idx


def coarsen(t: dict) -> dict:
    si = _coarse_indices(len(t["sin_theta_i"]))
    li = _coarse_indices(len(t["lambda_nm"]))
    c = dict(t)
    c["sin_theta_i"] = [t["sin_theta_i"][i] for i in si]
    c["lambda_nm"] = [t["lambda_nm"][j] for j in li]
    for pol in ("te", "tm"):
        a = np.asarray(t[pol])[:, li][:, :, si]
        c[pol] = np.round(a, RUST_DECIMALS).tolist()
    return c


def _lit(v: float) -> str:
    s = f"{v:.{RUST_DECIMALS}f}".rstrip("0")
    if s.endswith("."):
        s += "0"
    return "0.0" if s in ("0.0", "-0.0") else s


def _rust(root: Path) -> str:
    from tables import _wrap

    tables = {name: et.read_json(root / JSON_DIR / f"{name}.json") for name in preset_gratings()}
    header = [
        "// @generated by python_ref/presets.py (part `presets` of python_ref/generate.py): do not edit.",
        "// Regenerate with `python3 python_ref/generate.py` from the committed data/efficiencies/*.json",
        f"// (made by `{PRESETS_CMD}`).",
        "//",
    ]
    header += _wrap(
        "Rigorous per-order reflection efficiencies of the crate's presets (format: "
        "docs/efficiency_tables.md). For each preset NAME: NAME_PERIOD_NM, NAME_ORDER_MIN, "
        "NAME_ORDER_COUNT, NAME_SIN_THETA_I (strictly increasing), NAME_LAMBDA_NM (strictly "
        "increasing), NAME_TE and NAME_TM: f32 efficiencies, index ((k * n_lambda) + j) * n_sin + i "
        "for order m = NAME_ORDER_MIN + k, wavelength NAME_LAMBDA_NM[j], sin(theta_i) = "
        "NAME_SIN_THETA_I[i]; 0 where the order is evanescent at the node. Order m leaves at "
        "sin(theta_m) = sin(theta_i) + m lambda/d, sin(theta_i) = -wi.x, so u = wi.x + wo.x = m lambda/d; "
        "TE = E along the grooves, TM = H along the grooves; unpolarised = (TE + TM)/2."
    )
    header += _wrap(
        "Interpolation (docs/efficiency_tables.md): clamp sin(theta_i) and lambda to the grid; 0 where "
        "|sin(theta_i) + m lambda/d| >= 1; else q = eta cos(theta_i)/cos(theta_m) at the corners of the "
        "grid cell where the order propagates with cos^2(theta_m) > 1e-6, bilinear weights renormalised over those corners (0 if "
        "none), and eta = q cos(theta_m)/cos(theta_i) at the query. The order then appears exactly on "
        "its Rayleigh line with its square-root onset."
    )
    header += _wrap(
        "Grid: each preset's NAME_SIN_THETA_I and NAME_LAMBDA_NM, the JSON table's own nodes. "
        f"Values rounded to {RUST_DECIMALS} decimals."
    )
    body = [""]
    for name, t in tables.items():
        c = coarsen(t)
        g = t["grating"]
        up = name.upper()
        n_s, n_l = len(c["sin_theta_i"]), len(c["lambda_nm"])
        n_o = t["order_max"] - t["order_min"] + 1
        header.append("//")
        header += _wrap(
            f"{up}: {t['description']}. {_solver_text(t)}; {len(c['sin_theta_i'])} x {len(c['lambda_nm'])} nodes "
            f"(sin x lambda). {_interp_text(t)} Made by `{t['command']}`."
        )
        body.append(f"/// {name}: grating period, nm ({g['profile']}, {g['metal']}, cover {g['cover']}).")
        body.append(f"pub(crate) const {up}_PERIOD_NM: f64 = {g['period_nm']!r};")
        body.append(f"/// {name}: profile (sinusoid, lamellar or sawtooth; docs/efficiency_tables.md).")
        body.append(f"pub(crate) const {up}_PROFILE: &str = {json.dumps(g['profile'])};")
        body.append(f"/// {name}: depth, nm (peak-to-valley, ridge height, or d sin(blaze) cos(blaze)).")
        body.append(f"pub(crate) const {up}_DEPTH_NM: f64 = {float(g['depth_nm'])!r};")
        body.append(f"/// {name}: the raised ridge's share of the period (lamellar only).")
        duty = "None" if g["duty"] is None else f"Some({float(g['duty'])!r})"
        body.append(f"pub(crate) const {up}_DUTY: Option<f64> = {duty};")
        body.append(f"/// {name}: blaze angle, degrees (sawtooth only).")
        blaze = "None" if g["blaze_deg"] is None else f"Some({float(g['blaze_deg'])!r})"
        body.append(f"pub(crate) const {up}_BLAZE_DEG: Option<f64> = {blaze};")
        body.append(f"/// {name}: metal (a name of src/data/metals_data.rs, or N+Ki).")
        body.append(f"pub(crate) const {up}_METAL: &str = {json.dumps(g['metal'])};")
        body.append(f"/// {name}: cover over the metal (none or polycarbonate; docs/efficiency_tables.md).")
        body.append(f"pub(crate) const {up}_COVER: &str = {json.dumps(g['cover'])};")
        body.append(f"/// {name}: the first order of the table.")
        body.append(f"pub(crate) const {up}_ORDER_MIN: i32 = {t['order_min']};")
        body.append(f"/// {name}: the number of orders (consecutive from the first).")
        body.append(f"pub(crate) const {up}_ORDER_COUNT: usize = {n_o};")
        body.append(f"/// {name}: sin(theta_i) nodes, strictly increasing.")
        body.append(f"pub(crate) const {up}_SIN_THETA_I: [f32; {n_s}] = [{', '.join(_lit(v) if abs(v) != et.S_EDGE else repr(v) for v in c['sin_theta_i'])}];")
        body.append(f"/// {name}: wavelength nodes, nm, strictly increasing.")
        body.append(f"pub(crate) const {up}_LAMBDA_NM: [f32; {n_l}] = [{', '.join(_lit(v) for v in c['lambda_nm'])}];")
        for pol in ("te", "tm"):
            flat = np.asarray(c[pol]).reshape(-1)
            body.append(f"/// {name}: {pol.upper()} efficiencies, [order][lambda][sin] flattened.")
            body.append("#[rustfmt::skip]")
            body.append(f"pub(crate) static {up}_{pol.upper()}: [f32; {flat.size}] = [")
            # one [lambda] row of n_s values per group, wrapped at 100 columns
            for a in range(0, flat.size, n_s):
                line = "   "
                for v in flat[a:a + n_s]:
                    item = " " + _lit(v) + ","
                    if len(line) + len(item) > 100:
                        body.append(line)
                        line = "   "
                    line += item
                body.append(line)
            body.append("];")
    return "\n".join(header + body) + "\n"


def generate(out_root: Path) -> list[Path]:
    from tables import _rustfmt

    path = out_root / RUST_OUTPUT
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(_rust(REPO), encoding="utf-8")
    _rustfmt(path)
    return [RUST_OUTPUT]


def check_json(root: Path = REPO) -> list[str]:
    errs = []
    for name in ("cd", "dvd", "blazed600", "foil"):
        p = root / JSON_DIR / f"{name}.json"
        if not p.exists():
            errs.append(f"{p.relative_to(root)}: missing")
            continue
        try:
            et.read_json(p)
        except (et.TableError, ValueError, KeyError) as e:
            errs.append(f"{p.relative_to(root)}: {e}")
    return errs


def revalidate(name: str) -> None:
    """Redo a committed table's interpolation check (the same random points) and rewrite it."""
    g, _ = preset_gratings()[name]
    path = REPO / JSON_DIR / f"{name}.json"
    t = et.read_json(path)
    fixed = t["solver"].get("fixed_count")
    grid_extra = PRESET_GRIDS.get(name, (None, {}))[1]
    points = grid_extra.get("interp_points", t["validation"]["interpolation_points"])
    t.pop("sha256")
    check = et.interpolation_check(g, t, points, 1, fixed["harmonics"] if fixed else None, bool(fixed))
    t["validation"].update(check)
    et.write_json(t, path)
    print(f"{name}: interpolation |error| p95 {check['interpolation_abs_error_p95']:.2e}, max {check['interpolation_abs_error_max']:.2e}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rust", action="store_true", help="write src/data/efficiency_presets_data.rs from the JSON files")
    ap.add_argument("--revalidate", metavar="NAME", help="redo a committed table's interpolation check")
    ap.add_argument("--rust-solve", metavar="NAME", choices=sorted(RUST_SOLVED),
                    help="re-solve a preset with the Rust solver, then write the Rust file")
    args = ap.parse_args()
    if args.rust_solve:
        rust_solve(args.rust_solve)
        for p in generate(REPO):
            print(f"wrote {p}")
        return 0
    if args.revalidate:
        revalidate(args.revalidate)
        return 0
    if args.rust:
        for p in generate(REPO):
            print(f"wrote {p}")
        return 0
    ap.print_help()
    return 2


if __name__ == "__main__":
    sys.exit(main())
