//! The scalar relief model: a relief's order efficiencies on a metal by Kirchhoff's phase screen,
//! renormalised over the propagating orders, times the metal's Fresnel reflectance at each
//! order's facet angle.

use core::f64::consts::TAU;

use super::metal::Metal;
use super::shape::Relief;
use crate::error::{Error, Requirement};
use crate::num::math;

/// The longest period accepted, nm (1 mm, a 1 line/mm grating: coarser structures are not
/// gratings a renderer shows as such).
///
/// ```
/// use diffraction::relief::{Metal, Relief, ScalarRelief, MAX_PERIOD_NM};
/// let r = Relief::sinusoid(50.0)?;
/// assert!(ScalarRelief::new(r.clone(), Metal::AL, MAX_PERIOD_NM).is_ok());
/// assert!(ScalarRelief::new(r, Metal::AL, 2.0 * MAX_PERIOD_NM).is_err());
/// # Ok::<(), diffraction::Error>(())
/// ```
pub const MAX_PERIOD_NM: f64 = 1e6;
/// The orders the model computes: |m| ≤ this. A coarser grating (more than about 2·2048
/// propagating orders, d/λ > 2048, e.g. d > 0.9 mm at 450 nm) leaves its orders beyond out of
/// the renormalisation and reports them as carrying nothing: a documented truncation that bounds
/// a call to 4097 orders.
///
/// ```
/// use diffraction::relief::{Metal, Relief, ScalarRelief, MAX_RELIEF_ORDER};
/// // A 1 mm period at 100 nm: 20 000 orders propagate, 4097 are computed.
/// let g = ScalarRelief::new(Relief::sinusoid(50.0)?, Metal::AL, 1e6)?;
/// assert_eq!(g.orders(0.0, 100.0).count(), 2 * MAX_RELIEF_ORDER as usize + 1);
/// # Ok::<(), diffraction::Error>(())
/// ```
pub const MAX_RELIEF_ORDER: i32 = 2048;

/// Order efficiencies of the two linear polarisations: TE (electric field along the grooves, s)
/// and TM (magnetic field along the grooves, p).
///
/// ```
/// use diffraction::relief::Polarised;
/// let e = Polarised { te: 0.6, tm: 0.4 };
/// assert_eq!(e.unpolarised(), 0.5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Polarised {
    /// TE (s): the electric field along the grooves.
    pub te: f64,
    /// TM (p): the magnetic field along the grooves.
    pub tm: f64,
}

impl Polarised {
    /// (TE + TM)/2, the efficiency for unpolarised light.
    ///
    /// ```
    /// use diffraction::relief::Polarised;
    /// assert_eq!(Polarised { te: 1.0, tm: 0.0 }.unpolarised(), 0.5);
    /// ```
    #[must_use]
    pub fn unpolarised(&self) -> f64 {
        0.5 * (self.te + self.tm)
    }
}

/// One propagating reflected order of a [`ScalarRelief`] (see [`ScalarRelief::orders`]).
///
/// ```
/// use diffraction::relief::{Metal, Relief, ScalarRelief};
/// let g = ScalarRelief::new(Relief::sinusoid(100.0)?, Metal::AL, 1000.0)?;
/// let o = g.orders(0.5, 500.0).find(|o| o.order == -1).unwrap();
/// assert!((o.sin_theta - 0.0).abs() < 1e-15); // 0.5 − 500/1000
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReliefOrder {
    /// The order m.
    pub order: i32,
    /// sin θm = sin θi + m·λ/d, in (−1, 1).
    pub sin_theta: f64,
    /// Its efficiencies (the reflected z-flux of the order over the incident z-flux).
    pub efficiency: Polarised,
}

