//! `envelope_simplify::simplify` against CGAL (and OpenMesh): every output must
//!
//! * have no self-intersecting face pair (CGAL `does_self_intersect` pairs),
//! * be within epsilon of the input in **both** directions by CGAL's
//!   `bounded_error_Hausdorff_distance` (see [`within`] for how its error bound is used),
//! * keep the genus, components and border loops (CGAL `Surface_mesh` topology line),
//! * and hold `envelope-verify`'s exact certificate at epsilon (both directions, no
//!   self-intersection, same topology).
//!
//! Meshes: generated ones (icosphere, torus, box, open cylinder, the demo cup) at 1/16 %,
//! 1/4 % and 1 % of the bounding-box diagonal, and corpus meshes at 1/4 % and 1 %:
//! `fandisk.off`, `mech-holes-shark.off` and `elephant.off` always, `bunny00.off` and
//! `armadillo.off` only with `ENVELOPE_FULL_CORPUS=1` or in a release build; fandisk and
//! mech-holes-shark also with `Placement::Slide` (vertices moved along their fibers) and
//! `Placement::Collapse` (and edges collapsed to quadric points).
//!
//! Every failing (mesh, epsilon, property) is collected and printed together; the test then
//! fails naming all of them, except the ones listed in [`KNOWN_FAILURES`] (printed as
//! `KNOWN FAIL`; the test also fails when one of them starts passing, so the list stays true). Nothing is skipped silently: a corpus mesh that is missing or
//! not acceptable input is named in the output.

use std::path::Path;

use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::EpsilonField;
use envelope_simplify::{Placement, SimplifyOptions, input_problems, simplify};
use envelope_tests::oracle::{Oracle, TopoCounts, corpus_dir, oracle_or_skip};
use glam::DVec3;

/// Outputs known to violate the bound, with the diagnosis. Open problem, not hidden.
///
/// Empty. `mech-holes-shark.off` (4 border loops) was listed at 1/4 % and 1 %: the output
/// was several eps from the input, at an interior edge joining two border vertices across
/// a hole, because the envelopes are open along the borders and the tubes of 6.2 only
/// constrain *new border edges*. The border walls of `envelope_simplify::policy::border_walls`
/// (full barriers joining outer and inner envelope along every border loop) close that gap.
const KNOWN_FAILURES: &[(&str, f64)] = &[];

fn full_requested() -> bool {
    std::env::var("ENVELOPE_FULL_CORPUS").is_ok_and(|v| v == "1") || !cfg!(debug_assertions)
}

/// CGAL returns `h` with `|h - true distance| <= bound`. We ask with `bound = 0.05 eps` and
/// fail when `h > eps + bound`: then the true distance is `>= h - bound > eps`, a certain
/// violation. A pass means the true distance is `<= eps + 2 bound = 1.1 eps`. The bound is
/// that loose because CGAL's branch and bound is very slow where the surfaces coincide
/// (distance 0, as on a simplified flat box side), the slower the tighter the bound. The
/// exact check at `eps` is `envelope-verify`'s certificate, also run here
/// (and itself cross-checked against CGAL in `cross_verify`).
fn within(oracle: &Oracle, a: &Path, b: &Path, eps: f64) -> Result<f64, String> {
    let bound = 0.05 * eps;
    let h = oracle
        .try_hausdorff(a, b, bound)
        .map_err(|e| format!("CGAL hausdorff failed: {e}"))?;
    if h <= eps + bound {
        Ok(h)
    } else {
        Err(format!(
            "distance {h:.6e} > eps {eps:.6e} + bound {bound:.1e}"
        ))
    }
}

fn cgal_topology(oracle: &Oracle, path: &Path) -> Result<TopoCounts, String> {
    oracle.topology(path).cgal
}

struct Case {
    name: String,
    soup: TriangleSoup,
    percents: &'static [f64],
    placement: Placement,
    /// With the tolerance phase after the step (`SimplifyOptions::tolerance_phase`).
    tolerance_phase: bool,
}

/// Thin shapes at epsilons above half their thickness, with the tolerance phase: a
/// flattened sphere (an ear), a thin ring, a flattened open cylinder (two border loops,
/// whose vertices the phase removes too) and a block with a narrow fin.
const THIN_PERCENTS: &[f64] = &[2.0, 4.0];

