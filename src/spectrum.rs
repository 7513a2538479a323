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
//! | `Exact` | lobe by lobe when N·Δx ≤ 4096 lobes, else O(orders·128 lobes + log N per period) | below 1e-7 relative |
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
//! **The paper's peak colours** (its rendering steps 6-8) evaluate eq. 13 at the peak wavelengths
//! only, each with its peak intensity S(β_m) whatever N is, and convert each to colour:
//! XYZ = Σ_m S(β_m)·(E(λ_m)/Ē)·cmf(λ_m), with Ē = ∫E·ȳ/∫ȳ the mean power of the illuminant, so a
//! unit peak at 555 nm under E has Y ≈ 1; inside the order-0 lobe the colour is the illuminant's
//! white (Y = 1). It reproduces the paper's pictures but is not the integral: it is N·|m|/λ_m·(∫Eȳ/Ē)
//! times brighter per order than the peak-search estimate, so the relative brightness of orders
//! differs (higher orders are relatively brighter in the paper's mode).
//!
//! **Exact.** Between consecutive zeros of sin(Nα) (x = k/N) and the 1 nm rows of the tables the
//! integrand is smooth; each such piece gets an 8-point Gauss-Legendre rule. When there are more
//! than 4096 lobes in the band, only the 64 lobes on each side of every integer x and of each band
//! end are integrated that way; in between, sin²(Nα) is replaced by its mean ½ (an error below
//! 3·10⁻³/64³ ≈ 10⁻⁸ relative per period, by two integrations by parts) and the smooth envelope
//! is integrated on a geometrically graded grid.
//!
//! **Monte-Carlo.** [`Spectral::xyz_stratified`] and [`Spectral::xyz_hero`] take the caller's
//! random numbers, for spectral renderers that average over many samples per pixel.
//!
//! **N → ∞.** With the paper's 1/N² normalisation the area of every order vanishes as 1/N, so the
//! integral of an infinite grating is 0 except at u = 0 (white); only `PaperPeaks` shows colour.
//!
//! ```
//! use diffraction::spectrum::{Illuminant, Spectral, Strategy};
//! use diffraction::Grating;
//! let g = Grating::new(1600.0, 800.0, 1000)?;
//! let s = Spectral::new(Illuminant::D65);
//! let exact = s.xyz(&g, 0.34, Strategy::Exact);
//! let fast = s.xyz(&g, 0.34, Strategy::PeakSearch { refine: false });
//! assert!((fast.y - exact.y).abs() < 2e-3 * exact.y); // O(1/N)
//! # Ok::<(), diffraction::Error>(())
//! ```

use core::fmt;
use core::str::FromStr;

use glam::DVec3;

use crate::brdf::DiffractionBrdf;
use crate::cie;
pub use crate::cie::Illuminant;
use crate::color::Xyz;
use crate::grating::{Band, Grating, Slits};
use crate::kernel::{single_slit_cycles, sinpi};
use crate::math::{ceil, floor, rint, sqrt};

const BAND: Band = Band::VISIBLE;
/// Gauss-Legendre 8-point nodes and weights on [−1, 1] (numpy.polynomial.legendre.leggauss(8)).
const GL_X: [f64; 8] = [
    -0.9602898564975362,
    -0.7966664774136267,
    -0.525532409916329,
    -0.18343464249564978,
    0.18343464249564978,
    0.525532409916329,
    0.7966664774136267,
    0.9602898564975362,
];
const GL_W: [f64; 8] = [
    0.10122853629037706,
    0.22238103445337443,
    0.3137066458778869,
    0.36268378337836166,
    0.36268378337836166,
    0.3137066458778869,
    0.22238103445337443,
    0.10122853629037706,
];
/// Lobes integrated exactly on each side of a peak by `PeakSearch { refine: true }`.
const REFINE_LOBES: f64 = 4.0;
/// Lobes of order 0 the peak searches integrate lobe by lobe before averaging sin²(Nα).
const ORDER0_LOBES: f64 = 4.0;
/// The peak searches average sin²(Nα) over order 0's lobes only where these are narrower than
/// this, in wavelength.
const AVERAGE_BELOW_NM: f64 = 4.0;
/// Largest wavelength span of one 4-point Gauss-Legendre piece in the peak searches' treatment
/// of order 0.
const COARSE_SPAN_NM: f64 = 16.0;
/// Lobes integrated exactly around every integer x and band end by `Exact` in its hybrid mode.
const NEAR_LOBES: f64 = 64.0;
/// Above this many lobes in the band, `Exact` switches to its hybrid mode.
const MAX_LOBES: f64 = 4096.0;

