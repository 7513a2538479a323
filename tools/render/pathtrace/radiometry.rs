//! Physical units for the path tracer: the scene's `[radiometry]` table, spectral emitters
//! (spherical area lights, point lights, a sky) and the energy-normalised grating
//! (`model = "radiometric"`, the crate's `GratingBsdf`).
//!
//! # Units
//!
//! * Every emitter has the spectrum s(λ) = E(λ)/E(560 nm) of the scene's illuminant
//!   (`render.illuminant`: D65, E or A), scaled by one number: a spherical light's `intensity`
//!   is its spectral **radiance** at 560 nm, W·sr⁻¹·m⁻²·nm⁻¹; a point light's (radius 0) is its
//!   spectral **radiant intensity** at 560 nm, W·sr⁻¹·nm⁻¹ (lengths in the scene's units are
//!   read as metres); the sky's `sky_horizon` and `sky_zenith` are radiances like a spherical
//!   light's. A light's `color` must be white: its colour is its spectrum.
//! * The camera's `exposure` (sr·m²/W) turns radiance into the film's tristimulus values:
//!   XYZ = exposure · ∫ L(λ)·cmf(λ) dλ over 360-830 nm, then the crate's pipeline (XYZ → linear
//!   sRGB → Hall clipping → sRGB). There is no per-material exposure: a grating is as bright
//!   as the light it diffracts.
//! * Diffuse colours (linear sRGB) become reflectance spectra by a box upsampling: the red
//!   value above 585 nm, green on 490-585 nm, blue below 490 nm. White stays white (ρ = 1 at
//!   every λ) and greys stay flat; saturated colours are approximations.
//! * A material is `mirror·tint·δ + (1 − mirror)·(diffuse·colour/π + grating)`, the grating
//!   the crate's radiometric BSDF (`f` in 1/sr). The scene is refused if some material could
//!   reflect more than it receives (mirror + (1 − mirror)·(diffuse·max colour + w/d) > 1).

use diffraction::cie::{cmf, Illuminant};
use diffraction::color::Xyz;
use diffraction::grating_bsdf::OrderEfficiency;
use diffraction::relief::Preset;
use diffraction::spectrum::Spectral;
use diffraction::{Band, Grating, GratingBsdf, GrooveSpread};
use glam::DVec3;

use crate::diagnostics::{Check, FieldError};
use crate::limits::{count, RADIOMETRIC_SLITS};
use crate::material::{model_error, Material};
use crate::scene::{Light, Physics};
use crate::schema::{RawGrating, RawKind, RawRadiometry, RawScene};

/// The largest accepted camera exposure, sr·m²/W.
pub const MAX_EXPOSURE: f64 = 1e12;
/// The largest accepted radiance or intensity at 560 nm (W·sr⁻¹·m⁻²·nm⁻¹ or W·sr⁻¹·nm⁻¹).
pub const MAX_RADIANCE: f64 = 1e12;

/// One emitter of a radiometric scene, in the order of the scene's `[[lights]]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Emitter {
    pub center: DVec3,
    /// 0 for a point light.
    pub radius: f64,
    /// Radiance (sphere) or intensity (point) at 560 nm.
    pub scale: f64,
    /// Stratified directions per hit of the Whitted renderer.
    pub samples: u32,
}

/// The physical units of a radiometric scene (see the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Radiometry {
    pub exposure: f64,
    /// Sky radiance at 560 nm at the horizon and straight up.
    pub sky: [f64; 2],
    pub spectrum: Illuminant,
    pub emitters: Vec<Emitter>,
    /// ∫ s·cmf dλ: the XYZ of a unit-radiance emitter.
    pub white: Xyz,
    /// ∫ s·ȳ dλ (= `white.y`).
    pub ys: f64,
    /// ∫ s·B_c·cmf dλ for the box basis of red, green and blue.
    pub basis: [Xyz; 3],
    /// Whether these units are the mapping of a paper scene ([`crate::paper`]).
    pub from_paper: bool,
}

/// The box upsampling's channel at λ: 0 red (≥ 585 nm), 1 green (490-585 nm), 2 blue.
fn channel(lambda_nm: f64) -> usize {
    if lambda_nm >= 585.0 {
        0
    } else if lambda_nm >= 490.0 {
        1
    } else {
        2
    }
}

/// The reflectance spectrum of a linear-sRGB colour at λ (box upsampling, clamped to [0, 1]).
pub fn reflectance(rgb: DVec3, lambda_nm: f64) -> f64 {
    rgb.to_array()[channel(lambda_nm)].clamp(0.0, 1.0)
}

