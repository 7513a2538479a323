//! A minimal Whitted ray tracer of the paper's scenes with the crate's shading only, in one file
//! (and the PNG writer the examples share, `support/png.rs`).
//!
//! ```text
//! cargo run --release --example whitted                    # fig4a.png and cd.png into out/
//! cargo run --release --example whitted -- cd --table      # footprint-filtered colour table
//! cargo run --release --example whitted -- fig4a --clip constant --size 320x240 --spp 8
//! ```
//!
//! Per hit of a grating (the paper's rendering steps 3-8): the grating vector t from the
//! surface's field, the shading frame (normal, t), local `wi` and `wo`, the phase projection
//! u = wi.x + wo.x, the colour of the Agu-Hill intensity at u (`Spectral::xyz` of the `AguHill`
//! model's grating), and eq. 12 by `Illumination::shade` over the lights. With `--table` the colour is
//! instead a `ColorTable`'s mean over the interval of u the pixel sees (`footprint::u_interval`
//! from the pixel's ray differentials and the light's extent), which removes the aliasing of the
//! narrow spectral bands at low sample counts. The linear sRGB of the pixel is clipped by one of
//! Hall's methods (`--clip`), encoded, and written as a PNG by the small encoder at the end.
//!
//! The full renderer (TOML scenes, every figure of the paper, diagnostics, animation) is
//! `tools/render` (`cargo run --release -p diffraction-render --bin raytrace`).

use std::process::ExitCode;

use diffraction::color::{Clip, LinearSrgb};
use diffraction::footprint::{u_interval, LightExtent, PixelFootprint, PixelRay};
use diffraction::frame::ShadingFrame;
use diffraction::glam::DVec3;
use diffraction::spectrum::{Illuminant, Spectral, Strategy};
use diffraction::{AguHill, ColorTable, Grating, Illumination};

#[path = "support/png.rs"]
mod png;

// --- Scenes ----------------------------------------------------------------------------------

/// How the grating vector varies over a grating's surface.
#[derive(Debug, Clone, Copy)]
enum Field {
    /// One world direction (projected into the surface): straight grooves.
    Constant(DVec3),
    /// Away from a centre: circular tracks, as on a CD.
    Radial(DVec3),
}

/// What a surface does with light.
#[derive(Debug, Clone)]
enum Surface {
    /// A procedural wood texture, Lambertian.
    Wood,
    /// A diffuse colour.
    Diffuse(DVec3),
    /// A diffraction grating: the paper's model, its grooves and a dark base colour.
    Grating(AguHill, Field, DVec3),
    /// A mirror reflecting this fraction of the light, over a dark diffuse base.
    Mirror(f64),
}

/// The shapes: a box (centre, half sizes, turn about the vertical axis) and a horizontal disc
/// facing up (centre, radius, radius of its hole).
#[derive(Debug, Clone, Copy)]
enum Shape {
    Box(DVec3, DVec3, f64),
    Disc(DVec3, f64, f64),
}

#[derive(Debug, Clone)]
struct Object {
    shape: Shape,
    surface: Surface,
    /// Eq. 12's coefficients (ambient, diffuse, diffraction).
    shading: Illumination,
    /// Which entry of `Prepared::gratings` this object's grating is (gratings only).
    grating: usize,
}

/// A light: a sphere of `radius` (0: a point) of white intensity `power`, seen through
/// `samples` shadow rays.
#[derive(Debug, Clone, Copy)]
struct Light {
    position: DVec3,
    power: f64,
    radius: f64,
    samples: usize,
}

fn light(position: [f64; 3], power: f64, radius: f64) -> Light {
    let samples = if radius > 0.0 { 4 } else { 1 };
    let position = DVec3::from(position);
    Light {
        position,
        power,
        radius,
        samples,
    }
}

#[derive(Debug, Clone)]
struct Scene {
    name: &'static str,
    eye: DVec3,
    look_at: DVec3,
    lights: Vec<Light>,
    objects: Vec<Object>,
    /// The ambient light of eq. 12 and the sky at the horizon and at the zenith.
    ambient: DVec3,
    sky: (DVec3, DVec3),
}

