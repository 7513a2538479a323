// diffraction: the two slit factors in f32 with the phase in cycles, the GPU twin of
// src/num/kernel.rs (`single_slit_cycles`, `n_slit_cycles`). Only +, -, *, /, round, ldexp,
// conversions and integer arithmetic are used: WGSL's built-in `sin` is allowed an absolute
// error of 2^-11 (and only on [-pi, pi]), far too coarse near the peaks, so sin(pi z) is a
// polynomial here. Accuracy on any conforming implementation: docs/gpu.md (at most 1e-5
// absolute for each factor, derived from the WGSL accuracy rules).

// sin(pi z)/z for t = z^2, |z| <= 1/2: the Taylor coefficients (-1)^k pi^(2k+1)/(2k+1)!,
// k = 0..6 (truncation below 7e-10 on the range).
fn diffraction_sinpi_over(t: f32) -> f32 {
    var p = 0.00046630280576761234;
    p = p * t - 0.007370430945714348;
    p = p * t + 0.08214588661112819;
    p = p * t - 0.5992645293207919;
    p = p * t + 2.550164039877345;
    p = p * t - 5.167712780049969;
    return p * t + 3.141592653589793;
}

// sin(pi z) for |z| <= 1/2.
fn diffraction_sinpi(z: f32) -> f32 {
    return z * diffraction_sinpi_over(z * z);
}

// S(y) = (sin(pi y)/(pi y))^2, y = w*u/lambda in cycles; S(0) = 1, in [0, 1].
fn diffraction_single_slit_cycles(y: f32) -> f32 {
    var q: f32;
    if abs(y) <= 0.5 {
        // sinc without a division by y: exact limit at 0, no underflow.
        q = diffraction_sinpi_over(y * y) * 0.3183098861837907;
    } else {
        let r = y - round(y); // exact
        q = diffraction_sinpi(r) / (3.141592653589793 * y);
    }
    return min(q * q, 1.0);
}

// N*r reduced modulo 1 exactly, for 1/(2N) < |r| <= 1/2 (so r is a normal f32): r = m * 2^-k
// with the 24-bit integer m, N*m is formed exactly as a 64-bit integer (two u32 words), its
// low k bits are the fraction. Returns |N*r| mod 1 in [0, 1] (the sign is irrelevant to F_N).
fn diffraction_n_phase(r: f32, n: u32) -> f32 {
    let bits = bitcast<u32>(r);
    let m = (bits & 0x7fffffu) | 0x800000u;
    let k = 150u - ((bits >> 23u) & 0xffu); // 24 <= k <= 56 on the range
    // The 64-bit product n*m from 16-bit halves.
    let a0 = n & 0xffffu;
    let a1 = n >> 16u;
    let b0 = m & 0xffffu;
    let b1 = m >> 16u;
    let p0 = a0 * b0;
    let p1 = a0 * b1;
    let p2 = a1 * b0;
    let mid = (p0 >> 16u) + (p1 & 0xffffu) + (p2 & 0xffffu);
    let lo = (p0 & 0xffffu) | (mid << 16u);
    let hi = a1 * b1 + (p1 >> 16u) + (p2 >> 16u) + (mid >> 16u);
    if k >= 32u {
        let hk = k - 32u;
        let hi_m = hi & ((1u << hk) - 1u);
        return ldexp(f32(hi_m), 32 - i32(k)) + ldexp(f32(lo), -i32(k));
    }
    let lo_m = lo & ((1u << k) - 1u);
    return ldexp(f32(lo_m), -i32(k));
}

// F_N(x) = sin^2(pi N x)/(N^2 sin^2(pi x)), x = d*u/lambda in cycles: 1 at every integer x,
// in [0, 1]; N = 1 gives 1, N = 0 gives 0.
fn diffraction_n_slit_cycles(x: f32, n: u32) -> f32 {
    if n <= 1u {
        return f32(n);
    }
    let r = x - round(x); // exact; F_N has period 1
    let nf = f32(n);
    if nf * abs(r) <= 0.5 {
        // No wrap: sin(pi N r)/(N sin(pi r)) = sinc(pi N r)/sinc(pi r), the limit F = 1 at
        // r = 0 without 0/0.
        let s = nf * r;
        let q = diffraction_sinpi_over(s * s) / diffraction_sinpi_over(r * r);
        return min(q * q, 1.0);
    }
    let f = diffraction_n_phase(r, n);
    let s = f - round(f); // exact, |s| <= 1/2
    let q = diffraction_sinpi(s) / (nf * diffraction_sinpi(abs(r)));
    return min(q * q, 1.0);
}

// The paper's intensity I = S(w*u/lambda) * F_N(d*u/lambda) at phases in cycles.
fn diffraction_intensity_cycles(x: f32, y: f32, n: u32) -> f32 {
    return diffraction_single_slit_cycles(y) * diffraction_n_slit_cycles(x, n);
}
