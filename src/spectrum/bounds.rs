//! The error bounds of the colour strategies: one table, read by `Auto`
//! ([`Spectral::choose`](super::Spectral::choose)), by the colour table
//! ([`ColorTable`](crate::ColorTable)) and by the docs of [`Strategy`](super::Strategy) and
//! [`GenericStrategy`](super::GenericStrategy). Each number is the bound the crate promises,
//! kept above the worst error measured by the tests named beside it.
//!
//! Bounds on the grating paths are relative to the **accuracy unit** ([`accuracy_unit`]): the
//! Y of the grating's brightest diffracted order, floored at [`accuracy_floor`]`(N)` =
//! 555/(N·∫ȳ dλ), the Y of an ideal first-order peak at 555 nm under a flat illuminant (the
//! floor keeps a grating whose orders are all faint from being held to its own darkness).
//!
//! ```
//! use diffraction::spectrum::bounds;
//! // The floor for N = 1000 slits: 555 nm / (1000 · 106.857 nm).
//! let floor = bounds::accuracy_floor(1000.0);
//! assert!((floor * 1000.0 * 106.857 / 555.0 - 1.0).abs() < 1e-5); // ∫ȳ ≈ 106.857 nm
//! assert!(bounds::ASYMPTOTIC_ORDERS < bounds::PEAK_SEARCH_PER_SLIT / 1000.0);
//! ```

use crate::data::cie_data;

/// The peak search's bound is `PEAK_SEARCH_PER_SLIT / N` of the accuracy unit. Its leading
/// error is the far tails of each order (F_N's mass spread over the period, with E·S·cmf not
/// constant there), which falls as 1/N; the worst measured over the grid of
/// `tests/spectral_reference.rs` (d = 400-100 000 nm, N = 1-10⁶, E and D65) is 3.5/N.
pub const PEAK_SEARCH_PER_SLIT: f64 = 8.0;

/// The peak search integrates order 0's light coarsely (4-point Gauss-Legendre over pieces of
/// at most 16 nm, sin²(Nα) → ½ over narrow lobes): its error is below this fraction of order
/// 0's own colour where order 0's lobe reaches the band (measured over the same grid).
pub const PEAK_SEARCH_ORDER0: f64 = 2e-3;

/// `Asymptotic`'s bound where only orders m ≠ 0 reach the band, of the accuracy unit, for
/// N ≥ [`ASYMPTOTIC_MIN_SLITS`] (worst measured 1.3·10⁻⁴, `tests/asymptotic.rs`).
pub const ASYMPTOTIC_ORDERS: f64 = 5e-4;

/// `Asymptotic`'s bound relative to order 0's own light where its half period reaches the band
/// (worst measured 1.9·10⁻⁵, `tests/asymptotic.rs`).
pub const ASYMPTOTIC_ORDER0: f64 = 2e-4;

/// From this many slits on `Asymptotic`'s bound is the corrected peak search's
/// ([`ASYMPTOTIC_ORDERS`], [`ASYMPTOTIC_ORDER0`]: the expansion needs a few lobes per period);
/// below, it is [`ASYMPTOTIC_SMALL_N`], relative to the colour. Up to 7 slits the strategy
/// writes F_N as its N cosines (`src/spectrum/small_n.rs`), whose fixed work is below the
/// peak search's walk there; for 5-7 slits that rule meets both bounds (worst measured
/// 7.4·10⁻⁸ of the accuracy unit and 9.8·10⁻⁵ of the colour, `tests/asymptotic.rs`).
pub const ASYMPTOTIC_MIN_SLITS: u32 = 5;

/// `Asymptotic`'s bound below [`ASYMPTOTIC_MIN_SLITS`] slits, relative to the colour itself
/// (floored at [`DARK_FLOOR`] of the accuracy unit), as for [`EXACT`]: F_N as its cosines, the
/// terms the product rule resolves integrated against the tables, the others by parts with
/// the illuminant's node kinks (the observer's 1 nm rows are not summed). Worst measured
/// 9.8·10⁻⁵ against `Exact` (N = 1-7, d = 400 nm-100 µm, w = d … d/100, E, D65 and A; 6.7·10⁻⁵
/// for N ≤ 4) and 1.8·10⁻⁵ against the Python oracle (N = 1, 2 and 5, `tests/asymptotic.rs`).
pub const ASYMPTOTIC_SMALL_N: f64 = 5e-4;

/// `Exact`'s bound relative to the colour itself (floored at [`DARK_FLOOR`] of the accuracy
/// unit): worst measured 7.9·10⁻¹⁰ against the Python oracle (`tests/spectral_reference.rs`).
pub const EXACT: f64 = 1e-7;

/// Relative bounds of the colour itself (`Exact`, `WINDOWS`) apply to colours down to this
/// fraction of the unit; darker colours are held to this fraction of the unit instead.
pub const DARK_FLOOR: f64 = 1e-3;

