//! The order efficiencies η_m of a grating: the share of the incident power each diffraction
//! order carries. A concept of its own beside the shape of the orders' lobes (the N-slit factor
//! and the groove spread), so that a physical efficiency model can replace the amplitude reading
//! without touching the lobes or the sampler.

use crate::kernel::single_slit_cycles;

/// Where a grating's order efficiencies come from.
///
/// Today one model: [`Amplitude`](Self::Amplitude), the paper's grating read as an amplitude
/// grating (reflecting strips of width w on an absorbing background, open fraction ρ = w/d):
/// η_m = ρ²·S(π·ρ·m), Σ_m η_m = ρ (Parseval), the same at every angle and wavelength.
///
/// ```
/// use diffraction::grating_bsdf::OrderEfficiency;
/// use diffraction::{Grating, GratingBsdf};
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
/// assert_eq!(b.order_efficiency(), OrderEfficiency::Amplitude);
/// assert_eq!(b.efficiency(0), 0.25); // ρ² with ρ = ½
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum OrderEfficiency {
    /// η_m = ρ²·S(π·ρ·m): an amplitude grating of open fraction ρ (the paper's reading).
    #[default]
    Amplitude,
}

impl OrderEfficiency {
    /// η_m for a grating of open fraction `rho`.
    #[inline]
    pub(crate) fn efficiency(self, rho: f64, order: i64) -> f64 {
        rho * rho * self.relative(rho, order)
    }

    /// η_m/ρ²: the efficiency relative to that of order 0 of a flat strip (the order weights of
    /// the sampler use it).
    #[inline]
    pub(crate) fn relative(self, rho: f64, order: i64) -> f64 {
        match self {
            OrderEfficiency::Amplitude => single_slit_cycles(rho * order as f64),
        }
    }
}
