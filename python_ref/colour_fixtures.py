"""Colour fixtures: CMF interpolation, XYZ -> sRGB, the sRGB transfer function, CIELAB and ΔE2000."""

from __future__ import annotations

import math
from pathlib import Path

import colour
import numpy as np

from common import CMF_KEY, REGEN_CMD, cie, f, rng, uniform, versions, write_csv

CMF_OUT = Path("tests/data/cmf_interp.csv")
SRGB_OUT = Path("tests/data/xyz_to_srgb.csv")
TRANSFER_OUT = Path("tests/data/srgb_transfer.csv")
LAB_OUT = Path("tests/data/lab_de2000.csv")

SRGB = colour.RGB_COLOURSPACES["sRGB"]


# --------------------------------------------------------------------------------------------
# CMF linear interpolation


def cmf_rows() -> list[list[str]]:
    t = cie()
    r = rng(2001)
    wls = [360.0, 830.0, 361.0, 400.0, 555.0, 700.0, 829.0]
    wls += [360.5, 829.5, 555.5, 360.0 + 1e-9, 830.0 - 1e-9, 599.999999, 600.000001]
    while len(wls) < 214:
        w = uniform(r, 360.0, 830.0)
        if w != math.floor(w):
            wls.append(w)
    out = []
    for w in wls:
        vals = [np.interp(w, t.wavelengths, t.cmf[:, i]) for i in range(3)]
        out.append([f(w)] + [f(v) for v in vals])
    return out


# --------------------------------------------------------------------------------------------
# XYZ -> sRGB


def d65_white_xyz() -> np.ndarray:
    """White point of the 1 nm D65 table, the crate's reference colour of a white reflector:
    ∫E·cmf / ∫E·ȳ with E and the CMFs linearly interpolated between rows (so Y = 1)."""
    from spectral import xyz_mirror

    return np.array(xyz_mirror("D65"))


def xyz_to_linear_srgb(xyz: np.ndarray) -> np.ndarray:
    rgb = colour.XYZ_to_RGB(
        xyz,
        SRGB,
        illuminant=SRGB.whitepoint,
        chromatic_adaptation_transform=None,
        apply_cctf_encoding=False,
    )
    plain = np.matmul(SRGB.matrix_XYZ_to_RGB, np.asarray(xyz)[..., None])[..., 0]
    assert np.array_equal(rgb, plain), "XYZ_to_RGB is not the plain matrix product"
    return rgb


def encode(v):
    return colour.cctf_encoding(v, function="sRGB")


def srgb_rows() -> list[list[str]]:
    t = cie()
    r = rng(3001)
    m_inv = np.linalg.inv(SRGB.matrix_XYZ_to_RGB)
    xyzs: list[np.ndarray] = []
    white = d65_white_xyz()
    xyzs.append(np.zeros(3))
    xyzs.append(white)
    xyzs.append(0.5 * white)
    xyzs.append(colour.xy_to_XYZ(SRGB.whitepoint))  # the xy (0.3127, 0.329) white, Y = 1
    # in gamut: random linear RGB well inside [0, 1] mapped to XYZ, plus the primaries' XYZ (scaled down)
    for _ in range(40):
        rgb = np.array([uniform(r, 0.02, 0.98) for _ in range(3)])
        xyzs.append(m_inv @ rgb)
    for i in range(3):
        e = np.zeros(3)
        e[i] = 0.9
        xyzs.append(m_inv @ e)
    # spectral colours (far out of gamut, negative components), Y = 1 and Y = 0.1
    for wl in (380, 420, 450, 470, 490, 500, 510, 520, 540, 560, 580, 600, 620, 650, 700, 780):
        c = t.cmf[wl - 360]
        xyzs.append(c / c[1] * (0.1 if wl % 20 == 0 else 1.0))
    # random XYZ, mostly out of gamut, some brighter than 1
    for _ in range(30):
        xyzs.append(np.array([uniform(r, 0.0, 1.2), uniform(r, 0.0, 1.2), uniform(r, 0.0, 1.3)]))
    # tiny values
    xyzs.append(1e-6 * white)
    xyzs.append(np.array([1e-3, 2e-3, 5e-4]))
    out = []
    for xyz in xyzs:
        xyz = np.array([float(v) for v in xyz])
        lin = xyz_to_linear_srgb(xyz)
        row = [f(v) for v in xyz] + [f(v) for v in lin]
        if np.all((lin >= 0) & (lin <= 1)):
            row += [f(v) for v in encode(lin)]
        else:
            row += ["", "", ""]
        out.append(row)
    return out


