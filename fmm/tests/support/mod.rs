//! Shared helpers of the solver's tests: the committed rigorous reference cases and the named
//! tolerances.
#![allow(dead_code)]

pub mod cmethod_conical;

use diffraction::relief::Metal;
use diffraction_fmm::{Grating, Profile};

/// The reference data's own convergence: the Python solvers stopped when no order changed by
/// 1e-3 between two harmonic counts, so 1e-3 absolute per order is the agreement asked for.
pub const REFERENCE_TOLERANCE: f64 = 1e-3;

/// The `grating-table` arguments of a shallow lamellar Al grating of period 1000 nm: cheap
/// solves (the CLI's tests and sweeps).
pub const SHALLOW_LAMELLAR: [&str; 10] = [
    "--period",
    "1000",
    "--profile",
    "lamellar",
    "--depth",
    "20",
    "--duty",
    "0.5",
    "--metal",
    "Al",
];

/// The `foil` preset (python_ref's C method, converged to 1e-3) against this crate's C method
/// converged at 100 of its nodes: measured worst 5.0e-7, asserted at 1e-5.
pub const FOIL_PRESET_TOLERANCE: f64 = 1e-5;

/// A preset made by this solver, re-solved with its own settings: the file's 6 decimals (5e-7),
/// measured worst 4.97e-7 (cd, dvd, blazed600 at 4, 4 and 2 nodes); asserted at 1e-6.
pub const REPRODUCTION_TOLERANCE: f64 = 1e-6;

/// A metal of n + ik = 1 + 30i (a near-perfect conductor) read at fixed reduced coordinates
/// (s′, λ′) for |β| = 0-0.8, the largest change of an unpolarised order efficiency at one
/// truncation (161 harmonics): the mapping is exact for a perfect conductor, so what is left is
/// the surface impedance's 1/30 and the truncation's noise. Measured 1.96e-3 (4.9e-2 at fixed
/// λ; `a_near_perfect_conductor_reads_the_same_at_fixed_reduced_coordinates`); margin 2.5×.
pub const PEC_REDUCED_SPREAD: f64 = 5e-3;

/// Closed forms that the method reproduces to rounding (flat surface = Fresnel): 1e-12.
pub const FRESNEL_TOLERANCE: f64 = 1e-12;

/// The C method's energy balance on smooth lossless profiles, |ΣR + ΣT − 1|: measured worst
/// 6.9e-10 (a 500 nm deep sinusoid of period 800 nm, 41 harmonics), asserted at 5e-9.
pub const CMETHOD_SMOOTH_ENERGY_TOLERANCE: f64 = 5e-9;

/// Relative agreement of a shallow sinusoid with first-order perturbation theory, whose own
/// error is O((kh)²) = 4e-3 at h = 5 nm, λ = 500 nm: measured worst 1.14e-3, asserted at 5e-3.
pub const PERTURBATION_TOLERANCE: f64 = 5e-3;

/// One reference row: a propagating order of one case.
#[derive(Debug, Clone)]
pub struct Row {
    pub profile: String,
    pub metal: String,
    pub period_nm: f64,
    pub depth_nm: f64,
    pub duty: Option<f64>,
    pub blaze_deg: Option<f64>,
    pub lambda_nm: f64,
    pub theta_deg: f64,
    pub te: bool,
    pub order: i32,
    pub efficiency: f64,
    pub harmonics: usize,
}

/// A case: rows sharing geometry, wavelength and angle (both polarisations).
#[derive(Debug, Clone)]
pub struct Case {
    pub rows: Vec<Row>,
}

impl Case {
    pub fn first(&self) -> &Row {
        &self.rows[0]
    }
    pub fn grating(&self) -> Grating {
        let r = self.first();
        let metal = match r.metal.as_str() {
            "Al" => Metal::AL,
            "Ag" => Metal::AG,
            other => other.parse().expect("metal"),
        };
        let profile = match r.profile.as_str() {
            "lamellar" => Profile::Lamellar {
                duty: r.duty.expect("duty"),
                depth_nm: r.depth_nm,
            },
            "sinusoid" => Profile::Sinusoid {
                depth_nm: r.depth_nm,
            },
            "sawtooth" => Profile::Sawtooth {
                blaze: r.blaze_deg.expect("blaze").to_radians(),
            },
            p => panic!("profile {p}"),
        };
        Grating {
            period_nm: r.period_nm,
            profile,
            metal,
            cover: None,
        }
    }
    pub fn harmonics(&self) -> usize {
        self.first().harmonics
    }
}

