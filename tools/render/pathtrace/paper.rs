//! The paper's scenes (fig4a … fig6: no `[radiometry]` table, gratings of model "agu-hill") in
//! physical units, so that the path tracer renders them too. The mapping, once, here:
//!
//! * **Camera**: `exposure` = 1/∫ s·ȳ dλ, so that a radiance of 1 at 560 nm (spectrum s of the
//!   scene's illuminant) shows as Y = 1, the paper's white.
//! * **Lights**: the paper's light of intensity I (no fall-off with distance: eq. 12 lights every
//!   point by I·cos θ) becomes the emitter that gives the same irradiance, I·cos θ, at the
//!   reference distance r₀ = |light − camera.look_at| (the middle of the picture), and falls off
//!   as 1/r² around it: a point light has the radiant intensity π·I·r₀² (W·sr⁻¹·nm⁻¹ at 560 nm,
//!   scene lengths read as metres; the π makes a white Lambertian of albedo 1 show I, as k_d·I
//!   does in the paper), a spherical light of radius R the radiance I·r₀²/R². A coloured light
//!   keeps its luminance (0.2126 r + 0.7152 g + 0.0722 b) and loses its chroma: an emitter's
//!   spectrum is the illuminant's.
//! * **Ambient**: the paper's ambient term k_a·I_a·albedo becomes a uniform sky of radiance
//!   Y(I_a) (luminance, as the lights'): an unoccluded Lambertian of albedo ρ reflects ρ·Y(I_a)
//!   of it, the paper's term with k_a = 1. Unlike the paper's ambient term, this light is
//!   shadowed (corners and the undersides of objects are darker) and the materials' `ambient`
//!   coefficients are not used; the sky seen directly is that grey too, not the paper's
//!   `background` and `zenith` colours. The Whitted integrator leaves the sky's light out.
//! * **Materials**: the diffuse term k_d·colour is the Lambertian albedo (box-upsampled to a
//!   reflectance spectrum, [`crate::radiometry`]); `mirror` and `mirror_color` are the same;
//!   the scene is refused if a material would not be passive.
//! * **Gratings**: model "agu-hill" becomes the crate's `GratingBsdf` of the same grating (d, w,
//!   N): the paper's N-slit intensity read as an energy-normalised amplitude grating, albedo at
//!   most w/d. The paper's I(u, λ) does not depend on the direction along the grooves; the
//!   radiometric grating needs a finite spread there, the widest Gaussian the crate accepts
//!   ([`PAPER_GROOVE_SIGMA`] in v), so a point light lights a band across the grating as in the
//!   paper. The paper's per-material exposure (the brightest order shown at Y = 1) and the
//!   `diffraction` coefficient have no counterpart: a grating is as bright as the light it
//!   diffracts, so the orders are dimmer or brighter than the paper's where the physics says so,
//!   and order 0 (the mirror image of the light) is as bright as a mirror's. Other models
//!   (thorman, stam-*) have no radiometric reading and are refused.

use diffraction::groove::MAX_GROOVE_SIGMA;
use diffraction::{Grating, GratingBsdf, GrooveSpread};
use glam::DVec3;

use crate::diagnostics::{Check, FieldError};
use crate::limits::{self, count, RADIOMETRIC_SLITS};
use crate::material::model_error;
use crate::radiometry::Radiometry;
use crate::scene::{vec3, Light};
use crate::schema::{RawGrating, RawRadiometry, RawScene};

/// The spread along the grooves of a paper grating's radiometric reading: a Gaussian of this
/// standard deviation in v = (wi + wo)·groove, the widest the crate accepts.
pub const PAPER_GROOVE_SIGMA: f64 = MAX_GROOVE_SIGMA;

/// The luminance of a linear-sRGB colour.
fn luminance(c: DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The radiometric grating of a paper grating (model "agu-hill"): the same d, w (default d/2)
/// and N (default 1000), spread along the grooves by [`PAPER_GROOVE_SIGMA`].
pub fn grating(g: &RawGrating, period: f64, path: &str) -> Check<GratingBsdf> {
    let slits = count(
        &format!("{path}.slits"),
        g.slits.unwrap_or(1000),
        1,
        RADIOMETRIC_SLITS,
    )?;
    let grating = Grating::new(
        period,
        g.slit_width_nm.unwrap_or(period / 2.0),
        slits as u32,
    )
    .map_err(|e| model_error(g, path, e))?;
    let spread = GrooveSpread::gaussian(PAPER_GROOVE_SIGMA)
        .map_err(|e| FieldError::new(path, e.to_string()))?;
    Ok(GratingBsdf::new(grating).with_groove(spread))
}

/// The physical units of a paper scene (see the [module docs](self)).
pub fn units(
    raw: &RawScene,
    lights: &[Light],
    spectrum: diffraction::cie::Illuminant,
) -> Check<Radiometry> {
    let look_at = DVec3::from_array(raw.camera.look_at);
    let ambient = raw.environment.ambient.unwrap_or([0.1, 0.1, 0.1]);
    let ambient = vec3("environment.ambient", ambient, limits::COLOR)?;
    let sky = luminance(ambient);
    // The emitters' scales, then the exposure from the illuminant's ∫ s·ȳ.
    let keys: Vec<(DVec3, f64)> = lights
        .iter()
        .map(|l| {
            let i = luminance(l.color);
            let r0 = (l.position - look_at).length().max(1e-9);
            let scale = if l.radius > 0.0 {
                i * (r0 / l.radius).powi(2)
            } else {
                std::f64::consts::PI * i * r0 * r0
            };
            (DVec3::ONE, scale)
        })
        .collect();
    let table = RawRadiometry {
        exposure: 1.0,
        sky_horizon: Some(sky),
        sky_zenith: Some(sky),
    };
    let mut units = Radiometry::new(&table, lights, &keys, spectrum)?;
    units.exposure = 1.0 / units.ys;
    units.from_paper = true;
    Ok(units)
}
