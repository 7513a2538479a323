//! Gamut clipping: the schemes of Hall (1989) and their names.

use core::fmt;
use core::str::FromStr;

use super::srgb::clamp01;
use super::LinearSrgb;
use crate::ParseError;

impl LinearSrgb {
    /// Brings the colour into the gamut [0, 1]³ with the given scheme (see [`Clip`] for what each
    /// one does, including to negative components).
    ///
    /// Every scheme returns an in-gamut colour unchanged, always returns a colour inside
    /// [0, 1]³, and never returns NaN, whatever the input. Non-finite input: NaN components
    /// count as 0 for `Clamp` and `Intensity`; +∞ becomes 1 under `Clamp`, and under
    /// `Intensity` the infinite components become 1 and the others 0; `ConstantIntensity`
    /// gives white for a luminance of +∞ and black for −∞ or NaN.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(2.0, 0.5, -0.5);
    /// assert_eq!(c.clip(Clip::Clamp), LinearSrgb::new(1.0, 0.5, 0.0));
    /// assert_eq!(c.clip(Clip::Intensity), LinearSrgb::new(1.0, 0.25, 0.0));
    /// let k = c.clip(Clip::ConstantIntensity);
    /// assert!(k.is_in_gamut() && (k.luminance() - c.luminance()).abs() < 1e-15);
    /// ```
    #[must_use]
    pub fn clip(self, method: Clip) -> LinearSrgb {
        if self.is_in_gamut() {
            return self;
        }
        match method {
            Clip::Clamp => self.map(clamp01),
            Clip::Intensity => self.clip_intensity(),
            Clip::ConstantIntensity => self.clip_constant_intensity(),
        }
    }

    #[inline]
    fn map(self, f: impl Fn(f64) -> f64) -> LinearSrgb {
        LinearSrgb::new(f(self.r), f(self.g), f(self.b))
    }

    fn clip_intensity(self) -> LinearSrgb {
        // Negative (and NaN) components → 0.
        let c = self.map(|v| if v > 0.0 { v } else { 0.0 });
        let m = c.r.max(c.g).max(c.b);
        if m <= 1.0 {
            c
        } else if m.is_finite() {
            // The ratios survive up to rounding; the clamp only guards against it.
            c.map(|v| clamp01(v / m))
        } else {
            // Infinite components: the direction is that of the infinite ones.
            c.map(|v| if v == f64::INFINITY { 1.0 } else { 0.0 })
        }
    }

    fn clip_constant_intensity(self) -> LinearSrgb {
        let y = self.luminance();
        // NaN luminance (a NaN or ±∞ − ∞ input) is treated as no light at all.
        if y.is_nan() || y <= 0.0 {
            return LinearSrgb::new(0.0, 0.0, 0.0);
        }
        if y >= 1.0 {
            // Scaling to luminance 1 and desaturating toward the grey of luminance 1 always ends
            // at white: it is the only colour in [0,1]³ with luminance 1.
            return LinearSrgb::new(1.0, 1.0, 1.0);
        }
        // 0 < y < 1: c' = y + t (c − y) with the largest t in [0, 1] that keeps every channel
        // in [0, 1]. The denominators are positive (c > 1 > y, or c < 0 < y).
        let mut t: f64 = 1.0;
        for c in [self.r, self.g, self.b] {
            if c > 1.0 {
                t = t.min((1.0 - y) / (c - y));
            } else if c < 0.0 {
                t = t.min(y / (y - c));
            }
        }
        // The clamp removes the rounding of the limiting channel (a few ulp at most).
        self.map(|c| clamp01(y + t * (c - y)))
    }
}