impl Scene {
    /// The scene's camera and lights over a wooden floor.
    fn new(name: &'static str, eye: [f64; 3], look_at: [f64; 3], lights: Vec<Light>) -> Scene {
        let (eye, look_at) = (DVec3::from(eye), DVec3::from(look_at));
        let ambient = DVec3::splat(0.12);
        let sky = (DVec3::new(0.015, 0.015, 0.02), DVec3::new(0.04, 0.05, 0.08));
        let mut s = Scene {
            name,
            eye,
            look_at,
            lights,
            objects: vec![],
            ambient,
            sky,
        };
        s.add(
            Shape::Disc(DVec3::ZERO, 8.0, 0.0),
            Surface::Wood,
            (1.0, 0.9, 0.0),
        );
        s
    }

    /// Adds an object with eq. 12's coefficients (ambient, diffuse, diffraction).
    fn add(&mut self, shape: Shape, surface: Surface, (a, d, g): (f64, f64, f64)) {
        let shading = Illumination::new(a, d, g).expect("the scenes' coefficients are valid");
        self.objects.push(Object {
            shape,
            surface,
            shading,
            grating: 0,
        });
    }
}

/// Fig. 4a: a 625 lines/mm grating plate and a mirror cube on wood.
fn fig4a() -> Result<Scene, diffraction::Error> {
    let lights = vec![
        light([0.0, 6.0, -4.0], 0.9, 0.15),
        light([-5.0, 6.0, 6.0], 0.6, 0.0),
    ];
    let mut s = Scene::new("fig4a", [0.0, 3.0, 6.4], [0.3, 0.1, 0.0], lights);
    let turn = 8f64.to_radians();
    let plate = Shape::Box(
        DVec3::new(-1.0, 0.03, 0.4),
        DVec3::new(1.1, 0.03, 0.9),
        turn,
    );
    // The grating vector along the plate's depth (toward the camera): grooves run left-right.
    let field = Field::Constant(DVec3::new(turn.sin(), 0.0, turn.cos()));
    let model = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    let dark = DVec3::new(0.03, 0.03, 0.035);
    s.add(plate, Surface::Grating(model, field, dark), (1.0, 1.0, 1.0));
    let cube = Shape::Box(
        DVec3::new(1.55, 0.6, -0.2),
        DVec3::splat(0.6),
        35f64.to_radians(),
    );
    s.add(cube, Surface::Mirror(0.9), (1.0, 1.0, 0.0));
    let small = Shape::Box(
        DVec3::new(2.6, 0.3, 1.2),
        DVec3::splat(0.3),
        20f64.to_radians(),
    );
    let red = Surface::Diffuse(DVec3::new(0.5, 0.1, 0.08));
    s.add(small, red, (1.0, 0.9, 0.0));
    Ok(s)
}

/// Fig. 6's disc: a CD (1.6 µm track pitch, circular tracks) on wood.
fn cd() -> Result<Scene, diffraction::Error> {
    let lights = vec![
        light([0.0, 3.0, -2.0], 0.9, 0.05),
        light([-3.0, 4.0, 3.0], 0.6, 0.0),
    ];
    let mut s = Scene::new("cd", [0.0, 1.7, 2.9], [0.0, 0.1, 0.0], lights);
    let center = DVec3::new(0.0, 0.012, 0.1);
    let model = AguHill::new(Grating::new(1600.0, 800.0, 1000)?);
    let dark = DVec3::new(0.05, 0.05, 0.055);
    let disc = Surface::Grating(model, Field::Radial(center), dark);
    s.add(Shape::Disc(center, 0.6, 0.1), disc, (1.0, 1.0, 1.0));
    Ok(s)
}

// --- Geometry --------------------------------------------------------------------------------

#[derive(Debug, Clone, Copy)]
struct Ray {
    origin: DVec3,
    dir: DVec3,
}

#[derive(Debug, Clone, Copy)]
struct Hit {
    t: f64,
    point: DVec3,
    normal: DVec3,
    object: usize,
}

/// Turns `v` by `angle` about the vertical axis.
fn turn_y(v: DVec3, angle: f64) -> DVec3 {
    let (s, c) = angle.sin_cos();
    DVec3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z)
}

