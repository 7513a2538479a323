//! The names of the ways [`Spectral`](super::Spectral) evaluates a colour: [`Strategy`] for the
//! grating paths and [`GenericStrategy`] for models of any shape, each validated where it is
//! built, with its parsing and printing.

use core::fmt;
use core::str::FromStr;

use super::bounds::{self, Bound};
use super::MAX_WAVELENGTHS;
use crate::error::{Error, Requirement};
use crate::ParseError;

/// The default accuracy of [`Strategy::auto`] and [`GenericStrategy::auto`], relative to the
/// accuracy unit ([`accuracy_unit`](super::bounds::accuracy_unit)): 10⁻³. The colour table has
/// its own, finer default ([`ColorTable::DEFAULT_ACCURACY`](crate::ColorTable::DEFAULT_ACCURACY),
/// 10⁻⁴): a table built at 10⁻³ was measured up to 0.21 ΔE2000 from `Exact`.
///
/// ```
/// use diffraction::spectrum::{Strategy, DEFAULT_ACCURACY};
/// assert_eq!(DEFAULT_ACCURACY, 1e-3);
/// assert_eq!(Strategy::default(), Strategy::auto(DEFAULT_ACCURACY)?);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub const DEFAULT_ACCURACY: f64 = 1e-3;

/// The smallest accuracy `auto` accepts: ten times the bound of [`Strategy::EXACT`], the most
/// accurate algorithm.
///
/// ```
/// use diffraction::spectrum::{Strategy, MIN_ACCURACY};
/// assert!(Strategy::auto(MIN_ACCURACY).is_ok());
/// assert_eq!(Strategy::auto(MIN_ACCURACY / 2.0).unwrap_err().parameter(), "accuracy");
/// ```
pub const MIN_ACCURACY: f64 = 10.0 * bounds::EXACT;

/// The largest accuracy `auto` accepts (relative: 1 is an error as large as the unit itself).
///
/// ```
/// use diffraction::spectrum::{Strategy, MAX_ACCURACY};
/// assert!(Strategy::auto(MAX_ACCURACY).is_ok() && Strategy::auto(2.0).is_err());
/// ```
pub const MAX_ACCURACY: f64 = 1.0;

/// The most intervals of the Gauss-Legendre rules: `MAX_WAVELENGTHS / 8` (8 points each).
const MAX_INTERVALS: u32 = MAX_WAVELENGTHS / 8;

/// What a [`Strategy`] is, for reading (returned by [`Strategy::kind`]).
///
/// ```
/// use diffraction::spectrum::{Strategy, StrategyKind};
/// assert_eq!(Strategy::uniform(471)?.kind(), StrategyKind::Uniform { samples: 471 });
/// assert_eq!(Strategy::EXACT.kind(), StrategyKind::Exact);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum StrategyKind {
    /// The midpoint rule with `samples` wavelengths.
    Uniform {
        /// Number of wavelengths, 1 to [`MAX_WAVELENGTHS`].
        samples: u32,
    },
    /// 8-point Gauss-Legendre on each of `intervals` equal sub-intervals of the band.
    GaussLegendre {
        /// Number of sub-intervals, 1 to `MAX_WAVELENGTHS / 8`.
        intervals: u32,
    },
    /// The analytic weight of every visible order (its peak value times its equivalent width).
    PeakSearch,
    /// The peak search with the main and first side lobes of each peak integrated.
    PeakSearchRefined,
    /// The peak search with its 1/N² correction.
    Asymptotic,
    /// Lobe-exact quadrature, the crate's reference.
    Exact,
    /// The cheapest strategy whose bound meets `accuracy`.
    Auto {
        /// The requested accuracy, [`MIN_ACCURACY`] to [`MAX_ACCURACY`].
        accuracy: f64,
    },
}

