//! How the tracers compute a grating material's colour (the `--strategy` option and the
//! scenes' `strategy` key): one of the crate's spectral strategies, or the paper's own peak
//! colours, which are not an integral and so not a crate `Strategy`.

use std::fmt;
use std::str::FromStr;

use diffraction::spectrum::{GenericStrategy, Strategy, StrategyKind};

/// A material's colour rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Colour {
    /// The spectral integral by a crate strategy: on the grating paths for a model that is a
    /// grating's intensity (`Spectral::xyz_response`), and by its generic counterpart
    /// ([`Colour::generic`]) for any other model (`Spectral::xyz_brdf`).
    Integral(Strategy),
    /// The paper's own peak colours (its steps 6-8: `Spectral::paper_peaks`).
    Paper,
}

impl Colour {
    /// The default: the peak search.
    pub const DEFAULT: Colour = Colour::Integral(Strategy::PEAK_SEARCH);

    /// The generic path's rule for this strategy, for models without a grating form (Thorman,
    /// Stam): the same rule where the generic path has it (`uniform`, `gauss`, `peaks`, `auto`),
    /// and its most accurate rule, `windows`, for the grating-only algorithms (`peaks-refined`,
    /// `asymptotic`, `exact`), which need F_N's lobes. `None` for the paper's colours.
    pub fn generic(self) -> Option<GenericStrategy> {
        let Colour::Integral(s) = self else {
            return None;
        };
        Some(match s.kind() {
            StrategyKind::Uniform { samples } => {
                GenericStrategy::uniform(samples).unwrap_or(GenericStrategy::WINDOWS)
            }
            StrategyKind::GaussLegendre { intervals } => {
                GenericStrategy::gauss_legendre(intervals).unwrap_or(GenericStrategy::WINDOWS)
            }
            StrategyKind::PeakSearch => GenericStrategy::PEAK_SEARCH,
            StrategyKind::Auto { accuracy } => {
                GenericStrategy::auto(accuracy).unwrap_or(GenericStrategy::WINDOWS)
            }
            _ => GenericStrategy::WINDOWS,
        })
    }
}

impl fmt::Display for Colour {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Colour::Integral(s) => s.fmt(f),
            Colour::Paper => f.write_str("paper"),
        }
    }
}

impl FromStr for Colour {
    type Err = diffraction::ParseError;

    /// `paper`, or a crate strategy's name (`peaks`, `exact`, `auto:1e-3`, ...).
    fn from_str(s: &str) -> Result<Colour, Self::Err> {
        if s == "paper" {
            return Ok(Colour::Paper);
        }
        s.parse().map(Colour::Integral)
    }
}
