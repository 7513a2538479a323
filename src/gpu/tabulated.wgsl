// diffraction: the radiometric `GratingBsdf` with tabulated order efficiencies (a preset or any
// `EfficiencyTable`) in f32: f, pdf and the sampler, the twins of `eval`, `pdf` and `sample` of
// a tabulated model. Needs KERNEL_WGSL, TYPES_WGSL, BSDF_WGSL (the lobe, the density and the
// direction are the amplitude model's) and the global `diffraction_efficiency_tables:
// array<f32>` (read-only storage, `efficiency_table_bindings` writes it) holding the packed
// tables (`GpuEfficiencyTables`; layout in src/gpu/tabulated.rs and docs/gpu.md).
// The table is the model's `table` word offset.

// One query's interpolation cell, shared by every order (the CPU's `Cell`, or `Cell3` of a
// reduced conical table): the query clamped to the grid (alpha: sin(theta_i) = s, or
// s' * c of a reduced table; c2 = 1 - beta^2, 1 for a classical table; lambda), cos(theta_i),
// eight corners' weights (w0: corners 0-3, w1: corners 4-7, 0 for a classical table) and
// flat node indices within an order's slice of `slice` nodes, the cell's number among the
// marks, and the word offsets (from the table) of the nodes' q's, of the stored unpolarised
// values and of the marks; ok = false without a cell (grazing incidence, a non-finite query,
// alpha^2 + beta^2 >= 1): every order 0.
struct DiffractionEtaCell {
    alpha: f32,
    c2: f32,
    lambda_nm: f32,
    cos_i: f32,
    ok: bool,
    w0: vec4<f32>,
    w1: vec4<f32>,
    at0: vec4<u32>,
    at1: vec4<u32>,
    slice: u32,
    cell: u32,
    values: u32,
    nodes: u32,
    marks: u32,
}

// The words of a table's header (the Rust `EFFICIENCY_HEADER_WORDS`).
const DIFFRACTION_ETA_HEADER: u32 = 10u;

// The defensive share of the sampler's order proposal: the CPU's
// `grating_bsdf::TABULATED_DEFENSIVE_SHARE`.
const DIFFRACTION_DEFENSIVE_SHARE: f32 = 0.1;

// The index i of the grid interval [x_i, x_i+1] holding x among the n nodes from word first:
// the first node above x minus 1, clamped to [0, n - 2] (numpy's searchsorted, as the CPU).
fn diffraction_eta_interval(first: u32, n: u32, x: f32) -> u32 {
    var lo = 0u;
    var hi = n;
    while lo < hi {
        let mid = (lo + hi) / 2u;
        if diffraction_efficiency_tables[first + mid] <= x {
            lo = mid + 1u;
        } else {
            hi = mid;
        }
    }
    return min(max(lo, 1u) - 1u, n - 2u);
}

// Corner k's weight and flat index (k in 0..8).
fn diffraction_eta_corner_w(c: DiffractionEtaCell, k: u32) -> f32 {
    if k < 4u {
        return c.w0[k];
    }
    return c.w1[k - 4u];
}

fn diffraction_eta_corner_at(c: DiffractionEtaCell, k: u32) -> u32 {
    if k < 4u {
        return c.at0[k];
    }
    return c.at1[k - 4u];
}