/// How [`Spectral::xyz`](super::Spectral::xyz) and
/// [`Spectral::xyz_response`](super::Spectral::xyz_response) evaluate the colour of a grating's
/// intensity: each strategy is one algorithm with one stated error bound (see the
/// [module docs](super) for the algorithms).
///
/// Bounds are relative to the **accuracy unit** ([`accuracy_unit`](super::bounds::accuracy_unit)): the
/// Y of the grating's brightest diffracted order, floored at 555/(N·∫ȳ dλ), the Y of an ideal
/// first-order peak at 555 nm. Each is one number of the table in
/// [`bounds`](super::bounds), which `Auto`, the colour table and these docs read:
///
/// | strategy | cost | bound |
/// |---|---|---|
/// | [`uniform(K)`](Self::uniform) | K evaluations | none once peaks (width ≈ λ/(|m|·N)) are narrower than the step 470/K nm |
/// | [`gauss_legendre(K)`](Self::gauss_legendre) | 8K evaluations | the same, with higher order between |
/// | [`PEAK_SEARCH`](Self::PEAK_SEARCH) | O(visible orders) | [`PEAK_SEARCH_PER_SLIT`](super::bounds::PEAK_SEARCH_PER_SLIT)/N, plus [`PEAK_SEARCH_ORDER0`](super::bounds::PEAK_SEARCH_ORDER0) of order 0's own light where its lobe reaches the band |
/// | [`PEAK_SEARCH_REFINED`](Self::PEAK_SEARCH_REFINED) | plus 8 lobes × 8 points per order | the same |
/// | [`ASYMPTOTIC`](Self::ASYMPTOTIC) | O(visible orders), a few hundred evaluations | [`ASYMPTOTIC_ORDERS`](super::bounds::ASYMPTOTIC_ORDERS) for N ≥ [`ASYMPTOTIC_MIN_SLITS`](super::bounds::ASYMPTOTIC_MIN_SLITS), plus [`ASYMPTOTIC_ORDER0`](super::bounds::ASYMPTOTIC_ORDER0) of order 0's own light where its half period reaches the band; below that N, [`ASYMPTOTIC_SMALL_N`](super::bounds::ASYMPTOTIC_SMALL_N) of the colour itself (up to 7 slits F_N is written as its N cosines, a fixed number of evaluations, within both bounds) |
/// | [`EXACT`](Self::EXACT) | see the module docs | [`EXACT`](super::bounds::EXACT) of the colour itself (of 10⁻³ of the unit for darker colours) |
/// | [`auto(a)`](Self::auto) | the cheapest of the above whose bound meets `a` | a |
///
/// Built validated: a strategy cannot hold a count of 0 or an accuracy that is not a finite
/// number in [[`MIN_ACCURACY`], [`MAX_ACCURACY`]]. The paper's own peak colours (its steps 6-8)
/// are not an integral and not a strategy: [`Spectral::paper_peaks`](super::Spectral::paper_peaks).
///
/// ```
/// use diffraction::spectrum::{Strategy, DEFAULT_ACCURACY};
/// assert_eq!(Strategy::default(), Strategy::auto(DEFAULT_ACCURACY)?);
/// let s = Strategy::gauss_legendre(64)?;
/// assert_eq!(s.to_string(), "gauss:64");
/// assert_eq!("gauss:64".parse(), Ok(s));
/// assert_eq!(Strategy::uniform(0).unwrap_err().parameter(), "samples");
/// assert_eq!(Strategy::auto(f64::NAN).unwrap_err().parameter(), "accuracy");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strategy(StrategyKind);

/// What a [`GenericStrategy`] is, for reading (returned by [`GenericStrategy::kind`]).
///
/// ```
/// use diffraction::spectrum::{GenericStrategy, GenericStrategyKind};
/// assert_eq!(GenericStrategy::WINDOWS.kind(), GenericStrategyKind::Windows);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum GenericStrategyKind {
    /// The midpoint rule with `samples` wavelengths.
    Uniform {
        /// Number of wavelengths, 1 to [`MAX_WAVELENGTHS`].
        samples: u32,
    },
    /// 8-point Gauss-Legendre on each of `intervals` equal sub-intervals of the band.
    GaussLegendre {
        /// Number of sub-intervals, 1 to `MAX_WAVELENGTHS / 8`.
        intervals: u32,
    },
    /// Each reported peak's value times its equivalent width.
    PeakSearch,
    /// The 1 nm rule with every reported narrow peak resolved in a window.
    Windows,
    /// The cheapest generic rule whose bound meets `accuracy`.
    Auto {
        /// The requested accuracy, [`MIN_ACCURACY`] to [`MAX_ACCURACY`].
        accuracy: f64,
    },
}

