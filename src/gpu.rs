//! WGSL shaders of the kernels, the colour table's lookup and the paper's eq. 12, and the
//! plain-data structs a renderer uploads for them (feature `gpu`, no dependency: the renderer
//! brings its own wgpu or Bevy).
//!
//! WGSL has no modules: a renderer concatenates the sources it needs (in any order; WGSL
//! declarations are order-independent) with its own code, or registers them with its shader
//! composer. Every function and struct is prefixed `diffraction_` / `Diffraction`.
//!
//! | constant | functions | needs |
//! |---|---|---|
//! | [`KERNEL_WGSL`] | `diffraction_single_slit_cycles(y)`, `diffraction_n_slit_cycles(x, n)`, `diffraction_intensity_cycles(x, y, n)` | nothing |
//! | [`TYPES_WGSL`] | the structs of [`GpuGrating`], [`GpuIllumination`], [`GpuTableHeader`], [`GpuTableBlock`], [`GpuTableNode`] | nothing |
//! | [`COLOR_TABLE_WGSL`] | `diffraction_table_lookup(u) -> XYZ` | types, [`color_table_bindings`] |
//! | [`INCIDENCE_WGSL`] | `diffraction_table_colour(u, s) -> XYZ`: the table's colour at the incidence s = wi.x (a table of tabulated efficiencies); `diffraction_table_colour_conical(u, s, b) -> XYZ`: a conical table's, on its planes of b = min(\|wi.y\|, \|wo.y\|) | colour table, [`incidence_bindings`] |
//! | [`SHADING_WGSL`] | `diffraction_shade` (eq. 12), `diffraction_shade_grating`, `diffraction_xyz_to_linear_srgb`, `diffraction_phase_u` | types, colour table |
//! | [`BSDF_WGSL`] | `diffraction_bsdf_f`, `diffraction_bsdf_pdf`, `diffraction_bsdf_sample`: the radiometric [`GratingBsdf`] (amplitude efficiencies) from a [`GpuBsdf`] | types, kernels, [`bsdf_bindings`] |
//! | [`TABULATED_WGSL`] | `diffraction_bsdf_tabulated_f`, `_pdf`, `_sample`, `diffraction_eta`, `diffraction_eta_conical`: a tabulated model from its packed table (`GpuEfficiencyTables`, feature `relief`; a conical table read at the full incident direction) | types, kernels, BSDF, [`efficiency_table_bindings`] |
//!
//! [`shading_source`] is all of it with the table's and the BSDF's bindings at a group and
//! binding of your choice. The kernels are the f32 twins of [`kernel::single_slit_cycles`] and
//! [`kernel::n_slit_cycles`] with the same exact phase reduction (N·r modulo 1 in 64-bit integer
//! arithmetic on two `u32` words) and the same guarded limits; they use no built-in `sin`
//! (WGSL allows it an absolute error of 2⁻¹¹). On any conforming WGSL implementation each
//! factor is within 1·10⁻⁵ (absolute) of the exact value at its f32 argument; measured on Mesa
//! lavapipe 2.3·10⁻⁷. The derivation and the measurements are in `docs/gpu.md`.
//!
//! ```
//! use diffraction::gpu::{GpuColorTable, GpuGrating, shading_source};
//! use diffraction::spectrum::{Illuminant, Spectral};
//! use diffraction::{ColorTable, Grating};
//! let g = Grating::new(1600.0, 800.0, 300)?;
//! let table = ColorTable::new(&Spectral::new(Illuminant::D65), &g, 1e-3)?;
//! let gpu = GpuColorTable::new(&table);
//! // Upload: the header as a uniform, the blocks and nodes as read-only storage buffers.
//! assert_eq!(gpu.header_bytes().len(), 16);
//! assert_eq!(gpu.blocks_bytes().len(), 20 * gpu.blocks.len());
//! assert_eq!(gpu.nodes_bytes().len(), 32 * gpu.nodes.len());
//! assert_eq!(GpuGrating::from(&g).to_bytes().len(), 16);
//! let wgsl = shading_source(1, 0); // bindings 0, 1, 2 of group 1
//! assert!(wgsl.contains("fn diffraction_shade_grating("));
//! # Ok::<(), diffraction::Error>(())
//! ```
//!
//! [`kernel::single_slit_cycles`]: crate::num::kernel::single_slit_cycles
//! [`kernel::n_slit_cycles`]: crate::num::kernel::n_slit_cycles

