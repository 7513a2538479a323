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
//! | [`Strategy`] | cost | error |
//! |---|---|---|
//! | `Uniform { samples: K }` | K evaluations | fails once peaks (width ≈ λ/(mN)) are narrower than the step |
//! | `GaussLegendre { intervals: K }` | 8K evaluations | the same, with higher order between |
//! | `PeakSearch { refine: false }` | O(visible orders), independent of N (a few µs where order 0's light reaches the band) | 3.5/N of the brightest order; 2e-3 of order 0's light |
//! | `PeakSearch { refine: true }` | plus 8 lobes × 8 points per order | the same far tails dominate: barely better, except at N ≈ 30 |
//! | `PaperPeaks` | O(visible orders) | not the integral: the paper's steps 6-8 |
//! | `Asymptotic` | O(visible orders): 4 lobes × 6 points per bright order, one point per faint order, the envelope in 3-point pieces of 16-64 nm (order 0's: a product rule, 4 points per 30 nm); where N·d·\|u\| ≤ about 47,000 nm, and over the band's long end where lobes are wider than 5-8 nm, a product rule of 4-32 points per 30 nm against the tables (`smooth_band`) | 5e-4 of the brightest order (worst measured 1.3e-4, N ≥ 5); 2e-4 of order 0's light (measured 1.9e-5) |
//! | `Exact` | O(1 nm rows + orders·(16 lobes + log N)): lobes near every integer x, Filon-Legendre pieces between the rows elsewhere; where N·d·\|u\| ≤ about 29,000 nm (at most about 45 lobes over the band), a product rule of 64-512 points against the tables (`smooth_band`) | 10⁻⁶ of the colour (measured 8.9·10⁻⁹) |
//! | `Auto { accuracy }` | the cheapest of the above that meets `accuracy` | as requested |
//!
//! Δx = d·|u|·(1/360 − 1/830) is the range of the phase in cycles over the band.
//!
//! **Peak search.** For large N the intensity sits in narrow peaks at the grating-equation
//! wavelengths λ_m = d·|u|/|m|. Since F_N has mass 1/N per period in x = d·u/λ and
//! |dλ/dx| = λ_m/|m| at the peak, order m contributes about
//! S(β_m)·E(λ_m)·cmf(λ_m)·λ_m/(|m|·N): the peak value times its
//! [`equivalent width`](crate::Peak::equivalent_width_nm). With `refine`, the main lobe and the
//! first three side lobes on each side of every peak are integrated by Gauss-Legendre quadrature
//! lobe by lobe, and only the remaining mass is assigned at λ_m. This helps little: the error of
//! the analytic weight comes mostly from the far tails of each order (its mass spread over the
//! whole period), not from the main lobe. Peaks within four lobes of a band end are always
//! treated this way. Order 0 is broad in wavelength near the mirror direction: where its half
//! period reaches into the band it is integrated by coarse quadrature (its lobes while they are
//! wider than 4 nm, then the mean ½ of sin²(Nα)), to 2e-3 of its own colour.
//!
//! **Asymptotic.** The peak search with its leading correction. Write h(x) for the integrand in
//! the phase x = d·|u|/λ without F_N, h = E·S·cmf·|dλ/dx|·norm, so that
//! XYZ = ∫ F_N(πx)·h(x) dx over [d·|u|/830, d·|u|/360], h jumping to 0 at both ends. The Fejér
//! kernel is a trigonometric polynomial, N·F_N(πx) = Σ_{|k|<N} (1 − |k|/N)·e^{2πikx}, so
//!
//! ```text
//! ∫ F_N·h = (1/N)·Σ_{|k|<N} (1 − |k|/N)·ĥ(k),      ĥ(k) = ∫ h(x)·e^{2πikx} dx,
//!         = (1/N)·Σ_k ĥ(k) − (1/N²)·Σ_k |k|·ĥ(k) + (1/N)·Σ_{|k|≥N} (|k|/N − 1)·ĥ(k).
//! ```
//!
//! By Poisson summation Σ_k ĥ(k) = Σ_m h(m), the peak search; and Σ_k |k|·e^{2πikx} =
//! −1/(2 sin²πx) as distributions (Hadamard's finite part at the integers), so the second term
//! is (1/N²)·f.p.∫ h/(2 sin²πx) dx. The last term only holds the Fourier content of h above N
//! cycles per unit x: for a smooth h it vanishes faster than any power of 1/N, which is why the
//! corrected sum is so much better than the peak search (its error 3.5/N is the second term).
//! The same expansion in x-space: sin²(πNx) = ½·(1 − cos 2πNx), so away from the integers
//! F_N·h = G − cos(2πNx)·G with G = h/(2N² sin²πx), and two integrations by parts of the
//! oscillating part between zeros a, b of sin(πNx) (where cos 2πNx = 1) give
//!
//! ```text
//! ∫_a^b F_N·h = ∫_a^b G − [G']_a^b/(4π²N²) + Σ_j ΔG'_j·cos(2πN·x_j)/(4π²N²) + [G''']_a^b/(16π⁴N⁴) − …,
//! ```
//!
//! ΔG'_j the jump of G' at a kink x_j of h inside (a, b). Near an integer m, G ≈ h(m)/(2π²N²(x − m)²)
//! and the terms grow like (2k+1)!/(2πNε)^{2k} at a distance ε: the expansion holds from about
//! two lobes on. h is not smooth everywhere, and the strategy treats the exceptions exactly:
//!
//! - **Within two lobes of every integer** (the main lobe and first side lobe of each order,
//!   order 0 included) and **at each band end** (the partial lobe where h jumps to 0), lobe by
//!   lobe with 6-point Gauss-Legendre on whole lobes (the error of 6 points on a lobe of sin² is
//!   7e-7; 4 points on pieces up to half a lobe, 2 below 0.15 lobe; a window of an order m ≥ 1
//!   that spans at most 4 nm and no node of the illuminant takes h's interpolant at 5
//!   Gauss-Legendre points against F_N, integrated once per call), split where λ crosses a node of the
//!   illuminant (D65 is a 5 nm table interpolated linearly: relative slope jumps up to 8 %/nm;
//!   A is Planck's law at every row) and into pieces of at most 16 nm. The 1 nm rows of the observer are not split at:
//!   its linear interpolation differs from a smooth curve by a second difference/8 (below
//!   5e-4 of each function's maximum), which a peak narrower than a row samples and a wider one
//!   averages. (The finite-part formula itself would not survive the kinks: a kink of slope jump
//!   Δ within a lobe of m moves the finite part by Δ·ln(…)/(2π²), an error of order
//!   (Δ/h)·λ/(m·N) relative to the order, 10⁻² and more for D65 at N ≤ 1000.)
//! - **Lobes wider than 8 nm** (or than the illuminant's node spacing) in wavelength, q/(N·x²),
//!   which occur for small N and in order 0's half period near the mirror direction: the
//!   expansion needs h smooth on the scale of a lobe. Where N·q is at most about 47,000 nm (about
//!   74 lobes over the band) the whole band, and otherwise the fixed 30 nm pieces from the one
//!   where a lobe is that wide on to 830 nm, take the product rule of `smooth_band`: the whole
//!   integrand S·F_N·env, a trigonometric polynomial in x times a power of it, interpolated at
//!   4-32 points per piece by its local frequency 2π·N·q/λ² and integrated against the tables'
//!   weight exactly (within 4.3·10⁻⁶ of the lobe walk at its limits); the rest of such lobes
//!   are integrated lobe by lobe.
//! - **Between the windows**, ∫G in 3-point pieces (split at the illuminant's nodes in order 0's
//!   half period only, where G is the whole colour), at most 16 nm in order 0's half period and
//!   16·(N/5)^(1/6) nm, at most 64, next to the orders m ≠ 0 (there G's share of the colour
//!   relative to the order's peak h(m)/N falls as 1/N while the rule's error grows as span⁶), with the nearest integer's tangent line p of h subtracted and ∫p/(2 sin²πx) added
//!   analytically (−cot(πr)/(2π) and −r·cot(πr)/(2π) + ln|sin πr|/(2π²), r = x − m); −[G']/(4π²N²)
//!   at each window edge (h' by a one-sided difference over a quarter lobe). The first neglected
//!   end term is 7.8e-4/T⁵ of the tail beyond T = 2 lobes; the kinks' ΔG'_j terms are
//!   neglected (below 10⁻⁵ of the brightest order on the test grids). In order 0's half period
//!   the 30 nm pieces of the band it covers whole take a product rule instead: there
//!   ∫G dx = ∫ W(λ)·K(λ) dλ/N² with W = E·cmf the tables' weight (quadratic between the 1 nm
//!   rows, kinks included) and K = S(ρ·q/λ)/(2 sin²(π·q/λ)) smooth on the band (its poles
//!   λ = q/k are at least 415 nm away), so K's cubic interpolant at 4 Gauss-Legendre nodes is
//!   integrated against W exactly with weights computed from the tables at compile time: 4
//!   evaluations of K per 30 nm instead of 3 of h per 5 nm between D65's nodes.
//! - **Faint orders** (peak value below 1e-7·5.19/8·N, i.e. the peak search's error 8/N of them
//!   below 10⁻⁷ of the brightest order's floor) whose whole period lies between the band ends
//!   get the plain peak-search weight h(m)/N for their period; this keeps coarse gratings (100
//!   µm: hundreds of orders) at a few hundred evaluations.
//!
//! Below 5 slits the strategy is `Exact`. Measured against `Exact` (`tests/asymptotic.rs`: N = 5
//! … 10⁶, d = 400 nm … 100 µm, w = d/2 and d/10, 128 directions, E and D65) and the python
//! reference: at most 1.3e-4 of the brightest order's XYZ where only orders m ≠ 0 reach the band,
//! and 1.9e-5 of max(colour, brightest order) where order 0's half period does; `Spectral::choose`
//! relies on 5e-4 and 2e-4.
//!
//! **The paper's peak colours** (its rendering steps 6-8) evaluate eq. 13 at the peak wavelengths
//! only, each with its peak intensity S(β_m) whatever N is, and convert each to colour:
//! XYZ = Σ_m S(β_m)·(E(λ_m)/Ē)·cmf(λ_m), with Ē = ∫E·ȳ/∫ȳ the mean power of the illuminant, so a
//! unit peak at 555 nm under E has Y ≈ 1; inside the order-0 lobe the colour is the illuminant's
//! white (Y = 1). It reproduces the paper's pictures but is not the integral: it is N·|m|/λ_m·(∫Eȳ/Ē)
//! times brighter per order than the peak-search estimate, so the relative brightness of orders
//! differs (higher orders are relatively brighter in the paper's mode).
//!
//! **Exact.** In the phase x the integrand is sin²(πNx)·R(x) with R smooth between the 1 nm rows
//! of the tables. Within 8 lobes of every integer x (R's double pole) it is integrated lobe by
//! lobe, each piece of a lobe by the Gauss-Legendre rule its width allows (8 points down to 3);
//! elsewhere, between the rows, by Filon-Legendre quadrature: R interpolated at 8 (or 4)
//! Gauss-Legendre nodes and its product with cos(2πNx) integrated exactly, so a piece costs the
//! same however many lobes it holds. Measured within 8.9·10⁻⁹ of the python oracle, relative to
//! the colour (see `exact.rs`).
//!
//! **Monte-Carlo.** [`Spectral::xyz_stratified`] and [`Spectral::xyz_hero`] take the caller's
//! random numbers, for spectral renderers that average over many samples per pixel.
//!
//! **Extremes of d·|u|.** Where the whole band lies inside order 0's central lobe
//! (N·d·|u|/360 nm < 10⁻⁸), `Exact` and the peak searches return the white (I = 1 to
//! rounding). Where the band holds more than 4096 orders (d·|u| > 2.6 mm), `Exact`,
//! `PeakSearch` (both modes) and `PaperPeaks` sum the orders in blocks of consecutive orders
//! in closed form (Dirichlet sums of sin²(π·m·w/d), about 2·10⁴ weights) instead of one at a
//! time, so their work is bounded for every period; against the order-by-order walk the
//! difference is below 10⁻⁷ relative (`Exact` keeps its lobe walk for the partial periods at
//! the band ends).
//!
//! **N → ∞.** With the paper's 1/N² normalisation the area of every order vanishes as 1/N, so the
//! integral of an infinite grating is 0 except at u = 0 (white); only `PaperPeaks` shows colour.
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

use crate::cie;
pub use crate::cie::Illuminant;
use crate::color::Xyz;
use crate::{Band, Envelope, Grating, GratingResponse};

mod asymptotic;
mod auto;
mod dense;
mod exact;
mod generic;
mod lobes;
mod monte_carlo;
mod order0;
mod paper;
mod peak_search;
mod rules;
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
