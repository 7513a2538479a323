//! The order weights the grating BSDF delegates to (pbrt-v4's pattern of a BxDF that delegates
//! to its distribution): for one (wo, λ), which orders are candidates, the weight of each, the
//! choice of one and its probability, each order's efficiency for the pair (wo, wi), and the
//! order part of the sample weight's bound. `eval`, `pdf`, `sample` (and their four-wavelength
//! forms), the weight bound and the albedo are written once against [`OrderWeights`], for
//! both efficiency models:
//!
//! * [`AmplitudeWeights`]: the amplitude reading (`orders.rs`): w_m = S(π·ρ·m) + ε·U_m for
//!   finite N, S(π·ρ·m) for N = ∞; the lobe carries ρ²·S(π·ρ·x) itself, so the order's factor
//!   in f is 1.
//! * [`TabulatedWeights`]: the cell proposal P(m) = (1 − δ)·η̂_m/Σ η̂ + δ/K over the
//!   candidates that propagate at wo's table query (η̂ the stored efficiencies of its cell's
//!   corners with the query's bilinear weights, [`TABULATED_DEFENSIVE_SHARE`] δ; a classical
//!   table's fast reading, `FastProposal`, where it has one, else the table's
//!   `CellProposal`); the order's factor in f is η̃_m = min(η_m(−wi.x, −wi.y, λ),
//!   η_m(−wo.x, −wo.y, λ)) (`efficiency.rs`; a classical table ignores the second argument),
//!   interpolated for that order alone (`sample` reuses the proposal's location of wo), the
//!   lobe the unit-integral (N·d/λ)·F_N·g. [`TabulatedEtas`] holds every candidate's η_m(wo)
//!   for the albedo's integrand.
//!
//! The model-level [`OrderSource`] builds the weights of a query; each public method matches
//! on it once and runs the generic body, so the amplitude path never carries the tabulated
//! model's buffer of [`MAX_TABULATED_ORDERS`] efficiencies on its stack.

use glam::DVec3;

use super::efficiency::Tabulated;
#[cfg(feature = "relief")]
use super::efficiency::MAX_TABULATED_ORDERS;
use super::orders::{candidate_range, AmplitudeOrders, Candidates};
#[cfg(feature = "relief")]
use crate::num::math;
#[cfg(feature = "relief")]
use crate::relief::{CellProposal, FastProposal, Incidences};
#[cfg(feature = "relief")]
use crate::relief::{EfficiencyTable, Polarised};
use crate::Slits;

/// The order weights of one (wo, λ): what the sampler, the density and the weight bound need.
pub(super) trait OrderWeights {
    /// Σ w over the candidates.
    fn total(&self) -> f64;
    /// The weight w_m of order m (0 outside the candidates).
    fn weight(&self, m: i64) -> f64;
    /// Chooses an order from `uc` in [0, 1): the order and its probability w_m/Σ w.
    fn choose(&self, uc: f64) -> (i64, f64);
    /// The factor of order m's lobe in f for the pair (wo, wi) at λ: 1 for the amplitude
    /// reading (its lobe carries ρ²·S), η̃_m for a table.
    fn lobe_factor(&self, m: i64, wi: DVec3, lambda_nm: f64) -> f64;
    /// The efficiency of order m for delta lobes (N = ∞): η_m = ρ²·S(π·ρ·m) for the amplitude
    /// reading, η̃_m for a table.
    fn delta_efficiency(&self, m: i64, wi: DVec3, lambda_nm: f64) -> f64;
    /// The order part of the bound of f·cos θi/pdf (the rest is the period proxy's bound B_N
    /// and the groove proxy's sup g/q_v): ρ²·Σ w·max_m(U_m/w_m) (amplitude, finite N),
    /// ρ²·Σ w (amplitude, N = ∞) and max_m(η_m/P(m))·(1 + 10⁻¹²) (a table: η̃ ≤ η_m(−wo.x)).
    fn order_bound(&self) -> f64;
}

/// The amplitude reading's weights for one (wo, λ): the grating's precomputed weights and the
/// candidates.
pub(super) struct AmplitudeWeights<'a> {
    pub dist: &'a AmplitudeOrders,
    pub c: Candidates,
}

