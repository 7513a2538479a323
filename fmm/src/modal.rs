//! The Fourier modal method proper: Toeplitz matrices of ε and 1/ε, each layer's eigenmodes,
//! and the stable reflection-matrix recursion from the substrate up.
//!
//! Units: lengths times k0 = 2π/λ; H̃ = Z0·H, time dependence e^{-iωt}, so that
//! ∇×E = iH̃ and ∇×H̃ = -iεE. Fields of harmonic m go as e^{i(αₘx + βy)k0}, αₘ = α + mλ/d.
//! Tangential fields obey dE_t/dz = iP·H_t and dH_t/dz = iQ·E_t; for E_t = (Ex, Ey),
//! H_t = (Hx, Hy) (conical), with E = [[ε]] (Laurent, for the components along the walls) and
//! A = [[1/ε]]⁻¹ (Li's inverse rule, for Ex across them), Kx = diag(αₘ):
//!
//! P = [[β Kx E⁻¹, I − Kx E⁻¹ Kx], [β² E⁻¹ − I, −β E⁻¹ Kx]],
//! Q = [[−β Kx, Kx² − E], [A − β², β Kx]].
//!
//! The classical mount (β = 0) splits into TE (E_t = Ey, H_t = Hx: P = −I, Q = Kx² − E) and TM
//! (E_t = Ex, H_t = Hy: P = I − Kx E⁻¹ Kx, Q = A). A layer's modes: PQ·W = W·Λ², λ with Im ≥ 0,
//! V = Q·W·Λ⁻¹; E_t = W(e^{iλz}u + e^{-iλz}d), H_t = V(e^{iλz}u − e^{-iλz}d).

use faer::linalg::solvers::{DenseSolveCore, PartialPivLu, Solve};
use faer::{c64, Mat};

use crate::error::Error;

/// Which field components a solve carries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pol {
    /// Classical mount, E along the grooves: E_t = Ey.
    Te,
    /// Classical mount, H along the grooves: E_t = Ex.
    Tm,
    /// Conical mount: E_t = (Ex, Ey).
    Conical,
}

/// The harmonic lattice of one solve.
pub(crate) struct Lattice {
    /// αₘ for m = −M..M (index m + M).
    pub kx: Vec<f64>,
    pub beta: f64,
    pub pol: Pol,
}

impl Lattice {
    pub fn harmonics(&self) -> usize {
        self.kx.len()
    }
    /// Size of the field vectors: N (classical) or 2N (conical).
    pub fn size(&self) -> usize {
        match self.pol {
            Pol::Conical => 2 * self.kx.len(),
            _ => self.kx.len(),
        }
    }
}

/// One layer's modes: W (None = identity), V, and λ.
pub(crate) struct Modes {
    pub w: Option<Mat<c64>>,
    pub v: Mat<c64>,
    pub lam: Vec<c64>,
}

/// kz = √(ε − αₘ² − β²) on the physical branch (Im ≥ 0, and Re ≥ 0 when real).
pub(crate) fn kz(eps: c64, a: f64, b: f64) -> c64 {
    let z = eps - c64::new(a * a + b * b, 0.0);
    let mut r = z.sqrt();
    if r.im < 0.0 || (r.im == 0.0 && r.re < 0.0) {
        r = -r;
    }
    r
}

/// The modes of a homogeneous layer of permittivity `eps` (W = I, λ = kz).
pub(crate) fn homogeneous(lat: &Lattice, eps: c64) -> Modes {
    let n = lat.harmonics();
    let b = lat.beta;
    let kzs: Vec<c64> = lat.kx.iter().map(|&a| kz(eps, a, b)).collect();
    let size = lat.size();
    let mut v = Mat::<c64>::zeros(size, size);
    let mut lam = Vec::with_capacity(size);
    match lat.pol {
        Pol::Te => {
            for i in 0..n {
                v[(i, i)] = -kzs[i];
            }
            lam.extend_from_slice(&kzs);
        }
        Pol::Tm => {
            for i in 0..n {
                v[(i, i)] = eps / kzs[i];
            }
            lam.extend_from_slice(&kzs);
        }
        Pol::Conical => {
            for i in 0..n {
                let a = lat.kx[i];
                let k = kzs[i];
                v[(i, i)] = c64::new(-b * a, 0.0) / k;
                v[(i, n + i)] = (c64::new(a * a, 0.0) - eps) / k;
                v[(n + i, i)] = (eps - c64::new(b * b, 0.0)) / k;
                v[(n + i, n + i)] = c64::new(b * a, 0.0) / k;
            }
            lam.extend_from_slice(&kzs);
            lam.extend_from_slice(&kzs);
        }
    }
    Modes { w: None, v, lam }
}

