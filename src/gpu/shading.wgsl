// diffraction: the paper's eq. 12 (I = ambient + diffuse + diffraction), the twin of
// `Illumination::shade`, and a grating pixel shaded from its colour table. Needs TYPES_WGSL and
// COLOR_TABLE_WGSL (with its bindings).

// XYZ -> linear sRGB, IEC 61966-2-1 (the crate's `Xyz::to_linear_srgb`).
fn diffraction_xyz_to_linear_srgb(c: vec3<f32>) -> vec3<f32> {
    return vec3<f32>(
        3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
        -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
        0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z,
    );
}

// Eq. 12 for one light: ambient_light*albedo*k_a + light*(albedo*k_d*cos_i + diffracted*k_diff),
// the light term only where cos_i > 0 (cos_i clamped to 1). Sum over lights by calling it with a
// zero ambient for all lights but one.
fn diffraction_shade(
    k: DiffractionIllumination,
    ambient_light: vec3<f32>,
    albedo: vec3<f32>,
    light: vec3<f32>,
    cos_i: f32,
    diffracted: vec3<f32>,
) -> vec3<f32> {
    var c = ambient_light * albedo * k.ambient;
    if cos_i > 0.0 {
        c += light * (albedo * (k.diffuse * min(cos_i, 1.0)) + diffracted * k.diffraction);
    }
    return c;
}

// The phase projection u = (wi + wo) . t: t is the unit grating vector (across the grooves, in
// the tangent plane); wi toward the light, wo toward the viewer, both unit.
fn diffraction_phase_u(wo: vec3<f32>, wi: vec3<f32>, t: vec3<f32>) -> f32 {
    return dot(wi + wo, t);
}

// One light on a grating pixel in linear sRGB: the table's colour at u times `exposure` is the
// diffraction term of eq. 12 (the paper's diffraction colour in place of the specular one).
// n is the unit normal; below the horizon (either direction) only the ambient term is left.
fn diffraction_shade_grating(
    k: DiffractionIllumination,
    ambient_light: vec3<f32>,
    albedo: vec3<f32>,
    light: vec3<f32>,
    exposure: f32,
    n: vec3<f32>,
    t: vec3<f32>,
    wo: vec3<f32>,
    wi: vec3<f32>,
) -> vec3<f32> {
    var cos_i = dot(wi, n);
    if dot(wo, n) <= 0.0 {
        cos_i = 0.0;
    }
    let xyz = diffraction_table_lookup(diffraction_phase_u(wo, wi, t));
    let diffracted = diffraction_xyz_to_linear_srgb(xyz) * exposure;
    return diffraction_shade(k, ambient_light, albedo, light, cos_i, diffracted);
}
