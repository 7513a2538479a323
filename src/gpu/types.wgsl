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
