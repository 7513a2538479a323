//! The solver: one solve at a given truncation, the cover's passes, and the convergence loop.

use faer::{c64, Mat};

use crate::cmethod;
use crate::error::Error;
use crate::grating::{Grating, Incidence, Profile, MAX_SLABS};
use crate::modal::{self, Lattice, Pol, Stack};
use crate::surface::Surface;

/// Default convergence tolerance: absolute, per order and polarisation.
pub const DEFAULT_TOLERANCE: f64 = 1e-3;
/// Default cap on the harmonic count: [`MAX_HARMONICS`]. A hard case stops well before it (the
/// default [`DEFAULT_MAX_WORK`] ends a conical or C-method sequence earlier); at 801, 12 of the
/// 259 lamellar reference cases (fmm/README.md, "Convergence") did not converge to 10⁻³, at
/// 1601 one did.
pub const DEFAULT_MAX_HARMONICS: usize = MAX_HARMONICS;
/// The table builder's default cap per solve (`grating-table --max-harmonics`): a table takes
/// thousands of solves, and a node that has not converged by then is kept at the cap's count
/// and marked in the file.
pub const TABLE_MAX_HARMONICS: usize = 801;
/// The hard cap on the harmonic count whatever the options say.
pub const MAX_HARMONICS: usize = 1601;
/// Smallest first harmonic count.
pub const MIN_HARMONICS: usize = 21;
/// The harmonic count grows by this factor between two steps of the convergence loop.
pub const GROWTH: f64 = 1.5;
/// Default cap on one call's work, in the units of [`work`] (about 25 ns each on a 2-core
/// x86-64 machine of 2026: about 4 minutes). From the first count 21, a lamellar profile's
/// ×1.5 sequence reaches 1359 harmonics in either mount and the C method's 905 (the presets'
/// converged solves went to 1037, with a larger cap); it stops a deep staircase of hundreds
/// of slabs, which at the harmonic cap alone would run for hours.
pub const DEFAULT_MAX_WORK: f64 = 1e10;
/// The largest work cap the options accept (about 40 minutes).
pub const MAX_WORK: f64 = 1e11;

const PERIOD_REQUIREMENT: &str =
    "small enough that the propagating orders (2·n·d/λ + 1, ×2 and ×3 for the convergence steps) fit under max_harmonics";

/// How light that the grating sends back into a cover is counted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoverPasses {
    /// One pass: air → cover → grating → cover → air; light reflected back at the cover's top
    /// surface (including all that is totally reflected) is dropped.
    Single,
    /// Every pass, summed incoherently: light reflected at the top surface returns to the grating
    /// on the same lattice of directions and is diffracted again.
    Multiple,
}

/// Whether the harmonic sequence is extrapolated in 1/N.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extrapolation {
    /// Report the last count's values.
    Off,
    /// Richardson in 1/N for the polarisations whose field crosses the profile's corners (TM in
    /// the classical mount, both in the conical mount): η∞ ≈ (N₂η₂ − N₁η₁)/(N₂ − N₁); converged
    /// when three successive extrapolations agree (two successive changes below the tolerance:
    /// one agreement can be a chance crossing). Where they never agree within the cap but the
    /// plain values did at two successive steps, the last such plain values are returned
    /// (`Solution::extrapolated` false).
    Richardson,
}

/// Which rigorous method solves a grating.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The C method for continuous profiles (sinusoid, sawtooth, Fourier, sampled), classical
    /// and conical mounts; the Fourier modal method otherwise (lamellar, multilevel, flat).
    Auto,
    /// The Fourier modal method (a staircase of a continuous profile).
    Fmm,
    /// The C method (continuous profiles and flat ones, any mount: a lamellar or multilevel
    /// profile is refused with an error naming `depth_nm`).
    CMethod,
}

