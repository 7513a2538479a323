//! The numbers of `docs/baselines.md`: Agu & Hill's model beside Thorman's and Stam's, point by
//! point, printed as Markdown tables.
//!
//! ```text
//! cargo run --release --features stam --example compare_models
//! ```
//!
//! The models are matched as in the docs: a grating of period d = 1600 nm and N slits of half
//! the period (Agu-Hill), Thorman's lobe of the same equivalent width at 550 nm
//! (`Thorman::matching`), Stam's coherence width σ_c = N·d/(2√π) with a sinusoidal profile of
//! amplitude 100 nm and a binary one of depth 120 nm over half of each period.

use diffraction::color::{WhitePoint, Xyz};
use diffraction::spectrum::{GenericStrategy, Illuminant, Spectral, Strategy};
use diffraction::{
    AguHill, Band, DiffractionBrdf, Grating, Profile, SpectralResponse, Stam, Thorman,
};
use glam::DVec3;
use std::f64::consts::PI;

const D: f64 = 1600.0;
const NAMES: [&str; 4] = ["Agu-Hill", "Thorman", "Stam sine", "Stam binary"];

/// A model with its value and its colour (`dyn` needs one trait for both).
trait Model: DiffractionBrdf + SpectralResponse {}
impl<M: DiffractionBrdf + SpectralResponse> Model for M {}

/// The reference colour of a model: `Exact` on its grating form where it has one (Agu-Hill),
/// the generic path's `WINDOWS` otherwise (Thorman, Stam).
fn reference(spectral: &Spectral, m: &dyn Model, wo: DVec3, wi: DVec3) -> Xyz {
    match m.grating_response(wo, wi) {
        Some(r) => spectral.xyz_response(&r, Strategy::EXACT),
        None => spectral.xyz_brdf(m, wo, wi, GenericStrategy::WINDOWS),
    }
}

/// The peak search of a model: the grating path's where it has a grating form, the generic
/// path's otherwise.
fn peak_search(spectral: &Spectral, m: &dyn Model, wo: DVec3, wi: DVec3) -> Xyz {
    match m.grating_response(wo, wi) {
        Some(r) => spectral.xyz_response(&r, Strategy::PEAK_SEARCH),
        None => spectral.xyz_brdf(m, wo, wi, GenericStrategy::PEAK_SEARCH),
    }
}

fn models(n: u32) -> Vec<Box<dyn Model>> {
    let grating = Grating::new(D, D / 2.0, n).unwrap();
    let coherence = n as f64 * D / (2.0 * PI.sqrt());
    vec![
        Box::new(AguHill::new(grating)),
        Box::new(Thorman::matching(&grating, 550.0).unwrap()),
        Box::new(Stam::new(Profile::Sine, D, 100.0, coherence).unwrap()),
        Box::new(Stam::new(Profile::Binary { fraction: 0.5 }, D, 120.0, coherence).unwrap()),
    ]
}

/// The outgoing direction in the plane of incidence with u = wi.x + wo.x (v = 0).
fn outgoing(wi: DVec3, u: f64) -> DVec3 {
    let x = u - wi.x;
    DVec3::new(x, -wi.y, (1.0 - x * x - wi.y * wi.y).sqrt())
}

/// The light at `deg` from the normal, on the side of +x (so wo.x = u − sin θi).
fn incidence(deg: f64) -> DVec3 {
    let t = deg.to_radians();
    DVec3::new(t.sin(), 0.0, t.cos())
}

fn peak_positions() {
    println!("## Peak positions (N = 100)\n");
    println!("| θi | u | orders and λ_m (nm), every model |");
    println!("|---|---|---|");
    let all = models(100);
    for deg in [0.0, 30.0, 60.0] {
        let wi = incidence(deg);
        for u in [0.35, 0.9, 1.4, 1.8] {
            let wo = outgoing(wi, u);
            if !wo.z.is_finite() || wo.z <= 0.0 {
                continue;
            }
            let lists: Vec<Vec<(i32, f64)>> = all
                .iter()
                .map(|m| {
                    let mut v = vec![];
                    m.peaks(wo, wi, Band::VISIBLE, &mut |p| {
                        v.push((p.order, p.wavelength_nm))
                    });
                    v
                })
                .collect();
            assert!(lists.iter().all(|l| l == &lists[0]), "models disagree");
            let text: Vec<String> = lists[0]
                .iter()
                .map(|(m, l)| format!("{m}: {l:.1}"))
                .collect();
            println!("| {deg}° | {u} | {} |", text.join(", "));
        }
    }
    println!();
}

