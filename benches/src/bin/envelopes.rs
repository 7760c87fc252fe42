//! Envelope benchmark (Cohen et al. 4.1, 4.2): both methods on the bunny and the armadillo of
//! the corpus and on a generated ~1M-face torus, at 1/64 %, 1/16 %, 1/4 % and 1 % of the
//! bounding-box diagonal. Reports time, peak RSS of the run (`VmHWM`, reset before each run
//! through `/proc/self/clear_refs`), the fraction of the requested epsilon achieved (median
//! and 5th percentile over both sides of every vertex) and the exact proof result. Tubes are
//! off (closed models).
//!
//! `cargo run --release -p envelope-benches --bin envelopes [-- --quick] [--skip-large]
//! [--corpus DIR] [--only-mesh SUBSTR] [--only-eps LABEL] [--only-method numerical|analytical]`.
//! `--quick` (CI smoke): a generated sphere and torus only, two epsilons. The `--only-*` flags
//! restrict the table to matching rows (for profiling one configuration). `--isolate` runs
//! every row in a fresh child process (same arguments plus `--only-*`), so that the peak RSS
//! of a row is its own and not the high-water mark of the rows before it. `--input-free`
//! skips the proof's input-input pairs, as `envelope simplify` does (its input check, run
//! beside, tests those pairs).

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::{EnvelopeMethod, EnvelopeOptions, EpsilonField, build_envelopes};

fn vm_hwm_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kib| kib / 1024.0)
}

/// User + system CPU seconds of this process so far (`/proc/self/stat`, 100 ticks/s): on a
/// shared machine the wall time depends on the load, the CPU time much less.
fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            let rest = s.rsplit_once(')')?.1;
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

/// Runs one row in a child process and prints its row; true when it proved.
fn run_child(args: &[String], mesh: &str, eps: &str, method: EnvelopeMethod) -> bool {
    let mut cmd = std::process::Command::new(std::env::current_exe().expect("own path"));
    let mesh_key = mesh.split_whitespace().next().unwrap_or(mesh);
    cmd.args(args.iter().filter(|a| *a != "--isolate"))
        .args(["--no-header", "--only-mesh", mesh_key, "--only-eps", eps])
        .args(["--only-method", &format!("{method:?}")]);
    match cmd.output() {
        Ok(o) => {
            print!("{}", String::from_utf8_lossy(&o.stdout));
            o.status.success()
        }
        Err(e) => {
            println!("| {mesh} | | {eps} | {method:?} | error: {e} |");
            false
        }
    }
}

fn quantile(sorted: &[f64], q: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * q).round() as usize]
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let skip_large = args.iter().any(|a| a == "--skip-large");
    let isolate = args.iter().any(|a| a == "--isolate");
    let no_header = args.iter().any(|a| a == "--no-header");
    let input_free = args.iter().any(|a| a == "--input-free");
    let corpus = args
        .iter()
        .position(|a| a == "--corpus")
        .and_then(|i| args.get(i + 1))
        .map_or_else(|| PathBuf::from(".corpus/data/meshes"), PathBuf::from);
    let only = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let (only_mesh, only_eps, only_method) = (
        only("--only-mesh"),
        only("--only-eps"),
        only("--only-method"),
    );
    let mut meshes: Vec<(String, TriangleSoup)> = Vec::new();
    let percents: &[(&str, f64)] = if quick {
        meshes.push(("icosphere(4)".into(), generate::icosphere(4, 1.0)));
        meshes.push(("torus 64x24".into(), generate::torus(1.0, 0.3, 64, 24)));
        &[("1/64%", 1.0 / 64.0), ("1%", 1.0)]
    } else {
        for name in ["bunny00.off", "armadillo.off"] {
            match envelope_io::read_path(corpus.join(name)) {
                Ok((s, _)) => meshes.push((name.into(), s)),
                Err(e) => eprintln!("skipping {name}: {e} (run scripts/corpus.sh)"),
            }
        }
        if !skip_large {
            meshes.push((
                "torus 1000x500 (1M)".into(),
                generate::torus(1.0, 0.3, 1000, 500),
            ));
        }
        &[
            ("1/64%", 1.0 / 64.0),
            ("1/16%", 1.0 / 16.0),
            ("1/4%", 0.25),
            ("1%", 1.0),
        ]
    };
    if !no_header {
        println!(
            "| mesh | faces | eps | method | time (s) | CPU (s) | peak RSS (MiB) | median | p5 | proved | repair rounds |"
        );
        println!("|---|---|---|---|---|---|---|---|---|---|---|");
    }
    let mut all_proved = true;
    meshes.retain(|(name, _)| only_mesh.as_ref().is_none_or(|m| name.contains(m.as_str())));
    for (name, soup) in &meshes {
        let diag = soup.diagonal();
        for &(label, pct) in percents {
            if only_eps.as_ref().is_some_and(|e| e != label) {
                continue;
            }
            for method in [EnvelopeMethod::Numerical, EnvelopeMethod::Analytical] {
                if only_method
                    .as_ref()
                    .is_some_and(|m| !format!("{method:?}").eq_ignore_ascii_case(m))
                {
                    continue;
                }
                if isolate {
                    all_proved &= run_child(&args, name, label, method);
                    continue;
                }
                let _ = std::fs::write("/proc/self/clear_refs", "5");
                let mut o = EnvelopeOptions::new(EpsilonField::Constant(pct / 100.0 * diag));
                o.method = method;
                o.tube_segments = None;
                o.input_free_of_intersections = input_free;
                let t = Instant::now();
                let cpu0 = cpu_seconds();
                let env = match build_envelopes(soup, &o) {
                    Ok(e) => e,
                    Err(e) => {
                        println!(
                            "| {name} | {} | {label} | {method:?} | error: {e} |",
                            soup.num_faces()
                        );
                        all_proved = false;
                        continue;
                    }
                };
                let secs = t.elapsed().as_secs_f64();
                let cpu = cpu_seconds() - cpu0;
                let f = env.achieved_fractions();
                all_proved &= env.proof.holds();
                println!(
                    "| {name} | {} | {label} | {method:?} | {secs:.2} | {cpu:.2} | {:.0} | {:.1}% | {:.1}% | {} | {} |",
                    soup.num_faces(),
                    vm_hwm_mib(),
                    100.0 * quantile(&f, 0.5),
                    100.0 * quantile(&f, 0.05),
                    if env.proof.holds() { "yes" } else { "NO" },
                    env.proof.repair_rounds
                );
            }
        }
    }
    if all_proved {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
