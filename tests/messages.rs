//! The exact text of the errors a caller (and the ray tracer, which prints them) sees: each
//! names the parameter, the value it got and the range it needs. The texts follow
//! `Error`'s `Display` contract (`invalid NAME = VALUE: must …`, numbers in their shortest
//! round-trip form, scientific outside [10⁻⁴, 10¹⁶)), and `ParseError`'s
//! (`unknown WHAT: expected …`). Deserialisation (feature `serde`) goes through the same
//! constructors, so the same texts appear in serde's errors.

use diffraction::frame::{GratingField, Tile};
use diffraction::spectrum::{GenericStrategy, Strategy};
use diffraction::{
    Band, Grating, GrooveSpread, Illumination, Profile, SampledWavelengths, Slits, Stam, Thorman,
};

fn msg<T: std::fmt::Debug>(r: Result<T, diffraction::Error>) -> String {
    r.unwrap_err().to_string()
}

#[test]
fn band_errors_name_the_end_and_the_range() {
    assert_eq!(
        msg(Band::new(0.0, 780.0)),
        "invalid min_nm = 0: must be finite and > 0"
    );
    assert_eq!(
        msg(Band::new(700.0, 400.0)),
        "invalid max_nm = 400: must satisfy max_nm > min_nm (700)"
    );
    // The issue's band: accepted before, its uniform density was infinite.
    assert_eq!(
        msg(Band::new(5e-324, 1e-323)),
        "invalid max_nm = 1e-323: must satisfy max_nm >= min_nm + Band::MIN_WIDTH_NM (1e-6)"
    );
    assert_eq!(
        msg(Band::new(400.0, f64::INFINITY)),
        "invalid max_nm = inf: must be finite and > 0"
    );
}

#[test]
fn model_errors_name_the_parameter_and_the_range() {
    assert_eq!(
        msg(Stam::new(Profile::Sine, 1600.0, 100.0, 1e16)),
        "invalid coherence_nm = 1e16: must lie in [1600, 1000000000000000]"
    );
    assert_eq!(
        msg(Stam::new(Profile::Sine, 1600.0, 100.0, 1000.0)),
        "invalid coherence_nm = 1000: must satisfy coherence_nm >= period_nm (1600)"
    );
    assert_eq!(
        msg(Stam::new(Profile::Sine, 1600.0, -1.0, 5000.0)),
        "invalid depth_nm = -1: must lie in [0, 10000]"
    );
    assert_eq!(
        msg(Stam::new(
            Profile::Binary { fraction: 1.5 },
            1600.0,
            100.0,
            5000.0
        )),
        "invalid fraction = 1.5: must satisfy 0 < fraction <= 1 (1)"
    );
    assert_eq!(
        msg(Thorman::new(1600.0, 2.0)),
        "invalid lobe_width = 2: must satisfy 0 < lobe_width <= 1 (1)"
    );
    assert_eq!(
        msg(Grating::new(1600.0, 2000.0, 100)),
        "invalid slit_width_nm = 2000: must satisfy 0 < slit_width_nm <= period_nm (1600)"
    );
    assert_eq!(
        msg(Grating::with_slits(1600.0, 800.0, Slits::Finite(0))),
        "invalid slits = 0: must be at least 1"
    );
    assert_eq!(
        msg(Illumination::new(-1.0, 0.0, 1.0)),
        "invalid ambient = -1: must be finite and >= 0"
    );
}

#[test]
fn sampler_errors_name_the_parameter_and_the_range() {
    assert_eq!(
        msg(GrooveSpread::gaussian(-1.5)),
        "invalid sigma = -1.5: must be finite and > 0"
    );
    assert_eq!(
        msg(GrooveSpread::gaussian(5e-324)),
        "invalid sigma = 5e-324: must lie in [1e-12, 1]"
    );
    assert_eq!(
        msg(GrooveSpread::coherence_length(0.5)),
        "invalid length_nm = 0.5: must lie in [1, 1000000000000000]"
    );
    assert_eq!(
        msg(SampledWavelengths::new([500.0; 4], [0.1, -1.0, 0.1, 0.1])),
        "invalid pdf = -1: must be finite and >= 0"
    );
    assert_eq!(
        msg(SampledWavelengths::new([500.0, 0.0, 1.0, 2.0], [0.1; 4])),
        "invalid lambda_nm = 0: must be finite and > 0"
    );
    assert_eq!(
        msg(GratingField::checkerboard(0.0, Tile::Plain, Tile::Plain)),
        "invalid cell_size = 0: must be finite and > 0"
    );
}

/// A strategy name that parses nowhere lists every accepted spelling with its range, so the
/// message says what to change also for a count beyond the range (`uniform:4097` is accepted:
/// the library's limit is `MAX_WAVELENGTHS` = 65536).
#[test]
fn strategy_parse_errors_list_the_ranges() {
    let grating = "unknown strategy: expected uniform:K (K from 1 to 65536), gauss:K (K from 1 \
                   to 8192), peaks, peaks-refined, asymptotic, exact, auto or auto:ACCURACY \
                   (ACCURACY from 1e-6 to 1)";
    assert_eq!(
        "nonsense".parse::<Strategy>().unwrap_err().to_string(),
        grating
    );
    // A known name with its number out of range: the number and the range.
    for (s, want) in [
        (
            "uniform:99999999999",
            "uniform count 99999999999 is out of range: expected 1 to 65536",
        ),
        (
            "uniform:0",
            "uniform count 0 is out of range: expected 1 to 65536",
        ),
        (
            "gauss:9000",
            "gauss interval count 9000 is out of range: expected 1 to 8192",
        ),
        (
            "auto:0",
            "auto accuracy 0 is out of range: expected 1e-6 to 1",
        ),
        (
            "auto:1e-9",
            "auto accuracy 1e-9 is out of range: expected 1e-6 to 1",
        ),
    ] {
        assert_eq!(s.parse::<Strategy>().unwrap_err().to_string(), want, "{s}");
        assert_eq!(
            s.parse::<GenericStrategy>().unwrap_err().to_string(),
            want,
            "{s}"
        );
    }
    assert!("uniform:4097".parse::<Strategy>().is_ok());
    let generic = "unknown generic strategy: expected uniform:K (K from 1 to 65536), gauss:K (K \
                   from 1 to 8192), peaks, windows, auto or auto:ACCURACY (ACCURACY from 1e-6 \
                   to 1)";
    assert_eq!(
        "exact".parse::<GenericStrategy>().unwrap_err().to_string(),
        generic
    );
    // The constructors behind the names say which parameter and which range.
    assert_eq!(
        msg(Strategy::uniform(99_999_999)),
        "invalid samples = 99999999: must lie in [1, 65536]"
    );
}

