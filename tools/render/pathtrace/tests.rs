//! Tests of the radiometric scenes and of the path integrator: closed forms (a Lambertian
//! plane under a constant sky, under a spherical light), the MIS weights, and tiny renders.

use std::path::Path;

use diffraction::color::LinearSrgb;
use diffraction::{Band, SampledWavelengths};
use glam::DVec3;

use crate::budget;
use crate::geometry::Ray;
use crate::output::Image;
use crate::path::{self, mis_weights, PathOptions};
use crate::radiometry::Radiometric;
use crate::run::{scenes_dir, Renderer};
use crate::sampling::Rng;
use crate::scene::{self, Scene};
use crate::Integrator;

/// ∫ ȳ dλ over 360-830 nm of the CIE 1931 2° observer at 1 nm (the sum of the table's ȳ
/// column, 106.8566 in CIE 15:2004's table; colour-science gives the same).
const YBAR_INTEGRAL: f64 = 106.8566;
/// The relative tolerance of that value against the crate's linearly interpolated table (the
/// trapezoid rule of the 1 nm rows differs from their plain sum by the half end rows, ~1e-6).
const YBAR_TOLERANCE: f64 = 1e-4;
/// Monte-Carlo tolerance of the closed-form checks, in standard errors (measured errors were
/// within 1.5σ; 4σ fails a tenfold regression of the estimator's bias at these sample counts).
const SIGMAS: f64 = 4.0;
/// Relative tolerance of the Whitted renderer's 64 × 64 stratified light directions on the
/// sphere's closed form (measured 5·10⁻⁵; ten times that).
const WHITTED_TOLERANCE: f64 = 5e-4;

fn parse(src: &str) -> Scene<Radiometric> {
    scene::parse::<Radiometric>(src, "test.toml", "test", Path::new(".")).unwrap()
}

/// A plane (albedo `albedo`, grey) at y = 0 seen from above, an E-spectrum sky of radiance
/// `sky`, optionally a spherical light straight above.
fn plane_scene(albedo: f64, sky: f64, light: Option<(f64, f64, f64)>) -> Scene<Radiometric> {
    let light = light.map_or(String::new(), |(height, radius, radiance)| {
        format!(
            "[[lights]]\nposition = [0.0, {height}, 0.0]\nradius = {radius}\nintensity = {radiance}\nsamples = 64\n"
        )
    });
    parse(&format!(
        r#"
[render]
illuminant = "E"
[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 0.0, 0.3]
[radiometry]
exposure = 1.0
sky_horizon = {sky}
{light}
[[objects]]
shape = "quad"
scale = 1000.0
[objects.material]
type = "diffuse"
color = [{albedo}, {albedo}, {albedo}]
"#
    ))
}

/// Mean and standard error of Y over `n` paths along `ray` (film units).
fn mean_y(scene: &Scene<Radiometric>, ray: &Ray, n: u32, options: PathOptions) -> (f64, f64) {
    let r = &scene.units;
    let mut rng = Rng::new(11);
    let (mut s, mut s2) = (0.0, 0.0);
    for i in 0..n {
        let u = (i as f64 + rng.next_f64()) / n as f64;
        let l = SampledWavelengths::sample_uniform(u, Band::VISIBLE);
        let y = path::film_xyz(&l, path::li(scene, ray, l, &mut rng, options)).y * r.exposure;
        s += y;
        s2 += y * y;
    }
    let m = s / n as f64;
    (m, ((s2 / n as f64 - m * m).max(0.0) / n as f64).sqrt())
}

#[test]
fn the_ybar_integral_of_the_units_is_the_tables() {
    let r = plane_scene(0.5, 1.0, None).units;
    // Illuminant E: s = 1, so ∫ s·ȳ is the observer's own integral.
    assert!(
        (r.ys / YBAR_INTEGRAL - 1.0).abs() < YBAR_TOLERANCE,
        "{}",
        r.ys
    );
}

