//! The grating equation d·u = m·λ (the paper's eq. 11): which orders a period sends where.
//!
//! Every model of the crate (Agu-Hill, Thorman, Stam, the radiometric BSDF) puts its maxima on
//! the grating equation; only their brightness and shape differ. [`GratingEquation`] holds the
//! one parameter the equation needs, the period d, and answers the two questions every model
//! asks: which orders peak inside a wavelength band for a given phase projection u
//! ([`GratingEquation::orders`]), and in which directions a wavelength leaves for a given
//! incidence ([`GratingEquation::propagating`]).

use glam::DVec3;

use crate::error::{positive, Error};
use crate::num::math;
use crate::Band;

/// The most orders a library call visits one by one: the `peaks` of the crate's models
/// ([`SpectralResponse::peaks`](crate::SpectralResponse::peaks) of `AguHill`, `Thorman`, `Stam`,
/// `GratingBsdf`)
/// visit at most this many, those of lowest |m| (the longest wavelengths, and for the paper's
/// model the brightest: S(β_m) ≤ 1/(π·m·w/d)²), so that a call does bounded work whatever the
/// period. The band holds more orders only where d·|u| exceeds about 4·10⁷ nm (4 cm) for the
/// visible band, where the orders are spaced by less than 0.002 nm: a continuum for any
/// colour integral, which the spectral strategies integrate in closed form without visiting
/// the orders (see [`spectrum`](crate::spectrum)). The iterators [`GratingEquation::orders`]
/// and [`Grating::peaks`](crate::Grating::peaks) themselves are lazy and yield every order.
///
/// ```
/// use diffraction::{AguHill, Band, Grating, SpectralResponse, MAX_ORDERS};
/// use glam::DVec3;
/// let wide = Band::new(1e-9, 1000.0)?; // 1.6·10¹² orders at d = 1600 nm, u = 1
/// let model = AguHill::new(Grating::new(1600.0, 800.0, 10)?);
/// let (wo, wi) = (DVec3::new(0.4, 0.0, 0.9165), DVec3::new(-0.6, 0.0, 0.8));
/// let mut seen = 0u32;
/// let summary = model.peaks(wo, wi, wide, &mut |_| seen += 1);
/// assert_eq!((summary.orders, seen), (MAX_ORDERS, MAX_ORDERS));
/// # Ok::<(), diffraction::Error>(())
/// ```
pub const MAX_ORDERS: u32 = 1 << 16;

/// The grating equation of a period d: d·u = m·λ, m ∈ ℤ.
///
/// ```
/// use diffraction::{Band, GratingEquation};
/// let cd = GratingEquation::new(1600.0)?;
/// // d·u = 1440 nm: orders 2, 3 and 4 peak at 720, 480 and 360 nm.
/// let orders: Vec<i32> = cd.orders(0.9, Band::VISIBLE).map(|o| o.order).collect();
/// assert_eq!(orders, [2, 3, 4]);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GratingEquation {
    period_nm: f64,
}

/// One order of the grating equation with its peak wavelength (see [`GratingEquation::orders`]).
///
/// ```
/// use diffraction::{Band, GratingEquation};
/// let o = GratingEquation::new(1600.0)?.orders(-0.6, Band::VISIBLE).next().unwrap();
/// assert_eq!(o.order, -2); // the sign of u
/// assert!((o.wavelength_nm - 480.0).abs() < 1e-12);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Order {
    /// The order m (same sign as u, never 0).
    pub order: i32,
    /// λ_m = d·|u|/|m|, nm.
    pub wavelength_nm: f64,
}

