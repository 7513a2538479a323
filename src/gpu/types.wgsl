// diffraction: the plain-data structs a renderer uploads, the WGSL twins of the `#[repr(C)]`
// structs of src/gpu.rs (sizes and offsets checked by tests/gpu_wgsl.rs).

// A grating (`GpuGrating`): d and w in nm, N (u32::MAX for an infinite grating).
struct DiffractionGrating {
    period_nm: f32,
    slit_width_nm: f32,
    slits: u32,
    pad: u32,
}

// The coefficients of the paper's eq. 12 (`GpuIllumination`).
struct DiffractionIllumination {
    ambient: f32,
    diffuse: f32,
    diffraction: f32,
    pad: f32,
}

// A colour table's header (`GpuTableHeader`): the end of block 0, the key (f32 bits >> 20) of
// block 1, and the counts.
struct DiffractionTableHeader {
    u_lo: f32,
    base_key: u32,
    block_count: u32,
    node_count: u32,
}

// One uniform block of the table's grid (`GpuTableBlock`).
struct DiffractionTableBlock {
    u0: f32,
    h: f32,
    inv_h: f32,
    first: u32,
    n: u32,
}

// One node (`GpuTableNode`): XYZ and its derivative in u (w unused).
struct DiffractionTableNode {
    f: vec4<f32>,
    d: vec4<f32>,
}

// The radiometric `GratingBsdf` for the amplitude efficiencies (`GpuBsdf`, 48 bytes).
// groove: 0 a coherence length (groove_param = L, nm), 1 a Gaussian (groove_param = sigma),
// 2 not glossy (an ideal groove or N = infinity: f = pdf = 0). first_row: the first of the
// grating's 65 rows in `diffraction_bsdf_orders` (row k = (w_k, w_1 + ... + w_k, 0, 0): the
// sampler's order weight of |m| = k, eta/rho^2 plus the defensive share, and its prefix sum).
// table: a tabulated model's word offset in `diffraction_efficiency_tables` (0xffffffff for the
// amplitude model; then slit_width_nm = 0 and scale = N*d).
struct DiffractionBsdf {
    period_nm: f32,
    slit_width_nm: f32,
    slits: u32,
    groove: u32,
    groove_param: f32,
    scale: f32,
    atan_n: f32,
    rho: f32,
    first_row: u32,
    table: u32,
    pad0: u32,
    pad1: u32,
}
