//! What the colour integrator needs of a model: [`SpectralResponse`], the peaks it reports
//! ([`PeakSummary`]) and the grating form of a model's response ([`GratingResponse`] with its
//! [`Envelope`] of wavelength).

use glam::DVec3;

use crate::error::{Error, Requirement};
use crate::{Band, Grating, Peak};

/// What [`SpectralResponse::peaks`] found besides the peaks it visited.
///
/// ```
/// use diffraction::{AguHill, Band, Grating, SpectralResponse};
/// use glam::DVec3;
/// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
/// // The mirror direction (u = 0): inside the order-0 lobe, and no order m ≠ 0.
/// let (wo, wi) = (DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.6, 0.0, 0.8));
/// let summary = brdf.peaks(wo, wi, Band::VISIBLE, &mut |_| {});
/// assert_eq!((summary.orders, summary.specular), (0, true));
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub struct PeakSummary {
    /// How many orders m ≠ 0 were visited.
    pub orders: u32,
    /// Whether (wi, wo) lies inside the central order-0 (mirror) lobe for some wavelength of the
    /// band. There the model's light is the white specular, spread over every wavelength, and is
    /// not a peak at one wavelength.
    pub specular: bool,
}

/// What the colour integrator ([`spectrum`](crate::spectrum)) needs of a model: the light it
/// reflects per unit light, where its narrow peaks in wavelength are, and whether it is a
/// multiple of a grating's intensity. A capability a model opts into, separate from its value
/// ([`DiffractionBrdf`](crate::DiffractionBrdf)) and from its sampling ([`Bsdf`](crate::Bsdf)).
///
/// Directions as everywhere in the crate: local frame, `wo` toward the viewer, `wi` toward the
/// light, both above the surface (else nothing is reflected and nothing is visited).
///
/// ```
/// use diffraction::{AguHill, Band, Grating, SpectralResponse};
/// use glam::DVec3;
/// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
/// let (wo, wi) = (DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt()), DVec3::Z);
/// // u = 0.3: first order at 480 nm.
/// let mut seen = vec![];
/// let summary = brdf.peaks(wo, wi, Band::VISIBLE, &mut |p| seen.push(p.wavelength_nm));
/// assert_eq!(summary.orders, 1);
/// assert!((seen[0] - 480.0).abs() < 1e-9);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub trait SpectralResponse {
    /// The light reflected toward `wo` per unit of light arriving from `wi` at `lambda_nm`:
    /// the spectral reflectance whose colour [`Spectral`](crate::spectrum::Spectral)
    /// integrates. For a BRDF f (1/sr, cosine excluded) it is f·cos θi (the radiance toward wo
    /// from a point light of unit irradiance at normal incidence); for the paper's
    /// [`AguHill`](crate::AguHill) it is its intensity S·F_N, with no cosine (its eq. 12).
    /// Finite and ≥ 0 for every input; 0 below the surface.
    ///
    /// ```
    /// use diffraction::{DiffractionBrdf, Grating, GratingBsdf, SpectralResponse};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// assert_eq!(b.response(wo, wi, 480.0), b.eval(wo, wi, 480.0) * wi.z);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64;

    /// Visits every narrow peak (order m ≠ 0 on the grating equation inside `band`) that
    /// (wo, wi) sees, in order of increasing |m|, with its value of
    /// [`response`](Self::response) at the peak and its equivalent width; returns the count and
    /// whether the order-0 lobe is seen. The crate's models visit at most
    /// [`MAX_ORDERS`](crate::MAX_ORDERS) orders, those of lowest |m|, so the call does bounded
    /// work.
    ///
    /// This is the contract the colour integrator's generic path
    /// ([`Spectral::xyz_brdf`](crate::spectrum::Spectral::xyz_brdf)) relies on for its stated
    /// bounds: every feature of `response` in wavelength narrower than 2 nm is a visited peak,
    /// and `specular` is `true` wherever order 0's light reaches the band. A model whose
    /// response has unreported narrow side lobes (a grating's F_N) should say what it is
    /// through [`grating_response`](Self::grating_response).
    ///
    /// ```
    /// use diffraction::{AguHill, Band, Grating, SpectralResponse};
    /// use glam::DVec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wo, wi) = (DVec3::new(0.9, 0.0, 0.19f64.sqrt()), DVec3::Z); // u = 0.9, d·u = 1440 nm
    /// let mut orders = vec![];
    /// let summary = brdf.peaks(wo, wi, Band::VISIBLE, &mut |p| orders.push(p.order));
    /// assert_eq!(orders, [2, 3, 4]); // 720, 480 and 360 nm
    /// assert_eq!((summary.orders, summary.specular), (3, false));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary;

    /// What this model's response is in terms of the Agu-Hill intensity, where it is a
    /// multiple of it: `Some(r)` when, at these directions, `response(wo, wi, λ)` equals
    /// `r.scale · r.envelope.at(λ) · r.grating.intensity(r.u, λ)` for every λ. The colour
    /// integrator then takes the lobe-exact grating paths
    /// ([`Spectral::xyz_response`](crate::spectrum::Spectral::xyz_response)) with their
    /// bounds. Optics only: it says what the model is, not how to integrate it. The default is
    /// `None` (a model of another shape).
    ///
    /// ```
    /// use diffraction::{AguHill, Grating, SpectralResponse};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let (wo, wi) = (DVec3::new(0.34, 0.0, (1.0f64 - 0.34 * 0.34).sqrt()), DVec3::Z);
    /// let r = AguHill::new(g).grating_response(wo, wi).unwrap();
    /// assert_eq!((r.grating, r.u, r.scale), (g, 0.34, 1.0));
    /// assert!(AguHill::new(g).grating_response(wo, -wi).is_none()); // below the surface
    /// # #[cfg(feature = "baselines")]
    /// assert!(diffraction::Thorman::new(1600.0, 0.003)?.grating_response(wo, wi).is_none());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn grating_response(&self, wo: DVec3, wi: DVec3) -> Option<GratingResponse> {
        let _ = (wo, wi);
        None
    }
}

