//! `envelope genus IN OUT --alpha A [--beta DEG] [--union] [--report R.json]`: controlled
//! genus reduction (El-Sana and Varshney 1997) with `envelope_genus::reduce_genus_with`;
//! `--union` adds the rims from the union of alpha-prisms (the paper's option, sections 3.3
//! and 4), which fill narrow passages through smooth surfaces.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use envelope_genus::{GenusOptions, GenusReport, TessellationSource, reduce_genus_with};
use envelope_io::{Format, read_path, write_path};
use envelope_mesh::TriangleSoup;
use envelope_offset::parse_epsilon;

/// Arguments of `envelope genus`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL).
    pub input: PathBuf,
    /// Output mesh; the format follows the extension (written atomically).
    pub output: PathBuf,
    /// L-infinity radius: holes a cube of side 2*alpha cannot pass are filled. Absolute, or
    /// a percentage of the bounding-box diagonal ("2%").
    #[arg(long)]
    pub alpha: String,
    /// Sharp-edge threshold in degrees (angle between face normals).
    #[arg(long, default_value_t = 70.0)]
    pub beta: f64,
    /// Also take rims from the union of alpha-prisms (fills narrow tunnels and holes through
    /// smooth, non-sharp surfaces; slower: every face's prism is paired).
    #[arg(long)]
    pub union: bool,
    /// Write the report as JSON here.
    #[arg(long)]
    pub report: Option<PathBuf>,
}

/// Resolves an `--alpha`/`--epsilon`-style length ("0.5", "2%") against `diagonal`.
pub(crate) fn resolve_length(flag: &str, s: &str, diagonal: f64) -> Result<f64, String> {
    let v = parse_epsilon(s)
        .map_err(|e| format!("{flag} {s:?}: {e}"))?
        .resolve(diagonal);
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(format!("{flag} {s:?}: must resolve to a positive length"))
    }
}

/// The output format for `path` (from its extension).
pub(crate) fn format_for(path: &Path) -> Result<Format, String> {
    Format::from_path(path).ok_or_else(|| {
        format!(
            "{}: unknown output extension (use .obj, .off, .ply or .stl)",
            path.display()
        )
    })
}

/// Runs the genus reduction on a mesh already read (shared with `envelope pipeline`).
pub(crate) fn reduce(
    soup: &TriangleSoup,
    alpha: f64,
    beta: f64,
    union: bool,
) -> Result<(TriangleSoup, GenusReport), String> {
    let options = GenusOptions {
        alpha,
        beta_degrees: beta,
    };
    let source = if union {
        TessellationSource::PrismUnion
    } else {
        TessellationSource::SharpEdges
    };
    reduce_genus_with(soup, &options, source).map_err(|e| e.to_string())
}

/// Runs `envelope genus`.
pub fn run(args: &Args) -> Result<ExitCode, String> {
    let format = format_for(&args.output)?;
    let (soup, _) = read_path(&args.input).map_err(|e| e.to_string())?;
    let alpha = resolve_length("--alpha", &args.alpha, soup.diagonal())?;
    let (out, report) = reduce(&soup, alpha, args.beta, args.union)?;
    write_path(&args.output, &out, format).map_err(|e| e.to_string())?;
    let fmt_genus = |g: Option<u32>| g.map_or_else(|| "undefined".to_string(), |g| g.to_string());
    println!(
        "genus {} -> {}, border loops {} -> {}, {} rims capped, {} triangles added, {} removed, faces {} -> {}, {:.3} s (alpha = {alpha})",
        fmt_genus(report.genus_in),
        fmt_genus(report.genus_out),
        report.border_loops_in,
        report.border_loops_out,
        report.holes_filled,
        report.triangles_added,
        report.triangles_removed,
        report.faces_in,
        report.faces_out,
        report.seconds,
    );
    if let Some(path) = &args.report {
        let mut json = report.to_json();
        json["alpha"] = serde_json::json!(alpha);
        json["beta_degrees"] = serde_json::json!(args.beta);
        json["union"] = serde_json::json!(args.union);
        json["input"] = serde_json::json!(args.input.display().to_string());
        let text = serde_json::to_string_pretty(&json).map_err(|e| e.to_string())?;
        write_text_atomic(path, &text)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes `text` to `path` through a temporary file and a rename.
pub(crate) fn write_text_atomic(path: &Path, text: &str) -> Result<(), String> {
    let tmp = path.with_extension("json.tmp");
    std::fs::write(&tmp, text).map_err(|e| format!("{}: {e}", tmp.display()))?;
    std::fs::rename(&tmp, path).map_err(|e| format!("{}: {e}", path.display()))
}