/// The distance along `ray` to `shape` and the outward normal there, beyond `t_min`.
fn intersect(shape: &Shape, ray: &Ray, t_min: f64) -> Option<(f64, DVec3)> {
    match *shape {
        Shape::Disc(center, radius, hole) => {
            let t = (center.y - ray.origin.y) / ray.dir.y;
            let r = (ray.origin + ray.dir * t - center).length();
            (t > t_min && t.is_finite() && r <= radius && r >= hole).then_some((t, DVec3::Y))
        }
        Shape::Box(center, half, turn) => {
            // The slab test in the box's own frame.
            let o = turn_y(ray.origin - center, -turn);
            let d = turn_y(ray.dir, -turn);
            let (mut t0, mut t1, mut axis) = (f64::NEG_INFINITY, f64::INFINITY, 0);
            for i in 0..3 {
                let (a, b) = ((-half[i] - o[i]) / d[i], (half[i] - o[i]) / d[i]);
                let (near, far) = (a.min(b), a.max(b));
                if near > t0 {
                    (t0, axis) = (near, i);
                }
                t1 = t1.min(far);
            }
            if t0 > t1 || t0 <= t_min || !t0.is_finite() {
                return None;
            }
            let mut n = DVec3::ZERO;
            n[axis] = -d[axis].signum();
            Some((t0, turn_y(n, turn)))
        }
    }
}

fn nearest(scene: &Scene, ray: &Ray, t_max: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (object, o) in scene.objects.iter().enumerate() {
        if let Some((t, normal)) = intersect(&o.shape, ray, 1e-9) {
            if t < t_max && best.is_none_or(|b| t < b.t) {
                let point = ray.origin + ray.dir * t;
                best = Some(Hit {
                    t,
                    point,
                    normal,
                    object,
                });
            }
        }
    }
    best
}

/// A small deterministic generator (SplitMix64) for the pixel and light samples.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The wood: growth rings around a log's axis along x, planks 0.9 wide with dark seams.
fn wood(p: DVec3) -> DVec3 {
    let plank = (p.z / 0.9).floor();
    let z = p.z - (plank + 0.5) * 0.9 + 0.25 * (plank * 12.9898).sin();
    let y = 0.9 + 0.3 * (plank * 4.1414).cos();
    let wobble = 0.03 * (p.x * 1.3 + plank).sin() + 0.01 * (p.x * 5.3 + 9.0 * z).sin();
    let ring = (((y * y + z * z).sqrt() + wobble) / 0.03).fract();
    let (light, dark) = (DVec3::new(0.60, 0.38, 0.19), DVec3::new(0.30, 0.15, 0.06));
    let c = light.lerp(dark, ring.powi(3));
    let seam =
        ((p.z / 0.9).fract() - 0.5).abs() > 0.495 || ((p.x + 2.5 * plank) / 5.0).fract() < 0.003;
    if seam {
        c * 0.4
    } else {
        c
    }
}

// --- Shading ---------------------------------------------------------------------------------

/// The options of a run.
struct Options {
    scenes: Vec<String>,
    width: usize,
    height: usize,
    spp: usize,
    clip: Clip,
    table: bool,
    out: String,
}

/// A scene with what its gratings need once: the spectral integrator, each grating's exposure
/// and, with `--table`, its colour table.
struct Prepared {
    scene: Scene,
    spectral: Spectral,
    /// Per grating: (exposure, colour table).
    gratings: Vec<(f64, Option<ColorTable>)>,
}

/// The exposure of a grating: 1 / the largest Y of its diffracted orders over u ∈ [-2, 2]
/// (leaving out the mirror lobe near u = 0), so that its brightest diffracted colour has Y = 1
/// whatever N is (with the paper's 1/N² normalisation each order integrates to about 1/N).
fn exposure(spectral: &Spectral, grating: &Grating) -> f64 {
    let u_min = 360.0 / (2.0 * grating.period_nm());
    let max_y = (0..=2000)
        .map(|i| -2.0 + 4.0 * i as f64 / 2000.0)
        .filter(|u| u.abs() >= u_min)
        .map(|u| spectral.xyz(grating, u, Strategy::PEAK_SEARCH).y)
        .fold(0.0, f64::max);
    1.0 / if max_y > 0.0 { max_y } else { 1.0 }
}

