//! Geometry: the phase projection u and the grating direction across a surface.
//!
//! The diffraction term depends on the directions only through u = (wi + wo)·t, the component
//! along the grating vector t of the sum of the unit directions toward the light and toward the
//! viewer. In the paper's angles u = sin θ − sin θi (eq. 9-10); u = 0 is the mirror direction.
//!
//! # The paper's half vector, corrected
//!
//! The paper's step 5 substitutes the projection of the *normalised* half vector,
//! h·t with h = (wi + wo)/|wi + wo|. It has the right sign and the right zero, but it is u divided
//! by |wi + wo| = 2 cos θh, so every peak it predicts off the mirror direction sits at the wrong
//! angle. [`paper_half_vector_projection`] computes it for comparison only; the crate uses
//! [`phase_projection`] everywhere.
//!
//! ```
//! use diffraction::frame::{paper_half_vector_projection, phase_projection};
//! use glam::DVec3;
//! let wi = DVec3::Z; // light overhead
//! let wo = DVec3::new(0.5, 0.0, 0.75f64.sqrt()); // viewer 30° off the normal
//! let t = DVec3::X;
//! assert!((phase_projection(wo, wi, t) - 0.5).abs() < 1e-15); // sin 30° − sin 0°
//! assert!((paper_half_vector_projection(wo, wi, t) - 0.2588).abs() < 1e-4); // sin 15°
//! ```
//!
//! # Grating-direction fields
//!
//! A [`GratingField`] gives the grating vector at each point of a surface, in the surface's own
//! 2-D tangent coordinates (p.x along the first tangent, p.y along the second): constant, twisted
//! about the normal, radial about a centre (the concentric tracks of a CD), or a checkerboard
//! alternating two fields or a field and plain surface. [`ShadingFrame`] turns the result into
//! the local frame the BRDFs use.

use glam::{DVec2, DVec3, Vec3};

use crate::error::{finite, positive, Error};
use crate::num::math;

mod sealed {
    pub trait Sealed {}
    impl Sealed for glam::Vec3 {}
    impl Sealed for glam::DVec3 {}
}

/// A glam 3-vector of either precision ([`Vec3`] or [`DVec3`]); sealed.
///
/// ```
/// use diffraction::frame::phase_projection;
/// use glam::{DVec3, Vec3};
/// // `Scalar` is `f32` for `Vec3` and `f64` for `DVec3`.
/// let a: f32 = phase_projection(Vec3::new(0.5, 0.0, 0.75f32.sqrt()), Vec3::Z, Vec3::X);
/// let b: f64 = phase_projection(DVec3::new(0.5, 0.0, 0.75f64.sqrt()), DVec3::Z, DVec3::X);
/// assert_eq!((a, b), (0.5, 0.5));
/// ```
pub trait Vector: sealed::Sealed + Copy {
    /// The scalar type, `f32` or `f64`.
    type Scalar: crate::Float;
    #[doc(hidden)]
    fn sum_dot(a: Self, b: Self, t: Self) -> Self::Scalar;
    #[doc(hidden)]
    fn half_dot(a: Self, b: Self, t: Self) -> Self::Scalar;
}

impl Vector for Vec3 {
    type Scalar = f32;
    #[inline]
    fn sum_dot(a: Self, b: Self, t: Self) -> f32 {
        (a + b).dot(t)
    }
    #[inline]
    fn half_dot(a: Self, b: Self, t: Self) -> f32 {
        (a + b).normalize_or_zero().dot(t)
    }
}

impl Vector for DVec3 {
    type Scalar = f64;
    #[inline]
    fn sum_dot(a: Self, b: Self, t: Self) -> f64 {
        (a + b).dot(t)
    }
    #[inline]
    fn half_dot(a: Self, b: Self, t: Self) -> f64 {
        (a + b).normalize_or_zero().dot(t)
    }
}

/// The phase projection u = (wi + wo)·t, for [`Vec3`] or [`DVec3`].
///
/// `wo` toward the viewer, `wi` toward the light (the order of every function of the crate
/// that takes both), `t` the unit grating vector; all in one frame.
/// For unit vectors |u| ≤ 2; for vectors the caller made huge (components near `f64::MAX`)
/// the dot product overflows like any other, which is the caller's own arithmetic.
///
/// ```
/// use diffraction::frame::phase_projection;
/// use glam::Vec3;
/// // Mirror configuration: u = 0.
/// let wi = Vec3::new(-0.6, 0.0, 0.8);
/// let wo = Vec3::new(0.6, 0.0, 0.8);
/// assert_eq!(phase_projection(wo, wi, Vec3::X), 0.0);
/// ```
#[inline]
#[must_use]
pub fn phase_projection<V: Vector>(wo: V, wi: V, t: V) -> V::Scalar {
    V::sum_dot(wo, wi, t)
}

