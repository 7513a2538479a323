//! Materials: a diffuse colour source (solid, wood, image), optional mirror reflection, and for
//! diffraction gratings one of the crate's models (the paper's Agu-Hill model, or the baselines
//! Thorman and, with the `stam` feature, Stam) with a grating-direction field.

use std::sync::Arc;

use diffraction::color::Xyz;
use diffraction::frame::{GratingField, Tile};
use diffraction::spectrum::{Spectral, Strategy};
#[cfg(feature = "stam")]
use diffraction::Stam;
use diffraction::{AguHill, DiffractionBrdf, Grating, Illumination, Thorman};
use glam::DVec3;

use crate::geometry::{Hit, Part};
use crate::texture::{ImageTexture, Wood};

/// Where the diffuse colour of a surface comes from.
#[derive(Debug, Clone)]
pub enum Albedo {
    Solid(DVec3),
    Wood(Wood),
    /// An image on the side of a cylinder (a can's label); `other` colours the caps and any
    /// other part.
    Image {
        texture: Arc<ImageTexture>,
        other: DVec3,
    },
}

impl Albedo {
    pub fn at(&self, hit: &Hit) -> DVec3 {
        match self {
            Albedo::Solid(c) => *c,
            Albedo::Wood(w) => w.albedo(hit.object_point),
            Albedo::Image { texture, other } => match hit.part {
                Part::Side | Part::Face => texture.sample(hit.uv),
                Part::Cap => *other,
            },
        }
    }
}

/// A surface material.
#[derive(Debug, Clone)]
pub struct Material {
    pub albedo: Albedo,
    /// The coefficients of the paper's eq. 12 (k_a, k_d, k_diffraction), validated by the
    /// crate: the only place they are kept.
    pub shading: Illumination,
    /// Fraction of perfect mirror reflection (0: none), tinted by `mirror_tint`.
    pub mirror: f64,
    pub mirror_tint: DVec3,
    /// The diffraction grating, for diffractive materials; `None` costs nothing spectral.
    pub grating: Option<GratingMaterial>,
}

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
    /// The energy-normalised grating in physical units (scenes with `[radiometry]`).
    Radiometric(Box<diffraction::GratingBsdf>),
}

impl Model {
    /// The model as a BRDF.
    pub fn brdf(&self) -> &dyn DiffractionBrdf {
        match self {
            Model::AguHill(m) => m,
            Model::Thorman(m) => m,
            #[cfg(feature = "stam")]
            Model::Stam(m) => m,
            Model::Radiometric(m) => m.as_ref(),
        }
    }
}

/// A diffraction grating material: the paper's illumination model (eq. 12) with one of the
/// crate's diffraction models, over a field of grating directions.
#[derive(Debug, Clone)]
pub struct GratingMaterial {
    /// The diffraction model.
    pub model: Model,
    /// The grating vector across the surface (constant, twisted, radial, checkerboard).
    pub field: GratingField,
    /// How the spectral integral is evaluated.
    pub strategy: Strategy,
    /// Scale of the diffraction XYZ, see [`exposure`].
    pub exposure: f64,
    /// The diffuse colour of the plain (non-grating) squares of a checkerboard.
    pub plain_albedo: DVec3,
}

impl GratingMaterial {
    /// The diffraction term's colour for local directions `wi`, `wo` (z the normal, x the
    /// grating vector): k_diffraction · exposure · XYZ, with `k_diffraction` from the material's
    /// [`Illumination`]. Agu-Hill depends on u = wi.x + wo.x only
    /// and takes the lobe-exact paths of `Spectral::xyz`; the other models go through
    /// `Spectral::xyz_brdf` (with cos θi for Stam, a BRDF).
    pub fn xyz(&self, spectral: &Spectral, wi: DVec3, wo: DVec3, k_diffraction: f64) -> Xyz {
        let xyz = match &self.model {
            Model::AguHill(m) => spectral.xyz(m.grating(), wi.x + wo.x, self.strategy),
            other => spectral.xyz_brdf(other.brdf(), wi, wo, self.strategy),
        };
        xyz.scale(k_diffraction * self.exposure)
    }

    /// Whether the field has a grating at the tangent point `p` (not a plain square).
    pub fn is_plain_at(&self, p: glam::DVec2) -> bool {
        matches!(self.field.tile_at(p), Tile::Plain)
    }
}

