//! The energy-normalised Agu-Hill grating: a radiometric BSDF with exact importance sampling.
//!
//! # The model
//!
//! The paper's grating read as an amplitude grating (slits of width w reflect, the bars between
//! them absorb) in scalar Fraunhofer optics. With (u, v) the tangent part of wi + wo
//! (u = (wi + wo)·t across the grooves, v along them), ρ = w/d, x = d·u/λ:
//!
//! ```text
//! f(wo, wi, λ) = ρ² · S(π·ρ·x) · (N·d/λ)·F_N(π·x) · g(v),    1/sr, cosine excluded,
//! ```
//!
//! with S the single-slit factor, F_N the N-slit factor and g the spread along the grooves
//! ([`GrooveSpread`]). (N·d/λ)·F_N has unit integral in u over each period λ/d and g unit
//! integral in v, and d(wi.x)·d(wi.y) = cos θi·dωi, so ∫ f·cos θi dωi = ∬_D f du dv over the
//! disk D = {(u − wo.x)² + (v − wo.y)² < 1}: over the whole plane that is exactly ρ for every N
//! (Parseval); the albedo is the part inside D, at most ρ ≤ 1. f depends on wi + wo only:
//! reciprocal. Order m carries η_m = ρ²·S(π·ρ·m) ([`GratingBsdf::efficiency`]), the
//! amplitude reading of its order efficiency ([`OrderEfficiency`]).
//!
//! **Limits.** N = ∞ ([`Slits::Infinite`]): delta lobes at u = m·λ/d with weights η_m
//! (SPECULAR; `eval` and `pdf` are 0, `sample` returns them with their discrete probabilities).
//! N = 1: a single slit, f = ρ·(w/λ)·S·g. An ideal groove (g = δ) makes the lobes specular in v.
//!
//! # Physical order efficiencies
//!
//! `GratingBsdf::preset` (feature `presets`) and [`GratingBsdf::with_efficiency`] replace the
//! amplitude reading by tabulated efficiencies of a relief grating on a metal
//! (`OrderEfficiency::Tabulated`, feature `relief`):
//! f = η̃_m·ℓ_m(u, v) with ℓ_m = (N·d/λ)·F_N·g the order's unit-integral lobe and
//! η̃_m = min(η_m(−wi.x, λ), η_m(−wo.x, λ)) (unpolarised), exactly reciprocal; the sampler
//! picks m from the stored efficiencies of wo's table cell with a defensive share
//! (the weight is then at most max_m(η_m/P(m))·B_N·sup g/q_v, B_N below), and the albedo
//! is at most Σ_m η_m(−wo.x, λ) ≤ 1. Off the plane across the grooves (v ≠ 0) the tables are
//! still read at sin θi = −wi.x: the classical-mount approximation. `efficiency.rs` has the
//! details and `docs/radiometry.md` the measurements.
//!
//! # Sampling, with its exact density
//!
//! 1. **Order** (the order weights, `order_weights.rs` and `orders.rs`). The candidate orders are those whose
//!    period [(m − ½)·λ/d, (m + ½)·λ/d) meets the u-range (wo.x − 1, wo.x + 1) of D (for
//!    N = ∞: whose delta u = m·λ/d lies in it). Order m is chosen with probability
//!    P(m) = w_m/Σ w over the candidates, with w_m = η_m/ρ² + ε·U_m for finite N
//!    (ε = [`DEFENSIVE_ORDER_SHARE`], U_m = 3/(3 + (π·ρ·(|m| − ½)₊)²) an upper bound of S over
//!    the period, since S(β) ≤ 3/(3 + β²)), and w_m = η_m/ρ² for N = ∞. The defensive term
//!    keeps P(m) > 0 for missing orders (η_m = 0), where f is small but not 0 for finite N.
//!    When more than `MAX_WEIGHTED_ORDERS` orders are candidates (d/λ above about 127) the
//!    choice is uniform instead (bounded work).
//! 2. **u inside the period** (finite N), from a proxy of F_N (`lobe.rs`), x = m + r,
//!    u = x·λ/d. For N ≥ 2 the Lorentzian r = tan((2ξ − 1)·atan N)/(2N), with density
//!    q(r) = N/((1 + 4N²r²)·atan N) on |r| < ½; F_N(π·r) ≤ 2/(1 + 4N²r²) makes
//!    N·F_N/q ≤ B_N = 2·atan N < π. For N = 1 (F_1 ≡ 1) the uniform r = ξ − ½, q(r) = 1 on
//!    |r| < ½, so N·F_N/q = B_1 = 1 exactly (and no tangent is taken).
//! 3. **v** from the Cauchy proxy of g ([`GrooveSpread::sample`]); g/q_v is at most
//!    [`GrooveSpread::proxy_bound`] (1.4504 for the coherence length, 1.5204 for the Gaussian).
//! 4. **Direction** wi = (u − wo.x, v − wo.y, +√(1 − …)), rejected (`None`) outside the disk.
//!
//! Periods partition the u axis, so one order owns each u and
//! `pdf(wo, wi, λ) = P(m)·q(r)·(d/λ)·q_v(v)·cos θi` (the Jacobian dωi = du dv / cos θi); it
//! is positive wherever f is, and it integrates over the hemisphere to the probability that
//! `sample` returns a direction. The weight is bounded:
//!
//! ```text
//! f·cos θi / pdf = ρ²·S(π·ρ·x)/P(m) · N·F_N/q · g/q_v
//!                ≤ ρ²·(Σ w)·max_m(U_m/w_m) · B_N · sup g/q_v,
//! ```
//!
//! computed by [`GratingBsdf::sample_weight_bound`] (6.6-22 for a CD-like grating; the largest
//! weight measured in the furnace tests is 2.2, at N = 5); for N = ∞ with an ideal groove the
//! weight is the constant ρ²·Σ S(π·ρ·m). The bound holds for every input, also where a lobe is
//! narrower than the rounding of the phase x = d·u/λ (N·|x| beyond about 2⁵²: the sampled r
//! is then lost to rounding when u is re-derived from wi): `eval` and `pdf` read the same
//! rounded phase d·(u/λ), so N·F_N/q ≤ B_N holds at whatever r the returned direction
//! has.
//!
//! # Flags and the specular threshold
//!
//! A finite-N lobe is **GLOSSY** however narrow: `eval`, `sample` and `pdf` form a true density
//! at every width that `f64` resolves (the half-width λ/(N·d) in u is at least 360/(2³²·d),
//! far above the 10⁻¹⁶ resolution of unit vectors). The threshold for SPECULAR is therefore
//! **N = ∞** (or an ideal groove, specular in v). A renderer working in `f32` resolves u only to
//! about 10⁻⁷; [`GratingBsdf::is_near_specular`] reports lobes narrower than
//! `NEAR_SPECULAR_HALF_WIDTH` = 10⁻⁶, for which such a renderer should switch to N = ∞ (the
//! same orders, the same energy) rather than evaluate a lobe it cannot resolve.
//!
//! # Regularisation
//!
//! [`Bsdf::regularize`] widens lobes narrower than `REGULARIZE_MAX_HALF_WIDTH` (0.03 in u and
//! v) like pbrt-v4's microfacet `Regularize` (α < 0.3 → clamp(2α, 0.1, 0.3)): the half-width at
//! 550 nm becomes clamp(2·h, 0.01, 0.03). In u that lowers N (N = ∞ becomes a finite N), in v it
//! shortens the coherence length or widens the Gaussian (an ideal groove becomes a Gaussian
//! σ = 0.01). The orders, their efficiencies and the albedo's Parseval bound ρ do not change.
//!
//! # Parts
//!
//! One file each beside this one: the order efficiencies (`efficiency.rs`,
//! [`OrderEfficiency`]), the order weights the BSDF delegates to (`order_weights.rs`: for one
//! (wo, λ) the candidates, w_m, the choice, each order's factor in f and the order part of the
//! weight bound, built from either efficiency model, so that `eval`, `pdf`, `sample`, their
//! four-wavelength forms, the weight bound and the albedo are written once), the amplitude
//! reading's order distribution (`orders.rs`), the lobes and their proxy (`lobe.rs`), the
//! albedo (`albedo.rs`), the wavelength sampler (`wavelength.rs`) and the near-specular
//! threshold with regularisation (`regularize.rs`).
//!
//! ```
//! use diffraction::{DiffractionBrdf, Grating, GratingBsdf};
//! use glam::DVec3;
//! let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
//! let wo = DVec3::Z;
//! // The first order of 480 nm at normal incidence: u = 0.3.
//! let wi = DVec3::new(0.3, 0.0, 0.91f64.sqrt());
//! // On the peak: ρ²·S(π/2)·N·d/λ·g(0), g(0) = L/λ with L = N·d.
//! let peak = 0.25 * (4.0 / std::f64::consts::PI.powi(2)) * (1000.0f64 * 1600.0 / 480.0).powi(2);
//! assert!((b.eval(wo, wi, 480.0) - peak).abs() < 1e-9 * peak);
//! // Passive: the albedo is at most w/d.
//! let a = b.albedo(wo, 480.0).unwrap();
//! assert!(a > 0.45 && a <= 0.5);
//! # Ok::<(), diffraction::Error>(())
//! ```

