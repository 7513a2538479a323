//! The paper's renderer's reading of a scene: its grating models (the paper's Agu-Hill model,
//! and the baselines Thorman and, with the `stam` feature, Stam), the `[environment]`, and each
//! grating's exposure.

use std::collections::HashMap;

use diffraction::color::Xyz;
use diffraction::spectrum::Spectral;
#[cfg(feature = "stam")]
use diffraction::Stam;
use diffraction::{AguHill, DiffractionBrdf, Grating, SpectralResponse, Thorman};
use glam::DVec3;

use crate::budget::Integrand;
use crate::colour::Colour;
use crate::diagnostics::{Check, FieldError};
use crate::limits::{self, check, count};
use crate::material::{model_error, Material};
use crate::scene::{vec3, Light, Physics};
use crate::schema::{RawGrating, RawScene};

/// The diffraction model of a grating material (the scene's `model` key).
#[derive(Debug, Clone)]
pub enum Model {
    /// The paper's model (its eq. 12 coefficients are the material's `shading`).
    AguHill(AguHill),
    /// Thorman's: peak directions only, every order equally bright.
    Thorman(Thorman),
    /// Stam's Fourier optics (sinusoidal or binary profile).
    #[cfg(feature = "stam")]
    Stam(Stam),
}

/// A model with its value and its colour (`dyn` needs one trait for both).
pub trait Reflects: DiffractionBrdf + SpectralResponse {}
impl<M: DiffractionBrdf + SpectralResponse> Reflects for M {}

impl Model {
    /// The model, for its value and its colour.
    pub fn brdf(&self) -> &dyn Reflects {
        match self {
            Model::AguHill(m) => m,
            Model::Thorman(m) => m,
            #[cfg(feature = "stam")]
            Model::Stam(m) => m,
        }
    }

    /// How the crate integrates the model's colour (for the work estimate).
    pub fn integrand(&self) -> Integrand {
        match self {
            Model::AguHill(m) => Integrand::Grating(*m.grating()),
            Model::Thorman(m) => Integrand::Thorman(m.period_nm()),
            #[cfg(feature = "stam")]
            Model::Stam(m) => Integrand::Stam(m.period_nm()),
        }
    }

    /// The diffraction term's colour for local directions `wo` (toward the eye) and `wi`
    /// (toward the light), z the normal and x the grating vector, by `colour`, times
    /// `exposure`: for Agu-Hill (a function of u = wi.x + wo.x alone) the crate's lobe-exact
    /// grating paths `Spectral::xyz` (or the paper's peak colours `Spectral::paper_peaks`); for
    /// the others the generic path `Spectral::xyz_brdf` with the strategy's generic rule (or
    /// `Spectral::paper_peaks_brdf`).
    pub fn xyz(
        &self,
        spectral: &Spectral,
        wo: DVec3,
        wi: DVec3,
        colour: Colour,
        exposure: f64,
    ) -> Xyz {
        let xyz = match (self, colour) {
            (Model::AguHill(m), Colour::Integral(s)) => spectral.xyz(m.grating(), wi.x + wo.x, s),
            (Model::AguHill(m), Colour::Paper) => spectral.paper_peaks(m.grating(), wi.x + wo.x),
            (other, _) => match colour.generic() {
                Some(rule) => spectral.xyz_brdf(other.brdf(), wo, wi, rule),
                None => spectral.paper_peaks_brdf(other.brdf(), wo, wi),
            },
        };
        xyz.scale(exposure)
    }
}

/// The paper's light: the sky and the ambient light of eq. 12 (linear sRGB), from
/// `[environment]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Environment {
    /// Sky colour at the horizon and straight up.
    pub background: DVec3,
    pub zenith: DVec3,
    /// Ambient light.
    pub ambient: DVec3,
}

/// The scenes of the paper's renderer: no physical units, gratings of the paper's model or
/// its baselines.
#[derive(Debug, Clone, Copy)]
pub struct Paper;

impl Physics for Paper {
    type Grating = Model;
    type Units = Environment;

    fn accepts(raw: &RawScene) -> Check<()> {
        match raw.radiometry {
            Some(_) => Err(FieldError::new(
                "radiometry",
                "a scene in physical units (a [radiometry] table) is the path tracer's",
            )),
            None => Ok(()),
        }
    }

