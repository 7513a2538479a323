//! Grating parameters, the Agu-Hill intensity I(u, λ) = S(β)·F_N(α), and its peaks on the grating
//! equation (the peak search).

use glam::DVec3;

use crate::error::{positive, Error, Requirement};
use crate::num::float::Float;
use crate::num::kernel::{intensity_cycles, n_slit_cycles, single_slit_cycles};
use crate::num::math;
use crate::optics::orders::{GratingEquation, Orders, Propagating};
use crate::Band;

/// The number of coherently illuminated slits (periods), N.
///
/// The paper's normalisation puts every maximum at 1 whatever N is; the width of a maximum is
/// about 1/N of a period. [`Slits::Infinite`] is the limit N → ∞: the intensity is S(β) exactly on
/// the grating equation and 0 elsewhere, and every peak has zero width.
///
/// ```
/// use diffraction::{Grating, Slits};
/// let few = Grating::with_slits(1600.0, 800.0, Slits::Finite(10))?;
/// let ideal = Grating::with_slits(1600.0, 800.0, Slits::Infinite)?;
/// // Off the grating equation (x = d·u/λ = 0.05) ten slits still send light; the limit does not.
/// assert!(few.intensity(0.025, 800.0) > 0.1);
/// assert_eq!(ideal.intensity(0.025, 800.0), 0.0);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Slits {
    /// A finite number N ≥ 1 of slits.
    Finite(u32),
    /// The limit N → ∞.
    Infinite,
}

impl From<u32> for Slits {
    /// `Slits::Finite(n)`.
    ///
    /// ```
    /// use diffraction::Slits;
    /// assert_eq!(Slits::from(30), Slits::Finite(30));
    /// ```
    fn from(n: u32) -> Slits {
        Slits::Finite(n)
    }
}

impl Slits {
    /// N as a float, `f64::INFINITY` for the limit.
    ///
    /// ```
    /// use diffraction::Slits;
    /// assert_eq!(Slits::Finite(1000).as_f64(), 1000.0);
    /// assert_eq!(Slits::Infinite.as_f64(), f64::INFINITY);
    /// ```
    #[must_use]
    pub fn as_f64(self) -> f64 {
        match self {
            Slits::Finite(n) => n as f64,
            Slits::Infinite => f64::INFINITY,
        }
    }
}

/// A diffraction grating: period d, slit width w and number of slits N.
///
/// Its intensity is the paper's eq. 8 with I₀ = 1:
/// I(u, λ) = S(β)·F_N(α), α = π·d·u/λ, β = π·w·u/λ, where u = (wi + wo)·t
/// (see [`frame::phase_projection`](crate::optics::frame::phase_projection)).
///
/// ```
/// use diffraction::{Grating, Slits};
/// let cd = Grating::new(1600.0, 800.0, 2000)?;
/// assert_eq!(cd.slits(), Slits::Finite(2000));
/// assert_eq!(cd.intensity(0.0, 550.0), 1.0); // the mirror direction, white
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Grating {
    period_nm: f64,
    slit_width_nm: f64,
    slits: Slits,
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Grating {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        struct Raw {
            period_nm: f64,
            slit_width_nm: f64,
            slits: Slits,
        }
        let raw = Raw::deserialize(d)?;
        Grating::with_slits(raw.period_nm, raw.slit_width_nm, raw.slits)
            .map_err(serde::de::Error::custom)
    }
}

impl Grating {
    /// A grating of `slits` ≥ 1 periods; rejects d ≤ 0, w ≤ 0, w > d, N = 0 and non-finite values.
    ///
    /// ```
    /// use diffraction::Grating;
    /// assert!(Grating::new(1600.0, 800.0, 100).is_ok());
    /// assert_eq!(Grating::new(-1.0, 1.0, 1).unwrap_err().parameter(), "period_nm");
    /// assert_eq!(Grating::new(1600.0, 0.0, 1).unwrap_err().parameter(), "slit_width_nm");
    /// assert_eq!(Grating::new(1600.0, 800.0, 0).unwrap_err().parameter(), "slits");
    /// ```
    pub fn new(period_nm: f64, slit_width_nm: f64, slits: u32) -> Result<Grating, Error> {
        Grating::with_slits(period_nm, slit_width_nm, Slits::Finite(slits))
    }

