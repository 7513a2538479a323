//! Spectral integration: the colour a grating shows, and what each way of computing it costs.
//!
//! # The reference colour
//!
//! The colour of a spectral reflectance I(λ) under an illuminant E(λ) is
//!
//! ```text
//! XYZ = ∫ E(λ)·I(λ)·cmf(λ) dλ / ∫ E(λ)·ȳ(λ) dλ      over 360-830 nm,
//! ```
//!
//! with the CIE 1931 2° observer and the illuminant interpolated linearly between their 1 nm rows
//! ([`cie`]), so that a perfect white reflector has Y = 1. [`Spectral::xyz`] computes
//! it for the Agu-Hill intensity I(u, λ) = S(β)·F_N(α) of a [`Grating`] seen at phase projection u.
//!
//! # Strategies
//!
//! A [`Strategy`] names one algorithm with one bound, relative to the accuracy unit
//! ([`bounds::accuracy_unit`]: the Y of the brightest diffracted order, floored at that of an
//! ideal first-order peak at 555 nm); each bound is one constant of [`bounds`], which `Auto`,
//! the colour table and these docs read:
//!
//! | [`Strategy`] | cost | bound |
//! |---|---|---|
//! | [`uniform(K)`](Strategy::uniform) | K evaluations | none once peaks (width ≈ λ/(\|m\|·N)) are narrower than the step 470/K nm |
//! | [`gauss_legendre(K)`](Strategy::gauss_legendre) | 8K evaluations | the same, with higher order between |
//! | [`PEAK_SEARCH`](Strategy::PEAK_SEARCH) | O(visible orders), independent of N | [`PEAK_SEARCH_PER_SLIT`](bounds::PEAK_SEARCH_PER_SLIT)/N = 8/N (measured 3.5/N), plus [`PEAK_SEARCH_ORDER0`](bounds::PEAK_SEARCH_ORDER0) = 2·10⁻³ of order 0's own light where its lobe reaches the band |
//! | [`PEAK_SEARCH_REFINED`](Strategy::PEAK_SEARCH_REFINED) | plus 8 lobes × 8 points per order | the same (barely better, except at N ≈ 30) |
//! | [`ASYMPTOTIC`](Strategy::ASYMPTOTIC) | O(visible orders), a few hundred evaluations | [`ASYMPTOTIC_ORDERS`](bounds::ASYMPTOTIC_ORDERS) = 5·10⁻⁴ (measured 1.3·10⁻⁴) for N ≥ [`ASYMPTOTIC_MIN_SLITS`](bounds::ASYMPTOTIC_MIN_SLITS) = 5, plus [`ASYMPTOTIC_ORDER0`](bounds::ASYMPTOTIC_ORDER0) = 2·10⁻⁴ (measured 1.9·10⁻⁵) of order 0's own light where its half period reaches the band; below 5 slits [`ASYMPTOTIC_SMALL_N`](bounds::ASYMPTOTIC_SMALL_N) = 5·10⁻⁴ of the colour itself (measured 6.7·10⁻⁵); up to 7 slits F_N is written as its N cosines, a fixed number of evaluations whatever the period (for 5-7 slits within both bounds: 7.4·10⁻⁸ of the unit, 9.8·10⁻⁵ of the colour) |
//! | [`EXACT`](Strategy::EXACT) | O(1 nm rows + orders·(8 lobes + log N)) | [`EXACT`](bounds::EXACT) = 10⁻⁷ of the colour itself (measured 7.9·10⁻¹⁰), of [`DARK_FLOOR`](bounds::DARK_FLOOR) = 10⁻³ of the unit for darker colours |
//! | [`auto(a)`](Strategy::auto) | the cheapest of the above whose bound meets `a` | a |
//!
//! The paper's own peak colours (its steps 6-8) are not an integral and not a strategy:
//! [`Spectral::paper_peaks`]. [`Spectral::xyz_stratified`] and [`Spectral::xyz_hero`] are
//! Monte-Carlo estimates from the caller's random numbers, for spectral renderers. Every
//! strategy's work is bounded for every period and slit count. With the paper's 1/N²
//! normalisation an infinite grating's colour is 0 except at u = 0 (white): only
//! `paper_peaks` shows it colour.
//!
//! How each algorithm works, its derivation (the peak search's equivalent widths, the Fejér
//! expansion behind `ASYMPTOTIC` and its cosines for a few slits, the pieces of `EXACT` across the table's rows) and the extreme cases
//! (the band inside order 0's lobe, more than 4096 orders, N → ∞) are in
//! `docs/spectral_strategies.md`; the measured error against run time in `docs/accuracy.md`.
//!
//! ```
//! use diffraction::spectrum::{Illuminant, Spectral, Strategy};
//! use diffraction::Grating;
//! let g = Grating::new(1600.0, 800.0, 1000)?;
//! let s = Spectral::new(Illuminant::D65);
//! let exact = s.xyz(&g, 0.34, Strategy::EXACT);
//! let fast = s.xyz(&g, 0.34, Strategy::PEAK_SEARCH);
//! assert!((fast.y - exact.y).abs() < 2e-3 * exact.y); // O(1/N)
//! # Ok::<(), diffraction::Error>(())
//! ```

