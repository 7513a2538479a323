//! A wavelength band: the interval of wavelengths over which peaks are searched and colour is
//! integrated.

use crate::error::{positive, Error, Requirement};

/// A wavelength band [min_nm, max_nm], validated: 0 < min < max, both finite, and at least
/// [`Band::MIN_WIDTH_NM`] wide (so that the uniform density 1/(max − min) is finite).
///
/// ```
/// use diffraction::Band;
/// assert_eq!(Band::VISIBLE.min_nm(), 360.0);
/// let b = Band::new(400.0, 700.0)?;
/// assert!(b.contains(550.0) && !b.contains(750.0));
/// assert_eq!(Band::new(700.0, 400.0).unwrap_err().parameter(), "max_nm");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Band {
    min_nm: f64,
    max_nm: f64,
}

impl Band {
    /// The band of the CIE 1931 tables, 360-830 nm, over which the crate integrates colour.
    ///
    /// ```
    /// use diffraction::Band;
    /// assert_eq!((Band::VISIBLE.min_nm(), Band::VISIBLE.max_nm()), (360.0, 830.0));
    /// assert_eq!(Band::VISIBLE, Band::new(360.0, 830.0)?);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub const VISIBLE: Band = Band {
        min_nm: 360.0,
        max_nm: 830.0,
    };

    /// The narrowest accepted band, nm (a femtometre): `max_nm − min_nm` must be at least this,
    /// so that the density 1/(max − min) of a uniform wavelength (for example
    /// [`SampledWavelengths::sample_uniform`](crate::SampledWavelengths::sample_uniform)) is
    /// at most 10⁶ per nm, finite with room for the products a renderer makes with it. A band
    /// is an integration range; one narrower than this resolves nothing a colour could show
    /// (at 360 nm it is 3·10⁻⁹ of the wavelength).
    ///
    /// ```
    /// use diffraction::Band;
    /// assert!(Band::new(500.0, 500.00001).is_ok()); // 10⁻⁵ nm wide
    /// assert!(Band::new(500.0, 500.0000001).is_err()); // 10⁻⁷ nm
    /// assert_eq!(Band::new(5e-324, 1e-323).unwrap_err().parameter(), "max_nm");
    /// ```
    pub const MIN_WIDTH_NM: f64 = 1e-6;

    /// A custom band; rejects non-finite or non-positive ends, `max_nm <= min_nm` and bands
    /// narrower than [`MIN_WIDTH_NM`](Self::MIN_WIDTH_NM) (both reported as `max_nm`).
    ///
    /// ```
    /// use diffraction::Band;
    /// let b = Band::new(380.0, 780.0)?;
    /// assert_eq!((b.min_nm(), b.max_nm()), (380.0, 780.0));
    /// assert_eq!(Band::new(0.0, 780.0).unwrap_err().parameter(), "min_nm");
    /// assert_eq!(Band::new(500.0, 500.0).unwrap_err().parameter(), "max_nm"); // empty
    /// assert_eq!(
    ///     Band::new(500.0, 500.0000000001).unwrap_err().to_string(),
    ///     "invalid max_nm = 500.0000000001: must satisfy max_nm >= min_nm + Band::MIN_WIDTH_NM (500.000001)"
    /// );
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(min_nm: f64, max_nm: f64) -> Result<Band, Error> {
        let min_nm = positive("min_nm", min_nm)?;
        let max_nm = positive("max_nm", max_nm)?;
        if max_nm <= min_nm {
            return Err(Error::invalid(
                "max_nm",
                max_nm,
                Requirement::GreaterThan {
                    bound_name: "min_nm",
                    bound: min_nm,
                },
            ));
        }
        // max − min is exact or rounds down by at most half an ulp of max: a band that passes
        // has a width of at least MIN_WIDTH_NM·(1 − 2⁻⁵³).
        if max_nm - min_nm < Band::MIN_WIDTH_NM {
            return Err(Error::invalid(
                "max_nm",
                max_nm,
                Requirement::AtLeast {
                    bound_name: "min_nm + Band::MIN_WIDTH_NM",
                    bound: min_nm + Band::MIN_WIDTH_NM,
                },
            ));
        }
        Ok(Band { min_nm, max_nm })
    }

    /// Shortest wavelength, nm.
    ///
    /// ```
    /// use diffraction::Band;
    /// assert_eq!(Band::new(400.0, 700.0)?.min_nm(), 400.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn min_nm(self) -> f64 {
        self.min_nm
    }

    /// Longest wavelength, nm.
    ///
    /// ```
    /// use diffraction::Band;
    /// assert_eq!(Band::new(400.0, 700.0)?.max_nm(), 700.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn max_nm(self) -> f64 {
        self.max_nm
    }

    /// `max_nm - min_nm`.
    ///
    /// ```
    /// use diffraction::Band;
    /// assert_eq!(Band::VISIBLE.width_nm(), 470.0);
    /// assert_eq!(Band::new(400.0, 700.0)?.width_nm(), 300.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn width_nm(self) -> f64 {
        self.max_nm - self.min_nm
    }

    /// Whether `min_nm <= lambda_nm <= max_nm`.
    ///
    /// ```
    /// use diffraction::Band;
    /// let b = Band::VISIBLE;
    /// assert!(b.contains(360.0) && b.contains(830.0)); // both ends belong to the band
    /// assert!(!b.contains(830.5) && !b.contains(f64::NAN));
    /// ```
    #[must_use]
    pub fn contains(self, lambda_nm: f64) -> bool {
        self.min_nm <= lambda_nm && lambda_nm <= self.max_nm
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Band {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        struct Raw {
            min_nm: f64,
            max_nm: f64,
        }
        let raw = Raw::deserialize(d)?;
        Band::new(raw.min_nm, raw.max_nm).map_err(serde::de::Error::custom)
    }
}
