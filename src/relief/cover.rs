//! The dielectric covers of the tabulated gratings (a CD's or a DVD's polycarbonate).

use crate::num::math;

/// The refractive index of polycarbonate at `lambda_nm`: the Sellmeier fit of N. Sultanova,
/// S. Kasarova and I. Nikolov, "Dispersion properties of optical polymers", Acta Physica
/// Polonica A 116, 585 (2009), n² = 1 + 1.4182/(1 − 0.021304 µm²/λ²), fitted over
/// 437-1052 nm (n = 1.642 at 360 nm, 1.589 at 550 nm, 1.570 at 830 nm): the cover of the `cd`
/// and `dvd` presets and of `grating-table --cover polycarbonate` (diffraction-fmm's
/// `CoverIndex::POLYCARBONATE`, the same fit, which a test of that crate holds equal to this
/// one). Defined above its pole λ = 146 nm; 1 at or below it (negative λ included) and for λ
/// not finite.
///
/// ```
/// use diffraction::relief::polycarbonate_index;
/// assert!((polycarbonate_index(550.0) - 1.589).abs() < 1e-3);
/// assert_eq!(polycarbonate_index(100.0), 1.0);
/// assert_eq!(polycarbonate_index(f64::NAN), 1.0);
/// assert_eq!(polycarbonate_index(-550.0), 1.0);
/// assert_eq!(polycarbonate_index(5e-324), 1.0);
/// // Far beyond the fit: the Sellmeier limit √(1 + 1.4182).
/// assert!((polycarbonate_index(1e300) - 2.4182f64.sqrt()).abs() < 1e-15);
/// ```
#[must_use]
pub fn polycarbonate_index(lambda_nm: f64) -> f64 {
    if !(lambda_nm.is_finite() && lambda_nm > 0.0) {
        return 1.0;
    }
    let l_um = lambda_nm * 1e-3;
    // c/λ² in two divisions: no overflow of λ² for large λ.
    let q = 1.0 - 0.021304 / l_um / l_um;
    if q > 0.0 && q.is_finite() {
        math::sqrt(1.0 + 1.4182 / q)
    } else {
        1.0
    }
}
