//! A profile z = a(x) as the C method sees it: the Fourier coefficients of its slope a'(x) and
//! those of the phase factors exp(i·b·k0·a(x)) of the plane waves written on the surface.
//!
//! Two representations, both exact where they can be:
//! - a **series** (sinusoid, Fourier profile): a(x) = Σₖ Cₖ cos(2πkx/d) + Sₖ sin(2πkx/d); the
//!   slope's coefficients are closed forms, the phase factors' come from an FFT of samples
//!   (exponentially accurate for a smooth periodic function);
//! - **piecewise linear** (sawtooth, sampled profile): breakpoints tᵢ (fractions of the period)
//!   and heights zᵢ, linear between; the slope is a step function with closed-form
//!   coefficients, and so is each phase factor (the integral of an exponential over each
//!   piece), computed exactly when the pieces are few ([`EXACT_PIECES`]) and by an FFT of the
//!   samples otherwise.

use faer::c64;

use crate::grating::{Grating, Profile};

/// Piecewise-linear profiles with at most this many pieces get exact phase-factor
/// coefficients (cost pieces × harmonics per plane wave); beyond, an FFT of samples.
pub(crate) const EXACT_PIECES: usize = 256;
/// Smallest FFT used for the phase factors (Python's reference uses the same 2¹⁴ points).
const MIN_FFT: usize = 1 << 14;
/// Largest FFT (bounds the work for absurd depths).
const MAX_FFT: usize = 1 << 20;

/// The profile of one period, in nm, x measured as the fraction t = x/d.
#[derive(Debug, Clone)]
pub(crate) enum Surface {
    /// a(t) = Σₖ cos[k−1]·cos(2πkt) + sin[k−1]·sin(2πkt).
    Series { cos: Vec<f64>, sin: Vec<f64> },
    /// Breakpoints 0 = t₀ < t₁ < … < tₙ = 1 and heights z₀ … zₙ (zₙ = z₀), linear between.
    Linear { t: Vec<f64>, z: Vec<f64> },
}

impl Surface {
    /// The surface of a grating's profile; `None` for lamellar and multilevel profiles (not
    /// continuous) — a flat profile is the zero series.
    pub(crate) fn of(g: &Grating) -> Option<Surface> {
        match &g.profile {
            Profile::Flat => Some(Surface::Series {
                cos: Vec::new(),
                sin: Vec::new(),
            }),
            Profile::Sinusoid { depth_nm } => Some(Surface::Series {
                cos: Vec::new(),
                sin: vec![0.5 * depth_nm],
            }),
            Profile::Fourier { cos, sin } => Some(Surface::Series {
                cos: cos.clone(),
                sin: sin.clone(),
            }),
            Profile::Sawtooth { blaze } => {
                let h = g.period_nm * blaze.sin() * blaze.cos();
                Some(Surface::Linear {
                    t: vec![0.0, blaze.cos().powi(2), 1.0],
                    z: vec![h, 0.0, h],
                })
            }
            Profile::Sampled(z) => {
                let n = z.len();
                let mut zz = z.clone();
                zz.push(z[0]);
                Some(Surface::Linear {
                    t: (0..=n).map(|i| i as f64 / n as f64).collect(),
                    z: zz,
                })
            }
            Profile::Lamellar { .. } | Profile::Multilevel(_) => None,
        }
    }

    /// The largest |a'(x)| (dimensionless) and the height span, nm: they size the FFT.
    fn extent(&self, d: f64) -> (f64, f64) {
        match self {
            Surface::Series { cos, sin } => {
                let terms = cos.len().max(sin.len());
                let amp = |k: usize| {
                    let c = cos.get(k).copied().unwrap_or(0.0);
                    let s = sin.get(k).copied().unwrap_or(0.0);
                    c.hypot(s)
                };
                let slope: f64 = (0..terms)
                    .map(|k| core::f64::consts::TAU * (k + 1) as f64 * amp(k) / d)
                    .sum();
                let span: f64 = (0..terms).map(|k| 2.0 * amp(k)).sum();
                (slope, span)
            }
            Surface::Linear { t, z } => {
                let slope = t
                    .windows(2)
                    .zip(z.windows(2))
                    .map(|(t, z)| ((z[1] - z[0]) / ((t[1] - t[0]) * d)).abs())
                    .fold(0.0, f64::max);
                let lo = z.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = z.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                (slope, hi - lo)
            }
        }
    }