/// The paper's step-5 substitute for u: the normalised half vector's component along t.
///
/// Kept only to document the paper's error (see the [module docs](self)); it equals
/// u/|wi + wo|, and 0 when wi = −wo.
///
/// ```
/// use diffraction::frame::{paper_half_vector_projection, phase_projection};
/// use glam::DVec3;
/// let wi = DVec3::new(-0.6, 0.0, 0.8);
/// let wo = DVec3::new(0.8, 0.0, 0.6);
/// let ratio = paper_half_vector_projection(wo, wi, DVec3::X) / phase_projection(wo, wi, DVec3::X);
/// assert!((ratio - 1.0 / (wi + wo).length()).abs() < 1e-12);
/// ```
#[inline]
#[must_use]
pub fn paper_half_vector_projection<V: Vector>(wo: V, wi: V, t: V) -> V::Scalar {
    V::half_dot(wo, wi, t)
}

/// An orthonormal shading frame: `normal` (local z), `grating` vector t (local x) and the groove
/// direction (local y = z × x).
///
/// ```
/// use diffraction::frame::ShadingFrame;
/// use glam::DVec3;
/// let f = ShadingFrame::new(DVec3::Y, DVec3::new(1.0, 0.3, 0.0)).unwrap();
/// let local = f.to_local(DVec3::Y);
/// assert!((local - DVec3::Z).length() < 1e-15);
/// assert!((f.to_world(local) - DVec3::Y).length() < 1e-15);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadingFrame {
    /// Unit grating vector t (local x).
    pub grating: DVec3,
    /// Unit groove direction (local y).
    pub groove: DVec3,
    /// Unit normal (local z).
    pub normal: DVec3,
}

impl ShadingFrame {
    /// Builds the frame from a normal and an approximate grating vector, removing the latter's
    /// normal component (Gram-Schmidt). `None` if either is zero, non-finite, or they are parallel.
    ///
    /// ```
    /// use diffraction::frame::ShadingFrame;
    /// use glam::DVec3;
    /// let f = ShadingFrame::new(DVec3::Z, DVec3::new(2.0, 0.0, 5.0)).unwrap();
    /// assert_eq!(f.grating, DVec3::X); // normal component removed, then normalised
    /// assert_eq!(f.groove, DVec3::Y); // z × x
    /// assert!(ShadingFrame::new(DVec3::Z, DVec3::Z).is_none()); // parallel
    /// ```
    #[must_use]
    pub fn new(normal: DVec3, grating: DVec3) -> Option<ShadingFrame> {
        let n = normal.try_normalize()?;
        let t = (grating - n * grating.dot(n)).try_normalize()?;
        Some(ShadingFrame {
            grating: t,
            groove: n.cross(t),
            normal: n,
        })
    }

    /// A world direction in local coordinates (x along t, y along the grooves, z along the normal).
    ///
    /// ```
    /// use diffraction::frame::ShadingFrame;
    /// use glam::DVec3;
    /// // A disc in the xz-plane, grating vector along world x: local y (grooves) is world −z.
    /// let f = ShadingFrame::new(DVec3::Y, DVec3::X).unwrap();
    /// assert_eq!(f.to_local(DVec3::new(0.6, 0.8, 0.0)), DVec3::new(0.6, 0.0, 0.8));
    /// assert_eq!(f.to_local(DVec3::Z), DVec3::NEG_Y);
    /// ```
    #[inline]
    #[must_use]
    pub fn to_local(&self, v: DVec3) -> DVec3 {
        DVec3::new(v.dot(self.grating), v.dot(self.groove), v.dot(self.normal))
    }

    /// A local direction back in world coordinates.
    ///
    /// ```
    /// use diffraction::frame::ShadingFrame;
    /// use glam::DVec3;
    /// let f = ShadingFrame::new(DVec3::Y, DVec3::X).unwrap();
    /// assert_eq!(f.to_world(DVec3::Z), DVec3::Y); // the local normal
    /// assert_eq!(f.to_world(DVec3::Y), DVec3::NEG_Z); // the groove direction
    /// ```
    #[inline]
    #[must_use]
    pub fn to_world(&self, v: DVec3) -> DVec3 {
        self.grating * v.x + self.groove * v.y + self.normal * v.z
    }
}

