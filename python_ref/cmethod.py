"""The coordinate-transformation method (C method, Chandezon) for smooth or piecewise-linear 1-D profiles.

Why a second solver: the Fourier modal method (nannos, Li's rule) converges well on lamellar
profiles, but a staircase of a smooth metal profile converges very slowly in TM (every step is a
pair of metal corners with a singular field). Measured on an Al sinusoid, d = 1000 nm, h = 120 nm,
550 nm, sin(theta) = 0.5: the TM sum over orders went 0.54, 0.56, 0.59, 0.63, 0.64 at 47-241
harmonics with 8 slabs and 0.45, 0.60, 0.66, 0.69, 0.70 with 16 slabs (changes of 6e-3 to 3e-2
between counts, 30 s a solve), while TE had converged to 1e-4. The C method maps the surface
z = a(x) onto the plane u = z - a(x) = 0, so there is a single interface and no staircase.

Formulation (classical mount, time factor exp(-i omega t), lengths in units of 1/k0): the field
phi = E_y (TE, p = 1) or H_y (TM, p = epsilon) of a homogeneous medium, written in (x, u), with
F = phi and G = (1/p) (-a' d phi/dx + (1 + a'^2) d phi/du) (the normal flux times |grad u|, continuous
across u = 0 with phi), satisfies d/du [F; G] = M [F; G] with, in the Fourier basis exp(i alpha_n x),
alpha_n = sin(theta_i) + n lambda/d, D = i diag(alpha):

    [D F; p G] = B [Phi_x; Phi_z],   B = [[I, A], [-A, I]],   A = Toeplitz matrix of a'(x),
    F' = Phi_z,   G' = -(1/p) (D Phi_x + epsilon F),

Phi_x, Phi_z the Cartesian derivatives of phi (continuous along u = const even where the slope
jumps), so every product of a discontinuous a' is with a continuous factor and the Laurent rule
holds; the inverse of B replaces the Toeplitz matrix of 1/(1 + a'^2) of the original method, which
converges badly on piecewise-linear profiles (this is Li's factorisation applied to the C method,
L. Li and J. Chandezon, JOSA A 13, 2247 (1996)). So d/du [F; G] = M [F; G] with
M = [[B21 D, p B22], [-(1/p) (D B11 D + epsilon), -D B12]] (B^-1 = [[B11, B12], [B21, B22]]).
(From the Helmholtz equation in the coordinates (x, u): metric g^xx = 1, g^xu = -a',
g^uu = 1 + a'^2, Jacobian 1; Phi_x = d phi/dx - a' d phi/du, Phi_z = d phi/du.)
Modes exp(gamma u). Above the surface the propagating orders use the exact plane waves
exp(i alpha_n x + i beta_n z) (Rayleigh orders: their u-representation is the Fourier series of
exp(i beta_n a(x)), and G follows in closed form); the evanescent ones are the numerical
eigenvectors with Re(gamma) < 0 once the 2P eigenvalues nearest the imaginary axis (the numerical
copies of the P propagating pairs) are set aside. Below, in the metal, the numerical eigenvectors
with Re(gamma) > 0. Continuity of [F; G] at u = 0 gives the amplitudes; order n carries
|r_n|^2 beta_n / beta_0. In a lossless lower medium the propagating orders there use exact plane
waves too, so that sum R + sum T = 1 can be checked.

Fourier coefficients: the profiles' a' is piecewise constant (sawtooth) or smooth (sinusoid); the
coefficients of functions of a' are exact for the sawtooth (step functions) and by FFT on 2^14
points for the sinusoid (exponentially accurate); exp(i beta a(x)) by FFT on 2^14 points.

References: J. Chandezon, M. T. Dupuis, G. Cornet, D. Maystre, J. Opt. Soc. Am. 72, 839 (1982);
L. Li, J. Chandezon, G. Granet, J.-P. Plumey, Appl. Opt. 38, 304 (1999).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.linalg

FFT_POINTS = 2**14


@dataclass(frozen=True)
class Profile:
    """a(x) on one period [0, d), its slope, and whether the slope is piecewise constant."""

    kind: str  # "sinusoid" | "triangle"
    period: float
    depth: float
    blaze_deg: float | None = None  # triangle: facet slope; apex angle 90 degrees

    def height(self, x: np.ndarray) -> np.ndarray:
        d, h = self.period, self.depth
        if self.kind == "sinusoid":
            return 0.5 * h * np.sin(2 * np.pi * x / d)
        t = math.tan(math.radians(self.blaze_deg))
        x1 = d * math.cos(math.radians(self.blaze_deg)) ** 2
        return np.where(x < x1, h - x * t, (x - x1) / t)

    def slope(self, x: np.ndarray) -> np.ndarray:
        d, h = self.period, self.depth
        if self.kind == "sinusoid":
            return 0.5 * h * (2 * np.pi / d) * np.cos(2 * np.pi * x / d)
        t = math.tan(math.radians(self.blaze_deg))
        x1 = d * math.cos(math.radians(self.blaze_deg)) ** 2
        return np.where(x < x1, -t, 1.0 / t)

    def slope_pieces(self) -> tuple[list[float], list[float]]:
        """Triangle: breakpoints 0 = x0 < x1 < x2 = d and the slope on each piece."""
        d = self.period
        t = math.tan(math.radians(self.blaze_deg))
        x1 = d * math.cos(math.radians(self.blaze_deg)) ** 2
        return [0.0, x1, d], [-t, 1.0 / t]


def _fft_coeffs(values: np.ndarray, nmax: int) -> np.ndarray:
    """c_n, n = -nmax..nmax, of a periodic function sampled at x_j = j*d/N (numpy order -> centred)."""
    c = np.fft.fft(values) / values.size
    idx = np.arange(-nmax, nmax + 1)
    return c[idx % values.size]


def _step_coeffs(breaks: list[float], vals: list[float], d: float, nmax: int) -> np.ndarray:
    """Exact Fourier coefficients (1/d) int f(x) exp(-2 pi i n x/d) dx of a piecewise-constant f."""
    n = np.arange(-nmax, nmax + 1)
    out = np.zeros(n.size, dtype=complex)
    for (a, b), v in zip(zip(breaks, breaks[1:]), vals):
        nz = n != 0
        kn = 2 * np.pi * n[nz] / d
        out[nz] += v * (np.exp(-1j * kn * b) - np.exp(-1j * kn * a)) / (-1j * kn * d)
        out[~nz] += v * (b - a) / d
    return out


def _toeplitz(c: np.ndarray, n: int) -> np.ndarray:
    """T[j, k] = c_{j-k} for j, k in 0..n-1, from c_m, m = -(n-1)..(n-1) (centred array)."""
    mid = (c.size - 1) // 2
    j = np.arange(n)
    return c[mid + j[:, None] - j[None, :]]


def _evanescent(g: np.ndarray, betas: np.ndarray, count: int, sign: int) -> np.ndarray:
    """Indices of the `count` evanescent modes decaying away from the surface (Re(gamma) of the
    sign `sign`) among the eigenvalues g, once the numerical copies of the propagating pairs
    +-i*beta_n (each matched to its nearest eigenvalue) are set aside. The modes taken are the
    `count` with the largest sign*Re(gamma) among the rest; a mode with the wrong sign among them is an
    error."""
    free = np.ones(g.size, dtype=bool)
    for b in betas:
        for target in (1j * b, -1j * b):
            cand = np.where(free)[0]
            free[cand[np.argmin(np.abs(g[cand] - target))]] = False
    rest = np.where(free)[0]
    pick = rest[np.argsort(-sign * g[rest].real)][:count]
    if np.any(sign * g[pick].real <= 0):
        raise CMethodError(f"only {np.sum(sign * g[rest].real > 0)} evanescent modes decay, {count} needed")
    return pick


@dataclass
class Result:
    orders: np.ndarray
    r_eff: np.ndarray  # reflected efficiency of each propagating order of the upper medium
    t_total: float  # lossless lower medium only: sum of transmitted efficiencies (else nan)


class CMethodError(RuntimeError):
    pass


def solve(profile: Profile, lambda_nm: float, sin_theta_i: float, eps_up: float, eps_down: complex,
          pol: str, n_harm: int) -> Result:
    """Reflection efficiencies of the orders propagating in the upper medium (permittivity eps_up,
    real), for a plane wave from above with tangential index sin_theta_i (= n_up * sin(theta) in the
    upper medium; in air sin(theta)). pol: "TE" or "TM". n_harm odd: orders -M..M."""
    if n_harm % 2 == 0:
        raise ValueError("n_harm must be odd")
    M = n_harm // 2
    N = n_harm
    k0 = 2 * np.pi / lambda_nm
    d = profile.period
    orders = np.arange(-M, M + 1)
    alpha = sin_theta_i + orders * lambda_nm / d
    D = np.diag(1j * alpha)

    # The slope's Toeplitz matrix (exact step-function coefficients for the triangle).
    if profile.kind == "triangle":
        br, sl = profile.slope_pieces()
        cA = _step_coeffs(br, sl, d, 2 * M)
    else:
        x = np.arange(FFT_POINTS) * d / FFT_POINTS
        cA = _fft_coeffs(profile.slope(x), 2 * M)
    A = _toeplitz(cA, N)
    I = np.eye(N)
    # [D F; p G] = B [Phi_x; Phi_z] with B = [[I, A], [-A, I]]: only products of the slope with the
    # continuous Cartesian derivatives, so the Laurent rule is exact there (Li's rule); then
    # F' = Phi_z and G' = -(1/p) (D Phi_x + eps F).
    Binv = np.linalg.inv(np.block([[I, A], [-A, I]]))
    B11, B12, B21, B22 = Binv[:N, :N], Binv[:N, N:], Binv[N:, :N], Binv[N:, N:]

    xs = np.arange(FFT_POINTS) * d / FFT_POINTS
    a_k0 = k0 * profile.height(xs)  # a(x) in units of 1/k0
    slope_s = profile.slope(xs)

    def matrix(eps, p):
        top = np.hstack([B21 @ D, p * B22])
        bot = np.hstack([-(1 / p) * (D @ B11 @ D + eps * I), -(D @ B12)])
        return np.vstack([top, bot])

    def plane_wave(n_idx: int, beta: complex, p) -> np.ndarray:
        """[F; G] of exp(i alpha_n x + i beta z) (beta > 0 up-going, < 0 down-going)."""
        e = np.exp(1j * beta * a_k0)
        E = _fft_coeffs(e, 2 * M)
        AE = _fft_coeffs(slope_s * e, 2 * M)
        # the coefficient of exp(i alpha_m x) is the (m - n)-th coefficient of e
        mid = 2 * M
        sh = orders - orders[n_idx]
        F = E[mid + sh]
        G = (1 / p) * (1j * beta * E[mid + sh] - 1j * alpha[n_idx] * AE[mid + sh])
        return np.concatenate([F, G])

    p_up = 1.0 if pol == "TE" else eps_up
    p_dn = 1.0 if pol == "TE" else eps_down
    beta_up = np.sqrt(eps_up - alpha**2 + 0j)
    prop_up = np.where(alpha**2 < eps_up)[0]
    P = prop_up.size

    # upper medium: exact up-going plane waves + numerical evanescent modes
    g1, V1 = scipy.linalg.eig(matrix(eps_up, p_up))
    evan = _evanescent(g1, beta_up[prop_up].real, N - P, sign=-1)
    up_cols = [plane_wave(n, beta_up[n].real, p_up) for n in prop_up]
    U = np.column_stack(up_cols + [V1[:, j] for j in evan])

    # lower medium
    lossless = abs(np.imag(eps_down)) == 0.0
    g2, V2 = scipy.linalg.eig(matrix(eps_down, p_dn))
    if lossless:
        eps2 = float(np.real(eps_down))
        beta_dn = np.sqrt(eps2 - alpha**2 + 0j)
        prop_dn = np.where(alpha**2 < eps2)[0]
        evan2 = _evanescent(g2, beta_dn[prop_dn].real, N - prop_dn.size, sign=+1)
        dn_cols = [plane_wave(n, -beta_dn[n].real, p_dn) for n in prop_dn] + [V2[:, j] for j in evan2]
    else:
        down = np.where(g2.real > 0)[0]
        if down.size != N:
            raise CMethodError(f"lower medium: {down.size} decaying modes, expected {N}")
        dn_cols = [V2[:, j] for j in down]
    W = np.column_stack(dn_cols)

    i0 = M  # order 0
    inc = plane_wave(i0, -beta_up[i0].real, p_up)
    A = np.hstack([U, -W])
    sol = np.linalg.solve(A, -inc)
    r = sol[:N]
    t = sol[N:]
    beta0 = beta_up[i0].real
    eff = np.abs(r[:P]) ** 2 * beta_up[prop_up].real / beta0
    t_total = float("nan")
    if lossless:
        ratio = 1.0 if pol == "TE" else float(np.real(eps_up) / eps2)
        t_total = float(np.sum(np.abs(t[: prop_dn.size]) ** 2 * beta_dn[prop_dn].real / beta0) * ratio)
    return Result(orders[prop_up], eff, t_total)
