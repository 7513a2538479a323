//! The order efficiencies η_m of a grating: the share of the incident power each diffraction
//! order carries. A concept of its own beside the shape of the orders' lobes (the N-slit factor
//! and the groove spread), so that a physical efficiency model can replace the amplitude reading
//! without touching the lobes.
//!
//! Two models: the amplitude reading (η_m = ρ²·S(π·ρ·m), the same at every angle and λ) and
//! tabulated efficiencies of relief gratings on metals ([`EfficiencyTable`]), which depend on
//! the incidence and the wavelength. For a tabulated model the value of the pair (wo, wi) in the
//! order m owning u = wi.x + wo.x is
//!
//! ```text
//! η̃_m(wo, wi, λ) = min(η_m(−wi.x, −wi.y, λ), η_m(−wo.x, −wo.y, λ))   (unpolarised: (TE + TM)/2)
//! ```
//!
//! with η_m(α, β, λ) the efficiency for the incident direction of travel with direction cosines
//! α across and β along the grooves. The reciprocity theorem of gratings makes both readings
//! equal in exact theory (the reversed path, light arriving from wo, is the same order m with
//! incidence (−wo.x, −wo.y), and |β| = |wo.y| = |wi.y| on the order's lobe centre, where
//! η depends on |β| only by the grating's mirror symmetry y → −y), so the min changes nothing
//! there; between the table's nodes the interpolation breaks that equality by its error, and
//! the min keeps f exactly reciprocal and below the sampler's weight η_m(−wo.x, −wo.y, λ)
//! (bounded weights, albedo ≤ Σ_m η_m(−wo.x, −wo.y, λ) ≤ 1).
//!
//! A **conical table** (`EfficiencyTable::is_conical`, JSON versions 2 and 3) holds
//! η_m(α, |β|, λ) and is read at the full incident direction; the shipped presets are read so
//! by default (`OrderEfficiency::preset`: their classical tables in reduced coordinates). A
//! **classical table** (version 1, and `Preset::table`) holds the plane of incidence across
//! the grooves only and ignores β: off that plane it is the classical-mount approximation
//! (measured: 22-59 % of orders with η ≥ 1 % within 10 % at azimuths 30-80°;
//! `docs/efficiency_tables.md`, "Conical tables").
//!
//! **The reading.** A classical table whose fast reading exists (feature `std`, at most 2¹⁷
//! values: the presets and the usual user tables; `relief/table/lookup.rs`) gives η̃ from it:
//! the two incidences and the wavelength located in O(1), each order read from its cell's
//! record, both reads finished (no normalisation where the cell's bound needs none). That is
//! the table's rule to rounding, within 2.8·10⁻¹⁶ of the rounding's scale (the corners' q's
//! times cos θm/cos θi) of `EfficiencyTable::efficiency(..).unpolarised()`, not the same bits;
//! every identity of the model (reciprocity, `sample` against `eval` and `pdf`, the
//! four-wavelength forms) holds to the bit because every path reads the same way. A conical
//! table, and every table without `std`, is read by `efficiency_conical`.
//!
//! **The sampler** of a tabulated model: the candidate orders are those of the amplitude model
//! (periods meeting the disk's u-range), clipped to the table's orders and to those that
//! propagate at wo's table query (the query clamped to the grid, as the interpolation clamps
//! it); order m is chosen with the cell proposal P(m) = (1 − δ)·η̂_m/Σ η̂ + δ/K, η̂_m the
//! stored efficiencies of the query's cell corners with its bilinear weights and δ =
//! [`TABULATED_DEFENSIVE_SHARE`](super::TABULATED_DEFENSIVE_SHARE)
//! (one cell search and the corners' stored values: no q-factors, no square roots, no
//! allocation; from the fast reading, Σ η̂ from the corners' running sums over the orders,
//! the same to rounding), written as w_m/Σ w with w_m = (1 − δ)·K·η̂_m + δ·Σ η̂ so that the
//! density divides once. f
//! vanishes wherever η_m(−wo.x, λ) does (the min), and η_m(−wo.x, λ) vanishes for every order
//! that does not propagate at the query, so P(m) ≥ δ/K > 0 wherever f > 0. The rest (u from
//! the period proxy of F_N, v from the groove's Cauchy proxy) is the amplitude model's, and
//! the weight f·cos θi/pdf = (η̃_m/P(m))·N·F_N/q·g/q_v ≤ max_m(η_m/P(m))·B_N·sup g/q_v
//! (B_N = 2·atan N for N ≥ 2, 1 for N = 1; `sample_weight_bound`).
//!
//! **The albedo** of a tabulated model integrates η̃_m(u)·ℓ_m over the disk period by period
//! with the lobe-by-lobe rule (η̃ varies along u through −wi.x = wo.x − u and has the
//! bilinear table's kinks, so the moment rule is not used); for N = ∞ it is Σ η̃_m times the
//! groove's chord mass. Its error is that of the quadrature across the kinks, measured far
//! below the Monte-Carlo furnace's standard error (`tests/bsdf_efficiency.rs`).
//!
//! **Colour**: η̃ depends on λ, which a [`GratingResponse`](crate::GratingResponse) envelope
//! cannot express, so `grating_response` is `None` and the colour integrators take the generic
//! path (response + peaks); `peaks` reports each order with η̃ at the peak's λ, and the
//! wavelength sampler weighs peak m by η̃_m(λ_m)·(d/|m|)·g.