impl GratingEquation {
    /// The equation of period `period_nm` (finite, > 0).
    ///
    /// ```
    /// use diffraction::GratingEquation;
    /// assert_eq!(GratingEquation::new(1600.0)?.period_nm(), 1600.0);
    /// assert_eq!(GratingEquation::new(0.0).unwrap_err().parameter(), "period_nm");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn new(period_nm: f64) -> Result<GratingEquation, Error> {
        Ok(GratingEquation {
            period_nm: positive("period_nm", period_nm)?,
        })
    }

    /// The period d, nm.
    ///
    /// ```
    /// use diffraction::GratingEquation;
    /// assert_eq!(GratingEquation::new(740.0)?.period_nm(), 740.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.period_nm
    }

    /// The wavelength at which order `order` peaks for phase projection u: λ_m = d·u/m, or
    /// `None` when m = 0, when m has the wrong sign for u, or when λ_m is not a finite positive
    /// number.
    ///
    /// ```
    /// use diffraction::GratingEquation;
    /// let e = GratingEquation::new(1600.0)?;
    /// assert_eq!(e.wavelength(0.75, 2), Some(600.0));
    /// assert_eq!(e.wavelength(0.75, -2), None);
    /// assert_eq!(e.wavelength(0.75, 0), None);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn wavelength(&self, u: f64, order: i32) -> Option<f64> {
        if order == 0 || !u.is_finite() {
            return None;
        }
        let l = self.period_nm * u / order as f64;
        (l > 0.0 && l.is_finite()).then_some(l)
    }

    /// Every order m ≠ 0 whose peak λ_m = d·|u|/|m| lies in `band`, in order of increasing |m|
    /// (decreasing wavelength), as an allocation-free iterator.
    ///
    /// Order 0 (u = 0, the mirror direction for every wavelength) is never listed. Orders are
    /// `i32`: where the band would hold orders beyond |m| = `i32::MAX` (d·|u| above about
    /// 2·10¹² nm for the visible band), the iterator stops at `i32::MAX`; its length is always
    /// what it yields, and it never wraps.
    ///
    /// ```
    /// use diffraction::{Band, GratingEquation};
    /// let e = GratingEquation::new(1600.0)?;
    /// assert_eq!(e.orders(0.9, Band::VISIBLE).len(), 3);
    /// assert_eq!(e.orders(0.0, Band::VISIBLE).len(), 0);
    /// // A huge period: orders up to i32::MAX, never past it.
    /// let huge = GratingEquation::new(1.7824e12)?.orders(1.0, Band::VISIBLE);
    /// assert_eq!(huge.last().unwrap().order, i32::MAX);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn orders(&self, u: f64, band: Band) -> Orders {
        let q = self.period_nm * u.abs();
        let (next, last) = if q > 0.0 && q.is_finite() {
            order_range(q, band)
        } else {
            (1, 0)
        };
        Orders {
            q,
            negative: u < 0.0,
            next,
            last,
        }
    }

    /// The propagating diffracted orders for light arriving from `wi` (unit, toward the light,
    /// in the local frame: z normal, x grating vector) at one wavelength: the conical grating
    /// equation wo_x = m·λ/d − wi_x, wo_y = −wi_y, wo_z = √(1 − wo_x² − wo_y²).
    ///
    /// Evanescent orders (wo_z² = 1 − wo_x² − wo_y² ≤ 0 as computed) are never visited: the
    /// first and the last propagating order are found before the first item, by a closed form
    /// and two bisections of at most 34 evaluations each (the
    /// computed wo_z² rises and then falls with m, so the propagating orders are one run), and
    /// every item is then one step. The work to the first item is therefore bounded whatever λ/d
    /// is (λ/d = 10⁻²³ included, where rounding used to hide millions of empty orders at the
    /// ends); the iterator yields at most 2·d/λ + 1 orders, and never more than 2³² (orders are
    /// `i32`). It is lazy; no library call walks it. Order 0 is the mirror direction. Returns
    /// nothing for λ ≤ 0, a non-finite `wi` or |wi_y| ≥ 1.
    ///
    /// ```
    /// use diffraction::GratingEquation;
    /// use glam::DVec3;
    /// // 600 lines/mm, 532 nm at normal incidence: first orders at ±18.6°.
    /// let e = GratingEquation::new(1e6 / 600.0)?;
    /// let orders: Vec<_> = e.propagating(DVec3::Z, 532.0).collect();
    /// assert_eq!(orders.iter().map(|o| o.0).collect::<Vec<_>>(), [-3, -2, -1, 0, 1, 2, 3]);
    /// assert!((orders[4].1.x.asin().to_degrees() - 18.61).abs() < 0.01);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn propagating(&self, wi: DVec3, lambda_nm: f64) -> Propagating {
        let empty = Propagating {
            wi,
            step: 0.0,
            next: 1,
            last: 0,
        };
        if lambda_nm.is_nan() || lambda_nm <= 0.0 || !wi.is_finite() {
            return empty;
        }
        let step = lambda_nm / self.period_nm; // change of wo_x per order
        let c2 = 1.0 - wi.y * wi.y;
        if c2.is_nan() || c2 <= 0.0 || !step.is_finite() || step == 0.0 {
            return empty;
        }
        let c = math::sqrt(c2);
        // Propagating: |m·step − wi_x| < c, up to the rounding of the two sides.
        let lo = math::ceil((wi.x - c) / step);
        let hi = math::floor((wi.x + c) / step);
        let clamp = |v: f64| v.clamp(i32::MIN as f64, i32::MAX as f64) as i64;
        let (lo, hi) = (clamp(lo), clamp(hi));
        if lo > hi {
            return empty;
        }
        let probe = Propagating {
            wi,
            step,
            next: lo,
            last: hi,
        };
        // wo_z² as computed is non-decreasing in m up to the order nearest the mirror of wi_x
        // (wo_x = m·step − wi_x ≤ 0) and non-increasing after it: every operation is a
        // correctly rounded, monotone one. So the propagating orders are one run around the
        // crest; bisect for its ends.
        let crest = clamp(math::rint(wi.x / step)).clamp(lo, hi);
        let crest = [crest - 1, crest, crest + 1]
            .into_iter()
            .filter(|m| (lo..=hi).contains(m))
            .max_by(|&a, &b| probe.z2(a).total_cmp(&probe.z2(b)))
            .unwrap_or(crest);
        if probe.z2(crest) <= 0.0 || probe.z2(crest).is_nan() {
            return empty;
        }
        let up = |m: i64| probe.z2(m) > 0.0;
        let first = first_true(lo, crest, &up);
        let last = last_true(crest, hi, &up);
        Propagating {
            wi,
            step,
            next: first,
            last,
        }
    }
}

