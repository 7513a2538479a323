//! The shape of one period of a surface relief h(x) and the power of each order of its Kirchhoff
//! phase screen exp(−i·κ·h(x)).

#[cfg(feature = "alloc")]
use alloc::vec::Vec;
#[cfg(feature = "alloc")]
use core::f64::consts::TAU;
use core::f64::consts::{FRAC_PI_2, PI};

use crate::error::{Error, Requirement};
use crate::num::bessel::bessel_j_bounded;
#[cfg(feature = "alloc")]
use crate::num::complex::Complex;
use crate::num::kernel::sincospi;
use crate::num::math;

/// The largest relief depth accepted (peak-to-valley, nm): 10 µm, forty wavelengths of visible
/// light, far beyond where a scalar model means anything; it bounds the phases (κ·h ≤ 1.3·10⁵
/// at λ ≥ 1 nm) and so the Bessel recurrences.
///
/// ```
/// use diffraction::relief::{Relief, MAX_DEPTH_NM};
/// assert!(Relief::sinusoid(MAX_DEPTH_NM).is_ok());
/// assert_eq!(Relief::sinusoid(1.5 * MAX_DEPTH_NM).unwrap_err().parameter(), "depth_nm");
/// ```
pub const MAX_DEPTH_NM: f64 = 10_000.0;
/// The most heights of a [`Relief::sampled`] profile and the most harmonics of a
/// [`Relief::fourier`] series: bounds the work of one order to `QUADRATURE_NODES` complex
/// exponentials.
///
/// ```
/// use diffraction::relief::{Relief, MAX_SAMPLES};
/// assert!(Relief::sampled(&vec![0.0; MAX_SAMPLES]).is_ok());
/// assert_eq!(Relief::sampled(&vec![0.0; MAX_SAMPLES + 1]).unwrap_err().parameter(), "heights");
/// ```
pub const MAX_SAMPLES: usize = 4096;
/// The nodes of the trapezoid rule that integrates a [`Relief::fourier`] profile's phase screen
/// over one period (exact for every Fourier component of the integrand below this count; see
/// [`Relief::fourier`]).
///
/// ```
/// use diffraction::relief::Relief;
/// // The rule is a discrete Fourier transform on its J = 4096 nodes: order m and m + J alias.
/// let f = Relief::fourier(&[(40.0, 0.0)])?;
/// let j = 4096;
/// assert_eq!(f.power(3, 0.02, 1000.0), f.power(3 + j, 0.02, 1000.0));
/// # Ok::<(), diffraction::Error>(())
/// ```
#[cfg(feature = "alloc")]
pub(crate) const QUADRATURE_NODES: usize = 4096;
/// The most recurrence steps one Bessel value of a sinusoid may take before Debye's expansions
/// are used (their accuracy there is below 10⁻¹¹ of the local amplitude, `src/num/bessel.rs`): bounds
/// a sinusoid's order to about 2000 steps whatever its phase.
const BESSEL_STEPS: f64 = 2000.0;
/// Below this |t|, sin t / t is 1 − t²/6 (the next term, t⁴/120, is below 10⁻¹⁸).
const SINC_SERIES: f64 = 1e-4;

