//! The inputs of the WGSL kernel checks (tests/gpu_wgsl.rs and gpu-tests/tests/device.rs):
//! a small deterministic generator and the stiff phases.
#![allow(dead_code)]

/// SplitMix64, uniform in [0, 1).
pub struct Mix(pub u64);
impl Mix {
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The next f32 after finite `v`, up or down (`f32::next_up` is newer than the crate's
/// rust-version).
fn next(v: f32, up: bool) -> f32 {
    if v == 0.0 {
        let tiny = f32::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    let b = v.to_bits();
    // Away from zero the magnitude, and so the bits, grow.
    f32::from_bits(if (v > 0.0) == up { b + 1 } else { b - 1 })
}

/// `v` moved by `k` f32 ulps (up for k > 0).
pub fn ulps(v: f32, k: i32) -> f32 {
    let mut v = v;
    for _ in 0..k.abs() {
        v = next(v, k > 0);
    }
    v
}

/// The stiff phases for N slits: integers up to 10⁴ (log scale, both signs) and their f32
/// neighbours, the zeros m + k/N, uniform phases around m, and tiny phases down to 10⁻¹².
pub fn stiff_phases(n: u32, count: usize, rng: &mut Mix) -> Vec<f32> {
    let mut xs = Vec::with_capacity(count);
    while xs.len() < count {
        let sign = if rng.next() < 0.5 { -1.0 } else { 1.0 };
        let m = (10f64.powf(4.0 * rng.next())).floor() * sign;
        let x = match xs.len() % 5 {
            0 => m as f32,
            1 => ulps(m as f32, 1 + (rng.next() * 4.0) as i32),
            2 => (m + (1.0 + (rng.next() * 8.0).floor()) / n.max(1) as f64) as f32,
            3 => (m + (rng.next() - 0.5)) as f32,
            _ => (10f64.powf(-12.0 * rng.next()) * (rng.next() - 0.5)) as f32,
        };
        xs.push(x);
    }
    xs
}

/// The slit counts of the checks.
pub const SLITS: [u32; 8] = [1, 2, 3, 10, 1000, 5000, 1_000_000, 10_000_000];
