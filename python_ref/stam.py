"""`tests/data/stam_orders.csv`: the order efficiencies |c_m(phi)|^2 of Stam's model.

A one-dimensional periodic height profile h(x) of period d reflects, under the Kirchhoff
approximation, the Fourier series of p(x) = exp(i*phi*h(x)/h0), phi = k*w*h0; order m carries
|c_m|^2 of the light (Parseval: the sum over m is 1). Two profiles:

* sine,   h(x) = h0*sin(2*pi*x/d):  c_m = J_m(phi) (Jacobi-Anger), evaluated with mpmath.besselj;
* binary, h = h0 on [0, a*d), 0 elsewhere (a = fraction):
      |c_0|^2 = 1 - 4*a*(1 - a)*sin^2(phi/2),   |c_m|^2 = 4*sin^2(phi/2)*sin^2(pi*m*a)/(pi*m)^2.

Both are evaluated with mpmath at DPS digits from the exact binary values of the float arguments
and rounded once to f64. Independent cross-checks (reported in the header, not written as data):
J_m(phi) against the integral (1/pi)*int_0^pi cos(phi*sin t - m*t) dt, and the binary closed form
against the Fourier integral (1/d)*int_0^d p(x)*exp(-2*pi*i*m*x/d) dx, both by mpmath.quad.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
from mpmath import mp

from common import REGEN_CMD, f, randint, rng, uniform, versions, write_csv

OUTPUT = Path("tests/data/stam_orders.csv")
DPS = 50

# The zeros and maxima below are the f64 values nearest to them (mpmath, 30 digits).
SINE_PHASES = [
    0.0, 1e-12, 1e-9, 3e-6, 0.01, 0.5, 1.0,
    1.8411837813406593,  # maximum of J_1
    2.404825557695773,  # first zero of J_0
    3.8317059702075125,  # first zero of J_1
    5.0, 7.5, 10.0, 17.3, 31.4, 50.0, 99.9, 150.0, 200.0, 349.0, 500.0, 750.0, 999.75, 1000.0,
    -2.5, -120.7,
]
# Beyond 10^6 the crate switches to Hankel's expansion and forward recurrence: a few rows there.
LARGE_PHASES = [1.5e6, 2.0e7]
LARGE_ORDERS = [0, 1, 2, -3, 10, 1000]
SINE_ORDERS = [0, 1, 2, 3, -1, -2, -5, 7, 10, 20, 40, 100, -250]
BINARY_FRACTIONS = [0.5, 0.25, 0.1, 1.0 / 3.0, 0.75, 0.9, 1.0, 0.01]
BINARY_PHASES = [0.0, 1e-9, 0.3, math.pi / 2, 2.0, math.pi, 4.5, 2 * math.pi, 10.0, 100.5, -1.3]
BINARY_ORDERS = [0, 1, -1, 2, -2, 3, -3, 4, 5, 10, 17, 100, -100, 1001]
PHASE_MAX = 1000.0


def sine_coefficient(m: int, phi: float) -> mpmath.mpf:
    with mp.workdps(DPS):
        return mpmath.besselj(m, mpmath.mpf(phi))


def binary_efficiency(a: float, m: int, phi: float) -> mpmath.mpf:
    with mp.workdps(DPS):
        A, P = mpmath.mpf(a), mpmath.mpf(phi)
        s2 = mpmath.sin(P / 2) ** 2
        if m == 0:
            return 1 - 4 * A * (1 - A) * s2
        return 4 * s2 * mpmath.sinpi(m * A) ** 2 / (mp.pi * m) ** 2


def _sine_cases() -> list[tuple[float, int]]:
    r = rng(4242)
    phases = list(SINE_PHASES)
    phases += [uniform(r, 0.0, 20.0) for _ in range(8)]
    phases += [uniform(r, 20.0, PHASE_MAX) for _ in range(8)]
    out = []
    for phi in phases:
        n0 = int(abs(phi))
        orders = set(SINE_ORDERS)
        # Around the turning point m ~ phi, where J_m changes from oscillating to decaying.
        for dm in (-10, -1, 0, 1, 2, 5, 10, 30, 60):
            orders.add(n0 + dm)
            orders.add(-(n0 + dm))
        orders.add(randint(r, 0, n0 + 60))
        for m in sorted(orders):
            out.append((phi, m))
    for phi in LARGE_PHASES:
        for m in LARGE_ORDERS:
            out.append((phi, m))
    return out


def _check_sine() -> float:
    """Largest |besselj - integral| over a few cases."""
    worst = 0.0
    with mp.workdps(30):
        for m, phi in [(0, 2.5), (1, 1.8411837813406593), (3, 10.0), (-2, 7.5), (7, 31.4), (25, 30.0)]:
            P = mpmath.mpf(phi)
            integral = mpmath.quad(lambda t: mpmath.cos(P * mpmath.sin(t) - m * t), [0, mp.pi]) / mp.pi
            worst = max(worst, float(abs(integral - mpmath.besselj(m, P))))
    return worst


def _check_binary() -> float:
    """Largest |closed form - |Fourier integral|^2| over a few cases."""
    worst = 0.0
    with mp.workdps(30):
        for a, m, phi in [(0.5, 0, math.pi), (0.25, 1, 2.0), (1.0 / 3.0, -2, 4.5), (0.1, 3, 0.3), (0.75, 5, 10.0)]:
            A, P = mpmath.mpf(a), mpmath.mpf(phi)
            e = mpmath.expj(P)
            f_in = lambda x: e * mpmath.expj(-2 * mp.pi * m * x)  # noqa: E731
            f_out = lambda x: mpmath.expj(-2 * mp.pi * m * x)  # noqa: E731
            c = mpmath.quad(f_in, [0, A]) + mpmath.quad(f_out, [A, 1])
            worst = max(worst, float(abs(abs(c) ** 2 - binary_efficiency(a, m, phi))))
    return worst


def rows() -> list[list[str]]:
    out = []
    for phi, m in _sine_cases():
        with mp.workdps(DPS):
            j = sine_coefficient(m, phi)
            out.append(["sine", "", f(phi), str(m), f(j), f(j * j)])
    for a in BINARY_FRACTIONS:
        for phi in BINARY_PHASES:
            for m in BINARY_ORDERS:
                out.append(["binary", f(a), f(phi), str(m), "", f(binary_efficiency(a, m, phi))])
    return out


def generate(out_root: Path) -> list[Path]:
    data = rows()
    n_sine = sum(1 for r in data if r[0] == "sine")
    comments = [
        "stam_orders.csv: the order efficiencies |c_m(phi)|^2 of Stam's model for a periodic profile,",
        "  c_m = Fourier coefficients of p(x) = exp(i*phi*h(x)/h0) over one period, phi = k*w*h0.",
        "  sine:   h = h0*sin(2*pi*x/d), c_m = J_m(phi) (column bessel_j), efficiency = J_m(phi)^2;",
        "  binary: h = h0 on a fraction a (column fraction) of each period, 0 elsewhere;",
        "          |c_0|^2 = 1 - 4a(1-a) sin^2(phi/2), |c_m|^2 = 4 sin^2(phi/2) sin^2(pi m a)/(pi m)^2.",
        f"Made with mpmath at mp.dps = {DPS} ({versions()}): float arguments converted to mpf",
        "exactly, mpmath.besselj / mpmath.sin / mpmath.sinpi, each result rounded once to f64",
        "(float(mpf)); written with Python repr() (round-trip exact). bessel_j is empty on binary rows.",
        "Cross-checks by mpmath.quad at 30 digits: J_m against (1/pi) int_0^pi cos(phi sin t - m t) dt,",
        f"  max difference {_check_sine():.1e}; the binary closed form against |(1/d) int p(x) e^(-2 pi i m x/d) dx|^2,",
        f"  max difference {_check_binary():.1e}.",
        f"Ranges: sine |phi| <= {PHASE_MAX:g} (incl. zeros and maxima of J_0, J_1, tiny phi, seeded random phi,",
        "  Python random.Random), orders up to |phi| + 60 and fixed ones to |m| = 250; and phi = 1.5e6,",
        "  2e7 with |m| <= 1000 (the crate's large-argument path);",
        "  binary fractions 0.01-1, phases -1.3 to 100.5, orders up to |m| = 1001.",
        f"Rows: {len(data)} (sine: {n_sine}, binary: {len(data) - n_sine}).",
        f"Regenerate: {REGEN_CMD}",
    ]
    write_csv(
        out_root / OUTPUT,
        comments,
        ["profile", "fraction", "phase", "order", "bessel_j", "efficiency"],
        data,
    )
    return [OUTPUT]
