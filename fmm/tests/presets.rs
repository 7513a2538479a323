//! The presets this crate's solver made (`python_ref/presets.py --rust-solve NAME`, which runs
//! `grating-table --nodes-of` on the committed grid): at a sample of their nodes, the committed
//! tables are what the solver makes today, with the presets' settings. (`cd` and `dvd`: lamellar
//! Al under polycarbonate, one pass through the cover; `blazed600`: the ruled sawtooth, by the
//! C method.)

mod support;

use diffraction::relief::Metal;
use diffraction_fmm::table::{OrderSolver, Rigorous};
use diffraction_fmm::{Cover, CoverIndex, CoverPasses, Grating, Options, Profile, Solver};
use support::REPRODUCTION_TOLERANCE;

fn covered(period_nm: f64, duty: f64, depth_nm: f64) -> Grating {
    Grating {
        period_nm,
        profile: Profile::Lamellar { duty, depth_nm },
        metal: Metal::AL,
        cover: Some(Cover {
            index: CoverIndex::POLYCARBONATE,
            thickness_nm: 1.2e6,
        }),
    }
}

/// The preset's solver settings (python_ref/presets.py, `RUST_SOLVED`).
fn solver() -> Solver {
    Solver::new(Options {
        cover_passes: CoverPasses::Single,
        tolerance: 2.5e-4,
        max_harmonics: 1037,
        ..Options::default()
    })
    .unwrap()
}

/// Largest |η − table| over every order and both polarisations at every `stride`-th node with
/// |s| ≤ 0.95 off the Rayleigh lines (and λ ≥ `lambda_min`), and the nodes compared.
fn worst_at_nodes(name: &str, g: &Grating, stride: usize, lambda_min: f64) -> (f64, usize) {
    let path = format!(
        "{}/../data/efficiencies/{name}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let nums = |k: &str| -> Vec<f64> {
        v[k].as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (s_nodes, l_nodes) = (nums("sin_theta_i"), nums("lambda_nm"));
    let order_min = v["order_min"].as_i64().unwrap() as i32;
    let d = g.period_nm;
    let mut nodes = Vec::new();
    for (j, &l) in l_nodes.iter().enumerate() {
        for (i, &s) in s_nodes.iter().enumerate() {
            let n = g.cover.map_or(1.0, |c| c.index.at(l));
            let near_line = (-40..=40).any(|m| {
                let a = (s + m as f64 * l / d).abs();
                (a - 1.0).abs() < 1e-3 || (a - n).abs() < 1e-3
            });
            if s.abs() <= 0.95 && l >= lambda_min && !near_line {
                nodes.push((j, i));
            }
        }
    }
    // As the table builder solves (a solve that reaches the cap is kept at it).
    let rigorous = Rigorous {
        grating: g.clone(),
        solver: solver(),
        accept_unconverged: 2.5e-4,
    };
    let mut worst = 0.0f64;
    let mut count = 0;
    for &(j, i) in nodes.iter().step_by(stride) {
        let o = rigorous
            .solve(s_nodes[i], l_nodes[j])
            .expect("a solve at the node");
        for (te, key) in [(true, "te"), (false, "tm")] {
            for (k, row) in v[key].as_array().unwrap().iter().enumerate() {
                let table = row[j][i].as_f64().unwrap();
                let (a, b) = o.get(order_min + k as i32);
                worst = worst.max(((if te { a } else { b }) - table).abs());
            }
        }
        count += 1;
    }
    (worst, count)
}

#[test]
fn cd_preset_is_what_this_solver_makes() {
    let (worst, count) = worst_at_nodes("cd", &covered(1600.0, 0.3125, 110.0), 59, 360.0);
    println!("cd: {count} nodes, worst |η − table| = {worst:.2e}");
    assert!(worst < REPRODUCTION_TOLERANCE, "{worst}");
}

#[test]
fn dvd_preset_is_what_this_solver_makes() {
    let g = covered(740.0, 0.32 / 0.74, 105.0);
    let (worst, count) = worst_at_nodes("dvd", &g, 59, 360.0);
    println!("dvd: {count} nodes, worst |η − table| = {worst:.2e}");
    assert!(worst < REPRODUCTION_TOLERANCE, "{worst}");
}

#[test]
fn blazed600_preset_is_what_this_solver_makes() {
    let g = Grating {
        period_nm: 1e6 / 600.0,
        profile: Profile::Sawtooth {
            blaze: (500.0f64 / (2.0 * 1e6 / 600.0)).asin(),
        },
        metal: Metal::AL,
        cover: None,
    };
    let (worst, count) = worst_at_nodes("blazed600", &g, 25, 600.0);
    println!("blazed600: {count} nodes, worst |η − table| = {worst:.2e}");
    assert!(worst < REPRODUCTION_TOLERANCE, "{worst}");
}