/// The grating direction of one region of a surface (one tile of a checkerboard).
///
/// ```
/// use diffraction::frame::Tile;
/// use glam::DVec2;
/// assert_eq!(Tile::Plain.direction_at(DVec2::ZERO), None);
/// let t = Tile::Constant { angle: 0.0 };
/// assert_eq!(t.direction_at(DVec2::new(5.0, 7.0)), Some(DVec2::X)); // the same everywhere
/// ```
///
/// Its numbers must be finite; [`direction_at`](Tile::direction_at) returns `None` where they
/// are not, and deserialisation (feature `serde`) rejects them with an error that names the
/// field (`angle`, `center` or `twist`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Tile {
    /// No grating: a plain (non-diffractive) surface.
    Plain,
    /// A constant grating vector at `angle` radians from the first tangent axis, toward the second.
    Constant {
        /// Angle of the grating vector in the tangent plane, radians.
        angle: f64,
    },
    /// Concentric grooves about `center` (a CD's tracks): the grating vector points away from the
    /// centre, rotated by `twist` radians about the normal (0 for circular tracks).
    Radial {
        /// Centre of the tracks in tangent coordinates.
        center: [f64; 2],
        /// Extra rotation about the normal, radians.
        twist: f64,
    },
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Tile {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        /// The same shape as `Tile`, read before it is checked.
        #[derive(serde::Deserialize)]
        enum Raw {
            Plain,
            Constant { angle: f64 },
            Radial { center: [f64; 2], twist: f64 },
        }
        let tile = match Raw::deserialize(d)? {
            Raw::Plain => Tile::Plain,
            Raw::Constant { angle } => Tile::Constant { angle },
            Raw::Radial { center, twist } => Tile::Radial { center, twist },
        };
        tile.checked().map_err(serde::de::Error::custom)
    }
}

impl Tile {
    /// The tile if all its numbers are finite; otherwise the error names the first that is not.
    #[cfg(feature = "serde")]
    fn checked(self) -> Result<Tile, Error> {
        match self {
            Tile::Plain => {}
            Tile::Constant { angle } => {
                finite("angle", angle)?;
            }
            Tile::Radial { center, twist } => {
                finite("center", center[0])?;
                finite("center", center[1])?;
                finite("twist", twist)?;
            }
        }
        Ok(self)
    }

    /// The unit grating vector at `p` in tangent coordinates, or `None` (plain tile, the exact
    /// centre of a radial tile, where the direction is undefined, and a tile or point whose
    /// numbers are not finite: the result is always a finite unit vector).
    ///
    /// ```
    /// use diffraction::frame::Tile;
    /// use glam::DVec2;
    /// let cd = Tile::Radial { center: [1.0, 1.0], twist: 0.0 };
    /// assert_eq!(cd.direction_at(DVec2::new(5.0, 1.0)), Some(DVec2::X)); // away from the centre
    /// assert_eq!(cd.direction_at(DVec2::new(1.0, 1.0)), None); // the centre itself
    /// assert_eq!(Tile::Constant { angle: f64::INFINITY }.direction_at(DVec2::ZERO), None);
    /// ```
    #[must_use]
    pub fn direction_at(&self, p: DVec2) -> Option<DVec2> {
        let dir = match *self {
            Tile::Plain => None,
            Tile::Constant { angle } => Some(DVec2::new(math::cos(angle), math::sin(angle))),
            Tile::Radial { center, twist } => {
                let r = (p - DVec2::from(center)).try_normalize()?;
                Some(if twist == 0.0 {
                    r
                } else {
                    DVec2::from_angle(twist).rotate(r)
                })
            }
        };
        dir.filter(|d| d.is_finite())
    }

    /// The same tile rotated by `twist` radians about the normal (plain stays plain).
    ///
    /// ```
    /// use diffraction::frame::Tile;
    /// assert_eq!(Tile::Constant { angle: 0.25 }.twisted(0.5), Tile::Constant { angle: 0.75 });
    /// assert_eq!(Tile::Plain.twisted(0.5), Tile::Plain);
    /// ```
    #[must_use]
    pub fn twisted(self, twist: f64) -> Tile {
        match self {
            Tile::Plain => Tile::Plain,
            Tile::Constant { angle } => Tile::Constant {
                angle: angle + twist,
            },
            Tile::Radial { center, twist: t } => Tile::Radial {
                center,
                twist: t + twist,
            },
        }
    }
}

