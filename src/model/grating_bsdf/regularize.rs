//! Near-delta lobes: where a renderer should treat the grating as specular, and pbrt-v4's
//! regularisation that widens narrow lobes for the paths where they only add noise.

use super::GratingBsdf;
use crate::num::math;
use crate::optics::groove::{GrooveKind, GrooveSpread};
use crate::{Band, Grating, Slits};

/// Lobes narrower than this half-width in u (at the band's shortest wavelength) are reported by
/// [`GratingBsdf::is_near_specular`].
pub(crate) const NEAR_SPECULAR_HALF_WIDTH: f64 = 1e-6;
/// [`regularize`](crate::Bsdf::regularize) widens lobes whose half-width at 550 nm is below this
/// (in u or v).
pub(crate) const REGULARIZE_MAX_HALF_WIDTH: f64 = 0.03;
/// The smallest half-width [`regularize`](crate::Bsdf::regularize) produces.
pub(crate) const REGULARIZE_MIN_HALF_WIDTH: f64 = 0.01;
/// The wavelength at which [`regularize`](crate::Bsdf::regularize) measures widths, nm.
const REGULARIZE_REFERENCE_NM: f64 = 550.0;

/// Regularised half-width: pbrt's rule clamp(2h, min, max) below max, else unchanged.
fn widen(h: f64) -> f64 {
    if h < REGULARIZE_MAX_HALF_WIDTH {
        (2.0 * h).clamp(REGULARIZE_MIN_HALF_WIDTH, REGULARIZE_MAX_HALF_WIDTH)
    } else {
        h
    }
}

impl GratingBsdf {
    /// Whether the lobes at 360 nm are narrower than `NEAR_SPECULAR_HALF_WIDTH` in u or v
    /// (advice for `f32` renderers, see the [module docs](super)); always `false` for N = ∞ and
    /// ideal grooves, which are specular already.
    ///
    /// ```
    /// # use diffraction::{Grating, GratingBsdf};
    /// assert!(GratingBsdf::new(Grating::new(1600.0, 800.0, 1_000_000)?).is_near_specular());
    /// assert!(!GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?).is_near_specular());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn is_near_specular(&self) -> bool {
        let l = Band::VISIBLE.min_nm();
        let hu = self.lobe_half_width(l);
        if self.groove.is_delta() {
            return false;
        }
        let hv = self.groove.width(l);
        hu > 0.0 && (hu < NEAR_SPECULAR_HALF_WIDTH || hv < NEAR_SPECULAR_HALF_WIDTH)
    }

    /// The model after [`Bsdf::regularize`](crate::Bsdf::regularize): lobes narrower than
    /// `REGULARIZE_MAX_HALF_WIDTH` at 550 nm widened to clamp(2h,
    /// `REGULARIZE_MIN_HALF_WIDTH`, `REGULARIZE_MAX_HALF_WIDTH`): in u through N
    /// (h = λ/(N·d); N = ∞ counts as h = 0; N never grows), in v through the coherence length
    /// (h = λ/L), the Gaussian σ, or an ideal groove becoming a Gaussian of σ = 0.01. The orders,
    /// their efficiencies and the albedo's Parseval bound do not change.
    pub(super) fn regularized(&self) -> GratingBsdf {
        let l = REGULARIZE_REFERENCE_NM;
        let d = self.grating.period_nm();
        let hu = match self.grating.slits() {
            Slits::Finite(n) => l / (n as f64 * d),
            Slits::Infinite => 0.0,
        };
        let mut grating = self.grating;
        if hu < REGULARIZE_MAX_HALF_WIDTH {
            let target = widen(hu);
            let n_new = math::floor(l / (d * target)).clamp(1.0, u32::MAX as f64) as u32;
            let n_new = match self.grating.slits() {
                Slits::Finite(n) => n_new.min(n),
                Slits::Infinite => n_new,
            };
            if let Ok(g) =
                Grating::with_slits(d, self.grating.slit_width_nm(), Slits::Finite(n_new.max(1)))
            {
                grating = g;
            }
        }
        let widened = match self.groove.kind() {
            GrooveKind::CoherenceLength { length_nm } => {
                GrooveSpread::coherence_length_clamped(l / widen(l / length_nm))
            }
            GrooveKind::Gaussian { sigma } => GrooveSpread::gaussian(widen(sigma)).ok(),
            GrooveKind::Ideal => GrooveSpread::gaussian(REGULARIZE_MIN_HALF_WIDTH).ok(),
        };
        let groove = widened.unwrap_or(self.groove);
        GratingBsdf::build(grating, groove, self.efficiency.clone())
    }
}
