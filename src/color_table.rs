//! A per-grating colour table: XYZ(|u|) tabulated once, looked up in nanoseconds, and averaged
//! over an interval of u in O(1) for footprint filtering (see [`ColorTable`]), of the paper's
//! intensity or of the radiometric [`GratingBsdf`](crate::GratingBsdf) ([`TableSource`]).
//!
//! The parts: `layout` (the band, the blocks' bit layout, the caps and the work units),
//! `interpolant` (the Hermite cells), `grid` (the graded grid: refinement, lookup, mean),
//! `grating_nodes` and `delta_nodes` (the node values of a finite grating and of N = ∞),
//! `source` (what is tabulated, and what each source brings to the grid) and `stored` (the
//! cached form, feature `serde`). Imports run one way: `source` → nodes → `grid` →
//! `interpolant`, `layout`.

use glam::DVec3;

use crate::color::Xyz;
use crate::error::{Error, Requirement};
use crate::model::both_above;
#[cfg(doc)]
use crate::spectrum::bounds;
use crate::spectrum::saturate;
use crate::spectrum::{Illuminant, Spectral};
#[cfg(doc)]
use crate::spectrum::{Strategy, DEFAULT_ACCURACY};
use crate::spectrum::{MAX_ACCURACY, MIN_ACCURACY};
#[cfg(doc)]
use crate::Slits;
use crate::{Grating, GratingBsdf};

mod delta_nodes;
mod grating_nodes;
mod grid;
#[cfg(feature = "relief")]
mod incidence;
mod interpolant;
mod layout;
mod source;
#[cfg(feature = "serde")]
mod stored;
mod tabulated_access;
#[cfg(feature = "relief")]
mod tabulated_nodes;
use grid::Grid;
#[cfg(all(feature = "relief", feature = "gpu"))]
pub(crate) use incidence::GpuIncidence;
use layout::{LAMBDA_MIN_NM, U_MAX};
use source::Source;
pub use source::TableSource;

/// The colour table of the radiometric [`GratingBsdf`], now [`ColorTable`] built from a
/// `&GratingBsdf` ([`TableSource::Radiometric`]): `RadiometricTable::new(&spectral, &bsdf,
/// accuracy)` still compiles, and its stored form loads as a `ColorTable`. One difference:
/// [`ColorTable::bsdf`] returns an `Option`. This alias goes in the next release.
#[deprecated(
    since = "0.2.0",
    note = "use `ColorTable`: `ColorTable::new(&spectral, &bsdf, accuracy)` tabulates the radiometric BSDF"
)]
pub type RadiometricTable = ColorTable;

