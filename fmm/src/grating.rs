//! The grating (period, profile, metal, cover) and the incident plane wave, validated, and the
//! profile's staircase: the slabs and, in each, where the metal is.

use diffraction::relief::Metal;

use crate::error::{check_range, Error};

/// Largest period accepted, nm (0.1 mm: far above any visible-light grating).
pub const MAX_PERIOD_NM: f64 = 1e5;
/// Smallest period accepted, nm (below any ruled or holographic grating: λ/d ≤ 2·10⁴ over
/// [`WAVELENGTH_RANGE_NM`]). Far below it the evanescent orders' k_z ~ m·λ/d overflow the
/// methods' arithmetic: periods of 10⁻¹⁰ nm gave Σ η of 3.4 to 202 from the Fourier modal
/// method, 10⁻¹⁰⁰ nm 1.3·10³⁷ from the C method; at 10⁻² nm and above every probe stayed
/// below 1.
pub const MIN_PERIOD_NM: f64 = 1.0;
/// Largest profile depth accepted, nm, and at most [`MAX_ASPECT`] periods.
pub const MAX_DEPTH_NM: f64 = 1e5;
/// Largest depth / period accepted.
pub const MAX_ASPECT: f64 = 10.0;
/// Wavelengths accepted, nm.
pub const WAVELENGTH_RANGE_NM: (f64, f64) = (100.0, 20_000.0);
/// Largest incidence angle θ accepted (89.9°: grazing incidence carries no z-flux).
pub const MAX_THETA: f64 = 89.9 * core::f64::consts::PI / 180.0;
/// Thinnest cover accepted, nm. The cover is treated incoherently (its thickness is far above
/// the light's coherence length), which a film of a few wavelengths is not.
pub const MIN_COVER_THICKNESS_NM: f64 = 10_000.0;
/// Cover refractive indices accepted: (1, 4].
pub const MAX_COVER_INDEX: f64 = 4.0;
/// Most slabs a profile may be cut into, and most levels of a multilevel profile.
pub const MAX_SLABS: usize = 400;
/// Most samples of a sampled profile and most Fourier terms.
pub const MAX_SAMPLES: usize = 65_536;
/// Points at which a Fourier-series profile is sampled (piecewise linear between them).
pub const FOURIER_SAMPLES: usize = 2048;

/// A level of a multilevel profile: a slab of the given thickness in which the metal fills the
/// intervals `ridges` (fractions of the period, each `0 <= start < end <= 1`).
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// Thickness of the slab, nm.
    pub thickness_nm: f64,
    /// The metal's intervals across the period, as fractions of it.
    pub ridges: Vec<(f64, f64)>,
}

/// The relief profile z(x) of one period (x across the grooves), metal below it.
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    /// A flat surface (the Fresnel case).
    Flat,
    /// Raised metal ridges of width `duty`·d (from x = 0) and height `depth_nm`.
    Lamellar {
        /// Ridge width over period, in (0, 1).
        duty: f64,
        /// Ridge height, nm.
        depth_nm: f64,
    },
    /// Stacked slabs, top first (each its own ridges).
    Multilevel(Vec<Level>),
    /// z = (h/2)·sin(2πx/d), h = `depth_nm` peak-to-valley; staircased.
    Sinusoid {
        /// Peak-to-valley depth, nm.
        depth_nm: f64,
    },
    /// The 90°-apex triangle of a ruled grating (python_ref's geometry): the long facet of slope
    /// `blaze` falls from z = h at x = 0 to 0 at x = d·cos²(blaze), the short facet rises back;
    /// h = d·sin(blaze)·cos(blaze). Blazes into positive orders for θ < 0 (α < 0). Staircased.
    Sawtooth {
        /// Blaze angle, radians, in (0, π/4).
        blaze: f64,
    },
    /// z(x) = Σₖ cosₖ·cos(2πkx/d) + sinₖ·sin(2πkx/d), k = 1, 2, ... (nm); sampled on
    /// [`FOURIER_SAMPLES`] points and staircased.
    Fourier {
        /// Cosine coefficients for k = 1, 2, ..., nm.
        cos: Vec<f64>,
        /// Sine coefficients for k = 1, 2, ..., nm.
        sin: Vec<f64>,
    },
    /// Heights z(xᵢ) at xᵢ = i·d/n, i = 0..n, nm, linear between samples and periodic;
    /// staircased.
    Sampled(Vec<f64>),
}