#[test]
fn white_furnace_a_lambertian_plane_under_a_constant_sky() {
    // Everything the plane sees is sky: L_o = a·L at every bounce count.
    let (a, sky) = (0.5, 2.0);
    let scene = plane_scene(a, sky, None);
    let ray = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.1, -1.0, 0.2));
    for depth in [1, 5] {
        let options = PathOptions {
            grating_sampler: true,
            max_depth: depth,
        };
        let (y, se) = mean_y(&scene, &ray, 4000, options);
        let expected = a * sky * YBAR_INTEGRAL;
        assert!(
            (y - expected).abs() < SIGMAS * se + 1e-3 * expected,
            "depth {depth}: {y} ± {se}, expected {expected}"
        );
    }
}

#[test]
fn direct_light_of_a_sphere_on_a_lambertian_plane() {
    // A sphere of radiance L, radius R at height H over the plane: irradiance π·L·(R/H)²
    // below its centre, so L_o = a·L·(R/H)². Both integrators, direct light only, no sky.
    let (a, height, radius, radiance) = (0.8, 2.0, 0.5, 3.0);
    let scene = plane_scene(a, 0.0, Some((height, radius, radiance)));
    let expected = a * radiance * (radius / height).powi(2) * YBAR_INTEGRAL;
    let ray = Ray::new(DVec3::new(0.0, 1.0, 0.0), DVec3::NEG_Y);
    for sampler in [true, false] {
        let options = PathOptions {
            grating_sampler: sampler,
            max_depth: 1,
        };
        let (y, se) = mean_y(&scene, &ray, 4000, options);
        assert!(
            (y - expected).abs() < SIGMAS * se + 1e-3 * expected,
            "path: {y} ± {se}, expected {expected}"
        );
    }
    // Whitted: 64 stratified directions in the light's cone, 64 times.
    let mut rng = Rng::new(3);
    let mut y = 0.0;
    for _ in 0..64 {
        let c = crate::whitted::trace(&scene, &ray, 0, &mut rng);
        y += LinearSrgb::new(c.x, c.y, c.z).to_xyz().y / 64.0;
    }
    assert!(
        (y / expected - 1.0).abs() < WHITTED_TOLERANCE,
        "whitted: {y}, expected {expected}"
    );
}

#[test]
fn the_mis_weights_of_the_eight_techniques_sum_to_one() {
    // Equal densities under the four wavelengths: the two-strategy balance heuristic.
    let (p_l, p_b) = (3.0, 1.0);
    let (wl, wb) = mis_weights([1.0; 4], p_l, [p_b; 4]);
    for k in 0..4 {
        assert!((wl[k] - p_l / (p_l + p_b) / 4.0).abs() < 1e-15);
        assert!((wb[k] - p_b / (p_l + p_b) / 4.0).abs() < 1e-15);
    }
    // A grating's dispersive densities at a direction in the hero's lobe.
    use diffraction::{Bsdf, Grating, GratingBsdf};
    let b = GratingBsdf::new(Grating::new(1600.0, 800.0, 30).unwrap());
    let l = SampledWavelengths::sample_uniform(0.3, Band::VISIBLE);
    let wo = DVec3::new(0.1, 0.05, (1.0f64 - 0.0125).sqrt());
    let mut rng = Rng::new(5);
    for _ in 0..100 {
        let u2 = glam::DVec2::new(rng.next_f64(), rng.next_f64());
        let Some(s) = b.sample(wo, l.hero(), rng.next_f64(), u2) else {
            continue;
        };
        let pdf4 = b.pdf4(wo, s.wi, &l);
        let r_u = [1.0, 0.5, 2.0, 0.25];
        let (wl, wb) = mis_weights(r_u, 0.7, pdf4);
        let sum: f64 = wl.iter().chain(&wb).sum();
        assert!((sum - 1.0).abs() < 1e-12, "{sum}");
        assert!(wl.iter().chain(&wb).all(|w| (0.0..=1.0).contains(w)));
    }
    assert_eq!(mis_weights([1.0; 4], 0.0, [0.0; 4]), ([0.0; 4], [0.0; 4]));
}

