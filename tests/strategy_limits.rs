//! Strategies refuse counts and accuracies outside their ranges by name, and every strategy's
//! printed name parses back to it (split from `tests/extremes.rs`).

use diffraction::spectrum::{GenericStrategy, Strategy};

#[path = "support/extreme_inputs.rs"]
mod extreme_inputs;
#[path = "support/rng.rs"]
mod rng;
use extreme_inputs::{generic_strategies, strategies, Rng};

/// Counts and accuracies outside the accepted ranges are refused where the strategy is built,
/// with the parameter's name.
#[test]
fn strategies_outside_their_range_are_refused() {
    for k in [0, diffraction::spectrum::MAX_WAVELENGTHS + 1, u32::MAX] {
        assert_eq!(Strategy::uniform(k).unwrap_err().parameter(), "samples");
        assert_eq!(
            GenericStrategy::uniform(k).unwrap_err().parameter(),
            "samples"
        );
    }
    for k in [0, diffraction::spectrum::MAX_WAVELENGTHS, u32::MAX] {
        assert_eq!(
            Strategy::gauss_legendre(k).unwrap_err().parameter(),
            "intervals"
        );
    }
    for a in [
        0.0,
        -1.0,
        5e-324,
        1e-12,
        2.0,
        f64::MAX,
        f64::NAN,
        f64::INFINITY,
    ] {
        assert_eq!(
            Strategy::auto(a).unwrap_err().parameter(),
            "accuracy",
            "{a}"
        );
        assert_eq!(
            GenericStrategy::auto(a).unwrap_err().parameter(),
            "accuracy",
            "{a}"
        );
    }
}

/// Every strategy's printed name parses back to it; other strings are errors, never panics.
#[test]
fn strategies_parse_their_names() {
    for s in strategies() {
        assert_eq!(s.to_string().parse::<Strategy>(), Ok(s), "{s}");
    }
    for s in generic_strategies() {
        assert_eq!(s.to_string().parse::<GenericStrategy>(), Ok(s), "{s}");
    }
    let mut rng = Rng(rng::Rng(0xC0DE));
    let pieces = [
        "uniform",
        "gauss",
        "auto",
        "peaks",
        "exact",
        "windows",
        ":",
        "1",
        "0",
        "-1",
        "1e-3",
        "nan",
        "inf",
        "4294967296",
        "99999999999999999999",
        "1e400",
        " ",
        "",
        "é",
    ];
    for _ in 0..2000 {
        let s: String = (0..rng.next() % 4).map(|_| rng.pick(&pieces)).collect();
        if let Ok(st) = s.parse::<Strategy>() {
            assert_eq!(st.to_string().parse::<Strategy>(), Ok(st), "{s:?}");
        }
        if let Ok(st) = s.parse::<GenericStrategy>() {
            assert_eq!(st.to_string().parse::<GenericStrategy>(), Ok(st), "{s:?}");
        }
    }
}