use glam::DVec3;

use crate::color::Xyz;
use crate::data::cie;
pub use crate::data::cie::Illuminant;
use crate::{Band, Envelope, Grating, GratingResponse};

mod asymptotic;
mod auto;
mod dense;
mod exact;
mod generic;
mod levin;
mod lobes;
mod monte_carlo;
mod order0;
mod paper;
mod peak_search;
mod rules;
mod small_n;
mod smooth_band;
mod strategy;

pub mod bounds;
use rules::{gauss_legendre_rule, midpoint_rule};
pub use strategy::{
    GenericStrategy, GenericStrategyKind, Strategy, StrategyKind, DEFAULT_ACCURACY, MAX_ACCURACY,
    MIN_ACCURACY,
};

/// The band over which colour is integrated: that of the CIE tables.
const BAND: Band = Band::VISIBLE;

/// The most wavelengths any strategy or estimator evaluates per colour: `uniform(K)` accepts
/// at most this many samples and `gauss_legendre(K)` an eighth of it as intervals (a larger K
/// is an error naming it), and [`Spectral::xyz_hero`]'s `count` above it is taken as this
/// many, so every call does bounded work (2¹⁶ wavelengths: over 100 per nanometre of the band,
/// far past where any of these rules stops improving on the 1 nm tables).
///
/// ```
/// use diffraction::spectrum::{Strategy, MAX_WAVELENGTHS};
/// assert!(Strategy::uniform(MAX_WAVELENGTHS).is_ok());
/// assert!(Strategy::uniform(u32::MAX).is_err());
/// assert!(Strategy::gauss_legendre(MAX_WAVELENGTHS / 8 + 1).is_err());
/// ```
pub const MAX_WAVELENGTHS: u32 = 1 << 16;

/// Spectral integration under one illuminant over 360-830 nm (see the [module docs](self)).
///
/// ```
/// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
/// use diffraction::Grating;
/// let s = Spectral::new(Illuminant::D65);
/// let g = Grating::new(1600.0, 800.0, 1000)?;
/// assert_eq!(s.xyz(&g, 0.0, Strategy::EXACT), s.white()); // the mirror direction is white
/// let first = s.xyz(&g, 0.34, Strategy::EXACT); // order 1 at 544 nm
/// assert!(first.y > 0.0 && first.y < 0.01); // it holds about 1/N of the light
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spectral {
    illuminant: Illuminant,
    /// 1 / ∫ E·ȳ dλ.
    norm: f64,
    /// Ē = ∫E·ȳ / ∫ȳ.
    mean_power: f64,
    white: Xyz,
    /// The factor of wavelength every spectral weight carries (1 unless set).
    envelope: Envelope,
}

