"""fmm/tests/data/cmethod_conical_nannos.csv: conical sinusoid references from nannos staircases.

Run as `python3 python_ref/cmethod_conical.py --nannos` (needs requirements-rigorous.txt).

Lossless dielectric sinusoids (n = 1.5 and 2.0 below air; a dielectric staircase converges in
both polarisations, unlike a metal's in TM), azimuths 30-80 degrees, s and p. For each case nannos
(Fourier modal method, Li's rule, conical.py's polarisation conventions) solves staircases of
S = 24, 48 and 96 slabs (levels at the slabs' mid-heights) at a fixed harmonic count; the
mid-height staircase errs by O(1/S^2), so the reference is the Richardson extrapolation
(4 eta(2S) - eta(S)) / 3 from the last two, and the file records, per row, the difference between
the extrapolations from (24, 48) and from (48, 96) (`slab_change`) and the change of the
extrapolation from the lower harmonic count (`harmonic_change`). The header also gives the
largest difference between the references and python_ref/cmethod_conical.py's conical C method
converged (the same sinusoids at 121 harmonics, within 1e-6 of 81).
"""

from __future__ import annotations

import math
import time

import numpy as np
import scipy

import cmethod
import cmethod_conical as cc
import conical
import fmm
import rigorous

SLABS = (24, 48, 96)
NH = (91, 135)  # the reference at the last; the change from the first is recorded
CM_NH = (81, 121)  # the Python C method's check: its values at the last, the change from the first
# (period nm, depth nm, substrate n, lambda nm, theta deg, phi deg)
CASES = [
    (1000.0, 150.0, 1.5, 550.0, 30.0, 30.0),
    (1000.0, 150.0, 1.5, 550.0, 45.0, 60.0),
    (1000.0, 150.0, 1.5, 450.0, 60.0, 80.0),
    (600.0, 200.0, 1.5, 500.0, 30.0, 50.0),
    (600.0, 200.0, 1.5, 650.0, 50.0, 70.0),
    (1500.0, 300.0, 2.0, 600.0, 40.0, 40.0),
    (1500.0, 300.0, 2.0, 480.0, 25.0, 75.0),
]


def _nannos(d, h, n, lam, th, ph, nh, slabs):
    """{m: (eta_s, eta_p)} and the transmitted totals (s, p) of one staircase."""
    import nannos as nn

    g = fmm.Grating("sinusoid", d, h, f"{n}+0i")
    layers, _ = fmm._layers(g, lam, slabs)
    sim = nn.Simulation(layers, nn.PlaneWave(wavelength=float(lam), angles=(th, ph, 0.0)), nh=int(nh),
                        formulation=fmm.FORMULATION)
    r_p, t_p = sim.diffraction_efficiencies(orders=True)
    pw_s = nn.PlaneWave(wavelength=float(lam), angles=(th, ph, 90.0))
    sim.excitation = pw_s
    a0 = np.zeros(2 * sim.nh, dtype=complex)
    a0[sim.index_zeroth_order] = complex(pw_s.a0[0])
    a0[sim.nh + sim.index_zeroth_order] = complex(pw_s.a0[1])
    sim.a0 = a0
    r_s, t_s = sim.diffraction_efficiencies(orders=True)
    harm = np.asarray(sim.harmonics[0]).astype(int)
    a, b = cc._cosines(th, ph)
    out = {}
    for i, m in enumerate(harm.tolist()):
        if (a + m * lam / d) ** 2 + b * b < 1.0:
            out[m] = (float(np.real(r_s[i])), float(np.real(r_p[i])))
    t = (float(np.sum(np.real(np.asarray(t_s)))), float(np.sum(np.real(np.asarray(t_p)))))
    return out, t, int(sim.nh)


def _extrapolate(case, nh):
    """Per key (order m or "T") and polarisation index: (reference, |ext(S1,S2) - ext(S2,S3)|)."""
    vals = []
    for s in SLABS:
        o, t, got_nh = _nannos(*case, nh, s)
        flat = {(m, j): v[j] for m, v in o.items() for j in range(2)}
        flat.update({("T", j): t[j] for j in range(2)})
        vals.append(flat)
    out = {}
    for k in vals[0]:
        e1 = (4 * vals[1][k] - vals[0][k]) / 3
        e2 = (4 * vals[2][k] - vals[1][k]) / 3
        out[k] = (e2, abs(e2 - e1))
    return out, got_nh


