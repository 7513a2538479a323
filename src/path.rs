//! The path tracer's spectral kit: a path's four wavelengths, visible-wavelength sampling,
//! the values at the four wavelengths and the spectral film weight.

pub(crate) mod film;
pub(crate) mod sampled_spectrum;
pub mod visible;
pub(crate) mod wavelengths;