#[test]
fn the_cd_scene_loads_and_both_integrators_render_it() {
    let mut scene = scene::load::<Radiometric>(&scenes_dir().join("cd_area_light.toml")).unwrap();
    assert_eq!(
        scene
            .materials
            .iter()
            .filter(|m| m.grating.is_some())
            .count(),
        1
    );
    scene.settings.width = 16;
    scene.settings.height = 12;
    scene.settings.spp = 2;
    for integrator in [Integrator::Whitted, Integrator::Path] {
        let img = integrator.render(&scene, &scene.camera, None);
        for c in &img.pixels {
            let xyz = LinearSrgb::new(c.x, c.y, c.z).to_xyz();
            assert!(c.is_finite(), "{integrator:?}: {c}");
            // Linear sRGB of spectral colours can be negative; XYZ cannot.
            for v in [xyz.x, xyz.y, xyz.z] {
                assert!(v >= -1e-9, "{integrator:?}: {xyz:?}");
            }
        }
    }
}

#[test]
fn radiometric_scene_errors_name_the_field() {
    let base = r#"
[camera]
position = [0.0, 1.0, 0.0]
look_at = [0.0, 0.0, 0.3]
[[objects]]
shape = "quad"
[objects.material]
type = "grating"
period_nm = 1600.0
"#;
    let err = |s: &str| {
        scene::parse::<Radiometric>(s, "t.toml", "t", Path::new("."))
            .unwrap_err()
            .to_string()
    };
    // Without a [radiometry] table the scene is the paper's, mapped (crate::paper): a model
    // with no radiometric reading is refused at its field.
    let e = err(&format!("{base}model = \"thorman\"\n"));
    assert_eq!(
        e,
        "t.toml: line 10, field objects[0].material.model: the path tracer takes gratings of \
         model \"radiometric\", and \"agu-hill\" in the paper's scenes (read as the radiometric \
         grating); \"thorman\" has no physical units"
    );
    // Each error names the field, the range or the rule, and the numbers.
    let radiometric = |extra: &str| {
        err(&format!(
            "[radiometry]\nexposure = 1.0\n{base}model = \"radiometric\"\n{extra}\n"
        ))
    };
    for (extra, expected) in [
        ("diffuse = 0.0\ngroove_sigma = 3.0", "line 14, field objects[0].material.groove_sigma: invalid sigma = 3: must lie in [1e-12, 1]"),
        ("diffuse = 0.0\nslits = 4294967296", "line 14, field objects[0].material.slits: expected an integer in [1, 4294967295], got 4294967296"),
        ("diffuse = 0.0\nslits = 18446744073709551616", "line 14, field objects[0].material.slits: expected an integer in [1, 4294967295], got 18446744073709551616"),
        // Passivity: diffuse 1 × colour 0.7 + w/d 0.5 > 1 (the default diffuse: at the table).
        ("", "line 9, field objects[0].material.diffuse: expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color + slit_width/period) = 0·1 + 1·(1·0.7 + 0.5) = 1.2, above 1"),
        ("diffuse = 0.5\ncolor = [1.5, 1.5, 1.5]", "line 14, field objects[0].material.color: expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color + slit_width/period) = 0·1 + 1·(0.5·1.5 + 0.5) = 1.25, above 1"),
        ("diffuse = 0.0\nmirror = 0.5\nmirror_color = [2.0, 1.0, 1.0]", "line 15, field objects[0].material.mirror_color: expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color + slit_width/period) = 0.5·2 + 0.5·(0·0.7 + 0.5) = 1.25, above 1"),
        ("diffuse = 0.1\nslit_width_nm = 1600.0", "line 14, field objects[0].material.slit_width_nm: expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color + slit_width/period) = 0·1 + 1·(0.1·0.7 + 1) = 1.07, above 1"),
        // Just above 1: printed in full, not as "1.000".
        ("diffuse = 0.0\nmirror = 1.0\nmirror_color = [1.0000001, 1.0, 1.0]", "line 15, field objects[0].material.mirror_color: expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color + slit_width/period) = 1·1.0000001 + 0·(0·0.7 + 0.5) = 1.0000001, above 1"),
    ] {
        assert_eq!(radiometric(extra), format!("t.toml: {expected}"), "{extra}");
    }
    let e = err(&format!(
        "[radiometry]\nexposure = -1.0\n{base}model = \"radiometric\"\ndiffuse = 0.0\n"
    ));
    assert_eq!(
        e,
        "t.toml: line 2, field radiometry.exposure: expected a number in [0, 1e12], got -1"
    );
    let e = err(&format!(
        "[radiometry]\nexposure = 1.0\n{base}diffuse = 0.0\n"
    ));
    assert_eq!(
        e,
        "t.toml: line 9, field objects[0].material.model: a scene with a [radiometry] table takes \
         gratings of model \"radiometric\" only (the other models have no physical units)"
    );
}