use alloc::format;
use alloc::string::String;
use alloc::vec::Vec;

#[cfg(feature = "relief")]
mod tabulated;
#[cfg(feature = "relief")]
pub use tabulated::{
    pack_efficiency_table, GpuEfficiencyTables, EFFICIENCY_HEADER_WORDS, MAX_PACKED_TABLE_WORDS,
};

use crate::grating_bsdf::DEFENSIVE_ORDER_SHARE;
use crate::num::special::atan;
use crate::{ColorTable, Grating, GratingBsdf, GrooveKind, Illumination, Slits};

/// The slit kernels in f32, phases in cycles (see the [module docs](self)).
pub const KERNEL_WGSL: &str = include_str!("gpu/kernel.wgsl");
/// The WGSL structs matching [`GpuGrating`], [`GpuIllumination`], [`GpuTableHeader`],
/// [`GpuTableBlock`] and [`GpuTableNode`].
pub const TYPES_WGSL: &str = include_str!("gpu/types.wgsl");
/// The colour table's lookup, `diffraction_table_lookup(u) -> vec3<f32>` (XYZ); needs
/// [`TYPES_WGSL`] and the bindings of [`color_table_bindings`].
pub const COLOR_TABLE_WGSL: &str = include_str!("gpu/color_table.wgsl");
/// The colour at an incidence, `diffraction_table_colour(u, s) -> vec3<f32>` (XYZ; a table of
/// tabulated efficiencies depends on s = wi.x, the others give `diffraction_table_lookup(u)`),
/// and a conical table's off the plane across the grooves,
/// `diffraction_table_colour_conical(u, s, b)` with b = min(|wi.y|, |wo.y|) (its planes of
/// |wi.y|; the first function for any other table); needs [`COLOR_TABLE_WGSL`], its bindings
/// and the binding of [`incidence_bindings`].
pub const INCIDENCE_WGSL: &str = include_str!("gpu/incidence.wgsl");

/// The declaration of the colour table's incidence ([`GpuColorTable::incidence`]) at `group`,
/// `binding`: a read-only storage `array<u32>`.
///
/// ```
/// let b = diffraction::gpu::incidence_bindings(1, 5);
/// assert!(b.contains("@binding(5) var<storage, read> diffraction_table_incidence"));
/// ```
#[must_use]
pub fn incidence_bindings(group: u32, binding: u32) -> String {
    format!(
        "@group({group}) @binding({binding}) var<storage, read> diffraction_table_incidence: \
         array<u32>;\n"
    )
}

/// The paper's eq. 12 and a grating pixel shaded from its colour table; needs
/// [`TYPES_WGSL`] and [`COLOR_TABLE_WGSL`].
pub const SHADING_WGSL: &str = include_str!("gpu/shading.wgsl");

/// The declarations of the colour table's three buffers at `group`, bindings `binding`
/// (the header, a uniform [`GpuTableHeader`]), `binding + 1` (the blocks, read-only storage)
/// and `binding + 2` (the nodes, read-only storage).
///
/// ```
/// let b = diffraction::gpu::color_table_bindings(2, 5);
/// assert!(b.contains("@group(2) @binding(7) var<storage, read> diffraction_table_nodes"));
/// ```
#[must_use]
pub fn color_table_bindings(group: u32, binding: u32) -> String {
    format!(
        "@group({group}) @binding({b0}) var<uniform> diffraction_table: DiffractionTableHeader;\n\
         @group({group}) @binding({b1}) var<storage, read> diffraction_table_blocks: \
         array<DiffractionTableBlock>;\n\
         @group({group}) @binding({b2}) var<storage, read> diffraction_table_nodes: \
         array<DiffractionTableNode>;\n",
        b0 = binding,
        b1 = binding.saturating_add(1),
        b2 = binding.saturating_add(2),
    )
}

