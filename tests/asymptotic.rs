//! `Strategy::ASYMPTOTIC` against the independent reference of `python_ref/`
//! (`tests/data/spectral_xyz.csv`) and against `Strategy::EXACT` over a sweep of gratings and
//! directions.
//!
//! Errors are taken as in `tests/spectral_reference.rs` and docs/accuracy.md: the largest channel
//! difference over the grating's brightest diffraction colour Y_b (the largest Y over the u with
//! d·|u| ≥ 360 nm, floored at 555/(N·∫ȳ)). Where order 0's half period reaches into the band
//! (d·|u|/830 nm < ½) the colour can be far brighter than Y_b (the white near the mirror
//! direction); there the error is taken over max(colour, Y_b).

#[path = "support/tolerance.rs"]
mod tol;

use diffraction::spectrum::{bounds, Illuminant, Spectral, Strategy};
use diffraction::{Grating, Slits};
use std::collections::HashMap;

/// The most slits for which `Asymptotic` writes F_N as its cosines (`src/spectrum/small_n.rs`,
/// `MAX_SLITS`): the small-N tests cover every N up to it.
const SMALL_N_MAX: u32 = 7;

#[derive(Clone)]
struct Case {
    d: f64,
    w: f64,
    n: u32,
    ill: Illuminant,
    u: f64,
    want: [f64; 3],
    got: [f64; 3],
}

/// The worst errors (orders, order-0 region) of `cases`, grouped by N, with the worst case.
fn worst_by_n(cases: &[Case]) -> Vec<(u32, f64, f64, String)> {
    let mut bright: HashMap<(u64, u64, u32, Illuminant), f64> = HashMap::new();
    for c in cases {
        let e = bright
            .entry((c.d.to_bits(), c.w.to_bits(), c.n, c.ill))
            .or_insert(555.0 / (c.n as f64 * diffraction::cie::cmf_areas()[1]));
        if c.d * c.u.abs() >= 360.0 {
            *e = e.max(c.want[1]);
        }
    }
    let mut by_n: std::collections::BTreeMap<u32, (f64, f64, String)> = Default::default();
    for c in cases {
        let yb = bright[&(c.d.to_bits(), c.w.to_bits(), c.n, c.ill)];
        let err = (0..3)
            .map(|i| (c.got[i] - c.want[i]).abs())
            .fold(0.0, f64::max);
        let e = by_n.entry(c.n).or_default();
        let order0 = c.d * c.u.abs() / 830.0 < 0.5;
        let rel = if order0 {
            let size = c.want.iter().fold(yb, |a, &b| a.max(b));
            let rel = err / size;
            e.1 = e.1.max(rel);
            rel / tol::ASYMPTOTIC_ORDER0
        } else {
            let rel = err / yb;
            e.0 = e.0.max(rel);
            rel / tol::ASYMPTOTIC_ORDERS
        };
        if rel >= 1.0 || e.2.is_empty() {
            e.2 = format!(
                "d={} w={} u={} {:?}: got {:?} want {:?}",
                c.d, c.w, c.u, c.ill, c.got, c.want
            );
        }
    }
    by_n.into_iter()
        .map(|(n, (a, b, s))| (n, a, b, s))
        .collect()
}

fn check(cases: &[Case], what: &str) {
    for (n, orders, order0, case) in worst_by_n(cases) {
        println!("{what} N = {n:>8}: orders {orders:.2e} of Y_b, order-0 region {order0:.2e}");
        assert!(
            orders <= tol::ASYMPTOTIC_ORDERS,
            "{what} N={n}: {orders:e} ({case})"
        );
        assert!(
            order0 <= tol::ASYMPTOTIC_ORDER0,
            "{what} N={n}: {order0:e} ({case})"
        );
    }
}

fn reference_rows() -> Vec<(f64, f64, u32, f64, Illuminant, [f64; 3])> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/spectral_xyz.csv");
    let text = std::fs::read_to_string(path).expect("tests/data/spectral_xyz.csv");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("period_nm,slit_width_nm,n,u,illuminant,X,Y,Z")
    );
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let p = |i: usize| f[i].parse::<f64>().unwrap();
            (
                p(0),
                p(1),
                f[2].parse().unwrap(),
                p(3),
                f[4].parse().unwrap(),
                [p(5), p(6), p(7)],
            )
        })
        .collect()
}

