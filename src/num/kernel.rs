//! The two factors of the Agu-Hill intensity, evaluated stably.
//!
//! * [`single_slit`]`(β)` = (sin β / β)², the diffraction pattern of one slit (paper eq. 5),
//! * [`n_slit`]`(α, N)` = sin²(Nα) / (N² sin²α), the interference of N slits (paper eq. 7-8),
//!
//! each also in a *cycles* form ([`single_slit_cycles`], [`n_slit_cycles`]) that takes the phase
//! divided by π: x = α/π = d·u/λ and y = β/π = w·u/λ. Callers that know x (a grating does) should
//! use the cycles form: it never rounds through α = πx, so the reduction of the phase is exact.
//!
//! # Accuracy
//!
//! Every function here evaluates in `f64` whatever its argument type and rounds once to the
//! caller's precision. Measured against 100-digit mpmath values of the exact function *at the
//! given floating-point argument* (`tests/kernel_reference.rs`, data from `python_ref/`):
//!
//! | function | bound (absolute) | range |
//! |---|---|---|
//! | `n_slit_cycles`, `n_slit` (f64) | 1e-12 | N ≤ 10⁷, \|x\| < 2⁵² (cycles), \|α\| ≤ 10⁵ (radians) |
//! | `single_slit_cycles`, `single_slit` (f64) | 1e-12 | all finite input |
//! | the same in `f32` | 1e-5 (in practice one `f32` rounding) | N ≤ 10⁶, \|α\| ≤ 10⁴ |
//!
//! The results are always inside [0, 1] and never NaN for finite input (N = 0 gives 0: no slit,
//! no light). Non-finite input gives NaN.
//!
//! # How
//!
//! F_N has period 1 in x and depends only on r = x − round(x), which is exact in floating point.
//! The phase N·r is split as N·r_hi + N·r_lo with r_hi on a 2⁻²¹ grid so that N·r_hi is exact
//! (N < 2³²) and is reduced exactly again; only N·r_lo is rounded, which keeps the phase error
//! near 2⁻⁷⁵·N cycles. Near a peak (|N·r| ≤ ½) the ratio is evaluated as sinc(πNr)/sinc(πr), the
//! limit F_N → 1 without 0/0. `sin(π·)` on [−½, ½] is a short polynomial (Taylor coefficients,
//! error below 1e-19), so no general-purpose range reduction is needed on the hot path.
//! Radian arguments are first reduced modulo π with a three-part (Cody-Waite) π, exact for
//! |α| < 2²⁰·π ≈ 3.3·10⁶; beyond that the phase is taken as α/π (relative error 2⁻⁵³).
//!
//! The naive formula (module [`naive`]) has none of this; in `f32` near high orders it returns
//! values far above 1 (e.g. 1.88 at the first orders with N = 5000).

use crate::num::float::Float;
use crate::num::math::rint;

/// The Taylor coefficients (−1)^k π^(2k+1)/(2k+1)! of sin(π·z), k = 0..11, rounded to f64
/// (mpmath, 40 digits): `sinpi` uses the first 9, `sinpi_flat` all 12.
const SIN_PI_TAYLOR: [f64; 12] = [
    core::f64::consts::PI,
    -5.16771278004997,
    2.5501640398773455,
    -0.5992645293207921,
    0.08214588661112823,
    -0.0073704309457143504,
    0.00046630280576761255,
    -2.1915353447830217e-05,
    7.952054001475513e-07,
    -2.2948428997269873e-08,
    5.392664662608129e-10,
    -1.0518471716932065e-11,
];

/// The Taylor coefficients (−1)^k π^(2k)/(2k)! of cos(π·z), k = 0..9, rounded to f64 (mpmath,
/// 40 digits), for |z| ≤ ¼ (`sinpi`, `tanpi_flat`).
const COS_PI_TAYLOR: [f64; 10] = [
    1.0,
    -4.934802200544679,
    4.0587121264167685,
    -1.3352627688545895,
    0.2353306303588932,
    -0.02580689139001406,
    0.0019295743094039231,
    -0.0001046381049248457,
    4.303069587032947e-06,
    -1.3878952462213771e-07,
];

