//! The local simplifier of Simplification Envelopes (sections 5.1, 5.2).
#![forbid(unsafe_code)]
