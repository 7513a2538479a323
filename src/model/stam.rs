//! Stam's diffraction shader (1999) for a one-dimensional periodic surface: Fourier optics under
//! the Kirchhoff approximation, with a finite Gaussian coherence area (feature `stam`).
//!
//! # The model
//!
//! Stam, "Diffraction Shaders" (SIGGRAPH 1999), writes the BRDF of a surface of height h(x, y)
//! lit by a monochromatic plane wave as
//!
//! ```text
//! f(wi, wo, λ) = k²·F²·G / (4π²·A·w²) · ⟨|P(k·u, k·v)|²⟩,   G = (1 + wi·wo)² / (cos θi · cos θo),
//! ```
//!
//! with k = 2π/λ, (u, v, w) = wi + wo in the local frame (Stam's vector up to its sign, which
//! nothing below depends on: w enters squared, the |c_m|² are even in m and the lobes symmetric),
//! wi and wo both pointing away from the surface (then a flat mirror's lobe integrates to exactly
//! 1, which fixes the sign of wi·wo in G), F the Fresnel coefficient, A the area of the
//! coherently lit patch, and P the Fourier transform of p(x, y) = exp(i·k·w·h(x, y)) over that
//! patch. For this crate's grating, h depends on x (across the grooves, along the grating vector)
//! only and is periodic with period d, so p is a Fourier series,
//!
//! ```text
//! p(x) = Σ_m c_m(φ)·exp(2πi·m·x/d),   φ = k·w·h₀,
//! ```
//!
//! whose coefficients depend on the profile's shape and the phase φ only ([`Profile`]).
//! The patch is the Gaussian window W(x, y) = exp(−(x² + y²)/(2σ_c²)), σ_c = `coherence_nm`,
//! whose transform is 2π·σ_c²·exp(−σ_c²·(a² + b²)/2). Squaring, with A = ∫W² = π·σ_c² (which
//! makes a flat mirror's BRDF exactly δ(u)·δ(v), the mirror) and dropping the cross terms
//! between orders:
//!
//! ```text
//! f = F² · G/w² · Σ_m |c_m(φ)|² · (k²σ_c²/π) · exp(−k²σ_c²·[(u − m·λ/d)² + v²]).
//! ```
//!
//! Each order is a Gaussian lobe centred on the grating equation u = m·λ/d, v = 0, of standard
//! deviation 1/(√2·k·σ_c) = λ/(2√2·π·σ_c) in u and in v, whose (u, v) integral is 1 (so
//! ∫f·cos θo dωo = F²·(G/w²)·|c_m|² per order). At fixed directions, as a function of λ, the
//! lobe of order m ≠ 0 has the equivalent width (area over peak)
//!
//! ```text
//! Δλ_m = λ_m·d / (2√π·σ_c·|m|),
//! ```
//!
//! counting the Gaussian factor only (exact in the limit of narrow peaks; the slower changes of
//! k², c_m and exp(−k²σ_c²v²) with λ are neglected). That is the equivalent width λ_m/(|m|·N)
//! of an Agu-Hill grating with N = 2√π·σ_c/d slits.
//!
//! # Assumptions, stated
//!
//! * Scalar waves, no polarisation; the Kirchhoff (tangent-plane) approximation: no shadowing,
//!   masking or multiple scattering; meant for shallow profiles (h₀ well below d).
//! * The orders add incoherently (the cross terms between different m are dropped). This is
//!   accurate when the lobes are far apart compared with their width; [`Stam::new`] requires
//!   σ_c ≥ d, where neighbouring lobes are 2√2·π·σ_c/d ≥ 8.9 standard deviations apart.
//! * F² is the reflectance (Stam's F is an amplitude coefficient), by Schlick's approximation
//!   F² = R₀ + (1 − R₀)·(1 − cos θh)⁵ at the local angle of incidence, cos θh = wi·h =
//!   √((1 + wi·wo)/2) (h the half vector), with R₀ = [`reflectance`](Stam::reflectance) at
//!   normal incidence, the same at every wavelength. R₀ = 1 (the default) is a perfect
//!   conductor, F² = 1.
//! * Not energy conserving: order m carries F²·(G/w²)·|c_m|² of the incident power, and
//!   G/w² is 1 in the mirror direction but not in general elsewhere (at normal incidence it is
//!   1/cos θo, above 1). What holds
//!   exactly is Parseval, Σ_m |c_m|² = 1, and reciprocity f(wi, wo) = f(wo, wi).
//! * **Grazing angles**: G/w² grows without bound toward the horizon (as 1/cos θo at normal
//!   incidence), where the Kirchhoff approximation fails (the surface shadows itself). Each
//!   cosine of G/w²'s denominator is taken as at least 0.01 (a grazing angle of
//!   0.57°): a documented clamp that leaves the model unchanged above it and bounds G/w² by
//!   10⁸ everywhere; with σ_c ≤ [`MAX_COHERENCE_NM`] every value is finite.
//! * It is a BRDF (1/sr, cosine excluded): the renderer multiplies by cos θi, and its
//!   [`response`](SpectralResponse::response) is `eval·cos θi`.
//! * Unlike the paper's model and [`Thorman`](crate::Thorman), the light is confined to the
//!   cone of diffracted directions: the factor exp(−k²σ_c²v²), v = `wi.y + wo.y`, darkens every
//!   direction off the plane of the grating equation's cone.

