//! `envelope pipeline IN OUTDIR --steps "e0.5%,a2%,e1%,a5%,e2%"`: alternating genus-preserving
//! (`e`, the local simplifier at that epsilon) and genus-reducing (`a`, `envelope genus` at
//! that alpha, or `c`, the same said explicitly; `s`, the sharp-edge step alone, `envelope
//! genus --sharp`; `u`, the union-of-alpha-prisms rims, `envelope genus --union`)
//! steps, as in Fig. 11 and Table 1 of El-Sana and Varshney (1997). Percentages
//! are of the *input's* bounding-box diagonal (the paper's convention). Writes
//! OUTDIR/stage-0.off (the input), stage-1.off, ... and summary.json, all put in place
//! together when every step has run (`crate::outputs`); a missing OUTDIR is created (not its
//! parents).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use envelope::advanced::io::Format;
use envelope::advanced::mesh::{TriangleSoup, analyze};
use envelope::{Epsilon, Placement, Simplifier, TessellationSource};
use serde_json::json;

use crate::genus::reduce;
use crate::outputs::{Plan, Staging};
use crate::ranges::{self, Length, show, show_genus};

/// Arguments of `envelope pipeline`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL).
    pub input: PathBuf,
    /// Output directory: created if missing (its parent must exist); files in it are
    /// replaced only when every step has run.
    pub out_dir: PathBuf,
    /// Comma-separated steps: `eX` genus-preserving at epsilon X, `aX` (or `cX`)
    /// genus-reducing at alpha X as `envelope genus` does, `sX` with the sharp-edge step
    /// alone (`--sharp`), `uX` with the union-of-prisms rims (`--union`);
    /// each X > 0, absolute or a percentage of the input diagonal.
    #[arg(long, default_value = "e0.5%,a2%,e1%,a5%,e2%", value_parser = parse_steps)]
    pub steps: Steps,
    /// Sharp-edge threshold of the genus-reducing steps, degrees: (0, 180).
    #[arg(long, default_value_t = 70.0, value_parser = ranges::beta, allow_hyphen_values = true)]
    pub beta: f64,
}

/// What a step does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    /// Genus-preserving simplification (`e`).
    Preserve,
    /// Genus reduction from these rims (`a` sharp edges, `u` union of prisms, `c` closing).
    Reduce(TessellationSource),
}

/// The parsed `--steps` (their text is kept for the summary).
#[derive(Clone, Debug)]
pub struct Steps {
    text: String,
    steps: Vec<(Kind, Length)>,
}

fn parse_steps(s: &str) -> Result<Steps, String> {
    let mut steps = Vec::new();
    for (i, raw) in s.split(',').enumerate() {
        let t = raw.trim();
        let mut chars = t.chars();
        let kind = match chars.next() {
            Some('e') => Kind::Preserve,
            Some('a') => Kind::Reduce(TessellationSource::default()),
            Some('c') => Kind::Reduce(TessellationSource::Closing),
            Some('s') => Kind::Reduce(TessellationSource::SharpEdges),
            Some('u') => Kind::Reduce(TessellationSource::PrismUnion),
            _ => {
                return Err(format!(
                    "step {} {t:?} must start with 'e' (genus-preserving), 'a', 'c', 's' or 'u' (genus-reducing)",
                    i + 1
                ));
            }
        };
        let value =
            ranges::length(chars.as_str()).map_err(|e| format!("step {} {t:?}: {e}", i + 1))?;
        steps.push((kind, value));
    }
    Ok(Steps {
        text: s.to_string(),
        steps,
    })
}

/// The steps' lengths on the input.
fn resolve_steps(
    steps: &Steps,
    input: &str,
    soup: &TriangleSoup,
) -> Result<Vec<(Kind, f64)>, String> {
    steps
        .steps
        .iter()
        .map(|(kind, l)| {
            let e = l.resolve("--steps", input, soup)?;
            if *kind == Kind::Preserve {
                let flag = format!("--steps item e{}", l.text);
                let field = envelope::advanced::offset::EpsilonField::Constant(e);
                ranges::epsilon_in_range(&flag, input, &field, soup)?;
            }
            Ok((*kind, e))
        })
        .collect()
}

