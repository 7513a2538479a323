//! The reference colour of any [`DiffractionBrdf`]: the path for models that are not a multiple
//! of a grating's intensity.

use glam::DVec3;

use super::rules::{gauss_legendre_rule, gl8, midpoint_rule};
use super::{Spectral, Strategy, BAND, MAX_WAVELENGTHS};
use crate::cie;
use crate::color::Xyz;
use crate::math::{ceil, floor};
use crate::{DiffractionBrdf, MAX_ORDERS};

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
    /// visited peak narrower than 0.5 nm (the windows never overlap, so at most one per
    /// nanometre of the band does work). `PaperPeaks` sums the visited peaks only.
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
            return self.xyz(&r.grating, r.u, strategy) * r.scale;
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
                let summary = brdf.peaks(wi, wo, BAND, &mut |p| {
                    acc += self.weight(p.wavelength_nm) * p.intensity * cos * p.equivalent_width_nm;
                });
                if summary.orders >= MAX_ORDERS {
                    // Too many orders to visit (at most MAX_ORDERS were): a comb far finer
                    // than any table row, integrated by the finest Gauss-Legendre rule instead.
                    acc = gauss_legendre_rule(MAX_WAVELENGTHS / 8, &f);
                } else if summary.specular {
                    let step = BAND.width_nm() / 16.0;
                    for j in 0..16 {
                        let a = BAND.min_nm() + j as f64 * step;
                        gl8(a, a + step, &mut acc, &f);
                    }
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
                    for j in 0..16 {
                        mean += brdf.eval(wi, wo, BAND.min_nm() + (j as f64 + 0.5) * 29.375);
                    }
                    let k = mean / 16.0 * cos;
                    acc += DVec3::new(self.white.x, self.white.y, self.white.z) * k;
                }
            }
            Strategy::Exact | Strategy::Auto { .. } => {
                let (lo, hi) = (BAND.min_nm(), BAND.max_nm());
                let mut l = lo;
                while l < hi {
                    gl8(l, l + 1.0, &mut acc, &f);
                    l += 1.0;
                }
                // Resolve each narrow peak: over the whole 1 nm steps around ±64 equivalent
                // widths, replace the 1 nm rule by 128 pieces (split at the table rows). Peaks come
                // in order of decreasing wavelength; each window stops where the previous began,
                // so windows never overlap.
                let mut previous_start = hi;
                brdf.peaks(wi, wo, BAND, &mut |p| {
                    let w = p.equivalent_width_nm;
                    if w.is_nan() || w <= 0.0 || w >= 0.5 {
                        return;
                    }
                    let a = floor(p.wavelength_nm - 64.0 * w).max(lo);
                    let b = ceil(p.wavelength_nm + 64.0 * w).min(previous_start);
                    if b.is_nan() || b <= a {
                        return;
                    }
                    previous_start = a;
                    let (c0, c1) = (
                        (p.wavelength_nm - 64.0 * w).max(a),
                        (p.wavelength_nm + 64.0 * w).min(b),
                    );
                    let mut coarse = DVec3::ZERO;
                    let mut fine = DVec3::ZERO;
                    let mut t = a;
                    while t < b {
                        gl8(t, t + 1.0, &mut coarse, &f);
                        t += 1.0;
                    }
                    let by_rows = |s0: f64, s1: f64, out: &mut DVec3| {
                        let mut t = s0;
                        while t < s1 {
                            let e = (floor(t) + 1.0).min(s1);
                            gl8(t, e, out, &f);
                            t = e;
                        }
                    };
                    by_rows(a, c0, &mut fine);
                    by_rows(c1, b, &mut fine);
                    let piece = (c1 - c0) / 128.0;
                    for j in 0..128 {
                        let s0 = c0 + j as f64 * piece;
                        by_rows(s0, s0 + piece, &mut fine);
                    }
                    acc += fine - coarse;
                });
            }
        }
        Xyz::new(acc.x.max(0.0), acc.y.max(0.0), acc.z.max(0.0))
    }
}
