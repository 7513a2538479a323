//! Unit and property tests of `diffraction::color`: conversions, the transfer function, the three
//! clipping schemes and ΔE2000 (including the 34 test pairs of Sharma, Wu & Dalal 2005).

#[path = "support/fixed_seed.rs"]
mod fixed_seed;
use approx::assert_abs_diff_eq;
use diffraction::cie::Illuminant;
use diffraction::color::{srgb_decode, srgb_encode, Clip, Lab, LinearSrgb, Srgb, WhitePoint, Xyz};
use diffraction::ParseError;
use proptest::prelude::*;

/// Tolerances, each with its reason and measurement.
#[path = "support/color_tolerance.rs"]
mod tol;

// -------------------------------------------------------------------------------------------
// Matrices and XYZ
// -------------------------------------------------------------------------------------------

#[test]
fn matrices_are_colour_science_values() {
    // Columns of matrix_XYZ_to_RGB and matrix_RGB_to_XYZ of colour-science 0.4.7.
    assert_eq!(
        Xyz::new(1.0, 0.0, 0.0).to_linear_srgb(),
        LinearSrgb::new(3.2406, -0.9689, 0.0557)
    );
    assert_eq!(
        Xyz::new(0.0, 1.0, 0.0).to_linear_srgb(),
        LinearSrgb::new(-1.5372, 1.8758, -0.2040)
    );
    assert_eq!(
        Xyz::new(0.0, 0.0, 1.0).to_linear_srgb(),
        LinearSrgb::new(-0.4986, 0.0415, 1.0570)
    );
    assert_eq!(
        LinearSrgb::new(1.0, 0.0, 0.0).to_xyz(),
        Xyz::new(0.4124, 0.2126, 0.0193)
    );
    assert_eq!(
        LinearSrgb::new(0.0, 1.0, 0.0).to_xyz(),
        Xyz::new(0.3576, 0.7152, 0.1192)
    );
    assert_eq!(
        LinearSrgb::new(0.0, 0.0, 1.0).to_xyz(),
        Xyz::new(0.1805, 0.0722, 0.9505)
    );
}

#[test]
fn luminance_is_the_y_row_and_its_weights_sum_to_one() {
    assert_eq!(0.2126 + 0.7152 + 0.0722, 1.0);
    assert_eq!(LinearSrgb::new(1.0, 1.0, 1.0).luminance(), 1.0);
    for c in [
        LinearSrgb::new(0.3, -0.2, 1.7),
        LinearSrgb::new(0.0, 0.5, 0.0),
        LinearSrgb::new(2.0, 3.0, -4.0),
    ] {
        assert_eq!(c.luminance(), c.to_xyz().y);
    }
}

#[test]
fn d65_white_maps_close_to_but_not_exactly_to_one() {
    // colour-science's D65 xy; the rounded matrix gives (0.99984, 1.00010, 1.00007).
    let white = Xyz::new(0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290);
    let rgb = white.to_linear_srgb();
    for c in [rgb.r, rgb.g, rgb.b] {
        assert!((c - 1.0).abs() < tol::D65_WHITE_RGB, "{rgb:?}");
    }
    assert!(!rgb.is_in_gamut()); // G and B slightly above 1: no hidden tolerance
}

#[test]
fn chromaticity() {
    let (x, y) = Xyz::new(0.2, 0.3, 0.5).chromaticity().unwrap();
    assert_abs_diff_eq!(x, 0.2, epsilon = tol::CHROMATICITY);
    assert_abs_diff_eq!(y, 0.3, epsilon = tol::CHROMATICITY);
    assert_eq!(Xyz::new(0.0, 0.0, 0.0).chromaticity(), None);
    assert_eq!(Xyz::new(1.0, -1.0, 0.0).chromaticity(), None);
    assert_eq!(Xyz::new(f64::INFINITY, 1.0, 0.0).chromaticity(), None);
    assert_eq!(Xyz::new(f64::NAN, 1.0, 0.0).chromaticity(), None);
    // The sum would overflow: the components are scaled by 2^-64 first (exact).
    assert_eq!(
        Xyz::new(f64::MAX, f64::MAX, 0.0).chromaticity(),
        Some((0.5, 0.5))
    );
    // A non-physical colour whose sum nearly cancels: the coordinates would exceed f64::MAX.
    let e = f64::EPSILON;
    assert_eq!(Xyz::new(1.0 - e, -(1.0 - e), -5e-324).chromaticity(), None);
}

