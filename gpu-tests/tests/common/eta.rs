//! The error bounds of the packed tables' readings in WGSL (`TABULATED_WGSL`; docs/gpu.md,
//! "Tabulated efficiencies"): the query's cell recomputed in f64 from the packed words (a
//! classical table's four corners, a conical table's eight), each corner's weight with
//! the bound of its f32 error, and from them the bounds of the interpolated efficiency
//! ([`eta_bound`]) and of the sampler's order proposal ([`weights`]).

use diffraction::glam::DVec3;
use diffraction::gpu::EFFICIENCY_HEADER_WORDS;
use diffraction::grating_bsdf::TABULATED_DEFENSIVE_SHARE;

use super::gpu_tolerance::U;

/// One query's cell as the WGSL forms it, in f64, with the bounds of its f32 roundings.
pub struct Cell {
    /// The clamped query: α (s of a classical table, s′·c of a reduced one) and |Δα|.
    alpha: f64,
    d_alpha: f64,
    /// 1 − β² of the clamped query (1 classical) and its bound.
    c2: f64,
    d_c2: f64,
    lambda_nm: f64,
    cos_i: f64,
    /// The relative bound of cos θi.
    ci_rel: f64,
    /// Per corner: weight, the bound of its error, flat index in an order's slice.
    corners: Vec<(f64, f64, usize)>,
    slice: usize,
    /// The word offsets of the q's and of the stored unpolarised values.
    values: usize,
    nodes: usize,
    /// A position in the cell within its rounding of a node line (f32 may take the
    /// neighbouring cell, whose corners this bound does not hold).
    pub near_node: bool,
}

/// The index of the interval [x_i, x_i+1] holding x (the WGSL's and the CPU's rule).
fn interval(nodes: &[f64], x: f64) -> usize {
    let k = nodes.partition_point(|&n| n <= x);
    k.saturating_sub(1).min(nodes.len() - 2)
}

/// The cell of the incident direction of travel (α, β) at λ in the table packed at `words`
/// (its first word the table's): a reduced table's conical cell, a classical table's at
/// s = α. `None` where the WGSL has none (every order 0).
pub fn cell(words: &[f32], alpha: f64, beta: f64, l: f64) -> Option<Cell> {
    if words[8] > 0.5 {
        reduced_cell(words, alpha, beta, l)
    } else {
        classical_cell(words, alpha, l)
    }
}

fn classical_cell(words: &[f32], s: f64, l: f64) -> Option<Cell> {
    let w = |i: usize| words[i] as f64;
    let (n_s, n_l, h) = (w(1) as usize, w(2) as usize, EFFICIENCY_HEADER_WORDS);
    let sin: Vec<f64> = (0..n_s).map(|i| w(h + i)).collect();
    let lam: Vec<f64> = (0..n_l).map(|j| w(h + n_s + j)).collect();
    let s = s.clamp(sin[0], sin[n_s - 1]);
    let l = l.clamp(lam[0], lam[n_l - 1]);
    let cos_i = (1.0 - s * s).max(0.0).sqrt();
    if cos_i <= 0.0 {
        return None;
    }
    let (i, j) = (interval(&sin, s), interval(&lam, l));
    let tx = (s - sin[i]) / (sin[i + 1] - sin[i]);
    let ty = (l - lam[j]) / (lam[j + 1] - lam[j]);
    // The relative error of 1 − t (t itself: 8u): the same f32 inputs and nodes as the CPU's,
    // so a weight of 0 stays 0.
    let e1 = |t: f64| {
        if t < 1.0 {
            (U + 8.0 * U * t) / (1.0 - t)
        } else {
            f64::INFINITY
        }
    };
    let rel = [
        e1(tx) + e1(ty) + U,
        8.0 * U + e1(ty) + U,
        e1(tx) + 8.0 * U + U,
        16.0 * U + U,
    ];
    let wts = [
        (1.0 - tx) * (1.0 - ty),
        tx * (1.0 - ty),
        (1.0 - tx) * ty,
        tx * ty,
    ];
    let at = j * n_s + i;
    let index = [at, at + 1, at + n_s, at + n_s + 1];
    Some(Cell {
        alpha: s,
        d_alpha: 0.0,
        c2: 1.0,
        d_c2: 0.0,
        lambda_nm: l,
        cos_i,
        ci_rel: (2.0 * U * s * s + U) / (2.0 * cos_i * cos_i) + U,
        corners: (0..4)
            .map(|c| (wts[c], wts[c] * rel[c].min(1.0), index[c]))
            .collect(),
        slice: n_l * n_s,
        values: w(5) as usize,
        nodes: w(7) as usize,
        near_node: false,
    })
}