    /// A grating with N → ∞ (see [`Slits::Infinite`]).
    ///
    /// ```
    /// use diffraction::{Grating, Slits};
    /// let g = Grating::infinite(1600.0, 800.0)?;
    /// assert_eq!(g.slits(), Slits::Infinite);
    /// // On the grating equation (x = d·u/λ = 1) the envelope S(β); rounding of x only.
    /// assert!((g.intensity(0.3, 480.0) - g.single_slit(0.3, 480.0)).abs() < 1e-15);
    /// assert_eq!(g.intensity(0.3, 500.0), 0.0); // anywhere else
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn infinite(period_nm: f64, slit_width_nm: f64) -> Result<Grating, Error> {
        Grating::with_slits(period_nm, slit_width_nm, Slits::Infinite)
    }

    /// A grating from its groove density (lines per millimetre), the open fraction w/d of each
    /// period and N: d = 10⁶ nm / lines_per_mm.
    ///
    /// ```
    /// use diffraction::{Grating, Slits};
    /// let g = Grating::from_lines_per_mm(600.0, 0.5, Slits::Infinite)?;
    /// assert!((g.period_nm() - 1666.6666666666667).abs() < 1e-9);
    /// // A density so small that the period overflows is reported as what was passed.
    /// let err = Grating::from_lines_per_mm(1e-310, 0.5, Slits::Infinite).unwrap_err();
    /// assert_eq!(err.parameter(), "lines_per_mm");
    /// assert!(err.to_string().starts_with("invalid lines_per_mm = 1e-310: must satisfy"));
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn from_lines_per_mm(
        lines_per_mm: f64,
        open_fraction: f64,
        slits: Slits,
    ) -> Result<Grating, Error> {
        let lines = positive("lines_per_mm", lines_per_mm)?;
        let open = positive("open_fraction", open_fraction)?;
        if open > 1.0 {
            return Err(Error::invalid(
                "open_fraction",
                open,
                Requirement::AtMost {
                    bound_name: "1",
                    bound: 1.0,
                },
            ));
        }
        let d = 1.0e6 / lines;
        if !d.is_finite() {
            // 10⁶ nm / lines_per_mm overflows: name what the caller passed.
            return Err(Error::invalid(
                "lines_per_mm",
                lines,
                Requirement::AtLeast {
                    bound_name: "1e6 / f64::MAX",
                    bound: 1.0e6 / f64::MAX,
                },
            ));
        }
        let w = open * d;
        if w.is_nan() || w <= 0.0 {
            // open_fraction·d underflows.
            return Err(Error::invalid(
                "open_fraction",
                open,
                Requirement::AtLeast {
                    bound_name: "f64::MIN_POSITIVE / period_nm",
                    bound: f64::MIN_POSITIVE / d,
                },
            ));
        }
        Grating::with_slits(d, w.min(d), slits)
    }

