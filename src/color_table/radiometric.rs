//! The colour of the radiometric [`GratingBsdf`] in physical units, tabulated over u (see
//! [`RadiometricTable`]).

use glam::DVec3;

use super::grid::{power_of_two_below, work_units};
use super::nodes::GratingNodes;
use super::tabulated::{Plan, Tabulated};
use super::{first_block, ColorTable, DARK_SHARE, LAMBDA_MAX_NM, LAMBDA_MIN_NM, MIN_U_LO, U_MAX};
use crate::bxdf::both_above;
use crate::color::Xyz;
use crate::error::{Error, Requirement};
use crate::spectrum::{saturate, Illuminant, Spectral, Strategy, MAX_ACCURACY, MIN_ACCURACY};
use crate::{Band, Envelope, GratingBsdf, GrooveKind, Slits, MAX_ORDERS};

/// The colour C(u) of a [`GratingBsdf`] per unit of its spread g(v) along the grooves, in the
/// units of [`Spectral`]'s colour (a white reflector has Y = 1), tabulated over |u| ∈ [0, 2]
/// with O(1) lookups and O(1) means over intervals of u: the physical-units companion of
/// [`ColorTable`] (which tabulates the paper's unitless intensity).
///
/// # What it is
///
/// Where the BSDF's colour factorises as g(v)·C(u), the crate's colour of the BSDF's response
/// f·cos θi at (wo, wi) ([`Spectral::xyz_response`] of
/// [`SpectralResponse::grating_response`](crate::SpectralResponse::grating_response), or for
/// N = ∞ the areas of [`SpectralResponse::peaks`](crate::SpectralResponse::peaks)) is
///
/// ```text
/// XYZ(wo, wi) = cos θi · g(v) · C(u),     C(u) = ∫ E(λ)·[f/g](u, λ)·cmf(λ) dλ / ∫ E·ȳ dλ,
/// ```
///
/// u = (wi + wo)·t, v = (wi + wo)·y; [`lookup`](Self::lookup) returns C(u) (1/sr per unit of
/// g, cosine excluded) and [`xyz`](Self::xyz) the product. It factorises exactly where g does
/// not depend on λ and the order efficiencies do not depend on the directions or λ:
///
/// * **Gaussian groove, finite N**: f/g = ρ²·S·(N·d/λ)·F_N, so C(u) = ρ²·N·d times the colour of
///   the grating's intensity with the envelope λ⁻¹ ([`Spectral::with_envelope`]).
/// * **Ideal groove δ(v)**: the same C(u); the colour is C(u) per unit of δ(v), so a renderer
///   multiplies by the groove's mass over the v its light covers (1 if that holds v = 0), not
///   by a value ([`xyz`](Self::xyz) is 0, as `eval`).
/// * **N = ∞** (with either groove): the delta lobes of every order integrate over λ to
///   C(u) = Σ_m η_m·(d/|m|)·E(λ_m)·cmf(λ_m)/∫E·ȳ, λ_m = d·|u|/|m| in the band (the orders of
///   `peaks`, at most [`MAX_ORDERS`]), a function of u; order 0 is a delta δ(u) of colour
///   η₀·white per unit of δ(u)·g(v) ([`specular`](Self::specular)), the mirror reflection, not
///   in the table. Large-N tables converge to it away from u = 0.
/// * **Coherence length** L (the default of [`GratingBsdf::new`] for finite N): g = (L/λ)·
///   sinc²(π·L·v/λ) depends on λ, so the colour at (u, v) is not g(v)·C(u); refused (the error
///   names `groove`). Use [`Spectral::xyz_response`] per direction, or a Gaussian groove of
///   the width wanted ([`GratingBsdf::with_groove`]).
///
/// # What a renderer multiplies by
///
/// * A point or distant light of the illuminant's spectrum whose irradiance at normal
///   incidence has luminance E⊥ (∫E·ȳ of that irradiance; the unit of `Spectral`'s colour is
///   E⊥ = 1, under which a surface with f·cos θi ≡ 1 has Y = 1 and a white Lambertian one
///   1/π): radiance XYZ toward wo = E⊥ · cos θi · g(v) · `lookup(u)`
///   (= E⊥ · [`xyz`](Self::xyz)`(wo, wi)`).
/// * An area light of radiance L whose image in the (u, v) plane is the rectangle
///   [u0, u1] × [v0, v1] (d(wi.x)·d(wi.y) = cos θi·dωi): XYZ = L · (u1 − u0) ·
///   `mean(u0, u1)` · [`GrooveSpread::mass`](crate::GrooveSpread::mass)`(v0, v1, ·)` exactly,
///   since ∫f·cos θi dωi = ∬ f du dv.
/// * A pixel footprint [u0, u1] of a point light ([`footprint::u_interval`](crate::footprint::u_interval)):
///   E⊥ · cos θi · g(v) · `mean(u0, u1)`.
///
/// # Accuracy and cost
///
/// The grid, its refinement and its tolerance are those of [`ColorTable`] (its
/// [Accuracy](ColorTable#accuracy) section, with the error scale Y_b the largest Y at
/// d·|u| ≥ 360 nm, at least ρ²·d/∫ȳ: an order of efficiency ρ² at 555 nm under E); nodes of
/// finite N cost what `ColorTable`'s do, nodes of N = ∞ O(orders). Measured at 10⁻⁴
/// (`tests/radiometric_table.rs`, docs/color_table.md): within 7.4·10⁻⁵ of the exposure and
/// 0.023 ΔE2000 of the direct colour; `xyz` 75-88 ns against 441 µs for `Exact`; builds
/// 15 ms (N = ∞) to 0.46 s (d = 1600 nm, N = 1000), about `ColorTable`'s for the same grating.
#[derive(Debug, Clone, PartialEq)]
pub struct RadiometricTable {
    bsdf: GratingBsdf,
    illuminant: Illuminant,
    accuracy: f64,
    grid: Tabulated,
    /// Finite N whose order-0 lobe is narrower than the first block: below this a lookup is
    /// computed (`Exact`); −1 otherwise.
    exact_below: f64,
    /// The integrator with the envelope λ⁻¹ (finite N), for those lookups.
    spectral: Spectral,
    /// ρ²·N·d (finite N), the factor of those lookups.
    k: f64,
    /// η₀·white for N = ∞; black for finite N (order 0 is in the table).
    specular: Xyz,
    evaluations: usize,
}

