//! Shared helpers for the benchmarks (work in progress).
#![forbid(unsafe_code)]
