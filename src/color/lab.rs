//! CIE 1976 L*a*b* and the CIEDE2000 colour difference.

use super::Xyz;
use crate::math::{atan2, cbrt, cos, exp, sin, sqrt};

impl Xyz {
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