/// Largest Sellmeier coefficient `b` of a cover accepted.
pub const MAX_SELLMEIER_B: f64 = 10.0;
/// Largest Sellmeier pole `c` of a cover accepted, µm² (a pole at 1 µm).
pub const MAX_SELLMEIER_C_UM2: f64 = 1.0;

/// The real refractive index of a cover: a constant, or a one-term Sellmeier dispersion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CoverIndex {
    /// The same index at every wavelength, in (1, [`MAX_COVER_INDEX`]].
    Constant(f64),
    /// n(λ)² = 1 + b·λ²/(λ² − c), λ in µm: `b` in (0, [`MAX_SELLMEIER_B`]], `c_um2` in
    /// [0, [`MAX_SELLMEIER_C_UM2`]]. A solve needs n(λ) in (1, [`MAX_COVER_INDEX`]] at its
    /// wavelength (not near or below the pole λ = √c): else an error names `cover.index`.
    Sellmeier {
        /// The oscillator strength.
        b: f64,
        /// The pole, µm².
        c_um2: f64,
    },
}

impl CoverIndex {
    /// Polycarbonate: N. Sultanova, S. Kasarova and I. Nikolov, "Dispersion properties of
    /// optical polymers", Acta Physica Polonica A 116, 585 (2009), fitted over 0.437-1.052 µm
    /// (extrapolated below)
    /// (n = 1.642 at 360 nm, 1.589 at 550 nm, 1.570 at 830 nm); `python_ref/fmm.py`'s and the
    /// presets' cover.
    pub const POLYCARBONATE: CoverIndex = CoverIndex::Sellmeier {
        b: 1.4182,
        c_um2: 0.021304,
    };

    /// The index at `lambda_nm`; `None` where a Sellmeier index is undefined (λ not finite and
    /// positive, or at or below its pole λ = √c; [`Grating`]'s solves refuse that naming
    /// `cover.index`). A Constant is returned as it is. Evaluated as
    /// n² = 1 + b / (1 − c/λ²), finite for every λ above the pole (1 + b as λ grows without bound).
    #[must_use]
    pub fn at(&self, lambda_nm: f64) -> Option<f64> {
        match *self {
            CoverIndex::Constant(n) => Some(n),
            CoverIndex::Sellmeier { b, c_um2 } => {
                if !(lambda_nm.is_finite() && lambda_nm > 0.0) {
                    return None;
                }
                let l_um = lambda_nm * 1e-3;
                // c/λ² in two divisions: no overflow of λ² for large λ.
                let q = 1.0 - c_um2 / l_um / l_um;
                (q > 0.0).then(|| (1.0 + b / q).sqrt())
            }
        }
    }
}

/// A dielectric cover over the grating (a CD's or DVD's polycarbonate, a foil's lacquer): light
/// enters it from air through a flat surface, is diffracted by the grating inside it, and leaves
/// through the surface again. The cover is thick (incoherent: powers add, not amplitudes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cover {
    /// Real refractive index, constant or dispersive ([`CoverIndex::POLYCARBONATE`]), in
    /// (1, [`MAX_COVER_INDEX`]] at every solved wavelength.
    pub index: CoverIndex,
    /// Thickness, nm, at least [`MIN_COVER_THICKNESS_NM`] (a CD's is 1.2 mm).
    pub thickness_nm: f64,
}

