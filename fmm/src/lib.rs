//! Rigorous reflection efficiencies of 1-D periodic relief gratings: the Fourier modal method
//! (RCWA) with Li's factorisation rules, in the classical and the conical mount, with a stable
//! reflection-matrix recursion, staircased smooth profiles, metals from
//! [`diffraction::relief::Metal`], an optional thick dielectric cover, and convergence control;
//! and the C method (Chandezon) with Li's factorisation for continuous profiles (sinusoid,
//! sawtooth, Fourier series, sampled) in the classical and the conical mount, where the
//! staircase converges badly in TM on metals. [`Method::Auto`] (the default) picks the C method
//! for those and the Fourier modal method otherwise.
//!
//! Conventions (those of the `diffraction` crate's design notes): x across the grooves (the
//! grating vector), y along them, z the normal; the incident direction of travel has direction
//! cosines α = sin θ·cos φ across and β = sin θ·sin φ along the grooves; order m leaves with
//! αₘ = α + mλ/d, βₘ = β, and propagates iff αₘ² + β² < 1. TE (s) incidence: E perpendicular
//! to the plane of incidence (along the grooves at φ = 0); TM (p): E in it. Efficiency = the
//! order's reflected z-flux over the incident z-flux, summed over the reflected polarisations.
//!
//! ```
//! use diffraction::relief::Metal;
//! use diffraction_fmm::{Grating, Incidence, Options, Profile, Solver};
//! let g = Grating {
//!     period_nm: 1000.0,
//!     profile: Profile::Lamellar { duty: 0.5, depth_nm: 50.0 },
//!     metal: Metal::AL,
//!     cover: None,
//! };
//! let inc = Incidence::new(0.3, 0.0, 550.0)?;
//! let sol = Solver::new(Options::default())?.solve(&g, inc)?;
//! let (te, tm) = sol.total();
//! assert!(te < 1.0 && tm < 1.0 && sol.error < 1e-3);
//! # Ok::<(), diffraction_fmm::Error>(())
//! ```

mod cmethod;
mod error;
mod grating;
mod modal;
mod solver;
mod surface;

pub use error::Error;
pub use grating::{
    Cover, CoverIndex, Grating, Incidence, Level, Profile, FOURIER_SAMPLES, MAX_ASPECT,
    MAX_COVER_INDEX, MAX_DEPTH_NM, MAX_PERIOD_NM, MAX_SAMPLES, MAX_SELLMEIER_B,
    MAX_SELLMEIER_C_UM2, MAX_SLABS, MAX_THETA, MIN_COVER_THICKNESS_NM, MIN_PERIOD_NM,
    WAVELENGTH_RANGE_NM,
};
pub use solver::{
    work, CoverPasses, Extrapolation, Method, Options, Order, Solution, Solver,
    DEFAULT_MAX_HARMONICS, DEFAULT_MAX_WORK, DEFAULT_TOLERANCE, ENERGY_SLACK, GROWTH,
    MAX_HARMONICS, MAX_WORK, MIN_HARMONICS, TABLE_MAX_HARMONICS,
};

pub mod table;