// The cell of a classical table at s = sin(theta_i) (a conical table's first plane).
fn diffraction_eta_cell(t: u32, s_in: f32, lambda_in: f32) -> DiffractionEtaCell {
    var c: DiffractionEtaCell;
    let n_s = u32(diffraction_efficiency_tables[t + 1u]);
    let n_l = u32(diffraction_efficiency_tables[t + 2u]);
    let sn = t + DIFFRACTION_ETA_HEADER;
    let ln = sn + n_s;
    let s = clamp(s_in, diffraction_efficiency_tables[sn],
                  diffraction_efficiency_tables[sn + n_s - 1u]);
    let l = clamp(lambda_in, diffraction_efficiency_tables[ln],
                  diffraction_efficiency_tables[ln + n_l - 1u]);
    let i = diffraction_eta_interval(sn, n_s, s);
    let j = diffraction_eta_interval(ln, n_l, l);
    let s0 = diffraction_efficiency_tables[sn + i];
    let s1 = diffraction_efficiency_tables[sn + i + 1u];
    let l0 = diffraction_efficiency_tables[ln + j];
    let l1 = diffraction_efficiency_tables[ln + j + 1u];
    let tx = (s - s0) / (s1 - s0);
    let ty = (l - l0) / (l1 - l0);
    c.alpha = s;
    c.c2 = 1.0;
    c.lambda_nm = l;
    c.cos_i = sqrt(max(1.0 - s * s, 0.0));
    c.ok = c.cos_i > 0.0;
    c.w0 = vec4<f32>((1.0 - tx) * (1.0 - ty), tx * (1.0 - ty), (1.0 - tx) * ty, tx * ty);
    let index = j * n_s + i;
    c.at0 = vec4<u32>(index, index + 1u, index + n_s, index + n_s + 1u);
    c.slice = n_l * n_s;
    // The cell j * (n_s - 1) + i of corner 0 at j * n_s + i.
    c.cell = index - index / n_s;
    c.values = u32(diffraction_efficiency_tables[t + 5u]);
    c.nodes = u32(diffraction_efficiency_tables[t + 7u]);
    c.marks = u32(diffraction_efficiency_tables[t + 6u]);
    return c;
}

// The cell of the incident direction of travel (alpha, beta) = (-w.x, -w.y) at lambda: a
// conical table's (`diffraction_reduced_cell`: reduced or a version-2 tensor grid), a
// classical table's at s = alpha (beta ignored: the classical-mount reading).
fn diffraction_eta_cell_conical(t: u32, alpha: f32, beta: f32, lambda_nm: f32) -> DiffractionEtaCell {
    if diffraction_efficiency_tables[t + 8u] > 0.5 {
        return diffraction_reduced_cell(t, alpha, beta, lambda_nm);
    }
    return diffraction_eta_cell(t, alpha, lambda_nm);
}

// Order m's (TE, TM) efficiencies at the cell before the normalisation: 0 where it is
// evanescent at the query ((alpha + m*lambda/d)^2 >= c2) or at every corner of positive
// weight; otherwise the weighted mean of q = eta*cos(theta_i)/cos(theta_m) over the
// propagating corners, times cos(theta_m)/cos(theta_i) at the query. m must be a stored order.
fn diffraction_eta_raw(t: u32, c: DiffractionEtaCell, m: i32) -> vec2<f32> {
    let d = diffraction_efficiency_tables[t];
    let k = u32(m - i32(diffraction_efficiency_tables[t + 3u]));
    let am = c.alpha + f32(m) * c.lambda_nm / d;
    let cm2 = c.c2 - am * am;
    if !c.ok || !(cm2 > 0.0) {
        return vec2<f32>(0.0);
    }
    let base = t + c.values + 2u * k * c.slice;
    var num = vec2<f32>(0.0);
    var den = 0.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let w = diffraction_eta_corner_w(c, corner);
        if w > 0.0 {
            let at = base + 2u * diffraction_eta_corner_at(c, corner);
            let q = vec2<f32>(diffraction_efficiency_tables[at], diffraction_efficiency_tables[at + 1u]);
            if q.x >= 0.0 {
                num += w * q;
                den += w;
            }
        }
    }
    if !(den > 0.0) {
        return vec2<f32>(0.0);
    }
    return num * (sqrt(cm2) / (den * c.cos_i));
}

// The normalisation's factors per polarisation: 1/sum where the sum over every stored order
// at the cell exceeds 1, else 1.
fn diffraction_eta_scale(t: u32, c: DiffractionEtaCell) -> vec2<f32> {
    let first = i32(diffraction_efficiency_tables[t + 3u]);
    let count = i32(diffraction_efficiency_tables[t + 4u]);
    var sum = vec2<f32>(0.0);
    for (var m = first; m < first + count; m++) {
        sum += diffraction_eta_raw(t, c, m);
    }
    return select(vec2<f32>(1.0), 1.0 / sum, sum > vec2<f32>(1.0));
}