use glam::{DVec2, DVec3};

use crate::model::bsdf::{Bsdf, BsdfFlags, BsdfSample};
use crate::model::{both_above, SpectralResponse, MIN_COS_THETA};
use crate::num::random::unit_random;
use crate::num::special::atan;
use crate::optics::groove::{GrooveKind, GrooveSpread};
use crate::path::wavelengths::SampledWavelengths;
use crate::{Band, Grating, Peak, Slits, MAX_ORDERS};
use crate::{DiffractionBrdf, Envelope, GratingResponse, PeakSummary};

mod albedo;
mod efficiency;
mod four;
mod lobe;
mod order_weights;
mod orders;
mod regularize;
mod sampling;
mod wavelength;

pub use efficiency::OrderEfficiency;
#[cfg(feature = "relief")]
pub use efficiency::{Tabulated, MAX_TABULATED_ORDERS};
use lobe::{Lobe, PeriodProxy};
#[cfg(feature = "relief")]
pub use order_weights::TABULATED_DEFENSIVE_SHARE;
use order_weights::{AmplitudeWeights, OrderSource};
use orders::AmplitudeOrders;
pub use orders::DEFENSIVE_ORDER_SHARE;
pub use wavelength::{WavelengthSample, DEFENSIVE_WAVELENGTH_SHARE};

