// diffraction: the colour C(u, s) of a colour table at the incidence s = wi.x, the twin of the
// CPU's interpolation inside `ColorTable::xyz`. Needs the colour table (COLOR_TABLE_WGSL and its
// bindings) and one more global (`incidence_bindings` writes it):
//   diffraction_table_incidence: array<u32> (storage, read): K (incidence nodes), M (bins), the
//   M bins, then per node sigma and 1 / (next sigma - sigma) as f32 bits (`GpuColorTable`).

// C(u, s): for a table of tabulated efficiencies, linear in sigma between the Hermite
// interpolants of the two incidence nodes around (u, s) (s placed between the grazing
// directions at u, see `GpuColorTable`), 0 where wo or wi is below the surface; for a table
// without incidence (K = 0), `diffraction_table_lookup(u)`. u is clamped to [-2, 2]. The
// caller multiplies by cos(theta_i) * g(v) for the radiometric and tabulated sources, as
// `ColorTable::xyz` does.
fn diffraction_table_colour(u: f32, s: f32) -> vec3<f32> {
    let nodes = diffraction_table_incidence[0];
    if nodes == 0u {
        return diffraction_table_lookup(u);
    }
    let uc = clamp(u, -2.0, 2.0);
    let width = 2.0 - abs(uc);
    let tau = (s - max(uc, 0.0) + 1.0) / width;
    if !(width > 0.0 && tau >= 0.0 && tau <= 1.0) {
        return vec3<f32>(0.0);
    }
    let ra = sqrt(tau);
    let rb = sqrt(1.0 - tau);
    let sigma = ra / (ra + rb);
    let bins = diffraction_table_incidence[1];
    let i = diffraction_table_incidence[2u + min(u32(sigma * f32(bins)), bins - 1u)];
    let at = 2u + bins + 2u * i;
    let w = clamp(
        (sigma - bitcast<f32>(diffraction_table_incidence[at]))
            * bitcast<f32>(diffraction_table_incidence[at + 1u]),
        0.0,
        1.0
    );
    // Grid 1 + 2k: node k over u >= 0; 2 + 2k: over u <= 0 (in |u|).
    let side = select(2u, 1u, uc >= 0.0);
    let a = abs(uc);
    let x = diffraction_table_grid(side + 2u * i, a);
    let y = diffraction_table_grid(side + 2u * (i + 1u), a);
    return x * (1.0 - w) + y * w;
}