/// A 1-D periodic relief grating: period, profile, the metal below the profile (any
/// [`Metal`], a lossless dielectric included), and an optional cover.
#[derive(Debug, Clone, PartialEq)]
pub struct Grating {
    /// Period d, nm.
    pub period_nm: f64,
    /// The profile of one period.
    pub profile: Profile,
    /// The material below the profile (and of the ridges).
    pub metal: Metal,
    /// An optional dielectric cover; `None`: the grating is in air.
    pub cover: Option<Cover>,
}

/// The incident plane wave: direction cosines in air α = sin θ·cos φ across the grooves and
/// β = sin θ·sin φ along them (of the direction of travel), the azimuth φ (which fixes s and p at
/// normal incidence), and the wavelength in vacuum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Incidence {
    pub(crate) alpha: f64,
    pub(crate) beta: f64,
    pub(crate) phi: f64,
    pub(crate) wavelength_nm: f64,
}

impl Incidence {
    /// Polar angle θ from the normal (in air), azimuth φ from the grating vector (φ = 0: the
    /// classical mount), wavelength in vacuum. Errors name `theta`, `phi` or `wavelength_nm`.
    pub fn new(theta: f64, phi: f64, wavelength_nm: f64) -> Result<Incidence, Error> {
        if !(theta.is_finite() && (0.0..=MAX_THETA).contains(&theta)) {
            return Err(Error::invalid("theta", theta, "in [0, 89.9°] (radians)"));
        }
        if !(phi.is_finite() && phi.abs() <= 4.0 * core::f64::consts::PI) {
            return Err(Error::invalid("phi", phi, "finite, |phi| <= 4π (radians)"));
        }
        let wavelength_nm = check_wavelength(wavelength_nm)?;
        let s = theta.sin();
        Ok(Incidence {
            alpha: s * phi.cos(),
            beta: s * phi.sin(),
            phi,
            wavelength_nm,
        })
    }

    /// The classical mount (φ = 0) at sin θ = `sin_theta` (negative: light from the +x side).
    pub fn classical(sin_theta: f64, wavelength_nm: f64) -> Result<Incidence, Error> {
        Incidence::from_cosines(sin_theta, 0.0, wavelength_nm)
    }

    /// From the direction cosines (α, β) in air, α² + β² ≤ sin²(89.9°). Errors name `alpha`,
    /// `beta` (the larger of the two when only their sum of squares is too large) or `wavelength_nm`.
    pub fn from_cosines(alpha: f64, beta: f64, wavelength_nm: f64) -> Result<Incidence, Error> {
        if !alpha.is_finite() || alpha.abs() > 1.0 {
            return Err(Error::invalid("alpha", alpha, "finite, |alpha| < 1"));
        }
        if !beta.is_finite() || beta.abs() > 1.0 {
            return Err(Error::invalid("beta", beta, "finite, |beta| < 1"));
        }
        let s2 = alpha * alpha + beta * beta;
        if s2.sqrt() > MAX_THETA.sin() {
            // Name the larger cosine: the one a caller most likely got wrong.
            return Err(if beta.abs() > alpha.abs() {
                Error::invalid(
                    "beta",
                    beta,
                    "with alpha, sqrt(alpha² + beta²) <= sin(89.9°)",
                )
            } else {
                Error::invalid(
                    "alpha",
                    alpha,
                    "with beta, sqrt(alpha² + beta²) <= sin(89.9°)",
                )
            });
        }
        let wavelength_nm = check_wavelength(wavelength_nm)?;
        let phi = if s2 > 0.0 { beta.atan2(alpha) } else { 0.0 };
        Ok(Incidence {
            alpha,
            beta,
            phi,
            wavelength_nm,
        })
    }

    /// α = sin θ·cos φ, the direction cosine across the grooves.
    #[must_use]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// β = sin θ·sin φ, the direction cosine along the grooves.
    #[must_use]
    pub fn beta(&self) -> f64 {
        self.beta
    }
    /// The azimuth φ.
    #[must_use]
    pub fn phi(&self) -> f64 {
        self.phi
    }
    /// The wavelength in vacuum, nm.
    #[must_use]
    pub fn wavelength_nm(&self) -> f64 {
        self.wavelength_nm
    }
}

