//! Tolerances of the tabulated efficiency tests (tests/efficiency_table.rs), each with the
//! measurement behind it (printed by the named test with `--nocapture`) and its margin, so that
//! a tenfold regression fails.
#![allow(dead_code)]

/// The interpolation rule's grazing corner (`docs/efficiency_tables.md`, step 4): a node with
/// cos² θm at most this counts as evanescent for its order.
pub const GRAZING_CORNER: f64 = 1e-6;

/// The presets at their nodes against the JSON tables, absolute: the shipped data are the JSON's
/// 6-decimal values rounded to 5 decimals (half a unit, 5e-6; `python_ref/presets.py`
/// `RUST_DECIMALS`) and then to f32 (`F32`), on the JSON's nodes as f32 (up to 1.5e-9 off).
/// Measured 5.03e-6 (`presets_match_their_json_tables_at_every_node`): the rounding itself, so
/// the bound is the rounding's with a margin of 4 % for the node shift.
pub const NODE: f64 = 5.2e-6;
/// f32 rounding of a value, relative (half an f32 unit is 6e-8; margin 2×).
pub const F32: f64 = 1.2e-7;
/// The largest JSON efficiency at a node within the grazing corner of its order's Rayleigh line,
/// which the rule reads as 0. Measured 3.4e-4; margin 2.9×.
pub const GRAZING_NODE_ETA: f64 = 1e-3;
/// The crate's interpolation against python_ref/efficiency_table.py's `interpolate_normalised`
/// on the same f32 data (tests/data/efficiency_interp.csv, 2000 points, 3695 nonzero values),
/// absolute. Measured 2.2e-16 (`interpolation_matches_the_python_reference`); margin 9×.
pub const INTERPOLATION: f64 = 2e-15;
/// |η(4δ)/η(δ) − 2| at δ = 1e-8 inside a Rayleigh line (the square-root onset; what is left is
/// the change of the other orders' normalisation with δ). Measured 4.9e-5 over 338 onsets
/// (`orders_appear_exactly_on_their_rayleigh_lines`); margin 4×.
pub const SQRT_ONSET: f64 = 2e-4;
/// A sum over orders above 1 after the normalisation: the rounding of a sum of up to 19 scaled
/// values. Measured 4.4e-16 over 788,184 queries (`sums_stay_at_most_one_everywhere`); margin 9×.
pub const SUM_ROUNDING: f64 = 4e-15;
/// A table baked from the scalar model against the model at the nodes, absolute. Measured
/// 1.1e-16 (`scalar_model_baked_into_a_table_matches_it_at_the_nodes`); margin 9×.
pub const SCALAR_NODES: f64 = 1e-15;
/// An unpolarised efficiency against the mean of TE and TM, absolute. Measured 2.2e-16 over
/// 788,184 queries (`sums_stay_at_most_one_everywhere`); margin 4.5×.
pub const UNPOLARISED_MEAN: f64 = 1e-15;
/// A table read from the preset's JSON against the shipped preset at one point: the shipped
/// values are the JSON's rounded to 5 decimals (half a unit, 5e-6) and to f32. Measured 3.6e-6
/// (`json_tables_load_and_bad_ones_name_the_field`, 4 presets); margin 2.8×.
pub const JSON_AGAINST_PRESET: f64 = 1e-5;
/// A reduced conical table (version 3) holding an affine q(s′, λ′, √(1 − β²)) read against that
/// q, absolute: the rule reproduces it exactly, so this is rounding (values about 0.5).
/// Measured 2.3e-15 (`an_affine_q_is_read_exactly`, tests/reduced_table.rs); margin 8.6×.
pub const REDUCED_AFFINE: f64 = 2e-14;
/// A reduced table whose planes hold the CD preset at the same reduced nodes, read at
/// (α, β, λ), against the CD at (s′, λ′) = (α, λ)/√(1 − β²), absolute: the same corners and
/// weights up to rounding. Measured 2.5e-13
/// (`planes_of_one_classical_table_read_it_in_reduced_coordinates`); margin 8×.
pub const REDUCED_MAPPING: f64 = 2e-12;
/// The CD's reduced table (`Preset::reduced_table`, the reduction in the polycarbonate with
/// the cover-air interface at the real directions) read off the plane β = 0 against the direct
/// reduced reading (the CD at (α, λ)/√(1 − β²/n²) times the interfaces' transmittance ratios,
/// written out in the test), absolute, over orders at least 0.2 in cos θm from their cut-off
/// in air and where λ/c stays in the band: the planes' s′ nodes land between the classical
/// nodes (a second interpolation) and the table interpolates η/cos θm. Measured 0.0816
/// (`a_covered_table_reads_the_reduction_in_the_cover`; without the interfaces' ratios it is
/// 0.36); margin 1.5×.
pub const REDUCED_IN_THE_COVER: f64 = 0.12;
/// The same comparison's mean absolute difference off the plane. Measured 2.18e-3; margin 2.3×.
pub const REDUCED_IN_THE_COVER_MEAN: f64 = 5e-3;
