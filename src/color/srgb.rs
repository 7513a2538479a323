//! Linear and encoded sRGB (IEC 61966-2-1): the matrices and the transfer functions.

use core::ops::{Add, Mul};

use super::Xyz;
use crate::num::math::powf;

/// XYZ → linear sRGB, IEC 61966-2-1 as published (four decimals), as colour-science 0.4 uses it
/// (`colour.RGB_COLOURSPACES['sRGB'].matrix_XYZ_to_RGB`).
pub(super) const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Linear sRGB → XYZ, IEC 61966-2-1 as published (four decimals), as colour-science 0.4 uses it
/// (`matrix_RGB_to_XYZ`). Not the exact inverse of [`XYZ_TO_SRGB`]: their product differs from
/// the identity by up to 4.1e-5.
pub(super) const SRGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// Largest component magnitude for which a row of either matrix cannot overflow: the largest
/// absolute row sum is 5.2764 (the first row of [`XYZ_TO_SRGB`]) < 8, so for |vᵢ| ≤ f64::MAX / 8
/// every product and partial sum stays finite.
const MAT_UNSCALED_MAX: f64 = f64::MAX / 8.0;

/// 2⁶⁴: larger inputs are multiplied by its inverse (exactly, they are far from subnormal), the
/// products summed, and the result multiplied back; it then overflows only where the exact value
/// exceeds f64::MAX, and an ∞ − ∞ (NaN) of two overflowed products cannot occur.
const MAT_RESCALE: f64 = 18_446_744_073_709_551_616.0;

#[inline]
fn row_dot(w: &[f64; 3], v: [f64; 3]) -> f64 {
    w[0] * v[0] + w[1] * v[1] + w[2] * v[2]
}

/// Whether `v` is finite with a component too large for [`row_dot`] to be evaluated as written.
#[inline]
fn needs_rescale(v: [f64; 3]) -> bool {
    let m = v[0].abs().max(v[1].abs()).max(v[2].abs());
    m > MAT_UNSCALED_MAX && m.is_finite()
}

/// One row of a matrix times `v`: never NaN for finite `v`, ±∞ only where the exact value
/// exceeds f64::MAX in magnitude (see [`MAT_RESCALE`]).
#[inline]
pub(super) fn row_dot_safe(w: &[f64; 3], v: [f64; 3]) -> f64 {
    if needs_rescale(v) {
        row_dot(w, v.map(|c| c / MAT_RESCALE)) * MAT_RESCALE
    } else {
        row_dot(w, v)
    }
}

/// `m · v` with [`row_dot_safe`] for each row.
#[inline]
pub(super) fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [
        row_dot_safe(&m[0], v),
        row_dot_safe(&m[1], v),
        row_dot_safe(&m[2], v),
    ]
}

/// Clamps to [−f64::MAX, f64::MAX] (±∞ become ±f64::MAX, NaN stays NaN): where a nonlinear
/// function's exact value lies beyond the largest finite `f64`, it returns that instead of ∞.
#[inline]
pub(super) fn saturate(x: f64) -> f64 {
    x.clamp(-f64::MAX, f64::MAX)
}

/// Clamp to [0, 1], with NaN → 0.
#[inline]
pub(super) fn clamp01(x: f64) -> f64 {
    if x > 1.0 {
        1.0
    } else if x >= 0.0 {
        x
    } else {
        0.0
    }
}

/// Linear-light sRGB (the IEC 61966-2-1 primaries and D65 white, no transfer function).
///
/// Components are unbounded: a colour outside the sRGB gamut has components below 0 or above 1.
/// Bring it into [0, 1]³ with [`clip`](LinearSrgb::clip), then [`encode`](LinearSrgb::encode).
///
/// ```
/// use diffraction::color::LinearSrgb;
/// let c = LinearSrgb::new(0.2, 0.1, 0.0) + LinearSrgb::new(0.2, 0.1, 0.0) * 0.5;
/// assert!((c.r - 0.3).abs() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct LinearSrgb {
    /// Red, linear light.
    pub r: f64,
    /// Green, linear light.
    pub g: f64,
    /// Blue, linear light.
    pub b: f64,
}

impl LinearSrgb {
    /// Builds a linear sRGB triple (any values, in gamut or not).
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// assert_eq!(LinearSrgb::new(1.0, -0.5, 2.0).g, -0.5);
    /// ```
    #[inline]
    #[must_use]
    pub const fn new(r: f64, g: f64, b: f64) -> Self {
        LinearSrgb { r, g, b }
    }

    /// Converts to XYZ (relative to D65) with the IEC 61966-2-1 matrix as colour-science 0.4 uses
    /// it:
    ///
    /// ```text
    /// ⎡0.4124  0.3576  0.1805⎤
    /// ⎢0.2126  0.7152  0.0722⎥
    /// ⎣0.0193  0.1192  0.9505⎦
    /// ```
    ///
    /// (See [`Xyz::to_linear_srgb`] for why a round trip is only good to about 7e-5, and for the
    /// behaviour at huge components: never NaN, ±∞ only where the exact value exceeds f64::MAX.)
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// let white = LinearSrgb::new(1.0, 1.0, 1.0).to_xyz();
    /// assert!((white.x - 0.9505).abs() < 1e-12 && white.y == 1.0);
    /// ```
    #[inline]
    #[must_use]
    pub fn to_xyz(self) -> Xyz {
        let [x, y, z] = mat_vec(&SRGB_TO_XYZ, [self.r, self.g, self.b]);
        Xyz { x, y, z }
    }