fn check_wavelength(w: f64) -> Result<f64, Error> {
    let (lo, hi) = WAVELENGTH_RANGE_NM;
    if w.is_finite() && (lo..=hi).contains(&w) {
        Ok(w)
    } else {
        Err(Error::invalid("wavelength_nm", w, "in [100, 20000] nm"))
    }
}

/// One slab of the staircase: thickness and the metal's intervals (fractions of the period).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Slab {
    pub thickness_nm: f64,
    pub ridges: Vec<(f64, f64)>,
}

impl Grating {
    /// Checks every field; errors name `period_nm`, `depth_nm`, `duty`, `blaze`, `levels`,
    /// `ridges`, `samples`, `cover.index` or `cover.thickness_nm`.
    pub fn validate(&self) -> Result<(), Error> {
        let d = self.period_nm;
        if !(d.is_finite() && (MIN_PERIOD_NM..=MAX_PERIOD_NM).contains(&d)) {
            return Err(Error::invalid("period_nm", d, "finite, in [1, 1e5] nm"));
        }
        let max_depth = MAX_DEPTH_NM.min(MAX_ASPECT * d);
        let depth = |h: f64| -> Result<(), Error> {
            if h.is_finite() && h >= 0.0 && h <= max_depth {
                Ok(())
            } else {
                Err(Error::invalid(
                    "depth_nm",
                    h,
                    "finite, >= 0, at most 10 periods and 1e5 nm",
                ))
            }
        };
        match &self.profile {
            Profile::Flat => {}
            Profile::Lamellar { duty, depth_nm } => {
                if !(duty.is_finite() && *duty > 0.0 && *duty < 1.0) {
                    return Err(Error::invalid("duty", *duty, "in (0, 1)"));
                }
                depth(*depth_nm)?;
            }
            Profile::Multilevel(levels) => {
                if levels.is_empty() || levels.len() > MAX_SLABS {
                    return Err(Error::invalid(
                        "levels",
                        levels.len() as f64,
                        "between 1 and 400 levels",
                    ));
                }
                let mut total = 0.0;
                for l in levels {
                    depth(l.thickness_nm)?;
                    total += l.thickness_nm;
                    if l.ridges.len() > MAX_SAMPLES {
                        return Err(Error::invalid(
                            "ridges",
                            l.ridges.len() as f64,
                            "at most 65536 intervals",
                        ));
                    }
                    for &(a, b) in &l.ridges {
                        if !(a.is_finite() && b.is_finite() && 0.0 <= a && a < b && b <= 1.0) {
                            return Err(Error::invalid(
                                "ridges",
                                if a.is_finite() { b } else { a },
                                "intervals 0 <= start < end <= 1 (fractions of the period)",
                            ));
                        }
                    }
                }
                depth(total)?;
            }
            Profile::Sinusoid { depth_nm } => depth(*depth_nm)?,
            Profile::Sawtooth { blaze } => {
                if !(blaze.is_finite() && *blaze > 0.0 && *blaze < core::f64::consts::FRAC_PI_4) {
                    return Err(Error::invalid("blaze", *blaze, "in (0, π/4) radians"));
                }
            }
            Profile::Fourier { cos, sin } => {
                if cos.len() + sin.len() > MAX_SAMPLES {
                    return Err(Error::invalid(
                        "samples",
                        (cos.len() + sin.len()) as f64,
                        "at most 65536 Fourier terms",
                    ));
                }
                if let Some(bad) = cos.iter().chain(sin.iter()).find(|c| !c.is_finite()) {
                    return Err(Error::invalid(
                        "samples",
                        *bad,
                        "finite Fourier coefficients",
                    ));
                }
                let z = self.heights();
                depth(span(&z))?;
            }
            Profile::Sampled(z) => {
                if z.len() < 2 || z.len() > MAX_SAMPLES {
                    return Err(Error::invalid(
                        "samples",
                        z.len() as f64,
                        "between 2 and 65536 samples",
                    ));
                }
                if let Some(bad) = z.iter().find(|c| !c.is_finite()) {
                    return Err(Error::invalid("samples", *bad, "finite heights"));
                }
                depth(span(z))?;
            }
        }
        if let Some(c) = &self.cover {
            match c.index {
                CoverIndex::Constant(n) => {
                    check_range("cover.index", n, 1.0, MAX_COVER_INDEX, "finite, in (1, 4]")?;
                }
                CoverIndex::Sellmeier { b, c_um2 } => {
                    check_range(
                        "cover.index.b",
                        b,
                        0.0,
                        MAX_SELLMEIER_B,
                        "finite, in (0, 10]",
                    )?;
                    if !(c_um2.is_finite() && (0.0..=MAX_SELLMEIER_C_UM2).contains(&c_um2)) {
                        return Err(Error::invalid(
                            "cover.index.c_um2",
                            c_um2,
                            "finite, in [0, 1] µm²",
                        ));
                    }
                }
            }
            if !(c.thickness_nm.is_finite()
                && c.thickness_nm >= MIN_COVER_THICKNESS_NM
                && c.thickness_nm <= 1e9)
            {
                return Err(Error::invalid(
                    "cover.thickness_nm",
                    c.thickness_nm,
                    "in [1e4, 1e9] nm (a thick, incoherent cover)",
                ));
            }
        }
        Ok(())
    }

