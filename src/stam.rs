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
//! * It is a BRDF: [`cosine_included`](DiffractionBrdf::cosine_included) is `false`, the
//!   renderer multiplies by cos θi.
//! * Unlike the paper's model and [`Thorman`](crate::Thorman), the light is confined to the
//!   cone of diffracted directions: the factor exp(−k²σ_c²v²), v = `wi.y + wo.y`, darkens every
//!   direction off the plane of the grating equation's cone.

use core::f64::consts::PI;

use glam::DVec3;
use num_complex::Complex64;

use crate::brdf::{DiffractionBrdf, PeakSummary};
use crate::error::{positive, Error, Requirement};
use crate::grating::{Band, Grating, Peak, Slits};
use crate::kernel::sinpi;
use crate::math;

/// Lobes are summed out to k·σ_c·|Δu| = 6, where exp(−36) = 2.3·10⁻¹⁶.
const CUTOFF: f64 = 6.0;
/// The largest accepted h₀, nm (φ = k·w·h₀ ≤ 349 over the visible band).
const MAX_DEPTH_NM: f64 = 10_000.0;
/// Below this wavelength `eval` returns 0 (keeps φ ≤ 1.3·10⁵ and the Bessel sums short).
const MIN_WAVELENGTH_NM: f64 = 1.0;
/// √π.
const SQRT_PI: f64 = 1.772453850905516;
/// Rescaling threshold of the backward recurrence (its square and the sums stay finite).
const BIG: f64 = 1e100;
/// Below this argument, J_n(x) is the first two terms of its power series.
const SERIES_X: f64 = 1e-8;
/// Above this argument, J_0 and J_1 come from Hankel's expansion and J_n by forward recurrence.
const ASYMPTOTIC_X: f64 = 1e6;

/// The shape of one period of the surface height h(x), x across the grooves.
///
/// The Fourier coefficients c_m of p(x) = exp(i·φ·h(x)/h₀) depend on the shape and the phase
/// φ = k·w·h₀ only; [`Profile::efficiency`] is |c_m(φ)|², the share of order m, and
/// Σ_m |c_m|² = 1 (Parseval).
///
/// ```
/// use diffraction::Profile;
/// let sine = Profile::Sine;
/// let binary = Profile::Binary { fraction: 0.5 };
/// // A quarter-wave binary grating at normal incidence (φ = π): no order 0, no even order.
/// assert!(binary.efficiency(0, std::f64::consts::PI) < 1e-30);
/// assert!(binary.efficiency(2, std::f64::consts::PI) < 1e-30);
/// assert!((binary.efficiency(1, std::f64::consts::PI) - 4.0 / std::f64::consts::PI.powi(2)).abs() < 1e-15);
/// let total: f64 = (-60..=60).map(|m| sine.efficiency(m, 7.5)).sum();
/// assert!((total - 1.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Profile {
    /// h(x) = h₀·sin(2πx/d): c_m = J_m(φ) (Jacobi-Anger), so |c_m|² = J_m(φ)².
    /// h₀ is the amplitude, half the peak-to-valley depth.
    Sine,
    /// Grooves of depth h₀ over the fraction `fraction` = a of each period (a rectangular,
    /// binary profile): h = h₀ on [0, a·d), 0 on the rest. Then
    /// c_0 = 1 − a + a·e^{iφ} and c_m = (e^{iφ} − 1)·a·sinc(m·a)·e^{−iπma} for m ≠ 0
    /// (sinc t = sin πt/(πt)), so |c_0|² = 1 − 4a(1 − a)·sin²(φ/2) and
    /// |c_m|² = 4·sin²(φ/2)·sin²(πma)/(πm)².
    Binary {
        /// The fraction a of the period covered by the grooves, 0 < a ≤ 1.
        fraction: f64,
    },
}

