//! Tolerances of the WGSL shaders (src/gpu/*.wgsl): the bounds any conforming WGSL
//! implementation must meet, derived from the WGSL accuracy rules in docs/gpu.md, and the
//! worst errors measured by the spec-worst-case emulation (tests/gpu_wgsl.rs) with their margin.
//! Shared by tests/gpu_wgsl.rs and the device tests of gpu-tests/ (`#[path]`).
#![allow(dead_code)]

/// The unit roundoff of f32, 2⁻²⁴.
pub const U: f64 = 1.0 / 16_777_216.0;

/// The derived bound of `diffraction_n_slit_cycles` (absolute, at the exact f32 argument) on
/// any conforming implementation: 169·u = 1.0e-5 (docs/gpu.md: 2·(2·33u + 9u) from the
/// polynomial, the products and the division's 2.5 ulp, plus 2π·3u from the phase's
/// conversion).
pub const N_SLIT_SPEC: f64 = 169.0 * U;
/// The derived bound of `diffraction_single_slit_cycles`: 2·42u = 84u = 5.0e-6.
pub const SINGLE_SLIT_SPEC: f64 = 84.0 * U;
/// The derived bound of `diffraction_intensity_cycles` (the product: both plus one rounding).
pub const INTENSITY_SPEC: f64 = N_SLIT_SPEC + SINGLE_SLIT_SPEC + U;

/// The worst error of the emulation of `diffraction_n_slit_cycles` with every operation the
/// spec leaves free pushed to its limit (divisions 2.5 ulp either way, integer-to-float
/// conversions 1 ulp either way, Horner steps fused or not): measured 4.4e-7 (printed by
/// `gpu_wgsl -- --nocapture`); margin 2×. On Mesa lavapipe the device test measured 2.3e-7.
pub const N_SLIT_WORST_MEASURED: f64 = 9e-7;
/// The same for `diffraction_single_slit_cycles`: measured 2.4e-7; margin 2× (lavapipe 1.8e-7).
pub const SINGLE_SLIT_WORST_MEASURED: f64 = 5e-7;

/// The colour table's lookup: per channel, |GPU − CPU| ≤ `TABLE_ROUNDINGS`·u·M + 2u·|u|·D, with
/// M the sum of the magnitudes of the four Hermite terms and D twice the largest slope of the
/// cell (docs/gpu.md: the nodes rounded to f32, the cubic basis and the sum, and the rounding of
/// the position in the cell).
pub const TABLE_ROUNDINGS: f64 = 16.0;
/// A conical table's colour on its planes of |wi.y| (`diffraction_table_colour_conical`) against
/// `ColorTable::xyz`, relative to the table's scale: measured 2.05e-6 on lavapipe (the CD
/// preset, N = 8, 10⁻¹, 65,536 queries; 0.035 of the derived bound); margin 5×.
pub const CONICAL_COLOUR_WORST_MEASURED: f64 = 1e-5;
/// A packed efficiency table's interpolated η (`diffraction_eta`, `diffraction_eta_conical`)
/// against `EfficiencyTable::efficiency` and `efficiency_conical`, absolute: measured 3.7e-6
/// (classical tables), 5.4e-6 (the presets' conical tables) and 2.3e-6 (a version-2 tensor
/// grid, tests/support/tensor_cd.rs) on lavapipe at 10⁵ queries per table, 0.03-0.09 of the
/// derived bounds (gpu-tests/tests/tabulated.rs); margin 4.6×.
pub const ETA_WORST_MEASURED: f64 = 2.5e-5;

/// The mean ΔE2000 between the example gpu's fig. 6 (G-buffer on the CPU, eq. 12 and the colour
/// table in WGSL) and the reference tracer's with the same colour rule, at 96×72 and 4 spp
/// (gpu-tests/tests/scenes.rs): the f32 shading's roundings only, measured 1.5e-5 on lavapipe
/// (7.9e-6 at 480×360); margin 10× (far below the 1 of a visible difference: a tenfold
/// regression of the shading's precision, or any systematic error, fails it).
pub const SCENE_MEAN_DELTA_E: f64 = 1.5e-4;
/// The largest ΔE2000 of one pixel there: measured 0.06 (a grating pixel where a light is at
/// grazing incidence and f32 decides the sign of cos θ differently); margin 5×.
pub const SCENE_MAX_DELTA_E: f64 = 0.3;

/// An order row uploaded as f32 against its f64 value, relative: one rounding to f32 (half an
/// ulp, 6e-8). Measured 1.1e-8 (`the_bsdf_upload_matches_the_model`); allowed: twice the rounding.
pub const ORDER_ROW_F32: f64 = 1.2e-7;
/// The rows' running sum (64 orders, accumulated in f64 and rounded to f32) against the f64 sum
/// of the rounded weights, relative. Measured 6.4e-8; margin 7.8×.
pub const ORDER_ROW_SUM_F32: f64 = 5e-7;

/// The mean sample weight's systematic f32 error allowed in the device furnace test
/// (gpu-tests/tests/sample.rs), as a share of the weight bound, beside 5 standard errors: the
/// per-sample weight errors are the phase's roundings, of either sign (worst 3.0e-3 of the
/// bound on a narrow lobe's flank at N = 1000 and 5.1e-3 for the DVD preset at N = 300, 7e-4
/// and below for N ≤ 100), so their mean is far smaller; this allows a systematic 1e-4 (the
/// furnace tests use N ≤ 1000 amplitude gratings and the CD at N = 34).
pub const SAMPLE_WEIGHT_F32: f64 = 1e-4;

/// The mean ΔE2000 between the example's `gpu cd` (the CD preset's tabulated BSDF in WGSL) and
/// the same estimator on the CPU with the same random numbers, at 48×36, 4 spp, 8 wavelengths
/// (gpu-tests/tests/scenes.rs): the f32 shading's roundings only (and the rare sample whose
/// order or validity is decided within rounding), measured 1.16e-4 on lavapipe with the CD read
/// conically (its default; 1.1e-4 classically, and 1.16e-4 at 320×240, 32 spp, 16
/// wavelengths); margin 10×.
pub const CD_MEAN_DELTA_E: f64 = 1.1e-3;
/// The largest ΔE2000 of one pixel there: measured 0.011 (0.010 classically; at 320×240 the
/// largest is 0.68, one pixel, not traced to its sample); margin 5×.
pub const CD_MAX_DELTA_E: f64 = 0.05;
