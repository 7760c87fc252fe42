//! Input checking (work in progress).
#![forbid(unsafe_code)]
