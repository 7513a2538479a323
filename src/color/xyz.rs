//! CIE 1931 XYZ tristimulus values and their chromaticity.

use core::ops::{Add, AddAssign, Mul};

use super::srgb::{mat_vec, XYZ_TO_SRGB};
use super::LinearSrgb;

/// CIE 1931 XYZ tristimulus values, relative: a perfect white reflector under the illuminant has
/// Y = 1 (colour-science's "scale 1", not the 0-100 scale).
///
/// Spectral integration accumulates these, so `Xyz` adds, scales and accumulates:
///
/// ```
/// use diffraction::color::Xyz;
/// let mut sum = Xyz::default();
/// for (cmf, weight) in [(Xyz::new(0.1, 0.2, 0.3), 0.5), (Xyz::new(0.3, 0.2, 0.1), 0.5)] {
///     sum += cmf * weight;
/// }
/// assert_eq!(sum, Xyz::new(0.2, 0.2, 0.2));
/// assert_eq!(sum + sum, sum.scale(2.0));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Xyz {
    /// X.
    pub x: f64,
    /// Y, the luminance (1 for the illuminant's white).
    pub y: f64,
    /// Z.
    pub z: f64,
}

impl Xyz {
    /// Builds an XYZ triple.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// let c = Xyz::new(0.95, 1.0, 1.09);
    /// assert_eq!(c.y, 1.0);
    /// ```
    #[inline]
    #[must_use]
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Xyz { x, y, z }
    }

    /// Converts to linear sRGB with the IEC 61966-2-1 matrix; the XYZ must be relative to D65
    /// (no chromatic adaptation is done).
    ///
    /// The matrix is the standard's four-decimal one, exactly as colour-science 0.4 uses it:
    ///
    /// ```text
    /// ⎡ 3.2406  −1.5372  −0.4986⎤
    /// ⎢−0.9689   1.8758   0.0415⎥
    /// ⎣ 0.0557  −0.2040   1.0570⎦
    /// ```
    ///
    /// It is not the exact inverse of the matrix of [`LinearSrgb::to_xyz`] (both are rounded to
    /// four decimals), so a round trip is good to 7e-5 of the largest component, not to rounding;
    /// and D65 (x, y) = (0.3127, 0.3290) maps to (0.99984, 1.00010, 1.00007), not exactly to 1.
    ///
    /// The result is **not clipped**: spectral colours come out with negative components.
    /// It is the matrix product to rounding for every finite input and never NaN: a component
    /// is ±∞ only where its exact value exceeds f64::MAX (inputs above about 3.4e307), the
    /// plain overflow of a linear map.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// let grey = Xyz::new(0.2 * 0.3127 / 0.3290, 0.2, 0.2 * 0.3583 / 0.3290).to_linear_srgb();
    /// assert!((grey.r - 0.2).abs() < 1e-4 && (grey.g - 0.2).abs() < 1e-4);
    /// ```
    #[inline]
    #[must_use]
    pub fn to_linear_srgb(self) -> LinearSrgb {
        let [r, g, b] = mat_vec(&XYZ_TO_SRGB, [self.x, self.y, self.z]);
        LinearSrgb { r, g, b }
    }

    /// The chromaticity coordinates (x, y) = (X, Y) / (X + Y + Z).
    ///
    /// `None` when X + Y + Z is zero (black has no chromaticity), when a component is not
    /// finite, or when a coordinate would exceed f64::MAX (a non-physical colour whose sum nearly
    /// cancels, such as (1, −1, −5e-324)). Components near f64::MAX are scaled by 2⁻⁶⁴ first, so
    /// the sum cannot overflow.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// let (x, y) = Xyz::new(1.0, 1.0, 1.0).chromaticity().unwrap();
    /// assert!((x - 1.0 / 3.0).abs() < 1e-15 && (y - 1.0 / 3.0).abs() < 1e-15);
    /// assert_eq!(Xyz::default().chromaticity(), None);
    /// assert_eq!(Xyz::new(f64::MAX, f64::MAX, 0.0).chromaticity(), Some((0.5, 0.5)));
    /// assert_eq!(Xyz::new(1.0, -1.0, -5e-324).chromaticity(), None);
    /// ```
    #[inline]
    #[must_use]
    pub fn chromaticity(self) -> Option<(f64, f64)> {
        /// Above this a sum of three components may overflow (3 · MAX/4 > MAX).
        const UNSCALED_MAX: f64 = f64::MAX / 4.0;
        /// 2⁶⁴, an exact scale for components that large.
        const RESCALE: f64 = 18_446_744_073_709_551_616.0;
        let m = self.x.abs().max(self.y.abs()).max(self.z.abs());
        if !m.is_finite() {
            return None;
        }
        let c = if m > UNSCALED_MAX {
            self.scale(1.0 / RESCALE)
        } else {
            self
        };
        let sum = c.x + c.y + c.z;
        let (x, y) = (c.x / sum, c.y / sum);
        if sum == 0.0 || !x.is_finite() || !y.is_finite() {
            None
        } else {
            Some((x, y))
        }
    }

    /// Multiplies every component by `k` (the same as `self * k`).
    ///
    /// Plain `f64` arithmetic, like `+` and `+=`: never NaN for finite operands; a component is
    /// ±∞ only where the exact product (or sum) exceeds f64::MAX.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// assert_eq!(Xyz::new(1.0, 2.0, 3.0).scale(0.5), Xyz::new(0.5, 1.0, 1.5));
    /// ```
    #[inline]
    #[must_use]
    pub fn scale(self, k: f64) -> Xyz {
        Xyz::new(self.x * k, self.y * k, self.z * k)
    }
}

impl Add for Xyz {
    type Output = Xyz;
    #[inline]
    fn add(self, rhs: Xyz) -> Xyz {
        Xyz::new(self.x + rhs.x, self.y + rhs.y, self.z + rhs.z)
    }
}

impl AddAssign for Xyz {
    #[inline]
    fn add_assign(&mut self, rhs: Xyz) {
        *self = *self + rhs;
    }
}

impl Mul<f64> for Xyz {
    type Output = Xyz;
    #[inline]
    fn mul(self, k: f64) -> Xyz {
        self.scale(k)
    }
}