/// Whether the BSDF's colour factorises as g(v)·C(u): its order efficiencies must not depend
/// on the directions or λ, and its groove spread not on λ. Errors name `efficiency` or `groove`.
pub(super) fn factorises(bsdf: &GratingBsdf) -> Result<(), Error> {
    // An efficiency model that depends on incidence or λ does not factorise into one C(u).
    #[cfg(feature = "relief")]
    if let Some(t) = bsdf.order_efficiency().table() {
        return Err(Error::invalid(
            "efficiency",
            t.orders().count() as f64,
            Requirement::NotTabulated,
        ));
    }
    match bsdf.groove().kind() {
        GrooveKind::CoherenceLength { length_nm } => Err(Error::invalid(
            "groove",
            length_nm,
            Requirement::IndependentOfWavelength,
        )),
        GrooveKind::Gaussian { .. } | GrooveKind::Ideal => Ok(()),
    }
}

/// The end of the first block of a BSDF's table and whether that block is left to direct
/// evaluation: finite N as [`ColorTable`]; N = ∞ 2^⌊log₂(360 nm/d)⌋ (no order reaches the band
/// below 360 nm/d), within [2⁻⁶⁴, 1].
pub(super) fn radiometric_first_block(bsdf: &GratingBsdf) -> (f64, bool) {
    let g = bsdf.grating();
    match g.slits() {
        Slits::Finite(_) => first_block(g),
        Slits::Infinite => (
            power_of_two_below(LAMBDA_MIN_NM / g.period_nm()).clamp(MIN_U_LO, 1.0),
            false,
        ),
    }
}

impl RadiometricTable {
    /// The most nodes a table holds: [`ColorTable::MAX_NODES`].
    pub const MAX_NODES: usize = ColorTable::MAX_NODES;
    /// The work budget of a build: [`ColorTable::MAX_WORK`] (an N = ∞ node counts as a finite
    /// one with the same orders).
    pub const MAX_WORK: usize = ColorTable::MAX_WORK;
    /// The version of the stored form (feature `serde`): [`ColorTable::FORMAT_VERSION`].
    pub const FORMAT_VERSION: u32 = ColorTable::FORMAT_VERSION;