    /// The cover's index at `lambda_nm`, checked: in (1, [`MAX_COVER_INDEX`]] (an error names
    /// `cover.index`); 1 without a cover.
    pub(crate) fn cover_index_at(&self, lambda_nm: f64) -> Result<f64, Error> {
        match &self.cover {
            None => Ok(1.0),
            Some(c) => check_range(
                "cover.index",
                c.index.at(lambda_nm).unwrap_or(f64::NAN),
                1.0,
                MAX_COVER_INDEX,
                "finite, in (1, 4] at the solve's wavelength (a dispersive cover: not at or near its pole)",
            ),
        }
    }

    /// The cover's index at `lambda_nm` (1 without a cover), after [`Grating::cover_index_at`]
    /// has accepted it (NaN where it would not have).
    pub(crate) fn cover_n(&self, lambda_nm: f64) -> f64 {
        self.cover
            .map_or(Some(1.0), |c| c.index.at(lambda_nm))
            .unwrap_or(f64::NAN)
    }

    /// The profile's depth (peak to valley), nm.
    #[must_use]
    pub fn depth_nm(&self) -> f64 {
        match &self.profile {
            Profile::Flat => 0.0,
            Profile::Lamellar { depth_nm, .. } | Profile::Sinusoid { depth_nm } => *depth_nm,
            Profile::Multilevel(l) => l.iter().map(|l| l.thickness_nm).sum(),
            Profile::Sawtooth { blaze } => self.period_nm * blaze.sin() * blaze.cos(),
            Profile::Fourier { .. } | Profile::Sampled(_) => span(&self.heights()),
        }
    }

    /// Whether the profile is staircased (its slab count matters).
    pub(crate) fn is_smooth(&self) -> bool {
        matches!(
            self.profile,
            Profile::Sinusoid { .. }
                | Profile::Sawtooth { .. }
                | Profile::Fourier { .. }
                | Profile::Sampled(_)
        )
    }

    /// The default slab count for a smooth profile at λ: one per λ/40 of depth, at least 8, at
    /// most [`MAX_SLABS`].
    pub(crate) fn default_slabs(&self, wavelength_nm: f64) -> usize {
        let h = self.depth_nm();
        ((40.0 * h / wavelength_nm).ceil() as usize).clamp(8, MAX_SLABS)
    }