/// (sin πt, cos πt) with exact reduction of t to [−½, ½] (the profiles' Fourier coefficients).
#[cfg(any(feature = "relief", feature = "baselines"))]
pub(crate) fn sincospi(t: f64) -> (f64, f64) {
    let n = rint(t);
    let r = t - n;
    let (s, c) = (sinpi(r), sinpi(0.5 - r.abs()));
    if rint(0.5 * n) * 2.0 == n {
        (s, c)
    } else {
        (-s, -c)
    }
}

/// sin(π·z) for |z| ≤ ½ (accurate to a few ulp; larger |z| is not expected).
#[inline]
pub(crate) fn sinpi(z: f64) -> f64 {
    // The first 9 sine coefficients, and the cosine's.
    const S: &[f64; 12] = &SIN_PI_TAYLOR; // S[0..=8] are used
    const C: &[f64; 10] = &COS_PI_TAYLOR;
    let a = z.abs();
    if a <= 0.25 {
        let z2 = z * z;
        let mut p = S[8];
        let mut i = 8;
        while i > 0 {
            i -= 1;
            p = p * z2 + S[i];
        }
        p * z
    } else {
        // sin(πa) = cos(π(½ − a)); ½ − a is exact for a in [¼, ½].
        let c = 0.5 - a;
        let c2 = c * c;
        let mut p = C[9];
        let mut i = 9;
        while i > 0 {
            i -= 1;
            p = p * c2 + C[i];
        }
        if z < 0.0 {
            -p
        } else {
            p
        }
    }
}

/// Reduces a phase in radians modulo π and returns it in cycles: r with α ≡ π·r (mod π), |r| ≤ ½.
#[inline]
fn reduce_radians(alpha: f64) -> f64 {
    // π = P1 + P2 + P3 to 2⁻¹²⁰ relative; P1 and P2 have 33 significant bits, so k·P1 and
    // k·P2 are exact for |k| < 2²⁰ and α − k·P1 is exact (Sterbenz).
    const P1: f64 = 3.1415926534682512;
    const P2: f64 = 1.2154201012607932e-10;
    const P3: f64 = 4.044532497591901e-21;
    const FRAC_1_PI: f64 = core::f64::consts::FRAC_1_PI;
    let k = rint(alpha * FRAC_1_PI);
    if k.abs() < 1_048_576.0 {
        let rho = ((alpha - k * P1) - k * P2) - k * P3;
        rho * FRAC_1_PI
    } else {
        let x = alpha * FRAC_1_PI;
        x - rint(x)
    }
}

/// N·r = N·r_hi + N·r_lo is split at 2⁻²¹ so that N·r_hi is exact for every N < 2³²: r_hi has
/// at most 21 fraction bits below ½, so N·r_hi needs at most 53 bits.
const SPLIT: f64 = 2_097_152.0; // 2^21

/// N·r reduced modulo 1 exactly: r = r_hi + r_lo with r_hi on the 2⁻²¹ grid, N·r_hi exact and
/// reduced by `rint`, N·r_lo added, and the sum reduced again (|result| ≤ ½). The one phase
/// split of both N-slit kernels.
#[inline(always)]
fn reduce_n_phase(r: f64, nf: f64) -> f64 {
    let r_hi = rint(r * SPLIT) * (1.0 / SPLIT);
    let p_hi = nf * r_hi;
    let s = (p_hi - rint(p_hi)) + nf * (r - r_hi);
    s - rint(s)
}

/// F_N = (num/den)² at a phase reduced to |r| ≤ ½ cycles, `n` ≥ 2: the numerator and denominator
/// of sin(πNr)/(N·sin(πr)), with N·r reduced exactly and the limit at the peak guarded.
#[inline]
fn n_slit_ratio(r: f64, n: u32) -> (f64, f64) {
    let nf = n as f64;
    let s = reduce_n_phase(r, nf);
    if (nf * r).abs() <= 0.5 {
        // No wrap: s = N·r. Near the peak F = (sinc(πs)/sinc(πr))².
        if s.abs() < 1e-12 {
            (1.0, 1.0) // F = 1 − O((πs)²) = 1 in f64
        } else {
            // sinc(πs)/sinc(πr) = sin(πs)·r / (s·sin(πr)); r ≥ s/N > 1e-22, no underflow.
            (sinpi(s) * r, s * sinpi(r))
        }
    } else {
        (sinpi(s), nf * sinpi(r))
    }
}