    /// Fourier coefficients cₖ, k = −K..K (index k + K), of the slope a'(x) (dimensionless),
    /// d = the period in nm.
    pub(crate) fn slope_coefficients(&self, d: f64, kmax: usize) -> Vec<c64> {
        let mut c = vec![c64::new(0.0, 0.0); 2 * kmax + 1];
        match self {
            Surface::Series { cos, sin } => {
                // a' = (2π/d) Σ k(−Cₖ sin kτ + Sₖ cos kτ): c₊ₖ = (πk/d)(Sₖ + iCₖ).
                let terms = cos.len().max(sin.len()).min(kmax);
                for k in 1..=terms {
                    let ck = cos.get(k - 1).copied().unwrap_or(0.0);
                    let sk = sin.get(k - 1).copied().unwrap_or(0.0);
                    let v = c64::new(sk, ck) * (core::f64::consts::PI * k as f64 / d);
                    c[kmax + k] = v;
                    c[kmax - k] = v.conj();
                }
            }
            Surface::Linear { t, z } => {
                for (tp, zp) in t.windows(2).zip(z.windows(2)) {
                    let (a, b) = (tp[0], tp[1]);
                    if b <= a {
                        continue;
                    }
                    let s = (zp[1] - zp[0]) / ((b - a) * d);
                    c[kmax] += c64::new(s * (b - a), 0.0);
                    for k in 1..=kmax {
                        let w = core::f64::consts::TAU * k as f64;
                        let (sa, ca) = (w * a).sin_cos();
                        let (sb, cb) = (w * b).sin_cos();
                        // ∫ₐᵇ e^{−iwt} dt = ((sin wb − sin wa) + i(cos wb − cos wa))/w.
                        let plus = c64::new((sb - sa) / w, (cb - ca) / w) * s;
                        c[kmax + k] += plus;
                        c[kmax - k] += plus.conj();
                    }
                }
            }
        }
        c
    }

    /// The FFT size for phase factors exp(i·q·a) with |q| ≤ `q_max` (per nm) and coefficients
    /// up to K: at least [`MIN_FFT`], 4(2K + 1), and 8 points per cycle of the fastest phase.
    fn fft_size(&self, d: f64, q_max: f64, kmax: usize) -> usize {
        let (slope, _) = self.extent(d);
        let band = q_max * slope * d / core::f64::consts::TAU; // cycles per period
        let need = (4 * (2 * kmax + 1)).max((8.0 * band).ceil().min(MAX_FFT as f64) as usize);
        need.next_power_of_two().clamp(MIN_FFT, MAX_FFT)
    }

    /// Heights a(tᵢ), tᵢ = i/n, nm.
    fn samples(&self, n: usize) -> Vec<f64> {
        match self {
            Surface::Series { cos, sin } => {
                if cos.len().max(sin.len()) < n / 2 {
                    // Inverse FFT of the spectrum: a = Σₖ Re((Cₖ − iSₖ) e^{ikτ}).
                    let mut x = vec![c64::new(0.0, 0.0); n];
                    for (k, c) in cos.iter().enumerate() {
                        x[k + 1] += c64::new(0.5 * c, 0.0);
                        x[n - k - 1] += c64::new(0.5 * c, 0.0);
                    }
                    for (k, s) in sin.iter().enumerate() {
                        x[k + 1] += c64::new(0.0, -0.5 * s);
                        x[n - k - 1] += c64::new(0.0, 0.5 * s);
                    }
                    fft(&mut x, true);
                    x.iter().map(|v| v.re).collect()
                } else {
                    (0..n)
                        .map(|i| {
                            let tau = core::f64::consts::TAU * i as f64 / n as f64;
                            let c: f64 = cos
                                .iter()
                                .enumerate()
                                .map(|(k, a)| a * ((k + 1) as f64 * tau).cos())
                                .sum();
                            let s: f64 = sin
                                .iter()
                                .enumerate()
                                .map(|(k, b)| b * ((k + 1) as f64 * tau).sin())
                                .sum();
                            c + s
                        })
                        .collect()
                }
            }
            Surface::Linear { t, z } => {
                let mut out = Vec::with_capacity(n);
                let mut p = 0;
                for i in 0..n {
                    let x = i as f64 / n as f64;
                    while p + 2 < t.len() && t[p + 1] <= x {
                        p += 1;
                    }
                    let (a, b) = (t[p], t[p + 1]);
                    let f = if b > a { (x - a) / (b - a) } else { 0.0 };
                    out.push(z[p] + f * (z[p + 1] - z[p]));
                }
                out
            }
        }
    }
}

/// The phase factors' coefficients for several q (per nm): one FFT grid shared by all.
pub(crate) struct Phases<'a> {
    surface: &'a Surface,
    d: f64,
    kmax: usize,
    grid: Option<Vec<f64>>,
}

