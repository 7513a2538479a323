//! The crate's rigorous solver as a table builder's [`OrderSolver`].

use super::{OrderSolver, Orders};
use crate::{Grating, Incidence, Profile, Solver};

/// The crate's rigorous solver as an [`OrderSolver`]: [`Solver::solve`] (converged to its
/// options' tolerance) of `grating` in the classical mount.
#[derive(Debug, Clone, PartialEq)]
pub struct Rigorous {
    /// The grating.
    pub grating: Grating,
    /// The solver and its options.
    pub solver: Solver,
    /// A solve that reaches the harmonic cap is taken at the cap's count (never failing the
    /// build); one whose last change exceeds this (absolute) is also marked unconverged and
    /// counted in the build's report (`BuildReport::unconverged`). The table's tolerance is
    /// usually ten times the solver's: `grating-table` uses a quarter of the table's.
    pub accept_unconverged: f64,
}

impl OrderSolver for Rigorous {
    fn period_nm(&self) -> f64 {
        self.grating.period_nm
    }

    /// Flat, lamellar (a ridge is symmetric about its centre) and sinusoidal profiles.
    fn mirror_symmetric(&self) -> bool {
        matches!(
            self.grating.profile,
            Profile::Flat | Profile::Lamellar { .. } | Profile::Sinusoid { .. }
        )
    }

    /// The metal's tabulated wavelengths ([`diffraction::relief::Metal::wavelength_range_nm`]),
    /// above a Sellmeier cover's pole by 10 % (`None` for a custom metal without such a cover).
    fn wavelength_range_nm(&self) -> Option<(f64, f64)> {
        let metal = self.grating.metal.wavelength_range_nm();
        let pole = match self.grating.cover.map(|c| c.index) {
            Some(crate::CoverIndex::Sellmeier { c_um2, .. }) => Some(1.1e3 * c_um2.sqrt()),
            _ => None,
        };
        match (metal, pole) {
            (Some((lo, hi)), Some(p)) => Some((lo.max(p), hi)),
            (Some(r), None) => Some(r),
            (None, Some(p)) => Some((p, f64::INFINITY)),
            (None, None) => None,
        }
    }

    /// A point on a Rayleigh line (an order grazing in air or in the cover, up to 10⁻¹²) is
    /// solved 10⁻⁹ off it, as `python_ref` does: the appearing order's efficiency grows like the
    /// square root of the distance, so this changes it by about 3·10⁻⁵ of its scale.
    fn solve(&self, sin_theta_i: f64, lambda_nm: f64) -> Result<Orders, String> {
        self.solve_marked(sin_theta_i, 0.0, lambda_nm).map(|r| r.0)
    }

    /// The full vector (conical) solve at β ≠ 0; TE and TM are the incident s and p
    /// polarisations.
    fn solve_conical(&self, alpha: f64, beta: f64, lambda_nm: f64) -> Result<Orders, String> {
        self.solve_marked(alpha, beta, lambda_nm).map(|r| r.0)
    }

    /// A solve that reaches the harmonic cap is never a failure of the build: it is taken at
    /// the cap's count, and marked with its last change when that exceeds
    /// [`accept_unconverged`](Self::accept_unconverged).
    fn solve_marked(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
    ) -> Result<(Orders, Option<f64>), String> {
        let s = off_rayleigh(&self.grating, alpha, beta, lambda_nm);
        let inc = Incidence::from_cosines(s, beta, lambda_nm).map_err(|e| e.to_string())?;
        let mut mark = None;
        let sol = match self.solver.solve(&self.grating, inc) {
            Err(crate::Error::NotConverged {
                harmonics, change, ..
            }) => {
                if change.is_nan() || change > self.accept_unconverged {
                    mark = Some(if change.is_finite() { change } else { 1.0 });
                }
                self.solver.solve_at(&self.grating, inc, harmonics)
            }
            r => r,
        }
        .map_err(|e| e.to_string())?;
        let first = sol.orders.first().map_or(0, |o| o.m);
        let last = sol.orders.last().map_or(-1, |o| o.m);
        let n = (last - first + 1).max(0) as usize;
        let mut out = Orders {
            order_min: first,
            te: vec![0.0; n],
            tm: vec![0.0; n],
        };
        for o in &sol.orders {
            let k = (o.m - first) as usize;
            out.te[k] = o.te;
            out.tm[k] = o.tm;
        }
        Ok((out, mark))
    }
}

/// The distance by which a solve is moved off a Rayleigh line.
const RAYLEIGH_NUDGE: f64 = 1e-9;