/// The radiometric [`GratingBsdf`]'s value f, sampling density pdf and sampler for the
/// amplitude efficiencies, from a [`GpuBsdf`]; needs [`TYPES_WGSL`], [`KERNEL_WGSL`] and the
/// binding of [`bsdf_bindings`].
pub const BSDF_WGSL: &str = include_str!("gpu/bsdf.wgsl");

/// The radiometric [`GratingBsdf`] with tabulated efficiencies (a preset's or any
/// `EfficiencyTable`'s, packed by `GpuEfficiencyTables`): `diffraction_bsdf_tabulated_f`,
/// `_pdf`, `_sample` and the table's interpolation `diffraction_eta` (and
/// `diffraction_eta_conical` at the full incident direction: a conical table, reduced or a
/// version-2 tensor grid, is read conically, as the CPU reads it, a classical one at
/// sin θi = α); needs [`TYPES_WGSL`],
/// [`KERNEL_WGSL`], [`BSDF_WGSL`] and the binding of [`efficiency_table_bindings`].
pub const TABULATED_WGSL: &str = concat!(
    include_str!("gpu/tabulated.wgsl"),
    include_str!("gpu/reduced.wgsl")
);

/// The declaration of the efficiency tables' buffer at `group`, `binding`: a read-only
/// storage `array<f32>` of packed tables (`GpuEfficiencyTables`, feature `relief`).
///
/// ```
/// let b = diffraction::gpu::efficiency_table_bindings(0, 4);
/// assert!(b.contains("@binding(4) var<storage, read> diffraction_efficiency_tables"));
/// ```
#[must_use]
pub fn efficiency_table_bindings(group: u32, binding: u32) -> String {
    format!(
        "@group({group}) @binding({binding}) var<storage, read> diffraction_efficiency_tables: \
         array<f32>;\n"
    )
}

/// Every source of this module with the colour table's bindings at `group`, bindings
/// `binding` to `binding + 2` ([`color_table_bindings`]), the BSDF's order data at
/// `binding + 3` ([`bsdf_bindings`]) and the efficiency tables at `binding + 4`
/// ([`efficiency_table_bindings`]) and the colour table's incidence at `binding + 5`
/// ([`incidence_bindings`]): the kernels, the types, the lookups, eq. 12 and the BSDF of both
/// efficiency models.
#[must_use]
pub fn shading_source(group: u32, binding: u32) -> String {
    let mut s = String::new();
    for part in [
        TYPES_WGSL,
        &color_table_bindings(group, binding),
        &bsdf_bindings(group, binding.saturating_add(3)),
        &efficiency_table_bindings(group, binding.saturating_add(4)),
        &incidence_bindings(group, binding.saturating_add(5)),
        KERNEL_WGSL,
        COLOR_TABLE_WGSL,
        INCIDENCE_WGSL,
        SHADING_WGSL,
        BSDF_WGSL,
        TABULATED_WGSL,
    ] {
        s.push_str(part);
        s.push('\n');
    }
    s
}

/// One grid's nodes, (value, derivative) each, as `ColorTable::gpu_incidence` gives them.
#[cfg(feature = "relief")]
type GridNodes = Vec<([f64; 3], [f64; 3])>;

/// Appends the grids of `table`'s incidence nodes to `blocks` and `nodes` (grid g's blocks
/// from g·(blocks of grid 0) on: node k's over u ≥ 0 is grid 1 + 2k, over u ≤ 0 2 + 2k; every
/// grid of a table has the same blocks), then those of a conical table's other planes, and
/// returns the incidence words of [`GpuColorTable::incidence`].
#[cfg(feature = "relief")]
fn append_incidence(
    table: &ColorTable,
    blocks: &mut Vec<GpuTableBlock>,
    nodes: &mut Vec<GpuTableNode>,
) -> Vec<u32> {
    let Some(t) = table.gpu_incidence() else {
        return Vec::from([0, 0]);
    };
    let block_count = blocks.len();
    let mut words = Vec::new();
    append_plane(t, block_count, blocks, nodes, &mut words);
    let planes = table.gpu_planes();
    words.push(planes.len() as u32);
    let head = words.len();
    words.resize(head + 4 * planes.len(), 0);
    for (p, (b, c, t)) in planes.into_iter().enumerate() {
        let grid_base = (blocks.len() / block_count) as u32;
        let offset = words.len() as u32;
        words[head + 4 * p..head + 4 * p + 4].copy_from_slice(&[
            (b as f32).to_bits(),
            (c as f32).to_bits(),
            offset,
            grid_base,
        ]);
        append_plane(t, block_count, blocks, nodes, &mut words);
    }
    words
}

