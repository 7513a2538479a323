//! What the input sweeps share (`tests/surfaces_sweep.rs` and `tests/conical_surfaces_sweep.rs`,
//! which include `support/rng.rs` as `rng` beside it): the bounds their checks allow and the
//! draw of a hostile number. Each sweep keeps its own pool of extreme values.

#![allow(dead_code)]

use crate::rng::Rng;

/// How far a sum over orders may exceed 1: the rounding of a sum of at most a few hundred
/// terms each ≤ 1, each rescaled once (a few ulps per term).
pub const SUM_ROUNDING: f64 = 1e-12;
/// The longest refusal message accepted (strings are quoted to 40 characters).
pub const MAX_MESSAGE: usize = 400;

/// A number from `extremes`, or random in [lo, hi), or a random bit pattern's float (NaN and
/// the infinities included).
pub fn value(r: &mut Rng, extremes: &[f64], lo: f64, hi: f64) -> f64 {
    match r.next_u64() % 8 {
        0 => extremes[(r.next_u64() % extremes.len() as u64) as usize],
        1 => f64::from_bits(r.next_u64()),
        _ => lo + (hi - lo) * r.next_f64(),
    }
}
