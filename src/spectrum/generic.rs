//! The reference colour of a model of any shape through its [`SpectralResponse`]: the generic
//! path's own rules ([`GenericStrategy`]), and the paper's peak colours for any model.

use glam::DVec3;

use super::bounds;
use super::rules::{gauss_legendre_rule, gl8, midpoint_rule};
use super::strategy::GenericStrategyKind;
use super::{saturate, GenericStrategy, Spectral, BAND, MAX_WAVELENGTHS};
use crate::color::Xyz;
use crate::data::cie;
use crate::num::math::{ceil, floor};
use crate::{Peak, SpectralResponse, MAX_ORDERS};

/// Where a model's order-0 lobe is seen, the paper's peak colours take the model's mean
/// response over this many equal intervals of the band (29.4 nm each) as the white's weight.
const ORDER0_INTERVALS: u32 = 16;

/// `WINDOWS` resolves a peak over ±`PEAK_WINDOW_WIDTHS` equivalent widths around it: the mass of
/// an F_N-shaped lobe beyond k widths is about 1/(π²k) of the order, and the 1 nm rule outside
/// integrates that smooth tail.
const PEAK_WINDOW_WIDTHS: f64 = 64.0;

/// Pieces of the peak window, each integrated with 8 points: one piece per equivalent width, so
/// the main lobe (±1 width) gets 16 points.
const PEAK_WINDOW_PIECES: u32 = 128;

/// Peaks at least this wide (nm) are left to the 1 nm rule, whose 8 points per nanometre put 16
/// points across such a peak's main lobe, as the window does. (At 0.5 nm, Thorman's lobes of
/// 0.5-0.6 nm were integrated with 4 points per width, 1.2·10⁻⁶ off.)
const RESOLVED_WIDTH_NM: f64 = 2.0;

impl Spectral {
    /// The reference colour of any model with a [`SpectralResponse`] at (wo, wi):
    /// ∫E·response·cmf/∫E·ȳ, through the model's `response` and `peaks`, by a rule of the
    /// generic path ([`GenericStrategy`], with its bounds for models that keep the contract of
    /// [`SpectralResponse::peaks`]):
    ///
    /// * `uniform(K)`, `gauss_legendre(K)`: the rule applied to the response;
    /// * `PEAK_SEARCH`: each reported peak its value times its equivalent width (a peak whose
    ///   window of ±64 widths reaches a band end by quadrature of the part inside); `WINDOWS`
    ///   where order 0's lobe is seen, and the finest Gauss-Legendre rule where the model
    ///   reports [`MAX_ORDERS`] orders (a comb finer than any table row);
    /// * `WINDOWS`: 8-point Gauss-Legendre on every 1 nm row of the tables, refined to 128
    ///   pieces over ±64 equivalent widths around every reported peak narrower than 2 nm (the
    ///   windows never overlap, so at most one per nanometre of the band does work);
    /// * `auto(a)`: `PEAK_SEARCH` where its bound 8/N_eff (N_eff from the sharpest reported peak)
    ///   meets a and order 0's lobe is not seen, else `WINDOWS`.
    ///
    /// A model that is a multiple of a grating's intensity has better paths:
    /// [`SpectralResponse::grating_response`] and [`Spectral::xyz_response`].
    ///
    /// ```
    /// # #[cfg(feature = "baselines")] {
    /// use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
    /// use diffraction::{AguHill, Grating, SpectralResponse, Thorman};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 300)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wo, wi) = (DVec3::new(0.35, 0.0, (1.0f64 - 0.35 * 0.35).sqrt()), DVec3::Z);
    /// // Thorman's lobes are not a grating's intensity: the generic path.
    /// let t = Thorman::matching(&g, 560.0)?;
    /// let windows = s.xyz_brdf(&t, wo, wi, GenericStrategy::WINDOWS);
    /// let peaks = s.xyz_brdf(&t, wo, wi, GenericStrategy::PEAK_SEARCH);
    /// assert!((peaks.y - windows.y).abs() < 8.0 / 300.0 * windows.y);
    /// # }
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_brdf<M: SpectralResponse + ?Sized>(
        &self,
        model: &M,
        wo: DVec3,
        wi: DVec3,
        strategy: GenericStrategy,
    ) -> Xyz {
        if !(wi.is_finite() && wo.is_finite()) {
            return Xyz::default();
        }
        let f = |l: f64| -> DVec3 { self.weight(l) * model.response(wo, wi, l) };
        let acc = match strategy.kind() {
            GenericStrategyKind::Uniform { samples } => midpoint_rule(samples, &f),
            GenericStrategyKind::GaussLegendre { intervals } => gauss_legendre_rule(intervals, &f),
            GenericStrategyKind::PeakSearch => self.peak_search_generic(model, wo, wi, &f),
            GenericStrategyKind::Windows => self.windows(model, wo, wi, &f),
            GenericStrategyKind::Auto { accuracy } => {
                // The sharpest reported peak sets N_eff = λ_m/(|m|·Δλ_m).
                let mut n_eff = f64::INFINITY;
                let summary = model.peaks(wo, wi, BAND, &mut |p| {
                    let m = p.order.unsigned_abs() as f64;
                    let n = p.wavelength_nm / (m * p.equivalent_width_nm);
                    if n.is_finite() && n > 0.0 {
                        n_eff = n_eff.min(n);
                    }
                });
                let fits = bounds::GENERIC_PEAK_SEARCH_PER_SLIT / n_eff <= accuracy;
                if summary.orders > 0 && !summary.specular && fits {
                    self.peak_search_generic(model, wo, wi, &f)
                } else {
                    self.windows(model, wo, wi, &f)
                }
            }
        };
        saturate(Xyz::new(acc.x, acc.y, acc.z))
    }