/// Appends one plane's grids to `blocks` and `nodes` and its words (K, M, the M bins, each
/// node's σ and 1/(next σ − σ)) to `words`.
#[cfg(feature = "relief")]
fn append_plane(
    t: crate::color_table::GpuIncidence<'_>,
    block_count: usize,
    blocks: &mut Vec<GpuTableBlock>,
    nodes: &mut Vec<GpuTableNode>,
    words: &mut Vec<u32>,
) {
    // A grid equal to the one before it (the grid over u ≤ 0 of a mirror-symmetric table,
    // which is the one over u ≥ 0) repeats only its blocks; they point at the same nodes.
    let mut last: Option<(GridNodes, u32)> = None;
    for (grid_blocks, grid_nodes) in t.grids {
        debug_assert_eq!(grid_blocks.len(), block_count);
        let first = match &last {
            Some((prev, at)) if *prev == grid_nodes => *at,
            _ => {
                let at = nodes.len() as u32;
                nodes.extend(grid_nodes.iter().copied().map(gpu_node));
                at
            }
        };
        blocks.extend(
            grid_blocks
                .into_iter()
                .map(|(u0, h, f, n)| gpu_block((u0, h, first + f, n))),
        );
        last = Some((grid_nodes, first));
    }
    words.reserve(2 + t.bins.len() + 2 * t.nodes.len());
    words.extend([t.nodes.len() as u32, t.bins.len() as u32]);
    words.extend_from_slice(t.bins);
    for (sigma, inv_next) in t.nodes {
        words.extend([(sigma as f32).to_bits(), (inv_next as f32).to_bits()]);
    }
}

/// Without the feature `relief` no table has incidence nodes.
#[cfg(not(feature = "relief"))]
fn append_incidence(
    _: &ColorTable,
    _: &mut Vec<GpuTableBlock>,
    _: &mut Vec<GpuTableNode>,
) -> Vec<u32> {
    Vec::from([0, 0])
}

/// A block of `ColorTable::grid` in f32.
fn gpu_block((u0, h, first, n): (f64, f64, u32, u32)) -> GpuTableBlock {
    GpuTableBlock {
        u0: u0 as f32,
        h: h as f32,
        inv_h: (1.0 / h) as f32,
        first,
        n,
    }
}

/// A node of `ColorTable::grid` in f32.
fn gpu_node((f, d): ([f64; 3], [f64; 3])) -> GpuTableNode {
    GpuTableNode {
        f: [f[0] as f32, f[1] as f32, f[2] as f32, 0.0],
        d: [d[0] as f32, d[1] as f32, d[2] as f32, 0.0],
    }
}

/// Little-endian bytes of a list of 4-byte words (what every struct here is made of).
fn words_to_bytes(words: &[u32], out: &mut Vec<u8>) {
    for w in words {
        out.extend_from_slice(&w.to_le_bytes());
    }
}

/// A grating for the GPU, WGSL `DiffractionGrating` (16 bytes): d and w in nm as f32, N as
/// u32 (`u32::MAX` for [`Slits::Infinite`]).
///
/// ```wgsl
/// struct DiffractionGrating { period_nm: f32, slit_width_nm: f32, slits: u32, pad: u32 }
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuGrating {
    /// d, nm.
    pub period_nm: f32,
    /// w, nm.
    pub slit_width_nm: f32,
    /// N (`u32::MAX` for an infinite grating).
    pub slits: u32,
    /// Padding to 16 bytes (0).
    pub pad: u32,
}