/// The colour XYZ(|u|) of one grating under one illuminant, tabulated over [0, 2] on a graded
/// grid, with O(1) lookup and O(1) means over intervals of u: of the paper's intensity or of the
/// radiometric [`GratingBsdf`] ([`TableSource`]).
///
/// For a fixed [`Grating`] and illuminant the reference colour [`Spectral::xyz`] depends on the
/// phase projection u alone, and only on |u| (the intensity I(u, λ) = S(β)·F_N(α) is even in u).
/// The table samples it on [0, 2] (the range of u = (wi + wo)·t for unit directions) and
/// interpolates it. Needs the `alloc` feature (on with `std`, the default).
///
/// # Two sources
///
/// [`ColorTable::new`] takes what it tabulates as `&Grating` or `&GratingBsdf`
/// ([`TableSource`]); both share the grid, the tolerance, [`lookup`](Self::lookup),
/// [`mean`](Self::mean), [`xyz`](Self::xyz) and the stored form.
///
/// * **The paper's grating** ([`TableSource::Paper`]): `lookup(u)` is the colour
///   [`Spectral::xyz`] of the unitless intensity I(u, λ) under the `Spectral` passed to `new`
///   (with its envelope), and `xyz(wo, wi)` is `lookup(u)` above the surface (as
///   [`AguHill`](crate::AguHill)'s `eval`). The sections below describe this source.
/// * **The radiometric BSDF** ([`TableSource::Radiometric`]): where the BSDF's colour
///   factorises as g(v)·C(u), the crate's colour of its response f·cos θi at (wo, wi)
///   ([`Spectral::xyz_response`] of
///   [`SpectralResponse::grating_response`](crate::SpectralResponse::grating_response), or for
///   N = ∞ the areas of [`SpectralResponse::peaks`](crate::SpectralResponse::peaks)) is
///
///   ```text
///   XYZ(wo, wi) = cos θi · g(v) · C(u),     C(u) = ∫ E(λ)·[f/g](u, λ)·cmf(λ) dλ / ∫ E·ȳ dλ,
///   ```
///
///   u = (wi + wo)·t, v = (wi + wo)·y, in the units of `Spectral`'s colour (a white reflector
///   has Y = 1); `lookup(u)` returns C(u) (1/sr per unit of g, cosine excluded) and `xyz(wo,
///   wi)` the product. It factorises exactly where g does not depend on λ and the order
///   efficiencies do not depend on the directions or λ:
///   - *Gaussian groove, finite N*: f/g = ρ²·S·(N·d/λ)·F_N, so C(u) = ρ²·N·d times the colour
///     of the grating's intensity with the envelope λ⁻¹ ([`Spectral::with_envelope`]).
///   - *Ideal groove δ(v)*: the same C(u), per unit of δ(v): a renderer multiplies by the
///     groove's mass over the v its light covers (1 if that holds v = 0), not by a value
///     (`xyz` is 0, as `eval`).
///   - *N = ∞* (either groove): the delta lobes integrate over λ to
///     C(u) = Σ_m η_m·(d/|m|)·E(λ_m)·cmf(λ_m)/∫E·ȳ, λ_m = d·|u|/|m| in the band (at most
///     [`MAX_ORDERS`](crate::MAX_ORDERS) orders); order 0 is a delta δ(u) of colour η₀·white
///     per unit of δ(u)·g(v) ([`specular`](Self::specular)), not in the table.
///   - *Coherence length* L (the default of [`GratingBsdf::new`] for finite N): g depends on λ,
///     so the colour is not g(v)·C(u); refused (the error names `groove`). Use
///     [`Spectral::xyz_response`] per direction, or a Gaussian groove
///     ([`GratingBsdf::with_groove`]).
///   - *Tabulated order efficiencies* (feature `relief`, the presets): see
///     [Tabulated efficiencies](Self#tabulated-efficiencies).
///
///   What a renderer multiplies by: a point or distant light whose irradiance at normal
///   incidence has luminance E⊥ gives radiance E⊥ · `xyz(wo, wi)`; an area light of radiance L
///   whose image in the (u, v) plane is [u0, u1] × [v0, v1] (d(wi.x)·d(wi.y) = cos θi·dωi) gives
///   L · (u1 − u0) · `mean(u0, u1)` · [`GrooveSpread::mass`](crate::GrooveSpread::mass)`(v0, v1,
///   ·)` exactly; a pixel footprint [u0, u1] of a point light
///   ([`footprint::u_interval`](crate::optics::footprint::u_interval)) E⊥ · cos θi · g(v) · `mean(u0,
///   u1)`. The error scale Y_b is the largest C at d·|u| ≥ 360 nm, at least ρ²·d/∫ȳ (an order
///   of efficiency ρ² at 555 nm under E). Measured at 10⁻⁴ (`tests/radiometric_table.rs`,
///   docs/color_table.md): within 7.4·10⁻⁵ of the exposure and 0.023 ΔE2000 of the direct
///   colour; `xyz` 75-88 ns against 441 µs for `Exact`; builds 15 ms (N = ∞) to 0.46 s
///   (d = 1600 nm, N = 1000).
///
/// # Tabulated efficiencies
///
/// A radiometric BSDF with tabulated order efficiencies (`OrderEfficiency::from_table`,
/// `GratingBsdf::preset`; feature `relief`) has η̃_m = min(η_m(−wi.x, λ), η_m(−wo.x, λ)), which
/// depends on the incidence: its colour is cos θi · g(v) · C(u, s), s = wi.x. Its table holds
/// graded grids over u ≥ 0 and u ≤ 0 (one grid if the efficiencies are mirror symmetric) per
/// incidence node, placed between the grazing directions at each u and bisected where a midpoint
/// misses the accuracy (at most 129 nodes at 10⁻³, one more halving per halved accuracy below,
/// at most 513; each grid within [`MAX_NODES`](Self::MAX_NODES) and [`MAX_WORK`](Self::MAX_WORK)
/// at an accuracy of at least 2.5·10⁻⁴), and `xyz(wo, wi)` interpolates linearly between the
/// two nodes around wi.x. A node's colour integrates the BSDF's `eval` over panels cut at F_N's
/// zeros, the table's wavelengths and the orders' Rayleigh wavelengths.
/// [`lookup`](Self::lookup) and [`mean`](Self::mean) have no incidence: they return black.
/// [`incidence_count`](Self::incidence_count) counts the incidence nodes;
/// [`node_count`](Self::node_count), [`size_bytes`](Self::size_bytes), [`scale`](Self::scale)
/// and [`error_estimate`](Self::error_estimate) cover them all. No stored form (serialising is
/// an error); a `GpuColorTable` of it holds every node's grids (`diffraction_table_colour`).
/// Refused: N = ∞ (`slits`), a coherence-length groove (`groove`).
///
/// A conical table (the presets' default reading, `OrderEfficiency::preset`) makes the colour
/// depend on |wi.y| too: C(u, s, β) is tabulated on 9 planes |wi.y| = β from 0 to 0.96
/// (wo.y = −β, the groove lobe's centre), the plane β = 0 at `accuracy`, the others at
/// `accuracy` or 10⁻² if coarser (their error is mostly the interpolation between planes);
/// `xyz(wo, wi)` reads the two planes around β = min(|wi.y|, |wo.y|) at the place of
/// (u, s) between its grazing directions and blends them linearly in √(1 − β²). On the plane
/// across the grooves it is the first plane's reading (a preset's: the classical table's, to
/// the bit). Measured on the CD (N = 34, D65, 10⁻³; docs/color_table.md, "Conical tables"):
/// mean ΔE2000 0.013 / 0.073 / 0.15 / 0.49 against the conical BSDF's generic colour for
/// |wi.y| ≤ 0.05 / 0.05-0.3 / 0.3-0.6 / 0.6-0.9 (worst 0.17 / 1.2 / 4.7 / 22, where an
/// order's conical cut-off crosses the band between planes), built in about 20 s.
/// `GpuColorTable` packs the plane β = 0.
///
/// Measured (docs/color_table.md, "Tabulated efficiencies"): the CD preset (N = 34, Gaussian
/// σ = 0.02, D65) at 10⁻³ builds in 4-5 s (129 incidence nodes, 59,037 nodes, 4.8 MB) and
/// is within 0.071 ΔE2000 (600 random pairs; 0.15 over 4000) of the generic colour of the same
/// BSDF; at 2.5·10⁻⁴ in about 38 s (509 incidence nodes, 41 MB) within 0.043 over the 4000.
/// The efficiencies are piecewise bilinear in (incidence, λ): the colour's kinks cross both the
/// incidence nodes and the grids over u, so both are refined together.
///
/// ```
/// # #[cfg(feature = "presets")] {
/// use diffraction::relief::Preset;
/// use diffraction::spectrum::{Illuminant, Spectral};
/// use diffraction::{color::Xyz, ColorTable, GratingBsdf, GrooveSpread};
/// use diffraction::glam::DVec3;
/// let cd = GratingBsdf::preset(Preset::Cd, 8)?.with_groove(GrooveSpread::gaussian(0.02)?);
/// let t = ColorTable::new(&Spectral::new(Illuminant::D65), &cd, 1e-2)?;
/// assert!(t.incidence_count().unwrap() >= 9);
/// let wi = DVec3::new(0.2, 0.0, 0.96f64.sqrt());
/// let wo = DVec3::new(0.144, 0.0, (1.0f64 - 0.144 * 0.144).sqrt()); // u = 0.344: order 1 at 550 nm
/// assert!(t.xyz(wo, wi).y > 0.0);
/// assert_eq!(t.lookup(0.344), Xyz::default()); // no incidence
/// # }
/// # Ok::<(), diffraction::Error>(())
/// ```
///
/// # The grid
///
/// The colour has structure on every scale of u: order 0's lobe is λ/(N·d) wide around u = 0,
/// its side lobes and its 1/u² tail follow, and every order m ≠ 0 spans u ∈ [m·360/d, m·830/d]
/// with features that are a fixed fraction of u wide (a 10 nm feature of the colour-matching
/// functions at λ_m = d·u/m is a relative change δu/u = 10 nm/λ_m). So the grid is graded
/// geometrically: [0, 2] is cut into *blocks*, one block [0, u₀) with
/// u₀ = 2^⌊log₂(360 nm/(20·N·d))⌋ (where 1 − F_N < 1 %), then eight blocks per octave of u up
/// to 2, each 1/8 of its octave wide. Each block is uniform with its own number of intervals, a
/// power of two from 2 to 1024, doubled until the interpolant meets the accuracy at the midpoint
/// of every interval (where the error of cubic Hermite interpolation peaks), rechecked after every
/// round (a neighbour's refinement changes the derivatives), or until the node budget
/// [`MAX_NODES`](Self::MAX_NODES) is spent (worst blocks first).
///
/// **Lookup** is O(1): the block of u is read off the bits of u (its exponent and the top three
/// bits of its mantissa: one shift), the interval from the block's uniform spacing, and the colour
/// is the cubic Hermite interpolant of its two nodes, with derivatives estimated from the five
/// nearest nodes (a fourth-order Lagrange derivative; mirrored through u = 0, where the derivative
/// is 0 by symmetry). No search.
///
/// **Footprint filtering.** The table stores the integral of the interpolant from 0 to every node,
/// so the mean over [u0, u1] is a difference of cumulative values plus two partial cells, O(1)
/// ([`mean`](Self::mean)). The grid resolves order 0's lobe (it starts 20 times inside its first
/// zero), so the integral through the lobe has the interpolant's accuracy however narrow the lobe
/// (`tests/color_table.rs` checks it at N·d = 10⁹ nm against a quadrature of `Exact`).
///
/// # Accuracy
///
/// Errors are relative to the scale Y_b of the grating's brightest diffracted colour, the scale of
/// [`Strategy::auto`]: the largest Y at the table's u with d·|u| ≥ 360 nm (where an order m ≠ 0
/// can reach the band), at least 555/(N·∫ȳ dλ), the Y of an ideal first-order peak at 555 nm
/// ([`scale`](Self::scale)); where the colour is brighter (order 0 near u = 0) to its own Y. With
/// Y' = max(Y_b, Y) the exposure and t_c = XYZ_c/(white_c·Y'), every checked channel is within
///
/// `accuracy · white_c · Y' · max(t_c, (6/29)³)^(2/3)`
///
/// of the nodes: the change that moves CIELAB's f(t) = t^(1/3) by accuracy/3. That is at most
/// `accuracy · white_c · Y'` (relative to the brightest order) for channels up to the white, and
/// 23 times less where the colour is dark (t < 0.0089), where CIELAB is most sensitive. Measured
/// at 10⁻⁴ over a representative 20 of the 90
/// gratings of `tests/color_table.rs` (every N, 2000 random u each): within 1.9·10⁻⁴ of Y_b and
/// 0.027 ΔE2000 of `Exact` at the brightest order's exposure (docs/color_table.md); at 3·10⁻⁴
/// the full sweep reached 0.097. [`error_estimate`](Self::error_estimate) reports the worst
/// check.
///
/// Not resolved: where an order's peak crosses a band end (u = m·360/d, m·830/d) the colour steps
/// by that order's light at 360 or 830 nm over a width 360 nm/(N·d) in u; the step is below
/// 2·10⁻⁴ of Y_b (the colour-matching functions are below 6·10⁻⁴ there) and, for N ≳ 10⁴, narrower
/// than the finest block spacing u/8192; those blocks stop refining there
/// ([`error_estimate`](Self::error_estimate) then exceeds the accuracy).
///
/// # Cost
///
/// A build costs about twice the node count (100-5200 nodes) in calls of [`Spectral::xyz`]: at the
/// default accuracy 2.5-5.2 ms on one core for the gratings of `benches/goals.rs` (d = 740 nm to
/// 100 µm, N = 21 to 10⁶) and 0.4-7 ms for the 36 of the accuracy report (docs/accuracy.md),
/// at 10⁻⁴ up to about 0.4 s (N = 10⁶, d = 400 nm, measured before the product rules). For
/// N ≥ 5 and `accuracy` ≥ [`ASYMPTOTIC_ACCURACY`](Self::ASYMPTOTIC_ACCURACY) a node is
/// [`Strategy::ASYMPTOTIC`] (1-25 µs) where only orders m ≠ 0 reach the band (d·|u| ≥ 415 nm), and
/// where order 0's light reaches it but the colour is dark enough for `Asymptotic`'s bound
/// (2·10⁻⁴ of that light) to move CIELAB's f(t) by less than accuracy/3
/// (t ≤ (accuracy/(2·10⁻⁴))³: every node at the default accuracy 10⁻³, the darker ones at 10⁻⁴);
/// every other node (N < 5, and order 0's bright lobe and near tail below 10⁻³) is
/// [`Strategy::EXACT`], which then dominates the build time. Below that accuracy a node is the cheapest strategy whose
/// bound meets 0.043 of the accuracy ([`Spectral::choose`] with [`Strategy::auto`]: the peak
/// search for very fine gratings, N ≳ 10⁸ at 10⁻⁶, else `Exact`). Memory is 72 bytes per node plus 32 per block
/// ([`size_bytes`](Self::size_bytes)), at most 460 KiB.
///
/// # Limits
///
/// * The paper's grating with N = ∞ ([`Slits::Infinite`]) is rejected: with the paper's
///   normalisation the integral is 0 except at u = 0, nothing to tabulate (the radiometric BSDF
///   of N = ∞ is tabulated).
/// * The paper's peak colours ([`Spectral::paper_peaks`]) are not the integral and are not
///   tabulated; they cost O(visible orders) per call already.
/// * |u| > 2 (no pair of unit directions gives it) is taken as 2; NaN and ±∞ give black, as in
///   [`Spectral::xyz`].
/// * Where N·d > 3.3·10²⁰ nm order 0's lobe (360 nm/(N·d) wide in u) is narrower than 1/20 of
///   the first block [0, 2⁻⁶⁴): no grid of that spacing resolves it, so lookups with
///   |u| < 2⁻⁶⁴ are [`Strategy::EXACT`] (microseconds instead of nanoseconds, on a range of
///   u no unit direction pair is likely to give), [`error_estimate`](Self::error_estimate)
///   leaves that block out, and [`mean`](Self::mean) over intervals within it uses its three
///   tabulated values.
/// * The work is capped: [`MAX_WORK`](Self::MAX_WORK).
///   Nodes whose colour is provably below the tolerance (S(β) ≤ 1/β² at the band's smallest
///   phase, times the white, below 0.043·accuracy of the floor 555/(N·∫ȳ)) are black without an
///   evaluation: the dense combs of orders of very coarse gratings.
/// * The radiometric BSDF's colour in physical units is the radiometric source's (a paper's
///   table of `Spectral::with_envelope(λ⁻¹)` would measure its tolerance against the paper's
///   unitless floor, about 1/λ too coarse).
///
/// ```
/// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
/// use diffraction::{ColorTable, Grating};
/// let g = Grating::new(1600.0, 800.0, 30)?;
/// let s = Spectral::new(Illuminant::E);
/// let table = ColorTable::new(&s, &g, 1e-3)?;
/// assert_eq!(table.lookup(0.0), s.white()); // the mirror direction is white
/// assert_eq!(table.lookup(-0.4), table.lookup(0.4)); // even in u
/// let exact = s.xyz(&g, 0.4, Strategy::EXACT);
/// assert!((table.lookup(0.4).z - exact.z).abs() < 1e-2 * table.scale());
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ColorTable {
    source: Source,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Grid,
    /// Where order 0's lobe is narrower than the first block (N·d > 360/(20·2⁻⁶⁴) nm): the
    /// end of that block, below which a lookup is `Exact`; −1 where the grid resolves the lobe.
    exact_below: f64,
    /// The integrator of the nodes, for those lookups (see `Source::new`).
    spectral: Spectral,
    /// Colour evaluations the build took.
    evaluations: usize,
}

