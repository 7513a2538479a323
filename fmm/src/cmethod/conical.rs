//! The C method in the conical mount: fields ∝ e^{iβy} (β the incident direction cosine along
//! the grooves), a smooth or piecewise-linear profile z = a(x).
//!
//! Lengths in units of 1/k0, time factor e^{−iωt}, H̃ = Z₀H, so ∇×E = iH̃ and ∇×H̃ = −iεE. With
//! ∂_y = iβ and κ² = ε − β², the in-plane components of a homogeneous medium follow from the
//! two along the grooves (eliminating them from the curl equations):
//!
//! Eₓ = (i/κ²)(β∂ₓE_y − ∂_zH_y), E_z = (i/κ²)(∂ₓH_y + β∂_zE_y),
//! Hₓ = (i/κ²)(β∂ₓH_y + ε∂_zE_y), H_z = (−i/κ²)(ε∂ₓE_y − β∂_zH_y),
//!
//! and E_y, H_y each obey the 2-D Helmholtz equation (∂ₓ² + ∂_z² + κ²)φ = 0: in every medium both
//! have the classical C method's modes with ε replaced by κ² (the matrix M of the parent module
//! with p = 1, carrying F = φ and N = ∇u·∇φ = Φ_z − a'Φₓ, u = z − a(x)). The two couple only at
//! the surface, through the continuity of the tangential fields: E_y, H_y, and along the
//! surface's in-plane tangent (1, 0, a') (unnormalised, the same on both sides)
//!
//! Eₓ + a'E_z = (i/κ²)(β·T[E_y] − N[H_y]),  Hₓ + a'H_z = (i/κ²)(β·T[H_y] + ε·N[E_y]),
//!
//! where T[φ] = ∂φ/∂x at fixed u (the derivative along the surface, D·F in the Fourier basis)
//! and N[φ] the normal flux the classical method carries. Every quantity here is continuous
//! along u = const, and the slope multiplies nothing else: Li's factorisation holds as in the
//! classical mount. At β = 0 the conditions reduce to the classical TE (N[E_y] continuous) and
//! TM (N[H_y]/ε continuous) ones.
//!
//! So one solve is: the upper medium's modes (exact plane waves for its propagating orders, the
//! eigenvectors with Re γ < 0 for its evanescent ones, shared by E_y and H_y), the lower
//! medium's (Re γ > 0, exact plane waves for a lossless substrate's propagating orders), and one
//! 4N linear system for [r_E; r_H; t_E; t_H].
//!
//! Power: a plane wave of direction (α, β, γ) in a real ε carries the z-flux ½γ|E|² with
//! |E|² = (ε|E_y|² + |H_y|²)/κ² (the two parts are orthogonal in flux). Its s part (E along
//! ŝ = (−β, α, 0)/q, q = √(α² + β²)) carries ½γ|E·ŝ|², its p part ½γ|H̃·ŝ|²/ε; these feed the
//! cover's passes, which act per order and per s/p polarisation. Unit incident waves of
//! direction (α, β, −γ): s, E = ŝ: E_y = ŝ_y, H_y = −γ·ŝₓ; p, H̃ = n·ŝ: H_y = n·ŝ_y,
//! E_y = γ·ŝₓ/n (with ŝ = (ŝₓ, ŝ_y, 0)).
//!
//! References: L. Li, "Multilayer-coated diffraction gratings: differential method of Chandezon
//! et al. revisited", JOSA A 11, 2816 (1994) (conical diffraction); L. Li and J. Chandezon,
//! JOSA A 13, 2247 (1996) (the factorisation). The same formulation, in Python, is
//! `python_ref/cmethod_conical.py`.

use faer::linalg::solvers::Solve;
use faer::{c64, Mat};

use super::{decaying, matrix, modes, plane_wave, slope_matrices};
use crate::error::Error;
use crate::grating::{Grating, Incidence};
use crate::solver::{off_rayleigh, through_cover, Channel, Options, Order, Raw};
use crate::surface::{Phases, Surface};

/// The unit vector ŝ = (ŝₓ, ŝ_y) normal to the plane of incidence of direction cosines (a, b),
/// with the azimuth `phi` where a = b = 0 (normal incidence in the plane at azimuth φ).
fn s_hat(a: f64, b: f64, phi: f64) -> (f64, f64) {
    let q = a.hypot(b);
    if q > 0.0 {
        (-b / q, a / q)
    } else {
        (-phi.sin(), phi.cos())
    }
}