impl OrderWeights for AmplitudeWeights<'_> {
    #[inline(always)]
    fn total(&self) -> f64 {
        self.c.total
    }

    #[inline(always)]
    fn weight(&self, m: i64) -> f64 {
        if m < self.c.lo || m > self.c.hi {
            return 0.0;
        }
        self.dist.candidate_weight(&self.c, m)
    }

    #[inline(always)]
    fn choose(&self, uc: f64) -> (i64, f64) {
        self.dist.choose(&self.c, uc)
    }

    #[inline(always)]
    fn lobe_factor(&self, _m: i64, _wi: DVec3, _lambda_nm: f64) -> f64 {
        1.0
    }

    #[inline(always)]
    fn delta_efficiency(&self, m: i64, _wi: DVec3, _lambda_nm: f64) -> f64 {
        // The true order m, not the i32 a sample reports: beyond 2³¹ the two differ.
        self.dist.efficiency(m)
    }

    fn order_bound(&self) -> f64 {
        let rho = self.dist.rho();
        match self.dist.slits() {
            Slits::Infinite => rho * rho * self.c.total,
            Slits::Finite(_) => rho * rho * self.c.total * self.dist.worst_envelope_ratio(&self.c),
        }
    }
}

/// The defensive share δ of a tabulated model's order proposal (feature `relief`): the sampler
/// chooses order m with P(m) = (1 − δ)·η̂_m/Σ η̂ + δ/K among the K candidate orders that
/// propagate at wo, η̂_m = Σ_c w_c·η_m,c the stored efficiencies of the corners of wo's table
/// cell with the query's bilinear (trilinear) weights w_c (the WGSL sampler's
/// `DIFFRACTION_DEFENSIVE_SHARE`). The share keeps P(m) ≥ δ/K wherever the interpolated
/// η_m(wo) (and so f) can be positive, also for an order that propagates at the query but at
/// none of the corners; a tenth costs at most a tenth of the proposal's match to η_m(wo). The
/// proposal leaves out the interpolation's cos θi/cos θm factors (no square roots), so it
/// follows η_m(wo) except near the orders' Rayleigh lines.
#[cfg(feature = "relief")]
pub const TABULATED_DEFENSIVE_SHARE: f64 = 0.1;

/// A tabulated model's weights for one (wo, λ): the cell proposal of the candidate orders (one
/// cell search, the corners' stored values: no interpolation of q, no square root),
/// w_m = (1 − δ)·K·η̂_m + δ·Σ η̂ with Σ w = K·Σ η̂, so that P(m) = w_m/Σ w takes one division
/// (w_m = 1, Σ w = K where Σ η̂ = 0); each order's factor η̃_m is interpolated for the one
/// order a query needs.
#[cfg(feature = "relief")]
pub(super) struct TabulatedWeights<'a> {
    table: &'a EfficiencyTable,
    proposal: Proposal<'a>,
    /// The proposal's orders.
    lo: i64,
    hi: i64,
    wo: DVec3,
    lambda_nm: f64,
    /// w_m = scale·η̂_m + floor and Σ w: (1 − δ)·K, δ·Σ η̂ and K·Σ η̂, or 0, 1 and K where
    /// Σ η̂ = 0.
    scale: f64,
    floor: f64,
    total: f64,
}

/// The cell proposal of a classical table's fast reading, or the table's own.
#[cfg(feature = "relief")]
enum Proposal<'a> {
    Fast(FastProposal<'a>),
    Cell(CellProposal),
}

