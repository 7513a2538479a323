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

`tests/data/bessel_large.csv`: J_n(x) at large orders and arguments (n up to 2^31 - 1, x up to
1e10), where mpmath.besselj is too slow (its 0F1 series needs ~x bits and minutes at n = 1e5,
x = 1.01e5) or fails to converge (its Hankel series diverges for n^2 >> x). There J_n(x) is
Bessel's integral (1/2pi) int_{-pi}^{pi} exp(i(x sin t - n t)) dt on a deformed contour (the
integrand is entire and 2pi-periodic, so any periodic shift t -> t - i c(t) leaves it unchanged):

* n > x:  c = -alpha, cosh(alpha) = n/x, which makes the integrand real and peaked at t = 0,
          J_n(x) = (1/pi) int_0^pi exp(n (tanh(alpha) cos t - alpha)) cos(n (sin t - t)) dt;
* n <= x: c(t) = cos(beta) - cos(t), cos(beta) = n/x, through both saddle points t = +-beta
          scaled by 1/sin(beta) and held constant where |integrand| < e^-80 (leaving the saddles
          at -45 degrees, the steepest descent); for beta < 2.6 x^(-1/3) (the turning region)
          instead c(t) = cos(beta) - cos(t) + tan(30 deg) sin(t), the steepest direction from the
          double saddle at x = n.