fn off_rayleigh(g: &Grating, s: f64, beta: f64, lambda_nm: f64) -> f64 {
    let media = [1.0, g.cover_n(lambda_nm)];
    let ratio = lambda_nm / g.period_nm;
    let on_line = |s: f64| {
        let m_max = ((media[1] + 1.0) / ratio).ceil().min(1e5) as i64;
        (-m_max..=m_max).any(|m| {
            let a = s + m as f64 * ratio;
            let q = (a * a + beta * beta).sqrt();
            media.iter().any(|n| (q - n).abs() < 1e-12)
        })
    };
    let mut s = s;
    for _ in 0..3 {
        if !on_line(s) {
            break;
        }
        s = if s + RAYLEIGH_NUDGE < 1.0 {
            s + RAYLEIGH_NUDGE
        } else {
            s - RAYLEIGH_NUDGE
        };
    }
    s
}

/// The conical-to-classical mapping as an [`OrderSolver`]: a conical node (α, β, λ) is solved as
/// the classical problem at λ' = λ/√(1 − β²), s' = α/√(1 − β²), with every medium's
/// permittivity ε' = (ε − β²)/(1 − β²) (the metal's n + ik at λ, and the cover's). Exact for
/// perfect conductors; for metals an approximation whose error is measured against the full
/// conical solve in `fmm/tests/conical_reading.rs` (`docs/efficiency_tables.md`, "Conical
/// tables"). Its TE and TM are the E-along-the-grooves and H-along-the-grooves waves, not s and
/// p; their mean is the unpolarised efficiency. Cheaper than the vector solve (two scalar
/// problems of half the size).
#[derive(Debug, Clone, PartialEq)]
pub struct Mapped(pub Rigorous);

/// √z with a non-negative imaginary part, as (re, im).
fn sqrt_upper(re: f64, im: f64) -> (f64, f64) {
    let r = re.hypot(im);
    (
        ((r + re) / 2.0).max(0.0).sqrt(),
        ((r - re) / 2.0).max(0.0).sqrt(),
    )
}

impl Mapped {
    /// The mapped classical grating at λ for β.
    pub fn mapped_grating(&self, beta: f64, lambda_nm: f64) -> Result<Grating, String> {
        let g = &self.0.grating;
        let c = 1.0 - beta * beta;
        let (n, k) = g.metal.index(lambda_nm);
        let (er, ei) = ((n * n - k * k - beta * beta) / c, 2.0 * n * k / c);
        let (np, kp) = sqrt_upper(er, ei);
        let metal = diffraction::relief::Metal::custom(np, kp).map_err(|e| e.to_string())?;
        let cover = match g.cover {
            None => None,
            Some(cv) => {
                let n = cv.index.at(lambda_nm).ok_or_else(|| {
                    format!("cover.index: undefined at lambda_nm = {lambda_nm} (a Sellmeier pole)")
                })?;
                Some(crate::Cover {
                    index: crate::CoverIndex::Constant(((n * n - beta * beta) / c).sqrt()),
                    ..cv
                })
            }
        };
        Ok(Grating {
            metal,
            cover,
            ..g.clone()
        })
    }
}

impl OrderSolver for Mapped {
    fn period_nm(&self) -> f64 {
        self.0.period_nm()
    }

    fn mirror_symmetric(&self) -> bool {
        self.0.mirror_symmetric()
    }

    fn wavelength_range_nm(&self) -> Option<(f64, f64)> {
        self.0.wavelength_range_nm()
    }

    fn solve(&self, sin_theta_i: f64, lambda_nm: f64) -> Result<Orders, String> {
        self.0.solve(sin_theta_i, lambda_nm)
    }

    fn solve_conical(&self, alpha: f64, beta: f64, lambda_nm: f64) -> Result<Orders, String> {
        self.solve_marked(alpha, beta, lambda_nm).map(|r| r.0)
    }

    fn solve_marked(
        &self,
        alpha: f64,
        beta: f64,
        lambda_nm: f64,
    ) -> Result<(Orders, Option<f64>), String> {
        if beta == 0.0 {
            return self.0.solve_marked(alpha, 0.0, lambda_nm);
        }
        let cb = (1.0 - beta * beta).sqrt();
        let inner = Rigorous {
            grating: self.mapped_grating(beta, lambda_nm)?,
            ..self.0.clone()
        };
        inner.solve_marked(alpha / cb, 0.0, lambda_nm / cb)
    }
}
