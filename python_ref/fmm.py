"""Rigorous reflection efficiencies of 1-D metal relief gratings: the solvers' common front end.

Two rigorous methods, each where it converges:

* lamellar profiles: the Fourier modal method of the `nannos` package with its
  `formulation="tangent"`, which for a 1-D grating is Li's factorisation rule (the Toeplitz matrix
  of epsilon for the field component along the grooves, the inverse of the Toeplitz matrix of
  1/epsilon for the one across them; L. Li, JOSA A 13, 1870 (1996)). The Laurent rule
  (`"original"`) does not converge for TM on metals.
* sinusoidal and sawtooth profiles: the coordinate-transformation (C) method with Li's
  factorisation, cmethod.py. A staircase of such a profile in the Fourier modal method converges
  very slowly in TM on metals (every step is a pair of metal corners); see cmethod.py for the
  numbers. The staircase solver stays here (`solve_staircase`) for the cross-checks of
  `rigorous.py --validate`, where it converges (TE on metals, both polarisations on dielectrics).

Geometry (x across the grooves, z up, the light comes from z > 0; classical mount, plane of
incidence = xz; metal below the surface, filling the half-space):

* sinusoid: surface z(x) = (h/2)*sin(2*pi*x/d), h peak-to-valley;
* lamellar: raised metal ridges of width duty*d and height h on a flat metal (0 <= x < duty*d);
* sawtooth: the triangular profile of a ruled grating with a 90 degree apex: the long facet of
  slope theta_B (the blaze angle) falls from z = h at x = 0 to z = 0 at x = d*cos^2(theta_B), the
  short facet (slope 90 deg - theta_B) rises back; h = d*sin(theta_B)*cos(theta_B). The long facet's
  normal leans toward +x, so the grating blazes into positive orders: Littrow in order m at
  sin(theta_i) = -m*lambda/(2d), sin(theta_m) = +m*lambda/(2d) (theta_i < 0: the light comes from
  the +x side).

Angles: s = sin(theta_i) is the x component of the incident wave's direction of travel in air.
Order m leaves at sin(theta_m) = s + m*lambda/d (nannos's harmonic m has k_x = k_x,inc + 2*pi*m/d;
the C method's alpha_m likewise). In the crate's terms s = -wi.x and sin(theta_m) = wo.x, so
u = wi.x + wo.x = m*lambda/d. TE: E along the grooves (y, s); TM: H along the grooves (p).
nannos's psi = 90 deg is TE, psi = 0 is TM (checked against Fresnel by `rigorous.py --validate`).

Efficiency of order m: the z-flux of the reflected order over the incident z-flux, 0 for
evanescent orders.

A dielectric cover (polycarbonate) over the metal: the grating is solved rigorously with the
polycarbonate as incidence medium; the flat air-polycarbonate surface (1.2 mm away: incoherent)
is applied analytically, one pass: eta_m(air) = T(theta_i)*eta_m(pc)*T(theta_m) for orders
that leave (|sin theta_m| < 1 in air), T = 1 - R the Fresnel power transmittance of the surface for
the same polarisation, plus the surface's own Fresnel reflectance R(theta_i) added to order 0.
Orders with 1 <= |sin theta_m| < n_pc are totally reflected at the surface and trapped in the disc
(they travel sideways in the 1.2 mm slab, are partly absorbed by the metal and leave far from
the lit spot or at the rim); they and the internally reflected part of the leaving orders (second and
later passes) are dropped, so the table is a slight underestimate, never an overestimate. The
dropped fraction is returned for the record.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

import metals

# nannos logs at INFO by default and warns about its optional backends; keep the output readable.
os.environ.setdefault("NANNOS_LOGLEVEL", "WARNING")

FORMULATION = "tangent"
# Points of the x grid on which nannos samples epsilon before its FFT (the Toeplitz matrices).
# Edges are placed to d/2^14 (0.6 nm at d = 10 um); the harmonic counts used stay far below the
# Nyquist limit 2^13.
DISCRETIZATION = 2**14
# Convergence: the largest change of any order's efficiency between the last two harmonic counts.
CONVERGENCE_TOL = 1e-3
# Harmonic counts are odd (orders -M..M); the sequence grows by this factor until converged.
NH_GROWTH = 1.5
NH_MIN = 21
NH_CAP_CMETHOD = 401  # the C method's eigenproblems are 2N x 2N per polarisation, two per solve
NH_CAP = 401  # an 802 x 802 eigenproblem in nannos: beyond that the case is reported as not converged

# Polycarbonate: N. Sultanova, S. Kasarova, I. Nikolov, Dispersion properties of optical polymers,
# Acta Physica Polonica A 116, 585-587 (2009); Sellmeier fit from the refractiveindex.info database
# (database/data/organic/(C16H14O3)n - polycarbonate/nk/Sultanova.yml, CC0):
# n^2 - 1 = B1*l^2/(l^2 - C1), l in um, valid 436.8-1052 nm (extrapolated below 436.8 nm).
PC_B1 = 1.4182
PC_C1 = 0.021304


def polycarbonate_n(lambda_nm: float) -> float:
    l2 = (lambda_nm / 1000.0) ** 2
    return math.sqrt(1.0 + PC_B1 * l2 / (l2 - PC_C1))


class NotConverged(RuntimeError):
    """Raised by solve_converged at the cap; `last` holds the result at the highest count reached
    and `change` its change from the count before."""

    def __init__(self, message, last=None, change=float("nan")):
        super().__init__(message)
        self.last = last
        self.change = change


@dataclass(frozen=True)
class Grating:
    profile: str  # "sinusoid" | "lamellar" | "sawtooth"
    period_nm: float
    depth_nm: float  # h: peak-to-valley (sinusoid), ridge height (lamellar), d*sin(2*blaze)/2 (sawtooth)
    metal: str  # "Al", "Ag", "Au", "Cu", "Cr" or a complex index "n+ki" (e.g. "1.2+7.0i")
    duty: float | None = None  # lamellar only
    blaze_deg: float | None = None  # sawtooth only
    cover: str = "none"  # "none" | "polycarbonate"

    def __post_init__(self):
        if self.profile not in ("sinusoid", "lamellar", "sawtooth"):
            raise ValueError(f"profile: {self.profile!r} is not sinusoid, lamellar or sawtooth")
        if not (self.period_nm > 0 and math.isfinite(self.period_nm)):
            raise ValueError(f"period: {self.period_nm} nm must be positive")
        if not (self.depth_nm >= 0 and math.isfinite(self.depth_nm)):
            raise ValueError(f"depth: {self.depth_nm} nm must be >= 0")
        if self.profile == "lamellar" and not (self.duty is not None and 0 < self.duty < 1):
            raise ValueError(f"duty: {self.duty} must be inside (0, 1) for a lamellar profile")
        if self.profile == "sawtooth":
            if self.blaze_deg is None or not (0 < self.blaze_deg < 45):
                raise ValueError(f"blaze: {self.blaze_deg} deg must be inside (0, 45) for a sawtooth")
            h = sawtooth_depth(self.period_nm, self.blaze_deg)
            if abs(h - self.depth_nm) > 1e-9 * h:
                raise ValueError(f"depth: a sawtooth's depth is d*sin(blaze)*cos(blaze) = {h} nm, not {self.depth_nm}")
        if self.cover not in ("none", "polycarbonate"):
            raise ValueError(f"cover: {self.cover!r} is not none or polycarbonate")
        metal_index(self.metal, 550.0)  # validates the name

    @property
    def symmetric(self) -> bool:
        """Mirror-symmetric profile (z(-x) = z(x + c)): eta_m(s) = eta_-m(-s)."""
        return self.profile in ("sinusoid", "lamellar")


def sawtooth_depth(period_nm: float, blaze_deg: float) -> float:
    """h = d*sin(theta_B)*cos(theta_B): the 90-degree-apex triangle."""
    t = math.radians(blaze_deg)
    return period_nm * math.sin(t) * math.cos(t)


def sawtooth(period_nm: float, blaze_deg: float, metal: str, cover: str = "none") -> Grating:
    h = sawtooth_depth(period_nm, blaze_deg)
    return Grating("sawtooth", period_nm, h, metal, blaze_deg=blaze_deg, cover=cover)


def parse_index(text: str) -> complex:
    """'1.2+7.0i' (also 'j', spaces ignored) -> complex; n > 0, k >= 0."""
    t = text.replace(" ", "").replace("i", "j")
    try:
        z = complex(t)
    except ValueError:
        raise ValueError(f"metal: {text!r} is neither a known metal nor an index n+ki") from None
    if not (z.real > 0 and z.imag >= 0 and math.isfinite(z.real) and math.isfinite(z.imag)):
        raise ValueError(f"metal: index {text!r} needs n > 0 and k >= 0")
    return z


def metal_index(metal: str, lambda_nm: float) -> complex:
    if metal in metals.METALS:
        return complex(metals.table(metal).nk(lambda_nm))
    return parse_index(metal)


def default_slabs(g: Grating, lambda_nm: float) -> int:
    """Staircase slab count (cross-checks only): one slab per lambda/40 of depth, at least 6."""
    if g.profile == "lamellar" or g.depth_nm == 0:
        return 1
    return max(6, math.ceil(40.0 * g.depth_nm / lambda_nm))


def _profile_mask(g: Grating, x: np.ndarray, level: float) -> np.ndarray:
    """True where the metal reaches above `level` (z measured from the profile's bottom)."""
    d, h = g.period_nm, g.depth_nm
    if g.profile == "sinusoid":
        z = 0.5 * h * (1.0 + np.sin(2.0 * np.pi * x / d))
    elif g.profile == "sawtooth":
        t = math.tan(math.radians(g.blaze_deg))
        x1 = d * math.cos(math.radians(g.blaze_deg)) ** 2
        z = np.where(x < x1, h - x * t, (x - x1) / t)
    else:
        z = np.where(x < g.duty * d, h, 0.0)
    return z > level


def _layers(g: Grating, lambda_nm: float, slabs: int):
    import nannos as nn

    eps_metal = metal_index(g.metal, lambda_nm) ** 2
    n_in = polycarbonate_n(lambda_nm) if g.cover == "polycarbonate" else 1.0
    eps_in = n_in**2
    lat = nn.Lattice(float(g.period_nm), DISCRETIZATION)
    # Sample at cell centres x_j = (j + 1/2)*d/N: nannos takes the FFT of the N samples as one
    # period (its own grid repeats x = 0 at x = d).
    x = ((np.arange(DISCRETIZATION) + 0.5) * g.period_nm / DISCRETIZATION).reshape(lat.ones().shape)
    layers = [lat.Layer("Superstrate", epsilon=eps_in)]
    if g.depth_nm > 0:
        h = g.depth_nm
        for j in range(slabs):
            level = h - (j + 0.5) * h / slabs if slabs > 1 else 0.5 * h
            mask = _profile_mask(g, x, level)
            eps = lat.ones() * eps_in
            eps[mask] = eps_metal
            layers.append(lat.Layer(f"slab{j}", thickness=h / slabs, epsilon=eps))
    layers.append(lat.Layer("Substrate", epsilon=eps_metal))
    return layers, n_in


def _propagating(s_in_medium: np.ndarray) -> np.ndarray:
    return np.abs(s_in_medium) < 1.0


@dataclass
class Solve:
    """One (grating, lambda, sin theta_i) at one harmonic count; efficiencies in the incidence medium."""

    orders: np.ndarray  # m
    te: np.ndarray  # eta_m, TE
    tm: np.ndarray  # eta_m, TM
    nh: int
    slabs: int
    n_in: float
    extra: dict = field(default_factory=dict)


def solve_once(g: Grating, lambda_nm: float, sin_theta_i: float, nh: int, slabs: int | None = None,
               want_transmission: bool = False) -> Solve:
    """The production solver: nannos for lamellar profiles (and flat ones), the C method otherwise.

    An order exactly at grazing in either medium (k_z = 0: both solvers divide by it) is moved off
    its Rayleigh line by shifting sin(theta_i) by RAYLEIGH_NUDGE; the efficiency of an appearing
    order grows like sqrt(distance), so the shift changes it by about sqrt(2e-9) ~ 5e-5 of its scale."""
    sin_theta_i = _off_rayleigh(g, lambda_nm, sin_theta_i)
    if g.profile == "lamellar" or g.depth_nm == 0:
        return solve_staircase(g, lambda_nm, sin_theta_i, nh, slabs, want_transmission)
    return solve_cmethod(g, lambda_nm, sin_theta_i, nh)


RAYLEIGH_NUDGE = 1e-9


def _off_rayleigh(g: Grating, lambda_nm: float, s: float) -> float:
    n_in = polycarbonate_n(lambda_nm) if g.cover == "polycarbonate" else 1.0
    n_sub = metal_index(g.metal, lambda_nm)
    media = [n_in] + ([n_sub.real] if n_sub.imag == 0 else [])
    m = np.arange(-4000, 4001)
    for _ in range(3):
        a = s + m * lambda_nm / g.period_nm
        if not any(np.any(np.abs(np.abs(a) - n) < 1e-12) for n in media):
            return s
        s = s + RAYLEIGH_NUDGE if s + RAYLEIGH_NUDGE < 1.0 else s - RAYLEIGH_NUDGE
    return s


def solve_cmethod(g: Grating, lambda_nm: float, sin_theta_i: float, nh: int) -> Solve:
    import cmethod

    if not (-1.0 < sin_theta_i < 1.0):
        raise ValueError(f"sin_theta_i: {sin_theta_i} must be inside (-1, 1)")
    kind = "sinusoid" if g.profile == "sinusoid" else "triangle"
    prof = cmethod.Profile(kind, g.period_nm, g.depth_nm, g.blaze_deg)
    n_in = polycarbonate_n(lambda_nm) if g.cover == "polycarbonate" else 1.0
    eps_m = metal_index(g.metal, lambda_nm) ** 2
    nh = _odd(nh)
    te = cmethod.solve(prof, lambda_nm, sin_theta_i, n_in**2, eps_m, "TE", nh)
    tm = cmethod.solve(prof, lambda_nm, sin_theta_i, n_in**2, eps_m, "TM", nh)
    assert np.array_equal(te.orders, tm.orders)
    out = Solve(te.orders, te.r_eff, tm.r_eff, nh, 0, n_in)
    if np.imag(eps_m) == 0:
        out.extra["T_te"], out.extra["T_tm"] = te.t_total, tm.t_total
        out.extra["R_te_all"], out.extra["R_tm_all"] = float(te.r_eff.sum()), float(tm.r_eff.sum())
    return out


def solve_staircase(g: Grating, lambda_nm: float, sin_theta_i: float, nh: int, slabs: int | None = None,
                    want_transmission: bool = False) -> Solve:
    """nannos, Li's rule. Both polarisations from one set of layer eigenmodes (the S-matrix does not depend on the
    incident polarisation; only the incident amplitude vector changes)."""
    import nannos as nn

    if not (-1.0 < sin_theta_i < 1.0):
        raise ValueError(f"sin_theta_i: {sin_theta_i} must be inside (-1, 1)")
    slabs = default_slabs(g, lambda_nm) if slabs is None else slabs
    layers, n_in = _layers(g, lambda_nm, slabs)
    s_med = sin_theta_i / n_in
    theta_deg = math.degrees(math.asin(s_med))
    pw_tm = nn.PlaneWave(wavelength=float(lambda_nm), angles=(theta_deg, 0.0, 0.0))
    sim = nn.Simulation(layers, pw_tm, nh=int(nh), formulation=FORMULATION)
    r_tm, t_tm = sim.diffraction_efficiencies(orders=True)
    pw_te = nn.PlaneWave(wavelength=float(lambda_nm), angles=(theta_deg, 0.0, 90.0))
    sim.excitation = pw_te
    a0 = np.zeros(2 * sim.nh, dtype=complex)
    a0[sim.index_zeroth_order] = complex(pw_te.a0[0])
    a0[sim.nh + sim.index_zeroth_order] = complex(pw_te.a0[1])
    sim.a0 = a0
    r_te, t_te = sim.diffraction_efficiencies(orders=True)
    harm = np.asarray(sim.harmonics[0]).astype(int)
    idx = np.argsort(harm)
    m = harm[idx]
    s_m = s_med + m * lambda_nm / (n_in * g.period_nm)
    prop = _propagating(s_m)
    te = np.where(prop, np.real(np.asarray(r_te))[idx], 0.0)
    tm = np.where(prop, np.real(np.asarray(r_tm))[idx], 0.0)
    out = Solve(m[prop], te[prop], tm[prop], sim.nh, slabs, n_in)
    if want_transmission:
        out.extra["T_te"] = float(np.sum(np.real(np.asarray(t_te))))
        out.extra["T_tm"] = float(np.sum(np.real(np.asarray(t_tm))))
        out.extra["R_te_all"] = float(np.sum(np.real(np.asarray(r_te))))
        out.extra["R_tm_all"] = float(np.sum(np.real(np.asarray(r_tm))))
    return out


def _odd(n: float) -> int:
    n = int(math.ceil(n))
    return n if n % 2 == 1 else n + 1


def first_nh(g: Grating, lambda_nm: float, n_in: float) -> int:
    """Starting harmonic count: the propagating orders (2*n_in*d/lambda + 1) with margin, at least 21."""
    return _odd(max(NH_MIN, 2.0 * (2.0 * n_in * g.period_nm / lambda_nm) + 11))


def _max_change(a: Solve, b: Solve) -> float:
    worst = 0.0
    for pol in ("te", "tm"):
        da = dict(zip(a.orders.tolist(), getattr(a, pol).tolist()))
        db = dict(zip(b.orders.tolist(), getattr(b, pol).tolist()))
        assert da.keys() == db.keys()
        worst = max(worst, max(abs(da[k] - db[k]) for k in da))
    return worst


@dataclass
class Converged:
    result: Solve  # at the highest harmonic count
    nh_sequence: list[int]
    change: float  # max |delta eta| between the last two counts


def solve_converged(g: Grating, lambda_nm: float, sin_theta_i: float, slabs: int | None = None,
                    nh_start: int | None = None, tol: float = CONVERGENCE_TOL, solver=None) -> Converged:
    """Raise the harmonic count by NH_GROWTH until no order of TE or TM changes by `tol` or more."""
    solve = solver or solve_once
    n_in = polycarbonate_n(lambda_nm) if g.cover == "polycarbonate" else 1.0
    nh = nh_start or first_nh(g, lambda_nm, n_in)
    prev = solve(g, lambda_nm, sin_theta_i, nh, slabs)
    seq = [prev.nh]
    ch = float("nan")
    while True:
        nh = _odd(nh * NH_GROWTH)
        if nh > (NH_CAP if g.profile == "lamellar" else NH_CAP_CMETHOD):
            raise NotConverged(f"{g} at {lambda_nm} nm, s = {sin_theta_i}: not converged to {tol} by {seq[-1]} harmonics",
                               last=prev, change=ch)
        cur = solve(g, lambda_nm, sin_theta_i, nh, slabs)
        seq.append(cur.nh)
        ch = _max_change(prev, cur)
        if ch < tol:
            return Converged(cur, seq, ch)
        prev = cur


def fresnel_rs_rp(n1: complex, n2: complex, sin_theta1: float) -> tuple[float, float]:
    """Power reflectances R_s (TE) and R_p (TM) of a flat interface, light from medium n1."""
    s1 = sin_theta1
    c1 = math.sqrt(1.0 - s1 * s1)
    c2 = np.sqrt(1.0 - (n1 * s1 / n2) ** 2 + 0j)
    if np.imag(n2 * c2) < 0:
        c2 = -c2
    rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2)
    rp = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2)
    return float(abs(rs) ** 2), float(abs(rp) ** 2)


