//! The presets this crate's solver made (`python_ref/presets.py --rust-solve NAME`, which runs
//! `grating-table --nodes-of` on the committed grid): at a sample of their nodes, the committed
//! tables are what the solver makes today, with the presets' settings. (`cd` and `dvd`: lamellar
//! Al under polycarbonate, one pass through the cover; `blazed600`: the ruled sawtooth, by the
//! C method.)

mod support;

use diffraction::relief::Metal;
use diffraction_fmm::table::{OrderSolver, Rigorous};
use diffraction_fmm::{Cover, CoverIndex, CoverPasses, Grating, Options, Profile, Solver};
use support::{PresetTable, REPRODUCTION_TOLERANCE};

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
/// |s| ≤ 0.95 off the Rayleigh lines (and λ ≥ `lambda_min`), and the nodes compared; solved as
/// the table builder solves (a solve that reaches the cap is kept at it).
fn worst_at_nodes(name: &str, g: &Grating, stride: usize, lambda_min: f64) -> (f64, usize) {
    let table = PresetTable::read(name);
    let rigorous = Rigorous {
        grating: g.clone(),
        solver: solver(),
        accept_unconverged: 2.5e-4,
    };
    let cover = |l: f64| {
        g.cover
            .map_or(1.0, |c| c.index.at(l).expect("above the pole"))
    };
    let (mut worst, mut count) = (0.0f64, 0);
    for &(j, i) in table
        .nodes(g.period_nm, lambda_min, cover)
        .iter()
        .step_by(stride)
    {
        let o = rigorous
            .solve(table.sin_theta_i[i], table.lambda_nm[j])
            .expect("a solve at the node");
        worst = worst.max(table.worst_at((j, i), |m| o.get(m)));
        count += 1;
    }
    (worst, count)
}

#[test]
fn cd_preset_is_what_this_solver_makes() {
    let (worst, count) = worst_at_nodes("cd", &covered(1600.0, 0.3125, 110.0), 131, 360.0);
    println!("cd: {count} nodes, worst |η − table| = {worst:.2e}");
    assert!(worst < REPRODUCTION_TOLERANCE, "{worst}");
}

#[test]
fn dvd_preset_is_what_this_solver_makes() {
    let g = covered(740.0, 0.32 / 0.74, 105.0);
    let (worst, count) = worst_at_nodes("dvd", &g, 131, 360.0);
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
    let (worst, count) = worst_at_nodes("blazed600", &g, 40, 600.0);
    println!("blazed600: {count} nodes, worst |η − table| = {worst:.2e}");
    assert!(worst < REPRODUCTION_TOLERANCE, "{worst}");
}