#[cfg(all(feature = "relief", feature = "alloc"))]
use alloc::sync::Arc;

use glam::DVec3;

use super::GratingBsdf;
use crate::error::Error;
#[cfg(feature = "relief")]
use crate::error::Requirement;
use crate::num::kernel::single_slit_cycles;
#[cfg(feature = "relief")]
use crate::relief::EfficiencyTable;
#[cfg(feature = "presets")]
use crate::relief::Preset;
#[cfg(feature = "relief")]
use crate::Grating;
#[cfg(feature = "presets")]
use crate::Slits;

/// The most orders a tabulated model's table may store: the albedo and the sample weight's
/// bound read every order's efficiency for `wo` into a buffer of this many entries on the
/// stack (no allocation). The
/// shipped presets store 9-19; a baked scalar relief stores about 4·d/λ_min + 1 (d up to about
/// 11 µm at 360 nm).
#[cfg(feature = "relief")]
pub const MAX_TABULATED_ORDERS: usize = 128;

/// Where a grating's order efficiencies come from.
///
/// * [`Amplitude`](Self::Amplitude), the paper's grating read as an amplitude grating
///   (reflecting strips of width w on an absorbing background, open fraction ρ = w/d):
///   η_m = ρ²·S(π·ρ·m), Σ_m η_m = ρ (Parseval), the same at every angle and wavelength.
/// * `Tabulated` (feature `relief`): the efficiencies of a relief grating on a metal read
///   from an `EfficiencyTable` at the incidence and the wavelength (a shipped `Preset`,
///   feature `presets`; a `&'static` table; or with feature `alloc` a shared table such as a
///   baked scalar relief): see `OrderEfficiency::preset` and the [module docs](super) for the
///   value min(η_m(−wi.x), η_m(−wo.x)).
///
/// Equality compares tables by address. A tabulated model is not serialised (serde skips the
/// variant: serialising one is an error).
///
/// ```
/// use diffraction::grating_bsdf::OrderEfficiency;
/// use diffraction::{Grating, GratingBsdf};
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
/// assert_eq!(b.order_efficiency(), OrderEfficiency::Amplitude);
/// assert_eq!(b.efficiency(0), 0.25); // ρ² with ρ = ½
/// # #[cfg(feature = "presets")]
/// assert!(OrderEfficiency::preset(diffraction::relief::Preset::Cd).is_tabulated());
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum OrderEfficiency {
    /// η_m = ρ²·S(π·ρ·m): an amplitude grating of open fraction ρ (the paper's reading).
    #[default]
    Amplitude,
    /// η_m(sin θi, λ) from a table (built by [`OrderEfficiency::preset`],
    /// [`OrderEfficiency::from_static`] or [`OrderEfficiency::from_table`]).
    #[cfg(feature = "relief")]
    #[cfg_attr(feature = "serde", serde(skip))]
    Tabulated(Tabulated),
}

/// A table of order efficiencies held by an [`OrderEfficiency::Tabulated`]: `&'static` (the
/// presets; no allocation, `no_std`) or shared (`Arc`, feature `alloc`).
#[cfg(feature = "relief")]
#[derive(Debug, Clone)]
pub struct Tabulated(Held);

