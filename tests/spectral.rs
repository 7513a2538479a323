//! Spectral integration: CIE interpolation against colour-science, the white point, the
//! strategies' identities and the Monte-Carlo estimators.

use diffraction::cie::{cmf, Illuminant};
use diffraction::spectrum::{Spectral, Strategy};
use diffraction::{Band, Grating};
use proptest::prelude::*;
use std::fs;

fn data(name: &str) -> Vec<Vec<f64>> {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Linear interpolation of the 1 nm CMF rows agrees with numpy.interp on colour-science's
/// table; the tolerance is a few ulp of values below 2.
#[test]
fn cmf_interpolation_matches_colour_science() {
    let rows = data("cmf_interp.csv");
    assert!(rows.len() > 200);
    for r in rows {
        let got = cmf(r[0]);
        for c in 0..3 {
            assert!(
                (got[c] - r[c + 1]).abs() <= 1e-15,
                "cmf({})[{c}] = {} want {}",
                r[0],
                got[c],
                r[c + 1]
            );
        }
    }
    assert_eq!(cmf(359.999), [0.0; 3]);
    assert_eq!(cmf(f64::NAN), [0.0; 3]);
}

/// The white point is ∫E·cmf/∫E·ȳ: at u = 0 every strategy returns it, and under E it is close
/// to (1, 1, 1) (the CMFs have nearly equal areas: 106.86, 106.86, 106.77).
#[test]
fn white_points() {
    let e = Spectral::new(Illuminant::E).white();
    assert!((e.x - 1.0).abs() < 1e-3 && e.y == 1.0 && (e.z - 1.0).abs() < 1e-3);
    // D65 white, chromaticity (0.3127, 0.3290) to the precision of the 1 nm tables.
    let d = Spectral::new(Illuminant::D65).white();
    let (x, y) = d.chromaticity().unwrap();
    assert!(
        (x - 0.3127).abs() < 2e-4 && (y - 0.3290).abs() < 2e-4,
        "{x} {y}"
    );
    // The same white as colour-science's fixture (python_ref: exact integrals of the tables).
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/lab_de2000.csv");
    let line = fs::read_to_string(path)
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("# white: ").map(str::to_owned))
        .unwrap();
    let want: Vec<f64> = line.split(' ').map(|v| v.parse().unwrap()).collect();
    for (got, want) in [d.x, d.y, d.z].iter().zip(&want) {
        assert!((got - want).abs() < 1e-14, "{got} {want}");
    }
    let g = Grating::new(1600.0, 800.0, 100).unwrap();
    let s = Spectral::new(Illuminant::D65);
    for st in [
        Strategy::Exact,
        Strategy::PeakSearch { refine: false },
        Strategy::Uniform { samples: 10 },
        Strategy::PaperPeaks,
    ] {
        assert_eq!(s.xyz(&g, 0.0, st), d);
    }
}

/// The paper's mode is Σ S(β_m)·(E(λ_m)/Ē)·cmf(λ_m): under E (Ē = 1) one visible order gives
/// exactly S(β₁)·cmf(λ₁), whatever N.
#[test]
fn paper_peaks_are_weighted_spectral_colours() {
    let s = Spectral::new(Illuminant::E);
    for n in [10, 1000, 1_000_000] {
        let g = Grating::new(1600.0, 800.0, n).unwrap();
        let u = 0.35; // d·u = 560 nm: only order 1 is in the band
        let p: Vec<_> = g.peaks(u, Band::VISIBLE).collect();
        assert_eq!(p.len(), 1);
        let c = s.xyz(&g, u, Strategy::PaperPeaks);
        let want = cmf(560.0).map(|v| v * p[0].intensity);
        assert!((c.x - want[0]).abs() < 1e-12 && (c.y - want[1]).abs() < 1e-12);
        assert!((c.z - want[2]).abs() < 1e-12);
    }
}

