//! The solver's typed errors: every one names the parameter (or the limit) and the value.

use core::fmt;

/// What went wrong in a solve. `Display` names the parameter and its value.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// An input outside its domain: `parameter` = `value` must satisfy `requirement`.
    Invalid {
        /// The parameter's name, as in the API (`period_nm`, `theta`, `cover.index`, ...).
        parameter: &'static str,
        /// The offending value.
        value: f64,
        /// What the value must satisfy, in words.
        requirement: &'static str,
    },
    /// The harmonic count reached the cap before two successive counts agreed to the tolerance.
    NotConverged {
        /// The last harmonic count solved.
        harmonics: usize,
        /// The largest change of any order's efficiency between the last two counts.
        change: f64,
        /// The tolerance asked for.
        tolerance: f64,
    },
    /// A linear-algebra step failed or produced a non-finite value (a singular system at an
    /// exactly degenerate configuration); the string says which step.
    Numerical(&'static str),
}

impl Error {
    /// The parameter an [`Error::Invalid`] names (`"harmonics"` for [`Error::NotConverged`],
    /// `"numerics"` for [`Error::Numerical`]).
    #[must_use]
    pub fn parameter(&self) -> &'static str {
        match self {
            Error::Invalid { parameter, .. } => parameter,
            Error::NotConverged { .. } => "harmonics",
            Error::Numerical(_) => "numerics",
        }
    }

    pub(crate) fn invalid(parameter: &'static str, value: f64, requirement: &'static str) -> Error {
        Error::Invalid {
            parameter,
            value,
            requirement,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Invalid {
                parameter,
                value,
                requirement,
            } => write!(f, "{parameter} = {}: must be {requirement}", Num(*value)),
            Error::NotConverged {
                harmonics,
                change,
                tolerance,
            } => write!(
                f,
                "harmonics: not converged to {tolerance} by {harmonics} harmonics (last change {change:.3e})"
            ),
            Error::Numerical(what) => write!(f, "numerics: {what}"),
        }
    }
}

impl std::error::Error for Error {}

/// A value as a person reads it in a message: the shortest round-trip form, in scientific
/// notation when it is very large or very small (`f64::MAX` as `1.7976931348623157e308`, not
/// 309 digits; a subnormal as `5e-324`), as the `diffraction` crate's errors print theirs.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a != 0.0 && a.is_finite() && !(1e-4..1e16).contains(&a) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// Checks `lo < value <= hi` (finite) or returns [`Error::Invalid`].
pub(crate) fn check_range(
    parameter: &'static str,
    value: f64,
    lo_exclusive: f64,
    hi: f64,
    requirement: &'static str,
) -> Result<f64, Error> {
    if value.is_finite() && value > lo_exclusive && value <= hi {
        Ok(value)
    } else {
        Err(Error::invalid(parameter, value, requirement))
    }
}