// The unpolarised eta_m = (TE + TM)/2 after the normalisation (factors k); 0 for orders the
// table does not store.
fn diffraction_eta_at(t: u32, c: DiffractionEtaCell, k: vec2<f32>, m: i32) -> f32 {
    let first = i32(diffraction_efficiency_tables[t + 3u]);
    let count = i32(diffraction_efficiency_tables[t + 4u]);
    if m < first || m >= first + count {
        return 0.0;
    }
    let e = diffraction_eta_raw(t, c, m) * k;
    return 0.5 * (e.x + e.y);
}

// Whether no query in the cell needs the normalisation (the packed marks: the CPU's per-cell
// bound of the sum over orders).
fn diffraction_eta_unit(t: u32, c: DiffractionEtaCell) -> bool {
    return diffraction_efficiency_tables[t + c.marks + c.cell] > 0.5;
}

// The unpolarised eta_m of the stored order m at the cell, normalised: that order alone in a
// marked cell (the factors are 1 there), else with the factors of every stored order.
fn diffraction_eta_one(t: u32, c: DiffractionEtaCell, m: i32) -> f32 {
    if diffraction_eta_unit(t, c) {
        return diffraction_eta_at(t, c, vec2<f32>(1.0), m);
    }
    return diffraction_eta_at(t, c, diffraction_eta_scale(t, c), m);
}

// eta_m(sin(theta_i), lambda) of table t: the CPU's `EfficiencyTable::efficiency(m, s,
// lambda).unpolarised()`.
fn diffraction_eta(t: u32, m: i32, sin_theta_i: f32, lambda_nm: f32) -> f32 {
    return diffraction_eta_in(t, diffraction_eta_cell(t, sin_theta_i, lambda_nm), m);
}

// The unpolarised eta_m of order m at the cell c, normalised: 0 without a cell and for orders
// the table does not store.
fn diffraction_eta_in(t: u32, c: DiffractionEtaCell, m: i32) -> f32 {
    if !c.ok {
        return 0.0;
    }
    let first = i32(diffraction_efficiency_tables[t + 3u]);
    let count = i32(diffraction_efficiency_tables[t + 4u]);
    if m < first || m >= first + count {
        return 0.0;
    }
    return diffraction_eta_one(t, c, m);
}

// eta_m(alpha, beta, lambda) of table t for the incident direction of travel with direction
// cosines alpha across and beta along the grooves: the CPU's `EfficiencyTable::
// efficiency_conical(m, alpha, beta, lambda).unpolarised()` of a conical table, and
// `diffraction_eta(t, m, alpha, lambda)` of a classical one (beta ignored).
fn diffraction_eta_conical(t: u32, m: i32, alpha: f32, beta: f32, lambda_nm: f32) -> f32 {
    return diffraction_eta_in(t, diffraction_eta_cell_conical(t, alpha, beta, lambda_nm), m);
}

// f = eta~_m * (N*d/lambda) * F_N(d*u/lambda) * g(v) for the order m = round(x) owning u, with
// eta~_m = min(eta_m(-wo.x, -wo.y, lambda), eta_m(-wi.x, -wi.y, lambda)) (reciprocal; a
// classical table ignores the second argument); 0 below the surface and for delta lobes.
fn diffraction_bsdf_tabulated_f(b: DiffractionBsdf, wo: vec3<f32>, wi: vec3<f32>,
                                lambda_nm: f32) -> f32 {
    if b.groove >= 2u || wo.z <= 0.0 || wi.z <= 0.0 || lambda_nm <= 0.0 {
        return 0.0;
    }
    let x = b.period_nm * ((wi.x + wo.x) / lambda_nm);
    if !(abs(x) < 1.0e9) {
        return 0.0;
    }
    let m = i32(round(x));
    return diffraction_bsdf_tabulated_lobe(b, diffraction_eta_conical(b.table, m, -wo.x, -wo.y, lambda_nm), m, wo,
                                           wi, lambda_nm);
}

