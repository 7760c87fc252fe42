//! Fundamental prisms with bilinear-patch sides (Simplification Envelopes, sections 3-4): exact point, segment and triangle classification.
#![forbid(unsafe_code)]
