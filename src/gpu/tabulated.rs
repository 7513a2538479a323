//! Tabulated order efficiencies for the GPU (feature `relief`): an [`EfficiencyTable`] packed
//! into the words of one read-only storage buffer, `diffraction_efficiency_tables:
//! array<f32>` ([`efficiency_table_bindings`](super::efficiency_table_bindings)), read by
//! `TABULATED_WGSL` with the CPU's interpolation rule.
//!
//! The layout is documented on [`GpuEfficiencyTables`].

use alloc::vec::Vec;

use crate::error::{Error, Requirement};
use crate::relief::EfficiencyTable;

/// The words of a table's header in `diffraction_efficiency_tables`.
pub const EFFICIENCY_HEADER_WORDS: usize = 10;

/// The words of a conical table's section before its axes: the offsets of its q's, its stored
/// values and its marks, its band, and its format (0 reduced, 1 a version-2 tensor grid).
const REDUCED_HEADER_WORDS: usize = 6;

/// The most words one packed table may have: its offsets and counts are f32 words, exact up
/// to 2²⁴ (a table of about 5.6 million values per polarisation, or fewer for a reduced one).
pub const MAX_PACKED_TABLE_WORDS: usize = 1 << 24;

/// The CPU's grazing corner (`relief/table.rs`): cos² θm at or below this does not propagate.
const GRAZING_CORNER: f64 = 1e-6;

/// The number of words [`pack_efficiency_table`] writes for `table`.
fn packed_words(table: &EfficiencyTable) -> usize {
    let (n_s, n_l, k) = (
        table.sin_theta_i().len(),
        table.lambda_nm().len(),
        table.order_count(),
    );
    let classical = EFFICIENCY_HEADER_WORDS + n_s + n_l + 3 * k * n_l * n_s + (n_s - 1) * (n_l - 1);
    if !table.is_conical() {
        return classical;
    }
    let rows: Vec<usize> = (0..table.abs_beta().len())
        .map(|p| table.plane_lambda_nm(p).len())
        .collect();
    let n_b = rows.len();
    let all: usize = rows.iter().sum();
    let cells: usize = if table.is_reduced() {
        rows.windows(2).map(|r| (n_s - 1) * (r[0] + r[1] - 3)).sum()
    } else {
        (n_b - 1) * (n_l - 1) * (n_s - 1)
    };
    classical + REDUCED_HEADER_WORDS + 3 * n_b + 1 + all + 3 * k * all * n_s + cells
}

