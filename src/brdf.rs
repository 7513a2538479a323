//! The BRDF interface and the paper's illumination model.

use glam::{DVec3, Vec3};

use crate::color::Xyz;
use crate::error::{Error, Requirement};
use crate::grating::{Band, Grating, Peak};
use crate::spectrum::{Spectral, Strategy};

/// What [`DiffractionBrdf::peaks`] found besides the peaks it visited.
///
/// ```
/// use diffraction::{AguHill, Band, DiffractionBrdf, Grating};
/// use glam::DVec3;
/// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
/// // The mirror direction (u = 0): inside the order-0 lobe, and no order m ≠ 0.
/// let (wi, wo) = (DVec3::new(-0.6, 0.0, 0.8), DVec3::new(0.6, 0.0, 0.8));
/// let summary = brdf.peaks(wi, wo, Band::VISIBLE, &mut |_| {});
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

/// A spectral diffraction BRDF in the local shading frame.
///
/// Shaped like the BxDF interfaces of pbrt-v4 and Mitsuba: directions are unit vectors in the
/// local frame where `z` is the normal and `x` the grating vector t (`y` runs along the grooves);
/// `wi` points toward the light and `wo` toward the viewer. Both must be in the upper hemisphere
/// (z > 0); below it every method returns 0 / nothing.
///
/// The light reflected toward `wo` from a point light of spectral intensity E(λ) in direction
/// `wi` is `E(λ) · eval(wi, wo, λ)`, multiplied by cos θi = `wi.z` **only if**
/// [`cosine_included`](Self::cosine_included) is `false`. The paper's model does not apply a
/// cosine to its diffraction term, so [`AguHill`] reports `true`.
///
/// Later versions may add importance sampling (`sample`, `pdf`) as provided methods with
/// defaults, which is not a breaking change for implementors.
///
/// ```
/// use diffraction::{AguHill, Band, DiffractionBrdf, Grating};
/// use glam::DVec3;
/// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
/// let wi = DVec3::Z;
/// let wo = DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt());
/// // u = 0.3: first order at 480 nm.
/// let mut seen = vec![];
/// let summary = brdf.peaks(wi, wo, Band::VISIBLE, &mut |p| seen.push(p.wavelength_nm));
/// assert_eq!(summary.orders, 1);
/// assert!((seen[0] - 480.0).abs() < 1e-9);
/// assert!(brdf.eval(wi, wo, 480.0) > 100.0 * brdf.eval(wi, wo, 500.0));
/// # Ok::<(), diffraction::Error>(())
/// ```
pub trait DiffractionBrdf {
    /// The spectral value at wavelength `lambda_nm` (nm) for local directions `wi`, `wo`.
    /// Finite and ≥ 0 for finite input.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wi, wo) = (DVec3::new(-0.6, 0.0, 0.8), DVec3::new(0.6, 0.0, 0.8));
    /// assert_eq!(brdf.eval(wi, wo, 550.0), 1.0); // the mirror direction: S(0)·F_N(0) = 1
    /// assert_eq!(brdf.eval(-wi, wo, 550.0), 0.0); // light below the surface
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64;

    /// [`eval`](Self::eval) for `f32` callers. Implementations may override it with a faster
    /// path; the default widens to `f64`.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::Vec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wi, wo) = (Vec3::Z, Vec3::new(0.3, 0.0, 0.91f32.sqrt())); // near order 1 at 480 nm
    /// let wide = brdf.eval(wi.as_dvec3(), wo.as_dvec3(), 480.0);
    /// assert_eq!(brdf.eval_f32(wi, wo, 480.0), wide as f32); // the f64 value, rounded once
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn eval_f32(&self, wi: Vec3, wo: Vec3, lambda_nm: f32) -> f32 {
        self.eval(wi.as_dvec3(), wo.as_dvec3(), lambda_nm as f64) as f32
    }

