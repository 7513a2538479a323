//! The paper's illumination model (eq. 12): I = ambient + diffuse + diffraction, a shading model
//! around any diffraction model, not a BRDF itself.

use core::ops::{Add, Mul};

use glam::DVec3;

use crate::error::{Error, Requirement};
use crate::model::{both_above, SpectralResponse};

/// The coefficients of the paper's eq. 12, I = ambient + diffuse + diffraction, with Phong's
/// ambient and diffuse terms and a diffraction model in place of the specular one:
///
/// * ambient: `ambient · ambient_light`;
/// * diffuse (Lambert, as Phong): `diffuse · cos θi · light`;
/// * diffraction: `diffraction · response(wo, wi, λ) · light` for any model with a
///   [`SpectralResponse`] (the paper's intensity for [`AguHill`](crate::AguHill); f·cos θi for a
///   BRDF f).
///
/// ```
/// use diffraction::{AguHill, Grating, Illumination};
/// use glam::DVec3;
/// let model = AguHill::new(Grating::new(1600.0, 800.0, 500)?);
/// let shading = Illumination::new(0.1, 0.3, 1.0)?;
/// let (wo, wi) = (DVec3::new(0.6, 0.0, 0.8), DVec3::new(-0.6, 0.0, 0.8)); // mirror: order 0
/// let i = shading.eval(&model, wo, wi, 550.0, 1.0, 1.0);
/// assert!((i - (0.1 + 0.3 * 0.8 + 1.0)).abs() < 1e-12);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Illumination {
    ambient: f64,
    diffuse: f64,
    diffraction: f64,
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Illumination {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Raw {
            ambient: f64,
            diffuse: f64,
            diffraction: f64,
        }
        let r = Raw::deserialize(d)?;
        Illumination::new(r.ambient, r.diffuse, r.diffraction).map_err(serde::de::Error::custom)
    }
}

impl Default for Illumination {
    /// The diffraction term alone: ambient = diffuse = 0, diffraction = 1.
    ///
    /// ```
    /// use diffraction::Illumination;
    /// assert_eq!(Illumination::default().coefficients(), (0.0, 0.0, 1.0));
    /// ```
    fn default() -> Self {
        Illumination {
            ambient: 0.0,
            diffuse: 0.0,
            diffraction: 1.0,
        }
    }
}