    fn grating(name: &str, g: &RawGrating, period: f64, path: &str) -> Check<Model> {
        let f = |name: &str| format!("{path}.{name}");
        let crate_error = |e| model_error(g, path, e);
        match name {
            "agu-hill" => {
                let width = check(
                    &f("slit_width_nm"),
                    g.slit_width_nm.unwrap_or(period / 2.0),
                    limits::SLIT_WIDTH_NM,
                )?;
                let slits = g.slits.unwrap_or(1000);
                count(&f("slits"), slits, 1, limits::SLITS.max as u64)?;
                let grating = Grating::new(period, width, slits as u32).map_err(crate_error)?;
                Ok(Model::AguHill(AguHill::new(grating)))
            }
            "thorman" => {
                let lobe = check(
                    &f("lobe_width"),
                    g.lobe_width.unwrap_or(0.005),
                    limits::LOBE_WIDTH,
                )?;
                Ok(Model::Thorman(
                    Thorman::new(period, lobe).map_err(crate_error)?,
                ))
            }
            "radiometric" => Err(FieldError::new(
                f("model"),
                "model \"radiometric\" needs a [radiometry] table (the camera's exposure)",
            )),
            _ => {
                for (key, v, range) in [
                    ("depth_nm", g.depth_nm, limits::DEPTH_NM),
                    ("fraction", g.fraction, limits::FRACTION),
                    ("coherence_nm", g.coherence_nm, limits::COHERENCE_NM),
                    ("reflectance", g.reflectance, limits::FRACTION),
                ] {
                    if let Some(v) = v {
                        check(&f(key), v, range)?;
                    }
                }
                stam_model(g, path, name, period, &crate_error)
            }
        }
    }

    fn units(
        raw: &RawScene,
        _: &[Light],
        _: &[Material<Model>],
        _: &Spectral,
    ) -> Check<Environment> {
        let env = &raw.environment;
        let color = |path: &str, v: [f64; 3]| vec3(path, v, limits::COLOR);
        let background = color(
            "environment.background",
            env.background.unwrap_or([0.05, 0.05, 0.06]),
        )?;
        let zenith = match env.zenith {
            Some(z) => color("environment.zenith", z)?,
            None => background,
        };
        let ambient = color(
            "environment.ambient",
            env.ambient.unwrap_or([0.1, 0.1, 0.1]),
        )?;
        Ok(Environment {
            background,
            zenith,
            ambient,
        })
    }
}

/// `stam-sine` or `stam-binary`: depth_nm (default 100), coherence_nm (default 10 periods),
/// fraction (binary, default 0.5), reflectance (default 1).
#[cfg(feature = "stam")]
fn stam_model(
    g: &RawGrating,
    _: &str,
    name: &str,
    period: f64,
    crate_error: &dyn Fn(diffraction::Error) -> FieldError,
) -> Check<Model> {
    use diffraction::Profile;
    let profile = match name {
        "stam-sine" => Profile::Sine,
        _ => Profile::Binary {
            fraction: g.fraction.unwrap_or(0.5),
        },
    };
    let stam = Stam::new(
        profile,
        period,
        g.depth_nm.unwrap_or(100.0),
        g.coherence_nm.unwrap_or(10.0 * period),
    )
    .and_then(|s| s.with_reflectance(g.reflectance.unwrap_or(1.0)))
    .map_err(crate_error)?;
    Ok(Model::Stam(stam))
}

#[cfg(not(feature = "stam"))]
fn stam_model(
    _: &RawGrating,
    path: &str,
    name: &str,
    _: f64,
    _: &dyn Fn(diffraction::Error) -> FieldError,
) -> Check<Model> {
    Err(FieldError::new(
        format!("{path}.model"),
        format!(
            "model \"{name}\" needs the crate feature `stam`: build with `--features stam` \
             (e.g. cargo run --release -p diffraction-render --features stam --bin raytrace -- ...)"
        ),
    ))
}

/// The exposures of the distinct (model, scan strategy) pairs of a scene's materials, each
/// scanned once: per material, its grating's exposure (1 without a grating).
pub fn exposures(spectral: &Spectral, materials: &[Material<Model>]) -> Vec<f64> {
    let mut seen: HashMap<String, f64> = HashMap::new();
    materials
        .iter()
        .map(|m| match &m.grating {
            None => 1.0,
            Some(g) => {
                // Debug prints every parameter exactly (shortest round-trip floats); the scan
                // depends on the strategy through `exposure_strategy` only.
                let key = format!("{:?} {:?}", g.model, exposure_strategy(g.strategy));
                *seen
                    .entry(key)
                    .or_insert_with(|| model_exposure(spectral, &g.model, g.strategy))
            }
        })
        .collect()
}

/// The strategy used to measure a grating's exposure when rendering with `strategy`.
///
/// The peak search is cheap (O(visible orders)) and accurate to O(1/N), so it measures the
/// exposure for every strategy that estimates the spectral integral; the paper's peak colours
/// are normalised differently (each peak has weight S(β_m), about 1) and are measured with
/// themselves.
pub fn exposure_strategy(colour: Colour) -> Colour {
    match colour {
        Colour::Paper => Colour::Paper,
        Colour::Integral(_) => Colour::DEFAULT,
    }
}

/// Number of u values scanned by [`exposure`].
pub const EXPOSURE_SCAN: usize = 4000;

