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
//! reciprocal. Order m carries η_m = ρ²·S(π·ρ·m) ([`GratingBsdf::efficiency`]).
//!
//! **Limits.** N = ∞ ([`Slits::Infinite`]): delta lobes at u = m·λ/d with weights η_m
//! (SPECULAR; `f` and `pdf` are 0, `sample` returns them with their discrete probabilities).
//! N = 1: a single slit, f = ρ·(w/λ)·S·g. An ideal groove (g = δ) makes the lobes specular in v.
//!
//! # Sampling, with its exact density
//!
//! 1. **Order.** The candidate orders are those whose period [(m − ½)·λ/d, (m + ½)·λ/d) meets
//!    the u-range (wo.x − 1, wo.x + 1) of D (for N = ∞: whose delta u = m·λ/d lies in it).
//!    Order m is chosen with probability P(m) = w_m/Σ w over the candidates, with
//!    w_m = S(π·ρ·m) + ε·U_m for finite N (ε = [`DEFENSIVE_ORDER_SHARE`], U_m =
//!    3/(3 + (π·ρ·(|m| − ½)₊)²) an upper bound of S over the period, since S(β) ≤ 3/(3 + β²)),
//!    and w_m = S(π·ρ·m) for N = ∞. The defensive term keeps P(m) > 0 for missing orders
//!    (S(π·ρ·m) = 0), where f is small but not 0 for finite N. When more than
//!    [`MAX_WEIGHTED_ORDERS`] orders are candidates (d/λ above about 127) the choice is uniform
//!    instead (bounded work).
//! 2. **u inside the period** (finite N), from the Lorentzian proxy of F_N:
//!    r = tan((2ξ − 1)·atan N)/(2N), x = m + r, u = x·λ/d, with density
//!    q(r) = N/((1 + 4N²r²)·atan N) on |r| < ½. F_N(π·r) ≤ 2/(1 + 4N²r²) makes
//!    N·F_N/q ≤ 2·atan N < π for every N.
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
//!                ≤ ρ²·(Σ w)·max_m(U_m/w_m) · 2·atan N · sup g/q_v,
//! ```
//!
//! computed by [`GratingBsdf::sample_weight_bound`] (10-22 for a CD-like grating; the largest
//! weight measured in the furnace tests is 2.65, at N = 1); for N = ∞ with an ideal groove the weight is the constant ρ²·Σ S(π·ρ·m).
//!
//! # Flags and the specular threshold
//!
//! A finite-N lobe is **GLOSSY** however narrow: `f`, `sample` and `pdf` form a true density
//! at every width that `f64` resolves (the half-width λ/(N·d) in u is at least 360/(2³²·d),
//! far above the 10⁻¹⁶ resolution of unit vectors). The threshold for SPECULAR is therefore
//! **N = ∞** (or an ideal groove, specular in v). A renderer working in `f32` resolves u only to
//! about 10⁻⁷; [`GratingBsdf::is_near_specular`] reports lobes narrower than
//! [`NEAR_SPECULAR_HALF_WIDTH`] = 10⁻⁶, for which such a renderer should switch to N = ∞ (the
//! same orders, the same energy) rather than evaluate a lobe it cannot resolve.
//!
//! # Regularisation
//!
//! [`Bsdf::regularize`] widens lobes narrower than [`REGULARIZE_MAX_HALF_WIDTH`] (0.03 in u and
//! v) like pbrt-v4's microfacet `Regularize` (α < 0.3 → clamp(2α, 0.1, 0.3)): the half-width at
//! 550 nm becomes clamp(2·h, 0.01, 0.03). In u that lowers N (N = ∞ becomes a finite N), in v it
//! shortens the coherence length or widens the Gaussian (an ideal groove becomes a Gaussian
//! σ = 0.01). The orders, their efficiencies and the albedo's Parseval bound ρ do not change.
//!
//! ```
//! use diffraction::{Bsdf, Grating, GratingBsdf};
//! use glam::{DVec2, DVec3};
//! let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
//! let wo = DVec3::Z;
//! // The first order of 480 nm at normal incidence: u = 0.3.
//! let wi = DVec3::new(0.3, 0.0, 0.91f64.sqrt());
//! // On the peak: ρ²·S(π/2)·N·d/λ·g(0), g(0) = L/λ with L = N·d.
//! let peak = 0.25 * (4.0 / std::f64::consts::PI.powi(2)) * (1000.0f64 * 1600.0 / 480.0).powi(2);
//! assert!((b.f(wo, wi, 480.0) - peak).abs() < 1e-9 * peak);
//! // Passive: the albedo is at most w/d.
//! let a = b.albedo(wo, 480.0).unwrap();
//! assert!(a > 0.45 && a <= 0.5);
//! # Ok::<(), diffraction::Error>(())
//! ```

use core::f64::consts::PI;

use glam::{DVec2, DVec3};

use crate::bxdf::bsdf::{Bsdf, BsdfFlags, BsdfSample, SampledWavelengths};
use crate::error::Error;
use crate::groove::GrooveSpread;
use crate::kernel::{intensity_ratio_flat, single_slit_cycles, sinpi_flat};
use crate::math;
use crate::special::{atan, tan};
use crate::{Band, Grating, Peak, Slits};
use crate::{DiffractionBrdf, Envelope, GratingResponse, PeakSummary};

/// The share ε of the envelope bound U_m in the order weights w_m = S(π·ρ·m) + ε·U_m.
pub const DEFENSIVE_ORDER_SHARE: f64 = 0.125;
/// Above this many candidate orders the order is chosen uniformly (bounded work per call).
pub const MAX_WEIGHTED_ORDERS: i64 = 256;
/// [`GratingBsdf::albedo`] returns `None` above this many candidate orders.
pub const MAX_ALBEDO_ORDERS: i64 = 512;
/// Lobes narrower than this half-width in u (at the band's shortest wavelength) are reported by
/// [`GratingBsdf::is_near_specular`].
pub const NEAR_SPECULAR_HALF_WIDTH: f64 = 1e-6;
/// [`Bsdf::regularize`] widens lobes whose half-width at 550 nm is below this (in u or v).
pub const REGULARIZE_MAX_HALF_WIDTH: f64 = 0.03;
/// The smallest half-width [`Bsdf::regularize`] produces.
pub const REGULARIZE_MIN_HALF_WIDTH: f64 = 0.01;
/// The wavelength at which [`Bsdf::regularize`] measures widths, nm.
const REGULARIZE_REFERENCE_NM: f64 = 550.0;
/// The uniform share of [`GratingBsdf::sample_wavelength`].
pub const DEFENSIVE_WAVELENGTH_SHARE: f64 = 0.1;
/// [`GratingBsdf::sample_wavelength`] follows at most this many peaks (in order of |m|); the
/// uniform share covers the rest.
pub const MAX_WAVELENGTH_PEAKS: usize = 64;
/// Directions with cos θ below this count as below the horizon (f = pdf = 0, never sampled):
/// it keeps f/pdf finite (the pdf carries a factor cos θi) at a cost of a solid angle of 2π·10⁻¹⁰⁰.
pub const MIN_COS_THETA: f64 = 1e-100;
/// x = d·u/λ beyond this magnitude is not sampled (orders would not fit an `i64` exactly).
const MAX_PHASE: f64 = 4.0e15;

