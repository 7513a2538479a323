//! Colour: CIE XYZ, linear and encoded sRGB, gamut clipping, CIELAB and ΔE2000.
//!
//! # Types
//!
//! * [`Xyz`]: CIE 1931 XYZ tristimulus values, *relative*: a perfect white reflector under the
//!   illuminant has Y = 1. Spectral integration accumulates these (`+`, `+=`, `* f64`).
//! * [`LinearSrgb`]: linear-light sRGB. May be **out of gamut** (negative or above 1); nothing
//!   clips it behind your back.
//! * [`Srgb`]: encoded (non-linear, "gamma") sRGB, what image files and displays take.
//! * [`Lab`]: CIE 1976 L\*a\*b\*, with the CIEDE2000 colour difference [`delta_e2000`], the
//!   crate's unit of colour error.
//! * [`Clip`]: the three gamut-clipping schemes of Hall (1989).
//!
//! # Pipeline
//!
//! ```text
//! spectrum ──∫ E·I·cmf dλ──▶ Xyz ──to_linear_srgb──▶ LinearSrgb ──clip(Clip)──▶ LinearSrgb
//!                                                                 (in [0,1]³)
//!          ──encode──▶ Srgb ──to_rgb8──▶ [u8; 3]
//! ```
//!
//! ```
//! use diffraction::color::{Clip, Xyz};
//!
//! // A saturated green-cyan, roughly what a 500 nm spectral line looks like: far outside sRGB.
//! let xyz = Xyz::new(0.0049, 0.323, 0.272);
//! let linear = xyz.to_linear_srgb();
//! assert!(linear.r < 0.0 && !linear.is_in_gamut());
//!
//! // Clipping is an explicit, chosen step; then encode and quantise.
//! let clipped = linear.clip(Clip::ConstantIntensity);
//! assert!(clipped.is_in_gamut());
//! assert!((clipped.luminance() - linear.luminance()).abs() < 1e-12); // luminance survives
//! let rgb8 = clipped.encode().to_rgb8();
//! assert_eq!(rgb8[0], 0);
//! ```
//!
//! # Why clipping is explicit
//!
//! Pure spectral colours, which is what a diffraction grating shows, all lie outside the sRGB
//! gamut: every one has at least one negative linear component, and bright peaks exceed 1. *How*
//! such a colour is brought into the gamut changes the picture visibly (hue shifts, lost
//! brightness, or lost saturation), so no conversion here clips silently: [`Xyz::to_linear_srgb`]
//! and [`LinearSrgb::encode`] are unbounded, [`LinearSrgb::is_in_gamut`] tells whether a colour
//! needs clipping, and [`LinearSrgb::clip`] does it with the scheme you name. Only the final
//! quantisation [`Srgb::to_rgb8`] clamps, because a byte cannot hold anything else.
//!
//! Linear and encoded sRGB are distinct types, so encoding twice or forgetting to encode is a
//! type error:
//!
//! ```compile_fail,E0308
//! use diffraction::color::{LinearSrgb, Srgb};
//!
//! fn to_pixel(c: Srgb) -> [u8; 3] {
//!     c.to_rgb8()
//! }
//! let linear = LinearSrgb::new(0.5, 0.2, 0.1);
//! to_pixel(linear); // error: expected `Srgb`, found `LinearSrgb`
//! ```
//!
//! ```
//! # use diffraction::color::{LinearSrgb, Srgb};
//! # fn to_pixel(c: Srgb) -> [u8; 3] { c.to_rgb8() }
//! let linear = LinearSrgb::new(0.5, 0.2, 0.1);
//! assert_eq!(to_pixel(linear.encode()), [188, 124, 89]);
//! ```
//!
//! # Reference
//!
//! The matrices, the transfer function, CIELAB and ΔE2000 follow colour-science 0.4
//! (`tests/color_reference.rs` compares against fixtures it produced), with two documented
//! differences in the transfer function: negative values are mirrored rather than continued
//! linearly, and the decoding threshold is the standard's 0.04045 (see [`srgb_encode`],
//! [`srgb_decode`]).

