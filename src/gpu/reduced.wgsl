// diffraction: the cell of a conical table in f32. A reduced table (version 3): the twin of
// the CPU's `Reduced::find` (src/relief/table/reduced.rs): the query's reduced coordinate
// s' = alpha/c, c = sqrt(1 - beta^2), its two |beta| planes around |beta|, each read at its own
// physical wavelength lambda * c_p / c, and the planes blended linearly in c. A version-2
// tensor grid: the twin of `Cell3::find` (src/relief/table/conical.rs): the same s', every
// plane read at lambda, the planes blended linearly in |beta|. Part of TABULATED_WGSL; the
// section's layout is on `GpuEfficiencyTables` (src/gpu/tabulated.rs).

// (x - a)/(b - a) in [0, 1]; 0 where the nodes coincide.
fn diffraction_reduced_fraction(x: f32, a: f32, b: f32) -> f32 {
    if b == a {
        return 0.0;
    }
    return clamp((x - a) / (b - a), 0.0, 1.0);
}

// The cell of the incident direction of travel (alpha, beta) at lambda in the conical table
// at word t: s', |beta| and lambda clamped to the axes and the band (the query is then the
// clamped point), corner n = di + 2*dk + 4*dj of plane k + dk at s' node i + di and that
// plane's wavelength row j_dk + dj, with the weight wt(di, tx) * wt(dk, tb) * wt(dj, ty_dk).
// 1 - beta^2 is taken as (1 - |beta|)(1 + |beta|): no cancellation in f32 as |beta| -> 1.
fn diffraction_reduced_cell(t: u32, alpha: f32, beta: f32, lambda_in: f32) -> DiffractionEtaCell {
    var c: DiffractionEtaCell;
    let b0 = abs(beta);
    let c20 = (1.0 - b0) * (1.0 + b0);
    if !(alpha * alpha < c20) {
        return c;
    }
    let n_s = u32(diffraction_efficiency_tables[t + 1u]);
    let n_b = u32(diffraction_efficiency_tables[t + 8u]);
    let r = t + u32(diffraction_efficiency_tables[t + 9u]);
    let sn = t + DIFFRACTION_ETA_HEADER;
    let tensor = diffraction_efficiency_tables[r + 5u] > 0.5;
    let bn = r + 6u;
    let cn = bn + n_b;
    let rn = cn + n_b;
    let ln = rn + n_b + 1u;
    let s0 = alpha / sqrt(c20);
    let sp = clamp(s0, diffraction_efficiency_tables[sn], diffraction_efficiency_tables[sn + n_s - 1u]);
    let b = clamp(b0, diffraction_efficiency_tables[bn], diffraction_efficiency_tables[bn + n_b - 1u]);
    let lambda_nm = clamp(lambda_in, diffraction_efficiency_tables[r + 3u],
                          diffraction_efficiency_tables[r + 4u]);
    let c2 = (1.0 - b) * (1.0 + b);
    let cq = sqrt(c2);
    // Where nothing was clamped cos(theta_i) = sqrt(1 - beta^2 - alpha^2) for both formats (the
    // CPU's c * sqrt(1 - s'^2) of a tensor grid, without f32's cancellation in 1 - s'^2 at
    // grazing incidence).
    var cos_i: f32;
    if sp == s0 && b == b0 {
        cos_i = sqrt(c2 - alpha * alpha);
    } else {
        cos_i = cq * sqrt(max(1.0 - sp * sp, 0.0));
    }
    if !(cos_i > 0.0) {
        return c;
    }
    let i = diffraction_eta_interval(sn, n_s, sp);
    let k = diffraction_eta_interval(bn, n_b, b);
    let cp = vec2<f32>(diffraction_efficiency_tables[cn + k], diffraction_efficiency_tables[cn + k + 1u]);
    var tb: f32;
    if tensor {
        tb = diffraction_reduced_fraction(b, diffraction_efficiency_tables[bn + k],
                                          diffraction_efficiency_tables[bn + k + 1u]);
    } else {
        tb = diffraction_reduced_fraction(cq, cp.x, cp.y);
    }
    let tx = diffraction_reduced_fraction(sp, diffraction_efficiency_tables[sn + i],
                                          diffraction_efficiency_tables[sn + i + 1u]);
    var row = vec2<u32>(0u);
    var ty = vec2<f32>(0.0);
    for (var d = 0u; d < 2u; d++) {
        let first = u32(diffraction_efficiency_tables[rn + k + d]);
        let n = u32(diffraction_efficiency_tables[rn + k + d + 1u]) - first;
        var l = lambda_nm;
        if !tensor {
            l = clamp(lambda_nm * (cp[d] / cq), diffraction_efficiency_tables[ln + first],
                      diffraction_efficiency_tables[ln + first + n - 1u]);
        }
        let j = diffraction_eta_interval(ln + first, n, l);
        row[d] = first + j;
        ty[d] = diffraction_reduced_fraction(l, diffraction_efficiency_tables[ln + first + j],
                                             diffraction_efficiency_tables[ln + first + j + 1u]);
    }
    let r0 = u32(diffraction_efficiency_tables[rn]);
    let r1 = u32(diffraction_efficiency_tables[rn + 1u]);
    let rk = u32(diffraction_efficiency_tables[rn + k]);
    let rk1 = u32(diffraction_efficiency_tables[rn + k + 1u]);
    if tensor {
        // (k * (n_l - 1) + j) * (n_s - 1) + i, every plane of n_l = r1 - r0 rows.
        c.cell = (k * (r1 - r0 - 1u) + row.x - rk) * (n_s - 1u) + i;
    } else {
        // The slab's first cell, then the pair j_k + j_k+1 and i (the CPU's numbering).
        let slab = (n_s - 1u) * ((rk - r0) + (rk1 - r1) - 3u * k);
        c.cell = slab + (row.x + row.y - rk - rk1) * (n_s - 1u) + i;
    }
    let fx = vec2<f32>(1.0 - tx, tx);
    let fb = vec2<f32>(1.0 - tb, tb);
    let f0 = vec2<f32>(1.0 - ty.x, ty.x);
    let f1 = vec2<f32>(1.0 - ty.y, ty.y);
    // Corners n = di + 2*dk + 4*dj: w0 holds dj = 0, w1 dj = 1.
    c.w0 = vec4<f32>(fx.x * fb.x * f0.x, fx.y * fb.x * f0.x, fx.x * fb.y * f1.x, fx.y * fb.y * f1.x);
    c.w1 = vec4<f32>(fx.x * fb.x * f0.y, fx.y * fb.x * f0.y, fx.x * fb.y * f1.y, fx.y * fb.y * f1.y);
    let a0 = row.x * n_s + i;
    let a1 = row.y * n_s + i;
    c.at0 = vec4<u32>(a0, a0 + 1u, a1, a1 + 1u);
    c.at1 = vec4<u32>(a0 + n_s, a0 + n_s + 1u, a1 + n_s, a1 + n_s + 1u);
    c.alpha = sp * cq;
    c.c2 = c2;
    c.lambda_nm = lambda_nm;
    c.cos_i = cos_i;
    c.ok = true;
    c.slice = n_s * u32(diffraction_efficiency_tables[rn + n_b]);
    c.values = u32(diffraction_efficiency_tables[r]);
    c.nodes = u32(diffraction_efficiency_tables[r + 1u]);
    c.marks = u32(diffraction_efficiency_tables[r + 2u]);
    return c;
}
