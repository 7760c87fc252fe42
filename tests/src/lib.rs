//! Test support shared by the cross-crate integration tests (work in progress).
#![forbid(unsafe_code)]

pub mod r#gen;
pub mod oracle; // `gen` is reserved in edition 2024
