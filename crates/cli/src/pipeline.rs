//! `envelope pipeline IN OUTDIR --steps "e0.5%,a2%,e1%,a5%,e2%"`: alternating genus-preserving
//! (`e`, the local simplifier at that epsilon) and genus-reducing (`a`, `envelope genus` at
//! that alpha; `u`, the same with the union-of-alpha-prisms rims, `envelope genus --union`)
//! steps, as in Fig. 11 and Table 1 of El-Sana and Varshney (1997). Percentages
//! are of the *input's* bounding-box diagonal (the paper's convention). Writes
//! OUTDIR/stage-0.off (the input), stage-1.off, ... and summary.json.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::analyze;
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, simplify};
use serde_json::json;

use crate::genus::{reduce, resolve_length, write_text_atomic};

/// Arguments of `envelope pipeline`.
#[derive(clap::Args)]
pub struct Args {
    /// Input mesh (OBJ, OFF, PLY, STL).
    pub input: PathBuf,
    /// Output directory (created if missing).
    pub out_dir: PathBuf,
    /// Comma-separated steps: `eX` genus-preserving at epsilon X, `aX` genus-reducing at
    /// alpha X, `uX` genus-reducing at alpha X with the union-of-prisms rims (`--union`); X
    /// absolute or a percentage of the input diagonal.
    #[arg(long, default_value = "e0.5%,a2%,e1%,a5%,e2%")]
    pub steps: String,
    /// Sharp-edge threshold of the genus-reducing steps, degrees.
    #[arg(long, default_value_t = 70.0)]
    pub beta: f64,
}

/// One parsed step.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Step {
    Preserve(f64),
    /// Alpha, and whether the union-of-prisms rims are used.
    Reduce(f64, bool),
}

fn parse_steps(s: &str, diagonal: f64) -> Result<Vec<Step>, String> {
    let mut steps = Vec::new();
    for raw in s.split(',') {
        let t = raw.trim();
        if let Some(v) = t.strip_prefix('e') {
            steps.push(Step::Preserve(resolve_length("--steps e", v, diagonal)?));
        } else if let Some(v) = t.strip_prefix('a') {
            steps.push(Step::Reduce(
                resolve_length("--steps a", v, diagonal)?,
                false,
            ));
        } else if let Some(v) = t.strip_prefix('u') {
            steps.push(Step::Reduce(
                resolve_length("--steps u", v, diagonal)?,
                true,
            ));
        } else {
            return Err(format!(
                "--steps: {t:?} must start with 'e' (genus-preserving), 'a' or 'u' (genus-reducing)"
            ));
        }
    }
    if steps.is_empty() {
        return Err("--steps: no step".into());
    }
    Ok(steps)
}

/// Runs `envelope pipeline`.
pub fn run(args: &Args) -> Result<ExitCode, String> {
    let (mut soup, _) = read_path(&args.input).map_err(|e| e.to_string())?;
    let diagonal = soup.diagonal();
    let steps = parse_steps(&args.steps, diagonal)?;
    std::fs::create_dir_all(&args.out_dir)
        .map_err(|e| format!("{}: {e}", args.out_dir.display()))?;
    let stage_path = |k: usize| args.out_dir.join(format!("stage-{k}.off"));
    write_path(stage_path(0), &soup, Format::Off).map_err(|e| e.to_string())?;
    let t0 = analyze(&soup);
    let mut stages = vec![json!({
        "stage": 0, "step": "input", "faces": soup.num_faces(), "genus": t0.genus,
        "border_loops": t0.num_border_loops(), "seconds": 0.0,
        "file": "stage-0.off",
    })];
    println!(
        "stage 0: input, {} faces, genus {:?}",
        soup.num_faces(),
        t0.genus
    );
    for (k, step) in steps.iter().enumerate() {
        let start = Instant::now();
        let (label, value, extra) = match *step {
            Step::Preserve(eps) => {
                let options = SimplifyOptions::new(EpsilonField::Constant(eps));
                let (out, _) = simplify(&soup, &options, &mut ())
                    .map_err(|e| format!("stage {} (e = {eps}): {e}", k + 1))?;
                soup = out;
                ("genus-preserving", eps, json!({}))
            }
            Step::Reduce(alpha, union) => {
                let (out, report) = reduce(&soup, alpha, args.beta, union)
                    .map_err(|e| format!("stage {} (a = {alpha}): {e}", k + 1))?;
                soup = out;
                ("genus-reducing", alpha, report.to_json())
            }
        };
        let seconds = start.elapsed().as_secs_f64();
        let path = stage_path(k + 1);
        write_path(&path, &soup, Format::Off).map_err(|e| e.to_string())?;
        let t = analyze(&soup);
        println!(
            "stage {}: {label} at {value}, {} faces, genus {:?}, {seconds:.3} s",
            k + 1,
            soup.num_faces(),
            t.genus
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
        "steps": args.steps,
        "stages": stages,
    });
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    write_text_atomic(&args.out_dir.join("summary.json"), &text)?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_parse_and_reject() {
        assert_eq!(
            parse_steps("e1%, a0.5", 10.0).unwrap(),
            vec![Step::Preserve(0.1), Step::Reduce(0.5, false)]
        );
        assert_eq!(
            parse_steps("u2%", 10.0).unwrap(),
            vec![Step::Reduce(0.2, true)]
        );
        assert!(parse_steps("u", 1.0).is_err());
        assert!(parse_steps("x1", 1.0).is_err());
        assert!(parse_steps("e-1", 1.0).is_err());
        assert!(parse_steps("a", 1.0).is_err());
    }
}