use core::fmt;
use core::ops::{Add, AddAssign, Mul};
use core::str::FromStr;

use crate::math::{atan2, cbrt, cos, exp, powf, sin, sqrt};

/// XYZ → linear sRGB, IEC 61966-2-1 as published (four decimals), as colour-science 0.4 uses it
/// (`colour.RGB_COLOURSPACES['sRGB'].matrix_XYZ_to_RGB`).
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];

/// Linear sRGB → XYZ, IEC 61966-2-1 as published (four decimals), as colour-science 0.4 uses it
/// (`matrix_RGB_to_XYZ`). Not the exact inverse of [`XYZ_TO_SRGB`]: their product differs from
/// the identity by up to 4.1e-5.
const SRGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

#[inline]
fn mat_vec(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    [
        m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
        m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
        m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2],
    ]
}

/// Clamp to [0, 1], with NaN → 0.
#[inline]
fn clamp01(x: f64) -> f64 {
    if x > 1.0 {
        1.0
    } else if x >= 0.0 {
        x
    } else {
        0.0
    }
}

// ---------------------------------------------------------------------------------------------
// XYZ
// ---------------------------------------------------------------------------------------------

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
    /// `None` when X + Y + Z is zero (black has no chromaticity) or not finite.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// let (x, y) = Xyz::new(1.0, 1.0, 1.0).chromaticity().unwrap();
    /// assert!((x - 1.0 / 3.0).abs() < 1e-15 && (y - 1.0 / 3.0).abs() < 1e-15);
    /// assert_eq!(Xyz::default().chromaticity(), None);
    /// ```
    #[inline]
    #[must_use]
    pub fn chromaticity(self) -> Option<(f64, f64)> {
        let sum = self.x + self.y + self.z;
        if sum == 0.0 || !sum.is_finite() {
            None
        } else {
            Some((self.x / sum, self.y / sum))
        }
    }

    /// CIE 1976 L\*a\*b\* relative to the reference `white` (same scale as `self`, normally the
    /// illuminant's white with Y = 1).
    ///
    /// L\* = 116 f(Y/Yn) − 16, a\* = 500 (f(X/Xn) − f(Y/Yn)), b\* = 200 (f(Y/Yn) − f(Z/Zn)), with
    /// f(t) = ∛t for t > ε and (κ t + 16)/116 otherwise, ε = 216/24389, κ = 24389/27 (the exact
    /// rational constants of CIE 15:2004, continuous at ε). L\* is 100 for the white.
    ///
    /// ```
    /// use diffraction::color::Xyz;
    /// let white = Xyz::new(0.95047, 1.0, 1.08883);
    /// let lab = white.scale(0.5).to_lab(white);
    /// assert!((lab.l - 76.0693).abs() < 1e-4);
    /// assert!(lab.a.abs() < 1e-12 && lab.b.abs() < 1e-12);
    /// ```
    #[must_use]
    pub fn to_lab(self, white: Xyz) -> Lab {
        const EPSILON: f64 = 216.0 / 24389.0;
        const KAPPA: f64 = 24389.0 / 27.0;
        fn f(t: f64) -> f64 {
            if t > EPSILON {
                cbrt(t)
            } else {
                (KAPPA * t + 16.0) / 116.0
            }
        }
        let fx = f(self.x / white.x);
        let fy = f(self.y / white.y);
        let fz = f(self.z / white.z);
        Lab {
            l: 116.0 * fy - 16.0,
            a: 500.0 * (fx - fy),
            b: 200.0 * (fy - fz),
        }
    }

    /// Multiplies every component by `k` (the same as `self * k`).
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