/// F_N for a phase already reduced to |r| ≤ ½ cycles (f64 core).
#[inline]
fn n_slit_reduced(r: f64, n: u32) -> f64 {
    if n <= 1 {
        return if n == 0 { 0.0 } else { 1.0 };
    }
    let (num, den) = n_slit_ratio(r, n);
    let f = num / den;
    (f * f).min(1.0)
}

/// S(y)·F_N(x) with one division: the grating intensity for phases in cycles (x = d·u/λ,
/// y = w·u/λ), `n` ≥ 2. Same accuracy as the product of [`single_slit_cycles`] and
/// [`n_slit_cycles`] (a few ulp of each factor), about half the cost.
#[inline]
pub(crate) fn intensity_cycles(x: f64, y: f64, n: u32) -> f64 {
    let (f_num, f_den) = n_slit_ratio(x - rint(x), n);
    // S = (s_num/s_den)², as in `single_slit_core`.
    let (s_num, s_den) = if y.abs() < 1e-8 {
        (1.0, 1.0) // 1 − (πy)²/3 = 1 to 3e-16
    } else {
        (sinpi(y - rint(y)), core::f64::consts::PI * y)
    };
    let q = (f_num * s_num) / (f_den * s_den);
    let i = q * q;
    if i > 1.0 {
        1.0
    } else {
        i
    }
}

/// Σ c_k·x^k for k < K ≤ 12 by Estrin's scheme: pairs c_2j + c_2j+1·x, combined with x², x⁴
/// and x⁸ (a dependency chain of four products and sums where Horner's has K − 1), so that the
/// flat kernels' polynomials do not serialise a sample's arithmetic.
#[inline(always)]
fn estrin<const K: usize>(c: &[f64; K], x: f64) -> f64 {
    let at = |k: usize| if k < K { c[k] } else { 0.0 };
    let pair = |j: usize| {
        if 2 * j + 1 < K {
            c[2 * j] + c[2 * j + 1] * x
        } else {
            at(2 * j)
        }
    };
    let x2 = x * x;
    let x4 = x2 * x2;
    let (a0, a1, a2, a3, a4, a5) = (pair(0), pair(1), pair(2), pair(3), pair(4), pair(5));
    let b0 = a0 + a1 * x2;
    let b1 = a2 + a3 * x2;
    let b2 = a4 + a5 * x2;
    if K <= 4 {
        b0
    } else if K <= 8 {
        b0 + b1 * x4
    } else {
        b0 + x4 * (b1 + b2 * x4)
    }
}

/// sin(π·z) for |z| ≤ ½ without branches: one Taylor polynomial of degree 23 (truncation below
/// 2·10⁻¹⁸; measured 1.5 ulp relative against mpmath on a grid), for callers that evaluate
/// several phases at once and lose more to mispredicted branches than to the longer polynomial.
/// The polynomial in w = z² is evaluated in two parts: the 8 small terms of degree ≥ 4 in w by
/// Estrin's scheme (pairs of terms, then pairs of pairs with w² and w⁴), the 4 leading ones by
/// Horner's, whose last steps set the rounding: a chain of 7 multiply-adds instead of 11, the
/// latency that bounds the lobe integrands built on it, with Horner's accuracy.
#[inline(always)]
pub(crate) fn sinpi_flat(z: f64) -> f64 {
    const S: &[f64; 12] = &SIN_PI_TAYLOR;
    let w = z * z;
    let w2 = w * w;
    let w4 = w2 * w2;
    let a0 = S[4] + S[5] * w;
    let a1 = S[6] + S[7] * w;
    let a2 = S[8] + S[9] * w;
    let a3 = S[10] + S[11] * w;
    let tail = (a0 + a1 * w2) + (a2 + a3 * w2) * w4;
    let p = S[0] + w * (S[1] + w * (S[2] + w * (S[3] + w * tail)));
    p * z
}