/// A relief grating on a metal, with its order efficiencies by scalar (Kirchhoff) diffraction.
///
/// **The model.** Light of wavelength λ arrives with sin θi = s (the x component of its direction
/// of travel, x across the grooves, so s = −wi.x in the crate's frame); order m leaves at
/// sin θm = s + m·λ/d and propagates when |sin θm| < 1. Each propagating order sees the
/// Kirchhoff phase screen exp(−i·φ_m(x)) with
///
/// φ_m(x) = k·h(x)·(cos θi + cos θm),  k = 2π/λ,
///
/// (the path difference of a ray reflected at height h(x) toward order m), whose power
/// w_m = |c_m|² ([`Relief::power`] at κ = k·(cos θi + cos θm)) has a closed form for the
/// sinusoid (J_m(k·h·(cos θi + cos θm)/2)², h peak-to-valley), the lamellar profile and the
/// sawtooth, and a bounded numerical integral for a Fourier series or sampled heights.
///
/// **Energy.** Scalar theory puts part of the power into evanescent orders (|sin θm| ≥ 1), which
/// carry no energy away from a lossless surface. Following Harvey's nonparaxial scalar theory
/// (J. E. Harvey et al., Opt. Eng. 38, 1039 (1999); Harvey & Pfisterer, Opt. Eng. 58, 087105
/// (2019)), that power is redistributed over the propagating orders in proportion to their
/// scalar weights: a perfectly conducting grating sends all the light into its propagating
/// orders, w_m/Σ_prop w. Each order is then scaled by the metal's Fresnel reflectance at its
/// local facet angle, the angle of incidence on the facet that would mirror the incident
/// direction into the order's (half the angle between them: the specular-point approximation),
/// R_s for TE and R_p for TM:
///
/// η_m = w_m / Σ_prop w · R(θ_facet,m),  cos θ_facet,m = ½·|(sin θm − sin θi, cos θi + cos θm)|.
///
/// So Σ_prop η_m ≤ max_m R ≤ 1 for every input: the model never creates energy, and a metal
/// absorbs 1 − R. The alternative, dropping the evanescent power (w_m without renormalisation),
/// would darken a grating at every Rayleigh line (where an order becomes evanescent its power
/// vanishes from the sum abruptly), while rigorous solutions show the neighbouring orders taking
/// it over; the renormalisation is that behaviour's simplest scalar form. Where the propagating
/// weights all vanish (possible only at isolated parameters, e.g. a half-duty lamellar profile at
/// φ = π with order 0 alone propagating), order 0 takes the whole share (the single order's
/// limit) if it propagates, else every η is 0.
///
/// **Reciprocity.** Rigorous efficiencies satisfy η_m(s) = η_m(−s − m·λ/d) (the reversed path);
/// the phase and the facet angle are symmetric in the two directions, but the renormalisation
/// divides by the propagating orders of each direction, which differ, so the model is
/// reciprocal only where both directions propagate the same set of orders.
///
/// **Where it holds.** A scalar model ignores polarisation in the diffraction itself (only the
/// facet's Fresnel factor differs between TE and TM), shadowing and multiple reflection; it
/// fails near d ≈ λ, for deep profiles and at surface-plasmon resonances in TM.
/// [`ScalarRelief::is_valid`] states the measured region, `docs/validity.md` the measurement.
///
/// **Cost.** A query computes the scalar weight of every propagating order (at most
/// 2·[`MAX_RELIEF_ORDER`] + 1): O(1) each for the closed forms (a sinusoid's Bessel value at
/// most about 2000 recurrence steps), one complex exponential per sample or quadrature node for
/// the numerical profiles. [`orders`](Self::orders) computes them twice (once for the sum, once
/// as it yields), [`order`](Self::order) once.
///
/// ```
/// use diffraction::relief::{Metal, Relief, ScalarRelief};
/// // An embossed holographic foil: 1000 lines/mm, 100 nm deep sinusoid, aluminium.
/// let foil = ScalarRelief::new(Relief::sinusoid(100.0)?, Metal::AL, 1000.0)?;
/// let orders: Vec<_> = foil.orders(0.0, 550.0).collect();
/// assert_eq!(orders.iter().map(|o| o.order).collect::<Vec<_>>(), [-1, 0, 1]);
/// let total: f64 = orders.iter().map(|o| o.efficiency.te).sum();
/// assert!(total <= Metal::AL.reflectance(550.0, 0.0).0 && total > 0.85);
/// // A symmetric profile at normal incidence: orders ±1 alike.
/// assert!((orders[0].efficiency.te - orders[2].efficiency.te).abs() < 1e-15);
/// assert_eq!(foil.order(1, 0.0, 550.0), Some(orders[2].efficiency));
/// assert_eq!(foil.order(2, 0.0, 550.0), None); // evanescent: 2·550/1000 > 1
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct ScalarRelief {
    relief: Relief,
    metal: Metal,
    period_nm: f64,
}

/// What a query shares between its orders.
#[derive(Debug, Clone, Copy)]
struct Query {
    s: f64,
    cos_i: f64,
    lambda_nm: f64,
    /// λ/d.
    step: f64,
    /// k = 2π/λ.
    k: f64,
    lo: i32,
    hi: i32,
}

