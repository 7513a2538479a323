//! The metal under a relief grating: its complex refractive index n + ik over the visible band
//! (tabulated measurements, or a constant given by the user) and its Fresnel reflectances.

use core::fmt;
use core::str::FromStr;

use super::fresnel;
use crate::data::metals_data::{AG_NK, AL_NK, AU_NK, CR_NK, CU_NK};
use crate::error::{Error, Requirement};
use crate::ParseError;

/// The largest n and k [`Metal::custom`] accepts: above every measured material in the visible
/// and the near infrared (metals reach k ≈ 10-100 there), and far from any overflow (|N²| stays
/// below 10⁹).
///
/// ```
/// use diffraction::relief::{Metal, MAX_INDEX};
/// assert!(Metal::custom(MAX_INDEX, MAX_INDEX).is_ok());
/// assert_eq!(Metal::custom(2.0 * MAX_INDEX, 1.0).unwrap_err().parameter(), "n");
/// ```
pub const MAX_INDEX: f64 = 1e4;

/// A metal's complex refractive index n + ik as a function of wavelength, with its Fresnel
/// reflectances.
///
/// The tabulated metals are measurements at the sources' own wavelengths, generated into the
/// crate by `python_ref/metals.py` (`src/data/metals_data.rs`: Al from Rakić, Appl. Opt. 34, 4755
/// (1995); Ag, Au and Cu from Johnson & Christy, Phys. Rev. B 6, 4370 (1972); Cr from Johnson &
/// Christy, Phys. Rev. B 9, 5056 (1974)), each row set covering 200-1937 nm at least (the
/// visible band, and the wavelengths a reduced conical table's |β| planes reach beyond it;
/// [`Metal::wavelength_range_nm`]). n and k are each interpolated linearly in λ between
/// neighbouring rows; outside the rows the nearest end row is used. [`Metal::custom`] is a
/// constant n + ik at every wavelength.
///
/// ```
/// use diffraction::relief::Metal;
/// let (n, k) = Metal::AL.index(550.0);
/// assert!((n - 1.0152).abs() < 1e-4 && (k - 6.6273).abs() < 1e-4);
/// let (rs, rp) = Metal::AL.reflectance(550.0, 1.0); // normal incidence
/// assert!((rs - 0.9154).abs() < 1e-4 && (rs - rp).abs() < 1e-15);
/// let glass = Metal::custom(1.5, 0.0)?;
/// assert!((glass.reflectance(550.0, 1.0).0 - 0.04).abs() < 1e-15);
/// assert_eq!("Au".parse::<Metal>()?, Metal::AU);
/// assert_eq!("1.5+0i".parse::<Metal>()?, glass);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Metal {
    kind: Kind,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Table {
        name: &'static str,
        rows: &'static [[f64; 3]],
    },
    Custom {
        n: f64,
        k: f64,
    },
}

impl Metal {
    /// Aluminium (Rakić 1995): n + ik = 1.015 + 6.627i at 550 nm, normal reflectance 0.915.
    pub const AL: Metal = Metal::table("Al", &AL_NK);
    /// Silver (Johnson & Christy 1972).
    pub const AG: Metal = Metal::table("Ag", &AG_NK);
    /// Gold (Johnson & Christy 1972).
    pub const AU: Metal = Metal::table("Au", &AU_NK);
    /// Copper (Johnson & Christy 1972).
    pub const CU: Metal = Metal::table("Cu", &CU_NK);
    /// Chromium (Johnson & Christy 1974).
    pub const CR: Metal = Metal::table("Cr", &CR_NK);
    /// The tabulated metals, in the order Al, Ag, Au, Cu, Cr.
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// let names: Vec<_> = Metal::TABULATED.iter().map(|m| m.name()).collect();
    /// assert_eq!(names, ["Al", "Ag", "Au", "Cu", "Cr"]);
    /// ```
    pub const TABULATED: [Metal; 5] = [Metal::AL, Metal::AG, Metal::AU, Metal::CU, Metal::CR];

    const fn table(name: &'static str, rows: &'static [[f64; 3]]) -> Metal {
        Metal {
            kind: Kind::Table { name, rows },
        }
    }

