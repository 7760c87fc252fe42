//! Exact geometric predicates (work in progress).
#![forbid(unsafe_code)]