#[test]
fn xyz_arithmetic() {
    let a = Xyz::new(1.0, 2.0, 3.0);
    let b = Xyz::new(0.5, 0.25, 0.125);
    assert_eq!(a + b, Xyz::new(1.5, 2.25, 3.125));
    assert_eq!(a * 2.0, Xyz::new(2.0, 4.0, 6.0));
    assert_eq!(a.scale(2.0), a * 2.0);
    let mut s = Xyz::default();
    s += a;
    s += b;
    assert_eq!(s, a + b);
    let l = LinearSrgb::new(1.0, 2.0, 3.0);
    assert_eq!(l + l, l * 2.0);
}

#[test]
fn lab_of_white_and_of_colour_science_example() {
    let white = Xyz::new(0.3127 / 0.3290, 1.0, (1.0 - 0.3127 - 0.3290) / 0.3290);
    let lab_white = WhitePoint::new(white).unwrap();
    let lab = white.to_lab(lab_white);
    assert_abs_diff_eq!(lab.l, 100.0, epsilon = tol::LAB_WHITE);
    assert_abs_diff_eq!(lab.a, 0.0, epsilon = tol::LAB_WHITE);
    assert_abs_diff_eq!(lab.b, 0.0, epsilon = tol::LAB_WHITE);
    // The docstring example of colour.XYZ_to_Lab (printed there to 7 decimals).
    let lab = Xyz::new(0.20654008, 0.12197225, 0.05136952).to_lab(lab_white);
    assert_abs_diff_eq!(lab.l, 41.527_875_29, epsilon = tol::LAB_DOCSTRING);
    assert_abs_diff_eq!(lab.a, 52.638_583_04, epsilon = tol::LAB_DOCSTRING);
    assert_abs_diff_eq!(lab.b, 26.923_179_22, epsilon = tol::LAB_DOCSTRING);
    // Black, and the linear segment below ε = 216/24389 (L* = κ·Y there, κ = 24389/27).
    assert_eq!(Xyz::default().to_lab(lab_white).l, 0.0);
    let y = 0.001;
    assert_abs_diff_eq!(
        white.scale(y).to_lab(lab_white).l,
        24389.0 / 27.0 * y,
        epsilon = tol::LAB_LINEAR
    );
}

#[test]
fn lab_is_continuous_at_epsilon() {
    let white = Xyz::new(1.0, 1.0, 1.0);
    let lab_white = WhitePoint::new(white).unwrap();
    let eps = 216.0 / 24389.0;
    let below = white.scale(eps).to_lab(lab_white).l;
    let above = white.scale(eps * (1.0 + 1e-15)).to_lab(lab_white).l;
    assert_abs_diff_eq!(below, 8.0, epsilon = tol::LAB_BREAKPOINT);
    assert_abs_diff_eq!(above, below, epsilon = tol::LAB_BREAKPOINT);
}

// -------------------------------------------------------------------------------------------
// Transfer function
// -------------------------------------------------------------------------------------------

fn next_up(x: f64) -> f64 {
    // For positive finite x.
    f64::from_bits(x.to_bits() + 1)
}