impl From<&Grating> for GpuGrating {
    fn from(g: &Grating) -> GpuGrating {
        GpuGrating {
            period_nm: g.period_nm() as f32,
            slit_width_nm: g.slit_width_nm() as f32,
            slits: match g.slits() {
                Slits::Finite(n) => n,
                Slits::Infinite => u32::MAX,
            },
            pad: 0,
        }
    }
}

impl GpuGrating {
    /// The 16 bytes to upload (little-endian, as every wgpu backend reads them).
    #[must_use]
    pub fn to_bytes(&self) -> [u8; 16] {
        let mut out = Vec::with_capacity(16);
        words_to_bytes(
            &[
                self.period_nm.to_bits(),
                self.slit_width_nm.to_bits(),
                self.slits,
                self.pad,
            ],
            &mut out,
        );
        let mut b = [0u8; 16];
        b.copy_from_slice(&out);
        b
    }
}

/// The coefficients of the paper's eq. 12 for the GPU, WGSL `DiffractionIllumination`.
///
/// ```wgsl
/// struct DiffractionIllumination { ambient: f32, diffuse: f32, diffraction: f32, pad: f32 }
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuIllumination {
    /// k_a.
    pub ambient: f32,
    /// k_d.
    pub diffuse: f32,
    /// The diffraction coefficient.
    pub diffraction: f32,
    /// Padding to 16 bytes (0).
    pub pad: f32,
}

impl From<&Illumination> for GpuIllumination {
    fn from(i: &Illumination) -> GpuIllumination {
        let (ambient, diffuse, diffraction) = i.coefficients();
        GpuIllumination {
            ambient: ambient as f32,
            diffuse: diffuse as f32,
            diffraction: diffraction as f32,
            pad: 0.0,
        }
    }
}

impl GpuIllumination {
    /// The 16 bytes to upload.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; 16] {
        let mut out = Vec::with_capacity(16);
        words_to_bytes(
            &[
                self.ambient.to_bits(),
                self.diffuse.to_bits(),
                self.diffraction.to_bits(),
                self.pad.to_bits(),
            ],
            &mut out,
        );
        let mut b = [0u8; 16];
        b.copy_from_slice(&out);
        b
    }
}

/// A colour table's header, WGSL `DiffractionTableHeader` (a uniform, 16 bytes).
///
/// ```wgsl
/// struct DiffractionTableHeader { u_lo: f32, base_key: u32, block_count: u32, node_count: u32 }
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuTableHeader {
    /// The end of block 0 (a power of two).
    pub u_lo: f32,
    /// The key (f32 bits >> 20) of block 1: `u_lo.to_bits() >> 20`.
    pub base_key: u32,
    /// The number of blocks of a grid (a table of tabulated efficiencies has several grids,
    /// see [`GpuColorTable`]).
    pub block_count: u32,
    /// The number of nodes.
    pub node_count: u32,
}

/// One uniform block of a colour table's grid, WGSL `DiffractionTableBlock` (20 bytes).
///
/// ```wgsl
/// struct DiffractionTableBlock { u0: f32, h: f32, inv_h: f32, first: u32, n: u32 }
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuTableBlock {
    /// The first u of the block.
    pub u0: f32,
    /// The node spacing (a power of two).
    pub h: f32,
    /// 1/h (exact).
    pub inv_h: f32,
    /// The index of the block's first node.
    pub first: u32,
    /// The number of intervals (≥ 1).
    pub n: u32,
}

/// One node of a colour table, WGSL `DiffractionTableNode` (32 bytes): XYZ and its derivative in
/// u, the fourth components 0.
///
/// ```wgsl
/// struct DiffractionTableNode { f: vec4<f32>, d: vec4<f32> }
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuTableNode {
    /// X, Y, Z, 0.
    pub f: [f32; 4],
    /// dX/du, dY/du, dZ/du, 0.
    pub d: [f32; 4],
}

