//! Elementary functions behind one name, from `std` or from `libm`.
//!
//! The crate's own kernels avoid these on their hot paths (see `sinpi` in `kernel.rs`); they are
//! used for directions (square roots) and the radian-form entry points.

#[cfg(feature = "std")]
mod imp {
    #[inline]
    pub fn sqrt(x: f64) -> f64 {
        x.sqrt()
    }
    #[inline]
    pub fn sin(x: f64) -> f64 {
        x.sin()
    }
    #[inline]
    pub fn cos(x: f64) -> f64 {
        x.cos()
    }
    #[cfg(any(feature = "relief", feature = "baselines", feature = "delta-e"))]
    #[inline]
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
    #[inline]
    pub fn sinf(x: f32) -> f32 {
        x.sin()
    }
    #[inline]
    pub fn floor(x: f64) -> f64 {
        x.floor()
    }
    #[inline]
    pub fn ceil(x: f64) -> f64 {
        x.ceil()
    }
    #[inline]
    pub fn exp(x: f64) -> f64 {
        x.exp()
    }
    #[inline]
    pub fn powf(x: f64, y: f64) -> f64 {
        x.powf(y)
    }
    #[cfg(any(
        feature = "alloc",
        feature = "relief",
        feature = "baselines",
        feature = "delta-e"
    ))]
    #[inline]
    pub fn cbrt(x: f64) -> f64 {
        x.cbrt()
    }
    #[inline]
    pub fn ln(x: f64) -> f64 {
        x.ln()
    }
    #[inline]
    pub fn tanh(x: f64) -> f64 {
        x.tanh()
    }
    #[inline]
    pub fn atanh(x: f64) -> f64 {
        x.atanh()
    }
    #[inline]
    pub fn cosh(x: f64) -> f64 {
        x.cosh()
    }
}

#[cfg(all(not(feature = "std"), feature = "libm"))]
mod imp {
    #[inline]
    pub fn sqrt(x: f64) -> f64 {
        libm::sqrt(x)
    }
    #[inline]
    pub fn sin(x: f64) -> f64 {
        libm::sin(x)
    }
    #[inline]
    pub fn cos(x: f64) -> f64 {
        libm::cos(x)
    }
    #[cfg(any(feature = "relief", feature = "baselines", feature = "delta-e"))]
    #[inline]
    pub fn atan2(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
    #[inline]
    pub fn sinf(x: f32) -> f32 {
        libm::sinf(x)
    }
    #[inline]
    pub fn floor(x: f64) -> f64 {
        libm::floor(x)
    }
    #[inline]
    pub fn ceil(x: f64) -> f64 {
        libm::ceil(x)
    }
    #[inline]
    pub fn exp(x: f64) -> f64 {
        libm::exp(x)
    }
    #[inline]
    pub fn powf(x: f64, y: f64) -> f64 {
        libm::pow(x, y)
    }
    #[cfg(any(
        feature = "alloc",
        feature = "relief",
        feature = "baselines",
        feature = "delta-e"
    ))]
    #[inline]
    pub fn cbrt(x: f64) -> f64 {
        libm::cbrt(x)
    }
    #[inline]
    pub fn ln(x: f64) -> f64 {
        libm::log(x)
    }
    #[inline]
    pub fn tanh(x: f64) -> f64 {
        libm::tanh(x)
    }
    #[inline]
    pub fn atanh(x: f64) -> f64 {
        libm::atanh(x)
    }
    #[inline]
    pub fn cosh(x: f64) -> f64 {
        libm::cosh(x)
    }
}

#[allow(unused_imports)]
pub(crate) use imp::*;

/// Round to the nearest integer, ties to even, exactly, without `std`.
///
/// For |x| < 2^52 adding and subtracting 1.5·2^52 leaves the rounded value (the sum's
/// unit in the last place is 1); larger magnitudes are already integers. Non-finite input
/// comes back non-finite.
#[inline]
pub(crate) fn rint(x: f64) -> f64 {
    const MAGIC: f64 = 6_755_399_441_055_744.0; // 1.5 * 2^52
    if x.abs() < 4_503_599_627_370_496.0 {
        // 2^52
        (x + MAGIC) - MAGIC
    } else {
        x
    }
}

#[cfg(test)]
mod tests {
    use super::rint;

    #[test]
    fn rint_matches_round_half_even() {
        for &(x, r) in &[
            (0.5, 0.0),
            (1.5, 2.0),
            (2.5, 2.0),
            (-0.5, -0.0),
            (-1.5, -2.0),
            (0.49999999999999994, 0.0),
            (1e300, 1e300),
            (4503599627370495.5, 4503599627370496.0),
            (-7.25, -7.0),
        ] {
            assert_eq!(rint(x), r, "rint({x})");
        }
        assert!(rint(f64::NAN).is_nan());
        assert_eq!(rint(f64::INFINITY), f64::INFINITY);
    }
}
