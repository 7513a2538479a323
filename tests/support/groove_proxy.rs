//! The scale s of a groove spread's Cauchy proxy q(v) = s/(π·(s² + v²)), as
//! `GrooveSpread::sample` documents it: 1.2·λ/(π·L) for the coherence length, σ for the
//! Gaussian, 0 for the ideal lobe and for λ that is not a positive finite number (the crate
//! keeps its own copy internal).

use diffraction::{GrooveKind, GrooveSpread};

/// The documented proxy scale of `g` at `lambda_nm`, finite for every input.
pub fn proxy_scale(g: GrooveSpread, lambda_nm: f64) -> f64 {
    if !(lambda_nm > 0.0 && lambda_nm.is_finite()) {
        return 0.0;
    }
    let s = match g.kind() {
        GrooveKind::Ideal => 0.0,
        GrooveKind::CoherenceLength { length_nm } => {
            1.2 * (lambda_nm / (std::f64::consts::PI * length_nm))
        }
        GrooveKind::Gaussian { sigma } => sigma,
        // `GrooveKind` is non-exhaustive: a new kind would need its documented scale here.
        _ => 0.0,
    };
    s.min(f64::MAX)
}
