//! The shape of the grating's lobes: the value f(u, v) of the finite-N lobes (the single-slit
//! factor, the N-slit factor and the groove spread, fused into one division) and the proxy of F_N
//! inside one period that the sampler draws u from ([`PeriodProxy`]).
//!
//! For N ≥ 2, F_N(π·r) ≤ 2/(1 + 4N²r²) on |r| ≤ ½, so the Lorentzian density
//! q(r) = N/((1 + 4N²r²)·atan N) on |r| < ½ (inverse CDF r = tan((2ξ − 1)·atan N)/(2N)) bounds
//! N·F_N/q by 2·atan N < π. For N = 1, F_1 ≡ 1 and the proxy is F_1 itself: the uniform
//! density q(r) = 1 (r = ξ − ½, no tangent), for which N·F_N/q = 1 exactly.

use crate::optics::groove::{GrooveKind, GrooveSpread};
use core::f64::consts::FRAC_1_PI;

use crate::num::kernel::{intensity_ratio_flat, sinc_ratio_flat, tanpi_flat};

/// The Lorentzian proxy's inverse CDF: r = tan((2t − 1)·atan N)/(2N), |r| ≤ ½ (a = atan N),
/// with the tangent taken in cycles (`tanpi_flat` at (2t − 1)·a/π: no library call).
#[inline]
pub(super) fn lorentz_r(n: f64, atan_n: f64, t: f64) -> f64 {
    let r = tanpi_flat((2.0 * t - 1.0) * (atan_n * FRAC_1_PI)) / (2.0 * n);
    r.clamp(-0.5, 0.5)
}

/// The Lorentzian proxy's density on |r| < ½: N/((1 + 4N²r²)·atan N).
#[inline]
pub(super) fn lorentz_q(n: f64, atan_n: f64, r: f64) -> f64 {
    if r.abs() > 0.5 {
        return 0.0;
    }
    let t = 2.0 * n * r;
    n / ((1.0 + t * t) * atan_n)
}

/// The direction sampler's proxy of N·F_N(π·r) inside one period, r ∈ [−½, ½): the Lorentzian
/// q(r) = (N/atan N)/(1 + (2N·r)²) for N ≥ 2, the uniform q(r) = 1 for N = 1 (F_1 itself), with
/// its constants precomputed. Both densities have the form peak/(1 + (c·r)²) (c = 0 for the
/// uniform one), so the density is branch-free; only the inverse CDF tells them apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PeriodProxy {
    /// c: 2N for the Lorentzian, 0 for the uniform proxy.
    c: f64,
    /// atan N.
    atan_n: f64,
    /// atan N/π and 1/(2N): the Lorentzian's inverse CDF in cycles.
    a_pi: f64,
    inv_c: f64,
    /// q(0): N/atan N for the Lorentzian, 1 for the uniform proxy.
    peak: f64,
    /// The uniform proxy (N = 1).
    uniform: bool,
}

impl PeriodProxy {
    /// The proxy for N ≥ 1 slits (atan N given, the value every other part uses): uniform for
    /// N = 1, the Lorentzian otherwise.
    pub(super) fn new(n: u32, atan_n: f64) -> PeriodProxy {
        let nf = n as f64;
        let uniform = n <= 1;
        PeriodProxy {
            c: if uniform { 0.0 } else { 2.0 * nf },
            atan_n,
            a_pi: atan_n * FRAC_1_PI,
            inv_c: 1.0 / (2.0 * nf),
            peak: if uniform { 1.0 } else { nf / atan_n },
            uniform,
        }
    }

    /// r ∈ [−½, ½] from t ∈ [0, 1): t − ½ (uniform) or the Lorentzian's inverse CDF
    /// r = tan((2t − 1)·atan N)/(2N) ([`lorentz_r`], here with the constants precomputed).
    #[inline(always)]
    pub(super) fn r(&self, t: f64) -> f64 {
        if self.uniform {
            t - 0.5
        } else {
            let r = tanpi_flat((2.0 * t - 1.0) * self.a_pi) * self.inv_c;
            r.clamp(-0.5, 0.5)
        }
    }

    /// q(r) for |r| ≤ ½ (the caller's range) as (peak, 1 + (c·r)²), for a caller that folds
    /// the division into its own.
    #[inline(always)]
    pub(super) fn ratio(&self, r: f64) -> (f64, f64) {
        let t = self.c * r;
        (self.peak, 1.0 + t * t)
    }

