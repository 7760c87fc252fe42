//! The `envelope` program (work in progress).
fn main() {}
