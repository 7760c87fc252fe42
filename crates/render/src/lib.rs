//! Pictures without a GPU: colour ramps for error maps, and (to come) a CPU rasterizer and
//! plots of meshes and their levels of detail.
#![forbid(unsafe_code)]

pub mod ramp;
