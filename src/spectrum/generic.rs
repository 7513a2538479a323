//! The reference colour of any [`DiffractionBrdf`]: the path for models that are not a multiple
//! of a grating's intensity.

use glam::DVec3;

use super::rules::{gauss_legendre_rule, gl8, midpoint_rule};
use super::{Spectral, Strategy, BAND, MAX_WAVELENGTHS};
use crate::cie;
use crate::color::Xyz;
use crate::math::{ceil, floor};
use crate::{DiffractionBrdf, Peak, MAX_ORDERS};

/// Where a model's order-0 lobe is seen, the peak search integrates the whole band with 8-point
/// Gauss-Legendre on this many equal intervals (29.4 nm each): order 0's light is broad in
/// wavelength (its lobe spans the band near the mirror direction), and 128 evaluations resolve
/// the tables' variation to the peak search's accuracy.
const ORDER0_INTERVALS: u32 = 16;

/// `Exact` resolves a peak over ±`PEAK_WINDOW_WIDTHS` equivalent widths around it: the mass of an
/// F_N-shaped lobe beyond k widths is about 1/(π²k) of the order, and the 1 nm rule outside
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
    /// The reference colour of any [`DiffractionBrdf`] at (wi, wo): ∫E·f·cmf/∫E·ȳ with f the
    /// model's `eval`, multiplied by cos θi when the model does not include it.
    ///
    /// A model that says it is a multiple of a grating's intensity
    /// ([`DiffractionBrdf::grating_response`]) is integrated by the grating paths of
    /// [`Spectral::xyz`], times its scale. Any other model is integrated through `eval` and
    /// `peaks` with the same algorithm each [`Strategy`] names and the same bound (see
    /// [`Strategy`]): `Uniform` and `GaussLegendre` apply their rule to the integrand;
    /// `PeakSearch` (both modes) gives each visited peak its value times its equivalent width,
    /// plus 8-point Gauss-Legendre on 16 intervals where the order-0 lobe is seen (and, where
    /// the model reports [`MAX_ORDERS`] orders, the most it visits, the rule
    /// of `GaussLegendre` with its largest count instead); `PaperPeaks`
    /// the peak values at their wavelengths, and the white scaled by the band-averaged value
    /// where the order-0 lobe is seen; `Exact` and `Auto` 8-point Gauss-Legendre on every 1 nm
    /// step of the tables, refined to 128 pieces over ±64 equivalent widths around every
    /// visited peak narrower than 2 nm. The bounds hold for models that keep the contract of
    /// [`DiffractionBrdf::peaks`]. The windows never overlap, so at most one per
    /// nanometre of the band does work; where a model reports [`MAX_ORDERS`] peaks
    /// (a comb finer than any table row) the peak search is `GaussLegendre` with the finest
    /// rule. `PaperPeaks` sums the visited peaks only.
    ///
    /// ```
    /// use diffraction::spectrum::{Illuminant, Spectral, Strategy};
    /// use diffraction::{AguHill, Grating, Thorman};
    /// use glam::DVec3;
    /// let g = Grating::new(1600.0, 800.0, 300)?;
    /// let s = Spectral::new(Illuminant::D65);
    /// let (wi, wo) = (DVec3::Z, DVec3::new(0.35, 0.0, (1.0f64 - 0.35 * 0.35).sqrt()));
    /// // The paper's model is its grating's intensity: the same colour as `xyz` at u = 0.35.
    /// let model = s.xyz_brdf(&AguHill::new(g), wi, wo, Strategy::Exact);
    /// assert_eq!(model, s.xyz(&g, 0.35, Strategy::Exact));
    /// // Thorman's lobes are not: the generic path.
    /// let t = s.xyz_brdf(&Thorman::matching(&g, 560.0)?, wi, wo, Strategy::Exact);
    /// assert!(t.y > 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn xyz_brdf<B: DiffractionBrdf + ?Sized>(
        &self,
        brdf: &B,
        wi: DVec3,
        wo: DVec3,
        strategy: Strategy,
    ) -> Xyz {
        if !(wi.is_finite() && wo.is_finite()) {
            return Xyz::default();
        }
        if let Some(r) = brdf.grating_response(wi, wo) {
            let spectral = if r.envelope.is_one() {
                *self
            } else {
                self.with_envelope(r.envelope)
            };
            return spectral.xyz(&r.grating, r.u, strategy) * r.scale;
        }
        let cos = if brdf.cosine_included() {
            1.0
        } else {
            wi.z.max(0.0)
        };
        let f = |l: f64| -> DVec3 {
            let v = brdf.eval(wi, wo, l) * cos;
            let w = self.weight(l);
            w * v
        };
        let mut acc = DVec3::ZERO;
        match strategy {
            Strategy::Uniform { samples } => acc = midpoint_rule(samples, &f),
            Strategy::GaussLegendre { intervals } => acc = gauss_legendre_rule(intervals, &f),
            Strategy::PeakSearch { .. } => {
                // Each peak its value times its equivalent width; a peak whose window reaches a
                // band end by quadrature of the part inside, the window cut halfway to the
                // neighbouring peaks. Peaks come in order of decreasing wavelength, so each is
                // handled when the next arrives (its neighbours then known).
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
                        *acc += window(a, b, w, &f);
                    } else {
                        *acc += self.weight(p.wavelength_nm) * (p.intensity * cos * w);
                    }
                };
                let summary = brdf.peaks(wi, wo, BAND, &mut |p| {
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
                    // Too many orders to visit (at most MAX_ORDERS were): a comb far finer
                    // than any table row, integrated by the finest Gauss-Legendre rule instead.
                    acc = gauss_legendre_rule(MAX_WAVELENGTHS / 8, &f);
                } else if summary.specular {
                    // Order 0's light is broad and may lie under the peaks: where it is seen,
                    // the peak search is `Exact` (no peak counted twice).
                    acc = self.exact_generic(brdf, wi, wo, &f);
                }
            }
            Strategy::PaperPeaks => {
                let scale = 1.0 / self.mean_power;
                let summary = brdf.peaks(wi, wo, BAND, &mut |p| {
                    let e = self.illuminant.power(p.wavelength_nm) * scale * p.intensity * cos;
                    acc += DVec3::from(cie::cmf(p.wavelength_nm)) * e;
                });
                if summary.specular {
                    let mut mean = 0.0;
                    let step = BAND.width_nm() / ORDER0_INTERVALS as f64;
                    for j in 0..ORDER0_INTERVALS {
                        mean += brdf.eval(wi, wo, BAND.min_nm() + (j as f64 + 0.5) * step);
                    }
                    let k = mean / ORDER0_INTERVALS as f64 * cos;
                    acc += self.flat_dvec3() * k;
                }
            }
            Strategy::Exact | Strategy::Asymptotic | Strategy::Auto { .. } => {
                acc = self.exact_generic(brdf, wi, wo, &f)
            }
        }
        Xyz::new(acc.x.max(0.0), acc.y.max(0.0), acc.z.max(0.0))
    }

    /// `Exact` on the generic path: 8-point Gauss-Legendre on every 1 nm row of the tables, and
    /// over ±`PEAK_WINDOW_WIDTHS` equivalent widths around every visited peak narrower than
    /// `RESOLVED_WIDTH_NM`, `PEAK_WINDOW_PIECES` pieces instead.
    fn exact_generic<B: DiffractionBrdf + ?Sized>(
        &self,
        brdf: &B,
        wi: DVec3,
        wo: DVec3,
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
        brdf.peaks(wi, wo, BAND, &mut |p| {
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
