//! The Fresnel reflectances of a flat absorbing medium n + ik lit from air.

use crate::num::complex::Complex;

/// (R_s, R_p) for index n + ik (n > 0, k ≥ 0) at cos θ = `cos_theta` (clamped to [0, 1], NaN
/// as 0): see [`Metal::reflectance`](super::Metal::reflectance).
///
/// Both are |a|²/|b|², a = x − w and b = x + w with x = cos θ (s) or N²·cos θ (p); for a passive
/// medium |a| ≤ |b| (the quotient is clamped to 1 against rounding), and b = 0 only for N = 1 at
/// grazing incidence (no interface), where 0 is returned.
pub(crate) fn reflectances(n: f64, k: f64, cos_theta: f64) -> (f64, f64) {
    let c = if cos_theta >= 0.0 {
        cos_theta.min(1.0)
    } else {
        0.0
    };
    let eps = Complex::new((n - k) * (n + k), 2.0 * n * k); // N²
                                                            // sin²θ = (1 − c)(1 + c): exact near grazing incidence.
    let sin2 = (1.0 - c) * (1.0 + c);
    let w = (eps - Complex::new(sin2, 0.0)).sqrt();
    let cc = Complex::new(c, 0.0);
    let rs = ratio((cc - w).norm_sqr(), (cc + w).norm_sqr());
    let ec = eps.scale(c);
    let rp = ratio((ec - w).norm_sqr(), (ec + w).norm_sqr());
    (rs, rp)
}

/// a/b clamped to [0, 1], 0 where b = 0.
fn ratio(a: f64, b: f64) -> f64 {
    if b > 0.0 {
        (a / b).min(1.0)
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::reflectances;

    #[test]
    fn normal_incidence_is_the_textbook_formula() {
        for &(n, k) in &[(1.0152, 6.6273), (0.05, 3.5), (1.5, 0.0), (3.0, 3.0)] {
            let (rs, rp) = reflectances(n, k, 1.0);
            let r = ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
            assert!((rs - r).abs() < 1e-15 && (rp - r).abs() < 1e-15);
        }
    }

    #[test]
    fn grazing_and_degenerate_inputs_stay_in_range() {
        assert_eq!(reflectances(1.0152, 6.6273, 0.0), (1.0, 1.0));
        assert_eq!(reflectances(1.0152, 6.6273, f64::NAN), (1.0, 1.0));
        assert_eq!(reflectances(1.0, 0.0, 0.0), (0.0, 0.0)); // no interface
        assert_eq!(reflectances(1.0, 0.0, 0.5), (0.0, 0.0));
        // Total internal reflection of a medium with n < 1 beyond its critical angle.
        let (rs, rp) = reflectances(0.5, 0.0, 0.5);
        assert!((rs - 1.0).abs() < 1e-15 && (rp - 1.0).abs() < 1e-15);
        for i in 0..=1000 {
            let c = f64::from(i) / 1000.0;
            let (rs, rp) = reflectances(0.3, 4.0, c);
            assert!((0.0..=1.0).contains(&rs) && (0.0..=1.0).contains(&rp));
            assert!(rp <= rs + 1e-15, "R_p ≤ R_s for an absorbing medium");
        }
    }
}
