//! The crate's rigorous presets (feature `presets`): the four tables of
//! `src/data/efficiency_presets_data.rs` as static [`EfficiencyTable`]s.

use core::fmt;
use core::str::FromStr;

use super::{EfficiencyTable, Lookup, NodeQ, Storage, UnitCells};
use crate::data::efficiency_presets_data as data;
use crate::ParseError;

/// The crate's rigorous efficiency presets (`docs/efficiency_tables.md`, "The shipped
/// presets"): tables solved offline by a rigorous electromagnetic solver, shipped as static
/// data.
///
/// They are classical tables (the plane of incidence across the grooves): off that plane
/// (β ≠ 0) they are read as in the classical mount, which puts 41-44 % of the orders with
/// η ≥ 1 % within 10 % of a conical solve at azimuths 30-80° (`docs/validity.md`, "Conical
/// incidence"); [`reduced_table`](Preset::reduced_table) reads them in reduced coordinates
/// instead (80.8 %) for the BSDF.
///
/// ```
/// use diffraction::relief::Preset;
/// let p: Preset = "blazed600".parse()?;
/// assert_eq!(p, Preset::Blazed600);
/// assert_eq!(p.to_string(), "blazed600");
/// assert_eq!(Preset::ALL.len(), 4);
/// assert!("bluray".parse::<Preset>().is_err());
/// # Ok::<(), diffraction::ParseError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Preset {
    /// A pressed CD read through its polycarbonate: lamellar Al ridges, d = 1600 nm,
    /// 110 nm high, duty 0.3125.
    Cd,
    /// A DVD read through its polycarbonate: lamellar Al ridges, d = 740 nm, 105 nm high,
    /// duty 0.4324.
    Dvd,
    /// A ruled aluminium grating, 600 lines/mm, blazed for 500 nm in first-order Littrow.
    Blazed600,
    /// An embossed holographic foil: an aluminium sinusoid of 1000 lines/mm, 100 nm deep.
    Foil,
}

static CD: EfficiencyTable = EfficiencyTable {
    period_nm: data::CD_PERIOD_NM,
    order_min: data::CD_ORDER_MIN,
    order_count: data::CD_ORDER_COUNT,
    storage: Storage::Static {
        sin_theta_i: &data::CD_SIN_THETA_I,
        abs_beta: &[],
        lambda_nm: &data::CD_LAMBDA_NM,
        te: &data::CD_TE,
        tm: &data::CD_TM,
    },
    unit: UnitCells::new(),
    q: NodeQ::new(),
    lookup: Lookup::new(),
};

static DVD: EfficiencyTable = EfficiencyTable {
    period_nm: data::DVD_PERIOD_NM,
    order_min: data::DVD_ORDER_MIN,
    order_count: data::DVD_ORDER_COUNT,
    storage: Storage::Static {
        sin_theta_i: &data::DVD_SIN_THETA_I,
        abs_beta: &[],
        lambda_nm: &data::DVD_LAMBDA_NM,
        te: &data::DVD_TE,
        tm: &data::DVD_TM,
    },
    unit: UnitCells::new(),
    q: NodeQ::new(),
    lookup: Lookup::new(),
};

static BLAZED600: EfficiencyTable = EfficiencyTable {
    period_nm: data::BLAZED600_PERIOD_NM,
    order_min: data::BLAZED600_ORDER_MIN,
    order_count: data::BLAZED600_ORDER_COUNT,
    storage: Storage::Static {
        sin_theta_i: &data::BLAZED600_SIN_THETA_I,
        abs_beta: &[],
        lambda_nm: &data::BLAZED600_LAMBDA_NM,
        te: &data::BLAZED600_TE,
        tm: &data::BLAZED600_TM,
    },
    unit: UnitCells::new(),
    q: NodeQ::new(),
    lookup: Lookup::new(),
};

