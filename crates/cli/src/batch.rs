//! `envelope batch MANIFEST OUTDIR`: every item of a JSON Lines manifest simplified (or made
//! into a chain of levels) into `OUTDIR/<id>/`, with `OUTDIR/summary.jsonl`
//! (`envelope::batch`: layout, keys, resuming, shards).
//!
//! Exit codes: 0 every item of the shard is `ok`, 1 some item is not (the summary says which
//! and why; one bad item never stops the others), 2 the manifest or the arguments are wrong
//! (nothing is run).

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::process::ExitCode;

use envelope::Epsilon;
use envelope::batch::{Batch, Outcome, SUMMARY, Schedule, Shard, Status};
use indicatif::{ProgressBar, ProgressStyle};

/// Arguments of `envelope batch`.
#[derive(clap::Args)]
pub(crate) struct Args {
    /// JSON Lines manifest: one object per line with `id`, `input` (relative to the
    /// manifest's folder), `epsilon` (`"1%"`, `"1/64%"` or a number), and optionally `lod`
    /// (a list of epsilons), `method`, `placement`, `repair`, `format`.
    manifest: PathBuf,
    /// Output folder: created if missing (its parent must exist); item `id` goes to
    /// OUTDIR/<id>/, and OUTDIR/summary.jsonl lists every item's status.
    outdir: PathBuf,
    /// Run only shard I of N (`I/N`, 1 <= I <= N): every N-th item, from the I-th.
    #[arg(long, value_parser = parse::<Shard>)]
    shard: Option<Shard>,
    /// Threads of each item, 1..=1024 (default 1: --threads items run at a time, one thread
    /// each; a few large meshes go faster with more). Outputs are the same for any number.
    #[arg(long, value_parser = crate::ranges::threads, allow_hyphen_values = true)]
    threads_per_item: Option<usize>,
    /// Epsilon for items that give none (same syntax as the manifest's).
    #[arg(long, value_parser = parse::<Epsilon>, allow_hyphen_values = true)]
    epsilon: Option<Epsilon>,
    /// No progress bar and no per-item lines (the summary line is still printed).
    #[arg(long)]
    quiet: bool,
}

/// A value the library parses, with its message (`--shard`, `--epsilon`).
fn parse<T: std::str::FromStr<Err = envelope::Error>>(s: &str) -> Result<T, String> {
    s.parse().map_err(|e: envelope::Error| e.to_string())
}

/// Runs the batch.
pub(crate) fn run(args: &Args) -> Result<ExitCode, String> {
    if let (Ok(m), Ok(o)) = (args.manifest.canonicalize(), args.outdir.canonicalize())
        && m == o
    {
        return Err(format!(
            "{}: the output folder is the manifest",
            args.outdir.display()
        ));
    }
    let batch =
        Batch::open_with(&args.manifest, &args.outdir, args.epsilon).map_err(|e| e.to_string())?;
    let count = batch.shard(args.shard).count();
    let bar = if args.quiet || !std::io::stderr().is_terminal() {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(count as u64).with_style(
            ProgressStyle::with_template(
                "{bar:30} {pos}/{len} items  {elapsed} (eta {eta})  {msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
        )
    };
    let on_item = |o: &Outcome| {
        bar.inc(1);
        if !args.quiet {
            bar.suspend(|| println!("{}", line(o)));
        }
        ControlFlow::Continue(())
    };
    let schedule = Schedule {
        shard: args.shard,
        threads: None,
        threads_per_item: args.threads_per_item,
    };
    let outcomes = batch.run(schedule, &on_item).map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let n = |s: Status| outcomes.iter().filter(|o| o.status == s).count();
    let reused = outcomes.iter().filter(|o| !o.ran).count();
    println!(
        "{} items: {} ok, {} violated, {} bad input, {} undecided, {} failed ({reused} reused from \
         earlier runs); {}",
        outcomes.len(),
        n(Status::Ok),
        n(Status::Violated),
        n(Status::BadInput),
        n(Status::Undecided),
        n(Status::Failed),
        args.outdir.join(SUMMARY).display()
    );
    Ok(if outcomes.iter().all(|o| o.status == Status::Ok) {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// One item's line: id, status, faces and time, or why not.
fn line(o: &Outcome) -> String {
    let faces = |v: &[usize]| {
        v.iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(",")
    };
    let what = match (o.status, &o.message) {
        (Status::Ok, _) => format!(
            "{} -> {} faces",
            o.input_faces.unwrap_or(0),
            faces(&o.faces)
        ),
        (_, Some(m)) => m.clone(),
        (_, None) => String::new(),
    };
    let when = if o.ran {
        format!("{:.2} s", o.seconds)
    } else {
        "reused".into()
    };
    format!("{:<10} {}  {what}  ({when})", o.status.as_str(), o.id)
}