/// The strategy used to measure a grating's exposure when rendering with `strategy`.
///
/// The peak search is cheap (O(visible orders)) and accurate to O(1/N), so it measures the
/// exposure for every strategy that estimates the spectral integral; the paper's peak colours
/// are normalised differently (each peak has weight S(β_m), about 1) and are measured with
/// themselves.
fn exposure_strategy(strategy: Strategy) -> Strategy {
    match strategy {
        Strategy::PaperPeaks => Strategy::PaperPeaks,
        _ => Strategy::PeakSearch { refine: false },
    }
}

/// Number of u values scanned by [`exposure`].
pub const EXPOSURE_SCAN: usize = 4000;

/// The exposure of a grating's diffraction term: `1 / max Y(u)` over the diffracted orders,
/// computed once per material when the scene is loaded.
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
/// (`Strategy::PaperPeaks`, weights about 1) the exposure comes out near 1 and changes little.
pub fn exposure(spectral: &Spectral, grating: &Grating, strategy: Strategy) -> f64 {
    let strategy = exposure_strategy(strategy);
    let u_min = diffraction::Band::VISIBLE.min_nm() / (2.0 * grating.period_nm());
    let mut max_y: f64 = 0.0;
    for i in 0..=EXPOSURE_SCAN {
        let u = -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64;
        if u.abs() < u_min {
            continue;
        }
        max_y = max_y.max(spectral.xyz(grating, u, strategy).y);
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
pub fn model_exposure(spectral: &Spectral, model: &Model, strategy: Strategy) -> f64 {
    let (brdf, period) = match model {
        Model::AguHill(m) => return exposure(spectral, m.grating(), strategy),
        // Physical units: the light and the camera set the brightness.
        Model::Radiometric(_) => return 1.0,
        Model::Thorman(m) => (m as &dyn DiffractionBrdf, m.period_nm()),
        #[cfg(feature = "stam")]
        Model::Stam(m) => (m as &dyn DiffractionBrdf, m.period_nm()),
    };
    let strategy = exposure_strategy(strategy);
    let u_min = diffraction::Band::VISIBLE.min_nm() / (2.0 * period);
    let mut max_y: f64 = 0.0;
    for i in 0..=EXPOSURE_SCAN {
        let u = -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64;
        if u.abs() < u_min || u.abs() >= 2.0 {
            continue;
        }
        let w = DVec3::new(0.5 * u, 0.0, (1.0 - 0.25 * u * u).sqrt());
        max_y = max_y.max(spectral.xyz_brdf(brdf, w, w, strategy).y);
    }
    exposure_of(max_y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use diffraction::cie::Illuminant;

    #[test]
    fn exposure_brings_the_brightest_order_to_one() {
        let spectral = Spectral::new(Illuminant::D65);
        let g = Grating::new(1600.0, 800.0, 1000).unwrap();
        let k = exposure(&spectral, &g, Strategy::PeakSearch { refine: false });
        // About N / (λ·…): hundreds for N = 1000.
        assert!(k > 100.0 && k < 10_000.0, "{k}");
        let brightest = (0..=EXPOSURE_SCAN)
            .map(|i| -2.0 + 4.0 * i as f64 / EXPOSURE_SCAN as f64)
            .filter(|u: &f64| u.abs() > 0.2)
            .map(|u| {
                spectral
                    .xyz(&g, u, Strategy::PeakSearch { refine: false })
                    .y
                    * k
            })
            .fold(0.0, f64::max);
        assert!((brightest - 1.0).abs() < 1e-9);
        let paper = exposure(&spectral, &g, Strategy::PaperPeaks);
        assert!(paper > 0.3 && paper < 3.0, "{paper}");
        // The generic scan agrees with the grating's for Agu-Hill, and brings Thorman's
        // brightest diffracted colour to 1 too.
        let m = Model::AguHill(AguHill::new(g));
        assert_eq!(model_exposure(&spectral, &m, Strategy::PaperPeaks), paper);
        let t = Model::Thorman(Thorman::new(1600.0, 0.003).unwrap());
        let k = model_exposure(&spectral, &t, Strategy::PeakSearch { refine: false });
        assert!(k > 1.0 && k.is_finite(), "{k}");
    }
}
