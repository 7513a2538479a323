//! A small deterministic generator (SplitMix64), and the one-wavelength inputs built from it, for
//! the benches' and the accuracy report's fixed inputs. Shared by `#[path]` inclusion; not a bench target itself.

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

/// One-wavelength inputs (wi, wo, λ) for a grating of period `period` nm and `n` slits, every
/// other one within a few lobes of a peak of order 1-4; the same for a given (period, n).
#[allow(dead_code)] // not every includer evaluates single wavelengths
pub fn near_peak_samples(period: f64, n: u32, count: usize) -> Vec<(DVec3, DVec3, f64)> {
    let mut rng = Rng(0xB4D5 ^ u64::from(n) ^ ((period as u64) << 20));
    let mut v = Vec::with_capacity(count);
    while v.len() < count {
        let wi = rng.direction(0.05);
        let lambda = 360.0 + 470.0 * rng.next();
        let mut wo = rng.direction(0.05);
        if v.len() % 2 == 0 {
            // u = m·λ/d plus a few lobes λ/(N·d).
            let m = 1.0 + (rng.next() * 4.0).floor();
            let off = (rng.next() - 0.5) * 8.0 / f64::from(n);
            let x = (m + off) * lambda / period - wi.x;
            let y = 0.3 * (rng.next() - 0.5);
            let z2 = 1.0 - x * x - y * y;
            if z2 <= 0.0025 {
                continue;
            }
            wo = DVec3::new(x, y, z2.sqrt());
        }
        v.push((wi, wo, lambda));
    }
    v
}
