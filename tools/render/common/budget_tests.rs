//! Tests of the work estimate ([`crate::budget`]): the pilot's counts in scenes where they are
//! known in closed form, the message of a refused run, and a refused run writes nothing.

use std::path::Path;

use crate::budget::{self, Estimate, Pilot, BUDGET_S};
use crate::common_tests::{scratch, Flat};
use crate::scene::{self, Scene};

fn parse(src: &str) -> Scene<Flat> {
    scene::parse::<Flat>(src, "test.toml", "test", Path::new(".")).unwrap()
}

/// A camera at the origin looking along +z between two mirrors (z = −1 and z = 3, both
/// 2000 wide, facing each other), `extra` objects after them.
fn mirrors(max_depth: u32, extra: &str) -> String {
    format!(
        "[render]\nwidth = 16\nheight = 12\nspp = 1\nmax_depth = {max_depth}\n\
         [camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\n\
         [[objects]]\nshape = \"quad\"\nscale = 2000.0\nrotate_deg = [90.0, 0.0, 0.0]\n\
         translate = [0.0, 0.0, 3.0]\n[objects.material]\ntype = \"mirror\"\n\
         [[objects]]\nshape = \"quad\"\nscale = 2000.0\nrotate_deg = [90.0, 0.0, 0.0]\n\
         translate = [0.0, 0.0, -1.0]\n[objects.material]\ntype = \"mirror\"\n{extra}"
    )
}

#[test]
fn the_pilot_counts_what_the_rays_meet() {
    // Between two mirrors every ray is reflected max_depth times: 1 + max_depth rays and hits.
    let scene = parse(&mirrors(64, ""));
    let p = budget::pilot(&scene, &scene.camera, true);
    assert_eq!(
        p,
        Pilot {
            rays: 65.0,
            hits: 65.0,
            grating_hits: 0.0,
            shadow_rays: 0.0,
            lit: 0.0,
            lit_samples: 0.0
        }
    );
    // Not following mirrors: one ray and one hit.
    let p = budget::pilot(&scene, &scene.camera, false);
    assert_eq!(
        p,
        Pilot {
            rays: 1.0,
            hits: 1.0,
            grating_hits: 0.0,
            shadow_rays: 0.0,
            lit: 0.0,
            lit_samples: 0.0
        }
    );
    // Looking away from everything: nothing is hit.
    let empty = "[camera]\nposition = [0.0, 0.0, 0.0]\nlook_at = [0.0, 0.0, 1.0]\n";
    let p = budget::pilot(&parse(empty), &parse(empty).camera, true);
    assert_eq!(
        p,
        Pilot {
            rays: 1.0,
            hits: 0.0,
            grating_hits: 0.0,
            shadow_rays: 0.0,
            lit: 0.0,
            lit_samples: 0.0
        }
    );
    // A grating filling the view, half of it plain squares of a checkerboard of cells much
    // smaller than a pixel's spacing: about half the hits are on the grating.
    let checker =
        "[camera]\nposition = [0.0, 5.0, 0.0]\nlook_at = [0.0, 0.0, 0.01]\nfov_deg = 10\n\
         [[objects]]\nshape = \"quad\"\nscale = 100.0\n[objects.material]\ntype = \"grating\"\n\
         period_nm = 1600\n[objects.material.field]\ntype = \"checkerboard\"\ncell_size = 0.0137\n";
    let s = parse(checker);
    let p = budget::pilot(&s, &s.camera, true);
    assert_eq!((p.rays, p.hits), (1.0, 1.0));
    assert!((p.grating_hits - 0.5).abs() < 0.1, "{p:?}");
}

#[test]
fn a_run_above_the_budget_is_refused_with_its_largest_part() {
    let mut est = Estimate::default();
    est.add("1000 camera samples".into(), 1e8, "--spp");
    assert_eq!(est.check("small", budget::BUDGET_S), Ok(()));
    est.add(
        "7 colour tables".into(),
        (BUDGET_S + 1.0) * 1e9,
        "--filter none",
    );
    assert_eq!(
        est.check("big", budget::BUDGET_S),
        Err(
            "big: an estimated 121 s of work on one core, above the budget of 120 s \
             (--budget; tools/render/common/budget.rs); most of it, 121 s, is 7 colour tables: reduce \
             --filter none"
                .into()
        )
    );
    for (v, s) in [
        (0.0, "0"),
        (0.37, "0.37"),
        (3.7, "3.7"),
        (37.0, "37"),
        (370.0, "370"),
        (6.3e-3, "6.30e-3"),
        (1.234e4, "1.23e4"),
    ] {
        assert_eq!(budget::short(v), s);
    }
}

