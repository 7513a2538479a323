// diffraction: the radiometric `GratingBsdf` (amplitude efficiencies) in f32: its value f
// (1/sr, cosine excluded) and its sampling density pdf (solid angle), the twins of
// `DiffractionBrdf::eval` and `Bsdf::pdf`. Needs KERNEL_WGSL, TYPES_WGSL and the global
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

// pdf = P(m) * q(r) * (d/lambda) * q_v(v) * cos(theta_i) for the order m = round(x) owning
// u: P(m) = w_m / (sum of w over the orders whose period meets wo.x +- 1, uniform beyond 256
// of them), q the proxy of F_N (the Lorentzian N/((1 + (2N*r)^2)*atan N), the uniform 1 for
// N = 1), q_v the Cauchy proxy of g.
fn diffraction_bsdf_pdf(b: DiffractionBsdf, wo: vec3<f32>, wi: vec3<f32>, lambda_nm: f32) -> f32 {
    if b.groove >= 2u || wo.z <= 0.0 || wi.z <= 0.0 || lambda_nm <= 0.0 {
        return 0.0;
    }
    let step = lambda_nm / b.period_nm;
    let x_lo = (wo.x - 1.0) / step;
    let x_hi = (wo.x + 1.0) / step;
    if !(abs(x_lo) < 1.0e9 && abs(x_hi) < 1.0e9) {
        return 0.0;
    }
    let lo = i32(floor(x_lo - 0.5)) + 1;
    let hi = i32(ceil(x_hi + 0.5)) - 1;
    if hi < lo {
        return 0.0;
    }
    let u = wi.x + wo.x;
    let v = wi.y + wo.y;
    let x = b.period_nm * (u / lambda_nm);
    let mf = round(x);
    let r = x - mf;
    let m = i32(mf);
    if m < lo || m > hi {
        return 0.0;
    }
    var w = 1.0;
    var total = f32(hi - lo + 1);
    if hi - lo + 1 <= 256 {
        w = diffraction_bsdf_weight(b, m);
        total = diffraction_bsdf_total(b, lo, hi);
    }
    if total <= 0.0 {
        return 0.0;
    }
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
    let c = (inv_s * wi.z) / (3.141592653589793 * (1.0 + tv * tv));
    return a * c;
}
