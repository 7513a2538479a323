//! The CIE 1931 2° standard observer and the CIE illuminants, at 1 nm over 360-830 nm.
//!
//! The tables (`cie_data.rs`) are generated from colour-science by `python_ref/generate.py`, whose
//! header names the datasets; between the 1 nm rows the crate interpolates linearly, and outside
//! [360, 830] nm every function here is 0 (the band over which colour is integrated).
//!
//! * D65 is tabulated by the CIE (and colour-science) at 5 nm to 780 nm only; the 1 nm rows are
//!   colour-science's linear interpolation, and from 780 to 830 nm they repeat the 780 nm value
//!   (colour-science's constant extrapolation), where the colour-matching functions are below 1e-4.
//! * A is defined by the CIE as a Planckian radiator (CIE 15:2004 eq. 1),
//!   S_A(λ) = 100·(560/λ)⁵·(exp(c₂/(2848·560)) − 1)/(exp(c₂/(2848·λ)) − 1) with
//!   c₂ = 1.435·10⁷ nm·K, so its 1 nm rows are that formula evaluated at every integer wavelength
//!   of 360-830 nm (colour-science's `sd_CIE_standard_illuminant_A`): no extrapolation. They
//!   agree with the CIE's six-digit 5 nm table to 3.8e-6 relative over 360-780 nm.

use crate::data::cie_data::{CIE1931_2DEG, D65, FIRST_NM, ILLUMINANT_A, LAST_NM};
use crate::ParseError;

/// First wavelength of the tables, nm (360).
///
/// ```
/// use diffraction::cie::{cmf, TABLE_FIRST_NM};
/// assert_eq!(TABLE_FIRST_NM, 360.0);
/// assert_eq!(TABLE_FIRST_NM, diffraction::Band::VISIBLE.min_nm());
/// assert_eq!(cmf(TABLE_FIRST_NM - 1.0), [0.0; 3]); // outside the tables
/// ```
pub const TABLE_FIRST_NM: f64 = FIRST_NM as f64;
/// Last wavelength of the tables, nm (830).
///
/// ```
/// use diffraction::cie::{Illuminant, TABLE_LAST_NM};
/// assert_eq!(TABLE_LAST_NM, 830.0);
/// assert!(Illuminant::D65.power(TABLE_LAST_NM) > 0.0);
/// assert_eq!(Illuminant::D65.power(TABLE_LAST_NM + 1.0), 0.0); // outside the tables
/// ```
pub const TABLE_LAST_NM: f64 = LAST_NM as f64;

/// Index of the row at or below λ and the fraction toward the next row; `None` outside the table.
#[inline]
fn locate(lambda_nm: f64) -> Option<(usize, f64)> {
    let s = lambda_nm - TABLE_FIRST_NM;
    if !(s >= 0.0 && lambda_nm <= TABLE_LAST_NM) {
        return None;
    }
    let last = (LAST_NM - FIRST_NM) as usize - 1; // last row that has a successor
    let i = (s as usize).min(last);
    Some((i, s - i as f64))
}

/// The CIE 1931 2° colour-matching functions [x̄, ȳ, z̄] at λ, linearly interpolated between the
/// 1 nm rows; [0, 0, 0] outside 360-830 nm.
///
/// ```
/// use diffraction::cie::cmf;
/// let [_, y, _] = cmf(555.0);
/// assert!((y - 1.0).abs() < 1e-3);
/// assert_eq!(cmf(900.0), [0.0; 3]);
/// ```
#[inline]
#[must_use]
pub fn cmf(lambda_nm: f64) -> [f64; 3] {
    match locate(lambda_nm) {
        None => [0.0; 3],
        Some((i, t)) => {
            let a = CIE1931_2DEG[i];
            let b = CIE1931_2DEG[i + 1];
            [
                a[0] + t * (b[0] - a[0]),
                a[1] + t * (b[1] - a[1]),
                a[2] + t * (b[2] - a[2]),
            ]
        }
    }
}

/// E(λ) of `illuminant` and the colour-matching functions at λ with one table look-up: the same
/// values, to the bit, as [`Illuminant::power`] and [`cmf`] (the same interpolation of the same
/// rows); zeros outside 360-830 nm.
#[inline]
pub(crate) fn power_and_cmf(illuminant: Illuminant, lambda_nm: f64) -> (f64, [f64; 3]) {
    let Some((i, t)) = locate(lambda_nm) else {
        return (0.0, [0.0; 3]);
    };
    let e = match illuminant {
        Illuminant::E => 1.0,
        Illuminant::D65 => D65[i] + t * (D65[i + 1] - D65[i]),
        Illuminant::A => ILLUMINANT_A[i] + t * (ILLUMINANT_A[i + 1] - ILLUMINANT_A[i]),
    };
    let (a, b) = (CIE1931_2DEG[i], CIE1931_2DEG[i + 1]);
    (
        e,
        [
            a[0] + t * (b[0] - a[0]),
            a[1] + t * (b[1] - a[1]),
            a[2] + t * (b[2] - a[2]),
        ],
    )
}

