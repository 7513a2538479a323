//! The colour tables' GPU interpolants in f64 from their f32 data, and the bounds of their
//! lookups against the CPU's (docs/gpu.md), for the device tests of the lookups (`device.rs`).

use diffraction::gpu::GpuColorTable;

use super::gpu_tolerance::{TABLE_ROUNDINGS, U};

/// Per channel, the sum of the magnitudes of the cell's four Hermite terms at u and twice the
/// cell's largest slope (the scales of the lookup's rounding, see TABLE_ROUNDINGS), in grid 0.
pub fn cell_scale(t: &GpuColorTable, u: f32) -> ([f64; 3], [f64; 3]) {
    let (_, m, dm) = cell(t, 0, u.abs().min(2.0));
    (m, dm)
}

/// Grid g's interpolant at a ∈ [0, 2] in f64 from its f32 nodes, and the rounding scales of
/// `cell_scale`.
pub fn cell(t: &GpuColorTable, g: usize, a: f32) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let k = if a >= t.header.u_lo {
        ((a.to_bits() >> 20) - t.header.base_key + 1) as usize
    } else {
        0
    };
    let count = t.header.block_count as usize;
    let b = t.blocks[g * count + k.min(count - 1)];
    let s_all = ((a - b.u0) * b.inv_h) as f64;
    let j = (s_all as u32).min(b.n - 1);
    let s = s_all - j as f64;
    let (p, q) = (
        t.nodes[(b.first + j) as usize],
        t.nodes[(b.first + j + 1) as usize],
    );
    let h = b.h as f64;
    let (s2, s3) = (s * s, s * s * s);
    let w = [
        2.0 * s3 - 3.0 * s2 + 1.0,
        (s3 - 2.0 * s2 + s) * h,
        3.0 * s2 - 2.0 * s3,
        (s3 - s2) * h,
    ];
    let (mut v, mut m, mut dm) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for c in 0..3 {
        let (fp, dp, fq, dq) = (p.f[c] as f64, p.d[c] as f64, q.f[c] as f64, q.d[c] as f64);
        v[c] = (w[0] * fp + w[1] * dp + w[2] * fq + w[3] * dq).max(0.0);
        m[c] = w[0].abs() * fp.abs()
            + w[1].abs() * dp.abs()
            + w[2].abs() * fq.abs()
            + w[3].abs() * dq.abs();
        dm[c] = 2.0 * dp.abs().max(dq.abs()).max(((fq - fp) / h).abs());
    }
    (v, m, dm)
}

/// σ of the incidence s at u (the CPU's place between the grazing directions, in f64).
pub fn sigma_of(tau: f64) -> f64 {
    let (a, b) = (
        tau.clamp(0.0, 1.0).sqrt(),
        (1.0 - tau.clamp(0.0, 1.0)).sqrt(),
    );
    a / (a + b)
}

/// Per channel, the bound of one plane's colour on the GPU against the CPU's (the lookup bound
/// of each Hermite cell it may read plus the colour's slope in σ times σ's rounding `dsigma`,
/// over the neighbouring incidence nodes, since a σ near a node may fall in the next interval),
/// and the largest of those cells' values (a bound on the plane's colour). The plane's words
/// start at `at` of the incidence and its node k's grids at `first + 2k` (u ≥ 0, `pos`) and
/// `first + 2k + 1`; `a` is |u|.
pub fn plane_bound(
    t: &GpuColorTable,
    (at, first): (usize, usize),
    a: f32,
    pos: bool,
    sigma: f64,
    dsigma: f64,
) -> [(f64, f64); 3] {
    let words = &t.incidence;
    let (k, bins) = (words[at] as usize, words[at + 1] as usize);
    let inv_next = |j: usize| f32::from_bits(words[at + 3 + bins + 2 * j]) as f64;
    let i = ((sigma * bins as f64) as usize).min(bins - 1);
    let i = words[at + 2 + i] as usize;
    let side = if pos { 0 } else { 1 };
    let (lo, hi) = (i.saturating_sub(1), (i + 2).min(k - 1));
    let cells: Vec<_> = (lo..=hi)
        .map(|j| cell(t, first + side + 2 * j, a))
        .collect();
    let mut out = [(0.0, 0.0); 3];
    for (ch, o) in out.iter_mut().enumerate() {
        let (mut grid_tol, mut slope, mut most) = (0.0f64, 0.0f64, 0.0f64);
        for (jj, j) in (lo..=hi).enumerate() {
            let (v, m, dm) = cells[jj];
            grid_tol =
                grid_tol.max(TABLE_ROUNDINGS * U * m[ch] + 2.0 * U * a as f64 * dm[ch] + U * v[ch]);
            most = most.max(v[ch]);
            if j < hi {
                slope = slope.max((cells[jj + 1].0[ch] - v[ch]).abs() * inv_next(j));
            }
        }
        *o = (grid_tol + slope * (dsigma + 4.0 * U), most);
    }
    out
}