impl Spectral {
    /// Precomputes the normalisation ∫E·ȳ and the white point for `illuminant`.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// let s = Spectral::new(Illuminant::A);
    /// assert_eq!(s.illuminant(), Illuminant::A);
    /// let w = s.white();
    /// assert_eq!(w.y, 1.0); // normalised
    /// assert!(w.x > 1.0 && w.z < 0.5); // tungsten light is orange: X ≈ 1.10, Z ≈ 0.36
    /// ```
    #[must_use]
    pub fn new(illuminant: Illuminant) -> Spectral {
        let e = |i| cie::illuminant_row(illuminant, i);
        let channel = |c| cie::integrate_product_of_rows(e, |i| cie::cmf_row(i, c));
        let (x, y, z) = (channel(0), channel(1), channel(2));
        let ybar = cie::cmf_areas()[1];
        let white = Xyz::new(x / y, 1.0, z / y);
        Spectral {
            illuminant,
            norm: 1.0 / y,
            mean_power: y / ybar,
            white,
            envelope: Envelope::ONE,
        }
    }

    /// The same integrator with every spectral weight multiplied by `envelope(λ)`: the colour of
    /// a model that is `envelope(λ)·I(u, λ)` of a grating (the energy-normalised grating, for
    /// instance, carries (N·d/λ)·g(v, λ)). Every strategy keeps its bound, since the envelope
    /// changes slowly next to the lobes; the normalisation and [`white`](Self::white) stay those
    /// of the illuminant, and the colour of the mirror direction (I = 1) is the envelope's
    /// integral. [`Spectral::xyz_brdf`] applies a model's envelope by itself.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{Envelope, Grating};
    /// let s = Spectral::new(Illuminant::E);
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let per_nm = s.with_envelope(Envelope::new(1, 0.0)?);
    /// // Order 1 at 544 nm: about 1/544 of the plain colour.
    /// let (a, b) = (s.xyz(&g, 0.34, Strategy::EXACT).y, per_nm.xyz(&g, 0.34, Strategy::EXACT).y);
    /// assert!((b * 544.0 / a - 1.0).abs() < 2e-3);
    /// assert!(per_nm.xyz(&g, 0.0, Strategy::EXACT).y < 1.0 / 360.0); // ∫E·ȳ/λ / ∫E·ȳ
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn with_envelope(self, envelope: Envelope) -> Spectral {
        Spectral { envelope, ..self }
    }

    /// [`flat`](Self::flat) as the integrators' accumulator type.
    pub(super) fn flat_dvec3(&self) -> DVec3 {
        let w = self.flat();
        DVec3::new(w.x, w.y, w.z)
    }

    /// The colour of I ≡ 1 (the mirror direction): the white, times the envelope where there is
    /// one (8-point Gauss-Legendre on every nanometre: the envelope is smooth).
    pub(super) fn flat(&self) -> Xyz {
        if self.envelope.is_one() {
            return self.white;
        }
        let v = gauss_legendre_rule(BAND.width_nm() as u32, &|l| self.weight(l));
        Xyz::new(v.x, v.y, v.z)
    }

    /// The envelope every spectral weight carries ([`Envelope::ONE`] unless set by
    /// [`with_envelope`](Self::with_envelope)).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::Envelope;
    /// assert_eq!(Spectral::new(Illuminant::D65).envelope(), Envelope::ONE);
    /// ```
    #[must_use]
    pub fn envelope(&self) -> Envelope {
        self.envelope
    }

    /// The illuminant.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// assert_eq!(Spectral::new(Illuminant::D65).illuminant(), Illuminant::D65);
    /// ```
    #[must_use]
    pub fn illuminant(&self) -> Illuminant {
        self.illuminant
    }

    /// The XYZ of a perfect white reflector (Y = 1): the illuminant's white point.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// let w = Spectral::new(Illuminant::E).white();
    /// assert!((w.x - 1.0).abs() < 1e-3 && (w.z - 1.0).abs() < 1e-3);
    /// ```
    #[must_use]
    pub fn white(&self) -> Xyz {
        self.white
    }

    /// The spectral envelope's factor at λ times the normalisation: the part of a sample's
    /// weight besides the tables (1 where there is no envelope, without evaluating it).
    #[inline]
    pub(crate) fn envelope_norm(&self, lambda_nm: f64) -> f64 {
        if self.envelope.is_one() {
            self.norm
        } else {
            self.envelope.at(lambda_nm) * self.norm
        }
    }