use core::f64::consts::PI;

use glam::{DVec2, DVec3};

pub use crate::model::profile::Profile;
pub use crate::num::bessel::bessel_j;

use crate::error::{positive, Error, Requirement};
use crate::model::bsdf::{cosine_hemisphere_pdf, sample_cosine_hemisphere};
use crate::model::profile::binary_coefficient;
use crate::model::{both_above, Bsdf, BsdfFlags, BsdfSample, DiffractionBrdf, PeakSummary};
use crate::model::{SpectralResponse, MIN_COS_THETA};
use crate::num::bessel::bessel_squares;
use crate::num::math;
use crate::{Band, GratingEquation, Peak, MAX_ORDERS};

/// Lobes are summed out to k·σ_c·|Δu| = 6, where exp(−36) = 2.3·10⁻¹⁶.
const CUTOFF: f64 = 6.0;
/// The largest accepted h₀, nm (φ = k·w·h₀ ≤ 349 over the visible band).
const MAX_DEPTH_NM: f64 = 10_000.0;
/// Below this wavelength `eval` returns 0 (keeps φ ≤ 1.3·10⁵ and the Bessel sums short).
const MIN_WAVELENGTH_NM: f64 = 1.0;
/// √π.
const SQRT_PI: f64 = 1.772453850905516;
/// The smallest cosine the geometry factor G/w² sees: below it (a grazing angle under 0.57°)
/// each cosine of its denominator is taken as this. Stam's G/w² grows as 1/cos θ toward the
/// horizon (1/cos⁴θ where both directions graze), without bound, where the Kirchhoff
/// approximation it comes from has no validity (the tangent plane is shadowed); the clamp
/// bounds it by 1/`GRAZING_COS`⁴ = 10⁸ and changes the model only within a projected solid
/// angle of π·`GRAZING_COS`² = 3·10⁻⁴ sr of the horizon.
pub(crate) const GRAZING_COS: f64 = 0.01;
/// The longest accepted coherence width σ_c, nm (10⁶ km, the crate's longest coherence length,
/// [`MAX_COHERENCE_NM`](crate::optics::groove::MAX_COHERENCE_NM)): the lobe's peak k²σ_c²/π then stays
/// below 1.3·10³¹ at λ ≥ 1 nm, so every value of the model is finite.
pub const MAX_COHERENCE_NM: f64 = crate::optics::groove::MAX_COHERENCE_NM;
/// The most recurrence steps one Bessel value of [`Stam::peaks`](SpectralResponse::peaks) may
/// take before it uses Debye's expansions (see [`bessel_j`]; at most 1510 steps near the
/// turning point for the model's phases ≤ 4π·10⁴): bounds a `peaks` call to about
/// 2000·[`MAX_ORDERS`] steps.
const PEAK_BESSEL_STEPS: f64 = 2000.0;