impl Profile {
    /// |c_m(φ)|²: the share of the reflected light in order `order` at phase φ = k·w·h₀
    /// (radians). Finite and in [0, 1] for finite φ (to rounding).
    ///
    /// For [`Profile::Sine`] this is [`bessel_j`]`(m, φ)²`, for [`Profile::Binary`] the
    /// closed form above, computed from the complex coefficient with e^{iφ} − 1 written as
    /// 2i·sin(φ/2)·e^{iφ/2} (no cancellation for small φ).
    ///
    /// ```
    /// use diffraction::Profile;
    /// // Order 1 of a sine profile peaks near φ = 1.84 (the maximum of J₁) at 33.86 %.
    /// assert!((Profile::Sine.efficiency(1, 1.8411837813406593) - 0.338567139228272).abs() < 1e-15);
    /// assert_eq!(Profile::Sine.efficiency(3, 0.0), 0.0);
    /// ```
    #[must_use]
    pub fn efficiency(self, order: i32, phase: f64) -> f64 {
        match self {
            Profile::Sine => {
                let j = bessel_j(order, phase);
                j * j
            }
            Profile::Binary { fraction } => binary_coefficient(fraction, order, phase).norm_sqr(),
        }
    }
}

/// The Fourier coefficient c_m of the binary profile (see [`Profile::Binary`]).
fn binary_coefficient(a: f64, m: i32, phase: f64) -> Complex64 {
    let (s, c) = (math::sin(0.5 * phase), math::cos(0.5 * phase));
    // e^{iφ} − 1 = 2i·sin(φ/2)·e^{iφ/2} = −2 sin²(φ/2) + 2i·sin(φ/2)·cos(φ/2).
    let step = Complex64::new(-2.0 * s * s, 2.0 * s * c);
    if m == 0 {
        return Complex64::new(1.0, 0.0) + step * a;
    }
    let (sn, cs) = sincospi(m as f64 * a);
    // a·sinc(m·a) = sin(πma)/(πm).
    step * Complex64::new(cs, -sn) * (sn / (PI * m as f64))
}

/// (sin πt, cos πt) with exact reduction of t to [−½, ½].
fn sincospi(t: f64) -> (f64, f64) {
    let n = math::rint(t);
    let r = t - n;
    let (s, c) = (sinpi(r), sinpi(0.5 - r.abs()));
    if math::rint(0.5 * n) * 2.0 == n {
        (s, c)
    } else {
        (-s, -c)
    }
}

/// The Bessel function of the first kind J_n(x) for integer order n and real x.
///
/// J_{−n}(x) = (−1)ⁿ·J_n(x) and J_n(−x) = (−1)ⁿ·J_n(x) reduce it to n, x ≥ 0. Then:
///
/// * x < 10⁻⁸: the first two terms of the power series, (x/2)ⁿ/n!·(1 − x²/(4(n + 1)));
/// * n > 1.443·x + 1100: 0, since |J_n(x)| ≤ (x/2)ⁿ/n! < 2⁻¹⁰⁷⁵ (below the smallest `f64`);
/// * x ≤ 10⁶: Miller's backward recurrence J_{k−1} = (2k/x)·J_k − J_{k+1}, started at
///   k = max(n, x) + 10·x^{1/3} + 25 (past the turning point k ≈ x by ten times the width
///   x^{1/3} of the transition region, where the neglected solution Y has fallen below 10⁻¹⁷
///   relative) and normalised by J_0² + 2·Σ_k J_k² = 1 (a sum of squares: no cancellation),
///   its sign from J_0 + 2·Σ_k J_{2k} = 1. Cost: max(n, x) + 10·x^{1/3} + 25 steps;
/// * x > 10⁶: J_0 and J_1 from Hankel's asymptotic expansion (three terms, error below 10⁻²⁰)
///   and forward recurrence for n ≤ x, Miller as above for n > x.
///
/// **Accuracy**, guaranteed by `tests/baselines.rs` against `mpmath.besselj` at 50 digits
/// (`tests/data/stam_orders.csv`, 1200 cases): for |x| ≤ 1000 and every order, absolute error
/// below 10⁻¹⁴ (measured: 2.7·10⁻¹⁶), and relative error below 10⁻¹³ where J_n decays
/// (|n| > |x| + 5; measured 9·10⁻¹⁵); at x = 1.5·10⁶ and 2·10⁷ (the asymptotic path, |J| ≈ 10⁻³)
/// absolute error below 10⁻¹⁷. Non-finite x gives NaN.
///
/// ```
/// use diffraction::stam::bessel_j;
/// assert_eq!(bessel_j(0, 0.0), 1.0);
/// assert!((bessel_j(0, 2.404825557695773)).abs() < 1e-15); // the first zero of J₀
/// assert!((bessel_j(1, 1.0) - 0.44005058574493355).abs() < 1e-15);
/// assert_eq!(bessel_j(-3, 2.0), -bessel_j(3, 2.0));
/// assert!((bessel_j(2, 100.0) + 0.021528757344505366).abs() < 1e-15);
/// ```
#[must_use]
pub fn bessel_j(order: i32, x: f64) -> f64 {
    if !x.is_finite() {
        return f64::NAN;
    }
    let n = order.unsigned_abs();
    let odd = n % 2 == 1;
    let flip = odd && ((order < 0) != (x < 0.0));
    let j = bessel_j_nonnegative(n, x.abs());
    if flip {
        -j
    } else {
        j
    }
}

