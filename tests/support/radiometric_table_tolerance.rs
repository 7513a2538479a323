//! Tolerances of `tests/radiometric_table.rs`, each the measured worst case times a stated
//! margin of at most 10 (so a tenfold regression fails), or the table's colour target.
//!
//! Measured with `cargo test --release --all-features --test radiometric_table -- --nocapture`
//! at accuracy 10⁻⁴ (the tables' nodes: `Asymptotic` where only orders m ≠ 0 reach the band,
//! `Exact` in order 0's bright half period, as `ColorTable`).

/// Lookups (cos θi·g(v)·C(u)) of finite-N Gaussian-groove tables against `Exact` of the BSDF's
/// grating response, per channel over the exposure max(cos θi·g·Y_b, Y). Measured worst
/// 5.3e-5 (d = 1600 nm, N = 1000, D65; 4 gratings × 400 directions); margin 9.4.
pub const LOOKUP_REL: f64 = 5e-4;
/// The same in ΔE2000 at that exposure: the colour target of `ColorTable` (0.05). Measured
/// worst 0.023 (d = 10 µm, N = 300, E); margin 2.2.
pub const LOOKUP_DE2000: f64 = 0.05;
/// N = ∞ tables against the closed-form areas of the delta peaks, relative. Measured worst
/// 7.4e-5 (d = 1600 nm, D65; 3 gratings × 400 directions); margin 6.8.
pub const INFINITE_REL: f64 = 5e-4;
/// The same in ΔE2000. Measured worst 0.016 (d = 10 µm, D65); margin 3.2.
pub const INFINITE_DE2000: f64 = 0.05;
/// The N = ∞ table against `Exact` of N = 10⁶ away from u = 0, over Y_b: the O(1/N) of a
/// finite grating's tails plus the table's error. Measured 4.4e-6 (7 u); margin 9.2.
pub const LARGE_N_REL: f64 = 4e-5;
/// Footprint means (widths 5·10⁻⁴ … 2·10⁻²) against a 256-point Gauss-Legendre quadrature of
/// `Exact` (and, for N = ∞, of the delta peaks' areas), over Y_b. Measured 1.6e-5 (9 intervals,
/// worst at d = 1600 nm, N = 1000, D65; N = ∞ below it); margin 6.1.
pub const MEAN_REL: f64 = 1e-4;
/// The same in ΔE2000. Measured 0.0016; margin 6.3.
pub const MEAN_DE2000: f64 = 0.01;
/// `xyz(wo, wi)` of a rough table against `lookup(u)` times cos θi·g(v), relative: the same
/// product. Measured 0 (`exposure_relation`, 8 pairs); allowed: four ulp.
pub const SCALED_LOOKUP: f64 = 1e-15;