/// A model's value as a multiple of the Agu-Hill intensity of a grating (see
/// [`SpectralResponse::grating_response`]): `scale · envelope(λ) · grating.intensity(u, λ)`.
///
/// ```
/// use diffraction::{Envelope, Grating, GratingResponse};
/// let r = GratingResponse::new(Grating::new(1600.0, 800.0, 100)?, 0.3, 2.0);
/// assert_eq!((r.u, r.scale, r.envelope), (0.3, 2.0, Envelope::ONE));
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct GratingResponse {
    /// The grating whose intensity I(u, λ) the model is a multiple of.
    pub grating: Grating,
    /// The phase projection u = (wi + wo)·t of the directions.
    pub u: f64,
    /// The factor k ≥ 0, the same at every wavelength.
    pub scale: f64,
    /// The smooth factor of wavelength (1 for the paper's model).
    pub envelope: Envelope,
}

impl GratingResponse {
    /// `scale · grating.intensity(u, λ)`, with no factor of wavelength.
    ///
    /// ```
    /// use diffraction::{Grating, GratingResponse};
    /// let r = GratingResponse::new(Grating::new(1600.0, 800.0, 100)?, -0.3, 0.5);
    /// assert_eq!(r.u, -0.3);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn new(grating: Grating, u: f64, scale: f64) -> GratingResponse {
        GratingResponse {
            grating,
            u,
            scale,
            envelope: Envelope::ONE,
        }
    }

    /// The same response times `envelope(λ)`.
    ///
    /// ```
    /// use diffraction::{Envelope, Grating, GratingResponse};
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// let r = GratingResponse::new(g, 0.3, 1.0).with_envelope(Envelope::new(1, 0.0)?);
    /// assert_eq!(r.envelope.at(500.0), 1.0 / 500.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn with_envelope(self, envelope: Envelope) -> GratingResponse {
        GratingResponse { envelope, ..self }
    }
}