fn opt(s: &str) -> Option<f64> {
    if s.is_empty() {
        None
    } else {
        Some(s.parse().expect("number"))
    }
}

/// The cases of tests/data/rigorous_orders.csv, in file order.
pub fn rigorous_cases() -> Vec<Case> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/data/rigorous_orders.csv"
    ))
    .expect("tests/data/rigorous_orders.csv");
    let mut cases: Vec<Case> = Vec::new();
    let mut key = String::new();
    for line in text.lines().filter(|l| !l.starts_with('#')).skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let row = Row {
            profile: f[0].to_string(),
            metal: f[1].to_string(),
            period_nm: f[2].parse().unwrap(),
            depth_nm: f[3].parse().unwrap(),
            duty: opt(f[4]),
            blaze_deg: opt(f[5]),
            lambda_nm: f[6].parse().unwrap(),
            theta_deg: f[7].parse().unwrap(),
            te: f[8] == "TE",
            order: f[9].parse().unwrap(),
            efficiency: f[11].parse().unwrap(),
            harmonics: f[12].parse().unwrap(),
        };
        let k = f[..8].join(",");
        if k != key {
            cases.push(Case { rows: Vec::new() });
            key = k;
        }
        cases.last_mut().unwrap().rows.push(row);
    }
    cases
}

/// A committed preset table, `data/efficiencies/NAME.json`, as written.
pub struct PresetTable {
    json: serde_json::Value,
    /// The s nodes.
    pub sin_theta_i: Vec<f64>,
    /// The λ nodes, nm.
    pub lambda_nm: Vec<f64>,
    order_min: i32,
}

impl PresetTable {
    pub fn read(name: &str) -> PresetTable {
        let path = format!(
            "{}/../data/efficiencies/{name}.json",
            env!("CARGO_MANIFEST_DIR")
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let nums = |k: &str| -> Vec<f64> {
            json[k]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let (sin_theta_i, lambda_nm) = (nums("sin_theta_i"), nums("lambda_nm"));
        let order_min = json["order_min"].as_i64().unwrap() as i32;
        PresetTable {
            json,
            sin_theta_i,
            lambda_nm,
            order_min,
        }
    }

    /// The nodes (λ index j, s index i) with |s| ≤ 0.95 and λ ≥ `lambda_min`, at least 1e-3
    /// from every Rayleigh line |s + mλ/d| = n, n = 1 and `cover_index(λ)`.
    pub fn nodes(
        &self,
        period_nm: f64,
        lambda_min: f64,
        cover_index: impl Fn(f64) -> f64,
    ) -> Vec<(usize, usize)> {
        let mut nodes = Vec::new();
        for (j, &l) in self.lambda_nm.iter().enumerate() {
            let n = cover_index(l);
            for (i, &s) in self.sin_theta_i.iter().enumerate() {
                let near_line = (-40..=40).any(|m| {
                    let a = (s + m as f64 * l / period_nm).abs();
                    (a - 1.0).abs() < 1e-3 || (a - n).abs() < 1e-3
                });
                if s.abs() <= 0.95 && l >= lambda_min && !near_line {
                    nodes.push((j, i));
                }
            }
        }
        nodes
    }

    /// The largest |η − table| at node (j, i) over every stored order and both polarisations,
    /// `solved(m)` giving (TE, TM) of order m (0 where it does not propagate).
    pub fn worst_at(&self, (j, i): (usize, usize), solved: impl Fn(i32) -> (f64, f64)) -> f64 {
        let mut worst = 0.0f64;
        for (te, key) in [(true, "te"), (false, "tm")] {
            for (k, row) in self.json[key].as_array().unwrap().iter().enumerate() {
                let table = row[j][i].as_f64().unwrap();
                let (a, b) = solved(self.order_min + k as i32);
                worst = worst.max(((if te { a } else { b }) - table).abs());
            }
        }
        worst
    }
}