fn between_orders() {
    println!("## Brightness of the orders at λ = 440 nm, normal incidence (N = 100)\n");
    println!("Peak value of `eval` at u = m·λ/d, relative to order 1 (for Stam, with its order");
    println!("efficiency |c_m|² and geometric factor G/w² in brackets).\n");
    println!("| model | m = 1 | m = 2 | m = 3 |");
    println!("|---|---|---|---|");
    let l = 440.0;
    let wi = DVec3::Z;
    for (name, m) in NAMES.iter().zip(models(100)) {
        let values: Vec<f64> = (1..=3)
            .map(|k| m.eval(wi, outgoing(wi, k as f64 * l / D), l))
            .collect();
        let cells: Vec<String> = (1..=3)
            .map(|k| {
                let wo = outgoing(wi, k as f64 * l / D);
                let rel = values[k - 1] / values[0];
                if name.starts_with("Stam") {
                    let w = wi.z + wo.z;
                    let c = 1.0 + wi.dot(wo);
                    let g = c * c / (wi.z * wo.z * w * w);
                    let profile = if name.ends_with("sine") {
                        Profile::Sine
                    } else {
                        Profile::Binary { fraction: 0.5 }
                    };
                    let h = if name.ends_with("sine") { 100.0 } else { 120.0 };
                    let eff = profile.efficiency(k as i32, 2.0 * PI * w * h / l);
                    format!("{rel:.3} ({eff:.3}, {g:.3})")
                } else {
                    format!("{rel:.3}")
                }
            })
            .collect();
        println!("| {name} | {} |", cells.join(" | "));
    }
    println!();
}

fn between_peaks() {
    println!("## Light between the peaks (normal incidence, λ = 440 nm)\n");
    println!("Mean of `eval` over u ∈ [1.25, 1.75]·λ/d (between orders 1 and 2), relative to the");
    println!("order-1 peak value.\n");
    println!("| N | Agu-Hill | Thorman | Stam sine | Stam binary |");
    println!("|---|---|---|---|---|");
    let l = 440.0;
    let wi = DVec3::Z;
    for n in [10u32, 100, 1000] {
        let cells: Vec<String> = models(n)
            .iter()
            .map(|m| {
                let peak = m.eval(wi, outgoing(wi, l / D), l);
                let k = 4000;
                let mean = (0..k)
                    .map(|i| {
                        let u = (1.25 + 0.5 * (i as f64 + 0.5) / k as f64) * l / D;
                        m.eval(wi, outgoing(wi, u), l)
                    })
                    .sum::<f64>()
                    / k as f64;
                format!("{:.2e}", mean / peak)
            })
            .collect();
        println!("| {n} | {} |", cells.join(" | "));
    }
    println!();
}

fn growing_n(spectral: &Spectral) {
    println!("## As N (Agu-Hill, Thorman) or σ_c = N·d/(2√π) (Stam) grows\n");
    println!("Normal incidence, u = 0.34 (order 1 at 544 nm, in the plane of the cone):");
    println!("Y by `Strategy::EXACT` (Agu-Hill) and the generic `WINDOWS` rule (the others),");
    println!("and order 1's equivalent width.\n");
    println!("| N | Agu-Hill Y | Thorman Y | Stam sine Y | Stam binary Y | width (nm) |");
    println!("|---|---|---|---|---|---|");
    let wi = DVec3::Z;
    let wo = outgoing(wi, 0.34);
    for n in [10u32, 100, 1000, 10_000] {
        let all = models(n);
        let ys: Vec<String> = all
            .iter()
            .map(|m| format!("{:.3e}", reference(spectral, &**m, wo, wi).y))
            .collect();
        let mut width = 0.0;
        all[2].peaks(wo, wi, Band::VISIBLE, &mut |p| {
            width = p.equivalent_width_nm
        });
        println!("| {n} | {} | {width:.3} |", ys.join(" | "));
    }
    println!();
}