    /// A material of constant index n + ik: n finite in (0, [`MAX_INDEX`]], k finite in
    /// [0, [`MAX_INDEX`]] (k = 0: a lossless dielectric). Errors name `n` or `k`.
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// let m = Metal::custom(1.02, 6.64)?;
    /// assert_eq!(m.index(400.0), (1.02, 6.64));
    /// assert_eq!(m.name(), "custom");
    /// assert_eq!(Metal::custom(0.0, 6.0).unwrap_err().parameter(), "n");
    /// assert_eq!(Metal::custom(1.0, -1.0).unwrap_err().parameter(), "k");
    /// assert_eq!(Metal::custom(1.0, f64::NAN).unwrap_err().parameter(), "k");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn custom(n: f64, k: f64) -> Result<Metal, Error> {
        if !(n.is_finite() && n > 0.0 && n <= MAX_INDEX) {
            return Err(Error::invalid(
                "n",
                n,
                Requirement::AtMost {
                    bound_name: "MAX_INDEX",
                    bound: MAX_INDEX,
                },
            ));
        }
        if !(k.is_finite() && (0.0..=MAX_INDEX).contains(&k)) {
            return Err(Error::invalid(
                "k",
                k,
                Requirement::Within {
                    min: 0.0,
                    max: MAX_INDEX,
                },
            ));
        }
        Ok(Metal {
            kind: Kind::Custom { n, k },
        })
    }

    /// The metal's short name: `"Al"`, `"Ag"`, `"Au"`, `"Cu"`, `"Cr"`, or `"custom"`.
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// assert_eq!(Metal::CR.name(), "Cr");
    /// ```
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self.kind {
            Kind::Table { name, .. } => name,
            Kind::Custom { .. } => "custom",
        }
    }

    /// The complex refractive index (n, k) at `lambda_nm`: linear in λ between the table's rows,
    /// the nearest end row outside them (and for a non-finite λ, the first row); a custom
    /// metal's constant. Always finite, n > 0, k ≥ 0.
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// // Halfway between Rakić's rows at 516.6 nm and 563.57 nm.
    /// let (n, k) = Metal::AL.index(0.5 * (516.6 + 563.57));
    /// assert!((n - 0.5 * (0.8734 + 1.0728)).abs() < 1e-15);
    /// assert!((k - 0.5 * (6.2418 + 6.7839)).abs() < 1e-15);
    /// assert_eq!(Metal::AL.index(100.0), Metal::AL.index(177.12)); // the first row
    /// ```
    #[must_use]
    pub fn index(&self, lambda_nm: f64) -> (f64, f64) {
        match self.kind {
            Kind::Custom { n, k } => (n, k),
            Kind::Table { rows, .. } => interpolate(rows, lambda_nm),
        }
    }

    /// The wavelengths (nm) of the first and the last tabulated row, between which
    /// [`index`](Self::index) interpolates measurements (outside it repeats the end row);
    /// `None` for a custom metal (the same n + ik at every wavelength).
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// assert_eq!(Metal::AL.wavelength_range_nm(), Some((177.12, 2066.4)));
    /// assert_eq!(Metal::AG.wavelength_range_nm(), Some((199.3, 1937.0)));
    /// assert_eq!(Metal::custom(1.0, 7.0)?.wavelength_range_nm(), None);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn wavelength_range_nm(&self) -> Option<(f64, f64)> {
        match self.kind {
            Kind::Custom { .. } => None,
            Kind::Table { rows, .. } => Some((rows[0][0], rows[rows.len() - 1][0])),
        }
    }

    /// The Fresnel reflectances (R_s, R_p) of the flat metal in air at `lambda_nm` for light
    /// arriving at the angle θ with cos θ = `cos_theta` from the normal (clamped to [0, 1]; a
    /// NaN counts as grazing). R_s is for the electric field perpendicular to the plane of
    /// incidence (TE, s), R_p for it in the plane (TM, p); both in [0, 1], equal at normal
    /// incidence and 1 at grazing incidence.
    ///
    /// With N = n + ik and w = √(N² − sin²θ) (principal root):
    /// R_s = |cos θ − w|²/|cos θ + w|², R_p = |N²·cos θ − w|²/|N²·cos θ + w|².
    /// Neither quotient loses precision near normal or grazing incidence (no difference of
    /// nearly equal terms is divided), and both are finite for every input.
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// let (rs, rp) = Metal::AG.reflectance(600.0, 0.5); // 60°
    /// assert!(rp < rs && rs < 1.0);
    /// assert_eq!(Metal::AG.reflectance(600.0, 0.0), (1.0, 1.0));
    /// // A dielectric of index 1.5 at Brewster's angle, tan θ = 1.5: no p reflection.
    /// let glass = Metal::custom(1.5, 0.0)?;
    /// let cos_b = 1.0 / (1.0f64 + 2.25).sqrt();
    /// assert!(glass.reflectance(550.0, cos_b).1 < 1e-30);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn reflectance(&self, lambda_nm: f64, cos_theta: f64) -> (f64, f64) {
        let (n, k) = self.index(lambda_nm);
        fresnel::reflectances(n, k, cos_theta)
    }
}

