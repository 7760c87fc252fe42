//! `envelope repair IN OUT [--report R.json]`: repair that never moves the surface
//! (`envelope::repair`), and the `--repair` of `simplify`, `lod` and `verify` ([`in_memory`]).
//!
//! Exit codes: 0 repaired and now acceptable input, 1 repaired but still not acceptable (what
//! is left, e.g. intersecting faces, is printed and in the report; OUT is written: it is the
//! same surface with less wrong), 2 unreadable input, bad arguments, or a refusal naming the
//! element that cannot be repaired without moving the surface (OUT and the report untouched).
//! Outputs are checked before any work and written through `crate::outputs`.

use std::path::PathBuf;
use std::process::ExitCode;

use envelope::{Mesh, Repaired};

use crate::outputs::{Plan, Staging};

/// Arguments of `envelope repair`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL).
    input: PathBuf,
    /// Output mesh; the format follows the extension (.obj, .off, .ply, .stl). Its directory
    /// must exist; it must not be IN.
    output: PathBuf,
    /// Write the report (every change with counts and examples, what is left) as JSON to this
    /// file (its directory must exist).
    #[arg(long)]
    report: Option<PathBuf>,
    /// No summary (errors are still printed).
    #[arg(long)]
    quiet: bool,
}

/// The repair summary and, when the result is still not acceptable, what is left.
fn summary(label: &str, r: &Repaired) -> String {
    let mut s = format!("{label}: {}", r.report());
    if r.acceptable() {
        s.push_str("\nrepaired mesh: acceptable input");
    } else {
        let left: Vec<String> = r
            .left()
            .into_iter()
            .map(|c| {
                let f = r.check().finding(c);
                if f.undecided {
                    format!("{} (undecided: faces stacked too densely)", c.key())
                } else {
                    format!("{} ({})", c.key(), f.count)
                }
            })
            .collect();
        s.push_str(&format!(
            "\nrepaired mesh: still not acceptable, left: {} (not repairable without moving the surface)",
            left.join(", ")
        ));
    }
    s
}

/// The `--repair` of `simplify`, `lod` and `verify`: when `on`, `mesh` repaired in memory
/// (its point set unchanged, so certificates against it hold against the file; its topology
/// measured after the repair), the summary printed unless `quiet`, and the report's JSON for
/// the command's own report under `"repair"`. A refusal is an error naming the element.
pub(crate) fn maybe(
    mesh: Mesh,
    on: bool,
    label: &str,
    quiet: bool,
) -> Result<(Mesh, Option<serde_json::Value>), String> {
    if !on {
        return Ok((mesh, None));
    }
    let repaired = envelope::repair(&mesh).map_err(|e| format!("{label}: {e}"))?;
    if !quiet {
        println!("{}", summary(label, &repaired));
    }
    let json = repaired.to_json();
    Ok((repaired.into_mesh(), Some(json)))
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    let mut plan = Plan::new(&[("IN", args.input.as_path())]);
    let format = plan.mesh("OUT", &args.output)?;
    if let Some(path) = &args.report {
        plan.file("--report", path)?;
    }
    let input = args.input.display().to_string();
    let mesh = envelope::load(&args.input).map_err(|e| e.to_string())?;
    let repaired = envelope::repair(&mesh).map_err(|e| format!("{input}: {e}"))?;
    let mut staging = Staging::new();
    staging.mesh_with_attributes(&args.output, repaired.mesh(), format, args.quiet)?;
    if let Some(path) = &args.report {
        let mut v = serde_json::json!({
            "input": input,
            "output": args.output.display().to_string(),
        });
        v["repair"] = repaired.to_json();
        v["check"] = repaired.check().to_json();
        let text = serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?;
        staging.text(path, &(text + "\n"))?;
    }
    staging.commit()?;
    if !args.quiet {
        println!("{}", summary(&input, &repaired));
    }
    Ok(if repaired.acceptable() {
        ExitCode::SUCCESS
    } else {
        if args.quiet {
            let left: Vec<&str> = repaired.left().into_iter().map(|c| c.key()).collect();
            eprintln!(
                "envelope: {input}: repaired but still not acceptable: {}",
                left.join(", ")
            );
        }
        ExitCode::from(1)
    })
}
