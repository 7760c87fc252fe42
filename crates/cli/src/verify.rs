//! `envelope verify`: a certifying oracle for any simplifier's output (issue 6).
//!
//! Exit codes: 0 every checked property holds, 1 one is violated (the report names it, with
//! witnesses), 2 unreadable input or bad arguments, 3 undecided within the resolution.
//!
//! `--map MAP.ply` writes APPROX with the certified bound of each vertex's surroundings as
//! its PLY `quality` and viridis colours over `0 ..= epsilon` (`envelope::save_error_map`),
//! whatever the verdict (a map is most useful where the certificate fails): the file
//! appears, atomically, once the bounds are computed; on an error (exit 2) nothing is
//! written. The JSON report then has the per-face bounds both ways (`map`).

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

use envelope::Mesh;
use envelope::advanced::io::{Format, read_path};
use envelope::advanced::verify::{
    Certificate, OneSided, Options, TopologySummary, Verdict, certify,
};

use crate::outputs::Plan;
use crate::ranges::{self, Length};

/// Arguments of `envelope verify`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// The original mesh.
    orig: PathBuf,
    /// The simplified mesh to certify against ORIG.
    approx: PathBuf,
    /// Tolerance, > 0: every point of each mesh must be within it of the other. An absolute
    /// length, or a percentage of ORIG's bounding-box diagonal (`0.5%`, `1/64%`), as for
    /// `simplify`.
    #[arg(long, value_parser = ranges::length, allow_hyphen_values = true)]
    epsilon: Length,
    /// Read a plain --epsilon (and --resolution) as fractions of ORIG's bounding-box diagonal.
    #[arg(long)]
    relative: bool,
    /// Answer `undecided` where the bounds are closer than this, >= 0 [default: 1e-6 *
    /// epsilon].
    #[arg(long, value_parser = ranges::resolution, allow_hyphen_values = true)]
    resolution: Option<f64>,
    /// Skip the self-intersection test of APPROX.
    #[arg(long)]
    no_self_intersections: bool,
    /// Count every intersecting pair of APPROX as a violation, also a pair of unchanged ORIG
    /// faces that met in ORIG already (by default those are allowed and listed as kept: what
    /// `simplify` leaves of a self-intersecting input).
    #[arg(long)]
    strict_intersections: bool,
    /// Skip the topology comparison.
    #[arg(long)]
    no_topology: bool,
    /// Only decide whether APPROX lies in ORIG's epsilon-envelope (every point of APPROX within
    /// epsilon of ORIG: the one-sided Hausdorff distance approx -> orig); orig -> approx is not
    /// checked. Self-intersections and topology follow their own flags.
    #[arg(long)]
    envelope_of: bool,
    /// Stop the self-intersection test at the first intersecting pair (same verdict; the
    /// report names one pair instead of all).
    #[arg(long)]
    stop_at_first: bool,
    /// Repair ORIG in memory first, without moving its surface (`envelope repair`): distances
    /// are the same, the topology compared is the repaired ORIG's. The JSON's `repair` lists
    /// the changes.
    #[arg(long)]
    repair: bool,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Write APPROX as an error map to this .ply file: per vertex, the certified upper bound
    /// of the distance to ORIG of the faces around it (`quality`, float) and its viridis
    /// colour over 0..epsilon (the range is in the header comments). Written whatever the
    /// verdict; the JSON report then has per-face bounds both ways. Takes a few times
    /// longer than plain verification.
    #[arg(long, value_name = "MAP.ply")]
    map: Option<PathBuf>,
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    if crate::scene::is_scene(&args.orig) || crate::scene::is_scene(&args.approx) {
        if args.relative || args.json || args.repair || args.envelope_of || args.map.is_some() {
            return Err(
                "--relative, --json, --repair, --envelope-of and --map are not available for glTF scenes"
                    .into(),
            );
        }
        return crate::scene::verify(&args.orig, &args.approx, &args.epsilon);
    }
    if let Some(path) = &args.map {
        // Checked before any work: an error map is a PLY file in a writable place.
        if !matches!(Format::from_path(path), Some(Format::Ply(_))) {
            return Err(format!(
                "--map {}: an error map is a PLY file; give a .ply path",
                path.display()
            ));
        }
        Plan::new(&[
            ("ORIG", args.orig.as_path()),
            ("APPROX", args.approx.as_path()),
        ])
        .file("--map", path)?;
    }
    let (orig, _) = read_path(&args.orig).map_err(|e| e.to_string())?;
    let label = args.orig.display().to_string();
    let (orig, repair) =
        crate::repair::maybe(Mesh::from_soup(orig), args.repair, &label, args.json)?;
    let orig = orig.into_soup();
    let (approx, _) = read_path(&args.approx).map_err(|e| e.to_string())?;
    let scale = if args.relative { orig.diagonal() } else { 1.0 };
    let epsilon = args.epsilon.resolve_as(
        "--epsilon",
        &args.orig.display().to_string(),
        &orig,
        args.relative,
    )?;
    let mut options = Options::new(epsilon);
    if let Some(r) = args.resolution {
        options.resolution = r * scale;
    }
    options.self_intersections = !args.no_self_intersections;
    options.allow_input_intersections = !args.strict_intersections;
    options.topology = !args.no_topology;
    options.orig_to_approx = !args.envelope_of;
    options.first_intersection_only = args.stop_at_first;
    options.map = args.map.is_some();
    let cert = certify(&orig, &approx, &options);
    if let Some(path) = &args.map {
        envelope::save_error_map(&Mesh::from_soup(approx), &cert, path)
            .map_err(|e| e.to_string())?;
    }
    if args.json {
        let mut v = cert.to_json();
        v["orig"] = args.orig.display().to_string().into();
        v["approx"] = args.approx.display().to_string().into();
        if let Some(path) = &args.map {
            v["map_file"] = path.display().to_string().into();
        }
        if let Some(r) = repair {
            v["repair"] = r;
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?
        );
    } else {
        print!("{}", render_text(args, &cert));
    }
    Ok(ExitCode::from(match cert.verdict {
        Verdict::Holds => 0,
        Verdict::Violated => 1,
        Verdict::Undecided => 3,
    }))
}