/// Stam's diffraction shader for a one-dimensional periodic surface (see the
/// [module docs](self) for the derivation and every assumption).
///
/// Directions must be unit vectors. Other input is not physical but stays cheap and finite:
/// the cosines entering the phase are clamped to [0, 1] (see [`Stam::phase`]), which bounds
/// every Bessel sum, and a non-finite result is returned as 0.
///
/// ```text
/// f(wo, wi, λ) = F² · G/w² · Σ_m |c_m(k·w·h₀)|² · (k²σ_c²/π) · exp(−k²σ_c²·[(u − m·λ/d)² + v²])
/// ```
///
/// with (u, v, w) = wi + wo in the local frame, k = 2π/λ, G = (1 + wi·wo)²/(wi.z·wo.z) (each
/// cosine of G/w² at least 0.01, see the module docs), c_m the
/// [`Profile`]'s Fourier coefficients and F² Schlick's reflectance. A BRDF: multiply by
/// cos θi (its [`response`](SpectralResponse::response) does).
///
/// ```
/// use diffraction::{Band, DiffractionBrdf, Profile, SpectralResponse, Stam};
/// use glam::DVec3;
/// // A sinusoidal grating of period 1.6 µm and amplitude 80 nm, coherent over 8 µm.
/// let s = Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?;
/// let wi = DVec3::Z;
/// let wo = DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt()); // u = 0.3: order 1 at 480 nm
/// let mut peaks = vec![];
/// let summary = s.peaks(wo, wi, Band::VISIBLE, &mut |p| peaks.push(p));
/// assert_eq!((summary.orders, peaks[0].order), (1, 1));
/// assert!((peaks[0].wavelength_nm - 480.0).abs() < 1e-9);
/// assert!((s.eval(wo, wi, 480.0) - peaks[0].intensity).abs() < 1e-9 * peaks[0].intensity);
/// assert!(s.eval(wo, wi, 480.0) > 1e3 * s.eval(wo, wi, 530.0)); // between the orders: dark
/// assert_eq!(s.eval(wo, wi, 480.0), s.eval(wi, wo, 480.0)); // reciprocity
/// assert_eq!(s.response(wo, wi, 480.0), s.eval(wo, wi, 480.0) * wi.z);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stam {
    profile: Profile,
    /// The grating equation of the period.
    equation: GratingEquation,
    depth_nm: f64,
    coherence_nm: f64,
    reflectance: f64,
}

