//! The one error type of the crate: what a caller gave that cannot be drawn, or an encoder
//! that failed.

use crate::limits::{MAX_PIXELS, MAX_SIDE, MIN_SIDE};

/// Why a picture or a plot was not made.
///
/// ```
/// use envelope_render::{RenderError, Size};
/// assert_eq!(Size::new(8, 100), Err(RenderError::Size { width: 8, height: 100 }));
/// ```
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RenderError {
    /// A side of the picture is outside `MIN_SIDE..=MAX_SIDE`.
    #[error("picture size {width}x{height}: each side must be {MIN_SIDE}..={MAX_SIDE} pixels")]
    Size {
        /// The width asked for.
        width: u32,
        /// The height asked for.
        height: u32,
    },
    /// The whole picture (a strip of panels) has more than `MAX_PIXELS` pixels.
    #[error("picture of {width}x{height} pixels: more than {MAX_PIXELS} pixels in all")]
    TooLarge {
        /// The strip's width.
        width: u64,
        /// The strip's height.
        height: u64,
    },
    /// An angle of the view is not finite, or the elevation is outside -90..=90 degrees, or a
    /// perspective field of view is outside (0, 180) degrees.
    #[error(
        "view: azimuth must be finite, elevation in -90..=90 degrees, field of view in (0, 180) degrees"
    )]
    View,
    /// A face names a vertex the mesh does not have.
    #[error("face {face} refers to vertex {vertex}, but the mesh has {vertices} vertices")]
    Index {
        /// The face's index.
        face: usize,
        /// The vertex index it holds.
        vertex: u32,
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// A vertex has a coordinate that is NaN or infinite.
    #[error("vertex {vertex} has a coordinate that is not finite")]
    NotFinite {
        /// The vertex's index.
        vertex: usize,
    },
    /// Per-vertex values given, but not one per vertex.
    #[error("{got} per-vertex values for {vertices} vertices: give one per vertex")]
    Scalars {
        /// How many values were given.
        got: usize,
        /// How many vertices the mesh has.
        vertices: usize,
    },
    /// A strip with no panel.
    #[error("a picture needs at least one panel")]
    NoPanels,
    /// The PNG encoder failed.
    #[error("PNG encoding: {0}")]
    Png(String),
    /// The plotting library failed.
    #[error("plot: {0}")]
    Plot(String),
}