    fn heights(&self) -> Vec<f64> {
        match &self.profile {
            Profile::Sampled(z) => z.clone(),
            Profile::Fourier { cos, sin } => (0..FOURIER_SAMPLES)
                .map(|i| {
                    let t = core::f64::consts::TAU * i as f64 / FOURIER_SAMPLES as f64;
                    let c: f64 = cos
                        .iter()
                        .enumerate()
                        .map(|(k, a)| a * ((k + 1) as f64 * t).cos())
                        .sum();
                    let s: f64 = sin
                        .iter()
                        .enumerate()
                        .map(|(k, b)| b * ((k + 1) as f64 * t).sin())
                        .sum();
                    c + s
                })
                .collect(),
            _ => Vec::new(),
        }
    }

    /// The staircase, top slab first; `slabs` is used by smooth profiles only. Levels are at the
    /// slabs' mid-heights (midpoint rule).
    pub(crate) fn slabs(&self, slabs: usize) -> Vec<Slab> {
        let d = self.period_nm;
        let h = self.depth_nm();
        if h == 0.0 {
            return Vec::new();
        }
        match &self.profile {
            Profile::Flat => Vec::new(),
            Profile::Lamellar { duty, depth_nm } => vec![Slab {
                thickness_nm: *depth_nm,
                ridges: vec![(0.0, *duty)],
            }],
            Profile::Multilevel(levels) => levels
                .iter()
                .filter(|l| l.thickness_nm > 0.0)
                .map(|l| Slab {
                    thickness_nm: l.thickness_nm,
                    ridges: l.ridges.clone(),
                })
                .collect(),
            _ => {
                let z = self.heights();
                let zmin = z.iter().copied().fold(f64::INFINITY, f64::min);
                (0..slabs)
                    .map(|j| {
                        // Height above the profile's bottom of slab j's mid-plane (top first).
                        let level = h - (j as f64 + 0.5) * h / slabs as f64;
                        let ridges = match &self.profile {
                            Profile::Sinusoid { .. } => sinusoid_ridges(level / h),
                            Profile::Sawtooth { blaze } => {
                                let t = blaze.tan();
                                let x1 = blaze.cos().powi(2);
                                vec![((0.0), (h - level) / t / d), (x1 + level * t / d, 1.0)]
                            }
                            _ => linear_ridges(&z, zmin + level),
                        };
                        Slab {
                            thickness_nm: h / slabs as f64,
                            ridges: ridges.into_iter().filter(|(a, b)| b > a).collect(),
                        }
                    })
                    .collect()
            }
        }
    }
}

fn span(z: &[f64]) -> f64 {
    let lo = z.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = z.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if z.is_empty() {
        0.0
    } else {
        hi - lo
    }
}

/// Where (h/2)(1 + sin 2πt) > u·h, t in [0, 1): the metal of a sinusoid's slab.
fn sinusoid_ridges(u: f64) -> Vec<(f64, f64)> {
    let s = (2.0 * u - 1.0).clamp(-1.0, 1.0);
    let a = s.asin() / core::f64::consts::TAU; // in [-1/4, 1/4]
    let (t0, t1) = (a, 0.5 - a);
    if t0 >= 0.0 {
        vec![(t0, t1)]
    } else {
        vec![(0.0, t1), (1.0 + t0, 1.0)]
    }
}

/// Where the periodic piecewise-linear profile through `z` (at t = i/n) exceeds `level`.
fn linear_ridges(z: &[f64], level: f64) -> Vec<(f64, f64)> {
    let n = z.len();
    let mut out: Vec<(f64, f64)> = Vec::new();
    for i in 0..n {
        let (za, zb) = (z[i], z[(i + 1) % n]);
        let (ta, tb) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
        let piece = match (za > level, zb > level) {
            (true, true) => Some((ta, tb)),
            (false, false) => None,
            (true, false) => Some((ta, ta + (tb - ta) * (za - level) / (za - zb))),
            (false, true) => Some((ta + (tb - ta) * (level - za) / (zb - za), tb)),
        };
        if let Some((a, b)) = piece {
            match out.last_mut() {
                Some(last) if (last.1 - a).abs() < 1e-15 => last.1 = b,
                _ => out.push((a, b)),
            }
        }
    }
    out
}