/// The solver's options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Absolute tolerance per order and polarisation (default 1e-3).
    pub tolerance: f64,
    /// The harmonic cap of the convergence loop (default and at most [`MAX_HARMONICS`], 1601:
    /// of the 259 lamellar reference cases, 12 did not converge to 1e-3 with Richardson's two
    /// agreements by 801 harmonics, one by 1601; the work cap `max_work` ends a sequence first
    /// where its next step would pass it).
    pub max_harmonics: usize,
    /// Slabs of a staircased (smooth) profile; `None`: one per λ/40 of depth, at least 8.
    pub slabs: Option<usize>,
    /// Extrapolation in 1/N (default Richardson).
    pub extrapolation: Extrapolation,
    /// The cover's passes (default multiple).
    pub cover_passes: CoverPasses,
    /// Use the vector (conical) formulation even at β = 0 (twice the size, for checks; default
    /// false: the classical mount splits into TE and TM), in either method.
    pub always_conical: bool,
    /// The method (default [`Method::Auto`]).
    pub method: Method,
    /// The most work one call may do, in the units of [`work`] (default
    /// [`DEFAULT_MAX_WORK`], at most [`MAX_WORK`]): the convergence loop stops with
    /// [`Error::NotConverged`] before a step that would pass it, and [`Solver::solve_at`]
    /// refuses a truncation above it naming `harmonics`.
    pub max_work: f64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            tolerance: DEFAULT_TOLERANCE,
            max_harmonics: DEFAULT_MAX_HARMONICS,
            slabs: None,
            extrapolation: Extrapolation::Richardson,
            cover_passes: CoverPasses::Multiple,
            always_conical: false,
            method: Method::Auto,
            max_work: DEFAULT_MAX_WORK,
        }
    }
}

/// The work of one solve at `harmonics` (N) in arbitrary units, proportional to its
/// eigenproblems' and matrix products' O(N³) cost: N³ per slab for the Fourier modal method
/// in the classical mount (at least one: a flat surface's layers are diagonal, a lamellar
/// profile is one slab), 2.5·N³ per slab in the conical mount, 4·N³ for the C method in either
/// mount. The factors are the measured ratios of single solves at 1601 harmonics (lamellar
/// classical 103 s, conical 252 s; the C method 387 s classical, 315 s conical; fmm/README.md).
#[must_use]
pub fn work(harmonics: usize, slabs: usize, conical: bool, c_method: bool) -> f64 {
    let n3 = (harmonics as f64).powi(3);
    if c_method {
        4.0 * n3
    } else {
        let per_slab = if conical { 2.5 } else { 1.0 };
        per_slab * slabs.max(1) as f64 * n3
    }
}

/// One propagating reflected order in air.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Order {
    /// The order m.
    pub m: i32,
    /// αₘ = α + mλ/d, the direction cosine across the grooves of the order in air.
    pub alpha: f64,
    /// The efficiency for TE (s) incidence: E perpendicular to the plane of incidence (along the
    /// grooves in the classical mount). Summed over the reflected polarisations.
    pub te: f64,
    /// The efficiency for TM (p) incidence: E in the plane of incidence.
    pub tm: f64,
}

impl Order {
    /// The mean of the two: unpolarised incident light.
    #[must_use]
    pub fn unpolarised(&self) -> f64 {
        0.5 * (self.te + self.tm)
    }
}

/// A converged (or fixed-truncation) solve.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// The propagating reflected orders in air, by increasing m.
    pub orders: Vec<Order>,
    /// The harmonic count of the last solve.
    pub harmonics: usize,
    /// The slabs of the staircase (0 for a flat surface).
    pub slabs: usize,
    /// The error estimate: the largest change of any order's efficiency between the last two
    /// steps (of the extrapolations, where extrapolated); NaN for a fixed-truncation solve.
    /// Plain values converging like 1/N may still be about twice this from the limit.
    pub error: f64,
    /// Whether some values are extrapolated in 1/N.
    pub extrapolated: bool,
    /// Total transmitted efficiency into a lossless substrate (TE, TM), when the substrate is
    /// lossless and there is no cover; `None` otherwise.
    pub transmitted: Option<(f64, f64)>,
}