impl Stam {
    /// The model for a profile of shape `profile`, period d = `period_nm`, height h₀ =
    /// `depth_nm` (the sine's amplitude, the binary grooves' depth) and coherence width
    /// σ_c = `coherence_nm`, with reflectance R₀ = 1.
    ///
    /// Rejects d ≤ 0; h₀ < 0 or h₀ > 10 µm (h₀ = 0 is a flat mirror); σ_c < d (the orders would
    /// overlap, see the module docs) or σ_c > [`MAX_COHERENCE_NM`]; a binary `fraction` outside
    /// (0, 1]; non-finite values. Errors name `period_nm`, `depth_nm`, `coherence_nm` or
    /// `fraction`.
    ///
    /// ```
    /// use diffraction::{Profile, Stam};
    /// let s = Stam::new(Profile::Binary { fraction: 0.5 }, 1600.0, 120.0, 5000.0)?;
    /// assert_eq!((s.period_nm(), s.depth_nm(), s.coherence_nm()), (1600.0, 120.0, 5000.0));
    /// assert_eq!(s.profile(), Profile::Binary { fraction: 0.5 });
    /// let bad = |p, d, h, c| Stam::new(p, d, h, c).unwrap_err().parameter();
    /// assert_eq!(bad(Profile::Sine, -1.0, 100.0, 5000.0), "period_nm");
    /// assert_eq!(bad(Profile::Sine, 1600.0, -1.0, 5000.0), "depth_nm");
    /// assert_eq!(bad(Profile::Sine, 1600.0, 100.0, 1000.0), "coherence_nm");
    /// assert_eq!(bad(Profile::Binary { fraction: 0.0 }, 1600.0, 100.0, 5000.0), "fraction");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(
        profile: Profile,
        period_nm: f64,
        depth_nm: f64,
        coherence_nm: f64,
    ) -> Result<Stam, Error> {
        let d = positive("period_nm", period_nm)?;
        let equation = GratingEquation::new(d)?;
        if !(depth_nm.is_finite() && (0.0..=MAX_DEPTH_NM).contains(&depth_nm)) {
            return Err(Error::invalid(
                "depth_nm",
                depth_nm,
                Requirement::Within {
                    min: 0.0,
                    max: MAX_DEPTH_NM,
                },
            ));
        }
        let sigma = positive("coherence_nm", coherence_nm)?;
        if sigma > MAX_COHERENCE_NM {
            return Err(Error::invalid(
                "coherence_nm",
                sigma,
                Requirement::Within {
                    min: d,
                    max: MAX_COHERENCE_NM,
                },
            ));
        }
        if sigma < d {
            return Err(Error::invalid(
                "coherence_nm",
                sigma,
                Requirement::AtLeast {
                    bound_name: "period_nm",
                    bound: d,
                },
            ));
        }
        if let Profile::Binary { fraction } = profile {
            let a = positive("fraction", fraction)?;
            if a > 1.0 {
                return Err(Error::invalid(
                    "fraction",
                    a,
                    Requirement::AtMost {
                        bound_name: "1",
                        bound: 1.0,
                    },
                ));
            }
        }
        Ok(Stam {
            profile,
            equation,
            depth_nm,
            coherence_nm: sigma,
            reflectance: 1.0,
        })
    }

    /// Sets the reflectance R₀ at normal incidence of Schlick's approximation, in [0, 1]
    /// (error names `reflectance`).
    ///
    /// ```
    /// use diffraction::{DiffractionBrdf, Profile, Stam};
    /// use glam::DVec3;
    /// let s = Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?;
    /// let dim = s.with_reflectance(0.5)?;
    /// // At normal incidence and the mirror direction cos θh = 1: F² = R₀.
    /// let (wo, wi) = (DVec3::Z, DVec3::Z);
    /// assert!((dim.eval(wo, wi, 550.0) - 0.5 * s.eval(wo, wi, 550.0)).abs() < 1e-9 * s.eval(wo, wi, 550.0));
    /// assert_eq!(s.with_reflectance(1.5).unwrap_err().parameter(), "reflectance");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_reflectance(self, reflectance: f64) -> Result<Stam, Error> {
        if (0.0..=1.0).contains(&reflectance) {
            Ok(Stam {
                reflectance,
                ..self
            })
        } else {
            Err(Error::invalid(
                "reflectance",
                reflectance,
                Requirement::Within { min: 0.0, max: 1.0 },
            ))
        }
    }

    /// The profile's shape.
    ///
    /// ```
    /// # use diffraction::{Profile, Stam};
    /// assert_eq!(Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?.profile(), Profile::Sine);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn profile(&self) -> Profile {
        self.profile
    }

    /// The period d, nm.
    ///
    /// ```
    /// # use diffraction::{Profile, Stam};
    /// assert_eq!(Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?.period_nm(), 1600.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.equation.period_nm()
    }

    /// The height h₀, nm: the sine's amplitude or the binary grooves' depth.
    ///
    /// ```
    /// # use diffraction::{Profile, Stam};
    /// assert_eq!(Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?.depth_nm(), 80.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn depth_nm(&self) -> f64 {
        self.depth_nm
    }

    /// The coherence width σ_c of the Gaussian window, nm.
    ///
    /// ```
    /// # use diffraction::{Profile, Stam};
    /// assert_eq!(Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?.coherence_nm(), 8000.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn coherence_nm(&self) -> f64 {
        self.coherence_nm
    }

    /// The reflectance R₀ at normal incidence (1 unless set by [`with_reflectance`](Self::with_reflectance)).
    ///
    /// ```
    /// # use diffraction::{Profile, Stam};
    /// assert_eq!(Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?.reflectance(), 1.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn reflectance(&self) -> f64 {
        self.reflectance
    }

    /// The phase φ = k·w·h₀ = 2π·(wi.z + wo.z)·h₀/λ at which the profile's coefficients are
    /// taken.
    ///
    /// Directions must be unit (as everywhere in the model); the cosines are clamped to [0, 1],
    /// which changes nothing for unit directions and keeps φ ≤ 4π·h₀/λ for any other input. The
    /// model's domain is λ ≥ 1 nm (below it `eval` is 0); there and for non-finite input the
    /// phase is 0, so it is finite for every input (at most 4π·10⁴ for the deepest profile).
    ///
    /// ```
    /// use diffraction::{Profile, Stam};
    /// use glam::DVec3;
    /// let s = Stam::new(Profile::Sine, 1600.0, 100.0, 8000.0)?;
    /// // Normal incidence, mirror direction: w = 2, φ = 4π·h₀/λ.
    /// let phi = s.phase(DVec3::Z, DVec3::Z, 500.0);
    /// assert!((phi - 4.0 * std::f64::consts::PI * 100.0 / 500.0).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn phase(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(lambda_nm >= MIN_WAVELENGTH_NM && lambda_nm.is_finite()) {
            return 0.0;
        }
        let w = unit_cosine(wi.z) + unit_cosine(wo.z);
        2.0 * PI * w * self.depth_nm / lambda_nm
    }

    /// F²·G/w², the factor common to every order, with each cosine of G/w² taken in
    /// [[`GRAZING_COS`], 1] and 1 + wi·wo in [0, 2] (their ranges for unit directions), so that
    /// it is at most 1/`GRAZING_COS`⁴ for every input.
    fn geometry(&self, wo: DVec3, wi: DVec3) -> f64 {
        let (ci, co) = (grazing_cosine(wi.z), grazing_cosine(wo.z));
        let w = ci + co;
        let c = (1.0 + wi.dot(wo)).clamp(0.0, 2.0);
        let cos_h = math::sqrt(0.5 * c);
        let t = 1.0 - cos_h;
        let t2 = t * t;
        let fresnel = self.reflectance + (1.0 - self.reflectance) * (t2 * t2 * t);
        let g = fresnel * c * c / (ci * co * w * w);
        if g.is_finite() {
            g
        } else {
            0.0
        }
    }
}