    /// A grating with an explicit [`Slits`] value.
    ///
    /// ```
    /// use diffraction::{Grating, Slits};
    /// let g = Grating::with_slits(1600.0, 800.0, Slits::Finite(500))?;
    /// assert_eq!(g, Grating::new(1600.0, 800.0, 500)?);
    /// let err = Grating::with_slits(1600.0, 800.0, Slits::Finite(0)).unwrap_err();
    /// assert_eq!(err.parameter(), "slits");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn with_slits(period_nm: f64, slit_width_nm: f64, slits: Slits) -> Result<Grating, Error> {
        let d = positive("period_nm", period_nm)?;
        let w = positive("slit_width_nm", slit_width_nm)?;
        if w > d {
            return Err(Error::invalid(
                "slit_width_nm",
                w,
                Requirement::AtMost {
                    bound_name: "period_nm",
                    bound: d,
                },
            ));
        }
        if slits == Slits::Finite(0) {
            return Err(Error::invalid("slits", 0.0, Requirement::AtLeastOne));
        }
        Ok(Grating {
            period_nm: d,
            slit_width_nm: w,
            slits,
        })
    }

    /// The period d, nm.
    ///
    /// ```
    /// use diffraction::Grating;
    /// assert_eq!(Grating::new(1600.0, 800.0, 100)?.period_nm(), 1600.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn period_nm(&self) -> f64 {
        self.period_nm
    }

    /// The slit width w, nm.
    ///
    /// ```
    /// use diffraction::Grating;
    /// assert_eq!(Grating::new(1600.0, 800.0, 100)?.slit_width_nm(), 800.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn slit_width_nm(&self) -> f64 {
        self.slit_width_nm
    }

    /// The open fraction ρ = w/d: the share of each period that is a slit, in (0, 1].
    ///
    /// ```
    /// # use diffraction::Grating;
    /// assert_eq!(Grating::new(1600.0, 400.0, 10)?.open_fraction(), 0.25);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn open_fraction(&self) -> f64 {
        self.slit_width_nm / self.period_nm
    }

    /// The number of slits N.
    ///
    /// ```
    /// use diffraction::{Grating, Slits};
    /// assert_eq!(Grating::new(1600.0, 800.0, 100)?.slits(), Slits::Finite(100));
    /// assert_eq!(Grating::infinite(1600.0, 800.0)?.slits(), Slits::Infinite);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn slits(&self) -> Slits {
        self.slits
    }

    /// The phase in cycles, x = d·u/λ = α/π. Integer x is a grating-equation maximum.
    ///
    /// Finite for finite input: 0 for λ ≤ 0 (no wave), and ±`f64::MAX` where d·|u|/λ
    /// overflows.
    ///
    /// ```
    /// # use diffraction::Grating;
    /// let g = Grating::new(1000.0, 500.0, 10)?;
    /// assert_eq!(g.phase_cycles(0.5, 500.0), 1.0);
    /// assert_eq!(g.phase_cycles(2.0, 5e-324), f64::MAX); // saturates instead of ∞
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn phase_cycles(&self, u: f64, lambda_nm: f64) -> f64 {
        if lambda_nm.is_nan() || lambda_nm <= 0.0 {
            return 0.0;
        }
        (self.period_nm * (u / lambda_nm)).clamp(-f64::MAX, f64::MAX)
    }

    /// I(u, λ) = S(β)·F_N(α), the paper's eq. 8 with I₀ = 1, in [0, 1].
    ///
    /// For N = ∞ the pointwise limit is used: S(β) where x = d·u/λ is within 4 ulp of an
    /// integer (the roundings of forming x), 0 elsewhere. Renderers want the peak search
    /// ([`Grating::peaks`]) for that case.
    ///
    /// Evaluated in `f64` for either argument type; x = d·(u/λ) is formed with two roundings
    /// and then reduced exactly (see [`kernel`](crate::num::kernel) for the accuracy of the factors).
    /// Returns 0 for λ ≤ 0 and where the phase overflows (|d·u/λ| not finite), never NaN for
    /// finite input.
    ///
    /// ```
    /// # use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let u = 0.3; // first order at λ = d·u = 480 nm
    /// assert!((g.intensity(u, 480.0) - g.single_slit(u, 480.0)).abs() < 1e-15);
    /// assert!(g.intensity(u as f32, 520.0f32) < 1e-6);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[inline]
    #[must_use]
    pub fn intensity<T: Float>(&self, u: T, lambda_nm: T) -> T {
        T::from_f64(self.intensity_f64(u.to_f64(), lambda_nm.to_f64()))
    }

    #[inline]
    pub(crate) fn intensity_f64(&self, u: f64, lambda_nm: f64) -> f64 {
        if lambda_nm.is_nan() || lambda_nm <= 0.0 {
            return 0.0;
        }
        let q = u / lambda_nm;
        let x = self.period_nm * q;
        if !x.is_finite() {
            return 0.0;
        }
        let y = self.slit_width_nm * q;
        match self.slits {
            Slits::Finite(n) if n >= 2 => intensity_cycles(x, y, n),
            _ => single_slit_cycles(y) * self.n_slit_x(x),
        }
    }

    /// F_N at phase x in cycles, including the N → ∞ limit (1 on integers, 0 elsewhere).
    #[inline]
    pub(crate) fn n_slit_x(&self, x: f64) -> f64 {
        match self.slits {
            Slits::Finite(n) => n_slit_cycles(x, n),
            Slits::Infinite => {
                // x = d·u/λ is formed with a few roundings; within 4 ulp of an integer counts as
                // on the grating equation.
                if (x - math::rint(x)).abs() <= 4.0 * f64::EPSILON * x.abs() {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }

    /// The single-slit envelope S(β) alone, β = π·w·u/λ (0 for λ ≤ 0).
    ///
    /// ```
    /// use diffraction::Grating;
    /// use std::f64::consts::PI;
    /// let g = Grating::new(1600.0, 800.0, 100)?;
    /// assert_eq!(g.single_slit(0.0, 500.0), 1.0); // β = 0
    /// // w·u/λ = 1/2 (β = π/2): S = (2/π)², to rounding.
    /// assert!((g.single_slit(0.3125, 500.0) - 4.0 / (PI * PI)).abs() < 1e-15);
    /// assert!(g.single_slit(0.625, 500.0) < 1e-30); // β = π: the first zero
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn single_slit(&self, u: f64, lambda_nm: f64) -> f64 {
        if lambda_nm.is_nan() || lambda_nm <= 0.0 {
            return 0.0;
        }
        let y = self.slit_width_nm * u / lambda_nm;
        if !y.is_finite() {
            return 0.0;
        }
        single_slit_cycles(y)
    }

    /// The N-slit factor F_N(α) alone, α = π·d·u/λ (0 for λ ≤ 0).
    ///
    /// ```
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 4)?;
    /// assert_eq!(g.n_slit(0.625, 1000.0), 1.0); // x = d·u/λ = 1: a principal maximum
    /// assert!(g.n_slit(0.15625, 1000.0) < 1e-30); // x = 1/N: the first zero
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn n_slit(&self, u: f64, lambda_nm: f64) -> f64 {
        if lambda_nm.is_nan() || lambda_nm <= 0.0 {
            return 0.0;
        }
        let x = self.phase_cycles(u, lambda_nm);
        if !x.is_finite() {
            return 0.0;
        }
        self.n_slit_x(x)
    }

    /// The wavelength at which order `order` peaks for phase projection u: λ_m = d·u/m
    /// (grating equation, eq. 11), or `None` when m = 0 or m has the wrong sign for u.
    ///
    /// ```
    /// # use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 10)?;
    /// assert_eq!(g.peak_wavelength(0.75, 2), Some(600.0));
    /// assert_eq!(g.peak_wavelength(0.75, -2), None);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn peak_wavelength(&self, u: f64, order: i32) -> Option<f64> {
        self.equation().wavelength(u, order)
    }

    /// The grating equation of this grating's period (the orders every model shares).
    ///
    /// ```
    /// use diffraction::{Band, Grating};
    /// let g = Grating::new(1600.0, 800.0, 10)?;
    /// assert_eq!(g.equation().period_nm(), 1600.0);
    /// assert_eq!(g.equation().orders(0.9, Band::VISIBLE).len(), g.peaks(0.9, Band::VISIBLE).len());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn equation(&self) -> GratingEquation {
        GratingEquation::from_valid_period(self.period_nm)
    }

    /// The half-width, in u, of the central (order 0) lobe at wavelength λ: the first zero of
    /// F_N is at |u| = λ/(N·d). Zero for N = ∞; saturates at `f64::MAX` where λ/(N·d)
    /// overflows (a period of a few ulp of zero).
    ///
    /// ```
    /// use diffraction::Grating;
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// let h = g.specular_half_width(500.0);
    /// assert_eq!(h, 500.0 / (1000.0 * 1600.0)); // λ/(N·d)
    /// assert!(g.n_slit(h, 500.0) < 1e-20); // F_N's first zero, up to the rounding of x
    /// assert_eq!(Grating::infinite(1600.0, 800.0)?.specular_half_width(500.0), 0.0);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn specular_half_width(&self, lambda_nm: f64) -> f64 {
        (lambda_nm / (self.slits.as_f64() * self.period_nm)).min(f64::MAX)
    }

    /// Every order m ≠ 0 whose maximum λ_m = d·|u|/|m| lies in `band`, as an allocation-free
    /// iterator of [`Peak`]s in order of increasing |m| (decreasing wavelength).
    ///
    /// Order 0 (u = 0: the mirror direction for every wavelength) is reported apart, by
    /// [`Peaks::specular`]. |u| ≤ 2 for unit directions; larger |u| is accepted and simply has
    /// more orders (at most `i32::MAX`).
    ///
    /// ```
    /// use diffraction::{Band, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?; // CD track pitch
    /// let peaks: Vec<_> = g.peaks(0.9, Band::VISIBLE).collect();
    /// // d·u = 1440 nm: orders 2 (720 nm), 3 (480 nm) and 4 (360 nm) are visible.
    /// assert_eq!(peaks.iter().map(|p| p.order).collect::<Vec<_>>(), [2, 3, 4]);
    /// assert!((peaks[0].wavelength_nm - 720.0).abs() < 1e-12);
    /// assert!(!g.peaks(0.9, Band::VISIBLE).specular());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn peaks(&self, u: f64, band: Band) -> Peaks {
        let specular = match self.slits {
            Slits::Infinite => u == 0.0,
            Slits::Finite(_) => u.abs() < self.specular_half_width(band.max_nm()),
        };
        Peaks {
            orders: self.equation().orders(u, band),
            duty: self.slit_width_nm / self.period_nm,
            n: self.slits.as_f64(),
            specular,
        }
    }

    /// The propagating diffracted orders for light arriving from `wi` (unit, toward the light,
    /// in the local frame: z normal, x grating vector) at one wavelength: the conical grating
    /// equation wo_x = m·λ/d − wi_x, wo_y = −wi_y, wo_z = √(1 − wo_x² − wo_y²).
    ///
    /// Evanescent orders (wo_x² + wo_y² ≥ 1) are skipped, never returned as NaN, and never
    /// walked: the run of propagating orders is found before the first item in bounded work
    /// whatever λ/d is ([`GratingEquation::propagating`]), and its length is known
    /// (`ExactSizeIterator`). Order 0 is the mirror direction. Returns nothing for λ ≤ 0 or a
    /// non-finite `wi`.
    ///
    /// ```
    /// use diffraction::Grating;
    /// use glam::DVec3;
    /// // 600 lines/mm, 532 nm at normal incidence: first orders at ±18.6°.
    /// let g = Grating::from_lines_per_mm(600.0, 0.5, diffraction::Slits::Infinite)?;
    /// let orders: Vec<_> = g.diffracted_orders(DVec3::Z, 532.0).collect();
    /// assert_eq!(orders.iter().map(|o| o.order).collect::<Vec<_>>(), [-3, -2, -1, 0, 1, 2, 3]);
    /// let first = orders.iter().find(|o| o.order == 1).unwrap();
    /// assert!((first.direction.x.asin().to_degrees() - 18.61).abs() < 0.01);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn diffracted_orders(&self, wi: DVec3, lambda_nm: f64) -> DiffractedOrders {
        DiffractedOrders {
            orders: self.equation().propagating(wi, lambda_nm),
            duty: self.slit_width_nm / self.period_nm,
        }
    }
}