impl Solution {
    /// The order m, if it propagates.
    #[must_use]
    pub fn order(&self, m: i32) -> Option<&Order> {
        self.orders.iter().find(|o| o.m == m)
    }
    /// Σ over orders of the TE and TM efficiencies.
    #[must_use]
    pub fn total(&self) -> (f64, f64) {
        self.orders
            .iter()
            .fold((0.0, 0.0), |(a, b), o| (a + o.te, b + o.tm))
    }
}

/// The rigorous solver (Fourier modal method with Li's factorisation rules).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Solver {
    options: Options,
}

pub(crate) fn odd(n: f64) -> usize {
    let n = n.ceil() as usize;
    if n % 2 == 1 {
        n
    } else {
        n + 1
    }
}

impl Solver {
    /// A solver with the given options; errors name `tolerance`, `max_harmonics` or `slabs`.
    pub fn new(options: Options) -> Result<Solver, Error> {
        if !(options.tolerance.is_finite() && options.tolerance >= 1e-9 && options.tolerance <= 0.5)
        {
            return Err(Error::invalid(
                "tolerance",
                options.tolerance,
                "in [1e-9, 0.5]",
            ));
        }
        if !(3..=MAX_HARMONICS).contains(&options.max_harmonics) {
            return Err(Error::invalid(
                "max_harmonics",
                options.max_harmonics as f64,
                "in [3, 1601]",
            ));
        }
        if let Some(s) = options.slabs {
            if !(1..=MAX_SLABS).contains(&s) {
                return Err(Error::invalid("slabs", s as f64, "in [1, 400]"));
            }
        }
        if !(options.max_work > 0.0 && options.max_work <= MAX_WORK) {
            return Err(Error::invalid("max_work", options.max_work, "in (0, 1e11]"));
        }
        Ok(Solver { options })
    }

    /// The options.
    #[must_use]
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Whether this solve goes to the C method (see [`Method`]); an explicit
    /// [`Method::CMethod`] on an input it cannot take (lamellar, multilevel) is an error naming
    /// `depth_nm`.
    pub fn uses_cmethod(&self, g: &Grating, _inc: &Incidence) -> Result<bool, Error> {
        let continuous = Surface::of(g).is_some() && !matches!(g.profile, Profile::Flat);
        match self.options.method {
            Method::Fmm => Ok(false),
            Method::Auto => Ok(continuous),
            Method::CMethod => {
                if Surface::of(g).is_none() {
                    return Err(Error::invalid(
                        "depth_nm",
                        g.depth_nm(),
                        "on a continuous profile for the C method (sinusoid, sawtooth, Fourier, sampled, flat)",
                    ));
                }
                Ok(true)
            }
        }
    }

    fn slabs_for(&self, g: &Grating, inc: &Incidence) -> usize {
        if g.depth_nm() == 0.0 {
            0
        } else if g.is_smooth() {
            self.options
                .slabs
                .unwrap_or_else(|| g.default_slabs(inc.wavelength_nm))
        } else {
            g.slabs(1).len()
        }
    }

    fn check(&self, g: &Grating, inc: &Incidence, harmonics: usize) -> Result<(), Error> {
        g.validate()?;
        let n_c = g.cover_index_at(inc.wavelength_nm)?;
        // Orders propagating in the cover: they must fit in the truncation with margin.
        let prop = 2.0 * n_c * g.period_nm / inc.wavelength_nm + 1.0;
        if prop + 2.0 > harmonics as f64 {
            return Err(Error::invalid("period_nm", g.period_nm, PERIOD_REQUIREMENT));
        }
        Ok(())
    }

    /// One solve at a fixed odd harmonic count (an even count is raised by one), no convergence
    /// loop; `Solution::error` is NaN. A result whose TE or TM sum over orders exceeds 1 by
    /// more than [`ENERGY_SLACK`] is [`Error::Numerical`] (an ill-conditioned solve).
    pub fn solve_at(
        &self,
        g: &Grating,
        inc: Incidence,
        harmonics: usize,
    ) -> Result<Solution, Error> {
        physical(self.solve_at_unchecked(g, inc, harmonics)?)
    }