    /// Tabulates C(u) of `bsdf` under `spectral`'s illuminant (its envelope is not used: the
    /// table applies the BSDF's own) to `accuracy` in the sense of [`ColorTable`].
    ///
    /// # Errors
    ///
    /// `accuracy` outside [10⁻⁶, 1] or NaN ([`Requirement::Within`]); a coherence-length groove
    /// (`groove`, [`Requirement::IndependentOfWavelength`], with L as the value).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread, RadiometricTable, SpectralResponse};
    /// use glam::DVec3;
    /// let s = Spectral::new(Illuminant::D65);
    /// let rough = GrooveSpread::gaussian(0.01)?;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?).with_groove(rough);
    /// let t = RadiometricTable::new(&s, &b, 1e-3)?;
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.34, 0.005, (1.0f64 - 0.34 * 0.34 - 2.5e-5).sqrt()));
    /// let exact = s.xyz_response(&b.grating_response(wo, wi).unwrap(), Strategy::EXACT);
    /// let got = t.xyz(wo, wi); // cos θi · g(v) · C(u)
    /// assert!((got.y - exact.y).abs() < 1e-2 * exact.y);
    /// let default = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?); // L = N·d
    /// assert_eq!(RadiometricTable::new(&s, &default, 1e-3).unwrap_err().parameter(), "groove");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(
        spectral: &Spectral,
        bsdf: &GratingBsdf,
        accuracy: f64,
    ) -> Result<RadiometricTable, Error> {
        if !(MIN_ACCURACY..=MAX_ACCURACY).contains(&accuracy) {
            return Err(Error::invalid(
                "accuracy",
                accuracy,
                Requirement::Within {
                    min: MIN_ACCURACY,
                    max: MAX_ACCURACY,
                },
            ));
        }
        factorises(bsdf)?;
        let illuminant = spectral.illuminant();
        let plain = Spectral::new(illuminant);
        let white = plain.white();
        let white = [white.x, white.y, white.z];
        let g = bsdf.grating();
        let (d, rho) = (g.period_nm(), g.open_fraction());
        // Clamped to the normal range: a scale of 0 (d = 5e-324 nm) would leave no tolerance.
        let floor = (rho * rho * d / crate::cie::cmf_areas()[1]).clamp(f64::MIN_POSITIVE, f64::MAX);
        let (u_lo, unresolved) = radiometric_first_block(bsdf);
        let plan = Plan {
            accuracy,
            white,
            floor,
            diffracted_from: LAMBDA_MIN_NM / d,
            u_lo,
            skip_first: unresolved,
            period_nm: d,
            max_nodes: Self::MAX_NODES,
            max_work: Self::MAX_WORK,
        };
        let (grid, evaluations) = match g.slits() {
            Slits::Finite(n) => {
                let n = n as f64;
                let per_nm = plain.with_envelope(Envelope::new(1, 0.0)?);
                let k = (rho * rho * n * d).min(f64::MAX);
                let nodes = GratingNodes::new(&per_nm, g, n, accuracy, k, white, floor)?;
                let grid = Tabulated::build(&plan, &|u, scale| nodes.eval(u, scale), &|| {
                    nodes.work_done.get()
                });
                (grid, nodes.evaluations.get())
            }
            Slits::Infinite => {
                let delta = DeltaNodes::new(&plain, bsdf, accuracy, white, floor);
                let grid =
                    Tabulated::build(&plan, &|u, _| delta.eval(u), &|| delta.work_done.get());
                (grid, delta.evaluations.get())
            }
        };
        Self::with_grid(bsdf, illuminant, accuracy, grid, evaluations)
    }

    /// The table of `bsdf` (checked by [`factorises`]) around its tabulated `grid`: the
    /// integrator and factor of the direct lookups, and the order-0 delta.
    pub(super) fn with_grid(
        bsdf: &GratingBsdf,
        illuminant: Illuminant,
        accuracy: f64,
        grid: Tabulated,
        evaluations: usize,
    ) -> Result<RadiometricTable, Error> {
        let plain = Spectral::new(illuminant);
        let g = bsdf.grating();
        let rho = g.open_fraction();
        let (u_lo, unresolved) = radiometric_first_block(bsdf);
        let (k, spectral, specular) = match g.slits() {
            Slits::Finite(n) => (
                (rho * rho * n as f64 * g.period_nm()).min(f64::MAX),
                plain.with_envelope(Envelope::new(1, 0.0)?),
                Xyz::default(),
            ),
            Slits::Infinite => (1.0, plain, plain.white().scale(bsdf.efficiency(0))),
        };
        Ok(RadiometricTable {
            bsdf: bsdf.clone(),
            illuminant,
            accuracy,
            grid,
            exact_below: if unresolved { u_lo } else { -1.0 },
            spectral,
            k,
            specular,
            evaluations,
        })
    }

    /// C(|u|), O(1): the colour of f·cos θi per unit of cos θi·g(v) (see the
    /// [type docs](Self)). |u| > 2 is taken as 2; NaN and ±∞ give black. Never negative.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{color::Xyz, Grating, GratingBsdf, GrooveSpread, RadiometricTable};
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?); // an ideal groove
    /// let t = RadiometricTable::new(&Spectral::new(Illuminant::E), &b, 1e-3)?;
    /// assert_eq!(t.lookup(0.1), Xyz::default()); // d·u = 160 nm: no order in the band
    /// assert!(t.lookup(0.34).y > 0.0); // order 1 at 544 nm
    /// assert_eq!(t.lookup(-0.34), t.lookup(0.34));
    /// assert_eq!(t.lookup(f64::NAN), Xyz::default());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn lookup(&self, u: f64) -> Xyz {
        let a = u.abs();
        if !a.is_finite() {
            return Xyz::default();
        }
        if a < self.exact_below {
            let c = self.spectral.xyz(self.bsdf.grating(), a, Strategy::EXACT);
            return saturate(c.scale(self.k));
        }
        self.grid.value(a.min(U_MAX))
    }

    /// The colour of the BSDF's response f·cos θi at (wo, wi): cos θi · g(v) · C(u), with
    /// g = [`GrooveSpread::value`](crate::GrooveSpread::value) (0 for the ideal groove, whose
    /// colour is per unit of δ(v): see the [type docs](Self)). 0 below the surface and for
    /// non-finite input.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread, RadiometricTable};
    /// use glam::DVec3;
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 100)?)
    ///     .with_groove(GrooveSpread::gaussian(0.02)?);
    /// let t = RadiometricTable::new(&Spectral::new(Illuminant::E), &b, 1e-3)?;
    /// let (wo, wi) = (DVec3::Z, DVec3::new(0.3, 0.0, 0.91f64.sqrt()));
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
        // g does not depend on λ here (`factorises`): any wavelength gives its value.
        let g = self.bsdf.groove().value(v, LAMBDA_MIN_NM);
        saturate(self.lookup(u).scale(wi.z.min(1.0) * g))
    }

    /// The mean of C over u ∈ [u0, u1] (either order), O(1), as [`ColorTable::mean`]: an
    /// interval through 0 takes both sides, the part beyond |u| = 2 counts as C(2), an interval
    /// below 2⁻²⁰ of its cell gives [`lookup`](Self::lookup) at its midpoint; a NaN or
    /// infinite end gives black. For N = ∞ the order-0 delta is not in it
    /// ([`specular`](Self::specular)).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{Grating, GratingBsdf, GrooveSpread, RadiometricTable};
    /// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 300)?)
    ///     .with_groove(GrooveSpread::gaussian(0.02)?);
    /// let t = RadiometricTable::new(&Spectral::new(Illuminant::D65), &b, 1e-3)?;
    /// assert_eq!(t.mean(0.3, 0.3), t.lookup(0.3));
    /// let (a, c) = (t.mean(0.2, 0.3), t.mean(0.3, 0.4));
    /// assert!((0.5 * (a.y + c.y) - t.mean(0.2, 0.4).y).abs() < 1e-12 * t.scale());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn mean(&self, u0: f64, u1: f64) -> Xyz {
        self.grid.mean(u0, u1, &|u| self.lookup(u))
    }

    /// N = ∞: the colour η₀·white of order 0, a delta δ(u) in the mirror direction, per unit
    /// of δ(u)·g(v) (a renderer reflects the light in the mirror direction with it, times
    /// cos θi and g(v) or the groove's mass). Finite N: black (order 0's lobe is in the table).
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{Grating, GratingBsdf, RadiometricTable};
    /// let s = Spectral::new(Illuminant::E);
    /// let b = GratingBsdf::new(Grating::infinite(1600.0, 800.0)?);
    /// let t = RadiometricTable::new(&s, &b, 1e-3)?;
    /// assert_eq!(t.specular(), s.white().scale(0.25)); // η₀ = ρ² = ¼
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn specular(&self) -> Xyz {
        self.specular
    }

    /// The tabulated function.
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(super) fn grid(&self) -> &Tabulated {
        &self.grid
    }

    /// The tabulated BSDF.
    #[must_use]
    pub fn bsdf(&self) -> &GratingBsdf {
        &self.bsdf
    }

    /// The illuminant.
    #[must_use]
    pub fn illuminant(&self) -> Illuminant {
        self.illuminant
    }

    /// The accuracy the table was asked for.
    #[must_use]
    pub fn accuracy(&self) -> f64 {
        self.accuracy
    }

    /// The error scale Y_b (see the [type docs](Self)), in the units of C.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.grid.scale
    }

    /// The worst midpoint error of the build, in units of `accuracy` (as
    /// [`ColorTable::error_estimate`]).
    #[must_use]
    pub fn error_estimate(&self) -> f64 {
        self.grid.error
    }

    /// The number of node evaluations the build took.
    #[must_use]
    pub fn evaluations(&self) -> usize {
        self.evaluations
    }

    /// The number of nodes.
    #[must_use]
    pub fn node_count(&self) -> usize {
        self.grid.node_count()
    }

    /// Heap and inline memory of the table, bytes.
    #[must_use]
    pub fn size_bytes(&self) -> usize {
        core::mem::size_of::<Self>() + self.grid.heap_bytes()
    }
}

