//! # diffraction
//!
//! Closed-form, numerically robust shading of diffraction gratings after Agu & Hill,
//! "A Simple Method for Ray Tracing Diffraction": the Huygens-Fresnel intensity of N slits,
//!
//! I(u, λ) = S(β) · F_N(α),  S(β) = (sin β / β)²,  F_N(α) = sin²(Nα) / (N² sin²α),
//!
//! with α = π·d·u/λ, β = π·w·u/λ and u = (wi + wo)·t, used as the diffraction term of an
//! ambient + diffuse + diffraction illumination model.
//!
//! ## Conventions
//!
//! * Lengths and wavelengths are in **nanometres** (names end in `_nm`), angles in radians.
//! * Local shading frame: `z` is the surface normal, `x` the **grating vector** `t` (in the
//!   tangent plane, across the grooves), `y` the groove direction.
//! * `wi` points toward the light, `wo` toward the viewer, both unit and above the surface.
//! * The phase projection is **u = (wi + wo)·t**; u = 0 is the mirror direction. In the paper's
//!   angles u = sin θ − sin θi. The paper's step 5 uses the normalised half vector instead, which
//!   misplaces the peaks by the factor |wi + wo|; this crate uses the exact u
//!   ([`frame::paper_half_vector_projection`] exists only to document the difference).
//!
//! ## Quick start
//!
//! ```
//! use diffraction::{Band, Grating};
//!
//! // A 600 lines/mm ruled grating, half-open slits, 10 000 illuminated periods.
//! let g = Grating::new(1666.67, 833.33, 10_000)?;
//! // Where does the first order of 532 nm light go at normal incidence? sin θ = λ/d.
//! let u = 532.0 / 1666.67;
//! let first = g.peaks(u, Band::VISIBLE).next().unwrap();
//! assert_eq!(first.order, 1);
//! assert!((first.wavelength_nm - 532.0).abs() < 1e-9);
//! // The intensity there is the single-slit envelope S(β₁) (F_N = 1 at every maximum).
//! assert!((g.intensity(u, 532.0) - first.intensity).abs() < 1e-12);
//! # Ok::<(), diffraction::Error>(())
//! ```
//!
//! ## What to use for what
//!
//! * **The paper's pictures** (unitless intensity, the paper's eq. 12): [`AguHill`] with
//!   [`Illumination`], colours by [`Spectral::xyz`](spectrum::Spectral::xyz) with a
//!   [`Strategy`](spectrum::Strategy) (or the paper's own peak colours,
//!   [`Spectral::paper_peaks`](spectrum::Spectral::paper_peaks)). The minimal example
//!   `examples/whitted.rs` and the full reference ray tracer (`tools/render`) do exactly this.
//! * **A spectral path tracer** (physical units): [`GratingBsdf`], a [`Bsdf`] with an exact
//!   sampling density: `eval(wo, wi, λ)`, `sample`, `pdf`, and four wavelengths at once
//!   ([`Bsdf::sample4`], `eval4`, `pdf4`) with [`SampledWavelengths`] (uniform or
//!   [`visible`]-importance sampled); [`HeroMis`] gives the hero-wavelength MIS weights of BSDF
//!   and light samples along a path, [`SampledSpectrum`] carries the four values and
//!   [`SampledSpectrum::to_xyz`] with a [`SpectralFilm`] turns them into the film's XYZ. The
//!   recipe, with its furnace tests, is in [`HeroMis`]'s docs and `docs/radiometry.md`; a
//!   wavelength sampler from the grating's own response is [`GratingBsdf::sample_wavelength`].
//! * **An RGB renderer**: a [`ColorTable`] per grating material (feature `alloc`, on with `std`):
//!   the colour XYZ(u) in nanoseconds a lookup, with the footprint mean for antialiasing over the
//!   interval of u a pixel sees ([`footprint::u_interval`], from its ray differentials and the
//!   light's size), then [`color`]'s conversion and Hall's clipping; in physical units, for the
//!   radiometric [`GratingBsdf`] (Gaussian or ideal groove, finite N or N = ∞), the same
//!   [`ColorTable`] built from the BSDF ([`TableSource`]): the colour per unit of cos θi·g(v).
//!   Tables can be cached (feature `serde`).
//! * **Real time**: the same table, or the slit kernels ([`kernel`], `f32` and `f64`) evaluated at
//!   a few wavelengths.
//! * **How bright each order of a real grating is** (a relief on a metal, TE and TM; feature
//!   `relief`): `relief::ScalarRelief` (a sinusoid, lamellar, sawtooth, Fourier or sampled
//!   profile on a `relief::Metal`: Al, Ag, Au, Cu, Cr or n + ik) gives the order efficiencies
//!   η_m by scalar diffraction, never above the metal's reflectance, and `is_valid` says whether
//!   a query lies in the region where they were measured within 10 % of rigorous
//!   electromagnetics (`docs/validity.md`); outside it use rigorous tables
//!   (`relief::EfficiencyTable`, `python_ref/efficiencies.py`; the four shipped ones, feature
//!   `presets`: `relief::Preset`, `GratingBsdf::preset`). `examples/efficiencies` prints them.
//! * **Your own model**: implement [`DiffractionBrdf`] (and [`SpectralResponse`] to get its
//!   colour, [`Bsdf`] to sample it); `ARCHITECTURE.md` in the repository says how.
//!
//! ## Modules
//!
//! One concept per file; `ARCHITECTURE.md` in the repository says what flows where.
//!
//! * [`kernel`]: the two factors S and F_N, stable in `f32` and `f64`, with stated accuracy.
//! * [`Band`]: a wavelength band.
//! * [`GratingEquation`], [`Order`]: the grating equation d·u = m·λ, the orders every model
//!   shares (orders of a u inside a band, propagating directions of an incidence).
//! * [`Grating`], [`Peak`]: the paper's grating, its intensity I(u, λ) and its peaks.
//! * [`frame`]: the phase projection and grating-direction fields (constant, twisted, radial
//!   tracks of a CD, checkerboards).
//! * [`DiffractionBrdf`]: the value interface every model implements, `eval(wo, wi, λ)`; the
//!   models [`AguHill`] (the paper's), [`GratingBsdf`] (energy-normalised, for path tracers)
//!   and, with the feature `baselines`, `Thorman` (peak directions only, every order equally
//!   bright) and `Stam` (Fourier optics for sinusoidal and binary profiles, in `stam`).
//! * [`Bsdf`], [`BsdfSample`], [`BsdfSample4`], [`BsdfFlags`]: the samplable interface for path
//!   tracers (pbrt-v4's BxDF shape), with [`GrooveSpread`] (the lobes along the grooves) and
//!   [`grating_bsdf`] (the grating BSDF's parts: order efficiencies, sampling, albedo,
//!   wavelength sampling, regularisation).
//! * [`SampledWavelengths`], [`visible`], [`SampledSpectrum`], [`SpectralFilm`], [`HeroMis`]: a
//!   spectral path's four wavelengths, their values, the film's XYZ and the MIS weights.
//! * `relief` (feature `relief`): relief gratings on real metals: `relief::Metal` (n + ik,
//!   Fresnel), `relief::Relief` (profile shapes and their phase screens),
//!   `relief::ScalarRelief` (order efficiencies by scalar diffraction, with their measured valid
//!   region), `relief::EfficiencyTable` (tabulated efficiencies) and, feature `presets`,
//!   `relief::Preset` (the shipped rigorous tables).
//! * [`footprint`]: the interval of u a pixel sees, for footprint-filtered colour lookups.
//! * [`SpectralResponse`], [`GratingResponse`], [`Envelope`], [`PeakSummary`]: what the colour
//!   integrator needs of a model.
//! * [`Illumination`]: the paper's illumination model (eq. 12), ambient + diffuse + diffraction
//!   around any model.
//! * [`cie`]: the CIE 1931 2° observer and illuminants E, D65, A at 1 nm (from colour-science).
//! * [`spectrum`]: the reference colour XYZ of a grating or of any model, by named strategies
//!   with stated cost and bound (`spectrum::bounds`).
//! * [`ColorTable`], [`TableSource`]: a grating's colour tabulated once (the paper's, or the
//!   radiometric BSDF's in physical units), O(1) lookups and footprint means.
//! * [`color`]: XYZ, linear and encoded sRGB, Hall's clipping schemes, and (feature
//!   `delta-e`) CIELAB and ΔE2000.
//!
//! ## From a hit point to a pixel
//!
//! ```
//! use diffraction::color::Clip;
//! use diffraction::frame::{GratingField, ShadingFrame};
//! use diffraction::glam::{DVec2, DVec3};
//! use diffraction::spectrum::{Illuminant, Spectral, Strategy};
//! use diffraction::Grating;
//!
//! let cd = Grating::new(1600.0, 800.0, 1000)?;
//! let field = GratingField::radial(DVec2::ZERO); // CD tracks around the spindle
//! let spectral = Spectral::new(Illuminant::D65);
//!
//! // A hit at surface point p on a disc lying in the xz-plane (normal +y).
//! let p = DVec2::new(0.03, 0.01);
//! let t = field.world_direction(p, DVec3::X, DVec3::Z).unwrap();
//! let frame = ShadingFrame::new(DVec3::Y, t).unwrap();
//! let wi = frame.to_local(DVec3::new(-0.3, 1.0, 0.1).normalize()); // toward the light
//! let wo = frame.to_local(DVec3::new(0.6, 0.7, 0.2).normalize()); // toward the eye
//! let u = wi.x + wo.x;
//!
//! let xyz = spectral.xyz(&cd, u, Strategy::auto(1e-3)?);
//! let rgb = xyz.to_linear_srgb().clip(Clip::ConstantIntensity).encode().to_rgb8();
//! # let _ = rgb;
//! # Ok::<(), diffraction::Error>(())
//! ```
//!
//! ## Feature flags
//!
//! * `std` (default): maths from the standard library; implies `alloc`.
//! * `alloc`: heap storage for [`ColorTable`], for `no_std` targets with an allocator.
//! * `libm`: maths from the `libm` crate, for `no_std` (disable default features).
//! * `serde`: `Serialize`/`Deserialize` for the parameter types, validated on the way in, and
//!   (with `alloc`) for the colour tables, as caches with a format version.
//! * `relief`: order efficiencies of relief gratings on metals (`relief`: the scalar model, the
//!   metals, `EfficiencyTable`) and the grating BSDF's tabulated efficiencies
//!   (`grating_bsdf::OrderEfficiency::Tabulated`, `OrderEfficiency::from_static`, `from_table`).
//! * `presets` (implies `relief`): the four rigorous efficiency tables the crate ships
//!   (`relief::Preset`, `OrderEfficiency::preset`, `GratingBsdf::preset`; 4.7k lines of static
//!   data).
//! * `baselines`: the related work the paper argues against, `Thorman` and Stam's model
//!   (`Stam`, `Profile`, the `stam` module); works with `std` and with `libm`.
//! * `stam`: the former name of `baselines`, kept as its alias for one release (deprecated).
//! * `delta-e`: CIELAB and the CIEDE2000 colour difference (`color::Lab`, `color::WhitePoint`,
//!   `Xyz::to_lab`, `color::delta_e2000`), the unit of colour error of the crate's tests.
//!
//! None of these four adds a dependency, and the default build compiles none of them.
//!
//! One of `std` and `libm` must be enabled.
//!
//! ## Vectors
//!
//! Directions and points are `glam` 0.30's `DVec3`, `DVec2` and `Vec3`, re-exported as
//! [`diffraction::glam`](glam): use them from there, and no `glam` dependency of the renderer
//! has to match the crate's.