/// The first 9 sine coefficients (degree 17, for |w| ≤ ¼).
const SIN_PI_TAYLOR_9: [f64; 9] = [
    SIN_PI_TAYLOR[0],
    SIN_PI_TAYLOR[1],
    SIN_PI_TAYLOR[2],
    SIN_PI_TAYLOR[3],
    SIN_PI_TAYLOR[4],
    SIN_PI_TAYLOR[5],
    SIN_PI_TAYLOR[6],
    SIN_PI_TAYLOR[7],
    SIN_PI_TAYLOR[8],
];

/// (cos 2πc, sin 2πc) for any finite c without branches: c reduced to r ∈ [−½, ½] (exact),
/// e^{iπr/2} from the polynomials of `sinpi` at z = r/2 (|z| ≤ ¼, sharing z²), squared twice.
/// Within 1.0·10⁻¹⁵ of the standard library's (`tests`).
#[inline]
pub(crate) fn cis_turn(c: f64) -> (f64, f64) {
    let z = 0.5 * (c - rint(c));
    let w = z * z;
    let (co, si) = (estrin(&COS_PI_TAYLOR, w), estrin(&SIN_PI_TAYLOR_9, w) * z);
    let (co, si) = ((co - si) * (co + si), 2.0 * co * si);
    ((co - si) * (co + si), 2.0 * co * si)
}

/// tan(π·z) for |z| ≤ ½ without branches (selects only): with a = |z| folded to w = a (a ≤ ¼)
/// or w = ½ − a (exact for a ≥ ¼), the sine and cosine of π·w from the same Taylor polynomials
/// as [`sinpi`] (degrees 17 and 18 on |w| ≤ ¼, in parallel, by Estrin's scheme), and
/// tan = sin/cos or cos/sin: one division, no library call. Measured 2.3 ulp relative against
/// mpmath on 40,000 points of |z| < ½; ±∞ is never returned: at |z| = ½ the divisor is
/// taken as the smallest normal `f64` (a finite ±4.5·10³⁰⁷).
#[inline(always)]
pub(crate) fn tanpi_flat(z: f64) -> f64 {
    let a = z.abs();
    let low = a <= 0.25;
    let w = if low { a } else { 0.5 - a };
    let w2 = w * w;
    let sw = estrin(&SIN_PI_TAYLOR_9, w2) * w;
    let cp = estrin(&COS_PI_TAYLOR, w2);
    let (num, den) = if low { (sw, cp) } else { (cp, sw) };
    let t = num / den.max(f64::MIN_POSITIVE);
    if z < 0.0 {
        -t
    } else {
        t
    }
}

/// sin(π·y)/(π·y) as a numerator and a denominator without branches (selects only), y in
/// cycles: (sin(π·(y − round y)), π·y), and (1, 1) where |y| < 10⁻⁸ (the limit, 1 − (πy)²/6 = 1
/// to 2·10⁻¹⁶). Squared it is the single-slit factor S.
#[inline(always)]
pub(crate) fn sinc_ratio_flat(y: f64) -> (f64, f64) {
    let small = y.abs() < 1e-8;
    let num = if small { 1.0 } else { sinpi_flat(y - rint(y)) };
    let den = if small {
        1.0
    } else {
        core::f64::consts::PI * y
    };
    (num, den)
}