/// How [`LinearSrgb::clip`] brings an out-of-gamut colour into [0, 1]³ (the schemes of
/// R. Hall, *Illumination and Color in Computer Generated Imagery*, Springer 1989).
///
/// Every pure spectral colour has at least one **negative** linear sRGB component, and a bright
/// one also components above 1, so how each scheme treats negatives matters for every grating
/// picture.
///
/// Parsed from and displayed as `"clamp"`, `"intensity"`, `"constant"`:
///
/// ```
/// use diffraction::color::Clip;
/// let c: Clip = "constant".parse()?;
/// assert_eq!(c, Clip::ConstantIntensity);
/// assert_eq!(c.to_string(), "constant");
/// assert!("gamma".parse::<Clip>().is_err());
/// # Ok::<(), diffraction::ParseError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[non_exhaustive]
pub enum Clip {
    /// Clamp each channel to [0, 1] independently: negatives become 0, values above 1 become 1.
    ///
    /// Cheap, keeps in-range channels, but shifts the hue when a channel exceeds 1 (a bright
    /// orange turns yellow) and changes luminance.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(3.0, 1.5, -0.2).clip(Clip::Clamp);
    /// assert_eq!(c, LinearSrgb::new(1.0, 1.0, 0.0)); // orange became yellow
    /// ```
    Clamp,
    /// Intensity scaling: negative channels are set to 0 first, then, if the largest channel
    /// exceeds 1, the triple is divided by it.
    ///
    /// Keeps the ratios of the non-negative components (the hue and saturation of the colour
    /// with its negatives clamped) and loses brightness instead.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(3.0, 1.5, -0.2).clip(Clip::Intensity);
    /// assert_eq!(c, LinearSrgb::new(1.0, 0.5, 0.0)); // still orange, darker
    /// ```
    Intensity,
    /// Constant-intensity scaling: keeps the luminance Y ([`LinearSrgb::luminance`]) and moves
    /// the colour toward the grey (Y, Y, Y) of equal luminance, c' = Y + t (c − Y), with the
    /// largest t ∈ [0, 1] that puts every channel in [0, 1] (t ≤ (1 − Y)/(cᵢ − Y) for cᵢ > 1,
    /// t ≤ Y/(Y − cᵢ) for cᵢ < 0, so a negative channel ends at exactly 0 when it is the
    /// limiting one). It desaturates instead of darkening.
    ///
    /// Because the luminance weights sum to 1, the grey and every point of the segment have
    /// luminance Y: the luminance is kept (to rounding, about 1e-16) whenever 0 < Y < 1.
    /// If Y ≤ 0 the result is black. If Y ≥ 1 the triple is first scaled to luminance 1, and the
    /// only in-gamut colour of luminance 1 is white, so the result is white (1, 1, 1).
    /// A final clamp, which moves values by a few ulp at most, guards against rounding.
    ///
    /// ```
    /// use diffraction::color::{Clip, LinearSrgb};
    /// let c = LinearSrgb::new(1.2, 0.3, -0.1);
    /// let k = c.clip(Clip::ConstantIntensity);
    /// assert!(k.is_in_gamut() && (k.luminance() - c.luminance()).abs() < 1e-15);
    /// assert_eq!(LinearSrgb::new(3.0, 1.5, 0.0).clip(Clip::ConstantIntensity),
    ///            LinearSrgb::new(1.0, 1.0, 1.0));
    /// ```
    ConstantIntensity,
}

impl Clip {
    /// Every scheme, in declaration order.
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// assert_eq!(Clip::ALL.len(), 3);
    /// ```
    pub const ALL: [Clip; 3] = [Clip::Clamp, Clip::Intensity, Clip::ConstantIntensity];

    /// The name used by [`Display`](fmt::Display) and [`FromStr`].
    ///
    /// ```
    /// use diffraction::color::Clip;
    /// assert_eq!(Clip::Intensity.name(), "intensity");
    /// ```
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Clip::Clamp => "clamp",
            Clip::Intensity => "intensity",
            Clip::ConstantIntensity => "constant",
        }
    }
}

impl fmt::Display for Clip {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Clip {
    type Err = ParseError;

    /// Parses `"clamp"`, `"intensity"` or `"constant"` (exactly, lower case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Clip::ALL
            .into_iter()
            .find(|c| c.name() == s)
            .ok_or(ParseError::new(
                "clipping scheme",
                "one of \"clamp\", \"intensity\", \"constant\"",
            ))
    }
}