#[cfg(feature = "serde")]
mod serde_validation {
    use super::*;
    use diffraction::{AguHill, GratingBsdf};

    fn json_err<T: serde::de::DeserializeOwned + std::fmt::Debug>(s: &str) -> String {
        serde_json::from_str::<T>(s).unwrap_err().to_string()
    }

    fn toml_err<T: serde::de::DeserializeOwned + std::fmt::Debug>(s: &str) -> String {
        toml::from_str::<T>(s).unwrap_err().to_string()
    }

    /// Every type with a range is validated on the way in, with the constructor's message.
    #[test]
    fn deserialisation_validates_every_range() {
        let e = json_err::<GrooveSpread>(r#"{"Gaussian":{"sigma":-1.5}}"#);
        assert!(
            e.starts_with("invalid sigma = -1.5: must be finite and > 0"),
            "{e}"
        );
        let e = json_err::<GrooveSpread>(r#"{"CoherenceLength":{"length_nm":1e16}}"#);
        assert!(
            e.starts_with("invalid length_nm = 1e16: must lie in [1, 1000000000000000]"),
            "{e}"
        );
        let e = json_err::<Strategy>(r#""uniform:0""#);
        assert!(e.starts_with("uniform count 0 is out of range"), "{e}");
        let e = json_err::<Strategy>(r#""simpson""#);
        assert!(e.starts_with("unknown strategy: expected uniform:K"), "{e}");
        let e = json_err::<GenericStrategy>(r#""exact""#);
        assert!(e.starts_with("unknown generic strategy"), "{e}");
        let e = json_err::<Band>(r#"{"min_nm": 5e-324, "max_nm": 1e-323}"#);
        assert!(
            e.starts_with("invalid max_nm = 1e-323: must satisfy max_nm >= min_nm"),
            "{e}"
        );
        let e = json_err::<Grating>(
            r#"{"period_nm": -1.0, "slit_width_nm": 1.0, "slits": {"Finite": 10}}"#,
        );
        assert!(
            e.starts_with("invalid period_nm = -1: must be finite and > 0"),
            "{e}"
        );
        let e = json_err::<Grating>(
            r#"{"period_nm": 1600.0, "slit_width_nm": 800.0, "slits": {"Finite": 0}}"#,
        );
        assert!(
            e.starts_with("invalid slits = 0: must be at least 1"),
            "{e}"
        );
        let e = json_err::<AguHill>(
            r#"{"grating": {"period_nm": 1600.0, "slit_width_nm": 0.0, "slits": "Infinite"}}"#,
        );
        assert!(e.starts_with("invalid slit_width_nm = 0"), "{e}");
        let e = json_err::<Illumination>(r#"{"ambient": 0.1, "diffuse": -0.5, "diffraction": 1}"#);
        assert!(
            e.starts_with("invalid diffuse = -0.5: must be finite and >= 0"),
            "{e}"
        );
        let e = json_err::<GratingField>(
            r#"{"Checkerboard": {"cell_size": -1.0, "even": "Plain", "odd": "Plain"}}"#,
        );
        assert!(e.starts_with("invalid cell_size = -1"), "{e}");
        let bsdf = r#"{"grating": {"period_nm": 1600.0, "slit_width_nm": 800.0,
            "slits": {"Finite": 10}}, "groove": {"Gaussian": {"sigma": 7.0}}}"#;
        let e = json_err::<GratingBsdf>(bsdf);
        assert!(
            e.starts_with("invalid sigma = 7: must lie in [1e-12, 1]"),
            "{e}"
        );
    }

    /// A tile's numbers must be finite: TOML can spell ∞ and NaN, which JSON cannot.
    #[test]
    fn tiles_with_non_finite_numbers_are_refused() {
        let e = toml_err::<Tile>("Constant = { angle = inf }");
        assert!(e.contains("invalid angle = inf: must be finite"), "{e}");
        let e = toml_err::<Tile>("Radial = { center = [0.0, nan], twist = 0.0 }");
        assert!(e.contains("invalid center = NaN: must be finite"), "{e}");
        let e = toml_err::<Tile>("Radial = { center = [0.0, 1.0], twist = -inf }");
        assert!(e.contains("invalid twist = -inf: must be finite"), "{e}");
        let ok: Tile = toml::from_str("Constant = { angle = 0.5 }").unwrap();
        assert_eq!(ok, Tile::Constant { angle: 0.5 });
        // Inside a field, the same.
        let e = toml_err::<GratingField>(
            "[Checkerboard]\ncell_size = 1.0\neven = \"Plain\"\nodd = { Constant = { angle = nan } }",
        );
        assert!(e.contains("invalid angle = NaN: must be finite"), "{e}");
    }
}
