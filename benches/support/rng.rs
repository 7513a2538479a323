//! A small deterministic generator (SplitMix64) for the benches' and the accuracy report's fixed
//! inputs. Shared by `#[path]` inclusion; not a bench target itself.

use glam::DVec3;

/// SplitMix64: numbers in [0, 1), the same sequence on every machine for a given seed.
pub struct Rng(pub u64);

impl Rng {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A unit direction in the upper hemisphere with z ≥ `z_min`.
    #[allow(dead_code)] // not every includer draws directions
    pub fn direction(&mut self, z_min: f64) -> DVec3 {
        let z = z_min + (1.0 - z_min) * self.next();
        let phi = std::f64::consts::TAU * self.next();
        let s = (1.0 - z * z).sqrt();
        DVec3::new(s * phi.cos(), s * phi.sin(), z)
    }
}