static FOIL: EfficiencyTable = EfficiencyTable {
    period_nm: data::FOIL_PERIOD_NM,
    order_min: data::FOIL_ORDER_MIN,
    order_count: data::FOIL_ORDER_COUNT,
    storage: Storage::Static {
        sin_theta_i: &data::FOIL_SIN_THETA_I,
        abs_beta: &[],
        lambda_nm: &data::FOIL_LAMBDA_NM,
        te: &data::FOIL_TE,
        tm: &data::FOIL_TM,
    },
    unit: UnitCells::new(),
    q: NodeQ::new(),
    lookup: Lookup::new(),
};

/// The spellings [`Preset`]'s `FromStr` accepts.
const PRESET_SPELLINGS: &str = "one of cd, dvd, blazed600, foil";

impl Preset {
    /// Every preset.
    pub const ALL: [Preset; 4] = [Preset::Cd, Preset::Dvd, Preset::Blazed600, Preset::Foil];

    /// The preset's static table (no allocation).
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert!(core::ptr::eq(Preset::Cd.table(), Preset::Cd.table()));
    /// ```
    #[must_use]
    pub fn table(self) -> &'static EfficiencyTable {
        match self {
            Preset::Cd => &CD,
            Preset::Dvd => &DVD,
            Preset::Blazed600 => &BLAZED600,
            Preset::Foil => &FOIL,
        }
    }

    /// The name `FromStr` and `Display` use (`"cd"`, `"dvd"`, `"blazed600"`, `"foil"`, the
    /// JSON files' names in `data/efficiencies/`).
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert_eq!(Preset::Foil.name(), "foil");
    /// ```
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Preset::Cd => "cd",
            Preset::Dvd => "dvd",
            Preset::Blazed600 => "blazed600",
            Preset::Foil => "foil",
        }
    }

    /// What the preset models, in one sentence.
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert!(Preset::Cd.description().contains("1600 nm"));
    /// ```
    #[must_use]
    pub fn description(self) -> &'static str {
        match self {
            Preset::Cd => {
                "a pressed CD seen through its polycarbonate: lamellar aluminium ridges, \
                 period 1600 nm, 500 nm wide, 110 nm high"
            }
            Preset::Dvd => {
                "a DVD seen through its polycarbonate: lamellar aluminium ridges, \
                 period 740 nm, 320 nm wide, 105 nm high"
            }
            Preset::Blazed600 => {
                "a ruled aluminium grating of 600 lines/mm (period 1666.67 nm), blazed for \
                 500 nm in first-order Littrow (blaze 8.627 degrees)"
            }
            Preset::Foil => {
                "an embossed holographic foil: an aluminium sinusoid of 1000 lines/mm \
                 (period 1000 nm), 100 nm peak-to-valley"
            }
        }
    }

    /// The grating period d, nm (the table's [`period_nm`](EfficiencyTable::period_nm)).
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert_eq!(Preset::Cd.period_nm(), 1600.0);
    /// ```
    #[must_use]
    pub fn period_nm(self) -> f64 {
        self.table().period_nm
    }

    /// The refractive index of the preset's cover at `lambda_nm`: polycarbonate for `Cd` and
    /// `Dvd` ([`polycarbonate_index`](crate::relief::polycarbonate_index), the cover the tables
    /// were solved with), 1 for the bare `Blazed600` and `Foil`.
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert!((Preset::Cd.cover_index(550.0) - 1.589).abs() < 1e-3);
    /// assert_eq!(Preset::Foil.cover_index(550.0), 1.0);
    /// ```
    #[must_use]
    pub fn cover_index(self, lambda_nm: f64) -> f64 {
        match self {
            Preset::Cd | Preset::Dvd => crate::relief::polycarbonate_index(lambda_nm),
            Preset::Blazed600 | Preset::Foil => 1.0,
        }
    }

    /// The preset read in reduced coordinates off the plane across the grooves, in its
    /// cover's medium ([`EfficiencyTable::reduced_from_classical`] at the planes
    /// [`REDUCED_PLANES`](super::REDUCED_PLANES) with [`cover_index`](Self::cover_index);
    /// feature `alloc`): a conical table the BSDF reads at the full incident direction. For
    /// the four presets it puts 80.8 % of the orders with η ≥ 1 % within 10 % of a conical
    /// solve at azimuths 30-80°, where the classical reading of [`table`](Self::table) puts
    /// 41.2 % (`docs/validity.md`, "Conical incidence"). [`conical_table`](Self::conical_table)
    /// is this table built once, what `GratingBsdf::preset` reads. The colour tables tabulate
    /// a conical table on planes of |wi.y|, and the GPU's packed table holds its planes and
    /// reads them as the CPU does (`gpu::pack_efficiency_table`).
    ///
    /// # Errors
    ///
    /// None for the four presets (kept for presets whose table could not be read so).
    ///
    /// ```
    /// use std::sync::Arc;
    /// use diffraction::grating_bsdf::{GratingBsdf, OrderEfficiency};
    /// use diffraction::relief::Preset;
    /// use diffraction::Grating;
    /// let cd = Preset::Cd.reduced_table()?;
    /// assert!(cd.is_conical());
    /// let d = Preset::Cd.period_nm();
    /// let bsdf = GratingBsdf::new(Grating::new(d, 0.5 * d, 1000)?)
    ///     .with_efficiency(OrderEfficiency::from_table(Arc::new(cd))?)?;
    /// # let _ = bsdf;
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[cfg(feature = "alloc")]
    pub fn reduced_table(self) -> Result<EfficiencyTable, crate::Error> {
        self.table()
            .reduced_from_classical(&super::REDUCED_PLANES, |l| self.cover_index(l))
    }
}