/// One table in the layout of [`GpuEfficiencyTables`], as f32 words.
///
/// # Errors
///
/// `table` ([`Requirement::AtMost`] [`MAX_PACKED_TABLE_WORDS`], the value the table's word
/// count): the words' offsets would not be exact in f32.
///
/// ```
/// # #[cfg(feature = "presets")] {
/// use diffraction::gpu::pack_efficiency_table;
/// use diffraction::relief::Preset;
/// let t = Preset::Cd.table();
/// let words = pack_efficiency_table(t)?;
/// let (n_s, n_l, k) = (t.sin_theta_i().len(), t.lambda_nm().len(), t.order_count());
/// assert_eq!(words.len(), 10 + n_s + n_l + 3 * k * n_l * n_s + (n_s - 1) * (n_l - 1));
/// assert_eq!((words[0], words[3], words[4]), (1600.0, -8.0, 17.0));
/// // A classical table: no planes, no reduced section.
/// assert_eq!((words[8], words[9]), (0.0, 0.0));
/// # }
/// # Ok::<(), diffraction::Error>(())
/// ```
pub fn pack_efficiency_table(table: &EfficiencyTable) -> Result<Vec<f32>, Error> {
    let size = packed_words(table);
    if size > MAX_PACKED_TABLE_WORDS {
        return Err(Error::invalid(
            "table",
            size as f64,
            Requirement::AtMost {
                bound_name: "MAX_PACKED_TABLE_WORDS",
                bound: MAX_PACKED_TABLE_WORDS as f64,
            },
        ));
    }
    let sin: Vec<f64> = table.sin_theta_i().collect();
    let lam: Vec<f64> = table.lambda_nm().collect();
    let (n_s, n_l, count) = (sin.len(), lam.len(), table.order_count());
    let values = EFFICIENCY_HEADER_WORDS + n_s + n_l;
    let nodes = count * n_l * n_s;
    let cells = (n_s - 1) * (n_l - 1);
    let mut w = Vec::with_capacity(size);
    let d = table.period_nm();
    w.extend_from_slice(&[
        d as f32,
        n_s as f32,
        n_l as f32,
        *table.orders().start() as f32,
        count as f32,
        values as f32,
        (values + 3 * nodes) as f32,
        (values + 2 * nodes) as f32,
        0.0,
        0.0,
    ]);
    w.extend(sin.iter().map(|&s| s as f32));
    w.extend(lam.iter().map(|&l| l as f32));
    // A reduced conical table (version 3): its first plane's own nodes, read there alone (its
    // planes follow in its section).
    let reduced = table.is_reduced();
    for m in table.orders() {
        let mf = f64::from(m);
        for (j, &l) in lam.iter().enumerate() {
            for (i, &s) in sin.iter().enumerate() {
                // The CPU's corner test, with its operations (relief/table.rs, `Cell::order`).
                let sm = s + mf * l / d;
                let cm2 = 1.0 - sm * sm;
                if cm2 > GRAZING_CORNER {
                    let e = if reduced {
                        table.first_plane_node(m, j, i)
                    } else {
                        table.efficiency(m, s, l)
                    };
                    let g = crate::num::math::sqrt(1.0 - s * s) / crate::num::math::sqrt(cm2);
                    w.push((e.te * g) as f32);
                    w.push((e.tm * g) as f32);
                } else {
                    w.extend_from_slice(&[-1.0, -1.0]);
                }
            }
        }
    }
    // The sampler's proposal reads the stored values themselves (`EfficiencyTable`'s
    // unpolarised (TE + TM)/2), flattened as the q's; of a conical table its β = 0 plane, the
    // plane the q's above read (the first of each order's slice: a reduced table's slice holds
    // every plane's own rows).
    let slice = n_s
        * (0..table.abs_beta().len().max(1))
            .map(|p| table.plane_lambda_nm(p).len())
            .sum::<usize>();
    for k in 0..count {
        for at in 0..n_l * n_s {
            w.push(table.stored_unpolarised(k * slice + at) as f32);
        }
    }
    // The cells whose queries need no normalisation (the CPU's per-cell bound; none of a
    // conical table, whose bounds hold for its own reading, not the GPU's classical one).
    let conical = table.is_conical();
    w.extend((0..cells).map(|c| {
        if !conical && table.cell_needs_no_normalisation(c) {
            1.0
        } else {
            0.0
        }
    }));
    if let Some(parts) = table.reduced_parts() {
        pack_reduced(&mut w, &parts, n_s);
    }
    debug_assert_eq!(w.len(), size);
    Ok(w)
}

/// Appends a reduced table's section (layout on [`GpuEfficiencyTables`]) and sets the
/// header's plane count and offset.
fn pack_reduced(w: &mut Vec<f32>, p: &crate::relief::ReducedParts, n_s: usize) {
    let at = w.len();
    let n_b = p.abs_beta.len();
    let rows = p.rows[n_b];
    let axes = REDUCED_HEADER_WORDS + 2 * n_b + (n_b + 1) + rows;
    let (q, e) = (at + axes, at + axes + 2 * p.q.len());
    let m = e + p.unpolarised.len();
    w[8] = n_b as f32;
    w[9] = at as f32;
    w.extend_from_slice(&[
        q as f32,
        e as f32,
        m as f32,
        p.band.0 as f32,
        p.band.1 as f32,
        if p.tensor { 1.0 } else { 0.0 },
    ]);
    w.extend(p.abs_beta.iter().map(|&b| b as f32));
    w.extend(p.c.iter().map(|&c| c as f32));
    w.extend(p.rows.iter().map(|&r| r as f32));
    w.extend(p.lambda_nm.iter().map(|&l| l as f32));
    for v in &p.q {
        match v {
            Some([te, tm]) => w.extend_from_slice(&[*te as f32, *tm as f32]),
            None => w.extend_from_slice(&[-1.0, -1.0]),
        }
    }
    w.extend(p.unpolarised.iter().map(|&u| u as f32));
    w.extend(p.marks.iter().map(|&b| if b { 1.0 } else { 0.0 }));
    debug_assert_eq!(p.q.len() % (rows * n_s), 0);
}

