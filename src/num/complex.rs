//! The few complex operations the crate needs: the Fresnel equations and the Fourier
//! coefficients of a relief (`relief`), and the binary profile's coefficients (Stam's model).
//! No complex-number dependency: these are all of them, with the crate's own `std`/`libm`
//! maths.

use core::ops::{Add, Mul, Sub};

#[cfg(feature = "relief")]
use crate::num::math;

/// A complex number re + i·im.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Complex {
    pub(crate) re: f64,
    pub(crate) im: f64,
}

impl Complex {
    /// 0.
    #[cfg(feature = "relief")]
    pub(crate) const ZERO: Complex = Complex { re: 0.0, im: 0.0 };

    /// re + i·im.
    #[inline]
    pub(crate) const fn new(re: f64, im: f64) -> Complex {
        Complex { re, im }
    }

    /// e^{iθ}.
    #[cfg(all(feature = "relief", feature = "alloc"))]
    #[inline]
    pub(crate) fn cis(theta: f64) -> Complex {
        Complex::new(math::cos(theta), math::sin(theta))
    }

    /// |z|².
    #[inline]
    pub(crate) fn norm_sqr(self) -> f64 {
        self.re * self.re + self.im * self.im
    }

    /// z·t for real t.
    #[inline]
    pub(crate) fn scale(self, t: f64) -> Complex {
        Complex::new(self.re * t, self.im * t)
    }

    /// The principal square root (Re ≥ 0, and Im of the same sign as Im z), without
    /// cancellation: the larger part comes from √((|z| + |Re z|)/2), the other from Im z over it.
    #[cfg(feature = "relief")]
    pub(crate) fn sqrt(self) -> Complex {
        let r = math::sqrt(self.norm_sqr());
        if r == 0.0 {
            return Complex::ZERO;
        }
        let t = math::sqrt(0.5 * (r + self.re.abs()));
        if self.re >= 0.0 {
            Complex::new(t, 0.5 * self.im / t)
        } else {
            Complex::new(0.5 * self.im.abs() / t, t.copysign(self.im))
        }
    }
}

impl Add for Complex {
    type Output = Complex;
    #[inline]
    fn add(self, o: Complex) -> Complex {
        Complex::new(self.re + o.re, self.im + o.im)
    }
}

impl Sub for Complex {
    type Output = Complex;
    #[inline]
    fn sub(self, o: Complex) -> Complex {
        Complex::new(self.re - o.re, self.im - o.im)
    }
}

impl Mul for Complex {
    type Output = Complex;
    #[inline]
    fn mul(self, o: Complex) -> Complex {
        Complex::new(
            self.re * o.re - self.im * o.im,
            self.re * o.im + self.im * o.re,
        )
    }
}

#[cfg(all(test, feature = "relief"))]
mod tests {
    use super::Complex;

    #[test]
    fn square_root_squares_back_on_every_quadrant() {
        for &(re, im) in &[
            (4.0, 0.0),
            (-4.0, 0.0),
            (-4.0, -0.0),
            (0.0, 2.0),
            (-3.0, 4.0),
            (-3.0, -4.0),
            (1e-300, 1e-300),
            (-1.0, 1e-30),
        ] {
            let z = Complex::new(re, im);
            let r = z.sqrt();
            assert!(r.re >= 0.0);
            let back = r * r;
            let scale = z.norm_sqr().sqrt();
            assert!(
                (back - z).norm_sqr().sqrt() <= 4.0 * f64::EPSILON * scale,
                "{z:?}"
            );
        }
        assert_eq!(Complex::new(-4.0, 0.0).sqrt(), Complex::new(0.0, 2.0));
        assert_eq!(Complex::new(-4.0, -0.0).sqrt(), Complex::new(0.0, -2.0));
        assert_eq!(Complex::ZERO.sqrt(), Complex::ZERO);
    }
}
