//! The comparison of Table 1 of El-Sana and Varshney (1997) on the `libcgal-demo` CAD parts.
//!
//! For each mesh: first the genus-preserving simplifier (`envelope_simplify::simplify`) at
//! epsilon (the paper's starting point), then on that result
//! (a) genus-reducing at alpha (`envelope_genus::reduce_genus`) followed by genus-preserving
//! at epsilon, against (b) genus-preserving alone at alpha + epsilon. Printed: faces, genus and
//! seconds per stage, and the simplification-improvement ratio faces(b) / faces(a). Tolerances
//! are percentages of the input's bounding-box diagonal, as in the paper.
//!
//! The column `closing` is the genus of the L-infinity closing of (a)'s input with the cube of
//! side `2 alpha`, computed independently on voxels of side `diagonal / 200` (the test helper
//! `crates/genus/tests/support/voxel_closing.rs`): what the alpha-hull should leave.
//!
//! `--closing` prints instead, for every part at alpha 2 % and 5 % (or `--alpha`), the genus
//! after `reduce_genus` on the input itself beside the closing's genus, and whether it meets
//! issue 37's target (at most the closing's genus plus `max(1, genus_in / 10)`), and exits 1
//! when a row misses it (CI runs `--closing --fill-closing --only cheese --alpha 5`).
//!
//! `cargo run --release -p envelope-benches --bin genus_table -- [--quick] [--corpus DIR]
//! [--eps PCT] [--alpha PCT] [--only NAME] [--union | --fill-closing] [--closing]`; `--union`
//! runs the genus-reducing step with the union-of-alpha-prisms rims
//! (`TessellationSource::PrismUnion`), `--fill-closing` with the closing's regions after the
//! sharp rims (`TessellationSource::Closing`, `envelope genus --closing`); `--quick` runs one small part (`anchor` at
//! alpha 5 % unless `--alpha` is given, or a generated plate when the corpus is absent) for a
//! CI smoke run, and exits 1 when a row fails.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use envelope_genus::{GenusOptions, TessellationSource, reduce_genus_with};
use envelope_mesh::{TriangleSoup, analyze};
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, simplify};

#[path = "../../../crates/genus/tests/support/voxel_closing.rs"]
mod voxel_closing;

/// Voxels per bounding-box diagonal for the independent closing.
const VOXELS_PER_DIAGONAL: f64 = 200.0;

fn closing_genus(soup: &TriangleSoup, alpha: f64) -> i64 {
    voxel_closing::closing_genus(soup, alpha, soup.diagonal() / VOXELS_PER_DIAGONAL)
}

const PARTS: [&str; 9] = [
    "mech-holes-shark",
    "cheese",
    "couplingdown",
    "holes",
    "pinion",
    "spool",
    "anchor",
    "turbine",
    "blade",
];

fn arg_value(args: &[String], flag: &str) -> Option<String> {
    args.iter()
        .position(|a| a == flag)
        .and_then(|i| args.get(i + 1).cloned())
}

fn preserve(soup: &TriangleSoup, eps: f64) -> Result<(TriangleSoup, f64), String> {
    let t = Instant::now();
    let (out, _) = simplify(
        soup,
        &SimplifyOptions::new(EpsilonField::Constant(eps)),
        &mut (),
    )
    .map_err(|e| e.to_string())?;
    Ok((out, t.elapsed().as_secs_f64()))
}

/// The corpus part `name`, or `None` (said on stderr) when it cannot be read.
fn read_part(corpus: &std::path::Path, name: &str) -> Option<TriangleSoup> {
    match envelope_io::read_path(corpus.join(format!("{name}.off"))) {
        Ok((s, _)) => Some(s),
        Err(e) => {
            eprintln!("skipping {name}: {e} (run scripts/corpus.sh)");
            None
        }
    }
}

fn genus(s: &TriangleSoup) -> String {
    analyze(s)
        .genus
        .map_or_else(|| "-".to_string(), |g| g.to_string())
}

fn row(
    name: &str,
    soup: &TriangleSoup,
    eps_pct: f64,
    alpha_pct: f64,
    source: TessellationSource,
) -> Result<String, String> {
    let d = soup.diagonal();
    let (eps, alpha) = (eps_pct / 100.0 * d, alpha_pct / 100.0 * d);
    let (base, t_base) = preserve(soup, eps)?;
    // (a) genus-reducing at alpha, then genus-preserving at epsilon.
    let t = Instant::now();
    let (reduced, _) =
        reduce_genus_with(&base, &GenusOptions::new(alpha), source).map_err(|e| e.to_string())?;
    let t_reduce = t.elapsed().as_secs_f64();
    let closing = if analyze(&base).num_border_loops() == 0 {
        closing_genus(&base, alpha).to_string()
    } else {
        "-".to_string()
    };
    let (a, t_a) = preserve(&reduced, eps)?;
    // (b) genus-preserving alone at alpha + epsilon.
    let (b, t_b) = preserve(&base, alpha + eps)?;
    let ratio = b.num_faces() as f64 / a.num_faces().max(1) as f64;
    Ok(format!(
        "| {name} | {} | {} | {eps_pct} | {t_base:.2} | {} | {} | {alpha_pct} | {t_reduce:.3} | {} | {} | {closing} | {t_a:.2} | {} | {} | {t_b:.2} | {} | {} | {ratio:.2} |",
        soup.num_faces(),
        genus(soup),
        base.num_faces(),
        genus(&base),
        reduced.num_faces(),
        genus(&reduced),
        a.num_faces(),
        genus(&a),
        b.num_faces(),
        genus(&b),
    ))
}