/// A position t = (x − a)/(b − a) in [0, 1] and the bound of its f32 error, given the bound
/// `dx` of x and nodes rounded to f32 (u relative each): the numerator's and the denominator's
/// errors, and the quotient's rounding (3u: WGSL's division is within 2.5 ulp).
fn position(x: f64, a: f64, b: f64, dx: f64) -> (f64, f64) {
    if b == a {
        return (0.0, 0.0);
    }
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    let dt = (dx + U * a.abs() + U * (x - a).abs() + t * U * (a.abs() + b.abs())) / (b - a).abs()
        + 3.0 * U * t;
    (t, dt)
}

/// Whether t, in interval `i` of `n` intervals, lies within its bound dt of a node line with a
/// cell beyond it (and not on it by a clamp).
fn near(t: f64, dt: f64, i: usize, n: usize) -> bool {
    t > 0.0 && t < 1.0 && ((t <= 2.0 * dt && i > 0) || (1.0 - t <= 2.0 * dt && i + 2 < n + 1))
}

fn reduced_cell(words: &[f32], alpha: f64, beta: f64, l: f64) -> Option<Cell> {
    let w = |i: usize| words[i] as f64;
    let (n_s, n_b, r, h) = (
        w(1) as usize,
        w(8) as usize,
        w(9) as usize,
        EFFICIENCY_HEADER_WORDS,
    );
    let sin: Vec<f64> = (0..n_s).map(|i| w(h + i)).collect();
    let tensor = w(r + 5) > 0.5;
    let (bn, cn, rn) = (r + 6, r + 6 + n_b, r + 6 + 2 * n_b);
    let ln = rn + n_b + 1;
    let bet: Vec<f64> = (0..n_b).map(|k| w(bn + k)).collect();
    let cs: Vec<f64> = (0..n_b).map(|k| w(cn + k)).collect();
    let rows: Vec<usize> = (0..=n_b).map(|k| w(rn + k) as usize).collect();
    let b0 = beta.abs();
    if alpha * alpha + b0 * b0 >= 1.0 {
        return None;
    }
    let s0 = alpha / (1.0 - b0 * b0).sqrt();
    let sp = s0.clamp(sin[0], sin[n_s - 1]);
    let b = b0.clamp(bet[0], bet[n_b - 1]);
    let lambda_nm = l.clamp(w(r + 3), w(r + 4));
    let c2 = 1.0 - b * b;
    let c = c2.sqrt();
    // c from (1 − b)(1 + b): 3u relative for c², 2u for the root; a clamped b is a node
    // rounded to f32 (u·b), which moves c by b·u·b/c.
    let b_clamped = b != b0;
    let d_c2 = 3.0 * U * c2 + if b_clamped { 2.0 * U * b * b } else { 0.0 };
    let dc = d_c2 / (2.0 * c) + 2.0 * U * c;
    // s′ = α/c0 (c0 as c, 4u relative, and the quotient's 3u); 0 where clamped.
    let dsp = if sp == s0 { 8.0 * U * sp.abs() } else { 0.0 };
    let unclamped = sp == s0 && !b_clamped;
    let cos_i = if unclamped {
        (c2 - alpha * alpha).sqrt()
    } else {
        c * (1.0 - sp * sp).sqrt()
    };
    if cos_i.is_nan() || cos_i <= 0.0 {
        return None;
    }
    let ci_rel = (d_c2 + 3.0 * U * (c2 + alpha * alpha) + 2.0 * sp.abs() * dsp * c2)
        / (2.0 * cos_i * cos_i)
        + 4.0 * U;
    let i = interval(&sin, sp);
    let k = interval(&bet, b);
    let cp = [cs[k], cs[k + 1]];
    let (tx, dtx) = position(sp, sin[i], sin[i + 1], dsp);
    // A tensor grid: the position in |β| (exact but where clamped to a node rounded to f32);
    // a reduced table: in c, which falls as |β| grows, from c_k toward c_k+1.
    let (tb, dtb) = if tensor {
        position(b, bet[k], bet[k + 1], 0.0)
    } else if cp[1] == cp[0] {
        (0.0, 0.0)
    } else {
        position(c, cp[0], cp[1], dc)
    };
    let (mut row, mut ty, mut dty) = ([0usize; 2], [0.0f64; 2], [0.0f64; 2]);
    let mut near_node = near(tx, dtx, i, n_s - 1) || near(tb, dtb, k, n_b - 1);
    for d in 0..2 {
        let nodes: Vec<f64> = (rows[k + d]..rows[k + d + 1]).map(|x| w(ln + x)).collect();
        // A tensor grid reads every plane at λ; a reduced table at λ·c_p/c (c_p's rounding,
        // c's, the quotient and the product).
        let raw = if tensor {
            lambda_nm
        } else {
            lambda_nm * (cp[d] / c)
        };
        let lq = raw.clamp(nodes[0], nodes[nodes.len() - 1]);
        let dl = if lq == raw && !tensor {
            lq * (6.0 * U + dc / c)
        } else {
            0.0
        };
        let j = interval(&nodes, lq);
        row[d] = rows[k + d] + j;
        (ty[d], dty[d]) = position(lq, nodes[j], nodes[j + 1], dl);
        near_node |= near(ty[d], dty[d], j, nodes.len() - 1);
    }
    let f = |t: f64, dt: f64, side: usize| {
        if side == 1 {
            (t, dt)
        } else {
            (1.0 - t, dt + U * (1.0 - t))
        }
    };
    let corners = (0..8)
        .map(|n| {
            let (di, dk, dj) = (n & 1, (n >> 1) & 1, (n >> 2) & 1);
            let (a, da) = f(tx, dtx, di);
            let (bb, dbb) = f(tb, dtb, dk);
            let (y, dy) = f(ty[dk], dty[dk], dj);
            let wt = a * bb * y;
            // First order in each factor's error, the second-order terms and the two products'
            // roundings.
            let dw = (da * bb * y + a * dbb * y + a * bb * dy) * 1.01
                + da * dbb
                + dbb * dy
                + da * dy
                + 3.0 * U * wt;
            (wt, dw, (row[dk] + dj) * n_s + i + di)
        })
        .collect();
    let alpha_q = sp * c;
    Some(Cell {
        alpha: alpha_q,
        d_alpha: dsp * c + sp.abs() * dc + U * alpha_q.abs(),
        c2,
        d_c2,
        lambda_nm,
        cos_i,
        ci_rel,
        corners,
        slice: n_s * rows[n_b],
        values: w(r) as usize,
        nodes: w(r + 1) as usize,
        near_node,
    })
}