/// Fourier coefficients cₖ, k = −K..K (index k + K), of f(t) = `outside` + (`inside` −
/// `outside`)·[t in one of `ridges`], t = x/d in [0, 1).
pub(crate) fn coefficients(
    ridges: &[(f64, f64)],
    outside: c64,
    inside: c64,
    kmax: usize,
) -> Vec<c64> {
    let mut c = vec![c64::new(0.0, 0.0); 2 * kmax + 1];
    let jump = inside - outside;
    for &(a, b) in ridges {
        c[kmax] += jump * (b - a);
        for k in 1..=kmax {
            let w = core::f64::consts::TAU * k as f64;
            // (1/d)∫ e^{∓i w t} dt over [a, b], for +k and −k.
            let (sa, ca) = (w * a).sin_cos();
            let (sb, cb) = (w * b).sin_cos();
            // ∫ e^{-iwt} = (e^{-iwb} − e^{-iwa})/(−iw) = ((sb − sa) + i(cb − ca))/w
            let plus = c64::new((sb - sa) / w, (cb - ca) / w);
            c[kmax + k] += jump * plus;
            c[kmax - k] += jump * plus.conj();
        }
    }
    c[kmax] += outside;
    c
}

/// The Toeplitz matrix T[i][j] = c_{i−j} of size n from coefficients for k = −(n−1)..(n−1).
pub(crate) fn toeplitz(c: &[c64], n: usize) -> Mat<c64> {
    Mat::from_fn(n, n, |i, j| c[i + n - 1 - j])
}

fn finite(m: &Mat<c64>) -> bool {
    (0..m.ncols())
        .all(|j| (0..m.nrows()).all(|i| m[(i, j)].re.is_finite() && m[(i, j)].im.is_finite()))
}

/// The modes of a slab whose permittivity is `eps_out` except `eps_in` on `ridges`.
pub(crate) fn slab(
    lat: &Lattice,
    ridges: &[(f64, f64)],
    eps_out: c64,
    eps_in: c64,
) -> Result<Modes, Error> {
    let n = lat.harmonics();
    let one = c64::new(1.0, 0.0);
    let ce = coefficients(ridges, eps_out, eps_in, n - 1);
    let e = toeplitz(&ce, n);
    let kx = &lat.kx;
    let b = lat.beta;
    // P and Q of the layer.
    let (p, q) = match lat.pol {
        Pol::Te => {
            let p = Mat::from_fn(n, n, |i, j| if i == j { -one } else { c64::new(0.0, 0.0) });
            let q = Mat::from_fn(n, n, |i, j| {
                let d = if i == j {
                    c64::new(kx[i] * kx[i], 0.0)
                } else {
                    c64::new(0.0, 0.0)
                };
                d - e[(i, j)]
            });
            (p, q)
        }
        Pol::Tm | Pol::Conical => {
            let ci = coefficients(ridges, one / eps_out, one / eps_in, n - 1);
            let a = toeplitz(&ci, n).partial_piv_lu().inverse();
            let einv = e.partial_piv_lu().inverse();
            if lat.pol == Pol::Conical {
                if let Some(modes) = conical_slab(kx, b, &e, &einv, &a)? {
                    return Ok(modes);
                }
            }
            if lat.pol == Pol::Tm {
                let p = Mat::from_fn(n, n, |i, j| {
                    let d = if i == j { one } else { c64::new(0.0, 0.0) };
                    d - einv[(i, j)] * (kx[i] * kx[j])
                });
                (p, a)
            } else {
                conical_pq(kx, b, &e, &einv, &a)
            }
        }
    };
    let pq = &p * &q;
    if !finite(&pq) {
        return Err(Error::Numerical("a slab's Toeplitz matrix is singular"));
    }
    let eig = pq
        .eigen()
        .map_err(|_| Error::Numerical("a slab's eigenproblem did not converge"))?;
    let w = eig.U().to_owned();
    let s = eig.S().column_vector();
    let eigs: Vec<c64> = (0..s.nrows()).map(|i| s[i]).collect();
    Ok(modes_from(w, &eigs, &q))
}