    fn solve_at_unchecked(
        &self,
        g: &Grating,
        inc: Incidence,
        harmonics: usize,
    ) -> Result<Solution, Error> {
        if !(3..=MAX_HARMONICS).contains(&harmonics) {
            return Err(Error::invalid(
                "harmonics",
                harmonics as f64,
                "in [3, 1601]",
            ));
        }
        let nh = odd(harmonics as f64);
        self.check(g, &inc, nh)?;
        let conical = inc.beta != 0.0 || self.options.always_conical;
        let c_method = self.uses_cmethod(g, &inc)?;
        let slabs = if c_method { 0 } else { self.slabs_for(g, &inc) };
        if work(nh, slabs, conical, c_method) > self.options.max_work {
            return Err(Error::invalid(
                "harmonics",
                nh as f64,
                "within the options' max_work (fmm::work: about N³ per slab)",
            ));
        }
        if c_method {
            let raw = cmethod::solve_raw(g, &inc, nh, &self.options)?;
            return Ok(Solution {
                orders: raw.orders,
                harmonics: nh,
                slabs: 0,
                error: f64::NAN,
                extrapolated: false,
                transmitted: raw.transmitted,
            });
        }
        let raw = solve_raw(g, &inc, nh, slabs, &self.options)?;
        Ok(Solution {
            orders: raw.orders,
            harmonics: nh,
            slabs,
            error: f64::NAN,
            extrapolated: false,
            transmitted: raw.transmitted,
        })
    }

    /// Solves to the options' tolerance: the harmonic count starts at max(21, 4·n·d/λ + 11) and
    /// grows ×1.5 until two successive steps agree (or, extrapolated, three successive
    /// extrapolations); [`Error::NotConverged`] at the harmonic cap, or before a step that would
    /// take the call's [`work`] past `Options::max_work` (a first step past it is an error
    /// naming `slabs`, or `harmonics` for the C method). A result whose TE or TM sum over
    /// orders exceeds 1 by more than [`ENERGY_SLACK`] is [`Error::Numerical`].
    pub fn solve(&self, g: &Grating, inc: Incidence) -> Result<Solution, Error> {
        physical(self.solve_unchecked(g, inc)?)
    }

