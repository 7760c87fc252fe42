//! Simplification envelopes: vertex normals, analytical and numerical epsilon, per-vertex epsilon fields and border tubes (Cohen et al. 3, 4, 6.2, 6.3).
#![forbid(unsafe_code)]
