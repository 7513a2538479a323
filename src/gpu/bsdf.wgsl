// diffraction: the radiometric `GratingBsdf` (amplitude efficiencies) in f32: its value f
// (1/sr, cosine excluded), its sampling density pdf (solid angle) and its sampler, the twins
// of `DiffractionBrdf::eval`, `Bsdf::pdf` and `Bsdf::sample`. Needs KERNEL_WGSL, TYPES_WGSL
// and the global
// `diffraction_bsdf_orders: array<vec4<f32>>` (read-only storage, `bsdf_bindings` writes
// it), which holds 65 rows per grating (`GpuBsdf::order_rows`). Directions are in
// the local frame: z the normal, x the grating vector, y along the grooves.

// f = rho^2 * S(w*u/lambda) * (N*d/lambda) * F_N(d*u/lambda) * g(v), u = wi.x + wo.x,
// v = wi.y + wo.y; 0 below the surface and for delta lobes.
fn diffraction_bsdf_f(b: DiffractionBsdf, wo: vec3<f32>, wi: vec3<f32>, lambda_nm: f32) -> f32 {
    if b.groove >= 2u || wo.z <= 0.0 || wi.z <= 0.0 || lambda_nm <= 0.0 {
        return 0.0;
    }
    let u = wi.x + wo.x;
    let v = wi.y + wo.y;
    let q = u / lambda_nm;
    let i = diffraction_intensity_cycles(b.period_nm * q, b.slit_width_nm * q, b.slits);
    var g: f32;
    if b.groove == 0u {
        let k = b.groove_param / lambda_nm;
        g = k * diffraction_single_slit_cycles(k * v);
    } else {
        let t = v / b.groove_param;
        g = 0.3989422804014327 / b.groove_param * exp(-0.5 * t * t);
    }
    return b.scale / lambda_nm * i * g;
}

// The sampler's weight of order m: the table for |m| <= 64, the amplitude formula beyond.
fn diffraction_bsdf_weight(b: DiffractionBsdf, m: i32) -> f32 {
    let k = abs(m);
    if k <= 64 {
        return diffraction_bsdf_orders[b.first_row + u32(k)].x;
    }
    let a = (f32(k) - 0.5) * b.rho * 3.141592653589793;
    return diffraction_single_slit_cycles(b.rho * f32(m)) + 0.125 * 3.0 / (3.0 + a * a);
}

// The sum of the weights of the orders lo..=hi.
fn diffraction_bsdf_total(b: DiffractionBsdf, lo: i32, hi: i32) -> f32 {
    if lo >= -64 && hi <= 64 {
        let f = b.first_row;
        if lo >= 1 {
            return diffraction_bsdf_orders[f + u32(hi)].y - diffraction_bsdf_orders[f + u32(lo - 1)].y;
        }
        if hi <= -1 {
            return diffraction_bsdf_orders[f + u32(-lo)].y - diffraction_bsdf_orders[f + u32(-hi - 1)].y;
        }
        return diffraction_bsdf_orders[f + u32(-lo)].y + diffraction_bsdf_orders[f].x
            + diffraction_bsdf_orders[f + u32(hi)].y;
    }
    var s = 0.0;
    for (var m = lo; m <= hi; m++) {
        s += diffraction_bsdf_weight(b, m);
    }
    return s;
}

// The candidate orders (lo, hi) for wo at lambda: those whose period [m - 1/2, m + 1/2) in the
// phase meets the disk's u-range (wo.x - 1, wo.x + 1); hi < lo when there are none or the
// phase is beyond 1e9 (the i32 orders).
fn diffraction_bsdf_candidates(b: DiffractionBsdf, wo_x: f32, lambda_nm: f32) -> vec2<i32> {
    let step = lambda_nm / b.period_nm;
    let x_lo = (wo_x - 1.0) / step;
    let x_hi = (wo_x + 1.0) / step;
    if !(abs(x_lo) < 1.0e9 && abs(x_hi) < 1.0e9) {
        return vec2<i32>(1, 0);
    }
    return vec2<i32>(i32(floor(x_lo - 0.5)) + 1, i32(ceil(x_hi + 0.5)) - 1);
}

