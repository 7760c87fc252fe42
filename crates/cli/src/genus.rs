//! `envelope genus IN OUT --alpha A [--beta DEG] [--sharp | --union] [--report R.json]`:
//! controlled genus reduction (El-Sana and Varshney 1997) with
//! `envelope::advanced::genus::reduce_genus_with`. By default the sharp-edge step, then the
//! regions the L-infinity closing swallows (`--closing`, said explicitly); `--sharp` the
//! sharp-edge step alone; `--union` the rims from the union of alpha-prisms (the paper's
//! option, sections 3.3 and 4).

use std::path::PathBuf;
use std::process::ExitCode;

use envelope::{Epsilon, Genus, GenusReport, Mesh, TessellationSource, defaults};

use crate::outputs::{Plan, Staging};
use crate::ranges::{self, Length, show, show_genus};

/// Arguments of `envelope genus`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL).
    pub input: PathBuf,
    /// Output mesh; the format follows the extension (.obj, .off, .ply, .stl). Its directory
    /// must exist; it must not be IN. Replaced only when the command succeeds.
    pub output: PathBuf,
    /// L-infinity radius, > 0: holes a cube of side 2*alpha cannot pass are filled. Absolute,
    /// or a percentage of the bounding-box diagonal ("2%").
    #[arg(long, value_parser = ranges::length, allow_hyphen_values = true)]
    pub alpha: Length,
    /// Sharp-edge threshold in degrees (angle between face normals): (0, 180).
    #[arg(long, default_value_t = defaults::GENUS_BETA_DEGREES, value_parser = ranges::beta, allow_hyphen_values = true)]
    pub beta: f64,
    /// Take rims from the sharp edges and the union of alpha-prisms instead (fills narrow
    /// tunnels and holes through smooth, non-sharp surfaces; slower: every face's prism is
    /// paired).
    #[arg(long, conflicts_with_all = ["closing", "sharp"])]
    pub union: bool,
    /// The default, said explicitly: after the sharp-edge rims, fill the regions the
    /// L-infinity closing by the cube swallows (estimated on voxels, every cap checked
    /// exactly): networks of tunnels whose junctions are not sharp. Inputs with borders
    /// (no solid) get the sharp-edge step alone.
    #[arg(long, conflicts_with = "sharp")]
    pub closing: bool,
    /// The paper's sharp-edge step alone: only regions bounded by sharp rims are filled
    /// (faster; a network of tunnels whose junctions are not sharp stays).
    #[arg(long)]
    pub sharp: bool,
    /// Write the report as JSON here (its directory must exist).
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// Runs the genus reduction on a mesh already read (shared with `envelope pipeline`).
pub(crate) fn reduce(
    mesh: &Mesh,
    alpha: f64,
    beta: f64,
    source: TessellationSource,
) -> Result<(Mesh, GenusReport), String> {
    Genus::new(Epsilon::absolute(alpha))
        .beta_degrees(beta)
        .source(source)
        .run(mesh)
        .map_err(|e| e.to_string())
}

/// Runs `envelope genus`.
pub fn run(args: &Args) -> Result<ExitCode, String> {
    let mut plan = Plan::new(&[("IN", &args.input)]);
    let format = plan.mesh("OUT", &args.output)?;
    if let Some(path) = &args.report {
        plan.file("--report", path)?;
    }
    let mesh = envelope::load(&args.input).map_err(|e| e.to_string())?;
    let alpha = args
        .alpha
        .resolve("--alpha", &args.input.display().to_string(), mesh.soup())?;
    let source = if args.sharp {
        TessellationSource::SharpEdges
    } else if args.union {
        TessellationSource::PrismUnion
    } else if args.closing {
        TessellationSource::Closing
    } else {
        TessellationSource::default()
    };
    let (out, report) = reduce(&mesh, alpha, args.beta, source)
        .map_err(|e| format!("{}: {e}", args.input.display()))?;
    if !mesh.attributes().is_empty() {
        // The tessellation makes new surface: its corners would need values from nowhere.
        eprintln!(
            "envelope: note: genus does not carry texture coordinates, normals or colours; \
             {} has none",
            args.output.display()
        );
    }
    let mut staging = Staging::new();
    staging.mesh(&args.output, out.soup(), format)?;
    if let Some(path) = &args.report {
        let mut json = report.to_json();
        json["alpha"] = serde_json::json!(alpha);
        json["beta_degrees"] = serde_json::json!(args.beta);
        json["union"] = serde_json::json!(args.union);
        json["closing"] = serde_json::json!(source == TessellationSource::Closing);
        json["input"] = serde_json::json!(args.input.display().to_string());
        let text = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
        staging.text(path, &(text + "\n"))?;
    }
    staging.commit()?;
    let pieces = if report.pieces > 0 {
        format!(
            " ({} split into {} pieces at {} points on long rim edges)",
            report.split_faces, report.pieces, report.points_added
        )
    } else {
        String::new()
    };
    println!(
        "genus {} -> {}, border loops {} -> {}, {} rims capped, {} triangles added, {} removed{pieces}, faces {} -> {}, {:.3} s (alpha = {})",
        show_genus(report.genus_in),
        show_genus(report.genus_out),
        report.border_loops_in,
        report.border_loops_out,
        report.holes_filled,
        report.triangles_added,
        report.triangles_removed,
        report.faces_in,
        report.faces_out,
        report.seconds,
        show(alpha),
    );
    Ok(ExitCode::SUCCESS)
}