/// The plain peak search is the analytic weight S·E·cmf·λ_m/(|m|N)/∫Eȳ per order.
#[test]
fn peak_search_is_the_analytic_weight() {
    let s = Spectral::new(Illuminant::E);
    let g = Grating::new(1600.0, 800.0, 5000).unwrap();
    let u = 0.9; // orders 2, 3, 4 at 720, 480, 360 nm; the 360 nm one sits on the band edge
    let c = s.xyz(&g, u, Strategy::PeakSearch { refine: false });
    // ∫ȳ of the linearly interpolated table: the trapezoid rule on its 1 nm rows is exact.
    let ybar_area: f64 = (360..830)
        .map(|l| 0.5 * (cmf(l as f64)[1] + cmf(l as f64 + 1.0)[1]))
        .sum();
    let mut want = 0.0;
    for p in g.peaks(u, Band::VISIBLE).filter(|p| p.order < 4) {
        want += p.intensity * cmf(p.wavelength_nm)[1] * p.equivalent_width_nm / ybar_area;
    }
    // The edge order adds a little (half its mass, by quadrature); the others are exact.
    assert!(
        c.y >= want * (1.0 - 1e-12) && c.y < want * 1.001,
        "{} {}",
        c.y,
        want
    );
    let two_orders = s.xyz(
        &Grating::new(1600.0, 800.0, 5000).unwrap(),
        0.7,
        Strategy::PeakSearch { refine: false },
    );
    let mut want2 = 0.0; // d·u = 1120: orders 2 (560 nm) and 3 (373.3 nm), both inside
    for p in g.peaks(0.7, Band::VISIBLE) {
        want2 += p.intensity * cmf(p.wavelength_nm)[1] * p.equivalent_width_nm / ybar_area;
    }
    assert!((two_orders.y - want2).abs() < 1e-12 * want2);
}

#[test]
fn strategy_names_round_trip() {
    for st in [
        Strategy::Uniform { samples: 471 },
        Strategy::GaussLegendre { intervals: 16 },
        Strategy::PeakSearch { refine: false },
        Strategy::PeakSearch { refine: true },
        Strategy::PaperPeaks,
        Strategy::Exact,
        Strategy::Auto { accuracy: 1e-3 },
    ] {
        assert_eq!(st.to_string().parse::<Strategy>(), Ok(st));
    }
    for bad in [
        "",
        "uniform",
        "uniform:-3",
        "gauss:x",
        "auto:0",
        "auto:nan",
        "fast",
    ] {
        assert!(bad.parse::<Strategy>().is_err(), "{bad}");
    }
}

/// Stratified and hero estimators average to the exact integral (the mean of 4000 independent
/// estimates, each with its own random numbers, is within a few standard errors).
#[test]
fn monte_carlo_estimators_are_unbiased() {
    let s = Spectral::new(Illuminant::D65);
    let g = Grating::new(1600.0, 800.0, 20).unwrap();
    let u = 0.4;
    let exact = s.xyz(&g, u, Strategy::Exact);
    let mut state = 0x9E3779B97F4A7C15u64;
    let mut rand = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let trials = 4000;
    let (mut sum_s, mut sum_h, mut sq_s, mut sq_h) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..trials {
        let r: Vec<f64> = (0..8).map(|_| rand()).collect();
        let a = s.xyz_stratified(&g, u, &r).y;
        let b = s.xyz_hero(&g, u, rand(), 4).y;
        sum_s += a;
        sq_s += a * a;
        sum_h += b;
        sq_h += b * b;
    }
    let n = trials as f64;
    for (sum, sq, name) in [(sum_s, sq_s, "stratified"), (sum_h, sq_h, "hero")] {
        let mean = sum / n;
        let se = ((sq / n - mean * mean) / n).sqrt();
        assert!(
            (mean - exact.y).abs() < 5.0 * se,
            "{name}: mean {mean} exact {} se {se}",
            exact.y
        );
    }
    assert_eq!(s.xyz_stratified(&g, u, &[]).y, 0.0);
    assert_eq!(s.xyz_hero(&g, u, 0.3, 0).y, 0.0);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Every strategy returns finite, non-negative XYZ for any finite u and grating.
    #[test]
    fn strategies_are_finite_and_non_negative(d in 300.0f64..1e5, duty in 0.01f64..=1.0,
                                              n in 1u32..2_000_000, u in -2.5f64..2.5) {
        let g = Grating::new(d, duty * d, n).unwrap();
        let s = Spectral::new(Illuminant::D65);
        for st in [Strategy::Uniform { samples: 16 }, Strategy::GaussLegendre { intervals: 2 },
                   Strategy::PeakSearch { refine: false }, Strategy::PeakSearch { refine: true },
                   Strategy::PaperPeaks, Strategy::Auto { accuracy: 1e-2 }] {
            let c = s.xyz(&g, u, st);
            prop_assert!(c.x.is_finite() && c.y.is_finite() && c.z.is_finite(), "{st}: {c:?}");
            prop_assert!(c.x >= 0.0 && c.y >= 0.0 && c.z >= 0.0, "{st}: {c:?}");
        }
    }

    /// Uniform and Gauss-Legendre converge to Exact for a broad pattern (N = 1). Gauss-Legendre
    /// on the 470 one-nanometre steps of the tables never straddles a kink of their linear
    /// interpolation, so it is exact to rounding; the midpoint rule is second order.
    #[test]
    fn quadratures_converge_for_one_slit(d in 300.0f64..3000.0, u in -2.0f64..2.0) {
        let g = Grating::new(d, 0.5 * d, 1).unwrap();
        let s = Spectral::new(Illuminant::E);
        let exact = s.xyz(&g, u, Strategy::Exact).y;
        let gl = s.xyz(&g, u, Strategy::GaussLegendre { intervals: 470 }).y;
        let uni = s.xyz(&g, u, Strategy::Uniform { samples: 471 }).y;
        prop_assert!((gl - exact).abs() < 1e-9 * exact.max(1e-3));
        prop_assert!((uni - exact).abs() < 1e-3 * exact.max(1e-3));
    }
}