// ---------------------------------------------------------------------------------------------
// Linear sRGB
// ---------------------------------------------------------------------------------------------

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
    /// (See [`Xyz::to_linear_srgb`] for why a round trip is only good to about 7e-5.)
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
    /// lets [`Clip::ConstantIntensity`] move a colour toward the grey of equal luminance.
    ///
    /// ```
    /// use diffraction::color::LinearSrgb;
    /// assert_eq!(LinearSrgb::new(1.0, 1.0, 1.0).luminance(), 1.0);
    /// assert_eq!(LinearSrgb::new(0.0, 1.0, 0.0).luminance(), 0.7152);
    /// ```
    #[inline]
    #[must_use]
    pub fn luminance(self) -> f64 {
        let w = SRGB_TO_XYZ[1];
        w[0] * self.r + w[1] * self.g + w[2] * self.b
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

    /// Brings the colour into the gamut [0, 1]³ with the given scheme (see [`Clip`] for what each
    /// one does, including to negative components).
    ///
    /// Every scheme returns an in-gamut colour unchanged, always returns a colour inside
    /// [0, 1]³, and never returns NaN, whatever the input. Non-finite input: NaN components
    /// count as 0 for `Clamp` and `Intensity`; +∞ becomes 1 under `Clamp`, and under
    /// `Intensity` the infinite components become 1 and the others 0; `ConstantIntensity`
    /// gives white for a luminance of +∞ and black for −∞ or NaN.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(2.0, 0.5, -0.5);
    /// assert_eq!(c.clip(Clip::Clamp), LinearSrgb::new(1.0, 0.5, 0.0));
    /// assert_eq!(c.clip(Clip::Intensity), LinearSrgb::new(1.0, 0.25, 0.0));
    /// let k = c.clip(Clip::ConstantIntensity);
    /// assert!(k.is_in_gamut() && (k.luminance() - c.luminance()).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn clip(self, method: Clip) -> LinearSrgb {
        if self.is_in_gamut() {
            return self;
        }
        match method {
            Clip::Clamp => self.map(clamp01),
            Clip::Intensity => self.clip_intensity(),
            Clip::ConstantIntensity => self.clip_constant_intensity(),
        }
    }

    #[inline]
    fn map(self, f: impl Fn(f64) -> f64) -> LinearSrgb {
        LinearSrgb::new(f(self.r), f(self.g), f(self.b))
    }

    fn clip_intensity(self) -> LinearSrgb {
        // Negative (and NaN) components → 0.
        let c = self.map(|v| if v > 0.0 { v } else { 0.0 });
        let m = c.r.max(c.g).max(c.b);
        if m <= 1.0 {
            c
        } else if m.is_finite() {
            // The ratios survive up to rounding; the clamp only guards against it.
            c.map(|v| clamp01(v / m))
        } else {
            // Infinite components: the direction is that of the infinite ones.
            c.map(|v| if v == f64::INFINITY { 1.0 } else { 0.0 })
        }
    }

    fn clip_constant_intensity(self) -> LinearSrgb {
        let y = self.luminance();
        // NaN luminance (a NaN or ±∞ − ∞ input) is treated as no light at all.
        if y.is_nan() || y <= 0.0 {
            return LinearSrgb::new(0.0, 0.0, 0.0);
        }
        if y >= 1.0 {
            // Scaling to luminance 1 and desaturating toward the grey of luminance 1 always ends
            // at white: it is the only colour in [0,1]³ with luminance 1.
            return LinearSrgb::new(1.0, 1.0, 1.0);
        }
        // 0 < y < 1: c' = y + t (c − y) with the largest t in [0, 1] that keeps every channel
        // in [0, 1]. The denominators are positive (c > 1 > y, or c < 0 < y).
        let mut t: f64 = 1.0;
        for c in [self.r, self.g, self.b] {
            if c > 1.0 {
                t = t.min((1.0 - y) / (c - y));
            } else if c < 0.0 {
                t = t.min(y / (y - c));
            }
        }
        // The clamp removes the rounding of the limiting channel (a few ulp at most).
        self.map(|c| clamp01(y + t * (c - y)))
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

// ---------------------------------------------------------------------------------------------
// Encoded sRGB
// ---------------------------------------------------------------------------------------------

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
/// same power law above 1. NaN stays NaN.
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
/// ```
#[must_use]
pub fn srgb_decode(encoded: f64) -> f64 {
    let a = if encoded < 0.0 { -encoded } else { encoded };
    let l = if a <= 0.040_45 {
        a / 12.92
    } else {
        powf((a + 0.055) / 1.055, 2.4)
    };
    if encoded < 0.0 {
        -l
    } else {
        l
    }
}

// ---------------------------------------------------------------------------------------------
// Clipping
// ---------------------------------------------------------------------------------------------

/// How [`LinearSrgb::clip`] brings an out-of-gamut colour into [0, 1]³ (the schemes of
/// R. Hall, *Illumination and Color in Computer Generated Imagery*, Springer 1989).
///
/// Every pure spectral colour has at least one **negative** linear sRGB component, and a bright
/// one also components above 1, so how each scheme treats negatives matters for every grating
/// picture.
///
/// Parsed from and displayed as `"clamp"`, `"intensity"`, `"constant"`:
///
/// ```
/// use diffraction::color::Clip;
/// let c: Clip = "constant".parse()?;
/// assert_eq!(c, Clip::ConstantIntensity);
/// assert_eq!(c.to_string(), "constant");
/// assert!("gamma".parse::<Clip>().is_err());
/// # Ok::<(), diffraction::color::ParseClipError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Clip {
    /// Clamp each channel to [0, 1] independently: negatives become 0, values above 1 become 1.
    ///
    /// Cheap, keeps in-range channels, but shifts the hue when a channel exceeds 1 (a bright
    /// orange turns yellow) and changes luminance.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(3.0, 1.5, -0.2).clip(Clip::Clamp);
    /// assert_eq!(c, LinearSrgb::new(1.0, 1.0, 0.0)); // orange became yellow
    /// ```
    Clamp,
    /// Intensity scaling: negative channels are set to 0 first, then, if the largest channel
    /// exceeds 1, the triple is divided by it.
    ///
    /// Keeps the ratios of the non-negative components (the hue and saturation of the colour
    /// with its negatives clamped) and loses brightness instead.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(3.0, 1.5, -0.2).clip(Clip::Intensity);
    /// assert_eq!(c, LinearSrgb::new(1.0, 0.5, 0.0)); // still orange, darker
    /// ```
    Intensity,
    /// Constant-intensity scaling: keeps the luminance Y ([`LinearSrgb::luminance`]) and moves
    /// the colour toward the grey (Y, Y, Y) of equal luminance, c' = Y + t (c − Y), with the
    /// largest t ∈ [0, 1] that puts every channel in [0, 1] (t ≤ (1 − Y)/(cᵢ − Y) for cᵢ > 1,
    /// t ≤ Y/(Y − cᵢ) for cᵢ < 0, so a negative channel ends at exactly 0 when it is the
    /// limiting one). It desaturates instead of darkening.
    ///
    /// Because the luminance weights sum to 1, the grey and every point of the segment have
    /// luminance Y: the luminance is kept (to rounding, about 1e-16) whenever 0 < Y < 1.
    /// If Y ≤ 0 the result is black. If Y ≥ 1 the triple is first scaled to luminance 1, and the
    /// only in-gamut colour of luminance 1 is white, so the result is white (1, 1, 1).
    /// A final clamp, which moves values by a few ulp at most, guards against rounding.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(1.2, 0.3, -0.1);
    /// let k = c.clip(Clip::ConstantIntensity);
    /// assert!(k.is_in_gamut() && (k.luminance() - c.luminance()).abs() < 1e-15);
    /// assert_eq!(LinearSrgb::new(3.0, 1.5, 0.0).clip(Clip::ConstantIntensity),
    ///            LinearSrgb::new(1.0, 1.0, 1.0));
    /// ```
    ConstantIntensity,
}

