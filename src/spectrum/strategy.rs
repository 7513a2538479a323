//! The names of the ways [`Spectral`](super::Spectral) evaluates a colour, their parsing and
//! printing.

use core::fmt;
use core::str::FromStr;

#[cfg(doc)]
use super::Spectral;
use super::MAX_WAVELENGTHS;
use crate::ParseError;

/// How [`Spectral::xyz`] and [`Spectral::xyz_brdf`] evaluate the spectral integral: each
/// variant names one algorithm with one stated error bound, the same on every path that accepts
/// it (the grating paths, and the generic path of models that are not a multiple of a grating's
/// intensity; see the [module docs](super) for the algorithms).
///
/// Errors are relative to the XYZ of the brightest diffracted order of the model (the scale of
/// [`Spectral::choose`]). N_eff below is a peak's sharpness, λ_m/(|m|·Δλ_m) with Δλ_m its
/// equivalent width: N for an N-slit grating. On the generic path the bounds hold for models
/// that keep the contract of [`DiffractionBrdf::peaks`](crate::DiffractionBrdf::peaks): every
/// feature of `eval` narrower than 2 nm is a reported peak, and `specular` says where order 0's
/// light reaches the band.
///
/// | variant | cost | bound |
/// |---|---|---|
/// | `Uniform { samples: K }` | K evaluations | none once peaks (width ≈ λ/(|m|·N_eff)) are narrower than the step 470/K nm; the rule's O(step²) for smooth spectra |
/// | `GaussLegendre { intervals: K }` | 8K evaluations | the same, with higher order between |
/// | `PeakSearch { .. }` | O(visible orders) | 8/N_eff, plus 2·10⁻³ of order 0's own light where its lobe reaches the band |
/// | `PaperPeaks` | O(visible orders) | not the integral: the paper's steps 6-8 |
/// | `Asymptotic` | O(visible orders), a few hundred evaluations | 5·10⁻⁴ for N ≥ 5, plus 10⁻³ of order 0's own light where its half period reaches the band (for N < 5 and on the generic path it is `Exact`) |
/// | `Exact` | see the module docs | 10⁻⁶ of the colour itself (of 10⁻³ of the brightest order for darker colours) |
/// | `Auto { accuracy }` | the cheapest of the above whose bound meets `accuracy` | `accuracy` |
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
    /// The midpoint rule with `samples` wavelengths (0 is taken as 1, more than
    /// [`MAX_WAVELENGTHS`](super::MAX_WAVELENGTHS) as that many).
    Uniform {
        /// Number of wavelengths.
        samples: u32,
    },
    /// 8-point Gauss-Legendre on each of `intervals` equal sub-intervals (0 is taken as 1, more
    /// than [`MAX_WAVELENGTHS`](super::MAX_WAVELENGTHS)/8 as that many).
    GaussLegendre {
        /// Number of sub-intervals of the band.
        intervals: u32,
    },
    /// The analytic weight of every visible order (its peak value times its equivalent width);
    /// `refine` integrates the lobes near each peak.
    PeakSearch {
        /// Integrate the main and first side lobes of each peak by quadrature.
        refine: bool,
    },
    /// The paper's own rendering (steps 6-8): peak wavelengths only, each weighted by its peak
    /// value S(β_m).
    PaperPeaks,
    /// Lobe-exact quadrature (see the module docs), the crate's reference.
    Exact,
    /// The peak search with its leading 1/N² correction: the orders' point values, the
    /// mean-½ envelope between them with its end corrections, lobe-exact quadrature next to
    /// every peak and band end (see the module docs). `Exact` below 5 slits; on the generic
    /// path, as `Exact`.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 21)?; // a CD: the peak search is 4.5 ΔE2000 off
    /// let s = Spectral::new(Illuminant::D65);
    /// let exact = s.xyz(&g, 0.34, Strategy::Exact);
    /// let fast = s.xyz(&g, 0.34, Strategy::Asymptotic);
    /// assert!((fast.y - exact.y).abs() < 5e-4 * exact.y);
    /// assert_eq!("asymptotic".parse(), Ok(Strategy::Asymptotic));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    Asymptotic,
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
            Strategy::Asymptotic => f.write_str("asymptotic"),
            Strategy::Auto { accuracy } => write!(f, "auto:{accuracy:e}"),
        }
    }
}

/// The error of parsing a [`Strategy`] name: the crate's one parse error, [`ParseError`].
///
/// ```
/// use diffraction::spectrum::{ParseStrategyError, Strategy};
/// let err: ParseStrategyError = "simpson".parse::<Strategy>().unwrap_err();
/// assert_eq!(err.what(), "strategy");
/// assert!("gauss:0".parse::<Strategy>().is_err()); // K must be positive
/// ```
pub type ParseStrategyError = ParseError;

/// The accepted spellings, as the parse error lists them.
const EXPECTED: &str = "uniform:K, gauss:K, peaks, peaks-refined, paper, exact, asymptotic or \
                        auto:ACCURACY \
                        (K a positive integer, ACCURACY a positive number)";

/// The parse error of a strategy name.
const PARSE_ERROR: ParseError = ParseError::new("strategy", EXPECTED);

impl FromStr for Strategy {
    type Err = ParseStrategyError;

    /// Parses `uniform:K`, `gauss:K`, `peaks`, `peaks-refined`, `paper`, `exact`, `asymptotic`,
    /// `auto` or
    /// `auto:ACCURACY`. K must be positive and at most the cap of its rule
    /// ([`MAX_WAVELENGTHS`] wavelengths, `MAX_WAVELENGTHS / 8` intervals).
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// assert_eq!("uniform:471".parse(), Ok(Strategy::Uniform { samples: 471 }));
    /// assert_eq!("auto:1e-4".parse(), Ok(Strategy::Auto { accuracy: 1e-4 }));
    /// assert!("uniform:0".parse::<Strategy>().is_err());
    /// assert!("uniform:4294967295".parse::<Strategy>().is_err()); // above MAX_WAVELENGTHS
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let count = |v: &str, cap: u32| match v.parse::<u32>() {
            Ok(k) if k > 0 && k <= cap => Ok(k),
            _ => Err(PARSE_ERROR),
        };
        match s.split_once(':') {
            None => match s {
                "peaks" => Ok(Strategy::PeakSearch { refine: false }),
                "peaks-refined" => Ok(Strategy::PeakSearch { refine: true }),
                "paper" => Ok(Strategy::PaperPeaks),
                "exact" => Ok(Strategy::Exact),
                "asymptotic" => Ok(Strategy::Asymptotic),
                "auto" => Ok(Strategy::default()),
                _ => Err(PARSE_ERROR),
            },
            Some(("uniform", k)) => Ok(Strategy::Uniform {
                samples: count(k, MAX_WAVELENGTHS)?,
            }),
            Some(("gauss", k)) => Ok(Strategy::GaussLegendre {
                intervals: count(k, MAX_WAVELENGTHS / 8)?,
            }),
            Some(("auto", a)) => match a.parse::<f64>() {
                Ok(a) if a.is_finite() && a > 0.0 => Ok(Strategy::Auto { accuracy: a }),
                _ => Err(PARSE_ERROR),
            },
            Some(_) => Err(PARSE_ERROR),
        }
    }
}