/// A CIE illuminant: the light's relative spectral power E(λ).
///
/// ```
/// use diffraction::cie::Illuminant;
/// assert_eq!(Illuminant::E.power(500.0), 1.0);
/// assert!((Illuminant::D65.power(560.0) - 100.0).abs() < 1e-9);
/// assert_eq!("d65".parse::<Illuminant>(), Ok(Illuminant::D65));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Illuminant {
    /// The equal-energy illuminant, E(λ) = 1.
    E,
    /// CIE standard illuminant D65 (average daylight), 100 at 560 nm.
    D65,
    /// CIE standard illuminant A (tungsten, 2856 K), 100 at 560 nm: the CIE's Planckian formula
    /// at every 1 nm row over the whole 360-830 nm band (see the [module docs](self)).
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// // S_A(λ) = 100 (560/λ)⁵ (exp(c₂/(2848·560)) − 1) / (exp(c₂/(2848·λ)) − 1), c₂ = 1.435e7 nm·K.
    /// let planck = |l: f64| {
    ///     let c2: f64 = 1.435e7;
    ///     let ratio = (c2 / (2848.0 * 560.0)).exp_m1() / (c2 / (2848.0 * l)).exp_m1();
    ///     100.0 * (560.0 / l).powi(5) * ratio
    /// };
    /// for l in [360.0, 560.0, 780.0, 830.0] {
    ///     assert!((Illuminant::A.power(l) - planck(l)).abs() < 1e-12 * planck(l));
    /// }
    /// assert!(Illuminant::A.power(830.0) > Illuminant::A.power(780.0)); // not held constant
    /// ```
    A,
}

impl Illuminant {
    /// E(λ), linearly interpolated between the 1 nm rows; 0 outside 360-830 nm.
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// let a = Illuminant::A;
    /// assert!((a.power(560.0) - 100.0).abs() < 1e-9); // normalised at 560 nm
    /// // Halfway between two rows: their mean (up to rounding).
    /// let mean = 0.5 * (a.power(600.0) + a.power(601.0));
    /// assert!((a.power(600.5) - mean).abs() < 1e-12);
    /// assert_eq!(Illuminant::E.power(900.0), 0.0);
    /// ```
    #[inline]
    #[must_use]
    pub fn power(self, lambda_nm: f64) -> f64 {
        let table = match self {
            Illuminant::E => {
                return if locate(lambda_nm).is_some() {
                    1.0
                } else {
                    0.0
                }
            }
            Illuminant::D65 => &D65,
            Illuminant::A => &ILLUMINANT_A,
        };
        match locate(lambda_nm) {
            None => 0.0,
            Some((i, t)) => table[i] + t * (table[i + 1] - table[i]),
        }
    }

    /// The name used by `FromStr` and `Display`: `E`, `D65` or `A`.
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// assert_eq!(Illuminant::D65.name(), "D65");
    /// assert_eq!(Illuminant::A.to_string(), Illuminant::A.name());
    /// assert_eq!(Illuminant::E.name().parse::<Illuminant>(), Ok(Illuminant::E));
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Illuminant::E => "E",
            Illuminant::D65 => "D65",
            Illuminant::A => "A",
        }
    }
}

impl core::fmt::Display for Illuminant {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

impl core::str::FromStr for Illuminant {
    type Err = ParseError;

    /// Parses `E`, `D65` or `A`, upper or lower case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "E" | "e" => Ok(Illuminant::E),
            "D65" | "d65" => Ok(Illuminant::D65),
            "A" | "a" => Ok(Illuminant::A),
            _ => Err(ParseError::new("illuminant", "one of E, D65, A")),
        }
    }
}

/// ∫ a(λ)·b(λ) dλ over 360-830 nm of two functions given by their 1 nm rows and interpolated
/// linearly: the product is quadratic on each 1 nm step, so Simpson's rule is exact there.
pub(crate) fn integrate_product_of_rows(a: impl Fn(usize) -> f64, b: impl Fn(usize) -> f64) -> f64 {
    let rows = (LAST_NM - FIRST_NM) as usize;
    let mut sum = 0.0;
    for i in 0..rows {
        let (a0, a1) = (a(i), a(i + 1));
        let (b0, b1) = (b(i), b(i + 1));
        let mid = 0.25 * (a0 + a1) * (b0 + b1);
        sum += (a0 * b0 + 4.0 * mid + a1 * b1) / 6.0;
    }
    sum
}

/// Row `i` of the illuminant table.
pub(crate) fn illuminant_row(ill: Illuminant, i: usize) -> f64 {
    match ill {
        Illuminant::E => 1.0,
        Illuminant::D65 => D65[i],
        Illuminant::A => ILLUMINANT_A[i],
    }
}

/// Row `i` of the colour-matching table, channel `c`.
pub(crate) fn cmf_row(i: usize, c: usize) -> f64 {
    CIE1931_2DEG[i][c]
}

/// The areas ∫x̄, ∫ȳ, ∫z̄ dλ of the colour-matching functions over 360-830 nm, exact for their
/// linear interpolation between the 1 nm rows (about 106.86, 106.86, 106.77 nm): ∫ȳ is the
/// normalisation of illuminant E's white and the scale of a grating's brightest order
/// (about 555 nm/(N·∫ȳ) for N slits).
///
/// ```
/// use diffraction::cie::cmf_areas;
/// let [x, y, z] = cmf_areas();
/// assert!((y - 106.857).abs() < 1e-3);
/// // The equal-energy white has nearly equal X, Y, Z.
/// assert!((x / y - 1.0).abs() < 1e-3 && (z / y - 1.0).abs() < 2e-3);
/// ```
#[must_use]
pub fn cmf_areas() -> [f64; 3] {
    let channel = |c| integrate_product_of_rows(|_| 1.0, |i| cmf_row(i, c));
    [channel(0), channel(1), channel(2)]
}
