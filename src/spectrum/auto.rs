//! `Auto`: the cheapest strategy whose error bound meets a requested accuracy.

use super::bounds::{self, accuracy_floor};
use super::strategy::StrategyKind;
use super::{Spectral, Strategy, BAND};
use crate::num::kernel::sinpi;
use crate::num::math::rint;
use crate::{Grating, Slits};

/// Where the band holds at most this many lobes of F_N, `Exact` (which integrates every lobe
/// with an 8-point rule) costs no more than the peak search's treatment of the band ends, and
/// is chosen whatever the accuracy.
const EXACT_BELOW_LOBES: f64 = 64.0;

impl Spectral {
    /// The strategy `strategy` resolves to for this grating at u: itself, unless it is
    /// [`Strategy::auto`]`(a)`, which becomes the cheapest strategy whose bound
    /// ([`Strategy::bound`], read from the table in [`bounds`]) meets `a`,
    /// relative to the accuracy unit. The order-0 terms of the bounds are scaled by the largest
    /// Y that order 0's half period can bring into the band, in units of the unit's floor. The
    /// peak search is taken only where the band holds more than 64 lobes, then `Asymptotic`,
    /// then `Exact`.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let s = Spectral::new(Illuminant::D65);
    /// let auto = Strategy::auto(1e-3)?;
    /// let few = Grating::new(1600.0, 800.0, 3)?; // 3 lobes in the band: exact is cheap
    /// assert_eq!(s.choose(&few, 0.4, auto), Strategy::EXACT);
    /// let many = Grating::new(1600.0, 800.0, 100_000)?; // 8/N = 8e-5 meets 1e-3
    /// assert_eq!(s.choose(&many, 0.4, auto), Strategy::PEAK_SEARCH);
    /// let cd = Grating::new(1600.0, 800.0, 21)?; // 8/N is too coarse; 5e-4 meets 1e-3
    /// assert_eq!(s.choose(&cd, 0.4, auto), Strategy::ASYMPTOTIC);
    /// assert_eq!(s.choose(&cd, 0.4, Strategy::auto(1e-4)?), Strategy::EXACT);
    /// assert_eq!(s.choose(&cd, 0.4, Strategy::PEAK_SEARCH), Strategy::PEAK_SEARCH); // not auto
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn choose(&self, grating: &Grating, u: f64, strategy: Strategy) -> Strategy {
        let StrategyKind::Auto { accuracy } = strategy.kind() else {
            return strategy;
        };
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return Strategy::PEAK_SEARCH,
        };
        let q = grating.period_nm() * u.abs();
        let lobes = n * q * (1.0 / BAND.min_nm() - 1.0 / BAND.max_nm());
        // Order 0's half period in the band: its colour is at most F_N(x_lo) ≤ 1/(N·sin πx_lo)²
        // of the white (Y = 1); in units of the accuracy floor (the unit is at least the floor)
        // that is F_N(x_lo) / accuracy_floor(N), the factor of each strategy's order-0 bound.
        let x_lo = q / BAND.max_nm();
        let to_brightest = 1.0 / accuracy_floor(n);
        let order0 = if x_lo >= 0.5 {
            0.0
        } else if x_lo * n < 1.0 {
            to_brightest
        } else {
            let f = 1.0 / (n * sinpi(x_lo - rint(x_lo)));
            f * f * to_brightest
        };
        let fits = |s: Strategy| {
            s.bound(n as u32)
                .is_some_and(|b| b.of_colour == 0.0 && b.orders + b.order0 * order0 <= accuracy)
        };
        if lobes > EXACT_BELOW_LOBES && fits(Strategy::PEAK_SEARCH) {
            Strategy::PEAK_SEARCH
        } else if n >= bounds::ASYMPTOTIC_MIN_SLITS as f64 && fits(Strategy::ASYMPTOTIC) {
            Strategy::ASYMPTOTIC
        } else {
            Strategy::EXACT
        }
    }
}