/// A [`ColorTable`] for the GPU: its grid in f32, uploaded as one uniform (the header) and two
/// read-only storage buffers (blocks, nodes) and read by `diffraction_table_lookup`.
///
/// A table of tabulated efficiencies (feature `relief`) also holds every incidence node's two
/// grids after its grid of normal incidence (grid g's blocks from g·`block_count` on: node k's
/// over u ≥ 0 is grid 1 + 2k, over u ≤ 0 grid 2 + 2k; where the two are the same grid, as in a
/// mirror-symmetric table, the second repeats the first's blocks and shares its nodes) and the
/// nodes' places in
/// [`incidence`](Self::incidence), a third storage buffer ([`incidence_bindings`]) read by
/// `diffraction_table_colour(u, s)`, the CPU's interpolation in f32 (docs/gpu.md, "Colour
/// tables of tabulated efficiencies").
///
/// The lookup is the CPU's algorithm in f32 (same blocks, same Hermite cells): within a few f32
/// roundings of the nodes' scale of [`ColorTable::lookup`] (docs/gpu.md). Where the table does
/// not resolve order 0's lobe (N·d > 3.3·10²⁰ nm, [`resolved`](Self::resolved) false) the CPU
/// computes lookups with |u| < 2⁻⁶⁴ exactly; the GPU interpolates its three values there.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuColorTable {
    /// The header (uniform).
    pub header: GpuTableHeader,
    /// The blocks (storage).
    pub blocks: Vec<GpuTableBlock>,
    /// The nodes (storage).
    pub nodes: Vec<GpuTableNode>,
    /// The incidence of a table of tabulated efficiencies (storage, `array<u32>`, read by
    /// `diffraction_table_colour`): K (its incidence nodes), M (its bins), the M bins (the node
    /// starting each finest interval of σ), then per node σ and 1/(next σ − σ) as f32 bits;
    /// then P, a conical table's planes of |wi.y| off the plane across the grooves (0 for any
    /// other table), per plane |wi.y| and c = √(1 − wi.y²) as f32 bits, the word where its own
    /// K, M, bins and nodes start and its first grid, and those words (read by
    /// `diffraction_table_colour_conical`); `[0, 0]` for a table without incidence.
    pub incidence: Vec<u32>,
    resolved: bool,
}

impl GpuColorTable {
    /// The grid of `table` in f32.
    #[must_use]
    pub fn new(table: &ColorTable) -> GpuColorTable {
        let (u_lo, exact_below, blocks, nodes) = table.grid();
        let mut blocks: Vec<GpuTableBlock> = blocks.map(gpu_block).collect();
        let mut nodes: Vec<GpuTableNode> = nodes.map(gpu_node).collect();
        let block_count = blocks.len() as u32;
        let incidence = append_incidence(table, &mut blocks, &mut nodes);
        let u_lo = u_lo as f32;
        GpuColorTable {
            header: GpuTableHeader {
                u_lo,
                base_key: u_lo.to_bits() >> 20,
                block_count,
                node_count: nodes.len() as u32,
            },
            blocks,
            nodes,
            incidence,
            resolved: exact_below <= 0.0,
        }
    }

    /// Whether the grid resolves order 0's lobe (false where N·d > 3.3·10²⁰ nm: see the type's
    /// docs).
    #[must_use]
    pub fn resolved(&self) -> bool {
        self.resolved
    }

    /// The header's 16 bytes (the uniform).
    #[must_use]
    pub fn header_bytes(&self) -> Vec<u8> {
        let h = &self.header;
        let mut out = Vec::with_capacity(16);
        words_to_bytes(
            &[h.u_lo.to_bits(), h.base_key, h.block_count, h.node_count],
            &mut out,
        );
        out
    }

    /// The blocks' bytes (20 each, the storage buffer's array).
    #[must_use]
    pub fn blocks_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(20 * self.blocks.len());
        for b in &self.blocks {
            words_to_bytes(
                &[
                    b.u0.to_bits(),
                    b.h.to_bits(),
                    b.inv_h.to_bits(),
                    b.first,
                    b.n,
                ],
                &mut out,
            );
        }
        out
    }

    /// The incidence's bytes (4 a word, the storage buffer's array).
    #[must_use]
    pub fn incidence_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(4 * self.incidence.len());
        words_to_bytes(&self.incidence, &mut out);
        out
    }

    /// The nodes' bytes (32 each, the storage buffer's array).
    #[must_use]
    pub fn nodes_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(32 * self.nodes.len());
        for n in &self.nodes {
            for v in n.f.iter().chain(&n.d) {
                out.extend_from_slice(&v.to_bits().to_le_bytes());
            }
        }
        out
    }
}