/// √(S(y)·F_N(x)) as a numerator and a denominator, without branches on the phase (selects
/// only), for phases in cycles (x = d·u/λ, y = w·u/λ): the same reduction and the same guarded
/// limits as [`intensity_cycles`], with a branch-free sin(π·), so that a caller can evaluate four
/// wavelengths side by side and fold further factors into one division. `n` ≤ 1 is the single
/// slit alone (F_1 = 1; one branch on `n`, which is the same for every call of a grating).
/// Squared, num/den agrees with [`intensity_cycles`] to a few ulp (it is not clamped to 1).
#[inline(always)]
pub(crate) fn intensity_ratio_flat(x: f64, y: f64, n: u32) -> (f64, f64) {
    let (s_num, s_den) = sinc_ratio_flat(y);
    if n <= 1 {
        return (s_num, s_den);
    }
    let nf = n as f64;
    let r = x - rint(x);
    let s = reduce_n_phase(r, nf);
    let (sin_s, sin_r) = (sinpi_flat(s), sinpi_flat(r));
    let near = (nf * r).abs() <= 0.5;
    let top = s.abs() < 1e-12;
    let f_num = if near {
        if top {
            1.0
        } else {
            sin_s * r
        }
    } else {
        sin_s
    };
    let f_den = if near {
        if top {
            1.0
        } else {
            s * sin_r
        }
    } else {
        nf * sin_r
    };
    (f_num * s_num, f_den * s_den)
}

/// F_N(x) = sin²(πNx) / (N² sin²(πx)) with the phase in cycles, x = α/π = d·u/λ.
///
/// Equals 1 at every integer x (the grating-equation maxima), 0 at x = k/N for k not a
/// multiple of N, and lies in [0, 1] everywhere. `n = 1` gives 1 everywhere; `n = 0` gives 0.
/// See the [module docs](self) for the accuracy.
///
/// ```
/// use diffraction::kernel::n_slit_cycles;
/// assert_eq!(n_slit_cycles(40.0_f64, 5000), 1.0); // a maximum, order 40
/// assert!(n_slit_cycles(40.0 + 1.0 / 5000.0, 5000) < 1e-20); // its first zero
/// assert!(n_slit_cycles(40.1_f32, 5000) <= 1.0);
/// ```
#[inline]
#[must_use]
pub fn n_slit_cycles<T: Float>(x: T, n: u32) -> T {
    let x = x.to_f64();
    T::from_f64(n_slit_reduced(x - rint(x), n))
}

/// F_N(α) = sin²(Nα) / (N² sin²α), the N-slit factor of the paper's eq. 8, α in radians.
///
/// Prefer [`n_slit_cycles`] when the phase is known in cycles. See the [module docs](self)
/// for the accuracy.
///
/// ```
/// use diffraction::kernel::n_slit;
/// use core::f64::consts::PI;
/// assert!((n_slit(3.0 * PI, 1_000_000) - 1.0).abs() < 1e-12);
/// assert!(n_slit(PI / 2.0, 2) < 1e-30); // sin(π) = 0
/// ```
#[inline]
#[must_use]
pub fn n_slit<T: Float>(alpha: T, n: u32) -> T {
    T::from_f64(n_slit_reduced(reduce_radians(alpha.to_f64()), n))
}

/// S = (sin(πy)/(πy))² with y = β/π = w·u/λ in cycles; S(0) = 1.
///
/// Zeros at every non-zero integer y. See the [module docs](self) for the accuracy.
///
/// ```
/// use diffraction::kernel::single_slit_cycles;
/// assert_eq!(single_slit_cycles(0.0_f64), 1.0);
/// assert!(single_slit_cycles(3.0_f64) < 1e-30);
/// let half = single_slit_cycles(0.5_f64); // (2/π)²
/// assert!((half - 4.0 / (std::f64::consts::PI * std::f64::consts::PI)).abs() < 1e-15);
/// ```
#[inline]
#[must_use]
pub fn single_slit_cycles<T: Float>(y: T) -> T {
    let y = y.to_f64();
    T::from_f64(single_slit_core(y - rint(y), core::f64::consts::PI * y))
}

/// S(β) = (sin β / β)², the single-slit factor of the paper's eq. 5, β in radians; S(0) = 1.
///
/// ```
/// use diffraction::kernel::single_slit;
/// assert_eq!(single_slit(0.0_f32), 1.0);
/// assert!((single_slit(1.0_f64) - 0.708073418273571).abs() < 1e-15); // sin²1
/// ```
#[inline]
#[must_use]
pub fn single_slit<T: Float>(beta: T) -> T {
    let b = beta.to_f64();
    T::from_f64(single_slit_core(reduce_radians(b), b))
}

