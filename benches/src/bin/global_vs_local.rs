//! Local, global and hybrid simplification side by side (issues 8 and 37): output faces and
//! seconds of the simplification step on the corpus meshes under 20k faces at 1/16 %, 1/4 %
//! and 1 % of the diagonal, then the growth of the global method's time with mesh size on
//! icospheres (fitted exponent).
//!
//! `cargo run --release -p envelope-benches --bin global_vs_local [-- --quick] [--corpus DIR]`
//! `--quick`: a short CI smoke run on small generated meshes. `--verify`: certify
//! every output (`envelope-verify`; a violation fails the run). `--only NAME`: one corpus
//! mesh. `--no-growth`: skip the icosphere series. `--placement auto`: the command line's
//! default placement (moving phase when it pays) instead of `subset`. `--global-first`: a
//! last column with the global stage started on the input, then local (`GlobalStep`, slow).
use envelope_global::{GlobalStep, Method};
use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::EpsilonField;
use envelope_simplify::{Placement, SimplifyOptions, SimplifyStep, simplify_with};
use std::path::PathBuf;
use std::process::ExitCode;

struct Row {
    faces: usize,
    seconds: f64,
    ok: bool,
}

/// `--placement auto` on the command line: the CLI's default; otherwise `subset`.
fn placement() -> Placement {
    let args: Vec<String> = std::env::args().collect();
    match args.iter().position(|a| a == "--placement") {
        Some(i) if args.get(i + 1).is_some_and(|p| p == "auto") => Placement::Auto,
        _ => Placement::Subset,
    }
}

fn run(soup: &TriangleSoup, eps: f64, method: Method, verify: bool) -> Option<Row> {
    run_step(soup, eps, method.step().as_ref(), method.as_str(), verify)
}

fn run_step(
    soup: &TriangleSoup,
    eps: f64,
    step: &dyn SimplifyStep,
    label: &str,
    verify: bool,
) -> Option<Row> {
    let mut options = SimplifyOptions::new(EpsilonField::Constant(eps));
    options.verify = verify;
    options.placement = placement();
    match simplify_with(soup, &options, step, &mut ()) {
        Ok((out, r)) => Some(Row {
            faces: out.num_faces(),
            seconds: r.simplify_seconds,
            ok: r.verify.is_none_or(|v| v.violations.is_empty()),
        }),
        Err(e) => {
            eprintln!("{label}: {e}");
            None
        }
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let verify = args.iter().any(|a| a == "--verify");
    let corpus = args
        .iter()
        .position(|a| a == "--corpus")
        .and_then(|i| args.get(i + 1))
        .map_or_else(|| PathBuf::from(".corpus/data/meshes"), PathBuf::from);
    let only = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1))
        .cloned();
    let no_growth = args.iter().any(|a| a == "--no-growth");
    let with_global_first = args.iter().any(|a| a == "--global-first");
    let mut meshes: Vec<(String, TriangleSoup)> = Vec::new();
    let percents: &[(&str, f64)] = if quick {
        meshes.push(("icosphere(3)".into(), generate::icosphere(3, 1.0)));
        meshes.push(("torus 32x12".into(), generate::torus(1.0, 0.3, 32, 12)));
        &[("1/8%", 0.125), ("1%", 1.0)]
    } else {
        for name in [
            "rotor.off",
            "couplingdown.off",
            "elephant.off",
            "cow.off",
            "mech-holes-shark.off",
            "fandisk.off",
        ] {
            if only.as_ref().is_some_and(|o| o != name) {
                continue;
            }
            match envelope_io::read_path(corpus.join(name)) {
                Ok((s, _)) => meshes.push((name.into(), s)),
                Err(e) => eprintln!("skipping {name}: {e} (run scripts/corpus.sh)"),
            }
        }
        &[("1/16%", 0.0625), ("1/4%", 0.25), ("1%", 1.0)]
    };
    // The three methods, then (optionally) the global stage on the input, then local.
    let global_first = GlobalStep::default();
    let methods = [Method::Local, Method::Global, Method::Hybrid];
    println!(
        "| mesh | faces | eps | local faces | local s | global faces | global s | hybrid faces | hybrid s | fewest | global-first faces | s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut failed = false;
    for (name, soup) in &meshes {
        for &(label, pct) in percents {
            let eps = pct / 100.0 * soup.diagonal();
            let rows: Vec<Option<Row>> =
                methods.iter().map(|&m| run(soup, eps, m, verify)).collect();
            let other = with_global_first
                .then(|| run_step(soup, eps, &global_first, "global-first", verify))
                .flatten();
            let cell = |r: &Option<Row>| match r {
                Some(r) => format!(
                    "{}{} | {:.2}",
                    r.faces,
                    if r.ok { "" } else { " (VIOLATED)" },
                    r.seconds
                ),
                None => "error | -".into(),
            };
            failed |= rows.iter().any(|r| r.as_ref().is_none_or(|r| !r.ok))
                || other.as_ref().is_some_and(|r| !r.ok);
            let least = rows.iter().flatten().map(|r| r.faces).min();
            let winners: Vec<&str> = methods
                .iter()
                .zip(&rows)
                .filter(|(_, r)| r.as_ref().map(|r| r.faces) == least)
                .map(|(m, _)| m.as_str())
                .collect();
            let best = if winners.len() == methods.len() {
                "tie".to_string()
            } else {
                winners.join("=")
            };
            println!(
                "| {name} | {} | {label} | {} | {} | {} | {best} | {} |",
                soup.num_faces(),
                cell(&rows[0]),
                cell(&rows[1]),
                cell(&rows[2]),
                if with_global_first {
                    cell(&other)
                } else {
                    "- | -".into()
                }
            );
        }
    }
    // Growth of time with size: the global method on icospheres, epsilon 1/2 % of the
    // diagonal.
    let levels: &[u32] = if no_growth {
        &[]
    } else if quick {
        &[2, 3, 4]
    } else {
        &[2, 3, 4, 5, 6]
    };
    println!("\n| icosphere | faces | global s | local s |");
    println!("|---|---|---|---|");
    let mut pts = Vec::new();
    for &k in levels {
        let s = generate::icosphere(k, 1.0);
        let eps = 0.005 * s.diagonal();
        let g = run(&s, eps, Method::Global, false);
        let l = run(&s, eps, Method::Local, false);
        if let (Some(g), Some(l)) = (g, l) {
            println!(
                "| {k} | {} | {:.3} | {:.3} |",
                s.num_faces(),
                g.seconds,
                l.seconds
            );
            pts.push(((s.num_faces() as f64).ln(), g.seconds.max(1e-6).ln()));
        }
    }
    if pts.len() >= 2 {
        let n = pts.len() as f64;
        let (mx, my) = (
            pts.iter().map(|p| p.0).sum::<f64>() / n,
            pts.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let slope = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / pts.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        println!("\nglobal time ~ faces^{slope:.2} (least squares on log-log)");
    }
    if failed {
        eprintln!("some run failed or was not certified");
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
