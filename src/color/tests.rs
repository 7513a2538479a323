//! The whole colour pipeline on every row of the CIE 1931 table.

use super::*;
use crate::data::cie_data::CIE1931_2DEG;

/// Every integer wavelength of the CIE 1931 2° table (360..=830 nm) as a pure spectral colour
/// at five intensities, through the whole pipeline with each clipping scheme.
#[test]
fn monochromatic_sweep() {
    const INTENSITIES: [f64; 5] = [0.01, 0.1, 1.0, 10.0, 100.0];
    assert_eq!(CIE1931_2DEG.len(), 471);
    let white = LinearSrgb::new(1.0, 1.0, 1.0).to_xyz();
    let lab_white = WhitePoint::new(white).unwrap();
    let mut white_count = 0;
    for (i, &[xbar, ybar, zbar]) in CIE1931_2DEG.iter().enumerate() {
        let nm = 360 + i;
        let cmf = Xyz::new(xbar, ybar, zbar);
        let (x, y) = cmf.chromaticity().expect("every CMF row is non-zero");
        assert!(
            (0.0..=1.0).contains(&x) && (0.0..=1.0).contains(&y),
            "{nm} nm"
        );
        for k in INTENSITIES {
            let xyz = cmf * k;
            let linear = xyz.to_linear_srgb();
            assert!(
                linear.r.is_finite() && linear.g.is_finite() && linear.b.is_finite(),
                "{nm} nm × {k}"
            );
            // Spectral colours lie outside the sRGB triangle: a negative component.
            assert!(
                linear.r < 0.0 || linear.g < 0.0 || linear.b < 0.0,
                "{nm} nm × {k}: {linear:?} has no negative component"
            );
            assert!(!linear.is_in_gamut());
            let lum = linear.luminance();
            for method in Clip::ALL {
                let c = linear.clip(method);
                assert!(c.is_in_gamut(), "{nm} nm × {k}, {method}: {c:?}");
                let e = c.encode();
                for v in [e.r, e.g, e.b] {
                    assert!((0.0..=1.0).contains(&v), "{nm} nm × {k}, {method}");
                }
                let back = e.decode();
                for (b, l) in [(back.r, c.r), (back.g, c.g), (back.b, c.b)] {
                    // Round trip within the transfer function's breakpoint inconsistency.
                    assert!((b - l).abs() < 2.4e-9, "{nm} nm × {k}, {method}");
                }
                let _ = e.to_rgb8();
                let de = xyz
                    .to_lab(lab_white)
                    .delta_e2000(c.to_xyz().to_lab(lab_white));
                assert!(de.is_finite() && de >= 0.0, "{nm} nm × {k}, {method}: {de}");
                match method {
                    Clip::ConstantIntensity if lum <= 0.0 => {
                        assert_eq!(c, LinearSrgb::default());
                    }
                    Clip::ConstantIntensity if lum >= 1.0 => {
                        assert_eq!(c, LinearSrgb::new(1.0, 1.0, 1.0));
                        white_count += 1;
                    }
                    Clip::ConstantIntensity => {
                        assert!(
                            (c.luminance() - lum).abs() < 1e-12,
                            "{nm} nm × {k}: luminance {} -> {}",
                            lum,
                            c.luminance()
                        );
                    }
                    Clip::Intensity => {
                        // A negative component goes to 0, the others keep their ratios.
                        let pos = [linear.r, linear.g, linear.b].map(|v| v.max(0.0));
                        let m = pos[0].max(pos[1]).max(pos[2]).max(1.0);
                        for (o, p) in [c.r, c.g, c.b].into_iter().zip(pos) {
                            assert!((o * m - p).abs() <= 1e-15 * m, "{nm} nm × {k}");
                        }
                    }
                    _ => {}
                }
            }
        }
    }
    // Bright lines near the peak of ȳ saturate to white under constant intensity.
    assert!(white_count > 0);
}
