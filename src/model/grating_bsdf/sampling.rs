//! The grating's sampler and its density, written once against the order weights
//! ([`OrderWeights`]) of either efficiency model: the order from the weights, u from the
//! period proxy of F_N, v from the groove's proxy, and the exact density
//! P(m)·q(r)·(d/λ)·q_v(v)·cos θi of that procedure (the [module docs](super)).

use core::f64::consts::PI;

use glam::DVec3;

use super::lobe::GrooveFactor;
use super::order_weights::{
    AmplitudeWeights, OrderSource, OrderWeights, TabulatedEtas, TabulatedWeights,
};
use super::GratingBsdf;
use crate::model::bsdf::{BsdfFlags, BsdfSample};
use crate::model::MIN_COS_THETA;
use crate::num::math;
use crate::optics::groove::GrooveSpread;
#[cfg(feature = "relief")]
use crate::relief::Incidences;
use crate::Slits;

impl GratingBsdf {
    /// The direction of order m's sample, shared by both efficiency models: u from the
    /// period proxy (`ux`; u = m·λ/d for N = ∞), v from the groove's proxy (`uy`), and
    /// wi = (u − wo.x, v − wo.y, +√(1 − …)); `None` below the surface. Returns (wi, u, r, v).
    #[inline(always)]
    pub(super) fn sample_direction(
        &self,
        wo: DVec3,
        m: i64,
        step: f64,
        ux: f64,
        uy: f64,
        lambda_nm: f64,
    ) -> Option<(DVec3, f64, f64, f64)> {
        let (u, r) = match self.grating.slits() {
            Slits::Finite(_) => {
                let r = self.proxy.r(ux);
                ((m as f64 + r) * step, r)
            }
            Slits::Infinite => (m as f64 * step, 0.0),
        };
        // GrooveSpread::sample with the scale's constants precomputed (`uy` is in [0, 1)).
        let s = self.v_scale.0 + self.v_scale.1 * lambda_nm;
        let v = GrooveSpread::sample_scaled(uy, s);
        let (x, y) = (u - wo.x, v - wo.y);
        let z2 = 1.0 - x * x - y * y;
        if z2.is_nan() || z2 < MIN_COS_THETA * MIN_COS_THETA {
            return None;
        }
        Some((DVec3::new(x, y, math::sqrt(z2)), u, r, v))
    }

    /// Finite N with a groove spread: the lobes have a density (`eval` and `pdf` are not 0).
    #[inline]
    pub(super) fn is_glossy(&self) -> bool {
        matches!(self.grating.slits(), Slits::Finite(_)) && !self.groove.is_delta()
    }

    /// Runs `f` on the order weights of (wo, λ) (the delegate of `order_weights.rs`); `None`
    /// when no order is a candidate or the candidates carry nothing.
    #[inline(always)]
    pub(super) fn with_weights<R>(
        &self,
        wo: DVec3,
        lambda_nm: f64,
        f: impl FnOnce(&dyn OrderWeights) -> R,
    ) -> Option<R> {
        let inv_step = self.grating.period_nm() / lambda_nm;
        match &self.orders {
            OrderSource::Amplitude(a) => Some(f(&AmplitudeWeights {
                dist: a,
                c: a.candidates(wo, inv_step)?,
            })),
            OrderSource::Tabulated { .. } => Some(f(&self.tabulated_weights(wo, lambda_nm)?)),
        }
    }

    /// f for finite N and a non-ideal groove, after the checks: the factor of the order owning
    /// u (1 for the amplitude reading) times its lobe.
    #[inline(always)]
    pub(super) fn value(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        if let OrderSource::Amplitude(_) = self.orders {
            return self.lobe.value(u, v, lambda_nm);
        }
        let k = self
            .orders
            .lobe_factor(self.lobe.phase(u, lambda_nm), wo, wi, lambda_nm);
        if k == 0.0 {
            return 0.0;
        }
        k * self.lobe.value(u, v, lambda_nm)
    }

    /// [`value`](Self::value) of a tabulated model with the pair (wo, wi) located in its table
    /// (`OrderSource::incidences`): the same operations, so the same bits.
    #[cfg(feature = "relief")]
    #[inline(always)]
    pub(super) fn value_at(
        &self,
        pair: &Incidences<'_>,
        wo: DVec3,
        wi: DVec3,
        lambda_nm: f64,
    ) -> f64 {
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let k = OrderSource::factor_at(pair, self.lobe.phase(u, lambda_nm), lambda_nm);
        if k == 0.0 {
            return 0.0;
        }
        k * self.lobe.value(u, v, lambda_nm)
    }