/// Several packed tables in one storage buffer, each at the word offset [`push`](Self::push)
/// returns (a [`GpuBsdf`](super::GpuBsdf)'s `table`).
///
/// **Layout** of one table at word `o` (every integer is exact in f32; the table's offset is
/// [`GpuBsdf::table`](super::GpuBsdf::table)):
///
/// | words | what |
/// |---|---|
/// | `o + 0` | d, nm |
/// | `o + 1`, `o + 2` | n_s, n_λ: the node counts of sin θi and λ |
/// | `o + 3`, `o + 4` | the first stored order and the number of orders K |
/// | `o + 5` | V: the offset of the values from `o` (10 + n_s + n_λ) |
/// | `o + 6` | M: the offset of the cells' marks from `o` (P + K·n_λ·n_s) |
/// | `o + 7` | P: the offset of the node efficiencies from `o` (V + 2·K·n_λ·n_s) |
/// | `o + 8`, `o + 9` | n_β, R: a reduced conical table's plane count and the offset of its section from `o` (0 and 0 for any other table) |
/// | `o + 10 ..` | the n_s sin θi nodes, then the n_λ wavelength nodes (nm), ascending |
/// | `o + V ..` | per order k, wavelength node j, sin node i: (q_TE, q_TM) at `o + V + 2·((k·n_λ + j)·n_s + i)` |
/// | `o + P ..` | the stored unpolarised η = (TE + TM)/2 at `o + P + (k·n_λ + j)·n_s + i`, what the sampler's cell proposal reads |
/// | `o + M ..` | per interpolation cell (j, i) at `o + M + j·(n_s − 1) + i`: 1 where no query in it needs the normalisation (the CPU's per-cell bound), else 0 |
///
/// q = η·cos θi/cos θm at the node (what the CPU interpolates), or −1 where the order does not
/// propagate there (cos² θm ≤ 10⁻⁶, the CPU's grazing corner: such a corner never enters the
/// interpolation). The node values are the table's own query at the node
/// ([`EfficiencyTable::efficiency`], where the cell's weights are exactly 0 and 1): the stored
/// values to an f64 rounding, or, at a node whose stored sum over orders exceeds 1 (at most
/// 1 + 10⁻⁶ on load), the values scaled to sum 1.
///
/// A **conical table** (a reduced one, version 3, [`EfficiencyTable::is_reduced`]: the
/// presets' `Preset::conical_table`, which `GratingBsdf::preset` reads; or a version-2 tensor
/// grid) packs its first plane as above (a reduced table's on that plane's own wavelength
/// nodes; no cell marked), then its section at `o + R`, which `diffraction_eta_conical` and
/// the tabulated BSDF read at the full incident direction, as the CPU does (a classical table
/// is read at sin θi = α, ignoring β):
///
/// | words | what |
/// |---|---|
/// | `o + R + 0 ..= 2` | Q, E, M′: the offsets from `o` of its q's, stored values and marks |
/// | `o + R + 3`, `o + R + 4` | the band [λ0, λ1] a query's wavelength is clamped to |
/// | `o + R + 5` | 0 for a reduced table, 1 for a version-2 tensor grid (its planes blended linearly in \|β\| and read at the query's λ) |
/// | `o + R + 6 ..` | the n_β planes' \|β\|, their c = √(1 − β²), the n_β + 1 starts of their wavelength rows (n_rows in all; a version-2 table's planes each hold its n_λ nodes), and every plane's wavelength nodes |
/// | `o + Q ..` | per order k, row r, s′ node i: (q_TE, q_TM) at `o + Q + 2·((k·n_rows + r)·n_s + i)`, of the stored values at the node's conical incidence (α = s′·c_p, β_p, λ_r), −1 where the order does not propagate there |
/// | `o + E ..` | the stored unpolarised η at `o + E + (k·n_rows + r)·n_s + i` |
/// | `o + M′ ..` | per cell, numbered as the CPU numbers them (a reduced table per slab between planes p and p + 1, i + (n_s − 1)·(j_p + j_p+1); a version-2 table (k·(n_λ − 1) + j)·(n_s − 1) + i): 1 where no query in it needs the normalisation |
///
/// ```
/// # #[cfg(all(feature = "presets", feature = "std"))] {
/// use diffraction::gpu::{GpuBsdf, GpuEfficiencyTables};
/// use diffraction::relief::Preset;
/// use diffraction::GratingBsdf;
/// let mut tables = GpuEfficiencyTables::default();
/// // `GratingBsdf::preset` reads the preset's conical table: pack that one.
/// let cd = GratingBsdf::preset(Preset::Cd, 34)?;
/// let dvd = GratingBsdf::preset(Preset::Dvd, 34)?;
/// let at_cd = tables.push(Preset::Cd.conical_table())?;
/// let at_dvd = tables.push(Preset::Dvd.conical_table())?;
/// let (g_cd, g_dvd) = (GpuBsdf::new(&cd, 0).with_table(at_cd), GpuBsdf::new(&dvd, 0).with_table(at_dvd));
/// assert_eq!((g_cd.table, g_dvd.table), (0, at_dvd));
/// assert_eq!(tables.to_bytes().len(), 4 * tables.words().len());
/// # }
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GpuEfficiencyTables {
    words: Vec<f32>,
}