def transfer_rows() -> list[list[str]]:
    r = rng(4001)
    bp = 0.0031308
    vals = [0.0, 1.0, bp, math.nextafter(bp, 0), math.nextafter(bp, 1), bp * (1 - 1e-9), bp * (1 + 1e-9)]
    vals += [0.003, 0.00313, 0.00314, 0.0032, 0.0031, 0.0035, 0.004, 0.0025]
    vals += [1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 0.01, 0.018, 0.05, 0.1, 0.18, 0.2, 0.214, 0.5, 0.9, 0.99, 1 - 1e-12]
    vals += [math.nextafter(1.0, 0), 5e-324]
    while len(vals) < 70:
        vals.append(uniform(r, 0.0, 1.0))
    while len(vals) < 85:
        vals.append(10 ** uniform(r, -6.0, 0.0))
    while len(vals) < 100:
        vals.append(uniform(r, 0.0025, 0.0040))
    return [[f(v), f(encode(np.float64(v)))] for v in vals]


# --------------------------------------------------------------------------------------------
# CIELAB and CIEDE2000

# Sharma, Wu & Dalal (2005), "The CIEDE2000 color-difference formula: implementation notes,
# supplementary test data, and mathematical observations", Color Res. Appl. 30(1), Table 1:
# (Lab1, Lab2, published dE00 to 4 decimals).
SHARMA = [
    ((50.0000, 2.6772, -79.7751), (50.0000, 0.0000, -82.7485), 2.0425),
    ((50.0000, 3.1571, -77.2803), (50.0000, 0.0000, -82.7485), 2.8615),
    ((50.0000, 2.8361, -74.0200), (50.0000, 0.0000, -82.7485), 3.4412),
    ((50.0000, -1.3802, -84.2814), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, -1.1848, -84.8006), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, -0.9009, -85.5211), (50.0000, 0.0000, -82.7485), 1.0000),
    ((50.0000, 0.0000, 0.0000), (50.0000, -1.0000, 2.0000), 2.3669),
    ((50.0000, -1.0000, 2.0000), (50.0000, 0.0000, 0.0000), 2.3669),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0009), 7.1792),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0010), 7.1792),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0011), 7.2195),
    ((50.0000, 2.4900, -0.0010), (50.0000, -2.4900, 0.0012), 7.2195),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0009, -2.4900), 4.8045),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0010, -2.4900), 4.8045),
    ((50.0000, -0.0010, 2.4900), (50.0000, 0.0011, -2.4900), 4.7461),
    ((50.0000, 2.5000, 0.0000), (50.0000, 0.0000, -2.5000), 4.3065),
    ((50.0000, 2.5000, 0.0000), (73.0000, 25.0000, -18.0000), 27.1492),
    ((50.0000, 2.5000, 0.0000), (61.0000, -5.0000, 29.0000), 22.8977),
    ((50.0000, 2.5000, 0.0000), (56.0000, -27.0000, -3.0000), 31.9030),
    ((50.0000, 2.5000, 0.0000), (58.0000, 24.0000, 15.0000), 19.4535),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.1736, 0.5854), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.2972, 0.0000), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 1.8634, 0.5757), 1.0000),
    ((50.0000, 2.5000, 0.0000), (50.0000, 3.2592, 0.3350), 1.0000),
    ((60.2574, -34.0099, 36.2677), (60.4626, -34.1751, 39.4387), 1.2644),
    ((63.0109, -31.0961, -5.8663), (62.8187, -29.7946, -4.0864), 1.2630),
    ((61.2901, 3.7196, -5.3901), (61.4292, 2.2480, -4.9620), 1.8731),
    ((35.0831, -44.1164, 3.7933), (35.0232, -40.0716, 1.5901), 1.8645),
    ((22.7233, 20.0904, -46.6940), (23.0331, 14.9730, -42.5619), 2.0373),
    ((36.4612, 47.8580, 18.3852), (36.2715, 50.5065, 21.2231), 1.4146),
    ((90.8027, -2.0831, 1.4410), (91.1528, -1.6435, 0.0447), 1.4441),
    ((90.9257, -0.5406, -0.9208), (88.6381, -0.8985, -0.7239), 1.5381),
    ((6.7747, -0.2908, -2.4247), (5.8714, -0.0985, -2.2286), 0.6377),
    ((2.0776, 0.0795, -1.1350), (0.9033, -0.0636, -0.5514), 0.9082),
]
SHARMA_PAIR_ON_180 = 14  # 1-based: exactly 180° hue difference, see header


