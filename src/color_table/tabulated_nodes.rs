//! The node values of a tabulated grating's colour table (feature `relief`): the colour
//! C(u, s) of the radiometric BSDF with tabulated order efficiencies per unit of cos θi·g(v),
//! at u = wi.x + wo.x and the incidence s = wi.x (wo.x = u − s, v = 0).
//!
//! The integrand in λ is the BSDF's own `eval` (the order owning the phase x = d·u/λ, its
//! η̃_m = min(η_m(−wi.x, λ), η_m(−wo.x, λ)) and its unit-integral lobe (N·d/λ)·F_N) times the
//! illuminant and the colour-matching functions. It is smooth between these wavelengths, which
//! cut the band into panels, each integrated by 4-point Gauss-Legendre (the BSDF's `eval4`,
//! which locates the pair of incidences in the table once for the four wavelengths):
//!
//! * the zeros of F_N, x = k/N (every side lobe is one panel, the main lobe two), and the
//!   order boundaries x = k + ½ (where the owning order changes);
//! * the table's wavelength nodes (its interpolation is piecewise linear between them);
//! * every owning order's Rayleigh wavelengths at both incidences, sin θm = −α + m·λ/d = ±1
//!   (the efficiency falls to 0 there as a square root).
//!
//! Beyond [`MAX_LOBE_PANELS`] side lobes (N·d·|u|·(1/360 − 1/830) > 4096: N of thousands) the
//! work stays bounded by resolving only each order's peak: its main lobe and [`PEAK_LOBES`]
//! side lobes a side are one panel each, then panels grow geometrically (doubling in x) to the
//! order boundaries. A panel wider than one lobe reads the BSDF at x ± 1/(4N) about each node
//! and takes the mean, sin²(Nπx − π/4) + sin²(Nπx + π/4) = 1: the mean of F_N's oscillation,
//! exact up to the envelope's curvature over a quarter lobe. (Panels of several side lobes each
//! sampled the oscillation at 4 points a panel and missed the peaks: at N = 10⁵ the CD's
//! colour was 0.07-0.51 of its value, at N = 10⁷ below 0.01.)

use alloc::vec::Vec;
use core::cell::{Cell, RefCell};

use glam::DVec3;

use super::layout::{LAMBDA_MAX_NM, LAMBDA_MIN_NM};
use crate::num::math::{ceil, floor, sqrt};
use crate::spectrum::Spectral;
use crate::{DiffractionBrdf, GratingBsdf, GrooveSpread, SampledWavelengths};

/// 4-point Gauss-Legendre on [−1, 1]: nodes and weights.
const GL4_NODES: [f64; 4] = [
    -0.861_136_311_594_052_6,
    -0.339_981_043_584_856_3,
    0.339_981_043_584_856_3,
    0.861_136_311_594_052_6,
];
const GL4_WEIGHTS: [f64; 4] = [
    0.347_854_845_137_453_8,
    0.652_145_154_862_546_2,
    0.652_145_154_862_546_2,
    0.347_854_845_137_453_8,
];

/// The widest panel, nm: the colour-matching functions and illuminants change on scales of
/// 10 nm.
const MAX_PANEL_NM: f64 = 8.0;

/// The most F_N panels of one node at one panel a side lobe (beyond this only the orders'
/// peaks are resolved lobe by lobe).
const MAX_LOBE_PANELS: f64 = 4096.0;
/// Side lobes a side of each order's main lobe that are one panel each when the lobes are not
/// all resolved (beyond them F_N's oscillation is averaged).
const PEAK_LOBES: usize = 16;
/// The groove spread the nodes are evaluated with: any λ-independent spread gives the same
/// f/g(v) (the table's groove is Gaussian or ideal, whose f is a delta in v).
const STAND_IN_SIGMA: f64 = 0.02;

