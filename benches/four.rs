//! Cost of the four-wavelength sample against one wavelength, in one group so the ratios come
//! from one run: ns per `sample` + `eval` + `pdf` at the hero (one wavelength's bounce, the
//! baseline), per `sample4` with the trait's default (`sample`, then `eval4` and `pdf4`), and
//! per the grating's `sample4`, for N ∈ {1, 30, 1000, 10⁶}, a CD-like grating (d = 1600 nm,
//! w = d/2).
//!
//! Each iteration runs a fixed batch of 1024 inputs (half of them within a few lobes of a peak,
//! from the benches' shared generator) so criterion's per-element figure is ns per call.
//! Goal: `sample4` within 2× of the one-wavelength baseline.

use criterion::{black_box, BenchmarkId, Criterion, Throughput};
use diffraction::{
    Band, Bsdf, BsdfFlags, BsdfSample, DiffractionBrdf, Grating, GratingBsdf, SampledWavelengths,
};
use glam::{DVec2, DVec3};
use std::time::Duration;

#[path = "support/rng.rs"]
mod rng;

const BATCH: usize = 1024;
const SLITS: [u32; 4] = [1, 30, 1000, 1_000_000];
const PERIOD: f64 = 1600.0;

/// The grating with the trait's default `sample4` (everything else delegated).
struct DefaultFour(GratingBsdf);

impl DiffractionBrdf for DefaultFour {
    fn eval(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.0.eval(wo, wi, lambda_nm)
    }
    fn eval4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        self.0.eval4(wo, wi, lambdas)
    }
}

impl Bsdf for DefaultFour {
    fn sample(&self, wo: DVec3, lambda_nm: f64, uc: f64, u2: DVec2) -> Option<BsdfSample> {
        self.0.sample(wo, lambda_nm, uc, u2)
    }
    fn pdf(&self, wo: DVec3, wi: DVec3, lambda_nm: f64) -> f64 {
        self.0.pdf(wo, wi, lambda_nm)
    }
    fn pdf4(&self, wo: DVec3, wi: DVec3, lambdas: &SampledWavelengths) -> [f64; 4] {
        self.0.pdf4(wo, wi, lambdas)
    }
    fn flags(&self) -> BsdfFlags {
        self.0.flags()
    }
    fn regularize(&mut self) {
        self.0.regularize();
    }
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("four");
    g.throughput(Throughput::Elements(BATCH as u64))
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(1))
        .sample_size(30);
    for n in SLITS {
        let grating = Grating::new(PERIOD, PERIOD / 2.0, n).expect("valid grating");
        let bsdf = GratingBsdf::new(grating);
        let default = DefaultFour(bsdf.clone());
        let inputs = rng::near_peak_samples(PERIOD, n, BATCH);
        let mut r = rng::Rng(0xF0_0D ^ u64::from(n));
        let randoms: Vec<(f64, DVec2)> = (0..BATCH).map(|_| (r.next_f64(), r.u2())).collect();
        let lambdas: Vec<SampledWavelengths> = inputs
            .iter()
            .map(|&(_, _, l)| {
                SampledWavelengths::sample_uniform((l - 360.0) / 470.0, Band::VISIBLE)
            })
            .collect();
        let cases: Vec<(DVec3, SampledWavelengths, f64, DVec2)> = inputs
            .iter()
            .zip(&lambdas)
            .zip(&randoms)
            .map(|((&(_, wo, _), &l), &(uc, u2))| (wo, l, uc, u2))
            .collect();
        g.bench_with_input(
            BenchmarkId::new("sample_eval_pdf", n),
            &cases,
            |b, cases| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for &(wo, l, uc, u2) in cases {
                        let hero = l.hero();
                        if let Some(s) = bsdf.sample(black_box(wo), hero, uc, u2) {
                            acc += bsdf.eval(wo, black_box(s.wi), hero)
                                + bsdf.pdf(wo, black_box(s.wi), hero);
                        }
                    }
                    acc
                })
            },
        );
        g.bench_with_input(
            BenchmarkId::new("sample4_default", n),
            &cases,
            |b, cases| {
                b.iter(|| {
                    let mut acc = 0.0;
                    for (wo, l, uc, u2) in cases {
                        if let Some(s) = default.sample4(black_box(*wo), l, *uc, *u2) {
                            acc += s.f[3] + s.pdf[3];
                        }
                    }
                    acc
                })
            },
        );
        g.bench_with_input(BenchmarkId::new("sample4", n), &cases, |b, cases| {
            b.iter(|| {
                let mut acc = 0.0;
                for (wo, l, uc, u2) in cases {
                    if let Some(s) = bsdf.sample4(black_box(*wo), l, *uc, *u2) {
                        acc += s.f[3] + s.pdf[3];
                    }
                }
                acc
            })
        });
    }
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
}