/// J_n(x) for n ≥ 0, finite x ≥ 0.
fn bessel_j_nonnegative(n: u32, x: f64) -> f64 {
    if x < SERIES_X {
        return series(n, x);
    }
    let nf = n as f64;
    if nf > 1.443 * x + 1100.0 {
        return 0.0;
    }
    if x > ASYMPTOTIC_X && nf <= x {
        return forward(n, x);
    }
    let mut at_n = 0.0;
    let norm = miller(x, start_index(nf, x), &mut |k, jk, rescale| {
        at_n *= rescale;
        if k == n {
            at_n = jk;
        }
    });
    at_n * norm
}

/// (x/2)ⁿ/n!·(1 − x²/(4(n + 1))) for x < 10⁻⁸ (the next term is below 10⁻³³ relative).
fn series(n: u32, x: f64) -> f64 {
    if x == 0.0 {
        return if n == 0 { 1.0 } else { 0.0 };
    }
    let mut t = 1.0;
    let mut k = 1;
    while k <= n && t != 0.0 {
        t *= 0.5 * x / k as f64;
        k += 1;
    }
    t * (1.0 - x * x / (4.0 * (n as f64 + 1.0)))
}

/// The start of the backward recurrence for orders up to `n` at x.
fn start_index(n: f64, x: f64) -> u32 {
    let k = n.max(x) + 10.0 * math::cbrt(x.max(1.0)) + 25.0;
    math::ceil(k).min(u32::MAX as f64 - 1.0) as u32
}

/// Miller's backward recurrence from `top` down to 0 at x > 0. Calls `visit(k, J̃_k, rescale)`
/// for every k (J̃ the unnormalised values, already multiplied by every rescaling factor so far;
/// `rescale` is the factor applied to earlier values at this step, 1 if none) and returns the
/// normalisation s with J_k = s·J̃_k.
fn miller(x: f64, top: u32, visit: &mut dyn FnMut(u32, f64, f64)) -> f64 {
    let mut above = 0.0; // J̃_{k+1}
    let mut cur = 1.0; // J̃_k
    let mut squares = 0.0; // 2·Σ_{j>k} J̃_j²
    let mut even = 0.0; // 2·Σ_{j>k, j even} J̃_j
    let mut k = top;
    let mut rescale = 1.0;
    loop {
        visit(k, cur, rescale);
        if k == 0 {
            squares += cur * cur;
            even += cur;
            break;
        }
        squares += 2.0 * cur * cur;
        if k % 2 == 0 {
            even += 2.0 * cur;
        }
        let below = (2.0 * k as f64 / x) * cur - above;
        above = cur;
        cur = below;
        k -= 1;
        rescale = 1.0;
        if cur.abs() > BIG {
            rescale = 1.0 / BIG;
            cur *= rescale;
            above *= rescale;
            squares *= rescale * rescale;
            even *= rescale;
        }
    }
    let s = 1.0 / math::sqrt(squares);
    if even < 0.0 {
        -s
    } else {
        s
    }
}

/// J_n(x) for x > 10⁶, n ≤ x: Hankel's expansion for J_0 and J_1, then forward recurrence.
fn forward(n: u32, x: f64) -> f64 {
    let (s, c) = (math::sin(x), math::cos(x));
    let z = 8.0 * x;
    let hankel = |mu: f64, cos_chi: f64, sin_chi: f64| {
        let p = 1.0 - (mu - 1.0) * (mu - 9.0) / (2.0 * z * z);
        let q = (mu - 1.0) / z - (mu - 1.0) * (mu - 9.0) * (mu - 25.0) / (6.0 * z * z * z);
        math::sqrt(2.0 / (PI * x)) * (p * cos_chi - q * sin_chi)
    };
    let r = core::f64::consts::FRAC_1_SQRT_2;
    // χ₀ = x − π/4, χ₁ = x − 3π/4, by the addition formulas (no rounding of x − π/4).
    let j0 = hankel(0.0, r * (c + s), r * (s - c));
    if n == 0 {
        return j0;
    }
    let j1 = hankel(4.0, r * (s - c), -r * (s + c));
    let (mut prev, mut cur) = (j0, j1);
    for k in 1..n {
        let next = (2.0 * k as f64 / x) * cur - prev;
        prev = cur;
        cur = next;
    }
    cur
}

