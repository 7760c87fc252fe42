//! The `envelope` program.
//!
//! Exit codes: 0 success (for `check`: acceptable input), 1 the mesh has degeneracies (for
//! `verify`, `simplify`, `lod`, `demo`: the output violates a certified property), 2 the input
//! cannot be read or is not acceptable, or the arguments are wrong, 3 (`verify`, `simplify`,
//! `lod`, `demo`) a certificate is undecided.
//!
//! One module per subcommand; each exposes `Args` (clap) and `run(&Args) -> Result<ExitCode,
//! String>` (an `Err` is printed as `envelope: error: ...` with exit 2).
//!
//! Shared by every subcommand: `outputs` (each output checked before any work, all written
//! to temporaries and put in place only when the command completes, so exit 2 replaces
//! nothing) and `ranges` (the valid range of each numeric argument, checked by clap).
#![forbid(unsafe_code)]

mod batch;
mod check;
mod envelopes;
mod genus;
mod lod;
mod outputs;
mod pipeline;
mod ranges;
mod render;
mod repair;
mod scene;
mod simplify;
mod verify;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use check::run_check;

/// Guaranteed-error triangle-mesh simplification (Cohen et al. 1996; El-Sana and Varshney 1997).
#[derive(Parser)]
#[command(name = "envelope", version, about, max_term_width = 100)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Worker threads, 1..=1024 (default: one per core, or RAYON_NUM_THREADS). Outputs are
    /// the same for any number.
    #[arg(long, global = true, value_parser = ranges::threads, allow_hyphen_values = true)]
    threads: Option<usize>,
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
        /// How many offending elements to list per class: 0..=10000.
        #[arg(long, default_value_t = 5, value_parser = ranges::examples, allow_hyphen_values = true)]
        examples: usize,
    },
    /// Inner and outer simplification envelopes and border tubes (Cohen et al. 3, 4, 6.2-6.3).
    Envelopes(envelopes::Args),
    /// Certify that APPROX is within epsilon of ORIG both ways, free of self-intersections,
    /// and of the same topology (exit 0 holds, 1 violated, 2 unreadable, 3 undecided).
    Verify(verify::Args),
    /// Simplify IN within epsilon of it (Cohen et al. 5-6) and write OUT atomically.
    ///
    /// Exit 0 written and certified, 1 the output fails its certificate (OUT untouched, the
    /// output goes to OUT.failed.EXT) or the envelopes could not be proved (nothing written),
    /// 2 bad input or arguments (OUT and the report untouched), 3 certificate undecided.
    Simplify(simplify::Args),
    /// Levels of detail with nested vertex sets and switching distances (Cohen et al. 7.2).
    ///
    /// Writes OUTDIR/level-0.off (the input), level-1.off, ... and summary.json, all at the
    /// end; OUTDIR is created if missing (its parent must exist). A glTF IN (.glb, .gltf)
    /// gives one file OUT.glb with the levels as MSFT_lod nodes (and, with
    /// --per-level-files, OUT-level-K.glb).
    Lod(lod::Args),
    /// Fill the holes and tunnels an L-infinity cube of side 2*alpha cannot pass (El-Sana and
    /// Varshney 1997) and write OUT atomically.
    Genus(genus::Args),
    /// Alternate genus-preserving (eX) and genus-reducing (aX as `envelope genus`; sX the
    /// sharp-edge step alone, uX the union of alpha-prisms) steps; writes
    /// OUTDIR/stage-0.off (the input), stage-1.off, ... and summary.json.
    Pipeline(pipeline::Args),
    /// Simplify every item of a JSON Lines manifest into OUTDIR/<id>/, resumably (a rerun
    /// does no work for finished items), with OUTDIR/summary.jsonl.
    ///
    /// Exit 0 every item is ok, 1 some item is not (see the summary), 2 the manifest or the
    /// arguments are wrong.
    Batch(batch::Args),
    /// Repair IN without moving its surface (weld, duplicate and zero-area faces,
    /// T-junctions, non-manifold sheets, orientation) and write OUT atomically.
    ///
    /// Exit 0 repaired and acceptable input, 1 repaired but still not acceptable (what is
    /// left is printed; OUT is written), 2 unreadable, bad arguments, or refused (the element
    /// that cannot be repaired without moving the surface is named; OUT untouched).
    Repair(repair::Args),
    /// Pictures of meshes side by side, drawn on the CPU (no GPU, no system fonts): flat
    /// shading, optional wireframe and per-vertex colours, a caption each; written as PNG.
    ///
    /// Exit 0 written, 2 bad arguments or unreadable input (OUT untouched).
    Render(render::Args),
    /// Run the main job on a built-in model (a cup: curved wall, sharp bottom crease, open
    /// rim): its chain of levels of detail at 1/64% ... 1%, certified, into ./envelope-demo/,
    /// with a picture of the chain (lod.png) and its faces against epsilon.
    Demo {
        /// Output directory: created if missing (its parent must exist); files in it are
        /// replaced only when the command completes.
        #[arg(long, default_value = "envelope-demo")]
        out_dir: PathBuf,
    },
}

/// A reader that stops early (`envelope check m.off --json | head`) closes stdout, and
/// `println!` then panics: end quietly instead, as other command-line tools do, with the
/// status of SIGPIPE's default action (128 + 13). Outputs are unaffected (they are files,
/// renamed into place only when complete).
fn quiet_on_closed_stdout() {
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(141);
        }
        default_hook(info);
    }));
}

fn main() -> ExitCode {
    quiet_on_closed_stdout();
    let cli = Cli::parse();
    // The command runs on a worker of the pool (`in_pool`): from outside the pool every
    // parallel batch of the local simplifier would put this thread to sleep and wake it.
    let result = envelope::advanced::in_pool(cli.threads, move || match cli.command {
        Command::Check {
            input,
            json,
            examples,
        } => run_check(&input, json, examples),
        Command::Envelopes(args) => envelopes::run(&args),
        Command::Verify(args) => verify::run(&args),
        Command::Simplify(args) => simplify::run(&args),
        Command::Lod(args) => lod::run(&args),
        Command::Genus(args) => genus::run(&args),
        Command::Pipeline(args) => pipeline::run(&args),
        Command::Batch(args) => batch::run(&args),
        Command::Repair(args) => repair::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Demo { out_dir } => run_demo(&out_dir),
    })
    .map_err(|e| e.to_string())
    .and_then(|r| r);
    match result {
        Ok(code) => code,
        Err(message) => {
            eprintln!("envelope: error: {message}");
            ExitCode::from(2)
        }
    }
}

/// The built-in model: a cup with curvature, a sharp crease and a border
/// (`envelope::Mesh::demo`).
fn run_demo(out_dir: &Path) -> Result<ExitCode, String> {
    let epsilons = ranges::lengths(lod::DEFAULT_EPSILONS)?.0;
    lod::plan_chain(
        &mut outputs::Plan::new(&[]),
        out_dir,
        epsilons.len(),
        false,
        true,
    )?;
    let model = envelope::Mesh::demo();
    println!(
        "built-in model: a cup, {} faces, {} vertices (curved fluted wall, sharp bottom crease, open rim)",
        model.num_faces(),
        model.num_vertices()
    );
    lod::run_chain(
        &model,
        lod::Chain {
            input_label: "built-in cup (generate::demo_model)".into(),
            out_dir,
            epsilons: &epsilons,
            settings: lod::Settings::default(),
            quiet: false,
            repair: None,
            // The cup stands on its bottom along +Z.
            picture: Some(envelope_render::Up::Z),
        },
    )
}