#[test]
fn transfer_function_values() {
    assert_eq!(srgb_encode(0.0), 0.0);
    assert_eq!(srgb_decode(0.0), 0.0);
    assert_eq!(srgb_encode(0.0031308), 12.92 * 0.0031308);
    assert_eq!(srgb_decode(1.0), 1.0);
    assert_abs_diff_eq!(srgb_encode(1.0), 1.0, epsilon = tol::ENCODE_ONE);
    assert_abs_diff_eq!(
        srgb_encode(0.18),
        0.461_356_129_500_442,
        epsilon = tol::TRANSFER_POINTS
    );
    assert_abs_diff_eq!(
        srgb_decode(0.5),
        0.214_041_140_482_232_55,
        epsilon = tol::TRANSFER_POINTS
    );
    // Odd-symmetric extension, no clipping above 1.
    for x in [1e-5, 0.002, 0.0031308, 0.01, 0.5, 1.0, 2.0, 100.0] {
        assert_eq!(srgb_encode(-x), -srgb_encode(x));
        assert_eq!(srgb_decode(-x), -srgb_decode(x));
    }
    assert!(srgb_encode(2.0) > 1.0);
    assert!(srgb_decode(1.5) > 1.0);
    assert!(srgb_encode(f64::NAN).is_nan());
    assert!(srgb_decode(f64::NAN).is_nan());
}

#[test]
fn transfer_function_is_continuous_at_the_breakpoints() {
    let t = 0.0031308;
    let jump = srgb_encode(t) - srgb_encode(next_up(t));
    // The standard's curve drops by 2.85e-8 there (not monotone by that amount).
    assert!(jump.abs() < tol::ENCODE_JUMP, "encode jump {jump:e}");
    assert!(jump > 0.0);

    let v = 0.04045;
    let jump = srgb_decode(next_up(v)) - srgb_decode(v);
    assert!(jump.abs() < tol::DECODE_JUMP, "decode jump {jump:e}");

    // Both segments are continuous away from the breakpoints.
    for x in [1e-4, 0.003, 0.004, 0.5, 0.999] {
        assert!((srgb_encode(next_up(x)) - srgb_encode(x)).abs() < tol::CONTINUITY);
        assert!((srgb_decode(next_up(x)) - srgb_decode(x)).abs() < tol::CONTINUITY);
    }
}

#[test]
fn transfer_round_trip_near_the_breakpoint() {
    let mut x = 0.0031308 - 1e-7;
    while x < 0.0031308 + 1e-7 {
        let back = srgb_decode(srgb_encode(x));
        let err = (back - x).abs();
        let window = x > 0.0031308 && srgb_encode(x) <= 0.04045;
        let allowed = if window {
            tol::TRANSFER_BREAKPOINT_WINDOW
        } else {
            tol::TRANSFER_ROUND_TRIP * x
        };
        assert!(err <= allowed, "x = {x}: error {err:e}");
        x += 1e-10;
    }
}

fn transfer_window(x: f64) -> bool {
    let a = x.abs();
    a > 0.0031308 && srgb_encode(a) <= 0.04045
}

proptest! {
    #[test]
    fn transfer_round_trip(x in prop_oneof![-2.0..2.0f64, -1e-2..1e-2f64, -1e4..1e4f64]) {
        let back = srgb_decode(srgb_encode(x));
        let allowed = if transfer_window(x) {
            tol::TRANSFER_BREAKPOINT_WINDOW
        } else {
            tol::TRANSFER_ROUND_TRIP * x.abs()
        };
        prop_assert!((back - x).abs() <= allowed, "x = {}, back = {}", x, back);
    }

    #[test]
    fn transfer_inverse_round_trip(v in prop_oneof![-2.0..2.0f64, -0.05..0.05f64]) {
        let back = srgb_encode(srgb_decode(v));
        // Just below 0.04045 decode takes the linear branch but lands above 0.0031308, where
        // encode takes the power branch: the standard's 2.85e-8 jump.
        let a = v.abs();
        let allowed = if a > 12.92 * 0.0031308 && a <= 0.04045 {
            tol::ENCODE_JUMP
        } else {
            tol::TRANSFER_ROUND_TRIP * a
        };
        prop_assert!((back - v).abs() <= allowed, "v = {}, back = {}", v, back);
    }

    #[test]
    fn encode_decode_are_monotone_within_segments(a in 0.0..2.0f64, b in 0.0..2.0f64) {
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        let same_segment = (hi <= 0.0031308) || (lo > 0.0031308);
        if same_segment {
            prop_assert!(srgb_encode(lo) <= srgb_encode(hi));
        }
        prop_assert!(srgb_decode(lo) <= srgb_decode(hi));
    }

    #[test]
    fn xyz_linear_round_trip(x in -10.0..10.0f64, y in -10.0..10.0f64, z in -10.0..10.0f64) {
        let xyz = Xyz::new(x, y, z);
        let back = xyz.to_linear_srgb().to_xyz();
        let scale = x.abs().max(y.abs()).max(z.abs());
        let allowed = tol::MATRIX_ROUND_TRIP * scale;
        prop_assert!((back.x - x).abs() <= allowed);
        prop_assert!((back.y - y).abs() <= allowed);
        prop_assert!((back.z - z).abs() <= allowed);

        let rgb = LinearSrgb::new(x, y, z);
        let back = rgb.to_xyz().to_linear_srgb();
        prop_assert!((back.r - x).abs() <= allowed);
        prop_assert!((back.g - y).abs() <= allowed);
        prop_assert!((back.b - z).abs() <= allowed);
    }
}