    /// The relative luminance Y = 0.2126 R + 0.7152 G + 0.0722 B (the second row of the matrix of
    /// [`to_xyz`](LinearSrgb::to_xyz)).
    ///
    /// The weights are positive and sum to 1 (exactly, even in `f64` arithmetic:
    /// `0.2126 + 0.7152 + 0.0722 == 1.0`), so a grey (g, g, g) has luminance g; this is what
    /// lets [`Clip::ConstantIntensity`](super::Clip::ConstantIntensity) move a colour toward
    /// the grey of equal luminance. Finite for every finite input (the exact weighted mean lies
    /// between the smallest and the largest component; a rounding past f64::MAX saturates).
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// assert_eq!(LinearSrgb::new(1.0, 1.0, 1.0).luminance(), 1.0);
    /// assert_eq!(LinearSrgb::new(0.0, 1.0, 0.0).luminance(), 0.7152);
    /// ```
    #[inline]
    #[must_use]
    pub fn luminance(self) -> f64 {
        saturate(row_dot_safe(&SRGB_TO_XYZ[1], [self.r, self.g, self.b]))
    }

    /// Whether every component lies in [0, 1], inclusive and with **no tolerance** (a component
    /// of 1 + 1e-16 is out). NaN is out of gamut.
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// assert!(LinearSrgb::new(0.0, 0.5, 1.0).is_in_gamut());
    /// assert!(!LinearSrgb::new(-1e-300, 0.5, 1.0).is_in_gamut());
    /// assert!(!LinearSrgb::new(f64::NAN, 0.5, 1.0).is_in_gamut());
    /// ```
    #[inline]
    #[must_use]
    pub fn is_in_gamut(self) -> bool {
        let inside = |c: f64| (0.0..=1.0).contains(&c);
        inside(self.r) && inside(self.g) && inside(self.b)
    }

    /// Applies the sRGB transfer function ([`srgb_encode`]) to each channel.
    ///
    /// Out of [0, 1] nothing is clipped: negative values are mirrored (−f(|c|)) and values above
    /// 1 follow the power law beyond 1. Clip first ([`clip`](LinearSrgb::clip)) if you want a
    /// displayable colour.
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// let e = LinearSrgb::new(0.0, 1.0, 0.18).encode();
    /// assert_eq!(e.r, 0.0);
    /// assert!((e.g - 1.0).abs() < 1e-15);
    /// assert!((e.b - 0.461356).abs() < 1e-6);
    /// assert!(LinearSrgb::new(2.0, -0.5, 0.0).encode().g < 0.0); // not clipped
    /// ```
    #[inline]
    #[must_use]
    pub fn encode(self) -> Srgb {
        Srgb::new(
            srgb_encode(self.r),
            srgb_encode(self.g),
            srgb_encode(self.b),
        )
    }
}

impl Add for LinearSrgb {
    type Output = LinearSrgb;
    #[inline]
    fn add(self, rhs: LinearSrgb) -> LinearSrgb {
        LinearSrgb::new(self.r + rhs.r, self.g + rhs.g, self.b + rhs.b)
    }
}

impl Mul<f64> for LinearSrgb {
    type Output = LinearSrgb;
    #[inline]
    fn mul(self, k: f64) -> LinearSrgb {
        LinearSrgb::new(self.r * k, self.g * k, self.b * k)
    }
}

/// Encoded (non-linear) sRGB: the values image files store and displays expect, in [0, 1] for
/// displayable colours.
///
/// ```
/// use diffraction::color::Srgb;
/// let c = Srgb::new(1.0, 0.5, 0.0);
/// assert_eq!(c.to_rgb8(), [255, 128, 0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Srgb {
    /// Red, encoded.
    pub r: f64,
    /// Green, encoded.
    pub g: f64,
    /// Blue, encoded.
    pub b: f64,
}

impl Srgb {
    /// Builds an encoded sRGB triple.
    ///
    /// ```
    /// use diffraction::color::Srgb;
    /// assert_eq!(Srgb::new(0.1, 0.2, 0.3).b, 0.3);
    /// ```
    #[inline]
    #[must_use]
    pub const fn new(r: f64, g: f64, b: f64) -> Self {
        Srgb { r, g, b }
    }

    /// Removes the transfer function ([`srgb_decode`]) from each channel; the inverse of
    /// [`LinearSrgb::encode`], also outside [0, 1].
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// let c = LinearSrgb::new(0.001, 0.5, 3.0);
    /// let back = c.encode().decode();
    /// assert!((back.r - c.r).abs() < 1e-15 && (back.b - c.b).abs() < 1e-14);
    /// ```
    #[inline]
    #[must_use]
    pub fn decode(self) -> LinearSrgb {
        LinearSrgb::new(
            srgb_decode(self.r),
            srgb_decode(self.g),
            srgb_decode(self.b),
        )
    }

