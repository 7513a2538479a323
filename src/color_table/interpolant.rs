//! The cubic Hermite interpolant of the tables: a node's value and derivative, the derivatives
//! from the nearest nodes, the interpolant inside a cell and its integral.

use alloc::vec::Vec;

/// The value and the derivative in u at a node.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Node {
    pub f: [f64; 3],
    pub d: [f64; 3],
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