/// How [`Spectral::xyz`] evaluates the spectral integral (see the [module docs](self)).
///
/// ```
/// use diffraction::spectrum::{Strategy, DEFAULT_ACCURACY};
/// assert_eq!(Strategy::default(), Strategy::Auto { accuracy: DEFAULT_ACCURACY });
/// let s = Strategy::GaussLegendre { intervals: 64 };
/// assert_eq!(s.to_string(), "gauss:64");
/// assert_eq!("gauss:64".parse(), Ok(s));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Strategy {
    /// The midpoint rule with `samples` wavelengths (0 is taken as 1).
    Uniform {
        /// Number of wavelengths.
        samples: u32,
    },
    /// 8-point Gauss-Legendre on each of `intervals` equal sub-intervals (0 is taken as 1).
    GaussLegendre {
        /// Number of sub-intervals of the band.
        intervals: u32,
    },
    /// The analytic weight of every visible order; `refine` integrates the lobes near each peak.
    PeakSearch {
        /// Integrate the main and first side lobes of each peak by quadrature.
        refine: bool,
    },
    /// The paper's own rendering (steps 6-8): peak wavelengths only, each weighted by S(β_m).
    PaperPeaks,
    /// Lobe-exact quadrature (see the module docs), the crate's reference.
    Exact,
    /// The cheapest strategy whose error bound is within `accuracy` (relative, see
    /// [`Spectral::choose`]).
    Auto {
        /// Requested relative accuracy of XYZ.
        accuracy: f64,
    },
}

/// The default accuracy of [`Strategy::Auto`], relative: 10⁻³.
///
/// ```
/// use diffraction::spectrum::{Strategy, DEFAULT_ACCURACY};
/// assert_eq!(DEFAULT_ACCURACY, 1e-3);
/// assert_eq!("auto".parse(), Ok(Strategy::Auto { accuracy: DEFAULT_ACCURACY }));
/// ```
pub const DEFAULT_ACCURACY: f64 = 1e-3;

impl Default for Strategy {
    fn default() -> Self {
        Strategy::Auto {
            accuracy: DEFAULT_ACCURACY,
        }
    }
}

impl fmt::Display for Strategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Strategy::Uniform { samples } => write!(f, "uniform:{samples}"),
            Strategy::GaussLegendre { intervals } => write!(f, "gauss:{intervals}"),
            Strategy::PeakSearch { refine: false } => f.write_str("peaks"),
            Strategy::PeakSearch { refine: true } => f.write_str("peaks-refined"),
            Strategy::PaperPeaks => f.write_str("paper"),
            Strategy::Exact => f.write_str("exact"),
            Strategy::Auto { accuracy } => write!(f, "auto:{accuracy:e}"),
        }
    }
}

/// The error of parsing a [`Strategy`] name.
///
/// ```
/// use diffraction::spectrum::{ParseStrategyError, Strategy};
/// assert_eq!("simpson".parse::<Strategy>(), Err(ParseStrategyError));
/// assert_eq!("gauss:0".parse::<Strategy>(), Err(ParseStrategyError)); // K must be positive
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseStrategyError;

impl fmt::Display for ParseStrategyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(
            "unknown strategy: expected uniform:K, gauss:K, peaks, peaks-refined, paper, exact \
             or auto:ACCURACY (K a positive integer, ACCURACY a positive number)",
        )
    }
}

impl core::error::Error for ParseStrategyError {}

impl FromStr for Strategy {
    type Err = ParseStrategyError;

    /// Parses `uniform:K`, `gauss:K`, `peaks`, `peaks-refined`, `paper`, `exact`, `auto` or
    /// `auto:ACCURACY`.
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// assert_eq!("uniform:471".parse(), Ok(Strategy::Uniform { samples: 471 }));
    /// assert_eq!("auto:1e-4".parse(), Ok(Strategy::Auto { accuracy: 1e-4 }));
    /// assert!("uniform:0".parse::<Strategy>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let count = |v: &str| match v.parse::<u32>() {
            Ok(k) if k > 0 => Ok(k),
            _ => Err(ParseStrategyError),
        };
        match s.split_once(':') {
            None => match s {
                "peaks" => Ok(Strategy::PeakSearch { refine: false }),
                "peaks-refined" => Ok(Strategy::PeakSearch { refine: true }),
                "paper" => Ok(Strategy::PaperPeaks),
                "exact" => Ok(Strategy::Exact),
                "auto" => Ok(Strategy::default()),
                _ => Err(ParseStrategyError),
            },
            Some(("uniform", k)) => Ok(Strategy::Uniform { samples: count(k)? }),
            Some(("gauss", k)) => Ok(Strategy::GaussLegendre {
                intervals: count(k)?,
            }),
            Some(("auto", a)) => match a.parse::<f64>() {
                Ok(a) if a.is_finite() && a > 0.0 => Ok(Strategy::Auto { accuracy: a }),
                _ => Err(ParseStrategyError),
            },
            Some(_) => Err(ParseStrategyError),
        }
    }
}