    /// [`pdf_finite`](Self::pdf_finite) of a tabulated model with the pair (wo, wi) located in
    /// its table: the same weights (wo's location reused), so the same bits.
    #[cfg(feature = "relief")]
    #[inline]
    pub(super) fn pdf_at(
        &self,
        pair: &Incidences<'_>,
        wo: DVec3,
        wi: DVec3,
        lambda_nm: f64,
    ) -> f64 {
        let OrderSource::Tabulated { table, slits } = &self.orders else {
            return self.pdf_finite(wo, wi, lambda_nm);
        };
        let Some(range) = OrderSource::range(*slits, wo, self.grating.period_nm() / lambda_nm)
        else {
            return 0.0;
        };
        match TabulatedWeights::at(table, pair, wo, lambda_nm, range) {
            Some(w) => self.pdf_with(&w, wo, wi, lambda_nm),
            None => 0.0,
        }
    }

    /// The density for finite N and a non-ideal groove, after the checks.
    #[inline]
    pub(super) fn pdf_finite(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        match &self.orders {
            OrderSource::Amplitude(a) => {
                let Some(c) = a.candidates(wo, self.grating.period_nm() / lambda_nm) else {
                    return 0.0;
                };
                self.pdf_with(&AmplitudeWeights { dist: a, c }, wo, wi, lambda_nm)
            }
            OrderSource::Tabulated { .. } => self.pdf_tabulated(wo, wi, lambda_nm),
        }
    }

    /// [`pdf_finite`](Self::pdf_finite) for a tabulated model. Not inlined: its order buffer
    /// would otherwise enlarge the amplitude model's stack frame.
    #[inline(never)]
    pub(super) fn pdf_tabulated(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        match self.tabulated_weights(wo, lambda_nm) {
            Some(w) => self.pdf_with(&w, wo, wi, lambda_nm),
            None => 0.0,
        }
    }

