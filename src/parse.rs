//! The error of parsing one of the crate's named choices from a string.

use core::fmt;

/// A string is not one of the names a [`FromStr`](core::str::FromStr) implementation of the
/// crate accepts ([`Clip`](crate::color::Clip), [`Illuminant`](crate::data::cie::Illuminant)).
///
/// It says what was being parsed and lists the accepted spellings. It does not hold the rejected
/// input (the library allocates nothing); the caller has it and can print it beside this message.
///
/// ```
/// use diffraction::cie::Illuminant;
/// use diffraction::color::Clip;
/// use diffraction::ParseError;
///
/// let err: ParseError = "hard".parse::<Clip>().unwrap_err();
/// assert_eq!(err.what(), "clipping scheme");
/// assert_eq!(
///     err.to_string(),
///     "unknown clipping scheme: expected one of \"clamp\", \"intensity\", \"constant\""
/// );
/// let err: ParseError = "D50".parse::<Illuminant>().unwrap_err();
/// assert_eq!(err.what(), "illuminant");
/// assert_eq!(err.expected(), "one of E, D65, A");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParseError {
    what: &'static str,
    expected: &'static str,
    /// For a known name with a number out of its range: the number as parsed.
    out_of_range: Option<f64>,
}

impl ParseError {
    /// The error for a `what` (a noun phrase: "illuminant") whose accepted spellings are
    /// described by `expected` ("one of E, D65, A").
    pub(crate) const fn new(what: &'static str, expected: &'static str) -> Self {
        ParseError {
            what,
            expected,
            out_of_range: None,
        }
    }

    /// The error for a known name whose number `value` (a noun phrase `what`: "uniform count")
    /// lies outside its range `expected` ("1 to 65536").
    pub(crate) const fn number_out_of_range(
        what: &'static str,
        value: f64,
        expected: &'static str,
    ) -> Self {
        ParseError {
            what,
            expected,
            out_of_range: Some(value),
        }
    }

    /// The number that was out of range, where the name was known and only its number was not
    /// accepted (`None` for an unknown name).
    ///
    /// ```
    /// use diffraction::spectrum::Strategy;
    /// let e = "uniform:99999999999".parse::<Strategy>().unwrap_err();
    /// assert_eq!(e.out_of_range(), Some(99999999999.0));
    /// assert_eq!(e.to_string(), "uniform count 99999999999 is out of range: expected 1 to 65536");
    /// assert_eq!("simpson".parse::<Strategy>().unwrap_err().out_of_range(), None);
    /// ```
    #[must_use]
    pub const fn out_of_range(&self) -> Option<f64> {
        self.out_of_range
    }

    /// What was being parsed, e.g. `"clipping scheme"` or `"illuminant"`.
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// assert_eq!("Clamp".parse::<Clip>().unwrap_err().what(), "clipping scheme");
    /// ```
    #[must_use]
    pub const fn what(&self) -> &'static str {
        self.what
    }

    /// The accepted spellings, as the message lists them.
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// let err = "gamma".parse::<Clip>().unwrap_err();
    /// assert_eq!(err.expected(), "one of \"clamp\", \"intensity\", \"constant\"");
    /// ```
    #[must_use]
    pub const fn expected(&self) -> &'static str {
        self.expected
    }
}

impl fmt::Display for ParseError {
    /// `unknown {what}: expected {expected}`, or for a number out of range
    /// `{what} {value} is out of range: expected {expected}`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.out_of_range {
            None => write!(f, "unknown {}: expected {}", self.what, self.expected),
            Some(v) => write!(
                f,
                "{} {} is out of range: expected {}",
                self.what,
                crate::error::Num(v),
                self.expected
            ),
        }
    }
}

impl core::error::Error for ParseError {}