/// The shape of one period of a surface relief, the metal below it, light from above.
///
/// x runs across the grooves over one period d (the period belongs to the grating,
/// [`ScalarRelief`](super::ScalarRelief)); heights are in nm. Built by validating constructors:
///
/// * [`Relief::sinusoid`]: h(x) = (h/2)·sin(2πx/d), h peak-to-valley;
/// * [`Relief::lamellar`]: raised ridges of width duty·d and height h on flat metal;
/// * [`Relief::sawtooth`]: the 90°-apex triangle of a ruled grating with blaze angle θB;
/// * [`Relief::fourier`]: a user's Fourier series (feature `alloc`);
/// * [`Relief::sampled`]: a user's heights at equally spaced points, joined by straight lines
///   (feature `alloc`).
///
/// [`Relief::power`] is the share of order m in the Kirchhoff phase screen exp(−i·κ·h(x)) at a
/// given phase κ per nm of height (Parseval: the shares of all orders sum to 1).
///
/// ```
/// use diffraction::relief::Relief;
/// let r = Relief::lamellar(110.0, 0.3125)?;
/// assert_eq!(r.depth_nm(1600.0), 110.0);
/// assert_eq!(Relief::sinusoid(-1.0).unwrap_err().parameter(), "depth_nm");
/// assert_eq!(Relief::lamellar(100.0, 1.5).unwrap_err().parameter(), "duty");
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Relief {
    kind: Kind,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Sinusoid {
        depth_nm: f64,
    },
    Lamellar {
        depth_nm: f64,
        duty: f64,
    },
    Sawtooth {
        blaze: f64,
    },
    #[cfg(feature = "alloc")]
    Fourier {
        /// h at the `QUADRATURE_NODES` nodes x_j = j·d/J.
        nodes: Vec<f64>,
        depth_nm: f64,
        /// max_j |d·h'(x_j)|: the largest slope times the period.
        slope_period: f64,
    },
    #[cfg(feature = "alloc")]
    Sampled {
        heights: Vec<f64>,
        depth_nm: f64,
    },
}

/// Checks a depth: finite, in [0, MAX_DEPTH_NM].
fn depth(name: &'static str, h: f64) -> Result<f64, Error> {
    if h.is_finite() && (0.0..=MAX_DEPTH_NM).contains(&h) {
        Ok(h)
    } else {
        Err(Error::invalid(
            name,
            h,
            Requirement::Within {
                min: 0.0,
                max: MAX_DEPTH_NM,
            },
        ))
    }
}