// P(m) * q(r) * (d/lambda) * q_v(v) * cos(theta_i) with P(m) = w/total, r = x - round(x): the
// density of the sampler for an order of weight w among candidates of total weight total (both
// models' sampler).
fn diffraction_bsdf_density(b: DiffractionBsdf, w: f32, total: f32, x: f32, v: f32, cos_i: f32,
                            lambda_nm: f32) -> f32 {
    if !(w > 0.0 && total > 0.0) {
        return 0.0;
    }
    let r = x - round(x);
    let nf = f32(b.slits);
    // N = 1: the uniform proxy, q = 1 (c = 0 and the peak 1 below).
    let one = b.slits <= 1u;
    let t = select(2.0 * nf * r, 0.0, one);
    let peak = select(nf / b.atan_n, 1.0, one);
    var inv_s: f32;
    if b.groove == 0u {
        inv_s = (3.141592653589793 / 1.2) * b.groove_param / lambda_nm;
    } else {
        inv_s = 1.0 / b.groove_param;
    }
    let tv = v * inv_s;
    let a = (w * peak * b.period_nm) / (total * (1.0 + t * t) * lambda_nm);
    let c = (inv_s * cos_i) / (3.141592653589793 * (1.0 + tv * tv));
    return a * c;
}

// pdf = P(m) * q(r) * (d/lambda) * q_v(v) * cos(theta_i) for the order m = round(x) owning
// u: P(m) = w_m / (sum of w over the orders whose period meets wo.x +- 1, uniform beyond 256
// of them), q the proxy of F_N (the Lorentzian N/((1 + (2N*r)^2)*atan N), the uniform 1 for
// N = 1), q_v the Cauchy proxy of g.
fn diffraction_bsdf_pdf(b: DiffractionBsdf, wo: vec3<f32>, wi: vec3<f32>, lambda_nm: f32) -> f32 {
    if b.groove >= 2u || wo.z <= 0.0 || wi.z <= 0.0 || lambda_nm <= 0.0 {
        return 0.0;
    }
    let c = diffraction_bsdf_candidates(b, wo.x, lambda_nm);
    let lo = c.x;
    let hi = c.y;
    if hi < lo {
        return 0.0;
    }
    let u = wi.x + wo.x;
    let v = wi.y + wo.y;
    let x = b.period_nm * (u / lambda_nm);
    let m = i32(round(x));
    if m < lo || m > hi {
        return 0.0;
    }
    var w = 1.0;
    var total = f32(hi - lo + 1);
    if hi - lo + 1 <= 256 {
        w = diffraction_bsdf_weight(b, m);
        total = diffraction_bsdf_total(b, lo, hi);
    }
    return diffraction_bsdf_density(b, w, total, x, v, wi.z, lambda_nm);
}

// cos(pi w) for |w| <= 1/4 from t = w^2: the Taylor coefficients (-1)^k pi^(2k)/(2k)!,
// k = 0..6 (truncation below 5e-13 on the range).
fn diffraction_cospi_sq(t: f32) -> f32 {
    var p = 0.001929574309403922;
    p = p * t - 0.02580689139001405;
    p = p * t + 0.23533063035889312;
    p = p * t - 1.3352627688545893;
    p = p * t + 4.058712126416768;
    p = p * t - 4.934802200544679;
    return p * t + 1.0;
}

// tan(pi z) for |z| <= 1/2 without the built-in tan (WGSL inherits its error from sin and
// cos: 2^-11 absolute): sin/cos on |z| <= 1/4, cos/sin of 1/2 - |z| (exact) beyond, the
// divisor at least 1e-30 (finite at the poles), odd. The twin of `kernel::tanpi_flat`.
fn diffraction_tanpi(z: f32) -> f32 {
    let a = abs(z);
    let low = a <= 0.25;
    let w = select(0.5 - a, a, low);
    let w2 = w * w;
    let sw = w * diffraction_sinpi_over(w2);
    let cp = diffraction_cospi_sq(w2);
    var t: f32;
    if low {
        t = sw / cp;
    } else {
        t = cp / max(sw, 1.0e-30);
    }
    return select(t, -t, z < 0.0);
}