/// The colour C(u, s) of a tabulated BSDF, with the evaluations it took.
pub(super) struct TabulatedNodes {
    /// The BSDF with the stand-in Gaussian groove.
    bsdf: GratingBsdf,
    /// 1/g(0) of the stand-in groove.
    inv_g0: f64,
    /// The plain illuminant's integrator (E·cmf/∫E·ȳ).
    spectral: Spectral,
    d: f64,
    n: f64,
    /// The table's wavelengths inside the band.
    lambda_nodes: Vec<f64>,
    /// The table's stored orders.
    orders: (i64, i64),
    /// The plane: |wi.y| = `beta` (wo.y = −β, the groove lobe's centre) and r = √(1 − β²),
    /// the largest |wi.x| and |wo.x| above the surface there.
    beta: f64,
    r: f64,
    /// The breakpoints' buffer.
    cuts: RefCell<Vec<f64>>,
    pub evaluations: Cell<usize>,
    pub work_done: Cell<usize>,
}

impl TabulatedNodes {
    /// Whether the colour over u ≤ 0 is the colour over u ≥ 0 at the same node coordinate σ,
    /// to within `tolerance` of the efficiencies: the table's incidences and orders symmetric
    /// about 0, and η_m(s, λ) = η_−m(−s, λ) within `tolerance` at every node, both
    /// polarisations (a symmetric groove profile; on the plane's |β|, at α = s·r). Then mirroring x → −x maps (u, s) to
    /// (−u, −s) and reciprocity (wi ↔ wo) maps (−u, −s) to (−u, s − u), the point of the grid
    /// over u ≤ 0 at the same σ (the groove spreads the table takes are even in v, and the
    /// tabulated lobe is even in x).
    pub(super) fn mirror_symmetric(&self, tolerance: f64) -> bool {
        let model = self.bsdf.order_efficiency();
        let Some(table) = model.table() else {
            return false;
        };
        let s: Vec<f64> = table.sin_theta_i().collect();
        let orders = table.orders();
        if orders.end().checked_neg() != Some(*orders.start())
            || s.iter().zip(s.iter().rev()).any(|(a, b)| *a != -*b)
        {
            return false;
        }
        let symmetric = table.lambda_nm().all(|l| {
            s.iter().all(|&x| {
                orders.clone().all(|m| {
                    // On the plane: incidences α = s·r at |β| = β (a classical table ignores β).
                    let (a, b) = (x * self.r, self.beta);
                    let p = table.efficiency_conical(m, a, b, l);
                    let q = table.efficiency_conical(-m, -a, b, l);
                    (p.te - q.te).abs() <= tolerance && (p.tm - q.tm).abs() <= tolerance
                })
            })
        });
        symmetric
    }

    /// The nodes of `bsdf` (tabulated, finite N: the caller checks) under the plain
    /// illuminant of `spectral`, on the plane across the grooves.
    pub(super) fn new(bsdf: &GratingBsdf, spectral: &Spectral) -> TabulatedNodes {
        TabulatedNodes::on_plane(bsdf, spectral, 0.0)
    }

    /// The same at |wi.y| = `beta` (in [0, 1)), wo.y = −β: the plane a conical table's
    /// colour is tabulated on.
    pub(super) fn on_plane(bsdf: &GratingBsdf, spectral: &Spectral, beta: f64) -> TabulatedNodes {
        // σ = 0.02 is valid.
        let stand_in = GrooveSpread::gaussian(STAND_IN_SIGMA).unwrap_or(bsdf.groove());
        let lobe = bsdf.with_groove(stand_in);
        let g0 = stand_in.value(0.0, LAMBDA_MIN_NM);
        let (lambda_nodes, orders) = match bsdf.order_efficiency().table() {
            Some(t) => (
                t.lambda_nm()
                    .filter(|l| *l > LAMBDA_MIN_NM && *l < LAMBDA_MAX_NM)
                    .collect(),
                (i64::from(*t.orders().start()), i64::from(*t.orders().end())),
            ),
            None => (Vec::new(), (0, -1)),
        };
        let g = bsdf.grating();
        TabulatedNodes {
            bsdf: lobe,
            inv_g0: 1.0 / g0,
            spectral: Spectral::new(spectral.illuminant()),
            d: g.period_nm(),
            n: g.slits().as_f64(),
            lambda_nodes,
            orders,
            beta,
            r: sqrt(1.0 - beta * beta),
            cuts: RefCell::new(Vec::new()),
            evaluations: Cell::new(0),
            work_done: Cell::new(0),
        }
    }