impl ScalarRelief {
    /// The relief `relief` with period d = `period_nm` (finite, in (0, [`MAX_PERIOD_NM`]]) on
    /// `metal`. Errors name `period_nm`.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let r = Relief::lamellar(110.0, 0.3125)?;
    /// let cd = ScalarRelief::new(r.clone(), Metal::AL, 1600.0)?;
    /// assert_eq!((cd.period_nm(), cd.metal(), cd.relief()), (1600.0, Metal::AL, &r));
    /// assert_eq!(ScalarRelief::new(r, Metal::AL, 0.0).unwrap_err().parameter(), "period_nm");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(relief: Relief, metal: Metal, period_nm: f64) -> Result<ScalarRelief, Error> {
        if !(period_nm.is_finite() && period_nm > 0.0 && period_nm <= MAX_PERIOD_NM) {
            return Err(Error::invalid(
                "period_nm",
                period_nm,
                Requirement::AtMost {
                    bound_name: "MAX_PERIOD_NM",
                    bound: MAX_PERIOD_NM,
                },
            ));
        }
        Ok(ScalarRelief {
            relief,
            metal,
            period_nm,
        })
    }

    /// The relief's shape.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let g = ScalarRelief::new(Relief::sinusoid(80.0)?, Metal::AG, 740.0)?;
    /// assert_eq!(g.relief().name(), "sinusoid");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn relief(&self) -> &Relief {
        &self.relief
    }

    /// The metal.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let g = ScalarRelief::new(Relief::sinusoid(80.0)?, Metal::AG, 740.0)?;
    /// assert_eq!(g.metal(), Metal::AG);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn metal(&self) -> Metal {
        self.metal
    }

    /// The period d, nm.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let g = ScalarRelief::new(Relief::sinusoid(80.0)?, Metal::AG, 740.0)?;
    /// assert_eq!(g.period_nm(), 740.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.period_nm
    }

    /// The query's shared values and its candidate orders, `None` for an unphysical query
    /// (|s| ≥ 1, λ ≤ 0, non-finite input).
    fn query(&self, s: f64, lambda_nm: f64) -> Option<Query> {
        if !(s.is_finite() && s.abs() < 1.0 && lambda_nm.is_finite() && lambda_nm > 0.0) {
            return None;
        }
        let step = lambda_nm / self.period_nm;
        let cap = f64::from(MAX_RELIEF_ORDER);
        // −1 < s + m·step < 1, rounded outward and checked per order.
        let lo = math::floor((-1.0 - s) / step).clamp(-cap, cap) as i32;
        let hi = math::ceil((1.0 - s) / step).clamp(-cap, cap) as i32;
        Some(Query {
            s,
            cos_i: math::sqrt((1.0 - s) * (1.0 + s)),
            lambda_nm,
            step,
            k: TAU / lambda_nm,
            lo,
            hi,
        })
    }

    /// sin θm and cos θm of order m, `None` if it does not propagate.
    fn direction(q: &Query, m: i32) -> Option<(f64, f64)> {
        let sm = q.s + f64::from(m) * q.step;
        (sm.abs() < 1.0).then(|| (sm, math::sqrt((1.0 - sm) * (1.0 + sm))))
    }

    /// The scalar weight |c_m(κ_m)|² of a propagating order.
    fn weight(&self, q: &Query, m: i32, cos_m: f64) -> f64 {
        self.relief
            .power(m, q.k * (q.cos_i + cos_m), self.period_nm)
    }

    /// Σ_prop w_m over the query's orders.
    fn total_weight(&self, q: &Query) -> f64 {
        (q.lo..=q.hi)
            .filter_map(|m| Self::direction(q, m).map(|(_, c)| self.weight(q, m, c)))
            .sum()
    }

    /// The efficiencies of order m given its share.
    fn efficiency(&self, q: &Query, share: f64, sin_m: f64, cos_m: f64) -> Polarised {
        let (dx, dz) = (sin_m - q.s, q.cos_i + cos_m);
        let cos_facet = 0.5 * math::sqrt(dx * dx + dz * dz);
        let (rs, rp) = self.metal.reflectance(q.lambda_nm, cos_facet);
        Polarised {
            te: share * rs,
            tm: share * rp,
        }
    }

    /// The share of order m (w_m/W, or the degenerate rule of the type's docs where W = 0).
    fn share(weight: f64, total: f64, m: i32) -> f64 {
        if total > 0.0 {
            (weight / total).min(1.0)
        } else if m == 0 {
            1.0
        } else {
            0.0
        }
    }

    /// The efficiencies of order `order` for light arriving with sin θi = `sin_theta_i` at
    /// `lambda_nm`, `None` where the order is evanescent (|sin θi + m·λ/d| ≥ 1), beyond
    /// [`MAX_RELIEF_ORDER`], or the query is unphysical (|sin θi| ≥ 1: grazing incidence brings
    /// no flux; λ ≤ 0; non-finite input). Costs as much as computing every propagating order
    /// (the renormalisation needs their sum): use [`orders`](Self::orders) for all of them.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let g = ScalarRelief::new(Relief::lamellar(0.0, 0.5)?, Metal::AG, 1000.0)?;
    /// // A flat surface (depth 0) is a mirror: order 0 takes the Fresnel reflectance.
    /// let e = g.order(0, 0.5, 600.0).unwrap();
    /// let (rs, rp) = Metal::AG.reflectance(600.0, 0.75f64.sqrt());
    /// assert_eq!((e.te, e.tm), (rs, rp));
    /// assert_eq!(g.order(-1, 0.5, 600.0).map(|e| e.te), Some(0.0));
    /// assert_eq!(g.order(0, 1.0, 600.0), None);
    /// assert_eq!(g.order(0, 0.5, f64::NAN), None);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn order(&self, order: i32, sin_theta_i: f64, lambda_nm: f64) -> Option<Polarised> {
        let q = self.query(sin_theta_i, lambda_nm)?;
        if !(q.lo..=q.hi).contains(&order) {
            return None;
        }
        let (sm, cm) = Self::direction(&q, order)?;
        let total = self.total_weight(&q);
        let share = Self::share(self.weight(&q, order, cm), total, order);
        Some(self.efficiency(&q, share, sm, cm))
    }

    /// Every propagating reflected order (|m| ≤ [`MAX_RELIEF_ORDER`]) for light arriving with
    /// sin θi = `sin_theta_i` at `lambda_nm`, in increasing m; empty for an unphysical query (as
    /// in [`order`](Self::order)). Σ over the orders of TE (and of TM) is at most the largest
    /// Fresnel reflectance among them, ≤ 1.
    ///
    /// ```
    /// use diffraction::relief::{Metal, Relief, ScalarRelief};
    /// let blazed = ScalarRelief::new(Relief::sawtooth(8.627f64.to_radians())?, Metal::AL, 1666.67)?;
    /// // First-order Littrow at the blaze wavelength, 500 nm: s = −λ/(2d).
    /// let s = -500.0 / (2.0 * 1666.67);
    /// let first = blazed.orders(s, 500.0).find(|o| o.order == 1).unwrap();
    /// assert!((first.sin_theta + s).abs() < 1e-12); // back along the incident direction
    /// assert!(first.efficiency.te > 0.8);
    /// assert_eq!(blazed.orders(1.5, 500.0).count(), 0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn orders(&self, sin_theta_i: f64, lambda_nm: f64) -> ReliefOrders<'_> {
        let query = self.query(sin_theta_i, lambda_nm);
        let total = query.as_ref().map_or(0.0, |q| self.total_weight(q));
        ReliefOrders {
            grating: self,
            next: query.map_or(1, |q| q.lo),
            query,
            total,
        }
    }
}

/// The propagating orders of a [`ScalarRelief`] query, in increasing m (see
/// [`ScalarRelief::orders`]).
///
/// ```
/// use diffraction::relief::{Metal, Relief, ScalarRelief};
/// let g = ScalarRelief::new(Relief::sinusoid(50.0)?, Metal::AU, 2000.0)?;
/// let n = g.orders(0.3, 600.0).count(); // −1 < 0.3 + 0.3·m < 1: m = −4 … 2
/// assert_eq!(n, 7);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct ReliefOrders<'a> {
    grating: &'a ScalarRelief,
    query: Option<Query>,
    total: f64,
    next: i32,
}

impl Iterator for ReliefOrders<'_> {
    type Item = ReliefOrder;

    fn next(&mut self) -> Option<ReliefOrder> {
        let q = self.query?;
        while self.next <= q.hi {
            let m = self.next;
            self.next += 1;
            if let Some((sm, cm)) = ScalarRelief::direction(&q, m) {
                let g = self.grating;
                let share = ScalarRelief::share(g.weight(&q, m, cm), self.total, m);
                return Some(ReliefOrder {
                    order: m,
                    sin_theta: sm,
                    efficiency: g.efficiency(&q, share, sm, cm),
                });
            }
        }
        None
    }
}