/// Without the feature `relief` no table exists: the tabulated source of the order weights is
/// uninhabited, and the compiler removes its paths.
#[cfg(not(feature = "relief"))]
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Tabulated {}

#[cfg(feature = "relief")]
#[derive(Debug, Clone)]
enum Held {
    Static(&'static EfficiencyTable),
    #[cfg(feature = "alloc")]
    Shared(Arc<EfficiencyTable>),
}

#[cfg(feature = "relief")]
impl Tabulated {
    /// The table.
    #[must_use]
    pub fn table(&self) -> &EfficiencyTable {
        match &self.0 {
            Held::Static(t) => t,
            #[cfg(feature = "alloc")]
            Held::Shared(t) => t,
        }
    }
}

#[cfg(feature = "relief")]
impl PartialEq for Tabulated {
    fn eq(&self, other: &Tabulated) -> bool {
        core::ptr::eq(self.table(), other.table())
    }
}

/// A table's order count within [`MAX_TABULATED_ORDERS`], or the error naming `table`.
#[cfg(feature = "relief")]
fn checked(t: &EfficiencyTable) -> Result<(), Error> {
    let count = t.orders().count();
    if count > MAX_TABULATED_ORDERS {
        return Err(Error::invalid(
            "table",
            count as f64,
            Requirement::AtMost {
                bound_name: "MAX_TABULATED_ORDERS",
                bound: MAX_TABULATED_ORDERS as f64,
            },
        ));
    }
    Ok(())
}

impl OrderEfficiency {
    /// A shipped preset's rigorous efficiencies, read conically: at the full incident
    /// direction, across and along the grooves.
    ///
    /// - With feature `std` (the default): [`Preset::conical_table`], the preset's classical
    ///   table in reduced coordinates ([`Preset::reduced_table`]), built once and shared. For
    ///   the four presets it puts 80.8 % of the orders with η ≥ 1 % within 10 % of a conical
    ///   solve at azimuths 30-80° from the grating vector, where the classical reading puts
    ///   41.2 % (`docs/validity.md`, "Conical incidence"). It costs about 4× the classical
    ///   reading's `eval` (`benches/bsdf.rs`).
    /// - With `alloc` but not `std`: the same table, built on each call (1-5 ms) and shared
    ///   by the BSDFs cloned from it.
    /// - Without `alloc`: the classical table ([`Preset::table`]; no allocation).
    ///
    /// The classical reading (sin θi = −wi.x, the plane across the grooves, whatever wi.y) is
    /// `OrderEfficiency::from_static(preset.table())`.
    ///
    /// ```
    /// use diffraction::grating_bsdf::OrderEfficiency;
    /// use diffraction::relief::Preset;
    /// let e = OrderEfficiency::preset(Preset::Foil);
    /// let table = e.table().unwrap();
    /// assert_eq!(table.period_nm(), Preset::Foil.period_nm());
    /// assert!(table.is_conical());
    /// let classical = OrderEfficiency::from_static(Preset::Foil.table())?;
    /// assert!(!classical.table().unwrap().is_conical());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[cfg(feature = "presets")]
    #[must_use]
    pub fn preset(preset: Preset) -> OrderEfficiency {
        #[cfg(feature = "std")]
        let held = Held::Static(preset.conical_table());
        #[cfg(all(feature = "alloc", not(feature = "std")))]
        let held = match preset.reduced_table() {
            Ok(t) => Held::Shared(Arc::new(t)),
            Err(_) => Held::Static(preset.table()),
        };
        #[cfg(not(feature = "alloc"))]
        let held = Held::Static(preset.table());
        OrderEfficiency::Tabulated(Tabulated(held))
    }

    /// The efficiencies of a `&'static` table; an error naming `table` when it stores more than
    /// [`MAX_TABULATED_ORDERS`] orders.
    #[cfg(feature = "relief")]
    pub fn from_static(table: &'static EfficiencyTable) -> Result<OrderEfficiency, Error> {
        checked(table)?;
        Ok(OrderEfficiency::Tabulated(Tabulated(Held::Static(table))))
    }

    /// The efficiencies of a shared table (for instance a baked
    /// [`ScalarRelief`](crate::relief::ScalarRelief)); an error naming `table` when it stores
    /// more than [`MAX_TABULATED_ORDERS`] orders.
    #[cfg(all(feature = "relief", feature = "alloc"))]
    pub fn from_table(table: Arc<EfficiencyTable>) -> Result<OrderEfficiency, Error> {
        checked(&table)?;
        Ok(OrderEfficiency::Tabulated(Tabulated(Held::Shared(table))))
    }