/// Modes from PQ's eigenvectors `w` and eigenvalues: λ = √eig with Im λ ≥ 0, V = Q·W·Λ⁻¹.
fn modes_from(w: Mat<c64>, eigs: &[c64], q: &Mat<c64>) -> Modes {
    let one = c64::new(1.0, 0.0);
    let lam: Vec<c64> = eigs
        .iter()
        .map(|e| {
            let mut l = e.sqrt();
            if l.im < 0.0 {
                l = -l;
            }
            // A mode at λ = 0 exactly (a grazing mode of the slab) would divide by zero.
            if l.norm() < 1e-12 {
                l = c64::new(1e-12, 1e-12);
            }
            l
        })
        .collect();
    let mut v = q * &w;
    for (j, l) in lam.iter().enumerate() {
        let inv = one / l;
        for i in 0..v.nrows() {
            v[(i, j)] *= inv;
        }
    }
    Modes { w: Some(w), v, lam }
}

/// The conical mount's P and Q (the module's docs) from E, E⁻¹ and A.
fn conical_pq(
    kx: &[f64],
    b: f64,
    e: &Mat<c64>,
    einv: &Mat<c64>,
    a: &Mat<c64>,
) -> (Mat<c64>, Mat<c64>) {
    let n = kx.len();
    let s = 2 * n;
    let mut p = Mat::<c64>::zeros(s, s);
    let mut q = Mat::<c64>::zeros(s, s);
    for i in 0..n {
        for j in 0..n {
            let ei = einv[(i, j)];
            let delta = if i == j { 1.0 } else { 0.0 };
            p[(i, j)] = ei * (b * kx[i]);
            p[(i, n + j)] = c64::new(delta, 0.0) - ei * (kx[i] * kx[j]);
            p[(n + i, j)] = ei * (b * b) - c64::new(delta, 0.0);
            p[(n + i, n + j)] = -ei * (b * kx[j]);
            q[(i, n + j)] = c64::new(delta * kx[i] * kx[i], 0.0) - e[(i, j)];
            q[(n + i, j)] = a[(i, j)] - c64::new(delta * b * b, 0.0);
        }
        q[(i, i)] = c64::new(-b * kx[i], 0.0);
        q[(n + i, n + i)] = c64::new(b * kx[i], 0.0);
    }
    (p, q)
}

/// The conical slab's modes from two N × N eigenproblems instead of one 2N × 2N.
///
/// For a 1-D grating PQ is block lower triangular: with G = E⁻¹·Kx·A,
/// PQ = [[X, 0], [Y, Z]], X = A − Kx·G − β², Y = β(Kx − G), Z = E − Kx² − β²
/// (X is the TM matrix and Z the TE one, each shifted by β²). Z's eigenvectors w give the modes
/// (0, w); an eigenvector u of X with eigenvalue μ gives (u, (μ − Z)⁻¹Y·u), computed for all of
/// them at once in Z's eigenbasis: with Z = W_z Λ_z W_z⁻¹ and C = W_z⁻¹·Y·W_x, the lower block is
/// W_z·[C_ij / (μ_j − λ_i)]. Returns None when an eigenvalue of X is within rounding of one of Z
/// and Y couples them (the split is then ill-conditioned and the caller solves the 2N problem).
fn conical_slab(
    kx: &[f64],
    b: f64,
    e: &Mat<c64>,
    einv: &Mat<c64>,
    a: &Mat<c64>,
) -> Result<Option<Modes>, Error> {
    let n = kx.len();
    let ka = Mat::from_fn(n, n, |i, j| a[(i, j)] * kx[i]);
    let g = einv * &ka;
    let b2 = c64::new(b * b, 0.0);
    let x = Mat::from_fn(n, n, |i, j| {
        let d = if i == j { b2 } else { c64::new(0.0, 0.0) };
        a[(i, j)] - g[(i, j)] * kx[i] - d
    });
    let y = Mat::from_fn(n, n, |i, j| {
        let d = if i == j {
            c64::new(kx[i], 0.0)
        } else {
            c64::new(0.0, 0.0)
        };
        (d - g[(i, j)]) * b
    });
    let z = Mat::from_fn(n, n, |i, j| {
        let d = if i == j {
            c64::new(kx[i] * kx[i], 0.0) + b2
        } else {
            c64::new(0.0, 0.0)
        };
        e[(i, j)] - d
    });
    if !finite(&x) || !finite(&z) {
        return Err(Error::Numerical("a slab's Toeplitz matrix is singular"));
    }
    let ex = x
        .eigen()
        .map_err(|_| Error::Numerical("a slab's eigenproblem did not converge"))?;
    let ez = z
        .eigen()
        .map_err(|_| Error::Numerical("a slab's eigenproblem did not converge"))?;
    let (wx, sx) = (ex.U().to_owned(), ex.S().column_vector().to_owned());
    let (wz, sz) = (ez.U().to_owned(), ez.S().column_vector().to_owned());
    let c = wz.partial_piv_lu().solve(&(&y * &wx));
    let scale = (0..n)
        .map(|i| sx[i].norm().max(sz[i].norm()))
        .fold(1.0f64, f64::max);
    let c_scale = (0..n)
        .flat_map(|j| (0..n).map(move |i| (i, j)))
        .map(|ij| c[ij].norm())
        .fold(0.0f64, f64::max);
    let mut lower = Mat::<c64>::zeros(n, n);
    for j in 0..n {
        for i in 0..n {
            let den = sx[j] - sz[i];
            if den.norm() > 1e-10 * scale {
                lower[(i, j)] = c[(i, j)] / den;
            } else if c[(i, j)].norm() > 1e-12 * c_scale.max(1e-300) {
                // A degenerate pair that Y couples: PQ may be defective there.
                return Ok(None);
            }
            // else: the pair is uncoupled (a homogeneous slab: Y = 0), any basis of it will do.
        }
    }
    let lower = &wz * &lower;
    let s = 2 * n;
    let mut w = Mat::<c64>::zeros(s, s);
    for j in 0..n {
        for i in 0..n {
            w[(i, j)] = wx[(i, j)];
            w[(n + i, j)] = lower[(i, j)];
            w[(n + i, n + j)] = wz[(i, j)];
        }
    }
    if !finite(&w) {
        return Ok(None);
    }
    let eigs: Vec<c64> = (0..n).map(|i| sx[i]).chain((0..n).map(|i| sz[i])).collect();
    let (_, q) = conical_pq(kx, b, e, einv, a);
    Ok(Some(modes_from(w, &eigs, &q)))
}

