//! The tests' own Gauss-Legendre nodes and weights (the roots of P_n and 2/((1 − x²)·P_n'(x)²),
//! written out here rather than taken from the crate, so that a test reference does not share
//! the code it checks), and a composite rule on them.
#![allow(dead_code)]

/// 4 points: nodes on [−1, 1] and weights.
pub const X4: [f64; 4] = [
    -0.861_136_311_594_052_6,
    -0.339_981_043_584_856_3,
    0.339_981_043_584_856_3,
    0.861_136_311_594_052_6,
];
/// See [`X4`].
pub const W4: [f64; 4] = [
    0.347_854_845_137_453_8,
    0.652_145_154_862_546_2,
    0.652_145_154_862_546_2,
    0.347_854_845_137_453_8,
];
/// 8 points: nodes on [−1, 1] and weights.
pub const X8: [f64; 8] = [
    -0.960_289_856_497_536_3,
    -0.796_666_477_413_626_7,
    -0.525_532_409_916_329,
    -0.183_434_642_495_649_8,
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
/// See [`X8`].
pub const W8: [f64; 8] = [
    0.101_228_536_290_376_3,
    0.222_381_034_453_374_5,
    0.313_706_645_877_887_3,
    0.362_683_783_378_362,
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// ∫_a^b f by `pieces` equal pieces of 8-point Gauss-Legendre.
pub fn integrate(a: f64, b: f64, pieces: usize, f: &dyn Fn(f64) -> f64) -> f64 {
    let h = (b - a) / pieces as f64;
    let mut s = 0.0;
    for p in 0..pieces {
        let c = a + (p as f64 + 0.5) * h;
        for i in 0..8 {
            s += W8[i] * f(c + 0.5 * h * X8[i]);
        }
    }
    s * 0.5 * h
}
