"""Complex refractive indices n + ik of Al, Ag, Au, Cu and Cr over 360-830 nm.

Sources (all tabulated measurements, taken from the refractiveindex.info database, CC0 1.0):

* Al: A. D. Rakic, Appl. Opt. 34, 4755-4767 (1995), doi:10.1364/AO.34.004755
      (database/data/main/Al/nk/Rakic.yml)
* Ag, Au, Cu: P. B. Johnson and R. W. Christy, Phys. Rev. B 6, 4370-4379 (1972),
      doi:10.1103/PhysRevB.6.4370 (database/data/main/{Ag,Au,Cu}/nk/Johnson.yml)
* Cr: P. B. Johnson and R. W. Christy, Phys. Rev. B 9, 5056-5070 (1974),
      doi:10.1103/PhysRevB.9.5056 (database/data/main/Cr/nk/Johnson.yml); the same measurement
      technique and film preparation as the noble metals, so the five tables are comparable.

The rows used (every source row inside 200-2000 nm plus the nearest row on each side where
there is one, so that linear interpolation covers the visible band without extrapolation, and
the wavelengths a reduced conical table's |beta| planes reach beyond it: a plane between |beta|
nodes with c = sqrt(1 - beta^2) is read at lambda * c_p / c) are committed as
`python_ref/data/metals/<Metal>.csv`, with a header naming the paper, DOI, database path, commit and
licence. `python3 python_ref/metals.py --extract DIR` rebuilds those CSVs from a checkout of the
database (DIR contains `database/data/...`); it is not part of `generate.py` (the database is not a
Python package). Everything else is generated from the committed CSVs:

* `src/data/metals_data.rs`: rows [wavelength_nm, n, k] at the source's own points;
* `tests/data/metals.csv`: n, k linearly interpolated in wavelength at the source points, the
  midpoints between them and the band edges, with the normal-incidence reflectance
  R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2).

Wavelengths are stored in micrometres in the database; they are converted to nanometres with
exact decimal arithmetic (Decimal(um) * 1000), so 0.3315 um is 331.5 nm, not 331.49999999999994.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass
from decimal import Decimal
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True
sys.path.insert(0, str(Path(__file__).resolve().parent))

from common import FIRST_NM, LAST_NM, REGEN_CMD, REPO, f, write_csv  # noqa: E402

DATA_DIR = Path("python_ref/data/metals")
RUST_OUTPUT = Path("src/data/metals_data.rs")
CSV_OUTPUT = Path("tests/data/metals.csv")

# The rows kept: every source row inside this range (nm) plus the nearest one on each side.
KEEP_FIRST_NM = 200
KEEP_LAST_NM = 2000

# The database commit the committed CSVs were extracted from (refractiveindex.info-database).
DATABASE_COMMIT = "ff11b5897ef0754b15d939d921eb6c745693cbd1"
DATABASE_NAME = "refractiveindex.info database (github.com/polyanskiy/refractiveindex.info-database)"
LICENCE = "CC0 1.0 (the database's data files are in the public domain)"


@dataclass(frozen=True)
class Source:
    metal: str
    db_path: str
    citation: str
    doi: str

    @property
    def short(self) -> str:
        """'Rakic 1995' or 'Johnson & Christy 1972'."""
        year = self.citation.rsplit("(", 1)[1].rstrip(")")
        return ("Rakic" if self.citation.startswith("A. D. Rakic") else "Johnson & Christy") + " " + year


SOURCES = [
    Source(
        "Al",
        "database/data/main/Al/nk/Rakic.yml",
        "A. D. Rakic, Algorithm for the determination of intrinsic optical constants of metal films: "
        "application to aluminum, Appl. Opt. 34, 4755-4767 (1995)",
        "10.1364/AO.34.004755",
    ),
    Source(
        "Ag",
        "database/data/main/Ag/nk/Johnson.yml",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Phys. Rev. B 6, 4370-4379 (1972)",
        "10.1103/PhysRevB.6.4370",
    ),
    Source(
        "Au",
        "database/data/main/Au/nk/Johnson.yml",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Phys. Rev. B 6, 4370-4379 (1972)",
        "10.1103/PhysRevB.6.4370",
    ),
    Source(
        "Cu",
        "database/data/main/Cu/nk/Johnson.yml",
        "P. B. Johnson and R. W. Christy, Optical constants of the noble metals, "
        "Phys. Rev. B 6, 4370-4379 (1972)",
        "10.1103/PhysRevB.6.4370",
    ),
    Source(
        "Cr",
        "database/data/main/Cr/nk/Johnson.yml",
        "P. B. Johnson and R. W. Christy, Optical constants of transition metals: Ti, V, Cr, Mn, Fe, "
        "Co, Ni, and Pd, Phys. Rev. B 9, 5056-5070 (1974)",
        "10.1103/PhysRevB.9.5056",
    ),
]
METALS = [s.metal for s in SOURCES]


@dataclass(frozen=True)
class MetalTable:
    metal: str
    source: Source
    wavelength_nm: np.ndarray  # strictly increasing, first <= 360, last >= 830
    n: np.ndarray
    k: np.ndarray
    text_rows: list[tuple[str, str, str]]  # the committed strings (um, n, k) as in the source

    def nk(self, wavelength_nm) -> np.ndarray:
        """n + ik linearly interpolated in wavelength (n and k separately) between source rows."""
        w = np.asarray(wavelength_nm, dtype=np.float64)
        if np.any(w < self.wavelength_nm[0]) or np.any(w > self.wavelength_nm[-1]):
            raise ValueError(f"{self.metal}: wavelength outside {self.wavelength_nm[0]}-{self.wavelength_nm[-1]} nm")
        return np.interp(w, self.wavelength_nm, self.n) + 1j * np.interp(w, self.wavelength_nm, self.k)


def um_to_nm(text: str) -> float:
    return float(Decimal(text) * 1000)


# ---------------------------------------------------------------- extraction (one-off)


def _tabulated_rows(yml: str) -> list[tuple[str, str, str]]:
    """The `tabulated nk` data block of a database YAML file, as strings (no YAML library needed)."""
    lines = yml.splitlines()
    try:
        start = next(i for i, l in enumerate(lines) if l.strip() == "- type: tabulated nk")
    except StopIteration:
        raise SystemExit("no 'tabulated nk' block") from None
    assert lines[start + 1].strip() == "data: |", lines[start + 1]
    rows = []
    for l in lines[start + 2 :]:
        parts = l.split()
        if len(parts) != 3 or not l.startswith("        "):
            break
        rows.append((parts[0], parts[1], parts[2]))
    return rows


def extract(db_root: Path) -> list[Path]:
    out = []
    for s in SOURCES:
        rows = _tabulated_rows((db_root / s.db_path).read_text(encoding="utf-8"))
        wl = [um_to_nm(r[0]) for r in rows]
        assert all(a < b for a, b in zip(wl, wl[1:])), s.metal
        lo = max((i for i, w in enumerate(wl) if w <= KEEP_FIRST_NM), default=0)
        hi = min((i for i, w in enumerate(wl) if w >= KEEP_LAST_NM), default=len(wl) - 1)
        assert wl[lo] <= FIRST_NM and wl[hi] >= LAST_NM, s.metal
        keep = rows[lo : hi + 1]
        path = REPO / DATA_DIR / f"{s.metal}.csv"
        write_csv(
            path,
            [
                f"{s.metal}: complex refractive index n + ik, tabulated measurement.",
                f"Paper: {s.citation}, doi:{s.doi}.",
                f"Database: {DATABASE_NAME}, file {s.db_path}, commit {DATABASE_COMMIT}.",
                f"Licence: {LICENCE}.",
                f"Rows: every source row inside {KEEP_FIRST_NM}-{KEEP_LAST_NM} nm plus the nearest one on each side",
                "where there is one,",
                "copied verbatim (wavelength in micrometres as in the database). Extracted with",
                "`python3 python_ref/metals.py --extract DIR` (DIR: a checkout of the database).",
            ],
            ["wavelength_um", "n", "k"],
            [list(r) for r in keep],
        )
        out.append(path)
    return out


# ---------------------------------------------------------------- reading the committed rows

_CACHE: dict[str, MetalTable] = {}


def table(metal: str, root: Path = REPO) -> MetalTable:
    if metal in _CACHE:
        return _CACHE[metal]
    src = next((s for s in SOURCES if s.metal == metal), None)
    if src is None:
        raise ValueError(f"unknown metal {metal!r}: one of {', '.join(METALS)}")
    text_rows = []
    for line in (root / DATA_DIR / f"{metal}.csv").read_text(encoding="utf-8").splitlines():
        if line.startswith("#") or line.startswith("wavelength_um"):
            continue
        a, b, c = line.split(",")
        text_rows.append((a, b, c))
    wl = np.array([um_to_nm(r[0]) for r in text_rows])
    n = np.array([float(r[1]) for r in text_rows])
    k = np.array([float(r[2]) for r in text_rows])
    assert np.all(np.diff(wl) > 0) and wl[0] <= FIRST_NM and wl[-1] >= LAST_NM, metal
    assert np.all(n > 0) and np.all(k > 0), metal
    t = MetalTable(metal, src, wl, n, k, text_rows)
    _CACHE[metal] = t
    return t


def normal_reflectance(nk: complex | np.ndarray) -> np.ndarray:
    n, k = np.real(nk), np.imag(nk)
    return ((n - 1) ** 2 + k**2) / ((n + 1) ** 2 + k**2)


# ---------------------------------------------------------------- outputs


def _rust(root: Path) -> str:
    from tables import _wrap, rust_float

    header = [
        "// @generated by python_ref/metals.py (part `metals` of python_ref/generate.py) -- do not edit by hand.",
        f"// Regenerate with `{REGEN_CMD}` (check with `{REGEN_CMD} --check`).",
        "//",
    ]
    header += _wrap(
        "Complex refractive indices n + ik of metals, tabulated measurements at the sources' own "
        f"wavelengths, from the {DATABASE_NAME}, commit {DATABASE_COMMIT}; licence {LICENCE}. The rows "
        "are those committed in python_ref/data/metals/<Metal>.csv: every source row inside "
        f"{KEEP_FIRST_NM}-{KEEP_LAST_NM} nm plus the nearest one on each side where there is one "
        f"(the band {FIRST_NM}-{LAST_NM} nm, and the wavelengths the |beta| planes of a reduced "
        "conical table reach beyond it). Values are the sources' decimal "
        "strings (wavelengths converted from micrometres exactly), no resampling."
    )
    header += ["//"]
    for s in SOURCES:
        header += _wrap(f"{s.metal}: {s.citation}, doi:{s.doi} ({s.db_path}).")
    header += ["//"]
    header += _wrap(
        "Interpolation: n and k each linearly in wavelength between neighbouring rows (the "
        "expectation of tests/data/metals.csv, which holds such values computed with numpy.interp). "
        "Rows are [wavelength_nm, n, k], wavelength strictly increasing."
    )
    body = [""]
    for s in SOURCES:
        t = table(s.metal, root)
        body.append(f"/// {s.metal}: rows [wavelength_nm, n, k], {s.short} (doi:{s.doi}).")
        body.append(f"pub(crate) const {s.metal.upper()}_NK: [[f64; 3]; {len(t.wavelength_nm)}] = [")
        for w, n, k in zip(t.wavelength_nm, t.n, t.k):
            body.append(f"    [{rust_float(w)}, {rust_float(n)}, {rust_float(k)}],")
        body.append("];")
    return "\n".join(header + body) + "\n"


def _fixture_rows(root: Path) -> list[list[str]]:
    rows = []
    for metal in METALS:
        t = table(metal, root)
        pts: list[tuple[float, str]] = [(float(FIRST_NM), "band_edge"), (float(LAST_NM), "band_edge")]
        inside = [w for w in t.wavelength_nm if FIRST_NM < w < LAST_NM]
        pts += [(w, "source") for w in inside]
        for a, b in zip(t.wavelength_nm, t.wavelength_nm[1:]):
            mid = 0.5 * (a + b)
            if FIRST_NM < mid < LAST_NM:
                pts.append((mid, "midpoint"))
        for w, kind in sorted(pts):
            nk = complex(t.nk(w))
            rows.append([metal, f(w), kind, f(nk.real), f(nk.imag), f(normal_reflectance(nk))])
    return rows


def generate(out_root: Path) -> list[Path]:
    from tables import _rustfmt

    path = out_root / RUST_OUTPUT
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(_rust(REPO), encoding="utf-8")
    _rustfmt(path)

    al = table("Al")
    r550 = float(normal_reflectance(al.nk(550.0)))
    assert abs(r550 - 0.915) < 0.01, f"Al normal reflectance at 550 nm is {r550}, expected about 0.915"
    comments = [
        "Complex refractive index n + ik of Al, Ag, Au, Cu, Cr at the sources' own wavelengths inside",
        f"{FIRST_NM}-{LAST_NM} nm ('source'), the midpoints between neighbouring source rows ('midpoint') and",
        "the band edges ('band_edge'); n and k each linearly interpolated in wavelength with numpy.interp",
        "on the rows of python_ref/data/metals/<Metal>.csv (the rows of src/data/metals_data.rs), and the",
        "normal-incidence reflectance R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) in float64.",
        "Sources: " + "; ".join(f"{s.metal} doi:{s.doi}" for s in SOURCES) + ".",
        f"Check: Al at 550 nm: n + ik = {complex(al.nk(550.0)):.4f}, R = {r550:.4f}.",
        f"Made by python_ref/metals.py with numpy {np.__version__}; regenerate with `{REGEN_CMD}`.",
    ]
    write_csv(
        out_root / CSV_OUTPUT,
        comments,
        ["metal", "wavelength_nm", "kind", "n", "k", "reflectance_normal"],
        _fixture_rows(REPO),
    )
    return [RUST_OUTPUT, CSV_OUTPUT]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--extract", type=Path, metavar="DIR", help="rebuild python_ref/data/metals/*.csv from a database checkout")
    args = ap.parse_args()
    if args.extract:
        for p in extract(args.extract):
            print(f"wrote {p}")
        return 0
    for p in generate(REPO):
        print(f"wrote {p}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