    fn solve_unchecked(&self, g: &Grating, inc: Incidence) -> Result<Solution, Error> {
        let cap = self.options.max_harmonics;
        self.check(g, &inc, cap)?;
        let n_c = g.cover_n(inc.wavelength_nm);
        if self.uses_cmethod(g, &inc)? {
            let nh = cmethod::first_harmonics(g, &inc);
            if odd(nh as f64 * GROWTH) > cap {
                return Err(Error::invalid("period_nm", g.period_nm, PERIOD_REQUIREMENT));
            }
            return cmethod::solve(g, &inc, &self.options);
        }
        let slabs = self.slabs_for(g, &inc);
        let tol = self.options.tolerance;
        let nh =
            odd((MIN_HARMONICS as f64).max(4.0 * n_c * g.period_nm / inc.wavelength_nm + 11.0));
        if odd(odd(nh as f64 * GROWTH) as f64 * GROWTH) > cap {
            return Err(Error::invalid("period_nm", g.period_nm, PERIOD_REQUIREMENT));
        }
        let conical = inc.beta != 0.0 || self.options.always_conical;
        let extrap = self.options.extrapolation == Extrapolation::Richardson && slabs > 0;
        let max_work = self.options.max_work;
        let mut done = work(nh, slabs, conical, false);
        if done > max_work {
            return Err(Error::invalid(
                "slabs",
                slabs as f64,
                "few enough that the first step fits the options' max_work (fmm::work)",
            ));
        }
        let mut prev = solve_raw(g, &inc, nh, slabs, &self.options)?;
        let mut prev_n = nh;
        let mut prev_ext: Option<Vec<Order>> = None;
        let mut prev_ext_change = f64::INFINITY;
        let mut prev_plain_change = f64::INFINITY;
        let mut change = f64::NAN;
        let mut plain_done: Option<Solution> = None;
        loop {
            let next = odd(prev_n as f64 * GROWTH);
            let step = work(next, slabs, conical, false);
            if next > cap || done + step > max_work {
                // Extrapolations that never agreed, over plain steps that did: the plain values.
                if let Some(plain) = plain_done.take() {
                    return Ok(plain);
                }
                return Err(Error::NotConverged {
                    harmonics: prev_n,
                    change,
                    tolerance: tol,
                });
            }
            let cur = solve_raw(g, &inc, next, slabs, &self.options)?;
            done += step;
            let plain = max_change(&prev.orders, &cur.orders);
            // The fallback, too, takes two successive agreements (at s = −0.4, 360 nm on the
            // `dvd` preset, one plain agreement at 135 harmonics was 1.2e-3 off the limit).
            if plain < tol && (!extrap || prev_plain_change < tol) {
                plain_done = Some(Solution {
                    orders: cur.orders.clone(),
                    harmonics: next,
                    slabs,
                    error: plain,
                    extrapolated: false,
                    transmitted: cur.transmitted,
                });
            }
            if !extrap {
                change = plain;
                if plain < tol {
                    return Ok(Solution {
                        orders: cur.orders,
                        harmonics: next,
                        slabs,
                        error: plain,
                        extrapolated: false,
                        transmitted: cur.transmitted,
                    });
                }
            } else {
                if prev_ext.is_none() {
                    change = plain;
                }
                let ext = richardson(&prev.orders, prev_n, &cur.orders, next, conical);
                if let Some(pe) = &prev_ext {
                    let ch =
                        max_change(pe, &ext).max(max_change_te(&prev.orders, &cur.orders, conical));
                    change = ch;
                    // Two successive agreements: a single one can be a chance crossing of a
                    // sequence not yet in its 1/N regime (examples/convergence.rs: on 49 nodes
                    // of the `dvd` grating one agreement stopped up to 9.1× the tolerance from
                    // the limit at 1e-3, two at most 1.14×; at 2.5e-4, 4.55× against 0.63×).
                    if ch < tol && prev_ext_change < tol {
                        return Ok(Solution {
                            orders: ext,
                            harmonics: next,
                            slabs,
                            error: ch.max(prev_ext_change),
                            extrapolated: true,
                            transmitted: cur.transmitted,
                        });
                    }
                }
                if prev_ext.is_some() {
                    prev_ext_change = change;
                }
                prev_plain_change = plain;
                prev_ext = Some(ext);
            }
            prev = cur;
            prev_n = next;
        }
    }
}

/// How far a solution's TE or TM sum over the reflected orders may exceed 1 (the incident
/// power) before the solve is refused as [`Error::Numerical`]: a passive grating reflects at
/// most what it receives, so more is the method's ill-conditioning, not truncation noise. The
/// C method on a sinusoid of aspect 2 (d = 1000 nm, h = 2000 nm, Al, λ = 5 µm, s = 0.3) at 101
/// harmonics gave Σ TE = 1.17; of aspect 10 at λ = 20 µm, Σ TM = 1.92.
pub const ENERGY_SLACK: f64 = 1e-3;

/// `sol`, or [`Error::Numerical`] where its TE or TM sum exceeds 1 + [`ENERGY_SLACK`].
fn physical(sol: Solution) -> Result<Solution, Error> {
    let (te, tm) = sol.total();
    if te > 1.0 + ENERGY_SLACK || tm > 1.0 + ENERGY_SLACK {
        return Err(Error::Numerical(
            "the reflected orders carry more than the incident power (an ill-conditioned \
             solve: too deep a profile for the harmonic count?)",
        ));
    }
    Ok(sol)
}

pub(crate) fn max_change(a: &[Order], b: &[Order]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.te - y.te).abs().max((x.tm - y.tm).abs()))
        .fold(0.0, f64::max)
}

/// The plain change of the values that are not extrapolated (TE in the classical mount).
fn max_change_te(a: &[Order], b: &[Order], conical: bool) -> f64 {
    if conical {
        return 0.0;
    }
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.te - y.te).abs())
        .fold(0.0, f64::max)
}

