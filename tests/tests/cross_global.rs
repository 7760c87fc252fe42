//! The global and hybrid simplifiers (`envelope-global`, issue 8) against CGAL: every output
//! must
//!
//! * have no self-intersecting face pair (CGAL `does_self_intersect` pairs),
//! * be within epsilon of the input in **both** directions by CGAL's
//!   `bounded_error_Hausdorff_distance` (asked with an error bound of 0.05 eps; a certain
//!   violation is `h > eps + bound`, as in `cross_simplify`),
//! * keep the genus, components and border loops (CGAL `Surface_mesh` topology),
//! * and hold `envelope-verify`'s exact certificate at epsilon.
//!
//! Meshes: generated ones (icosphere, torus, box, open cylinder, the demo cup) at 1/4 % and
//! 1 % of the diagonal, `fandisk.off` at 1/2 % and `mech-holes-shark.off` (four border loops)
//! at 1/4 %, 1/2 % and 1 %. Under `CI=true`
//! a missing oracle or corpus fails the test (`oracle_or_skip`, `corpus_dir`); elsewhere the
//! skip is loud.

use std::path::Path;

use envelope_global::Method;
use envelope_io::{Format, read_path, write_path};
use envelope_mesh::{TriangleSoup, generate};
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, input_problems, simplify_with};
use envelope_tests::oracle::{Oracle, corpus_dir, oracle_or_skip};
use glam::DVec3;

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

fn cases(log: &mut Vec<String>) -> Vec<(String, TriangleSoup, &'static [f64])> {
    const GENERATED: &[f64] = &[0.25, 1.0];
    const CORPUS: &[f64] = &[0.5];
    // Four border loops: global and hybrid remove border vertices there (open regions).
    const BORDERED: &[f64] = &[0.25, 0.5, 1.0];
    let mut v: Vec<(String, TriangleSoup, &'static [f64])> = vec![
        (
            "icosphere(3)".into(),
            generate::icosphere(3, 1.0),
            GENERATED,
        ),
        (
            "torus(48x24)".into(),
            generate::torus(1.0, 0.35, 48, 24),
            GENERATED,
        ),
        (
            "box(1x2x3, 6)".into(),
            generate::box_mesh(DVec3::new(1.0, 2.0, 3.0), 6),
            GENERATED,
        ),
        (
            "open_cylinder(32x8)".into(),
            generate::open_cylinder(1.0, 2.0, 32, 8),
            GENERATED,
        ),
        ("demo_model (cup)".into(), generate::demo_model(), GENERATED),
    ];
    let Some(dir) = corpus_dir() else {
        log.push("corpus missing: corpus meshes not run".into());
        return v;
    };
    for name in ["fandisk.off", "mech-holes-shark.off"] {
        match read_path(dir.join(name)) {
            Ok((soup, _)) if input_problems(&soup).is_empty() => {
                let percents = if name == "mech-holes-shark.off" {
                    BORDERED
                } else {
                    CORPUS
                };
                v.push((name.to_string(), soup, percents));
            }
            Ok(_) => log.push(format!("{name}: not acceptable input, not run")),
            Err(e) => log.push(format!("{name}: unreadable ({e}), not run")),
        }
    }
    v
}

#[test]
fn global_and_hybrid_outputs_pass_cgal() {
    let Some(oracle) = oracle_or_skip() else {
        return;
    };
    let tmp = tempfile::tempdir().unwrap();
    let mut log = Vec::new();
    let mut failures = Vec::new();
    for (k, (name, soup, percents)) in cases(&mut log).iter().enumerate() {
        let orig_path = tmp.path().join(format!("{k}-orig.off"));
        write_path(&orig_path, soup, Format::Off).unwrap();
        let topo_in = oracle.topology(&orig_path).cgal;
        for &percent in *percents {
            for method in [Method::Global, Method::Hybrid] {
                let tag = format!("{name} at {percent}% ({})", method.as_str());
                let eps = percent / 100.0 * soup.diagonal();
                let mut options = SimplifyOptions::new(EpsilonField::Constant(eps));
                options.verify = true;
                let (out, report) =
                    match simplify_with(soup, &options, method.step().as_ref(), &mut ()) {
                        Ok(r) => r,
                        Err(e) => {
                            failures.push(format!("{tag}: simplify failed: {e}"));
                            continue;
                        }
                    };
                let out_path = tmp
                    .path()
                    .join(format!("{k}-{percent}-{}.off", method.as_str()));
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
                    problems.push(format!("{} self-intersecting pairs", pairs.len()));
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
                match (&topo_in, oracle.topology(&out_path).cgal) {
                    (Ok(a), Ok(b)) => {
                        if (a.genus, a.borders, a.components) != (b.genus, b.borders, b.components)
                        {
                            problems.push(format!(
                                "topology changed: genus {:?} -> {:?}, borders {} -> {}",
                                a.genus, b.genus, a.borders, b.borders
                            ));
                        }
                    }
                    (a, b) => {
                        problems.push(format!("CGAL topology unavailable: {a:?} / {b:?}"));
                    }
                }
                let line = format!(
                    "{tag}: {} -> {} faces, CGAL h(out,in) {:.4}% h(in,out) {:.4}% of diag",
                    report.input_faces,
                    report.output_faces,
                    100.0 * dist[0] / report.diagonal,
                    100.0 * dist[1] / report.diagonal,
                );
                if problems.is_empty() {
                    log.push(format!("ok   {line}"));
                } else {
                    log.push(format!("FAIL {line}: {}", problems.join("; ")));
                    failures.push(format!("{tag}: {}", problems.join("; ")));
                }
            }
        }
    }
    println!("{}", log.join("\n"));
    assert!(
        failures.is_empty(),
        "{} outputs fail the CGAL oracle:\n{}",
        failures.len(),
        failures.join("\n")
    );
}