/// The radiometric [`GratingBsdf`] for the GPU, WGSL `DiffractionBsdf` (48 bytes), read by
/// `diffraction_bsdf_f`, `diffraction_bsdf_pdf` and `diffraction_bsdf_sample` (the amplitude
/// model) together with its 65 rows of order data in
/// the shared storage buffer `diffraction_bsdf_orders` ([`bsdf_bindings`]), from row
/// `first_row` on (so that many gratings share one buffer).
///
/// The per-order data ([`order_rows`](Self::order_rows)) are the sampler's order weights
/// w_m = η_m/ρ² + ε·U_m ([`GratingBsdf::efficiency`] over ρ², plus [`DEFENSIVE_ORDER_SHARE`]
/// times the envelope bound U_m = 3/(3 + (π·ρ·(|m| − ½)₊)²)) for |m| ≤ 64 and their prefix
/// sums; beyond, the shader computes the amplitude reading's weights itself.
///
/// A tabulated model (feature `relief`) is read by `diffraction_bsdf_tabulated_f`, `_pdf` and
/// `_sample` ([`TABULATED_WGSL`]) from its packed table at word [`table`](Self::table) of
/// `diffraction_efficiency_tables` (`GpuEfficiencyTables`); its lobe is the unit-integral
/// (N·d/λ)·F_N·g (slit width 0, `scale` N·d) and it needs no order rows.
///
/// ```wgsl
/// struct DiffractionBsdf {
///     period_nm: f32, slit_width_nm: f32, slits: u32, groove: u32,
///     groove_param: f32, scale: f32, atan_n: f32, rho: f32,
///     first_row: u32, table: u32, pad0: u32, pad1: u32,
/// }
/// ```
///
/// ```
/// use diffraction::gpu::{order_rows_bytes, GpuBsdf};
/// use diffraction::{Grating, GratingBsdf};
/// let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 1000)?);
/// let g = GpuBsdf::new(&b, 0);
/// assert_eq!(g.to_bytes().len(), 48);
/// assert_eq!(order_rows_bytes(&GpuBsdf::order_rows(&b)).len(), 65 * 16);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GpuBsdf {
    /// d, nm.
    pub period_nm: f32,
    /// w, nm (0 for a tabulated model: its lobe has no single-slit factor).
    pub slit_width_nm: f32,
    /// N (0 for N = ∞, then `groove` is 2).
    pub slits: u32,
    /// 0: a coherence length, 1: a Gaussian groove, 2: not glossy (an ideal groove or N = ∞:
    /// delta lobes, f = pdf = 0 as on the CPU).
    pub groove: u32,
    /// L (nm) for a coherence length, σ for a Gaussian, 0 otherwise.
    pub groove_param: f32,
    /// ρ²·N·d (N·d for a tabulated model).
    pub scale: f32,
    /// atan N.
    pub atan_n: f32,
    /// ρ = w/d.
    pub rho: f32,
    /// The first of the grating's 65 rows in `diffraction_bsdf_orders`.
    pub first_row: u32,
    /// A tabulated model's word offset in `diffraction_efficiency_tables` (0 unless set by
    /// [`with_table`](Self::with_table)); [`NO_TABLE`] for the amplitude model.
    pub table: u32,
    /// Padding to 48 bytes (0).
    pub pad: [u32; 2],
}

/// [`GpuBsdf::table`] of the amplitude model.
pub const NO_TABLE: u32 = u32::MAX;

/// The rows of order data per grating in `diffraction_bsdf_orders`: |m| = 0..=64.
pub const BSDF_ORDER_ROWS: usize = 65;

