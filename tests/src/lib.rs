//! Test support shared by the cross-crate integration tests (work in progress).
#![forbid(unsafe_code)]

pub mod oracle;
pub mod r#gen; // `gen` is reserved in edition 2024