    /// E(λ)·cmf(λ)·norm at one wavelength, the weight of a spectral sample.
    #[inline]
    pub(crate) fn weight(&self, lambda_nm: f64) -> DVec3 {
        let (power, c) = cie::power_and_cmf(self.illuminant, lambda_nm);
        let mut e = power * self.norm;
        if !self.envelope.is_one() {
            e *= self.envelope.at(lambda_nm);
        }
        DVec3::new(e * c[0], e * c[1], e * c[2])
    }

    /// The reference colour of the Agu-Hill intensity I(u, λ) of `grating`, by `strategy`.
    ///
    /// The result is relative to the illuminant's white (a white reflector has Y = 1); every
    /// strategy returns finite, non-negative values for finite u. I is even in u.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let s = Spectral::new(Illuminant::E);
    /// let exact = s.xyz(&g, 0.34, Strategy::EXACT);
    /// assert_eq!(exact, s.xyz(&g, -0.34, Strategy::EXACT)); // I is even in u
    /// let auto = s.xyz(&g, 0.34, Strategy::auto(1e-2)?);
    /// // As requested: the only visible order is the brightest, so the bound is relative to it.
    /// assert!((auto.y - exact.y).abs() <= 1e-2 * exact.y);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz(&self, grating: &Grating, u: f64, strategy: Strategy) -> Xyz {
        let u = u.abs();
        if !u.is_finite() {
            return Xyz::default();
        }
        if u == 0.0 {
            // I(0, λ) = S(0)·F_N(0) = 1 at every wavelength.
            return self.flat();
        }
        let v = match self.choose(grating, u, strategy).kind() {
            StrategyKind::Uniform { samples } => {
                midpoint_rule(samples, &|l| self.integrand(grating, u, l))
            }
            StrategyKind::GaussLegendre { intervals } => {
                gauss_legendre_rule(intervals, &|l| self.integrand(grating, u, l))
            }
            StrategyKind::PeakSearch => self.peak_search(grating, u, false),
            StrategyKind::PeakSearchRefined => self.peak_search(grating, u, true),
            StrategyKind::Exact => self.exact(grating, u),
            StrategyKind::Asymptotic => self.asymptotic(grating, u),
            // `choose` resolves `auto` into one of the above.
            StrategyKind::Auto { .. } => self.exact(grating, u),
        };
        Xyz::new(v.x, v.y, v.z)
    }

    /// The reference colour of a model's response in its grating form
    /// ([`SpectralResponse::grating_response`](crate::SpectralResponse::grating_response)):
    /// `scale · envelope(λ) · I(u, λ)` of the response's grating, by `strategy`, with the
    /// strategy's bound.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{AguHill, Grating, SpectralResponse};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 300)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wo, wi) = (DVec3::new(0.35, 0.0, (1.0f64 - 0.35 * 0.35).sqrt()), DVec3::Z);
    /// let r = AguHill::new(g).grating_response(wo, wi).unwrap();
    /// // The paper's model is its grating's intensity: the colour of `xyz` at u = 0.35.
    /// assert_eq!(s.xyz_response(&r, Strategy::EXACT), s.xyz(&g, 0.35, Strategy::EXACT));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_response(&self, response: &GratingResponse, strategy: Strategy) -> Xyz {
        let spectral = if response.envelope.is_one() {
            *self
        } else {
            self.with_envelope(response.envelope)
        };
        let scale = if response.scale.is_finite() {
            response.scale.max(0.0)
        } else {
            0.0
        };
        saturate(spectral.xyz(&response.grating, response.u, strategy) * scale)
    }

    /// E·I·cmf·norm at λ.
    #[inline]
    pub(super) fn integrand(&self, grating: &Grating, u: f64, lambda_nm: f64) -> DVec3 {
        let i = grating.intensity_f64(u, lambda_nm);
        let w = self.weight(lambda_nm);
        w * i
    }
}

/// Every component finite and ≥ 0: NaN and negative as 0, +∞ as `f64::MAX` (a product of a
/// caller's huge scale with a colour saturates instead of overflowing).
pub(crate) fn saturate(c: Xyz) -> Xyz {
    let f = |v: f64| if v > 0.0 { v.min(f64::MAX) } else { 0.0 };
    Xyz::new(f(c.x), f(c.y), f(c.z))
}
