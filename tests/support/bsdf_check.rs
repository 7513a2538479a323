//! Shared machinery of the BSDF tests: a seeded generator, the χ² goodness-of-fit test (after
//! pbrt-v4's `bsdfs_test.cpp`: pool small expected counts, Šidák correction for the number of
//! tests), Gauss-Legendre rules and the tolerances, each with its reason.
#![allow(dead_code)]

use diffraction::{Bsdf, GratingBsdf, Slits};
use glam::DVec3;

#[path = "groove_proxy.rs"]
mod groove_proxy;
#[path = "quadrature.rs"]
mod quadrature;
pub use groove_proxy::proxy_scale;
#[path = "rng.rs"]
mod rng;
pub use quadrature::integrate;
pub use rng::Rng;

/// Significance of each family of χ² tests, before the Šidák correction (pbrt's CHI2_SLEVEL).
pub const CHI2_SIGNIFICANCE: f64 = 0.01;
/// Cells with a smaller expected count are pooled (pbrt's CHI2_MINFREQ).
pub const CHI2_MIN_EXPECTED: f64 = 5.0;
/// A cell the pdf says is empty may hold this share of the samples (rounding at period and
/// disk boundaries), as pbrt allows 10⁻⁵.
pub const CHI2_EMPTY_CELL_SHARE: f64 = 1e-5;
/// The furnace: the sampled albedo must be within this many standard errors of the analytic one
/// (fixed seeds, so the outcome is reproducible).
pub const FURNACE_SIGMAS: f64 = 3.0;
/// `sample`'s f and pdf against `f` and `pdf` at its direction: the sampler re-derives u and v
/// from the direction it returns with the same operations, so they are bit-identical.
pub const SAMPLE_CONSISTENCY: f64 = 0.0;
/// The library's albedo quadrature against the test's own (different pieces, graded edges,
/// averaged tail): measured agreement 1.9·10⁻⁸ relative (N ≤ 1000), asserted at 10⁻⁷.
pub const ALBEDO_AGREEMENT: f64 = 1e-7;

/// The unit direction above the surface with tangent part (x, y).
pub fn dir(x: f64, y: f64) -> DVec3 {
    DVec3::new(x, y, (1.0 - x * x - y * y).sqrt())
}

/// Regularised lower incomplete gamma P(a, x) (series below a + 1, continued fraction above).
pub fn gamma_p(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let ln_pre = a * x.ln() - x - ln_gamma(a);
    if x < a + 1.0 {
        let (mut ap, mut sum, mut del) = (a, 1.0 / a, 1.0 / a);
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-16 {
                break;
            }
        }
        sum * ln_pre.exp()
    } else {
        // Lentz for the continued fraction of Q(a, x).
        let tiny = 1e-300;
        let mut b = x + 1.0 - a;
        let mut c = 1.0 / tiny;
        let mut d = 1.0 / b;
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            if d.abs() < tiny {
                d = tiny;
            }
            c = b + an / c;
            if c.abs() < tiny {
                c = tiny;
            }
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-16 {
                break;
            }
        }
        1.0 - ln_pre.exp() * h
    }
}

/// ln Γ(a) for a > 0 (Lanczos, g = 7, 9 terms; 1e-15 relative).
pub fn ln_gamma(a: f64) -> f64 {
    const G: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if a < 0.5 {
        let pi = std::f64::consts::PI;
        return (pi / (pi * a).sin()).ln() - ln_gamma(1.0 - a);
    }
    let a = a - 1.0;
    let mut x = G[0];
    for (i, g) in G.iter().enumerate().skip(1) {
        x += g / (a + i as f64);
    }
    let t = a + 7.5;
    0.5 * (2.0 * std::f64::consts::PI).ln() + (a + 0.5) * t.ln() - t + x.ln()
}

/// The outcome of one χ² test.
#[derive(Debug)]
pub struct Chi2 {
    pub statistic: f64,
    pub dof: usize,
    pub p_value: f64,
}