impl Clip {
    /// Every scheme, in declaration order.
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// assert_eq!(Clip::ALL.len(), 3);
    /// ```
    pub const ALL: [Clip; 3] = [Clip::Clamp, Clip::Intensity, Clip::ConstantIntensity];

    /// The name used by [`Display`](fmt::Display) and [`FromStr`].
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// assert_eq!(Clip::Intensity.name(), "intensity");
    /// ```
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Clip::Clamp => "clamp",
            Clip::Intensity => "intensity",
            Clip::ConstantIntensity => "constant",
        }
    }
}

impl fmt::Display for Clip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Clip {
    type Err = ParseClipError;

    /// Parses `"clamp"`, `"intensity"` or `"constant"` (exactly, lower case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Clip::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or(ParseClipError { _private: () })
    }
}

/// The error of parsing a [`Clip`] from a string that is not one of its names.
///
/// ```
/// use diffraction::color::Clip;
/// let err = "hard".parse::<Clip>().unwrap_err();
/// assert_eq!(
///     err.to_string(),
///     "unknown clipping scheme: expected one of \"clamp\", \"intensity\", \"constant\""
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParseClipError {
    _private: (),
}

impl fmt::Display for ParseClipError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(
            "unknown clipping scheme: expected one of \"clamp\", \"intensity\", \"constant\"",
        )
    }
}