/// The first and last |m| ≥ 1 with q/|m| inside the band (q = d·|u| > 0); empty when first > last.
fn order_range(q: f64, band: Band) -> (i64, i64) {
    let cap = i32::MAX as f64;
    let mut first = math::ceil(q / band.max_nm()).max(1.0);
    let mut last = math::floor(q / band.min_nm());
    // The divisions round; settle the ends with the exact membership test on λ = q/m.
    if first > 1.0 && band.contains(q / (first - 1.0)) {
        first -= 1.0;
    }
    if !band.contains(q / first) {
        first += 1.0;
    }
    if band.contains(q / (last + 1.0)) {
        last += 1.0;
    }
    if last >= 1.0 && !band.contains(q / last) {
        last -= 1.0;
    }
    if first > cap {
        return (1, 0);
    }
    (first as i64, last.clamp(0.0, cap) as i64)
}

/// The orders of one u inside a band, from [`GratingEquation::orders`].
///
/// ```
/// use diffraction::{Band, GratingEquation};
/// let mut orders = GratingEquation::new(1600.0)?.orders(0.9, Band::VISIBLE);
/// assert_eq!(orders.len(), 3);
/// assert_eq!(orders.next().map(|o| o.order), Some(2));
/// assert_eq!(orders.len(), 2);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Orders {
    q: f64,
    negative: bool,
    /// |m| of the next order; `i64` so that stepping past `i32::MAX` cannot wrap.
    next: i64,
    last: i64,
}

impl Iterator for Orders {
    type Item = Order;

