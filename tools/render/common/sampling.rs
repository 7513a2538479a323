//! Random numbers and the one stratification of every integrator: camera samples over a pixel
//! and light samples over a disc or a cone.

use glam::DVec2;

/// A small deterministic hash (SplitMix64's finaliser).
pub fn hash64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A uniform number in [0, 1) from a hash.
pub fn hash_unit(z: u64) -> f64 {
    (hash64(z) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// A small deterministic generator (SplitMix64), seeded per pixel so that the picture does not
/// depend on how rayon splits the work.
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator seeded with (a hash of) `seed`.
    pub fn new(seed: u64) -> Rng {
        Rng(hash64(seed))
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        hash64(self.0)
    }

    /// A uniform number in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// An integer in [0, n), n ≥ 1, by the high half of a 64 × 64-bit product (Lemire's method
    /// without the rejection step: the bias is below n / 2⁶⁴, under 10⁻¹⁵ for the counts here).
    pub fn below(&mut self, n: u32) -> u32 {
        ((self.next_u64() as u128 * n as u128) >> 64) as u32
    }
}

/// Largest number of samples in one [`Strata`] set (larger counts are taken as this): the
/// limits on samples per pixel and light samples are at most this.
pub const MAX_STRATA_SAMPLES: u32 = 4096;

/// Largest number of cells a [`Strata`] grid leaves empty: a grid of cols = ⌈√n⌉ columns and
/// rows = ⌈n / cols⌉ rows has fewer than cols cells over n, and cols ≤ 64 for n ≤
/// [`MAX_STRATA_SAMPLES`].
const MAX_EMPTY_CELLS: usize = 64;

/// `n` stratified samples of the unit square for any n ≥ 1: a grid of cols = ⌈√n⌉ by
/// rows = ⌈n / cols⌉ cells (cols·rows ≥ n, fewer than cols cells too many), one jittered sample
/// in each of n distinct cells. When the grid has more cells than samples, the cells left empty
/// are a uniformly random subset (Floyd's algorithm) drawn afresh for every set, so every cell
/// is sampled with the same probability n / (cols·rows) and every sample is uniform over the
/// square: the estimate is unbiased and no part of the domain is ever skipped (the first n
/// cells of the grid, the old rule, never sampled a quarter of a pixel at 3 samples, nor a
/// ninth of a light at 8). When n is a square or the grid is full (cols·rows = n) no cell is
/// left out and nothing extra is drawn.
#[derive(Debug, Clone)]
pub struct Strata {
    cols: u32,
    rows: u32,
    /// The cells left empty, sorted.
    empty: [u32; MAX_EMPTY_CELLS],
    n_empty: usize,
    /// The next cell to visit and the next empty cell to skip.
    cell: u32,
    skip: usize,
    left: u32,
}

impl Strata {
    /// The grid for `n` samples (0 is taken as 1, more than [`MAX_STRATA_SAMPLES`] as that),
    /// its empty cells drawn from `rng`.
    pub fn new(n: u32, rng: &mut Rng) -> Strata {
        let n = n.clamp(1, MAX_STRATA_SAMPLES);
        let cols = (n as f64).sqrt().ceil() as u32;
        let rows = n.div_ceil(cols);
        let cells = cols * rows;
        let n_empty = (cells - n) as usize; // < cols ≤ MAX_EMPTY_CELLS
        let mut empty = [0u32; MAX_EMPTY_CELLS];
        // Floyd's algorithm: a uniformly random n_empty-subset of 0..cells.
        for (k, j) in (cells - n_empty as u32..cells).enumerate() {
            let t = rng.below(j + 1);
            empty[k] = if empty[..k].contains(&t) { j } else { t };
        }
        empty[..n_empty].sort_unstable();
        Strata {
            cols,
            rows,
            empty,
            n_empty,
            cell: 0,
            skip: 0,
            left: n,
        }
    }

    /// The grid's columns and rows.
    pub fn grid(&self) -> (u32, u32) {
        (self.cols, self.rows)
    }

    /// The cell (column, row) of the next sample; the caller jitters inside it, at
    /// ((column + ξ₁) / cols, (row + ξ₂) / rows), or calls [`Strata::next_sample`].
    pub fn next_cell(&mut self) -> Option<(u32, u32)> {
        if self.left == 0 {
            return None;
        }
        while self.skip < self.n_empty && self.empty[self.skip] == self.cell {
            self.skip += 1;
            self.cell += 1;
        }
        let cell = (self.cell % self.cols, self.cell / self.cols);
        self.cell += 1;
        self.left -= 1;
        Some(cell)
    }

    /// The next sample's cell and the sample jittered in it, ξ₁ drawn for x first: a point of
    /// the unit square.
    pub fn next_sample(&mut self, rng: &mut Rng) -> Option<((u32, u32), DVec2)> {
        let (cx, cy) = self.next_cell()?;
        let x = (cx as f64 + rng.next_f64()) / self.cols as f64;
        let y = (cy as f64 + rng.next_f64()) / self.rows as f64;
        Some(((cx, cy), DVec2::new(x, y)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every cell of the stratification grid is reached, for every count, with the same
    /// probability n / (cols·rows): no part of the pixel or of a disc light is skipped (the
    /// first-n cells of a ⌈√n⌉ grid used to leave the last cells empty, e.g. one sector of the
    /// outer ring of a disc light for the default 8 shadow samples).
    #[test]
    fn strata_reach_every_cell_with_equal_probability() {
        /// Sets drawn per count.
        const TRIALS: u32 = 4000;
        /// Allowed deviation of a cell's count from its binomial mean, in standard deviations:
        /// over the ~35000 cells checked, a fair sampler exceeds 5.5σ with probability ~1e-3.
        const SIGMAS: f64 = 5.5;
        let mut rng = Rng::new(11);
        for n in (1..=100).chain([255, 1000, 4095, MAX_STRATA_SAMPLES]) {
            let (cols, rows) = Strata::new(n, &mut rng).grid();
            let cells = (cols * rows) as usize;
            assert!(
                cells >= n as usize && cells - (n as usize) < cols as usize,
                "{n}"
            );
            let trials = if n > 100 { 200 } else { TRIALS };
            let mut counts = vec![0u32; cells];
            for _ in 0..trials {
                let mut strata = Strata::new(n, &mut rng);
                let mut seen = vec![false; cells];
                let mut k = 0;
                while let Some((cx, cy)) = strata.next_cell() {
                    assert!(cx < cols && cy < rows, "{n}: cell ({cx}, {cy})");
                    let c = (cy * cols + cx) as usize;
                    assert!(!seen[c], "{n}: cell ({cx}, {cy}) twice in one set");
                    seen[c] = true;
                    counts[c] += 1;
                    k += 1;
                }
                assert_eq!(k, n, "{n} samples");
            }
            let p = n as f64 / cells as f64;
            let (mean, sd) = (trials as f64 * p, (trials as f64 * p * (1.0 - p)).sqrt());
            for (c, &k) in counts.iter().enumerate() {
                assert!(k > 0, "{n}: cell {c} never sampled");
                assert!(
                    (k as f64 - mean).abs() <= SIGMAS * sd.max(0.5),
                    "{n}: cell {c} sampled {k} times, expected {mean} ± {sd}"
                );
            }
        }
        // The default 8 shadow samples: a 3 × 3 grid; the last cell (column 2, row 2) is among
        // the reached cells.
        let mut rng = Rng::new(3);
        let reached = (0..100).any(|_| {
            let mut s = Strata::new(8, &mut rng);
            std::iter::from_fn(|| s.next_cell()).any(|c| c == (2, 2))
        });
        assert!(reached);
    }

    /// The jittered points of a set lie in their cells: at 3 samples (a 2 × 2 grid, one cell
    /// left out at random) every quarter of the square is sampled over a few sets, and the
    /// mean of the points is the centre (an unbiased estimate of ∫x = ½).
    #[test]
    fn points_cover_every_quarter_at_three_samples() {
        /// Sets drawn; the mean of 3·SETS uniform points has a standard deviation of
        /// 1/√(12·3·SETS) ≈ 0.0029, and the bound is 4 of them.
        const SETS: usize = 3000;
        const MEAN_TOLERANCE: f64 = 0.012;
        let mut rng = Rng::new(5);
        let mut quarters = [0u32; 4];
        let mut sum = DVec2::ZERO;
        for _ in 0..SETS {
            let mut s = Strata::new(3, &mut rng);
            while let Some((_, p)) = s.next_sample(&mut rng) {
                assert!(
                    (0.0..1.0).contains(&p.x) && (0.0..1.0).contains(&p.y),
                    "{p}"
                );
                quarters[(p.x >= 0.5) as usize + 2 * (p.y >= 0.5) as usize] += 1;
                sum += p;
            }
        }
        assert!(quarters.iter().all(|&q| q > 0), "{quarters:?}");
        let mean = sum / (3 * SETS) as f64;
        assert!(
            (mean - DVec2::splat(0.5)).abs().max_element() < MEAN_TOLERANCE,
            "{mean}"
        );
    }
}
