//! `Exact`: lobe-exact quadrature of the reference colour, the crate's reference.

use glam::DVec3;

use super::lobes::Lobes;
use super::{Spectral, BAND};
use crate::math::{ceil, floor};
use crate::{Grating, Slits};

/// Lobes integrated exactly around every integer x and band end by `Exact` in its hybrid mode.
pub(super) const NEAR_LOBES: f64 = 64.0;
/// Above this many lobes in the band, `Exact` switches to its hybrid mode.
pub(super) const MAX_LOBES: f64 = 4096.0;

impl Spectral {
    pub(super) fn exact(&self, grating: &Grating, u: f64) -> DVec3 {
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return DVec3::ZERO,
        };
        let q = grating.period_nm() * u;
        if Self::order0_everywhere(grating, q) {
            return {
                let w = self.flat();
                DVec3::new(w.x, w.y, w.z)
            };
        }
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobes = Lobes::new(self, grating, q, n);
        if Self::is_dense(q) {
            // Too many orders to walk (see `dense`): closed form for the whole periods.
            let n_int = n as u32;
            return self.dense_exact(grating, &lobes, q, n_int, &|l, a, b| hybrid(l, n, a, b));
        }
        if n * (x_hi - x_lo) <= MAX_LOBES {
            return lobes.lobes(x_lo, x_hi);
        }
        hybrid(&lobes, n, x_lo, x_hi)
    }
}

/// Hybrid: lobe-exact within NEAR_LOBES lobes of every integer x and of the ends of [x_lo, x_hi]
/// (aligned to lobe boundaries), the envelope with sin² → ½ elsewhere. At most a few pieces per
/// integer x in the range (fewer than `dense::DENSE_ORDERS` + 2 of them).
pub(super) fn hybrid(lobes: &Lobes<'_>, n: f64, x_lo: f64, x_hi: f64) -> DVec3 {
    let k = NEAR_LOBES / n;
    let start_end = (ceil((x_lo + k) * n) / n).min(x_hi);
    let end_start = (floor((x_hi - k) * n) / n).max(x_lo);
    let mut acc = DVec3::ZERO;
    let mut cursor = x_lo;
    while cursor < x_hi {
        let m_prev = floor(cursor);
        let m_next = m_prev + 1.0;
        let (near, until) = if cursor < start_end {
            (true, start_end)
        } else if cursor >= end_start {
            (true, x_hi)
        } else if cursor < m_prev + k {
            (true, m_prev + k)
        } else if cursor >= m_next - k {
            (true, m_next + k)
        } else {
            (false, (m_next - k).min(end_start))
        };
        // Progress is guaranteed: a piece that would not advance (rounding at huge x) takes
        // the rest of the range.
        let until = until.min(x_hi);
        let until = if until > cursor { until } else { x_hi };
        if near {
            acc += lobes.lobes(cursor, until);
        } else {
            acc += lobes.envelope(cursor, until, true);
        }
        cursor = until;
    }
    acc
}