impl core::error::Error for ParseClipError {}

// ---------------------------------------------------------------------------------------------
// CIELAB and ΔE2000
// ---------------------------------------------------------------------------------------------

/// CIE 1976 L\*a\*b\* (L\* in [0, 100] for surface colours), made by [`Xyz::to_lab`].
///
/// ```
/// use diffraction::color::Lab;
/// let a = Lab::new(50.0, 2.5, 0.0);
/// let b = Lab::new(50.0, 0.0, -2.5);
/// assert!((a.delta_e2000(b) - 4.3065).abs() < 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Lab {
    /// Lightness L\*.
    pub l: f64,
    /// a\* (green − / red +).
    pub a: f64,
    /// b\* (blue − / yellow +).
    pub b: f64,
}

impl Lab {
    /// Builds a L\*a\*b\* triple.
    ///
    /// ```
    /// use diffraction::color::Lab;
    /// assert_eq!(Lab::new(50.0, 1.0, -1.0).l, 50.0);
    /// ```
    #[inline]
    #[must_use]
    pub const fn new(l: f64, a: f64, b: f64) -> Self {
        Lab { l, a, b }
    }

    /// The CIEDE2000 colour difference to `other`; see [`delta_e2000`].
    ///
    /// ```
    /// use diffraction::color::Lab;
    /// let a = Lab::new(50.0, 2.6772, -79.7751);
    /// let b = Lab::new(50.0, 0.0, -82.7485);
    /// assert!((a.delta_e2000(b) - 2.0425).abs() < 1e-4);
    /// ```
    #[inline]
    #[must_use]
    pub fn delta_e2000(self, other: Lab) -> f64 {
        delta_e2000(self, other)
    }
}

/// 25⁷, the chroma constant of CIEDE2000.
const POW25_7: f64 = 6_103_515_625.0;

#[inline]
fn pow7(x: f64) -> f64 {
    let x2 = x * x;
    x2 * x2 * x2 * x
}

/// Hue angle in degrees, in [0, 360); 0 when both coordinates are 0 (Sharma et al. eq. 7).
#[inline]
fn hue_deg(b: f64, a: f64) -> f64 {
    if a == 0.0 && b == 0.0 {
        return 0.0;
    }
    let h = atan2(b, a).to_degrees();
    if h < 0.0 {
        h + 360.0
    } else {
        h
    }
}

