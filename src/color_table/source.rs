//! What a colour table tabulates: the paper's grating or the radiometric [`GratingBsdf`], and
//! what each source brings to the shared grid (its checks, its error floor, its first block,
//! its node values, its direct lookups where the grid leaves the first block to them, the
//! order-0 delta of N = ∞).
//!
//! A BSDF whose order efficiencies are tabulated (feature `relief`) has a colour C(u, s) that
//! depends on the incidence s = wi.x as well: it is the third [`Source`] variant, holding one
//! pair of grids per incidence node (`incidence.rs`, each built by [`Grid::build`] from
//! `tabulated_nodes.rs`), with `ColorTable::xyz(wo, wi)` interpolating between them;
//! `lookup(u)` and `mean`, which have no incidence, do not apply to it (black).

use alloc::boxed::Box;
#[cfg(feature = "relief")]
use alloc::vec::Vec;

use super::delta_nodes::{peak_weight, DeltaNodes};
use super::grating_nodes::GratingNodes;
use super::grid::{Grid, Limits, Plan};
#[cfg(feature = "relief")]
use super::incidence::Incidence;
use super::layout::{comb_block, lobe_block, LAMBDA_MIN_NM};
#[cfg(feature = "relief")]
use super::tabulated_nodes::TabulatedNodes;
use crate::color::Xyz;
use crate::error::{Error, Requirement};
#[cfg(feature = "relief")]
use crate::num::math;
use crate::spectrum::Spectral;
use crate::{Envelope, Grating, GratingBsdf, GrooveKind, Slits};

/// What a [`ColorTable`](crate::ColorTable) tabulates: the argument of
/// [`ColorTable::new`](crate::ColorTable::new) (from `&Grating` or `&GratingBsdf`, by `From`)
/// and the answer of [`ColorTable::source`](crate::ColorTable::source).
///
/// ```
/// use diffraction::spectrum::{Illuminant, Spectral};
/// use diffraction::{ColorTable, Grating, GratingBsdf, GrooveSpread, TableSource};
/// let g = Grating::new(1600.0, 800.0, 30)?;
/// let s = Spectral::new(Illuminant::E);
/// let paper = ColorTable::new(&s, &g, 1e-2)?;
/// assert_eq!(paper.source(), TableSource::Paper(&g));
/// let b = GratingBsdf::new(g).with_groove(GrooveSpread::gaussian(0.02)?);
/// let physical = ColorTable::new(&s, &b, 1e-2)?;
/// assert_eq!(physical.source(), TableSource::Radiometric(&b));
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum TableSource<'a> {
    /// The paper's unitless intensity I(u, λ) = S(β)·F_N(α) of a finite grating: the table
    /// holds its colour [`Spectral::xyz`].
    Paper(&'a Grating),
    /// The radiometric BSDF with a groove spread that does not depend on λ (Gaussian or
    /// ideal) and the amplitude order efficiencies: the table holds C(u), its colour per unit
    /// of cos θi·g(v), in physical units.
    Radiometric(&'a GratingBsdf),
}

impl<'a> From<&'a Grating> for TableSource<'a> {
    fn from(g: &'a Grating) -> TableSource<'a> {
        TableSource::Paper(g)
    }
}

impl<'a> From<&'a GratingBsdf> for TableSource<'a> {
    fn from(b: &'a GratingBsdf) -> TableSource<'a> {
        TableSource::Radiometric(b)
    }
}

/// The planes |wi.y| = β of a conical table's colour (wo.y = −β, the groove lobe's centre):
/// C(u, s, β) is tabulated on each and interpolated linearly in c = √(1 − β²) between them
/// (at the same place σ between the grazing directions), the last plane's beyond it. Measured
/// on the CD (N = 34, D65, 10⁻³, the planes off β = 0 at 10⁻²): 9 planes gave a mean ΔE2000
/// of 0.073 / 0.153 / 0.491 for |wi.y| in 0.05-0.3 / 0.3-0.6 / 0.6-0.9 in 21.5 s of build;
/// 5 planes (0, 0.4, 0.65, 0.85, 0.95, at 4·10⁻³) 0.082 / 0.164 / 0.518 in 20.7 s, and at
/// 10⁻³ 0.081 / 0.157 / 0.516 in 67 s: the error is the interpolation between planes.
#[cfg(feature = "relief")]
pub(super) const COLOUR_PLANES: [f64; 9] = [0.0, 0.25, 0.4, 0.52, 0.63, 0.73, 0.82, 0.9, 0.96];

/// The finest accuracy of a conical table's planes off the plane across the grooves: their
/// error is mostly the interpolation between the planes ([`COLOUR_PLANES`]), which the
/// planes' own accuracy hardly changes and their cost does (three times the build at 10⁻³).
#[cfg(feature = "relief")]
const OFF_PLANE_ACCURACY: f64 = 1e-2;

/// The finest accuracy of a tabulated table's grids over u (a finer one is taken as this for
/// the grids; the incidence bisection takes the table's own). Measured on the CD preset (N = 34,
/// D65, 4000 pairs against the 4096-wavelength colour, both grids of every incidence node
/// built): at 10⁻³ 0.15 ΔE2000 (5-7 s, 9.5 MB), at 5·10⁻⁴ 0.078 (18 s, 21.5 MB), at 2.5·10⁻⁴
/// 0.043 (69 s, 81 MB); the grids at 10⁻⁴ cost several times more (225 s, 57 MB with the
/// incidence at its depth of 10⁻³, and no better). A mirror-symmetric profile halves each.
#[cfg(feature = "relief")]
pub(super) const TABULATED_ACCURACY: f64 = 2.5e-4;

/// The source a table keeps, with what its direct lookups need.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Source {
    /// The paper's colour of a finite grating.
    Paper { grating: Grating },
    /// The radiometric BSDF's C(u).
    Radiometric {
        /// Boxed: a `GratingBsdf` is several times the size of a `Grating`.
        bsdf: Box<GratingBsdf>,
        /// ρ²·N·d (finite N), the factor of the direct lookups; 1 for N = ∞.
        k: f64,
        /// η₀·white for N = ∞; black for finite N (order 0 is in the table).
        specular: Xyz,
    },
    /// The radiometric BSDF with tabulated order efficiencies (finite N): C(u, s) over the
    /// incidence nodes on the plane across the grooves, and for a conical table on the planes
    /// |wi.y| = [`COLOUR_PLANES`]`[1..]` too (C(u, s, |wi.y|)), set by [`Source::build`].
    #[cfg(feature = "relief")]
    Tabulated {
        bsdf: Box<GratingBsdf>,
        incidence: Option<Box<Incidence>>,
        /// The planes off the plane across the grooves: (|wi.y|, c = √(1 − wi.y²), table).
        planes: Vec<(f64, f64, Incidence)>,
    },
}

