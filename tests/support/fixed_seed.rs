//! The property tests' configuration: a fixed seed for every `proptest!` block, so that every run
//! (a fresh clone in CI included) tries the same cases, and the regressions file named from the
//! package root (proptest's default looks for `lib.rs` beside the test and finds none).

use proptest::prelude::ProptestConfig;
use proptest::test_runner::{FileFailurePersistence, RngAlgorithm, RngSeed};

/// `cases` cases from the fixed `seed`, failures recorded in `regressions` (a path from the
/// package root, such as `"tests/grating.proptest-regressions"`).
pub fn config(cases: u32, seed: u64, regressions: &'static str) -> ProptestConfig {
    ProptestConfig {
        cases,
        rng_algorithm: RngAlgorithm::ChaCha,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(regressions))),
        ..ProptestConfig::default()
    }
}