/// The energy-normalised Agu-Hill grating (see the [module docs](self)): a radiometric
/// [`Bsdf`] whose orders carry the power of an amplitude grating, with exact sampling.
///
/// The name says what it is: the grating's BSDF, next to the paper's unitless
/// [`AguHill`](crate::AguHill) intensity, built on the same [`Grating`].
///
/// ```
/// use diffraction::{Bsdf, DiffractionBrdf, Grating, GratingBsdf, GrooveSpread};
/// use glam::DVec3;
/// let g = Grating::new(1600.0, 800.0, 30)?;
/// let b = GratingBsdf::new(g);
/// assert_eq!(b.groove(), GrooveSpread::CoherenceLength { length_nm: 30.0 * 1600.0 });
/// let (wo, wi) = (DVec3::new(0.1, 0.2, 0.95f64.sqrt()), DVec3::new(0.25, -0.2, 0.8955f64.sqrt()));
/// assert_eq!(b.eval(wi, wo, 500.0), b.f(wo, wi, 500.0));
/// assert!(!b.cosine_included());
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct GratingBsdf {
    grating: Grating,
    groove: GrooveSpread,
    /// Derived from `grating` (rebuilt by every constructor and by `regularize`).
    #[cfg_attr(feature = "serde", serde(skip))]
    cache: Cache,
}

/// Orders |m| ≤ this have their weights w_m summed in a table, so that the order choice and
/// its probability cost O(log K) and O(1) instead of O(K).
const TABLE_ORDERS: usize = 64;

/// What `sample` and `pdf` would otherwise recompute on every call.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Cache {
    /// atan N (π/2 for N = ∞).
    atan_n: f64,
    /// w_0.
    w0: f64,
    /// prefix\[k\] = Σ_{j=1}^{k} w_j (w is even in m).
    prefix: [f64; TABLE_ORDERS + 1],
    /// weight\[k\] = w_k = w_{−k}, exactly as [`order_weight`] computes it.
    weight: [f64; TABLE_ORDERS + 1],
    /// ρ².
    rho2: f64,
    /// N·d (0 for N = ∞).
    nd: f64,
}

impl Cache {
    fn new(grating: &Grating) -> Cache {
        let rho = grating.slit_width_nm() / grating.period_nm();
        let mut prefix = [0.0; TABLE_ORDERS + 1];
        let mut weight = [0.0; TABLE_ORDERS + 1];
        weight[0] = order_weight(grating.slits(), rho, 0);
        for k in 1..=TABLE_ORDERS {
            weight[k] = order_weight(grating.slits(), rho, k as i64);
            prefix[k] = prefix[k - 1] + weight[k];
        }
        Cache {
            atan_n: atan(grating.slits().as_f64()),
            w0: weight[0],
            prefix,
            weight,
            rho2: rho * rho,
            nd: match grating.slits() {
                Slits::Finite(n) => n as f64 * grating.period_nm(),
                Slits::Infinite => 0.0,
            },
        }
    }

    /// Σ_{k=a}^{b} w_k for −64 ≤ a ≤ b ≤ 64.
    #[inline]
    fn sum(&self, a: i64, b: i64) -> f64 {
        let p = |k: i64| self.prefix[k as usize];
        if a >= 1 {
            p(b) - p(a - 1)
        } else if b <= -1 {
            p(-a) - p(-b - 1)
        } else {
            p(-a) + self.w0 + p(b)
        }
    }
}

/// The weight w_m of order m in the order choice.
#[inline]
fn order_weight(slits: Slits, rho: f64, m: i64) -> f64 {
    let s = single_slit_cycles(rho * m as f64);
    match slits {
        Slits::Infinite => s,
        Slits::Finite(_) => s + DEFENSIVE_ORDER_SHARE * envelope_bound(rho, m),
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for GratingBsdf {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        struct Raw {
            grating: Grating,
            groove: GrooveSpread,
        }
        let r = Raw::deserialize(d)?;
        GratingBsdf::new(r.grating)
            .with_groove(r.groove)
            .map_err(serde::de::Error::custom)
    }
}

/// The candidate orders for one (wo, λ) and the normaliser of their weights.
#[derive(Debug, Clone, Copy)]
struct Candidates {
    lo: i64,
    hi: i64,
    total: f64,
    uniform: bool,
}

/// One sampled wavelength (see [`GratingBsdf::sample_wavelength`]).
///
/// ```
/// use diffraction::{Band, Grating, GratingBsdf};
/// use glam::DVec3;
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
/// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
/// let s = b.sample_wavelength(wo, wi, Band::VISIBLE, 0.5).unwrap();
/// assert!((s.lambda_nm - 480.0).abs() < 1.0); // near the first-order peak
/// assert!((s.pdf - b.wavelength_pdf(wo, wi, Band::VISIBLE, s.lambda_nm)).abs() < 1e-9 * s.pdf);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct WavelengthSample {
    /// The wavelength, nm, inside the band.
    pub lambda_nm: f64,
    /// Its density, 1/nm.
    pub pdf: f64,
}

