//! Every public colour function on extreme finite inputs: ±0, subnormals, the smallest normal,
//! 1e±300, ±f64::MAX, values next to the formulas' breakpoints, and mixed signs, from a seeded
//! generator (no dependency, the same inputs on every run).
//!
//! Each call must return a finite value or a typed error, with one documented exception: the
//! linear maps (the two matrices, `scale`, `+`, `*`) are plain arithmetic and may return ±∞, but
//! only where the exact value exceeds f64::MAX, never NaN. Every function here is a closed form
//! (no loop depends on its input), so the work per call is bounded by construction; the sweep
//! checks values only.
//!
//! `sweep` runs in well under a second; `sweep_long` (ignored) runs a hundred times as many.

#[path = "support/rng.rs"]
mod rng;
#[path = "support/color_tolerance.rs"]
mod tol;

use diffraction::cie::{cmf, Illuminant};
use diffraction::color::{srgb_decode, srgb_encode, Clip, Lab, LinearSrgb, Srgb, WhitePoint, Xyz};
use diffraction::{Error, ParseError};

/// XYZ → linear sRGB, IEC 61966-2-1 as colour-science 0.4.7 has it (`matrix_XYZ_to_RGB`).
const XYZ_TO_SRGB: [[f64; 3]; 3] = [
    [3.2406, -1.5372, -0.4986],
    [-0.9689, 1.8758, 0.0415],
    [0.0557, -0.2040, 1.0570],
];
/// Linear sRGB → XYZ (`matrix_RGB_to_XYZ`).
const SRGB_TO_XYZ: [[f64; 3]; 3] = [
    [0.4124, 0.3576, 0.1805],
    [0.2126, 0.7152, 0.0722],
    [0.0193, 0.1192, 0.9505],
];

/// Hand-picked extremes; every input of the sweep is drawn from these or from random magnitudes.
const SPECIAL: [f64; 24] = [
    0.0,
    -0.0,
    5e-324,
    -5e-324,
    2.225_073_858_507_201e-308, // largest subnormal
    -2.225_073_858_507_201e-308,
    f64::MIN_POSITIVE,
    1e-300,
    -1e-300,
    0.003_130_8,     // sRGB encode breakpoint
    0.040_45,        // sRGB decode breakpoint
    216.0 / 24389.0, // CIELAB ε
    1.0 - f64::EPSILON,
    -(1.0 - f64::EPSILON),
    1.0,
    -1.0,
    25.0, // the CIEDE2000 chroma constant
    1e50,
    -1e50,
    1e300,
    -1e300,
    f64::MAX,
    -f64::MAX,
    f64::MAX / 2.0,
];

/// Inputs drawn from the tests' seeded generator.
struct Rng(rng::Rng);

impl Rng {
    fn next_u64(&mut self) -> u64 {
        self.0.next_u64()
    }

    /// Half the time a special value, otherwise ±m·10^e with e uniform in [−323, 308] (clamped
    /// to a finite value): subnormals, tiny, ordinary and huge magnitudes of either sign.
    fn value(&mut self) -> f64 {
        let r = self.next_u64();
        if r & 1 == 0 {
            return SPECIAL[(r >> 1) as usize % SPECIAL.len()];
        }
        let e = ((r >> 8) % 632) as i32 - 323;
        let m = 1.0 + ((r >> 20) as f64 / (1u64 << 44) as f64) * 9.0;
        let v = (m * 10f64.powi(e)).min(f64::MAX);
        if r & 2 == 0 {
            v
        } else {
            -v
        }
    }

    fn triple(&mut self) -> [f64; 3] {
        [self.value(), self.value(), self.value()]
    }
}

/// `m · v` evaluated with every product scaled by 2⁻⁶⁴ (exact for these magnitudes except where
/// it underflows, which only loses values far below the threshold): its magnitude times 2⁶⁴ is
/// the exact value to rounding, and cannot overflow.
fn scaled_rows(m: &[[f64; 3]; 3], v: [f64; 3]) -> [f64; 3] {
    let s = 2f64.powi(-64);
    m.map(|w| w[0] * (v[0] * s) + w[1] * (v[1] * s) + w[2] * (v[2] * s))
}

