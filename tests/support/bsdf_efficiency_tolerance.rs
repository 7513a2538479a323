//! Tolerances of the tabulated-efficiency BSDF tests (`tests/bsdf_efficiency.rs`), each with its
//! reason.
#![allow(dead_code)]

/// The furnace of a tabulated model: `albedo()` (quadrature of η̃·ℓ over the disk) against the
/// sampler's Monte-Carlo mean, in standard errors. The albedo's own error (the quadrature across
/// the bilinear table's kinks) is far below one standard error at the sample counts used
/// (measured |z| ≤ 1.75 over the finite-N cases; at N = ∞ the weight varies with the order the
/// cell proposal picks, 1.9·10⁻³ relative worst); 4σ keeps the fixed-seed test robust
/// while a 10 % bias
/// (hundreds of σ) fails it.
pub const TAB_FURNACE_SIGMAS: f64 = 4.0;

/// Σ_m η̃_m ≤ 1 up to the rounding of the sum.
pub const TAB_SUM_ROUNDING: f64 = 1e-12;

/// At N = ∞ with an ideal groove `sample` returns f = η̃/cos θi: f·cos θi equals η̃ up to one
/// rounding of the division and the product.
pub const TAB_DELTA_WEIGHT: f64 = 4.0 * f64::EPSILON;

/// The baked scalar relief against the relief model at a node of the table (blaze check): the
/// table stores the model's value at its nodes (f64 storage), so only rounding separates them.
pub const TAB_NODE_AGREEMENT: f64 = 1e-12;

/// The generic colour path (`GenericStrategy::WINDOWS`) on a tabulated model against the
/// independent 0.01 nm quadrature, relative in Y: measured 9.0·10⁻⁶ worst (CD, N = 1000, a dim
/// pair; 10⁻⁸-10⁻¹⁰ elsewhere), above the 10⁻⁶ that `WINDOWS` states for models that keep the
/// peaks contract, because η̃(λ) has the table's kinks (bilinear nodes every 20 nm, Rayleigh
/// onsets) that are not reported as peaks. Asserted with a margin of 10.
pub const TAB_WINDOWS_COLOUR: f64 = 1e-4;

/// At N = ∞ with an ideal groove the albedo is Σ η̃ over the propagating orders, absolute.
/// Measured 0 (`infinite_n_carries_exactly_the_efficiency_of_each_order`, 5 models: the same
/// sum); allowed: ten ulp of 1.
pub const TAB_ALBEDO_SUM: f64 = 2e-15;
/// A reported peak's intensity against `response` at its wavelength, relative. Measured 3.9e-16
/// (`peaks_report_the_response_at_their_wavelength`, 347 peaks); margin 5×.
pub const TAB_PEAK_RESPONSE: f64 = 2e-15;

/// The model's η̃ (a classical table's fast reading, `relief/table/lookup.rs`) against the
/// table's own reading, absolute (η ≤ 1): the same rule rounded differently (the bilinear
/// weights from reciprocals, TE and TM interpolated together). Measured 4.4e-16
/// (`the_models_efficiency_is_the_tables_to_rounding`, four presets and a baked scalar
/// sinusoid, 71,404 pairs); margin 4.5×.
pub const TAB_FAST_READING: f64 = 2e-15;