/// The energy-normalised Agu-Hill grating (see the [module docs](self)): a radiometric
/// [`Bsdf`] whose orders carry the power of an amplitude grating, with exact sampling.
///
/// The name says what it is: the grating's BSDF, next to the paper's unitless
/// [`AguHill`](crate::AguHill) intensity, built on the same [`Grating`].
///
/// ```
/// use diffraction::{DiffractionBrdf, Grating, GratingBsdf, GrooveKind, SpectralResponse};
/// use glam::DVec3;
/// let g = Grating::new(1600.0, 800.0, 30)?;
/// let b = GratingBsdf::new(g);
/// assert_eq!(b.groove().kind(), GrooveKind::CoherenceLength { length_nm: 30.0 * 1600.0 });
/// let (wo, wi) = (DVec3::new(0.1, 0.2, 0.95f64.sqrt()), DVec3::new(0.25, -0.2, 0.8955f64.sqrt()));
/// assert_eq!(b.eval(wo, wi, 500.0), b.eval(wi, wo, 500.0)); // reciprocal
/// assert_eq!(b.response(wo, wi, 500.0), b.eval(wo, wi, 500.0) * wi.z); // a BRDF: times cos θi
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct GratingBsdf {
    grating: Grating,
    groove: GrooveSpread,
    efficiency: OrderEfficiency,
    /// Derived from the above by [`GratingBsdf::build`]: where the order weights come from
    /// (the delegate of `order_weights.rs`), the lobe's constants and atan N (π/2 for N = ∞).
    orders: OrderSource,
    lobe: Lobe,
    atan_n: f64,
    /// The proxy of F_N inside a period that u is drawn from (finite N).
    proxy: PeriodProxy,
    /// 1/d, and the groove proxy's scale s = s₀ + s₁·λ ([`GrooveSpread::proxy_scale_affine`]).
    inv_d: f64,
    v_scale: (f64, f64),
}