fn richardson(a: &[Order], na: usize, b: &[Order], nb: usize, conical: bool) -> Vec<Order> {
    let (na, nb) = (na as f64, nb as f64);
    let ext = |x: f64, y: f64| ((nb * y - na * x) / (nb - na)).max(0.0);
    a.iter()
        .zip(b)
        .map(|(x, y)| Order {
            m: y.m,
            alpha: y.alpha,
            te: if conical { ext(x.te, y.te) } else { y.te },
            tm: ext(x.tm, y.tm),
        })
        .collect()
}

pub(crate) struct Raw {
    pub orders: Vec<Order>,
    pub transmitted: Option<(f64, f64)>,
}

/// Fresnel power reflectances (s, p) of a flat interface between real indices, light from n1 at
/// sin θ₁ = `s1` (1 beyond the critical angle).
pub(crate) fn fresnel_real(n1: f64, n2: f64, s1: f64) -> (f64, f64) {
    let c1 = (1.0 - s1 * s1).max(0.0).sqrt();
    let s2 = n1 * s1 / n2;
    if s2 >= 1.0 {
        return (1.0, 1.0);
    }
    let c2 = (1.0 - s2 * s2).sqrt();
    let rs = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2);
    let rp = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
    (rs * rs, rp * rp)
}

/// Moves α off a Rayleigh line (an order grazing in the superstrate or a lossless substrate,
/// where kz = 0 would divide) by a few 1e-9.
pub(crate) fn off_rayleigh(alpha: f64, beta: f64, step: f64, media: &[f64]) -> f64 {
    let mut a = alpha;
    let m_max = (2.0 / step).ceil() as i64 + 2;
    for _ in 0..4 {
        let bad = (-m_max..=m_max).any(|m| {
            let am = a + m as f64 * step;
            media
                .iter()
                .any(|&n| (n * n - am * am - beta * beta).abs() < 1e-10)
        });
        if !bad {
            break;
        }
        a += 2e-9;
    }
    a
}

