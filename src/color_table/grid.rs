//! The table's grid arithmetic: the tolerance of a node, the assembly of the blocks' nodes,
//! their derivatives, the cubic Hermite interpolant and its integral, and the work units of one
//! colour evaluation.

use alloc::vec::Vec;

use super::tabulated::{Node, Work};
use super::{LAMBDA_MAX_NM, LAMBDA_MIN_NM};
use crate::math::cbrt;

/// The error allowed in channel `c` of `exact`, over the accuracy: the change of that channel
/// that moves CIELAB's f(t) = t^(1/3) (linear below t = (6/29)³) by 1/3, at the exposure
/// Y' = max(`scale`, Y) (t = channel / (white · Y')). So it is white_c·Y'·max(t, (6/29)³)^(2/3):
/// at most white_c·Y' for channels up to the white, 0.043·white_c·Y_b where the colour is dark.
pub(super) fn tolerance(exact: &[f64; 3], c: usize, scale: f64, white: [f64; 3]) -> f64 {
    const DARK: f64 = (6.0 / 29.0) * (6.0 / 29.0) * (6.0 / 29.0);
    let exposure = scale.max(exact[1]);
    let t = (exact[c] / (white[c] * exposure)).max(DARK);
    let r = cbrt(t);
    white[c] * exposure * r * r
}

/// 2^⌊log₂ x⌋ for positive finite x (the smallest normal number for smaller x).
pub(super) fn power_of_two_below(x: f64) -> f64 {
    let x = x.max(f64::MIN_POSITIVE);
    f64::from_bits(x.to_bits() & !((1u64 << 52) - 1))
}

/// The nodes of all blocks in order (shared ends once), their values, and each block's first
/// node index.
pub(super) fn assemble(work: &[Work]) -> (Vec<f64>, Vec<[f64; 3]>, Vec<usize>) {
    let total = 1 + work.iter().map(|w| w.n).sum::<usize>();
    let (mut xs, mut fs, mut starts) = (
        Vec::with_capacity(total),
        Vec::with_capacity(total),
        Vec::with_capacity(work.len()),
    );
    for (k, w) in work.iter().enumerate() {
        starts.push(if k == 0 { 0 } else { xs.len() - 1 });
        let skip = (k > 0) as usize;
        for j in skip..=w.n {
            xs.push(w.u0 + j as f64 * w.h);
            fs.push(w.vals[j]);
        }
    }
    (xs, fs, starts)
}

/// Derivatives at the nodes: the derivative of the Lagrange polynomial through the five nearest
/// nodes (shifted inward at u = 2; mirrored through u = 0, where the colour is even, so the
/// derivative at 0 is 0).
pub(super) fn derivatives(xs: &[f64], fs: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let m = xs.len() as isize;
    let point = |j: isize| -> (f64, [f64; 3]) {
        if j >= 0 {
            (xs[j as usize], fs[j as usize])
        } else {
            (-xs[(-j) as usize], fs[(-j) as usize])
        }
    };
    let mut out = Vec::with_capacity(xs.len());
    out.push([0.0; 3]);
    for i in 1..m {
        let lo = (i - 2).min(m - 5).max(-(m - 1));
        let hi = (lo + 4).min(m - 1);
        let (xc, _) = point(i);
        let mut d = [0.0; 3];
        for k in lo..=hi {
            let (xk, fk) = point(k);
            let weight = if k == i {
                (lo..=hi)
                    .filter(|&j| j != i)
                    .map(|j| 1.0 / (xc - point(j).0))
                    .sum::<f64>()
            } else {
                let mut num = 1.0;
                let mut den = 1.0;
                for j in lo..=hi {
                    if j != k {
                        den *= xk - point(j).0;
                        if j != i {
                            num *= xc - point(j).0;
                        }
                    }
                }
                num / den
            };
            for c in 0..3 {
                d[c] += weight * fk[c];
            }
        }
        out.push(d);
    }
    out
}

/// The cubic Hermite interpolant between nodes p and q (spacing h) at fraction s.
#[inline]
pub(super) fn hermite(p: &Node, q: &Node, h: f64, s: f64) -> [f64; 3] {
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = (s3 - 2.0 * s2 + s) * h;
    let h01 = 3.0 * s2 - 2.0 * s3;
    let h11 = (s3 - s2) * h;
    [
        h00 * p.f[0] + h10 * p.d[0] + h01 * q.f[0] + h11 * q.d[0],
        h00 * p.f[1] + h10 * p.d[1] + h01 * q.f[1] + h11 * q.d[1],
        h00 * p.f[2] + h10 * p.d[2] + h01 * q.f[2] + h11 * q.d[2],
    ]
}

/// ∫ of the Hermite interpolant over the first fraction s of the cell [p, q] (spacing h).
#[inline]
pub(super) fn cell_integral(p: &Node, q: &Node, h: f64, s: f64) -> [f64; 3] {
    let s2 = s * s;
    let s3 = s2 * s;
    let s4 = s2 * s2;
    let i00 = (s - s3 + 0.5 * s4) * h;
    let i10 = (0.5 * s2 - 2.0 / 3.0 * s3 + 0.25 * s4) * h * h;
    let i01 = (s3 - 0.5 * s4) * h;
    let i11 = (0.25 * s4 - s3 / 3.0) * h * h;
    core::array::from_fn(|c| i00 * p.f[c] + i10 * p.d[c] + i01 * q.f[c] + i11 * q.d[c])
}

/// The work units of one colour evaluation at q = d·|u| (see
/// [`ColorTable::MAX_WORK`](super::ColorTable::MAX_WORK)).
pub(super) fn work_units(q: f64) -> usize {
    const ORDERS_PER_UNIT: f64 = 1024.0;
    const MOST_ORDERS: f64 = 4096.0;
    let orders = q * (1.0 / LAMBDA_MIN_NM - 1.0 / LAMBDA_MAX_NM);
    let orders = if orders.is_nan() {
        MOST_ORDERS
    } else {
        orders.clamp(0.0, MOST_ORDERS)
    };
    1 + (orders / ORDERS_PER_UNIT) as usize
}