// r in [-1/2, 1/2] from t in [0, 1): the period proxy's inverse CDF, t - 1/2 for N = 1,
// tan((2t - 1) * atan N)/(2N) for the Lorentzian.
fn diffraction_bsdf_proxy_r(b: DiffractionBsdf, t: f32) -> f32 {
    if b.slits <= 1u {
        return t - 0.5;
    }
    let z = (2.0 * t - 1.0) * (b.atan_n * 0.3183098861837907);
    return clamp(diffraction_tanpi(z) / (2.0 * f32(b.slits)), -0.5, 0.5);
}

// One sample of the BSDF: the direction wi (local frame), f and pdf at it (the values of
// `diffraction_bsdf_f` and `diffraction_bsdf_pdf` there), the order and whether there is a
// sample (valid = 0: none, as the CPU's `None`; every other field is then 0).
struct DiffractionBsdfSample {
    wi: vec3<f32>,
    f: f32,
    pdf: f32,
    order: i32,
    valid: u32,
}

// The direction of order m's sample: u = (m + r) * lambda/d with r from the period proxy
// (xi_u), v from the groove's Cauchy proxy (xi_v), wi = (u - wo.x, v - wo.y, +sqrt(...));
// wi.z = 0 when it falls below the surface.
fn diffraction_bsdf_direction(b: DiffractionBsdf, wo: vec3<f32>, m: i32, xi_u: f32, xi_v: f32,
                              lambda_nm: f32) -> vec3<f32> {
    let r = diffraction_bsdf_proxy_r(b, xi_u);
    let u = (f32(m) + r) * (lambda_nm / b.period_nm);
    // The Cauchy proxy's scale: 1.2 * lambda/(pi * L) for a coherence length, sigma otherwise.
    var s = b.groove_param;
    if b.groove == 0u {
        s = 0.3819718634205488 * lambda_nm / b.groove_param;
    }
    // |v| > 2 always falls outside the disk: the clamp keeps the tails finite.
    let v = clamp(s * diffraction_tanpi(xi_v - 0.5), -4.0, 4.0);
    let x = u - wo.x;
    let y = v - wo.y;
    let z2 = 1.0 - x * x - y * y;
    if !(z2 > 0.0) {
        return vec3<f32>(0.0);
    }
    return vec3<f32>(x, y, sqrt(z2));
}

// `Bsdf::sample` of the amplitude model from the random numbers xi in [0, 1)^3 (the CPU's uc,
// u2.x, u2.y): the order by its weight among the candidates (the first m whose running sum of
// weights exceeds xi.x times their total; uniform beyond 256 candidates), u inside its period
// from the period proxy (xi.y), v from the groove's proxy (xi.z); f and pdf from the direction
// itself. Delta lobes (groove = 2) have no sample here (the CPU returns their specular ones).
fn diffraction_bsdf_sample(b: DiffractionBsdf, wo: vec3<f32>, lambda_nm: f32,
                           xi: vec3<f32>) -> DiffractionBsdfSample {
    var out: DiffractionBsdfSample;
    if b.groove >= 2u || !(wo.z > 0.0) || !(lambda_nm > 0.0) {
        return out;
    }
    let c = diffraction_bsdf_candidates(b, wo.x, lambda_nm);
    let lo = c.x;
    let hi = c.y;
    if hi < lo {
        return out;
    }
    var m = lo;
    if hi - lo + 1 > 256 {
        m = lo + clamp(i32(xi.x * f32(hi - lo + 1)), 0, hi - lo);
    } else {
        let goal = xi.x * diffraction_bsdf_total(b, lo, hi);
        var acc = diffraction_bsdf_weight(b, lo);
        while acc <= goal && m < hi {
            m += 1;
            acc += diffraction_bsdf_weight(b, m);
        }
    }
    let wi = diffraction_bsdf_direction(b, wo, m, xi.y, xi.z, lambda_nm);
    if !(wi.z > 0.0) {
        return out;
    }
    let pdf = diffraction_bsdf_pdf(b, wo, wi, lambda_nm);
    if !(pdf > 0.0) {
        return out;
    }
    out.wi = wi;
    out.f = diffraction_bsdf_f(b, wo, wi, lambda_nm);
    out.pdf = pdf;
    out.order = m;
    out.valid = 1u;
    return out;
}