#[cfg(feature = "relief")]
impl<'a> TabulatedWeights<'a> {
    /// The proposal of the candidate orders [lo, hi] for wo at λ; `None` when none of them is
    /// stored and propagates at wo (every η_m(−wo.x, −wo.y, λ) is 0 there).
    #[inline(always)]
    pub(super) fn new(
        table: &'a Tabulated,
        wo: DVec3,
        lambda_nm: f64,
        (lo, hi): (i64, i64),
    ) -> Option<TabulatedWeights<'a>> {
        let table = table.table();
        let proposal = match table.fast_proposal(-wo.x, lambda_nm, lo..=hi) {
            Some(p) => Proposal::Fast(p?),
            None => Proposal::Cell(table.cell_proposal(-wo.x, -wo.y, lambda_nm, lo..=hi)?),
        };
        TabulatedWeights::from_proposal(table, proposal, wo, lambda_nm)
    }

    /// [`new`](Self::new) with wo located in `pair` (its first incidence, (−wo.x, −wo.y)),
    /// for the reads of several wavelengths: the same weights.
    #[inline(always)]
    pub(super) fn at(
        table: &'a Tabulated,
        pair: &Incidences<'a>,
        wo: DVec3,
        lambda_nm: f64,
        (lo, hi): (i64, i64),
    ) -> Option<TabulatedWeights<'a>> {
        let table = table.table();
        let proposal = match pair.proposal(lambda_nm, lo..=hi) {
            Some(p) => Proposal::Fast(p?),
            None => Proposal::Cell(table.cell_proposal(-wo.x, -wo.y, lambda_nm, lo..=hi)?),
        };
        TabulatedWeights::from_proposal(table, proposal, wo, lambda_nm)
    }

    /// The weights of a proposal.
    #[inline(always)]
    fn from_proposal(
        table: &'a EfficiencyTable,
        proposal: Proposal<'a>,
        wo: DVec3,
        lambda_nm: f64,
    ) -> Option<TabulatedWeights<'a>> {
        let (count, total, orders) = match &proposal {
            Proposal::Fast(p) => (p.count(), p.total(), p.orders()),
            Proposal::Cell(p) => (p.count(), p.total(), p.orders()),
        };
        let k = count as f64;
        let (scale, floor, total) = if total > 0.0 && total.is_finite() {
            (
                (1.0 - TABULATED_DEFENSIVE_SHARE) * k,
                TABULATED_DEFENSIVE_SHARE * total,
                k * total,
            )
        } else {
            (0.0, 1.0, k)
        };
        Some(TabulatedWeights {
            table,
            proposal,
            lo: i64::from(*orders.start()),
            hi: i64::from(*orders.end()),
            wo,
            lambda_nm,
            scale,
            floor,
            total,
        })
    }

    /// The candidate orders that propagate at wo.
    #[inline(always)]
    fn orders(&self) -> (i64, i64) {
        (self.lo, self.hi)
    }

    /// η̃_m = min(η_m(−wo.x, −wo.y, λ), η_m(−wi.x, −wi.y, λ)), 0 where the first is.
    #[inline]
    fn eta_pair(&self, m: i64, wi: DVec3, lambda_nm: f64) -> f64 {
        if let Proposal::Fast(p) = &self.proposal {
            if lambda_nm == self.lambda_nm {
                return p.min_efficiency(m, -wi.x);
            }
        }
        let wo = self.wo;
        self.table
            .incidences((-wo.x, -wo.y), (-wi.x, -wi.y))
            .min(m, lambda_nm)
    }
}

#[cfg(feature = "relief")]
impl OrderWeights for TabulatedWeights<'_> {
    #[inline(always)]
    fn total(&self) -> f64 {
        self.total
    }

    #[inline(always)]
    fn weight(&self, m: i64) -> f64 {
        let (lo, hi) = self.orders();
        if m < lo || m > hi {
            return 0.0;
        }
        // m is a stored order (i32).
        let e = match &self.proposal {
            Proposal::Fast(p) => p.efficiency(m as i32),
            Proposal::Cell(p) => self.table.cell_efficiency(p, m as i32),
        };
        self.scale * e + self.floor
    }

    #[inline]
    fn choose(&self, uc: f64) -> (i64, f64) {
        let (lo, hi) = self.orders();
        let target = uc * self.total;
        let mut acc = 0.0;
        for m in lo..=hi {
            let w = self.weight(m);
            acc += w;
            if target < acc {
                return (m, w / self.total);
            }
        }
        (hi, self.weight(hi) / self.total)
    }

    #[inline]
    fn lobe_factor(&self, m: i64, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eta_pair(m, wi, lambda_nm)
    }

    #[inline]
    fn delta_efficiency(&self, m: i64, wi: DVec3, lambda_nm: f64) -> f64 {
        self.eta_pair(m, wi, lambda_nm)
    }

    fn order_bound(&self) -> f64 {
        // max_m η_m(wo)/P(m) (η̃ ≤ η_m(wo)), every order interpolated once; the relative
        // 10⁻¹² covers the rounding of the weight's products and quotients.
        let mut buf = [Polarised::default(); MAX_TABULATED_ORDERS];
        let count = self.table.order_count().min(MAX_TABULATED_ORDERS);
        let wo = self.wo;
        self.table
            .efficiencies_conical(-wo.x, -wo.y, self.lambda_nm, &mut buf[..count]);
        let first = i64::from(*self.table.orders().start());
        let (lo, hi) = self.orders();
        let mut worst = 0.0f64;
        for m in lo..=hi {
            let e = buf[(m - first) as usize].unpolarised();
            if e.is_finite() && e > 0.0 {
                worst = worst.max(e * self.total / self.weight(m));
            }
        }
        worst * (1.0 + 1e-12)
    }
}