/// Spectral integration under one illuminant over 360-830 nm (see the [module docs](self)).
///
/// ```
/// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
/// use diffraction::Grating;
/// let s = Spectral::new(Illuminant::D65);
/// let g = Grating::new(1600.0, 800.0, 1000)?;
/// assert_eq!(s.xyz(&g, 0.0, Strategy::Exact), s.white()); // the mirror direction is white
/// let first = s.xyz(&g, 0.34, Strategy::Exact); // order 1 at 544 nm
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
        let ybar = cie::integrate_product_of_rows(|_| 1.0, |i| cie::cmf_row(i, 1));
        Spectral {
            illuminant,
            norm: 1.0 / y,
            mean_power: y / ybar,
            white: Xyz::new(x / y, 1.0, z / y),
        }
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

    /// E(λ)·cmf(λ)·norm at one wavelength, the weight of a spectral sample.
    #[inline]
    fn weight(&self, lambda_nm: f64) -> [f64; 3] {
        let e = self.illuminant.power(lambda_nm) * self.norm;
        let c = cie::cmf(lambda_nm);
        [e * c[0], e * c[1], e * c[2]]
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
    /// let exact = s.xyz(&g, 0.34, Strategy::Exact);
    /// assert_eq!(exact, s.xyz(&g, -0.34, Strategy::Exact)); // I is even in u
    /// let auto = s.xyz(&g, 0.34, Strategy::Auto { accuracy: 1e-2 });
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
            return self.white;
        }
        let [x, y, z] = match strategy {
            Strategy::Uniform { samples } => {
                midpoint_rule(samples, &|l| self.integrand(grating, u, l))
            }
            Strategy::GaussLegendre { intervals } => {
                gauss_legendre_rule(intervals, &|l| self.integrand(grating, u, l))
            }
            Strategy::PeakSearch { refine } => self.peak_search(grating, u, refine),
            Strategy::PaperPeaks => self.paper_peaks(grating, u),
            Strategy::Exact => self.exact(grating, u),
            Strategy::Auto { accuracy } => {
                return self.xyz(grating, u, self.choose(grating, u, accuracy))
            }
        };
        Xyz::new(x, y, z)
    }

    /// The strategy [`Strategy::Auto`] picks for `accuracy`: the cheapest whose error bound,
    /// relative to the XYZ of the brightest order of this grating, is within it.
    ///
    /// Bounds (measured over the test grid of `tests/spectral_reference.rs`, where the worst
    /// is 3.5/N, and kept with a margin): peak search 8/N, plus 2e-3 of the order-0 light where
    /// order 0's half period reaches into the band (d·|u|/830 nm < ½); `Exact` 1e-7. Where the
    /// band holds at most 64 lobes, `Exact` costs no more than the peak search and is chosen.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let s = Spectral::new(Illuminant::D65);
    /// let few = Grating::new(1600.0, 800.0, 3)?; // 3 lobes in the band: exact is cheap
    /// assert_eq!(s.choose(&few, 0.4, 1e-3), Strategy::Exact);
    /// let many = Grating::new(1600.0, 800.0, 100_000)?; // 8/N = 8e-5 meets 1e-3
    /// assert_eq!(s.choose(&many, 0.4, 1e-3), Strategy::PeakSearch { refine: false });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn choose(&self, grating: &Grating, u: f64, accuracy: f64) -> Strategy {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return Strategy::PeakSearch { refine: false },
        };
        let q = grating.period_nm() * u.abs();
        let lobes = n * q * (1.0 / BAND.min_nm() - 1.0 / BAND.max_nm());
        let accuracy = if accuracy.is_finite() && accuracy > 0.0 {
            accuracy
        } else {
            DEFAULT_ACCURACY
        };
        // Order 0's half period in the band: the peak search integrates it coarsely (2e-3 of
        // its own colour). Its colour is at most F_N(x_lo) of the white, and the brightest
        // order is about Y₁ = 555 nm/(N·∫ȳ) ≈ 5.2/N.
        let x_lo = q / BAND.max_nm();
        let order0 = if x_lo >= 0.5 {
            0.0
        } else if x_lo * n < 1.0 {
            2e-3 * n / 5.2
        } else {
            let f = 1.0 / (n * sinpi(x_lo - rint(x_lo)));
            2e-3 * f * f * n / 5.2
        };
        if lobes > 64.0 && 8.0 / n + order0 <= accuracy {
            Strategy::PeakSearch { refine: false }
        } else {
            Strategy::Exact
        }
    }

    /// E·I·cmf·norm at λ.
    #[inline]
    fn integrand(&self, grating: &Grating, u: f64, lambda_nm: f64) -> [f64; 3] {
        let i = grating.intensity_f64(u, lambda_nm);
        let w = self.weight(lambda_nm);
        [w[0] * i, w[1] * i, w[2] * i]
    }

    fn peak_search(&self, grating: &Grating, u: f64, refine: bool) -> [f64; 3] {
        let peaks = grating.peaks(u, BAND);
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return [0.0; 3],
        };
        let q = grating.period_nm() * u;
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobes = Lobes::new(self, grating, q, n);
        let mut acc = [0.0; 3];
        // Order 0 is broad in wavelength: where its half period (x < ½) reaches into the band,
        // the partial lobe at the start, the next ORDER0_LOBES lobes and all lobes wider than
        // AVERAGE_BELOW_NM are integrated lobe by lobe, the rest with sin²(Nα) → ½ (starting and ending on zeros of sin(Nα), where that
        // costs nothing), and the final partial lobe again lobe by lobe; every piece spans at
        // most COARSE_SPAN_NM and is not split at table rows. This light is broad and its error
        // is small against the orders' (see the module docs).
        if x_lo < 0.5 {
            let end = x_hi.min(0.5);
            // Lobes are q/(N·x²) nm wide: average only where they are narrower than
            // AVERAGE_BELOW_NM, after at least ORDER0_LOBES lobes.
            let narrow_from = ceil(sqrt(q / (n * AVERAGE_BELOW_NM)) * n);
            let near_end = (ceil(x_lo * n) + ORDER0_LOBES).max(narrow_from) / n;
            let near_end = near_end.min(end);
            add(&mut acc, lobes.coarse_lobes(x_lo, near_end));
            let tail_end = (floor(end * n) / n).max(near_end);
            if near_end < tail_end {
                add(&mut acc, lobes.envelope(near_end, tail_end, false));
            }
            add(&mut acc, lobes.coarse_lobes(tail_end, end));
        }
        let half = REFINE_LOBES / n;
        // Mass of F_N within ±REFINE_LOBES lobes of a peak (the same for every order), and the
        // rest of the period's mass 1/N, half on each side.
        let near_mass = if refine { lobes.kernel_mass(half) } else { 0.0 };
        let mut near_mass_edge = near_mass;
        for p in peaks {
            let m = p.order.unsigned_abs() as f64;
            let at_edge = m - half < x_lo || m + half > x_hi;
            if !refine && !at_edge {
                let w = self.weight(p.wavelength_nm);
                add_scaled(&mut acc, w, p.intensity * p.equivalent_width_nm);
                continue;
            }
            if near_mass_edge == 0.0 {
                near_mass_edge = lobes.kernel_mass(half);
            }
            // Main and first side lobes by quadrature (clipped to the band), the rest of the
            // mass of each side that lies in the band at the peak.
            // (Refined: exact lobes; plain: the coarse rule, enough for the peak search's
            // accuracy and far cheaper when N is small and the lobes are wide.)
            let (a, b) = ((m - half).max(x_lo), (m + half).min(x_hi));
            let near = if refine {
                lobes.lobes(a, b)
            } else {
                lobes.coarse_lobes(a, b)
            };
            add(&mut acc, near);
            let sides = (m - half >= x_lo) as u8 + (m + half <= x_hi) as u8;
            let rest = 0.5 * sides as f64 * (1.0 / n - near_mass_edge).max(0.0);
            let w = self.weight(p.wavelength_nm);
            add_scaled(&mut acc, w, p.intensity * rest * p.wavelength_nm / m);
        }
        // Orders just outside the band whose main lobes reach into it.
        for m in [floor(x_lo), ceil(x_hi)] {
            if m >= 1.0 && !(x_lo..=x_hi).contains(&m) {
                let (a, b) = ((m - half).max(x_lo), (m + half).min(x_hi));
                add(&mut acc, lobes.coarse_lobes(a, b));
            }
        }
        acc
    }

    fn paper_peaks(&self, grating: &Grating, u: f64) -> [f64; 3] {
        let peaks = grating.peaks(u, BAND);
        let mut acc = [0.0; 3];
        if peaks.specular() {
            acc = [self.white.x, self.white.y, self.white.z];
        }
        let scale = 1.0 / self.mean_power;
        for p in peaks {
            let e = self.illuminant.power(p.wavelength_nm) * scale * p.intensity;
            add_scaled(&mut acc, cie::cmf(p.wavelength_nm), e);
        }
        acc
    }

    fn exact(&self, grating: &Grating, u: f64) -> [f64; 3] {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return [0.0; 3],
        };
        let q = grating.period_nm() * u;
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobes = Lobes::new(self, grating, q, n);
        if n * (x_hi - x_lo) <= MAX_LOBES {
            return lobes.lobes(x_lo, x_hi);
        }
        // Hybrid: lobe-exact within NEAR_LOBES lobes of every integer x and of the band ends
        // (aligned to lobe boundaries), the envelope with sin² → ½ elsewhere.
        let k = NEAR_LOBES / n;
        let start_end = (ceil((x_lo + k) * n) / n).min(x_hi);
        let end_start = (floor((x_hi - k) * n) / n).max(x_lo);
        let mut acc = [0.0; 3];
        let mut cursor = x_lo;
        while cursor < x_hi {
            let m_prev = floor(cursor);
            let m_next = m_prev + 1.0;
            let (near, until) = if cursor < start_end {
                (true, start_end)
            } else if cursor >= end_start {
                (true, x_hi)
            } else if cursor < m_prev + k {
                (true, m_prev + k)
            } else if cursor >= m_next - k {
                (true, m_next + k)
            } else {
                (false, (m_next - k).min(end_start))
            };
            let until = until.min(x_hi);
            if near {
                add(&mut acc, lobes.lobes(cursor, until));
            } else {
                add(&mut acc, lobes.envelope(cursor, until, true));
            }
            cursor = until;
        }
        acc
    }

    /// An unbiased estimate of [`xyz`](Self::xyz) from one jittered wavelength in each of
    /// `randoms.len()` equal strata of the band, `randoms` being the caller's numbers in [0, 1).
    /// An empty slice gives black.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 3)?;
    /// let s = Spectral::new(Illuminant::E);
    /// let est = s.xyz_stratified(&g, 0.4, &[0.5; 64]); // midpoints: the uniform rule
    /// assert_eq!(est, s.xyz(&g, 0.4, Strategy::Uniform { samples: 64 }));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_stratified(&self, grating: &Grating, u: f64, randoms: &[f64]) -> Xyz {
        let k = randoms.len();
        if k == 0 || !u.is_finite() {
            return Xyz::default();
        }
        let step = BAND.width_nm() / k as f64;
        let mut acc = [0.0; 3];
        for (j, &r) in randoms.iter().enumerate() {
            let r = if (0.0..1.0).contains(&r) { r } else { 0.5 };
            let l = BAND.min_nm() + (j as f64 + r) * step;
            add_scaled(&mut acc, self.integrand(grating, u.abs(), l), step);
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }

    /// Hero wavelengths (as in pbrt-v4): one random number `xi` in [0, 1) places the first of
    /// `count` wavelengths uniformly in the band and the others at equal spacing after it,
    /// wrapping around; an unbiased estimate of [`xyz`](Self::xyz). `count` = 0 gives black.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{color::Xyz, Grating};
    /// let g = Grating::new(1600.0, 800.0, 3)?;
    /// let s = Spectral::new(Illuminant::E);
    /// // xi = 0.5/count puts the wavelengths at the strata midpoints: the uniform rule.
    /// let hero = s.xyz_hero(&g, 0.4, 0.5 / 8.0, 8);
    /// let uniform = s.xyz(&g, 0.4, Strategy::Uniform { samples: 8 });
    /// assert!((hero.y - uniform.y).abs() < 1e-12 * uniform.y); // same wavelengths, rounded apart
    /// assert_eq!(s.xyz_hero(&g, 0.4, 0.5, 0), Xyz::default()); // no wavelength: black
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_hero(&self, grating: &Grating, u: f64, xi: f64, count: u32) -> Xyz {
        if count == 0 || !u.is_finite() {
            return Xyz::default();
        }
        let xi = if (0.0..1.0).contains(&xi) { xi } else { 0.5 };
        let w = BAND.width_nm();
        let step = w / count as f64;
        let mut acc = [0.0; 3];
        for j in 0..count {
            let mut off = xi * w + j as f64 * step;
            if off >= w {
                off -= w;
            }
            add_scaled(
                &mut acc,
                self.integrand(grating, u.abs(), BAND.min_nm() + off),
                step,
            );
        }
        Xyz::new(acc[0], acc[1], acc[2])
    }
}