/// How [`Spectral::xyz_brdf`](super::Spectral::xyz_brdf) evaluates the colour of a model of any
/// shape, through its [`SpectralResponse`](crate::SpectralResponse) (`response` and `peaks`):
/// the generic path's own rules, each one algorithm with one bound.
///
/// The bounds hold for models that keep the contract of
/// [`SpectralResponse::peaks`](crate::SpectralResponse::peaks) (every feature of the response
/// narrower than 2 nm is a reported peak; `specular` says where order 0's light reaches the
/// band) and are relative to the Y of the model's brightest diffracted order; N_eff is the
/// sharpest reported peak's λ_m/(|m|·Δλ_m), Δλ_m its equivalent width (N for an N-slit grating):
///
/// | strategy | cost | bound |
/// |---|---|---|
/// | [`uniform(K)`](Self::uniform) | K evaluations | none once peaks are narrower than the step |
/// | [`gauss_legendre(K)`](Self::gauss_legendre) | 8K evaluations | the same |
/// | [`PEAK_SEARCH`](Self::PEAK_SEARCH) | O(reported peaks); `WINDOWS` where order 0's lobe is seen | [`GENERIC_PEAK_SEARCH_PER_SLIT`](super::bounds::GENERIC_PEAK_SEARCH_PER_SLIT)/N_eff |
/// | [`WINDOWS`](Self::WINDOWS) | 8 points per 1 nm row, 128 pieces over ±64 widths of every narrow peak | [`WINDOWS`](super::bounds::WINDOWS) of the colour itself (of 10⁻³ of the brightest order for darker colours) |
/// | [`auto(a)`](Self::auto) | `PEAK_SEARCH` where its bound meets a, else `WINDOWS` | a |
///
/// A model that is a multiple of a grating's intensity is integrated better by the grating
/// paths: [`SpectralResponse::grating_response`](crate::SpectralResponse::grating_response) and
/// [`Spectral::xyz_response`](super::Spectral::xyz_response) with a [`Strategy`].
///
/// ```
/// use diffraction::spectrum::GenericStrategy;
/// assert_eq!("windows".parse(), Ok(GenericStrategy::WINDOWS));
/// assert_eq!(GenericStrategy::auto(1e-3)?.to_string(), "auto:1e-3");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenericStrategy(GenericStrategyKind);

/// `samples` in 1..=MAX_WAVELENGTHS.
fn check_count(name: &'static str, k: u32, cap: u32) -> Result<u32, Error> {
    if k == 0 {
        return Err(Error::invalid(name, 0.0, Requirement::AtLeastOne));
    }
    if k > cap {
        return Err(Error::invalid(
            name,
            k as f64,
            Requirement::Within {
                min: 1.0,
                max: cap as f64,
            },
        ));
    }
    Ok(k)
}

/// `accuracy` finite in [MIN_ACCURACY, MAX_ACCURACY].
fn check_accuracy(accuracy: f64) -> Result<f64, Error> {
    if accuracy.is_finite() && (MIN_ACCURACY..=MAX_ACCURACY).contains(&accuracy) {
        Ok(accuracy)
    } else {
        Err(Error::invalid(
            "accuracy",
            accuracy,
            Requirement::Within {
                min: MIN_ACCURACY,
                max: MAX_ACCURACY,
            },
        ))
    }
}

impl Strategy {
    /// The peak search (see the [type docs](Self)).
    pub const PEAK_SEARCH: Strategy = Strategy(StrategyKind::PeakSearch);
    /// The peak search with the lobes next to each peak integrated.
    pub const PEAK_SEARCH_REFINED: Strategy = Strategy(StrategyKind::PeakSearchRefined);
    /// The peak search with its 1/N² correction (see the module docs).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 21)?; // a CD: the peak search is 4.5 ΔE2000 off
    /// let s = Spectral::new(Illuminant::D65);
    /// let exact = s.xyz(&g, 0.34, Strategy::EXACT);
    /// let fast = s.xyz(&g, 0.34, Strategy::ASYMPTOTIC);
    /// assert!((fast.y - exact.y).abs() < 5e-4 * exact.y);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub const ASYMPTOTIC: Strategy = Strategy(StrategyKind::Asymptotic);
    /// Lobe-exact quadrature, the crate's reference.
    pub const EXACT: Strategy = Strategy(StrategyKind::Exact);