impl Radiometry {
    /// Builds the units from the table, the scene's lights (as built, with each one's `color`
    /// and `intensity` as written) and illuminant.
    pub fn new(
        raw: &RawRadiometry,
        lights: &[Light],
        intensities: &[(DVec3, f64)],
        spectrum: Illuminant,
    ) -> Check<Radiometry> {
        let range = |path: &str, v: f64, max: f64| -> Result<f64, FieldError> {
            if v.is_finite() && v >= 0.0 && v <= max {
                Ok(v)
            } else {
                Err(FieldError::new(
                    path,
                    format!("expected a number in [0, {max:e}], got {v}"),
                ))
            }
        };
        let exposure = range("radiometry.exposure", raw.exposure, MAX_EXPOSURE)?;
        let horizon = range(
            "radiometry.sky_horizon",
            raw.sky_horizon.unwrap_or(0.0),
            MAX_RADIANCE,
        )?;
        let zenith = range(
            "radiometry.sky_zenith",
            raw.sky_zenith.unwrap_or(horizon),
            MAX_RADIANCE,
        )?;
        let mut emitters = Vec::with_capacity(lights.len());
        for (i, (l, &(color, intensity))) in lights.iter().zip(intensities).enumerate() {
            if color != DVec3::ONE {
                return Err(FieldError::new(
                    format!("lights[{i}].color"),
                    "expected [1, 1, 1] or nothing: in a radiometric scene a light's colour is \
                     its spectrum, the scene's illuminant",
                ));
            }
            emitters.push(Emitter {
                center: l.position,
                radius: l.radius,
                scale: range(&format!("lights[{i}].intensity"), intensity, MAX_RADIANCE)?,
                samples: l.samples,
            });
        }
        let s560 = spectrum.power(560.0);
        let s = |l: f64| spectrum.power(l) / s560;
        // Simpson on every 1 nm row: exact for the products of the linearly interpolated
        // tables, which are quadratic between rows (the box edges are on rows).
        let mut white = [0.0; 3];
        let mut basis = [[0.0; 3]; 3];
        let band = Band::VISIBLE;
        let rows = band.width_nm().round() as usize;
        for i in 0..rows {
            let a = band.min_nm() + i as f64;
            for (x, w) in [(a, 1.0 / 6.0), (a + 0.5, 4.0 / 6.0), (a + 1.0, 1.0 / 6.0)] {
                let c = cmf(x);
                // At a box edge the row belongs to the channel of its midpoint.
                let ch = channel(a + 0.5);
                for k in 0..3 {
                    white[k] += w * s(x) * c[k];
                    basis[ch][k] += w * s(x) * c[k];
                }
            }
        }
        let xyz = |v: [f64; 3]| Xyz::new(v[0], v[1], v[2]);
        Ok(Radiometry {
            exposure,
            sky: [horizon, zenith],
            spectrum,
            emitters,
            white: xyz(white),
            ys: white[1],
            basis: [xyz(basis[0]), xyz(basis[1]), xyz(basis[2])],
            from_paper: false,
        })
    }

    /// The relative spectrum s(λ) = E(λ)/E(560).
    pub fn s(&self, lambda_nm: f64) -> f64 {
        self.spectrum.power(lambda_nm) / self.spectrum.power(560.0)
    }

    /// The sky's radiance scale (at 560 nm) along `dir`: horizon below, linear in dir.y above.
    pub fn sky_scale(&self, dir: DVec3) -> f64 {
        let t = dir.y.clamp(0.0, 1.0);
        self.sky[0] + (self.sky[1] - self.sky[0]) * t
    }

    /// The film XYZ of a diffuse reflection of unit-radiance light by `rgb` (box upsampling).
    pub fn diffuse_xyz(&self, rgb: DVec3) -> Xyz {
        let c = rgb.clamp(DVec3::ZERO, DVec3::ONE);
        self.basis[0] * c.x + self.basis[1] * c.y + self.basis[2] * c.z
    }
}

/// `v` in at most six significant digits, or in full where that would hide that it is above 1.
fn number(v: f64) -> String {
    let short = format!("{}", format!("{v:.6}").parse::<f64>().unwrap_or(v));
    if v > 1.0 && short.parse::<f64>().is_ok_and(|s| s <= 1.0) {
        format!("{v}")
    } else {
        short
    }
}