/// A stack top to bottom: the superstrate's modes, the slabs' (with thicknesses times k0), the
/// substrate's.
pub(crate) struct Stack {
    pub layers: Vec<Modes>,
    /// k0·h of each layer (the half-spaces' entries are unused).
    pub thickness: Vec<f64>,
}

/// The reflection matrix in the superstrate (u = R·d at the top interface) and, on request, the
/// downward chain's matrices for the transmitted field.
pub(crate) struct Reflection {
    pub r: Mat<c64>,
    /// For interface j (between layer j and j + 1): the LU of D_j (d_j = ½D_j·d_{j+1}).
    pub chain: Vec<PartialPivLu<c64>>,
}

fn apply_w(w: &Option<Mat<c64>>, m: &Mat<c64>) -> Mat<c64> {
    match w {
        None => m.clone(),
        Some(w) => w * m,
    }
}

/// The stable recursion: R at the substrate's top is 0 (nothing comes up from below); crossing
/// the interface into the layer above, R_a = U·D⁻¹ with D = W_a⁻¹F − V_a⁻¹G, U = W_a⁻¹F + V_a⁻¹G,
/// F = W_b(I + R_b), G = V_b(R_b − I); through a slab, R → X·R·X with X = diag(e^{iλh}), |X| ≤ 1:
/// no growing exponential appears.
pub(crate) fn reflect(stack: &Stack, keep_chain: bool) -> Result<Reflection, Error> {
    let nl = stack.layers.len();
    let size = stack.layers[0].v.nrows();
    let mut r = Mat::<c64>::zeros(size, size);
    let mut chain = Vec::new();
    let ident = Mat::<c64>::identity(size, size);
    for j in (0..nl - 1).rev() {
        let (a, b) = (&stack.layers[j], &stack.layers[j + 1]);
        let f = apply_w(&b.w, &(&ident + &r));
        let g = &b.v * &(&r - &ident);
        let a1 = match &a.w {
            None => f,
            Some(w) => w.partial_piv_lu().solve(&f),
        };
        let a2 = a.v.partial_piv_lu().solve(&g);
        let d = &a1 - &a2;
        let u = &a1 + &a2;
        let lu = d.partial_piv_lu();
        r = lu.rsolve(&u);
        if keep_chain {
            chain.push(lu);
        }
        if j > 0 {
            let x: Vec<c64> = a
                .lam
                .iter()
                .map(|l| (c64::new(0.0, 1.0) * l * stack.thickness[j]).exp())
                .collect();
            for jj in 0..size {
                for ii in 0..size {
                    r[(ii, jj)] *= x[ii] * x[jj];
                }
            }
        }
    }
    if !finite(&r) {
        return Err(Error::Numerical("the reflection matrix is not finite"));
    }
    chain.reverse();
    Ok(Reflection { r, chain })
}

