//! The `envelope` program.
//!
//! Exit codes, for every subcommand: 0 success (for `check`: acceptable input), 1 the mesh has
//! degeneracies, 2 the input cannot be read or the arguments are wrong.
#![forbid(unsafe_code)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use envelope_check::{CheckOptions, CheckReport, DegeneracyClass, Element, Severity, check};
use envelope_io::{Format, ReadReport, read_path, write_path};
use envelope_mesh::{TriangleSoup, generate};

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

fn run_check(input: &Path, json: bool, examples: usize) -> Result<ExitCode, String> {
    let (soup, read_report) = read_path(input).map_err(|e| e.to_string())?;
    let options = CheckOptions {
        max_examples: examples,
        ..CheckOptions::default()
    };
    let report = check(&soup, &options);
    if json {
        let mut v = report.to_json();
        v["file"] = input.display().to_string().into();
        v["format"] = read_report.format.to_string().into();
        v["polygons_triangulated"] = read_report.polygons_triangulated.into();
        v["read_notes"] = read_report
            .to_string()
            .lines()
            .skip(1)
            .collect::<Vec<_>>()
            .into();
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", render_text(input, &read_report, &report));
    }
    Ok(if report.acceptable() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
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

fn yes_no(b: bool) -> &'static str {
    if b { "yes" } else { "no" }
}

fn describe(e: &Element) -> String {
    let p = |p: glam::DVec3| format!("({}, {}, {})", p.x, p.y, p.z);
    match e {
        Element::Vertex { vertex, position } => format!("{vertex} at {}", p(*position)),
        Element::VertexGroup { vertices, position } => {
            let ids: Vec<String> = vertices.iter().map(ToString::to_string).collect();
            format!("{} at {}", ids.join(" "), p(*position))
        }
        Element::Face {
            face,
            vertices: [a, b, c],
            quality,
        } => match quality {
            Some(q) => format!("{face} [{a} {b} {c}] quality {q:.2e}"),
            None => format!("{face} [{a} {b} {c}]"),
        },
        Element::FacePair { faces: [f, g] } => format!("{f} x {g}"),
        Element::Edge {
            edge: [a, b],
            faces,
        } => {
            let fs: Vec<String> = faces.iter().map(ToString::to_string).collect();
            format!("{a}-{b} in {}", fs.join(" "))
        }
        Element::VertexOnEdge {
            vertex,
            position,
            edge: [a, b],
        } => {
            format!("{vertex} at {} inside {a}-{b}", p(*position))
        }
    }
}

fn render_text(input: &Path, read: &ReadReport, r: &CheckReport) -> String {
    let mut s = String::new();
    let genus = r
        .genus
        .map_or_else(|| "undefined".to_owned(), |g| g.to_string());
    let _ = writeln!(s, "file        {}", input.display());
    for line in read.to_string().lines() {
        let _ = writeln!(s, "read        {line}");
    }
    let _ = writeln!(
        s,
        "counts      {} vertices, {} faces, {} edges, {} border loops, {} components",
        r.vertices, r.faces, r.edges, r.border_loops, r.components
    );
    let _ = writeln!(
        s,
        "topology    euler {}, genus {genus}, manifold {}, orientable {}",
        r.euler,
        yes_no(r.manifold),
        yes_no(r.orientable)
    );
    let _ = writeln!(s, "degeneracies");
    for class in DegeneracyClass::ALL {
        let Some(f) = r.degeneracies.get(&class) else {
            continue;
        };
        let severity = match class.severity() {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let _ = write!(s, "  {:<26} {:>8}  {severity:<7}", class.key(), f.count);
        if f.count > 0 {
            let ex: Vec<String> = f.examples.iter().map(describe).collect();
            let more = if f.count > ex.len() { ", ..." } else { "" };
            let _ = write!(s, "  {}{more}", ex.join(", "));
        }
        s.push('\n');
    }
    let errors: Vec<&str> = r.errors().map(DegeneracyClass::key).collect();
    if errors.is_empty() {
        let _ = writeln!(s, "verdict     acceptable input");
    } else {
        let _ = writeln!(s, "verdict     not acceptable: {}", errors.join(", "));
    }
    s
}
