//! `envelope envelopes`: inner/outer envelopes and border tubes (issue 4).

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
        "envelopes is not implemented yet (input {})",
        args.input.display()
    ))
}
