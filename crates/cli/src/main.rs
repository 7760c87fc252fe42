//! The `envelope` program.
//!
//! Exit codes: 0 success (for `check`: acceptable input), 1 the mesh has degeneracies (for
//! `verify`: a property is violated), 2 the input cannot be read or the arguments are wrong,
//! 3 (`verify` only) undecided.
//!
//! One module per subcommand; each exposes `Args` (clap) and `run(&Args) -> Result<ExitCode,
//! String>` (an `Err` is printed as `envelope: error: ...` with exit 2).
#![forbid(unsafe_code)]

mod check;
mod envelopes;
mod verify;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use envelope_io::{Format, write_path};
use envelope_mesh::{TriangleSoup, generate};

use check::run_check;

/// Guaranteed-error triangle-mesh simplification (Cohen et al. 1996; El-Sana and Varshney 1997).
#[derive(Parser)]
#[command(name = "envelope", version, about, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Counts, topology and every degeneracy class of a mesh (Simplification Envelopes, 7.1).
    ///
    /// Exit 0 when the mesh is acceptable input for the simplifier, 1 when it has degeneracies
    /// of an error class, 2 when it cannot be read. Warnings (unreferenced vertices, sliver
    /// triangles) do not change the exit code.
    Check {
        /// Mesh file: OBJ, OFF, PLY (ascii or binary) or STL (ascii or binary).
        input: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// How many offending elements to list per class.
        #[arg(long, default_value_t = 5)]
        examples: usize,
    },
    /// Inner and outer simplification envelopes and border tubes (Cohen et al. 3, 4, 6.2-6.3).
    Envelopes(envelopes::Args),
    /// Certify that APPROX is within epsilon of ORIG both ways, free of self-intersections,
    /// and of the same topology (exit 0 holds, 1 violated, 2 unreadable, 3 undecided).
    Verify(verify::Args),
    /// Run the main job on a built-in model, writing into ./envelope-demo/.
    ///
    /// Until the simplifier lands, the main job is `check` on the built-in model.
    Demo {
        /// Output directory.
        #[arg(long, default_value = "envelope-demo")]
        out_dir: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Check {
            input,
            json,
            examples,
        } => run_check(&input, json, examples),
        Command::Envelopes(args) => envelopes::run(&args),
        Command::Verify(args) => verify::run(&args),
        Command::Demo { out_dir } => run_demo(&out_dir),
    };
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("envelope: error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The built-in model: a torus (curved, genus 1). The simplifier issue replaces it with a
/// model that also has sharp edges and a border.
fn builtin_model() -> TriangleSoup {
    generate::torus(1.0, 0.35, 96, 48)
}

fn run_demo(out_dir: &Path) -> Result<ExitCode, String> {
    std::fs::create_dir_all(out_dir)
        .map_err(|e| format!("cannot create {}: {e}", out_dir.display()))?;
    let model = builtin_model();
    let path = out_dir.join("model.off");
    write_path(&path, &model, Format::Off).map_err(|e| e.to_string())?;
    println!("wrote the built-in model to {}", path.display());
    run_check(&path, false, 5)
}