@dataclass
class AirEfficiencies:
    """Efficiencies of the orders that leave into air (|sin theta_m| < 1)."""

    orders: np.ndarray
    sin_theta: np.ndarray
    te: np.ndarray
    tm: np.ndarray
    dropped_te: float  # cover only: power trapped (TIR) or internally reflected, not in the table
    dropped_tm: float


def to_air(g: Grating, lambda_nm: float, sin_theta_i: float, r: Solve) -> AirEfficiencies:
    s_m = sin_theta_i + r.orders * lambda_nm / g.period_nm
    leave = np.abs(s_m) < 1.0
    if g.cover == "none":
        return AirEfficiencies(r.orders, s_m, r.te.copy(), r.tm.copy(), 0.0, 0.0)
    n = r.n_in
    rs_i, rp_i = fresnel_rs_rp(1.0, n, sin_theta_i)
    te = np.zeros(int(leave.sum()))
    tm = np.zeros_like(te)
    dropped = [0.0, 0.0]
    out_orders = r.orders[leave]
    for pol, (r_in, arr, eta) in enumerate(((rs_i, te, r.te), (rp_i, tm, r.tm))):
        t_in = 1.0 - r_in
        j = 0
        for m, s, e in zip(r.orders, s_m, eta):
            if abs(s) < 1.0:
                rs_o, rp_o = fresnel_rs_rp(n, 1.0, s / n)
                r_out = rs_o if pol == 0 else rp_o
                arr[j] = t_in * e * (1.0 - r_out)
                dropped[pol] += t_in * e * r_out
                if m == 0:
                    arr[j] += r_in
                j += 1
            else:
                dropped[pol] += t_in * e
    return AirEfficiencies(out_orders, s_m[leave], te, tm, dropped[0], dropped[1])