// -------------------------------------------------------------------------------------------
// Encoded sRGB
// -------------------------------------------------------------------------------------------

#[test]
fn rgb8_quantisation() {
    assert_eq!(Srgb::new(0.0, 1.0, 0.5).to_rgb8(), [0, 255, 128]);
    assert_eq!(Srgb::new(-3.0, 7.0, f64::NAN).to_rgb8(), [0, 255, 0]);
    assert_eq!(
        Srgb::new(f64::NEG_INFINITY, f64::INFINITY, 0.0).to_rgb8(),
        [0, 255, 0]
    );
    // Round to nearest: k/255 ± a bit.
    for k in 0..=255u8 {
        let v = f64::from(k) / 255.0;
        assert_eq!(
            Srgb::new(v, v + 0.49 / 255.0, v - 0.49 / 255.0).to_rgb8()[0],
            k
        );
        assert_eq!(Srgb::new(v + 0.49 / 255.0, 0.0, 0.0).to_rgb8()[0], k);
        if k > 0 {
            assert_eq!(Srgb::new(v - 0.49 / 255.0, 0.0, 0.0).to_rgb8()[0], k);
        }
    }
    // The white of the pipeline encodes to 1 − 2⁻⁵³ and still gives 255.
    assert_eq!(LinearSrgb::new(1.0, 1.0, 1.0).encode().to_rgb8(), [255; 3]);
}

#[test]
fn encode_and_decode_are_inverse_types() {
    let c = LinearSrgb::new(0.25, 0.5, 0.75);
    let back = c.encode().decode();
    assert_abs_diff_eq!(back.r, c.r, epsilon = tol::ENCODE_DECODE_TYPES);
    assert_abs_diff_eq!(back.g, c.g, epsilon = tol::ENCODE_DECODE_TYPES);
    assert_abs_diff_eq!(back.b, c.b, epsilon = tol::ENCODE_DECODE_TYPES);
}

// -------------------------------------------------------------------------------------------
// Clipping
// -------------------------------------------------------------------------------------------

#[test]
fn clip_names() {
    for c in Clip::ALL {
        assert_eq!(c.to_string().parse::<Clip>(), Ok(c));
    }
    assert_eq!("clamp".parse::<Clip>(), Ok(Clip::Clamp));
    assert_eq!("intensity".parse::<Clip>(), Ok(Clip::Intensity));
    assert_eq!("constant".parse::<Clip>(), Ok(Clip::ConstantIntensity));
    let err: ParseError = "Clamp".parse::<Clip>().unwrap_err();
    assert_eq!(err.what(), "clipping scheme");
    let msg = err.to_string();
    for name in ["clamp", "intensity", "constant"] {
        assert!(msg.contains(name), "{msg}");
    }
    assert!("".parse::<Clip>().is_err());
}

#[test]
fn clip_and_illuminant_share_one_parse_error() {
    let clip = "gamma".parse::<Clip>().unwrap_err();
    let illuminant = "D50".parse::<Illuminant>().unwrap_err();
    for (err, what) in [(clip, "clipping scheme"), (illuminant, "illuminant")] {
        assert_eq!(err.what(), what);
        assert_eq!(
            err.to_string(),
            format!("unknown {what}: expected {}", err.expected())
        );
    }
    for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
        assert!(illuminant.expected().contains(ill.name()));
        assert_eq!(ill.name().parse::<Illuminant>(), Ok(ill));
    }
}