/// One grating-equation maximum of a given order (see [`Grating::peaks`]).
///
/// ```
/// use diffraction::{Band, Grating};
/// let g = Grating::new(1600.0, 800.0, 1000)?;
/// let p = g.peaks(0.6, Band::VISIBLE).next().unwrap(); // d·u = 960 nm: order 1 is infrared
/// assert_eq!(p.order, 2);
/// assert!((p.wavelength_nm - 480.0).abs() < 1e-12); // d·u/m, rounding of d·u only
/// assert!((p.equivalent_width_nm - 480.0 / (2.0 * 1000.0)).abs() < 1e-12); // λ_m/(|m|·N)
/// assert!(p.intensity < 1e-30); // w = d/2: the even orders are missing (S(β_2) = 0)
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Peak {
    /// The diffraction order m (same sign as u, never 0).
    pub order: i32,
    /// The peak wavelength λ_m = d·|u|/|m|, nm.
    pub wavelength_nm: f64,
    /// The model's value at the peak. For [`Grating::peaks`] the single-slit envelope S(β_m),
    /// β_m = π·m·w/d, since F_N = 1 on the grating equation; a
    /// [`DiffractionBrdf`](crate::DiffractionBrdf) reports its own value there.
    pub intensity: f64,
    /// The peak's equivalent width in wavelength, nm: the width of a rectangle of height
    /// `intensity` with the area of the whole order (main lobe and side lobes of one period), so
    /// that `intensity · equivalent_width_nm` is the order's spectral area. For the N-slit factor
    /// this is λ_m/(|m|·N), which is also the distance from the peak to its first zero, and 0 for
    /// N = ∞ ([`Grating::peaks`]: the paper's unitless orders have no area in the limit). A model
    /// with delta lobes of finite weight ([`GratingBsdf`](crate::GratingBsdf) for N = ∞) reports
    /// `intensity` = the order's weight and the width |dλ/du| = d/|m|, so that the product is
    /// again the area.
    pub equivalent_width_nm: f64,
}

