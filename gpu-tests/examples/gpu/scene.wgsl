// Fig. 6 of Agu & Hill on the GPU (headless): a CD beside a can on a wooden table, ray cast
// per pixel in a compute shader, the CD's data area shaded by the library's
// `diffraction_shade_grating` (eq. 12 with the colour table's lookup). A simplified version
// of examples/scenes/fig6.toml: no mirror reflections, a striped can instead of the label
// image, hard shadows of the can only.

struct Params {
    width: u32,
    height: u32,
    exposure: f32,
    pad: f32,
    k_grating: DiffractionIllumination,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read_write> pixels: array<u32>;

const CD_CENTER = vec3<f32>(-0.35, 0.012, 0.15);
const CAN_CENTER = vec3<f32>(0.75, 0.0, -0.35);
const CAN_RADIUS = 0.33;
const CAN_HEIGHT = 1.22;
const AMBIENT = vec3<f32>(0.12, 0.12, 0.12);
const BACKGROUND = vec3<f32>(0.015, 0.015, 0.02);

struct Hit {
    t: f32,
    p: vec3<f32>,
    n: vec3<f32>,
    kind: u32, // 0 none, 1 table, 2 CD data area, 3 CD rim, 4 CD inner ring, 5 can
}

fn can_t(o: vec3<f32>, d: vec3<f32>) -> vec2<f32> {
    // The side of the cylinder around the y axis through CAN_CENTER: (t, side) or t < 0.
    let oc = o - CAN_CENTER;
    let a = d.x * d.x + d.z * d.z;
    let b = oc.x * d.x + oc.z * d.z;
    let c = oc.x * oc.x + oc.z * oc.z - CAN_RADIUS * CAN_RADIUS;
    let disc = b * b - a * c;
    if disc < 0.0 || a < 1e-12 {
        return vec2<f32>(-1.0, 0.0);
    }
    let t = (-b - sqrt(disc)) / a;
    let y = o.y + t * d.y;
    if t > 1e-4 && y >= 0.0 && y <= CAN_HEIGHT {
        return vec2<f32>(t, 1.0);
    }
    // The top cap.
    if abs(d.y) > 1e-6 {
        let tc = (CAN_HEIGHT - o.y) / d.y;
        let q = o + tc * d - CAN_CENTER;
        if tc > 1e-4 && q.x * q.x + q.z * q.z <= CAN_RADIUS * CAN_RADIUS {
            return vec2<f32>(tc, 2.0);
        }
    }
    return vec2<f32>(-1.0, 0.0);
}

fn trace(o: vec3<f32>, d: vec3<f32>) -> Hit {
    var h = Hit(1e30, vec3<f32>(0.0), vec3<f32>(0.0, 1.0, 0.0), 0u);
    if d.y < 0.0 {
        // The table (y = 0) and the CD (a disc just above it).
        let tt = -o.y / d.y;
        let pt = o + tt * d;
        if abs(pt.x) <= 6.0 && abs(pt.z) <= 6.0 {
            h = Hit(tt, pt, vec3<f32>(0.0, 1.0, 0.0), 1u);
        }
        let tcd = (CD_CENTER.y - o.y) / d.y;
        let p = o + tcd * d;
        let r = length((p - CD_CENTER).xz);
        if r < 0.6 && r > 0.075 {
            var kind = 4u;
            if r > 0.58 {
                kind = 3u;
            } else if r > 0.23 {
                kind = 2u;
            }
            h = Hit(tcd, p, vec3<f32>(0.0, 1.0, 0.0), kind);
        }
    }
    let c = can_t(o, d);
    if c.x > 0.0 && c.x < h.t {
        let p = o + c.x * d;
        var n = vec3<f32>(0.0, 1.0, 0.0);
        if c.y < 1.5 {
            n = normalize(vec3<f32>(p.x - CAN_CENTER.x, 0.0, p.z - CAN_CENTER.z));
        }
        h = Hit(c.x, p, n, 5u);
    }
    return h;
}

fn wood(p: vec3<f32>) -> vec3<f32> {
    let light = vec3<f32>(0.62, 0.40, 0.20);
    let dark = vec3<f32>(0.32, 0.16, 0.07);
    let plank = floor(p.x / 0.6);
    let q = vec2<f32>(p.x - (plank + 0.5) * 0.6, p.z * 0.2 + plank * 1.7);
    let rings = 0.5 + 0.5 * sin(length(q) / 0.03 + 1.5 * sin(3.0 * p.z + plank));
    return mix(dark, light, rings);
}

fn albedo(h: Hit) -> vec3<f32> {
    switch h.kind {
        case 1u: { return wood(h.p); }
        case 2u, 3u: { return vec3<f32>(0.05, 0.05, 0.055); }
        case 4u: { return vec3<f32>(0.35, 0.36, 0.38); }
        case 5u: {
            if h.n.y > 0.5 {
                return vec3<f32>(0.6, 0.6, 0.62);
            }
            let band = fract(h.p.y / CAN_HEIGHT * 3.0);
            if band < 0.5 {
                return vec3<f32>(0.7, 0.08, 0.06);
            }
            return vec3<f32>(0.85, 0.82, 0.75);
        }
        default: { return BACKGROUND; }
    }
}

fn shadowed(p: vec3<f32>, l: vec3<f32>) -> bool {
    let d = normalize(l - p);
    let c = can_t(p + 1e-3 * d, d);
    return c.x > 0.0 && c.x < length(l - p);
}

fn srgb_encode(c: f32) -> f32 {
    let x = clamp(c, 0.0, 1.0);
    if x <= 0.0031308 {
        return 12.92 * x;
    }
    return 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

@compute @workgroup_size(8, 8)
fn render(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let eye = vec3<f32>(0.0, 1.7, 2.9);
    let fwd = normalize(vec3<f32>(0.15, 0.3, 0.0) - eye);
    let right = normalize(cross(fwd, vec3<f32>(0.0, 1.0, 0.0)));
    let up = cross(right, fwd);
    let half_h = tan(0.5 * radians(40.0));
    let aspect = f32(params.width) / f32(params.height);
    let sx = (2.0 * (f32(id.x) + 0.5) / f32(params.width) - 1.0) * half_h * aspect;
    let sy = (1.0 - 2.0 * (f32(id.y) + 0.5) / f32(params.height)) * half_h;
    let d = normalize(fwd + sx * right + sy * up);
    let h = trace(eye, d);
    var c = BACKGROUND;
    if h.kind != 0u {
        let a = albedo(h);
        let wo = -d;
        let lights = array<vec4<f32>, 2>(
            vec4<f32>(0.0, 3.0, -2.0, 0.9),
            vec4<f32>(-3.0, 4.0, 3.0, 0.6),
        );
        let plain = DiffractionIllumination(1.0, 1.0, 0.0, 0.0);
        c = vec3<f32>(0.0);
        for (var i = 0; i < 2; i++) {
            let lp = lights[i].xyz;
            let wi = normalize(lp - h.p);
            var light = vec3<f32>(lights[i].w);
            if shadowed(h.p, lp) {
                light = vec3<f32>(0.0);
            }
            // The ambient term once (with the first light).
            var amb = vec3<f32>(0.0);
            if i == 0 {
                amb = AMBIENT;
            }
            if h.kind == 2u {
                // The data area: a radial grating, its grating vector away from the centre.
                let t = normalize(vec3<f32>(h.p.x - CD_CENTER.x, 0.0, h.p.z - CD_CENTER.z));
                c += diffraction_shade_grating(
                    params.k_grating, amb, a, light, params.exposure, h.n, t, wo, wi);
            } else {
                c += diffraction_shade(plain, amb, a, light, dot(wi, h.n), vec3<f32>(0.0));
            }
        }
    }
    let r = u32(round(255.0 * srgb_encode(c.x)));
    let g = u32(round(255.0 * srgb_encode(c.y)));
    let b = u32(round(255.0 * srgb_encode(c.z)));
    pixels[id.y * params.width + id.x] = r | (g << 8u) | (b << 16u) | (255u << 24u);
}