    /// The plane's r = √(1 − β²): |wi.x| and |wo.x| stay below it.
    pub(super) fn r(&self) -> f64 {
        self.r
    }

    /// C(u, s): ∫ E·(f/g)·cmf dλ/∫E·ȳ at wi = (s, β), wo = (u − s, −β); black where either
    /// direction is not above the surface.
    pub(super) fn eval(&self, u: f64, s: f64) -> [f64; 3] {
        self.evaluations.set(self.evaluations.get() + 1);
        let ox = u - s;
        if !(s.abs() < self.r && ox.abs() < self.r) {
            return [0.0; 3];
        }
        let b = self.beta;
        let wi = DVec3::new(s, b, sqrt(1.0 - s * s - b * b));
        let wo = DVec3::new(ox, -b, sqrt(1.0 - ox * ox - b * b));
        let mut cuts = self.cuts.borrow_mut();
        cuts.clear();
        cuts.push(LAMBDA_MIN_NM);
        cuts.push(LAMBDA_MAX_NM);
        cuts.extend_from_slice(&self.lambda_nodes);
        let a = u.abs();
        let q = self.d * a;
        if q > 0.0 {
            let (x_lo, x_hi) = (q / LAMBDA_MAX_NM, q / LAMBDA_MIN_NM);
            let sign = if u < 0.0 { -1.0 } else { 1.0 };
            // Orders the table does not store carry nothing (no cuts): at most its |m|.
            let most = self
                .orders
                .0
                .unsigned_abs()
                .max(self.orders.1.unsigned_abs()) as f64;
            if self.n * (x_hi - x_lo) <= MAX_LOBE_PANELS {
                // F_N's zeros k/N: every side lobe one panel.
                let step = 1.0 / self.n;
                let mut k = ceil(x_lo / step);
                while k * step < x_hi {
                    cuts.push(q / (k * step));
                    k += 1.0;
                }
            } else {
                // Each stored order's peak lobe by lobe, then doubling panels (averaged).
                let mut m = floor(x_lo + 0.5).max(0.0);
                while m <= floor(x_hi + 0.5).min(most) {
                    let signed = (sign * m) as i64;
                    if signed >= self.orders.0 && signed <= self.orders.1 {
                        for side in [-1.0, 1.0] {
                            let mut j = 0.0;
                            while j < 0.5 * self.n {
                                let x = m + side * j / self.n;
                                if x > x_lo && x < x_hi {
                                    cuts.push(q / x);
                                }
                                j = if j < PEAK_LOBES as f64 {
                                    j + 1.0
                                } else {
                                    2.0 * j
                                };
                            }
                        }
                    }
                    m += 1.0;
                }
            }
            // The order boundaries and each owning order's Rayleigh wavelengths.
            let (m_lo, m_hi) = (floor(x_lo + 0.5), floor(x_hi + 0.5).min(most + 1.0));
            let mut m = m_lo;
            while m <= m_hi {
                let b = q / (m + 0.5);
                cuts.push(b);
                let signed = sign * m;
                if m > 0.0 && signed as i64 >= self.orders.0 && signed as i64 <= self.orders.1 {
                    // −α + m·λ/d = ±1 with α = −s (wi) and α = −ox (wo).
                    for alpha in [-s, -ox] {
                        for edge in [-1.0, 1.0] {
                            cuts.push(self.d * (edge + alpha) / signed);
                        }
                    }
                }
                m += 1.0;
            }
        }
        cuts.retain(|l| *l >= LAMBDA_MIN_NM && *l <= LAMBDA_MAX_NM);
        cuts.sort_unstable_by(f64::total_cmp);
        cuts.dedup();
        let mut acc = DVec3::ZERO;
        let panels = cuts.windows(2).flat_map(|w| {
            let pieces = ceil((w[1] - w[0]) / MAX_PANEL_NM).max(1.0);
            let step = (w[1] - w[0]) / pieces;
            (0..pieces as usize).map(move |k| (w[0] + k as f64 * step, step))
        });
        for (a, width) in panels {
            let (mid, half) = (a + 0.5 * width, 0.5 * width);
            let lambda = GL4_NODES.map(|x| mid + half * x);
            // The four wavelengths of the panel in one call (the pair located once); each
            // is in the band, and a density of 1 is valid.
            let Ok(l) = SampledWavelengths::new(lambda, [1.0; 4]) else {
                continue;
            };
            let mut f = self.bsdf.eval4(wo, wi, &l);
            // Wider than one lobe (only where the lobes are not all panels): the mean of the
            // readings a quarter lobe either side of each node.
            if self.n * (q / a - q / (a + width)) > 1.5 {
                let shifted = |dx: f64| lambda.map(|l| q / (q / l + dx));
                let (lo, hi) = (shifted(-0.25 / self.n), shifted(0.25 / self.n));
                if let (Ok(lo), Ok(hi)) = (
                    SampledWavelengths::new(lo, [1.0; 4]),
                    SampledWavelengths::new(hi, [1.0; 4]),
                ) {
                    let (p, r) = (self.bsdf.eval4(wo, wi, &lo), self.bsdf.eval4(wo, wi, &hi));
                    f = core::array::from_fn(|k| 0.5 * (p[k] + r[k]));
                }
            }
            for k in 0..4 {
                acc += self.spectral.weight(lambda[k]) * (f[k] * GL4_WEIGHTS[k] * half);
            }
        }
        self.work_done
            .set(self.work_done.get() + 1 + cuts.len() / 64);
        let c = acc * self.inv_g0;
        [c.x.max(0.0), c.y.max(0.0), c.z.max(0.0)]
    }
}

