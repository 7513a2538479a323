//! The tests' one random generator (SplitMix64): the same sequence on every machine for a given
//! seed. Included by `#[path]` (tests, benches, the accuracy report); not every includer uses
//! every method.
#![allow(dead_code)]

use glam::{DVec2, DVec3};

/// SplitMix64 (Steele, Lea & Flood 2014).
#[derive(Debug, Clone)]
pub struct Rng(pub u64);

impl Rng {
    /// A generator whose state is `seed` mixed (so that small consecutive seeds give unrelated
    /// sequences).
    pub fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// The next number in [0, 1), on the 2⁻⁵³ grid.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Two numbers in [0, 1).
    pub fn u2(&mut self) -> DVec2 {
        DVec2::new(self.next_f64(), self.next_f64())
    }

    /// A unit direction in the upper hemisphere with z ≥ `z_min`, uniform in z and azimuth.
    pub fn direction(&mut self, z_min: f64) -> DVec3 {
        let z = z_min + (1.0 - z_min) * self.next_f64();
        let phi = std::f64::consts::TAU * self.next_f64();
        let s = (1.0 - z * z).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }
}