impl Spectral {
    /// The reference colour of any [`DiffractionBrdf`] at (wi, wo): ∫E·f·cmf/∫E·ȳ with f the
    /// BRDF's `eval`, multiplied by cos θi when the BRDF does not include it.
    ///
    /// This is the generic path behind [`DiffractionBrdf::xyz`]; models with a known lobe
    /// structure ([`AguHill`](crate::AguHill)) override that method with the exact paths of
    /// [`Spectral::xyz`]. Here the strategies mean:
    /// `Uniform`, `GaussLegendre`: as for a grating; `PeakSearch`: each visited peak's value
    /// times its equivalent width (both modes), plus 8-point Gauss-Legendre on 16 intervals where
    /// the order-0 lobe is seen; `PaperPeaks`: the peak values at their wavelengths, and the
    /// white scaled by the band-averaged value where the order-0 lobe is seen; `Exact` and
    /// `Auto`: Gauss-Legendre on every 1 nm step of the tables plus 128 pieces over ±64
    /// equivalent widths around every visited peak narrower than 0.5 nm.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{AguHill, DiffractionBrdf, Grating};
    /// use glam::DVec3;
    /// let m = AguHill::new(Grating::new(1600.0, 800.0, 300)?);
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wi, wo) = (DVec3::Z, DVec3::new(0.35, 0.0, (1.0f64 - 0.35 * 0.35).sqrt()));
    /// let generic = s.xyz_brdf(&m, wi, wo, Strategy::Exact);
    /// let special = m.xyz(wi, wo, &s, Strategy::Exact); // AguHill's lobe-exact override
    /// assert!((generic.y - special.y).abs() < 1e-6 * special.y);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_brdf<B: DiffractionBrdf + ?Sized>(
        &self,
        brdf: &B,
        wi: DVec3,
        wo: DVec3,
        strategy: Strategy,
    ) -> Xyz {
        if !(wi.is_finite() && wo.is_finite()) {
            return Xyz::default();
        }
        let cos = if brdf.cosine_included() {
            1.0
        } else {
            wi.z.max(0.0)
        };
        let f = |l: f64| -> [f64; 3] {
            let v = brdf.eval(wi, wo, l) * cos;
            let w = self.weight(l);
            [w[0] * v, w[1] * v, w[2] * v]
        };
        let mut acc = [0.0; 3];
        match strategy {
            Strategy::Uniform { samples } => acc = midpoint_rule(samples, &f),
            Strategy::GaussLegendre { intervals } => acc = gauss_legendre_rule(intervals, &f),
            Strategy::PeakSearch { .. } => {
                let summary = brdf.peaks(wi, wo, BAND, &mut |p| {
                    add_scaled(
                        &mut acc,
                        self.weight(p.wavelength_nm),
                        p.intensity * cos * p.equivalent_width_nm,
                    );
                });
                if summary.specular {
                    let step = BAND.width_nm() / 16.0;
                    for j in 0..16 {
                        let a = BAND.min_nm() + j as f64 * step;
                        gl8(a, a + step, &mut acc, &f);
                    }
                }
            }
            Strategy::PaperPeaks => {
                let scale = 1.0 / self.mean_power;
                let summary = brdf.peaks(wi, wo, BAND, &mut |p| {
                    let e = self.illuminant.power(p.wavelength_nm) * scale * p.intensity * cos;
                    add_scaled(&mut acc, cie::cmf(p.wavelength_nm), e);
                });
                if summary.specular {
                    let mut mean = 0.0;
                    for j in 0..16 {
                        mean += brdf.eval(wi, wo, BAND.min_nm() + (j as f64 + 0.5) * 29.375);
                    }
                    let k = mean / 16.0 * cos;
                    add(
                        &mut acc,
                        [self.white.x * k, self.white.y * k, self.white.z * k],
                    );
                }
            }
            Strategy::Exact | Strategy::Auto { .. } => {
                let (lo, hi) = (BAND.min_nm(), BAND.max_nm());
                let mut l = lo;
                while l < hi {
                    gl8(l, l + 1.0, &mut acc, &f);
                    l += 1.0;
                }
                // Resolve each narrow peak: over the whole 1 nm steps around ±64 equivalent
                // widths, replace the 1 nm rule by 128 pieces (split at the table rows). Peaks come
                // in order of decreasing wavelength; each window stops where the previous began,
                // so windows never overlap.
                let mut previous_start = hi;
                brdf.peaks(wi, wo, BAND, &mut |p| {
                    let w = p.equivalent_width_nm;
                    if w.is_nan() || w <= 0.0 || w >= 0.5 {
                        return;
                    }
                    let a = floor(p.wavelength_nm - 64.0 * w).max(lo);
                    let b = ceil(p.wavelength_nm + 64.0 * w).min(previous_start);
                    if b.is_nan() || b <= a {
                        return;
                    }
                    previous_start = a;
                    let (c0, c1) = (
                        (p.wavelength_nm - 64.0 * w).max(a),
                        (p.wavelength_nm + 64.0 * w).min(b),
                    );
                    let mut coarse = [0.0; 3];
                    let mut fine = [0.0; 3];
                    let mut t = a;
                    while t < b {
                        gl8(t, t + 1.0, &mut coarse, &f);
                        t += 1.0;
                    }
                    let by_rows = |s0: f64, s1: f64, out: &mut [f64; 3]| {
                        let mut t = s0;
                        while t < s1 {
                            let e = (floor(t) + 1.0).min(s1);
                            gl8(t, e, out, &f);
                            t = e;
                        }
                    };
                    by_rows(a, c0, &mut fine);
                    by_rows(c1, b, &mut fine);
                    let piece = (c1 - c0) / 128.0;
                    for j in 0..128 {
                        let s0 = c0 + j as f64 * piece;
                        by_rows(s0, s0 + piece, &mut fine);
                    }
                    for ((acc, fine), coarse) in acc.iter_mut().zip(fine).zip(coarse) {
                        *acc += fine - coarse;
                    }
                });
            }
        }
        Xyz::new(acc[0].max(0.0), acc[1].max(0.0), acc[2].max(0.0))
    }
}

