//! Relief gratings on real metals: the metal's optical constants and Fresnel reflectances, and
//! the scalar (Kirchhoff) model of the order efficiencies of a surface relief.
//!
//! * [`Metal`]: n + ik of Al, Ag, Au, Cu, Cr (tabulated, cited) or a constant, with the Fresnel
//!   reflectances R_s and R_p.
//! * [`Relief`]: the shape of one period (sinusoid, lamellar, sawtooth, a Fourier series or
//!   sampled heights) and the power of each order of its Kirchhoff phase screen.
//! * [`ScalarRelief`]: a relief on a metal with its order efficiencies η_m (TE and TM) by
//!   scalar diffraction, never above the metal's reflectance, and
//!   [`is_valid`](ScalarRelief::is_valid), the region where they were measured to agree with
//!   rigorous electromagnetics (`docs/validity.md`).
//!
//! Conventions (those of `docs/efficiency_tables.md`): x across the grooves; s = sin θi = the
//! x component of the incident light's direction of travel (−wi.x in the crate's frame); order m
//! leaves at sin θm = s + m·λ/d (= wo.x); TE = electric field along the grooves, TM = magnetic
//! field along the grooves, unpolarised = (TE + TM)/2.
//!
//! ```
//! use diffraction::relief::{Metal, Relief, ScalarRelief};
//! let cd = ScalarRelief::new(Relief::lamellar(110.0, 0.3125)?, Metal::AL, 1600.0)?;
//! for o in cd.orders(0.0, 550.0) {
//!     assert!((o.sin_theta - f64::from(o.order) * 550.0 / 1600.0).abs() < 1e-15);
//!     assert!(o.efficiency.te >= 0.0 && o.efficiency.tm <= 1.0);
//! }
//! # Ok::<(), diffraction::Error>(())
//! ```

mod cover;
mod fresnel;
mod metal;
mod scalar;
mod shape;
mod table;
mod validity;

pub use cover::polycarbonate_index;
pub use metal::{Metal, MAX_INDEX};
pub use scalar::{
    Polarised, ReliefOrder, ReliefOrders, ScalarRelief, MAX_PERIOD_NM, MAX_RELIEF_ORDER,
};
pub use shape::{Relief, MAX_DEPTH_NM, MAX_SAMPLES};
#[cfg(feature = "presets")]
pub use table::Preset;
#[cfg(feature = "gpu")]
pub(crate) use table::ReducedParts;
pub(crate) use table::{CellProposal, FastProposal, Incidences};
pub use table::{EfficiencyTable, MAX_TABLE_ABS_BETA};
#[cfg(feature = "alloc")]
pub use table::{ReducedGrid, MAX_TABLE_NODES, MAX_TABLE_ORDERS, MAX_TABLE_VALUES, REDUCED_PLANES};