#![cfg_attr(not(feature = "std"), no_std)]
#![cfg_attr(docsrs, feature(doc_cfg))]

#[cfg(not(any(feature = "std", feature = "libm")))]
compile_error!("diffraction needs either the `std` (default) or the `libm` feature for its maths");

#[cfg(feature = "alloc")]
extern crate alloc;

pub mod color;
#[cfg(feature = "alloc")]
mod color_table;
mod data;
mod error;
#[cfg(feature = "gpu")]
pub mod gpu;
mod illumination;
mod model;
mod num;
mod optics;
mod parse;
mod path;
#[cfg(feature = "relief")]
pub mod relief;
pub mod spectrum;

#[cfg(feature = "alloc")]
#[allow(deprecated)]
pub use color_table::RadiometricTable;
#[cfg(feature = "alloc")]
pub use color_table::{ColorTable, TableSource};
pub use data::cie;
pub use error::{Error, Requirement};
/// The vector library of every direction and point in the API: [`glam`](https://docs.rs/glam)
/// **0.30** (`DVec3`, `DVec2`, `Vec3`), re-exported so that a renderer uses the very types the
/// crate takes, whatever `glam` it depends on itself. Write `use diffraction::glam::DVec3;`;
/// a renderer on another `glam` version (0.29, 0.31) converts at the boundary
/// (`DVec3::new(v.x, v.y, v.z)` or `DVec3::from_array`).
///
/// ```
/// use diffraction::glam::DVec3;
/// use diffraction::{DiffractionBrdf, Grating, GratingBsdf};
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
/// assert!(b.eval(DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()), 480.0) > 0.0);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub use glam;
pub use illumination::Illumination;
#[cfg(feature = "baselines")]
pub use model::stam;
pub use model::{
    bsdf, grating_bsdf, AguHill, Bsdf, BsdfFlags, BsdfSample, BsdfSample4, DiffractionBrdf,
    Envelope, GratingBsdf, GratingResponse, HeroMis, PeakSummary, SpectralResponse,
    WavelengthSample, MIN_COS_THETA,
};
#[cfg(feature = "baselines")]
pub use model::{Profile, Stam, Thorman};
pub use num::float::Float;
pub use num::kernel;
pub use num::random::unit_random;
pub use optics::band::Band;
pub use optics::footprint;
pub use optics::frame;
pub use optics::grating::{DiffractedOrder, DiffractedOrders, Grating, Peak, Peaks, Slits};
pub use optics::groove;
pub use optics::groove::{GrooveKind, GrooveSpread};
pub use optics::orders::{GratingEquation, Order, Orders, Propagating, MAX_ORDERS};
pub use parse::ParseError;
pub use path::film::SpectralFilm;
pub use path::sampled_spectrum::SampledSpectrum;
pub use path::visible;
pub use path::wavelengths::SampledWavelengths;

/// The README's examples, compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

/// The registry page's README (`README.crates-io.md`), compiled and run as doc tests.
#[cfg(doctest)]
#[doc = include_str!("../README.crates-io.md")]
pub struct PackageReadmeDoctests;
