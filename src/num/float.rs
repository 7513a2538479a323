//! The two floating-point precisions the crate accepts, behind one sealed trait.

use core::fmt::{Debug, Display};
use core::ops::{Add, Div, Mul, Neg, Sub};

mod sealed {
    /// Operations in the caller's own precision; only the naive comparison kernels use them.
    pub trait Sealed {
        fn sin_native(self) -> Self;
    }
    impl Sealed for f32 {
        #[inline]
        fn sin_native(self) -> Self {
            crate::num::math::sinf(self)
        }
    }
    impl Sealed for f64 {
        #[inline]
        fn sin_native(self) -> Self {
            crate::num::math::sin(self)
        }
    }
}

pub(crate) use sealed::Sealed;

/// `f32` or `f64`: the precisions every kernel accepts.
///
/// The trait is sealed (it cannot be implemented outside this crate). The stable kernels
/// evaluate in `f64` whatever the argument type and round the result once to the caller's
/// precision, so an `f32` call is as accurate as its `f32` argument allows.
///
/// ```
/// use diffraction::kernel::n_slit_cycles;
/// let a: f32 = n_slit_cycles(3.0_f32, 1000);
/// let b: f64 = n_slit_cycles(3.0_f64, 1000);
/// assert_eq!(a, 1.0);
/// assert_eq!(b, 1.0);
/// ```
pub trait Float:
    Sealed
    + Copy
    + Debug
    + Display
    + Default
    + PartialOrd
    + Send
    + Sync
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + 'static
{
    /// Widens to `f64` (exact).
    ///
    /// ```
    /// use diffraction::Float;
    /// assert_eq!(0.5f32.to_f64(), 0.5);
    /// assert_ne!(0.1f32.to_f64(), 0.1f64); // exact: the f32 nearest 0.1 is not the f64 nearest
    /// ```
    fn to_f64(self) -> f64;
    /// Narrows from `f64`, rounding to nearest.
    ///
    /// ```
    /// use diffraction::Float;
    /// assert_eq!(f32::from_f64(0.1), 0.1f32); // to nearest
    /// assert_eq!(f64::from_f64(0.1), 0.1);
    /// ```
    fn from_f64(value: f64) -> Self;
    /// Converts a small integer exactly (|n| < 2^24).
    ///
    /// ```
    /// use diffraction::Float;
    /// assert_eq!(f32::from_u32(5000), 5000.0f32);
    /// assert_eq!(f64::from_u32(5000), 5000.0);
    /// ```
    fn from_u32(n: u32) -> Self;
}

impl Float for f32 {
    #[inline]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline]
    fn from_f64(value: f64) -> Self {
        value as f32
    }
    #[inline]
    fn from_u32(n: u32) -> Self {
        n as f32
    }
}

impl Float for f64 {
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn from_f64(value: f64) -> Self {
        value
    }
    #[inline]
    fn from_u32(n: u32) -> Self {
        n as f64
    }
}
