// diffraction: the colour C(u, s) of a colour table at the incidence s = wi.x, the twin of the
// CPU's interpolation inside `ColorTable::xyz`, and of a conical table's colour C(u, s, |wi.y|)
// on its planes of |wi.y|. Needs the colour table (COLOR_TABLE_WGSL and its bindings) and one
// more global (`incidence_bindings` writes it):
//   diffraction_table_incidence: array<u32> (storage, read): K (incidence nodes), M (bins), the
//   M bins, then per node sigma and 1 / (next sigma - sigma) as f32 bits; then P (a conical
//   table's planes off the plane across the grooves, 0 for any other) and per plane |wi.y|,
//   c = sqrt(1 - wi.y^2) (f32 bits), the word where its own K, M, bins and nodes start, and
//   its first grid (`GpuColorTable`).

// One plane's colour at u (clamped to [-2, 2]) and the place sigma in [0, 1]: linear in sigma
// between the Hermite interpolants of the two incidence nodes around it. `at` is the word of
// the plane's K; node k's grid over u >= 0 is grid_base + 2k, over u <= 0 grid_base + 2k + 1.
fn diffraction_table_plane(at: u32, grid_base: u32, uc: f32, sigma: f32) -> vec3<f32> {
    let bins = diffraction_table_incidence[at + 1u];
    let i = diffraction_table_incidence[at + 2u + min(u32(sigma * f32(bins)), bins - 1u)];
    let node = at + 2u + bins + 2u * i;
    let w = clamp(
        (sigma - bitcast<f32>(diffraction_table_incidence[node]))
            * bitcast<f32>(diffraction_table_incidence[node + 1u]),
        0.0,
        1.0
    );
    let side = select(1u, 0u, uc >= 0.0);
    let a = abs(uc);
    let x = diffraction_table_grid(grid_base + side + 2u * i, a);
    let y = diffraction_table_grid(grid_base + side + 2u * (i + 1u), a);
    return x * (1.0 - w) + y * w;
}

// C(u, s): for a table of tabulated efficiencies, linear in sigma between the Hermite
// interpolants of the two incidence nodes around (u, s) (s placed between the grazing
// directions at u, see `GpuColorTable`), 0 where wo or wi is below the surface; for a table
// without incidence (K = 0), `diffraction_table_lookup(u)`. u is clamped to [-2, 2]. The
// caller multiplies by cos(theta_i) * g(v) for the radiometric and tabulated sources, as
// `ColorTable::xyz` does. A conical table's plane across the grooves (the classical mount).
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
    return diffraction_table_plane(0u, 1u, uc, ra / (ra + rb));
}

// C(u, s, b) with b = min(|wi.y|, |wo.y|), the twin of `ColorTable::xyz` for a conical table:
// each of the two planes around b read at the place sigma of (u, s) between the grazing
// directions at r = sqrt(1 - b^2) (clamped to them), blended linearly in r; the last plane
// beyond it. b = 0, or a table without planes: `diffraction_table_colour(u, s)`.
fn diffraction_table_colour_conical(u: f32, s: f32, b: f32) -> vec3<f32> {
    let nodes = diffraction_table_incidence[0];
    if nodes == 0u {
        return diffraction_table_lookup(u);
    }
    let head = 2u + diffraction_table_incidence[1] + 2u * nodes;
    let planes = diffraction_table_incidence[head];
    if b == 0.0 || planes == 0u {
        return diffraction_table_colour(u, s);
    }
    let uc = clamp(u, -2.0, 2.0);
    let r = sqrt(1.0 - b * b);
    let ur = uc / r;
    let width = 2.0 - abs(ur);
    if !(width > 0.0) {
        return vec3<f32>(0.0);
    }
    let p = clamp(s / r - max(ur, 0.0) + 1.0, 0.0, width);
    let ra = sqrt(p);
    let rb = sqrt(width - p);
    let sigma = ra / (ra + rb);
    // The plane at or below b (0: the plane across the grooves) and the next one.
    var k = 0u;
    while k < planes && bitcast<f32>(diffraction_table_incidence[head + 1u + 4u * k]) <= b {
        k += 1u;
    }
    var c0 = 1.0;
    var at0 = 0u;
    var base0 = 1u;
    if k > 0u {
        let e = head + 1u + 4u * (k - 1u);
        c0 = bitcast<f32>(diffraction_table_incidence[e + 1u]);
        at0 = diffraction_table_incidence[e + 2u];
        base0 = diffraction_table_incidence[e + 3u];
    }
    let x = diffraction_table_plane(at0, base0, uc, sigma);
    if k == planes {
        return x;
    }
    let e = head + 1u + 4u * k;
    let c1 = bitcast<f32>(diffraction_table_incidence[e + 1u]);
    let y = diffraction_table_plane(
        diffraction_table_incidence[e + 2u],
        diffraction_table_incidence[e + 3u],
        uc,
        sigma
    );
    let t = clamp((c0 - r) / (c0 - c1), 0.0, 1.0);
    return x * (1.0 - t) + y * t;
}