/// The exposure of a grating's diffraction term: `1 / max Y(u)` over the diffracted orders,
/// computed once per distinct grating before rendering.
///
/// With the paper's 1/N² normalisation the peak of every order is 1 but its width is about
/// λ/(|m|·N), so the colour an order integrates to, XYZ(u) = ∫ E·I(u, λ)·cmf dλ / ∫ E·ȳ dλ, is
/// about 1/N as bright as a white reflector (Y ≈ 5·10⁻⁴ for N = 1000). Scaling the diffraction
/// XYZ by this exposure gives the grating's brightest **diffracted** colour Y = 1, the crate's
/// convention for colour errors too, whatever N is; the relative brightness of the orders and
/// the hues are the integral's.
///
/// The scan covers u ∈ [-2, 2] at [`EXPOSURE_SCAN`] points with the cheap peak search, but
/// leaves out |u| < λ_min/(2d), the neighbourhood of the order-0 (mirror) lobe: there
/// I(u, λ) ≈ 1 at every wavelength, Y ≈ 1, and including it would always give exposure 1. The
/// mirror highlight of a light is therefore `exposure` times overexposed, as a real grating's
/// zeroth order is next to its faint spectra. With the paper's own peak colours
/// (`Colour::Paper`, weights about 1) the exposure comes out near 1 and changes little.
pub fn exposure(spectral: &Spectral, grating: &Grating, colour: Colour) -> f64 {
    let colour = exposure_strategy(colour);
    let u_min = diffraction::Band::VISIBLE.min_nm() / (2.0 * grating.period_nm());
    let mut max_y: f64 = 0.0;
    for i in 0..=EXPOSURE_SCAN {
        let u = -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64;
        if u.abs() < u_min {
            continue;
        }
        let y = match colour {
            Colour::Integral(s) => spectral.xyz(grating, u, s).y,
            Colour::Paper => spectral.paper_peaks(grating, u).y,
        };
        max_y = max_y.max(y);
    }
    exposure_of(max_y)
}

/// `1 / max_y`, at most [`crate::limits::MAX_EXPOSURE`]; 1 when nothing diffracted is seen.
fn exposure_of(max_y: f64) -> f64 {
    if max_y > 0.0 && max_y.is_finite() {
        (1.0 / max_y).min(crate::limits::MAX_EXPOSURE)
    } else {
        1.0
    }
}

/// The exposure of any model: as [`exposure`] (the same for Agu-Hill), scanning the Littrow
/// configuration wi = wo = (u/2, 0, √(1 − u²/4)), which reaches every u in (−2, 2) on the plane
/// of the diffracted cone (v = 0, where Stam's lobes are).
pub fn model_exposure(spectral: &Spectral, model: &Model, colour: Colour) -> f64 {
    let period = match model {
        Model::AguHill(m) => return exposure(spectral, m.grating(), colour),
        Model::Thorman(m) => m.period_nm(),
        #[cfg(feature = "stam")]
        Model::Stam(m) => m.period_nm(),
    };
    let colour = exposure_strategy(colour);
    let u_min = diffraction::Band::VISIBLE.min_nm() / (2.0 * period);
    let mut max_y: f64 = 0.0;
    for i in 0..=EXPOSURE_SCAN {
        let u = -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64;
        if u.abs() < u_min || u.abs() >= 2.0 {
            continue;
        }
        let w = DVec3::new(0.5 * u, 0.0, (1.0 - 0.25 * u * u).sqrt());
        max_y = max_y.max(model.xyz(spectral, w, w, colour, 1.0).y);
    }
    exposure_of(max_y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use diffraction::cie::Illuminant;
    use diffraction::spectrum::Strategy;

    #[test]
    fn exposure_brings_the_brightest_order_to_one() {
        let spectral = Spectral::new(Illuminant::D65);
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        let k = exposure(&spectral, &g, Colour::DEFAULT);
        // About N / (λ·…): hundreds for N = 1000.
        assert!(k > 100.0 && k < 10_000.0, "{k}");
        let brightest = (0..=EXPOSURE_SCAN)
            .map(|i| -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64)
            .filter(|u: &f64| u.abs() > 0.2)
            .map(|u| spectral.xyz(&g, u, Strategy::PEAK_SEARCH).y * k)
            .fold(0.0, f64::max);
        assert!((brightest - 1.0).abs() < 1e-9);
        let paper = exposure(&spectral, &g, Colour::Paper);
        assert!(paper > 0.3 && paper < 3.0, "{paper}");
        // The generic scan agrees with the grating's for Agu-Hill, and brings Thorman's
        // brightest diffracted colour to 1 too.
        let m = Model::AguHill(AguHill::new(g));
        assert_eq!(model_exposure(&spectral, &m, Colour::Paper), paper);
        let t = Model::Thorman(Thorman::new(1600.0, 0.003).unwrap());
        let k = model_exposure(&spectral, &t, Colour::DEFAULT);
        assert!(k > 1.0 && k.is_finite(), "{k}");
    }
}
