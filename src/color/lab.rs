//! CIE 1976 L*a*b* and the CIEDE2000 colour difference.

use super::srgb::saturate;
use super::Xyz;
use crate::error::positive;
use crate::num::math::{atan2, cbrt, cos, exp, sin, sqrt};
use crate::Error;

/// A reference white for CIELAB: an XYZ whose three components are finite and positive.
///
/// CIELAB divides by the white's components, so a zero, negative or non-finite white has no
/// L\*a\*b\*; it is rejected here, where the white is made, with an [`Error`] naming the component.
///
/// ```
/// use diffraction::color::{WhitePoint, Xyz};
/// let white = WhitePoint::new(Xyz::new(0.95047, 1.0, 1.08883))?;
/// assert_eq!(white.xyz().y, 1.0);
/// let err = WhitePoint::new(Xyz::new(0.95047, 0.0, 1.08883)).unwrap_err();
/// assert_eq!(err.parameter(), "white.y");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WhitePoint {
    xyz: Xyz,
}

impl WhitePoint {
    /// Checks that every component of `white` is finite and > 0.
    ///
    /// ```
    /// use diffraction::color::{WhitePoint, Xyz};
    /// assert!(WhitePoint::new(Xyz::new(1.0, 1.0, 1.0)).is_ok());
    /// assert_eq!(WhitePoint::new(Xyz::new(-1.0, 1.0, 1.0)).unwrap_err().parameter(), "white.x");
    /// assert_eq!(WhitePoint::new(Xyz::new(1.0, 1.0, f64::NAN)).unwrap_err().parameter(), "white.z");
    /// ```
    pub fn new(white: Xyz) -> Result<WhitePoint, Error> {
        positive("white.x", white.x)?;
        positive("white.y", white.y)?;
        positive("white.z", white.z)?;
        Ok(WhitePoint { xyz: white })
    }

    /// The white's XYZ.
    ///
    /// ```
    /// use diffraction::color::{WhitePoint, Xyz};
    /// let w = Xyz::new(0.9, 1.0, 1.1);
    /// assert_eq!(WhitePoint::new(w)?.xyz(), w);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub const fn xyz(self) -> Xyz {
        self.xyz
    }
}

impl TryFrom<Xyz> for WhitePoint {
    type Error = Error;

    /// The same as [`WhitePoint::new`].
    fn try_from(white: Xyz) -> Result<WhitePoint, Error> {
        WhitePoint::new(white)
    }
}

/// ε = 216/24389 of CIE 15:2004: the end of the linear segment of f.
const EPSILON: f64 = 216.0 / 24389.0;
/// κ = 24389/27 of CIE 15:2004, the slope of the linear segment (f = (κ t + 16)/116).
const KAPPA: f64 = 24389.0 / 27.0;
/// Below −f64::MAX/κ ≈ −2e305 the product κ·t of the linear segment would overflow while the
/// exact f = (κ t + 16)/116 may still be finite; there f is evaluated as (κ/116)·t + 16/116.
const LINEAR_UNSCALED_MIN: f64 = -f64::MAX / KAPPA;

/// The CIELAB function f of the ratio t = v / vn (vn > 0 finite), finite for every finite v.
#[inline]
fn lab_f(v: f64, vn: f64) -> f64 {
    let t = v / vn;
    if t > EPSILON {
        if t.is_finite() {
            cbrt(t)
        } else {
            // v / vn overflowed (a tiny white): ∛v / ∛vn ≤ 5.7e102 / 1.7e-108 is finite.
            cbrt(v) / cbrt(vn)
        }
    } else if t >= LINEAR_UNSCALED_MIN {
        (KAPPA * t + 16.0) / 116.0
    } else {
        saturate((KAPPA / 116.0) * t) + 16.0 / 116.0
    }
}