/// A linear map's result `got` for the exact value `scaled · 2⁶⁴`: never NaN; ±∞ only when the
/// exact value is at least f64::MAX (to a relative 1e-12, the rounding of the scaled sum).
fn check_linear(what: &str, input: [f64; 3], got: [f64; 3], scaled: [f64; 3]) {
    let limit = f64::MAX * 2f64.powi(-64) * (1.0 - 1e-12);
    for (g, s) in got.into_iter().zip(scaled) {
        assert!(!g.is_nan(), "{what}({input:?}) = {got:?}: NaN");
        if g.is_infinite() {
            assert!(
                s.abs() >= limit && g.signum() == s.signum(),
                "{what}({input:?}) = {got:?}: infinite, but the exact value is {s:e}·2^64"
            );
        }
    }
}

fn finite(what: &str, input: impl core::fmt::Debug, vals: &[f64]) {
    for v in vals {
        assert!(v.is_finite(), "{what}({input:?}) = {vals:?}: not finite");
    }
}

#[derive(Default)]
struct Counts {
    calls: u64,
    errors: u64,
    infinite_linear: u64,
    chromaticities: u64,
}

fn whites(rng: &mut Rng) -> (Xyz, Result<WhitePoint, Error>) {
    let w = Xyz::new(rng.value().abs(), rng.value().abs(), rng.value().abs());
    let w = if rng.next_u64() % 8 == 0 {
        // Sometimes a signed or zero component, which must be rejected.
        Xyz::new(rng.value(), w.y, w.z)
    } else {
        w
    };
    (w, WhitePoint::new(w))
}