/// Against the python reference (float64 lobe-by-lobe quadrature, cross-checked with mpmath):
/// every row with N ≥ 5 (the strategy is `Exact` below).
#[test]
fn asymptotic_matches_reference_data() {
    let spectral = [Spectral::new(Illuminant::E), Spectral::new(Illuminant::D65)];
    let mut cases = Vec::new();
    for (d, w, n, u, ill, want) in reference_rows() {
        if n < 5 {
            continue;
        }
        let s = &spectral[(ill == Illuminant::D65) as usize];
        let g = Grating::with_slits(d, w, Slits::Finite(n)).unwrap();
        let c = s.xyz(&g, u, Strategy::ASYMPTOTIC);
        cases.push(Case {
            d,
            w,
            n,
            ill,
            u,
            want,
            got: [c.x, c.y, c.z],
        });
    }
    assert!(cases.len() > 1000);
    check(&cases, "reference");
}

/// The worst error of `cases` relative to the colour itself (its largest channel, floored at
/// `DARK_FLOOR` of the grating's Y_b), with the case.
fn worst_of_colour(cases: &[Case]) -> (f64, String) {
    let mut bright: HashMap<(u64, u64, u32, Illuminant), f64> = HashMap::new();
    for c in cases {
        let e = bright
            .entry((c.d.to_bits(), c.w.to_bits(), c.n, c.ill))
            .or_insert(555.0 / (c.n as f64 * diffraction::cie::cmf_areas()[1]));
        if c.d * c.u.abs() >= 360.0 {
            *e = e.max(c.want[1]);
        }
    }
    let mut worst = (0.0f64, String::new());
    for c in cases {
        let yb = bright[&(c.d.to_bits(), c.w.to_bits(), c.n, c.ill)];
        let size = c
            .want
            .iter()
            .fold(bounds::DARK_FLOOR * yb, |a, &b| a.max(b));
        let err = (0..3)
            .map(|i| (c.got[i] - c.want[i]).abs())
            .fold(0.0, f64::max);
        if err / size > worst.0 || worst.1.is_empty() {
            worst = (
                err / size,
                format!(
                    "d={} w={} N={} u={} {:?}: got {:?} want {:?}",
                    c.d, c.w, c.n, c.u, c.ill, c.got, c.want
                ),
            );
        }
    }
    worst
}

/// Up to `SMALL_N_MAX` slits (the Fejér kernel as its cosines) against the python reference:
/// every row with N ≤ 7 (N = 1, 2 and 5), relative to the colour itself.
#[test]
fn small_n_matches_reference_data() {
    let spectral = [Spectral::new(Illuminant::E), Spectral::new(Illuminant::D65)];
    let mut cases = Vec::new();
    for (d, w, n, u, ill, want) in reference_rows() {
        if n > SMALL_N_MAX {
            continue;
        }
        let s = &spectral[(ill == Illuminant::D65) as usize];
        let g = Grating::with_slits(d, w, Slits::Finite(n)).unwrap();
        let c = s.xyz(&g, u, Strategy::ASYMPTOTIC);
        cases.push(Case {
            d,
            w,
            n,
            ill,
            u,
            want,
            got: [c.x, c.y, c.z],
        });
    }
    assert!(cases.len() > 500);
    let (worst, case) = worst_of_colour(&cases);
    println!("reference N <= {SMALL_N_MAX}: {worst:.2e} of the colour ({case})");
    assert!(worst <= tol::ASYMPTOTIC_SMALL_N, "{worst:e} ({case})");
}