impl GpuEfficiencyTables {
    /// Appends `table` ([`pack_efficiency_table`]); returns its word offset.
    ///
    /// # Errors
    ///
    /// `table`: as [`pack_efficiency_table`], or ([`Requirement::AtMost`] `u32::MAX`, the value
    /// the buffer's word count with it) when its offset or end would not fit the `u32` word
    /// offsets of [`GpuBsdf::table`](super::GpuBsdf::table). The buffer is unchanged then.
    pub fn push(&mut self, table: &EfficiencyTable) -> Result<u32, Error> {
        let words = pack_efficiency_table(table)?;
        let end = self.words.len() + words.len();
        if end > u32::MAX as usize {
            return Err(Error::invalid(
                "table",
                end as f64,
                Requirement::AtMost {
                    bound_name: "u32::MAX words",
                    bound: u32::MAX as f64,
                },
            ));
        }
        let at = self.words.len() as u32;
        self.words.extend(words);
        Ok(at)
    }

    /// The [`GpuBsdf`](super::GpuBsdf) of `bsdf` ([`GpuBsdf::new`](super::GpuBsdf::new) with
    /// `first_row`), with the table it reads appended here and its offset set: the table
    /// `bsdf.order_efficiency().table()` holds, so the WGSL reads what the CPU reads (a preset
    /// from [`GratingBsdf::preset`](crate::GratingBsdf::preset) its conical table, one from
    /// `OrderEfficiency::from_static(preset.table())` the classical one). The amplitude model
    /// packs nothing and keeps [`NO_TABLE`](super::NO_TABLE). Each call packs its table anew;
    /// models that share one table can share one [`push`](Self::push) through
    /// [`GpuBsdf::with_table`](super::GpuBsdf::with_table).
    ///
    /// # Errors
    ///
    /// As [`push`](Self::push); the buffer is unchanged then.
    ///
    /// ```
    /// # #[cfg(all(feature = "presets", feature = "std"))] {
    /// use diffraction::gpu::{GpuEfficiencyTables, NO_TABLE};
    /// use diffraction::relief::Preset;
    /// use diffraction::{Grating, GratingBsdf};
    /// let mut tables = GpuEfficiencyTables::default();
    /// let flat = tables.push_bsdf(&GratingBsdf::new(Grating::new(1600.0, 800.0, 34)?), 0)?;
    /// assert_eq!((flat.table, tables.words().len()), (NO_TABLE, 0));
    /// let cd = tables.push_bsdf(&GratingBsdf::preset(Preset::Cd, 34)?, 65)?;
    /// assert_eq!(cd.table, 0);
    /// // The conical table the preset reads: its planes follow its first one.
    /// assert_eq!(tables.words()[8] as usize, Preset::Cd.conical_table().abs_beta().len());
    /// # }
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn push_bsdf(
        &mut self,
        bsdf: &crate::GratingBsdf,
        first_row: u32,
    ) -> Result<super::GpuBsdf, Error> {
        let g = super::GpuBsdf::new(bsdf, first_row);
        match bsdf.order_efficiency().table() {
            Some(t) => Ok(g.with_table(self.push(t)?)),
            None => Ok(g),
        }
    }

    /// The words.
    #[must_use]
    pub fn words(&self) -> &[f32] {
        &self.words
    }

    /// The little-endian bytes to upload (4 per word).
    #[must_use]
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(4 * self.words.len());
        for w in &self.words {
            out.extend_from_slice(&w.to_bits().to_le_bytes());
        }
        out
    }
}