#[test]
fn infinite_gratings_integrate_to_zero_off_the_mirror() {
    let g = Grating::infinite(1600.0, 800.0).unwrap();
    let s = Spectral::new(Illuminant::E);
    assert_eq!(s.xyz(&g, 0.4, Strategy::Exact).y, 0.0);
    assert_eq!(
        s.xyz(&g, 0.4, Strategy::PeakSearch { refine: false }).y,
        0.0
    );
    assert!(s.xyz(&g, 0.4, Strategy::PaperPeaks).y > 0.0);
    assert_eq!(s.xyz(&g, 0.0, Strategy::Exact).y, 1.0);
}

/// A model that hides that it is a grating's intensity (no `grating_response`), so that the
/// colour integrator takes its generic path through `eval` and `peaks`.
struct Opaque(diffraction::AguHill);

impl diffraction::DiffractionBrdf for Opaque {
    fn eval(&self, wi: glam::DVec3, wo: glam::DVec3, lambda_nm: f64) -> f64 {
        self.0.eval(wi, wo, lambda_nm)
    }
    fn peaks(
        &self,
        wi: glam::DVec3,
        wo: glam::DVec3,
        band: Band,
        visit: &mut dyn FnMut(diffraction::Peak),
    ) -> diffraction::PeakSummary {
        self.0.peaks(wi, wo, band, visit)
    }
    fn cosine_included(&self) -> bool {
        self.0.cosine_included()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(60))]

    /// The generic BRDF path (what any model gets) agrees with the grating's lobe-exact path on
    /// the Agu-Hill model: Exact to 1e-3 of the brightest order's scale, the peak search and the
    /// paper's mode exactly for the orders (away from order 0 and the band edges).
    #[test]
    fn generic_brdf_path_agrees_with_grating_path(d in 700.0f64..20000.0, n in 100u32..1_000_000,
                                                   t in 0.05f64..1.2) {
        use diffraction::AguHill;
        use glam::DVec3;
        let g = Grating::new(d, 0.5 * d, n).unwrap();
        let m = AguHill::new(g);
        let opaque = Opaque(m);
        let s = Spectral::new(Illuminant::D65);
        let wi = DVec3::Z;
        let wo = DVec3::new(t.sin(), 0.0, t.cos());
        let special = s.xyz_brdf(&m, wi, wo, Strategy::Exact);
        let generic = s.xyz_brdf(&opaque, wi, wo, Strategy::Exact);
        let scale = 555.0 / (n as f64 * 106.857);
        prop_assert!((special.y - generic.y).abs() < 1e-3 * scale.max(special.y),
            "special {:?} generic {:?}", special, generic);
        let q = d * t.sin();
        let clear_of_edges = g.peaks(t.sin(), Band::VISIBLE).all(|p| {
            let w = 64.0 * p.equivalent_width_nm;
            p.wavelength_nm - w > 360.0 && p.wavelength_nm + w < 830.0
        });
        if q > 830.0 && clear_of_edges {
            let a = s.xyz_brdf(&m, wi, wo, Strategy::PaperPeaks);
            let b = s.xyz_brdf(&opaque, wi, wo, Strategy::PaperPeaks);
            prop_assert!((a.y - b.y).abs() <= 1e-12 * a.y.max(1e-300));
        }
    }
}
