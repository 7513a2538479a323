#!/usr/bin/env python3
"""The C method in the conical mount, and the reference cases of fmm/tests/cmethod_conical.rs.

    python3 python_ref/cmethod_conical.py            # fmm/tests/data/cmethod_conical_fixed.csv (numpy + scipy, about a minute)
    python3 python_ref/cmethod_conical.py --nannos   # fmm/tests/data/cmethod_conical_nannos.csv (nannos staircases, about 20 min)

Formulation (time factor exp(-i omega t), lengths in units of 1/k0, H = Z0 H_SI, so
curl E = i H and curl H = -i eps E). The incident direction of travel has direction cosines
alpha across and beta along the grooves (x across, y along, z the normal, light from z > 0); all
fields vary as exp(i beta y). In a homogeneous medium, with kappa^2 = eps - beta^2,

    Ex = (i/kappa^2) (beta dEy/dx - dHy/dz),   Ez = (i/kappa^2) (dHy/dx + beta dEy/dz),
    Hx = (i/kappa^2) (beta dHy/dx + eps dEy/dz), Hz = (-i/kappa^2) (eps dEy/dx - beta dHy/dz),

and Ey, Hy each solve (d^2/dx^2 + d^2/dz^2 + kappa^2) phi = 0: each has the classical C method's
modes (cmethod.py, TE, p = 1) with eps replaced by kappa^2, carrying F = phi and
N = dphi/dz - a' dphi/dx (the gradient along grad u, u = z - a(x)). The surface couples them:
continuity of Ey, Hy and of the tangential components along (1, 0, a'),

    Ex + a' Ez = (i/kappa^2) (beta T[Ey] - N[Hy]),   Hx + a' Hz = (i/kappa^2) (beta T[Hy] + eps N[Ey]),

T[phi] = d phi/dx at fixed u (i alpha_n in the Fourier basis). These conditions are written here
as they stand, with their 1/kappa^2 factors, in a 4N system for [r_E, r_H, t_E, t_H].

Efficiency: a plane wave of direction (alpha, beta, gamma) in a real eps carries the z-flux
gamma |E|^2 / 2 with |E|^2 = (eps |Ey|^2 + |Hy|^2) / kappa^2 (derived from the relations
above; the Ey and Hy parts carry orthogonal fluxes), summed over both output polarisations.
Incident unit waves, direction (alpha, beta, -gamma) in air: s has E = s_hat =
(-beta, alpha, 0)/q, q = sqrt(alpha^2 + beta^2), so Ey = alpha/q and Hy = (k x E)_y =
beta gamma/q; p has H = s_hat, so Hy = alpha/q and Ey = -(k x H)_y = -beta gamma/q.

The Fourier coefficients are cmethod.py's: the slope's from the closed forms of a step function
(sawtooth) or an FFT of 2^14 samples (sinusoid), the plane waves' exp(i gamma a(x)) and
a'(x) exp(i gamma a(x)) by FFTs of 2^14 samples (2^20 for the sawtooth, whose slope jumps; the
Rust code integrates exactly, using a' exp(i g a) = (exp(i g a))'/(i g)).

`--nannos` checks the formulation against an independent method: nannos (the Fourier modal
method with Li's rule) on staircases of the same sinusoids with S, 2S and 4S slabs at a fixed
harmonic count, extrapolated in 1/S^2 (the mid-height staircase's error), on lossless
dielectric sinusoids, where the staircase converges in both polarisations.
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

sys.dont_write_bytecode = True
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("NANNOS_LOGLEVEL", "WARNING")
sys.path.insert(0, str(Path(__file__).resolve().parent))

import numpy as np  # noqa: E402
import scipy  # noqa: E402
import scipy.linalg  # noqa: E402

import cmethod  # noqa: E402
import fmm  # noqa: E402

REPO = Path(__file__).resolve().parent.parent
OUT_FIXED = REPO / "fmm" / "tests" / "data" / "cmethod_conical_fixed.csv"
OUT_NANNOS = REPO / "fmm" / "tests" / "data" / "cmethod_conical_nannos.csv"
CMD = "python3 python_ref/cmethod_conical.py"


def solve(profile: cmethod.Profile, lambda_nm: float, alpha: float, beta: float, eps_down: complex, n_harm: int):
    """Air above the profile, the medium eps_down below. Returns (orders, eta_s, eta_p, t_s, t_p):
    the reflected efficiencies of the orders propagating in air (alpha_m^2 + beta^2 < 1) for s and
    p incidence, and the transmitted totals (nan unless eps_down is real)."""
    if n_harm % 2 == 0:
        raise ValueError("n_harm must be odd")
    M = n_harm // 2
    N = n_harm
    k0 = 2 * np.pi / lambda_nm
    d = profile.period
    orders = np.arange(-M, M + 1)
    al = alpha + orders * lambda_nm / d
    D = np.diag(1j * al)
    if profile.kind == "triangle":
        br, sl = profile.slope_pieces()
        cA = cmethod._step_coeffs(br, sl, d, 2 * M)
    else:
        xs = np.arange(cmethod.FFT_POINTS) * d / cmethod.FFT_POINTS
        cA = cmethod._fft_coeffs(profile.slope(xs), 2 * M)
    A = cmethod._toeplitz(cA, N)
    I = np.eye(N)
    Binv = np.linalg.inv(np.block([[I, A], [-A, I]]))
    B11, B12, B21, B22 = Binv[:N, :N], Binv[:N, N:], Binv[N:, :N], Binv[N:, N:]
    # The plane waves' a' exp(i g a) is a step function times a continuous one on the sawtooth,
    # whose sampled coefficients err by O(1/points): 2^20 points there.
    points = 2**20 if profile.kind == "triangle" else cmethod.FFT_POINTS
    xs = np.arange(points) * d / points
    a_k0 = k0 * profile.height(xs)
    slope_s = profile.slope(xs)

    def matrix(kap2):
        # [D F; N] = B [Phi_x; Phi_z], F' = Phi_z, N' = -(D Phi_x + kappa^2 F)
        top = np.hstack([B21 @ D, B22])
        bot = np.hstack([-(D @ B11 @ D + kap2 * I), -(D @ B12)])
        return np.vstack([top, bot])

    def plane_wave(n_idx: int, g: float) -> np.ndarray:
        """[F; N] of exp(i al_n x + i g z)."""
        e = np.exp(1j * g * a_k0)
        E = cmethod._fft_coeffs(e, 2 * M)
        AE = cmethod._fft_coeffs(slope_s * e, 2 * M)
        sh = orders - orders[n_idx]
        F = E[2 * M + sh]
        Nf = 1j * g * E[2 * M + sh] - 1j * al[n_idx] * AE[2 * M + sh]
        return np.concatenate([F, Nf])

    b2 = beta * beta
    kap_up = 1.0 - b2
    kap_dn = eps_down - b2
    g_up = np.sqrt(kap_up - al**2 + 0j)
    prop = np.where(al**2 < kap_up)[0]
    gu, Vu = scipy.linalg.eig(matrix(kap_up))
    evan = cmethod._evanescent(gu, g_up[prop].real, N - prop.size, sign=-1)
    U = np.column_stack([plane_wave(n, g_up[n].real) for n in prop] + [Vu[:, j] for j in evan])
    lossless = np.imag(eps_down) == 0.0
    gd, Vd = scipy.linalg.eig(matrix(kap_dn))
    if lossless:
        kd = float(np.real(kap_dn))
        g_dn = np.sqrt(kd - al**2 + 0j)
        prop_dn = np.where(al**2 < kd)[0]
        ev2 = cmethod._evanescent(gd, g_dn[prop_dn].real, N - prop_dn.size, sign=+1)
        W = np.column_stack([plane_wave(n, -g_dn[n].real) for n in prop_dn] + [Vd[:, j] for j in ev2])
    else:
        down = np.where(gd.real > 0)[0]
        if down.size != N:
            raise cmethod.CMethodError(f"lower medium: {down.size} decaying modes, expected {N}")
        W = Vd[:, down]
    UF, UN, WF, WN = U[:N], U[N:], W[:N], W[N:]
    Z = np.zeros((N, N))
    bD = beta * D
    # Rows: Ey, Hy, (Ex + a'Ez)/i, (Hx + a'Hz)/i; columns r_E, r_H, t_E, t_H.
    sysm = np.block([
        [UF, Z, -WF, Z],
        [Z, UF, Z, -WF],
        [bD @ UF / kap_up, -UN / kap_up, -bD @ WF / kap_dn, WN / kap_dn],
        [UN / kap_up, bD @ UF / kap_up, -eps_down * WN / kap_dn, -bD @ WF / kap_dn],
    ])
    i0 = M
    g0 = g_up[i0].real
    q = math.hypot(alpha, beta)
    inc = plane_wave(i0, -g0)
    iF, iN = inc[:N], inc[N:]
    rhs = []
    for ey, hy in ((alpha / q, beta * g0 / q), (-beta * g0 / q, alpha / q)):  # s, p
        rhs.append(-np.concatenate([iF * ey, iF * hy, (bD @ iF * ey - iN * hy) / kap_up, (iN * ey + bD @ iF * hy) / kap_up]))
    x = np.linalg.solve(sysm, np.column_stack(rhs))
    rE, rH, tE, tH = x[:N], x[N:2 * N], x[2 * N:3 * N], x[3 * N:]
    air = np.where(al**2 + b2 < 1.0)[0]
    eff = []
    for c in range(2):
        flux = np.zeros(N)
        for j, n in enumerate(prop):
            flux[n] = g_up[n].real * (abs(rE[j, c]) ** 2 + abs(rH[j, c]) ** 2) / kap_up / g0
        eff.append(flux[air])
    t = [float("nan"), float("nan")]
    if lossless:
        for c in range(2):
            t[c] = float(sum(g_dn[n].real * (np.real(eps_down) * abs(tE[j, c]) ** 2 + abs(tH[j, c]) ** 2) / kd
                             for j, n in enumerate(prop_dn)) / g0)
    return orders[air], eff[0], eff[1], t[0], t[1]


# Fixed-truncation cases: (kind, period nm, depth nm, blaze deg, substrate, lambda nm, theta deg, phi deg, harmonics)
BLAZE_600 = math.degrees(math.asin(500.0 / (2 * (1e6 / 600.0))))
FIXED = [
    ("sinusoid", 1000.0, 100.0, None, "Al", 550.0, 30.0, 60.0, (41,)),  # the foil grating
    ("sinusoid", 1000.0, 100.0, None, "Al", 450.0, 60.0, 30.0, (41, 61)),
    ("sinusoid", 1e6 / 1200.0, 150.0, None, "Ag", 650.0, 45.0, 80.0, (41,)),
    ("sinusoid", 500.0, 200.0, None, "Ag", 450.0, 20.0, 45.0, (31, 47)),
    ("sinusoid", 2000.0, 300.0, None, "Au", 600.0, 40.0, 70.0, (61,)),
    ("sinusoid", 800.0, 400.0, None, "1.5+0i", 550.0, 35.0, 50.0, (41,)),  # lossless: R + T
    ("triangle", 1e6 / 600.0, None, BLAZE_600, "Al", 500.0, 20.0, 40.0, (41, 81)),  # blazed600
    ("triangle", 1000.0, None, 24.0, "Ag", 550.0, 30.0, 75.0, (61,)),
    ("triangle", 1600.0, None, 20.0, "1.5+0i", 500.0, 25.0, 30.0, (81,)),  # lossless: R + T
]


def _profile(kind, d, h, blaze):
    if kind == "triangle":
        h = fmm.sawtooth_depth(d, blaze)
    return cmethod.Profile(kind, d, h, blaze)


def _cosines(theta_deg, phi_deg):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    return math.sin(t) * math.cos(p), math.sin(t) * math.sin(p)


def fixed() -> int:
    rows = []
    t0 = time.time()
    for kind, d, h, blaze, sub, lam, th, ph, counts in FIXED:
        prof = _profile(kind, d, h, blaze)
        nk = fmm.metal_index(sub, lam)
        a, b = _cosines(th, ph)
        for nh in counts:
            m, es, ep, ts, tp = solve(prof, lam, a, b, complex(nk) ** 2, nh)
            for pol, e, t in (("s", es, ts), ("p", ep, tp)):
                for mm, v in zip(m, e):
                    rows.append((kind, d, prof.depth, blaze, nk, lam, a, b, nh, pol, str(int(mm)), float(v)))
                if not math.isnan(t):
                    rows.append((kind, d, prof.depth, blaze, nk, lam, a, b, nh, pol, "T", t))
    with OUT_FIXED.open("w") as f:
        f.write("# Conical C-method efficiencies at fixed harmonic counts (orders -M..M, M = harmonics // 2), one row per\n")
        f.write("# propagating reflected order (order = T: total transmitted into a lossless substrate) and incident polarisation.\n")
        f.write(f"# Made by python_ref/cmethod_conical.py (numpy {np.__version__}, scipy {scipy.__version__}); regenerate: `{CMD}`.\n")
        f.write("# Profiles: sinusoid z = (h/2) sin(2 pi x/d); triangle = the 90-degree-apex sawtooth of blaze_deg\n")
        f.write("# (depth d sin(blaze) cos(blaze)). Air above; substrate n + ik as written (metals from python_ref/data/metals).\n")
        f.write("# alpha, beta: the incident direction of travel's cosines across and along the grooves; s = E normal to the\n")
        f.write("# plane of incidence, p = E in it; efficiency = reflected z-flux of the order (both output polarisations)\n")
        f.write("# over the incident z-flux.\n")
        f.write("profile,period_nm,depth_nm,blaze_deg,n,k,lambda_nm,alpha,beta,harmonics,polarisation,order,efficiency\n")
        for kind, d, h, blaze, nk, lam, a, b, nh, pol, m, e in rows:
            bl = "" if blaze is None else repr(blaze)
            f.write(f"{kind},{d!r},{h!r},{bl},{nk.real!r},{nk.imag!r},{lam!r},{a!r},{b!r},{nh},{pol},{m},{e!r}\n")
    print(f"{len(rows)} rows -> {OUT_FIXED} ({time.time() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    if "--nannos" in sys.argv[1:]:
        import cmethod_conical_nannos

        raise SystemExit(cmethod_conical_nannos.main())
    raise SystemExit(fixed())
