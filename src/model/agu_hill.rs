//! The paper's model: the Agu-Hill intensity I(u, λ) = S(β)·F_N(α) of a grating as a spectral
//! reflectance model (eq. 8 with I₀ = 1).

use glam::{DVec3, Vec3};

use crate::model::{both_above, DiffractionBrdf, GratingResponse, PeakSummary, SpectralResponse};
use crate::{Band, Grating, Peak, MAX_ORDERS};

/// The paper's model: the unitless Agu-Hill intensity of a grating, S(β)·F_N(α) at
/// u = (wi + wo)·t = `wi.x + wo.x` (eq. 8, 13), peak 1 at every order's maximum.
///
/// At u ≈ 0 (order 0, step 6) this is the white specular, since F_N(0) = S(0) = 1 at every λ.
/// It is the paper's diffraction term, not a radiometric BRDF: its peaks are 1 whatever N is,
/// so the light an order carries falls as 1/N. The paper's illumination model (eq. 12), which
/// adds ambient and diffuse terms and a diffraction coefficient, is
/// [`Illumination`](crate::Illumination).
///
/// ```
/// use diffraction::{AguHill, DiffractionBrdf, Grating};
/// use glam::DVec3;
/// let m = AguHill::new(Grating::new(1600.0, 800.0, 500)?);
/// let wo = DVec3::new(0.6, 0.0, 0.8);
/// let wi = DVec3::new(-0.6, 0.0, 0.8); // mirror: order 0
/// assert_eq!(m.eval(wo, wi, 550.0), 1.0);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct AguHill {
    grating: Grating,
}

impl AguHill {
    /// The paper's model of `grating`.
    ///
    /// ```
    /// use diffraction::{AguHill, Grating};
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// assert_eq!(AguHill::new(g).grating(), &g);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn new(grating: Grating) -> AguHill {
        AguHill { grating }
    }

    /// The grating.
    ///
    /// ```
    /// use diffraction::{AguHill, Grating};
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert_eq!(m.grating().period_nm(), 1600.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn grating(&self) -> &Grating {
        &self.grating
    }
}

impl DiffractionBrdf for AguHill {
    /// I(u, λ) = S(β)·F_N(α) at u = wi.x + wo.x; 0 below the surface.
    #[inline]
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !both_above(wo, wi) {
            return 0.0;
        }
        self.grating.intensity_f64(wi.x + wo.x, lambda_nm)
    }

    /// The f64 intensity at the f32 directions' u (summed in f64), rounded once.
    #[inline]
    fn eval_f32(&self, wo: Vec3, wi: Vec3, lambda_nm: f32) -> f32 {
        if !both_above(wo.as_dvec3(), wi.as_dvec3()) {
            return 0.0;
        }
        let u = wi.x as f64 + wo.x as f64;
        self.grating.intensity_f64(u, lambda_nm as f64) as f32
    }
}

impl SpectralResponse for AguHill {
    /// The paper applies no cosine to its diffraction term (eq. 12): the response is
    /// [`eval`](DiffractionBrdf::eval).
    #[inline]
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eval(wo, wi, lambda_nm)
    }

    /// The grating's peaks ([`Grating::peaks`]) at u = wi.x + wo.x, at most
    /// [`MAX_ORDERS`] of them.
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !both_above(wo, wi) {
            return PeakSummary::default();
        }
        let peaks = self.grating.peaks(wi.x + wo.x, band);
        let specular = peaks.specular();
        let mut orders = 0;
        for p in peaks.take(MAX_ORDERS as usize) {
            visit(p);
            orders += 1;
        }
        PeakSummary { orders, specular }
    }

    /// The grating itself at u = wi.x + wo.x, scale 1; `None` below the surface and where u
    /// is not finite (directions so far from unit that wi.x + wo.x overflows).
    fn grating_response(&self, wo: DVec3, wi: DVec3) -> Option<GratingResponse> {
        let u = wi.x + wo.x;
        if !(both_above(wo, wi) && u.is_finite()) {
            return None;
        }
        Some(GratingResponse::new(self.grating, u, 1.0))
    }
}