impl Cell {
    /// Order m's raw (before the normalisation) unpolarised-enough value, the larger
    /// polarisation's, and its bound: the weighted mean of the corners' q (at most Q, the
    /// largest) with the weights' errors and the roundings, cos θm/cos θi at the query (the
    /// conditioning of √(1 − β² − α_m²) near the order's Rayleigh line) and cos θi's bound.
    fn raw(&self, words: &[f32], first: i32, d: f64, m: i32) -> (f64, f64) {
        let w = |i: usize| words[i] as f64;
        let k = (m - first) as usize;
        let base = self.values + 2 * k * self.slice;
        let (mut num, mut den, mut q_max, mut werr) = (0.0, 0.0, 0.0f64, 0.0);
        for &(wc, dw, at) in &self.corners {
            let at = base + 2 * at;
            let q = w(at).max(w(at + 1));
            if w(at) >= 0.0 && (wc > 0.0 || dw > 0.0) {
                if wc > 0.0 {
                    num += wc * q;
                    den += wc;
                }
                q_max = q_max.max(q);
                werr += dw;
            }
        }
        let ml = m as f64 * self.lambda_nm / d;
        let am = self.alpha + ml;
        let dam = self.d_alpha + ml.abs() * 7.0 * U + U * am.abs() + U;
        let a = self.c2 - am * am;
        let da = 2.0 * am.abs() * dam + dam * dam + self.d_c2 + 2.0 * U;
        if den <= 0.0 {
            return (0.0, 0.0);
        }
        let r = num / den;
        let dr = q_max * (2.0 * werr / den + 15.0 * U);
        let (root, droot) = if a > 0.0 {
            let root = a.sqrt();
            (root, (da / root).min(da.sqrt()) + U * root)
        } else {
            (0.0, (a + da).max(0.0).sqrt())
        };
        let kk = root / self.cos_i;
        (
            r * kk,
            (dr + r) * droot / self.cos_i + dr * kk + r * kk * (self.ci_rel + 6.0 * U),
        )
    }