/// The grating vector as a function of position on a surface (see the [module docs](self)).
///
/// ```
/// use diffraction::frame::{GratingField, Tile};
/// use glam::DVec2;
/// // Fig. 5b: squares alternating the groove twist between 0° and 90°.
/// let f = GratingField::checkerboard(0.25, Tile::Constant { angle: 0.0 },
///                                    Tile::Constant { angle: std::f64::consts::FRAC_PI_2 })?;
/// let a = f.direction_at(DVec2::new(0.1, 0.1)).unwrap();
/// let b = f.direction_at(DVec2::new(0.3, 0.1)).unwrap();
/// assert!(a.dot(b).abs() < 1e-12);
/// // A CD: the grating vector is radial.
/// let cd = GratingField::radial(DVec2::ZERO);
/// assert!((cd.direction_at(DVec2::new(0.0, 2.0)).unwrap() - DVec2::Y).length() < 1e-15);
/// # Ok::<(), diffraction::Error>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(transparent))]
pub struct GratingField(Field);

/// The two kinds of field, private so that every field is built by a constructor that
/// validates it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
enum Field {
    /// One tile everywhere.
    Uniform(Tile),
    /// Squares of side `cell_size` (finite, > 0) alternating `even` (the square containing the
    /// origin's positive quadrant corner) and `odd`.
    Checkerboard {
        cell_size: f64,
        even: Tile,
        odd: Tile,
    },
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for GratingField {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(serde::Deserialize)]
        enum Raw {
            Uniform(Tile),
            Checkerboard {
                cell_size: f64,
                even: Tile,
                odd: Tile,
            },
        }
        match Raw::deserialize(d)? {
            Raw::Uniform(t) => Ok(GratingField::uniform(t)),
            Raw::Checkerboard {
                cell_size,
                even,
                odd,
            } => GratingField::checkerboard(cell_size, even, odd).map_err(serde::de::Error::custom),
        }
    }
}

impl GratingField {
    /// A constant grating vector at `angle` radians from the first tangent axis.
    ///
    /// ```
    /// use diffraction::frame::{GratingField, Tile};
    /// use glam::DVec2;
    /// use std::f64::consts::FRAC_PI_2;
    /// let f = GratingField::constant(FRAC_PI_2);
    /// assert_eq!(f, GratingField::uniform(Tile::Constant { angle: FRAC_PI_2 }));
    /// let t = f.direction_at(DVec2::new(3.0, -2.0)).unwrap();
    /// assert!((t - DVec2::Y).length() < 1e-15); // cos(π/2) rounds to 6e-17, not 0
    /// ```
    #[must_use]
    pub fn constant(angle: f64) -> GratingField {
        GratingField::uniform(Tile::Constant { angle })
    }

    /// Concentric circular grooves about `center` (the grating vector is radial).
    ///
    /// ```
    /// use diffraction::frame::GratingField;
    /// use glam::DVec2;
    /// let cd = GratingField::radial(DVec2::new(1.0, 0.0));
    /// // The grating vector points away from the centre.
    /// assert_eq!(cd.direction_at(DVec2::new(1.0, -4.0)), Some(DVec2::NEG_Y));
    /// assert_eq!(cd.direction_at(DVec2::new(1.0, 0.0)), None); // the centre itself
    /// ```
    #[must_use]
    pub fn radial(center: DVec2) -> GratingField {
        GratingField::uniform(Tile::Radial {
            center: center.to_array(),
            twist: 0.0,
        })
    }

    /// One tile everywhere (a twisted radial field, say).
    ///
    /// ```
    /// use diffraction::frame::{GratingField, Tile};
    /// use glam::DVec2;
    /// let f = GratingField::uniform(Tile::Radial { center: [0.0, 0.0], twist: 0.5 });
    /// assert_eq!(f.tile_at(DVec2::new(3.0, 4.0)), Tile::Radial { center: [0.0, 0.0], twist: 0.5 });
    /// ```
    #[must_use]
    pub fn uniform(tile: Tile) -> GratingField {
        GratingField(Field::Uniform(tile))
    }