/// Up to `SMALL_N_MAX` slits against `Exact`: N = 1-7, d = 400 nm-100 µm (coarse gratings, where the
/// cosines are far finer than the tables' rows), w = d/2, d/10 and d/100, E, D65 and A, every
/// direction of the report's grid and 64 more; relative to the colour itself.
#[test]
fn small_n_matches_exact() {
    let mut cases = Vec::new();
    for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
        let s = Spectral::new(ill);
        for n in 1..=SMALL_N_MAX {
            for d in [400.0, 1600.0, 10_000.0, 30_000.0, 100_000.0] {
                for duty in [0.5, 0.1, 0.01, 1.0] {
                    let g = Grating::new(d, d * duty, n).unwrap();
                    for u in u_grid(true) {
                        let e = s.xyz(&g, u, Strategy::EXACT);
                        let a = s.xyz(&g, u, Strategy::ASYMPTOTIC);
                        cases.push(Case {
                            d,
                            w: d * duty,
                            n,
                            ill,
                            u,
                            want: [e.x, e.y, e.z],
                            got: [a.x, a.y, a.z],
                        });
                    }
                }
            }
        }
    }
    for n in 1..=SMALL_N_MAX {
        let of_n: Vec<Case> = cases.iter().filter(|c| c.n == n).map(Case::clone).collect();
        println!(
            "exact N = {n}: {:.2e} of the colour",
            worst_of_colour(&of_n).0
        );
    }
    let (worst, case) = worst_of_colour(&cases);
    println!("exact N <= {SMALL_N_MAX}: {worst:.2e} of the colour ({case})");
    assert!(worst <= tol::ASYMPTOTIC_SMALL_N, "{worst:e} ({case})");
}

/// Up to `SMALL_N_MAX` slits with a spectral envelope (1/λ, as a radiometric model's) and slits far
/// narrower than the period: against `Exact`, relative to the colour itself.
#[test]
fn small_n_with_an_envelope_matches_exact() {
    let mut cases = Vec::new();
    let s = Spectral::new(Illuminant::D65)
        .with_envelope(diffraction::Envelope::new(1, 0.0).expect("valid envelope"));
    for n in [1u32, 2, 4, SMALL_N_MAX] {
        for (d, duty) in [(100_000.0, 0.5), (1e6, 1e-9), (30_000.0, 0.37)] {
            let g = Grating::new(d, d * duty, n).unwrap();
            for u in u_grid(false).into_iter().step_by(4) {
                let e = s.xyz(&g, u, Strategy::EXACT);
                let a = s.xyz(&g, u, Strategy::ASYMPTOTIC);
                cases.push(Case {
                    d,
                    w: d * duty,
                    n,
                    ill: Illuminant::D65,
                    u,
                    want: [e.x, e.y, e.z],
                    got: [a.x, a.y, a.z],
                });
            }
        }
    }
    let (worst, case) = worst_of_colour(&cases);
    println!("exact N <= {SMALL_N_MAX} with an envelope: {worst:.2e} of the colour ({case})");
    assert!(worst <= tol::ASYMPTOTIC_SMALL_N, "{worst:e} ({case})");
}

/// The directions of the accuracy report (64) and, with `extra`, 64 more from a Weyl sequence.
fn u_grid(extra: bool) -> Vec<f64> {
    let mut v: Vec<f64> = (0..6).map(|k| 10f64.powf(-8.0 + k as f64)).collect();
    let ratio = (0.15f64 / 0.002).powf(1.0 / 13.0);
    v.extend((0..14).map(|k| 0.002 * ratio.powi(k)));
    v.extend((0..44).map(|k| 0.15 + 1.83 * (k as f64 + 0.5) / 44.0));
    if extra {
        v.extend((1..=64).map(|k| 0.0005 + 1.99 * ((k as f64 * 0.618_033_988_749_895) % 1.0)));
    }
    v
}

fn sweep(slits: &[u32], periods: &[f64], duties: &[f64], us: &[f64]) -> Vec<Case> {
    let mut out = Vec::new();
    for ill in [Illuminant::E, Illuminant::D65] {
        let s = Spectral::new(ill);
        for &d in periods {
            for &duty in duties {
                for &n in slits {
                    let g = Grating::new(d, d * duty, n).unwrap();
                    for &u in us {
                        let e = s.xyz(&g, u, Strategy::EXACT);
                        let a = s.xyz(&g, u, Strategy::ASYMPTOTIC);
                        out.push(Case {
                            d,
                            w: d * duty,
                            n,
                            ill,
                            u,
                            want: [e.x, e.y, e.z],
                            got: [a.x, a.y, a.z],
                        });
                    }
                }
            }
        }
    }
    out
}

