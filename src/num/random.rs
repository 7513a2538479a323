//! The crate's one rule for the caller's uniform random numbers.
//!
//! Their names follow pbrt-v4 in every public signature: `uc` for one number, `u2` for a pair
//! (a `DVec2`), so that `u` is only ever the phase projection u = (wi + wo)·t.

use crate::num::math;

/// The crate's one rule for a random number a caller passes where a uniform number in [0, 1) is
/// expected (every sampler of the crate applies it): a value in [0, 1) is used as it
/// is, any other finite value is taken modulo 1 (so a generator that returns 1.0 or values
/// beyond [0, 1) still gives uniform samples), and a non-finite value (NaN, ±∞: a bug in the
/// caller's generator) is taken as 0, so no sampler panics or returns NaN because of it.
///
/// ```
/// use diffraction::unit_random;
/// assert_eq!(unit_random(0.25), 0.25);
/// assert_eq!(unit_random(1.25), 0.25);
/// assert_eq!(unit_random(-0.75), 0.25);
/// assert_eq!(unit_random(1.0), 0.0);
/// assert_eq!(unit_random(f64::NAN), 0.0);
/// assert!(unit_random(-1e-300) < 1.0); // never 1
/// ```
#[inline]
#[must_use]
pub fn unit_random(uc: f64) -> f64 {
    if (0.0..1.0).contains(&uc) {
        return uc;
    }
    if !uc.is_finite() {
        return 0.0;
    }
    let r = uc - math::floor(uc);
    // uc just below an integer rounds to r = 1; that is uc ≡ 0 (mod 1) to its precision.
    if r < 1.0 {
        r
    } else {
        0.0
    }
}