/// A tabulated model's efficiencies for one (wo, λ), for the albedo's integrand: η_m(−wo.x,
/// −wo.y, λ) of every stored order (one cell search, a stack buffer, no allocation) and the
/// candidates clipped to the table.
#[cfg(feature = "relief")]
pub(super) struct TabulatedEtas<'a> {
    table: &'a EfficiencyTable,
    buf: [Polarised; MAX_TABULATED_ORDERS],
    first: i64,
    lo: i64,
    hi: i64,
    /// Σ η_m(wo) over the candidates (at most 1).
    pub total: f64,
}

#[cfg(feature = "relief")]
impl<'a> TabulatedEtas<'a> {
    /// η_m(−wo.x, −wo.y, λ) of the candidate orders [lo, hi] of `t`; `None` when they carry
    /// nothing.
    pub(super) fn new(
        table: &'a Tabulated,
        wo: DVec3,
        lambda_nm: f64,
        (lo, hi): (i64, i64),
    ) -> Option<TabulatedEtas<'a>> {
        let table = table.table();
        let first = i64::from(*table.orders().start());
        let last = i64::from(*table.orders().end());
        let count = ((last - first + 1) as usize).min(MAX_TABULATED_ORDERS);
        let mut o = TabulatedEtas {
            table,
            buf: [Polarised::default(); MAX_TABULATED_ORDERS],
            first,
            lo: lo.max(first),
            hi: hi.min(first + count as i64 - 1),
            total: 0.0,
        };
        table.efficiencies_conical(-wo.x, -wo.y, lambda_nm, &mut o.buf[..count]);
        o.total = (o.lo..=o.hi).map(|m| o.eta_wo(m)).sum();
        (o.total > 0.0 && o.total.is_finite()).then_some(o)
    }

    /// η_m(−wo.x, −wo.y, λ), 0 outside the candidates and where it is not a finite positive
    /// number.
    #[inline]
    pub(super) fn eta_wo(&self, m: i64) -> f64 {
        if m < self.lo || m > self.hi {
            return 0.0;
        }
        let e = self.buf[(m - self.first) as usize].unpolarised();
        if e.is_finite() && e > 0.0 {
            e
        } else {
            0.0
        }
    }

    /// η̃_m at (u, v) for light leaving toward `wo` (wi.x = u − wo.x, wi.y = v − wo.y; v = 0
    /// is the groove lobe's centre): the albedo's integrand, read as `eval` reads it.
    #[inline]
    pub(super) fn eta_at(&self, m: i64, u: f64, v: f64, wo: DVec3, lambda_nm: f64) -> f64 {
        if self.eta_wo(m) == 0.0 {
            return 0.0;
        }
        self.table
            .incidences((-wo.x, -wo.y), (-(u - wo.x), wo.y - v))
            .min(m, lambda_nm)
    }

    /// Whether the efficiencies depend on the incidence along the grooves (a conical table).
    pub(super) fn conical(&self) -> bool {
        self.table.is_conical()
    }
}

/// Without the feature `relief` there are no tables: the tabulated weights are uninhabited.
#[cfg(not(feature = "relief"))]
pub(super) struct TabulatedWeights<'a> {
    never: core::convert::Infallible,
    _table: core::marker::PhantomData<&'a ()>,
}

#[cfg(not(feature = "relief"))]
impl<'a> TabulatedWeights<'a> {
    pub(super) fn new(
        table: &'a Tabulated,
        _wo: DVec3,
        _lambda_nm: f64,
        _range: (i64, i64),
    ) -> Option<TabulatedWeights<'a>> {
        match *table {}
    }
}

/// Without the feature `relief`: uninhabited, as the weights.
#[cfg(not(feature = "relief"))]
pub(super) struct TabulatedEtas<'a> {
    never: core::convert::Infallible,
    _table: core::marker::PhantomData<&'a ()>,
    pub total: f64,
}