#[cfg(feature = "serde")]
impl serde::Serialize for GratingBsdf {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("GratingBsdf", 3)?;
        st.serialize_field("grating", &self.grating)?;
        st.serialize_field("groove", &self.groove)?;
        st.serialize_field("efficiency", &self.efficiency)?;
        st.end()
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for GratingBsdf {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Raw {
            grating: Grating,
            groove: GrooveSpread,
            #[serde(default)]
            efficiency: OrderEfficiency,
        }
        let r = Raw::deserialize(d)?;
        Ok(GratingBsdf::build(r.grating, r.groove, r.efficiency))
    }
}

impl GratingBsdf {
    /// The model and everything derived from it.
    fn build(grating: Grating, groove: GrooveSpread, efficiency: OrderEfficiency) -> GratingBsdf {
        let rho = grating.open_fraction();
        // A tabulated model's lobe is the unit-integral (N·d/λ)·F_N·g alone (w = 0: S = 1).
        let tabulated = efficiency.is_tabulated();
        let (n, nd) = match grating.slits() {
            Slits::Finite(n) => (n, n as f64 * grating.period_nm()),
            Slits::Infinite => (0, 0.0),
        };
        let orders = match efficiency.tabulated() {
            None => OrderSource::Amplitude(AmplitudeOrders::new(&grating)),
            #[cfg(feature = "relief")]
            Some(t) => OrderSource::Tabulated {
                table: t.clone(),
                slits: grating.slits(),
            },
            #[cfg(not(feature = "relief"))]
            Some(t) => match *t {},
        };
        GratingBsdf {
            orders,
            lobe: Lobe {
                d: grating.period_nm(),
                w: if tabulated {
                    0.0
                } else {
                    grating.slit_width_nm()
                },
                n,
                scale: if tabulated {
                    nd.min(f64::MAX)
                } else {
                    (rho * rho * nd).min(f64::MAX)
                },
                groove,
            },
            atan_n: atan(grating.slits().as_f64()),
            proxy: PeriodProxy::new(n, atan(grating.slits().as_f64())),
            inv_d: 1.0 / grating.period_nm(),
            v_scale: groove.proxy_scale_affine(),
            grating,
            groove,
            efficiency,
        }
    }