fn thin_cases() -> Vec<Case> {
    let mut ear = generate::icosphere(3, 1.0);
    for p in &mut ear.positions {
        *p *= DVec3::new(1.0, 0.7, 0.02);
    }
    let mut flat_tube = generate::open_cylinder(1.0, 2.0, 64, 8);
    for p in &mut flat_tube.positions {
        p.y *= 0.03;
    }
    [
        ("ear (tolerance)", ear),
        ("ring (tolerance)", generate::torus(1.0, 0.02, 96, 8)),
        ("flat open tube (tolerance)", flat_tube),
        ("block with fin (tolerance)", generate::block_with_fin(0.04)),
    ]
    .into_iter()
    .map(|(n, soup)| Case {
        name: n.to_string(),
        soup,
        percents: THIN_PERCENTS,
        placement: Placement::Auto,
        tolerance_phase: true,
    })
    .collect()
}

const GENERATED_PERCENTS: &[f64] = &[1.0 / 16.0, 0.25, 1.0];
const CORPUS_PERCENTS: &[f64] = &[0.25, 1.0];

fn cases(log: &mut Vec<String>) -> Vec<Case> {
    let mut v: Vec<Case> = [
        ("icosphere(3)", generate::icosphere(3, 1.0)),
        ("torus(48x24)", generate::torus(1.0, 0.35, 48, 24)),
        (
            "box(1x2x3, 6)",
            generate::box_mesh(DVec3::new(1.0, 2.0, 3.0), 6),
        ),
        (
            "open_cylinder(32x8)",
            generate::open_cylinder(1.0, 2.0, 32, 8),
        ),
        ("demo_model (cup)", generate::demo_model()),
        // A folded vertex (no valid normal): pinned, kept, fills may use it as a corner.
        ("folded_vertex", generate::folded_vertex()),
    ]
    .into_iter()
    // The command line's default placement: the subset run, and at the larger epsilons (few
    // vertices left) the collapse phase after it, borders (cylinder, cup) included.
    .map(|(n, soup)| Case {
        name: n.to_string(),
        soup,
        percents: GENERATED_PERCENTS,
        placement: Placement::Auto,
        tolerance_phase: false,
    })
    .collect();
    v.extend(thin_cases());
    // hand and femur each have one folded vertex (pinned).
    let mut corpus = vec![
        "fandisk.off",
        "mech-holes-shark.off",
        "elephant.off",
        "hand.off",
        "femur.off",
    ];
    if full_requested() {
        corpus.extend(["bunny00.off", "armadillo.off"]);
    } else {
        log.push(
            "skipped in debug (ENVELOPE_FULL_CORPUS=1 runs them): bunny00.off, armadillo.off"
                .into(),
        );
    }
    let Some(dir) = corpus_dir() else {
        log.push("corpus missing: corpus meshes not run".into());
        return v;
    };
    for name in corpus {
        match read_path(dir.join(name)) {
            Ok((soup, _)) if input_problems(&soup).is_empty() => {
                // Sliding (section 8) and edge collapses on two of them: vertices leave the
                // input.
                if matches!(name, "fandisk.off" | "mech-holes-shark.off") {
                    for (tag, placement) in [
                        ("slide", Placement::Slide),
                        ("collapse", Placement::Collapse),
                    ] {
                        v.push(Case {
                            name: format!("{name} ({tag})"),
                            soup: soup.clone(),
                            percents: CORPUS_PERCENTS,
                            placement,
                            tolerance_phase: false,
                        });
                    }
                }
                // The tolerance phase with the envelopes capped, on a thin-limbed model
                // and on a part with four border loops.
                if matches!(name, "elephant.off" | "mech-holes-shark.off") {
                    v.push(Case {
                        name: format!("{name} (tolerance)"),
                        soup: soup.clone(),
                        percents: THIN_PERCENTS,
                        placement: Placement::Auto,
                        tolerance_phase: true,
                    });
                }
                v.push(Case {
                    name: name.to_string(),
                    soup,
                    percents: CORPUS_PERCENTS,
                    placement: Placement::Subset,
                    tolerance_phase: false,
                });
            }
            Ok(_) => log.push(format!("{name}: not acceptable input, not run")),
            Err(e) => log.push(format!("{name}: unreadable ({e}), not run")),
        }
    }
    v
}

