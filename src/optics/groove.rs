//! The spread g(v) of a grating's lobes along the grooves.
//!
//! In the radiometric model ([`GratingBsdf`](crate::GratingBsdf)) the light of each order is
//! spread in v = (wi + wo)·y (y along the grooves) by a lobe g(v) of unit integral. Its physical
//! choices ([`GrooveSpread`]):
//!
//! * a **coherence length** L along the grooves: the Fraunhofer pattern of a coherently lit
//!   length L, g(v) = (L/λ)·sinc²(π·L·v/λ), whose width λ/L depends on the wavelength (the
//!   default L = N·d is a square coherently lit patch);
//! * a **Gaussian** of standard deviation σ (groove roughness, the same at every λ):
//!   g(v) = exp(−v²/(2σ²))/(σ·√(2π));
//! * the **ideal** limit δ(v): every order stays on its cone; the lobes are then specular in v.
//!
//! Each choice comes with its value, a sampler with an exact density (a Cauchy proxy of the
//! lobe, inverse CDF v = s·tan(π(ξ − ½))), and the closed-form mass and mean over an interval
//! (for footprint filtering and the albedo): sinc² by the sine integral, the Gaussian by erf.
//!
//! ```
//! use diffraction::GrooveSpread;
//! let g = GrooveSpread::coherence_length(50_000.0)?;
//! // Unit integral: the mass over |v| < 1 is 1 less the sinc² tails beyond t = L·v/λ = 100,
//! // 1/(π²·100) to 5·10⁻⁹ (mpmath).
//! let tail = 1.0 / (std::f64::consts::PI.powi(2) * 100.0);
//! assert!((g.mass(-1.0, 1.0, 500.0) - (1.0 - tail)).abs() < 1e-8);
//! // The peak is L/λ.
//! assert_eq!(g.value(0.0, 500.0), 100.0);
//! # Ok::<(), diffraction::Error>(())
//! ```

use core::f64::consts::PI;

use crate::error::{positive, Error, Requirement};
use crate::num::kernel::single_slit_cycles;
use crate::num::math;
use crate::num::random::unit_random;
use crate::num::special::{erf, erfc, sinc2_integral};

/// Scale of the Cauchy proxy of sinc²(a), in a = π·L·v/λ: with c = 1.2,
/// sinc²(a)·(c² + a²)/c ≤ 1.4504 for all a (the sup is at a = 0 … 1.3; c = 1.165 would give
/// 1.4492).
const SINC2_PROXY_SCALE: f64 = 1.2;
/// sup g/q for the coherence-length lobe and its proxy (measured on a 5·10⁻⁵ grid to a = 400,
/// beyond which the ratio is below 1/c·(1 + c²/a²) < 0.84), rounded up.
pub(crate) const COHERENCE_PROXY_BOUND: f64 = 1.4504;
/// sup g/q for the Gaussian and its Cauchy proxy of the same scale σ: √(2π)·e^{−½} = 1.52035.
pub(crate) const GAUSSIAN_PROXY_BOUND: f64 = 1.5204;
/// The largest accepted Gaussian σ (v spans [−2, 2]).
pub const MAX_GROOVE_SIGMA: f64 = 1.0;
/// The smallest accepted Gaussian σ: a lobe 10⁻¹² wide in v is far below what unit directions
/// in `f64` resolve (10⁻¹⁶ near the mirror direction, much less after a renderer's transforms)
/// and keeps the value 1/(σ·√(2π)) and the sampler's density 1/(π·σ) finite.
pub const MIN_GROOVE_SIGMA: f64 = 1e-12;
/// The shortest accepted coherence length, nm: the lobe's width λ/L in v is then at most 830,
/// far wider than the range [−2, 2] of v, so shorter lengths change nothing.
pub const MIN_COHERENCE_NM: f64 = 1.0;
/// The longest accepted coherence length, nm (10⁶ km): the lobe's width λ/L in v is then at
/// least 3.6·10⁻¹³, still a thousand times what unit directions in `f64` resolve, and L/λ,
/// the lobe's peak, stays finite for every λ above 10⁻²⁹³ nm. Longer defaults (N·d of a huge
/// grating) are taken as this.
pub const MAX_COHERENCE_NM: f64 = 1e15;
/// 1/√(2π).
const INV_SQRT_TAU: f64 = 0.3989422804014327;

