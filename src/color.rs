//! Colour: CIE XYZ, linear and encoded sRGB, gamut clipping, and (feature `delta-e`) CIELAB and
//! ΔE2000.
//!
//! # Types
//!
//! * [`Xyz`]: CIE 1931 XYZ tristimulus values, *relative*: a perfect white reflector under the
//!   illuminant has Y = 1. Spectral integration accumulates these (`+`, `+=`, `* f64`).
//! * [`LinearSrgb`]: linear-light sRGB. May be **out of gamut** (negative or above 1); nothing
//!   clips it behind your back.
//! * [`Srgb`]: encoded (non-linear, "gamma") sRGB, what image files and displays take.
//! * `Lab` (feature `delta-e`): CIE 1976 L\*a\*b\*, with the CIEDE2000 colour difference
//!   `Lab::delta_e2000`, the crate's unit of colour error.
//! * `WhitePoint` (feature `delta-e`): a validated reference white for CIELAB (finite, positive
//!   components).
//! * [`Clip`]: the three gamut-clipping schemes of Hall (1989).
//!
//! # Pipeline
//!
//! ```text
//! spectrum ──∫ E·I·cmf dλ──▶ Xyz ──to_linear_srgb──▶ LinearSrgb ──clip(Clip)──▶ LinearSrgb
//!                                                                 (in [0,1]³)
//!          ──encode──▶ Srgb ──to_rgb8──▶ [u8; 3]
//! ```
//!
//! ```
//! use diffraction::color::{Clip, Xyz};
//!
//! // A saturated green-cyan, roughly what a 500 nm spectral line looks like: far outside sRGB.
//! let xyz = Xyz::new(0.0049, 0.323, 0.272);
//! let linear = xyz.to_linear_srgb();
//! assert!(linear.r < 0.0 && !linear.is_in_gamut());
//!
//! // Clipping is an explicit, chosen step; then encode and quantise.
//! let clipped = linear.clip(Clip::ConstantIntensity);
//! assert!(clipped.is_in_gamut());
//! assert!((clipped.luminance() - linear.luminance()).abs() < 1e-12); // luminance survives
//! let rgb8 = clipped.encode().to_rgb8();
//! assert_eq!(rgb8[0], 0);
//! ```
//!
//! # Why clipping is explicit
//!
//! Pure spectral colours, which is what a diffraction grating shows, all lie outside the sRGB
//! gamut: every one has at least one negative linear component, and bright peaks exceed 1. *How*
//! such a colour is brought into the gamut changes the picture visibly (hue shifts, lost
//! brightness, or lost saturation), so no conversion here clips silently: [`Xyz::to_linear_srgb`]
//! and [`LinearSrgb::encode`] are unbounded, [`LinearSrgb::is_in_gamut`] tells whether a colour
//! needs clipping, and [`LinearSrgb::clip`] does it with the scheme you name. Only the final
//! quantisation [`Srgb::to_rgb8`] clamps, because a byte cannot hold anything else.
//!
//! Linear and encoded sRGB are distinct types, so encoding twice or forgetting to encode is a
//! type error:
//!
//! ```compile_fail,E0308
//! use diffraction::color::{LinearSrgb, Srgb};
//!
//! fn to_pixel(c: Srgb) -> [u8; 3] {
//!     c.to_rgb8()
//! }
//! let linear = LinearSrgb::new(0.5, 0.2, 0.1);
//! to_pixel(linear); // error: expected `Srgb`, found `LinearSrgb`
//! ```
//!
//! ```
//! # use diffraction::color::{LinearSrgb, Srgb};
//! # fn to_pixel(c: Srgb) -> [u8; 3] { c.to_rgb8() }
//! let linear = LinearSrgb::new(0.5, 0.2, 0.1);
//! assert_eq!(to_pixel(linear.encode()), [188, 124, 89]);
//! ```
//!
//! # Extreme values
//!
//! No function here returns NaN for finite input. The linear maps ([`Xyz::to_linear_srgb`],
//! [`LinearSrgb::to_xyz`], `+`, `*`, `scale`) are exact to rounding and give ±∞ only where the
//! exact value exceeds f64::MAX (the plain overflow of the caller's own huge values). Everything
//! else is finite for every finite input: [`srgb_decode`], `Xyz::to_lab` and
//! [`LinearSrgb::luminance`] saturate at ±f64::MAX where the exact value lies beyond it,
//! `Lab::delta_e2000` clamps its components to ±1e150, [`Xyz::chromaticity`] is `None` where the
//! coordinates would overflow, and a CIELAB white with a zero, negative or non-finite component
//! is rejected by `WhitePoint::new` with an error naming it.
//!
//! ```
//! use diffraction::color::srgb_decode;
//! assert_eq!(srgb_decode(1e300), f64::MAX);
//! # #[cfg(feature = "delta-e")] {
//! use diffraction::color::{Lab, WhitePoint, Xyz};
//! assert!(Lab::new(50.0, 1e50, 0.0).delta_e2000(Lab::default()).is_finite());
//! assert_eq!(WhitePoint::new(Xyz::default()).unwrap_err().parameter(), "white.x");
//! # }
//! ```
//!
//! # Reference
//!
//! The matrices, the transfer function, CIELAB and ΔE2000 follow colour-science 0.4
//! (`tests/color_reference.rs` compares against fixtures it produced), with two documented
//! differences in the transfer function: negative values are mirrored rather than continued
//! linearly, and the decoding threshold is the standard's 0.04045 (see [`srgb_encode`],
//! [`srgb_decode`]).

mod clip;
#[cfg(feature = "delta-e")]
mod lab;
mod srgb;
#[cfg(all(test, feature = "delta-e"))]
mod tests;
mod xyz;

pub use clip::Clip;
#[cfg(feature = "delta-e")]
pub use lab::{Lab, WhitePoint};
pub use srgb::{srgb_decode, srgb_encode, LinearSrgb, Srgb};
pub use xyz::Xyz;