fn in_unit_cube(c: LinearSrgb) -> bool {
    c.is_in_gamut() && !c.r.is_nan() && !c.g.is_nan() && !c.b.is_nan()
}

#[test]
fn clip_examples() {
    let c = LinearSrgb::new(1.5, 0.5, -0.25);
    assert_eq!(c.clip(Clip::Clamp), LinearSrgb::new(1.0, 0.5, 0.0));
    assert_eq!(
        c.clip(Clip::Intensity),
        LinearSrgb::new(1.0, 0.5 / 1.5, 0.0)
    );
    let k = c.clip(Clip::ConstantIntensity);
    assert!(in_unit_cube(k));
    assert_abs_diff_eq!(k.luminance(), c.luminance(), epsilon = tol::LUMINANCE);
    // The limiting channel lands on the boundary: here the red (1.5) at 1 or the blue at 0.
    assert!(k.r == 1.0 || k.b == 0.0, "{k:?}");

    // All negative → black for Intensity and ConstantIntensity (Y < 0), clamp too.
    let neg = LinearSrgb::new(-1.0, -2.0, -0.5);
    for m in Clip::ALL {
        assert_eq!(neg.clip(m), LinearSrgb::default());
    }
    // Bright: ConstantIntensity gives white; Intensity keeps the hue.
    let bright = LinearSrgb::new(4.0, 2.0, 1.0);
    assert_eq!(
        bright.clip(Clip::ConstantIntensity),
        LinearSrgb::new(1.0, 1.0, 1.0)
    );
    assert_eq!(
        bright.clip(Clip::Intensity),
        LinearSrgb::new(1.0, 0.5, 0.25)
    );
    assert_eq!(bright.clip(Clip::Clamp), LinearSrgb::new(1.0, 1.0, 1.0));
}

#[test]
fn clip_never_returns_nan() {
    let specials = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        f64::MIN_POSITIVE,
        -f64::MIN_POSITIVE,
        5e-324,
        -5e-324,
        f64::MAX,
        f64::MIN,
        1e300,
        -1e300,
        0.5,
    ];
    for &r in &specials {
        for &g in &specials {
            for &b in &specials {
                let c = LinearSrgb::new(r, g, b);
                for m in Clip::ALL {
                    let out = c.clip(m);
                    assert!(in_unit_cube(out), "{m}: {c:?} -> {out:?}");
                }
            }
        }
    }
    // Non-finite input: still inside the cube, no NaN.
    for c in [
        LinearSrgb::new(f64::NAN, 0.5, 0.5),
        LinearSrgb::new(f64::INFINITY, 0.5, 0.5),
        LinearSrgb::new(f64::INFINITY, f64::NEG_INFINITY, 0.5),
        LinearSrgb::new(f64::NEG_INFINITY, 0.5, 0.5),
    ] {
        for m in Clip::ALL {
            let out = c.clip(m);
            assert!(in_unit_cube(out), "{m}: {c:?} -> {out:?}");
        }
    }
    assert_eq!(
        LinearSrgb::new(f64::INFINITY, 0.5, -1.0).clip(Clip::Intensity),
        LinearSrgb::new(1.0, 0.0, 0.0)
    );
}

/// Components from the unit cube, mildly and wildly out of gamut, and exact edge values.
fn component() -> impl Strategy<Value = f64> {
    prop_oneof![
        0.0..=1.0f64,
        -1.0..2.0f64,
        -100.0..100.0f64,
        -1e6..1e6f64,
        Just(0.0),
        Just(1.0),
        Just(-1e-300),
    ]
}

fn colour() -> impl Strategy<Value = LinearSrgb> {
    (component(), component(), component()).prop_map(|(r, g, b)| LinearSrgb::new(r, g, b))
}