Both by Gauss-Legendre quadrature on 48 and 96 panels over the window where the integrand is
above e^-72 of its peak (plus one panel each side); the two must agree.
"""

from __future__ import annotations

import math
from pathlib import Path

import mpmath
from mpmath import mp

from common import REGEN_CMD, f, randint, rng, uniform, versions, write_csv

OUTPUT = Path("tests/data/stam_orders.csv")
LARGE_OUTPUT = Path("tests/data/bessel_large.csv")
LARGE_DPS = 30
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


def bessel_contour(n: int, x: float) -> tuple[mpmath.mpf, mpmath.mpf]:
    """J_n(x) for n >= 0, x > 0 by the deformed Bessel integral (module docstring), and the
    difference between the 48- and 96-panel quadratures relative to max(|J|, x^-1/2) (n <= x)."""
    with mp.workdps(LARGE_DPS):
        N, X = mpmath.mpf(n), mpmath.mpf(x)
        if N > X:
            ta = mpmath.sqrt((N - X) * (N + X)) / N
            a = mpmath.acosh(N / X)

            def g(t):
                return mpmath.exp(N * (ta * mpmath.cos(t) - a)) * mpmath.cos(N * (mpmath.sin(t) - t))

            # The Gaussian exp(-n tanh(alpha) t^2/2) has fallen below e^-72 at 12 widths.
            window = [mpmath.mpf(0), min(+mp.pi, 12 / mpmath.sqrt(N * ta))]
        else:
            cb = N / X
            sb = mpmath.sqrt((1 - cb) * (1 + cb))
            beta = mpmath.acos(cb)
            if beta >= 2.6 / mpmath.cbrt(X):
                # Separated saddles: c = (cos(beta) - cos t)/sin(beta) leaves t = beta at -45
                # degrees (the steepest descent), |integrand| ~ exp(-x sin(beta) c^2/2 + x c^3/6);
                # c is held where that reaches e^-80 (beyond, |integrand| only decreases).
                c_hi = mpmath.sqrt(160 / (X * sb))
                c_lo = max(-c_hi, (cb - 1) / sb)

                def path(t):
                    c = (cb - mpmath.cos(t)) / sb
                    if c >= c_hi:
                        return c_hi, 0
                    if c <= c_lo:
                        return c_lo, 0
                    return c, mpmath.sin(t) / sb

                window = [mpmath.acos(min(1, cb - c_lo * sb)), mpmath.acos(max(-1, cb - c_hi * sb))]
            else:
                # Near the turning point: c = cos(beta) - cos t + tan(30 deg) sin t, the steepest
                # direction -30 degrees from the double saddle at x = n, |integrand| ~ exp(-0.26 x t^3).
                tilt = mpmath.tan(mp.pi / 6)

                def path(t):
                    return cb - mpmath.cos(t) + tilt * mpmath.sin(t), mpmath.sin(t) + tilt * mpmath.cos(t)

                window = [mpmath.mpf(0), 2 * beta + 10 / mpmath.cbrt(X)]

            def g(t):
                c, dc = path(t)
                th = t - 1j * c
                return (mpmath.exp(1j * (X * mpmath.sin(th) - N * th)) * (1 - 1j * dc)).real

        def integral(panels: int) -> mpmath.mpf:
            lo, hi = window
            pts = {mpmath.mpf(0), +mp.pi} | {lo + (hi - lo) * k / panels for k in range(panels + 1)}
            return mpmath.quad(g, sorted(pts), method="gauss-legendre") / mp.pi

        coarse, fine = integral(48), integral(96)
        scale = abs(fine) if N > X else 1 / mpmath.sqrt(X)
        return fine, (abs(coarse - fine) / scale if scale else mpmath.mpf(0))


# Orders of the large-order rows and the arguments around them: x = n*factor and the turning
# region x = n + offset*n^(1/3) (Debye's expansions start at |n - x| = 15 x^(1/3) in the crate).
LARGE_ORDERS_N = [100_000, 1_000_000, 2**31 - 1]
LARGE_FACTORS = [0.5, 0.9, 0.99, 0.999, 1.0, 1.001, 1.01, 1.1, 2.0]
TURNING_OFFSETS = [-40.0, -16.0, -14.0, -7.0, -1.0, -0.1, 0.1, 1.0, 7.0, 14.0, 16.0, 40.0]
# Small orders at arguments where the crate's recurrences would take more than 1e5 steps.
SMALL_ORDER_CASES = [(0, 5e5), (1, 5e5), (7, 5e5), (-100, 5e5), (1000, 9.99e5), (0, 2.5e5), (3, -3e5)]
# x = 1e10 with orders above the forward-recurrence range.
HUGE_X_ORDERS = [100_001, 1_000_000, 123_456_789, 2**31 - 1, -(2**31 - 1)]


def _large_cases() -> list[tuple[int, float]]:
    out = []
    for n in LARGE_ORDERS_N:
        for fac in LARGE_FACTORS:
            out.append((n, float(n) * fac))
        c = float(n) ** (1.0 / 3.0)
        for off in TURNING_OFFSETS:
            out.append((n, float(round(n + off * c, 3))))
        out.append((-n, float(n) * 1.01))
        out.append((n, -float(n) * 1.001))
    out += SMALL_ORDER_CASES
    out += [(m, 1e10) for m in HUGE_X_ORDERS]
    return out


def _large_rows() -> tuple[list[list[str]], float, float]:
    rows, worst_panels = [], 0.0
    for m, x in _large_cases():
        n, ax = abs(m), abs(x)
        if n > 1.5 * ax + 1100:  # J <= (e|x|/2n)^n < 1e-4000 at |n| >= 1e5: the f64 value is 0, no quadrature needed
            j = mpmath.mpf(0)
        else:
            j, diff = bessel_contour(n, ax)
            worst_panels = max(worst_panels, float(diff))
        if n % 2 == 1 and (m < 0) != (x < 0):
            j = -j
        rows.append([str(m), f(x), f(j)])
    # The oracle against mpmath.besselj where the latter is fast.
    worst_besselj = 0.0
    for n, x in [(200, 150.0), (200, 199.0), (200, 200.0), (200, 203.0), (200, 400.0), (0, 300.0),
                 (10_000, 9000.0), (100_000, 1e10), (7, 5e5), (1000, 1001.0), (2000, 1990.0)]:
        j, _ = bessel_contour(n, x)
        with mp.workdps(LARGE_DPS):
            ref = mpmath.besselj(n, mpmath.mpf(x))
            worst_besselj = max(worst_besselj, float(abs(j - ref) / abs(ref)))
    return rows, worst_panels, worst_besselj


def generate_large(out_root: Path) -> Path:
    data, worst_panels, worst_besselj = _large_rows()
    assert worst_panels < 1e-20, worst_panels
    assert worst_besselj < 1e-20, worst_besselj
    comments = [
        "bessel_large.csv: the Bessel function J_n(x) at large orders and arguments (|n| up to 2^31 - 1,",
        "  |x| up to 1e10): x = n*(0.5 ... 2), the turning region x = n + c*n^(1/3), small orders at",
        "  x up to 1e6, and x = 1e10; the crate's bounded-cost path (Debye's expansions).",
        f"Made with mpmath at mp.dps = {LARGE_DPS} ({versions()}): Bessel's integral",
        "  (1/2pi) int exp(i(x sin t - n t)) dt on a deformed periodic contour (through the saddle",
        "  points; see python_ref/stam.py), Gauss-Legendre on 48 and 96 panels; rows with",
        "  |n| > 1.5|x| + 1100 are 0 (J < 1e-4000 at these orders, |n| >= 1e5). Float arguments converted to mpf exactly, each result",
        "  rounded once to f64 (float(mpf)), written with Python repr() (round-trip exact).",
        f"  48- vs 96-panel difference (relative to |J|, or to x^-1/2 where n <= x): max {worst_panels:.1e};",
        f"  against mpmath.besselj at 11 moderate cases (n <= 1e5): max relative difference {worst_besselj:.1e}.",
        f"Rows: {len(data)}.",
        f"Regenerate: {REGEN_CMD}",
    ]
    write_csv(out_root / LARGE_OUTPUT, comments, ["order", "x", "bessel_j"], data)
    return LARGE_OUTPUT


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
    return [OUTPUT, generate_large(out_root)]
