//! The C method (Chandezon's coordinate transformation) with Li's factorisation, for smooth and
//! piecewise-linear profiles: the classical mount here, the conical one in `cmethod/conical.rs` (which
//! reuses this module's matrix, modes and plane waves with ε − β² in place of ε).
//!
//! The surface z = a(x) becomes the plane u = z − a(x) = 0, so there is a single interface and
//! no staircase. Lengths are in units of 1/k0, time factor e^{−iωt}. In each homogeneous medium
//! (permittivity ε) the field φ = E_y (TE, p = 1) or H_y (TM, p = ε) in the coordinates (x, u) is
//! carried by F = φ and G = (1/p)(−a'∂φ/∂x + (1 + a'²)∂φ/∂u) (the normal derivative times
//! |∇u|/p, continuous with φ across u = 0). In the Fourier basis e^{iαₙx}, αₙ = α + nλ/d,
//! D = i·diag(α), A the Toeplitz matrix of a'(x):
//!
//! [D·F; p·G] = B·[Φx; Φz], B = [[I, A], [−A, I]], F' = Φz, G' = −(1/p)(D·Φx + ε·F),
//!
//! where Φx, Φz are the Cartesian derivatives of φ, continuous along u = const even where the
//! slope jumps: every product with the discontinuous a' is with a continuous factor, so the
//! Laurent rule is exact there (Li's factorisation applied to the C method; L. Li and
//! J. Chandezon, JOSA A 13, 2247 (1996)). With S = (I + A²)⁻¹ (B⁻¹ = [[S, −AS], [AS, S]]):
//!
//! d/du [F; G] = M·[F; G], M = [[A·S·D, p·S], [−(1/p)(D·S·D + ε), D·A·S]].
//!
//! Modes e^{γu}: faer's eigendecomposition of M. Above the surface the propagating orders are
//! the exact plane waves e^{i(αₙx + βₙz)}, whose u-representation is Fₘ = E_{m−n},
//! Gₘ = i·E_{m−n}·(ε − αₙαₘ)/(p·βₙ) with E the Fourier coefficients of e^{iβₙa(x)} (from
//! a'·e^{iβa} = (e^{iβa})'/(iβ)); the evanescent ones are the eigenvectors with Re γ < 0 once
//! the eigenvalues nearest ±iβₙ (the numerical copies of the propagating pairs) are set aside.
//! Below, in a metal, the N eigenvectors with Re γ > 0; in a lossless dielectric, exact plane
//! waves for its propagating orders too (so that Σ R + Σ T = 1 can be checked). Continuity of
//! [F; G] at u = 0 gives the amplitudes; order n carries |rₙ|²·βₙ/β₀.
//!
//! References: J. Chandezon, M. T. Dupuis, G. Cornet, D. Maystre, JOSA 72, 839 (1982);
//! L. Li, J. Chandezon, G. Granet, J.-P. Plumey, Appl. Opt. 38, 304 (1999). The same
//! formulation, in Python, is `python_ref/cmethod.py`.

use faer::linalg::solvers::{DenseSolveCore, Solve};
use faer::{c64, Mat};

use crate::error::Error;
use crate::grating::{Grating, Incidence};
use crate::modal::toeplitz;
use crate::solver::{
    max_change, odd, off_rayleigh, through_cover, work, Channel, Options, Order, Raw, Solution,
    GROWTH, MIN_HARMONICS,
};
use crate::surface::{Phases, Surface};

mod conical;

/// S = (I + A²)⁻¹ and A·S, A the Toeplitz matrix of the slope a'(x) (`nh` harmonics).
fn slope_matrices(surface: &Surface, d: f64, nh: usize) -> (Mat<c64>, Mat<c64>) {
    let a = toeplitz(&surface.slope_coefficients(d, nh - 1), nh);
    let ident = Mat::<c64>::identity(nh, nh);
    let s = (&ident + &a * &a).partial_piv_lu().inverse();
    let as_ = &a * &s;
    (s, as_)
}

