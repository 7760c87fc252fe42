//! Helpers shared by the end-to-end tests of the `envelope` binary (each test file uses
//! some of them).
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// The `envelope` binary built for these tests.
pub fn envelope() -> Command {
    Command::new(env!("CARGO_BIN_EXE_envelope"))
}

/// Fails, showing the process's stderr, unless it exited 0.
pub fn assert_ok(out: &Output) {
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A JSON file (a report or a summary).
pub fn read_json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}