#[cfg(not(feature = "relief"))]
impl<'a> TabulatedEtas<'a> {
    pub(super) fn new(
        table: &'a Tabulated,
        _wo: DVec3,
        _lambda_nm: f64,
        _range: (i64, i64),
    ) -> Option<TabulatedEtas<'a>> {
        match *table {}
    }

    pub(super) fn eta_at(&self, _m: i64, _u: f64, _v: f64, _wo: DVec3, _lambda_nm: f64) -> f64 {
        match self.never {}
    }

    pub(super) fn conical(&self) -> bool {
        match self.never {}
    }

    pub(super) fn eta_wo(&self, _m: i64) -> f64 {
        match self.never {}
    }
}

#[cfg(not(feature = "relief"))]
impl OrderWeights for TabulatedWeights<'_> {
    fn total(&self) -> f64 {
        match self.never {}
    }
    fn weight(&self, _m: i64) -> f64 {
        match self.never {}
    }
    fn choose(&self, _uc: f64) -> (i64, f64) {
        match self.never {}
    }
    fn lobe_factor(&self, _m: i64, _wi: DVec3, _lambda_nm: f64) -> f64 {
        match self.never {}
    }
    fn delta_efficiency(&self, _m: i64, _wi: DVec3, _lambda_nm: f64) -> f64 {
        match self.never {}
    }
    fn order_bound(&self) -> f64 {
        match self.never {}
    }
}

/// [`OrderSource::lobe_factor`] of a table. Not inlined: the table's reading would otherwise
/// fill the amplitude model's `eval` (measured: its code's layout then cost the amplitude
/// `eval` up to 3× its time in the benches' binary, at the same instructions).
#[cfg(feature = "relief")]
#[inline(never)]
fn table_factor(table: &Tabulated, x: f64, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
    let pair = table.table().incidences((-wo.x, -wo.y), (-wi.x, -wi.y));
    OrderSource::factor_at(&pair, x, lambda_nm)
}

/// Where a grating's order weights come from: the amplitude reading's precomputed weights, or
/// a table (with the grating's N, for the candidate range).
// The amplitude variant holds its weight tables inline (2.2 kB, as the BSDF always has): boxing
// them would need `alloc` and put an indirection on every sample's path.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub(super) enum OrderSource {
    Amplitude(AmplitudeOrders),
    // Uninhabited without the feature `relief` (no table exists): never built there.
    #[cfg_attr(not(feature = "relief"), allow(dead_code))]
    Tabulated {
        table: Tabulated,
        slits: Slits,
    },
}

impl OrderSource {
    /// The factor of the lobe of the order owning the phase `x` in f for the pair (wo, wi)
    /// at λ, without building the weights of every order: 1 for the amplitude reading, η̃_m
    /// for a table (0 where either reading is 0 or the phase is not finite).
    #[inline(always)]
    pub(super) fn lobe_factor(&self, x: f64, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        match self {
            OrderSource::Amplitude(_) => 1.0,
            #[cfg(not(feature = "relief"))]
            OrderSource::Tabulated { table, .. } => {
                let _ = (x, wo, wi, lambda_nm);
                match *table {}
            }
            #[cfg(feature = "relief")]
            OrderSource::Tabulated { table, .. } => table_factor(table, x, wo, wi, lambda_nm),
        }
    }

    /// A tabulated model's pair (wo, wi) located in its table (wo first), for the reads of
    /// several wavelengths; `None` for the amplitude reading.
    #[cfg(feature = "relief")]
    #[inline(always)]
    pub(super) fn incidences(&self, wo: DVec3, wi: DVec3) -> Option<Incidences<'_>> {
        match self {
            OrderSource::Amplitude(_) => None,
            OrderSource::Tabulated { table, .. } => {
                Some(table.table().incidences((-wo.x, -wo.y), (-wi.x, -wi.y)))
            }
        }
    }

    /// [`lobe_factor`](Self::lobe_factor) of a table with the pair located.
    #[cfg(feature = "relief")]
    #[inline(always)]
    pub(super) fn factor_at(pair: &Incidences<'_>, x: f64, lambda_nm: f64) -> f64 {
        let m = math::rint(x);
        if !m.is_finite() {
            return 0.0;
        }
        pair.min(m as i64, lambda_nm)
    }

    /// The candidate orders' range for wo (`inv_step` = d/λ), for a table's weights.
    #[inline]
    pub(super) fn range(slits: Slits, wo: DVec3, inv_step: f64) -> Option<(i64, i64)> {
        candidate_range(slits, wo, inv_step)
    }
}
