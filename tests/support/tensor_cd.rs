//! A version-2 conical table (a tensor grid in (s′, |β|, λ)) for the GPU tests: the CD preset's
//! conical reading (`Preset::conical_table`) sampled at the nodes of a tensor grid, so that it
//! is a realistic table with every order's Rayleigh lines and cut-offs. Shared by
//! tests/gpu_wgsl.rs and gpu-tests/tests/tabulated.rs (`#[path]`).
#![allow(dead_code)]

use diffraction::relief::{EfficiencyTable, Preset};

/// The CD's conical reading on s′ = the CD's 25 nodes, |β| ∈ {0, 0.3, 0.5, 0.64, 0.75, 0.84,
/// 0.9}, λ = 360, 380, …, 820, 830 nm; 0 exactly where an order is evanescent at the node, as
/// a version-2 table must be.
pub fn tensor_cd() -> EfficiencyTable {
    let r = Preset::Cd.conical_table();
    let sin: Vec<f64> = Preset::Cd.table().sin_theta_i().collect();
    let bet: Vec<f64> = vec![0.0, 0.3, 0.5, 0.64, 0.75, 0.84, 0.9];
    let lam: Vec<f64> = (0..24)
        .map(|j| 360.0 + 20.0 * j as f64)
        .chain([830.0])
        .collect();
    let d = r.period_nm();
    let (mut te, mut tm) = (Vec::new(), Vec::new());
    for m in r.orders() {
        for &b in &bet {
            let c = (1.0 - b * b).sqrt();
            for &l in &lam {
                for &s in &sin {
                    let am = s * c + f64::from(m) * l / d;
                    let e = if am * am + b * b >= 1.0 {
                        Default::default()
                    } else {
                        r.efficiency_conical(m, s * c, b, l)
                    };
                    te.push(e.te);
                    tm.push(e.tm);
                }
            }
        }
    }
    EfficiencyTable::new_conical(d, *r.orders().start(), sin, bet, lam, te, tm)
        .expect("the CD's conical reading on a tensor grid")
}