// f from eta_m(-wo.x, -wo.y, lambda) = e of the order m owning u: min(e, eta_m(-wi.x, -wi.y,
// lambda)) times the lobe.
fn diffraction_bsdf_tabulated_lobe(b: DiffractionBsdf, e: f32, m: i32, wo: vec3<f32>,
                                   wi: vec3<f32>, lambda_nm: f32) -> f32 {
    if !(e > 0.0) {
        return 0.0;
    }
    let k = min(e, diffraction_eta_conical(b.table, m, -wi.x, -wi.y, lambda_nm));
    return k * diffraction_bsdf_f(b, wo, wi, lambda_nm);
}

// The candidate orders clipped to the stored ones, (lo, hi); hi < lo when there are none.
fn diffraction_bsdf_tabulated_candidates(b: DiffractionBsdf, wo_x: f32, lambda_nm: f32) -> vec2<i32> {
    let c = diffraction_bsdf_candidates(b, wo_x, lambda_nm);
    let first = i32(diffraction_efficiency_tables[b.table + 3u]);
    let count = i32(diffraction_efficiency_tables[b.table + 4u]);
    return vec2<i32>(max(c.x, first), min(c.y, first + count - 1));
}

// The sampler's order proposal at wo's cell (the CPU's `CellProposal` and order weights):
// the candidates trimmed to the orders that propagate at the query, and
// P(m) = scale * eta^_m + floor, eta^_m = sum_c w_c * eta_m,c the corners' stored unpolarised
// efficiencies with the cell's bilinear weights (corners of positive weight),
// scale = (1 - share)/sum eta^ and floor = share/K (0 and 1/K where the sum is 0); hi < lo when
// no candidate propagates.
struct DiffractionEtaProposal {
    lo: i32,
    hi: i32,
    scale: f32,
    floor: f32,
}

// Whether order m propagates at the cell's query: the test of `diffraction_eta_raw`.
fn diffraction_eta_propagates(t: u32, c: DiffractionEtaCell, m: i32) -> bool {
    let d = diffraction_efficiency_tables[t];
    let am = c.alpha + f32(m) * c.lambda_nm / d;
    return c.ok && c.c2 - am * am > 0.0;
}

// eta^_m of the stored order m: the corners' stored unpolarised efficiencies with the cell's
// bilinear weights.
fn diffraction_eta_node(t: u32, c: DiffractionEtaCell, m: i32) -> f32 {
    let k = u32(m - i32(diffraction_efficiency_tables[t + 3u]));
    let base = t + c.nodes + k * c.slice;
    var e = 0.0;
    for (var corner = 0u; corner < 8u; corner++) {
        let w = diffraction_eta_corner_w(c, corner);
        if w > 0.0 {
            e += w * diffraction_efficiency_tables[base + diffraction_eta_corner_at(c, corner)];
        }
    }
    return e;
}

fn diffraction_eta_proposal(t: u32, c: DiffractionEtaCell, range: vec2<i32>) -> DiffractionEtaProposal {
    var p: DiffractionEtaProposal;
    p.lo = range.x;
    p.hi = range.y;
    while p.lo <= p.hi && !diffraction_eta_propagates(t, c, p.lo) {
        p.lo += 1;
    }
    while p.hi >= p.lo && !diffraction_eta_propagates(t, c, p.hi) {
        p.hi -= 1;
    }
    if p.hi < p.lo {
        return p;
    }
    var total = 0.0;
    for (var m = p.lo; m <= p.hi; m++) {
        total += diffraction_eta_node(t, c, m);
    }
    let k = f32(p.hi - p.lo + 1);
    if total > 0.0 {
        p.scale = (1.0 - DIFFRACTION_DEFENSIVE_SHARE) / total;
        p.floor = DIFFRACTION_DEFENSIVE_SHARE / k;
    } else {
        p.scale = 0.0;
        p.floor = 1.0 / k;
    }
    return p;
}

// P(m) of the proposal p (0 outside its orders).
fn diffraction_eta_weight(t: u32, c: DiffractionEtaCell, p: DiffractionEtaProposal, m: i32) -> f32 {
    if m < p.lo || m > p.hi {
        return 0.0;
    }
    return p.scale * diffraction_eta_node(t, c, m) + p.floor;
}