/// Linear interpolation of (n, k) in the rows [λ, n, k] (strictly increasing λ), constant
/// beyond the ends.
fn interpolate(rows: &[[f64; 3]], lambda_nm: f64) -> (f64, f64) {
    let (first, last) = (rows[0], rows[rows.len() - 1]);
    // A NaN fails every comparison: the first row.
    if lambda_nm.is_nan() || lambda_nm <= first[0] {
        return (first[1], first[2]);
    }
    if lambda_nm >= last[0] {
        return (last[1], last[2]);
    }
    // rows[i][0] < λ ≤ rows[i + 1][0] for exactly one i (at most 18 rows: a scan).
    let i = rows
        .windows(2)
        .position(|w| lambda_nm <= w[1][0])
        .unwrap_or(rows.len() - 2);
    let (a, b) = (rows[i], rows[i + 1]);
    let t = (lambda_nm - a[0]) / (b[0] - a[0]);
    (a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]))
}

/// The spellings [`Metal`]'s `FromStr` accepts.
const METAL_SPELLINGS: &str = "one of Al, Ag, Au, Cu, Cr, or N+Ki (e.g. 1.02+6.64i)";

impl FromStr for Metal {
    type Err = ParseError;

    /// `Al`, `Ag`, `Au`, `Cu`, `Cr` (case-sensitive, as chemists write them), or a constant
    /// index `N+Ki` such as `1.02+6.64i` (both numbers decimal, k ≥ 0), validated as by
    /// [`Metal::custom`].
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// assert_eq!("1.02+6.64i".parse::<Metal>()?.index(500.0), (1.02, 6.64));
    /// let err = "gold".parse::<Metal>().unwrap_err();
    /// assert_eq!(err.to_string(), "unknown metal: expected one of Al, Ag, Au, Cu, Cr, or N+Ki (e.g. 1.02+6.64i)");
    /// assert_eq!("0+1i".parse::<Metal>().unwrap_err().out_of_range(), Some(0.0));
    /// # Ok::<(), diffraction::ParseError>(())
    /// ```
    fn from_str(s: &str) -> Result<Metal, ParseError> {
        if let Some(m) = Metal::TABULATED.iter().find(|m| m.name() == s) {
            return Ok(*m);
        }
        let unknown = ParseError::new("metal", METAL_SPELLINGS);
        let body = s.strip_suffix('i').ok_or(unknown)?;
        let (n, k) = body.split_once('+').ok_or(unknown)?;
        let n: f64 = n.parse().map_err(|_| unknown)?;
        let k: f64 = k.parse().map_err(|_| unknown)?;
        Metal::custom(n, k).map_err(|e| {
            ParseError::number_out_of_range(
                "metal index",
                e.value(),
                "0 < n <= 1e4 and 0 <= k <= 1e4",
            )
        })
    }
}

impl fmt::Display for Metal {
    /// The name of a tabulated metal, `N+Ki` for a custom one (parses back to the same metal).
    ///
    /// ```
    /// use diffraction::relief::Metal;
    /// assert_eq!(Metal::AL.to_string(), "Al");
    /// let m = Metal::custom(1.5, 0.25)?;
    /// assert_eq!(m.to_string(), "1.5+0.25i");
    /// assert_eq!(m.to_string().parse::<Metal>().unwrap(), m);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            Kind::Table { name, .. } => f.write_str(name),
            Kind::Custom { n, k } => write!(f, "{n}+{k}i"),
        }
    }
}