    /// The paper's own colours (its rendering steps 6-8) for any model: every reported peak's
    /// response at its wavelength, converted to colour as in [`Spectral::paper_peaks`]; where
    /// order 0's lobe is seen, the white times the model's mean response over the band (16
    /// equal intervals). Not an integral: see [`Spectral::paper_peaks`].
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral};
    /// use diffraction::{AguHill, Grating};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 300)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wo, wi) = (DVec3::new(0.35, 0.0, (1.0f64 - 0.35 * 0.35).sqrt()), DVec3::Z);
    /// let generic = s.paper_peaks_brdf(&AguHill::new(g), wo, wi);
    /// assert!((generic.y - s.paper_peaks(&g, 0.35).y).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn paper_peaks_brdf<M: SpectralResponse + ?Sized>(
        &self,
        model: &M,
        wo: DVec3,
        wi: DVec3,
    ) -> Xyz {
        if !(wi.is_finite() && wo.is_finite()) {
            return Xyz::default();
        }
        let mut acc = DVec3::ZERO;
        let scale = 1.0 / self.mean_power;
        let summary = model.peaks(wo, wi, BAND, &mut |p| {
            let e = self.illuminant.power(p.wavelength_nm) * scale * p.intensity;
            acc += DVec3::from(cie::cmf(p.wavelength_nm)) * e;
        });
        if summary.specular {
            let mut mean = 0.0;
            let step = BAND.width_nm() / ORDER0_INTERVALS as f64;
            for j in 0..ORDER0_INTERVALS {
                mean += model.response(wo, wi, BAND.min_nm() + (j as f64 + 0.5) * step);
            }
            acc += self.flat_dvec3() * (mean / ORDER0_INTERVALS as f64);
        }
        saturate(Xyz::new(acc.x, acc.y, acc.z))
    }

    /// The generic peak search (see [`Spectral::xyz_brdf`]).
    fn peak_search_generic<M: SpectralResponse + ?Sized>(
        &self,
        model: &M,
        wo: DVec3,
        wi: DVec3,
        f: &dyn Fn(f64) -> DVec3,
    ) -> DVec3 {
        let mut acc = DVec3::ZERO;
        // Each peak its value times its equivalent width; a peak whose window reaches a band
        // end by quadrature of the part inside, the window cut halfway to the neighbouring
        // peaks. Peaks come in order of decreasing wavelength, so each is handled when the next
        // arrives (its neighbours then known).
        let mut pending: Option<(Peak, f64)> = None; // the peak, the previous λ
        let handle = |p: Peak, longer: f64, shorter: f64, acc: &mut DVec3| {
            let w = p.equivalent_width_nm;
            let (l0, l1) = (
                p.wavelength_nm - PEAK_WINDOW_WIDTHS * w,
                p.wavelength_nm + PEAK_WINDOW_WIDTHS * w,
            );
            if l0 < BAND.min_nm() || l1 > BAND.max_nm() {
                let a = l0.max(0.5 * (p.wavelength_nm + shorter)).max(BAND.min_nm());
                let b = l1.min(0.5 * (p.wavelength_nm + longer)).min(BAND.max_nm());
                *acc += window(a, b, w, f);
            } else {
                *acc += self.weight(p.wavelength_nm) * (p.intensity * w);
            }
        };
        let summary = model.peaks(wo, wi, BAND, &mut |p| {
            if let Some((q, longer)) = pending.take() {
                handle(q, longer, p.wavelength_nm, &mut acc);
                pending = Some((p, q.wavelength_nm));
            } else {
                pending = Some((p, f64::INFINITY));
            }
        });
        if let Some((q, longer)) = pending {
            handle(q, longer, f64::NEG_INFINITY, &mut acc);
        }
        if summary.orders >= MAX_ORDERS {
            // Too many orders to visit (at most MAX_ORDERS were): a comb far finer than any
            // table row, integrated by the finest Gauss-Legendre rule instead.
            gauss_legendre_rule(MAX_WAVELENGTHS / 8, f)
        } else if summary.specular {
            // Order 0's light is broad and may lie under the peaks: where it is seen, the peak
            // search is `WINDOWS` (no peak counted twice).
            self.windows(model, wo, wi, f)
        } else {
            acc
        }
    }

    /// `WINDOWS`: 8-point Gauss-Legendre on every 1 nm row of the tables, and over
    /// ±`PEAK_WINDOW_WIDTHS` equivalent widths around every visited peak narrower than
    /// `RESOLVED_WIDTH_NM`, `PEAK_WINDOW_PIECES` pieces instead.
    fn windows<M: SpectralResponse + ?Sized>(
        &self,
        model: &M,
        wo: DVec3,
        wi: DVec3,
        f: &dyn Fn(f64) -> DVec3,
    ) -> DVec3 {
        let mut acc = DVec3::ZERO;
        let (lo, hi) = (BAND.min_nm(), BAND.max_nm());
        let mut l = lo;
        while l < hi {
            gl8(l, l + 1.0, &mut acc, f);
            l += 1.0;
        }
        // Resolve each narrow peak: over the whole 1 nm steps around ±PEAK_WINDOW_WIDTHS
        // equivalent widths, replace the 1 nm rule by the window's pieces (split at the table
        // rows). Peaks come in order of decreasing wavelength; each window stops where the
        // previous began, so windows never overlap.
        let mut previous_start = hi;
        model.peaks(wo, wi, BAND, &mut |p| {
            let w = p.equivalent_width_nm;
            if !(w > 0.0 && w < RESOLVED_WIDTH_NM) {
                return;
            }
            let (l0, l1) = (
                p.wavelength_nm - PEAK_WINDOW_WIDTHS * w,
                p.wavelength_nm + PEAK_WINDOW_WIDTHS * w,
            );
            let a = floor(l0).max(lo);
            let b = ceil(l1).min(previous_start);
            if b.partial_cmp(&a) != Some(core::cmp::Ordering::Greater) {
                return;
            }
            previous_start = a;
            let (c0, c1) = (l0.max(a), l1.min(b));
            let mut coarse = DVec3::ZERO;
            let mut t = a;
            while t < b {
                gl8(t, t + 1.0, &mut coarse, f);
                t += 1.0;
            }
            let mut fine = window(c0, c1, w, f);
            by_rows(a, c0, &mut fine, f);
            by_rows(c1, b, &mut fine, f);
            acc += fine - coarse;
        });
        acc
    }
}