impl GratingBsdf {
    /// The radiometric grating with the natural groove spread: a coherence length L = N·d (a
    /// square coherently lit patch), or the ideal δ(v) for N = ∞.
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread};
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// assert_eq!(b.groove(), GrooveSpread::Ideal);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn new(grating: Grating) -> GratingBsdf {
        let groove = match grating.slits() {
            Slits::Finite(n) => GrooveSpread::CoherenceLength {
                length_nm: n as f64 * grating.period_nm(),
            },
            Slits::Infinite => GrooveSpread::Ideal,
        };
        GratingBsdf {
            grating,
            groove,
            cache: Cache::new(&grating),
        }
    }

    /// Sets the groove spread, validated ([`GrooveSpread::validate`]).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?)
    ///     .with_groove(GrooveSpread::Gaussian { sigma: 0.02 })?;
    /// assert_eq!(b.groove(), GrooveSpread::Gaussian { sigma: 0.02 });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_groove(self, groove: GrooveSpread) -> Result<GratingBsdf, Error> {
        Ok(GratingBsdf {
            groove: groove.validate()?,
            ..self
        })
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
    /// assert_eq!(b.groove(), GrooveSpread::CoherenceLength { length_nm: 10_000.0 });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn groove(&self) -> GrooveSpread {
        self.groove
    }

    /// ρ = w/d, the open fraction.
    fn duty(&self) -> f64 {
        self.grating.slit_width_nm() / self.grating.period_nm()
    }

    /// The efficiency η_m = ρ²·S(π·ρ·m) of order m: the share of the incident power it carries
    /// over the whole (u, v) plane. Σ_m η_m = ρ (Parseval).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert_eq!(b.efficiency(0), 0.25);
    /// assert!(b.efficiency(2) < 1e-30); // w = d/2: even orders are missing
    /// let total: f64 = (-20000..=20000).map(|m| b.efficiency(m)).sum();
    /// assert!((total - 0.5).abs() < 1e-5); // Parseval, to the 1/m² tail
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn efficiency(&self, order: i32) -> f64 {
        let rho = self.duty();
        rho * rho * single_slit_cycles(rho * order as f64)
    }

    /// The half-width λ/(N·d) in u of every lobe (the distance from a peak to the first zero of
    /// F_N); 0 for N = ∞.
    ///
    /// ```
    /// # use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
    /// assert_eq!(b.lobe_half_width(480.0), 480.0 / 1.6e6);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn lobe_half_width(&self, lambda_nm: f64) -> f64 {
        match self.grating.slits() {
            Slits::Finite(n) => lambda_nm / (n as f64 * self.grating.period_nm()),
            Slits::Infinite => 0.0,
        }
    }

    /// Whether the lobes at 360 nm are narrower than [`NEAR_SPECULAR_HALF_WIDTH`] in u or v
    /// (advice for `f32` renderers, see the [module docs](self)); always `false` for N = ∞ and
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
        let hv = match self.groove {
            GrooveSpread::CoherenceLength { length_nm } => l / length_nm,
            GrooveSpread::Gaussian { sigma } => sigma,
            GrooveSpread::Ideal => return false,
        };
        hu > 0.0 && (hu < NEAR_SPECULAR_HALF_WIDTH || hv < NEAR_SPECULAR_HALF_WIDTH)
    }

    /// The weight w_m of order m in the order choice.
    #[inline]
    fn order_weight(&self, m: i64) -> f64 {
        let k = m.unsigned_abs();
        if k <= TABLE_ORDERS as u64 {
            self.cache.weight[k as usize]
        } else {
            order_weight(self.grating.slits(), self.duty(), m)
        }
    }

    /// Whether [lo, hi] lies inside the table.
    #[inline]
    fn tabled(lo: i64, hi: i64) -> bool {
        lo >= -(TABLE_ORDERS as i64) && hi <= TABLE_ORDERS as i64
    }

    /// The candidate orders for wo at step λ/d (u per order), or `None` when there are none.
    #[inline]
    fn candidates(&self, wo: DVec3, step: f64) -> Option<Candidates> {
        let x_lo = (wo.x - 1.0) / step;
        let x_hi = (wo.x + 1.0) / step;
        if !(x_lo.abs() < MAX_PHASE && x_hi.abs() < MAX_PHASE) {
            return None;
        }
        let (lo, hi) = match self.grating.slits() {
            Slits::Finite(_) => (
                floor_exact(x_lo - 0.5) as i64 + 1,
                ceil_exact(x_hi + 0.5) as i64 - 1,
            ),
            Slits::Infinite => (floor_exact(x_lo) as i64 + 1, ceil_exact(x_hi) as i64 - 1),
        };
        if hi < lo {
            return None;
        }
        let count = hi - lo + 1;
        if count > MAX_WEIGHTED_ORDERS {
            return Some(Candidates {
                lo,
                hi,
                total: count as f64,
                uniform: true,
            });
        }
        let total = if Self::tabled(lo, hi) {
            self.cache.sum(lo, hi)
        } else {
            let mut total = 0.0;
            for m in lo..=hi {
                total += self.order_weight(m);
            }
            total
        };
        (total > 0.0).then_some(Candidates {
            lo,
            hi,
            total,
            uniform: false,
        })
    }

    /// Chooses an order from `uc` in [0, 1); returns it with its probability.
    fn choose_order(&self, c: &Candidates, uc: f64) -> (i64, f64) {
        if c.uniform {
            let k = ((uc * c.total) as i64).clamp(0, c.hi - c.lo);
            return (c.lo + k, 1.0 / c.total);
        }
        let target = uc * c.total;
        if Self::tabled(c.lo, c.hi) {
            // The first m with Σ_{lo}^{m} w > target, by bisection on the table's sums.
            let (mut a, mut b) = (c.lo, c.hi);
            while a < b {
                let mid = a + (b - a) / 2;
                if self.cache.sum(c.lo, mid) > target {
                    b = mid;
                } else {
                    a = mid + 1;
                }
            }
            let mut m = a;
            while m > c.lo && self.order_weight(m) == 0.0 {
                m -= 1;
            }
            return (m, self.order_weight(m) / c.total);
        }
        let mut acc = 0.0;
        let mut last = c.lo;
        for m in c.lo..=c.hi {
            let w = self.order_weight(m);
            if w > 0.0 {
                last = m;
                acc += w;
                if target < acc {
                    return (m, w / c.total);
                }
            }
        }
        (last, self.order_weight(last) / c.total)
    }

    /// f at (u, v) for finite N and a non-ideal groove, after the hemisphere checks.
    #[inline]
    fn value_uv(&self, n: u32, u: f64, v: f64, lambda_nm: f64) -> f64 {
        let q = u / lambda_nm;
        let (big, coherent) = match self.groove {
            GrooveSpread::CoherenceLength { length_nm } => (length_nm / lambda_nm, true),
            _ => (self.groove.value_unchecked(v, lambda_nm), false),
        };
        let (num, den) = self.lane(n, q, big, coherent, v, lambda_nm);
        let f = num / den;
        if (self.grating.period_nm() * q).is_finite() && f.is_finite() {
            f
        } else {
            0.0
        }
    }

    /// f = ρ²·(N·d/λ)·G·(a/b)² as a numerator and a denominator (one division), without
    /// branches, from q = u/λ: (a/b)² = S(π·w·q)·F_N(π·d·q) ([`intensity_ratio_flat`]); for a
    /// coherence length (`coherent`) G = k = L/λ (`big`) and a/b also carries sin(π·t)/(π·t),
    /// t = k·v, so that G·(a/b)² holds g = k·sinc²(π·t); otherwise G = g(v) (`big`). `f`,
    /// `f4` and `sample` all go through here, so they agree to the last bit.
    #[inline(always)]
    fn lane(&self, n: u32, q: f64, big: f64, coherent: bool, v: f64, lambda_nm: f64) -> (f64, f64) {
        let (d, w) = (self.grating.period_nm(), self.grating.slit_width_nm());
        let (mut a, mut b) = if n == 1 {
            // F_1 = 1: the single slit alone, as in `intensity_ratio_flat`.
            let y = w * q;
            let small = y.abs() < 1e-8;
            (
                if small {
                    1.0
                } else {
                    sinpi_flat(y - math::rint(y))
                },
                if small { 1.0 } else { PI * y },
            )
        } else {
            intensity_ratio_flat(d * q, w * q, n)
        };
        let mut big = big;
        if coherent {
            let t = big * v;
            let bt = PI * t;
            let small = bt.abs() < 1e-8;
            a *= if small {
                1.0
            } else {
                sinpi_flat(t - math::rint(t))
            };
            b *= if small { 1.0 } else { bt };
            // g = 0 where t overflows, as `GrooveSpread::value`.
            if !t.is_finite() {
                big = 0.0;
            }
        }
        (
            self.cache.rho2 * self.cache.nd * big * (a * a),
            (b * b) * lambda_nm,
        )
    }

    /// The bound of f·cos θi/pdf for samples from `wo` at λ (see the [module docs](self)):
    /// ρ²·(Σ w)·max_m(U_m/w_m)·2·atan N·sup g/q_v for finite N; ρ²·Σ w·sup g/q_v for N = ∞.
    /// 0 where nothing is sampled; for the uniform order choice (K candidates)
    /// ρ²·K·max_m U_m·2·atan N·sup g/q_v.
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
        if !(wo.z > 0.0 && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        let step = lambda_nm / self.grating.period_nm();
        let Some(c) = self.candidates(wo, step) else {
            return 0.0;
        };
        let rho = self.duty();
        let gv = self.groove.proxy_bound();
        match self.grating.slits() {
            Slits::Infinite => rho * rho * c.total * gv,
            Slits::Finite(_) => {
                let fu = 2.0 * self.cache.atan_n;
                if c.uniform {
                    return rho * rho * c.total * fu * gv;
                }
                let mut worst: f64 = 0.0;
                for m in c.lo..=c.hi {
                    worst = worst.max(envelope_bound(rho, m) / self.order_weight(m));
                }
                rho * rho * c.total * worst * fu * gv
            }
        }
    }

    /// The albedo ∫ f·cos θi dωi for light leaving toward `wo` at λ: the part of every lobe
    /// inside the disk D (see the [module docs](self)); at most ρ = w/d. `None` when more than
    /// [`MAX_ALBEDO_ORDERS`] orders are candidates; 0 below the surface.
    ///
    /// N = ∞: the closed form Σ_m η_m·∫ g over the chord of D at u = m·λ/d (by
    /// [`GrooveSpread::mass`]). Finite N: per period, Gauss-Legendre (8 points) on every side
    /// lobe of F_N out to 64 lobes from the peak (all of them for N ≤ 128), and beyond them
    /// F_N replaced by its local mean 1/(2N²·sin²(π·r)) on 24 geometric pieces (the error of
    /// that average is below 1/(2π²·64³) of the lobe's area); the pieces are split where the
    /// chord meets the edge of D. Relative accuracy about 10⁻⁶ (tests compare with an
    /// independent quadrature of `f`).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// // Normal incidence at 550 nm: orders −2 … 2 propagate (|m|·λ/d < 1); 0 and ±1 carry light.
    /// let want = b.efficiency(0) + 2.0 * b.efficiency(1) + 2.0 * b.efficiency(2);
    /// assert!((b.albedo(DVec3::Z, 550.0).unwrap() - want).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn albedo(&self, wo: DVec3, lambda_nm: f64) -> Option<f64> {
        if !(wo.z > 0.0 && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return Some(0.0);
        }
        let step = lambda_nm / self.grating.period_nm();
        let Some(c) = self.candidates(wo, step) else {
            return Some(0.0);
        };
        if c.hi - c.lo + 1 > MAX_ALBEDO_ORDERS {
            return None;
        }
        let rho = self.duty();
        // ∫ g over the chord of D at u.
        let chord = |u: f64| {
            let a = u - wo.x;
            let h2 = 1.0 - a * a;
            if h2 <= 0.0 {
                return 0.0;
            }
            let h = math::sqrt(h2);
            self.groove.mass(wo.y - h, wo.y + h, lambda_nm)
        };
        let mut sum = 0.0;
        match self.grating.slits() {
            Slits::Infinite => {
                for m in c.lo..=c.hi {
                    let s = single_slit_cycles(rho * m as f64);
                    sum += rho * rho * s * chord(m as f64 * step);
                }
            }
            Slits::Finite(n) => {
                // Where the chord starts or stops: |u − wo.x| = 1, and for an ideal groove
                // |u − wo.x| = √(1 − wo.y²) (the step of C).
                // Where the chord's end crosses v = 0 (the centre of g): a step for an ideal
                // groove, a steep rise of width about the groove's width otherwise.
                let e = math::sqrt((1.0 - wo.y * wo.y).max(0.0));
                let edges = [wo.x - 1.0, wo.x + 1.0, wo.x - e, wo.x + e];
                let nf = n as f64;
                for m in c.lo..=c.hi {
                    let h = |r: f64| {
                        let x = m as f64 + r;
                        rho * rho * single_slit_cycles(rho * x) * chord(x * step)
                    };
                    let mut cuts = [f64::NAN; 4];
                    for (k, e) in edges.iter().enumerate() {
                        let r = e / step - m as f64;
                        if r > -0.5 && r < 0.5 {
                            cuts[k] = r;
                        }
                    }
                    sum += period_integral(nf, &cuts, &h);
                }
            }
        }
        Some(sum.clamp(0.0, rho))
    }

    /// Samples a wavelength in `band` for the fixed pair (wo, wi) from the grating's own
    /// spectral response, from one uniform `xi` in [0, 1).
    ///
    /// At fixed directions f is a sum of peaks at λ_m = d·|u|/|m| of width about λ_m/(|m|·N).
    /// The sampler is a mixture: with probability [`DEFENSIVE_WAVELENGTH_SHARE`] uniform over
    /// the band; otherwise peak m (the first [`MAX_WAVELENGTH_PEAKS`] orders m ≠ 0 with λ_m in
    /// the band, [`Grating::peaks`]) with probability ∝ its area η_m·(d/|m|)·g(v; λ_m), or
    /// order 0 (when its period, λ > 2·d·|u|, reaches the band) with probability ∝ f at the
    /// middle of that range times its length. Inside peak m the phase x = d·|u|/λ is drawn
    /// from the Lorentzian proxy of its period (x = |m| + r as in `sample`) and λ = d·|u|/x, so
    /// the density is q(r)·d·|u|/λ²; inside order 0's range λ is uniform. Samples outside the
    /// band are rejected (`None`); [`wavelength_pdf`](Self::wavelength_pdf) is the exact
    /// density and integrates to the probability of `Some`. For N = ∞ (delta peaks, no
    /// spectral density) only the uniform part is used.
    ///
    /// ```
    /// use diffraction::{Band, Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1_000_000)?);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// let s = b.sample_wavelength(wo, wi, Band::VISIBLE, 0.7).unwrap();
    /// assert!((s.lambda_nm - 480.0).abs() < 0.01); // inside the peak, 5·10⁻⁴ nm wide
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn sample_wavelength(
        &self,
        wo: DVec3,
        wi: DVec3,
        band: Band,
        xi: f64,
    ) -> Option<WavelengthSample> {
        let xi = if xi.is_finite() {
            xi.clamp(0.0, 1.0 - f64::EPSILON)
        } else {
            0.5
        };
        let mix = self.wavelength_mixture(wo, wi, band);
        let b = band.width_nm();
        let lambda = if mix.total <= 0.0 || xi < DEFENSIVE_WAVELENGTH_SHARE {
            let t = if mix.total <= 0.0 {
                xi
            } else {
                xi / DEFENSIVE_WAVELENGTH_SHARE
            };
            (band.min_nm() + t * b).min(band.max_nm())
        } else {
            let target =
                (xi - DEFENSIVE_WAVELENGTH_SHARE) / (1.0 - DEFENSIVE_WAVELENGTH_SHARE) * mix.total;
            let mut acc = mix.zero_weight;
            if target < acc {
                let t = target / mix.zero_weight;
                mix.zero_lo + t * (band.max_nm() - mix.zero_lo)
            } else {
                let n = mix.n;
                let mut chosen = None;
                let mut last = None;
                for p in self.grating.peaks(mix.u, band).take(MAX_WAVELENGTH_PEAKS) {
                    let w = self.peak_weight(&p, mix.v);
                    if w > 0.0 {
                        last = Some((p, w, acc));
                        if target < acc + w {
                            chosen = Some((p, w, acc));
                            break;
                        }
                        acc += w;
                    }
                }
                let (p, w, start) = chosen.or(last)?;
                let t = ((target - start) / w).clamp(0.0, 1.0);
                let r = lorentz_r(n, self.cache.atan_n, t);
                let x = (p.order.unsigned_abs() as f64) + r;
                mix.q / x
            }
        };
        if !band.contains(lambda) {
            return None;
        }
        let pdf = self.wavelength_pdf_mix(&mix, band, lambda);
        (pdf > 0.0 && pdf.is_finite()).then_some(WavelengthSample {
            lambda_nm: lambda,
            pdf,
        })
    }

    /// The density (1/nm) with which [`sample_wavelength`](Self::sample_wavelength) returns
    /// `lambda_nm` for (wo, wi); 0 outside the band.
    ///
    /// ```
    /// use diffraction::{Band, Grating, GratingBsdf};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// // Far from every peak only the uniform share remains (and order 1's far tail).
    /// let p = b.wavelength_pdf(wo, wi, Band::VISIBLE, 700.0);
    /// assert!(p >= 0.1 / 470.0 && p < 0.11 / 470.0);
    /// assert_eq!(b.wavelength_pdf(wo, wi, Band::VISIBLE, 900.0), 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn wavelength_pdf(&self, wo: DVec3, wi: DVec3, band: Band, lambda_nm: f64) -> f64 {
        if !band.contains(lambda_nm) {
            return 0.0;
        }
        let mix = self.wavelength_mixture(wo, wi, band);
        self.wavelength_pdf_mix(&mix, band, lambda_nm)
    }

    /// The area-based weight of one peak in the wavelength mixture.
    fn peak_weight(&self, p: &Peak, v: f64) -> f64 {
        let l = p.wavelength_nm;
        let g = if self.groove.is_delta() {
            1.0
        } else {
            self.groove.value(v, l)
        };
        let w = self.efficiency(p.order) * (self.grating.period_nm() / p.order.abs() as f64) * g;
        if w.is_finite() {
            w
        } else {
            0.0
        }
    }

    fn wavelength_mixture(&self, wo: DVec3, wi: DVec3, band: Band) -> WavelengthMixture {
        let mut mix = WavelengthMixture {
            u: 0.0,
            v: 0.0,
            q: 0.0,
            n: 1.0,
            total: 0.0,
            zero_weight: 0.0,
            zero_lo: band.max_nm(),
        };
        let Slits::Finite(n) = self.grating.slits() else {
            return mix;
        };
        if !(wi.z > 0.0 && wo.z > 0.0 && wi.is_finite() && wo.is_finite()) {
            return mix;
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        mix.u = u;
        mix.v = v;
        mix.n = n as f64;
        mix.q = self.grating.period_nm() * u.abs();
        let mut total = 0.0;
        // Order 0's period: x = q/λ < ½, λ > 2q.
        let zero_lo = (2.0 * mix.q).max(band.min_nm());
        if zero_lo < band.max_nm() {
            let mid = 0.5 * (zero_lo + band.max_nm());
            let g = if self.groove.is_delta() {
                1.0
            } else {
                self.groove.value(v, mid)
            };
            let rho = self.duty();
            let f = rho
                * rho
                * (mix.n * self.grating.period_nm() / mid)
                * self.grating.intensity_f64(u, mid)
                * g;
            let w = f * (band.max_nm() - zero_lo);
            if w.is_finite() && w > 0.0 {
                mix.zero_weight = w;
                mix.zero_lo = zero_lo;
                total += w;
            }
        }
        for p in self.grating.peaks(u, band).take(MAX_WAVELENGTH_PEAKS) {
            total += self.peak_weight(&p, v);
        }
        mix.total = if total.is_finite() { total } else { 0.0 };
        mix
    }

    fn wavelength_pdf_mix(&self, mix: &WavelengthMixture, band: Band, lambda: f64) -> f64 {
        if !band.contains(lambda) {
            return 0.0;
        }
        let b = band.width_nm();
        if mix.total <= 0.0 {
            return 1.0 / b;
        }
        let mut p = DEFENSIVE_WAVELENGTH_SHARE / b;
        let share = (1.0 - DEFENSIVE_WAVELENGTH_SHARE) / mix.total;
        if mix.zero_weight > 0.0 && lambda >= mix.zero_lo {
            p += share * mix.zero_weight / (band.max_nm() - mix.zero_lo);
        }
        if mix.q > 0.0 {
            let x = mix.q / lambda;
            let m = math::rint(x);
            if m >= 1.0 {
                let r = x - m;
                // Is order m among the peaks the sampler follows?
                let peaks = self.grating.peaks(mix.u, band);
                let mut found = None;
                for pk in peaks.take(MAX_WAVELENGTH_PEAKS) {
                    if pk.order.unsigned_abs() as f64 == m {
                        found = Some(pk);
                        break;
                    }
                    if pk.order.unsigned_abs() as f64 > m {
                        break;
                    }
                }
                if let Some(pk) = found {
                    let w = self.peak_weight(&pk, mix.v);
                    p += share * w * lorentz_q(mix.n, self.cache.atan_n, r) * mix.q
                        / (lambda * lambda);
                }
            }
        }
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// Regularised half-width: pbrt's rule clamp(2h, min, max) below max, else unchanged.
    fn widen(h: f64) -> f64 {
        if h < REGULARIZE_MAX_HALF_WIDTH {
            (2.0 * h).clamp(REGULARIZE_MIN_HALF_WIDTH, REGULARIZE_MAX_HALF_WIDTH)
        } else {
            h
        }
    }
}

/// The mixture of `sample_wavelength` for one (wo, wi).
struct WavelengthMixture {
    u: f64,
    v: f64,
    q: f64,
    n: f64,
    total: f64,
    zero_weight: f64,
    zero_lo: f64,
}

/// U_m = 3/(3 + (π·ρ·(|m| − ½)₊)²) ≥ S(π·ρ·x) on the period of m, since S(β) ≤ 3/(3 + β²).
#[inline]
fn envelope_bound(rho: f64, m: i64) -> f64 {
    let a = ((m.unsigned_abs() as f64) - 0.5).max(0.0) * rho * PI;
    3.0 / (3.0 + a * a)
}

/// ⌊a⌋ for finite a through `rint` (no library call where `floor` is not an instruction).
#[inline(always)]
fn floor_exact(a: f64) -> f64 {
    let r = math::rint(a);
    if r > a {
        r - 1.0
    } else {
        r
    }
}

/// ⌈a⌉ for finite a through `rint`.
#[inline(always)]
fn ceil_exact(a: f64) -> f64 {
    let r = math::rint(a);
    if r < a {
        r + 1.0
    } else {
        r
    }
}

/// The Lorentzian proxy's inverse CDF: r = tan((2t − 1)·atan N)/(2N), |r| ≤ ½ (a = atan N).
#[inline]
fn lorentz_r(n: f64, a: f64, t: f64) -> f64 {
    let r = tan((2.0 * t - 1.0) * a) / (2.0 * n);
    r.clamp(-0.5, 0.5)
}

/// The Lorentzian proxy's density on |r| < ½: N/((1 + 4N²r²)·atan N) (a = atan N).
#[inline]
fn lorentz_q(n: f64, a: f64, r: f64) -> f64 {
    if r.abs() > 0.5 {
        return 0.0;
    }
    let t = 2.0 * n * r;
    n / ((1.0 + t * t) * a)
}

/// ∫_{−½}^{½} N·F_N(π·r)·h(r) dr for a smooth h, with the pieces also split at `cuts`
/// (NaN entries ignored). See [`GratingBsdf::albedo`].
fn period_integral(n: f64, cuts: &[f64; 4], h: &dyn Fn(f64) -> f64) -> f64 {
    const RESOLVED: f64 = 64.0;
    const FULL: f64 = 128.0;
    const TAIL_PIECES: u32 = 24;
    let fejer = |r: f64| {
        // N·F_N(π r): exact F_N through the kernel, in cycles.
        n * crate::kernel::n_slit_cycles(r, n as u32)
    };
    let tail = |r: f64| {
        let s = crate::kernel::sinpi(r);
        1.0 / (2.0 * n * s * s)
    };
    let mut sum = 0.0;
    // Resolved zone: every side lobe [k/N, (k+1)/N] out to `RESOLVED` lobes (or all).
    let lobes = if n <= FULL {
        math::floor(n / 2.0)
    } else {
        RESOLVED
    };
    let edge = if n <= FULL { 0.5 } else { RESOLVED / n };
    let mut piece = |a: f64, b: f64, w: &dyn Fn(f64) -> f64| {
        // Split [a, b] at the cuts, then 8-point Gauss-Legendre on each part.
        let mut pts = [a, b, f64::NAN, f64::NAN, f64::NAN, f64::NAN];
        let mut k = 2;
        for &c in cuts {
            if c > a && c < b {
                pts[k] = c;
                k += 1;
            }
        }
        let pts = &mut pts[..k];
        pts.sort_unstable_by(|x, y| x.partial_cmp(y).unwrap_or(core::cmp::Ordering::Equal));
        for j in 0..k - 1 {
            let (p0, p1) = (pts[j], pts[j + 1]);
            let f = |r: f64| w(r) * h(r);
            let at_cut = |p: f64| cuts.contains(&p);
            sum += match (at_cut(p0), at_cut(p1)) {
                (true, false) => graded(p0, p1, &f),
                (false, true) => graded(p1, p0, &f),
                (true, true) => {
                    let mid = 0.5 * (p0 + p1);
                    graded(p0, mid, &f) + graded(p1, mid, &f)
                }
                (false, false) => {
                    // Pieces longer than 1/64 of a period (small N) are split.
                    let k = math::ceil((p1 - p0) * 64.0).max(1.0);
                    let h = (p1 - p0) / k;
                    let mut acc = 0.0;
                    let mut j = 0.0;
                    while j < k {
                        acc += gl8(p0 + j * h, p0 + (j + 1.0) * h, &f);
                        j += 1.0;
                    }
                    acc
                }
            };
        }
    };
    let nl = lobes as u32;
    for side in [-1.0, 1.0] {
        for k in 0..nl {
            let (a, b) = (k as f64 / n, ((k + 1) as f64 / n).min(0.5));
            if side > 0.0 {
                piece(a, b, &fejer);
            } else {
                piece(-b, -a, &fejer);
            }
        }
        // For even N ≤ 128 the last lobe ends at ½ exactly; odd N leaves [⌊N/2⌋/N, ½].
        let resolved_end = (lobes / n).min(0.5);
        if n <= FULL {
            if resolved_end < 0.5 {
                if side > 0.0 {
                    piece(resolved_end, 0.5, &fejer);
                } else {
                    piece(-0.5, -resolved_end, &fejer);
                }
            }
        } else {
            // Averaged tail on geometric pieces from edge to ½.
            let ratio = math::powf(0.5 / edge, 1.0 / TAIL_PIECES as f64);
            let mut a = edge;
            for j in 0..TAIL_PIECES {
                let b = if j + 1 == TAIL_PIECES { 0.5 } else { a * ratio };
                if side > 0.0 {
                    piece(a, b, &tail);
                } else {
                    piece(-b, -a, &tail);
                }
                a = b;
            }
        }
    }
    sum
}

/// ∫ between `at` (a cut: the disk's edge, where the integrand behaves like a square root, or
/// the steep rise of the chord's mass) and `to` on 16 pieces graded geometrically (ratio ½)
/// toward `at`, the innermost with the substitution r = at + (to − at)·s² that makes a
/// square-root end smooth.
fn graded(at: f64, to: f64, f: &dyn Fn(f64) -> f64) -> f64 {
    const LEVELS: i32 = 16;
    let len = to - at;
    let mut sum = 0.0;
    let mut outer = 1.0;
    for _ in 0..LEVELS {
        let inner = 0.5 * outer;
        let (a, b) = (at + inner * len, at + outer * len);
        sum += if len > 0.0 {
            gl8(a, b, f)
        } else {
            gl8(b, a, f)
        };
        outer = inner;
    }
    let e = outer * len;
    sum + gl8(0.0, 1.0, &|s| f(at + e * s * s) * 2.0 * e.abs() * s)
}

/// 8-point Gauss-Legendre on [a, b].
fn gl8(a: f64, b: f64, f: &dyn Fn(f64) -> f64) -> f64 {
    const X: [f64; 4] = [
        0.1834346424956498,
        0.525532409916329,
        0.7966664774136267,
        0.9602898564975363,
    ];
    const W: [f64; 4] = [
        0.362683783378362,
        0.31370664587788727,
        0.22238103445337448,
        0.10122853629037626,
    ];
    let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
    let mut s = 0.0;
    for i in 0..4 {
        s += W[i] * (f(c - h * X[i]) + f(c + h * X[i]));
    }
    s * h
}

impl DiffractionBrdf for GratingBsdf {
    /// `f(wo, wi, λ)` (note the argument order): the BRDF in 1/sr, cosine excluded.
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        self.f(wo, wi, lambda_nm)
    }

    /// Every order m ≠ 0 with λ_m = d·|u|/|m| in `band`: for finite N with the value of f at
    /// the peak, ρ²·S(π·ρ·m)·(N·d/λ_m)·g(v; λ_m), and the equivalent width λ_m/(|m|·N), whose
    /// product is the order's spectral area η_m·(d/|m|)·g (independent of N). For N = ∞ (delta
    /// peaks) `intensity` is η_m·g(v; λ_m) and `equivalent_width_nm` is d/|m| = |dλ/du|, so
    /// that the product is again the area. For an ideal groove g is taken as 1 where v = 0 and
    /// 0 elsewhere. Order 0 is seen where |u| < λ_max/(N·d) (never for N = ∞, whose order 0 is
    /// a delta in u).
    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !(wi.z > 0.0 && wo.z > 0.0 && wi.is_finite() && wo.is_finite()) {
            return PeakSummary::default();
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let d = self.grating.period_nm();
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
        for p in peaks {
            let l = p.wavelength_nm;
            let eta = self.efficiency(p.order);
            let am = p.order.unsigned_abs() as f64;
            let (intensity, width) = match self.grating.slits() {
                Slits::Finite(n) => (eta * (n as f64 * d / l) * g_at(l), l / (am * n as f64)),
                Slits::Infinite => (eta * g_at(l), d / am),
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

    fn cosine_included(&self) -> bool {
        false
    }

    /// For finite N, f·cos θi = cos θi·ρ²·N·d·(g(v, λ)/λ)·I(u, λ): the grating's intensity times
    /// the envelope λ⁻¹ (a groove spread that does not depend on λ) or λ⁻²·sinc²(π·L·v/λ) (a
    /// coherence length L, whose g is (L/λ)·sinc²(π·L·v/λ)), so the colour integrator takes its
    /// lobe-exact paths. `None` for N = ∞ and the ideal groove (delta lobes: `eval` is 0 and
    /// the colour is the peaks' areas) and below the horizon.
    fn grating_response(&self, wi: DVec3, wo: DVec3) -> Option<GratingResponse> {
        if !(wi.z >= MIN_COS_THETA && wo.z >= MIN_COS_THETA && wi.is_finite() && wo.is_finite()) {
            return None;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return None;
        };
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let rho = self.duty();
        let base = wi.z * rho * rho * n as f64 * self.grating.period_nm();
        let (scale, envelope) = match self.groove {
            GrooveSpread::CoherenceLength { length_nm } => (
                base * length_nm,
                Envelope::new(2, (length_nm * v).abs()).ok()?,
            ),
            GrooveSpread::Gaussian { .. } => (
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
    /// ρ²·S·(N·d/λ)·F_N·g(v) at u = wi.x + wo.x, v = wi.y + wo.y; 0 below the surface, for
    /// λ ≤ 0, for non-finite input and for delta lobes (N = ∞ or an ideal groove).
    #[inline]
    fn f(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(wi.z >= MIN_COS_THETA
            && wo.z >= MIN_COS_THETA
            && lambda_nm > 0.0
            && lambda_nm.is_finite())
        {
            return 0.0;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return 0.0;
        };
        if self.groove.is_delta() {
            return 0.0;
        }
        self.value_uv(n, wi.x + wo.x, wi.y + wo.y, lambda_nm)
    }

    /// Shares the hemisphere checks, u, v and (Gaussian groove) g(v) between the four
    /// wavelengths, and evaluates them as four branch-free lanes, each the same operations as
    /// [`f`](Bsdf::f) (so `f4` equals four `f` calls to the bit).
    fn f4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        let out = [0.0; 4];
        if !(wi.z >= MIN_COS_THETA && wo.z >= MIN_COS_THETA) || self.groove.is_delta() {
            return out;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return out;
        };
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let l = lambdas.lambda();
        let ok = l.map(|l| l > 0.0 && l.is_finite());
        // A lane with an invalid λ computes at λ = 1 and is zeroed below.
        let l = [0, 1, 2, 3].map(|k| if ok[k] { l[k] } else { 1.0 });
        let q = l.map(|l| u / l);
        // The four lanes side by side (see `lane`); the Gaussian's g(v) is the same for every λ
        // and computed once.
        let d = self.grating.period_nm();
        let (gauss, coherence) = match self.groove {
            GrooveSpread::Gaussian { .. } => (self.groove.value_unchecked(v, 1.0), 0.0),
            GrooveSpread::CoherenceLength { length_nm } => (0.0, length_nm),
            GrooveSpread::Ideal => return out,
        };
        // Stage by stage over the four lanes (divisions side by side), each lane the same
        // operations as `f`.
        let big = if coherence > 0.0 {
            l.map(|l| coherence / l)
        } else {
            [gauss; 4]
        };
        let mut num = [0.0; 4];
        let mut den = [0.0; 4];
        for k in 0..4 {
            (num[k], den[k]) = self.lane(n, q[k], big[k], coherence > 0.0, v, l[k]);
        }
        let mut f = [
            num[0] / den[0],
            num[1] / den[1],
            num[2] / den[2],
            num[3] / den[3],
        ];
        for k in 0..4 {
            if !((d * q[k]).is_finite() && f[k].is_finite() && ok[k]) {
                f[k] = 0.0;
            }
        }
        f
    }

    fn sample(&self, wo: DVec3, lambda_nm: f64, uc: f64, u2: DVec2) -> Option<BsdfSample> {
        if !(wo.z >= MIN_COS_THETA && wo.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return None;
        }
        if !(uc.is_finite() && u2.is_finite()) {
            return None;
        }
        let unit = |x: f64| x.clamp(0.0, 1.0 - f64::EPSILON);
        let (uc, ux, uy) = (unit(uc), unit(u2.x), unit(u2.y));
        let step = lambda_nm / self.grating.period_nm();
        let c = self.candidates(wo, step)?;
        let (m, pm) = self.choose_order(&c, uc);
        let (u, r) = match self.grating.slits() {
            Slits::Finite(n) => {
                let r = lorentz_r(n as f64, self.cache.atan_n, ux);
                ((m as f64 + r) * step, r)
            }
            Slits::Infinite => (m as f64 * step, 0.0),
        };
        let v = self.groove.sample(uy, lambda_nm);
        let (x, y) = (u - wo.x, v - wo.y);
        let z2 = 1.0 - x * x - y * y;
        if z2.is_nan() || z2 < MIN_COS_THETA * MIN_COS_THETA {
            return None;
        }
        let wi = DVec3::new(x, y, math::sqrt(z2));
        let order = m.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        let rho = self.duty();
        let (f, pdf, flags) = match (self.grating.slits(), self.groove.is_delta()) {
            (Slits::Finite(n), false) => {
                // f and pdf from the returned direction itself (u and v re-derived from wi, the
                // same operations as `f` and `pdf`, sharing q = u/λ and the candidates), so the
                // sample agrees with them exactly.
                let (u, v) = (wi.x + wo.x, wi.y + wo.y);
                (
                    self.value_uv(n, u, v, lambda_nm),
                    self.pdf_x(&c, n as f64, u / step, v, wi.z, lambda_nm),
                    BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
                )
            }
            (Slits::Finite(n), true) => {
                // δ(v) omitted from both f and pdf.
                let i = self.grating.intensity_f64(u, lambda_nm);
                let f = rho * rho * (n as f64 / step) * i;
                (
                    f,
                    pm * (lorentz_q(n as f64, self.cache.atan_n, r) / step) * wi.z,
                    BsdfFlags::REFLECTION | BsdfFlags::SPECULAR,
                )
            }
            (Slits::Infinite, false) => {
                let eta = rho * rho * single_slit_cycles(rho * m as f64);
                let pv = self.groove.pdf(v, lambda_nm);
                (
                    eta * self.groove.value(v, lambda_nm),
                    pm * pv * wi.z,
                    BsdfFlags::REFLECTION | BsdfFlags::SPECULAR,
                )
            }
            (Slits::Infinite, true) => {
                let eta = rho * rho * single_slit_cycles(rho * m as f64);
                (eta / wi.z, pm, BsdfFlags::REFLECTION | BsdfFlags::SPECULAR)
            }
        };
        if !(pdf > 0.0 && pdf.is_finite() && f.is_finite()) {
            return None;
        }
        Some(BsdfSample::new(wi, f, pdf, flags).with_order(order))
    }

    /// P(m)·q(r)·(d/λ)·q_v(v)·cos θi for the order m owning u (see the [module docs](self));
    /// 0 for delta lobes, below the surface and for non-finite input.
    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        if !(wi.z >= MIN_COS_THETA
            && wo.z >= MIN_COS_THETA
            && lambda_nm > 0.0
            && lambda_nm.is_finite())
        {
            return 0.0;
        }
        if !(wi.is_finite() && wo.is_finite()) || self.groove.is_delta() {
            return 0.0;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return 0.0;
        };
        self.pdf_finite(n as f64, wo, wi, lambda_nm)
    }

    /// Shares the checks, u and v; the candidate orders depend on λ and are found per λ.
    fn pdf4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        let mut out = [0.0; 4];
        if !(wi.z >= MIN_COS_THETA && wo.z >= MIN_COS_THETA && wi.is_finite() && wo.is_finite()) {
            return out;
        }
        if self.groove.is_delta() {
            return out;
        }
        let Slits::Finite(n) = self.grating.slits() else {
            return out;
        };
        for (o, &l) in out.iter_mut().zip(lambdas.lambda().iter()) {
            if l > 0.0 && l.is_finite() {
                *o = self.pdf_finite(n as f64, wo, wi, l);
            }
        }
        out
    }

    /// REFLECTION | GLOSSY for finite N with a groove spread; REFLECTION | SPECULAR for N = ∞
    /// or an ideal groove (the threshold is discussed in the [module docs](self)).
    fn flags(&self) -> BsdfFlags {
        match (self.grating.slits(), self.groove.is_delta()) {
            (Slits::Finite(_), false) => BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
            _ => BsdfFlags::REFLECTION | BsdfFlags::SPECULAR,
        }
    }

    /// Widens lobes narrower than [`REGULARIZE_MAX_HALF_WIDTH`] at 550 nm to
    /// clamp(2h, [`REGULARIZE_MIN_HALF_WIDTH`], [`REGULARIZE_MAX_HALF_WIDTH`]): in u through N
    /// (h = λ/(N·d); N = ∞ counts as h = 0; N never grows), in v through the coherence length
    /// (h = λ/L), the Gaussian σ, or an ideal groove becoming a Gaussian of σ = 0.01.
    fn regularize(&mut self) {
        let l = REGULARIZE_REFERENCE_NM;
        let d = self.grating.period_nm();
        let hu = match self.grating.slits() {
            Slits::Finite(n) => l / (n as f64 * d),
            Slits::Infinite => 0.0,
        };
        if hu < REGULARIZE_MAX_HALF_WIDTH {
            let target = Self::widen(hu);
            let n_new = math::floor(l / (d * target)).clamp(1.0, u32::MAX as f64) as u32;
            let n_new = match self.grating.slits() {
                Slits::Finite(n) => n_new.min(n),
                Slits::Infinite => n_new,
            };
            if let Ok(g) =
                Grating::with_slits(d, self.grating.slit_width_nm(), Slits::Finite(n_new.max(1)))
            {
                self.grating = g;
                self.cache = Cache::new(&g);
            }
        }
        self.groove = match self.groove {
            GrooveSpread::CoherenceLength { length_nm } => {
                let h = l / length_nm;
                GrooveSpread::CoherenceLength {
                    length_nm: l / Self::widen(h),
                }
            }
            GrooveSpread::Gaussian { sigma } => GrooveSpread::Gaussian {
                sigma: Self::widen(sigma),
            },
            GrooveSpread::Ideal => GrooveSpread::Gaussian {
                sigma: REGULARIZE_MIN_HALF_WIDTH,
            },
        };
    }
}

impl GratingBsdf {
    /// The density for finite N and a non-ideal groove, after the checks.
    #[inline]
    fn pdf_finite(&self, n: f64, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        let step = lambda_nm / self.grating.period_nm();
        let Some(c) = self.candidates(wo, step) else {
            return 0.0;
        };
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        self.pdf_x(&c, n, u / step, v, wi.z, lambda_nm)
    }

    /// P(m)·q(r)·(d/λ)·q_v(v)·cos θi at the phase x = u/(λ/d) (m = round(x), r = x − m) for the
    /// candidates `c`, with two divisions: the order and u factors, and the v and cosine
    /// factors (q_v = (1/s)/(π·(1 + (v/s)²)), [`GrooveSpread::pdf`] to rounding).
    #[inline(always)]
    fn pdf_x(&self, c: &Candidates, n: f64, x: f64, v: f64, cos_i: f64, lambda_nm: f64) -> f64 {
        let m = math::rint(x);
        let r = x - m;
        let mi = m as i64;
        if mi < c.lo || mi > c.hi {
            return 0.0;
        }
        let w = if c.uniform {
            1.0
        } else {
            self.order_weight(mi)
        };
        let t = 2.0 * n * r;
        let inv_s = self.groove.proxy_inverse_scale(lambda_nm);
        let tv = v * inv_s;
        let a = (w * n * self.grating.period_nm())
            / (c.total * (1.0 + t * t) * self.cache.atan_n * lambda_nm);
        let b = (inv_s * cos_i) / (PI * (1.0 + tv * tv));
        let p = a * b;
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::n_slit_cycles;

    /// f against the separate factors of the formula (kernel functions tested against mpmath)
    /// and f4 against four f calls: the fused, branch-free path rounds differently from the
    /// product of the factors by a few ulp of each factor (measured: at most 8.3·ε relative;
    /// f4 equals f exactly); 32·ε leaves 4×.
    const FUSED_REL: f64 = 32.0 * f64::EPSILON;
    /// pdf against the module docs' formula P(m)·q(r)·(d/λ)·q_v(v)·cos θi with each factor
    /// computed separately: a few roundings each (measured: at most 5.4·ε); 48·ε leaves 9×.
    const PDF_REL: f64 = 48.0 * f64::EPSILON;

    /// SplitMix64 in [0, 1).
    struct Rng(u64);
    impl Rng {
        fn next(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 53) as f64
        }
        fn dir(&mut self) -> DVec3 {
            let z = 0.05 + 0.95 * self.next();
            let phi = 2.0 * PI * self.next();
            let s = (1.0 - z * z).sqrt();
            DVec3::new(s * phi.cos(), s * phi.sin(), z)
        }
    }

    fn models() -> Vec<GratingBsdf> {
        let mut v = Vec::new();
        for n in [1u32, 2, 5, 30, 1000, 1_000_000] {
            let b = GratingBsdf::new(Grating::new(1600.0, 800.0, n).unwrap());
            v.push(b);
            v.push(
                b.with_groove(GrooveSpread::Gaussian { sigma: 0.02 })
                    .unwrap(),
            );
            let c = GratingBsdf::new(Grating::new(1000.0, 300.0, n).unwrap());
            v.push(c);
        }
        v
    }

    /// (wo, wi, λ): every other pair within a few lobes of a peak of order 1-3.
    fn inputs(b: &GratingBsdf, rng: &mut Rng, count: usize) -> Vec<(DVec3, DVec3, f64)> {
        let d = b.grating().period_nm();
        let n = b.grating().slits().as_f64();
        let mut out = Vec::new();
        while out.len() < count {
            let wo = rng.dir();
            let l = 360.0 + 470.0 * rng.next();
            let mut wi = rng.dir();
            if out.len() % 2 == 0 {
                let m = 1.0 + (3.0 * rng.next()).floor();
                let x = (m + (rng.next() - 0.5) * 8.0 / n) * l / d - wo.x;
                let y = 0.05 * (rng.next() - 0.5) - wo.y;
                let z2 = 1.0 - x * x - y * y;
                if z2 <= 1e-4 {
                    continue;
                }
                wi = DVec3::new(x, y, z2.sqrt());
            }
            out.push((wo, wi, l));
        }
        out
    }

    /// Below this, factors such as a far Gaussian tail are subnormal and keep only a few bits.
    const SUBNORMAL_FACTORS: f64 = 1e-290;

    fn rel(a: f64, b: f64) -> f64 {
        if a == b || a.abs().max(b.abs()) < SUBNORMAL_FACTORS {
            0.0
        } else {
            (a - b).abs() / a.abs().max(b.abs())
        }
    }

    #[test]
    fn floor_and_ceil_through_rint() {
        for a in [
            -2.5,
            -2.0,
            -1.5,
            -0.5,
            -0.0,
            0.0,
            0.3,
            0.5,
            1.5,
            2.5,
            1e15 + 0.5,
            -4e15,
        ] {
            assert_eq!(floor_exact(a), a.floor(), "{a}");
            assert_eq!(ceil_exact(a), a.ceil(), "{a}");
        }
        let mut rng = Rng(3);
        for _ in 0..10000 {
            let a = (rng.next() - 0.5) * 1e3;
            assert_eq!((floor_exact(a), ceil_exact(a)), (a.floor(), a.ceil()));
        }
    }

    #[test]
    fn f_is_the_grating_formula() {
        let mut rng = Rng(7);
        let mut worst: f64 = 0.0;
        for b in models() {
            let (d, w) = (b.grating().period_nm(), b.grating().slit_width_nm());
            let n = b.grating().slits().as_f64() as u32;
            let rho = w / d;
            for (wo, wi, l) in inputs(&b, &mut rng, 400) {
                let (u, v) = (wi.x + wo.x, wi.y + wo.y);
                // The phases as the grating forms them: x = d·(u/λ), y = w·(u/λ).
                let (x, y) = (d * (u / l), w * (u / l));
                let want = rho
                    * rho
                    * (n as f64 * d / l)
                    * single_slit_cycles(y)
                    * n_slit_cycles(x, n)
                    * b.groove().value(v, l);
                let got = b.f(wo, wi, l);
                worst = worst.max(rel(got, want));
                assert!(
                    rel(got, want) <= FUSED_REL,
                    "{b:?} {wo} {wi} {l}: {got} vs {want}"
                );
            }
        }
        eprintln!("f against the formula: worst {:.1} ε", worst / f64::EPSILON);
    }

    #[test]
    fn f4_is_four_f() {
        let mut rng = Rng(8);
        for b in models() {
            for (wo, wi, l) in inputs(&b, &mut rng, 200) {
                let others = [l, 360.0 + 470.0 * rng.next(), l * 1.001, 829.0];
                let lambdas = SampledWavelengths::new(others, [1.0; 4]).unwrap();
                let got = b.f4(wo, wi, &lambdas);
                for k in 0..4 {
                    let want = b.f(wo, wi, others[k]);
                    assert!(
                        rel(got[k], want) <= FUSED_REL,
                        "{b:?} lane {k}: {} vs {want}",
                        got[k]
                    );
                }
            }
        }
    }

    #[test]
    fn pdf_is_the_documented_density() {
        let mut rng = Rng(9);
        let mut worst: f64 = 0.0;
        for b in models() {
            let d = b.grating().period_nm();
            let nf = b.grating().slits().as_f64();
            for (wo, wi, l) in inputs(&b, &mut rng, 400) {
                let step = l / d;
                // The candidates: periods [(m − ½)·step, (m + ½)·step) meeting (wo.x ± 1).
                let lo = ((wo.x - 1.0) / step - 0.5).floor() as i64 + 1;
                let hi = ((wo.x + 1.0) / step + 0.5).ceil() as i64 - 1;
                let total: f64 = (lo..=hi)
                    .map(|m| order_weight(b.grating().slits(), b.duty(), m))
                    .sum();
                let (u, v) = (wi.x + wo.x, wi.y + wo.y);
                let x = u / step;
                let m = math::rint(x);
                let r = x - m;
                let pm = order_weight(b.grating().slits(), b.duty(), m as i64) / total;
                let q = nf / ((1.0 + 4.0 * nf * nf * r * r) * nf.atan());
                let want = pm * q / step * b.groove().pdf(v, l) * wi.z;
                let got = b.pdf(wo, wi, l);
                worst = worst.max(rel(got, want));
                assert!(
                    rel(got, want) <= PDF_REL,
                    "{b:?} {wo} {wi} {l}: {got} vs {want}"
                );
            }
        }
        eprintln!(
            "pdf against the formula: worst {:.1} ε",
            worst / f64::EPSILON
        );
    }
}
