//! The tabulated source's incidence tables as the table's accessors see them: the plane
//! across the grooves and, for a conical table, its planes of |wi.y| (none without the
//! feature `relief`).

#[cfg(feature = "relief")]
use super::incidence;
#[cfg(feature = "relief")]
use super::source::Source;
use super::ColorTable;

impl ColorTable {
    /// The incidence nodes of a tabulated source.
    #[cfg(feature = "relief")]
    #[inline]
    pub(super) fn tabulated(&self) -> Option<&incidence::Incidence> {
        match &self.source {
            Source::Tabulated { incidence, .. } => incidence.as_deref(),
            _ => None,
        }
    }

    /// The incidence nodes of a conical table's planes off the plane across the grooves.
    #[cfg(feature = "relief")]
    pub(super) fn off_plane(&self) -> impl Iterator<Item = &incidence::Incidence> {
        let planes = match &self.source {
            Source::Tabulated { planes, .. } => &planes[..],
            _ => &[],
        };
        planes.iter().map(|(_, _, t)| t)
    }

    /// A conical table's planes off the plane across the grooves: (|wi.y|, c = √(1 − wi.y²),
    /// incidence nodes).
    #[cfg(all(feature = "relief", feature = "gpu"))]
    pub(super) fn planes(&self) -> impl Iterator<Item = (f64, f64, &incidence::Incidence)> {
        let planes = match &self.source {
            Source::Tabulated { planes, .. } => &planes[..],
            _ => &[],
        };
        planes.iter().map(|(b, c, t)| (*b, *c, t))
    }

    /// Without the feature `relief` there are no tabulated sources.
    #[cfg(not(feature = "relief"))]
    #[inline(always)]
    pub(super) fn tabulated(&self) -> Option<&NoIncidence> {
        None
    }

    /// Without the feature `relief` there are no planes.
    #[cfg(not(feature = "relief"))]
    pub(super) fn off_plane(&self) -> core::iter::Empty<&NoIncidence> {
        core::iter::empty()
    }
}

/// Stands for the incidence nodes without the feature `relief` (never built).
#[cfg(not(feature = "relief"))]
pub(super) struct NoIncidence {
    pub(super) scale: f64,
    pub(super) error: f64,
}

#[cfg(not(feature = "relief"))]
impl NoIncidence {
    pub(super) fn node_count(&self) -> usize {
        0
    }
    pub(super) fn heap_bytes(&self) -> usize {
        0
    }
}