/// A quadrature rule applied to one piece [a, b] of a [`Lobes`] integral.
type PieceRule<'a> = fn(&Lobes<'a>, f64, f64, &mut [f64; 3], &dyn Fn(f64) -> [f64; 3]);

/// Quadrature in the phase x = q/λ (q = d·|u|) of E·S·cmf·F_N·norm·q/x².
struct Lobes<'a> {
    s: &'a Spectral,
    q: f64,
    n: f64,
    n_int: u32,
    duty: f64,
}

impl<'a> Lobes<'a> {
    fn new(s: &'a Spectral, grating: &Grating, q: f64, n: f64) -> Lobes<'a> {
        Lobes {
            s,
            q,
            n,
            n_int: n as u32,
            duty: grating.slit_width_nm() / grating.period_nm(),
        }
    }

    /// E·S·cmf·norm·|dλ/dx| at phase x, without F_N.
    #[inline]
    fn envelope_at(&self, x: f64) -> [f64; 3] {
        let l = self.q / x;
        let jac = l / x;
        let s = single_slit_cycles(self.duty * x);
        let w = self.s.weight(l);
        let k = s * jac;
        [w[0] * k, w[1] * k, w[2] * k]
    }

    /// ∫ over [a, b] lobe by lobe, split at the 1 nm rows of the tables (8-point rule).
    fn lobes(&self, a: f64, b: f64) -> [f64; 3] {
        self.lobes_by(a, b, Self::split_at_rows)
    }

    /// ∫ over [a, b] lobe by lobe, each lobe in pieces of at most COARSE_SPAN_NM, 4-point
    /// Gauss-Legendre, not split at the table rows.
    fn coarse_lobes(&self, a: f64, b: f64) -> [f64; 3] {
        self.lobes_by(a, b, Self::coarse)
    }

    /// ∫ over [a, b] of the full integrand, one lobe (between zeros x = k/N) at a time, each
    /// lobe handed to `rule`.
    fn lobes_by(&self, a: f64, b: f64, rule: PieceRule<'a>) -> [f64; 3] {
        let mut acc = [0.0; 3];
        if b.is_nan() || a.is_nan() || b <= a {
            return acc;
        }
        let integrand = |x: f64| {
            let f = crate::kernel::n_slit_cycles(x, self.n_int);
            let e = self.envelope_at(x);
            [e[0] * f, e[1] * f, e[2] * f]
        };
        let mut k = floor(a * self.n) + 1.0;
        let mut lo = a;
        while lo < b {
            let hi = (k / self.n).min(b);
            if hi > lo {
                rule(self, lo, hi, &mut acc, &integrand);
            }
            lo = hi;
            k += 1.0;
        }
        acc
    }

    /// 4-point Gauss-Legendre on pieces of [a, b] spanning at most COARSE_SPAN_NM.
    fn coarse(&self, a: f64, b: f64, acc: &mut [f64; 3], f: &dyn Fn(f64) -> [f64; 3]) {
        let span = self.q / a - self.q / b;
        let pieces = ceil(span / COARSE_SPAN_NM).max(1.0);
        let step = (b - a) / pieces;
        let count = pieces as u32;
        let mut t = a;
        for j in 1..=count {
            let e = if j == count { b } else { a + j as f64 * step };
            gl4(t, e, acc, f);
            t = e;
        }
    }

    /// ∫ F_N dr over [−h, h] (lobe-exact Gauss-Legendre), h a whole number of lobes.
    fn kernel_mass(&self, h: f64) -> f64 {
        let mut sum = 0.0;
        let lobes = rint(h * self.n) as u32;
        let width = 1.0 / self.n;
        for j in 0..lobes {
            let (mid, half) = ((j as f64 + 0.5) * width, 0.5 * width);
            for (xi, wi) in GL_X.iter().zip(GL_W) {
                sum += wi * half * crate::kernel::n_slit_cycles(mid + half * xi, self.n_int);
            }
        }
        2.0 * sum
    }

    /// ∫ over [a, b] (away from integers) with sin²(πNx) replaced by its mean ½, on a grid
    /// where the distance to the nearest integer changes by at most a factor 2 per piece.
    fn envelope(&self, a: f64, b: f64, split_rows: bool) -> [f64; 3] {
        let mut acc = [0.0; 3];
        let mut lo = a;
        while lo < b {
            let m = floor(lo);
            let mid = m + 0.5;
            let hi = if lo < mid {
                (lo + (lo - m)).min(mid)
            } else {
                lo + 0.5 * (m + 1.0 - lo)
            };
            let hi = if hi > lo { hi.min(b) } else { b };
            let f = |x: f64| {
                let den = self.n * sinpi(x - rint(x));
                let f = 0.5 / (den * den);
                let e = self.envelope_at(x);
                [e[0] * f, e[1] * f, e[2] * f]
            };
            if split_rows {
                self.split_at_rows(lo, hi, &mut acc, &f);
            } else {
                self.coarse(lo, hi, &mut acc, &f);
            }
            lo = hi;
        }
        acc
    }

    /// Gauss-Legendre over [a, b] split where λ = q/x crosses an integer nanometre.
    fn split_at_rows(&self, a: f64, b: f64, acc: &mut [f64; 3], f: &dyn Fn(f64) -> [f64; 3]) {
        // λ runs from q/a down to q/b; rows j with q/b < j < q/a sit at x = q/j.
        let mut lo = a;
        let mut j = ceil(self.q / a) - 1.0;
        let j_end = self.q / b;
        while j > j_end && lo < b {
            let x = (self.q / j).min(b);
            if x > lo {
                gl8(lo, x, acc, f);
                lo = x;
            }
            j -= 1.0;
        }
        if b > lo {
            gl8(lo, b, acc, f);
        }
    }
}

/// The midpoint rule with `k` (at least 1) wavelengths over the band.
fn midpoint_rule(k: u32, f: &dyn Fn(f64) -> [f64; 3]) -> [f64; 3] {
    let k = k.max(1);
    let step = BAND.width_nm() / k as f64;
    let mut acc = [0.0; 3];
    for j in 0..k {
        add_scaled(&mut acc, f(BAND.min_nm() + (j as f64 + 0.5) * step), step);
    }
    acc
}

/// 8-point Gauss-Legendre on each of `k` (at least 1) equal intervals of the band.
fn gauss_legendre_rule(k: u32, f: &dyn Fn(f64) -> [f64; 3]) -> [f64; 3] {
    let k = k.max(1);
    let step = BAND.width_nm() / k as f64;
    let mut acc = [0.0; 3];
    for j in 0..k {
        let a = BAND.min_nm() + j as f64 * step;
        gl8(a, a + step, &mut acc, f);
    }
    acc
}

/// 4-point Gauss-Legendre over [a, b] (numpy.polynomial.legendre.leggauss(4)).
#[inline]
fn gl4(a: f64, b: f64, acc: &mut [f64; 3], f: &dyn Fn(f64) -> [f64; 3]) {
    const X: [f64; 2] = [0.33998104358485626, 0.8611363115940526];
    const W: [f64; 2] = [0.6521451548625464, 0.34785484513745357];
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    for (x, w) in X.iter().zip(W) {
        add_scaled(acc, f(mid - half * x), w * half);
        add_scaled(acc, f(mid + half * x), w * half);
    }
}

#[inline]
fn gl8(a: f64, b: f64, acc: &mut [f64; 3], f: &dyn Fn(f64) -> [f64; 3]) {
    let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
    for (xi, wi) in GL_X.iter().zip(GL_W) {
        add_scaled(acc, f(mid + half * xi), wi * half);
    }
}

#[inline]
fn add(acc: &mut [f64; 3], v: [f64; 3]) {
    acc[0] += v[0];
    acc[1] += v[1];
    acc[2] += v[2];
}

#[inline]
fn add_scaled(acc: &mut [f64; 3], v: [f64; 3], k: f64) {
    acc[0] += v[0] * k;
    acc[1] += v[1] * k;
    acc[2] += v[2] * k;
}