/// A cosine as the geometry factor sees it: in [[`GRAZING_COS`], 1] (`GRAZING_COS` for NaN).
fn grazing_cosine(z: f64) -> f64 {
    if z > GRAZING_COS {
        z.min(1.0)
    } else {
        GRAZING_COS
    }
}

/// A direction's cosine clamped to [0, 1] (0 for NaN): the identity for unit directions above
/// the surface, and a bound on the work of the Bessel sums for any other input.
fn unit_cosine(z: f64) -> f64 {
    if z > 0.0 {
        z.min(1.0)
    } else {
        0.0
    }
}

impl DiffractionBrdf for Stam {
    /// The formula of [`Stam`]; 0 below the surface, for λ < 1 nm (outside optics) and for
    /// non-finite input.
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(both_above(wo, wi) && lambda_nm >= MIN_WAVELENGTH_NM && lambda_nm.is_finite()) {
            return 0.0;
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let ks = 2.0 * PI * self.coherence_nm / lambda_nm;
        let reach = CUTOFF / ks; // in u and v
        if v.abs() >= reach {
            return 0.0;
        }
        let step = lambda_nm / self.equation.period_nm();
        let lo = math::ceil((u - reach) / step);
        let hi = math::floor((u + reach) / step);
        // σ_c ≥ d keeps the range to at most 2·6/(2π) + 1 ≤ 3 orders.
        if lo > hi || lo.abs() > 1e15 || hi.abs() > 1e15 {
            return 0.0;
        }
        let (lo, hi) = (lo as i64, hi as i64);
        let ks2 = ks * ks;
        let lobe = |m: i64| {
            let du = u - m as f64 * step;
            math::exp(-ks2 * (du * du + v * v))
        };
        let phase = self.phase(wo, wi, lambda_nm);
        let sum = match self.profile {
            Profile::Sine => bessel_squares(phase.abs(), lo, hi, &mut |m| lobe(m)),
            Profile::Binary { fraction } => (lo..=hi)
                .map(|m| {
                    let m32 = m.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
                    binary_coefficient(fraction, m32, phase).norm_sqr() * lobe(m)
                })
                .sum(),
        };
        let f = self.geometry(wo, wi) * ks2 / PI * sum;
        if f.is_finite() {
            f
        } else {
            0.0
        }
    }
}

