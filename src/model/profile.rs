//! The shape of one period of a surface profile and its Fourier coefficients (Stam's model,
//! feature `stam`).

use core::f64::consts::PI;

use crate::num::bessel::{bessel_j, bessel_j_bounded};
use crate::num::complex::Complex;
use crate::num::kernel::sincospi;
use crate::num::math;

/// The shape of one period of the surface height h(x), x across the grooves.
///
/// The Fourier coefficients c_m of p(x) = exp(i·φ·h(x)/h₀) depend on the shape and the phase
/// φ = k·w·h₀ only; [`Profile::efficiency`] is |c_m(φ)|², the share of order m, and
/// Σ_m |c_m|² = 1 (Parseval).
///
/// ```
/// use diffraction::Profile;
/// let sine = Profile::Sine;
/// let binary = Profile::Binary { fraction: 0.5 };
/// // A quarter-wave binary grating at normal incidence (φ = π): no order 0, no even order.
/// assert!(binary.efficiency(0, std::f64::consts::PI) < 1e-30);
/// assert!(binary.efficiency(2, std::f64::consts::PI) < 1e-30);
/// assert!((binary.efficiency(1, std::f64::consts::PI) - 4.0 / std::f64::consts::PI.powi(2)).abs() < 1e-15);
/// let total: f64 = (-60..=60).map(|m| sine.efficiency(m, 7.5)).sum();
/// assert!((total - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Profile {
    /// h(x) = h₀·sin(2πx/d): c_m = J_m(φ) (Jacobi-Anger), so |c_m|² = J_m(φ)².
    /// h₀ is the amplitude, half the peak-to-valley depth.
    Sine,
    /// Grooves of depth h₀ over the fraction `fraction` = a of each period (a rectangular,
    /// binary profile): h = h₀ on [0, a·d), 0 on the rest. Then
    /// c_0 = 1 − a + a·e^{iφ} and c_m = (e^{iφ} − 1)·a·sinc(m·a)·e^{−iπma} for m ≠ 0
    /// (sinc t = sin πt/(πt)), so |c_0|² = 1 − 4a(1 − a)·sin²(φ/2) and
    /// |c_m|² = 4·sin²(φ/2)·sin²(πma)/(πm)².
    Binary {
        /// The fraction a of the period covered by the grooves, 0 < a ≤ 1.
        fraction: f64,
    },
}

impl Profile {
    /// |c_m(φ)|²: the share of the reflected light in order `order` at phase φ = k·w·h₀
    /// (radians). Finite and in [0, 1] for finite φ (to rounding).
    ///
    /// For [`Profile::Sine`] this is [`bessel_j`]`(m, φ)²`, for [`Profile::Binary`] the
    /// closed form above, computed from the complex coefficient with e^{iφ} − 1 written as
    /// 2i·sin(φ/2)·e^{iφ/2} (no cancellation for small φ).
    ///
    /// ```
    /// use diffraction::Profile;
    /// // Order 1 of a sine profile peaks near φ = 1.84 (the maximum of J₁) at 33.86 %.
    /// assert!((Profile::Sine.efficiency(1, 1.8411837813406593) - 0.338567139228272).abs() < 1e-15);
    /// assert_eq!(Profile::Sine.efficiency(3, 0.0), 0.0);
    /// ```
    #[must_use]
    pub fn efficiency(self, order: i32, phase: f64) -> f64 {
        match self {
            Profile::Sine => {
                let j = bessel_j(order, phase);
                j * j
            }
            Profile::Binary { fraction } => binary_coefficient(fraction, order, phase).norm_sqr(),
        }
    }
}

impl Profile {
    /// [`efficiency`](Self::efficiency) with the Bessel recurrence of the sine limited to
    /// `max_steps` steps (Debye's expansions beyond, see `bessel_j_bounded`).
    pub(crate) fn efficiency_bounded(self, order: i32, phase: f64, max_steps: f64) -> f64 {
        match self {
            Profile::Sine => {
                let j = bessel_j_bounded(order, phase, max_steps);
                j * j
            }
            Profile::Binary { .. } => self.efficiency(order, phase),
        }
    }
}

/// The Fourier coefficient c_m of the binary profile (see [`Profile::Binary`]).
pub(crate) fn binary_coefficient(a: f64, m: i32, phase: f64) -> Complex {
    let (s, c) = (math::sin(0.5 * phase), math::cos(0.5 * phase));
    // e^{iφ} − 1 = 2i·sin(φ/2)·e^{iφ/2} = −2 sin²(φ/2) + 2i·sin(φ/2)·cos(φ/2).
    let step = Complex::new(-2.0 * s * s, 2.0 * s * c);
    if m == 0 {
        return Complex::new(1.0, 0.0) + step.scale(a);
    }
    let (sn, cs) = sincospi(m as f64 * a);
    // a·sinc(m·a) = sin(πma)/(πm).
    (step * Complex::new(cs, -sn)).scale(sn / (PI * m as f64))
}