    /// The radiometric grating with the natural groove spread: a coherence length L = N·d (a
    /// square coherently lit patch; taken into [`MIN_COHERENCE_NM`](crate::optics::groove::MIN_COHERENCE_NM)
    /// … [`MAX_COHERENCE_NM`](crate::optics::groove::MAX_COHERENCE_NM)), or the ideal δ(v) for N = ∞.
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread};
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// assert_eq!(b.groove(), GrooveSpread::IDEAL);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn new(grating: Grating) -> GratingBsdf {
        let groove = match grating.slits() {
            Slits::Finite(n) => {
                GrooveSpread::coherence_length_clamped(n as f64 * grating.period_nm())
                    .unwrap_or(GrooveSpread::IDEAL)
            }
            Slits::Infinite => GrooveSpread::IDEAL,
        };
        GratingBsdf::build(grating, groove, OrderEfficiency::Amplitude)
    }

    /// The same grating with the groove spread `groove` (validated where it was built).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread};
    /// let rough = GrooveSpread::gaussian(0.02)?;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?).with_groove(rough);
    /// assert_eq!(b.groove(), rough);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn with_groove(&self, groove: GrooveSpread) -> GratingBsdf {
        GratingBsdf::build(self.grating, groove, self.efficiency.clone())
    }

    /// The grating.
    ///
    /// ```
    /// # use diffraction::{Grating, GratingBsdf};
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// assert_eq!(GratingBsdf::new(g).grating(), &g);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn grating(&self) -> &Grating {
        &self.grating
    }

    /// The spread along the grooves.
    ///
    /// ```
    /// # use diffraction::{Grating, GratingBsdf, GrooveSpread};
    /// let b = GratingBsdf::new(Grating::new(1000.0, 500.0, 10)?);
    /// assert_eq!(b.groove(), GrooveSpread::coherence_length(10_000.0)?);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn groove(&self) -> GrooveSpread {
        self.groove
    }

    /// The half-width λ/(N·d) in u of every lobe (the distance from a peak to the first zero of
    /// F_N); 0 for N = ∞ and for λ that is not a positive finite number. Finite for every input.
    ///
    /// ```
    /// # use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
    /// assert_eq!(b.lobe_half_width(480.0), 480.0 / 1.6e6);
    /// assert!(GratingBsdf::new(Grating::new(5e-324, 5e-324, 1)?).lobe_half_width(500.0).is_finite());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn lobe_half_width(&self, lambda_nm: f64) -> f64 {
        if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        match self.grating.slits() {
            Slits::Finite(n) => (lambda_nm / (n as f64 * self.grating.period_nm())).min(f64::MAX),
            Slits::Infinite => 0.0,
        }
    }

    /// The bound of f·cos θi/pdf for samples from `wo` at λ (see the [module docs](self)):
    /// ρ²·(Σ w)·max_m(U_m/w_m)·B_N·sup g/q_v for finite N (B_N = 2·atan N, the Lorentzian
    /// proxy's bound of N·F_N/q, for N ≥ 2; B_1 = 1, the uniform proxy's); ρ²·Σ w·sup g/q_v
    /// for N = ∞. 0 where nothing is sampled; for the uniform order choice (K candidates)
    /// ρ²·K·max_m U_m·B_N·sup g/q_v.
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let bound = b.sample_weight_bound(DVec3::Z, 550.0);
    /// assert!(bound > 0.5 && bound < 25.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn sample_weight_bound(&self, wo: DVec3, lambda_nm: f64) -> f64 {
        if !(wo.z >= MIN_COS_THETA && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        let order = self
            .with_weights(wo, lambda_nm, |w| w.order_bound())
            .unwrap_or(0.0);
        let fu = match self.grating.slits() {
            Slits::Infinite => 1.0,
            Slits::Finite(_) => self.proxy.bound(),
        };
        (order * fu * self.groove.proxy_bound()).min(f64::MAX)
    }
}

impl DiffractionBrdf for GratingBsdf {
    /// ρ²·S·(N·d/λ)·F_N·g(v) at u = wi.x + wo.x, v = wi.y + wo.y; 0 below the surface, for
    /// λ ≤ 0, for non-finite input and for delta lobes (N = ∞ or an ideal groove).
    #[inline]
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(both_above(wo, wi) && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        if !self.is_glossy() {
            return 0.0;
        }
        self.value(wo, wi, lambda_nm)
    }

    /// Shares the hemisphere checks, u, v and (Gaussian groove) g(v) between the four
    /// wavelengths, and evaluates them as four branch-free lanes, each the same operations as
    /// [`eval`](DiffractionBrdf::eval) (so `eval4` equals four `eval` calls to the bit).
    fn eval4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        let out = [0.0; 4];
        if !(both_above(wo, wi) && self.is_glossy()) {
            return out;
        }
        if let OrderSource::Tabulated { .. } = self.orders {
            return self.eval4_tabulated(wo, wi, lambdas);
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let l = lambdas.lambda();
        let ok = l.map(|l| l > 0.0 && l.is_finite());
        // A lane with an invalid λ computes at λ = 1 and is zeroed below.
        let l = [0, 1, 2, 3].map(|k| if ok[k] { l[k] } else { 1.0 });
        let q = l.map(|l| u / l);
        // The four lanes side by side; the Gaussian's g(v) is the same for every λ and is
        // computed once.
        let g = match self.groove.kind() {
            GrooveKind::Gaussian { .. } => [self.lobe.groove_factor(v, 1.0); 4],
            _ => l.map(|l| self.lobe.groove_factor(v, l)),
        };
        let mut num = [0.0; 4];
        let mut den = [0.0; 4];
        for k in 0..4 {
            (num[k], den[k]) = self.lobe.ratio(q[k], g[k], v, l[k]);
        }
        let mut f = [
            num[0] / den[0],
            num[1] / den[1],
            num[2] / den[2],
            num[3] / den[3],
        ];
        for k in 0..4 {
            if !((self.lobe.d * q[k]).is_finite() && f[k].is_finite() && ok[k]) {
                f[k] = 0.0;
            }
        }
        f
    }
}