fn in_gamut_colour() -> impl Strategy<Value = LinearSrgb> {
    (0.0..=1.0f64, 0.0..=1.0f64, 0.0..=1.0f64).prop_map(|(r, g, b)| LinearSrgb::new(r, g, b))
}

proptest! {
    #![proptest_config(fixed_seed::config(2000, 0x5EED_0004, "tests/color.proptest-regressions"))]

    #[test]
    fn every_clip_lands_in_gamut(c in colour()) {
        for m in Clip::ALL {
            let out = c.clip(m);
            prop_assert!(in_unit_cube(out), "{}: {:?} -> {:?}", m, c, out);
        }
    }

    #[test]
    fn in_gamut_colours_are_unchanged(c in in_gamut_colour()) {
        prop_assert!(c.is_in_gamut());
        for m in Clip::ALL {
            prop_assert_eq!(c.clip(m), c);
        }
    }

    #[test]
    fn clamp_is_idempotent_and_per_channel(c in colour()) {
        let once = c.clip(Clip::Clamp);
        prop_assert_eq!(once.clip(Clip::Clamp), once);
        prop_assert_eq!(once.r, c.r.clamp(0.0, 1.0));
        prop_assert_eq!(once.g, c.g.clamp(0.0, 1.0));
        prop_assert_eq!(once.b, c.b.clamp(0.0, 1.0));
    }

    #[test]
    fn other_clips_are_idempotent(c in colour()) {
        for m in [Clip::Intensity, Clip::ConstantIntensity] {
            let once = c.clip(m);
            prop_assert_eq!(once.clip(m), once);
        }
    }

    #[test]
    fn intensity_keeps_ratios_of_non_negative_components(c in colour()) {
        let out = c.clip(Clip::Intensity);
        let pos = [c.r.max(0.0), c.g.max(0.0), c.b.max(0.0)];
        let m = pos[0].max(pos[1]).max(pos[2]);
        // Divided by the largest component when it exceeds 1, unchanged otherwise.
        let k = if m > 1.0 { m } else { 1.0 };
        for (o, p) in [out.r, out.g, out.b].into_iter().zip(pos) {
            prop_assert!((o * k - p).abs() <= tol::RATIO * k, "{:?} -> {:?}", c, out);
        }
        if m > 1.0 {
            prop_assert!(out.r == 1.0 || out.g == 1.0 || out.b == 1.0);
        }
    }

    #[test]
    fn constant_intensity_keeps_luminance(c in colour()) {
        let y = c.luminance();
        let out = c.clip(Clip::ConstantIntensity);
        if y <= 0.0 {
            prop_assert_eq!(out, LinearSrgb::new(0.0, 0.0, 0.0));
        } else if y > 1.0 {
            prop_assert_eq!(out, LinearSrgb::new(1.0, 1.0, 1.0));
            prop_assert_eq!(out.luminance(), 1.0);
        } else {
            prop_assert!((out.luminance() - y).abs() <= tol::LUMINANCE,
                "{:?} (Y = {}) -> {:?} (Y = {})", c, y, out, out.luminance());
            // It moved along the line toward the grey: out − Y ∥ c − Y with the same sense.
            if !c.is_in_gamut() {
                let d = [c.r - y, c.g - y, c.b - y];
                let e = [out.r - y, out.g - y, out.b - y];
                let dn = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                let en = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
                let dot = d[0] * e[0] + d[1] * e[1] + d[2] * e[2];
                prop_assert!(en <= dn * (1.0 + tol::CLIP_SHORTER));
                if en > 1e-9 {
                    prop_assert!((dot / (dn * en) - 1.0).abs() < tol::CLIP_PARALLEL);
                }
                // ... as far as the gamut allows: some channel touches 0 or 1.
                prop_assert!([out.r, out.g, out.b].iter().any(|&v| v <= tol::GAMUT_TOUCH || v >= 1.0 - tol::GAMUT_TOUCH),
                    "{:?} -> {:?}", c, out);
            }
        }
    }
}

// -------------------------------------------------------------------------------------------
// ΔE2000
// -------------------------------------------------------------------------------------------

