// The CD demo of the example gpu (cd.rs): a CD (the `cd` preset's rigorous efficiencies, N = 34,
// a Gaussian groove spread) on a grey table under a disk light and a sky, one compute
// invocation per pixel. Per pixel sample: the camera ray meets the plane y = 0; on the data
// area the shading frame is (radial, tangential, up) and the pixel gets the disk light's direct
// light at K stratified wavelengths (diffraction_bsdf_tabulated_f) and one BSDF sample toward
// the sky (diffraction_bsdf_tabulated_sample, its weight f*cos/pdf); elsewhere a Lambertian grey.
// cd.rs renders the same estimator on the CPU with the same random numbers.

struct Params {
    width: u32,
    height: u32,
    spp: u32,
    lambdas: u32,
    eye: vec4<f32>,
    forward: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    // xyz: the disk light's centre, w: its radius.
    light: vec4<f32>,
    // x: the light's intensity, y: the sky's radiance at the zenith, z: at the horizon.
    radiance: vec4<f32>,
    // The hole, the inner and outer radii of the data area, the disc's radius.
    disc: vec4<f32>,
    // The table's and the clear ring's albedo.
    albedo: vec4<f32>,
    seed: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<storage, read> params: Params;
@group(0) @binding(1) var<storage, read> model: array<DiffractionBsdf>;
@group(0) @binding(2) var<storage, read> diffraction_efficiency_tables: array<f32>;
// 471 rows, 360..830 nm at 1 nm: the CMFs times the light's spectrum, Y summing to 1.
@group(0) @binding(3) var<storage, read> cmf: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read_write> out: array<vec4<f32>>;

fn cd_hash(x: u32) -> u32 {
    let v = x * 747796405u + 2891336453u;
    let w = ((v >> ((v >> 28u) + 4u)) ^ v) * 277803737u;
    return (w >> 22u) ^ w;
}

// A uniform number in [0, 1) with 24 bits for (pixel, sample, dimension).
fn cd_rand(pixel: u32, s: u32, d: u32) -> f32 {
    let h = cd_hash(pixel ^ cd_hash(s * 2654435769u + d * 2246822519u + params.seed));
    return f32(h >> 8u) / 16777216.0;
}

fn cd_row(lambda_nm: f32) -> vec3<f32> {
    return cmf[min(u32(lambda_nm - 360.0), 470u)].xyz;
}

fn cd_white() -> vec3<f32> {
    var w = vec3<f32>(0.0);
    for (var i = 0u; i < 471u; i++) {
        w += cmf[i].xyz;
    }
    return w;
}

fn cd_sky(d: vec3<f32>) -> f32 {
    let y = max(d.y, 0.0);
    return params.radiance.z + (params.radiance.y - params.radiance.z) * y * y;
}

@compute @workgroup_size(64)
fn cd_main(@builtin(global_invocation_id) id: vec3<u32>) {
    let pixel = id.x;
    if pixel >= params.width * params.height {
        return;
    }
    let px = f32(pixel % params.width);
    let py = f32(pixel / params.width);
    let white = cd_white();
    let b = model[0];
    let k_count = params.lambdas;
    var sum = vec3<f32>(0.0);
    for (var s = 0u; s < params.spp; s++) {
        let sx = 2.0 * (px + cd_rand(pixel, s, 0u)) / f32(params.width) - 1.0;
        let sy = 1.0 - 2.0 * (py + cd_rand(pixel, s, 1u)) / f32(params.height);
        let dir = normalize(params.forward.xyz + sx * params.right.xyz + sy * params.up.xyz);
        if dir.y >= 0.0 {
            sum += cd_sky(dir) * white;
            continue;
        }
        let t = -params.eye.y / dir.y;
        let p = params.eye.xyz + t * dir;
        let r = length(p.xz);
        let wo_w = -dir;
        // A point of the disk light, uniform by area on the disk facing p.
        let to_light = params.light.xyz - p;
        let axis = normalize(to_light);
        let e1 = normalize(cross(axis, select(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 0.0, 1.0),
                                              abs(axis.x) > 0.9)));
        let e2 = cross(axis, e1);
        let lr = params.light.w * sqrt(cd_rand(pixel, s, 2u));
        let lphi = 6.283185307179586 * cd_rand(pixel, s, 3u);
        let q = params.light.xyz + lr * (cos(lphi) * e1 + sin(lphi) * e2);
        let dl = q - p;
        let dist2 = dot(dl, dl);
        let wi_w = dl / sqrt(dist2);
        let irradiance = params.radiance.x * max(wi_w.y, 0.0) / dist2;
        if r < params.disc.y || r > params.disc.z {
            // The table (outside the disc or in the hole) or the clear ring.
            let on_disc = r > params.disc.x && r <= params.disc.w;
            let albedo = select(params.albedo.x, params.albedo.y, on_disc);
            sum += (albedo / 3.141592653589793) * irradiance * white;
            continue;
        }
        // The grating: x radial (across the circular tracks), y along them, z up.
        let tx = vec3<f32>(p.x / r, 0.0, p.z / r);
        let nz = vec3<f32>(0.0, 1.0, 0.0);
        let ty = cross(nz, tx);
        let wo = vec3<f32>(dot(wo_w, tx), dot(wo_w, ty), wo_w.y);
        let wi = vec3<f32>(dot(wi_w, tx), dot(wi_w, ty), wi_w.y);
        let xi_l = cd_rand(pixel, s, 4u);
        for (var k = 0u; k < k_count; k++) {
            let lambda = 360.0 + 470.0 * (f32(k) + xi_l) / f32(k_count);
            let f = diffraction_bsdf_tabulated_f(b, wo, wi, lambda);
            sum += (f * irradiance * 470.0 / f32(k_count)) * cd_row(lambda);
        }
        let lambda_h = 360.0 + 470.0 * cd_rand(pixel, s, 5u);
        let xi = vec3<f32>(cd_rand(pixel, s, 6u), cd_rand(pixel, s, 7u), cd_rand(pixel, s, 8u));
        let smp = diffraction_bsdf_tabulated_sample(b, wo, lambda_h, xi);
        if smp.valid != 0u {
            let d = smp.wi.x * tx + smp.wi.y * ty + smp.wi.z * nz;
            let weight = smp.f * smp.wi.z / smp.pdf;
            sum += (weight * cd_sky(d) * 470.0) * cd_row(lambda_h);
        }
    }
    out[pixel] = vec4<f32>(sum / f32(params.spp), 0.0);
}