/// pbrt-v4's χ² test: cells sorted by expected count, those below [`CHI2_MIN_EXPECTED`]
/// pooled, and an error when a cell expected empty holds more than
/// [`CHI2_EMPTY_CELL_SHARE`] of the samples.
pub fn chi2(observed: &[f64], expected: &[f64], samples: f64) -> Result<Chi2, String> {
    let mut idx: Vec<usize> = (0..observed.len()).collect();
    idx.sort_by(|&a, &b| expected[a].partial_cmp(&expected[b]).unwrap());
    let (mut pooled_obs, mut pooled_exp, mut stat) = (0.0, 0.0, 0.0);
    let mut dof = 0usize;
    for &i in &idx {
        let (o, e) = (observed[i], expected[i]);
        if e == 0.0 {
            if o > samples * CHI2_EMPTY_CELL_SHARE {
                return Err(format!(
                    "{o} samples in a cell with expected count 0 (cell {i})"
                ));
            }
        } else if e < CHI2_MIN_EXPECTED || (pooled_exp > 0.0 && pooled_exp < CHI2_MIN_EXPECTED) {
            pooled_obs += o;
            pooled_exp += e;
        } else {
            stat += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pooled_exp > 0.0 || pooled_obs > 0.0 {
        stat += (pooled_obs - pooled_exp).powi(2) / pooled_exp.max(1e-300);
        dof += 1;
    }
    if dof < 2 {
        return Err(format!("too few degrees of freedom ({dof})"));
    }
    let dof = dof - 1;
    let p_value = 1.0 - gamma_p(0.5 * dof as f64, 0.5 * stat);
    Ok(Chi2 {
        statistic: stat,
        dof,
        p_value,
    })
}

/// The Šidák-corrected significance for `tests` independent tests at overall level α.
pub fn sidak(alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / tests as f64)
}

/// The number N as a float (∞ for the limit).
pub fn slits_f64(b: &GratingBsdf) -> f64 {
    b.grating().slits().as_f64()
}

/// The period proxy's documented inverse CDF and its derivative: r = tan((2ξ − 1)·atan N)/(2N)
/// and dr/dξ = atan N·(1 + 4N²r²)/N for N ≥ 2 (the Lorentzian), r = ξ − ½ and 1 for N = 1 (the
/// uniform proxy).
pub fn period_r(n: f64, xu: f64) -> (f64, f64) {
    if n == 1.0 {
        return (xu - 0.5, 1.0);
    }
    let a = n.atan();
    let r = ((2.0 * xu - 1.0) * a).tan() / (2.0 * n);
    (r, a * (1.0 + 4.0 * n * n * r * r) / n)
}

/// The period proxy's CDF ξ ∈ [0, 1] at r ∈ [−½, ½], the inverse of [`period_r`].
pub fn period_xi(n: f64, r: f64) -> f64 {
    let r = r.clamp(-0.5, 0.5);
    let xi = if n == 1.0 {
        r + 0.5
    } else {
        0.5 * ((2.0 * n * r).atan() / n.atan() + 1.0)
    };
    xi.clamp(0.0, 1.0)
}

/// The lobe-adapted coordinates of a direction for the grating sampler: the order m owning u,
/// the proxy's CDF ξ_u ∈ [0, 1] of r = x − m and the groove proxy's CDF ξ_v ∈ [0, 1] of v
/// (the documented maps [`period_r`] and v = s·tan(π(ξ − ½))).
pub fn lobe_coordinates(b: &GratingBsdf, wo: DVec3, wi: DVec3, lambda: f64) -> (i64, f64, f64) {
    let n = match b.grating().slits() {
        Slits::Finite(n) => n as f64,
        Slits::Infinite => panic!("finite N only"),
    };
    let step = lambda / b.grating().period_nm();
    let (u, v) = (wi.x + wo.x, wi.y + wo.y);
    let x = u / step;
    let m = x.round();
    let r = x - m;
    let xu = period_xi(n, r);
    let s = proxy_scale(b.groove(), lambda);
    let xv = 0.5 + (v / s).atan() / std::f64::consts::PI;
    (m as i64, xu, xv.clamp(0.0, 1.0))
}

/// The inverse of [`lobe_coordinates`] with the Jacobian |dω/dξ_u dξ_v| (None below the
/// horizon).
pub fn lobe_direction(
    b: &GratingBsdf,
    wo: DVec3,
    m: i64,
    xu: f64,
    xv: f64,
    lambda: f64,
) -> Option<(DVec3, f64)> {
    let n = slits_f64(b);
    let step = lambda / b.grating().period_nm();
    let (r, dr) = period_r(n, xu);
    let s = proxy_scale(b.groove(), lambda);
    let v = s * (std::f64::consts::PI * (xv - 0.5)).tan();
    let dv = std::f64::consts::PI * s * (1.0 + (v / s).powi(2));
    let u = (m as f64 + r) * step;
    let (x, y) = (u - wo.x, v - wo.y);
    let z2 = 1.0 - x * x - y * y;
    if z2 <= 0.0 {
        return None;
    }
    let z = z2.sqrt();
    Some((DVec3::new(x, y, z), step * dr * dv / z))
}

/// χ² of `sample` against `pdf` for a finite-N grating in lobe-adapted bins: every candidate
/// order × `bu` bins of ξ_u × `bv` bins of ξ_v. The expected count of a bin is `samples` times
/// the integral of `pdf` over it (4×4 Gauss-Legendre in (ξ_u, ξ_v) with the Jacobian, the
/// bins crossed by the disk's edge on a finer 4× grid). Returns the test and the integral of
/// the pdf over the hemisphere together with the share of samples that returned a direction.
pub fn chi2_grating(
    b: &GratingBsdf,
    wo: DVec3,
    lambda: f64,
    samples: usize,
    bu: usize,
    bv: usize,
    rng: &mut Rng,
) -> Result<(Chi2, f64, f64), String> {
    let step = lambda / b.grating().period_nm();
    let lo = ((wo.x - 1.0) / step - 0.5).floor() as i64 + 1;
    let hi = ((wo.x + 1.0) / step + 0.5).ceil() as i64 - 1;
    let orders = (hi - lo + 1) as usize;
    let cells = orders * bu * bv;
    let mut observed = vec![0.0; cells];
    let mut accepted = 0usize;
    for _ in 0..samples {
        let Some(s) = b.sample(wo, lambda, rng.next_f64(), rng.u2()) else {
            continue;
        };
        accepted += 1;
        let (m, xu, xv) = lobe_coordinates(b, wo, s.wi, lambda);
        if m < lo || m > hi {
            return Err(format!(
                "sample in order {m} outside the candidates {lo}..={hi}"
            ));
        }
        let iu = ((xu * bu as f64) as usize).min(bu - 1);
        let iv = ((xv * bv as f64) as usize).min(bv - 1);
        observed[((m - lo) as usize * bu + iu) * bv + iv] += 1.0;
    }
    // Expected counts: ∫ pdf·|dω/dξ| over each cell, with the nodes placed inside the exact
    // part of the cell that lies in the disk (for each ξ_u the inside is an interval of ξ_v,
    // and the inside's ξ_u-range is known), so the quadrature sees a smooth integrand.
    let (gx, gw) = (&quadrature::X8, &quadrature::W8);
    let n = slits_f64(b);
    let s = proxy_scale(b.groove(), lambda);
    let xi_v = |v: f64| 0.5 + (v / s).atan() / std::f64::consts::PI;
    let xi_u_of_u = |m: i64, u: f64| {
        let r = u / step - m as f64;
        period_xi(n, r)
    };
    let mut expected = vec![0.0; cells];
    let mut total = 0.0;
    for k in 0..orders {
        let m = lo + k as i64;
        // The ξ_u-range where |u − wo.x| < 1.
        let (ua, ub) = (xi_u_of_u(m, wo.x - 1.0), xi_u_of_u(m, wo.x + 1.0));
        for iu in 0..bu {
            let (c0, c1) = (iu as f64 / bu as f64, (iu + 1) as f64 / bu as f64);
            let (a0, a1) = (c0.max(ua), c1.min(ub));
            if a1 <= a0 {
                continue;
            }
            // Square-root ends at the disk's u-extremes: graded pieces in ξ_u.
            let sub = 4;
            for iv in 0..bv {
                let (d0, d1) = (iv as f64 / bv as f64, (iv + 1) as f64 / bv as f64);
                let mut acc = 0.0;
                for p in 0..sub {
                    let (p0, p1) = (
                        a0 + (a1 - a0) * p as f64 / sub as f64,
                        a0 + (a1 - a0) * (p + 1) as f64 / sub as f64,
                    );
                    for i in 0..8 {
                        let xu = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * gx[i];
                        let (r, _) = period_r(n, xu);
                        let u = (m as f64 + r) * step;
                        let h2 = 1.0 - (u - wo.x).powi(2);
                        if h2 <= 0.0 {
                            continue;
                        }
                        let h = h2.sqrt();
                        let (e0, e1) = (d0.max(xi_v(wo.y - h)), d1.min(xi_v(wo.y + h)));
                        if e1 <= e0 {
                            continue;
                        }
                        let mut inner = 0.0;
                        for j in 0..8 {
                            let xv = 0.5 * (e0 + e1) + 0.5 * (e1 - e0) * gx[j];
                            if let Some((wi, jac)) = lobe_direction(b, wo, m, xu, xv, lambda) {
                                inner += gw[j] * b.pdf(wo, wi, lambda) * jac;
                            }
                        }
                        acc += gw[i] * 0.5 * (p1 - p0) * inner * 0.5 * (e1 - e0);
                    }
                }
                expected[(k * bu + iu) * bv + iv] = acc * samples as f64;
                total += acc;
            }
        }
    }
    let test = chi2(&observed, &expected, samples as f64)?;
    Ok((test, total, accepted as f64 / samples as f64))
}

/// Mean and standard error of the furnace estimator f·cos θi/pdf over `samples` draws (a
/// `None` counts as 0); also the largest weight seen.
pub fn furnace<B: Bsdf + ?Sized>(
    b: &B,
    wo: DVec3,
    lambda: f64,
    samples: usize,
    rng: &mut Rng,
) -> (f64, f64, f64) {
    let (mut s1, mut s2, mut worst) = (0.0, 0.0, 0.0f64);
    for _ in 0..samples {
        let w = b
            .sample(wo, lambda, rng.next_f64(), rng.u2())
            .map_or(0.0, |s| s.weight());
        s1 += w;
        s2 += w * w;
        worst = worst.max(w);
    }
    let n = samples as f64;
    let mean = s1 / n;
    let var = (s2 / n - mean * mean).max(0.0);
    (mean, (var / n).sqrt(), worst)
}

/// ∫ f·cos θi dωi over the hemisphere for any model by a (θ, φ) product rule: `nt` × `np`
/// pieces of 8-point Gauss-Legendre (for smooth, moderately wide lobes only).
pub fn hemisphere_integral<B: Bsdf + ?Sized>(
    b: &B,
    wo: DVec3,
    lambda: f64,
    nt: usize,
    np: usize,
) -> f64 {
    let pi = std::f64::consts::PI;
    integrate(0.0, 0.5 * pi, nt, &|t: f64| {
        let (st, ct) = t.sin_cos();
        st * ct
            * integrate(0.0, 2.0 * pi, np, &|p: f64| {
                let wi = DVec3::new(st * p.cos(), st * p.sin(), ct);
                b.eval(wo, wi, lambda)
            })
    })
}

// ---- the amplitude grating BSDF (tests/bsdf_grating.rs) ----

/// `sample_weight_bound` for the CD-like grating: measured 6.57 (N = 1, whose uniform period
/// proxy has B_1 = 1) to 21.7 (N = 10⁶, normal incidence, 450 nm); asserted below 25.
pub const WEIGHT_BOUND_CAP: f64 = 25.0;
/// The largest f·cos θi/pdf seen in the furnace runs: measured 2.20 (N = 5, normal incidence,
/// 450 nm; 1.71 at N = 1, 1.23 at N = 10⁶); asserted below 10 (over 4× margin), far inside
/// the bound.
pub const WEIGHT_MEASURED_CAP: f64 = 10.0;

// ---- its formulas (tests/bsdf_grating.rs, `formulas`) ----

/// `eval` against the separate factors of the formula (kernel functions tested against
/// mpmath) and `eval4` against four `eval` calls: the fused, branch-free path rounds
/// differently from the product of the factors by a few ulp of each factor (measured: at
/// most 8.3·ε relative; `eval4` equals `eval` exactly); 32·ε leaves 4×.
pub const FUSED_REL: f64 = 32.0 * f64::EPSILON;
/// `pdf` against the module docs' formula P(m)·q(r)·(d/λ)·q_v(v)·cos θi with each factor
/// computed separately: a few roundings each (measured: at most 5.4·ε); 48·ε leaves 9×.
pub const PDF_REL: f64 = 48.0 * f64::EPSILON;

// ---- the groove spread (tests/bsdf_groove.rs) ----

/// Closed-form mass against 8-point Gauss-Legendre on ≥ 4000 pieces of the value: measured
/// ≤ 8·10⁻¹⁵ absolute, asserted at 10⁻¹³; for the narrowest lobe (L = 1.6 m) over wide
/// intervals the reference itself (2·10⁶ pieces) is off by 2·10⁻¹¹, so there 10⁻⁹ relative.
pub const MASS_AGREEMENT: f64 = 1e-13;
/// The same for the narrowest lobe over wide intervals, relative: the reference's own 2·10⁻¹¹
/// (2·10⁶ pieces), margin 50 for the reference's error, which is not the crate's.
pub const MASS_AGREEMENT_NARROW_REL: f64 = 1e-9;

// ---- the wavelength sampler (tests/bsdf_wavelength.rs) ----

/// Variance ratio (uniform / grating sampler) for N = 1000 at u = 0.9, D65, Y: measured
/// 3.81·10³ (see `variance_ratios`); asserted above a tenth of it.
pub const MIN_RATIO_N1000: f64 = 381.0;

// ---- closed forms and roundings of the BSDF tests (bsdf_grating, bsdf_efficiency,
// bsdf_wavelength, bsdf_groove), measured by the named tests and printed once with `--nocapture` ----

/// N = ∞ albedo against the closed form ρ²·Σ S(β_m) over the propagating orders, absolute.
/// Measured 0 (`infinite_albedo_is_the_closed_form`, 4 cases: the same sum); allowed: a few ulp.
pub const ALBEDO_CLOSED_FORM: f64 = 1e-15;
/// A furnace whose every sample has the same weight (N = ∞, ideal groove) has a standard error
/// of 0: what is left is the rounding of the mean of 20 000 equal weights. Measured 2.0e-13
/// (`infinite_albedo_is_the_closed_form`); margin 5×.
pub const FURNACE_ROUNDING: f64 = 1e-12;
/// | |wi| − 1 | of sampled directions. Measured 1.1e-16 (`samples_agree_with_f_and_pdf`, 14 181
/// samples); margin 9×.
pub const SAMPLED_UNIT_LENGTH: f64 = 1e-15;
/// ∫pdf over the χ² bins against the share of draws that sample, beyond 3 standard errors: the
/// allowance for the test's own quadrature of the pdf over the bins, not separated from the
/// sampling noise (largest |∫pdf − share| measured 2.1·10⁻³ at a standard error of 1.5·10⁻³,
/// `chi2_in_lobe_adapted_bins`, `chi2_of_the_sampler`, `chi2_and_integral_of_the_wavelength_sampler`);
/// a fifteenth of one standard error.
pub const PDF_INTEGRAL_QUADRATURE: f64 = 1e-4;
/// ∫pdf ≤ 1: measured at most 1 − 5.0·10⁻³ (`chi2_in_lobe_adapted_bins`, 24 cases); the
/// allowance is the rounding of the quadrature only.
pub const PDF_INTEGRAL_ABOVE_ONE: f64 = 1e-9;
/// A delta lobe's direction against the grating equation wi.x = m·λ/d − wo.x, absolute.
/// Measured 0 (`infinite_and_ideal_lobes_are_specular`); allowed: a few ulp of values ≤ 1.
pub const DELTA_DIRECTION: f64 = 1e-15;
/// A groove spread's mean × width against its mass, absolute. Measured 1.1e-16
/// (`mass_is_the_integral_of_the_value`, 12 intervals); margin 9×.
pub const MEAN_TIMES_WIDTH: f64 = 1e-15;
/// The groove proxy's inverse CDF and CDF round trip, absolute. Measured 1.1e-16
/// (`proxy_bound_holds_and_the_proxy_is_a_density`, 297 values); margin 9×.
pub const PROXY_ROUND_TRIP: f64 = 1e-15;

/// The Monte-Carlo variance of the wavelength sampler's estimate (200 000 draws, fixed seed)
/// against the variance by quadrature, relative. Measured 8.1e-4
/// (`grating_wavelengths_beat_uniform_ones`); margin 6×.
pub const MC_VARIANCE: f64 = 5e-3;
/// How far below its stated supremum the groove proxy's largest value/pdf ratio on a grid of
/// 200 000 points may fall, relative: the bound is tight. Measured 3.5e-5
/// (`proxy_bound_holds_and_the_proxy_is_a_density`); margin 5.7×.
pub const PROXY_BOUND_TIGHT: f64 = 2e-4;