fn solve_raw(
    g: &Grating,
    inc: &Incidence,
    nh: usize,
    slabs: usize,
    opt: &Options,
) -> Result<Raw, Error> {
    let passes = opt.cover_passes;
    let lambda = inc.wavelength_nm;
    let (n, k) = g.metal.index(lambda);
    let eps_m = c64::new(n, k) * c64::new(n, k);
    let n_c = g.cover_n(lambda);
    let eps_c = c64::new(n_c * n_c, 0.0);
    let step = lambda / g.period_nm;
    let mut media = vec![n_c];
    if k == 0.0 {
        media.push(n);
    }
    let alpha = off_rayleigh(inc.alpha, inc.beta, step, &media);
    let beta = inc.beta;
    let mm = (nh / 2) as i64;
    let kx: Vec<f64> = (-mm..=mm).map(|m| alpha + m as f64 * step).collect();
    let k0 = core::f64::consts::TAU / lambda;
    let geometry = g.slabs(slabs.max(1));
    let pols: &[Pol] = if beta == 0.0 && !opt.always_conical {
        &[Pol::Te, Pol::Tm]
    } else {
        &[Pol::Conical]
    };
    // Power matrices per polarisation set, and the channels.
    let mut results: Vec<(Vec<Channel>, Vec<Vec<f64>>)> = Vec::new();
    let mut transmitted = [0.0f64; 2];
    let want_t = k == 0.0 && g.cover.is_none();
    for &pol in pols {
        let lat = Lattice {
            kx: kx.clone(),
            beta,
            pol,
        };
        let mut layers = vec![modal::homogeneous(&lat, eps_c)];
        let mut thickness = vec![0.0];
        for s in &geometry {
            layers.push(modal::slab(&lat, &s.ridges, eps_c, eps_m)?);
            thickness.push(k0 * s.thickness_nm);
        }
        layers.push(modal::homogeneous(&lat, eps_m));
        thickness.push(0.0);
        let stack = Stack { layers, thickness };
        let refl = modal::reflect(&stack, want_t)?;
        let chans = channels(&lat, n_c, inc.phi);
        let size = lat.size();
        let sup = &stack.layers[0];
        // Basis matrix of the channels and their unit fluxes.
        let mut b = Mat::<c64>::zeros(size, chans.len());
        for (c, ch) in chans.iter().enumerate() {
            for &(i, v) in &ch.basis {
                b[(i, c)] = c64::new(v, 0.0);
            }
        }
        let fl: Vec<f64> = chans.iter().map(|ch| unit_flux(&lat, &sup.v, ch)).collect();
        let rb = &refl.r * &b;
        let mut pm = vec![vec![0.0; chans.len()]; chans.len()];
        for (o, cho) in chans.iter().enumerate() {
            for c in 0..chans.len() {
                let amp: c64 = cho.basis.iter().map(|&(i, v)| rb[(i, c)] * v).sum();
                pm[o][c] = amp.norm_sqr() * fl[o] / fl[c];
            }
        }
        if want_t {
            let sub = &stack.layers[stack.layers.len() - 1];
            for (c, ch) in chans
                .iter()
                .enumerate()
                .filter(|(_, c)| c.order == mm as usize)
            {
                let mut d = Mat::<c64>::zeros(size, 1);
                for &(i, v) in &ch.basis {
                    d[(i, 0)] = c64::new(v, 0.0);
                }
                let dt = modal::transmit(&stack, &refl, &d);
                let h = &sub.v * &dt;
                let e: Vec<c64> = (0..size).map(|i| dt[(i, 0)]).collect();
                let hv: Vec<c64> = (0..size).map(|i| h[(i, 0)]).collect();
                // Downward flux of the substrate's propagating orders over the incident flux.
                let t: f64 = (0..lat.harmonics())
                    .filter(|&i| modal::kz(eps_m, kx[i], beta).im.abs() < 1e-12)
                    .map(|i| modal::flux(&lat, &e, &hv, i))
                    .sum();
                transmitted[ch.pol] = t / fl[c];
            }
        }
        results.push((chans, pm));
    }
    // The incident channels (order M; s = TE, p = TM) and the air-side passes.
    let mut orders: Vec<Order> = Vec::new();
    for (i, &a) in kx.iter().enumerate() {
        if a * a + beta * beta < 1.0 {
            orders.push(Order {
                m: i as i32 - mm as i32,
                alpha: a,
                te: 0.0,
                tm: 0.0,
            });
        }
    }
    let q_inc = (alpha * alpha + beta * beta).sqrt();
    for (chans, pm) in &results {
        for (inc_pol, target) in [(0usize, 0usize), (1, 1)] {
            let Some(c_in) = chans
                .iter()
                .position(|c| c.order == mm as usize && c.pol == inc_pol)
            else {
                continue;
            };
            let eta = through_cover(
                chans,
                pm,
                c_in,
                n_c,
                q_inc,
                beta,
                &kx,
                g.cover.is_some(),
                passes,
            );
            for (c, ch) in chans.iter().enumerate() {
                let a = kx[ch.order];
                if a * a + beta * beta < 1.0 {
                    let m = ch.order as i32 - mm as i32;
                    if let Some(o) = orders.iter_mut().find(|o| o.m == m) {
                        if target == 0 {
                            o.te += eta[c];
                        } else {
                            o.tm += eta[c];
                        }
                    }
                }
            }
        }
    }
    if orders
        .iter()
        .any(|o| !(o.te.is_finite() && o.tm.is_finite()))
    {
        return Err(Error::Numerical("a non-finite efficiency"));
    }
    Ok(Raw {
        orders,
        transmitted: want_t.then_some((transmitted[0], transmitted[1])),
    })
}

/// A propagating plane wave in the superstrate: order index, polarisation (0 = s, 1 = p) and its
/// unit tangential E as (component index, value) pairs.
pub(crate) struct Channel {
    order: usize,
    pol: usize,
    basis: Vec<(usize, f64)>,
}

impl Channel {
    /// A classical-mount channel: harmonic index `order`, polarisation `pol` (0 = TE, 1 = TM).
    pub(crate) fn scalar(order: usize, pol: usize) -> Channel {
        Channel {
            order,
            pol,
            basis: vec![(order, 1.0)],
        }
    }
}

