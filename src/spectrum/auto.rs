//! `Auto`: the cheapest strategy whose error bound meets a requested accuracy.

use super::{Spectral, Strategy, BAND, DEFAULT_ACCURACY};
use crate::kernel::sinpi;
use crate::math::rint;
use crate::{Grating, Slits};

impl Spectral {
    /// The strategy [`Strategy::Auto`] picks for `accuracy`: the cheapest whose error bound,
    /// relative to the XYZ of the brightest order of this grating, is within it.
    ///
    /// Bounds (measured over the test grid of `tests/spectral_reference.rs`, where the worst
    /// is 3.5/N, and kept with a margin): peak search 8/N, plus 2e-3 of the order-0 light where
    /// order 0's half period reaches into the band (d·|u|/830 nm < ½); `Exact` 1e-7. Where the
    /// band holds at most 64 lobes, `Exact` costs no more than the peak search and is chosen.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let s = Spectral::new(Illuminant::D65);
    /// let few = Grating::new(1600.0, 800.0, 3)?; // 3 lobes in the band: exact is cheap
    /// assert_eq!(s.choose(&few, 0.4, 1e-3), Strategy::Exact);
    /// let many = Grating::new(1600.0, 800.0, 100_000)?; // 8/N = 8e-5 meets 1e-3
    /// assert_eq!(s.choose(&many, 0.4, 1e-3), Strategy::PeakSearch { refine: false });
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
        // Order 0's half period in the band: the peak search integrates it coarsely (2e-3 of
        // its own colour). Its colour is at most F_N(x_lo) of the white, and the brightest
        // order is about Y₁ = 555 nm/(N·∫ȳ) ≈ 5.2/N.
        let x_lo = q / BAND.max_nm();
        let order0 = if x_lo >= 0.5 {
            0.0
        } else if x_lo * n < 1.0 {
            2e-3 * n / 5.2
        } else {
            let f = 1.0 / (n * sinpi(x_lo - rint(x_lo)));
            2e-3 * f * f * n / 5.2
        };
        if lobes > 64.0 && 8.0 / n + order0 <= accuracy {
            Strategy::PeakSearch { refine: false }
        } else {
            Strategy::Exact
        }
    }
}
