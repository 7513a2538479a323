// The shading half of the GPU renderer: one invocation per pixel sums its G-buffer records'
// eq. 12 (the library's diffraction_shade, and diffraction_shade_grating with the colour table
// bound at group 1 for grating records) times their weights into the pixel. One dispatch per
// colour table: pass k shades the grating records whose material uses table k, pass 0 also
// every other record. Follows the library's shading_source(1, 0).

struct Params {
    pixels: u32,
    lights: u32,
    table: u32,
    pad: u32,
    ambient: vec4<f32>,
}

struct Record {
    point: vec3<f32>,
    material: u32,
    normal: vec3<f32>,
    // 1: a grating here (t below), 0: not.
    grating: u32,
    wo: vec3<f32>,
    pad0: u32,
    t: vec3<f32>,
    pad1: u32,
    albedo: vec3<f32>,
    pad2: u32,
    weight: vec3<f32>,
    pad3: u32,
}

struct Material {
    k: DiffractionIllumination,
    exposure: f32,
    table: u32,
    pad0: u32,
    pad1: u32,
}

struct Light {
    position: vec4<f32>,
    color: vec4<f32>,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> records: array<Record>;
@group(0) @binding(2) var<storage, read> offsets: array<u32>;
@group(0) @binding(3) var<storage, read> visibility: array<f32>;
@group(0) @binding(4) var<storage, read> materials: array<Material>;
@group(0) @binding(5) var<storage, read> lights: array<Light>;
@group(0) @binding(6) var<storage, read_write> image: array<vec4<f32>>;

@compute @workgroup_size(64)
fn shade(@builtin(global_invocation_id) id: vec3<u32>) {
    let p = id.x;
    if p >= params.pixels {
        return;
    }
    let zero = vec3<f32>(0.0);
    var c = zero;
    for (var r = offsets[p]; r < offsets[p + 1u]; r++) {
        let rec = records[r];
        let m = materials[rec.material];
        let grating = rec.grating == 1u;
        if select(0u, m.table, grating) != params.table {
            continue;
        }
        var s = diffraction_shade(m.k, params.ambient.xyz, rec.albedo, zero, 0.0, zero);
        for (var l = 0u; l < params.lights; l++) {
            let v = visibility[r * params.lights + l];
            if v <= 0.0 {
                continue;
            }
            let light = lights[l];
            let wi = normalize(light.position.xyz - rec.point);
            let rgb = light.color.xyz * v;
            if grating {
                s += diffraction_shade_grating(
                    m.k, zero, rec.albedo, rgb, m.exposure, rec.normal, rec.t, rec.wo, wi,
                );
            } else {
                s += diffraction_shade(m.k, zero, rec.albedo, rgb, dot(wi, rec.normal), zero);
            }
        }
        c += rec.weight * s;
    }
    image[p] += vec4<f32>(c, 0.0);
}