/// A smooth factor of wavelength in a model's response to a grating:
/// k(λ) = λ^(−p) · sinc²(π·c/λ), with sinc t = sin t / t, an integer power p ∈ [0, 4] and a length
/// c ≥ 0 (nm; c = 0 gives no sinc factor).
///
/// The energy-normalised grating ([`GratingBsdf`](crate::GratingBsdf)) is the Agu-Hill intensity times
/// (N·d/λ)·g(v, λ): p = 1 for a groove spread g that does not depend on λ, and p = 2 with
/// c = L·v for a coherence length L, whose g is (L/λ)·sinc²(π·L·v/λ). The colour integrator
/// ([`Spectral`](crate::spectrum::Spectral::with_envelope)) multiplies its spectral weight by
/// k(λ), which changes over many table rows, so every strategy keeps its bound.
///
/// ```
/// use diffraction::Envelope;
/// assert_eq!(Envelope::ONE.at(550.0), 1.0);
/// let e = Envelope::new(2, 275.0)?; // λ⁻² · sinc²(π·275/λ)
/// assert!((e.at(550.0) - (2.0 / std::f64::consts::PI).powi(2) / 550.0f64.powi(2)).abs() < 1e-20);
/// assert_eq!(Envelope::new(5, 0.0).unwrap_err().parameter(), "inverse_power");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Envelope {
    inverse_power: u8,
    sinc_length_nm: f64,
}

impl Envelope {
    /// k(λ) = 1.
    pub const ONE: Envelope = Envelope {
        inverse_power: 0,
        sinc_length_nm: 0.0,
    };

    /// The factor λ^(−inverse_power) · sinc²(π·sinc_length_nm/λ); `inverse_power` at most 4,
    /// `sinc_length_nm` finite and ≥ 0.
    ///
    /// ```
    /// use diffraction::Envelope;
    /// assert_eq!(Envelope::new(1, 0.0)?.at(400.0), 1.0 / 400.0);
    /// assert_eq!(Envelope::new(0, -1.0).unwrap_err().parameter(), "sinc_length_nm");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(inverse_power: u8, sinc_length_nm: f64) -> Result<Envelope, Error> {
        if inverse_power > 4 {
            return Err(Error::invalid(
                "inverse_power",
                inverse_power as f64,
                Requirement::Within { min: 0.0, max: 4.0 },
            ));
        }
        if !(sinc_length_nm.is_finite() && sinc_length_nm >= 0.0) {
            return Err(Error::invalid(
                "sinc_length_nm",
                sinc_length_nm,
                Requirement::NonNegative,
            ));
        }
        Ok(Envelope {
            inverse_power,
            sinc_length_nm,
        })
    }

    /// k(λ); 0 for λ ≤ 0 or non-finite λ; saturates at `f64::MAX` where λ^(−p) would overflow
    /// (λ below about 10⁻⁷⁷ nm for p = 4), so it is finite for every finite λ.
    ///
    /// ```
    /// use diffraction::Envelope;
    /// let e = Envelope::new(0, 500.0)?;
    /// assert!(e.at(500.0) < 1e-30); // sinc²(π) = 0
    /// assert_eq!(e.at(-1.0), 0.0);
    /// assert_eq!(Envelope::new(4, 0.0)?.at(5e-324), f64::MAX); // saturates, never ∞
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn at(&self, lambda_nm: f64) -> f64 {
        if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        let mut k = 1.0;
        for _ in 0..self.inverse_power {
            k /= lambda_nm;
        }
        if self.sinc_length_nm != 0.0 {
            k *= crate::num::kernel::single_slit_cycles(self.sinc_length_nm / lambda_nm);
        }
        k.min(f64::MAX)
    }

    /// The largest argument y of the sinc² factor sinc²(π·y), y = L/λ, over the band (0 without
    /// one): below ½ the factor has no zero in the band and is as smooth as λ⁻ᵖ.
    pub(crate) fn band_sinc_cycles(&self) -> f64 {
        self.sinc_length_nm / crate::data::cie::TABLE_FIRST_NM
    }

    /// Whether k(λ) = 1 everywhere.
    ///
    /// ```
    /// use diffraction::Envelope;
    /// assert!(Envelope::ONE.is_one() && !Envelope::new(1, 0.0)?.is_one());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn is_one(&self) -> bool {
        self.inverse_power == 0 && self.sinc_length_nm == 0.0
    }
}
