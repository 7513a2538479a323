//! A thick dielectric cover: a flat metal under it has closed forms for the single pass and for
//! the incoherent sum of all passes.

use diffraction::relief::Metal;
use diffraction_fmm::{
    Cover, CoverIndex, CoverPasses, Grating, Incidence, Options, Profile, Solver,
};
use num_complex::Complex64;

/// The solve evaluates the same closed forms, to rounding.
const COVER_TOLERANCE: f64 = 1e-12;

/// Power reflectances (s, p) of a flat interface from a real index n1 into a complex n2.
fn fresnel(n1: f64, n2: Complex64, s1: f64) -> (f64, f64) {
    let c1 = (1.0 - s1 * s1).sqrt();
    let n1c = Complex64::new(n1, 0.0);
    let mut c2 = (Complex64::new(1.0, 0.0) - (n1c * s1 / n2).powi(2)).sqrt();
    if (n2 * c2).im < 0.0 {
        c2 = -c2;
    }
    let rs = (n1c * c1 - n2 * c2) / (n1c * c1 + n2 * c2);
    let rp = (n2 * c1 - n1c * c2) / (n2 * c1 + n1c * c2);
    (rs.norm_sqr(), rp.norm_sqr())
}

#[test]
fn flat_metal_under_a_cover_single_and_multiple_passes() {
    let n_c = 1.58;
    let g = Grating {
        period_nm: 740.0,
        profile: Profile::Flat,
        metal: Metal::AL,
        cover: Some(Cover {
            index: CoverIndex::Constant(n_c),
            thickness_nm: 1.2e6,
        }),
    };
    let lambda = 600.0;
    let (n, k) = Metal::AL.index(lambda);
    for theta in [0.0f64, 0.5, 1.1] {
        for phi in [0.0, 0.9] {
            let inc = Incidence::new(theta, phi, lambda).unwrap();
            let s = theta.sin();
            let surf = fresnel(1.0, Complex64::new(n_c, 0.0), s);
            let metal = fresnel(n_c, Complex64::new(n, k), s / n_c);
            for passes in [CoverPasses::Single, CoverPasses::Multiple] {
                let solver = Solver::new(Options {
                    cover_passes: passes,
                    ..Options::default()
                })
                .unwrap();
                let o = *solver.solve(&g, inc).unwrap().order(0).unwrap();
                for (got, rs, rm) in [(o.te, surf.0, metal.0), (o.tm, surf.1, metal.1)] {
                    let t = 1.0 - rs;
                    let expect = match passes {
                        CoverPasses::Single => rs + t * t * rm,
                        CoverPasses::Multiple => rs + t * t * rm / (1.0 - rs * rm),
                    };
                    assert!(
                        (got - expect).abs() < COVER_TOLERANCE,
                        "θ {theta} φ {phi} {passes:?}: {got} vs {expect}"
                    );
                }
            }
        }
    }
}

/// A DVD-like grating (740 nm, lamellar, polycarbonate cover) at 740 nm: light totally reflected
/// inside the cover comes back; the multiple-pass sum exceeds the single pass, and both stay ≤ 1.
#[test]
fn trapped_light_returns_in_the_multiple_pass_sum() {
    let g = Grating {
        period_nm: 740.0,
        profile: Profile::Lamellar {
            duty: 0.5,
            depth_nm: 120.0,
        },
        metal: Metal::AL,
        cover: Some(Cover {
            index: CoverIndex::Constant(1.58),
            thickness_nm: 6e5,
        }),
    };
    let inc = Incidence::new(0.2, 0.0, 740.0).unwrap();
    let single = Solver::new(Options {
        cover_passes: CoverPasses::Single,
        ..Options::default()
    })
    .unwrap();
    let multi = Solver::default();
    let a = single.solve_at(&g, inc, 81).unwrap().total();
    let b = multi.solve_at(&g, inc, 81).unwrap().total();
    println!("single {a:?} multiple {b:?}");
    assert!(b.0 > a.0 && b.1 > a.1);
    assert!(b.0 <= 1.0 && b.1 <= 1.0);
}

/// The library's `polycarbonate_index` (what `Preset::reduced_table` reduces the CD and DVD
/// with) and this crate's `CoverIndex::POLYCARBONATE` (what their tables were solved with) are
/// the same fit written twice: equal to the bit across and beyond the band.
#[test]
fn the_librarys_polycarbonate_is_the_solvers() {
    use diffraction::relief::polycarbonate_index;
    for k in 0..=400 {
        let l = 150.0 + 10.0 * f64::from(k);
        assert_eq!(
            polycarbonate_index(l),
            CoverIndex::POLYCARBONATE.at(l).unwrap(),
            "{l}"
        );
    }
    // Below the pole the solver refuses the index; the library reads it as 1.
    assert!(CoverIndex::POLYCARBONATE.at(100.0).is_none());
    assert_eq!(polycarbonate_index(100.0), 1.0);
}