impl<'a> Phases<'a> {
    /// Ready for coefficients k = −K..K of exp(i·q·a(x)) with |q| ≤ `q_max`.
    pub(crate) fn new(surface: &'a Surface, d: f64, kmax: usize, q_max: f64) -> Phases<'a> {
        let exact = matches!(surface, Surface::Linear { t, .. } if t.len() - 1 <= EXACT_PIECES);
        let grid = if exact {
            None
        } else {
            let n = surface.fft_size(d, q_max, kmax);
            Some(surface.samples(n))
        };
        Phases {
            surface,
            d,
            kmax,
            grid,
        }
    }

    /// Eⱼ = (1/d)∫₀ᵈ exp(i·q·a(x)) e^{−2πijx/d} dx, j = −K..K (index j + K).
    pub(crate) fn coefficients(&self, q: f64) -> Vec<c64> {
        let kmax = self.kmax;
        let mut out = vec![c64::new(0.0, 0.0); 2 * kmax + 1];
        match (&self.grid, self.surface) {
            (None, Surface::Linear { t, z }) => {
                for (tp, zp) in t.windows(2).zip(z.windows(2)) {
                    let (a, b) = (tp[0], tp[1]);
                    if b <= a {
                        continue;
                    }
                    let len = b - a;
                    let mid = 0.5 * (a + b);
                    // On the piece, q·a(t) = q·z_mid + g·(t − mid), g = q·(z₁ − z₀)/len.
                    let g = q * (zp[1] - zp[0]) / len;
                    let phase0 = q * 0.5 * (zp[0] + zp[1]);
                    for (idx, o) in out.iter_mut().enumerate() {
                        let j = idx as f64 - kmax as f64;
                        let w = g - core::f64::consts::TAU * j;
                        // ∫ e^{i(phase0 + w(t − mid)) − 2πij·mid} over the piece.
                        let arg = phase0 - core::f64::consts::TAU * j * mid;
                        *o += c64::from_polar(len * sinc(0.5 * w * len), arg);
                    }
                }
            }
            (Some(a), _) => {
                let n = a.len();
                let mut x: Vec<c64> = a.iter().map(|&h| c64::from_polar(1.0, q * h)).collect();
                fft(&mut x, false);
                let scale = 1.0 / n as f64;
                for (idx, o) in out.iter_mut().enumerate() {
                    let j = idx as i64 - kmax as i64;
                    *o = x[j.rem_euclid(n as i64) as usize] * scale;
                }
            }
            (None, Surface::Series { .. }) => unreachable!("series profiles always sample"),
        }
        let _ = self.d;
        out
    }
}

fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// In-place radix-2 FFT (length a power of two): X_k = Σⱼ xⱼ e^{∓2πijk/n} (− forward, + inverse,
/// unnormalised).
pub(crate) fn fft(x: &mut [c64], inverse: bool) {
    let n = x.len();
    debug_assert!(n.is_power_of_two());
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            x.swap(i, j);
        }
    }
    let sign = if inverse { 1.0 } else { -1.0 };
    let mut len = 2;
    while len <= n {
        let ang = sign * core::f64::consts::TAU / len as f64;
        let half = len / 2;
        let tw: Vec<c64> = (0..half)
            .map(|k| c64::from_polar(1.0, ang * k as f64))
            .collect();
        for start in (0..n).step_by(len) {
            for k in 0..half {
                let u = x[start + k];
                let v = x[start + k + half] * tw[k];
                x[start + k] = u + v;
                x[start + k + half] = u - v;
            }
        }
        len <<= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fft_matches_a_direct_sum() {
        let n = 16;
        let x: Vec<c64> = (0..n)
            .map(|i| c64::new((i as f64 * 0.7).sin(), (i as f64 * 0.3).cos()))
            .collect();
        let mut y = x.clone();
        fft(&mut y, false);
        for (k, yk) in y.iter().enumerate() {
            let s: c64 = x
                .iter()
                .enumerate()
                .map(|(j, xj)| {
                    xj * c64::from_polar(1.0, -core::f64::consts::TAU * (j * k) as f64 / n as f64)
                })
                .sum();
            assert!((s - yk).norm() < 1e-12);
        }
    }

    #[test]
    fn exact_and_sampled_phase_factors_agree_on_a_triangle() {
        let lin = Surface::Linear {
            t: vec![0.0, 0.7, 1.0],
            z: vec![300.0, 0.0, 300.0],
        };
        let exact = Phases::new(&lin, 1000.0, 10, 0.02).coefficients(0.013);
        let grid = Phases {
            surface: &lin,
            d: 1000.0,
            kmax: 10,
            grid: Some(lin.samples(1 << 16)),
        }
        .coefficients(0.013);
        for (a, b) in exact.iter().zip(&grid) {
            // The sampled integral of a kinked function errs by O(1/n²).
            assert!((a - b).norm() < 1e-7, "{a} {b}");
        }
    }
}