fn prepare(mut scene: Scene, table: bool) -> Result<Prepared, diffraction::Error> {
    let spectral = Spectral::new(Illuminant::D65);
    let mut gratings = Vec::new();
    for o in &mut scene.objects {
        if let Surface::Grating(model, ..) = &o.surface {
            let g = model.grating();
            let t = table
                .then(|| ColorTable::new(&spectral, g, 1e-2))
                .transpose()?;
            o.grating = gratings.len();
            gratings.push((exposure(&spectral, g), t));
        }
    }
    Ok(Prepared {
        scene,
        spectral,
        gratings,
    })
}

/// The rays through the neighbouring pixels (one pixel right and one down), for the footprint.
type Differentials = Option<(PixelRay, PixelRay)>;

/// The linear sRGB radiance along `ray` (Whitted: direct light and mirror recursion).
fn trace(p: &Prepared, ray: &Ray, diff: Differentials, depth: u32, rng: &mut Rng) -> DVec3 {
    let scene = &p.scene;
    let Some(hit) = nearest(scene, ray, f64::INFINITY) else {
        return scene.sky.0.lerp(scene.sky.1, ray.dir.y.clamp(0.0, 1.0));
    };
    let obj = &scene.objects[hit.object];
    let (n, wo) = (hit.normal, -ray.dir);
    let origin = hit.point + n * 1e-7;
    let albedo = match &obj.surface {
        Surface::Wood => wood(hit.point),
        Surface::Diffuse(c) => *c,
        Surface::Grating(_, _, albedo) => *albedo,
        Surface::Mirror(_) => DVec3::splat(0.02),
    };
    // Step 4: the shading frame of a grating (normal, grating vector); none elsewhere.
    let grating = match &obj.surface {
        Surface::Grating(model, field, _) => {
            let t = match *field {
                Field::Constant(t) => t,
                Field::Radial(c) => hit.point - c,
            };
            ShadingFrame::new(n, t).map(|frame| (model, frame, &p.gratings[obj.grating]))
        }
        _ => None,
    };
    // For each light: its visible colour, cos θi, and the diffraction colour toward it.
    let each = |l: &'_ Light| std::iter::repeat_n(*l, l.samples);
    let lights = scene.lights.iter().flat_map(each).filter_map(|light| {
        // A random point of the light's disc (facing the hit) for each of its samples.
        let (a, b) = (light.position - origin).normalize().any_orthonormal_pair();
        let r = rng.next().sqrt() * light.radius;
        let phi = std::f64::consts::TAU * rng.next();
        let target = light.position + (a * phi.cos() + b * phi.sin()) * r;
        let to = target - origin;
        let dist = to.length();
        let wi = to / dist;
        let cos = n.dot(wi);
        if cos <= 0.0 || nearest(scene, &Ray { origin, dir: wi }, dist).is_some() {
            return None;
        }
        let mut diffracted = DVec3::ZERO;
        if let Some((model, frame, (exposure, table))) = &grating {
            // Steps 3 and 5: the local directions and u = (wi + wo)·t.
            let (wi_l, wo_l) = (frame.to_local(wi), frame.to_local(wo));
            if wi_l.z > 0.0 && wo_l.z > 0.0 {
                let u = wi_l.x + wo_l.x;
                // Steps 6-8: the colour of I(u, λ) over the band, or the table's mean over the
                // u the pixel sees.
                let xyz = match (table, diff) {
                    (Some(table), Some((dx, dy))) => {
                        let cam = PixelRay::new(ray.origin, ray.dir);
                        let fp = PixelFootprint::Differentials { dx, dy };
                        let lamp = LightExtent::sphere(light.position, light.radius).ok()?;
                        let (u0, u1) =
                            u_interval(cam, hit.point, frame, fp, lamp).unwrap_or((u, u));
                        table.mean(u0, u1)
                    }
                    (Some(table), None) => table.lookup(u),
                    (None, _) => p.spectral.xyz(model.grating(), u, Strategy::PEAK_SEARCH),
                };
                let rgb = xyz.scale(*exposure).to_linear_srgb();
                diffracted = DVec3::new(rgb.r, rgb.g, rgb.b);
            }
        }
        let power = DVec3::splat(light.power / light.samples as f64);
        Some((power, cos, diffracted))
    });
    let mut color = obj.shading.shade(scene.ambient, albedo, lights);
    if let Surface::Mirror(k) = obj.surface {
        if depth < 5 {
            let dir = ray.dir - n * (2.0 * ray.dir.dot(n));
            let reflected = trace(p, &Ray { origin, dir }, None, depth + 1, rng);
            color = color * (1.0 - k) + reflected * k;
        }
    }
    color
}