    #[inline]
    fn next(&mut self) -> Option<Order> {
        if self.next > self.last {
            return None;
        }
        let m = self.next;
        self.next += 1;
        let order = m as i32; // m ≤ i32::MAX by construction
        Some(Order {
            order: if self.negative { -order } else { order },
            wavelength_nm: self.q / m as f64,
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.last - self.next + 1).max(0) as usize;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Orders {}
impl core::iter::FusedIterator for Orders {}

/// The propagating orders for one incidence and wavelength, from
/// [`GratingEquation::propagating`]: `(order, outgoing unit direction)`.
///
/// ```
/// use diffraction::GratingEquation;
/// use glam::DVec3;
/// // Normal incidence, λ/d = 1/2: wo_x = m/2, so |m| = 2 would graze (wo_z = 0) and is skipped.
/// let e = GratingEquation::new(1600.0)?;
/// let orders: Vec<i32> = e.propagating(DVec3::Z, 800.0).map(|o| o.0).collect();
/// assert_eq!(orders, [-1, 0, 1]);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Propagating {
    wi: DVec3,
    step: f64,
    next: i64,
    last: i64,
}

impl Iterator for Propagating {
    type Item = (i32, DVec3);

    fn next(&mut self) -> Option<(i32, DVec3)> {
        if self.next > self.last {
            return None;
        }
        let m = self.next;
        self.next += 1;
        let ox = m as f64 * self.step - self.wi.x;
        let oy = -self.wi.y;
        // Positive for every m of the run (found so in `propagating`); the guard only keeps a
        // direction with a real z.
        let z2 = (1.0 - ox * ox - oy * oy).max(0.0);
        Some((m as i32, DVec3::new(ox, oy, math::sqrt(z2))))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = (self.last - self.next + 1).max(0) as usize;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Propagating {}
impl core::iter::FusedIterator for Propagating {}

impl Propagating {
    /// wo_z² of order m, exactly as `next` computes it.
    #[inline]
    fn z2(&self, m: i64) -> f64 {
        let ox = m as f64 * self.step - self.wi.x;
        let oy = -self.wi.y;
        1.0 - ox * ox - oy * oy
    }
}

/// The most evaluations of wo_z² each of the two bisections of
/// [`GratingEquation::propagating`] makes: the orders span at most 2³² values, so 33 halvings
/// settle an end; one more for the test at the end.
#[cfg(test)]
const PROPAGATING_SEARCH_STEPS: u32 = 34;

/// The smallest m in [lo, hi] with `ok(m)`, for `ok` false then true on [lo, hi] and true at hi.
fn first_true(mut lo: i64, mut hi: i64, ok: &dyn Fn(i64) -> bool) -> i64 {
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    hi
}

/// The largest m in [lo, hi] with `ok(m)`, for `ok` true then false on [lo, hi] and true at lo.
fn last_true(mut lo: i64, mut hi: i64, ok: &dyn Fn(i64) -> bool) -> i64 {
    while lo < hi {
        let mid = hi - (hi - lo) / 2;
        if ok(mid) {
            lo = mid;
        } else {
            hi = mid - 1;
        }
    }
    lo
}

impl GratingEquation {
    /// The equation of a period already validated by its owner.
    pub(crate) fn from_valid_period(period_nm: f64) -> GratingEquation {
        GratingEquation { period_nm }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each bisection settles an end of a range of up to 2³² orders in at most
    /// `PROPAGATING_SEARCH_STEPS` evaluations.
    #[test]
    fn the_bisections_are_bounded() {
        use core::cell::Cell;
        let calls = Cell::new(0u32);
        let (lo, hi) = (i32::MIN as i64, i32::MAX as i64);
        for edge in [lo, lo + 1, -7, 0, 12345, hi - 1, hi] {
            calls.set(0);
            let ok = |m: i64| {
                calls.set(calls.get() + 1);
                m >= edge
            };
            assert_eq!(first_true(lo, hi, &ok), edge);
            assert!(calls.get() <= PROPAGATING_SEARCH_STEPS, "{}", calls.get());
            calls.set(0);
            let ok = |m: i64| {
                calls.set(calls.get() + 1);
                m <= edge
            };
            assert_eq!(last_true(lo, hi, &ok), edge);
            assert!(calls.get() <= PROPAGATING_SEARCH_STEPS, "{}", calls.get());
        }
    }

    /// The run of propagating orders is exactly the set of m whose wo_z² is positive, also
    /// where λ/d is so small that rounding leaves millions of empty orders at its ends.
    #[test]
    fn the_run_is_every_propagating_order() {
        let e = GratingEquation::new(1600.0).unwrap();
        for wi in [
            DVec3::Z,
            DVec3::new(0.6, 0.0, 0.8),
            DVec3::new(-0.6, 0.0, 0.8),
            DVec3::new(0.3, -0.4, (0.75f64).sqrt()),
        ] {
            for l in [400.0, 550.0, 800.0, 1600.0, 3199.0] {
                let p = e.propagating(wi, l);
                let step = l / 1600.0;
                let want: Vec<i32> = (-10..=10)
                    .filter(|&m| {
                        let ox = m as f64 * step - wi.x;
                        1.0 - ox * ox - wi.y * wi.y > 0.0
                    })
                    .collect();
                assert_eq!(p.len(), want.len());
                assert_eq!(p.map(|o| o.0).collect::<Vec<_>>(), want, "{wi} {l}");
            }
        }
        // λ/d = 10⁻²³ at grazing incidence: the first order of the run is the first m whose
        // wo_z² is positive, found without walking the empty ones.
        let tiny = GratingEquation::new(1e23).unwrap();
        for wi in [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.6, 0.8, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
        ] {
            let mut p = tiny.propagating(wi, 1.0);
            let (m, dir) = p.next().unwrap();
            let ox = (m as f64 - 1.0) * 1e-23 - wi.x;
            let before = 1.0 - ox * ox - wi.y * wi.y;
            assert!(m == i32::MIN || before <= 0.0, "{wi}: {m} is not the first");
            assert!(dir.z > 0.0 && dir.is_finite());
        }
    }
}
