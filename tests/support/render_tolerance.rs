//! Tolerances of the renderer-facing tests (the hero-MIS furnaces, the spectral types, the
//! footprint), each with the measurement behind it and its margin; the looser promises to users
//! live in the crate's docs.
#![allow(dead_code)]

// ---- furnaces (tests/hero_mis.rs) ----

/// A furnace estimate must be within this many standard errors of its expected value. 44
/// estimates run with fixed seeds (largest |z| measured: 2.34, printed by `-- --nocapture`);
/// for a family significance of 0.01 (Šidák) each needs |z| < 3.7 if the estimator is
/// unbiased; 4 is that, rounded up. The old recipe's 4× error is over 100 standard errors.
pub const FURNACE_SIGMAS: f64 = 4.0;
/// The standard error of a furnace estimate (40 000 samples), relative to the expected value:
/// measured at most 6.6·10⁻³ (the grating at N = 1000 with an ideal groove); margin 3×, so a
/// tenfold rise in the weights' variance fails.
pub const FURNACE_MAX_RELATIVE_SE: f64 = 0.02;

// ---- the film and the visible sampler (tests/spectral_types.rs) ----

/// Samples per `to_xyz` estimate.
pub const FILM_SAMPLES: usize = 40_000;
/// A film estimate must be within this many standard errors of the reference colour (about 40
/// estimates per channel; Šidák at 0.01 needs 3.7).
pub const FILM_SIGMAS: f64 = 4.0;
/// ... plus this share of the reference, for the reference's own error: `Spectral`'s `Exact`
/// is within 7·10⁻⁸ of an independent reference (`tests/spectral_reference.rs`); margin 3×.
/// (Largest |z| measured over the 54 channel estimates: 2.16.)
pub const FILM_ROUNDING: f64 = 2e-7;
/// ∫p over the band and P(λ) against ∫p, by the test's own 8-point rule on every nanometre,
/// absolute: measured 2.6·10⁻¹⁵ (P(829 nm)); margin 3.9×.
pub const VISIBLE_PDF_INTEGRAL: f64 = 1e-14;
/// |P(P⁻¹(u)) − u| over 10⁵ u: measured 3.3·10⁻¹⁶ (three ulps of ½); margin 3×.
pub const VISIBLE_CDF_ROUND_TRIP: f64 = 1e-15;
/// |P⁻¹(P(λ)) − λ|/λ over the same: measured 3.2·10⁻¹⁶; margin 3×.
pub const VISIBLE_LAMBDA_ROUND_TRIP: f64 = 1e-15;

// ---- the footprint (tests/footprint.rs) ----

/// `u_interval` against the brute-force range over the pixel, at either end, relative to the
/// range's width: measured 5.4·10⁻⁶ (grazing view, 4-pixel steps: the corner directions are
/// interpolated, and the brute force's 512 rim directions miss the extreme by up to
/// α·(π/512)²/2); margin 3.7×.
pub const FOOTPRINT_RELATIVE: f64 = 2e-5;
/// `u_range_at` against 10⁵ directions of the light's rim, absolute: measured 6.2·10⁻¹¹ (the
/// rim's sampling error is below α·(π/10⁵)²/2 = 1.5·10⁻¹⁰ for α = 0.3); margin 4×.
pub const CONE_ABSOLUTE: f64 = 2.5e-10;
/// The furnaces' expected value (20 nm pieces, 0.5 nm next to the albedo's kinks) against a
/// rule on every nanometre (0.1 nm next to the kinks), relative: measured 5.5·10⁻⁵ (the 1 nm
/// kinks of the tables inside 20 nm pieces), below 1/70 of the furnaces' standard errors;
/// margin 3.6×.
pub const QUADRATURE_AGREEMENT: f64 = 2e-4;

/// A point light seen by a pixel without extent: the interval collapses to u itself, absolute.
/// Measured 0 (`a_point_sample_with_a_point_light_is_its_own_u`); allowed: four ulp of |u| ≤ 2.
pub const POINT_FOOTPRINT: f64 = 2e-15;
