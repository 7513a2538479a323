//! The crate's one error type.

use core::fmt;

/// A parameter was rejected where the value was built.
///
/// Every constructor of the crate that takes physical parameters validates them and returns this
/// error, naming the parameter, the value it got and what it requires.
///
/// ```
/// use diffraction::{Error, Grating};
/// let err = Grating::new(1600.0, 2000.0, 100).unwrap_err();
/// assert_eq!(err.parameter(), "slit_width_nm");
/// assert_eq!(
///     err.to_string(),
///     "invalid slit_width_nm = 2000: must satisfy 0 < slit_width_nm <= period_nm (1600)"
/// );
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A numeric parameter is out of its domain.
    InvalidParameter {
        /// The parameter's name, as spelled in the constructor's signature.
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What the parameter must satisfy.
        requirement: Requirement,
    },
}

/// What a rejected parameter must satisfy (used in [`Error::InvalidParameter`]).
///
/// ```
/// use diffraction::{Error, Grating, Requirement};
/// let err = Grating::new(1600.0, 2000.0, 100).unwrap_err();
/// assert!(matches!(
///     err,
///     Error::InvalidParameter {
///         requirement: Requirement::AtMost { bound_name: "period_nm", bound },
///         ..
///     } if bound == 1600.0
/// ));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum Requirement {
    /// Finite and strictly positive.
    Positive,
    /// Finite (not NaN nor infinite).
    Finite,
    /// Finite and ≥ 0.
    NonNegative,
    /// At least one.
    AtLeastOne,
    /// 0 < value ≤ the given bound (named in the message).
    AtMost {
        /// The name of the bound.
        bound_name: &'static str,
        /// The bound's value.
        bound: f64,
    },
    /// At least the given bound.
    AtLeast {
        /// The name of the bound.
        bound_name: &'static str,
        /// The bound's value.
        bound: f64,
    },
    /// Strictly greater than the given bound.
    GreaterThan {
        /// The name of the bound.
        bound_name: &'static str,
        /// The bound's value.
        bound: f64,
    },
    /// Inside a closed interval.
    Within {
        /// Lower end.
        min: f64,
        /// Upper end.
        max: f64,
    },
    /// Each element of a sequence above the one before it (the value is the first that is not).
    StrictlyIncreasing,
    /// A sequence with `min` to `max` elements (the value is the count it has).
    Count {
        /// The fewest elements accepted.
        min: usize,
        /// The most elements accepted.
        max: usize,
    },
    /// A sequence whose length is a multiple of `slice` (one slice per order), with 1 to
    /// `max_slices` slices (the value is the length it has).
    Slices {
        /// The length of one slice.
        slice: usize,
        /// The most slices accepted.
        max_slices: usize,
    },
    /// A sum over orders at most `bound` (the value is the largest sum found).
    SumAtMost {
        /// The largest sum accepted.
        bound: f64,
    },
    /// Zero where the given order is evanescent (the value is the nonzero one found).
    ZeroWhereEvanescent {
        /// The diffraction order.
        order: i32,
    },
    /// Zero where the given order is evanescent at a node of a conical table, whose order m
    /// leaves with α_m = s·√(1 − β²) + m·λ/d and β (the value is the nonzero one found).
    ZeroWhereEvanescentConical {
        /// The diffraction order.
        order: i32,
    },
    /// A whole number of `[beta][lambda][sin_theta_i]` slices of a conical table, one per order.
    ConicalSlices {
        /// The length of one slice.
        slice: usize,
        /// The most slices accepted.
        max_slices: usize,
    },
    /// A whole number of `[plane][lambda][sin_theta_i]` slices of a reduced conical table
    /// (version 3: each |β| plane with its own wavelength rows), one per order.
    PlaneSlices {
        /// The length of one slice (n_s times the rows of every plane).
        slice: usize,
        /// The most slices accepted.
        max_slices: usize,
    },
    /// A reduced conical table's plane `plane` (its wavelength nodes `lambda_nm[plane]`) must
    /// reach from `min` to `max` nm: the wavelengths that the queries of the table's band in the
    /// cells beside the plane read there (the value is the plane's end node that falls short).
    PlaneCovers {
        /// The plane (index into `abs_beta`).
        plane: usize,
        /// The shortest wavelength the plane must hold, nm.
        min: f64,
        /// The longest wavelength the plane must hold, nm.
        max: f64,
    },
    /// An element of plane `plane`'s wavelength nodes (`lambda_nm[plane]`) of a reduced conical
    /// table: the plane has 2 to `relief::MAX_TABLE_NODES` finite
    /// wavelengths > 0, strictly increasing (the value is the first that is not, or the count).
    PlaneNodes {
        /// The plane (index into `abs_beta`).
        plane: usize,
    },
    /// The same at every wavelength (a groove spread other than a coherence length, whose
    /// width λ/L changes with λ): the value is the rejected length.
    IndependentOfWavelength,
    /// Order efficiencies that are the same at every incidence and wavelength (the amplitude
    /// reading): a colour table of a tabulated model, whose colour depends on the incidence
    /// too, has no stored form. The value is the number of orders the table stores.
    NotTabulated,
    /// A classical table (efficiencies of incidences in the plane of the grating vector, no
    /// conical slices): a reduced table is read from one.
    /// The value is the number of orders the table stores.
    Classical,
}

impl Error {
    pub(crate) fn invalid(name: &'static str, value: f64, requirement: Requirement) -> Self {
        Error::InvalidParameter {
            name,
            value,
            requirement,
        }
    }

