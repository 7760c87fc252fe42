//! Mesh file formats (work in progress).
#![forbid(unsafe_code)]