    /// The table of a tabulated model.
    #[cfg(feature = "relief")]
    #[must_use]
    pub fn table(&self) -> Option<&EfficiencyTable> {
        match self {
            OrderEfficiency::Amplitude => None,
            OrderEfficiency::Tabulated(t) => Some(t.table()),
        }
    }

    /// Whether the efficiencies come from a table (they depend on incidence and λ); always
    /// false without the feature `relief`.
    #[must_use]
    pub fn is_tabulated(&self) -> bool {
        self.tabulated().is_some()
    }

    /// The table holder of a tabulated model.
    #[inline]
    pub(super) fn tabulated(&self) -> Option<&Tabulated> {
        match self {
            OrderEfficiency::Amplitude => None,
            #[cfg(feature = "relief")]
            OrderEfficiency::Tabulated(t) => Some(t),
        }
    }
}

/// Unpolarised η of one order of a table for the incident direction of travel (α, β) = `dir`
/// (= (−wi.x, −wi.y)), 0 outside its orders and where it is not a finite positive number. A
/// classical table ignores β.
#[cfg(feature = "relief")]
#[inline]
pub(super) fn eta(t: &EfficiencyTable, order: i64, dir: (f64, f64), lambda_nm: f64) -> f64 {
    if order < i64::from(*t.orders().start()) || order > i64::from(*t.orders().end()) {
        return 0.0;
    }
    // A stored order fits an i32.
    t.unpolarised(order as i32, dir, lambda_nm)
}

impl GratingBsdf {
    /// The same grating with the order efficiencies `efficiency`. A tabulated model brings its
    /// own period: the grating takes the table's period d (keeping N and the open fraction
    /// ρ = w/d, which a tabulated model does not use: its lobes are (N·d/λ)·F_N·g without the
    /// single-slit factor, and the orders' powers are the table's). The groove spread is kept.
    ///
    /// # Errors
    ///
    /// The grating of the table's period cannot be built (ρ·d rounds to 0: an open fraction
    /// below about 10⁻³⁰⁸/d): the [`Grating`](crate::Grating) error, naming `slit_width_nm`. Before, the old
    /// period was silently kept.
    ///
    /// ```
    /// use diffraction::grating_bsdf::OrderEfficiency;
    /// use diffraction::relief::Preset;
    /// use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1500.0, 750.0, 30)?)
    ///     .with_efficiency(OrderEfficiency::preset(Preset::Cd))?;
    /// assert_eq!(b.grating().period_nm(), 1600.0);
    /// assert!(b.order_efficiency().is_tabulated());
    /// // A slit of 5e-324 nm on a 1600 nm grating is an open fraction of 0 at the DVD's period.
    /// let thin = GratingBsdf::new(Grating::new(1600.0, 5e-324, 30)?);
    /// let e = thin.with_efficiency(OrderEfficiency::preset(Preset::Dvd)).unwrap_err();
    /// assert_eq!(e.to_string(), "invalid slit_width_nm = 0: must be finite and > 0");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_efficiency(&self, efficiency: OrderEfficiency) -> Result<GratingBsdf, Error> {
        #[cfg(feature = "relief")]
        let grating = match efficiency.table() {
            Some(t) if t.period_nm() != self.grating.period_nm() => {
                let d = t.period_nm();
                Grating::with_slits(d, self.grating.open_fraction() * d, self.grating.slits())?
            }
            _ => self.grating,
        };
        #[cfg(not(feature = "relief"))]
        let grating = self.grating;
        Ok(GratingBsdf::build(grating, self.groove, efficiency))
    }

