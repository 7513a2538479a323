//! A spectral quantity at a path's four wavelengths (pbrt-v4's `SampledSpectrum`): throughput,
//! BSDF values, radiance, with the arithmetic a path tracer needs and the film's estimate of
//! its colour.

use core::ops::{Add, AddAssign, Div, DivAssign, Index, IndexMut, Mul, MulAssign, Sub, SubAssign};

use crate::color::Xyz;
use crate::path::film::SpectralFilm;
use crate::path::wavelengths::SampledWavelengths;

/// Values at the four wavelengths of a [`SampledWavelengths`] (index 0 the hero): pbrt-v4's
/// `SampledSpectrum` with four samples.
///
/// Arithmetic is per wavelength. **Division is safe**: a quotient whose divisor is 0 is 0
/// (pbrt's `SafeDiv`), so the 0/0 of a terminated wavelength or of a zero density stays 0 and
/// no NaN enters a path from finite input. [`to_xyz`](Self::to_xyz) is the film's unbiased
/// estimate of the colour.
///
/// ```
/// use diffraction::SampledSpectrum;
/// let f = SampledSpectrum::new([0.2, 0.4, 0.0, 0.8]);
/// let pdf = SampledSpectrum::new([0.5, 0.5, 0.0, 2.0]);
/// let w = f * 0.5 / pdf; // f·cos/pdf, with 0/0 → 0
/// assert_eq!(w.values(), [0.2, 0.4, 0.0, 0.2]);
/// assert_eq!(w.max_value(), 0.4);
/// assert!((w.average() - 0.2).abs() < 1e-16);
/// let mut beta = SampledSpectrum::ONE;
/// beta *= w;
/// assert_eq!(beta, w);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct SampledSpectrum([f64; 4]);

impl SampledSpectrum {
    /// 0 at every wavelength.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert!(SampledSpectrum::ZERO.is_zero());
    /// ```
    pub const ZERO: SampledSpectrum = SampledSpectrum([0.0; 4]);
    /// 1 at every wavelength (a path's initial throughput; a light that emits the illuminant).
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::ONE.average(), 1.0);
    /// ```
    pub const ONE: SampledSpectrum = SampledSpectrum([1.0; 4]);

    /// The spectrum with these values (index 0 the hero wavelength's).
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::new([1.0, 2.0, 3.0, 4.0])[2], 3.0);
    /// ```
    #[must_use]
    pub const fn new(values: [f64; 4]) -> SampledSpectrum {
        SampledSpectrum(values)
    }

    /// `v` at every wavelength.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::splat(0.5).values(), [0.5; 4]);
    /// ```
    #[must_use]
    pub const fn splat(v: f64) -> SampledSpectrum {
        SampledSpectrum([v; 4])
    }

    /// The spectrum whose value at index j is `f(j)`.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::from_fn(|j| j as f64).values(), [0.0, 1.0, 2.0, 3.0]);
    /// ```
    #[must_use]
    pub fn from_fn(f: impl FnMut(usize) -> f64) -> SampledSpectrum {
        SampledSpectrum(core::array::from_fn(f))
    }

    /// The four values.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::ONE.values(), [1.0; 4]);
    /// ```
    #[must_use]
    pub const fn values(self) -> [f64; 4] {
        self.0
    }

    /// The largest value (pbrt's `MaxComponentValue`), for Russian roulette.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::new([0.1, 0.7, 0.3, 0.0]).max_value(), 0.7);
    /// ```
    #[must_use]
    pub fn max_value(self) -> f64 {
        self.0.iter().fold(self.0[0], |m, &v| m.max(v))
    }

    /// The smallest value.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::new([0.1, 0.7, 0.3, 0.2]).min_value(), 0.1);
    /// ```
    #[must_use]
    pub fn min_value(self) -> f64 {
        self.0.iter().fold(self.0[0], |m, &v| m.min(v))
    }

    /// The per-wavelength maximum of two spectra.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// let a = SampledSpectrum::new([1.0, 0.0, 3.0, -1.0]);
    /// assert_eq!(a.max(SampledSpectrum::ZERO).values(), [1.0, 0.0, 3.0, 0.0]);
    /// ```
    #[must_use]
    pub fn max(self, other: SampledSpectrum) -> SampledSpectrum {
        SampledSpectrum::from_fn(|j| self.0[j].max(other.0[j]))
    }

    /// The per-wavelength minimum of two spectra.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// let a = SampledSpectrum::new([1.0, 0.0, 3.0, -1.0]);
    /// assert_eq!(a.min(SampledSpectrum::ONE).values(), [1.0, 0.0, 1.0, -1.0]);
    /// ```
    #[must_use]
    pub fn min(self, other: SampledSpectrum) -> SampledSpectrum {
        SampledSpectrum::from_fn(|j| self.0[j].min(other.0[j]))
    }

    /// The mean of the four values.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert_eq!(SampledSpectrum::new([1.0, 2.0, 3.0, 6.0]).average(), 3.0);
    /// ```
    #[must_use]
    pub fn average(self) -> f64 {
        0.25 * ((self.0[0] + self.0[1]) + (self.0[2] + self.0[3]))
    }

    /// Whether every value is 0 (a path that carries nothing).
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// assert!(!SampledSpectrum::new([0.0, 0.0, 1e-300, 0.0]).is_zero());
    /// ```
    #[must_use]
    pub fn is_zero(self) -> bool {
        self.0.iter().all(|&v| v == 0.0)
    }

    /// Per-wavelength division with 0 where the divisor is 0 (pbrt's `SafeDiv`); the same as
    /// `/`.
    ///
    /// ```
    /// # use diffraction::SampledSpectrum;
    /// let q = SampledSpectrum::ONE.safe_div(SampledSpectrum::new([2.0, 0.0, 4.0, 0.0]));
    /// assert_eq!(q.values(), [0.5, 0.0, 0.25, 0.0]);
    /// ```
    #[must_use]
    pub fn safe_div(self, divisor: SampledSpectrum) -> SampledSpectrum {
        SampledSpectrum::from_fn(|j| safe_div(self.0[j], divisor.0[j]))
    }

    /// The film's estimate of the colour from one path: the mean over the four wavelengths of
    /// value·w(λ_j)/p(λ_j), with w the film weight E·cmf/∫E·ȳ of `film`
    /// ([`SpectralFilm::weight`]) and p the wavelengths' densities; a wavelength of density 0
    /// (terminated secondaries) contributes 0. Its expectation over the wavelength sampler is
    /// ∫ value(λ)·E(λ)·cmf(λ) dλ/∫E·ȳ, the crate's reference colour (a white reflector, value
    /// 1, under the film's illuminant averages to Y = 1), whatever the sampler, as long as its
    /// density is positive wherever w is. Finite for finite values: a sum that would overflow
    /// saturates at ±`f64::MAX` per channel (before the mean over the four).
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// use diffraction::{SampledSpectrum, SampledWavelengths, SpectralFilm};
    /// let film = SpectralFilm::new(Illuminant::E);
    /// // A white reflector, stratified wavelengths: the mean over u of Y is 1.
    /// let n = 2000;
    /// let y: f64 = (0..n)
    ///     .map(|i| {
    ///         let l = SampledWavelengths::sample_visible((i as f64 + 0.5) / n as f64);
    ///         SampledSpectrum::ONE.to_xyz(&l, &film).y
    ///     })
    ///     .sum::<f64>()
    ///     / n as f64;
    /// assert!((y - 1.0).abs() < 1e-3);
    /// ```
    #[must_use]
    pub fn to_xyz(&self, lambdas: &SampledWavelengths, film: &SpectralFilm) -> Xyz {
        let (l, p) = (lambdas.lambda(), lambdas.pdf());
        let mut acc = [0.0; 3];
        for j in 0..4 {
            if p[j] > 0.0 && self.0[j] != 0.0 {
                // Each step saturates at ±f64::MAX: a finite value over a density down to
                // `SampledWavelengths::MIN_PDF` may overflow, the estimate does not.
                let k = (self.0[j] / p[j]).clamp(-f64::MAX, f64::MAX);
                let w = film.weight(l[j]);
                for c in 0..3 {
                    acc[c] =
                        (acc[c] + (k * w[c]).clamp(-f64::MAX, f64::MAX)).clamp(-f64::MAX, f64::MAX);
                }
            }
        }
        Xyz::new(0.25 * acc[0], 0.25 * acc[1], 0.25 * acc[2])
    }
}