/// Sharma, Wu & Dalal (2005), Table 1: L1 a1 b1, L2 a2 b2, ΔE00 (4 decimals).
const SHARMA: [[f64; 7]; 34] = [
    [50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425],
    [50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615],
    [50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412],
    [
        50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000,
    ],
    [
        50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000,
    ],
    [
        50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000,
    ],
    [50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669],
    [50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669],
    [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792],
    [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792],
    [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195],
    [50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195],
    [50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045],
    [50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045],
    [50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461],
    [50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065],
    [50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492],
    [50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977],
    [50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030],
    [50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535],
    [50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000],
    [50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000],
    [50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000],
    [50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000],
    [
        60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644,
    ],
    [
        63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630,
    ],
    [61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731],
    [35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645],
    [
        22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373,
    ],
    [36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146],
    [90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441],
    [90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381],
    [6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377],
    [2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082],
];

#[test]
fn delta_e2000_reproduces_sharma_table() {
    for (i, row) in SHARMA.iter().enumerate() {
        let a = Lab::new(row[0], row[1], row[2]);
        let b = Lab::new(row[3], row[4], row[5]);
        let expected = row[6];
        for d in [a.delta_e2000(b), b.delta_e2000(a)] {
            if i == 13 {
                // Pair 14: the hues differ by exactly 180° (up to one ulp of atan2), where the
                // mean hue jumps by 180°; the paper's 4.8045 and the other side's 4.7461 are
                // both legitimate results (colour-science's tests skip this pair).
                assert!(
                    (d - 4.8045).abs() < tol::SHARMA || (d - 4.7461).abs() < tol::SHARMA,
                    "pair 14: {d}"
                );
            } else {
                assert!(
                    (d - expected).abs() < tol::SHARMA,
                    "pair {}: got {d}, expected {expected}",
                    i + 1
                );
            }
        }
    }
}

#[test]
fn delta_e2000_edge_cases() {
    let grey = Lab::new(50.0, 0.0, 0.0);
    assert_eq!(grey.delta_e2000(grey), 0.0);
    // Pure lightness difference between greys: ΔL'/S_L only.
    let d = grey.delta_e2000(Lab::new(60.0, 0.0, 0.0));
    let l50 = 25.0; // (55 − 50)²
    let s_l = 1.0 + 0.015 * l50 / (20.0f64 + l50).sqrt();
    assert_abs_diff_eq!(d, 10.0 / s_l, epsilon = tol::DE2000_CLOSED_FORM);
    // Both on the a' = b = 0 axis and one with chroma: C'1·C'2 = 0 path.
    let d = grey.delta_e2000(Lab::new(50.0, 10.0, 0.0));
    assert!(d.is_finite() && d > 0.0);
    assert!(Lab::new(f64::NAN, 0.0, 0.0).delta_e2000(grey).is_nan());
}

fn lab() -> impl Strategy<Value = Lab> {
    (0.0..100.0f64, -128.0..128.0f64, -128.0..128.0f64).prop_map(|(l, a, b)| Lab::new(l, a, b))
}

proptest! {
    #![proptest_config(fixed_seed::config(2000, 0x5EED_0005, "tests/color.proptest-regressions"))]

    #[test]
    fn delta_e2000_is_a_symmetric_non_negative_difference(a in lab(), b in lab()) {
        let ab = a.delta_e2000(b);
        let ba = b.delta_e2000(a);
        prop_assert!(ab >= 0.0);
        prop_assert!((ab - ba).abs() <= tol::SYMMETRY * ab.max(1.0), "{} vs {}", ab, ba);
        prop_assert_eq!(a.delta_e2000(a), 0.0);
        prop_assert_eq!(a.delta_e2000(b), ab);
    }

    #[test]
    fn delta_e2000_zero_on_identical_from_xyz(x in 0.0..1.2f64, y in 0.0..1.2f64, z in 0.0..1.2f64) {
        let white = Xyz::new(0.95047, 1.0, 1.08883);
        let lab_white = WhitePoint::new(white).unwrap();
        let l = Xyz::new(x, y, z).to_lab(lab_white);
        prop_assert_eq!(l.delta_e2000(l), 0.0);
    }
}