    /// A tabulated model's order weights for (wo, λ) (`None` for the amplitude reading).
    #[inline(always)]
    pub(super) fn tabulated_weights(
        &self,
        wo: DVec3,
        lambda_nm: f64,
    ) -> Option<TabulatedWeights<'_>> {
        let OrderSource::Tabulated { table, slits } = &self.orders else {
            return None;
        };
        let range = OrderSource::range(*slits, wo, self.grating.period_nm() / lambda_nm)?;
        TabulatedWeights::new(table, wo, lambda_nm, range)
    }

    /// A tabulated model's efficiencies at wo for every candidate order, for the albedo
    /// (`None` for the amplitude reading).
    pub(super) fn tabulated_etas(&self, wo: DVec3, lambda_nm: f64) -> Option<TabulatedEtas<'_>> {
        let OrderSource::Tabulated { table, slits } = &self.orders else {
            return None;
        };
        let range = OrderSource::range(*slits, wo, self.grating.period_nm() / lambda_nm)?;
        TabulatedEtas::new(table, wo, lambda_nm, range)
    }

    /// [`Bsdf::sample`] for a tabulated model. Not inlined, like
    /// [`pdf_tabulated`](Self::pdf_tabulated).
    #[inline(never)]
    pub(super) fn sample_tabulated(
        &self,
        wo: DVec3,
        lambda_nm: f64,
        xi: [f64; 3],
    ) -> Option<BsdfSample> {
        self.sample_with(&self.tabulated_weights(wo, lambda_nm)?, wo, lambda_nm, xi)
    }

    /// P(m)·q(r)·(d/λ)·q_v(v)·cos θi for the order m owning the phase x = d·(u/λ) (m = round(x),
    /// r = x − m; the phase `eval` evaluates F_N at, rounded the same way: `Lobe::phase`) with
    /// the order weights `w`.
    #[inline(always)]
    pub(super) fn pdf_with<W: OrderWeights + ?Sized>(
        &self,
        w: &W,
        wo: DVec3,
        wi: DVec3,
        lambda_nm: f64,
    ) -> f64 {
        let (u, v) = (wi.x + wo.x, wi.y + wo.y);
        let x = self.lobe.phase(u, lambda_nm);
        self.pdf_x(w, x, v, wi.z, lambda_nm)
    }

    /// [`pdf_with`](Self::pdf_with) at the phase x, with two divisions: the order and u
    /// factors, and the v and cosine factors (q_v = (1/s)/(π·(1 + (v/s)²)),
    /// [`GrooveSpread::pdf`] to rounding).
    #[inline(always)]
    pub(super) fn pdf_x<W: OrderWeights + ?Sized>(
        &self,
        w: &W,
        x: f64,
        v: f64,
        cos_i: f64,
        lambda_nm: f64,
    ) -> f64 {
        // The weight is 0 outside the candidates, and so is the density.
        self.pdf_w(
            w.weight(math::rint(x) as i64),
            w.total(),
            x,
            v,
            cos_i,
            lambda_nm,
        )
    }

    /// [`Bsdf::sample`] with the order weights `w`: order m from `uc`, u from the period proxy
    /// (`ux`), v from the groove's proxy (`uy`); f and the density from the returned direction
    /// itself (u and v re-derived from wi, the same operations as `eval` and `pdf`), so the
    /// sample agrees with them to the bit.
    #[inline(always)]
    pub(super) fn sample_with<W: OrderWeights + ?Sized>(
        &self,
        w: &W,
        wo: DVec3,
        lambda_nm: f64,
        [uc, ux, uy]: [f64; 3],
    ) -> Option<BsdfSample> {
        // λ/d by a product: u is re-derived from the direction, so its rounding is free.
        let step = lambda_nm * self.inv_d;
        let (m, pm) = w.choose(uc);
        let (wi, u, r, v) = self.sample_direction(wo, m, step, ux, uy, lambda_nm)?;
        let order = m.clamp(i32::MIN as i64, i32::MAX as i64) as i32;
        let specular = BsdfFlags::REFLECTION | BsdfFlags::SPECULAR;
        let (f, pdf, flags) = match (self.grating.slits(), self.groove.is_delta()) {
            (Slits::Finite(_), false) => {
                let (u, v) = (wi.x + wo.x, wi.y + wo.y);
                // q = u/λ once: the lobe's value is f at q and the phase is d·q.
                let q = u / lambda_nm;
                let x = self.lobe.d * q;
                let f = match self.orders {
                    OrderSource::Amplitude(_) => self.lobe.value_q(q, v, lambda_nm),
                    OrderSource::Tabulated { .. } => {
                        match w.lobe_factor(math::rint(x) as i64, wi, lambda_nm) {
                            0.0 => 0.0,
                            k => k * self.lobe.value_q(q, v, lambda_nm),
                        }
                    }
                };
                (
                    f,
                    self.pdf_x(w, x, v, wi.z, lambda_nm),
                    BsdfFlags::REFLECTION | BsdfFlags::GLOSSY,
                )
            }
            (Slits::Finite(_), true) => {
                // δ(v) omitted from both f and pdf: the lobe's value with g = 1, the same fused
                // kernel as `eval`.
                let unit = GrooveFactor {
                    big: 1.0,
                    coherent: false,
                };
                let (num, den) = self.lobe.ratio(u / lambda_nm, unit, 0.0, lambda_nm);
                let k = w.lobe_factor(m, wi, lambda_nm);
                (
                    k * (num / den),
                    pm * (self.proxy.q(r) / step) * wi.z,
                    specular,
                )
            }
            (Slits::Infinite, false) => {
                let eta = w.delta_efficiency(m, wi, lambda_nm);
                let pv = self.groove.pdf(v, lambda_nm);
                (
                    eta * self.groove.value(v, lambda_nm),
                    pm * pv * wi.z,
                    specular,
                )
            }
            (Slits::Infinite, true) => {
                let eta = w.delta_efficiency(m, wi, lambda_nm);
                (eta / wi.z, pm, specular)
            }
        };
        if !(pdf > 0.0 && pdf.is_finite() && f.is_finite()) {
            return None;
        }
        Some(BsdfSample::new(wi, f, pdf, flags).with_order(order))
    }

    /// P(m)·q(r)·(d/λ)·q_v(v)·cos θi with P(m) = w/total (see [`pdf_x`](Self::pdf_x)).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn pdf_w(
        &self,
        w: f64,
        total: f64,
        x: f64,
        v: f64,
        cos_i: f64,
        lambda_nm: f64,
    ) -> f64 {
        if w == 0.0 {
            return 0.0;
        }
        let r = x - math::rint(x);
        let (qa, qb) = self.proxy.ratio(r);
        let inv_s = self.groove.proxy_inverse_scale(lambda_nm);
        let tv = v * inv_s;
        let a = (w * qa * self.grating.period_nm()) / (total * qb * lambda_nm);
        let b = (inv_s * cos_i) / (PI * (1.0 + tv * tv));
        let p = a * b;
        if p.is_finite() {
            p
        } else {
            0.0
        }
    }
}