    /// A checkerboard of two tiles; rejects a non-positive or non-finite `cell_size`.
    ///
    /// ```
    /// use diffraction::frame::{GratingField, Tile};
    /// use glam::DVec2;
    /// let f = GratingField::checkerboard(1.0, Tile::Plain, Tile::Constant { angle: 0.0 })?;
    /// assert_eq!(f.direction_at(DVec2::new(0.5, 0.5)), None); // even square: plain
    /// assert_eq!(f.direction_at(DVec2::new(1.5, 0.5)), Some(DVec2::X)); // odd square
    /// let err = GratingField::checkerboard(0.0, Tile::Plain, Tile::Plain).unwrap_err();
    /// assert_eq!(err.parameter(), "cell_size");
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn checkerboard(cell_size: f64, even: Tile, odd: Tile) -> Result<GratingField, Error> {
        let cell_size = positive("cell_size", cell_size)?;
        Ok(GratingField(Field::Checkerboard {
            cell_size,
            even,
            odd,
        }))
    }

    /// The whole field rotated by `twist` radians about the normal.
    ///
    /// ```
    /// use diffraction::frame::GratingField;
    /// use glam::DVec2;
    /// let f = GratingField::constant(0.0).twisted(std::f64::consts::FRAC_PI_2)?;
    /// assert!((f.direction_at(DVec2::ZERO).unwrap() - DVec2::Y).length() < 1e-15);
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    pub fn twisted(self, twist: f64) -> Result<GratingField, Error> {
        let twist = finite("twist", twist)?;
        Ok(GratingField(match self.0 {
            Field::Uniform(t) => Field::Uniform(t.twisted(twist)),
            Field::Checkerboard {
                cell_size,
                even,
                odd,
            } => Field::Checkerboard {
                cell_size,
                even: even.twisted(twist),
                odd: odd.twisted(twist),
            },
        }))
    }

    /// The tile that applies at `p`.
    ///
    /// ```
    /// use diffraction::frame::{GratingField, Tile};
    /// use glam::DVec2;
    /// let (even, odd) = (Tile::Plain, Tile::Constant { angle: 0.0 });
    /// let f = GratingField::checkerboard(2.0, even, odd)?;
    /// assert_eq!(f.tile_at(DVec2::new(1.0, 1.0)), even);
    /// assert_eq!(f.tile_at(DVec2::new(3.0, 1.0)), odd);
    /// assert_eq!(f.tile_at(DVec2::new(-1.0, 1.0)), odd); // the squares continue below zero
    /// # Ok::<(), diffraction::Error>(())
    /// ```
    #[must_use]
    pub fn tile_at(&self, p: DVec2) -> Tile {
        match self.0 {
            Field::Uniform(t) => t,
            Field::Checkerboard {
                cell_size,
                even,
                odd,
            } => {
                let i = math::floor(p.x / cell_size);
                let j = math::floor(p.y / cell_size);
                let parity = (i + j) - 2.0 * math::floor((i + j) / 2.0);
                if parity == 0.0 {
                    even
                } else {
                    odd
                }
            }
        }
    }

    /// The unit grating vector at `p` in tangent coordinates, or `None` where there is no grating.
    ///
    /// ```
    /// use diffraction::frame::GratingField;
    /// use glam::DVec2;
    /// let f = GratingField::constant(0.0);
    /// assert_eq!(f.direction_at(DVec2::new(2.0, 3.0)), Some(DVec2::X));
    /// assert_eq!(f.direction_at(DVec2::new(f64::NAN, 0.0)), None); // not a point
    /// ```
    #[must_use]
    pub fn direction_at(&self, p: DVec2) -> Option<DVec2> {
        if !p.is_finite() {
            return None;
        }
        self.tile_at(p).direction_at(p)
    }

    /// The world-space grating vector at `p`, given the surface's world tangents at that point.
    ///
    /// ```
    /// use diffraction::frame::GratingField;
    /// use glam::{DVec2, DVec3};
    /// let cd = GratingField::radial(DVec2::ZERO);
    /// // A disc in the xz-plane: tangent coordinates (p.x, p.y) run along world x and z.
    /// let t = cd.world_direction(DVec2::new(0.0, 2.0), DVec3::X, DVec3::Z);
    /// assert_eq!(t, Some(DVec3::Z));
    /// assert_eq!(cd.world_direction(DVec2::ZERO, DVec3::X, DVec3::Z), None); // the centre
    /// ```
    #[must_use]
    pub fn world_direction(&self, p: DVec2, tangent: DVec3, bitangent: DVec3) -> Option<DVec3> {
        let d = self.direction_at(p)?;
        (tangent * d.x + bitangent * d.y).try_normalize()
    }
}
