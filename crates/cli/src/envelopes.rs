//! `envelope envelopes`: inner/outer envelopes and border tubes (Cohen et al. 3, 4, 6.2, 6.3).
//!
//! Writes `outer.EXT`, `inner.EXT` and `tube-N.EXT` into the output directory, prints the
//! achieved per-vertex epsilon (min, median, max as a fraction of the requested), the time
//! and the exact non-intersection proof. Exit 0 when proved, 1 when not, 2 for bad input.
//! The output directory is checked before any work and its files are put in place together
//! at the end (`crate::outputs`); a missing one is created (not its parents).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use envelope::advanced::io::{Format, PlyEncoding, read_path};
use envelope::advanced::offset::{
    EnvelopeOptions, EpsilonField, build_envelopes, read_epsilon_file,
};

use crate::outputs::{Plan, Staging};
use crate::ranges::{self, Length};
use crate::simplify::MethodArg;

/// Output mesh format.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
enum FormatArg {
    Off,
    Ply,
}

/// Arguments of `envelope envelopes`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL); must be manifold and consistently oriented.
    input: PathBuf,
    /// Requested epsilon, > 0: `0.5%` or `1/64%` of the bounding-box diagonal, or an absolute
    /// length.
    #[arg(long, required_unless_present = "epsilon_file", value_parser = ranges::length, allow_hyphen_values = true)]
    epsilon: Option<Length>,
    /// Per-vertex epsilon file: one value per line in vertex order (same syntax as
    /// --epsilon), `#` comments.
    #[arg(long, conflicts_with = "epsilon")]
    epsilon_file: Option<PathBuf>,
    /// Epsilon method (the default is `simplify`'s).
    #[arg(long, value_enum, default_value_t = MethodArg::default_())]
    method: MethodArg,
    /// Output directory: created if missing (its parent must exist); files in it are
    /// replaced only when the command completes.
    #[arg(long, default_value = "envelopes-out")]
    out_dir: PathBuf,
    /// Output mesh format.
    #[arg(long, value_enum, default_value_t = FormatArg::Off)]
    format: FormatArg,
    /// Vertices per border-tube ring: 0 (no tubes) or 3..=64.
    #[arg(long, default_value_t = 8, value_parser = ranges::tube_segments, allow_hyphen_values = true)]
    tube_segments: u32,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    let (format, ext) = match args.format {
        FormatArg::Off => (Format::Off, "off"),
        FormatArg::Ply => (Format::Ply(PlyEncoding::BinaryLittleEndian), "ply"),
    };
    let mut inputs = vec![("INPUT", args.input.as_path())];
    if let Some(path) = &args.epsilon_file {
        inputs.push(("--epsilon-file", path));
    }
    let mut plan = Plan::new(&inputs);
    let names = [format!("outer.{ext}"), format!("inner.{ext}")];
    plan.dir("--out-dir", &args.out_dir, &names)?;
    let tube_ext = format!(".{ext}");
    plan.inputs_not_in("--out-dir", &args.out_dir, |n| {
        n.starts_with("tube-") && n.ends_with(&tube_ext)
    })?;
    let (soup, _) = read_path(&args.input).map_err(|e| e.to_string())?;
    let diagonal = soup.diagonal();
    let field = match (&args.epsilon, &args.epsilon_file) {
        (Some(e), _) => EpsilonField::Constant(e.resolve(
            "--epsilon",
            &args.input.display().to_string(),
            &soup,
        )?),
        (None, Some(f)) => {
            let specs = read_epsilon_file(f, soup.num_vertices())
                .map_err(|err| format!("--epsilon-file {}: {err}", f.display()))?;
            EpsilonField::from_specs(&specs, diagonal)
        }
        (None, None) => return Err("--epsilon or --epsilon-file is required".into()),
    };
    let flag = match (&args.epsilon, &args.epsilon_file) {
        (Some(e), _) => format!("--epsilon {}", e.text),
        (None, Some(f)) => format!("--epsilon-file {}", f.display()),
        (None, None) => String::new(),
    };
    ranges::epsilon_in_range(&flag, &args.input.display().to_string(), &field, &soup)?;
    let mut options = EnvelopeOptions::new(field);
    options.method = args.method.method();
    options.tube_segments = (args.tube_segments > 0).then_some(args.tube_segments);
    let start = Instant::now();
    let env =
        build_envelopes(&soup, &options).map_err(|e| format!("{}: {e}", args.input.display()))?;
    let seconds = start.elapsed().as_secs_f64();

    let mut staging = Staging::new();
    staging.dir(&args.out_dir)?;
    let mut written = Vec::new();
    let mut write =
        |name: String, mesh: &envelope::advanced::mesh::TriangleSoup| -> Result<(), String> {
            let p = args.out_dir.join(name);
            staging.mesh(&p, mesh, format)?;
            written.push(p.display().to_string());
            Ok(())
        };
    write(format!("outer.{ext}"), &env.outer)?;
    write(format!("inner.{ext}"), &env.inner)?;
    for (i, t) in env.tubes.iter().enumerate() {
        write(format!("tube-{i}.{ext}"), &t.mesh)?;
    }
    staging.commit()?;

    let fractions = env.achieved_fractions();
    let (min, median, max) = (
        quantile(&fractions, 0.0),
        quantile(&fractions, 0.5),
        quantile(&fractions, 1.0),
    );
    let proved = env.proof.holds();
    let method = format!("{:?}", options.method).to_lowercase();
    if args.json {
        let contacts: Vec<serde_json::Value> = env
            .proof
            .contacts
            .iter()
            .chain(&env.proof.tube_contacts)
            .take(100)
            .map(|c| {
                serde_json::json!([
                    format!("{:?}", c.a.0),
                    c.a.1.0,
                    format!("{:?}", c.b.0),
                    c.b.1.0
                ])
            })
            .collect();
        let v = serde_json::json!({
            "input": args.input.display().to_string(),
            "method": method,
            "diagonal": diagonal,
            "epsilon_fraction": { "min": min, "median": median, "max": max },
            "seconds": seconds,
            "proved": proved,
            "contacts": env.proof.contacts.len(),
            "tube_contacts": env.proof.tube_contacts.len(),
            "first_contacts": contacts,
            "repair_rounds": env.proof.repair_rounds,
            "repaired_vertices": env.proof.repaired_vertices,
            "tubes": env.tubes.len(),
            "pinned": env.pinned.iter().map(|v| v.0).collect::<Vec<_>>(),
            "written": written,
        });
        println!("{v}");
    } else {
        println!("input            {}", args.input.display());
        println!("method           {method}");
        println!(
            "epsilon achieved min {:.1}%  median {:.1}%  max {:.1}% of requested",
            100.0 * min,
            100.0 * median,
            100.0 * max
        );
        println!("time             {seconds:.3} s");
        println!(
            "repair           {} rounds, {} vertices shrunk",
            env.proof.repair_rounds, env.proof.repaired_vertices
        );
        println!("tubes            {}", env.tubes.len());
        if !env.pinned.is_empty() {
            println!(
                "pinned           {} vertices without a valid normal (offsets zero; first: {})",
                env.pinned.len(),
                env.pinned[0].0
            );
        }
        if proved {
            println!(
                "proof            PROVED: no self-intersection, none with the input or between envelopes (exact)"
            );
        } else {
            println!(
                "proof            FAILED: {} envelope contacts, {} tube contacts",
                env.proof.contacts.len(),
                env.proof.tube_contacts.len()
            );
            for c in env
                .proof
                .contacts
                .iter()
                .chain(&env.proof.tube_contacts)
                .take(10)
            {
                println!(
                    "  {:?} face {} meets {:?} face {}",
                    c.a.0, c.a.1.0, c.b.0, c.b.1.0
                );
            }
        }
        for w in &written {
            println!("wrote            {w}");
        }
    }
    Ok(if proved {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}