/// Renders `p` into clipped 8-bit sRGB rows, the rows split among the machine's cores.
fn render(p: &Prepared, o: &Options) -> Vec<u8> {
    let (w, h, spp) = (o.width, o.height, o.spp);
    // The pinhole camera: y up, a 38° vertical field of view.
    let forward = (p.scene.look_at - p.scene.eye).normalize();
    let right = forward.cross(DVec3::Y).normalize();
    let up = right.cross(forward);
    let half_h = (38f64.to_radians() * 0.5).tan();
    let half_w = half_h * w as f64 / h as f64;
    let ray = |x: f64, y: f64| Ray {
        origin: p.scene.eye,
        dir: (forward
            + right * half_w * (2.0 * x / w as f64 - 1.0)
            + up * half_h * (1.0 - 2.0 * y / h as f64))
            .normalize(),
    };
    let row = |y: usize, out: &mut [u8]| {
        let mut rng = Rng(0x5EED ^ (y as u64) << 20);
        for x in 0..w {
            let mut sum = DVec3::ZERO;
            for s in 0..spp {
                // Stratified in x over the samples, jittered in y.
                let (jx, jy) = ((s as f64 + rng.next()) / spp as f64, rng.next());
                let (fx, fy) = (x as f64 + jx, y as f64 + jy);
                let pix = |dx: f64, dy: f64| {
                    let r = ray(fx + dx, fy + dy);
                    PixelRay::new(r.origin, r.dir)
                };
                let diff = Some((pix(1.0, 0.0), pix(0.0, 1.0)));
                sum += trace(p, &ray(fx, fy), diff, 0, &mut rng);
            }
            let c = sum / spp as f64;
            let rgb = LinearSrgb::new(c.x, c.y, c.z)
                .clip(o.clip)
                .encode()
                .to_rgb8();
            out[3 * x..3 * x + 3].copy_from_slice(&rgb);
        }
    };
    let mut pixels = vec![0u8; w * h * 3];
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(h.max(1));
    let rows_per = h.div_ceil(threads).max(1);
    std::thread::scope(|s| {
        for (i, chunk) in pixels.chunks_mut(rows_per * w * 3).enumerate() {
            s.spawn(move || {
                for (j, out) in chunk.chunks_mut(w * 3).enumerate() {
                    row(i * rows_per + j, out);
                }
            });
        }
    });
    pixels
}

// --- Command line ----------------------------------------------------------------------------

const HELP: &str = "\
whitted [SCENE...] [--table] [--clip clamp|intensity|constant] [--size WxH] [--spp N] [--out DIR] [--quick]

Renders the paper's scenes (fig4a: a grating plate and a mirror cube on wood; cd: a CD) with the
Agu-Hill model and eq. 12 into DIR/SCENE.png (default: both scenes, 480x360, 4 samples a pixel,
intensity clipping, out/). --table averages each grating colour over the pixel's footprint in u
by a ColorTable; --quick renders 96x72 at 1 sample.";

