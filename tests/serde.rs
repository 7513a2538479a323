//! Parameter types round-trip through serde and are validated on the way in.
#![cfg(feature = "serde")]

use diffraction::frame::{GratingField, Tile};
use diffraction::{AguHill, Band, Grating, Illumination, Slits};

#[test]
fn parameter_types_round_trip() {
    let g = Grating::new(1600.0, 800.0, 2000).unwrap();
    let json = serde_json::to_string(&g).unwrap();
    assert_eq!(serde_json::from_str::<Grating>(&json).unwrap(), g);
    let inf = Grating::infinite(740.0, 370.0).unwrap();
    let back: Grating = serde_json::from_str(&serde_json::to_string(&inf).unwrap()).unwrap();
    assert_eq!(back.slits(), Slits::Infinite);
    let m = AguHill::new(g);
    let back: AguHill = serde_json::from_str(&serde_json::to_string(&m).unwrap()).unwrap();
    assert_eq!(back, m);
    let i = Illumination::new(0.1, 0.4, 1.0).unwrap();
    let back: Illumination = serde_json::from_str(&serde_json::to_string(&i).unwrap()).unwrap();
    assert_eq!(back, i);
    let f = GratingField::checkerboard(0.5, Tile::Plain, Tile::Constant { angle: 0.3 }).unwrap();
    let back: GratingField = serde_json::from_str(&serde_json::to_string(&f).unwrap()).unwrap();
    assert_eq!(back, f);
    let b: Band = serde_json::from_str(r#"{"min_nm": 400.0, "max_nm": 700.0}"#).unwrap();
    assert_eq!(b, Band::new(400.0, 700.0).unwrap());
}

#[test]
fn invalid_values_are_rejected_with_the_parameter_name() {
    let e = serde_json::from_str::<Grating>(
        r#"{"period_nm": 1600.0, "slit_width_nm": 2000.0, "slits": {"Finite": 10}}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("slit_width_nm"), "{e}");
    let e = serde_json::from_str::<Band>(r#"{"min_nm": 700.0, "max_nm": 400.0}"#).unwrap_err();
    assert!(e.to_string().contains("max_nm"), "{e}");
    let e = serde_json::from_str::<GratingField>(
        r#"{"Checkerboard": {"cell_size": -1.0, "even": "Plain", "odd": "Plain"}}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("cell_size"), "{e}");
    let e = serde_json::from_str::<AguHill>(
        r#"{"grating": {"period_nm": 1600.0, "slit_width_nm": -800.0, "slits": "Infinite"}}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("slit_width_nm"), "{e}");
    let e = serde_json::from_str::<Illumination>(
        r#"{"ambient": -1.0, "diffuse": 0.0, "diffraction": 1.0}"#,
    )
    .unwrap_err();
    assert!(e.to_string().contains("ambient"), "{e}");
}