/// Whether the BSDF's colour factorises as g(v)·C(u) (amplitude efficiencies) or
/// g(v)·C(u, s) (tabulated ones): its groove spread must not depend on λ. The error names
/// `groove`.
fn factorises(bsdf: &GratingBsdf) -> Result<(), Error> {
    match bsdf.groove().kind() {
        GrooveKind::CoherenceLength { length_nm } => Err(Error::invalid(
            "groove",
            length_nm,
            Requirement::IndependentOfWavelength,
        )),
        GrooveKind::Gaussian { .. } | GrooveKind::Ideal => Ok(()),
    }
}

/// A tabulated BSDF's source: finite N (`slits`); `None` for the amplitude reading. A conical
/// table's colour is tabulated on the planes [`COLOUR_PLANES`] ([`Source::build`]).
#[cfg(feature = "relief")]
fn tabulated(bsdf: &GratingBsdf) -> Result<Option<Source>, Error> {
    if bsdf.order_efficiency().table().is_none() {
        return Ok(None);
    }
    if bsdf.grating().slits() == Slits::Infinite {
        return Err(Error::invalid("slits", f64::INFINITY, Requirement::Finite));
    }
    Ok(Some(Source::Tabulated {
        bsdf: Box::new(bsdf.clone()),
        incidence: None,
        planes: Vec::new(),
    }))
}

/// The BSDF whose colour on the plane across the grooves (wi.y = wo.y = 0) a tabulated
/// table's nodes integrate: `bsdf` itself (a conical table is read there at β = 0), except
/// that a preset's conical table ([`Preset::conical_table`](crate::relief::Preset::conical_table))
/// is read through the preset's classical table, which it equals on that plane (to
/// 1.1·10⁻¹⁶, `tests/reduced_table.rs`) and which reads about 4× faster.
#[cfg(feature = "relief")]
fn on_the_plane(bsdf: &GratingBsdf) -> GratingBsdf {
    #[cfg(all(feature = "presets", feature = "std"))]
    if let Some(p) = bsdf
        .order_efficiency()
        .table()
        .and_then(crate::relief::Preset::of_conical_table)
    {
        // The same period: the classical table is accepted and the grating kept.
        let classical = crate::grating_bsdf::OrderEfficiency::from_static(p.table())
            .and_then(|e| bsdf.with_efficiency(e));
        if let Ok(b) = classical {
            return b;
        }
    }
    bsdf.clone()
}

