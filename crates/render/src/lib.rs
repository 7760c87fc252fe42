//! Pictures without a GPU: a deterministic CPU rasterizer for meshes and their levels of
//! detail, colour ramps for per-vertex values, and plots of faces against epsilon.
//!
//! Everything is drawn on the CPU in a fixed order, with a public-domain bitmap font (no
//! system fonts, no C libraries), and encoded without timestamps: the same input gives the
//! same PNG bytes on every machine.
//!
//! ```
//! use envelope_render::{Panel, Size, Style, View, render};
//! let cube = envelope_mesh::generate::box_mesh(glam::DVec3::ONE, 1);
//! let style = Style { view: View::new(30.0, 20.0)?, wireframe: true, ..Style::default() };
//! let panel = Panel { mesh: &cube, caption: "cube  12 faces", scalars: None };
//! let png = render(&panel, &style, Size::new(160, 120)?)?.to_png()?;
//! assert_eq!(&png[1..4], b"PNG");
//! # Ok::<(), envelope_render::RenderError>(())
//! ```
#![forbid(unsafe_code)]

mod camera;
mod canvas;
mod error;
mod limits;
pub mod plot;
pub mod ramp;
mod raster;
pub mod text;

pub use camera::{Projection, Up, View};
pub use canvas::{Canvas, Size};
pub use error::RenderError;
pub use limits::{MAX_PIXELS, MAX_SIDE, MIN_SIDE};
pub use raster::{Panel, Style, render, render_strip};