fn run(seed: u64, iterations: u64) -> Counts {
    let mut rng = Rng(rng::Rng(seed));
    let mut n = Counts::default();
    let d65 = WhitePoint::new(Xyz::new(
        0.950_470_713_436_261_4,
        1.0,
        1.088_815_180_633_995_6,
    ))
    .expect("D65 is a valid white");
    for _ in 0..iterations {
        let v = rng.triple();
        let xyz = Xyz::new(v[0], v[1], v[2]);
        let lin = LinearSrgb::new(v[0], v[1], v[2]);

        // Linear maps: plain overflow only.
        let r = xyz.to_linear_srgb();
        check_linear(
            "to_linear_srgb",
            v,
            [r.r, r.g, r.b],
            scaled_rows(&XYZ_TO_SRGB, v),
        );
        let x = lin.to_xyz();
        check_linear("to_xyz", v, [x.x, x.y, x.z], scaled_rows(&SRGB_TO_XYZ, v));
        let k = rng.value();
        let s = xyz.scale(k);
        let half_exact = v.map(|c| (c * 0.5) * k); // the exact product halved, or ±∞ if ≥ 2·MAX
        for (g, h) in [s.x, s.y, s.z].into_iter().zip(half_exact) {
            assert!(!g.is_nan(), "scale({v:?}, {k:e})");
            assert!(!g.is_infinite() || h.abs() >= f64::MAX * 0.5 * (1.0 - 1e-15));
        }
        assert_eq!(xyz * k, s);
        let w = rng.triple();
        let sum = xyz + Xyz::new(w[0], w[1], w[2]);
        let lsum = lin + LinearSrgb::new(w[0], w[1], w[2]);
        for ((g, l), (a, b)) in [sum.x, sum.y, sum.z]
            .into_iter()
            .zip([lsum.r, lsum.g, lsum.b])
            .zip(v.into_iter().zip(w))
        {
            assert!(!g.is_nan() && g.to_bits() == l.to_bits(), "{a:e} + {b:e}");
            assert!(!g.is_infinite() || (a * 0.5 + b * 0.5).abs() >= f64::MAX * 0.5);
        }
        n.infinite_linear += [r.r, r.g, r.b, x.x, x.y, x.z]
            .iter()
            .filter(|c| c.is_infinite())
            .count() as u64;
        n.calls += 6;

        // Everything else: finite.
        finite("luminance", v, &[lin.luminance()]);
        if let Some((cx, cy)) = xyz.chromaticity() {
            n.chromaticities += 1;
            finite("chromaticity", v, &[cx, cy]);
        }
        for method in Clip::ALL {
            let c = lin.clip(method);
            assert!(c.is_in_gamut(), "clip({v:?}, {method}) = {c:?}");
            let _ = c.encode().to_rgb8();
        }
        let e = lin.encode();
        finite("encode", v, &[e.r, e.g, e.b]);
        let d = Srgb::new(v[0], v[1], v[2]).decode();
        finite("decode", v, &[d.r, d.g, d.b]);
        for c in v {
            finite("srgb_encode", c, &[srgb_encode(c)]);
            finite("srgb_decode", c, &[srgb_decode(c)]);
            assert!(
                srgb_encode(c) * c >= 0.0 && srgb_decode(c) * c >= 0.0,
                "sign of {c:e}"
            );
        }
        let _ = Srgb::new(v[0], v[1], v[2]).to_rgb8();
        let _ = lin.is_in_gamut();
        n.calls += 13;

        let lab = xyz.to_lab(d65);
        finite("to_lab(D65)", v, &[lab.l, lab.a, lab.b]);
        let (white, wp) = whites(&mut rng);
        match wp {
            Ok(wp) => {
                let l = xyz.to_lab(wp);
                finite("to_lab", (v, white), &[l.l, l.a, l.b]);
                let de = l.delta_e2000(lab);
                finite("delta_e2000", (l, lab), &[de]);
                assert!(de >= 0.0);
            }
            Err(err) => {
                n.errors += 1;
                let bad = [
                    ("white.x", white.x),
                    ("white.y", white.y),
                    ("white.z", white.z),
                ]
                .into_iter()
                .find(|&(_, c)| c.is_nan() || c <= 0.0)
                .expect("a white with positive components is accepted");
                assert_eq!(err.parameter(), bad.0, "{white:?}");
                assert_eq!(err.value().to_bits(), bad.1.to_bits());
            }
        }
        let (p, q) = (Lab::new(v[0], v[1], v[2]), Lab::new(w[0], w[1], w[2]));
        let de = p.delta_e2000(q);
        finite("delta_e2000", (p, q), &[de]);
        assert!(de >= 0.0, "{p:?}.delta_e2000({q:?}) = {de}");
        n.calls += 5;

        // The CIE tables at any wavelength.
        let nm = rng.value();
        for ill in [Illuminant::E, Illuminant::D65, Illuminant::A] {
            let e = ill.power(nm);
            assert!(e.is_finite() && e >= 0.0, "{ill}.power({nm:e}) = {e}");
        }
        let c = cmf(nm);
        assert!(c.iter().all(|v| v.is_finite() && *v >= 0.0), "cmf({nm:e})");
        n.calls += 4;
    }

    // The names: every parse is a value or a ParseError.
    for s in [
        "", "clamp", "CLAMP", "constant", "A", "d65", "D50", "\u{0}", "é", "a:b",
    ] {
        let r: Result<Clip, ParseError> = s.parse();
        assert!(r.is_ok() || r.unwrap_err().what() == "clipping scheme");
        let r: Result<Illuminant, ParseError> = s.parse();
        assert!(r.is_ok() || r.unwrap_err().what() == "illuminant");
        n.calls += 2;
    }
    n
}

#[test]
fn sweep() {
    let n = run(0x00C0_10C0_1DE5, 20_000);
    println!(
        "{} calls, {} typed errors, {} infinite components of linear maps, {} chromaticities",
        n.calls, n.errors, n.infinite_linear, n.chromaticities
    );
    assert!(
        n.errors > 0 && n.infinite_linear > 0,
        "the generator reaches both edges"
    );
    // Most of the 20 000 colours have a chromaticity (measured 19 840); only sums that cancel
    // or overflow have none, so its finiteness check is not vacuous.
    assert!(2 * n.chromaticities >= 20_000, "{}", n.chromaticities);
}