/// ∫ f over the part [a, b] of the window of a peak of equivalent width `width`: one piece per
/// width (at most `PEAK_WINDOW_PIECES`, at least one), each split at the tables' 1 nm rows
/// (8-point Gauss-Legendre on every part). The cost follows the window's size in widths, so
/// windows cut short by their neighbours cost little however many there are.
fn window(a: f64, b: f64, width: f64, f: &dyn Fn(f64) -> DVec3) -> DVec3 {
    let mut out = DVec3::ZERO;
    if a.partial_cmp(&b) != Some(core::cmp::Ordering::Less) {
        return out;
    }
    let pieces = ceil((b - a) / width).clamp(1.0, PEAK_WINDOW_PIECES as f64) as u32;
    let piece = (b - a) / pieces as f64;
    for j in 0..pieces {
        let s0 = a + j as f64 * piece;
        let s1 = if j + 1 == pieces { b } else { s0 + piece };
        by_rows(s0, s1, &mut out, f);
    }
    out
}

/// 8-point Gauss-Legendre over [s0, s1] split at the integer nanometres.
fn by_rows(s0: f64, s1: f64, out: &mut DVec3, f: &dyn Fn(f64) -> DVec3) {
    let mut t = s0;
    while t < s1 {
        let e = (floor(t) + 1.0).min(s1);
        gl8(t, e, out, f);
        t = e;
    }
}