/// One medium's matrix M for polarisation weight p and permittivity ε.
fn matrix(s: &Mat<c64>, as_: &Mat<c64>, alpha: &[f64], eps: c64, p: c64) -> Mat<c64> {
    let n = alpha.len();
    let d = |i: usize| c64::new(0.0, alpha[i]);
    let mut m = Mat::<c64>::zeros(2 * n, 2 * n);
    let inv_p = c64::new(1.0, 0.0) / p;
    for j in 0..n {
        for i in 0..n {
            m[(i, j)] = as_[(i, j)] * d(j);
            m[(i, n + j)] = p * s[(i, j)];
            let mut b = d(i) * s[(i, j)] * d(j);
            if i == j {
                b += eps;
            }
            m[(n + i, j)] = -inv_p * b;
            m[(n + i, n + j)] = d(i) * as_[(i, j)];
        }
    }
    m
}

/// The eigenvalues and eigenvectors of M.
fn modes(m: &Mat<c64>) -> Result<(Vec<c64>, Mat<c64>), Error> {
    if !(0..m.ncols())
        .all(|j| (0..m.nrows()).all(|i| m[(i, j)].re.is_finite() && m[(i, j)].im.is_finite()))
    {
        return Err(Error::Numerical("the C method's matrix is not finite"));
    }
    let eig = m
        .eigen()
        .map_err(|_| Error::Numerical("the C method's eigenproblem did not converge"))?;
    let s = eig.S().column_vector();
    let g: Vec<c64> = (0..s.nrows()).map(|i| s[i]).collect();
    Ok((g, eig.U().to_owned()))
}

/// Indices of the `count` modes decaying away from the surface (sign·Re γ > 0) once the
/// numerical copies ±iβₙ of the propagating pairs are set aside: the `count` with the largest
/// sign·Re γ among the rest.
fn decaying(g: &[c64], betas: &[f64], count: usize, sign: f64) -> Result<Vec<usize>, Error> {
    let mut free = vec![true; g.len()];
    for &b in betas {
        for target in [c64::new(0.0, b), c64::new(0.0, -b)] {
            let best = (0..g.len())
                .filter(|&i| free[i])
                .min_by(|&i, &j| (g[i] - target).norm().total_cmp(&(g[j] - target).norm()));
            if let Some(i) = best {
                free[i] = false;
            }
        }
    }
    let mut rest: Vec<usize> = (0..g.len()).filter(|&i| free[i]).collect();
    rest.sort_by(|&i, &j| (sign * g[j].re).total_cmp(&(sign * g[i].re)));
    rest.truncate(count);
    if rest.len() < count
        || rest
            .iter()
            .any(|&i| (sign * g[i].re).is_nan() || sign * g[i].re <= 0.0)
    {
        return Err(Error::Numerical(
            "the C method's evanescent modes could not be separated (too deep a profile?)",
        ));
    }
    Ok(rest)
}

/// [F; G] at u = 0 of the plane wave e^{i(αₙx + b·z)} (b > 0 up, < 0 down) in a medium ε, p.
fn plane_wave(ph: &Phases, k0: f64, alpha: &[f64], n: usize, b: f64, eps: c64, p: c64) -> Vec<c64> {
    let nh = alpha.len();
    let e = ph.coefficients(b * k0);
    let kmax = nh - 1;
    let mut v = vec![c64::new(0.0, 0.0); 2 * nh];
    for m in 0..nh {
        let j = kmax + m - n; // index of E_{m − n}
        v[m] = e[j];
        v[nh + m] =
            c64::new(0.0, 1.0) * e[j] * (eps - c64::new(alpha[n] * alpha[m], 0.0)) / (p * b);
    }
    v
}