/// The ten thousand objects, 4096 shadow rays and 64 mirror bounces of one hit, each within
/// its limit, multiply to about 5·10¹¹ ray-object tests at 16 × 12 pixels: refused before
/// anything is prepared or rendered, and nothing is written.
#[test]
fn objects_times_shadow_rays_times_bounces_is_refused() {
    let dir = scratch("budget");
    // Four lights of 1024 samples between the mirrors, and 9998 tiny cubes far to the side.
    let mut extra = String::new();
    for i in 0..4 {
        extra += &format!(
            "[[lights]]\nposition = [{}.0, 1.0, 1.0]\nradius = 0.1\nsamples = 1024\n",
            i - 2
        );
    }
    for i in 0..9998 {
        extra += &format!(
            "[[objects]]\nshape = \"cube\"\nscale = 0.001\ntranslate = [100000.0, {}.0, 0.0]\n\
             material = {{ type = \"diffuse\" }}\n",
            i % 1000
        );
    }
    let file = dir.join("hall.toml");
    std::fs::write(&file, mirrors(64, &extra)).unwrap();
    let out = dir.join("hall.png");
    let args = crate::cli::Options {
        scenes: vec![file.display().to_string()],
        out: Some(out.clone()),
        quiet: true,
        ..Default::default()
    };
    let e = crate::run::run(&Flat, &args).unwrap_err();
    // Closed form: 192 samples × 65 rays (all hits) × 10⁴ objects × (1 + 4096 shadow rays).
    let tests = 192.0 * 65.0 * 1e4 * 4097.0;
    let hits = 192.0 * 65.0;
    let total = 192.0 * budget::SAMPLE_NS
        + hits * budget::HIT_NS
        + hits * 4096.0 * budget::SHADOW_NS
        + tests * budget::RAY_TEST_NS;
    assert_eq!(
        e,
        format!(
            "hall: an estimated {} s of work on one core, above the budget of 120 s \
             (--budget; tools/render/common/budget.rs); most of it, {} s, is {} ray-object tests: reduce \
             --width/--height, --spp, --frames, --max-depth, the lights' samples or the number \
             of objects",
            budget::short(total * 1e-9),
            budget::short(tests * budget::RAY_TEST_NS * 1e-9),
            budget::count(tests)
        )
    );
    assert!(!out.exists());
    // `--budget` above the estimate accepts it (a dry run: nothing is rendered or written).
    let raised = crate::cli::Options {
        budget: Some(crate::cli::MAX_BUDGET_S),
        dry_run: true,
        ..args.clone()
    };
    assert!(total * 1e-9 < crate::cli::MAX_BUDGET_S as f64);
    assert_eq!(crate::run::run(&Flat, &raised), Ok(()));
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--budget` takes whole seconds in [1, 10⁷]; the refusal names the budget given.
#[test]
fn the_budget_flag_is_checked_and_used() {
    let args = |s: &str| -> Vec<String> { s.split_whitespace().map(String::from).collect() };
    let parse = |s: &str| crate::cli::parse::<crate::Args>(&args(s));
    for v in ["0", "10000001", "1.5", "-3"] {
        assert_eq!(
            parse(&format!("fig4a --budget {v}")),
            Err(format!(
                "--budget: expected an integer in [1, 10000000], got \"{v}\""
            ))
        );
    }
    let Ok(crate::cli::Command::Render(o, _)) = parse("fig4a --budget 300") else {
        panic!("--budget 300")
    };
    assert_eq!(o.budget, Some(300));
    let mut est = Estimate::default();
    est.add("1000 camera samples".into(), 2e11, "--spp");
    assert_eq!(est.check("s", 300.0), Ok(()));
    assert_eq!(
        est.check("s", 100.0),
        Err(
            "s: an estimated 200 s of work on one core, above the budget of 100 s (--budget; \
             tools/render/common/budget.rs); most of it, 200 s, is 1000 camera samples: reduce \
             --spp"
                .into()
        )
    );
}