/// The downward amplitudes in the substrate for downward amplitudes `d` in the superstrate.
pub(crate) fn transmit(stack: &Stack, refl: &Reflection, d: &Mat<c64>) -> Mat<c64> {
    let mut d = d.clone();
    let nl = stack.layers.len();
    for j in 0..nl - 1 {
        let mut db = refl.chain[j].solve(&d);
        for i in 0..db.nrows() {
            for k in 0..db.ncols() {
                db[(i, k)] *= 2.0;
            }
        }
        if j + 1 < nl - 1 {
            let l = &stack.layers[j + 1];
            for i in 0..db.nrows() {
                let x = (c64::new(0.0, 1.0) * l.lam[i] * stack.thickness[j + 1]).exp();
                for k in 0..db.ncols() {
                    db[(i, k)] *= x;
                }
            }
        }
        d = db;
    }
    d
}

/// The z-flux (upward positive) of the homogeneous-layer field E_t = `e`, H_t = `h` in order i.
pub(crate) fn flux(lat: &Lattice, e: &[c64], h: &[c64], i: usize) -> f64 {
    let n = lat.harmonics();
    match lat.pol {
        Pol::Te => -(e[i] * h[i].conj()).re,
        Pol::Tm => (e[i] * h[i].conj()).re,
        Pol::Conical => (e[i] * h[n + i].conj() - e[n + i] * h[i].conj()).re,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// max |PQ·W − W·Λ²| / max |PQ| of a conical slab's modes.
    fn residual(ridges: &[(f64, f64)], eps_in: c64) -> f64 {
        let n = 21;
        let lat = Lattice {
            kx: (0..n).map(|m| 0.3 + (m as f64 - 10.0) * 0.55).collect(),
            beta: 0.4,
            pol: Pol::Conical,
        };
        let one = c64::new(1.0, 0.0);
        let eps_out = one;
        let modes = slab(&lat, ridges, eps_out, eps_in).unwrap();
        let e = toeplitz(&coefficients(ridges, eps_out, eps_in, n - 1), n);
        let ci = coefficients(ridges, one / eps_out, one / eps_in, n - 1);
        let a = toeplitz(&ci, n).partial_piv_lu().inverse();
        let einv = e.partial_piv_lu().inverse();
        let (p, q) = conical_pq(&lat.kx, lat.beta, &e, &einv, &a);
        let pq = &p * &q;
        let w = modes.w.unwrap();
        let lhs = &pq * &w;
        let scale = (0..2 * n)
            .flat_map(|j| (0..2 * n).map(move |i| (i, j)))
            .map(|ij| pq[ij].norm())
            .fold(0.0f64, f64::max);
        let mut worst = 0.0f64;
        for j in 0..2 * n {
            let l2 = modes.lam[j] * modes.lam[j];
            for i in 0..2 * n {
                worst = worst.max((lhs[(i, j)] - w[(i, j)] * l2).norm());
            }
        }
        worst / scale
    }

    /// The split into two N × N eigenproblems gives eigenpairs of the full 2N × 2N PQ: on a
    /// metal lamellar slab, and on a slab filled with one medium (X = Z there, every eigenvalue
    /// doubly degenerate and Y = 0: the uncoupled pairs need no fallback). Measured residuals
    /// 1.9-2.5e-15 relative; asserted at 1e-11.
    #[test]
    fn the_split_conical_modes_are_eigenpairs_of_pq() {
        let metal = c64::new(-30.0, 2.0);
        let r = residual(&[(0.2, 0.7)], metal);
        assert!(r < 1e-11, "metal slab: residual {r:e}");
        let r = residual(&[(0.0, 1.0)], metal);
        assert!(r < 1e-11, "filled slab: residual {r:e}");
        let r = residual(&[(0.1, 0.35), (0.5, 0.9)], c64::new(2.25, 0.0));
        assert!(r < 1e-11, "dielectric slab: residual {r:e}");
    }
}