    /// Visits every narrow peak (order m ≠ 0 on the grating equation inside `band`) that
    /// (wi, wo) sees, in order of increasing |m|, with its value of `eval` at the peak and its
    /// equivalent width; returns the count and whether the order-0 lobe is seen.
    ///
    /// ```
    /// use diffraction::{AguHill, Band, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wi, wo) = (DVec3::Z, DVec3::new(0.9, 0.0, 0.19f64.sqrt())); // u = 0.9, d·u = 1440 nm
    /// let mut orders = vec![];
    /// let summary = brdf.peaks(wi, wo, Band::VISIBLE, &mut |p| orders.push(p.order));
    /// assert_eq!(orders, [2, 3, 4]); // 720, 480 and 360 nm
    /// assert_eq!((summary.orders, summary.specular), (3, false));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary;

    /// Whether `eval` already contains the cosine cos θi (see the trait docs).
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// let brdf = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    /// assert!(brdf.cosine_included()); // the paper applies no cos θi to its diffraction term
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn cosine_included(&self) -> bool;

    /// The reference colour XYZ of the light this BRDF sends toward `wo` from a light at `wi`
    /// whose spectrum is `spectral`'s illuminant, relative to that illuminant's white (the cosine
    /// applied as [`cosine_included`](Self::cosine_included) says).
    ///
    /// The default integrates [`eval`](Self::eval) and [`peaks`](Self::peaks) by
    /// [`Spectral::xyz_brdf`]; models with a known lobe structure override it.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let brdf = AguHill::new(g).with_coefficients(0.0, 0.0, 2.0)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wi, wo) = (DVec3::Z, DVec3::new(0.34, 0.0, (1.0f64 - 0.34 * 0.34).sqrt())); // u = 0.34
    /// // The grating's colour at u, times the diffraction coefficient.
    /// assert_eq!(brdf.xyz(wi, wo, &s, Strategy::Exact), s.xyz(&g, 0.34, Strategy::Exact) * 2.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn xyz(&self, wi: DVec3, wo: DVec3, spectral: &Spectral, strategy: Strategy) -> Xyz {
        spectral.xyz_brdf(self, wi, wo, strategy)
    }
}

/// The paper's model: an Agu-Hill grating as the diffraction term of the illumination model
/// I = ambient + diffuse + diffraction (eq. 12).
///
/// * diffraction (eq. 8, 13): `diffraction · S(β)·F_N(α)` at u = (wi + wo)·t = `wi.x + wo.x`;
///   at u ≈ 0 (order 0, step 6) this is the white specular, since F_N(0) = S(0) = 1 at every λ;
/// * diffuse (Phong): `diffuse · cos θi`;
/// * ambient (Phong): `ambient`, times the ambient light.
///
/// [`DiffractionBrdf::eval`] returns the diffraction term only; [`AguHill::illumination`]
/// evaluates the whole of eq. 12 at one wavelength.
///
/// ```
/// use diffraction::{AguHill, Grating};
/// use glam::DVec3;
/// let m = AguHill::new(Grating::new(1600.0, 800.0, 500)?).with_coefficients(0.1, 0.3, 1.0)?;
/// let wi = DVec3::new(-0.6, 0.0, 0.8);
/// let wo = DVec3::new(0.6, 0.0, 0.8); // mirror: order 0
/// let i = m.illumination(wi, wo, 550.0, 1.0, 1.0);
/// assert!((i - (0.1 + 0.3 * 0.8 + 1.0)).abs() < 1e-12);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct AguHill {
    grating: Grating,
    ambient: f64,
    diffuse: f64,
    diffraction: f64,
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for AguHill {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        struct Raw {
            grating: Grating,
            ambient: f64,
            diffuse: f64,
            diffraction: f64,
        }
        let r = Raw::deserialize(d)?;
        AguHill::new(r.grating)
            .with_coefficients(r.ambient, r.diffuse, r.diffraction)
            .map_err(serde::de::Error::custom)
    }
}