/// The comparisons of the docs (`cargo test --release -p diffraction-render --bin pathtrace -- --ignored
/// cd_area_light_comparison --nocapture`): (a) Whitted against (b) path-traced direct light of
/// `cd_area_light` without the sky, mean ΔE2000 of the clipped pictures; (c) at equal time, the
/// pixel variance of path tracing with and without the grating sampler in the MIS, over
/// independent renders. Writes the pictures into docs/images/.
#[test]
#[ignore = "minutes of rendering; the figures of the docs"]
fn cd_area_light_comparison() {
    use diffraction::color::Lab;
    use std::time::Instant;
    let images = scenes_dir().join("../../docs/images");
    let base = scene::load::<Radiometric>(&scenes_dir().join("cd_area_light.toml")).unwrap();
    let white = diffraction::color::WhitePoint::new(base.spectral.white()).unwrap();
    let clip = base.settings.clip;
    let lab = |img: &Image| -> Vec<Lab> {
        img.pixels
            .iter()
            .map(|c| {
                LinearSrgb::new(c.x, c.y, c.z)
                    .clip(clip)
                    .to_xyz()
                    .to_lab(white)
            })
            .collect()
    };
    let save = |img: &Image, name: &str| {
        let png = crate::output::to_rgb8(img, clip);
        crate::files::write_one(&images.join(name), crate::files::Kind::Png, "", |w| {
            crate::output::png_to(w, &png)
        })
        .unwrap();
    };
    let env = |k: &str, d: u32| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };

    // (a) and (b): direct light of the spherical light only.
    let mut direct = base.clone();
    direct.units.sky = [0.0; 2];
    direct.settings.spp = env("WHITTED_SPP", 64);
    let t = Instant::now();
    let whitted = crate::whitted::render(&direct, &direct.camera, None);
    let t_whitted = t.elapsed().as_secs_f64();
    direct.settings.spp = env("DIRECT_SPP", 1024);
    let t = Instant::now();
    let options = PathOptions {
        grating_sampler: true,
        max_depth: 1,
    };
    let traced = path::render(&direct, &direct.camera, options, None);
    let t_traced = t.elapsed().as_secs_f64();
    let (a, b) = (lab(&whitted), lab(&traced));
    let de: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x.delta_e2000(*y)).collect();
    let mean = de.iter().sum::<f64>() / de.len() as f64;
    let mut sorted = de.clone();
    sorted.sort_by(f64::total_cmp);
    println!(
        "(a) whitted {} spp × 16 light samples: {t_whitted:.1} s; (b) path direct {} spp: \
         {t_traced:.1} s; mean ΔE2000 {mean:.3}, median {:.3}, 99th percentile {:.3}",
        env("WHITTED_SPP", 64),
        env("DIRECT_SPP", 1024),
        sorted[sorted.len() / 2],
        sorted[sorted.len() * 99 / 100]
    );
    save(&whitted, "cd_area_whitted.png");
    save(&traced, "cd_area_path_direct.png");

    // (c) Full paths with the sky, with and without the grating sampler, at equal time.
    let runs = env("RUNS", 4);
    let spp = env("EQUAL_SPP", 16);
    let mut full = base.clone();
    let mut time_of = |sampler: bool, spp: u32, seed: u64| {
        full.settings.spp = spp;
        full.settings.seed = seed;
        let options = PathOptions {
            grating_sampler: sampler,
            max_depth: full.settings.max_depth,
        };
        let t = Instant::now();
        let img = path::render(&full, &full.camera, options, None);
        (img, t.elapsed().as_secs_f64())
    };
    // Cost per sample of each, to give both the same time.
    let (_, t_s) = time_of(true, spp, 100);
    let (_, t_c) = time_of(false, spp, 100);
    let spp_cosine = ((spp as f64 * t_s / t_c).round() as u32).max(1);
    let mut variance = |sampler: bool, spp: u32| -> (f64, f64, Image, f64) {
        let mut imgs = Vec::new();
        let mut time = 0.0;
        for k in 0..runs {
            let (img, t) = time_of(sampler, spp, 1000 + k as u64);
            time += t;
            imgs.push(img);
        }
        // Per-pixel variance of the film's XYZ (summed over X, Y, Z), unclipped, over the runs.
        let n = imgs[0].pixels.len();
        let mut total = 0.0;
        let mut on_cd = (0.0, 0usize);
        for p in 0..n {
            let xyz: Vec<[f64; 3]> = imgs
                .iter()
                .map(|im| {
                    let c = im.pixels[p];
                    let x = LinearSrgb::new(c.x, c.y, c.z).to_xyz();
                    [x.x, x.y, x.z]
                })
                .collect();
            let mut v = 0.0;
            for ch in 0..3 {
                let m = xyz.iter().map(|x| x[ch]).sum::<f64>() / runs as f64;
                v += xyz.iter().map(|x| (x[ch] - m).powi(2)).sum::<f64>() / (runs as f64 - 1.0);
            }
            total += v;
            // The grating's pixels: the first render's hit is the CD (the middle of the frame).
            let (x, y) = (p % imgs[0].width as usize, p / imgs[0].width as usize);
            let (w, h) = (imgs[0].width as usize, imgs[0].height as usize);
            let in_disc = {
                let (dx, dy) = (x as f64 / w as f64 - 0.47, y as f64 / h as f64 - 0.58);
                (dx / 0.25).powi(2) + (dy / 0.16).powi(2) < 1.0
            };
            if in_disc {
                on_cd.0 += v;
                on_cd.1 += 1;
            }
        }
        (
            total / n as f64,
            on_cd.0 / on_cd.1.max(1) as f64,
            imgs.swap_remove(0),
            time / runs as f64,
        )
    };
    let (v_s, v_s_cd, img_s, time_s) = variance(true, spp);
    let (v_c, v_c_cd, img_c, time_c) = variance(false, spp_cosine);
    println!(
        "(c) grating sampler {spp} spp: {time_s:.2} s, variance {v_s:.4e} (CD {v_s_cd:.4e}); \
         cosine {spp_cosine} spp: {time_c:.2} s, variance {v_c:.4e} (CD {v_c_cd:.4e}); \
         ratio cosine/sampler {:.2} (CD {:.2}), time-normalised {:.2} (CD {:.2})",
        v_c / v_s,
        v_c_cd / v_s_cd,
        v_c * time_c / (v_s * time_s),
        v_c_cd * time_c / (v_s_cd * time_s),
    );
    save(&img_s, "cd_area_path_equal_time.png");
    save(&img_c, "cd_area_path_nosampler.png");
}

