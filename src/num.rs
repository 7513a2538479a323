//! Numerics: the stable slit kernels, special functions, quadrature, the few complex
//! operations, Bessel functions, the `Float` trait, `std`/`libm` maths and the rule for random
//! numbers.

#[cfg(any(feature = "relief", feature = "baselines"))]
pub(crate) mod bessel;
#[cfg(any(feature = "relief", feature = "baselines"))]
pub(crate) mod complex;
pub(crate) mod float;
pub mod kernel;
pub(crate) mod math;
pub(crate) mod quadrature;
pub(crate) mod random;
pub(crate) mod special;