impl AguHill {
    /// The model with coefficients ambient = 0, diffuse = 0, diffraction = 1: the grating alone.
    ///
    /// ```
    /// use diffraction::{AguHill, Grating};
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// let m = AguHill::new(g);
    /// assert_eq!(m.grating(), &g);
    /// assert_eq!(m.coefficients(), (0.0, 0.0, 1.0));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn new(grating: Grating) -> AguHill {
        AguHill {
            grating,
            ambient: 0.0,
            diffuse: 0.0,
            diffraction: 1.0,
        }
    }

    /// Sets the coefficients of eq. 12; each must be finite and ≥ 0.
    ///
    /// ```
    /// use diffraction::{AguHill, Grating};
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert_eq!(m.with_coefficients(0.1, 0.5, 2.0)?.coefficients(), (0.1, 0.5, 2.0));
    /// assert_eq!(m.with_coefficients(0.1, -0.5, 2.0).unwrap_err().parameter(), "diffuse");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_coefficients(
        self,
        ambient: f64,
        diffuse: f64,
        diffraction: f64,
    ) -> Result<AguHill, Error> {
        let check = |name: &'static str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                Err(Error::invalid(
                    name,
                    v,
                    Requirement::Within {
                        min: 0.0,
                        max: f64::MAX,
                    },
                ))
            }
        };
        Ok(AguHill {
            grating: self.grating,
            ambient: check("ambient", ambient)?,
            diffuse: check("diffuse", diffuse)?,
            diffraction: check("diffraction", diffraction)?,
        })
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

    /// The coefficients (ambient, diffuse, diffraction).
    ///
    /// ```
    /// use diffraction::{AguHill, Grating};
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 100)?).with_coefficients(0.2, 0.0, 1.5)?;
    /// let (ambient, diffuse, diffraction) = m.coefficients();
    /// assert_eq!((ambient, diffuse, diffraction), (0.2, 0.0, 1.5));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn coefficients(&self) -> (f64, f64, f64) {
        (self.ambient, self.diffuse, self.diffraction)
    }

    /// Eq. 12 at one wavelength: `ambient·ambient_light + light·(diffuse·cos θi + eval)`, with
    /// the light terms 0 when either direction is below the surface.
    ///
    /// ```
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 500)?).with_coefficients(0.1, 0.3, 1.0)?;
    /// // u = 0.3: order 1 at 480 nm.
    /// let (wi, wo) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// let i = m.illumination(wi, wo, 480.0, 2.0, 1.0);
    /// let expected = 0.1 * 2.0 + 0.3 * 1.0 + m.eval(wi, wo, 480.0);
    /// assert!((i - expected).abs() < 1e-12); // the order of the additions only
    /// // Light from below the surface: only the ambient term remains.
    /// assert_eq!(m.illumination(-wi, wo, 480.0, 2.0, 1.0), 0.1 * 2.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn illumination(
        &self,
        wi: DVec3,
        wo: DVec3,
        lambda_nm: f64,
        ambient_light: f64,
        light: f64,
    ) -> f64 {
        let mut i = self.ambient * ambient_light;
        if both_above(wi.z, wo.z) {
            i += light * (self.diffuse * wi.z + self.eval(wi, wo, lambda_nm));
        }
        i
    }
}

impl DiffractionBrdf for AguHill {
    #[inline]
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        if !both_above(wi.z, wo.z) {
            return 0.0;
        }
        self.diffraction * self.grating.intensity_f64(wi.x + wo.x, lambda_nm)
    }

    #[inline]
    fn eval_f32(&self, wi: Vec3, wo: Vec3, lambda_nm: f32) -> f32 {
        if !both_above(wi.z as f64, wo.z as f64) {
            return 0.0;
        }
        let u = wi.x as f64 + wo.x as f64;
        (self.diffraction * self.grating.intensity_f64(u, lambda_nm as f64)) as f32
    }

    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !both_above(wi.z, wo.z) {
            return PeakSummary::default();
        }
        let peaks = self.grating.peaks(wi.x + wo.x, band);
        let specular = peaks.specular();
        let mut orders = 0;
        for mut p in peaks {
            p.intensity *= self.diffraction;
            visit(p);
            orders += 1;
        }
        PeakSummary { orders, specular }
    }

    fn cosine_included(&self) -> bool {
        true
    }

    /// The lobe-exact paths of [`Spectral::xyz`] for the grating, times the diffraction
    /// coefficient (0 below the surface).
    fn xyz(&self, wi: DVec3, wo: DVec3, spectral: &Spectral, strategy: Strategy) -> Xyz {
        if !both_above(wi.z, wo.z) {
            return Xyz::default();
        }
        spectral.xyz(&self.grating, wi.x + wo.x, strategy) * self.diffraction
    }
}

/// Whether both directions are strictly above the surface (false for NaN).
#[inline]
fn both_above(zi: f64, zo: f64) -> bool {
    zi > 0.0 && zo > 0.0
}