/// Four area lights of 1024 samples and an `exact` radiometric grating of N = 2³² − 1, each
/// within its limit: the Whitted renderer would take minutes at 16 × 12 pixels and is refused
/// with its estimate; the path tracer (one light sample per vertex) renders it.
#[test]
fn light_samples_times_exact_colours_are_bounded() {
    let mut src = String::from(
        "[render]\nwidth = 16\nheight = 12\nspp = 4\nstrategy = \"exact\"\n\
         [camera]\nposition = [0.0, 5.0, 0.0]\nlook_at = [0.0, 0.0, 0.01]\n\
         [radiometry]\nexposure = 1.0\n\
         [[objects]]\nshape = \"quad\"\nscale = 1000.0\n[objects.material]\ntype = \"grating\"\n\
         model = \"radiometric\"\nperiod_nm = 1600.0\nslits = 4294967295\ndiffuse = 0.0\n",
    );
    for i in 0..4 {
        src += &format!("[[lights]]\nposition = [{i}.0, 3.0, 0.0]\nradius = 0.3\nsamples = 1024\n");
    }
    let scene = scene::parse::<Radiometric>(&src, "t.toml", "exact", Path::new(".")).unwrap();
    // Closed form: 768 samples, each one hit on the grating, 4096 light samples there, each
    // with a colour of `exact` at d = 1600 nm and a shadow ray against the one object.
    let (samples, light) = (768.0, 4096.0);
    let colours = samples * light;
    let colour_ns = budget::colour_ns(
        &scene.spectral,
        budget::Integrand::Grating(diffraction::Grating::new(1600.0, 800.0, u32::MAX).unwrap()),
        crate::colour::Colour::Integral(diffraction::spectrum::Strategy::EXACT),
    );
    assert_eq!(colour_ns, 3e5 + 45.0 * 1600.0);
    let total = samples * budget::SAMPLE_NS
        + samples * budget::HIT_NS
        + colours * budget::SHADOW_NS
        + samples * (1.0 + light) * budget::RAY_TEST_NS
        + colours * colour_ns;
    assert_eq!(
        Integrator::Whitted.estimate(&scene, 1).check("exact", budget::BUDGET_S),
        Err(format!(
            "exact: an estimated {} s of work on one core, above the budget of 120 s \
             (--budget; tools/render/common/budget.rs); most of it, {} s, is {} colour evaluations (strategy \
             exact of objects[0].material): reduce --width/--height, --spp, --frames, the \
             lights' samples, or a cheaper --strategy or material strategy",
            budget::short(total * 1e-9),
            budget::short(colours * colour_ns * 1e-9),
            budget::count(colours)
        ))
    );
    let path = Integrator::Path.estimate(&scene, 1);
    assert!(path.seconds() < 0.1, "{path:?}");
    let img = Integrator::Path.render(&scene, &scene.camera, None);
    assert!(img.pixels.iter().all(|p| p.is_finite()));
    // With `peaks` and 16 samples a light, the Whitted renderer is within the budget too.
    let cheap = src
        .replace("strategy = \"exact\"", "strategy = \"peaks\"")
        .replace("samples = 1024", "samples = 16");
    let scene = scene::parse::<Radiometric>(&cheap, "t.toml", "cheap", Path::new(".")).unwrap();
    assert_eq!(
        Integrator::Whitted
            .estimate(&scene, 1)
            .check("cheap", budget::BUDGET_S),
        Ok(())
    );
}