def main() -> int:
    conical._check_fresnel()
    t0 = time.time()
    rows = []
    worst_cm, worst_slab, worst_nh, worst_conv = 0.0, 0.0, 0.0, 0.0
    for case in CASES:
        d, h, n, lam, th, ph = case
        lo, _ = _extrapolate(case, NH[0])
        hi, nh = _extrapolate(case, NH[1])
        a, b = cc._cosines(th, ph)
        prof = cmethod.Profile("sinusoid", d, h)
        cm = {}
        for nh_c in CM_NH:
            m, es, ep, ts, tp = cc.solve(prof, lam, a, b, complex(n) ** 2, nh_c)
            cur = {(int(mm), 0): v for mm, v in zip(m, es)} | {(int(mm), 1): v for mm, v in zip(m, ep)}
            cur |= {("T", 0): ts, ("T", 1): tp}
            if cm:
                conv = max(abs(cur[k] - cm[k]) for k in cur)
                worst_conv = max(worst_conv, conv)
                if conv > 1e-6:
                    raise SystemExit(f"{case}: the C method changed by {conv:.2g} from {CM_NH[0]} to {CM_NH[1]} harmonics")
            cm = cur
        for k in sorted(hi, key=lambda k: (k[1], k[0] == "T", k[0] if k[0] != "T" else 0)):
            ref, slab = hi[k]
            change = abs(ref - lo[k][0])
            worst_slab, worst_nh = max(worst_slab, slab), max(worst_nh, change)
            worst_cm = max(worst_cm, abs(ref - cm[k]))
            rows.append((d, h, n, lam, a, b, nh, "sp"[k[1]], str(k[0]), ref, slab, change))
        print(f"{case}: done, {time.time() - t0:.0f} s", flush=True)
    f = rigorous._fmt
    head = [
        "Conical reflection efficiencies of lossless dielectric sinusoids from nannos staircases extrapolated in the slab count,",
        "one row per propagating reflected order (order = T: total transmitted) and incident polarisation.",
        f"Made by `python3 python_ref/cmethod_conical.py --nannos` (python_ref/cmethod_conical_nannos.py) with {rigorous._versions()}:",
        f"nannos formulation=\"{fmm.FORMULATION}\" (Li's rule), epsilon on {fmm.DISCRETIZATION} points per period, staircases of",
        f"{', '.join(map(str, SLABS))} slabs (levels at mid-heights) at {NH[1]} harmonics; efficiency = (4 eta({SLABS[2]}) - eta({SLABS[1]}))/3",
        "(the staircase errs by O(1/S^2)). slab_change: |that - (4 eta(48) - eta(24))/3|; harmonic_change: the change of the",
        f"extrapolation from {NH[0]} harmonics. Largest slab_change {worst_slab:.2g}, largest harmonic_change {worst_nh:.2g}.",
        "Profile z = (h/2) sin(2 pi x/d) over a substrate of index n (k = 0), air above; alpha, beta: the incident direction",
        "of travel's cosines across and along the grooves; s = E normal to the plane of incidence, p = E in it (conical.py's",
        "conventions, checked against Fresnel at oblique azimuths); efficiency = the order's reflected z-flux over the incident's.",
        f"Check: python_ref/cmethod_conical.py's conical C method ({CM_NH[1]} harmonics; changed by at most {worst_conv:.2g} from {CM_NH[0]}) differs from these",
        f"references by at most {worst_cm:.2g}. {time.time() - t0:.0f} s on a shared 2-core machine.",
    ]
    lines = ["profile,period_nm,depth_nm,blaze_deg,n,k,lambda_nm,alpha,beta,harmonics,polarisation,order,efficiency,slab_change,harmonic_change"]
    for d, h, n, lam, a, b, nh, pol, m, ref, slab, change in rows:
        lines.append(",".join(["sinusoid", f(d), f(h), "", f(n), "0.0", f(lam), f(a), f(b), str(nh), pol, m, f(ref),
                               f"{slab:.3g}", f"{change:.3g}"]))
    cc.OUT_NANNOS.write_text("".join(f"# {c}\n" for c in head) + "\n".join(lines) + "\n", encoding="utf-8")
    print(f"{len(rows)} rows -> {cc.OUT_NANNOS}; C method vs nannos {worst_cm:.2g}, slab change {worst_slab:.2g}, "
          f"harmonic change {worst_nh:.2g} ({time.time() - t0:.0f} s)")
    return 0