/// One solve at `nh` harmonics in the conical mount, s (TE) and p (TM) incidence: the air-side
/// orders (through the cover's passes when there is one) and, for a lossless substrate without
/// a cover, the transmitted totals.
pub(crate) fn solve_raw(
    g: &Grating,
    inc: &Incidence,
    nh: usize,
    opt: &Options,
) -> Result<Raw, Error> {
    let surface = Surface::of(g).ok_or(Error::invalid(
        "depth_nm",
        g.depth_nm(),
        "a continuous profile for the C method (sinusoid, sawtooth, Fourier, sampled or flat)",
    ))?;
    let lambda = inc.wavelength_nm;
    let d = g.period_nm;
    let beta = inc.beta;
    let (nr, ki) = g.metal.index(lambda);
    let eps_m = c64::new(nr, ki) * c64::new(nr, ki);
    let lossless = ki == 0.0 && eps_m.re > 0.0;
    let n_c = g.cover_n(lambda);
    let eps_c = n_c * n_c;
    let step = lambda / d;
    let mut media = vec![n_c];
    if lossless {
        media.push(nr);
    }
    let alpha0 = off_rayleigh(inc.alpha, beta, step, &media);
    let mm = (nh / 2) as i64;
    let alpha: Vec<f64> = (-mm..=mm).map(|m| alpha0 + m as f64 * step).collect();
    let k0 = core::f64::consts::TAU / lambda;
    let kmax = nh - 1;
    let one = c64::new(1.0, 0.0);

    let (s, as_) = slope_matrices(&surface, d, nh);

    // κ² = ε − β² per medium: the transverse wavenumber² of E_y and H_y.
    let b2 = beta * beta;
    let kap_c = eps_c - b2;
    let kap_m = eps_m - c64::new(b2, 0.0);
    let kap_s = eps_m.re - b2; // the lossless substrate's (real) κ²
    let gamma_up: Vec<f64> = alpha
        .iter()
        .map(|&x| (kap_c - x * x).max(0.0).sqrt())
        .collect();
    let prop_up: Vec<usize> = (0..nh).filter(|&i| alpha[i] * alpha[i] < kap_c).collect();
    let prop_dn: Vec<usize> = if lossless {
        (0..nh).filter(|&i| alpha[i] * alpha[i] < kap_s).collect()
    } else {
        Vec::new()
    };
    let gamma_dn: Vec<f64> = alpha
        .iter()
        .map(|&x| (kap_s - x * x).max(0.0).sqrt())
        .collect();
    let q_max = k0 * n_c.max(if lossless { nr } else { 0.0 });
    let phases = Phases::new(&surface, d, kmax, q_max);
    let i0 = mm as usize;
    let cover = g.cover.is_some();

    // The two media's bases [F; N] (2N × N each), shared by E_y and H_y.
    let up_kap = c64::new(kap_c, 0.0);
    let (g1, v1) = modes(&matrix(&s, &as_, &alpha, up_kap, one))?;
    let b_up: Vec<f64> = prop_up.iter().map(|&i| gamma_up[i]).collect();
    let evan = decaying(&g1, &b_up, nh - prop_up.len(), -1.0)?;
    let (g2, v2) = modes(&matrix(&s, &as_, &alpha, kap_m, one))?;
    let down = if lossless {
        let b_dn: Vec<f64> = prop_dn.iter().map(|&i| gamma_dn[i]).collect();
        decaying(&g2, &b_dn, nh - prop_dn.len(), 1.0)?
    } else {
        decaying(&g2, &[], nh, 1.0)?
    };
    let size = 2 * nh;
    let mut u = Mat::<c64>::zeros(size, nh);
    for (c, &n) in prop_up.iter().enumerate() {
        let w = plane_wave(&phases, k0, &alpha, n, gamma_up[n], up_kap, one);
        for (r, val) in w.into_iter().enumerate() {
            u[(r, c)] = val;
        }
    }
    for (c, &j) in evan.iter().enumerate() {
        for r in 0..size {
            u[(r, prop_up.len() + c)] = v1[(r, j)];
        }
    }
    let mut w = Mat::<c64>::zeros(size, nh);
    let dn_kap = c64::new(kap_s, 0.0);
    for (c, &n) in prop_dn.iter().enumerate() {
        let pw = plane_wave(&phases, k0, &alpha, n, -gamma_dn[n], dn_kap, one);
        for (r, val) in pw.into_iter().enumerate() {
            w[(r, c)] = val;
        }
    }
    for (c, &j) in down.iter().enumerate() {
        for r in 0..size {
            w[(r, prop_dn.len() + c)] = v2[(r, j)];
        }
    }

    // Continuity at u = 0, unknowns [r_E; r_H; t_E; t_H], rows (×κ_c² for the last two):
    // F_E; F_H; β·D·F_E − N_H; β·D·F_H + ε·N_E (the lower medium's scaled by ρ = κ_c²/κ²).
    let rho = up_kap / kap_m;
    let bd = |i: usize| c64::new(0.0, beta * alpha[i]); // β·D
    let n = nh;
    let mut sys = Mat::<c64>::zeros(4 * n, 4 * n);
    for c in 0..n {
        for i in 0..n {
            let (uf, un) = (u[(i, c)], u[(n + i, c)]);
            let (wf, wn) = (w[(i, c)], w[(n + i, c)]);
            sys[(i, c)] = uf;
            sys[(i, 2 * n + c)] = -wf;
            sys[(n + i, n + c)] = uf;
            sys[(n + i, 3 * n + c)] = -wf;
            sys[(2 * n + i, c)] = bd(i) * uf;
            sys[(2 * n + i, n + c)] = -un;
            sys[(2 * n + i, 2 * n + c)] = -rho * bd(i) * wf;
            sys[(2 * n + i, 3 * n + c)] = rho * wn;
            sys[(3 * n + i, n + c)] = bd(i) * uf;
            sys[(3 * n + i, c)] = c64::new(eps_c, 0.0) * un;
            sys[(3 * n + i, 3 * n + c)] = -rho * bd(i) * wf;
            sys[(3 * n + i, 2 * n + c)] = -rho * eps_m * wn;
        }
    }
    // Incident channels: (order, pol) with pol 0 = s, 1 = p; all of the cover's under a cover.
    let incident: Vec<(usize, usize)> = if cover {
        prop_up.iter().flat_map(|&i| [(i, 0), (i, 1)]).collect()
    } else {
        vec![(i0, 0), (i0, 1)]
    };
    let mut rhs = Mat::<c64>::zeros(4 * n, incident.len());
    for (c, &(m, pol)) in incident.iter().enumerate() {
        let (sx, sy) = s_hat(alpha[m], beta, inc.phi);
        let gam = gamma_up[m];
        let (ey, hy) = if pol == 0 {
            (sy, -gam * sx)
        } else {
            (gam * sx / n_c, n_c * sy)
        };
        let pw = plane_wave(&phases, k0, &alpha, m, -gam, up_kap, one);
        for i in 0..n {
            let (f, nn) = (pw[i], pw[n + i]);
            rhs[(i, c)] = -f * ey;
            rhs[(n + i, c)] = -f * hy;
            rhs[(2 * n + i, c)] = -(bd(i) * f * ey - nn * hy);
            rhs[(3 * n + i, c)] = -(bd(i) * f * hy + c64::new(eps_c, 0.0) * nn * ey);
        }
    }
    let x = sys.partial_piv_lu().solve(&rhs);

    // Power matrix between the cover's propagating channels (order, s/p).
    let chans: Vec<Channel> = prop_up
        .iter()
        .flat_map(|&i| [Channel::scalar(i, 0), Channel::scalar(i, 1)])
        .collect();
    let mut pm = vec![vec![0.0; incident.len()]; chans.len()];
    for (o, &m) in prop_up.iter().enumerate() {
        let (sx, sy) = s_hat(alpha[m], beta, inc.phi);
        let gam = gamma_up[m];
        for (c, &(mi, _)) in incident.iter().enumerate() {
            let (re, rh) = (x[(o, c)], x[(n + o, c)]);
            // The up-going wave's Eₓ and Hₓ from E_y and H_y.
            let ex = (rh * gam - re * (beta * alpha[m])) / kap_c;
            let hx = -(rh * (beta * alpha[m]) + re * (eps_c * gam)) / kap_c;
            let e_s = ex * sx + re * sy;
            let h_s = hx * sx + rh * sy;
            let g_in = gamma_up[mi];
            pm[2 * o][c] = gam * e_s.norm_sqr() / g_in;
            pm[2 * o + 1][c] = gam * h_s.norm_sqr() / eps_c / g_in;
        }
    }
    let mut orders: Vec<Order> = alpha
        .iter()
        .enumerate()
        .filter(|(_, &a)| a * a + b2 < 1.0)
        .map(|(i, &a)| Order {
            m: i as i32 - mm as i32,
            alpha: a,
            te: 0.0,
            tm: 0.0,
        })
        .collect();
    let q_inc = alpha0.hypot(beta);
    for pol in 0..2 {
        let c_in = incident
            .iter()
            .position(|&c| c == (i0, pol))
            .ok_or(Error::Numerical("the incident order does not propagate"))?;
        let eta: Vec<f64> = if cover {
            through_cover(
                &chans,
                &pm,
                c_in,
                n_c,
                q_inc,
                beta,
                &alpha,
                true,
                opt.cover_passes,
            )
        } else {
            (0..chans.len()).map(|o| pm[o][c_in]).collect()
        };
        for (o, &m) in prop_up.iter().enumerate() {
            let mi = m as i32 - mm as i32;
            if let Some(ord) = orders.iter_mut().find(|x| x.m == mi) {
                let v = eta[2 * o] + eta[2 * o + 1];
                if pol == 0 {
                    ord.te = v;
                } else {
                    ord.tm = v;
                }
            }
        }
    }
    let mut transmitted = [0.0f64; 2];
    if lossless && !cover {
        for (pol, t) in transmitted.iter_mut().enumerate() {
            *t = prop_dn
                .iter()
                .enumerate()
                .map(|(c, &m)| {
                    let (te, th) = (x[(2 * n + c, pol)], x[(3 * n + c, pol)]);
                    gamma_dn[m] * (eps_m.re * te.norm_sqr() + th.norm_sqr()) / kap_s
                })
                .sum::<f64>()
                / gamma_up[i0];
        }
    }
    if orders
        .iter()
        .any(|o| !(o.te.is_finite() && o.tm.is_finite()))
        || !(transmitted[0].is_finite() && transmitted[1].is_finite())
    {
        return Err(Error::Numerical("a non-finite efficiency"));
    }
    Ok(Raw {
        orders,
        transmitted: (lossless && !cover).then_some((transmitted[0], transmitted[1])),
    })
}