    /// The midpoint rule with `samples` wavelengths, 1 to [`MAX_WAVELENGTHS`]; the error names
    /// `samples`.
    ///
    /// ```
    /// use diffraction::spectrum::{Strategy, MAX_WAVELENGTHS};
    /// assert!(Strategy::uniform(471).is_ok());
    /// assert_eq!(Strategy::uniform(MAX_WAVELENGTHS + 1).unwrap_err().parameter(), "samples");
    /// ```
    pub fn uniform(samples: u32) -> Result<Strategy, Error> {
        Ok(Strategy(StrategyKind::Uniform {
            samples: check_count("samples", samples, MAX_WAVELENGTHS)?,
        }))
    }

    /// 8-point Gauss-Legendre on `intervals` equal sub-intervals, 1 to `MAX_WAVELENGTHS / 8`;
    /// the error names `intervals`.
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// assert!(Strategy::gauss_legendre(4).is_ok());
    /// assert_eq!(Strategy::gauss_legendre(0).unwrap_err().parameter(), "intervals");
    /// ```
    pub fn gauss_legendre(intervals: u32) -> Result<Strategy, Error> {
        Ok(Strategy(StrategyKind::GaussLegendre {
            intervals: check_count("intervals", intervals, MAX_INTERVALS)?,
        }))
    }

    /// The cheapest strategy whose bound meets `accuracy` (relative to the accuracy unit,
    /// [`MIN_ACCURACY`] to [`MAX_ACCURACY`]; the error names `accuracy`). What it picks:
    /// [`Spectral::choose`](super::Spectral::choose).
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// assert!(Strategy::auto(1e-3).is_ok());
    /// assert!(Strategy::auto(0.0).is_err() && Strategy::auto(f64::INFINITY).is_err());
    /// ```
    pub fn auto(accuracy: f64) -> Result<Strategy, Error> {
        Ok(Strategy(StrategyKind::Auto {
            accuracy: check_accuracy(accuracy)?,
        }))
    }

    /// What the strategy is.
    ///
    /// ```
    /// use diffraction::spectrum::{Strategy, StrategyKind};
    /// assert_eq!(Strategy::auto(1e-4)?.kind(), StrategyKind::Auto { accuracy: 1e-4 });
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn kind(self) -> StrategyKind {
        self.0
    }

    /// The strategy's error bound for `slits` N (`None` where it has none: the fixed rules,
    /// and N = ∞, whose colour the paper's normalisation makes 0 off the mirror direction).
    ///
    /// ```
    /// use diffraction::spectrum::{bounds, Strategy};
    /// let b = Strategy::PEAK_SEARCH.bound(1000).unwrap();
    /// assert_eq!(b.orders, bounds::PEAK_SEARCH_PER_SLIT / 1000.0);
    /// assert!(Strategy::uniform(10)?.bound(1000).is_none());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn bound(self, slits: u32) -> Option<Bound> {
        let n = slits.max(1) as f64;
        match self.0 {
            StrategyKind::Uniform { .. } | StrategyKind::GaussLegendre { .. } => None,
            StrategyKind::PeakSearch | StrategyKind::PeakSearchRefined => Some(Bound {
                orders: bounds::PEAK_SEARCH_PER_SLIT / n,
                order0: bounds::PEAK_SEARCH_ORDER0,
                of_colour: 0.0,
            }),
            StrategyKind::Asymptotic if slits >= bounds::ASYMPTOTIC_MIN_SLITS => Some(Bound {
                orders: bounds::ASYMPTOTIC_ORDERS,
                order0: bounds::ASYMPTOTIC_ORDER0,
                of_colour: 0.0,
            }),
            StrategyKind::Asymptotic => Some(Bound::of_colour(bounds::ASYMPTOTIC_SMALL_N)),
            StrategyKind::Exact => Some(Bound::of_colour(bounds::EXACT)),
            StrategyKind::Auto { accuracy } => Some(Bound {
                orders: accuracy,
                order0: 0.0,
                of_colour: 0.0,
            }),
        }
    }
}

