//! One item, start to end: its key, the work, and its folder put in place in one rename.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use envelope_io::{Format, read_bytes_with_attributes, write_path_with_attributes};
use envelope_verify::Verdict;
use serde_json::json;
use sha2::{Digest, Sha256};

use super::manifest::{Item, Job};
use super::outcome::{Outcome, Status};
use crate::{Error, Lod, Mesh, Simplifier};

/// The file of an item's result, inside its folder; written last.
pub(crate) const RESULT: &str = "result.json";

/// The key of `item` on these input bytes: any change of program, parameters or input makes
/// another key.
pub(crate) fn key(item: &Item, bytes: &[u8]) -> String {
    let params = json!({
        "program": concat!("envelope ", env!("CARGO_PKG_VERSION")),
        "job": match &item.job {
            Job::Simplify(e) => json!({"simplify": e.to_string()}),
            Job::Lod(es) => json!({"lod": es.iter().map(ToString::to_string).collect::<Vec<_>>()}),
        },
        "method": item.method.as_str(),
        "placement": item.placement.as_str(),
        "repair": item.repair,
        "format": item.format,
    });
    let mut hash = Sha256::new();
    hash.update(params.to_string().as_bytes());
    hash.update([0]);
    hash.update(bytes);
    hash.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

/// The result recorded in `item`'s folder by an earlier run, whatever its key.
pub(crate) fn recorded(outdir: &Path, item: &Item) -> Option<Outcome> {
    let text = fs::read_to_string(outdir.join(&item.id).join(RESULT)).ok()?;
    let outcome: Outcome = serde_json::from_str(&text).ok()?;
    (outcome.id == item.id).then_some(outcome)
}

/// The final result of an earlier run for this key, if its folder has one.
fn finished(outdir: &Path, item: &Item, key: &str) -> Option<Outcome> {
    recorded(outdir, item).filter(|o| o.key == key)
}

/// Runs `item` unless an earlier run finished it; never panics (a panic in the engine is a
/// `failed` outcome). `stop` cancels between stages.
pub(crate) fn run_item(outdir: &Path, item: &Item, stop: &AtomicBool) -> Outcome {
    let start = Instant::now();
    let bytes = match fs::read(&item.input) {
        Ok(b) => b,
        Err(e) => {
            let mut o = Outcome::new(&item.id, String::new(), &item.input_as_written);
            o.status = Status::BadInput;
            o.message = Some(format!("{}: {e}", item.input.display()));
            // Not final: the file may appear later.
            o.transient = true;
            return o;
        }
    };
    let key = key(item, &bytes);
    if let Some(mut done) = finished(outdir, item, &key) {
        done.ran = false;
        return done;
    }
    let mut outcome = Outcome::new(&item.id, key, &item.input_as_written);
    let staging = staging_dir(outdir, &item.id);
    let work = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        work(item, &bytes, &staging, stop, &mut outcome)
    }));
    match work {
        Ok(Ok(())) => {}
        Ok(Err(e)) => classify(&mut outcome, &e),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(ToString::to_string)
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            outcome.status = Status::Failed;
            outcome.message = Some(format!("internal error (please report it): {what}"));
            outcome.transient = true;
        }
    }
    outcome.seconds = start.elapsed().as_secs_f64();
    if outcome.is_final()
        && let Err(e) = put_in_place(outdir, &staging, &item.id, &outcome)
    {
        outcome.status = Status::Failed;
        outcome.message = Some(e);
        outcome.transient = true;
    }
    let _ = fs::remove_dir_all(&staging);
    outcome
}

/// A folder of its own for this attempt, beside the final one (same file system, so the
/// final rename is atomic); hidden, as ids never start with a dot.
fn staging_dir(outdir: &Path, id: &str) -> PathBuf {
    use std::sync::atomic::AtomicU64;
    static ATTEMPT: AtomicU64 = AtomicU64::new(0);
    let n = ATTEMPT.fetch_add(1, Ordering::Relaxed);
    outdir.join(format!(".{id}.partial-{}-{n}", std::process::id()))
}