impl Xyz {
    /// CIE 1976 L\*a\*b\* relative to the reference `white` (same scale as `self`, normally the
    /// illuminant's white with Y = 1).
    ///
    /// L\* = 116 f(Y/Yn) − 16, a\* = 500 (f(X/Xn) − f(Y/Yn)), b\* = 200 (f(Y/Yn) − f(Z/Zn)), with
    /// f(t) = ∛t for t > ε and (κ t + 16)/116 otherwise, ε = 216/24389, κ = 24389/27 (the exact
    /// rational constants of CIE 15:2004, continuous at ε). L\* is 100 for the white.
    ///
    /// Finite for every finite `self`: a ratio that overflows is taken through ∛X / ∛Xn, and a
    /// result whose exact value exceeds f64::MAX (large *negative* components, which have no
    /// physical meaning, give |L\*| beyond it) saturates at ±f64::MAX. NaN stays NaN.
    ///
    /// ```
    /// use diffraction::color::{WhitePoint, Xyz};
    /// let white = Xyz::new(0.95047, 1.0, 1.08883);
    /// let lab = white.scale(0.5).to_lab(WhitePoint::new(white)?);
    /// assert!((lab.l - 76.0693).abs() < 1e-4);
    /// assert!(lab.a.abs() < 1e-12 && lab.b.abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn to_lab(self, white: WhitePoint) -> Lab {
        let w = white.xyz;
        let fx = lab_f(self.x, w.x);
        let fy = lab_f(self.y, w.y);
        let fz = lab_f(self.z, w.z);
        Lab {
            l: saturate(116.0 * fy - 16.0),
            a: saturate(500.0 * saturate(fx - fy)),
            b: saturate(200.0 * saturate(fy - fz)),
        }
    }
}

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

    /// The CIEDE2000 colour difference ΔE₀₀ to `other`, with the parametric factors
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
    /// Finite for every finite input: components are first clamped to ±1e150 (far beyond any real
    /// colour, whose CIELAB components are below 10³), which keeps every square of the formula finite.
    ///
    /// ```
    /// use diffraction::color::Lab;
    /// let a = Lab::new(50.0, 2.5, 0.0);
    /// let b = Lab::new(73.0, 25.0, -18.0);
    /// assert!((a.delta_e2000(b) - 27.1492).abs() < 1e-4);
    /// assert_eq!(a.delta_e2000(a), 0.0);
    /// assert!(Lab::new(50.0, 1e50, 0.0).delta_e2000(a).is_finite());
    /// let (c, d) = (Lab::new(50.0, 2.6772, -79.7751), Lab::new(50.0, 0.0, -82.7485));
    /// assert!((c.delta_e2000(d) - 2.0425).abs() < 1e-4); // Sharma et al.'s first pair
    /// ```
    #[inline]
    #[must_use]
    pub fn delta_e2000(self, other: Lab) -> f64 {
        ciede2000(self, other)
    }
}

/// 25⁷, the chroma constant of CIEDE2000.
const POW25_7: f64 = 6_103_515_625.0;

#[inline]
fn pow7(x: f64) -> f64 {
    let x2 = x * x;
    x2 * x2 * x2 * x
}

/// Above this chroma C⁷/(C⁷ + 25⁷) is 1 in `f64` (25⁷/C⁷ < 1e-270), and C⁷ could overflow.
const CHROMA_RATIO_ONE: f64 = 1e40;

/// C⁷ / (C⁷ + 25⁷) for C ≥ 0, without overflowing C⁷.
#[inline]
fn chroma_ratio(c: f64) -> f64 {
    if c > CHROMA_RATIO_ONE {
        1.0
    } else {
        let c7 = pow7(c);
        c7 / (c7 + POW25_7)
    }
}

/// |L\*|, |a\*|, |b\*| are clamped to this before ΔE2000: then every square and product of the
/// formula (at most about 1e301) stays finite. CIELAB components of real colours are below 10³.
const DE2000_COMPONENT_MAX: f64 = 1e150;

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

/// CIEDE2000 (see [`Lab::delta_e2000`]).
fn ciede2000(lab1: Lab, lab2: Lab) -> f64 {
    let m = |v: f64| v.clamp(-DE2000_COMPONENT_MAX, DE2000_COMPONENT_MAX);
    let (l1, a1, b1) = (m(lab1.l), m(lab1.a), m(lab1.b));
    let (l2, a2, b2) = (m(lab2.l), m(lab2.a), m(lab2.b));

    // Eqs. 2-7: C*, G, a', C', h'.
    let c1 = sqrt(a1 * a1 + b1 * b1);
    let c2 = sqrt(a2 * a2 + b2 * b2);
    let g = 0.5 * (1.0 - sqrt(chroma_ratio((c1 + c2) / 2.0)));
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
    let r_c = 2.0 * sqrt(chroma_ratio(c_bar_p));
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