impl GenericStrategy {
    /// Each reported peak's value times its equivalent width (see the [type docs](Self)).
    pub const PEAK_SEARCH: GenericStrategy = GenericStrategy(GenericStrategyKind::PeakSearch);
    /// The 1 nm rule with every reported narrow peak resolved in a window.
    pub const WINDOWS: GenericStrategy = GenericStrategy(GenericStrategyKind::Windows);

    /// The midpoint rule with `samples` wavelengths, 1 to [`MAX_WAVELENGTHS`].
    ///
    /// ```
    /// use diffraction::spectrum::GenericStrategy;
    /// assert_eq!(GenericStrategy::uniform(0).unwrap_err().parameter(), "samples");
    /// ```
    pub fn uniform(samples: u32) -> Result<GenericStrategy, Error> {
        Ok(GenericStrategy(GenericStrategyKind::Uniform {
            samples: check_count("samples", samples, MAX_WAVELENGTHS)?,
        }))
    }

    /// 8-point Gauss-Legendre on `intervals` equal sub-intervals, 1 to `MAX_WAVELENGTHS / 8`.
    ///
    /// ```
    /// use diffraction::spectrum::GenericStrategy;
    /// assert!(GenericStrategy::gauss_legendre(16).is_ok());
    /// ```
    pub fn gauss_legendre(intervals: u32) -> Result<GenericStrategy, Error> {
        Ok(GenericStrategy(GenericStrategyKind::GaussLegendre {
            intervals: check_count("intervals", intervals, MAX_INTERVALS)?,
        }))
    }

    /// `PEAK_SEARCH` where its bound meets `accuracy`, else `WINDOWS`; `accuracy` from
    /// [`MIN_ACCURACY`] to [`MAX_ACCURACY`].
    ///
    /// ```
    /// use diffraction::spectrum::GenericStrategy;
    /// assert!(GenericStrategy::auto(1e-2).is_ok() && GenericStrategy::auto(-1.0).is_err());
    /// ```
    pub fn auto(accuracy: f64) -> Result<GenericStrategy, Error> {
        Ok(GenericStrategy(GenericStrategyKind::Auto {
            accuracy: check_accuracy(accuracy)?,
        }))
    }

    /// What the strategy is.
    ///
    /// ```
    /// use diffraction::spectrum::{GenericStrategy, GenericStrategyKind};
    /// assert_eq!(GenericStrategy::PEAK_SEARCH.kind(), GenericStrategyKind::PeakSearch);
    /// ```
    #[must_use]
    pub fn kind(self) -> GenericStrategyKind {
        self.0
    }
}

impl Default for Strategy {
    /// `auto` at [`DEFAULT_ACCURACY`].
    fn default() -> Self {
        Strategy(StrategyKind::Auto {
            accuracy: DEFAULT_ACCURACY,
        })
    }
}

impl Default for GenericStrategy {
    /// `auto` at [`DEFAULT_ACCURACY`].
    fn default() -> Self {
        GenericStrategy(GenericStrategyKind::Auto {
            accuracy: DEFAULT_ACCURACY,
        })
    }
}

impl fmt::Display for Strategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            StrategyKind::Uniform { samples } => write!(f, "uniform:{samples}"),
            StrategyKind::GaussLegendre { intervals } => write!(f, "gauss:{intervals}"),
            StrategyKind::PeakSearch => f.write_str("peaks"),
            StrategyKind::PeakSearchRefined => f.write_str("peaks-refined"),
            StrategyKind::Exact => f.write_str("exact"),
            StrategyKind::Asymptotic => f.write_str("asymptotic"),
            StrategyKind::Auto { accuracy } => write!(f, "auto:{accuracy:e}"),
        }
    }
}