/// (sin(π r)/β)² where r ≡ β/π (mod 1), reduced, and β is the full phase in radians.
#[inline]
fn single_slit_core(r: f64, beta: f64) -> f64 {
    if beta.abs() < 1e-8 {
        // 1 − β²/3 + O(β⁴): exact to f64 precision here, and safe for subnormal β.
        return 1.0 - beta * beta / 3.0;
    }
    let q = sinpi(r) / beta;
    let s = q * q;
    if s > 1.0 {
        1.0
    } else {
        s
    }
}

/// The textbook formulas evaluated directly in the caller's precision, for comparison only.
///
/// These are what the stable kernels replace: they divide 0 by 0 at the maxima (returning NaN),
/// and in `f32` they leave [0, 1] near high-order peaks. Benchmarks and tests use them as the
/// baseline; renderers should not.
///
/// ```
/// use diffraction::kernel::{n_slit, n_slit_cycles, naive};
/// let x = 40.000004f32; // just off the 40th order, N = 5000
/// let alpha = std::f32::consts::PI * x;
/// assert!(naive::n_slit(alpha, 5000) > 2.0); // far outside [0, 1]
/// assert!(n_slit(alpha, 5000) <= 1.0); // the same f32 input
/// assert!(n_slit_cycles(x, 5000) <= 1.0);
/// ```
pub mod naive {
    use crate::num::float::Float;

    /// sin²(Nα)/(N² sin²α) evaluated directly in `T`; NaN where sin α = 0.
    ///
    /// ```
    /// use diffraction::kernel::{n_slit, naive};
    /// // Away from the zeros of sin α the direct formula is accurate.
    /// assert!((naive::n_slit(0.1f64, 4) - n_slit(0.1f64, 4)).abs() < 1e-14);
    /// assert!(naive::n_slit(0.0f64, 4).is_nan()); // 0/0 at the principal maximum, where F_N = 1
    /// ```
    #[inline]
    #[must_use]
    pub fn n_slit<T: Float>(alpha: T, n: u32) -> T {
        let nf = T::from_u32(n);
        let num = (nf * alpha).sin_native();
        let den = nf * alpha.sin_native();
        let q = num / den;
        q * q
    }

