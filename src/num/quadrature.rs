//! Gauss-Legendre rules, the crate's one set of quadrature nodes: 2, 3, 4, 6 and 8 points on
//! [−1, 1], correctly rounded (mpmath, 40 digits: the roots of P_n and 2/((1 − x²)·P_n'(x)²)),
//! applied to integrands with values in `f64` or in `DVec3` (XYZ).

use core::ops::{Add, Mul};

use glam::DVec3;

/// What a rule can integrate: values that add and scale (`f64`, `DVec3`).
pub(crate) trait Value: Copy + Add<Output = Self> + Mul<f64, Output = Self> {
    /// The additive identity.
    const ZERO: Self;
}

impl Value for f64 {
    const ZERO: f64 = 0.0;
}

impl Value for DVec3 {
    const ZERO: DVec3 = DVec3::ZERO;
}

/// A Gauss-Legendre rule: nodes and weights on [−1, 1], symmetric.
pub(crate) struct Rule<const K: usize> {
    pub nodes: [f64; K],
    pub weights: [f64; K],
}

/// 2 points: ±1/√3, weights 1.
pub(crate) const GL2: Rule<2> = Rule {
    nodes: [-0.5773502691896257, 0.5773502691896257],
    weights: [1.0, 1.0],
};

/// 3 points: 0, ±√(3/5); weights 8/9, 5/9.
pub(crate) const GL3: Rule<3> = Rule {
    nodes: [-0.7745966692414834, 0.0, 0.7745966692414834],
    weights: [0.5555555555555556, 0.8888888888888888, 0.5555555555555556],
};

/// 4 points.
pub(crate) const GL4: Rule<4> = Rule {
    nodes: [
        -0.8611363115940526,
        -0.33998104358485626,
        0.33998104358485626,
        0.8611363115940526,
    ],
    weights: [
        0.34785484513745385,
        0.6521451548625461,
        0.6521451548625461,
        0.34785484513745385,
    ],
};

/// 6 points.
pub(crate) const GL6: Rule<6> = Rule {
    nodes: [
        -0.932469514203152,
        -0.6612093864662645,
        -0.2386191860831969,
        0.2386191860831969,
        0.6612093864662645,
        0.932469514203152,
    ],
    weights: [
        0.17132449237917036,
        0.3607615730481386,
        0.46791393457269104,
        0.46791393457269104,
        0.3607615730481386,
        0.17132449237917036,
    ],
};

/// 8 points.
pub(crate) const GL8: Rule<8> = Rule {
    nodes: [
        -0.9602898564975363,
        -0.7966664774136267,
        -0.525532409916329,
        -0.1834346424956498,
        0.1834346424956498,
        0.525532409916329,
        0.7966664774136267,
        0.9602898564975363,
    ],
    weights: [
        0.10122853629037626,
        0.22238103445337448,
        0.31370664587788727,
        0.362683783378362,
        0.362683783378362,
        0.31370664587788727,
        0.22238103445337448,
        0.10122853629037626,
    ],
};

impl<const K: usize> Rule<K> {
    /// ∫_a^b f by the rule mapped onto [a, b] (b < a gives the negative).
    #[inline]
    pub(crate) fn integrate<T: Value>(&self, a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let mut s = T::ZERO;
        for k in 0..K {
            s = s + f(mid + half * self.nodes[k]) * self.weights[k];
        }
        s * half
    }
}

/// 8-point Gauss-Legendre over [a, b].
#[inline]
pub(crate) fn gl8<T: Value>(a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
    GL8.integrate(a, b, f)
}

/// 6-point Gauss-Legendre over [a, b].
#[inline]
pub(crate) fn gl6<T: Value>(a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
    GL6.integrate(a, b, f)
}

/// 4-point Gauss-Legendre over [a, b].
#[inline]
pub(crate) fn gl4<T: Value>(a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
    GL4.integrate(a, b, f)
}

/// 3-point Gauss-Legendre over [a, b].
#[inline]
pub(crate) fn gl3<T: Value>(a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
    GL3.integrate(a, b, f)
}

/// 2-point Gauss-Legendre over [a, b].
#[inline]
pub(crate) fn gl2<T: Value>(a: f64, b: f64, f: &dyn Fn(f64) -> T) -> T {
    GL2.integrate(a, b, f)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rule integrates the monomials up to its degree 2K − 1 exactly (to rounding), and its
    /// weights sum to 2: the identities that define it.
    #[test]
    fn rules_are_exact_to_their_degree() {
        fn check<const K: usize>(r: &Rule<K>) {
            let sum: f64 = r.weights.iter().sum();
            assert!((sum - 2.0).abs() < 4.0 * f64::EPSILON, "{K}: {sum}");
            for p in 0..2 * K as i32 {
                let got = r.integrate(0.0, 1.0, &|x: f64| x.powi(p));
                let want = 1.0 / (p as f64 + 1.0);
                assert!(
                    (got - want).abs() < 8.0 * f64::EPSILON,
                    "{K} x^{p}: {got} {want}"
                );
            }
        }
        check(&GL2);
        check(&GL3);
        check(&GL4);
        check(&GL6);
        check(&GL8);
    }
}
