//! `Auto`: the cheapest strategy whose error bound meets a requested accuracy.

use super::asymptotic;
use super::{Spectral, Strategy, BAND, DEFAULT_ACCURACY};
use crate::kernel::sinpi;
use crate::math::rint;
use crate::{Grating, Slits};

/// The peak search's error bound is `PEAK_SEARCH_BOUND_N / N` of the brightest order. Its
/// leading error is the far tails of each order (the mass of F_N spread over the period, with
/// E·S·cmf not constant there), which falls as 1/N; the worst measured over the grid of
/// `tests/spectral_reference.rs` (d = 400-100 000 nm, N = 1-10⁶, both illuminants) is 3.5/N, and
/// 8 keeps a margin above it.
const PEAK_SEARCH_BOUND_N: f64 = 8.0;

/// The peak search integrates order 0's light coarsely (4-point Gauss-Legendre over pieces of
/// at most 16 nm, sin²(Nα) → ½ over narrow lobes): its error is below this fraction of order 0's
/// own colour (measured over the same grid).
const ORDER0_RELATIVE_ERROR: f64 = 2e-3;

/// N times the Y of the brightest order: an order at λ_m carries about
/// S·E(λ_m)·ȳ(λ_m)·λ_m/(|m|·N)/∫E·ȳ (its peak value times its equivalent width), which is largest
/// for the first order at the peak of ȳ (555 nm, ȳ = 1, S ≤ 1, flat E):
/// 555 nm/∫ȳ dλ = 555/106.857 ≈ 5.2. It converts errors of order 0's light into the
/// brightest-order scale of the bounds.
const BRIGHTEST_ORDER_Y_TIMES_N: f64 = 5.2;

/// Where the band holds at most this many lobes of F_N, `Exact` (which integrates every lobe
/// with an 8-point rule) costs no more than the peak search's treatment of the band ends, and
/// is chosen whatever the accuracy.
const EXACT_BELOW_LOBES: f64 = 64.0;

impl Spectral {
    /// The strategy [`Strategy::Auto`] picks for `accuracy`: the cheapest whose error bound,
    /// relative to the XYZ of the brightest order of this grating, is within it.
    ///
    /// Bounds (measured over the test grids of `tests/spectral_reference.rs` and
    /// `tests/asymptotic.rs`, and kept with a margin): peak search 8/N (worst measured 3.5/N),
    /// plus 2e-3 of the order-0 light where order 0's half period reaches into the band
    /// (d·|u|/830 nm < ½); `Asymptotic` 5e-4 (worst 1.4e-4) plus 1e-3 of the order-0 light
    /// (worst 5.7e-4), for N ≥ 5; `Exact` 1e-7. The peak search is taken only where the band
    /// holds more than 64 lobes, then `Asymptotic`, then `Exact`.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let s = Spectral::new(Illuminant::D65);
    /// let few = Grating::new(1600.0, 800.0, 3)?; // 3 lobes in the band: exact is cheap
    /// assert_eq!(s.choose(&few, 0.4, 1e-3), Strategy::Exact);
    /// let many = Grating::new(1600.0, 800.0, 100_000)?; // 8/N = 8e-5 meets 1e-3
    /// assert_eq!(s.choose(&many, 0.4, 1e-3), Strategy::PeakSearch { refine: false });
    /// let cd = Grating::new(1600.0, 800.0, 21)?; // 8/N is too coarse; 5e-4 meets 1e-3
    /// assert_eq!(s.choose(&cd, 0.4, 1e-3), Strategy::Asymptotic);
    /// assert_eq!(s.choose(&cd, 0.4, 1e-4), Strategy::Exact);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn choose(&self, grating: &Grating, u: f64, accuracy: f64) -> Strategy {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return Strategy::PeakSearch { refine: false },
        };
        let q = grating.period_nm() * u.abs();
        let lobes = n * q * (1.0 / BAND.min_nm() - 1.0 / BAND.max_nm());
        let accuracy = if accuracy.is_finite() && accuracy > 0.0 {
            accuracy
        } else {
            DEFAULT_ACCURACY
        };
        // Order 0's half period in the band: its colour is at most F_N(x_lo) ≤ 1/(N·sin πx_lo)²
        // of the white (Y = 1), integrated to ORDER0_RELATIVE_ERROR of itself; on the scale of
        // the brightest order (Y ≈ BRIGHTEST_ORDER_Y_TIMES_N / N) that error is
        // ORDER0_RELATIVE_ERROR · F_N(x_lo) · N / BRIGHTEST_ORDER_Y_TIMES_N.
        let x_lo = q / BAND.max_nm();
        // (The same with asymptotic::ORDER0_BOUND for `Asymptotic`.)
        let to_brightest = n / BRIGHTEST_ORDER_Y_TIMES_N;
        let order0 = if x_lo >= 0.5 {
            0.0
        } else if x_lo * n < 1.0 {
            to_brightest
        } else {
            let f = 1.0 / (n * sinpi(x_lo - rint(x_lo)));
            f * f * to_brightest
        };
        if lobes > EXACT_BELOW_LOBES
            && PEAK_SEARCH_BOUND_N / n + ORDER0_RELATIVE_ERROR * order0 <= accuracy
        {
            Strategy::PeakSearch { refine: false }
        } else if n >= asymptotic::MIN_SLITS
            && asymptotic::ORDERS_BOUND + asymptotic::ORDER0_BOUND * order0 <= accuracy
        {
            Strategy::Asymptotic
        } else {
            Strategy::Exact
        }
    }
}