#[cfg(all(test, feature = "presets"))]
mod tests {
    use super::*;
    use crate::relief::Preset;
    use crate::spectrum::{GenericStrategy, Illuminant};

    /// The nodes against the generic colour of the same BSDF by 8-point Gauss-Legendre on 512
    /// intervals of the band, per channel relative to the largest channel of the reference.
    /// Measured worst 1.0·10⁻⁴ (14 pairs, D65 and E); margin 10.
    const NODE_REL: f64 = 1e-3;

    /// Mirror symmetry is recognised where the stored efficiencies have it: exactly for `cd`
    /// and `dvd` (solved so), within 1.0·10⁻⁵ for `foil` (each node solved on its own), not
    /// for `blazed600`. Where it holds, the colour over u ≤ 0 at σ is the colour over u ≥ 0
    /// at σ (mirror and reciprocity): for the CD to the integrator's rounding (measured
    /// 8·10⁻¹⁷ relative), while the blazed grating's differ by up to 60 times.
    #[test]
    fn mirror_symmetry_of_the_presets() {
        let s = Spectral::new(Illuminant::D65);
        let nodes = |p: Preset| {
            let b = GratingBsdf::preset(p, 34)
                .unwrap()
                .with_groove(GrooveSpread::gaussian(0.02).unwrap());
            TabulatedNodes::new(&b, &s)
        };
        for (p, coarse, fine) in [
            (Preset::Cd, true, true),
            (Preset::Dvd, true, true),
            (Preset::Foil, true, false),
            (Preset::Blazed600, false, false),
        ] {
            let n = nodes(p);
            assert_eq!(n.mirror_symmetric(2e-5), coarse, "{p}");
            assert_eq!(n.mirror_symmetric(5e-6), fine, "{p}");
        }
        // The colour at (−a, s) for s = −1 + τ·(2 − a) against that at (a, a − 1 + τ·(2 − a)).
        let asymmetry = |p: Preset| {
            let n = nodes(p);
            let mut worst = 0.0f64;
            for (a, tau) in [(0.255, 0.3), (0.6, 0.5), (1.2, 0.8), (0.4, 0.1), (1.5, 0.6)] {
                let w = 2.0 - a;
                let (pos, neg) = (n.eval(a, a - 1.0 + tau * w), n.eval(-a, -1.0 + tau * w));
                let big = pos[0].max(pos[1]).max(pos[2]);
                for (x, y) in pos.iter().zip(neg) {
                    worst = worst.max((x - y).abs() / big);
                }
            }
            worst
        };
        let (cd, blazed) = (asymmetry(Preset::Cd), asymmetry(Preset::Blazed600));
        std::println!("mirror: CD {cd:.1e}, blazed600 {blazed:.1e}");
        assert!(cd <= 1e-12, "{cd:e}");
        assert!(blazed >= 0.1, "{blazed:e}");
    }