/// Checks that every material is passive: mirror·mirror_color + (1 − mirror)·(diffuse·colour +
/// slit_width/period) ≤ 1. The error names the field of the largest term and prints every
/// number.
pub fn check_materials(materials: &[Material<GratingBsdf>]) -> Check<()> {
    for (i, m) in materials.iter().enumerate() {
        let duty = m.grating.as_ref().map_or(0.0, |g| {
            g.model.grating().slit_width_nm() / g.model.grating().period_nm()
        });
        let (kd, albedo, tint) = (
            m.shading.coefficients().1,
            m.albedo.max_component(),
            m.mirror_tint.max_element(),
        );
        let rest = 1.0 - m.mirror;
        let total = m.mirror * tint + rest * (kd * albedo + duty);
        if total <= 1.0 + 1e-12 {
            continue;
        }
        // The field whose term is the largest.
        let terms = [
            (
                m.mirror * tint,
                if tint > 1.0 { "mirror_color" } else { "mirror" },
            ),
            (
                rest * kd * albedo,
                if kd >= albedo { "diffuse" } else { "color" },
            ),
            (rest * duty, "slit_width_nm"),
        ];
        let field = terms
            .iter()
            .fold(terms[0], |a, &b| if b.0 > a.0 { b } else { a })
            .1;
        let n = number;
        return Err(FieldError::new(
            format!("objects[{i}].material.{field}"),
            format!(
                "expected a passive material: mirror·mirror_color + (1 − mirror)·(diffuse·color \
                 + slit_width/period) = {}·{} + {}·({}·{} + {}) = {}, above 1",
                n(m.mirror),
                n(tint),
                n(rest),
                n(kd),
                n(albedo),
                n(duty),
                n(total)
            ),
        ));
    }
    Ok(())
}

/// The radiometric grating of a scene's grating material: `slit_width_nm` (default d/2),
/// `slits` (default 1000), and the spread along the grooves, either `coherence_nm` (a
/// coherence length, default N·d) or `groove_sigma` (a Gaussian, groove roughness).
pub fn grating_model(g: &RawGrating, period: f64, path: &str) -> Check<GratingBsdf> {
    let f = |name: &str| format!("{path}.{name}");
    let slits = count(&f("slits"), g.slits.unwrap_or(1000), 1, RADIOMETRIC_SLITS)?;
    let grating = Grating::new(
        period,
        g.slit_width_nm.unwrap_or(period / 2.0),
        slits as u32,
    )
    .map_err(|e| model_error(g, path, e))?;
    let groove = match (g.coherence_nm, g.groove_sigma) {
        (Some(_), Some(_)) => {
            return Err(FieldError::new(
                f("groove_sigma"),
                "give either coherence_nm or groove_sigma, not both",
            ))
        }
        (Some(l), None) => Some(
            GrooveSpread::coherence_length(l)
                .map_err(|e| FieldError::new(f("coherence_nm"), e.to_string()))?,
        ),
        (None, Some(s)) => Some(
            GrooveSpread::gaussian(s)
                .map_err(|e| FieldError::new(f("groove_sigma"), e.to_string()))?,
        ),
        (None, None) => None,
    };
    let bsdf = match groove {
        None => GratingBsdf::new(grating),
        Some(spread) => GratingBsdf::new(grating).with_groove(spread),
    };
    // `reading` reads a classical table: a preset's or a file's (the amplitude reading has no
    // table). A preset is read reduced unless the material says "classical" (the library's
    // default, `OrderEfficiency::preset`); a file classically unless it says "reduced".
    let reduced = match (g.reading.as_deref(), g.efficiency.as_deref()) {
        (Some("classical"), _) => false,
        (None, Some(name)) => name != "amplitude" && !name.ends_with(".json"),
        (None, None) => false,
        (Some("reduced"), Some(name)) if name != "amplitude" => true,
        (Some("reduced"), _) => {
            return Err(FieldError::new(
                f("reading"),
                "\"reduced\" reads a table: a preset's (efficiency = \"cd\", \"dvd\", \
                 \"blazed600\" or \"foil\") or a file's, not the amplitude reading",
            ))
        }
        (Some(other), _) => {
            return Err(FieldError::new(
                f("reading"),
                format!("expected \"classical\" or \"reduced\", got {other:?}"),
            ))
        }
    };
    match g.efficiency.as_deref() {
        None | Some("amplitude") => Ok(bsdf),
        // A table file, read by the loader.
        Some(name) if name.ends_with(".json") => {
            let Some(table) = g.table.clone() else {
                return Err(FieldError::new(f("efficiency"), "the table was not read"));
            };
            if table.period_nm() != period {
                return Err(FieldError::new(
                    f("period_nm"),
                    format!(
                        "the table {name:?} is tabulated for a period of {} nm, got {period} \
                         (leave period_nm out to take the table's)",
                        table.period_nm()
                    ),
                ));
            }
            let table = if reduced {
                // The cover the file names; a conical file is refused by the library (`table`).
                let index: fn(f64) -> f64 = match g.table_cover.as_deref() {
                    None | Some("none") => |_| 1.0,
                    Some("polycarbonate") => diffraction::relief::polycarbonate_index,
                    Some(other) => {
                        return Err(FieldError::new(
                            f("reading"),
                            format!(
                                "the table {name:?} names the cover {other:?}: \"reduced\" knows \
                                 \"none\" and \"polycarbonate\""
                            ),
                        ))
                    }
                };
                let reduced = table
                    .reduced_from_classical(&diffraction::relief::REDUCED_PLANES, index)
                    .map_err(|e| {
                        FieldError::new(f("reading"), format!("the table {name:?}: {e}"))
                    })?;
                std::sync::Arc::new(reduced)
            } else {
                table
            };
            let efficiency =
                OrderEfficiency::from_table(table).map_err(|e| model_error(g, path, e))?;
            bsdf.with_efficiency(efficiency)
                .map_err(|e| model_error(g, path, e))
        }
        Some(name) => {
            let preset: Preset = name.parse().map_err(|e: diffraction::ParseError| {
                FieldError::new(f("efficiency"), format!("{e} or amplitude, got \"{name}\""))
            })?;
            if preset.period_nm() != period {
                return Err(FieldError::new(
                    f("period_nm"),
                    format!(
                        "the preset \"{name}\" is tabulated for a period of {} nm, got {period} \
                         (leave period_nm out to take the preset's)",
                        preset.period_nm()
                    ),
                ));
            }
            let efficiency = if reduced {
                OrderEfficiency::preset(preset)
            } else {
                OrderEfficiency::from_static(preset.table()).map_err(|e| model_error(g, path, e))?
            };
            bsdf.with_efficiency(efficiency)
                .map_err(|e| model_error(g, path, e))
        }
    }
}