/// C(u, s, |β|) of a conical table's planes (`first` at β = 0, then `planes`), β the
/// smaller of |wi.y| and |wo.y| (they differ by |v|, the groove lobe's width): each plane
/// read at the place σ of (u, s) between the grazing directions at r = √(1 − β²) (clamped to
/// them: at the larger |wi.y| or |wo.y| a direction may pass r by the lobe's width), the two
/// planes around β blended linearly in c = r (the last plane beyond it).
#[cfg(feature = "relief")]
pub(super) fn conical_value(
    first: &Incidence,
    planes: &[(f64, f64, Incidence)],
    u: f64,
    s: f64,
    b: f64,
) -> Xyz {
    if b == 0.0 {
        // On the plane across the grooves: the first plane's own reading.
        return first.value(u, s);
    }
    let r = math::sqrt(1.0 - b * b);
    let (u_r, s_r) = (u / r, s / r);
    let width = 2.0 - u_r.abs();
    if width.is_nan() || width <= 0.0 {
        return Xyz::default();
    }
    // σ from the clamped p itself (a round trip through s would leave [0, w] by rounding at
    // the ends, where the clamp puts the directions past the grazing ones).
    let p = (s_r - u_r.max(0.0) + 1.0).clamp(0.0, width);
    let sigma = super::incidence::place(p, width);
    // The plane at or below |β| (index into [first, planes...]) and the blend toward the next.
    let at = |k: usize| if k == 0 { first } else { &planes[k - 1].2 };
    let c_of = |k: usize| if k == 0 { 1.0 } else { planes[k - 1].1 };
    let beta_of = |k: usize| if k == 0 { 0.0 } else { planes[k - 1].0 };
    let last = planes.len();
    let mut k = 0;
    while k < last && beta_of(k + 1) <= b {
        k += 1;
    }
    if k == last {
        return at(k).value_at(u, sigma);
    }
    let (c0, c1) = (c_of(k), c_of(k + 1));
    let t = ((c0 - r) / (c0 - c1)).clamp(0.0, 1.0);
    let (x, y) = (at(k).value_at(u, sigma), at(k + 1).value_at(u, sigma));
    x.scale(1.0 - t) + y.scale(t)
}

impl Source {
    /// The checked sourceimpl Source {
    /// The checked source of `source` under `spectral`, and the integrator of its nodes and
    /// direct lookups: `spectral` itself for the paper's grating; for the BSDF its illuminant
    /// with the envelope λ⁻¹ (finite N) or plain (N = ∞, whose nodes are sums over orders).
    ///
    /// # Errors
    ///
    /// The paper's grating with N = ∞ (`slits`); a BSDF whose colour does not factorise
    /// (`efficiency`, `groove`).
    pub(super) fn new(
        source: TableSource<'_>,
        spectral: &Spectral,
    ) -> Result<(Source, Spectral), Error> {
        match source {
            TableSource::Paper(g) => {
                if g.slits() == Slits::Infinite {
                    return Err(Error::invalid("slits", f64::INFINITY, Requirement::Finite));
                }
                Ok((Source::Paper { grating: *g }, *spectral))
            }
            TableSource::Radiometric(bsdf) => {
                factorises(bsdf)?;
                #[cfg(feature = "relief")]
                if let Some(source) = tabulated(bsdf)? {
                    return Ok((source, Spectral::new(spectral.illuminant())));
                }
                let plain = Spectral::new(spectral.illuminant());
                let g = bsdf.grating();
                let rho = g.open_fraction();
                let (k, nodes, specular) = match g.slits() {
                    Slits::Finite(n) => (
                        (rho * rho * n as f64 * g.period_nm()).min(f64::MAX),
                        plain.with_envelope(Envelope::new(1, 0.0)?),
                        Xyz::default(),
                    ),
                    Slits::Infinite => (1.0, plain, plain.white().scale(bsdf.efficiency(0))),
                };
                let source = Source::Radiometric {
                    bsdf: Box::new(bsdf.clone()),
                    k,
                    specular,
                };
                Ok((source, nodes))
            }
        }
    }