fn peak_search_error(spectral: &Spectral) {
    println!("## The peak search against the reference\n");
    println!("Relative error of Y by the peak search (peak value times equivalent width at λ_m;");
    println!(
        "`Strategy::PEAK_SEARCH` for Agu-Hill, `GenericStrategy::PEAK_SEARCH` for the others)"
    );
    println!("against `Strategy::EXACT` (Agu-Hill) and `GenericStrategy::WINDOWS` (the others),");
    println!("normal incidence, u = 0.34.\n");
    println!("| N | Agu-Hill | Thorman | Stam sine | Stam binary |");
    println!("|---|---|---|---|---|");
    let wi = DVec3::Z;
    let wo = outgoing(wi, 0.34);
    for n in [10u32, 100, 1000] {
        let cells: Vec<String> = models(n)
            .iter()
            .map(|m| {
                let exact = reference(spectral, &**m, wo, wi).y;
                let fast = peak_search(spectral, &**m, wo, wi).y;
                format!("{:.1e}", (fast - exact).abs() / exact)
            })
            .collect();
        println!("| {n} | {} |", cells.join(" | "));
    }
    println!();
}

fn colours(spectral: &Spectral) {
    println!("## Colour (N = 100, D65, `Strategy::EXACT` / `GenericStrategy::WINDOWS`)\n");
    println!("Each model's XYZ is scaled so that its order-1 colour at normal incidence and");
    println!("u = 0.34 has Y = 1 (as the ray tracer's exposure does with the brightest order);");
    println!("ΔE2000 against Agu-Hill, CIELAB relative to the D65 white.\n");
    println!("| θi | u | v | Agu-Hill XYZ | Thorman ΔE | Stam sine ΔE | Stam binary ΔE |");
    println!("|---|---|---|---|---|---|---|");
    let all = models(100);
    let reference_wo = outgoing(DVec3::Z, 0.34);
    let scales: Vec<f64> = all
        .iter()
        .map(|m| 1.0 / reference(spectral, &**m, reference_wo, DVec3::Z).y)
        .collect();
    let white = spectral.white();
    for (deg, u, v) in [
        (0.0, 0.3, 0.0),
        (0.0, 0.4, 0.0),
        (0.0, 0.75, 0.0),
        (0.0, 0.9, 0.0),
        (30.0, 1.2, 0.0),
        (60.0, 1.5, 0.0),
        (0.0, 0.34, 0.01),
    ] {
        let wi = incidence(deg);
        let mut wo = outgoing(wi, u);
        wo.y += v;
        wo.z = (1.0 - wo.x * wo.x - wo.y * wo.y).sqrt();
        let xyz: Vec<Xyz> = all
            .iter()
            .zip(&scales)
            .map(|(m, k)| reference(spectral, &**m, wo, wi) * *k)
            .collect();
        let white = WhitePoint::new(white).expect("the white of a spectral integrator is positive");
        let lab: Vec<_> = xyz.iter().map(|c| c.to_lab(white)).collect();
        let de: Vec<String> = lab[1..]
            .iter()
            .zip(&xyz[1..])
            .map(|(l, c)| format!("{:.1} (Y {:.3})", lab[0].delta_e2000(*l), c.y))
            .collect();
        println!(
            "| {deg}° | {u} | {v} | {:.3}, {:.3}, {:.3} | {} |",
            xyz[0].x,
            xyz[0].y,
            xyz[0].z,
            de.join(" | ")
        );
    }
    println!();
}

fn main() {
    let spectral = Spectral::new(Illuminant::D65);
    peak_positions();
    between_orders();
    between_peaks();
    growing_n(&spectral);
    peak_search_error(&spectral);
    colours(&spectral);
}