    /// A shipped preset's grating (its rigorous order efficiencies read conically,
    /// [`OrderEfficiency::preset`]) with
    /// `slits` coherently lit grooves and the natural groove spread of [`GratingBsdf::new`]
    /// (a coherence length N·d; ideal for N = ∞). The period is the table's; the open
    /// fraction is irrelevant for a tabulated model (set to ½). An error naming `slits` for
    /// N = 0.
    ///
    /// **Choosing N.** N is the number of grooves the light illuminates coherently, not the
    /// number on the part: the coherence width of light from a source of angular size δ is
    /// about λ/δ, so a lamp of δ = 0.01 rad at 550 nm lights about 55 µm coherently, about 34
    /// grooves of a CD (d = 1.6 µm); the sun (δ ≈ 0.0093 rad) about the same; a distant point
    /// source or a laser many more (N = ∞ is the limit). Larger N narrows each order's lobe
    /// (half-width λ/(N·d) in u) without changing its power.
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// use diffraction::{GratingBsdf, Slits};
    /// let cd = GratingBsdf::preset(Preset::Cd, 34)?;
    /// assert_eq!(cd.grating().slits(), Slits::Finite(34));
    /// assert_eq!(GratingBsdf::preset(Preset::Dvd, Slits::Infinite)?.grating().period_nm(), 740.0);
    /// assert_eq!(GratingBsdf::preset(Preset::Cd, 0).unwrap_err().parameter(), "slits");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[cfg(feature = "presets")]
    pub fn preset(preset: Preset, slits: impl Into<Slits>) -> Result<GratingBsdf, Error> {
        let d = preset.period_nm();
        let grating = Grating::with_slits(d, 0.5 * d, slits.into())?;
        GratingBsdf::new(grating).with_efficiency(OrderEfficiency::preset(preset))
    }

    /// Where the order efficiencies come from.
    ///
    /// ```
    /// use diffraction::grating_bsdf::OrderEfficiency;
    /// use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert_eq!(b.order_efficiency(), OrderEfficiency::Amplitude);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn order_efficiency(&self) -> OrderEfficiency {
        self.efficiency.clone()
    }

    /// The efficiency η_m of order m: the share of the incident power it carries over the whole
    /// (u, v) plane; for the amplitude reading η_m = ρ²·S(π·ρ·m) and Σ_m η_m = ρ (Parseval).
    ///
    /// ```
    /// use diffraction::{Grating, GratingBsdf};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?);
    /// assert_eq!(b.efficiency(0), 0.25);
    /// assert!(b.efficiency(2) < 1e-30); // w = d/2: even orders are missing
    /// let total: f64 = (-20000..=20000).map(|m| b.efficiency(m)).sum();
    /// assert!((total - 0.5).abs() < 1e-5); // Parseval, to the 1/m² tail
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    ///
    /// A tabulated model's efficiencies depend on incidence and λ
    /// ([`efficiency_at`](Self::efficiency_at)); for it this is η_m at normal incidence at
    /// 550 nm.
    #[must_use]
    pub fn efficiency(&self, order: i32) -> f64 {
        #[cfg(feature = "relief")]
        if let Some(t) = self.table() {
            return eta(t, i64::from(order), (0.0, 0.0), 550.0);
        }
        let rho = self.grating.open_fraction();
        rho * rho * single_slit_cycles(rho * f64::from(order))
    }

    /// The table of a tabulated model.
    #[cfg(feature = "relief")]
    #[inline]
    pub(super) fn table(&self) -> Option<&EfficiencyTable> {
        self.efficiency.table()
    }

    /// η̃_m = min(η_m(−wi.x, −wi.y, λ), η_m(−wo.x, −wo.y, λ)) of a tabulated model (see the
    /// [module docs](super)), unpolarised; the amplitude reading's η_m otherwise. Symmetric in
    /// (wo, wi) and ≥ 0; 0 for orders the table does not store and for non-finite input.
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// use diffraction::GratingBsdf;
    /// use glam::DVec3;
    /// let cd = GratingBsdf::preset(Preset::Cd, diffraction::Slits::Infinite)?;
    /// // Order 1 of 550 nm from normal incidence leaves at wi.x = λ/d.
    /// let (wo, x) = (DVec3::Z, 550.0 / 1600.0);
    /// let wi = DVec3::new(x, 0.0, (1.0 - x * x).sqrt());
    /// let e = cd.efficiency_at(1, wo, wi, 550.0);
    /// assert!(e > 0.0 && e < 1.0);
    /// assert_eq!(e, cd.efficiency_at(1, wi, wo, 550.0)); // reciprocal
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn efficiency_at(&self, order: i32, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        #[cfg(feature = "relief")]
        if let Some(t) = self.table() {
            return t
                .incidences((-wo.x, -wo.y), (-wi.x, -wi.y))
                .min(i64::from(order), lambda_nm);
        }
        #[cfg(not(feature = "relief"))]
        let _ = (wo, wi, lambda_nm);
        self.efficiency(order)
    }
}
