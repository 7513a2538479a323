"""Shared helpers for the reference generator: the CIE tables, float formatting, CSV writing."""

from __future__ import annotations

import math
import random
from dataclasses import dataclass
from pathlib import Path

import colour
import mpmath
import numpy as np
import scipy

REPO = Path(__file__).resolve().parent.parent
REGEN_CMD = "python3 python_ref/generate.py"
CHECK_CMD = "python3 python_ref/generate.py --check"

FIRST_NM = 360
LAST_NM = 830
N_ROWS = LAST_NM - FIRST_NM + 1  # 471

CMF_KEY = "CIE 1931 2 Degree Standard Observer"


def versions() -> str:
    """The library versions a file was made with, for headers."""
    return (
        f"colour-science {colour.__version__}, numpy {np.__version__}, "
        f"scipy {scipy.__version__}, mpmath {mpmath.__version__}"
    )


def f(v) -> str:
    """A float written so that it reads back exactly (shortest round-trip repr)."""
    v = float(v)
    if not math.isfinite(v):
        raise ValueError(f"non-finite value {v!r}")
    return repr(v)


def rng(seed: int) -> random.Random:
    """A seeded generator whose `random()` stream Python guarantees across versions."""
    return random.Random(seed)


def uniform(r: random.Random, a: float, b: float) -> float:
    return a + (b - a) * r.random()


def randint(r: random.Random, a: int, b: int) -> int:
    """Integer in [a, b] from `random()` only (stable across Python versions)."""
    return a + min(int((b - a + 1) * r.random()), b - a)


@dataclass(frozen=True)
class CieTables:
    wavelengths: np.ndarray  # float64, 360..=830 step 1
    cmf: np.ndarray  # (471, 3)
    d65: np.ndarray  # (471,)
    a: np.ndarray  # (471,)
    d65_native: str  # description of the native shape
    a_native: str


_TABLES: CieTables | None = None


def _aligned(sd_key: str) -> tuple[np.ndarray, str]:
    sd = colour.SDS_ILLUMINANTS[sd_key].copy()
    native = sd.shape
    interp = sd.interpolator.__name__
    sd = sd.align(colour.SpectralShape(FIRST_NM, LAST_NM, 1))
    wl = sd.wavelengths
    assert wl[0] == FIRST_NM and wl[-1] == LAST_NM and len(wl) == N_ROWS
    desc = (
        f"native {native.start:g}-{native.end:g} nm at {native.interval:g} nm; "
        f"brought to 360-830 nm at 1 nm with "
        f".align(colour.SpectralShape(360, 830, 1)) and its defaults, i.e. "
        f"{interp} (the dataset's own interpolator) between the native rows"
    )
    if native.end < LAST_NM or native.start > FIRST_NM:
        desc += (
            " and the default Extrapolator(method=\"Constant\"), which repeats "
            f"the {native.end:g} nm value over {native.end:g}-830 nm"
        )
    return np.asarray(sd.values, dtype=np.float64), desc


def _illuminant_a() -> tuple[np.ndarray, str]:
    """CIE standard illuminant A from its definition (CIE 15:2004 eq. 1, ISO 11664-2), a Planckian
    radiator: S_A(l) = 100 (560/l)^5 (exp(c2/(2848*560)) - 1) / (exp(c2/(2848*l)) - 1), c2 = 1.435e7
    nm K, evaluated by colour-science at every 1 nm row of 360-830 nm (no table, no extrapolation)."""
    shape = colour.SpectralShape(FIRST_NM, LAST_NM, 1)
    sd = colour.colorimetry.sd_CIE_standard_illuminant_A(shape)
    wl = np.asarray(sd.wavelengths, dtype=np.float64)
    assert np.array_equal(wl, np.arange(FIRST_NM, LAST_NM + 1, dtype=np.float64))
    values = np.asarray(sd.values, dtype=np.float64)
    # The function is the closed form above (colour-science writes it with numpy.expm1).
    c2 = 1.435e7
    closed = 100 * (560 / wl) ** 5 * np.expm1(c2 / (2848 * 560)) / np.expm1(c2 / (2848 * wl))
    assert np.allclose(values, closed, rtol=1e-14, atol=0), "sd_CIE_standard_illuminant_A changed"
    # The tabulated CIE A (300-780 nm at 5 nm, 6 significant digits) agrees to rounding.
    ref = colour.SDS_ILLUMINANTS["A"]
    rows = (ref.wavelengths >= FIRST_NM) & (ref.wavelengths <= LAST_NM)
    tab = np.asarray(ref.values, dtype=np.float64)[rows]
    at = values[(ref.wavelengths[rows] - FIRST_NM).astype(int)]
    worst = float(np.max(np.abs(at - tab) / tab))
    assert worst < 1e-5, worst
    desc = (
        "colour.colorimetry.sd_CIE_standard_illuminant_A(colour.SpectralShape(360, 830, 1)): the CIE "
        "definition (CIE 15:2004 eq. 1), a Planckian radiator, S_A(l) = 100 (560/l)^5 "
        "(exp(c2/(2848*560)) - 1) / (exp(c2/(2848*l)) - 1) with c2 = 1.435e7 nm K (so about 2856 K "
        "on the c2 = 1.4388e7 scale), evaluated at every 1 nm row up to 830 nm, no extrapolation; it "
        f'matches the 6-digit colour.SDS_ILLUMINANTS["A"] rows at 360-780 nm to {worst:.2g} relative'
    )
    return values, desc


def cie() -> CieTables:
    global _TABLES
    if _TABLES is None:
        cmfs = colour.MSDS_CMFS[CMF_KEY].copy()
        shape = cmfs.shape
        assert (shape.start, shape.end, shape.interval) == (FIRST_NM, LAST_NM, 1), shape
        wl = np.asarray(cmfs.wavelengths, dtype=np.float64)
        assert np.array_equal(wl, np.arange(FIRST_NM, LAST_NM + 1, dtype=np.float64))
        cmf = np.asarray(cmfs.values, dtype=np.float64)
        assert cmf.shape == (N_ROWS, 3) and np.all(cmf >= 0)
        d65, d65_desc = _aligned("D65")
        a, a_desc = _illuminant_a()
        _TABLES = CieTables(wl, cmf, d65, a, d65_desc, a_desc)
    return _TABLES


def write_csv(path: Path, comments: list[str], columns: list[str], rows: list[list[str]]) -> None:
    """Write `# comment` lines, one header row, then the rows (already formatted strings)."""
    lines = []
    for c in comments:
        for part in c.split("\n"):
            lines.append(("# " + part).rstrip())
    lines.append(",".join(columns))
    for row in rows:
        assert len(row) == len(columns), (row, columns)
        lines.append(",".join(row))
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