/// Runs `envelope pipeline`.
pub fn run(args: &Args) -> Result<ExitCode, String> {
    let mut plan = Plan::new(&[("IN", &args.input)]);
    let mut names: Vec<String> = (0..=args.steps.steps.len())
        .map(|k| format!("stage-{k}.off"))
        .collect();
    names.push("summary.json".into());
    plan.dir("OUTDIR", &args.out_dir, &names)?;
    let mut mesh = envelope::load(&args.input).map_err(|e| e.to_string())?;
    let soup = mesh.soup();
    let diagonal = soup.diagonal();
    let steps = resolve_steps(&args.steps, &args.input.display().to_string(), soup)?;
    let mut staging = Staging::new();
    staging.dir(&args.out_dir)?;
    let stage_path = |k: usize| args.out_dir.join(format!("stage-{k}.off"));
    staging.mesh(&stage_path(0), soup, Format::Off)?;
    let t0 = analyze(soup);
    let mut stages = vec![json!({
        "stage": 0, "step": "input", "faces": soup.num_faces(), "genus": t0.genus,
        "border_loops": t0.num_border_loops(), "seconds": 0.0,
        "file": "stage-0.off",
    })];
    println!(
        "stage 0: input, {} faces, genus {}",
        soup.num_faces(),
        show_genus(t0.genus)
    );
    // A failed step names its input, its number and its text as the user wrote it.
    let fail = |k: usize, e: String| {
        let written = args.steps.text.split(',').nth(k).unwrap_or("").trim();
        format!(
            "{}: --steps step {} {written}: {e}",
            args.input.display(),
            k + 1,
        )
    };
    for (k, step) in steps.iter().enumerate() {
        let start = Instant::now();
        let (label, value, extra) = match *step {
            // Input vertices only (the stages' vertex sets nest, as in the paper's
            // alternation), uncertified: each stage is held by its proved envelopes.
            (Kind::Preserve, eps) => {
                let done = Simplifier::new(Epsilon::absolute(eps))
                    .placement(Placement::Subset)
                    .certify(false)
                    .run(&mesh)
                    .map_err(|e| fail(k, e.to_string()))?;
                mesh = done.into_mesh();
                ("genus-preserving", eps, json!({}))
            }
            (Kind::Reduce(source), alpha) => {
                let (out, report) =
                    reduce(&mesh, alpha, args.beta, source).map_err(|e| fail(k, e))?;
                mesh = out;
                ("genus-reducing", alpha, report.to_json())
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        let soup = mesh.soup();
        staging.mesh(&stage_path(k + 1), soup, Format::Off)?;
        let t = analyze(soup);
        println!(
            "stage {}: {label} at {}, {} faces, genus {}, {seconds:.3} s",
            k + 1,
            show(value),
            soup.num_faces(),
            show_genus(t.genus)
        );
        stages.push(json!({
            "stage": k + 1, "step": label, "value": value, "faces": soup.num_faces(),
            "genus": t.genus, "border_loops": t.num_border_loops(), "seconds": seconds,
            "file": format!("stage-{}.off", k + 1), "genus_report": extra,
        }));
    }
    let summary = json!({
        "input": args.input.display().to_string(),
        "diagonal": diagonal,
        "steps": args.steps.text,
        "stages": stages,
    });
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    staging.text(&args.out_dir.join("summary.json"), &(text + "\n"))?;
    staging.commit()?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_parse_and_reject() {
        let tri = TriangleSoup::from_raw(
            &[[0.0, 0.0, 0.0], [6.0, 0.0, 0.0], [0.0, 8.0, 0.0]],
            &[[0, 1, 2]],
        );
        let s = parse_steps("e1%, a0.5, s1").unwrap();
        assert_eq!(
            resolve_steps(&s, "t", &tri).unwrap(),
            vec![
                (Kind::Preserve, 0.1),
                (Kind::Reduce(TessellationSource::Closing), 0.5),
                (Kind::Reduce(TessellationSource::SharpEdges), 1.0)
            ]
        );
        let s = parse_steps("u2%").unwrap();
        assert_eq!(
            resolve_steps(&s, "t", &tri).unwrap(),
            vec![(Kind::Reduce(TessellationSource::PrismUnion), 0.2)]
        );
        let s = parse_steps("c5%").unwrap();
        assert_eq!(
            resolve_steps(&s, "t", &tri).unwrap(),
            vec![(Kind::Reduce(TessellationSource::Closing), 0.5)]
        );
        for bad in ["u", "c", "s", "x1", "e-1", "a", "", "e1%,"] {
            assert!(parse_steps(bad).is_err(), "{bad}");
        }
    }
}