/// The declaration of the BSDF's order data at `group`, `binding`: a read-only storage
/// `array<vec4<f32>>` of [`BSDF_ORDER_ROWS`] rows per grating.
///
/// ```
/// let b = diffraction::gpu::bsdf_bindings(0, 3);
/// assert!(b.contains("@binding(3) var<storage, read> diffraction_bsdf_orders"));
/// ```
#[must_use]
pub fn bsdf_bindings(group: u32, binding: u32) -> String {
    format!(
        "@group({group}) @binding({binding}) var<storage, read> diffraction_bsdf_orders: \
         array<vec4<f32>>;\n"
    )
}

/// The little-endian bytes of order rows ([`GpuBsdf::order_rows`], one grating's after
/// another).
#[must_use]
pub fn order_rows_bytes(rows: &[[f32; 4]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(16 * rows.len());
    for row in rows {
        for v in row {
            out.extend_from_slice(&v.to_bits().to_le_bytes());
        }
    }
    out
}

impl GpuBsdf {
    /// The scalars of `bsdf`, its order rows starting at row `first_row` of the shared buffer.
    #[must_use]
    pub fn new(bsdf: &GratingBsdf, first_row: u32) -> GpuBsdf {
        let g = bsdf.grating();
        let rho = g.open_fraction();
        let (slits, glossy) = match g.slits() {
            Slits::Finite(n) => (n, true),
            Slits::Infinite => (0, false),
        };
        let (groove, groove_param) = match bsdf.groove().kind() {
            GrooveKind::CoherenceLength { length_nm } if glossy => (0, length_nm),
            GrooveKind::Gaussian { sigma } if glossy => (1, sigma),
            _ => (2, 0.0),
        };
        let nd = slits as f64 * g.period_nm();
        let tabulated = bsdf.order_efficiency().is_tabulated();
        GpuBsdf {
            period_nm: g.period_nm() as f32,
            slit_width_nm: if tabulated {
                0.0
            } else {
                g.slit_width_nm() as f32
            },
            slits,
            groove,
            groove_param: groove_param as f32,
            scale: if tabulated { nd } else { rho * rho * nd } as f32,
            atan_n: atan(slits as f64) as f32,
            rho: rho as f32,
            first_row,
            table: if tabulated { 0 } else { NO_TABLE },
            pad: [0; 2],
        }
    }

    /// The same model with its packed efficiency table at word `offset` of
    /// `diffraction_efficiency_tables` (what `GpuEfficiencyTables::push` returned); for a
    /// tabulated model.
    #[must_use]
    pub fn with_table(self, offset: u32) -> GpuBsdf {
        GpuBsdf {
            table: offset,
            ..self
        }
    }

    /// The 65 rows of order data of `bsdf`: (w_k, w_1 + … + w_k, 0, 0) for k = |m| = 0..=64
    /// (see the type's docs).
    #[must_use]
    pub fn order_rows(bsdf: &GratingBsdf) -> [[f32; 4]; BSDF_ORDER_ROWS] {
        let rho = bsdf.grating().open_fraction();
        let mut rows = [[0.0f32; 4]; BSDF_ORDER_ROWS];
        let mut prefix = 0.0f64;
        for (k, row) in rows.iter_mut().enumerate() {
            let a = (k as f64 - 0.5).max(0.0) * rho * core::f64::consts::PI;
            let w = bsdf.efficiency(k as i32) / (rho * rho)
                + DEFENSIVE_ORDER_SHARE * 3.0 / (3.0 + a * a);
            if k > 0 {
                prefix += w;
            }
            *row = [w as f32, prefix as f32, 0.0, 0.0];
        }
        rows
    }

    /// The 48 bytes to upload.
    #[must_use]
    pub fn to_bytes(&self) -> [u8; 48] {
        let mut out = Vec::with_capacity(48);
        words_to_bytes(
            &[
                self.period_nm.to_bits(),
                self.slit_width_nm.to_bits(),
                self.slits,
                self.groove,
                self.groove_param.to_bits(),
                self.scale.to_bits(),
                self.atan_n.to_bits(),
                self.rho.to_bits(),
                self.first_row,
                self.table,
                self.pad[0],
                self.pad[1],
            ],
            &mut out,
        );
        let mut b = [0u8; 48];
        b.copy_from_slice(&out);
        b
    }
}