#[test]
#[ignore = "a hundred times the inputs of `sweep` (about a minute in a debug build)"]
fn sweep_long() {
    let n = run(0x5EED_0000_0002, 2_000_000);
    println!("{} calls, {} typed errors", n.calls, n.errors);
}

/// The edges named in the docs, each side of them.
#[test]
fn documented_edges() {
    // srgb_decode saturates where 1.055·MAX^(1/2.4) − 0.055 ≈ 2.9e128 is passed.
    let edge = 1.055 * f64::MAX.powf(1.0 / 2.4) - 0.055;
    assert!(srgb_decode(edge * 0.99) < f64::MAX);
    assert!(srgb_decode(edge * 0.99) > 1e307);
    assert_eq!(srgb_decode(edge * 1.01), f64::MAX);
    assert_eq!(srgb_decode(-1e300), -f64::MAX);
    // srgb_encode of the largest value: MAX^(1/2.4) ≈ 1.5e128.
    let top = srgb_encode(f64::MAX);
    assert!((top / (1.055 * f64::MAX.powf(1.0 / 2.4)) - 1.0).abs() < tol::EXTREME_CLOSED_FORM);

    // A CIELAB white with a zero, negative, or non-finite component is an error naming it.
    for (white, name) in [
        (Xyz::new(0.0, 1.0, 1.0), "white.x"),
        (Xyz::new(1.0, -0.0, 1.0), "white.y"),
        (Xyz::new(1.0, 1.0, f64::INFINITY), "white.z"),
    ] {
        assert_eq!(WhitePoint::new(white).unwrap_err().parameter(), name);
    }
    // The smallest valid white: ratios overflow and go through ∛X / ∛Xn.
    let tiny = WhitePoint::new(Xyz::new(5e-324, 5e-324, 5e-324)).unwrap();
    let lab = Xyz::new(1.0, 1.0, 1.0).to_lab(tiny);
    let f = 1.0 / 5e-324f64.cbrt();
    assert!(
        (lab.l - (116.0 * f - 16.0)).abs() <= tol::EXTREME_CLOSED_FORM * lab.l,
        "{lab:?}"
    );
    assert_eq!((lab.a, lab.b), (0.0, 0.0));
    // Large negative components saturate.
    let lab = Xyz::new(-f64::MAX, 0.0, 0.0).to_lab(tiny);
    assert_eq!(lab.a, -f64::MAX);

    // ΔE2000 is computed for components up to 1e150 and clamped beyond: a = 1e50 is finite, and
    // two colours that differ only beyond the clamp have ΔE2000 = 0.
    let grey = Lab::new(50.0, 0.0, 0.0);
    assert!(Lab::new(50.0, 1e50, 0.0).delta_e2000(grey).is_finite());
    assert_eq!(
        Lab::new(50.0, 1e200, 0.0).delta_e2000(Lab::new(50.0, f64::MAX, 0.0)),
        0.0
    );

    // chromaticity: a sum that nearly cancels has no representable chromaticity.
    let e = f64::EPSILON;
    assert_eq!(Xyz::new(1.0 - e, -(1.0 - e), -5e-324).chromaticity(), None);
    assert_eq!(
        Xyz::new(f64::MAX, f64::MAX, 0.0).chromaticity(),
        Some((0.5, 0.5))
    );

    // The matrices: ∞ only beyond f64::MAX, and a cancelling pair of huge products is exact.
    let r = Xyz::new(f64::MAX, f64::MAX, 0.0).to_linear_srgb();
    assert_eq!(r.r, f64::INFINITY); // (3.2406 − 1.5372)·MAX > MAX
                                    // −0.9689 + 1.8758 = 0.9069 and 0.0557 − 0.2040 = −0.1483: finite although both products
                                    // of each row are near f64::MAX.
    assert!(
        (r.g / f64::MAX - 0.9069).abs() < tol::EXTREME_CLOSED_FORM,
        "{r:?}"
    );
    assert!(
        (r.b / f64::MAX + 0.1483).abs() < tol::EXTREME_CLOSED_FORM,
        "{r:?}"
    );
}