fn render_side(out: &mut String, name: &str, s: &OneSided, diag: f64) {
    let rel = |x: f64| if diag > 0.0 { x / diag } else { f64::NAN };
    let _ = writeln!(
        out,
        "{name:<16} {:<9} hausdorff in [{:.6e}, {:.6e}] ({:.3e} .. {:.3e} of diagonal)",
        s.verdict.as_str(),
        s.lower,
        s.upper,
        rel(s.lower),
        rel(s.upper)
    );
    if let Some(w) = &s.witness {
        let p = w.point;
        let _ = writeln!(
            out,
            "  witness: face {} point ({}, {}, {}){} distance >= {:.6e}",
            w.face,
            p.x,
            p.y,
            p.z,
            if w.exact_f64 {
                String::new()
            } else {
                format!(
                    " (rounded; exactly {:?}/2^{} of the corners)",
                    w.barycentric, w.level
                )
            },
            w.distance
        );
    }
    if s.undecided_regions > 0 {
        let _ = writeln!(
            out,
            "  {} region(s) undecided at the resolution",
            s.undecided_regions
        );
    }
}

fn render_topology(t: &TopologySummary) -> String {
    let genus = t.genus.map_or("undefined".to_string(), |g| g.to_string());
    format!(
        "genus {genus}, {} component(s), {} border loop(s)",
        t.components, t.border_loops
    )
}

fn render_text(args: &Args, c: &Certificate) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "verify {} against {}",
        args.approx.display(),
        args.orig.display()
    );
    let _ = writeln!(
        out,
        "epsilon {:e} ({:.3e} of diagonal {:e}), resolution {:e}",
        c.epsilon,
        c.epsilon / c.diagonal,
        c.diagonal,
        c.resolution
    );
    render_side(&mut out, "approx -> orig", &c.approx_to_orig, c.diagonal);
    if c.two_sided {
        render_side(&mut out, "orig -> approx", &c.orig_to_approx, c.diagonal);
    } else {
        let _ = writeln!(out, "orig -> approx   not checked (--envelope-of)");
    }
    let _ = writeln!(
        out,
        "envelope_of: {} (approx within epsilon of orig everywhere)",
        c.envelope_of().as_str()
    );
    if c.self_intersections_undecided {
        let _ = writeln!(
            out,
            "self-intersections of approx: undecided (faces stacked too densely to test every pair; none among the pairs tested)"
        );
    } else if let Some(pairs) = &c.self_intersections {
        let first: Vec<String> = pairs
            .iter()
            .take(5)
            .map(|(a, b)| format!("({a}, {b})"))
            .collect();
        let kept = c.kept_intersections.len();
        let _ = writeln!(
            out,
            "self-intersections of approx: {}{}{}{}",
            pairs.len(),
            if kept > 0 {
                format!(" new ({kept} kept from orig: unchanged faces that met there)")
            } else {
                String::new()
            },
            if c.self_intersections_complete || pairs.is_empty() {
                ""
            } else {
                " or more (stopped at the first)"
            },
            if first.is_empty() {
                String::new()
            } else {
                format!(" e.g. {}", first.join(" "))
            }
        );
    }
    if let Some(t) = &c.topology {
        let _ = writeln!(
            out,
            "topology {}: orig {}; approx {}",
            if t.matches() { "matches" } else { "differs" },
            render_topology(&t.orig),
            render_topology(&t.approx)
        );
    }
    if let (Some(path), Some(map)) = (&args.map, &c.map) {
        let _ = writeln!(
            out,
            "error map: {} (largest vertex bound {:.6e}; colours 0 .. epsilon)",
            path.display(),
            map.max_vertex_value()
        );
    }
    let v = c.violations();
    let _ = writeln!(
        out,
        "verdict: {}{}",
        c.verdict.as_str(),
        if v.is_empty() {
            String::new()
        } else {
            format!(" ({})", v.join(", "))
        }
    );
    out
}