/// The visible orders for one u, from [`Grating::peaks`].
///
/// ```
/// use diffraction::{Band, Grating};
/// let g = Grating::new(1600.0, 800.0, 1000)?;
/// let peaks = g.peaks(0.9, Band::VISIBLE); // d·u = 1440 nm: orders 2, 3 and 4
/// assert_eq!(peaks.len(), 3);
/// assert!(!peaks.specular());
/// assert_eq!(peaks.map(|p| p.order).max(), Some(4));
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct Peaks {
    orders: Orders,
    duty: f64,
    n: f64,
    specular: bool,
}

impl Peaks {
    /// Whether u lies inside the central (order 0, mirror) lobe for some wavelength of the band:
    /// |u| < λ_max/(N·d), or u = 0 exactly for N = ∞. There the model shows the white specular.
    ///
    /// ```
    /// use diffraction::{Band, Grating};
    /// let g = Grating::new(1600.0, 800.0, 1000)?;
    /// // Order 0's half-width at 830 nm is 830/(N·d) ≈ 5.19e-4 in u.
    /// assert!(g.peaks(5e-4, Band::VISIBLE).specular());
    /// assert!(!g.peaks(6e-4, Band::VISIBLE).specular());
    /// let ideal = Grating::infinite(1600.0, 800.0)?; // N = ∞: only u = 0
    /// assert!(ideal.peaks(0.0, Band::VISIBLE).specular());
    /// assert!(!ideal.peaks(5e-4, Band::VISIBLE).specular());
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn specular(&self) -> bool {
        self.specular
    }
}