/// The lobe g(v) of a grating along its grooves (see the [module docs](self)): validated where
/// it is built, so every method can rely on its parameter.
///
/// ```
/// use diffraction::{GrooveKind, GrooveSpread};
/// let rough = GrooveSpread::gaussian(0.01)?;
/// assert!((rough.value(0.0, 550.0) - 1.0 / (0.01 * (2.0 * std::f64::consts::PI).sqrt())).abs() < 1e-9);
/// assert_eq!(rough.kind(), GrooveKind::Gaussian { sigma: 0.01 });
/// assert_eq!(GrooveSpread::IDEAL.value(0.0, 550.0), 0.0); // a delta has no finite value
/// assert!(GrooveSpread::IDEAL.is_delta());
/// assert_eq!(GrooveSpread::gaussian(-1.5).unwrap_err().parameter(), "sigma");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrooveSpread(GrooveKind);

/// What a [`GrooveSpread`] is, for reading ([`GrooveSpread::kind`]); build one with the
/// constructors of [`GrooveSpread`], which validate it.
///
/// ```
/// use diffraction::{GrooveKind, GrooveSpread};
/// assert_eq!(GrooveSpread::IDEAL.kind(), GrooveKind::Ideal);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
#[non_exhaustive]
pub enum GrooveKind {
    /// A coherence length L along the grooves: g(v) = (L/λ)·sinc²(π·L·v/λ).
    CoherenceLength {
        /// L, nm, in [[`MIN_COHERENCE_NM`], [`MAX_COHERENCE_NM`]].
        length_nm: f64,
    },
    /// Groove roughness: a Gaussian of standard deviation σ in v, the same at every λ.
    Gaussian {
        /// σ, in units of v, in [[`MIN_GROOVE_SIGMA`], [`MAX_GROOVE_SIGMA`]].
        sigma: f64,
    },
    /// The ideal grating: g = δ(v).
    Ideal,
}

impl GrooveSpread {
    /// The ideal grating: g = δ(v), every order on its cone.
    pub const IDEAL: GrooveSpread = GrooveSpread(GrooveKind::Ideal);