    /// The public view.
    pub(super) fn view(&self) -> TableSource<'_> {
        match self {
            Source::Paper { grating } => TableSource::Paper(grating),
            Source::Radiometric { bsdf, .. } => TableSource::Radiometric(bsdf.as_ref()),
            #[cfg(feature = "relief")]
            Source::Tabulated { bsdf, .. } => TableSource::Radiometric(bsdf.as_ref()),
        }
    }

    /// The grating of the source.
    pub(super) fn grating(&self) -> &Grating {
        match self {
            Source::Paper { grating } => grating,
            Source::Radiometric { bsdf, .. } => bsdf.grating(),
            #[cfg(feature = "relief")]
            Source::Tabulated { bsdf, .. } => bsdf.grating(),
        }
    }

    /// The end of the first block and whether that block is left to direct lookups: finite N
    /// the end of order 0's lobe block; N = ∞ (the BSDF) 2^⌊log₂(360 nm/d)⌋.
    pub(super) fn first_block(&self) -> (f64, bool) {
        let g = self.grating();
        match g.slits() {
            Slits::Finite(_) => lobe_block(g),
            Slits::Infinite => comb_block(g),
        }
    }

    /// The colour at |u| = `a` computed directly (`Exact`), as the grid's nodes are.
    pub(super) fn direct(&self, spectral: &Spectral, a: f64) -> Xyz {
        use crate::spectrum::{saturate, Strategy};
        match self {
            Source::Paper { grating } => spectral.xyz(grating, a, Strategy::EXACT),
            Source::Radiometric { bsdf, k, .. } => {
                let c = spectral.xyz(bsdf.grating(), a, Strategy::EXACT);
                saturate(c.scale(*k))
            }
            // No incidence: `lookup` does not apply.
            #[cfg(feature = "relief")]
            Source::Tabulated { .. } => Xyz::default(),
        }
    }

    /// What a build of this source can produce, for the checks of a stored table: node values
    /// at most twice the largest a build makes (the white for the paper's grating, k·white/360
    /// nm with k = ρ²·N·d for the BSDF of finite N, d times the largest film weight for N = ∞,
    /// since Σ η ≤ 1), the error scale from the build's floor to twice the largest Y, and
    /// error·scale at most 10⁴ times the largest value over the white.
    #[cfg_attr(not(feature = "serde"), allow(dead_code))]
    pub(super) fn stored_limits(&self, illuminant: crate::spectrum::Illuminant) -> Limits {
        /// Headroom over the largest node value a build produces, for the strategies' rounding.
        const VALUE_HEADROOM: f64 = 2.0;
        /// A bound of error·scale per unit of (largest value)/white: the worst midpoint error
        /// is a difference of the interpolant (within a small multiple of the largest value)
        /// and a node value, over a tolerance of at least (6/29)²·white·scale = 0.043·white·
        /// scale; 10⁴ is ample.
        const ERROR_FACTOR: f64 = 1e4;
        let plain = Spectral::new(illuminant);
        let w = plain.white();
        let white = [w.x, w.y, w.z];
        let g = self.grating();
        let (d, rho) = (g.period_nm(), g.open_fraction());
        let (max_value, floor) = match (self, g.slits()) {
            (Source::Paper { .. }, slits) => (white, GratingNodes::paper_floor(slits.as_f64())),
            (_, slits) => {
                // As the build's (a tabulated source has no stored form: never reached).
                let floor = (rho * rho * d / crate::data::cie::cmf_areas()[1])
                    .clamp(f64::MIN_POSITIVE, f64::MAX);
                let max = match slits {
                    Slits::Finite(n) => {
                        let k = (rho * rho * n as f64 * d).min(f64::MAX);
                        white.map(|c| k * c / LAMBDA_MIN_NM)
                    }
                    Slits::Infinite => peak_weight(&plain).map(|c| d * c),
                };
                (max, floor)
            }
        };
        let value = max_value.map(|v| VALUE_HEADROOM * v);
        let ratio = (0..3).map(|c| value[c] / white[c]).fold(0.0, f64::max);
        Limits {
            value,
            scale: (floor, floor.max(value[1])),
            error_times_scale: ERROR_FACTOR * ratio,
        }
    }

    /// The order-0 delta's colour (black but for the BSDF with N = ∞).
    pub(super) fn specular(&self) -> Xyz {
        match self {
            Source::Radiometric { specular, .. } => *specular,
            _ => Xyz::default(),
        }
    }

    /// Builds the grid of the source to `accuracy` (validated by the caller) with the nodes'
    /// integrator `spectral` (from [`Source::new`]), within the caps; returns it with the
    /// evaluations it took.
    pub(super) fn build(
        &mut self,
        spectral: &Spectral,
        accuracy: f64,
        max_nodes: usize,
        max_work: usize,
    ) -> Result<(Grid, usize), Error> {
        let (u_lo, unresolved) = self.first_block();
        #[cfg(feature = "relief")]
        if let Source::Tabulated {
            bsdf,
            incidence,
            planes,
        } = self
        {
            let d = bsdf.grating().period_nm();
            let white = Spectral::new(spectral.illuminant()).white();
            let plan = |floor: f64| Plan {
                accuracy: accuracy.max(TABULATED_ACCURACY),
                white: [white.x, white.y, white.z],
                floor,
                diffracted_from: LAMBDA_MIN_NM / d,
                u_lo,
                skip_first: unresolved,
                period_nm: d,
                max_nodes,
                max_work,
            };
            // An order of efficiency 1 at 555 nm under E, as the amplitude reading's ρ².
            let floor = (d / crate::data::cie::cmf_areas()[1]).clamp(f64::MIN_POSITIVE, f64::MAX);
            let nodes = TabulatedNodes::new(&on_the_plane(bsdf), spectral);
            let (table, normal) = Incidence::build(&nodes, plan(floor), accuracy);
            let mut evaluations = nodes.evaluations.get();
            // A conical table's other planes, at the first plane's error scale.
            let conical = bsdf
                .order_efficiency()
                .table()
                .is_some_and(|t| t.is_conical());
            planes.clear();
            if conical {
                let off = accuracy.max(OFF_PLANE_ACCURACY);
                for &b in &COLOUR_PLANES[1..] {
                    let nodes = TabulatedNodes::on_plane(bsdf, spectral, b);
                    let mut p = plan(table.scale);
                    p.accuracy = p.accuracy.max(off);
                    let (t, _) = Incidence::build(&nodes, p, off);
                    evaluations += nodes.evaluations.get();
                    planes.push((b, math::sqrt(1.0 - b * b), t));
                }
            }
            *incidence = Some(Box::new(table));
            return Ok((normal, evaluations));
        }
        let g = *self.grating();
        let g = &g;
        let d = g.period_nm();
        let mut plan = Plan {
            accuracy,
            white: [0.0; 3],
            floor: 0.0,
            diffracted_from: LAMBDA_MIN_NM / d,
            u_lo,
            // Where the first block holds a lobe no grid of that spacing resolves, lookups
            // there are direct, so the block is neither refined nor checked (its values only
            // enter `mean`).
            skip_first: unresolved,
            period_nm: d,
            max_nodes,
            max_work,
        };
        match (&*self, g.slits()) {
            (Source::Paper { .. }, Slits::Finite(n)) => {
                let n = n as f64;
                let white = spectral.white();
                plan.white = [white.x, white.y, white.z];
                plan.floor = GratingNodes::paper_floor(n);
                let nodes =
                    GratingNodes::new(spectral, g, n, accuracy, 1.0, plan.white, plan.floor)?;
                let grid = Grid::build(&plan, &|u, scale| nodes.eval(u, scale), &|| {
                    nodes.work_done.get()
                });
                Ok((grid, nodes.evaluations.get()))
            }
            (Source::Radiometric { bsdf, k, .. }, slits) => {
                let white = Spectral::new(spectral.illuminant()).white();
                plan.white = [white.x, white.y, white.z];
                let rho = g.open_fraction();
                // Clamped to the normal range: a scale of 0 (d = 5e-324 nm) would leave no
                // tolerance.
                plan.floor = (rho * rho * d / crate::data::cie::cmf_areas()[1])
                    .clamp(f64::MIN_POSITIVE, f64::MAX);
                if let Slits::Finite(n) = slits {
                    let (w, f) = (plan.white, plan.floor);
                    let nodes = GratingNodes::new(spectral, g, n as f64, accuracy, *k, w, f)?;
                    let grid = Grid::build(&plan, &|u, scale| nodes.eval(u, scale), &|| {
                        nodes.work_done.get()
                    });
                    Ok((grid, nodes.evaluations.get()))
                } else {
                    let delta = DeltaNodes::new(spectral, bsdf, accuracy, plan.white, plan.floor);
                    let grid = Grid::build(&plan, &|u, _| delta.eval(u), &|| delta.work_done.get());
                    Ok((grid, delta.evaluations.get()))
                }
            }
            // `Source::new` refuses N = ∞ for the paper's grating; the tabulated source returned
            // above.
            _ => Err(Error::invalid("slits", f64::INFINITY, Requirement::Finite)),
        }
    }
}