fn channels(lat: &Lattice, n_c: f64, phi: f64) -> Vec<Channel> {
    let n = lat.harmonics();
    let b = lat.beta;
    let mut out = Vec::new();
    for i in 0..n {
        let a = lat.kx[i];
        if a * a + b * b >= n_c * n_c {
            continue;
        }
        match lat.pol {
            Pol::Te => out.push(Channel {
                order: i,
                pol: 0,
                basis: vec![(i, 1.0)],
            }),
            Pol::Tm => out.push(Channel {
                order: i,
                pol: 1,
                basis: vec![(i, 1.0)],
            }),
            Pol::Conical => {
                let q = (a * a + b * b).sqrt();
                let (c, s) = if q > 0.0 {
                    (a / q, b / q)
                } else {
                    (phi.cos(), phi.sin())
                };
                out.push(Channel {
                    order: i,
                    pol: 0,
                    basis: vec![(i, -s), (n + i, c)],
                });
                out.push(Channel {
                    order: i,
                    pol: 1,
                    basis: vec![(i, c), (n + i, s)],
                });
            }
        }
    }
    out
}

fn unit_flux(lat: &Lattice, v: &Mat<c64>, ch: &Channel) -> f64 {
    let size = lat.size();
    let mut e = vec![c64::new(0.0, 0.0); size];
    for &(i, val) in &ch.basis {
        e[i] = c64::new(val, 0.0);
    }
    let h: Vec<c64> = (0..size)
        .map(|r| ch.basis.iter().map(|&(i, val)| v[(r, i)] * val).sum())
        .collect();
    modal::flux(lat, &e, &h, ch.order)
}

/// The efficiencies in air of every channel for incident channel `c_in`: without a cover the
/// power matrix's column; with one, the Fresnel passes through its top surface (single pass, or
/// the incoherent sum of all passes).
#[allow(clippy::too_many_arguments)]
pub(crate) fn through_cover(
    chans: &[Channel],
    pm: &[Vec<f64>],
    c_in: usize,
    n_c: f64,
    q_inc: f64,
    beta: f64,
    kx: &[f64],
    cover: bool,
    passes: CoverPasses,
) -> Vec<f64> {
    let nc = chans.len();
    if !cover {
        return (0..nc).map(|o| pm[o][c_in]).collect();
    }
    let pol_of = |c: usize, r: (f64, f64)| if chans[c].pol == 0 { r.0 } else { r.1 };
    let r_in = pol_of(c_in, fresnel_real(1.0, n_c, q_inc));
    // Internal reflectance of the top surface for each channel (1 when totally reflected).
    let r_int: Vec<f64> = chans
        .iter()
        .enumerate()
        .map(|(c, ch)| {
            let a = kx[ch.order];
            let q = (a * a + beta * beta).sqrt();
            pol_of(c, fresnel_real(n_c, 1.0, q / n_c))
        })
        .collect();
    // Power going down onto the grating, per channel.
    let mut down = vec![0.0; nc];
    down[c_in] = 1.0 - r_in;
    let up: Vec<f64> = match passes {
        CoverPasses::Single => (0..nc).map(|o| pm[o][c_in] * down[c_in]).collect(),
        CoverPasses::Multiple => {
            // up = G·down_total, down_total = down + D·up  ⇒  (I − G·D)·up = G·down.
            let mut m = Mat::<f64>::zeros(nc, nc);
            let mut rhs = Mat::<f64>::zeros(nc, 1);
            for o in 0..nc {
                for c in 0..nc {
                    m[(o, c)] = if o == c { 1.0 } else { 0.0 } - pm[o][c] * r_int[c];
                }
                rhs[(o, 0)] = pm[o][c_in] * down[c_in];
            }
            let x = faer::linalg::solvers::Solve::solve(&m.partial_piv_lu(), &rhs);
            (0..nc).map(|o| x[(o, 0)].max(0.0)).collect()
        }
    };
    let mut out: Vec<f64> = (0..nc).map(|o| up[o] * (1.0 - r_int[o])).collect();
    out[c_in] += r_in;
    out
}