/// The scenes of the path tracer: physical units (a `[radiometry]` table), gratings of model
/// "radiometric".
#[derive(Debug, Clone, Copy)]
pub struct Radiometric;

impl Physics for Radiometric {
    type Grating = GratingBsdf;
    type Units = Radiometry;

    /// Every scene: one without a `[radiometry]` table is the paper's, mapped to physical
    /// units ([`crate::paper`]).
    fn accepts(_: &RawScene) -> Check<()> {
        Ok(())
    }

    /// "radiometric", and "agu-hill" read radiometrically ([`crate::paper::grating`]; refused
    /// in a scene with a `[radiometry]` table by [`Physics::units`], which sees the table).
    fn grating(name: &str, g: &RawGrating, period: f64, path: &str) -> Check<GratingBsdf> {
        match name {
            "radiometric" => grating_model(g, period, path),
            "agu-hill" => crate::paper::grating(g, period, path),
            _ => Err(FieldError::new(
                format!("{path}.model"),
                format!(
                    "the path tracer takes gratings of model \"radiometric\", and \"agu-hill\" \
                     in the paper's scenes (read as the radiometric grating); \"{name}\" has no \
                     physical units"
                ),
            )),
        }
    }

    fn units(
        raw: &RawScene,
        lights: &[Light],
        materials: &[Material<GratingBsdf>],
        spectral: &Spectral,
    ) -> Check<Radiometry> {
        let Some(table) = &raw.radiometry else {
            check_materials(materials)?;
            return crate::paper::units(raw, lights, spectral.illuminant());
        };
        // A paper grating has no place among physical units.
        for (i, o) in raw.objects.iter().enumerate() {
            if let RawKind::Grating(g) = &o.material.kind {
                if g.model.as_deref().unwrap_or("agu-hill") != "radiometric" {
                    return Err(FieldError::new(
                        format!("objects[{i}].material.model"),
                        "a scene with a [radiometry] table takes gratings of model \
                         \"radiometric\" only (the other models have no physical units)",
                    ));
                }
            }
        }
        check_materials(materials)?;
        let keys: Vec<(DVec3, f64)> = raw
            .lights
            .iter()
            .map(|l| {
                (
                    DVec3::from_array(l.color.unwrap_or([1.0; 3])),
                    l.intensity.unwrap_or(1.0),
                )
            })
            .collect();
        Radiometry::new(table, lights, &keys, spectral.illuminant())
    }
}