/// One solve at `nh` harmonics, TE and TM: the air-side orders (through the cover's passes
/// when there is one) and, for a lossless substrate without a cover, the transmitted totals.
pub(crate) fn solve_raw(
    g: &Grating,
    inc: &Incidence,
    nh: usize,
    opt: &Options,
) -> Result<Raw, Error> {
    if inc.beta != 0.0 || opt.always_conical {
        return conical::solve_raw(g, inc, nh, opt);
    }
    let surface = Surface::of(g).ok_or(Error::invalid(
        "depth_nm",
        g.depth_nm(),
        "a continuous profile for the C method (sinusoid, sawtooth, Fourier, sampled or flat)",
    ))?;
    let lambda = inc.wavelength_nm;
    let d = g.period_nm;
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
    let alpha0 = off_rayleigh(inc.alpha, 0.0, step, &media);
    let mm = (nh / 2) as i64;
    let alpha: Vec<f64> = (-mm..=mm).map(|m| alpha0 + m as f64 * step).collect();
    let k0 = core::f64::consts::TAU / lambda;
    let kmax = nh - 1;

    let (s, as_) = slope_matrices(&surface, d, nh);

    let beta_up: Vec<f64> = alpha
        .iter()
        .map(|&x| (eps_c - x * x).max(0.0).sqrt())
        .collect();
    let prop_up: Vec<usize> = (0..nh).filter(|&i| alpha[i] * alpha[i] < eps_c).collect();
    let eps_dn = eps_m.re;
    let prop_dn: Vec<usize> = if lossless {
        (0..nh).filter(|&i| alpha[i] * alpha[i] < eps_dn).collect()
    } else {
        Vec::new()
    };
    let beta_dn: Vec<f64> = alpha
        .iter()
        .map(|&x| (eps_dn - x * x).max(0.0).sqrt())
        .collect();
    let q_max = k0 * n_c.max(if lossless { nr } else { 0.0 });
    let phases = Phases::new(&surface, d, kmax, q_max);
    let i0 = mm as usize;
    let cover = g.cover.is_some();
    let incident: Vec<usize> = if cover { prop_up.clone() } else { vec![i0] };

    let mut orders: Vec<Order> = alpha
        .iter()
        .enumerate()
        .filter(|(_, a)| a.abs() < 1.0)
        .map(|(i, &a)| Order {
            m: i as i32 - mm as i32,
            alpha: a,
            te: 0.0,
            tm: 0.0,
        })
        .collect();
    let mut transmitted = [0.0f64; 2];
    let mut upper: Option<(c64, Vec<c64>, Mat<c64>)> = None;
    for (pol, t_out) in transmitted.iter_mut().enumerate() {
        let one = c64::new(1.0, 0.0);
        let (p_up, p_dn) = if pol == 0 {
            (one, one)
        } else {
            (c64::new(eps_c, 0.0), eps_m)
        };
        let eps_up = c64::new(eps_c, 0.0);
        // The upper medium's modes (the same for TE and TM in air, p = 1 both).
        if upper.as_ref().is_none_or(|(p, _, _)| *p != p_up) {
            let (gv, v) = modes(&matrix(&s, &as_, &alpha, eps_up, p_up))?;
            upper = Some((p_up, gv, v));
        }
        let (_, g1, v1) = upper.as_ref().expect("set above");
        let b_up: Vec<f64> = prop_up.iter().map(|&i| beta_up[i]).collect();
        let evan = decaying(g1, &b_up, nh - prop_up.len(), -1.0)?;
        let (g2, v2) = modes(&matrix(&s, &as_, &alpha, eps_m, p_dn))?;
        let down: Vec<usize> = if lossless {
            let b_dn: Vec<f64> = prop_dn.iter().map(|&i| beta_dn[i]).collect();
            decaying(&g2, &b_dn, nh - prop_dn.len(), 1.0)?
        } else {
            decaying(&g2, &[], nh, 1.0)?
        };
        // The system [U, −W]·[r; t] = −incident.
        let size = 2 * nh;
        let mut sys = Mat::<c64>::zeros(size, size);
        for (c, &n) in prop_up.iter().enumerate() {
            let w = plane_wave(&phases, k0, &alpha, n, beta_up[n], eps_up, p_up);
            for (r, val) in w.into_iter().enumerate() {
                sys[(r, c)] = val;
            }
        }
        for (c, &j) in evan.iter().enumerate() {
            for r in 0..size {
                sys[(r, prop_up.len() + c)] = v1[(r, j)];
            }
        }
        let eps_dn_c = c64::new(eps_dn, 0.0);
        for (c, &n) in prop_dn.iter().enumerate() {
            let w = plane_wave(&phases, k0, &alpha, n, -beta_dn[n], eps_dn_c, p_dn);
            for (r, val) in w.into_iter().enumerate() {
                sys[(r, nh + c)] = -val;
            }
        }
        for (c, &j) in down.iter().enumerate() {
            for r in 0..size {
                sys[(r, nh + prop_dn.len() + c)] = -v2[(r, j)];
            }
        }
        let mut rhs = Mat::<c64>::zeros(size, incident.len());
        for (c, &n) in incident.iter().enumerate() {
            let w = plane_wave(&phases, k0, &alpha, n, -beta_up[n], eps_up, p_up);
            for (r, val) in w.into_iter().enumerate() {
                rhs[(r, c)] = -val;
            }
        }
        let x = sys.partial_piv_lu().solve(&rhs);
        // Power matrix between the upper medium's propagating channels.
        let np = prop_up.len();
        let chans: Vec<Channel> = prop_up.iter().map(|&i| Channel::scalar(i, pol)).collect();
        let mut pm = vec![vec![0.0; incident.len()]; np];
        for (o, &n) in prop_up.iter().enumerate() {
            for (c, &ni) in incident.iter().enumerate() {
                pm[o][c] = x[(o, c)].norm_sqr() * beta_up[n] / beta_up[ni];
            }
        }
        let c_in = prop_up
            .iter()
            .position(|&i| i == i0)
            .ok_or(Error::Numerical("the incident order does not propagate"))?;
        let eta = if cover {
            through_cover(
                &chans,
                &pm,
                c_in,
                n_c,
                alpha0.abs(),
                0.0,
                &alpha,
                true,
                opt.cover_passes,
            )
        } else {
            (0..np).map(|o| pm[o][0]).collect()
        };
        for (o, &n) in prop_up.iter().enumerate() {
            if alpha[n].abs() < 1.0 {
                let m = n as i32 - mm as i32;
                if let Some(ord) = orders.iter_mut().find(|x| x.m == m) {
                    if pol == 0 {
                        ord.te = eta[o];
                    } else {
                        ord.tm = eta[o];
                    }
                }
            }
        }
        if lossless && !cover {
            let ratio = if pol == 0 { 1.0 } else { eps_c / eps_dn };
            *t_out = prop_dn
                .iter()
                .enumerate()
                .map(|(c, &n)| x[(nh + c, 0)].norm_sqr() * beta_dn[n] / beta_up[i0])
                .sum::<f64>()
                * ratio;
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

/// The first harmonic count of the C method's convergence loop: the propagating orders with
/// margin, max(21, 4·n·d/λ + 11) (as python_ref's).
pub(crate) fn first_harmonics(g: &Grating, inc: &Incidence) -> usize {
    let n_c = g.cover_n(inc.wavelength_nm);
    odd((MIN_HARMONICS as f64).max(4.0 * n_c * g.period_nm / inc.wavelength_nm + 11.0))
}

/// The convergence loop: ×[`GROWTH`] from [`first_harmonics`] until two successive counts agree
/// to the tolerance (every order, TE and TM); [`Error::NotConverged`] at the cap, or before a
/// step that would take the call's [`work`] past `Options::max_work`. No
/// extrapolation: the C method converges much faster than 1/N on these profiles.
pub(crate) fn solve(g: &Grating, inc: &Incidence, opt: &Options) -> Result<Solution, Error> {
    let cap = opt.max_harmonics;
    let tol = opt.tolerance;
    let conical = inc.beta != 0.0 || opt.always_conical;
    let mut n = first_harmonics(g, inc);
    let mut done = work(n, 0, conical, true);
    if done > opt.max_work {
        return Err(Error::invalid(
            "harmonics",
            n as f64,
            "a first step within the options' max_work (fmm::work)",
        ));
    }
    let mut prev = solve_raw(g, inc, n, opt)?;
    let mut change = f64::NAN;
    loop {
        let next = odd(n as f64 * GROWTH);
        let step = work(next, 0, conical, true);
        if next > cap || done + step > opt.max_work {
            return Err(Error::NotConverged {
                harmonics: n,
                change,
                tolerance: tol,
            });
        }
        let cur = solve_raw(g, inc, next, opt)?;
        done += step;
        change = max_change(&prev.orders, &cur.orders);
        if change < tol {
            return Ok(Solution {
                orders: cur.orders,
                harmonics: next,
                slabs: 0,
                error: change,
                extrapolated: false,
                transmitted: cur.transmitted,
            });
        }
        prev = cur;
        n = next;
    }
}