/// The generic peak search's bound is `GENERIC_PEAK_SEARCH_PER_SLIT / N_eff` of the model's
/// brightest order (worst measured 3.5/N_eff, `tests/spectral.rs`).
pub const GENERIC_PEAK_SEARCH_PER_SLIT: f64 = 8.0;

/// The generic `WINDOWS` rule's bound relative to the colour itself (floored at
/// [`DARK_FLOOR`] of the brightest order), for models that keep the contract of
/// [`SpectralResponse::peaks`](crate::SpectralResponse::peaks): within 1·10⁻¹⁰ of a 0.01 nm
/// quadrature in `tests/spectral.rs`, which is itself good to 2·10⁻⁶; the bound is what that
/// reference can confirm.
pub const WINDOWS: f64 = 1e-6;

/// The wavelength of the ideal first-order peak that floors the accuracy unit, nm (the peak of
/// ȳ).
pub const FLOOR_PEAK_NM: f64 = 555.0;

/// ∫ȳ dλ over the band, as [`cmf_areas`](crate::data::cie::cmf_areas) integrates it (the same operations in the same
/// order, at compile time, so that the floor costs one division instead of a pass over the
/// table).
const YBAR_AREA: f64 = {
    let rows = (cie_data::LAST_NM - cie_data::FIRST_NM) as usize;
    let mut sum = 0.0;
    let mut i = 0;
    while i < rows {
        let (a0, a1) = (1.0, 1.0);
        let (b0, b1) = (
            cie_data::CIE1931_2DEG[i][1],
            cie_data::CIE1931_2DEG[i + 1][1],
        );
        let mid = 0.25 * (a0 + a1) * (b0 + b1);
        sum += (a0 * b0 + 4.0 * mid + a1 * b1) / 6.0;
        i += 1;
    }
    sum
};

/// The floor of the accuracy unit for N slits: 555/(N·∫ȳ dλ), the Y of an ideal first-order
/// peak (S = 1) at 555 nm under a flat illuminant: the peak value 1 times its equivalent width
/// λ/(|m|·N), over ∫ȳ. `f64::MIN_POSITIVE` for N = ∞ (or N ≤ 0).
///
/// ```
/// use diffraction::spectrum::bounds::accuracy_floor;
/// assert!(accuracy_floor(1.0) > 5.19 && accuracy_floor(1.0) < 5.2);
/// assert_eq!(accuracy_floor(f64::INFINITY), f64::MIN_POSITIVE);
/// ```
#[must_use]
pub fn accuracy_floor(slits: f64) -> f64 {
    let y = FLOOR_PEAK_NM / (slits * YBAR_AREA);
    if y.is_finite() && y > 0.0 {
        y.max(f64::MIN_POSITIVE)
    } else {
        f64::MIN_POSITIVE
    }
}

/// The accuracy unit of a grating: `brightest_y` (the Y of its brightest diffracted order,
/// as the caller measured it) floored at [`accuracy_floor`]`(N)`.
///
/// ```
/// use diffraction::spectrum::bounds::{accuracy_floor, accuracy_unit};
/// assert_eq!(accuracy_unit(0.0, 100.0), accuracy_floor(100.0));
/// assert_eq!(accuracy_unit(1.0, 100.0), 1.0);
/// ```
#[must_use]
pub fn accuracy_unit(brightest_y: f64, slits: f64) -> f64 {
    let floor = accuracy_floor(slits);
    if brightest_y > floor {
        brightest_y
    } else {
        floor
    }
}

/// A strategy's error bound ([`Strategy::bound`](super::Strategy::bound)): the error of every
/// XYZ channel is at most `orders·unit + order0·Y₀ + of_colour·max(|colour|, DARK_FLOOR·unit)`,
/// with `unit` the accuracy unit and Y₀ the Y of order 0's own light where it reaches the band.
///
/// ```
/// use diffraction::spectrum::{bounds, Strategy};
/// let b = Strategy::EXACT.bound(100).unwrap();
/// assert_eq!((b.orders, b.of_colour), (0.0, bounds::EXACT));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Bound {
    /// The part relative to the accuracy unit.
    pub orders: f64,
    /// The part relative to order 0's own light.
    pub order0: f64,
    /// The part relative to the colour itself.
    pub of_colour: f64,
}

impl Bound {
    /// A bound relative to the colour itself only.
    pub(crate) const fn of_colour(of_colour: f64) -> Bound {
        Bound {
            orders: 0.0,
            order0: 0.0,
            of_colour,
        }
    }
}

#[cfg(test)]
mod tests {
    /// The compile-time ∫ȳ is the run-time one to the bit.
    #[test]
    fn ybar_area_matches_the_table() {
        assert_eq!(super::YBAR_AREA, crate::data::cie::cmf_areas()[1]);
    }
}