impl Relief {
    /// The sinusoid h(x) = (h/2)·sin(2πx/d) of peak-to-valley depth h = `depth_nm` (finite, in
    /// [0, [`MAX_DEPTH_NM`]]). Its phase screen's orders have the power J_m(κ·h/2)²
    /// (Jacobi-Anger).
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// let r = Relief::sinusoid(100.0)?;
    /// // κ·h/2 = 1 rad: J₁(1)² = 0.19364...
    /// assert!((r.power(1, 0.02, 1000.0) - 0.44005058574493355f64.powi(2)).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn sinusoid(depth_nm: f64) -> Result<Relief, Error> {
        Ok(Relief {
            kind: Kind::Sinusoid {
                depth_nm: depth("depth_nm", depth_nm)?,
            },
        })
    }

    /// Raised ridges of width `duty`·d (duty finite in [0, 1]) and height h = `depth_nm`
    /// (finite, in [0, [`MAX_DEPTH_NM`]]) on flat metal: a two-level phase screen of phase
    /// difference φ = κ·h, whose orders have the power (closed form)
    ///
    /// |c₀|² = 1 − 4·duty·(1 − duty)·sin²(φ/2),  |c_m|² = 4·sin²(φ/2)·sin²(π·m·duty)/(π·m)².
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// use std::f64::consts::PI;
    /// let r = Relief::lamellar(100.0, 0.5)?;
    /// // φ = π (a quarter-wave deep groove at normal incidence): no order 0, no even order.
    /// let kappa = PI / 100.0;
    /// assert!(r.power(0, kappa, 1000.0) < 1e-30 && r.power(2, kappa, 1000.0) < 1e-30);
    /// assert!((r.power(1, kappa, 1000.0) - 4.0 / (PI * PI)).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn lamellar(depth_nm: f64, duty: f64) -> Result<Relief, Error> {
        let depth_nm = depth("depth_nm", depth_nm)?;
        if !(duty.is_finite() && (0.0..=1.0).contains(&duty)) {
            return Err(Error::invalid(
                "duty",
                duty,
                Requirement::Within { min: 0.0, max: 1.0 },
            ));
        }
        Ok(Relief {
            kind: Kind::Lamellar { depth_nm, duty },
        })
    }

    /// The triangular profile of a ruled grating with a 90° apex and blaze angle θB =
    /// `blaze_rad` (finite, in [0, π/2]): the long facet of slope θB falls from h at x = 0 to 0
    /// at x = d·cos²θB, the short facet (slope 90° − θB) rises back, so h = d·sin θB·cos θB.
    /// The long facet's normal leans toward +x: the grating blazes into positive orders
    /// (Littrow in order m at sin θi = −m·λ/(2d)).
    ///
    /// Each facet is a linear phase, so (closed form, f₁ = cos²θB, f₂ = sin²θB, φ = κ·h)
    ///
    /// c_m = f₁·e^{−iπmf₁}·sinc((φ − 2πmf₁)/2) + f₂·e^{iπmf₂}·sinc((φ + 2πmf₂)/2)
    ///
    /// up to a common phase, sinc t = sin t/t; for a vanishing short facet this is the ideal
    /// sawtooth's sinc²(φ/2 − π·m).
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// let blaze = 8.627f64.to_radians(); // 600 lines/mm blazed for 500 nm
    /// let r = Relief::sawtooth(blaze)?;
    /// let d = 1666.67;
    /// assert!((r.depth_nm(d) - d * blaze.sin() * blaze.cos()).abs() < 1e-12);
    /// // At the long facet's own phase φ = 2π·f₁ its light all goes into order 1, and the
    /// // short facet's term vanishes there: |c₁|² = f₁².
    /// let f1 = blaze.cos().powi(2);
    /// let kappa = std::f64::consts::TAU * f1 / r.depth_nm(d);
    /// assert!((r.power(1, kappa, d) - f1 * f1).abs() < 1e-12);
    /// assert_eq!(Relief::sawtooth(2.0).unwrap_err().parameter(), "blaze_rad");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn sawtooth(blaze_rad: f64) -> Result<Relief, Error> {
        if !(blaze_rad.is_finite() && (0.0..=FRAC_PI_2).contains(&blaze_rad)) {
            return Err(Error::invalid(
                "blaze_rad",
                blaze_rad,
                Requirement::Within {
                    min: 0.0,
                    max: FRAC_PI_2,
                },
            ));
        }
        Ok(Relief {
            kind: Kind::Sawtooth { blaze: blaze_rad },
        })
    }

    /// A Fourier series h(x) = Σ_{k=1}^{K} (a_k·cos(2πkx/d) + b_k·sin(2πkx/d)), `harmonics`
    /// = [(a_1, b_1), …, (a_K, b_K)] in nm (1 ≤ K ≤ [`MAX_SAMPLES`], every coefficient finite,
    /// peak-to-valley depth at most [`MAX_DEPTH_NM`]). Feature `alloc`.
    ///
    /// The phase screen's coefficients are integrated by the trapezoid rule on
    /// `QUADRATURE_NODES` points, which is exact (to rounding) for every Fourier component of
    /// the periodic integrand below that count: for order m when |m| + K·(κ·A + 20) < 4096,
    /// A = Σ_k √(a_k² + b_k²), the integrand's bandwidth (the components of exp(−iκh) beyond
    /// K·(κA + 20) are below 10⁻¹⁷). Orders and phases beyond that are aliased: a documented
    /// truncation, reached only for profiles hundreds of wavelengths deep or with thousands of
    /// harmonics.
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// // One harmonic b₁ = 50 nm is the sinusoid of depth 100 nm.
    /// let f = Relief::fourier(&[(0.0, 50.0)])?;
    /// let s = Relief::sinusoid(100.0)?;
    /// for m in -3..=3 {
    ///     assert!((f.power(m, 0.03, 1000.0) - s.power(m, 0.03, 1000.0)).abs() < 1e-14);
    /// }
    /// assert_eq!(f.depth_nm(1000.0), 100.0);
    /// assert_eq!(Relief::fourier(&[]).unwrap_err().parameter(), "harmonics");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[cfg(feature = "alloc")]
    pub fn fourier(harmonics: &[(f64, f64)]) -> Result<Relief, Error> {
        let count = harmonics.len();
        if count == 0 || count > MAX_SAMPLES {
            return Err(Error::invalid(
                "harmonics",
                count as f64,
                Requirement::Within {
                    min: 1.0,
                    max: MAX_SAMPLES as f64,
                },
            ));
        }
        if let Some(&(a, b)) = harmonics
            .iter()
            .find(|(a, b)| !(a.is_finite() && b.is_finite()))
        {
            let bad = if a.is_finite() { b } else { a };
            return Err(Error::invalid("harmonics", bad, Requirement::Finite));
        }
        let j_count = QUADRATURE_NODES;
        let nodes: Vec<f64> = (0..j_count)
            .map(|j| {
                harmonics
                    .iter()
                    .enumerate()
                    .map(|(i, &(a, b))| {
                        // 2π·k·j/J with k·j reduced modulo J exactly.
                        let t = ((i + 1) * j % j_count) as f64 / j_count as f64;
                        let (s, c) = sincospi(2.0 * t);
                        a * c + b * s
                    })
                    .sum()
            })
            .collect();
        let depth_nm = depth("harmonics", peak_to_valley(&nodes))?;
        // d·h'(x) = Σ_k 2πk·(−a_k·sin + b_k·cos) at the same nodes.
        let slope_period = (0..j_count)
            .map(|j| {
                let sum: f64 = harmonics
                    .iter()
                    .enumerate()
                    .map(|(i, &(a, b))| {
                        let t = ((i + 1) * j % j_count) as f64 / j_count as f64;
                        let (s, c) = sincospi(2.0 * t);
                        TAU * (i + 1) as f64 * (b * c - a * s)
                    })
                    .sum();
                sum.abs()
            })
            .fold(0.0, f64::max);
        Ok(Relief {
            kind: Kind::Fourier {
                nodes,
                depth_nm,
                slope_period,
            },
        })
    }

    /// A profile given by its heights h_j (nm) at x_j = j·d/M, j = 0…M−1 (2 ≤ M ≤
    /// [`MAX_SAMPLES`], every height finite, peak-to-valley at most [`MAX_DEPTH_NM`]), repeated
    /// with period d and joined by straight lines (h_M = h_0). Feature `alloc`.
    ///
    /// Each straight piece is a linear phase, integrated exactly: the coefficients are those of
    /// the piecewise-linear surface, with no quadrature error (M complex exponentials an order).
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// // Two samples h = (110, 0) are a symmetric triangle wave of depth 110 nm.
    /// let r = Relief::sampled(&[110.0, 0.0])?;
    /// assert_eq!(r.depth_nm(1600.0), 110.0);
    /// let total: f64 = (-2000..=2000).map(|m| r.power(m, 0.02, 1600.0)).sum();
    /// assert!((total - 1.0).abs() < 1e-6); // Parseval, up to the 1/m⁴ tail
    /// assert_eq!(Relief::sampled(&[1.0]).unwrap_err().parameter(), "heights");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[cfg(feature = "alloc")]
    pub fn sampled(heights_nm: &[f64]) -> Result<Relief, Error> {
        let count = heights_nm.len();
        if !(2..=MAX_SAMPLES).contains(&count) {
            return Err(Error::invalid(
                "heights",
                count as f64,
                Requirement::Within {
                    min: 2.0,
                    max: MAX_SAMPLES as f64,
                },
            ));
        }
        if let Some(&h) = heights_nm.iter().find(|h| !h.is_finite()) {
            return Err(Error::invalid("heights", h, Requirement::Finite));
        }
        let depth_nm = depth("heights", peak_to_valley(heights_nm))?;
        Ok(Relief {
            kind: Kind::Sampled {
                heights: heights_nm.to_vec(),
                depth_nm,
            },
        })
    }

    /// The peak-to-valley depth in nm for period `period_nm` (the period matters only for the
    /// sawtooth, h = d·sin θB·cos θB; for a Fourier series it is measured on its quadrature
    /// nodes).
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// assert_eq!(Relief::sinusoid(120.0)?.depth_nm(500.0), 120.0);
    /// let r = Relief::sawtooth(30f64.to_radians())?;
    /// assert!((r.depth_nm(1000.0) - 1000.0 * 3f64.sqrt() / 4.0).abs() < 1e-12);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn depth_nm(&self, period_nm: f64) -> f64 {
        match self.kind {
            Kind::Sinusoid { depth_nm } | Kind::Lamellar { depth_nm, .. } => depth_nm,
            Kind::Sawtooth { blaze } => period_nm * math::sin(blaze) * math::cos(blaze),
            #[cfg(feature = "alloc")]
            Kind::Fourier { depth_nm, .. } | Kind::Sampled { depth_nm, .. } => depth_nm,
        }
    }

    /// The largest slope |dh/dx| of the profile for period `period_nm`: π·h/d for the
    /// sinusoid; infinite for the lamellar profile (vertical walls, unless it is flat: depth 0 or
    /// duty 0 or 1 gives 0); max(tan θB, cot θB) for the sawtooth (its short facet, the steeper one
    /// for θB < 45°); for a Fourier series the largest over its quadrature nodes; for sampled
    /// heights the steepest straight piece. [`ScalarRelief::is_valid`](super::ScalarRelief::is_valid)
    /// judges smooth profiles by it.
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// use std::f64::consts::PI;
    /// assert!((Relief::sinusoid(30.0)?.max_slope(1000.0) - PI * 0.03).abs() < 1e-15);
    /// assert_eq!(Relief::lamellar(30.0, 0.5)?.max_slope(1000.0), f64::INFINITY);
    /// let f = Relief::fourier(&[(0.0, 15.0)])?; // the same sinusoid
    /// assert!((f.max_slope(1000.0) - PI * 0.03).abs() < 1e-12);
    /// assert!((Relief::sampled(&[0.0, 10.0, 0.0, 0.0])?.max_slope(1000.0) - 0.04).abs() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn max_slope(&self, period_nm: f64) -> f64 {
        match &self.kind {
            Kind::Sinusoid { depth_nm } => PI * depth_nm / period_nm,
            Kind::Lamellar { depth_nm, duty } => {
                if *depth_nm == 0.0 || *duty == 0.0 || *duty == 1.0 {
                    0.0
                } else {
                    f64::INFINITY
                }
            }
            Kind::Sawtooth { blaze } => {
                let (s, c) = (math::sin(*blaze), math::cos(*blaze));
                if s < c {
                    c / s
                } else {
                    s / c
                }
            }
            #[cfg(feature = "alloc")]
            Kind::Fourier { slope_period, .. } => slope_period / period_nm,
            #[cfg(feature = "alloc")]
            Kind::Sampled { heights, .. } => {
                let m = heights.len();
                let steepest = (0..m)
                    .map(|j| (heights[(j + 1) % m] - heights[j]).abs())
                    .fold(0.0, f64::max);
                steepest * m as f64 / period_nm
            }
        }
    }

    /// Whether the profile is smooth (no vertical walls, no facets): the sinusoid, a Fourier
    /// series, sampled heights.
    pub(crate) fn is_smooth(&self) -> bool {
        !matches!(self.kind, Kind::Lamellar { .. } | Kind::Sawtooth { .. })
    }

    /// The profile's name: `"sinusoid"`, `"lamellar"`, `"sawtooth"`, `"fourier"` or
    /// `"sampled"`.
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// assert_eq!(Relief::sawtooth(0.2)?.name(), "sawtooth");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self.kind {
            Kind::Sinusoid { .. } => "sinusoid",
            Kind::Lamellar { .. } => "lamellar",
            Kind::Sawtooth { .. } => "sawtooth",
            #[cfg(feature = "alloc")]
            Kind::Fourier { .. } => "fourier",
            #[cfg(feature = "alloc")]
            Kind::Sampled { .. } => "sampled",
        }
    }

    /// The ridge share of a lamellar profile (`None` for the other shapes).
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// assert_eq!(Relief::lamellar(50.0, 0.25)?.duty(), Some(0.25));
    /// assert_eq!(Relief::sinusoid(50.0)?.duty(), None);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn duty(&self) -> Option<f64> {
        match self.kind {
            Kind::Lamellar { duty, .. } => Some(duty),
            _ => None,
        }
    }

    /// |c_m|²: the share of order `order` in the phase screen p(x) = exp(−i·κ·h(x)) of one
    /// period d = `period_nm`, c_m = (1/d)·∫₀^d p(x)·e^{−2πimx/d} dx, at the phase κ =
    /// `phase_per_nm` (rad per nm of height; the scalar relief model takes
    /// κ = (2π/λ)·(cos θi + cos θm) for order m). Σ_m |c_m|² = 1 for every κ (Parseval). In
    /// [0, 1] and finite for finite input; bounded work (see [`MAX_SAMPLES`]). A non-finite or
    /// non-positive period gives 0.
    ///
    /// ```
    /// use diffraction::relief::Relief;
    /// let r = Relief::lamellar(120.0, 0.5)?;
    /// let total: f64 = (-20_000..=20_000).map(|m| r.power(m, 0.017, 1000.0)).sum();
    /// // Parseval, up to the tail beyond 20 000 orders: 4·sin²(φ/2)/(π²·20 000) = 1.5·10⁻⁵.
    /// assert!(total < 1.0 && 1.0 - total < 2e-5);
    /// assert_eq!(r.power(0, 0.0, 1000.0), 1.0); // no phase: a flat mirror
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn power(&self, order: i32, phase_per_nm: f64, period_nm: f64) -> f64 {
        if !(period_nm.is_finite() && period_nm > 0.0 && phase_per_nm.is_finite()) {
            return 0.0;
        }
        let p = match &self.kind {
            Kind::Sinusoid { depth_nm } => {
                let j = bessel_j_bounded(order, 0.5 * phase_per_nm * depth_nm, BESSEL_STEPS);
                j * j
            }
            Kind::Lamellar { depth_nm, duty } => lamellar(order, phase_per_nm * depth_nm, *duty),
            Kind::Sawtooth { blaze } => sawtooth(order, phase_per_nm, period_nm, *blaze),
            #[cfg(feature = "alloc")]
            Kind::Fourier { nodes, .. } => trapezoid(order, phase_per_nm, nodes),
            #[cfg(feature = "alloc")]
            Kind::Sampled { heights, .. } => piecewise_linear(order, phase_per_nm, heights),
        };
        if p.is_finite() {
            p.clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// max − min of heights (finite).
#[cfg(feature = "alloc")]
fn peak_to_valley(h: &[f64]) -> f64 {
    let max = h.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = h.iter().copied().fold(f64::INFINITY, f64::min);
    max - min
}

/// sin t / t, 1 at 0.
fn sinc(t: f64) -> f64 {
    if t.abs() < SINC_SERIES {
        1.0 - t * t / 6.0
    } else {
        math::sin(t) / t
    }
}

/// The two-level screen's |c_m|² (see [`Relief::lamellar`]).
fn lamellar(m: i32, phi: f64, duty: f64) -> f64 {
    let s = math::sin(0.5 * phi);
    let s2 = s * s;
    if m == 0 {
        return 1.0 - 4.0 * duty * (1.0 - duty) * s2;
    }
    let (sn, _) = sincospi(f64::from(m) * duty);
    let pm = PI * f64::from(m);
    4.0 * s2 * (sn / pm) * (sn / pm)
}

/// The 90°-apex triangle's |c_m|² (see [`Relief::sawtooth`]).
fn sawtooth(m: i32, kappa: f64, period_nm: f64, blaze: f64) -> f64 {
    let (sb, cb) = (math::sin(blaze), math::cos(blaze));
    let (f1, f2) = (cb * cb, sb * sb);
    let phi = kappa * period_nm * sb * cb;
    let mf = f64::from(m);
    // e^{−iπmf₁} and e^{iπmf₂}, reduced exactly.
    let (s1, c1) = sincospi(mf * f1);
    let (s2, c2) = sincospi(mf * f2);
    let a1 = f1 * sinc(0.5 * phi - PI * mf * f1);
    let a2 = f2 * sinc(0.5 * phi + PI * mf * f2);
    let re = a1 * c1 + a2 * c2;
    let im = -a1 * s1 + a2 * s2;
    re * re + im * im
}

/// The trapezoid rule of a Fourier profile's screen on its nodes (see [`Relief::fourier`]).
#[cfg(feature = "alloc")]
fn trapezoid(m: i32, kappa: f64, nodes: &[f64]) -> f64 {
    let count = nodes.len();
    let m_mod = i64::from(m).rem_euclid(count as i64) as usize;
    let mut sum = Complex::ZERO;
    for (j, &h) in nodes.iter().enumerate() {
        // −κ·h − 2π·m·j/J, the second part reduced modulo J exactly.
        let t = (m_mod * j % count) as f64 / count as f64;
        let (s, c) = sincospi(2.0 * t);
        let screen = Complex::cis(-kappa * h);
        sum = sum + screen * Complex::new(c, -s);
    }
    sum.scale(1.0 / count as f64).norm_sqr()
}

/// The exact coefficient of the piecewise-linear surface through `heights` (see
/// [`Relief::sampled`]).
#[cfg(feature = "alloc")]
fn piecewise_linear(m: i32, kappa: f64, heights: &[f64]) -> f64 {
    let count = heights.len();
    let m_mod = i64::from(m).rem_euclid(count as i64) as usize;
    // The order's phase advance over one piece, 2π·m/M (only its value matters, not its
    // reduction: it enters through sinc).
    let step = TAU * f64::from(m) / count as f64;
    let mut sum = Complex::ZERO;
    for j in 0..count {
        let (h0, h1) = (heights[j], heights[(j + 1) % count]);
        // The phase at the piece's middle: −κ(h0 + h1)/2 − 2π·m·(j + ½)/M, the order's part
        // π·(2mj + m)/M reduced exactly with m mod M in place of m (which changes every piece's
        // term by the same sign, leaving |c_m|² as it is).
        let cycles = ((2 * (m_mod * j % count) + m_mod) % (2 * count)) as f64 / count as f64;
        let (s, c) = sincospi(cycles);
        let mid = Complex::cis(-0.5 * kappa * (h0 + h1)) * Complex::new(c, -s);
        let half = 0.5 * (-kappa * (h1 - h0) - step);
        sum = sum + mid.scale(sinc(half));
    }
    sum.scale(1.0 / count as f64).norm_sqr()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sawtooth_without_short_facet_is_the_ideal_blaze() {
        // θB → 0 makes f₂ → 0; check the closed form's limit sinc²(φ/2 − πm) directly at a
        // small blaze where f₂ = 10⁻⁸.
        let blaze = 1e-4;
        let r = Relief::sawtooth(blaze).unwrap();
        let d = 1000.0;
        let h = r.depth_nm(d);
        for m in -3..=3 {
            let kappa = 2.6 / h;
            let phi = kappa * h;
            let f1 = blaze.cos().powi(2);
            let want = sinc(0.5 * phi - PI * f64::from(m) * f1).powi(2) * f1 * f1;
            assert!((r.power(m, kappa, d) - want).abs() < 1e-7, "{m}");
        }
    }
}
