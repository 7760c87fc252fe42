//! `envelope verify`: a certifying oracle for any simplifier's output (issue 6).

use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments (to be completed with the subcommand).
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Input mesh.
    input: PathBuf,
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    Err(format!(
        "verify is not implemented yet (input {})",
        args.input.display()
    ))
}
