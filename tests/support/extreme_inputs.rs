//! The pools of extreme inputs and the strategies at the ends of their ranges, shared by
//! `tests/extremes.rs` (the sweep) and `tests/strategy_limits.rs` (which include `support/rng.rs`
//! as `rng` beside it), and the sweep's generator of them.

#![allow(dead_code)]

use diffraction::spectrum::{GenericStrategy, Strategy};
use glam::DVec3;

/// Finite values at and near every boundary the public functions have (zeros, subnormals,
/// the band's edges, grazing u, the largest finite values).
pub const EXTREMES: &[f64] = &[
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    1e-310,
    f64::MIN_POSITIVE,
    1e-300,
    1e-23,
    1e-12,
    1e-9,
    1e-6,
    0.3,
    0.5,
    1.0,
    -1.0,
    1.999,
    2.0,
    -2.0,
    360.0,
    550.0,
    830.0,
    1600.0,
    1e6,
    1e9,
    1.7824e12,
    1e12,
    1e19,
    1e300,
    -1e300,
    f64::MAX,
    -f64::MAX,
];

/// Counts at the edges of every count-taking constructor (0 is refused, u32::MAX capped).
pub const COUNTS: &[u32] = &[0, 1, 2, 3, 7, 1000, 1_000_000, 10_000_000, u32::MAX];

/// Every grating strategy at the ends of its accepted range.
pub fn strategies() -> Vec<Strategy> {
    vec![
        Strategy::uniform(1).unwrap(),
        Strategy::uniform(7).unwrap(),
        Strategy::uniform(diffraction::spectrum::MAX_WAVELENGTHS).unwrap(),
        Strategy::gauss_legendre(1).unwrap(),
        Strategy::gauss_legendre(16).unwrap(),
        Strategy::gauss_legendre(diffraction::spectrum::MAX_WAVELENGTHS / 8).unwrap(),
        Strategy::PEAK_SEARCH,
        Strategy::PEAK_SEARCH_REFINED,
        Strategy::ASYMPTOTIC,
        Strategy::EXACT,
        Strategy::auto(1e-3).unwrap(),
        Strategy::auto(diffraction::spectrum::MIN_ACCURACY).unwrap(),
        Strategy::auto(diffraction::spectrum::MAX_ACCURACY).unwrap(),
    ]
}

/// Every generic rule at the ends of its accepted range.
pub fn generic_strategies() -> Vec<GenericStrategy> {
    vec![
        GenericStrategy::uniform(1).unwrap(),
        GenericStrategy::uniform(diffraction::spectrum::MAX_WAVELENGTHS).unwrap(),
        GenericStrategy::gauss_legendre(16).unwrap(),
        GenericStrategy::gauss_legendre(diffraction::spectrum::MAX_WAVELENGTHS / 8).unwrap(),
        GenericStrategy::PEAK_SEARCH,
        GenericStrategy::WINDOWS,
        GenericStrategy::auto(1e-3).unwrap(),
        GenericStrategy::auto(diffraction::spectrum::MIN_ACCURACY).unwrap(),
    ]
}

/// Inputs drawn from the tests' seeded generator, so that every run tries the same ones.
pub struct Rng(pub super::rng::Rng);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    pub fn pick<T: Copy>(&mut self, pool: &[T]) -> T {
        pool[(self.next() % pool.len() as u64) as usize]
    }
    /// A value from the pool of extremes, or (one time in four) a log-uniform one in
    /// [1e-320, 1e308] with a random sign.
    pub fn real(&mut self) -> f64 {
        if self.next() % 4 == 0 {
            let e = -320.0 + 628.0 * (self.next() as f64 / u64::MAX as f64);
            let v = 10f64.powf(e);
            if self.next() % 2 == 0 {
                v
            } else {
                -v
            }
        } else {
            self.pick(EXTREMES)
        }
    }
    pub fn positive(&mut self) -> f64 {
        self.real().abs()
    }
    pub fn direction(&mut self) -> DVec3 {
        // Mostly unit directions, sometimes wild ones.
        if self.next() % 3 == 0 {
            DVec3::new(self.real(), self.real(), self.real())
        } else {
            let (a, b) = (
                self.next() as f64 / u64::MAX as f64,
                self.next() as f64 / u64::MAX as f64,
            );
            let (z, phi) = (a, std::f64::consts::TAU * b);
            let r = (1.0 - z * z).max(0.0).sqrt();
            DVec3::new(r * phi.cos(), r * phi.sin(), z)
        }
    }
}