    /// q(r), 0 for |r| > ½.
    #[inline]
    pub(super) fn q(&self, r: f64) -> f64 {
        if r.abs() > 0.5 {
            return 0.0;
        }
        let (a, b) = self.ratio(r);
        a / b
    }

    /// sup over the period of N·F_N/q: 2·atan N for the Lorentzian, 1 for the uniform proxy.
    #[inline]
    pub(super) fn bound(&self) -> f64 {
        if self.uniform {
            1.0
        } else {
            2.0 * self.atan_n
        }
    }
}

/// The value of a finite-N lobe with a non-ideal groove spread, for one grating: everything that
/// does not depend on the directions or λ, precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lobe {
    /// d, w (nm), N.
    pub d: f64,
    pub w: f64,
    pub n: u32,
    /// ρ²·N·d.
    pub scale: f64,
    pub groove: GrooveSpread,
}

/// The groove's factor at one wavelength in the fused form of [`Lobe::ratio`]: G, and whether
/// G·(a/b)² must also carry the sinc² of a coherence length.
#[derive(Debug, Clone, Copy)]
pub(super) struct GrooveFactor {
    /// L/λ for a coherence length; g(v) otherwise.
    pub big: f64,
    pub coherent: bool,
}

impl Lobe {
    /// The groove's factor at (v, λ): L/λ (coherence length; its sinc² goes into the ratio) or
    /// g(v) (Gaussian, the same at every λ).
    #[inline]
    pub(super) fn groove_factor(&self, v: f64, lambda_nm: f64) -> GrooveFactor {
        match self.groove.kind() {
            GrooveKind::CoherenceLength { length_nm } => GrooveFactor {
                big: length_nm / lambda_nm,
                coherent: true,
            },
            _ => GrooveFactor {
                big: self.groove.value_unchecked(v, lambda_nm),
                coherent: false,
            },
        }
    }

    /// f = ρ²·(N·d/λ)·G·(a/b)² as a numerator and a denominator (one division), without
    /// branches on the phase, from q = u/λ: (a/b)² = S(π·w·q)·F_N(π·d·q) (the crate's fused
    /// kernel); for a coherence length G = L/λ and a/b also carries sinc(π·t), t = (L/λ)·v, so
    /// that G·(a/b)² holds g = (L/λ)·sinc²(π·t); otherwise G = g(v). `eval`, `eval4` and
    /// `sample` all go through here, so they agree to the last bit.
    #[inline(always)]
    pub(super) fn ratio(&self, q: f64, g: GrooveFactor, v: f64, lambda_nm: f64) -> (f64, f64) {
        let (mut a, mut b) = intensity_ratio_flat(self.d * q, self.w * q, self.n);
        let mut big = g.big;
        if g.coherent {
            let t = big * v;
            let (sa, sb) = sinc_ratio_flat(t);
            a *= sa;
            b *= sb;
            // g = 0 where t overflows, as `GrooveSpread::value`.
            if !t.is_finite() {
                big = 0.0;
            }
        }
        (self.scale * big * (a * a), (b * b) * lambda_nm)
    }

    /// The phase x = d·(u/λ) as [`ratio`](Self::ratio) rounds it (the product of d with
    /// q = u/λ), which the density reads too, so that f and pdf see the same r = x − round(x)
    /// wherever rounding moves x by more than a lobe.
    #[inline(always)]
    pub(super) fn phase(&self, u: f64, lambda_nm: f64) -> f64 {
        self.d * (u / lambda_nm)
    }

    /// f at (u, v), finite and ≥ 0 (0 where the phase or the value is not finite).
    #[inline]
    pub(super) fn value(&self, u: f64, v: f64, lambda_nm: f64) -> f64 {
        self.value_q(u / lambda_nm, v, lambda_nm)
    }

    /// [`value`](Self::value) from q = u/λ, for a caller that also needs the phase d·q.
    #[inline(always)]
    pub(super) fn value_q(&self, q: f64, v: f64, lambda_nm: f64) -> f64 {
        let (num, den) = self.ratio(q, self.groove_factor(v, lambda_nm), v, lambda_nm);
        let f = num / den;
        if (self.d * q).is_finite() && f.is_finite() {
            f
        } else {
            0.0
        }
    }
}