def lab_rows(white: np.ndarray) -> tuple[list[list[str]], float]:
    ill = colour.XYZ_to_xy(white)
    r = rng(5001)
    m_inv = np.linalg.inv(SRGB.matrix_XYZ_to_RGB)

    def lab(xyz):
        return colour.XYZ_to_Lab(np.asarray(xyz, dtype=np.float64), illuminant=ill)

    def from_lab(l):
        return colour.Lab_to_XYZ(np.asarray(l, dtype=np.float64), illuminant=ill)

    pairs: list[tuple[np.ndarray, np.ndarray]] = []
    # random pairs of in-gamut colours
    for _ in range(40):
        a = m_inv @ np.array([uniform(r, 0, 1) for _ in range(3)])
        b = m_inv @ np.array([uniform(r, 0, 1) for _ in range(3)])
        pairs.append((a, b))
    # random XYZ pairs (any, incl. out of gamut and Y > 1)
    for _ in range(25):
        a = np.array([uniform(r, 0, 1.1) for _ in range(3)])
        b = np.array([uniform(r, 0, 1.1) for _ in range(3)])
        pairs.append((a, b))
    # near-identical pairs
    for k in range(24):
        a = m_inv @ np.array([uniform(r, 0.05, 0.95) for _ in range(3)])
        eps = 10.0 ** -(1 + k % 8)
        b = a * (1 + eps * np.array([uniform(r, -1, 1) for _ in range(3)]))
        pairs.append((a, b))
    # hue-angle wrap-around (h near 0/360 on both sides) and near-opposite hues, built in Lab
    for k in range(20):
        L = uniform(r, 20, 90)
        C1, C2 = uniform(r, 1, 60), uniform(r, 1, 60)
        h1 = math.radians(uniform(r, 0.01, 8.0))
        h2 = math.radians(360.0 - uniform(r, 0.01, 8.0))
        if k % 4 == 3:  # near-opposite hues, avoiding exactly 180°
            h2 = h1 + math.radians(180.0 + (1 if k % 8 == 3 else -1) * uniform(r, 0.05, 3.0))
        lab1 = (L, C1 * math.cos(h1), C1 * math.sin(h1))
        lab2 = (L + uniform(r, -3, 3), C2 * math.cos(h2), C2 * math.sin(h2))
        pairs.append((from_lab(lab1), from_lab(lab2)))
    # special colours: black, white, greys (chroma ~0), identical pair
    pairs.append((np.zeros(3), white.copy()))
    pairs.append((white.copy(), white.copy()))
    pairs.append((0.18 * white, 0.2 * white))
    pairs.append((np.zeros(3), 1e-4 * white))
    pairs.append((white.copy(), white * np.array([1.0, 1.0, 0.98])))
    pairs.append((0.5 * white, m_inv @ np.array([0.5, 0.5, 0.5])))

    rows: list[list[str]] = []
    for a, b in pairs:
        a = np.array([float(v) for v in a])
        b = np.array([float(v) for v in b])
        la, lb = lab(a), lab(b)
        de = colour.delta_E(la, lb, method="CIE 2000")
        rows.append([f(v) for v in a] + [f(v) for v in b] + [f(v) for v in la] + [f(v) for v in lb] + [f(de)])
    worst = 0.0
    for i, (l1, l2, published) in enumerate(SHARMA, start=1):
        de = float(colour.delta_E(np.array(l1), np.array(l2), method="CIE 2000"))
        worst = max(worst, abs(de - published))
        if abs(de - published) > 5.001e-5:
            raise SystemExit(f"colour-science's dE2000 disagrees with Sharma pair {i}: {de} vs {published}")
        rows.append([""] * 6 + [f(v) for v in l1] + [f(v) for v in l2] + [f(de)])
    return rows, worst


# --------------------------------------------------------------------------------------------