impl SpectralResponse for GratingBsdf {
    /// The BRDF times cos θi.
    #[inline]
    fn response(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eval(wo, wi, lambda_nm) * wi.z.min(1.0)
    }

    /// Every order m ≠ 0 with λ_m = d·|u|/|m| in `band`: for finite N with the response f·cos θi at
    /// the peak, cos θi·ρ²·S(π·ρ·m)·(N·d/λ_m)·g(v; λ_m), and the equivalent width λ_m/(|m|·N), whose
    /// product is the order's spectral area η_m·(d/|m|)·g (independent of N). For N = ∞ (delta
    /// peaks) `intensity` is cos θi·η_m·g(v; λ_m) and `equivalent_width_nm` is d/|m| = |dλ/du|, so
    /// that the product is again the area. For an ideal groove g is taken as 1 where v = 0 and
    /// 0 elsewhere. Order 0 is seen where |u| < λ_max/(N·d) (never for N = ∞, whose order 0 is
    /// a delta in u).
    fn peaks(&self, wo: DVec3, wi: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !both_above(wo, wi) {
            return PeakSummary::default();
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let d = self.grating.period_nm();
        let cos_i = wi.z.min(1.0);
        let g_at = |l: f64| {
            if self.groove.is_delta() {
                if v == 0.0 {
                    1.0
                } else {
                    0.0
                }
            } else {
                self.groove.value(v, l)
            }
        };
        let peaks = self.grating.peaks(u, band);
        let specular = match self.grating.slits() {
            Slits::Finite(_) => peaks.specular(),
            Slits::Infinite => false,
        };
        let mut orders = 0;
        for p in peaks.take(MAX_ORDERS as usize) {
            let l = p.wavelength_nm;
            let eta = self.efficiency_at(p.order, wo, wi, l);
            let am = p.order.unsigned_abs() as f64;
            let (intensity, width) = match self.grating.slits() {
                Slits::Finite(n) => (
                    cos_i * eta * (n as f64 * d / l) * g_at(l),
                    l / (am * n as f64),
                ),
                Slits::Infinite => (cos_i * eta * g_at(l), d / am),
            };
            visit(Peak {
                order: p.order,
                wavelength_nm: l,
                intensity: if intensity.is_finite() {
                    intensity
                } else {
                    0.0
                },
                equivalent_width_nm: width,
            });
            orders += 1;
        }
        PeakSummary { orders, specular }
    }

    /// For finite N, f·cos θi = cos θi·ρ²·N·d·(g(v, λ)/λ)·I(u, λ): the grating's intensity times
    /// the envelope λ⁻¹ (a groove spread that does not depend on λ) or λ⁻²·sinc²(π·L·v/λ) (a
    /// coherence length L, whose g is (L/λ)·sinc²(π·L·v/λ)), so the colour integrator takes its
    /// lobe-exact paths. `None` for N = ∞ and the ideal groove (delta lobes: `eval` is 0 and
    /// the colour is the peaks' areas), below the horizon, and where u = wi.x + wo.x or
    /// v = wi.y + wo.y is not finite (non-unit inputs whose sum overflows).
    fn grating_response(&self, wo: DVec3, wi: DVec3) -> Option<GratingResponse> {
        if !both_above(wo, wi) {
            return None;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return None;
        };
        if let OrderSource::Tabulated { .. } = self.orders {
            // η̃ depends on λ, which the envelope cannot express: the generic colour path.
            return None;
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        if !(u.is_finite() && v.is_finite()) {
            // Components beyond unit vectors whose sum overflows: no finite phase.
            return None;
        }
        let rho = self.grating.open_fraction();
        let base = wi.z.min(1.0) * rho * rho * n as f64 * self.grating.period_nm();
        let (scale, envelope) = match self.groove.kind() {
            GrooveKind::CoherenceLength { length_nm } => (
                base * length_nm,
                Envelope::new(2, (length_nm * v).abs()).ok()?,
            ),
            GrooveKind::Gaussian { .. } => (
                // g(v) at any wavelength: it does not depend on λ.
                base * self.groove.value(v, 1.0),
                Envelope::new(1, 0.0).ok()?,
            ),
            _ => return None,
        };
        scale
            .is_finite()
            .then(|| GratingResponse::new(self.grating, u, scale).with_envelope(envelope))
    }
}

impl Bsdf for GratingBsdf {
    fn sample(&self, wo: DVec3, lambda_nm: f64, uc: f64, u2: DVec2) -> Option<BsdfSample> {
        if !(wo.z >= MIN_COS_THETA && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return None;
        }
        let xi = [unit_random(uc), unit_random(u2.x), unit_random(u2.y)];
        match &self.orders {
            OrderSource::Amplitude(a) => {
                let w = AmplitudeWeights {
                    dist: a,
                    c: a.candidates(wo, self.grating.period_nm() / lambda_nm)?,
                };
                self.sample_with(&w, wo, lambda_nm, xi)
            }
            OrderSource::Tabulated { .. } => self.sample_tabulated(wo, lambda_nm, xi),
        }
    }

    /// P(m)·q(r)·(d/λ)·q_v(v)·cos θi for the order m owning u (see the [module docs](self));
    /// 0 for delta lobes, below the surface and for non-finite input.
    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(both_above(wo, wi) && lambda_nm > 0.0 && lambda_nm.is_finite() && self.is_glossy()) {
            return 0.0;
        }
        self.pdf_finite(wo, wi, lambda_nm)
    }

    /// Shares the checks, u and v (and a table's location of wo); the candidate orders depend
    /// on λ and are found per λ.
    fn pdf4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        let mut out = [0.0; 4];
        if !(both_above(wo, wi) && self.is_glossy()) {
            return out;
        }
        if let OrderSource::Tabulated { .. } = self.orders {
            return self.pdf4_tabulated(wo, wi, lambdas);
        }
        for (o, &l) in out.iter_mut().zip(lambdas.lambda().iter()) {
            if l > 0.0 && l.is_finite() {
                *o = self.pdf_finite(wo, wi, l);
            }
        }
        out
    }

    /// The hero's `sample` and the secondaries' values and densities at its direction, sharing
    /// the checks and (u, v) (`four.rs`); equal to `sample` + `eval4` + `pdf4` to the bit.
    fn sample4(
        &self,
        wo: DVec3,
        lambdas: &SampledWavelengths,
        uc: f64,
        u2: DVec2,
    ) -> Option<crate::BsdfSample4> {
        self.sample_four(wo, lambdas, uc, u2)
    }

    /// REFLECTION | GLOSSY for finite N with a groove spread; REFLECTION | SPECULAR for N = ∞
    /// or an ideal groove (the threshold is discussed in the [module docs](self)).
    fn flags(&self) -> BsdfFlags {
        match (self.grating.slits(), self.groove.is_delta()) {
            (Slits::Finite(_), false) => BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
            _ => BsdfFlags::REFLECTION | BsdfFlags::SPECULAR,
        }
    }

    /// Widens narrow lobes (see `REGULARIZE_MAX_HALF_WIDTH` and the [module docs](self)).
    fn regularize(&mut self) {
        *self = self.regularized();
    }
}