#[test]
fn outputs_pass_cgal() {
    let Some(oracle) = oracle_or_skip() else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut log = Vec::new();
    let mut failures = Vec::new();
    // What the auto placement ran, over all cases: both branches must have been checked.
    let mut auto_ran = std::collections::BTreeSet::new();
    for (k, case) in cases(&mut log).iter().enumerate() {
        let orig_path = tmp.path().join(format!("{k}-orig.off"));
        write_path(&orig_path, &case.soup, Format::Off).unwrap();
        let topo_in = cgal_topology(&oracle, &orig_path);
        for &percent in case.percents {
            let tag = format!("{} at {percent}%", case.name);
            let eps = percent / 100.0 * case.soup.diagonal();
            let mut options = SimplifyOptions::new(EpsilonField::Constant(eps));
            options.verify = true;
            options.placement = case.placement;
            options.tolerance_phase = case.tolerance_phase;
            let (out, report) = match simplify(&case.soup, &options, &mut ()) {
                Ok(r) => r,
                Err(e) => {
                    failures.push(format!("{tag}: simplify failed: {e}"));
                    continue;
                }
            };
            if case.tolerance_phase && report.tolerance_phase.is_none() {
                failures.push(format!("{tag}: the tolerance phase did not run"));
            }
            if case.placement == Placement::Auto {
                auto_ran.insert(report.placement);
            }
            let out_path = tmp.path().join(format!("{k}-{percent}.off"));
            write_path(&out_path, &out, Format::Off).unwrap();
            let mut problems = Vec::new();
            if let Some(v) = report.verify.as_ref().filter(|v| {
                !v.violations.is_empty() || v.verdict != envelope_verify::Verdict::Holds
            }) {
                problems.push(format!(
                    "envelope-verify {}: {:?}",
                    v.verdict.as_str(),
                    v.violations
                ));
            }
            let pairs = oracle.self_intersections(&out_path);
            if !pairs.is_empty() {
                problems.push(format!(
                    "{} self-intersecting pairs (first {:?})",
                    pairs.len(),
                    pairs[0]
                ));
            }
            let mut dist = [f64::NAN; 2];
            for (i, (a, b, dir)) in [
                (&out_path, &orig_path, "output->input"),
                (&orig_path, &out_path, "input->output"),
            ]
            .into_iter()
            .enumerate()
            {
                match within(&oracle, a, b, eps) {
                    Ok(h) => dist[i] = h,
                    Err(e) => problems.push(format!("{dir}: {e}")),
                }
            }
            match (&topo_in, cgal_topology(&oracle, &out_path)) {
                (Ok(a), Ok(b)) => {
                    if (a.genus, a.borders, a.components) != (b.genus, b.borders, b.components) {
                        problems.push(format!(
                            "topology changed: genus {:?} -> {:?}, borders {} -> {}, components {} -> {}",
                            a.genus, b.genus, a.borders, b.borders, a.components, b.components
                        ));
                    }
                }
                (a, b) => problems.push(format!("CGAL topology unavailable: {a:?} / {b:?}")),
            }
            let line = format!(
                "{tag}: {} -> {} faces ({}), {:.2} s, CGAL h(out,in) {:.4}% h(in,out) {:.4}% of diag, envelope proof {}",
                report.input_faces,
                report.output_faces,
                report.placement,
                report.seconds,
                100.0 * dist[0] / report.diagonal,
                100.0 * dist[1] / report.diagonal,
                report.envelope.proved
            );
            let known = KNOWN_FAILURES.contains(&(case.name.as_str(), percent));
            match (problems.is_empty(), known) {
                (true, false) => {
                    eprintln!("ok   {line}");
                    log.push(format!("ok   {line}"));
                }
                (true, true) => {
                    eprintln!("FIXED {line}");
                    failures.push(format!("{tag}: passes now; remove it from KNOWN_FAILURES"));
                }
                (false, true) => {
                    eprintln!("KNOWN FAIL {line}: {}", problems.join("; "));
                    log.push(format!("KNOWN FAIL {line}: {}", problems.join("; ")));
                    // The open problem must never reach a user as a good output: our own
                    // certificate has to flag it (then `envelope simplify` exits 1 and leaves
                    // OUT alone).
                    let flagged = report
                        .verify
                        .as_ref()
                        .is_some_and(|v| v.verdict == envelope_verify::Verdict::Violated);
                    if !flagged {
                        failures.push(format!(
                            "{tag}: known violation not flagged by envelope-verify"
                        ));
                    }
                }
                (false, false) => {
                    eprintln!("FAIL {line}: {}", problems.join("; "));
                    log.push(format!("FAIL {line}"));
                    failures.push(format!("{tag}: {}", problems.join("; ")));
                }
            }
        }
    }
    println!("{}", log.join("\n"));
    assert!(
        ["auto: collapse", "auto: light collapse"]
            .iter()
            .all(|b| auto_ran.contains(*b)),
        "the auto placement's branches that ran: {auto_ran:?}"
    );
    assert!(
        failures.is_empty(),
        "{} outputs fail the CGAL oracle:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