def generate(out_root: Path) -> list[Path]:
    ver = versions()
    t = cie()

    rows = cmf_rows()
    write_csv(
        out_root / CMF_OUT,
        [
            "cmf_interp.csv: CIE 1931 2-degree colour-matching functions LINEARLY interpolated between the",
            f'1 nm rows of colour.MSDS_CMFS["{CMF_KEY}"] (the same table as src/data/cie_data.rs).',
            f"Made with numpy.interp in float64 ({ver}); written with Python repr().",
            "Wavelengths: 360, 830, a few integers and near-integers, and seeded random non-integers in [360, 830].",
            f"Rows: {len(rows)}.",
            f"Regenerate: {REGEN_CMD}",
        ],
        ["wavelength_nm", "x_bar", "y_bar", "z_bar"],
        rows,
    )

    rows = srgb_rows()
    n_enc = sum(1 for r in rows if r[6] != "")
    m = SRGB.matrix_XYZ_to_RGB
    write_csv(
        out_root / SRGB_OUT,
        [
            "xyz_to_srgb.csv: CIE XYZ (relative to D65, Y = 1 for white) -> linear sRGB -> encoded sRGB.",
            'linear = colour.XYZ_to_RGB(XYZ, colour.RGB_COLOURSPACES["sRGB"], illuminant=<sRGB whitepoint>,',
            "         chromatic_adaptation_transform=None, apply_cctf_encoding=False),",
            'which is exactly colour.RGB_COLOURSPACES["sRGB"].matrix_XYZ_to_RGB @ XYZ (asserted bit-for-bit):',
            "the IEC 61966-2-1 matrix with NO chromatic adaptation:",
            *[f"  [{', '.join(f(v) for v in row)}]" for row in m],
            'encoded = colour.cctf_encoding(linear, function="sRGB"), only for rows whose linear components',
            "are all in [0, 1]; the encoded columns are empty otherwise.",
            f"Made in float64 ({ver}); written with Python repr().",
            "Rows include black, the 1 nm-table D65 white (Y = 1) and half of it, the xy (0.3127, 0.329) white,",
            "in-gamut colours, spectral colours (negative components) and random XYZ (some with components > 1).",
            f"Rows: {len(rows)} ({n_enc} with encoded values).",
            f"Regenerate: {REGEN_CMD}",
        ],
        ["X", "Y", "Z", "R_linear", "G_linear", "B_linear", "R_encoded", "G_encoded", "B_encoded"],
        rows,
    )

    rows = transfer_rows()
    write_csv(
        out_root / TRANSFER_OUT,
        [
            "srgb_transfer.csv: the sRGB encoding transfer function (IEC 61966-2-1):",
            "encoded = 12.92 * linear for linear <= 0.0031308, else 1.055 * linear^(1/2.4) - 0.055.",
            f'Made with colour.cctf_encoding(linear, function="sRGB") in float64 ({ver}); Python repr().',
            "Values: 0, 1, the breakpoint 0.0031308 and its neighbours, seeded random values.",
            "Note: the standard's rounded constants make the curve jump by about 2.9e-8 at the breakpoint",
            "(0.040449936 at 0.0031308 vs 0.0404499075 just above); this file follows the formula as written.",
            f"Rows: {len(rows)}.",
            f"Regenerate: {REGEN_CMD}",
        ],
        ["linear", "encoded"],
        rows,
    )

    white = d65_white_xyz()
    rows, worst = lab_rows(white)
    n_sharma = len(SHARMA)
    write_csv(
        out_root / LAB_OUT,
        [
            "lab_de2000.csv: CIE XYZ pairs -> CIELAB (L*, a*, b*) -> CIEDE2000 colour difference.",
            "White (Xn, Yn, Zn): the D65 white of the 1 nm tables of src/data/cie_data.rs,",
            "  Xn = int(D65 * xbar) / int(D65 * ybar), Yn = 1, Zn = int(D65 * zbar) / int(D65 * ybar) over",
            "  360-830 nm with both factors linearly interpolated between rows (exact integrals of the",
            "  piecewise-quadratic products): the reference colour of a white reflector, Spectral::white().",
            "Lab = colour.XYZ_to_Lab(XYZ, illuminant=colour.XYZ_to_xy(white)) (colour goes through xy, so its",
            "  internal white equals (Xn, 1, Zn) to within ~1 ulp); L* in 0..100 scale.",
            'dE2000 = colour.delta_E(Lab1, Lab2, method="CIE 2000") (kL = kC = kH = 1).',
            f"Made in float64 ({ver}); written with Python repr().",
            "Rows: random pairs, near-identical pairs, hue wrap-around (h near 0/360) and near-opposite hues,",
            f"black/white/greys, then the {n_sharma} pairs of Sharma, Wu & Dalal (2005), Table 1, given as Lab",
            "  (their X,Y,Z columns are empty; dE2000 is colour-science's value, which matches the published",
            f"  4-decimal values to within {worst:.2g}). Sharma pair {SHARMA_PAIR_ON_180} (-0.001, 2.49) vs (0.0010, -2.49) has a hue",
            "  difference of exactly 180 degrees, where CIEDE2000 is discontinuous: published 4.8045, but one",
            "  ulp in atan2 gives 4.7461 (colour-science's own tests skip it for that reason). Test it loosely.",
            f"Rows: {len(rows)} ({len(rows) - n_sharma} XYZ pairs + {n_sharma} Sharma pairs).",
            f"Regenerate: {REGEN_CMD}",
            f"white: {f(white[0])} {f(white[1])} {f(white[2])}",
        ],
        ["X1", "Y1", "Z1", "X2", "Y2", "Z2", "L1", "a1", "b1", "L2", "a2", "b2", "dE2000"],
        rows,
    )
    return [CMF_OUT, SRGB_OUT, TRANSFER_OUT, LAB_OUT]