impl ColorTable {
    /// The accuracy to build a table at when nothing else is asked for: 10⁻⁴, ten times finer
    /// than `Strategy::auto`'s [`DEFAULT_ACCURACY`], so that lookups stay within 0.05 ΔE2000 of
    /// [`Strategy::EXACT`] at the brightest order's exposure on every grating measured: worst
    /// 0.047 (d = 100 µm, N = 30, illuminant E) over 110 gratings under E and D65 (N = 1-4, 5,
    /// 21, 30, 300, 1000, 3000, 10⁶; d = 400, 740, 1600, 10⁴, 10⁵ nm; w = d/2; 1500 u each, half
    /// log-uniform in |u| down to 2·10⁻¹²; `tests/color_table_default.rs`). At 10⁻³ the same
    /// sweep reaches 0.21 ΔE2000, at 3·10⁻⁴ 0.097, at 5·10⁻⁵ 0.017 (with up to 6079 nodes).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// assert_eq!(ColorTable::DEFAULT_ACCURACY, 1e-4);
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::D65), &g, ColorTable::DEFAULT_ACCURACY)?;
    /// assert!(t.error_estimate() <= ColorTable::DEFAULT_ACCURACY);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub const DEFAULT_ACCURACY: f64 = 1e-4;

    /// The smallest `accuracy` at which nodes are computed by [`Strategy::ASYMPTOTIC`] (for
    /// N ≥ 5, where it meets the tolerance: see the [Cost](Self#cost) section); below it every
    /// node is [`Strategy::EXACT`]. `Asymptotic` is within 1.3·10⁻⁴ of the brightest order
    /// (measured, `tests/asymptotic.rs`); the tables built with it at 10⁻⁴ were measured within
    /// 0.027 ΔE2000 of `Exact` (docs/color_table.md).
    ///
    /// ```
    /// use diffraction::spectrum::DEFAULT_ACCURACY;
    /// use diffraction::ColorTable;
    /// assert!(ColorTable::ASYMPTOTIC_ACCURACY <= DEFAULT_ACCURACY);
    /// ```
    pub const ASYMPTOTIC_ACCURACY: f64 = layout::ASYMPTOTIC_ACCURACY;

    /// The version of the stored form (feature `serde`) that this crate writes and reads; a
    /// stored table of another version is refused on load (the error names `format_version`).
    /// The stored form and its checks are described in docs/color_table.md.
    ///
    /// ```
    /// assert_eq!(diffraction::ColorTable::FORMAT_VERSION, 1);
    /// ```
    pub const FORMAT_VERSION: u32 = 1;

    /// The most nodes a table holds (72 bytes each, 442 KiB): refinement stops there, worst blocks
    /// first, and [`error_estimate`](Self::error_estimate) says what was reached. For tabulated
    /// efficiencies this bounds each of its grids over u (two per incidence node).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 5)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.node_count() <= ColorTable::MAX_NODES);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub const MAX_NODES: usize = 6144;

    /// The work budget of a build's refinement, in units of colour evaluations: each
    /// [`Spectral::xyz`] call counts 1 + min(K, 4096)/1024 units for K orders in the band at
    /// its u (the part of every strategy's work that grows with the grating). The initial grid
    /// (at most 1041 nodes, 1040 midpoint checks and 520 block midpoints) is always evaluated;
    /// refinement goes on while the budget lasts (worst blocks first;
    /// [`error_estimate`](Self::error_estimate) says what was reached). Every evaluation does
    /// bounded work, so every build does: the slowest measured are N ≈ 2³² at accuracy 10⁻⁶
    /// (nodes by the peak search over up to 4096 orders, about 0.1-0.3 ms each: 1-2 s for the
    /// table); tables of N ≤ 10⁶ and d ≤ 100 µm stay below the budget. For tabulated efficiencies
    /// this bounds the refinement of each first grid over u (the others take their layout).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.evaluations() <= ColorTable::MAX_WORK);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub const MAX_WORK: usize = 16384;

    /// Tabulates the colour of `source` (a `&Grating` for the paper's colour, a `&GratingBsdf`
    /// for the radiometric one: see [Two sources](Self#two-sources)) under `spectral`'s
    /// illuminant, refining until every interval's midpoint meets `accuracy` in the sense of
    /// the [Accuracy](Self#accuracy) section (relative to [`scale`](Self::scale) per channel,
    /// tighter in the dark) or the node budget [`MAX_NODES`](Self::MAX_NODES) is reached. The
    /// radiometric source applies the BSDF's own envelope (`spectral`'s is not used).
    ///
    /// `accuracy` must lie in [[`MIN_ACCURACY`], [`MAX_ACCURACY`]] (those of `Strategy::auto`;
    /// [`ColorTable::DEFAULT_ACCURACY`] when nothing else is asked for). Measured (docs/color_table.md): 10⁻⁴
    /// keeps lookups within 0.03 ΔE2000 of [`Strategy::EXACT`] at the brightest order's exposure
    /// over 20 representative gratings.
    ///
    /// # Errors
    ///
    /// `accuracy` outside [10⁻⁶, 1] or NaN ([`Requirement::Within`]); the paper's grating with
    /// N = ∞ (parameter `slits`, [`Requirement::Finite`]); a BSDF with a coherence-length
    /// groove (`groove`, [`Requirement::IndependentOfWavelength`], with L as the value) or
    /// tabulated order efficiencies (`efficiency`, [`Requirement::NotTabulated`]).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{ColorTable, Grating, GratingBsdf, GrooveSpread, SpectralResponse};
    /// use diffraction::glam::DVec3;
    /// let s = Spectral::new(Illuminant::D65);
    /// let g = Grating::new(740.0, 370.0, 1000)?;
    /// let t = ColorTable::new(&s, &g, 1e-3)?;
    /// assert!(t.error_estimate() <= 1e-3);
    /// assert_eq!(ColorTable::new(&s, &g, 0.0).unwrap_err().parameter(), "accuracy");
    /// let ideal = Grating::infinite(740.0, 370.0)?;
    /// assert_eq!(ColorTable::new(&s, &ideal, 1e-3).unwrap_err().parameter(), "slits");
    ///
    /// // The radiometric BSDF with a Gaussian groove: cos θi · g(v) · C(u).
    /// let rough = GrooveSpread::gaussian(0.01)?;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?).with_groove(rough);
    /// let t = ColorTable::new(&s, &b, 1e-3)?;
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.34, 0.005, (1.0f64 - 0.34 * 0.34 - 2.5e-5).sqrt()));
    /// let exact = s.xyz_response(&b.grating_response(wo, wi).unwrap(), Strategy::EXACT);
    /// assert!((t.xyz(wo, wi).y - exact.y).abs() < 1e-2 * exact.y);
    /// let default = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?); // L = N·d
    /// assert_eq!(ColorTable::new(&s, &default, 1e-3).unwrap_err().parameter(), "groove");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new<'a>(
        spectral: &Spectral,
        source: impl Into<TableSource<'a>>,
        accuracy: f64,
    ) -> Result<ColorTable, Error> {
        check_accuracy(accuracy)?;
        let (mut source, nodes) = Source::new(source.into(), spectral)?;
        let (grid, evaluations) =
            source.build(&nodes, accuracy, Self::MAX_NODES, Self::MAX_WORK)?;
        Ok(ColorTable::with_grid(
            source,
            nodes,
            spectral.illuminant(),
            accuracy,
            grid,
            evaluations,
        ))
    }

    /// The table of `source` around its `grid` (built or loaded), with `spectral` the
    /// integrator of its nodes.
    fn with_grid(
        source: Source,
        spectral: Spectral,
        illuminant: Illuminant,
        accuracy: f64,
        grid: Grid,
        evaluations: usize,
    ) -> ColorTable {
        let (u_lo, unresolved) = source.first_block();
        ColorTable {
            source,
            illuminant,
            accuracy,
            grid,
            exact_below: if unresolved { u_lo } else { -1.0 },
            spectral,
            evaluations,
        }
    }

    /// The number of colour evaluations ([`Spectral::xyz`] calls) the build took (see
    /// [`MAX_WORK`](Self::MAX_WORK)).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 21)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.evaluations() >= t.node_count()); // every node, and the midpoint checks
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The interpolated colour at u: XYZ(|u|), O(1). |u| > 2 is taken as 2; NaN and ±∞ give
    /// black. Never negative. Black for a table of tabulated efficiencies, whose colour needs
    /// the incidence too (use [`xyz`](Self::xyz)).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{color::Xyz, ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let t = ColorTable::new(&s, &g, 1e-4)?;
    /// let exact = s.xyz(&g, 0.34, Strategy::EXACT);
    /// let got = t.lookup(0.34);
    /// assert!((got.y - exact.y).abs() < 1e-3 * t.scale());
    /// assert_eq!(t.lookup(5.0), t.lookup(2.0)); // clamped
    /// assert_eq!(t.lookup(f64::NAN), Xyz::default());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn lookup(&self, u: f64) -> Xyz {
        let a = u.abs();
        if !a.is_finite() || self.tabulated().is_some() {
            return Xyz::default();
        }
        if a < self.exact_below {
            return self.source.direct(&self.spectral, a);
        }
        self.grid.value(a.min(U_MAX))
    }

    /// The colour at the pair of directions (wo, wi) in the grating's local frame, 0 below the
    /// surface and for non-finite input: the paper's source `lookup(u)` with
    /// u = wi.x + wo.x (as [`AguHill`](crate::AguHill)'s `eval`); the radiometric source the
    /// colour of the BSDF's response f·cos θi, cos θi · g(v) · C(u), with
    /// g = [`GrooveSpread::value`](crate::GrooveSpread::value) (0 for the ideal groove, whose
    /// colour is per unit of δ(v): see [Two sources](Self#two-sources)).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating, GratingBsdf, GrooveSpread};
    /// use diffraction::glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// let s = Spectral::new(Illuminant::E);
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
    /// let paper = ColorTable::new(&s, &g, 1e-3)?;
    /// assert_eq!(paper.xyz(wo, wi), paper.lookup(0.3));
    /// let b = GratingBsdf::new(g).with_groove(GrooveSpread::gaussian(0.02)?);
    /// let t = ColorTable::new(&s, &b, 1e-3)?;
    /// let g0 = b.groove().value(0.0, 550.0);
    /// assert_eq!(t.xyz(wo, wi), t.lookup(0.3).scale(0.91f64.sqrt() * g0));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz(&self, wo: DVec3, wi: DVec3) -> Xyz {
        if !both_above(wo, wi) {
            return Xyz::default();
        }
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        match &self.source {
            Source::Paper { .. } => self.lookup(u),
            Source::Radiometric { bsdf, .. } => {
                // g does not depend on λ here (`Source::new`): any wavelength gives its value.
                let g = bsdf.groove().value(v, LAMBDA_MIN_NM);
                saturate(self.lookup(u).scale(wi.z.min(1.0) * g))
            }
            #[cfg(feature = "relief")]
            Source::Tabulated {
                bsdf,
                incidence,
                planes,
            } => match incidence {
                Some(t) => {
                    let g = bsdf.groove().value(v, LAMBDA_MIN_NM);
                    let u = u.clamp(-U_MAX, U_MAX);
                    let c = if planes.is_empty() {
                        t.value(u, wi.x)
                    } else {
                        let b = wi.y.abs().min(wo.y.abs());
                        source::conical_value(t, planes, u, wi.x, b)
                    };
                    saturate(c.scale(wi.z.min(1.0) * g))
                }
                None => Xyz::default(),
            },
        }
    }

    /// The radiometric source with N = ∞: the colour η₀·white of order 0, a delta δ(u) in the
    /// mirror direction, per unit of δ(u)·g(v) (a renderer reflects the light in the mirror
    /// direction with it, times cos θi and g(v) or the groove's mass). Black otherwise (for
    /// finite N order 0's lobe is in the table; the paper's N = ∞ is refused).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating, GratingBsdf};
    /// let s = Spectral::new(Illuminant::E);
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// let t = ColorTable::new(&s, &b, 1e-3)?;
    /// assert_eq!(t.specular(), s.white().scale(0.25)); // η₀ = ρ² = ¼
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn specular(&self) -> Xyz {
        self.source.specular()
    }

    /// The mean colour over u ∈ [u0, u1] (either order): (1/|u1 − u0|)·∫ XYZ(|u|) du of the
    /// interpolant, O(1); an interval through 0 takes both sides by symmetry, the part beyond
    /// |u| = 2 counts as the colour at 2, and an interval too short for the cumulative form to keep
    /// its digits (below 2⁻²⁰ of its cell, including zero width) gives
    /// [`lookup`](Self::lookup) at its midpoint. A NaN or infinite end gives black.
    ///
    /// This is the colour of a pixel whose footprint (from ray differentials) or light's extent
    /// spans that range of u. Black for a table of tabulated efficiencies (no incidence).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 300)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let t = ColorTable::new(&s, &g, 1e-3)?;
    /// assert_eq!(t.mean(0.3, 0.3), t.lookup(0.3)); // zero width
    /// assert_eq!(t.mean(0.4, 0.2), t.mean(0.2, 0.4)); // either order
    /// let through_zero = t.mean(-0.1, 0.1);
    /// assert!((through_zero.y - t.mean(0.0, 0.1).y).abs() < 1e-12);
    /// // The mean of two halves is the mean of the whole.
    /// let (a, b) = (t.mean(0.2, 0.3), t.mean(0.3, 0.4));
    /// assert!((0.5 * (a.y + b.y) - t.mean(0.2, 0.4).y).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn mean(&self, u0: f64, u1: f64) -> Xyz {
        if self.tabulated().is_some() {
            return Xyz::default();
        }
        self.grid.mean(u0, u1, &|u| self.lookup(u))
    }

    /// The grid for `gpu::GpuColorTable`: the end of block 0, the u below which lookups are
    /// `Exact` (−1 where the grid resolves order 0's lobe), every block's (u0, h, first node,
    /// intervals) and every node's (value, derivative).
    #[cfg(feature = "gpu")]
    #[allow(clippy::type_complexity)]
    pub(crate) fn grid(
        &self,
    ) -> (
        f64,
        f64,
        impl Iterator<Item = (f64, f64, u32, u32)> + '_,
        impl Iterator<Item = ([f64; 3], [f64; 3])> + '_,
    ) {
        let (blocks, nodes) = self.grid.gpu_parts();
        (self.grid.u_lo, self.exact_below, blocks, nodes)
    }

    /// The error scale Y_b: the largest Y at the table's u with d·|u| ≥ 360 nm (the brightest
    /// diffracted colour), at least 555/(N·∫ȳ dλ), the Y of an ideal first-order peak at 555 nm.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// let ideal = 555.0 / (1000.0 * 106.857); // ∫ȳ = 106.857 for the 1 nm CIE 1931 table
    /// assert!(t.scale() >= ideal * (1.0 - 1e-4));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn scale(&self) -> f64 {
        if let Some(t) = self.tabulated() {
            return t.scale;
        }
        self.grid.scale
    }

    /// The worst error found at the midpoint checks when the table was built, in the units of
    /// `accuracy` (see the [Accuracy](Self#accuracy) section: relative to [`scale`](Self::scale)
    /// per channel, weighted as CIELAB is); above the requested accuracy only where refinement
    /// stopped (band-end steps narrower than the finest spacing, or the node budget).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 21)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.error_estimate() <= t.accuracy());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn error_estimate(&self) -> f64 {
        if let Some(t) = self.tabulated() {
            return self.off_plane().fold(t.error, |e, p| e.max(p.error));
        }
        self.grid.error
    }

    /// The accuracy the table was asked for.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 2)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert_eq!(t.accuracy(), 1e-3);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn accuracy(&self) -> f64 {
        self.accuracy
    }

    /// What the table tabulates.
    #[must_use]
    pub fn source(&self) -> TableSource<'_> {
        self.source.view()
    }

    /// The tabulated grating (the BSDF's, for the radiometric source).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 2)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert_eq!(t.grating(), &g);
    /// assert!(t.bsdf().is_none());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn grating(&self) -> &Grating {
        self.source.grating()
    }

    /// The tabulated BSDF of the radiometric source; `None` for the paper's.
    #[must_use]
    pub fn bsdf(&self) -> Option<&GratingBsdf> {
        match &self.source {
            Source::Radiometric { bsdf, .. } => Some(bsdf.as_ref()),
            #[cfg(feature = "relief")]
            Source::Tabulated { bsdf, .. } => Some(bsdf.as_ref()),
            Source::Paper { .. } => None,
        }
    }

    /// The illuminant.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 2)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::D65), &g, 1e-3)?;
    /// assert_eq!(t.illuminant(), Illuminant::D65);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn illuminant(&self) -> Illuminant {
        self.illuminant
    }

    /// The number of nodes.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 2)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.node_count() > 8 && t.node_count() <= ColorTable::MAX_NODES);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn node_count(&self) -> usize {
        if let Some(t) = self.tabulated() {
            return t.node_count() + self.off_plane().map(|p| p.node_count()).sum::<usize>();
        }
        self.grid.node_count()
    }

    /// Heap and inline memory of the table, bytes.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{ColorTable, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let t = ColorTable::new(&Spectral::new(Illuminant::E), &g, 1e-3)?;
    /// assert!(t.size_bytes() >= 72 * t.node_count());
    /// assert!(t.size_bytes() <= 512 * 1024);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn size_bytes(&self) -> usize {
        let incidence = self.tabulated().map_or(0, |t| {
            let planes = self
                .off_plane()
                .map(|p| core::mem::size_of_val(p) + p.heap_bytes())
                .sum::<usize>();
            core::mem::size_of_val(t)
                + t.heap_bytes()
                + core::mem::size_of::<GratingBsdf>()
                + planes
        });
        core::mem::size_of::<Self>() + self.grid.heap_bytes() + incidence
    }

    /// The number of incidence nodes of a table of tabulated efficiencies (see
    /// [Tabulated efficiencies](Self#tabulated-efficiencies)); `None` for the other sources,
    /// whose colour does not depend on the incidence.
    #[must_use]
    pub fn incidence_count(&self) -> Option<usize> {
        #[cfg(feature = "relief")]
        if let Some(t) = self.tabulated() {
            let planes = self.off_plane().map(|p| p.incidence_count()).sum::<usize>();
            return Some(t.incidence_count() + planes);
        }
        None
    }
}

/// `accuracy` within [[`MIN_ACCURACY`], [`MAX_ACCURACY`]]; the error names `accuracy`.
fn check_accuracy(accuracy: f64) -> Result<(), Error> {
    if (MIN_ACCURACY..=MAX_ACCURACY).contains(&accuracy) {
        return Ok(());
    }
    Err(Error::invalid(
        "accuracy",
        accuracy,
        Requirement::Within {
            min: MIN_ACCURACY,
            max: MAX_ACCURACY,
        },
    ))
}