fn parse(args: &[String]) -> Result<Options, String> {
    let mut o = Options {
        scenes: Vec::new(),
        width: 480,
        height: 360,
        spp: 4,
        clip: Clip::Intensity,
        table: false,
        out: "out".into(),
    };
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().cloned().ok_or(format!("{name} needs a value"));
        match a.as_str() {
            "--table" => o.table = true,
            "--quick" => (o.width, o.height, o.spp) = (96, 72, 1),
            "--clip" => {
                o.clip = value("--clip")?
                    .parse()
                    .map_err(|e| format!("--clip: {e}"))?
            }
            "--size" => {
                let v = value("--size")?;
                let (w, h) = v.split_once('x').unwrap_or((&v, ""));
                (o.width, o.height) = (number("--size", w, 8192)?, number("--size", h, 8192)?);
            }
            "--spp" => o.spp = number("--spp", &value("--spp")?, 1024)?,
            "--out" => o.out = value("--out")?,
            "fig4a" | "cd" => o.scenes.push(a.clone()),
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if o.scenes.is_empty() {
        o.scenes = vec!["fig4a".into(), "cd".into()];
    }
    Ok(o)
}

/// A whole number from 1 to `max`, or an error naming `option`.
fn number(option: &str, v: &str, max: usize) -> Result<usize, String> {
    match v.parse::<usize>() {
        Ok(n) if (1..=max).contains(&n) => Ok(n),
        _ => Err(format!(
            "{option}: {v:?} is not a whole number from 1 to {max}"
        )),
    }
}

fn scene(name: &str) -> Result<Scene, diffraction::Error> {
    if name == "cd" {
        cd()
    } else {
        fig4a()
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--help" || a == "-h") {
        println!("{HELP}");
        return ExitCode::SUCCESS;
    }
    match parse(&args)
        .map_err(|e| format!("{e}\n\n{HELP}"))
        .and_then(|o| run(&o))
    {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("whitted: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Renders each scene of `o` into its PNG.
fn run(o: &Options) -> Result<(), String> {
    std::fs::create_dir_all(&o.out).map_err(|e| format!("cannot make {}: {e}", o.out))?;
    for name in &o.scenes {
        let start = std::time::Instant::now();
        let p = scene(name)
            .and_then(|s| prepare(s, o.table))
            .map_err(|e| format!("{name}: {e}"))?;
        let pixels = render(&p, o);
        let path = format!("{}/{}.png", o.out, p.scene.name);
        png::write(path.as_ref(), o.width, o.height, &pixels)
            .map_err(|e| format!("cannot write {path}: {e}"))?;
        let (w, h, spp, t) = (o.width, o.height, o.spp, start.elapsed().as_secs_f64());
        println!("{path}: {w}x{h}, {spp} spp, {t:.2} s");
    }
    Ok(())
}

// --- Smoke tests (`cargo test --example whitted`) --------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    /// The first order's rainbow: blue nearer the mirror direction (smaller |u|) than red, as
    /// the grating equation d·u = λ puts it (d = 1600 nm: 450 nm at u = 0.28, 650 nm at 0.41).
    #[test]
    fn first_order_runs_blue_to_red_away_from_the_mirror() {
        let p = prepare(fig4a().unwrap(), false).unwrap();
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        let rgb = |u: f64| p.spectral.xyz(&g, u, Strategy::EXACT).to_linear_srgb();
        let (blue, red) = (rgb(450.0 / 1600.0), rgb(650.0 / 1600.0));
        assert!(blue.b > blue.r && red.r > red.b, "{blue:?} {red:?}");
    }

    /// Both scenes, both colour paths, at a tiny size: finite, and the grating shows colours
    /// (pixels whose channels differ by more than a quarter of the range).
    #[test]
    fn quick_renders_show_grating_colours() {
        for table in [false, true] {
            for name in ["fig4a", "cd"] {
                let args = ["--quick", "--size", "64x48"].map(String::from);
                let o = Options {
                    table,
                    ..parse(&args).unwrap()
                };
                let p = prepare(scene(name).unwrap(), table).unwrap();
                let px = render(&p, &o);
                let vivid = px
                    .chunks(3)
                    .filter(|c| c.iter().max().unwrap() - c.iter().min().unwrap() > 64)
                    .count();
                assert!(vivid >= 5, "{name} table={table}: {vivid} coloured pixels");
                assert!(png::png(o.width, o.height, &px).len() > px.len());
            }
        }
    }
}