    /// Quantises to 8 bits: each channel is clamped to [0, 1] (NaN → 0), multiplied by 255 and
    /// rounded to the nearest integer (halves round up).
    ///
    /// This is the only place where the colour pipeline clamps without being asked: a byte
    /// cannot hold anything else. Clip the linear colour first to choose how.
    ///
    /// ```
    /// use diffraction::color::Srgb;
    /// assert_eq!(Srgb::new(-0.2, 0.5, 7.0).to_rgb8(), [0, 128, 255]);
    /// assert_eq!(Srgb::new(f64::NAN, 1.0 / 255.0, 0.498 / 255.0).to_rgb8(), [0, 1, 0]);
    /// ```
    #[inline]
    #[must_use]
    pub fn to_rgb8(self) -> [u8; 3] {
        // In [0.5, 255.5]: the cast truncates, i.e. rounds the unshifted value half up.
        let q = |c: f64| (clamp01(c) * 255.0 + 0.5) as u8;
        [q(self.r), q(self.g), q(self.b)]
    }
}

/// The sRGB transfer function (IEC 61966-2-1), linear → encoded:
/// 12.92 c for c ≤ 0.0031308, 1.055 c^(1/2.4) − 0.055 above.
///
/// Extended to all reals without clipping: odd-symmetric for negatives (sign(c)·f(|c|)) and the
/// same power law above 1. NaN stays NaN. Finite for every finite input (the power law grows
/// like c^(1/2.4), so `srgb_encode(f64::MAX)` is about 1.5e128).
///
/// The formula is evaluated as written, so `srgb_encode(1.0)` is `1.055 - 0.055`, which is
/// 1 − 2⁻⁵³ in `f64` (as in colour-science); it still quantises to 255.
///
/// colour-science's `eotf_inverse_sRGB` agrees on [0, ∞) but continues the *linear* segment
/// for all negatives (12.92 c), so the two differ below −0.0031308. The standard's rounded
/// constants leave a downward jump of 2.85e-8 at the breakpoint (the curve is not quite
/// monotone there).
///
/// ```
/// use diffraction::color::srgb_encode;
/// assert_eq!(srgb_encode(0.0), 0.0);
/// assert!((srgb_encode(1.0) - 1.0).abs() < 1e-15);
/// assert_eq!(srgb_encode(0.001), 12.92 * 0.001); // the linear segment
/// assert_eq!(srgb_encode(-0.5), -srgb_encode(0.5));
/// ```
#[must_use]
pub fn srgb_encode(linear: f64) -> f64 {
    let a = if linear < 0.0 { -linear } else { linear };
    let e = if a <= 0.003_130_8 {
        12.92 * a
    } else {
        1.055 * powf(a, 1.0 / 2.4) - 0.055
    };
    if linear < 0.0 {
        -e
    } else {
        e
    }
}

/// The inverse sRGB transfer function (IEC 61966-2-1), encoded → linear:
/// v / 12.92 for v ≤ 0.04045, ((v + 0.055) / 1.055)^2.4 above.
///
/// Extended like [`srgb_encode`]: odd-symmetric for negatives, the power law above 1.
///
/// Finite for every finite input: the power law exceeds f64::MAX for |v| above
/// 1.055·f64::MAX^(1/2.4) − 0.055 ≈ 2.9e128, and there the result **saturates** at ±f64::MAX
/// (the largest finite value, not ∞). NaN stays NaN.
///
/// colour-science's `eotf_sRGB` places the threshold at `eotf_inverse_sRGB(0.0031308)` =
/// 0.040449936 instead of 0.04045, so on that interval of width 6.4e-8 the two differ by up to
/// 2.3e-9 (the jump of the standard's rounded constants); for negatives it continues the linear
/// segment (v / 12.92) instead of mirroring.
///
/// ```
/// use diffraction::color::{srgb_decode, srgb_encode};
/// assert_eq!(srgb_decode(1.0), 1.0);
/// assert!((srgb_decode(srgb_encode(0.18)) - 0.18).abs() < 1e-16);
/// assert_eq!(srgb_decode(-0.5), -srgb_decode(0.5));
/// assert_eq!(srgb_decode(1e300), f64::MAX); // saturates instead of overflowing
/// assert_eq!(srgb_decode(-1e300), -f64::MAX);
/// ```
#[must_use]
pub fn srgb_decode(encoded: f64) -> f64 {
    let a = if encoded < 0.0 { -encoded } else { encoded };
    let l = if a <= 0.040_45 {
        a / 12.92
    } else {
        // Above 2.9e128 the power exceeds f64::MAX: return the largest finite value.
        saturate(powf((a + 0.055) / 1.055, 2.4))
    };
    if encoded < 0.0 {
        -l
    } else {
        l
    }
}