/// Σ_{m=lo}^{hi} J_m(x)²·weight(m) for x ≥ 0, in one backward recurrence.
fn bessel_squares(x: f64, lo: i64, hi: i64, weight: &mut dyn FnMut(i64) -> f64) -> f64 {
    if lo > hi {
        return 0.0;
    }
    let nearest = if lo <= 0 && hi >= 0 {
        0
    } else {
        lo.abs().min(hi.abs())
    };
    if nearest as f64 > 1.443 * x + 1100.0 {
        return 0.0;
    }
    if !(SERIES_X..=ASYMPTOTIC_X).contains(&x) || hi - lo > 4096 {
        let mut sum = 0.0;
        for m in lo..=hi.min(lo + 4096) {
            if let Ok(m32) = i32::try_from(m) {
                let j = bessel_j(m32, x);
                if j != 0.0 {
                    sum += j * j * weight(m);
                }
            }
        }
        return sum;
    }
    let farthest = lo.abs().max(hi.abs()) as f64;
    let mut acc = 0.0;
    let norm = miller(x, start_index(farthest, x), &mut |k, jk, rescale| {
        acc *= rescale * rescale;
        let k = k as i64;
        let sq = jk * jk;
        if (lo..=hi).contains(&k) {
            acc += sq * weight(k);
        }
        if k != 0 && (lo..=hi).contains(&-k) {
            acc += sq * weight(-k);
        }
    });
    acc * norm * norm
}

/// Stam's diffraction shader for a one-dimensional periodic surface (see the
/// [module docs](self) for the derivation and every assumption).
///
/// ```text
/// f(wi, wo, λ) = F² · G/w² · Σ_m |c_m(k·w·h₀)|² · (k²σ_c²/π) · exp(−k²σ_c²·[(u − m·λ/d)² + v²])
/// ```
///
/// with (u, v, w) = wi + wo in the local frame, k = 2π/λ, G = (1 + wi·wo)²/(wi.z·wo.z), c_m the
/// [`Profile`]'s Fourier coefficients and F² Schlick's reflectance. A BRDF: multiply by
/// cos θi ([`cosine_included`](DiffractionBrdf::cosine_included) is `false`).
///
/// ```
/// use diffraction::{Band, DiffractionBrdf, Profile, Stam};
/// use glam::DVec3;
/// // A sinusoidal grating of period 1.6 µm and amplitude 80 nm, coherent over 8 µm.
/// let s = Stam::new(Profile::Sine, 1600.0, 80.0, 8000.0)?;
/// let wi = DVec3::Z;
/// let wo = DVec3::new(0.3, 0.0, (1.0f64 - 0.09).sqrt()); // u = 0.3: order 1 at 480 nm
/// let mut peaks = vec![];
/// let summary = s.peaks(wi, wo, Band::VISIBLE, &mut |p| peaks.push(p));
/// assert_eq!((summary.orders, peaks[0].order), (1, 1));
/// assert!((peaks[0].wavelength_nm - 480.0).abs() < 1e-9);
/// assert!((s.eval(wi, wo, 480.0) - peaks[0].intensity).abs() < 1e-9 * peaks[0].intensity);
/// assert!(s.eval(wi, wo, 480.0) > 1e3 * s.eval(wi, wo, 530.0)); // between the orders: dark
/// assert_eq!(s.eval(wi, wo, 480.0), s.eval(wo, wi, 480.0)); // reciprocity
/// assert!(!s.cosine_included());
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stam {
    profile: Profile,
    /// The grating equation (slit width = period: no envelope is used).
    grating: Grating,
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
    /// overlap, see the module docs); a binary `fraction` outside (0, 1]; non-finite values.
    /// Errors name `period_nm`, `depth_nm`, `coherence_nm` or `fraction`.
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
        let grating = Grating::with_slits(d, d, Slits::Infinite)?;
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
            grating,
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
    /// let (wi, wo) = (DVec3::Z, DVec3::Z);
    /// assert!((dim.eval(wi, wo, 550.0) - 0.5 * s.eval(wi, wo, 550.0)).abs() < 1e-9 * s.eval(wi, wo, 550.0));
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
        self.grating.period_nm()
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
    pub fn phase(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        2.0 * PI * (wi.z + wo.z) * self.depth_nm / lambda_nm
    }

    /// F²·G/w², the factor common to every order (0 where it is not finite).
    fn geometry(&self, wi: DVec3, wo: DVec3) -> f64 {
        let w = wi.z + wo.z;
        let c = 1.0 + wi.dot(wo);
        let cos_h = math::sqrt((0.5 * c).clamp(0.0, 1.0));
        let t = 1.0 - cos_h;
        let t2 = t * t;
        let fresnel = self.reflectance + (1.0 - self.reflectance) * (t2 * t2 * t);
        let g = fresnel * c * c / (wi.z * wo.z * w * w);
        if g.is_finite() {
            g
        } else {
            0.0
        }
    }
}