/// A scene the path tracer cannot render (a Thorman grating: no physical units), after one it
/// can, is reported before anything is rendered or written: the first scene's existing picture
/// stays as it was.
#[test]
fn a_scene_the_path_tracer_refuses_fails_the_run_before_any_write() {
    let dir = std::env::temp_dir().join(format!("pathtrace-plan-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let old = b"an existing picture";
    std::fs::write(dir.join("cd_area_light.png"), old).unwrap();
    let compare = scenes_dir().join("baselines/compare.toml");
    let opts = crate::cli::Options {
        scenes: vec!["cd_area_light".into(), compare.display().to_string()],
        out: Some(dir.clone()),
        quiet: true,
        ..Default::default()
    };
    assert_eq!(
        crate::run::run(&Integrator::Path, &opts),
        Err(format!(
            "{}: line 124, field objects[5].material.model: the path tracer takes gratings of \
             model \"radiometric\", and \"agu-hill\" in the paper's scenes (read as the \
             radiometric grating); \"thorman\" has no physical units",
            compare.display()
        ))
    );
    assert_eq!(std::fs::read(dir.join("cd_area_light.png")).unwrap(), old);
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--filter footprint` is refused on both integrators, in either order of the options, with
/// the reason; `--filter none` is the default.
#[test]
fn filter_footprint_is_refused_with_the_reason_on_every_integrator() {
    let args = |s: &str| -> Vec<String> { s.split_whitespace().map(String::from).collect() };
    let path = "--filter footprint: not with the path integrator, which averages each pixel's \
                radiance by its samples (raise --spp); the footprint filter averages the paper's \
                diffraction colour over a pixel's interval of u, in the binary raytrace";
    let whitted = "--filter footprint: not with --integrator whitted of the path tracer: the \
                   radiometric grating's colour depends on the direction along the grooves as \
                   well as on u, so no colour table over u can average it; the footprint filter \
                   is the binary raytrace's, for the paper's model";
    for (line, expected) in [
        ("cd_area_light --filter footprint", path),
        ("fig6 --filter footprint --integrator path", path),
        (
            "cd_area_light --filter footprint --integrator whitted",
            whitted,
        ),
        (
            "cd_area_light --integrator whitted --filter footprint",
            whitted,
        ),
    ] {
        assert_eq!(
            crate::command(&args(line)),
            Err(expected.to_string()),
            "{line}"
        );
    }
    let Ok(crate::cli::Command::Render(_, a)) =
        crate::command(&args("cd_area_light --filter none --integrator whitted"))
    else {
        panic!("--filter none")
    };
    assert_eq!((a.integrator, a.footprint), (Integrator::Whitted, false));
    assert_eq!(
        crate::command(&args("cd_area_light --filter box")),
        Err("--filter: expected none or footprint, got \"box\"".to_string())
    );
}

/// The path tracer's rows of `tools/render/budget_calibration.csv`, both integrators: each
/// estimate within 5× of its measured CPU time (the measurement is the file's; nothing is
/// timed here).
#[test]
fn the_estimates_stay_within_five_times_the_measured_time() {
    let checked = crate::calibration_tests::check(
        "pathtrace",
        |args| match crate::command(args).unwrap() {
            crate::cli::Command::Render(o, a) => (a.integrator, o),
            crate::cli::Command::Help => panic!("{args:?}"),
        },
        |_| false,
    );
    assert_eq!(checked.len(), 20);
}

/// A fresh temporary directory holding `name` with `src`: (directory, file).
fn scratch_scene(name: &str, src: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = std::env::temp_dir().join(format!("pathtrace-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, src).unwrap();
    (dir, file)
}

fn run_options(file: &Path, out: &Path) -> crate::cli::Options {
    crate::cli::Options {
        scenes: vec![file.display().to_string()],
        out: Some(out.to_path_buf()),
        quiet: true,
        ..Default::default()
    }
}

/// The reproducer `area_lights_exact` (tools/render/tests/data): four area lights of 1024
/// samples and an `exact` grating, each value within its limit. The Whitted integrator, an
/// exact colour per visible light sample, is refused before anything is rendered, with the
/// estimate, the budget and the colours that make it; nothing is written. The path integrator
/// (one light sample a vertex) is within the budget and renders it.
#[test]
fn many_exact_area_light_samples_are_refused_or_path_traced() {
    let src = include_str!("../tests/data/area_lights_exact.toml");
    let (dir, file) = scratch_scene("area_lights_exact", src);
    let out = dir.join("area_lights_exact.png");
    let opts = run_options(&file, &out);
    let e = crate::run::run(&Integrator::Whitted, &opts).unwrap_err();
    let scene = scene::load::<Radiometric>(&file).unwrap();
    let est = Integrator::Whitted.estimate(&scene, 1);
    let colours = est.parts.last().unwrap();
    assert_eq!(
        e,
        format!(
            "area_lights_exact: an estimated {} s of work on one core, above the budget of 120 s \
             (--budget; tools/render/common/budget.rs); most of it, {} s, is {}: reduce \
             --width/--height, --spp, --frames, the lights' samples, or a cheaper --strategy or \
             material strategy",
            budget::short(est.seconds()),
            budget::short(colours.ns * 1e-9),
            colours.what
        )
    );
    // The colours: at most every camera sample's hit on the disc lit by all 4096 light
    // samples, at least a twentieth of that (the disc fills a quarter of the picture); each an
    // `exact` colour at d = 1600 nm.
    let samples = 320.0 * 240.0 * 16.0;
    let count = colours.ns / (3e5 + 45.0 * 1600.0);
    assert!(
        count <= samples * 4096.0 && count >= samples * 4096.0 / 20.0,
        "{count}"
    );
    assert!(est.seconds() > 1000.0 * budget::BUDGET_S, "{est:?}");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    // The path integrator: within the budget, rendered.
    let path = Integrator::Path.estimate(&scene, 1);
    assert!(path.seconds() < budget::BUDGET_S / 10.0, "{path:?}");
    assert_eq!(crate::run::run(&Integrator::Path, &opts), Ok(()));
    assert!(image::open(&out).is_ok());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The reproducer `work_limits_multiply` (tools/render/tests/data): every value within its
/// limit, their product far beyond the budget. The path tracer refuses it on both integrators
/// (the paper's scene mapped to physical units), naming the estimate, the budget and the part
/// that dominates; nothing is written.
#[test]
fn work_limits_that_multiply_are_refused_by_both_integrators() {
    let src = include_str!("../tests/data/work_limits_multiply.toml");
    let (dir, file) = scratch_scene("work_limits_multiply", src);
    let opts = run_options(&file, &dir.join("work_limits_multiply.png"));
    let scene = scene::load::<Radiometric>(&file).unwrap();
    for (integrator, part) in [
        (Integrator::Path, "grating BSDF evaluations"),
        (
            Integrator::Whitted,
            "colour evaluations (strategy exact of objects[0].material)",
        ),
    ] {
        let e = crate::run::run(&integrator, &opts).unwrap_err();
        let est = integrator.estimate(&scene, 1);
        let top = est
            .parts
            .iter()
            .max_by(|a, b| a.ns.total_cmp(&b.ns))
            .unwrap();
        assert!(top.what.contains(part), "{integrator:?}: {est:?}");
        let head = format!(
            "work_limits_multiply: an estimated {} s of work on one core, above the budget of \
             120 s (--budget; tools/render/common/budget.rs); most of it, {} s, is {}: reduce \
             --width/--height, --spp, --frames",
            budget::short(est.seconds()),
            budget::short(top.ns * 1e-9),
            top.what
        );
        assert!(e.starts_with(&head), "{e}");
        // 2³² camera samples, each at least a vertex on a grating.
        assert!(est.seconds() > 4.0e9 * budget::BSDF_NS * 1e-9, "{est:?}");
    }
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The Whitted renderer's estimate counts each tabulated grating's colour table at its preset's
/// measured build, read conically (the default: the CD 20 s, the foil 32 s, the DVD 44 s,
/// `blazed600` 211 s on one core; `whitted::table_build_ns`) or classically (docs/color_table.md:
/// the CD 4.3 s, the foil 4.2 s, the DVD 35 s, `blazed600` 66 s), not one figure for all. The
/// scene is `cd_preset` with its preset swapped.
#[test]
fn whitted_estimates_count_each_presets_table_build() {
    let path = scenes_dir().join("presets/cd_preset.toml");
    let src = std::fs::read_to_string(&path).unwrap();
    let dir = path.parent().unwrap();
    let table_s = |preset: &str, reading: &str| {
        let text = src.replace(
            "efficiency = \"cd\"",
            &format!("efficiency = \"{preset}\"\nreading = \"{reading}\""),
        );
        let scene = scene::parse::<Radiometric>(&text, "t.toml", preset, dir).unwrap();
        let est = Integrator::Whitted.estimate(&scene, 1);
        let tables: Vec<_> = est
            .parts
            .iter()
            .filter(|p| p.what.contains("colour tables"))
            .collect();
        assert_eq!(tables.len(), 1, "{est:?}");
        (tables[0].ns * 1e-9, est.check(preset, budget::BUDGET_S))
    };
    // Each at least its measured build and at most twice its slowest measured build.
    for (preset, reading, lo, hi) in [
        ("cd", "classical", 4.3, 8.6),
        ("foil", "classical", 4.2, 8.4),
        ("blazed600", "classical", 66.0, 120.0),
        ("dvd", "classical", 35.0, 70.0),
        ("cd", "reduced", 20.0, 40.0),
        ("foil", "reduced", 32.0, 64.0),
        ("dvd", "reduced", 44.0, 90.0),
        ("blazed600", "reduced", 211.0, 422.0),
    ] {
        let (s, check) = table_s(preset, reading);
        assert!((lo..=hi).contains(&s), "{preset} {reading}: {s} s");
        // The shipped scene's size fits the default budget with any preset's table but
        // `blazed600`'s read conically, which asks for `--budget`.
        let fits = !(preset == "blazed600" && reading == "reduced");
        assert_eq!(check.is_ok(), fits, "{preset} {reading}: {check:?}");
    }
}