/// Against `Exact` (within 1e-7 of the reference) on a small sweep.
#[test]
fn asymptotic_matches_exact() {
    let us: Vec<f64> = u_grid(false).into_iter().step_by(3).collect();
    let cases = sweep(
        &[5, 7, 21, 300, 1_000_000],
        &[740.0, 10_000.0],
        &[0.5, 0.1],
        &us,
    );
    check(&cases, "exact (small sweep)");
}

/// The sweep behind the bounds (about a minute in release).
#[test]
#[ignore = "slow sweep (about a minute in release)"]
fn asymptotic_matches_exact_full_sweep() {
    let slits = [5, 7, 10, 21, 30, 100, 300, 1000, 3000, 30_000, 1_000_000];
    let periods = [400.0, 740.0, 1600.0, 10_000.0, 100_000.0];
    let cases = sweep(&slits, &periods, &[0.5, 0.1], &u_grid(true));
    check(&cases, "exact");
}

#[test]
fn asymptotic_name_round_trips() {
    assert_eq!(Strategy::ASYMPTOTIC.to_string(), "asymptotic");
    assert_eq!("asymptotic".parse(), Ok(Strategy::ASYMPTOTIC));
}

/// Finite, non-negative and bounded work at the extremes: N = 1, 2, 4 (the cosines), 5 and 10⁷,
/// u = 0 and 2,
/// coarse and fine gratings, slit width equal to the period.
#[test]
fn asymptotic_is_finite_at_extremes() {
    for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
        let s = Spectral::new(ill);
        for (d, w) in [(400.0, 400.0), (1600.0, 800.0), (1e6, 10.0)] {
            for n in [1u32, 2, 4, 5, 7, 10_000_000] {
                let g = Grating::new(d, w, n).unwrap();
                for u in [0.0, 1e-12, 1e-6, 0.5, 1.0, 2.0, -2.0, 1e3] {
                    let c = s.xyz(&g, u, Strategy::ASYMPTOTIC);
                    assert!(
                        c.x.is_finite() && c.y.is_finite() && c.z.is_finite(),
                        "d={d} w={w} N={n} u={u}: {c:?}"
                    );
                    assert!(c.x >= 0.0 && c.y >= 0.0 && c.z >= 0.0, "{c:?}");
                }
            }
        }
    }
}

/// Wall-clock time per XYZ over the accuracy report's grid (printed; criterion's
/// `benches/spectral.rs` is the measurement of record).
#[test]
#[ignore = "timing listing"]
fn list_times_over_the_report_grid() {
    let s = Spectral::new(Illuminant::D65);
    let us = u_grid(false);
    let strategies = [
        Strategy::ASYMPTOTIC,
        Strategy::PEAK_SEARCH,
        Strategy::auto(1e-3).unwrap(),
    ];
    let mut cells = vec![Vec::new(); strategies.len()];
    for d in [740.0, 1600.0, 10_000.0, 100_000.0] {
        for n in [1u32, 2, 5, 30, 300, 1000, 3000, 30_000, 1_000_000] {
            let g = Grating::new(d, d / 2.0, n).unwrap();
            let mut line = format!("d={d:>7} N={n:>8}");
            for (k, &st) in strategies.iter().enumerate() {
                let mut best = f64::INFINITY;
                for _ in 0..5 {
                    let t = std::time::Instant::now();
                    let mut acc = 0.0;
                    for &u in &us {
                        acc += s.xyz(&g, std::hint::black_box(u), st).y;
                    }
                    std::hint::black_box(acc);
                    best = best.min(t.elapsed().as_nanos() as f64 / us.len() as f64);
                }
                cells[k].push(best);
                line += &format!("  {st}: {best:>9.0} ns");
            }
            println!("{line}");
        }
    }
    for (k, st) in strategies.iter().enumerate() {
        let v = &mut cells[k];
        v.sort_by(f64::total_cmp);
        println!(
            "{st}: median {:.0} ns per XYZ over {} cells",
            v[v.len() / 2],
            v.len()
        );
    }
}
