//! The peak search: each visible order's peak value times its equivalent width, with order 0's
//! broad light near the mirror direction integrated coarsely (see the module docs of
//! [`spectrum`](super)).

use glam::DVec3;

use super::lobes::Lobes;
use super::{Spectral, BAND};
use crate::num::math::{ceil, floor, sqrt};
use crate::{Grating, Slits};

/// Lobes integrated exactly on each side of a peak by `PeakSearch { refine: true }`.
pub(super) const REFINE_LOBES: f64 = 4.0;
/// Lobes of order 0 the peak searches integrate lobe by lobe before averaging sin²(Nα).
pub(super) const ORDER0_LOBES: f64 = 4.0;
/// The peak searches average sin²(Nα) over order 0's lobes only where these are narrower than
/// this, in wavelength.
pub(super) const AVERAGE_BELOW_NM: f64 = 4.0;

impl Spectral {
    pub(super) fn peak_search(&self, grating: &Grating, u: f64, refine: bool) -> DVec3 {
        let peaks = grating.peaks(u, BAND);
        let n = match grating.slits() {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => return DVec3::ZERO,
        };
        let q = grating.period_nm() * u;
        if Self::order0_everywhere(grating, q) {
            return self.flat_dvec3();
        }
        if Self::is_dense(q) {
            // Too many orders to walk one by one: the same sum in closed form (see `dense`).
            return self.dense_peak_search(grating, q);
        }
        let (x_lo, x_hi) = (q / BAND.max_nm(), q / BAND.min_nm());
        let lobes = Lobes::new(self, grating, q, n);
        let mut acc = DVec3::ZERO;
        // Order 0 is broad in wavelength: where its half period (x < ½) reaches into the band,
        // the partial lobe at the start, the next ORDER0_LOBES lobes and all lobes wider than
        // AVERAGE_BELOW_NM are integrated lobe by lobe, the rest with sin²(Nα) → ½ (starting and ending on zeros of sin(Nα), where that
        // costs nothing), and the final partial lobe again lobe by lobe; every piece spans at
        // most COARSE_SPAN_NM and is not split at table rows. This light is broad and its error
        // is small against the orders' (see the module docs).
        if x_lo < 0.5 {
            let end = x_hi.min(0.5);
            // Lobes are q/(N·x²) nm wide: average only where they are narrower than
            // AVERAGE_BELOW_NM, after at least ORDER0_LOBES lobes.
            let narrow_from = ceil(sqrt(q / (n * AVERAGE_BELOW_NM)) * n);
            let near_end = (ceil(x_lo * n) + ORDER0_LOBES).max(narrow_from) / n;
            let near_end = near_end.min(end);
            acc += lobes.coarse_lobes(x_lo, near_end);
            let tail_end = (floor(end * n) / n).max(near_end);
            if near_end < tail_end {
                acc += lobes.envelope(near_end, tail_end, false);
            }
            acc += lobes.coarse_lobes(tail_end, end);
        }
        let half = REFINE_LOBES / n;
        // Mass of F_N within ±REFINE_LOBES lobes of a peak (the same for every order), and the
        // rest of the period's mass 1/N, half on each side.
        let near_mass = if refine { lobes.kernel_mass(half) } else { 0.0 };
        let mut near_mass_edge = near_mass;
        for p in peaks {
            let m = p.order.unsigned_abs() as f64;
            let at_edge = m - half < x_lo || m + half > x_hi;
            if !refine && !at_edge {
                let w = self.weight(p.wavelength_nm);
                acc += w * p.intensity * p.equivalent_width_nm;
                continue;
            }
            if near_mass_edge == 0.0 {
                near_mass_edge = lobes.kernel_mass(half);
            }
            // Main and first side lobes by quadrature (clipped to the band), the rest of the
            // mass of each side that lies in the band at the peak.
            // (Refined: exact lobes; plain: the coarse rule, enough for the peak search's
            // accuracy and far cheaper when N is small and the lobes are wide.)
            let (a, b) = ((m - half).max(x_lo), (m + half).min(x_hi));
            let near = if refine {
                lobes.lobes(a, b)
            } else {
                lobes.coarse_lobes(a, b)
            };
            acc += near;
            let sides = (m - half >= x_lo) as u8 + (m + half <= x_hi) as u8;
            let rest = 0.5 * sides as f64 * (1.0 / n - near_mass_edge).max(0.0);
            let w = self.weight(p.wavelength_nm);
            acc += w * p.intensity * rest * p.wavelength_nm / m;
        }
        // Orders just outside the band whose main lobes reach into it.
        for m in [floor(x_lo), ceil(x_hi)] {
            if m >= 1.0 && !(x_lo..=x_hi).contains(&m) {
                let (a, b) = ((m - half).max(x_lo), (m + half).min(x_hi));
                acc += lobes.coarse_lobes(a, b);
            }
        }
        acc
    }
}