impl SpectralResponse for Stam {
    /// A BRDF: `eval·cos θi` (0 for non-finite input, as `eval`).
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eval(wo, wi, lambda_nm) * unit_cosine(wi.z)
    }

    /// Every order m ≠ 0 with λ_m = d·|u|/|m| in `band`, at most [`MAX_ORDERS`] of them (the
    /// lowest |m|), each with its own lobe's response (`eval·cos θi`) at λ_m (the whole of
    /// `eval` there but for the far tails of the other orders, below 10⁻¹⁶ of their peaks) and
    /// the equivalent width λ_m·d/(2√π·σ_c·|m|). Order 0's lobe is seen where
    /// k·σ_c·√(u² + v²) < 6 at the band's longest wavelength.
    ///
    /// Bounded work: each order's coefficient J_m(φ)² takes at most 2000 recurrence steps,
    /// beyond which it comes from Debye's expansions (which agree with the recurrence to
    /// 10⁻¹¹ of the local amplitude, `src/num/bessel.rs`), so a call over any band costs at most
    /// about 2000·[`MAX_ORDERS`] steps.
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !both_above(wo, wi) {
            return PeakSummary::default();
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let d = self.equation.period_nm();
        let sigma = self.coherence_nm;
        // The response carries cos θi (a BRDF).
        let geometry = self.geometry(wo, wi) * wi.z.min(1.0);
        let mut orders = 0;
        for p in self.equation.orders(u, band).take(MAX_ORDERS as usize) {
            let l = p.wavelength_nm;
            let ks = 2.0 * PI * sigma / l;
            let ks2 = ks * ks;
            // The same cut-off as `eval`: beyond 6 widths off the cone the lobe is 0.
            let efficiency = if l >= MIN_WAVELENGTH_NM && ks * v.abs() < CUTOFF {
                self.profile
                    .efficiency_bounded(p.order, self.phase(wo, wi, l), PEAK_BESSEL_STEPS)
            } else {
                0.0
            };
            let value = geometry * ks2 / PI * efficiency * math::exp(-ks2 * v * v);
            // d/σ_c ≤ 1, so the width is at most λ_m/(2√π): finite.
            let width = l * (d / sigma) / (2.0 * SQRT_PI * (p.order as f64).abs());
            visit(Peak {
                order: p.order,
                wavelength_nm: l,
                intensity: if value.is_finite() { value } else { 0.0 },
                equivalent_width_nm: width,
            });
            orders += 1;
        }
        let reach = CUTOFF * band.max_nm() / (2.0 * PI * sigma);
        PeakSummary {
            orders,
            specular: u * u + v * v < reach * reach,
        }
    }
}

/// Stam's model has no sampler of its own: it uses the crate's documented default, a
/// **cosine-weighted hemisphere** ([`sample_cosine_hemisphere`], density cos θi/π), exact and
/// positive wherever the value is, so every generic test (furnace, reciprocity, χ², finite
/// values) runs on it as on [`GratingBsdf`](crate::GratingBsdf); its weight f·cos θi/pdf = π·f.
/// It finds narrow lobes only by chance: for those, a renderer should prefer light sampling
/// (MIS does this automatically). GLOSSY; [`regularize`](Bsdf::regularize) leaves it
/// unchanged (its lobe widths are parameters of the published model).
///
/// ```
/// use diffraction::{Bsdf, DiffractionBrdf, Profile, Stam};
/// use glam::{DVec2, DVec3};
/// let s = Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?;
/// let wo = DVec3::new(0.3, 0.0, 0.91f64.sqrt());
/// let sample = s.sample(wo, 480.0, 0.0, DVec2::new(0.3, 0.8)).unwrap();
/// assert!((sample.pdf - sample.wi.z / std::f64::consts::PI).abs() < 1e-15);
/// assert_eq!(sample.f, s.eval(wo, sample.wi, 480.0));
/// # Ok::<(), diffraction::Error>(())
/// ```
impl Bsdf for Stam {
    fn sample(&self, wo: DVec3, lambda_nm: f64, _uc: f64, u2: DVec2) -> Option<BsdfSample> {
        if !(wo.z >= MIN_COS_THETA && wo.is_finite() && lambda_nm >= MIN_WAVELENGTH_NM) {
            return None;
        }
        let wi = sample_cosine_hemisphere(u2);
        let pdf = cosine_hemisphere_pdf(wi.z);
        if !(wi.z >= MIN_COS_THETA && pdf > 0.0) {
            return None;
        }
        Some(BsdfSample::new(
            wi,
            self.eval(wo, wi, lambda_nm),
            pdf,
            BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
        ))
    }

    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if both_above(wo, wi) && lambda_nm >= MIN_WAVELENGTH_NM {
            cosine_hemisphere_pdf(wi.z)
        } else {
            0.0
        }
    }

    fn flags(&self) -> BsdfFlags {
        BsdfFlags::REFLECTION | BsdfFlags::GLOSSY
    }

    fn regularize(&mut self) {}
}
