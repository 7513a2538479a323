//! How far a converged solve is from the limit, for the stopping rules of `Solver::solve` with
//! Richardson extrapolation: converged at the first agreement of two successive extrapolations
//! ("one agreement", the former rule) or at two successive agreements ("two agreements", the
//! rule now). The grating is the `dvd` preset's (lamellar Al under polycarbonate, one pass), the
//! hardest shipped case for lamellar TM; the nodes a 7 × 7 sample of its grid. At each node the
//! plain efficiencies are solved at the solver's own harmonic counts (from max(21, 4·n·d/λ + 11),
//! ×1.5) up to `CAP`; the limit is the extrapolation of the last two counts, and each rule is
//! applied to the counts before them.
//!
//! ```sh
//! cargo run --release -p diffraction-fmm --example convergence
//! ```

use diffraction::relief::Metal;
use diffraction_fmm::{
    Cover, CoverIndex, CoverPasses, Grating, Incidence, Options, Profile, Solver, GROWTH,
    MIN_HARMONICS,
};

/// The largest count solved (the last two give the limit).
const CAP: usize = 1300;

fn odd(x: f64) -> usize {
    let n = x.ceil() as usize;
    n | 1
}

/// (TE, TM) of orders −4..=4 at one count (0 where evanescent).
type Values = Vec<(f64, f64)>;

fn values(sol: &diffraction_fmm::Solution) -> Values {
    (-4..=4)
        .map(|m| sol.order(m).map_or((0.0, 0.0), |o| (o.te, o.tm)))
        .collect()
}

/// TE as it is (it converges fast), TM extrapolated in 1/N.
fn extrapolate(a: &Values, na: usize, b: &Values, nb: usize) -> Values {
    let (na, nb) = (na as f64, nb as f64);
    a.iter()
        .zip(b)
        .map(|(x, y)| (y.0, ((nb * y.1 - na * x.1) / (nb - na)).max(0.0)))
        .collect()
}

fn change(a: &Values, b: &Values) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x.0 - y.0).abs().max((x.1 - y.1).abs()))
        .fold(0.0, f64::max)
}

/// For each node: the counts and the plain values at each.
fn sequence(g: &Grating, solver: &Solver, s: f64, lambda: f64) -> Vec<(usize, Values)> {
    let inc = Incidence::classical(s, lambda).expect("a valid node");
    let n_c = CoverIndex::POLYCARBONATE
        .at(lambda)
        .expect("above the pole");
    let mut n = odd((MIN_HARMONICS as f64).max(4.0 * n_c * g.period_nm / lambda + 11.0));
    let mut out = Vec::new();
    while n <= CAP {
        let sol = solver.solve_at(g, inc, n).expect("solves");
        out.push((n, values(&sol)));
        n = odd(n as f64 * GROWTH);
    }
    out
}

/// Where a rule stops (count, error against the limit), or None within the counts before the
/// limit's pair.
fn stop(seq: &[(usize, Values)], tol: f64, agreements: usize) -> Option<(usize, f64)> {
    let k_last = seq.len() - 2;
    let limit = extrapolate(
        &seq[k_last].1,
        seq[k_last].0,
        &seq[k_last + 1].1,
        seq[k_last + 1].0,
    );
    let ext: Vec<Values> = (1..seq.len())
        .map(|k| extrapolate(&seq[k - 1].1, seq[k - 1].0, &seq[k].1, seq[k].0))
        .collect();
    // ext[k - 1] is made from counts k − 1 and k; a change uses ext[k − 2] and ext[k − 1].
    let mut run = 0;
    for k in 2..=k_last {
        let te_plain = seq[k - 1]
            .1
            .iter()
            .zip(&seq[k].1)
            .map(|(x, y)| (x.0 - y.0).abs())
            .fold(0.0, f64::max);
        let ch = change(&ext[k - 2], &ext[k - 1]).max(te_plain);
        run = if ch < tol { run + 1 } else { 0 };
        if run >= agreements {
            return Some((seq[k].0, change(&ext[k - 1], &limit)));
        }
    }
    None
}

fn main() {
    let g = Grating {
        period_nm: 740.0,
        profile: Profile::Lamellar {
            duty: 0.32 / 0.74,
            depth_nm: 105.0,
        },
        metal: Metal::AL,
        cover: Some(Cover {
            index: CoverIndex::POLYCARBONATE,
            thickness_nm: 1.2e6,
        }),
    };
    let solver = Solver::new(Options {
        cover_passes: CoverPasses::Single,
        max_harmonics: 1601,
        ..Options::default()
    })
    .expect("valid options");
    let nodes: Vec<(f64, f64)> = [-0.9, -0.6, -0.3, 0.0, 0.3, 0.6, 0.9]
        .iter()
        .flat_map(|&s| [360.0, 420.0, 500.0, 580.0, 660.0, 740.0, 830.0].map(|l| (s, l)))
        .collect();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let seqs: Vec<Vec<(usize, Values)>> = std::thread::scope(|scope| {
        let chunks: Vec<_> = nodes
            .chunks(nodes.len().div_ceil(threads))
            .map(|chunk| {
                let (g, solver) = (&g, &solver);
                scope.spawn(move || {
                    chunk
                        .iter()
                        .map(|&(s, l)| sequence(g, solver, s, l))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        chunks
            .into_iter()
            .flat_map(|h| h.join().expect("no panic"))
            .collect()
    });
    println!(
        "{} nodes of the dvd grating, counts up to {CAP}",
        nodes.len()
    );
    for tol in [1e-3, 2.5e-4] {
        for (rule, agreements) in [("one agreement", 1), ("two agreements", 2)] {
            let stops: Vec<(usize, f64)> = seqs
                .iter()
                .filter_map(|s| stop(s, tol, agreements))
                .collect();
            let worst = stops.iter().map(|x| x.1).fold(0.0, f64::max);
            let over = stops.iter().filter(|x| x.1 > tol).count();
            let mut counts: Vec<usize> = stops.iter().map(|x| x.0).collect();
            counts.sort_unstable();
            let median = counts.get(counts.len() / 2).copied().unwrap_or(0);
            println!(
                "tolerance {tol:.1e}, {rule}: {} of {} nodes stop before the limit's counts; \
                 worst error {:.2}× the tolerance, {over} above it; median count {median}",
                stops.len(),
                seqs.len(),
                worst / tol
            );
        }
    }
}
