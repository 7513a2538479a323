//! The layout every colour table shares: the band, the graded grid's blocks (their bit layout,
//! the end of the first block, the caps), the tolerance's dark share and the work units of one
//! colour evaluation.

use crate::Grating;

/// Blocks per octave of u, as a power of two: the lookup reads the block from the exponent and the
/// top `SUB_BITS` bits of the mantissa.
const SUB_BITS: u32 = 3;
/// Right shift of the bits of a positive f64 that leaves (exponent, top mantissa bits).
pub(super) const SHIFT: u32 = 52 - SUB_BITS;
/// The largest |u| of unit directions.
pub(super) const U_MAX: f64 = 2.0;
/// Shortest wavelength of the band, nm: order 0's first zero is at u = λ/(N·d), at least this
/// over N·d.
pub(super) const LAMBDA_MIN_NM: f64 = 360.0;
/// Longest wavelength of the band, nm: the smallest phase over the band is d·|u|/830.
pub(super) const LAMBDA_MAX_NM: f64 = 830.0;
/// The first block [0, u₀) ends below λ_min/(`LOBE_FRACTION`·N·d): 1 − F_N < π²/(3·20²) < 1 %.
const LOBE_FRACTION: f64 = 20.0;
/// The first block ends at least here, 2⁻⁶⁴, so that there are at most 65 octaves (520 blocks,
/// 1041 initial nodes) whatever N·d is; a lobe narrower than that (N·d > 10¹⁹ nm) is resolved
/// inside the first block, up to its 1024 intervals.
pub(super) const MIN_U_LO: f64 = 1.0 / 18_446_744_073_709_551_616.0;
/// Where d·|u| is below this (nm), order 0's half period (x = d·|u|/λ < ½) reaches into the band
/// (λ ≤ 830 nm): `Asymptotic`'s bound there is relative to order 0's own light, so a node there
/// is `Strategy::EXACT` unless the colour is dark enough (see `ColorTable::new`).
pub(super) const ORDER0_HALF_PERIOD_NM: f64 = 415.0;
/// Most intervals in one block (1/8 octave): a spacing of u/8192, fine enough for the band-end
/// steps of N ≤ 1000 (relative width 1/(m·N)); narrower steps cannot be resolved and must not
/// take the whole node budget.
pub(super) const MAX_BLOCK_INTERVALS: usize = 1024;
/// An interval shorter than this fraction of its cell is averaged as the lookup at its midpoint
/// (the difference is of order (fraction)² of the cell's curvature; the cumulative form would
/// lose digits instead).
pub(super) const TINY_FRACTION: f64 = 1.0 / (1u64 << 20) as f64;
/// The share of the accuracy a node may use where `Exact` would otherwise be taken: the
/// tolerance in the dark is (6/29)² = 0.043 of the accuracy (see `grid::tolerance`), so a
/// strategy whose bound meets this share of it keeps every channel inside its tolerance.
pub(super) const DARK_SHARE: f64 = (6.0 / 29.0) * (6.0 / 29.0);
/// The smallest accuracy at which nodes are `Strategy::ASYMPTOTIC` (`ColorTable::ASYMPTOTIC_ACCURACY`).
pub(super) const ASYMPTOTIC_ACCURACY: f64 = 1e-4;

/// 2^⌊log₂ x⌋ for positive finite x (the smallest normal number for smaller x).
pub(super) fn power_of_two_below(x: f64) -> f64 {
    let x = x.max(f64::MIN_POSITIVE);
    f64::from_bits(x.to_bits() & !((1u64 << 52) - 1))
}

/// The block boundaries of the layout with block 0 ending at `u_lo`: 0, u_lo, then every
/// 1/2^SUB_BITS of an octave up to 2.
pub(super) fn bounds(u_lo: f64) -> alloc::vec::Vec<f64> {
    let base_key = u_lo.to_bits() >> SHIFT;
    let end_key = U_MAX.to_bits() >> SHIFT;
    let mut out = alloc::vec::Vec::with_capacity((end_key - base_key + 2) as usize);
    out.push(0.0);
    for key in base_key..=end_key {
        out.push(f64::from_bits(key << SHIFT));
    }
    out
}

/// The end u_lo of a finite grating's first block, 2^⌊log₂(360 nm/(20·N·d))⌋ within [2⁻⁶⁴, 1],
/// and whether order 0's lobe is narrower than that block (N·d > 360/(20·2⁻⁶⁴) nm: not
/// resolved).
pub(super) fn lobe_block(grating: &Grating) -> (f64, bool) {
    let (n, d) = (grating.slits().as_f64(), grating.period_nm());
    let lobe_end = LAMBDA_MIN_NM / (LOBE_FRACTION * n * d);
    let u_lo = power_of_two_below(lobe_end).clamp(MIN_U_LO, 1.0);
    (u_lo, lobe_end < MIN_U_LO || lobe_end.is_nan())
}

/// The end of the first block of an N = ∞ grating's table, 2^⌊log₂(360 nm/d)⌋ within
/// [2⁻⁶⁴, 1] (no order reaches the band below 360 nm/d); that block is always tabulated.
pub(super) fn comb_block(grating: &Grating) -> (f64, bool) {
    (
        power_of_two_below(LAMBDA_MIN_NM / grating.period_nm()).clamp(MIN_U_LO, 1.0),
        false,
    )
}

/// The work units of one colour evaluation at q = d·|u| (see `ColorTable::MAX_WORK`).
pub(super) fn work_units(q: f64) -> usize {
    const ORDERS_PER_UNIT: f64 = 1024.0;
    const MOST_ORDERS: f64 = 4096.0;
    let orders = q * (1.0 / LAMBDA_MIN_NM - 1.0 / LAMBDA_MAX_NM);
    let orders = if orders.is_nan() {
        MOST_ORDERS
    } else {
        orders.clamp(0.0, MOST_ORDERS)
    };
    1 + (orders / ORDERS_PER_UNIT) as usize
}