    #[test]
    fn nodes_match_a_fine_rule() {
        let b = GratingBsdf::preset(Preset::Cd, 34)
            .unwrap()
            .with_groove(GrooveSpread::gaussian(0.02).unwrap());
        let rule = GenericStrategy::gauss_legendre(512).unwrap();
        let mut worst = 0.0f64;
        for illuminant in [Illuminant::D65, Illuminant::E] {
            let s = Spectral::new(illuminant);
            let nodes = TabulatedNodes::new(&b, &s);
            for (u, si) in [
                (0.255, -0.633),
                (0.255, 0.0),
                (0.6, 0.2),
                (1.2, 0.5),
                (-0.4, 0.3),
                (-1.5, -0.7),
                (0.01, 0.3),
            ] {
                let c = nodes.eval(u, si);
                let ox: f64 = u - si;
                let wi = DVec3::new(si, 0.0, sqrt(1.0 - si * si));
                let wo = DVec3::new(ox, 0.0, sqrt(1.0 - ox * ox));
                let g = wi.z * b.groove().value(0.0, 550.0);
                let r = s.xyz_brdf(&b, wo, wi, rule).scale(1.0 / g);
                let big = r.x.max(r.y).max(r.z);
                for (got, want) in c.iter().zip([r.x, r.y, r.z]) {
                    worst = worst.max((got - want).abs() / big);
                }
            }
        }
        std::println!("worst {worst:.2e}");
        assert!(worst <= NODE_REL, "{worst:.3e}");
    }

    /// Beyond `MAX_LOBE_PANELS` side lobes (here N = 10⁵: 1.5·10⁵ lobes over the band) the
    /// nodes against a midpoint rule in x = d·|u|/λ with 16 points in every lobe of F_N
    /// (independent of the panels), per channel relative to the largest: measured worst
    /// 2.7·10⁻⁵ (the first point has order 2's Rayleigh wavelength 46 lobes from its peak).
    /// Panels of several side lobes each gave 0.07-0.51 of the colour (0.92 off here).
    #[test]
    fn nodes_of_many_slits_match_a_rule_in_every_lobe() {
        let s = Spectral::new(Illuminant::D65);
        let n = 100_000u32;
        let b = GratingBsdf::preset(Preset::Cd, n)
            .unwrap()
            .with_groove(GrooveSpread::gaussian(0.02).unwrap());
        let nodes = TabulatedNodes::new(&b, &s);
        let mut worst = 0.0f64;
        for (u, si) in [(0.6001, 0.2), (0.255, -0.633), (-1.5, -0.7)] {
            let c = nodes.eval(u, si);
            let ox: f64 = u - si;
            let wi = DVec3::new(si, 0.0, sqrt(1.0 - si * si));
            let wo = DVec3::new(ox, 0.0, sqrt(1.0 - ox * ox));
            let q = 1600.0 * f64::abs(u);
            let (x0, x1) = (q / LAMBDA_MAX_NM, q / LAMBDA_MIN_NM);
            let steps = (f64::from(n) * (x1 - x0) * 16.0).ceil() as usize;
            let h = (x1 - x0) / steps as f64;
            let mut r = DVec3::ZERO;
            for k in 0..steps {
                let x = x0 + (k as f64 + 0.5) * h;
                let l = q / x;
                // dλ = q/x² dx.
                r += s.weight(l) * (b.eval(wo, wi, l) * q / (x * x) * h);
            }
            let r = r / b.groove().value(0.0, 550.0);
            let big = r.x.max(r.y).max(r.z);
            for (got, want) in c.iter().zip([r.x, r.y, r.z]) {
                worst = worst.max((got - want).abs() / big);
            }
        }
        std::println!("worst {worst:.2e}");
        assert!(worst <= NODE_REL, "{worst:.3e}");
    }
}