    /// (sin β/β)² evaluated directly in `T`; NaN at β = 0.
    ///
    /// ```
    /// use diffraction::kernel::{naive, single_slit};
    /// assert!((naive::single_slit(1.0f64) - single_slit(1.0f64)).abs() < 1e-15);
    /// assert!(naive::single_slit(0.0f64).is_nan()); // 0/0 at β = 0, where S = 1
    /// ```
    #[inline]
    #[must_use]
    pub fn single_slit<T: Float>(beta: T) -> T {
        let q = beta.sin_native() / beta;
        q * q
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sinpi_matches_std_on_its_range() {
        let mut worst: f64 = 0.0;
        for i in -5000..=5000 {
            let z = i as f64 / 10000.0;
            let e = (sinpi(z) - (core::f64::consts::PI * z).sin()).abs();
            worst = worst.max(e);
        }
        assert!(worst < 4e-16, "worst {worst}");
        assert_eq!(sinpi(0.5), 1.0);
        assert_eq!(sinpi(-0.5), -1.0);
        assert_eq!(sinpi(0.0), 0.0);
    }

    /// e^{2πic} against the standard library's sin and cos of 2π·r (r = c − round(c)), over
    /// several periods. Measured 1.0e-15 at worst (the two squarings double the polynomials'
    /// error twice; the rounding of 2π·r itself is up to 3.5e-16); asserted below 2e-15.
    #[test]
    fn cis_turn_matches_std() {
        let two_pi = 2.0 * core::f64::consts::PI;
        let mut worst: f64 = 0.0;
        for i in -40_000..=40_000 {
            let c = i as f64 / 10_000.0 + 3.1e-7 * (i % 5) as f64;
            let r = c - c.round();
            let (co, si) = cis_turn(c);
            worst = worst.max((co - (two_pi * r).cos()).abs());
            worst = worst.max((si - (two_pi * r).sin()).abs());
        }
        assert!(worst < 2e-15, "worst {worst}");
        assert_eq!(cis_turn(0.0), (1.0, 0.0));
    }

    /// tan(π·z) against the standard library's: tan(π·z) where π·z rounds harmlessly
    /// (|z| ≤ 0.4, condition number below 5), and 1/tan(π·(½ − |z|)) (with ½ − |z| exact) in
    /// the outer part where tan itself is ill-conditioned. Measured 4.0 ulp relative at worst;
    /// asserted below 8 ulp.
    #[test]
    fn tanpi_flat_matches_std() {
        let pi = core::f64::consts::PI;
        let mut worst: f64 = 0.0;
        for i in -100_000..=100_000 {
            let z = i as f64 / 200_000.0 + 1.37e-7 * (i % 7) as f64;
            let z = z.clamp(-0.5, 0.5);
            let a = z.abs();
            let want = if a <= 0.4 {
                (pi * z).tan()
            } else if a < 0.5 {
                z.signum() / (pi * (0.5 - a)).tan()
            } else {
                continue;
            };
            let got = tanpi_flat(z);
            if want != 0.0 {
                worst = worst.max(((got - want) / want).abs());
            } else {
                assert_eq!(got, 0.0);
            }
        }
        eprintln!("tanpi_flat: worst {:.2} ulp", worst / f64::EPSILON);
        assert!(worst < 8.0 * f64::EPSILON, "worst {worst:e}");
        // tan(π/4) = 1 to the quotient's rounding, odd.
        assert!((tanpi_flat(0.25) - 1.0).abs() <= 2.0 * f64::EPSILON);
        assert_eq!(tanpi_flat(-0.25), -tanpi_flat(0.25));
        // The poles stay finite, with the sign of z.
        assert!(tanpi_flat(0.5).is_finite() && tanpi_flat(0.5) > 1e300);
        assert!(tanpi_flat(-0.5).is_finite() && tanpi_flat(-0.5) < -1e300);
    }

    #[test]
    fn flat_kernels_match_the_branching_ones() {
        // The degree-23 polynomial against the two short ones (each a few ulp from sin(πz)).
        let mut worst: f64 = 0.0;
        for i in -5000..=5000 {
            let z = i as f64 / 10000.0;
            worst = worst.max((sinpi_flat(z) - sinpi(z)).abs());
        }
        assert!(worst < 4e-16, "worst {worst}");
        // The flat ratio squared against `intensity_cycles` (measured within 4 ulp relative).
        for n in [2u32, 5, 1000, 1_000_000] {
            for i in 0..4000 {
                let x = 3.0 * i as f64 / 4000.0 + 1e-3 / n as f64;
                let (num, den) = intensity_ratio_flat(x, 0.5 * x, n);
                let q = num / den;
                let (a, b) = (q * q, intensity_cycles(x, 0.5 * x, n));
                assert!(
                    (a - b).abs() <= 16.0 * f64::EPSILON * b,
                    "n={n} x={x}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn reduction_is_exact_at_multiples_of_pi() {
        // α = fl(k·π) differs from k·π by its rounding. With π = π_hi + π_lo (two doubles) and a
        // fused multiply-add, α − k·π is known to far below the size of that rounding; the
        // reduced phase must be that difference over π, not a rounding artefact of α/π.
        const PI_LO: f64 = 1.2246467991473532e-16;
        for k in [1.0f64, 7.0, 1000.0, 31831.0, 100_000.0] {
            let alpha = k * core::f64::consts::PI;
            let diff = (-k).mul_add(core::f64::consts::PI, alpha) - k * PI_LO;
            let want = diff / core::f64::consts::PI;
            let r = reduce_radians(alpha);
            assert!(
                (r - want).abs() <= 1e-9 * want.abs(),
                "k={k} r={r} want={want}"
            );
        }
    }
}
