//! The fast reading against the parent module's: the cell search, every order's value, the
//! pair's min and the proposal, on the presets and on random tables (uniform, graded and
//! clustered grids; node sums near 1, so that some cells need the normalisation).

use std::vec::Vec;

use super::super::{interval, EfficiencyTable};
use super::{bins::Bins, Fast};

/// The fast reading against the parent module's, relative to the scale of its rounding: the
/// corners' q's (or stored values) times cos θm/cos θi, summed over the four corners. The
/// bilinear weights from the reciprocals of the spacings (1 − tx loses digits as tx → 1) and
/// q̄ = (q_TE + q_TM)/2 interpolated once (against TE and TM interpolated apart and averaged)
/// round differently. Measured 2.8e-16 over the reads of `reads_agree_with_the_rule` and
/// 2.6e-16 over the proposals' weighted values; margin 3.6×.
const READ_ROUNDING: f64 = 1e-15;
/// The fast proposal's sum against the parent module's, relative to the scale of its rounding:
/// the corners' running sums through the last candidate, unweighted (as for the reads: the
/// weights from the reciprocals of the spacings). Measured 2.1e-16; margin 4.8×.
const PROPOSAL_TOTAL: f64 = 1e-15;

fn rng(seed: u64) -> impl FnMut() -> f64 {
    let mut state = seed;
    move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random classical table on the axes `s`, `l`: node sums in [0.5, 1] (TE) and
/// [`tm_low`, 1] (TM), 0 where an order is evanescent.
fn random_table(
    next: &mut impl FnMut() -> f64,
    s: Vec<f64>,
    l: Vec<f64>,
    tm_low: f64,
) -> EfficiencyTable {
    let d = 700.0 + 1500.0 * next();
    let (orders, first) = (9usize, -4i32);
    let slice = s.len() * l.len();
    let (mut te, mut tm) = (vec![0.0; orders * slice], vec![0.0; orders * slice]);
    for (j, &lj) in l.iter().enumerate() {
        for (i, &si) in s.iter().enumerate() {
            let at = j * s.len() + i;
            let live: Vec<usize> = (0..orders)
                .filter(|&k| {
                    let am = si + f64::from(first + k as i32) * lj / d;
                    1.0 - am * am > 0.0
                })
                .collect();
            let raw: Vec<(f64, f64)> = live.iter().map(|_| (next(), next())).collect();
            let (st, sm) = raw.iter().fold((0.0, 0.0), |(p, q), r| (p + r.0, q + r.1));
            let (gt, gm) = (0.5 + 0.5 * next(), tm_low + (1.0 - tm_low) * next());
            for (&k, r) in live.iter().zip(&raw) {
                te[k * slice + at] = r.0 / st * gt;
                tm[k * slice + at] = r.1 / sm * gm;
            }
        }
    }
    EfficiencyTable::new(d, first, s, l, te, tm).unwrap()
}

/// Axes of several kinds: uniform, graded (the presets' kind), and clustered (spacings from
/// 10⁻⁹ up, several nodes to a bin).
fn axes(next: &mut impl FnMut() -> f64, kind: usize, lo: f64, hi: f64) -> Vec<f64> {
    let n = 3 + (8.0 * next()) as usize;
    let mut v: Vec<f64> = match kind {
        0 => (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect(),
        1 => (0..n)
            .map(|i| {
                let t = i as f64 / (n - 1) as f64;
                lo + (hi - lo) * t * t
            })
            .collect(),
        _ => {
            let mut v = std::vec![lo, hi];
            let c = lo + (hi - lo) * (0.2 + 0.6 * next());
            for k in 0..n {
                v.push(c + 1e-9 * (k as f64 + next()) * 10f64.powi(k as i32 % 6));
            }
            v
        }
    };
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The tables of the tests: the four presets and random ones.
fn tables() -> Vec<(std::string::String, &'static EfficiencyTable)> {
    let mut out: Vec<(std::string::String, &'static EfficiencyTable)> = Vec::new();
    #[cfg(feature = "presets")]
    for p in crate::relief::Preset::ALL {
        out.push((std::format!("{p}"), p.table()));
    }
    let mut next = rng(7);
    for t in 0..24 {
        let s = axes(&mut next, t % 3, -0.995, 0.995);
        let l = axes(&mut next, (t / 3) % 3, 360.0, 830.0);
        let table = random_table(&mut next, s, l, if t % 2 == 0 { 0.8 } else { 0.3 });
        out.push((
            std::format!("random {t}"),
            std::boxed::Box::leak(std::boxed::Box::new(table)),
        ));
    }
    out
}

/// The binned search gives the binary search's interval, with the interval's first node and
/// reciprocal width, everywhere on the axis: at every node, one unit in the last place either
/// side of it, and between.
#[test]
fn bins_locate_as_the_binary_search() {
    let mut next = rng(11);
    let mut checked = 0;
    let mut several = 0;
    let mut grids: Vec<Vec<f64>> = Vec::new();
    for kind in 0..3 {
        for _ in 0..40 {
            grids.push(axes(&mut next, kind, -0.9999, 0.9999));
            grids.push(axes(&mut next, kind, 360.0, 830.0));
        }
    }
    for (_, t) in tables() {
        grids.push(t.sin_theta_i().collect());
        grids.push(t.lambda_nm().collect());
    }
    for nodes in &grids {
        let bins = Bins::new(nodes).unwrap();
        let inv: Vec<f64> = nodes.windows(2).map(|w| 1.0 / (w[1] - w[0])).collect();
        several += bins.crowded();
        let (lo, hi) = (nodes[0], nodes[nodes.len() - 1]);
        let mut xs: Vec<f64> = Vec::new();
        for &x in nodes.iter() {
            xs.extend([
                x,
                f64::from_bits(x.to_bits() + 1),
                f64::from_bits(x.to_bits() - 1),
            ]);
        }
        xs.extend((0..200).map(|_| lo + (hi - lo) * next()));
        for x in xs {
            let x = bins.clamp(x);
            let at = bins.locate(nodes, &inv, x);
            let want = interval(nodes.as_slice(), x);
            assert_eq!(at.i, want, "{nodes:?} at {x}");
            assert_eq!((at.node, at.inv), (nodes[want], inv[want]));
            checked += 1;
        }
    }
    std::println!("{checked} searches, {several} bins holding several nodes");
    assert!(several > 50, "{several}");
}

/// Every stored order's fast reading at a query against the parent module's unpolarised,
/// normalised value, counted per path (plain, partial, normalised cells); returns the largest
/// difference in units of its rounding's scale ([`READ_ROUNDING`]).
fn compare(t: &EfficiencyTable, f: &Fast, s: f64, l: f64, counts: &mut [usize; 3]) -> f64 {
    let (a, w) = (f.side(s), f.wave(l).unwrap());
    let mut worst = 0.0f64;
    let slice = f.s.len() * f.l.len();
    let n_s = f.s.len();
    for (k, m) in t.orders().enumerate() {
        let want = t.efficiency(m, s, l).unpolarised();
        if !a.ok {
            assert_eq!(want, 0.0);
            continue;
        }
        let got = f.read(m, k, &a, &w);
        counts[if !f.cells[k * f.cell_count + w.row + a.i][0].is_nan() {
            0
        } else if f.unit[w.row + a.i] {
            1
        } else {
            2
        }] += 1;
        // The scale: the corners' q's (both polarisations) times cos θm/cos θi.
        let base = k * slice + w.j * n_s + a.i;
        let corners: f64 = [base, base + 1, base + n_s, base + n_s + 1]
            .iter()
            .map(|&n| f.q[n][0].max(0.0) + f.q[n][1].max(0.0))
            .sum();
        let sm = a.s + f64::from(m) * w.l / f.period_nm;
        let ratio = ((1.0 - sm * sm).max(0.0) / a.c_i).sqrt();
        let scale = (corners * ratio).max(want);
        if scale > 0.0 {
            worst = worst.max((got - want).abs() / scale);
        } else {
            assert_eq!(got, 0.0);
        }
    }
    worst
}

#[test]
fn reads_agree_with_the_rule() {
    let mut next = rng(5);
    let mut worst = 0.0f64;
    let mut counts = [0usize; 3];
    for (_, t) in tables() {
        let f = t
            .fast()
            .expect("a small classical table has a fast reading");
        let (s, l): (Vec<f64>, Vec<f64>) = (t.sin_theta_i().collect(), t.lambda_nm().collect());
        let mut queries: Vec<(f64, f64)> = (0..3000)
            .map(|_| (-1.02 + 2.04 * next(), 340.0 + 510.0 * next()))
            .collect();
        // The nodes themselves, and the grid's far corner.
        queries.extend(s.iter().flat_map(|&x| l.iter().map(move |&y| (x, y))));
        queries.push((1.0, 900.0));
        for (x, y) in queries {
            worst = worst.max(compare(t, f, x, y, &mut counts));
        }
    }
    std::println!(
        "reads: {} plain, {} partial, {} normalised; within {worst:.2e} of the rounding's scale",
        counts[0],
        counts[1],
        counts[2]
    );
    assert!(counts.iter().all(|&c| c > 1000), "{counts:?}");
    assert!(worst <= READ_ROUNDING, "{worst:e}");
}

/// The pair's min is symmetric to the bit, and is the min of the two reads.
#[test]
fn pair_min_is_symmetric_and_the_smaller_read() {
    let mut next = rng(9);
    let mut compared = 0;
    for (_, t) in tables() {
        let f = t.fast().unwrap();
        for _ in 0..2000 {
            let (a, b) = (-1.01 + 2.02 * next(), -1.01 + 2.02 * next());
            let l = 350.0 + 490.0 * next();
            let m =
                i64::from(*t.orders().start()) - 1 + (next() * (t.order_count() + 2) as f64) as i64;
            let ab = t.incidences((a, 0.3), (b, -0.2)).min(m, l);
            let ba = t.incidences((b, 0.1), (a, 0.0)).min(m, l);
            assert_eq!(ab.to_bits(), ba.to_bits(), "m={m} s={a}, {b} λ={l}");
            let (sa, sb, w) = (f.side(a), f.side(b), f.wave(l).unwrap());
            let read = |x: &super::Side| {
                let k = m - i64::from(f.order_min);
                if !x.ok || k < 0 || k >= f.order_count as i64 {
                    0.0
                } else {
                    f.read(m as i32, k as usize, x, &w)
                }
            };
            assert_eq!(ab, read(&sa).min(read(&sb)));
            compared += 1;
        }
    }
    assert!(compared > 50_000);
}

/// The fast proposal has the parent module's orders, its sum to rounding and each order's
/// weighted stored efficiency to rounding.
#[test]
fn proposals_agree_with_the_cell_proposal() {
    let mut next = rng(13);
    let (mut worst, mut worst_e) = (0.0f64, 0.0f64);
    let mut compared = 0;
    for (name, t) in tables() {
        for _ in 0..2000 {
            let (s, l) = (-1.01 + 2.02 * next(), 350.0 + 490.0 * next());
            let first = i64::from(*t.orders().start());
            let lo = first - 1 + (next() * 4.0) as i64;
            let hi = lo + (next() * t.order_count() as f64) as i64;
            let fast = t.fast_proposal(s, l, lo..=hi).expect("a fast reading");
            let cell = t.cell_proposal(s, 0.0, l, lo..=hi);
            let (Some(p), Some(c)) = (fast, cell) else {
                assert!(
                    fast.is_none() && cell.is_none(),
                    "{name}: s={s} λ={l} {lo}..={hi}"
                );
                continue;
            };
            assert_eq!((p.orders(), p.count()), (c.orders(), c.count()), "{name}");
            let f = t.fast().unwrap();
            let k_hi = (p.hi - f.order_min) as usize;
            let upper = f.cum[k_hi * f.cell_count + p.cell];
            let scale: f64 = upper.iter().sum();
            worst = worst.max((p.total() - c.total()).abs() / scale);
            for m in p.orders() {
                let (e, want) = (p.efficiency(m), t.cell_efficiency(&c, m));
                let k = (m - f.order_min) as usize;
                let scale: f64 = f.eta[k * f.cell_count + p.cell].iter().sum();
                worst_e = worst_e.max((e - want).abs() / scale.max(want));
            }
            compared += 1;
        }
    }
    std::println!(
        "{compared} proposals, sums within {worst:.2e} of the running sums, weighted values \
         within {worst_e:.2e} of the rounding's scale"
    );
    assert!(compared > 20_000);
    assert!(worst <= PROPOSAL_TOTAL, "{worst:e}");
    assert!(worst_e <= READ_ROUNDING, "{worst_e:e}");
}