/// The nodes of an N = ∞ table: Σ_m η_m·(d/|m|)·weight(λ_m) over the orders of
/// `Grating::peaks` (at most [`MAX_ORDERS`]), black without evaluation where provably below the
/// tolerance.
struct DeltaNodes<'a> {
    spectral: &'a Spectral,
    bsdf: &'a GratingBsdf,
    /// An upper bound of weight(λ) per channel over the band, over the white.
    peak_weight: [f64; 3],
    white: [f64; 3],
    /// DARK_SHARE·accuracy·floor.
    dark: f64,
    evaluations: core::cell::Cell<usize>,
    work_done: core::cell::Cell<usize>,
}

/// An upper bound of `spectral.weight(λ)` per channel over the band: E and the observer are
/// linear between their 1 nm rows, so each is largest at a row, and the product of their
/// largest values bounds the weight.
pub(super) fn peak_weight(spectral: &Spectral) -> [f64; 3] {
    let (mut e_max, mut c_max) = (0.0f64, [0.0f64; 3]);
    let mut l = LAMBDA_MIN_NM;
    while l <= LAMBDA_MAX_NM {
        let w = spectral.weight(l);
        let e = spectral.illuminant().power(l);
        e_max = e_max.max(e);
        if e > 0.0 {
            c_max = [
                c_max[0].max(w.x / e),
                c_max[1].max(w.y / e),
                c_max[2].max(w.z / e),
            ];
        }
        l += 1.0;
    }
    [e_max * c_max[0], e_max * c_max[1], e_max * c_max[2]]
}