impl Illumination {
    /// The coefficients (ambient, diffuse, diffraction); each must be finite and ≥ 0.
    ///
    /// ```
    /// use diffraction::Illumination;
    /// assert_eq!(Illumination::new(0.1, 0.5, 2.0)?.coefficients(), (0.1, 0.5, 2.0));
    /// let err = Illumination::new(0.1, -0.5, 2.0).unwrap_err();
    /// assert_eq!(err.parameter(), "diffuse");
    /// assert_eq!(err.to_string(), "invalid diffuse = -0.5: must be finite and >= 0");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(ambient: f64, diffuse: f64, diffraction: f64) -> Result<Illumination, Error> {
        let check = |name: &'static str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                Err(Error::invalid(name, v, Requirement::NonNegative))
            }
        };
        Ok(Illumination {
            ambient: check("ambient", ambient)?,
            diffuse: check("diffuse", diffuse)?,
            diffraction: check("diffraction", diffraction)?,
        })
    }

    /// The coefficients (ambient, diffuse, diffraction).
    ///
    /// ```
    /// use diffraction::Illumination;
    /// let (ambient, diffuse, diffraction) = Illumination::new(0.2, 0.0, 1.5)?.coefficients();
    /// assert_eq!((ambient, diffuse, diffraction), (0.2, 0.0, 1.5));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn coefficients(&self) -> (f64, f64, f64) {
        (self.ambient, self.diffuse, self.diffraction)
    }

    /// Eq. 12 on colours, for renderers that shade in a colour space rather than per
    /// wavelength: `ambient·ambient_light·albedo + Σ light·(diffuse·cos θi·albedo +
    /// diffraction·colour)` over `lights`, each given as (light, cos θi, diffraction colour):
    /// the light's colour (times the fraction of it that is visible), the cosine between the
    /// direction to it and the normal, and the diffraction model's colour toward it (for
    /// instance `Spectral::xyz` of the grating at that u, in the caller's colour space; zero off
    /// a grating). `C` is any colour with component-wise products, such as a linear-RGB
    /// `DVec3`, or `f64` for one channel, where one light gives [`eval`](Self::eval)'s number.
    ///
    /// A light with cos θi ≤ 0 (below the surface) or NaN adds nothing; cos θi above 1 counts
    /// as 1. Colours are used as given: linear RGB of spectral colours can be negative, and no
    /// component is clipped here (clipping is the caller's explicit step).
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating, Illumination};
    /// use glam::DVec3;
    /// let shading = Illumination::new(0.5, 0.8, 2.0)?;
    /// let (ambient, albedo) = (DVec3::splat(0.1), DVec3::new(0.6, 0.4, 0.2));
    /// let (light, diffracted) = (DVec3::splat(0.9), DVec3::new(0.0, 0.3, 0.1));
    /// let c = shading.shade(ambient, albedo, [(light, 0.5, diffracted), (light, -0.2, diffracted)]);
    /// // The second light is below the surface.
    /// let expected = ambient * albedo * 0.5 + light * (albedo * (0.8 * 0.5) + diffracted * 2.0);
    /// assert!((c - expected).abs().max_element() < 1e-15);
    /// // One channel and one light: the number `eval` gives at one wavelength.
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 500)?);
    /// let (wo, wi) = (DVec3::new(0.3, 0.0, 0.91f64.sqrt()), DVec3::Z);
    /// let value = m.eval(wo, wi, 480.0);
    /// let one = shading.shade(2.0, 1.0, [(1.5, wi.z, value)]);
    /// assert_eq!(one, shading.eval(&m, wo, wi, 480.0, 2.0, 1.5));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn shade<C, I>(&self, ambient_light: C, albedo: C, lights: I) -> C
    where
        C: Copy + Add<Output = C> + Mul<Output = C> + Mul<f64, Output = C>,
        I: IntoIterator<Item = (C, f64, C)>,
    {
        let mut c = ambient_light * albedo * self.ambient;
        for (light, cos_i, diffracted) in lights {
            if cos_i > 0.0 {
                let reflected =
                    albedo * (self.diffuse * cos_i.min(1.0)) + diffracted * self.diffraction;
                c = c + light * reflected;
            }
        }
        c
    }

    /// Eq. 12 at one wavelength: `ambient·ambient_light + light·(diffuse·cos θi +
    /// diffraction·response)`, where `response` is the model's
    /// [`response`](SpectralResponse::response) (`wo` toward the viewer, `wi` toward the light);
    /// the light terms are 0 when either direction is below the surface.
    ///
    /// Directions must be unit (cos θi = `wi.z` is clamped to 1 for other input) and lights are
    /// powers, ≥ 0 (a negative light counts as 0). The result is finite and ≥ 0 for finite
    /// input: where the caller's own coefficients, lights and the model's value are so large
    /// that their products overflow, it saturates at `f64::MAX`.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating, Illumination};
    /// use glam::DVec3;
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 500)?);
    /// let shading = Illumination::new(0.1, 0.3, 1.0)?;
    /// // u = 0.3: order 1 at 480 nm.
    /// let (wo, wi) = (DVec3::new(0.3, 0.0, 0.91f64.sqrt()), DVec3::Z);
    /// let i = shading.eval(&m, wo, wi, 480.0, 2.0, 1.0);
    /// let expected = 0.1 * 2.0 + 0.3 * 1.0 + m.eval(wo, wi, 480.0);
    /// assert!((i - expected).abs() < 1e-12); // the order of the additions only
    /// // Light from below the surface: only the ambient term remains.
    /// assert_eq!(shading.eval(&m, wo, -wi, 480.0, 2.0, 1.0), 0.1 * 2.0);
    /// // Products that overflow saturate instead.
    /// let bright = Illumination::new(1.0, 1.0, 1.0)?;
    /// assert_eq!(bright.eval(&m, wo, wi, 480.0, f64::MAX, f64::MAX), f64::MAX);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn eval<M: SpectralResponse + ?Sized>(
        &self,
        model: &M,
        wo: DVec3,
        wi: DVec3,
        lambda_nm: f64,
        ambient_light: f64,
        light: f64,
    ) -> f64 {
        let (ambient_light, light) = (ambient_light.max(0.0), light.max(0.0));
        let mut i = self.ambient * ambient_light;
        if both_above(wo, wi) {
            let cos_i = wi.z.min(1.0);
            let value = model.response(wo, wi, lambda_nm);
            i += light * (self.diffuse * cos_i + self.diffraction * value);
        }
        // Each term is ≥ 0, so the sum is never NaN; it saturates instead of overflowing.
        i.min(f64::MAX)
    }
}
