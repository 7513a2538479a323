//! Monte-Carlo estimates of the reference colour from the caller's random numbers: stratified and
//! hero wavelengths, as spectral renderers draw them.

use glam::DVec3;

use super::{Spectral, BAND, MAX_WAVELENGTHS};
use crate::color::Xyz;
use crate::num::math::floor;
use crate::Grating;

impl Spectral {
    /// An unbiased estimate of [`xyz`](Self::xyz) from one jittered wavelength in each of
    /// `randoms.len()` equal strata of the band, `randoms` being the caller's numbers in [0, 1).
    /// A number outside [0, 1) is taken modulo 1 (so uniform numbers on any interval of integer
    /// length keep the estimate unbiased); a non-finite one contributes nothing. An empty slice
    /// gives black. The work is one evaluation per number the caller passes.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 3)?;
    /// let s = Spectral::new(Illuminant::E);
    /// let est = s.xyz_stratified(&g, 0.4, &[0.5; 64]); // midpoints: the uniform rule
    /// assert_eq!(est, s.xyz(&g, 0.4, Strategy::uniform(64)?));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_stratified(&self, grating: &Grating, u: f64, randoms: &[f64]) -> Xyz {
        let k = randoms.len();
        if k == 0 || !u.is_finite() {
            return Xyz::default();
        }
        let step = BAND.width_nm() / k as f64;
        let mut acc = DVec3::ZERO;
        for (j, &r) in randoms.iter().enumerate() {
            let Some(r) = unit_interval(r) else {
                continue;
            };
            let l = BAND.min_nm() + (j as f64 + r) * step;
            acc += self.integrand(grating, u.abs(), l) * step;
        }
        Xyz::new(acc.x, acc.y, acc.z)
    }

    /// Hero wavelengths: one random number `uc` in [0, 1) places the first of `count`
    /// wavelengths uniformly in the band and the others at equal spacing after it, wrapping
    /// around (the rotation of Wilkie et al. 2014, with pbrt-v4's `SampleUniform` for the first
    /// wavelength, not its default visible-wavelength importance sampling); an unbiased estimate
    /// of [`xyz`](Self::xyz). `uc` outside [0, 1) is taken modulo 1; a non-finite `uc` or
    /// `count` = 0 gives black. `count` is capped at [`MAX_WAVELENGTHS`]
    /// (still unbiased: fewer, equally spaced wavelengths).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{color::Xyz, Grating};
    /// let g = Grating::new(1600.0, 800.0, 3)?;
    /// let s = Spectral::new(Illuminant::E);
    /// // uc = 0.5/count puts the wavelengths at the strata midpoints: the uniform rule.
    /// let hero = s.xyz_hero(&g, 0.4, 0.5 / 8.0, 8);
    /// let uniform = s.xyz(&g, 0.4, Strategy::uniform(8)?);
    /// assert!((hero.y - uniform.y).abs() < 1e-12 * uniform.y); // same wavelengths, rounded apart
    /// assert_eq!(s.xyz_hero(&g, 0.4, 0.5, 0), Xyz::default()); // no wavelength: black
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_hero(&self, grating: &Grating, u: f64, uc: f64, count: u32) -> Xyz {
        let Some(xi) = unit_interval(uc) else {
            return Xyz::default();
        };
        let count = count.min(MAX_WAVELENGTHS);
        if count == 0 || !u.is_finite() {
            return Xyz::default();
        }
        let w = BAND.width_nm();
        let step = w / count as f64;
        let mut acc = DVec3::ZERO;
        for j in 0..count {
            let mut off = xi * w + j as f64 * step;
            if off >= w {
                off -= w;
            }
            acc += self.integrand(grating, u.abs(), BAND.min_nm() + off) * step;
        }
        Xyz::new(acc.x, acc.y, acc.z)
    }
}

/// `r` modulo 1 in [0, 1), or `None` for a non-finite `r`.
fn unit_interval(r: f64) -> Option<f64> {
    if !r.is_finite() {
        return None;
    }
    let t = r - floor(r);
    // r − floor(r) rounds up to 1 for tiny negative r.
    Some(if t < 1.0 { t } else { 0.0 })
}