/// a/b, 0 when b is 0.
#[inline]
fn safe_div(a: f64, b: f64) -> f64 {
    if b == 0.0 {
        0.0
    } else {
        a / b
    }
}

impl From<[f64; 4]> for SampledSpectrum {
    fn from(v: [f64; 4]) -> SampledSpectrum {
        SampledSpectrum(v)
    }
}

impl From<SampledSpectrum> for [f64; 4] {
    fn from(s: SampledSpectrum) -> [f64; 4] {
        s.0
    }
}

impl Index<usize> for SampledSpectrum {
    type Output = f64;
    fn index(&self, i: usize) -> &f64 {
        &self.0[i]
    }
}

impl IndexMut<usize> for SampledSpectrum {
    fn index_mut(&mut self, i: usize) -> &mut f64 {
        &mut self.0[i]
    }
}

/// The arithmetic operators, per wavelength, against a spectrum and against a scalar (`/` is
/// safe division).
macro_rules! ops {
    ($tr:ident, $f:ident, $atr:ident, $af:ident, $op:expr) => {
        impl $tr for SampledSpectrum {
            type Output = SampledSpectrum;
            #[inline]
            fn $f(self, rhs: SampledSpectrum) -> SampledSpectrum {
                SampledSpectrum::from_fn(|j| $op(self.0[j], rhs.0[j]))
            }
        }
        impl $tr<f64> for SampledSpectrum {
            type Output = SampledSpectrum;
            #[inline]
            fn $f(self, rhs: f64) -> SampledSpectrum {
                SampledSpectrum::from_fn(|j| $op(self.0[j], rhs))
            }
        }
        impl $atr for SampledSpectrum {
            #[inline]
            fn $af(&mut self, rhs: SampledSpectrum) {
                *self = $tr::$f(*self, rhs);
            }
        }
        impl $atr<f64> for SampledSpectrum {
            #[inline]
            fn $af(&mut self, rhs: f64) {
                *self = $tr::$f(*self, rhs);
            }
        }
    };
}

ops!(Add, add, AddAssign, add_assign, |a: f64, b: f64| a + b);
ops!(Sub, sub, SubAssign, sub_assign, |a: f64, b: f64| a - b);
ops!(Mul, mul, MulAssign, mul_assign, |a: f64, b: f64| a * b);
ops!(Div, div, DivAssign, div_assign, safe_div);

impl Mul<SampledSpectrum> for f64 {
    type Output = SampledSpectrum;
    #[inline]
    fn mul(self, rhs: SampledSpectrum) -> SampledSpectrum {
        rhs * self
    }
}
