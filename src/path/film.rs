//! The film of a spectral renderer ([`SpectralFilm`]).

use crate::data::cie::{self, Illuminant};

/// The film of a spectral renderer: the weight that turns a radiance sample at one wavelength
/// into CIE XYZ, normalised like the crate's reference colour
/// ([`Spectral`](crate::spectrum::Spectral)), for one illuminant.
///
/// The reference colour of a spectral reflectance I(λ) under an illuminant E(λ) is
/// XYZ = ∫ E·I·cmf dλ / ∫ E·ȳ dλ over 360-830 nm, so a perfect white reflector has Y = 1. A path
/// tracer that carries radiance **relative to the illuminant** (its lights emit 1, meaning
/// "E(λ)") estimates it from wavelength samples λ with density p(λ) as the mean of
/// I(λ)·w(λ)/p(λ), with the film weight
///
/// ```text
/// w(λ) = E(λ) · cmf(λ) / ∫ E·ȳ dλ          (1/nm)
/// ```
///
/// [`weight`](Self::weight) is w, with ∫E·ȳ computed once (exact for the linear interpolation
/// of the 1 nm tables: the number `Spectral` normalises with);
/// [`SampledSpectrum::to_xyz`](crate::SampledSpectrum::to_xyz) applies it to a path's four
/// wavelengths. With [`Illuminant::E`] the weight is cmf/∫ȳ: the film of a renderer whose lights
/// carry their own absolute spectra.
///
/// ```
/// use diffraction::cie::Illuminant;
/// use diffraction::SpectralFilm;
/// let film = SpectralFilm::new(Illuminant::D65);
/// assert_eq!(film.illuminant(), Illuminant::D65);
/// // A white reflector sampled uniformly over the band: Y = 1 (midpoint rule on 1 nm steps).
/// let y: f64 = (0..470).map(|i| film.weight(360.5 + i as f64)[1]).sum();
/// assert!((y - 1.0).abs() < 1e-4);
/// assert_eq!(film.weight(900.0), [0.0; 3]); // outside the band
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpectralFilm {
    illuminant: Illuminant,
    /// 1 / ∫ E·ȳ dλ.
    norm: f64,
}

impl SpectralFilm {
    /// The film for `illuminant` (a sum over the 470 rows of the tables: build it once).
    ///
    /// ```
    /// use diffraction::cie::{cmf, cmf_areas, Illuminant};
    /// use diffraction::SpectralFilm;
    /// let film = SpectralFilm::new(Illuminant::E);
    /// let [_, ybar, _] = cmf_areas();
    /// assert!((film.weight(555.0)[1] - cmf(555.0)[1] / ybar).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn new(illuminant: Illuminant) -> SpectralFilm {
        let y = cie::integrate_product_of_rows(
            |i| cie::illuminant_row(illuminant, i),
            |i| cie::cmf_row(i, 1),
        );
        SpectralFilm {
            illuminant,
            norm: 1.0 / y,
        }
    }

    /// The illuminant.
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// use diffraction::SpectralFilm;
    /// assert_eq!(SpectralFilm::new(Illuminant::D65).illuminant(), Illuminant::D65);
    /// ```
    #[must_use]
    pub fn illuminant(&self) -> Illuminant {
        self.illuminant
    }

    /// The weight w(λ) = E(λ)·(x̄, ȳ, z̄)(λ)/∫E·ȳ, 1/nm; [0, 0, 0] outside 360-830 nm and for NaN.
    ///
    /// ```
    /// use diffraction::cie::Illuminant;
    /// use diffraction::SpectralFilm;
    /// let film = SpectralFilm::new(Illuminant::D65);
    /// let [x, y, z] = film.weight(600.0);
    /// assert!(x > y && y > 0.0 && z < 0.01 * y); // orange: almost no z̄ at 600 nm
    /// assert_eq!(film.weight(f64::NAN), [0.0; 3]);
    /// ```
    #[inline]
    #[must_use]
    pub fn weight(&self, lambda_nm: f64) -> [f64; 3] {
        let e = self.illuminant.power(lambda_nm) * self.norm;
        cie::cmf(lambda_nm).map(|c| e * c)
    }
}