    /// A coherence length L = `length_nm` along the grooves, in [[`MIN_COHERENCE_NM`],
    /// [`MAX_COHERENCE_NM`]]; the error names `length_nm`.
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::coherence_length(1000.0)?;
    /// assert!(g.value(0.5, 500.0) < 1e-30); // L·v/λ = 1: the first zero
    /// assert_eq!(GrooveSpread::coherence_length(5e-324).unwrap_err().parameter(), "length_nm");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn coherence_length(length_nm: f64) -> Result<GrooveSpread, Error> {
        let l = positive("length_nm", length_nm)?;
        if !(MIN_COHERENCE_NM..=MAX_COHERENCE_NM).contains(&l) {
            return Err(Error::invalid(
                "length_nm",
                l,
                Requirement::Within {
                    min: MIN_COHERENCE_NM,
                    max: MAX_COHERENCE_NM,
                },
            ));
        }
        Ok(GrooveSpread(GrooveKind::CoherenceLength { length_nm: l }))
    }

    /// The coherence length nearest to `length_nm` inside the accepted range (for defaults
    /// computed from a grating, such as N·d, which may fall outside it); `None` for a value
    /// that is not a positive number.
    pub(crate) fn coherence_length_clamped(length_nm: f64) -> Option<GrooveSpread> {
        (length_nm > 0.0).then(|| {
            GrooveSpread(GrooveKind::CoherenceLength {
                length_nm: length_nm.clamp(MIN_COHERENCE_NM, MAX_COHERENCE_NM),
            })
        })
    }

    /// Groove roughness: a Gaussian of standard deviation `sigma` in v, in
    /// [[`MIN_GROOVE_SIGMA`], [`MAX_GROOVE_SIGMA`]]; the error names `sigma`.
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// assert!(GrooveSpread::gaussian(0.05).is_ok());
    /// assert_eq!(GrooveSpread::gaussian(2.0).unwrap_err().parameter(), "sigma");
    /// assert_eq!(GrooveSpread::gaussian(5e-324).unwrap_err().parameter(), "sigma");
    /// ```
    pub fn gaussian(sigma: f64) -> Result<GrooveSpread, Error> {
        let s = positive("sigma", sigma)?;
        if !(MIN_GROOVE_SIGMA..=MAX_GROOVE_SIGMA).contains(&s) {
            return Err(Error::invalid(
                "sigma",
                s,
                Requirement::Within {
                    min: MIN_GROOVE_SIGMA,
                    max: MAX_GROOVE_SIGMA,
                },
            ));
        }
        Ok(GrooveSpread(GrooveKind::Gaussian { sigma: s }))
    }

    /// The spread described by `kind`, validated as by its constructor.
    ///
    /// ```
    /// use diffraction::{GrooveKind, GrooveSpread};
    /// let g = GrooveSpread::new(GrooveKind::Gaussian { sigma: 0.02 })?;
    /// assert_eq!(g, GrooveSpread::gaussian(0.02)?);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(kind: GrooveKind) -> Result<GrooveSpread, Error> {
        match kind {
            GrooveKind::CoherenceLength { length_nm } => GrooveSpread::coherence_length(length_nm),
            GrooveKind::Gaussian { sigma } => GrooveSpread::gaussian(sigma),
            GrooveKind::Ideal => Ok(GrooveSpread::IDEAL),
        }
    }

    /// What the spread is.
    ///
    /// ```
    /// use diffraction::{GrooveKind, GrooveSpread};
    /// let g = GrooveSpread::coherence_length(2000.0)?;
    /// assert_eq!(g.kind(), GrooveKind::CoherenceLength { length_nm: 2000.0 });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn kind(self) -> GrooveKind {
        self.0
    }

    /// Whether g is the delta δ(v) (then `value` and `pdf` are 0 and the lobes are specular in v).
    ///
    /// ```
    /// # use diffraction::GrooveSpread;
    /// assert!(!GrooveSpread::gaussian(0.1)?.is_delta());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn is_delta(self) -> bool {
        matches!(self.0, GrooveKind::Ideal)
    }

    /// The lobe's width in v at λ (λ/L for the coherence length, σ for the Gaussian, 0 for the
    /// ideal lobe).
    ///
    /// ```
    /// # use diffraction::GrooveSpread;
    /// assert_eq!(GrooveSpread::coherence_length(1000.0)?.width(500.0), 0.5);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn width(self, lambda_nm: f64) -> f64 {
        if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        match self.0 {
            GrooveKind::CoherenceLength { length_nm } => lambda_nm / length_nm,
            GrooveKind::Gaussian { sigma } => sigma,
            GrooveKind::Ideal => 0.0,
        }
    }

    /// g(v) at wavelength λ, 1/(unit of v); 0 for the ideal lobe, for λ ≤ 0 and non-finite
    /// input.
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::coherence_length(1000.0)?;
    /// assert_eq!(g.value(0.0, 500.0), 2.0); // the peak L/λ
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn value(self, v: f64, lambda_nm: f64) -> f64 {
        if !(v.is_finite() && lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        self.value_unchecked(v, lambda_nm)
    }

    /// [`value`](Self::value) without its checks, for a finite v and a positive finite λ (the
    /// caller's checks): the same arithmetic, so the same result.
    #[inline]
    pub(crate) fn value_unchecked(self, v: f64, lambda_nm: f64) -> f64 {
        let g = match self.0 {
            GrooveKind::CoherenceLength { length_nm } => {
                let k = length_nm / lambda_nm;
                let t = k * v;
                if !t.is_finite() {
                    return 0.0;
                }
                k * single_slit_cycles(t)
            }
            GrooveKind::Gaussian { sigma } => {
                let t = v / sigma;
                INV_SQRT_TAU / sigma * math::exp(-0.5 * t * t)
            }
            GrooveKind::Ideal => 0.0,
        };
        if g.is_finite() {
            g
        } else {
            0.0
        }
    }

    /// 1/s for the proxy scale s of [`proxy_scale`](Self::proxy_scale) (a positive finite λ):
    /// the proxy density is (1/s)/(π·(1 + (v/s)²)), as [`pdf`](Self::pdf) up to rounding. 0 for
    /// the ideal groove.
    #[inline]
    pub(crate) fn proxy_inverse_scale(self, lambda_nm: f64) -> f64 {
        match self.0 {
            GrooveKind::CoherenceLength { length_nm } => {
                // The factor L/λ the lobe's value forms too (one division for both).
                (PI / SINC2_PROXY_SCALE) * (length_nm / lambda_nm)
            }
            GrooveKind::Gaussian { sigma } => 1.0 / sigma,
            GrooveKind::Ideal => 0.0,
        }
    }

    /// The scale s of the Cauchy proxy q(v) = s/(π·(s² + v²)): 1.2·λ/(π·L) for the coherence
    /// length, σ for the Gaussian, 0 for the ideal lobe and for λ that is not a positive finite
    /// number. Finite for every input.
    #[must_use]
    pub(crate) fn proxy_scale(self, lambda_nm: f64) -> f64 {
        if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        let s = match self.0 {
            GrooveKind::CoherenceLength { length_nm } => {
                SINC2_PROXY_SCALE * (lambda_nm / (PI * length_nm))
            }
            GrooveKind::Gaussian { sigma } => sigma,
            GrooveKind::Ideal => 0.0,
        };
        s.min(f64::MAX)
    }

    /// Samples v from the lobe's Cauchy proxy q(v) = s/(π·(s² + v²)), whose scale s is
    /// 1.2·λ/(π·L) for the coherence length and σ for the Gaussian: v = s·tan(π·(uc − ½)) (the
    /// tangent taken in cycles, to a few ulp), `uc` by the crate's rule for random numbers ([`unit_random`]). The ideal lobe gives
    /// v = 0. Its density is [`pdf`](Self::pdf).
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::gaussian(0.1)?;
    /// assert_eq!(g.sample(0.5, 550.0), 0.0);
    /// assert!((g.sample(0.75, 550.0) - 0.1).abs() < 1e-15); // the proxy's quartile is s
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[doc(hidden)]
    #[must_use]
    pub fn sample(self, uc: f64, lambda_nm: f64) -> f64 {
        let s = self.proxy_scale(lambda_nm);
        if !(s > 0.0 && s.is_finite()) {
            return 0.0;
        }
        Self::sample_scaled(unit_random(uc), s)
    }

    /// The proxy's scale as s = s₀ + s₁·λ: (0, 1.2/(π·L)) for the coherence length, (σ, 0) for
    /// the Gaussian, (0, 0) for the ideal lobe; for a caller that samples many λ of one groove
    /// ([`sample_scaled`](Self::sample_scaled); equal to [`proxy_scale`](Self::proxy_scale) to
    /// rounding).
    #[inline]
    pub(crate) fn proxy_scale_affine(self) -> (f64, f64) {
        match self.0 {
            GrooveKind::CoherenceLength { length_nm } => {
                (0.0, SINC2_PROXY_SCALE / (PI * length_nm))
            }
            GrooveKind::Gaussian { sigma } => (sigma, 0.0),
            GrooveKind::Ideal => (0.0, 0.0),
        }
    }

    /// v = s·tan(π·(uc − ½)) for uc in [0, 1) and a scale s ≥ 0 (the tangent in cycles, without a
    /// library call); 0 where that is not finite.
    #[inline(always)]
    pub(crate) fn sample_scaled(uc: f64, s: f64) -> f64 {
        let v = s * crate::num::kernel::tanpi_flat(uc - 0.5);
        if v.is_finite() {
            v
        } else {
            0.0
        }
    }

    /// The density of [`sample`](Self::sample) at v: s/(π·(s² + v²)); 0 for the ideal lobe.
    /// Computed without intermediate overflow, so it is positive wherever the density itself
    /// is above the smallest `f64` (a sample far in the proxy's tails keeps its density) and 0
    /// only where it is below it or above `f64::MAX` (a scale s under 2·10⁻³⁰⁹, λ below
    /// about 10⁻³⁰⁹·L).
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::gaussian(0.1)?;
    /// assert!((g.pdf(0.0, 550.0) - 1.0 / (std::f64::consts::PI * 0.1)).abs() < 1e-12);
    /// // Far tails: s/(π·v²) = 0.1/(π·10³⁰⁰), not 0.
    /// assert!((g.pdf(1e150, 550.0) / (0.1 / (std::f64::consts::PI * 1e300)) - 1.0).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[doc(hidden)]
    #[must_use]
    pub fn pdf(self, v: f64, lambda_nm: f64) -> f64 {
        let s = self.proxy_scale(lambda_nm);
        if !(s > 0.0 && s.is_finite() && v.is_finite()) {
            return 0.0;
        }
        let p = if v.abs() > s {
            // (r/π)/|v|/(1 + r²) with r = s/|v| ≤ 1: no square to overflow or underflow.
            let r = s / v.abs();
            (r / PI) / v.abs() / (1.0 + r * r)
        } else {
            let t = v / s;
            1.0 / (PI * s * (1.0 + t * t))
        };
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }

    /// sup g/q over v: the most the sampler's weight g/pdf can be (1.4504 for the coherence
    /// length, measured on a 5·10⁻⁵ grid and rounded up; √(2π)·e^{−½} = 1.52035, rounded up to
    /// 1.5204, for the Gaussian; 1 for the ideal lobe, whose sample is exact).
    ///
    /// ```
    /// # use diffraction::GrooveSpread;
    /// assert!(GrooveSpread::gaussian(0.1)?.proxy_bound() < 1.53);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[doc(hidden)]
    #[must_use]
    pub fn proxy_bound(self) -> f64 {
        match self.0 {
            GrooveKind::CoherenceLength { .. } => COHERENCE_PROXY_BOUND,
            GrooveKind::Gaussian { .. } => GAUSSIAN_PROXY_BOUND,
            GrooveKind::Ideal => 1.0,
        }
    }

    /// ∫ g over [v0, v1] (the order of the ends does not matter; the result is in [0, 1]), in
    /// closed form: (Φ(L·v1/λ) − Φ(L·v0/λ)) with Φ(t) = (Si(2πt) − sin²(πt)/(πt))/π for the
    /// coherence length, ½(erf(v1/(σ√2)) − erf(v0/(σ√2))) for the Gaussian (erfc in the tails),
    /// and 1 or 0 for the ideal lobe (1 when v0 ≤ 0 < v1). 0 for λ ≤ 0 or NaN.
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::gaussian(0.1)?;
    /// assert!((g.mass(-0.1, 0.1, 500.0) - 0.682689492137086).abs() < 1e-14); // one σ
    /// assert_eq!(GrooveSpread::IDEAL.mass(-0.1, 0.1, 500.0), 1.0);
    /// assert_eq!(GrooveSpread::IDEAL.mass(0.1, 0.2, 500.0), 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn mass(self, v0: f64, v1: f64, lambda_nm: f64) -> f64 {
        if v0.is_nan() || v1.is_nan() || !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
            return 0.0;
        }
        let (a, b) = if v0 <= v1 { (v0, v1) } else { (v1, v0) };
        let m = match self.0 {
            GrooveKind::CoherenceLength { length_nm } => {
                let k = length_nm / lambda_nm;
                let phi = |v: f64| {
                    let t = k * v;
                    if t.is_finite() {
                        sinc2_integral(t)
                    } else if t > 0.0 {
                        0.5
                    } else {
                        -0.5
                    }
                };
                phi(b) - phi(a)
            }
            GrooveKind::Gaussian { sigma } => {
                let s = sigma * core::f64::consts::SQRT_2;
                let (ta, tb) = (a / s, b / s);
                if ta > 0.0 {
                    0.5 * (erfc(ta) - erfc(tb))
                } else if tb < 0.0 {
                    0.5 * (erfc(-tb) - erfc(-ta))
                } else {
                    0.5 * (erf(tb) - erf(ta))
                }
            }
            GrooveKind::Ideal => {
                if a <= 0.0 && 0.0 < b {
                    1.0
                } else {
                    0.0
                }
            }
        };
        if m.is_finite() {
            m.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }

    /// The mean of g over [v0, v1], mass/(v1 − v0): what a footprint of that extent sees. For an
    /// empty or degenerate interval (|v1 − v0| below 10⁻⁹ of the lobe's width) the value at the
    /// midpoint; for the ideal lobe a degenerate interval gives 0.
    ///
    /// ```
    /// use diffraction::GrooveSpread;
    /// let g = GrooveSpread::coherence_length(10_000.0)?;
    /// // Over one lobe width either side of the centre: most of the unit mass, spread over 2λ/L.
    /// let mean = g.mean(-0.05, 0.05, 500.0);
    /// assert!((mean * 0.1 - 0.9028).abs() < 1e-4);
    /// assert_eq!(g.mean(0.0, 0.0, 500.0), g.value(0.0, 500.0));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn mean(self, v0: f64, v1: f64, lambda_nm: f64) -> f64 {
        let width = (v1 - v0).abs();
        if width.is_nan() || width <= 1e-9 * self.width(lambda_nm) || !width.is_finite() {
            return self.value(0.5 * (v0 + v1), lambda_nm);
        }
        let m = self.mass(v0, v1, lambda_nm) / width;
        if m.is_finite() {
            m
        } else {
            0.0
        }
    }
}

/// A spread (de)serialises as its [`GrooveKind`], validated on the way in:
/// `{"Gaussian":{"sigma":-1.5}}` is an error naming `sigma`.
#[cfg(feature = "serde")]
impl serde::Serialize for GrooveSpread {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for GrooveSpread {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        GrooveSpread::new(GrooveKind::deserialize(d)?).map_err(serde::de::Error::custom)
    }
}
