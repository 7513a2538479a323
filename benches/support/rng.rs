//! The tests' deterministic generator (SplitMix64, `tests/support/rng.rs`) and the one-wavelength
//! inputs built from it, for the benches' and the accuracy report's fixed inputs. Shared by
//! `#[path]` inclusion; not a bench target itself.

use glam::DVec3;

#[path = "../../tests/support/rng.rs"]
mod generator;
pub use generator::Rng;

/// One-wavelength inputs (wi, wo, λ) for a grating of period `period` nm and `n` slits, every
/// other one within a few lobes of a peak of order 1-4; the same for a given (period, n).
#[allow(dead_code)] // not every includer evaluates single wavelengths
pub fn near_peak_samples(period: f64, n: u32, count: usize) -> Vec<(DVec3, DVec3, f64)> {
    let mut rng = Rng(0xB4D5 ^ u64::from(n) ^ ((period as u64) << 20));
    let mut v = Vec::with_capacity(count);
    while v.len() < count {
        let wi = rng.direction(0.05);
        let lambda = 360.0 + 470.0 * rng.next_f64();
        let mut wo = rng.direction(0.05);
        if v.len() % 2 == 0 {
            // u = m·λ/d plus a few lobes λ/(N·d).
            let m = 1.0 + (rng.next_f64() * 4.0).floor();
            let off = (rng.next_f64() - 0.5) * 8.0 / f64::from(n);
            let x = (m + off) * lambda / period - wi.x;
            let y = 0.3 * (rng.next_f64() - 0.5);
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