impl Iterator for Peaks {
    type Item = Peak;

    #[inline]
    fn next(&mut self) -> Option<Peak> {
        let o = self.orders.next()?;
        let am = o.order.unsigned_abs() as f64;
        Some(Peak {
            order: o.order,
            wavelength_nm: o.wavelength_nm,
            intensity: single_slit_cycles(self.duty * am),
            equivalent_width_nm: o.wavelength_nm / (am * self.n),
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.orders.size_hint()
    }
}

impl ExactSizeIterator for Peaks {}
impl core::iter::FusedIterator for Peaks {}

/// One propagating diffracted order (see [`Grating::diffracted_orders`]).
///
/// ```
/// use diffraction::Grating;
/// use glam::DVec3;
/// let g = Grating::new(1600.0, 800.0, 100)?;
/// let mut orders = g.diffracted_orders(DVec3::new(-0.6, 0.0, 0.8), 500.0);
/// let mirror = orders.find(|o| o.order == 0).unwrap();
/// assert!((mirror.direction - DVec3::new(0.6, 0.0, 0.8)).length() < 1e-15); // rounding only
/// assert_eq!(mirror.intensity, 1.0); // S(0)
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffractedOrder {
    /// The order m (0 is the mirror direction).
    pub order: i32,
    /// The outgoing unit direction in the local frame (z normal, x grating vector).
    pub direction: DVec3,
    /// The single-slit envelope S(β_m) of this order, the intensity of its maximum.
    pub intensity: f64,
}

/// The propagating orders for one incidence and wavelength, from [`Grating::diffracted_orders`].
///
/// ```
/// use diffraction::Grating;
/// use glam::DVec3;
/// let g = Grating::new(1600.0, 800.0, 100)?;
/// // Normal incidence, λ/d = 1/2: wo_x = m/2, so |m| = 2 would graze (wo_z = 0) and is skipped.
/// let orders: Vec<i32> = g.diffracted_orders(DVec3::Z, 800.0).map(|o| o.order).collect();
/// assert_eq!(orders, [-1, 0, 1]);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct DiffractedOrders {
    orders: Propagating,
    duty: f64,
}

impl Iterator for DiffractedOrders {
    type Item = DiffractedOrder;

    fn next(&mut self) -> Option<DiffractedOrder> {
        let (order, direction) = self.orders.next()?;
        Some(DiffractedOrder {
            order,
            direction,
            intensity: single_slit_cycles(self.duty * order as f64),
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.orders.size_hint()
    }
}

impl ExactSizeIterator for DiffractedOrders {}
impl core::iter::FusedIterator for DiffractedOrders {}