/// Issue 37's target table: genus after the genus-reducing step on the input beside the
/// closing's genus.
fn closing_table(
    corpus: &std::path::Path,
    names: &[&str],
    only: Option<&str>,
    alphas: &[f64],
    source: TessellationSource,
) -> ExitCode {
    println!(
        "| mesh | faces | genus | border loops | genus (voxels) | alpha % | GR s | genus (ours) | closing (voxels) | target | met |"
    );
    println!("|{}", "---|".repeat(11));
    let mut missed = false;
    for &name in names {
        if only.is_some_and(|o| o != name) {
            continue;
        }
        let Some(soup) = read_part(corpus, name) else {
            continue;
        };
        let topo = analyze(&soup);
        let g_in = topo.genus.map_or(0, i64::from);
        // The voxel closing needs a closed surface (inside by ray parity).
        let closed = topo.num_border_loops() == 0 && topo.genus.is_some();
        let h = soup.diagonal() / VOXELS_PER_DIAGONAL;
        let g_vox = if closed {
            voxel_closing::voxel_genus(&soup, h).to_string()
        } else {
            "-".to_string()
        };
        for &alpha_pct in alphas {
            let alpha = alpha_pct / 100.0 * soup.diagonal();
            let t = Instant::now();
            let ours = reduce_genus_with(&soup, &GenusOptions::new(alpha), source)
                .map(|(out, _)| analyze(&out).genus);
            let secs = t.elapsed().as_secs_f64();
            let closing = closed.then(|| closing_genus(&soup, alpha));
            let target = closing.map(|c| c + (g_in / 10).max(1));
            let (ours, met) = match (ours, target) {
                (Ok(Some(g)), Some(t)) => {
                    (g.to_string(), if i64::from(g) <= t { "yes" } else { "no" })
                }
                (Ok(Some(g)), None) => (g.to_string(), "-"),
                (Ok(None), _) => ("-".to_string(), "-"),
                (Err(e), _) => (format!("error: {e}"), "no"),
            };
            missed |= met == "no";
            let show = |x: Option<i64>| x.map_or_else(|| "-".to_string(), |v| v.to_string());
            println!(
                "| {name} | {} | {g_in} | {} | {g_vox} | {alpha_pct} | {secs:.3} | {ours} | {} | {} | {met} |",
                soup.num_faces(),
                topo.num_border_loops(),
                show(closing),
                show(target),
            );
        }
    }
    if missed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let corpus = arg_value(&args, "--corpus")
        .map_or_else(|| PathBuf::from(".corpus/data/meshes"), PathBuf::from);
    let eps_pct: f64 = arg_value(&args, "--eps")
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.5);
    let alpha_pct: f64 = arg_value(&args, "--alpha")
        .and_then(|s| s.parse().ok())
        .unwrap_or(if quick { 5.0 } else { 2.0 });
    let only = arg_value(&args, "--only");
    let source = if args.iter().any(|a| a == "--union") {
        TessellationSource::PrismUnion
    } else if args.iter().any(|a| a == "--fill-closing") {
        TessellationSource::Closing
    } else {
        TessellationSource::SharpEdges
    };
    let closing_names: Vec<&str> = if quick {
        vec!["anchor"]
    } else {
        PARTS.to_vec()
    };
    if args.iter().any(|a| a == "--closing") {
        let alphas: Vec<f64> = arg_value(&args, "--alpha")
            .and_then(|s| s.parse().ok())
            .map_or_else(|| vec![2.0, 5.0], |a| vec![a]);
        return closing_table(&corpus, &closing_names, only.as_deref(), &alphas, source);
    }
    println!(
        "| mesh | faces | genus | eps % | GP s | GP faces | genus | alpha % | GR s | GR faces | genus | closing | GP(eps) s | faces (a) | genus | GP(a+e) s | faces (b) | genus | ratio b/a |"
    );
    println!("|{}", "---|".repeat(19));
    let mut names: Vec<&str> = PARTS.to_vec();
    if quick {
        names = vec!["anchor"];
    }
    let mut failed = false;
    for name in names {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let Some(soup) = read_part(&corpus, name) else {
            if quick {
                let plate = envelope_genus::testmeshes::plate_with_square_holes(&[1, 2, 4], 2, 1.0);
                match row("generated plate [1,2,4]", &plate, eps_pct, 10.0, source) {
                    Ok(r) => println!("{r}"),
                    Err(e) => {
                        eprintln!("generated plate: {e}");
                        failed = true;
                    }
                }
            }
            continue;
        };
        match row(name, &soup, eps_pct, alpha_pct, source) {
            Ok(r) => println!("{r}"),
            Err(e) => {
                eprintln!("{name}: {e}");
                failed |= quick;
                println!(
                    "| {name} | {} | {} | error: {e} |",
                    soup.num_faces(),
                    genus(&soup)
                );
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}