/// The work: read, repair, simplify or chain, certify, write into `staging`.
fn work(
    item: &Item,
    bytes: &[u8],
    staging: &Path,
    stop: &AtomicBool,
    outcome: &mut Outcome,
) -> Result<(), Error> {
    let (soup, attributes, _) = read_bytes_with_attributes(bytes, &item.input)?;
    let mut mesh = Mesh::from_parts(soup, attributes);
    fs::create_dir_all(staging).map_err(|e| write_error(staging, &e))?;
    if item.repair {
        // The repaired mesh has the file's point set: the certificate against it holds
        // against the file (`envelope::repair`).
        let repaired = crate::repair(&mesh)?;
        write_json(staging, "repair.json", &repaired.to_json())?;
        outcome.outputs.push("repair.json".into());
        mesh = repaired.into_mesh();
    }
    outcome.input_faces = Some(mesh.num_faces());
    // The manifest allows only the four extensions, and an input read has one of them
    // (or was sniffed: its format's own extension).
    let format = match &item.format {
        Some(f) => Format::from_extension(f),
        None => Format::from_path(&item.input),
    }
    .or_else(|| Format::sniff(bytes, Some(bytes.len() as u64)))
    .ok_or_else(|| Error::InvalidArgument(format!("{}: no output format", item.id)))?;
    let ext = format.extension();
    let cancel = |_| {
        if stop.load(Ordering::Relaxed) {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    };
    // With the attributes the format holds (`envelope_io::Format::dropped_attributes`).
    let mut write = |name: String, m: &Mesh| -> Result<(), Error> {
        write_path_with_attributes(staging.join(&name), m.soup(), m.attributes(), format)?;
        outcome.outputs.push(name);
        Ok(())
    };
    let diagonal = mesh.diagonal();
    match &item.job {
        Job::Simplify(epsilon) => {
            let result = Simplifier::new(*epsilon)
                .method(item.method)
                .placement(item.placement)
                .progress(cancel)
                .run(&mesh);
            let (done, status) = match result {
                Ok(done) => {
                    let status = match done.certificate().map(|c| c.verdict) {
                        Some(Verdict::Undecided) => Status::Undecided,
                        _ => Status::Ok,
                    };
                    (done, status)
                }
                Err(Error::CertificateViolated(done)) => (*done, Status::Violated),
                Err(e) => return Err(e),
            };
            let name = match status {
                Status::Violated => format!("simplified.failed.{ext}"),
                _ => format!("simplified.{ext}"),
            };
            write(name, done.mesh())?;
            let report = done.report();
            outcome.faces.push(done.mesh().num_faces());
            outcome.epsilon.push(report.epsilon_abs);
            if let Some(v) = &report.verify {
                outcome.approx_to_orig = Some(v.approx_to_orig_upper);
                outcome.orig_to_approx = Some(v.orig_to_approx_upper);
            }
            write_json(staging, "report.json", &report.to_json())?;
            outcome.outputs.push("report.json".into());
            set_status(outcome, status, &done.violations());
        }
        Job::Lod(epsilons) => {
            let levels = Lod::new(epsilons.clone()).progress(cancel).run(&mesh)?;
            let mut status = Status::Ok;
            let mut violations = Vec::new();
            for level in &levels {
                write(
                    format!("level-{}.{ext}", level.index),
                    &Lod::level_mesh(&mesh, level),
                )?;
                outcome.faces.push(level.mesh.num_faces());
                outcome.epsilon.push(level.cumulative);
                if let Some(v) = &level.certified {
                    let up = |a: Option<f64>, b: f64| Some(a.map_or(b, |a| a.max(b)));
                    outcome.approx_to_orig = up(outcome.approx_to_orig, v.approx_to_orig_upper);
                    outcome.orig_to_approx = up(outcome.orig_to_approx, v.orig_to_approx_upper);
                    status = status.worse(match v.verdict {
                        Verdict::Holds => Status::Ok,
                        Verdict::Undecided => Status::Undecided,
                        Verdict::Violated => Status::Violated,
                    });
                    violations.extend(v.certificate.violations());
                }
            }
            let chain: Vec<_> = levels.iter().map(|l| l.to_json(diagonal)).collect();
            write_json(staging, "lod.json", &json!({ "levels": chain }))?;
            outcome.outputs.push("lod.json".into());
            violations.sort_unstable();
            violations.dedup();
            set_status(outcome, status, &violations);
        }
    }
    Ok(())
}

fn set_status(outcome: &mut Outcome, status: Status, violations: &[&str]) {
    outcome.status = status;
    outcome.message = match status {
        Status::Violated => Some(format!(
            "the output FAILED its certificate ({})",
            violations.join(", ")
        )),
        Status::Undecided => Some("the certificate is undecided".into()),
        _ => None,
    };
}

/// Sorts an error into a status: what the input decides is final, the rest is retried.
fn classify(outcome: &mut Outcome, e: &Error) {
    use envelope_simplify::DriverError;
    outcome.message = Some(e.to_string());
    (outcome.status, outcome.transient) = match e {
        Error::Read(_)
        | Error::InvalidMesh(_)
        | Error::InvalidEpsilon(_)
        | Error::Genus(_)
        | Error::Repair(_) => (Status::BadInput, false),
        Error::Simplify(
            DriverError::Unacceptable(_)
            | DriverError::Build(_)
            | DriverError::Barrier(_)
            | DriverError::Epsilons(_),
        ) => (Status::BadInput, false),
        Error::Simplify(DriverError::UnprovedEnvelopes { .. } | DriverError::Envelope(_)) => {
            (Status::Failed, false)
        }
        _ => (Status::Failed, true),
    };
}

fn write_json(dir: &Path, name: &str, value: &serde_json::Value) -> Result<(), Error> {
    let path = dir.join(name);
    let text = serde_json::to_string_pretty(value).unwrap_or_default() + "\n";
    fs::write(&path, text).map_err(|e| write_error(&path, &e))
}

fn write_error(path: &Path, e: &std::io::Error) -> Error {
    Error::io(path, e)
}

/// Writes the result into the staging folder, then swaps it in for the item's folder: the
/// folder under the id is always a whole earlier result or a whole new one.
fn put_in_place(outdir: &Path, staging: &Path, id: &str, outcome: &Outcome) -> Result<(), String> {
    let fail = |what: &Path, e: std::io::Error| format!("{}: {e}", what.display());
    fs::create_dir_all(staging).map_err(|e| fail(staging, e))?;
    let result = staging.join(RESULT);
    let mut file = fs::File::create(&result).map_err(|e| fail(&result, e))?;
    writeln!(file, "{}", outcome.to_json_line()).map_err(|e| fail(&result, e))?;
    file.sync_all().map_err(|e| fail(&result, e))?;
    let target = outdir.join(id);
    if target.exists() {
        // Moved aside first, so that a crash between the two renames leaves the old result
        // under a hidden name, never half a folder under the id.
        let old = outdir.join(format!(".{id}.old-{}", std::process::id()));
        let _ = fs::remove_dir_all(&old);
        fs::rename(&target, &old).map_err(|e| fail(&target, e))?;
        fs::rename(staging, &target).map_err(|e| fail(&target, e))?;
        let _ = fs::remove_dir_all(&old);
    } else {
        fs::rename(staging, &target).map_err(|e| fail(&target, e))?;
    }
    Ok(())
}