    /// The name of the rejected parameter.
    ///
    /// ```
    /// use diffraction::Band;
    /// assert_eq!(Band::new(400.0, f64::NAN).unwrap_err().parameter(), "max_nm");
    /// ```
    #[must_use]
    pub fn parameter(&self) -> &'static str {
        match self {
            Error::InvalidParameter { name, .. } => name,
        }
    }

    /// The rejected value.
    ///
    /// ```
    /// use diffraction::Grating;
    /// assert_eq!(Grating::new(-5.0, 1.0, 1).unwrap_err().value(), -5.0);
    /// assert_eq!(Grating::new(1600.0, 800.0, 0).unwrap_err().value(), 0.0);
    /// ```
    #[must_use]
    pub fn value(&self) -> f64 {
        match self {
            Error::InvalidParameter { value, .. } => *value,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::InvalidParameter {
                name,
                value: count,
                requirement: Requirement::Count { min, max },
            } => {
                write!(f, "invalid {name}: has {count} values, must have ")?;
                if min == max {
                    write!(f, "{min}")
                } else {
                    write!(f, "{min} to {max}")
                }
            }
            Error::InvalidParameter {
                name,
                value: len,
                requirement: Requirement::Slices { slice, max_slices },
            } => write!(
                f,
                "invalid {name}: has {len} values, must have a multiple of {slice} \
                 (one [lambda][sin_theta_i] slice per order), 1 to {max_slices} slices"
            ),
            Error::InvalidParameter {
                name,
                value: len,
                requirement: Requirement::ConicalSlices { slice, max_slices },
            } => write!(
                f,
                "invalid {name}: has {len} values, must have a multiple of {slice} \
                 (one [abs_beta][lambda][sin_theta_i] slice per order), 1 to {max_slices} slices"
            ),
            Error::InvalidParameter {
                name,
                value: len,
                requirement: Requirement::PlaneSlices { slice, max_slices },
            } => write!(
                f,
                "invalid {name}: has {len} values, must have a multiple of {slice} \
                 (one [plane][lambda][sin_theta_i] slice per order), 1 to {max_slices} slices"
            ),
            Error::InvalidParameter {
                name,
                requirement: Requirement::NotTabulated,
                ..
            } => write!(
                f,
                "invalid {name}: tabulated order efficiencies depend on the incidence and the \
                 wavelength, so the colour is no function of u alone (a colour table of them \
                 has no stored form: rebuild it)"
            ),
            Error::InvalidParameter {
                name,
                value,
                requirement,
            } => {
                write!(f, "invalid {name} = {}: must ", Num(*value))?;
                match requirement {
                    Requirement::Positive => write!(f, "be finite and > 0"),
                    Requirement::Finite => write!(f, "be finite"),
                    Requirement::NonNegative => write!(f, "be finite and >= 0"),
                    Requirement::AtLeastOne => write!(f, "be at least 1"),
                    Requirement::AtMost { bound_name, bound } => {
                        write!(f, "satisfy 0 < {name} <= {bound_name} ({})", Num(*bound))
                    }
                    Requirement::AtLeast { bound_name, bound } => {
                        write!(f, "satisfy {name} >= {bound_name} ({})", Num(*bound))
                    }
                    Requirement::GreaterThan { bound_name, bound } => {
                        write!(f, "satisfy {name} > {bound_name} ({})", Num(*bound))
                    }
                    Requirement::Within { min, max } => {
                        write!(f, "lie in [{}, {}]", Num(*min), Num(*max))
                    }
                    Requirement::StrictlyIncreasing => {
                        write!(f, "be strictly increasing (above the value before it)")
                    }
                    Requirement::SumAtMost { bound } => {
                        write!(f, "be a sum over orders <= {}", Num(*bound))
                    }
                    Requirement::ZeroWhereEvanescent { order } => write!(
                        f,
                        "be 0: order {order} is evanescent there (|sin_theta_i + m lambda/d| >= 1)"
                    ),
                    Requirement::ZeroWhereEvanescentConical { order } => write!(
                        f,
                        "be 0: order {order} is evanescent there \
                         ((sin_theta_i sqrt(1 - beta^2) + m lambda/d)^2 + beta^2 >= 1)"
                    ),
                    Requirement::PlaneCovers { plane, min, max } => write!(
                        f,
                        "let plane {plane} (lambda_nm[{plane}]) reach from {} to {} nm, the \
                         wavelengths the band's queries in the cells beside it read there",
                        Num(*min),
                        Num(*max)
                    ),
                    Requirement::PlaneNodes { plane } => write!(
                        f,
                        "be in plane {plane} (lambda_nm[{plane}]): 2 to 4096 finite wavelengths \
                         > 0, strictly increasing"
                    ),
                    // Printed by the arms above.
                    Requirement::Count { .. }
                    | Requirement::Slices { .. }
                    | Requirement::ConicalSlices { .. }
                    | Requirement::PlaneSlices { .. }
                    | Requirement::NotTabulated => Ok(()),
                    Requirement::IndependentOfWavelength => {
                        write!(f, "be the same at every wavelength")
                    }
                    Requirement::Classical => write!(
                        f,
                        "be a classical table (one plane across the grooves, no |β| planes)"
                    ),
                }
            }
        }
    }
}

impl core::error::Error for Error {}

/// A number as a person reads it in a message: the shortest round-trip form, in scientific
/// notation when it is very large or very small (so `f64::MAX` prints as `1.7976931348623157e308`,
/// not as 309 digits, and a subnormal as `5e-324`).
pub(crate) struct Num(pub(crate) f64);

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

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, Requirement::Positive))
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, Requirement::Finite))
    }
}