/// The CIEDE2000 colour difference ΔE₀₀ between two CIELAB colours, with the parametric factors
/// kL = kC = kH = 1.
///
/// Implements G. Sharma, W. Wu, E. N. Dalal, "The CIEDE2000 color-difference formula:
/// implementation notes, supplementary test data, and mathematical observations", *Color Res.
/// Appl.* 30 (2005), eqs. 1-22, including its conventions for the hue: h' = 0 when a' = b = 0;
/// Δh' = 0 when C'₁C'₂ = 0, otherwise the difference taken the short way round the circle; the
/// mean hue h̄' = h'₁ + h'₂ when C'₁C'₂ = 0, otherwise the mean taken the short way round (adding
/// or subtracting 360° as the paper prescribes). It reproduces the paper's 34 test pairs and
/// colour-science's `delta_E_CIE2000`.
///
/// The result is symmetric, zero for identical inputs, and non-negative (the rotation term is
/// bounded by |R_T| < 2, so the quadratic form is positive definite; a rounding-level negative
/// radicand is returned as 0). NaN input gives NaN.
///
/// ```
/// use diffraction::color::{delta_e2000, Lab};
/// let a = Lab::new(50.0, 2.5, 0.0);
/// let b = Lab::new(73.0, 25.0, -18.0);
/// assert!((delta_e2000(a, b) - 27.1492).abs() < 1e-4);
/// assert_eq!(delta_e2000(a, a), 0.0);
/// ```
#[must_use]
pub fn delta_e2000(lab1: Lab, lab2: Lab) -> f64 {
    let (l1, a1, b1) = (lab1.l, lab1.a, lab1.b);
    let (l2, a2, b2) = (lab2.l, lab2.a, lab2.b);

    // Eqs. 2-7: C*, G, a', C', h'.
    let c1 = sqrt(a1 * a1 + b1 * b1);
    let c2 = sqrt(a2 * a2 + b2 * b2);
    let c_bar7 = pow7((c1 + c2) / 2.0);
    let g = 0.5 * (1.0 - sqrt(c_bar7 / (c_bar7 + POW25_7)));
    let a1p = (1.0 + g) * a1;
    let a2p = (1.0 + g) * a2;
    let c1p = sqrt(a1p * a1p + b1 * b1);
    let c2p = sqrt(a2p * a2p + b2 * b2);
    let h1p = hue_deg(b1, a1p);
    let h2p = hue_deg(b2, a2p);

    // Eqs. 8-11: ΔL', ΔC', Δh', ΔH'.
    let dl = l2 - l1;
    let dc = c2p - c1p;
    let c_prod = c1p * c2p;
    let dh_deg = if c_prod == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dh = 2.0 * sqrt(c_prod) * sin((dh_deg / 2.0).to_radians());

    // Eqs. 12-14: means.
    let l_bar = (l1 + l2) / 2.0;
    let c_bar_p = (c1p + c2p) / 2.0;
    let h_sum = h1p + h2p;
    let h_bar = if c_prod == 0.0 {
        h_sum
    } else {
        let d = h1p - h2p;
        if (-180.0..=180.0).contains(&d) {
            h_sum / 2.0
        } else if h_sum < 360.0 {
            (h_sum + 360.0) / 2.0
        } else {
            (h_sum - 360.0) / 2.0
        }
    };

    // Eqs. 15-21: weights and rotation.
    let t = 1.0 - 0.17 * cos((h_bar - 30.0).to_radians())
        + 0.24 * cos((2.0 * h_bar).to_radians())
        + 0.32 * cos((3.0 * h_bar + 6.0).to_radians())
        - 0.20 * cos((4.0 * h_bar - 63.0).to_radians());
    let x = (h_bar - 275.0) / 25.0;
    let d_theta = 30.0 * exp(-(x * x));
    let c_bar_p7 = pow7(c_bar_p);
    let r_c = 2.0 * sqrt(c_bar_p7 / (c_bar_p7 + POW25_7));
    let l50 = (l_bar - 50.0) * (l_bar - 50.0);
    let s_l = 1.0 + 0.015 * l50 / sqrt(20.0 + l50);
    let s_c = 1.0 + 0.045 * c_bar_p;
    let s_h = 1.0 + 0.015 * c_bar_p * t;
    let r_t = -sin((2.0 * d_theta).to_radians()) * r_c;

    // Eq. 22.
    let (ql, qc, qh) = (dl / s_l, dc / s_c, dh / s_h);
    let sum = ql * ql + qc * qc + qh * qh + r_t * qc * qh;
    if sum < 0.0 {
        0.0
    } else {
        sqrt(sum)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cie_data::CIE1931_2DEG;

    /// Every integer wavelength of the CIE 1931 2° table (360..=830 nm) as a pure spectral colour
    /// at five intensities, through the whole pipeline with each clipping scheme.
    #[test]
    fn monochromatic_sweep() {
        const INTENSITIES: [f64; 5] = [0.01, 0.1, 1.0, 10.0, 100.0];
        assert_eq!(CIE1931_2DEG.len(), 471);
        let white = LinearSrgb::new(1.0, 1.0, 1.0).to_xyz();
        let mut white_count = 0;
        for (i, &[xbar, ybar, zbar]) in CIE1931_2DEG.iter().enumerate() {
            let nm = 360 + i;
            let cmf = Xyz::new(xbar, ybar, zbar);
            let (x, y) = cmf.chromaticity().expect("every CMF row is non-zero");
            assert!(
                (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y),
                "{nm} nm"
            );
            for k in INTENSITIES {
                let xyz = cmf * k;
                let linear = xyz.to_linear_srgb();
                assert!(
                    linear.r.is_finite() && linear.g.is_finite() && linear.b.is_finite(),
                    "{nm} nm × {k}"
                );
                // Spectral colours lie outside the sRGB triangle: a negative component.
                assert!(
                    linear.r < 0.0 || linear.g < 0.0 || linear.b < 0.0,
                    "{nm} nm × {k}: {linear:?} has no negative component"
                );
                assert!(!linear.is_in_gamut());
                let lum = linear.luminance();
                for method in Clip::ALL {
                    let c = linear.clip(method);
                    assert!(c.is_in_gamut(), "{nm} nm × {k}, {method}: {c:?}");
                    let e = c.encode();
                    for v in [e.r, e.g, e.b] {
                        assert!((0.0..=1.0).contains(&v), "{nm} nm × {k}, {method}");
                    }
                    let back = e.decode();
                    for (b, l) in [(back.r, c.r), (back.g, c.g), (back.b, c.b)] {
                        // Round trip within the transfer function's breakpoint inconsistency.
                        assert!((b - l).abs() < 2.4e-9, "{nm} nm × {k}, {method}");
                    }
                    let _ = e.to_rgb8();
                    let de = xyz.to_lab(white).delta_e2000(c.to_xyz().to_lab(white));
                    assert!(de.is_finite() && de >= 0.0, "{nm} nm × {k}, {method}: {de}");
                    match method {
                        Clip::ConstantIntensity if lum <= 0.0 => {
                            assert_eq!(c, LinearSrgb::default());
                        }
                        Clip::ConstantIntensity if lum >= 1.0 => {
                            assert_eq!(c, LinearSrgb::new(1.0, 1.0, 1.0));
                            white_count += 1;
                        }
                        Clip::ConstantIntensity => {
                            assert!(
                                (c.luminance() - lum).abs() < 1e-12,
                                "{nm} nm × {k}: luminance {} -> {}",
                                lum,
                                c.luminance()
                            );
                        }
                        Clip::Intensity => {
                            // A negative component goes to 0, the others keep their ratios.
                            let pos = [linear.r, linear.g, linear.b].map(|v| v.max(0.0));
                            let m = pos[0].max(pos[1]).max(pos[2]).max(1.0);
                            for (o, p) in [c.r, c.g, c.b].into_iter().zip(pos) {
                                assert!((o * m - p).abs() <= 1e-15 * m, "{nm} nm × {k}");
                            }
                        }
                        _ => {}
                    }
                }
            }
        }
        // Bright lines near the peak of ȳ saturate to white under constant intensity.
        assert!(white_count > 0);
    }
}
