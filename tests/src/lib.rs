//! Test support shared by the cross-crate integration tests (work in progress).
#![forbid(unsafe_code)]

pub mod oracle;
