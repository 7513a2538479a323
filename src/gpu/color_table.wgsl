// diffraction: the colour table's lookup, the twin of `ColorTable::lookup`. Needs the types
// (TYPES_WGSL) and three globals the renderer declares (`color_table_bindings` writes them):
//   diffraction_table: DiffractionTableHeader (uniform),
//   diffraction_table_blocks: array<DiffractionTableBlock> (storage, read),
//   diffraction_table_nodes: array<DiffractionTableNode> (storage, read).

// The cubic Hermite interpolant of grid g (its blocks from g * block_count on: grid 0 is the
// table's over u >= 0) at a in [0, 2]; each channel >= 0.
fn diffraction_table_grid(g: u32, a: f32) -> vec3<f32> {
    var k = 0u;
    if a >= diffraction_table.u_lo {
        // The block from the exponent and the top three mantissa bits: one shift, no search.
        k = (bitcast<u32>(a) >> 20u) - diffraction_table.base_key + 1u;
    }
    let count = diffraction_table.block_count;
    let b = diffraction_table_blocks[g * count + min(k, count - 1u)];
    let t = (a - b.u0) * b.inv_h;
    let j = min(u32(t), b.n - 1u);
    let s = t - f32(j);
    let p = diffraction_table_nodes[b.first + j];
    let q = diffraction_table_nodes[b.first + j + 1u];
    let s2 = s * s;
    let s3 = s2 * s;
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = (s3 - 2.0 * s2 + s) * b.h;
    let h01 = 3.0 * s2 - 2.0 * s3;
    let h11 = (s3 - s2) * b.h;
    let f = h00 * p.f.xyz + h10 * p.d.xyz + h01 * q.f.xyz + h11 * q.d.xyz;
    return max(f, vec3<f32>(0.0));
}

// XYZ(|u|) of the table's grating, the cubic Hermite interpolant of the two nodes around |u|
// (|u| > 2 is taken as 2); each channel >= 0. A table of tabulated efficiencies gives its
// colour at normal incidence over u >= 0 (its colour at any incidence is
// `diffraction_table_colour`).
fn diffraction_table_lookup(u: f32) -> vec3<f32> {
    return diffraction_table_grid(0u, min(abs(u), 2.0));
}