impl<'a> DeltaNodes<'a> {
    fn new(
        spectral: &'a Spectral,
        bsdf: &'a GratingBsdf,
        accuracy: f64,
        white: [f64; 3],
        floor: f64,
    ) -> DeltaNodes<'a> {
        let peak_weight = peak_weight(spectral);
        DeltaNodes {
            spectral,
            bsdf,
            peak_weight,
            white,
            dark: accuracy * DARK_SHARE * floor,
            evaluations: core::cell::Cell::new(0),
            work_done: core::cell::Cell::new(0),
        }
    }

    /// Σ_m η_m·(d/|m|) ≤ d·Σ_{m ≥ a} 1/(π²·m³) ≤ d·(1/a³ + 1/(2a²))/π² with a the lowest order
    /// in the band (η_m = ρ²·S(π·ρ·m) ≤ 1/(π·m)²): where that times the peak weight is below
    /// the tolerance in every channel the node is black.
    fn provably_dark(&self, u: f64) -> bool {
        let d = self.bsdf.grating().period_nm();
        let a = (d * u / LAMBDA_MAX_NM).max(1.0);
        let pi2 = core::f64::consts::PI * core::f64::consts::PI;
        let bound = d * (1.0 / (a * a * a) + 0.5 / (a * a)) / pi2;
        a > 1.0 && (0..3).all(|c| bound * self.peak_weight[c] <= self.dark * self.white[c])
    }

    fn eval(&self, u: f64) -> [f64; 3] {
        if self.provably_dark(u) {
            return [0.0; 3];
        }
        let g = self.bsdf.grating();
        let d = g.period_nm();
        self.evaluations.set(self.evaluations.get() + 1);
        self.work_done.set(self.work_done.get() + work_units(d * u));
        let mut acc = DVec3::ZERO;
        for p in g.peaks(u, Band::VISIBLE).take(MAX_ORDERS as usize) {
            let area = self.bsdf.efficiency(p.order) * d / p.order.unsigned_abs() as f64;
            acc += self.spectral.weight(p.wavelength_nm) * area;
        }
        let c = saturate(Xyz::new(acc.x, acc.y, acc.z));
        [c.x, c.y, c.z]
    }
}