impl Preset {
    /// The table [`OrderEfficiency::preset`](crate::grating_bsdf::OrderEfficiency::preset)
    /// reads (feature `std`): [`reduced_table`](Self::reduced_table), built once on first use
    /// (1-5 ms) and kept for the life of the program, so that every BSDF of the preset shares
    /// it. The BSDF reads it at the full incident direction, across and along the grooves.
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// let cd = Preset::Cd.conical_table();
    /// assert!(cd.is_conical());
    /// assert!(core::ptr::eq(cd, Preset::Cd.conical_table()));
    /// ```
    #[cfg(feature = "std")]
    #[must_use]
    pub fn conical_table(self) -> &'static EfficiencyTable {
        // `reduced_table` succeeds for the four presets (tests/reduced_table.rs); the
        // classical table stands in were it ever to fail.
        self.conical_slot()
            .get_or_init(|| self.reduced_table().ok())
            .as_ref()
            .unwrap_or(self.table())
    }

    /// The preset whose [`conical_table`](Self::conical_table) `table` is (by address), if it
    /// was built.
    #[cfg(feature = "std")]
    pub(crate) fn of_conical_table(table: &EfficiencyTable) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| {
            p.conical_slot()
                .get()
                .and_then(Option::as_ref)
                .is_some_and(|t| core::ptr::eq(t, table))
        })
    }

    /// Where [`conical_table`](Self::conical_table) keeps the preset's table.
    #[cfg(feature = "std")]
    fn conical_slot(self) -> &'static std::sync::OnceLock<Option<EfficiencyTable>> {
        use std::sync::OnceLock;
        static HELD: [OnceLock<Option<EfficiencyTable>>; 4] = [const { OnceLock::new() }; 4];
        match self {
            Preset::Cd => &HELD[0],
            Preset::Dvd => &HELD[1],
            Preset::Blazed600 => &HELD[2],
            Preset::Foil => &HELD[3],
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Preset {
    type Err = ParseError;

    /// `cd`, `dvd`, `blazed600` or `foil` (lower case, the names of `data/efficiencies/`).
    ///
    /// ```
    /// use diffraction::relief::Preset;
    /// assert_eq!("dvd".parse::<Preset>()?, Preset::Dvd);
    /// assert_eq!(
    ///     "CD".parse::<Preset>().unwrap_err().to_string(),
    ///     "unknown efficiency preset: expected one of cd, dvd, blazed600, foil"
    /// );
    /// # Ok::<(), diffraction::ParseError>(())
    /// ```
    fn from_str(s: &str) -> Result<Preset, ParseError> {
        Preset::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or(ParseError::new("efficiency preset", PRESET_SPELLINGS))
    }
}