impl fmt::Display for GenericStrategy {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            GenericStrategyKind::Uniform { samples } => write!(f, "uniform:{samples}"),
            GenericStrategyKind::GaussLegendre { intervals } => write!(f, "gauss:{intervals}"),
            GenericStrategyKind::PeakSearch => f.write_str("peaks"),
            GenericStrategyKind::Windows => f.write_str("windows"),
            GenericStrategyKind::Auto { accuracy } => write!(f, "auto:{accuracy:e}"),
        }
    }
}

/// The parse error of a strategy name.
const PARSE_STRATEGY: ParseError = ParseError::new(
    "strategy",
    "uniform:K (K from 1 to 65536), gauss:K (K from 1 to 8192), peaks, peaks-refined, \
     asymptotic, exact, auto or auto:ACCURACY (ACCURACY from 1e-6 to 1)",
);

/// The parse error of a generic strategy name.
const PARSE_GENERIC: ParseError = ParseError::new(
    "generic strategy",
    "uniform:K (K from 1 to 65536), gauss:K (K from 1 to 8192), peaks, windows, auto or \
     auto:ACCURACY (ACCURACY from 1e-6 to 1)",
);

/// The parts both spellings share: `uniform:K`, `gauss:K`, `auto`, `auto:A`.
enum Shared {
    Uniform(u32),
    Gauss(u32),
    Auto(f64),
}

/// A count in `1..=cap`, or the error that names the count and the range (digits beyond any
/// integer type are out of range too).
fn parse_count(
    k: &str,
    cap: u32,
    what: &'static str,
    range: &'static str,
) -> Option<Result<u32, ParseError>> {
    if k.is_empty() || !k.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let v: f64 = k.parse().ok()?;
    Some(match k.parse::<u32>() {
        Ok(n) if (1..=cap).contains(&n) => Ok(n),
        _ => Err(ParseError::number_out_of_range(what, v, range)),
    })
}

/// `uniform:K`, `gauss:K`, `auto`, `auto:A`: `None` for anything else, an error naming the
/// number where the name is known and its number out of range.
fn parse_shared(s: &str) -> Option<Result<Shared, ParseError>> {
    Some(match s.split_once(':') {
        None => return (s == "auto").then_some(Ok(Shared::Auto(DEFAULT_ACCURACY))),
        Some(("uniform", k)) => {
            parse_count(k, MAX_WAVELENGTHS, "uniform count", "1 to 65536")?.map(Shared::Uniform)
        }
        Some(("gauss", k)) => {
            parse_count(k, MAX_INTERVALS, "gauss interval count", "1 to 8192")?.map(Shared::Gauss)
        }
        Some(("auto", a)) => {
            let v: f64 = a.parse().ok()?;
            if v.is_finite() && (MIN_ACCURACY..=MAX_ACCURACY).contains(&v) {
                Ok(Shared::Auto(v))
            } else {
                Err(ParseError::number_out_of_range(
                    "auto accuracy",
                    v,
                    "1e-6 to 1",
                ))
            }
        }
        Some(_) => return None,
    })
}

impl FromStr for Strategy {
    type Err = ParseError;

    /// Parses `uniform:K`, `gauss:K`, `peaks`, `peaks-refined`, `asymptotic`, `exact`, `auto`
    /// or `auto:ACCURACY`, with the ranges of the constructors (the error lists them).
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// assert_eq!("uniform:471".parse(), Ok(Strategy::uniform(471)?));
    /// assert_eq!("auto:1e-4".parse(), Ok(Strategy::auto(1e-4)?));
    /// assert!("uniform:0".parse::<Strategy>().is_err());
    /// assert!("uniform:4294967295".parse::<Strategy>().is_err()); // above MAX_WAVELENGTHS
    /// assert!("windows".parse::<Strategy>().is_err()); // a generic rule only
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let fixed = match s {
            "peaks" => Some(Strategy::PEAK_SEARCH),
            "peaks-refined" => Some(Strategy::PEAK_SEARCH_REFINED),
            "asymptotic" => Some(Strategy::ASYMPTOTIC),
            "exact" => Some(Strategy::EXACT),
            _ => None,
        };
        if let Some(f) = fixed {
            return Ok(f);
        }
        match parse_shared(s) {
            Some(Ok(Shared::Uniform(k))) => Strategy::uniform(k).map_err(|_| PARSE_STRATEGY),
            Some(Ok(Shared::Gauss(k))) => Strategy::gauss_legendre(k).map_err(|_| PARSE_STRATEGY),
            Some(Ok(Shared::Auto(a))) => Strategy::auto(a).map_err(|_| PARSE_STRATEGY),
            Some(Err(e)) => Err(e),
            None => Err(PARSE_STRATEGY),
        }
    }
}

