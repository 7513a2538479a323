//! The shared physics of a grating: the N-slit grating and its peaks, the grating
//! equation, the spread along the grooves, the visible band, the local frame and the u-interval a
//! pixel sees.

pub(crate) mod band;
pub mod footprint;
pub mod frame;
pub(crate) mod grating;
pub mod groove;
pub(crate) mod orders;