impl DiffractionBrdf for Stam {
    /// The formula of [`Stam`]; 0 below the surface, for λ < 1 nm (outside optics) and for
    /// non-finite input.
    fn eval(&self, wi: DVec3, wo: DVec3, lambda_nm: f64) -> f64 {
        if !(wi.z > 0.0 && wo.z > 0.0 && lambda_nm >= MIN_WAVELENGTH_NM) {
            return 0.0;
        }
        if !(wi.is_finite() && wo.is_finite() && lambda_nm.is_finite()) {
            return 0.0;
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let ks = 2.0 * PI * self.coherence_nm / lambda_nm;
        let reach = CUTOFF / ks; // in u and v
        if v.abs() >= reach {
            return 0.0;
        }
        let step = lambda_nm / self.grating.period_nm();
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
        let phase = self.phase(wi, wo, lambda_nm);
        let sum = match self.profile {
            Profile::Sine => bessel_squares(phase.abs(), lo, hi, &mut |m| lobe(m)),
            Profile::Binary { fraction } => (lo..=hi)
                .map(|m| {
                    let m32 = m.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
                    binary_coefficient(fraction, m32, phase).norm_sqr() * lobe(m)
                })
                .sum(),
        };
        let f = self.geometry(wi, wo) * ks2 / PI * sum;
        if f.is_finite() {
            f
        } else {
            0.0
        }
    }

    /// Every order m ≠ 0 with λ_m = d·|u|/|m| in `band`, each with its own lobe's value at
    /// λ_m (the whole of `eval` there but for the far tails of the other orders, below
    /// 10⁻¹⁶ of their peaks) and the equivalent width λ_m·d/(2√π·σ_c·|m|). Order 0's lobe is
    /// seen where k·σ_c·√(u² + v²) < 6 at the band's longest wavelength.
    fn peaks(&self, wi: DVec3, wo: DVec3, band: Band, visit: &mut dyn FnMut(Peak)) -> PeakSummary {
        if !(wi.z > 0.0 && wo.z > 0.0 && wi.is_finite() && wo.is_finite()) {
            return PeakSummary::default();
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let d = self.grating.period_nm();
        let sigma = self.coherence_nm;
        let geometry = self.geometry(wi, wo);
        let mut orders = 0;
        for p in self.grating.peaks(u, band) {
            let l = p.wavelength_nm;
            let ks = 2.0 * PI * sigma / l;
            let ks2 = ks * ks;
            // The same cut-off as `eval`: beyond 6 widths off the cone the lobe is 0.
            let efficiency = if l >= MIN_WAVELENGTH_NM && ks * v.abs() < CUTOFF {
                self.profile.efficiency(p.order, self.phase(wi, wo, l))
            } else {
                0.0
            };
            let value = geometry * ks2 / PI * efficiency * math::exp(-ks2 * v * v);
            visit(Peak {
                order: p.order,
                wavelength_nm: l,
                intensity: if value.is_finite() { value } else { 0.0 },
                equivalent_width_nm: l * d / (2.0 * SQRT_PI * sigma * (p.order as f64).abs()),
            });
            orders += 1;
        }
        let reach = CUTOFF * band.max_nm() / (2.0 * PI * sigma);
        PeakSummary {
            orders,
            specular: u * u + v * v < reach * reach,
        }
    }

    fn cosine_included(&self) -> bool {
        false
    }
}