// pdf = P(m) * q(r) * (d/lambda) * q_v(v) * cos(theta_i) with the proposal's P(m): the
// density of `diffraction_bsdf_tabulated_sample`.
fn diffraction_bsdf_tabulated_pdf(b: DiffractionBsdf, wo: vec3<f32>, wi: vec3<f32>,
                                  lambda_nm: f32) -> f32 {
    if b.groove >= 2u || wo.z <= 0.0 || wi.z <= 0.0 || lambda_nm <= 0.0 {
        return 0.0;
    }
    let range = diffraction_bsdf_tabulated_candidates(b, wo.x, lambda_nm);
    if range.y < range.x {
        return 0.0;
    }
    let c = diffraction_eta_cell_conical(b.table, -wo.x, -wo.y, lambda_nm);
    let p = diffraction_eta_proposal(b.table, c, range);
    if p.hi < p.lo {
        return 0.0;
    }
    return diffraction_bsdf_tabulated_density(b, c, p, wo, wi, lambda_nm);
}

// The pdf from wo's cell c and its proposal p.
fn diffraction_bsdf_tabulated_density(b: DiffractionBsdf, c: DiffractionEtaCell,
                                      p: DiffractionEtaProposal, wo: vec3<f32>, wi: vec3<f32>,
                                      lambda_nm: f32) -> f32 {
    let x = b.period_nm * ((wi.x + wo.x) / lambda_nm);
    let m = i32(round(x));
    let w = diffraction_eta_weight(b.table, c, p, m);
    if !(w > 0.0) {
        return 0.0;
    }
    return diffraction_bsdf_density(b, w, 1.0, x, wi.y + wo.y, wi.z, lambda_nm);
}

// `Bsdf::sample` of a tabulated model from xi in [0, 1)^3: the order by the proposal (the
// first m whose running sum of P exceeds xi.x, the last one if none: the CPU's choice), then
// the amplitude model's direction; f and pdf from the direction itself (the values of
// `diffraction_bsdf_tabulated_f` and `_pdf` there, with wo's interpolation cell computed
// once).
fn diffraction_bsdf_tabulated_sample(b: DiffractionBsdf, wo: vec3<f32>, lambda_nm: f32,
                                     xi: vec3<f32>) -> DiffractionBsdfSample {
    var out: DiffractionBsdfSample;
    if b.groove >= 2u || !(wo.z > 0.0) || !(lambda_nm > 0.0) {
        return out;
    }
    let range = diffraction_bsdf_tabulated_candidates(b, wo.x, lambda_nm);
    if range.y < range.x {
        return out;
    }
    let c = diffraction_eta_cell_conical(b.table, -wo.x, -wo.y, lambda_nm);
    let p = diffraction_eta_proposal(b.table, c, range);
    if p.hi < p.lo {
        return out;
    }
    var acc = 0.0;
    var m = p.hi;
    for (var o = p.lo; o <= p.hi; o++) {
        acc += diffraction_eta_weight(b.table, c, p, o);
        if xi.x < acc {
            m = o;
            break;
        }
    }
    let wi = diffraction_bsdf_direction(b, wo, m, xi.y, xi.z, lambda_nm);
    if !(wi.z > 0.0) {
        return out;
    }
    let pdf = diffraction_bsdf_tabulated_density(b, c, p, wo, wi, lambda_nm);
    if !(pdf > 0.0) {
        return out;
    }
    // The order owning u (m unless rounding moved wi across its period's end) and its eta at
    // wo from the same cell: the value `diffraction_eta` gives.
    let x = b.period_nm * ((wi.x + wo.x) / lambda_nm);
    let owner = i32(round(x));
    let e = diffraction_eta_in(b.table, c, owner);
    out.wi = wi;
    out.f = diffraction_bsdf_tabulated_lobe(b, e, owner, wo, wi, lambda_nm);
    out.pdf = pdf;
    out.order = m;
    out.valid = 1u;
    return out;
}