    /// Whether order m propagates at the query, and whether f32 may decide otherwise.
    fn propagates(&self, d: f64, m: i32) -> (bool, bool) {
        let am = self.alpha + m as f64 * self.lambda_nm / d;
        let a = self.c2 - am * am;
        let da = 2.0 * am.abs() * (self.d_alpha + 8.0 * U * am.abs() + U) + self.d_c2 + 2.0 * U;
        (a > 0.0, a.abs() <= 4.0 * da + 1e-5)
    }
}

/// The bound of |η_GPU − η_CPU| (unpolarised, normalised) for order m at the incident
/// direction of travel (α, β) and λ of the table packed at `words` (docs/gpu.md, "Tabulated
/// efficiencies"): [`Cell::raw`] of the order, and the normalisation over every order where
/// the sum may reach 1. 0 where the WGSL has no cell; `None` where f32 may take another cell
/// ([`Cell::near_node`]).
pub fn eta_bound(words: &[f32], m: i32, alpha: f64, beta: f64, l: f64) -> Option<f64> {
    let Some(c) = cell(words, alpha, beta, l) else {
        return Some(0.0);
    };
    if c.near_node {
        return None;
    }
    let (d, first, count) = (words[0] as f64, words[3] as i32, words[4] as usize);
    let (eta, deta) = c.raw(words, first, d, m);
    let (mut sum, mut dsum) = (0.0, 0.0);
    for k in 0..count {
        let (a, b) = c.raw(words, first, d, first + k as i32);
        sum += a;
        dsum += b;
    }
    let norm = if sum + dsum >= 1.0 {
        eta * (dsum + count as f64 * U * sum) / sum.max(1.0)
    } else {
        0.0
    };
    Some(deta + norm + 2.0 * U * eta)
}

/// The sampler's order proposal for wo at λ from the packed table: the candidates clipped to
/// the stored orders and trimmed to those propagating at the clamped query,
/// P(m) = (1 − δ)·η̂_m/Σ η̂ + δ/K with η̂_m = Σ_c w_c·η_m,c the corners' stored values, and each
/// P's device bound: the weights' bounds times the corners' values, the values' roundings and
/// the products and sums (6u·η̂_m), the total within the sum of those plus K·u of it; P through
/// the quotients, the product and the sum (8u). `None` where f32 may trim another order (a
/// candidate within rounding of its Rayleigh line at the query) or take another cell.
pub fn weights(words: &[f32], wo: DVec3, l: f64) -> Option<Vec<(i64, f64, f64)>> {
    let (d, first, count) = (words[0] as f64, words[3] as i64, words[4] as i64);
    let step = l / d;
    let lo = (((wo.x - 1.0) / step - 0.5).floor() as i64 + 1).max(first);
    let hi = (((wo.x + 1.0) / step + 0.5).ceil() as i64 - 1).min(first + count - 1);
    let Some(c) = cell(words, -wo.x, -wo.y, l) else {
        return Some(Vec::new());
    };
    if c.near_node {
        return None;
    }
    let mut orders = Vec::new();
    for m in lo..=hi {
        let (p, edge) = c.propagates(d, m as i32);
        if edge {
            return None;
        }
        if p {
            orders.push(m);
        }
    }
    // (η̂_m, its bound)
    let hat: Vec<(f64, f64)> = orders
        .iter()
        .map(|&m| {
            let base = c.nodes + (m - first) as usize * c.slice;
            let (mut e, mut de) = (0.0, 0.0);
            for &(wc, dw, at) in &c.corners {
                let v = words[base + at] as f64;
                if wc > 0.0 {
                    e += wc * v;
                }
                de += dw * v;
            }
            (e, de + 6.0 * U * e)
        })
        .collect();
    let total: f64 = hat.iter().map(|h| h.0).sum();
    let k = orders.len() as f64;
    let dtotal: f64 = hat.iter().map(|h| h.1).sum::<f64>() + k * U * total;
    let share = TABULATED_DEFENSIVE_SHARE;
    Some(
        orders
            .iter()
            .zip(&hat)
            .map(|(&m, &(e, de))| {
                if total > 0.0 {
                    let p = (1.0 - share) * e / total + share / k;
                    let dp =
                        (1.0 - share) * (de / total + e * dtotal / (total * total)) + 8.0 * U * p;
                    (m, p, dp)
                } else {
                    (m, 1.0 / k, 8.0 * U / k)
                }
            })
            .collect(),
    )
}