impl FromStr for GenericStrategy {
    type Err = ParseError;

    /// Parses `uniform:K`, `gauss:K`, `peaks`, `windows`, `auto` or `auto:ACCURACY`.
    ///
    /// ```
    /// use diffraction::spectrum::GenericStrategy;
    /// assert_eq!("peaks".parse(), Ok(GenericStrategy::PEAK_SEARCH));
    /// assert!("exact".parse::<GenericStrategy>().is_err()); // a grating algorithm only
    /// ```
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let fixed = match s {
            "peaks" => Some(GenericStrategy::PEAK_SEARCH),
            "windows" => Some(GenericStrategy::WINDOWS),
            _ => None,
        };
        if let Some(f) = fixed {
            return Ok(f);
        }
        match parse_shared(s) {
            Some(Ok(Shared::Uniform(k))) => GenericStrategy::uniform(k).map_err(|_| PARSE_GENERIC),
            Some(Ok(Shared::Gauss(k))) => {
                GenericStrategy::gauss_legendre(k).map_err(|_| PARSE_GENERIC)
            }
            Some(Ok(Shared::Auto(a))) => GenericStrategy::auto(a).map_err(|_| PARSE_GENERIC),
            Some(Err(e)) => Err(e),
            None => Err(PARSE_GENERIC),
        }
    }
}

/// Strategies (de)serialise as their names (`"auto:1e-3"`, `"exact"`), validated on the way in.
#[cfg(feature = "serde")]
mod serde_impls {
    use super::{GenericStrategy, Strategy};
    use alloc_free::Name;

    /// A strategy's printed name without allocating: at most 32 bytes.
    mod alloc_free {
        use core::fmt::{self, Write};

        pub struct Name {
            buf: [u8; 32],
            len: usize,
        }

        impl Name {
            pub fn of(v: &dyn fmt::Display) -> Name {
                let mut n = Name {
                    buf: [0; 32],
                    len: 0,
                };
                // Every strategy name fits (the longest, "auto:2.2250738585072014e-308", has 28
                // bytes); a write that does not is cut, which cannot happen.
                let _ = write!(n, "{v}");
                n
            }

            pub fn as_str(&self) -> &str {
                core::str::from_utf8(&self.buf[..self.len]).unwrap_or("")
            }
        }

        impl Write for Name {
            fn write_str(&mut self, s: &str) -> fmt::Result {
                let end = self.len + s.len();
                if end > self.buf.len() {
                    return Err(fmt::Error);
                }
                self.buf[self.len..end].copy_from_slice(s.as_bytes());
                self.len = end;
                Ok(())
            }
        }
    }

    macro_rules! by_name {
        ($t:ty, $what:literal) => {
            impl serde::Serialize for $t {
                fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
                    s.serialize_str(Name::of(self).as_str())
                }
            }

            impl<'de> serde::Deserialize<'de> for $t {
                fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                    struct Visitor;
                    impl serde::de::Visitor<'_> for Visitor {
                        type Value = $t;
                        fn expecting(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                            f.write_str($what)
                        }
                        fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<$t, E> {
                            v.parse().map_err(E::custom)
                        }
                    }
                    d.deserialize_str(Visitor)
                }
            }
        };
    }

    by_name!(
        Strategy,
        "a strategy name such as \"auto:1e-3\" or \"exact\""
    );
    by_name!(
        GenericStrategy,
        "a generic strategy name such as \"windows\""
    );
}
