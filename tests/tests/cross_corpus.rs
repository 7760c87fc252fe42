//! Every libcgal-demo corpus mesh our reader loads, against CGAL (and OpenMesh):
//!
//! (a) topology: V, F, E, isolated vertices, border loops, components, Euler characteristic
//!     and genus from `envelope_mesh::analyze` equal the oracle's CGAL `Surface_mesh` line, and
//!     OpenMesh's where it loaded every face. Where our reader and CGAL see different V/F the
//!     mesh is named with the reason (our reader fan-triangulates polygons; CGAL keeps them) and
//!     the counts are checked against the reason (F differs by exactly the triangles the fans
//!     added) and topology against OpenMesh, which also triangulates, when it loaded all faces.
//! (b) intersecting face pairs from `envelope_check::check` equal CGAL's `self_intersections`
//!     (see `envelope_tests::gen::compare_self_intersections` for the degenerate-face rule).
//!
//! In debug builds files above [`DEBUG_MAX_BYTES`] are skipped (named in the output);
//! `ENVELOPE_FULL_CORPUS=1`, a release build, or the ignored `corpus_full` test covers them.

use std::path::PathBuf;

use envelope_mesh::analyze;
use envelope_tests::r#gen::compare_self_intersections;
use envelope_tests::oracle::{Oracle, OracleTopology, TopoCounts, corpus_meshes, oracle_or_skip};

/// Largest file the default debug run reads.
const DEBUG_MAX_BYTES: u64 = 700_000;

fn full_requested() -> bool {
    std::env::var("ENVELOPE_FULL_CORPUS").is_ok_and(|v| v == "1") || !cfg!(debug_assertions)
}

fn name(p: &std::path::Path) -> String {
    p.file_name().unwrap().to_string_lossy().into_owned()
}

/// Our counts in the oracle's shape, and whether the soup is manifold.
fn our_counts(soup: &envelope_mesh::TriangleSoup) -> (TopoCounts, bool) {
    let t = analyze(soup);
    let c = TopoCounts {
        v: t.num_vertices as u64,
        f: t.num_faces as u64,
        e: t.num_edges as u64,
        isolated: t.unreferenced_vertices.len() as u64,
        borders: t.num_border_loops() as u64,
        components: t.components.len() as u64,
        chi: t.euler,
        genus: t.genus.map(u64::from),
    };
    (c, t.manifold)
}

/// OpenMesh keeps pinch (non-manifold) vertices, where its boundary cycles follow its own
/// halfedge links, its components join through vertices and its genus formula still yields a
/// number; we pair border edges at pinches by our own rule, join components through edges and
/// leave the genus undefined. On a non-manifold soup only V, F, E, isolated vertices and the
/// Euler characteristic are convention-free, so only those are compared.
fn same_as_openmesh(ours: &TopoCounts, om: &TopoCounts, manifold: bool) -> bool {
    if manifold {
        ours == om
    } else {
        (ours.v, ours.f, ours.e, ours.isolated, ours.chi) == (om.v, om.f, om.e, om.isolated, om.chi)
    }
}

struct Outcome {
    failures: Vec<String>,
    skipped: Vec<String>,
    notes: Vec<String>,
    topo_compared: usize,
    selfint_compared: usize,
    total_pairs: usize,
}

fn run(full: bool) -> Option<Outcome> {
    let o: Oracle = oracle_or_skip()?;
    let all = corpus_meshes();
    if all.is_empty() {
        return None;
    }
    let mut out = Outcome {
        failures: Vec::new(),
        skipped: Vec::new(),
        notes: Vec::new(),
        topo_compared: 0,
        selfint_compared: 0,
        total_pairs: 0,
    };
    let paths: Vec<PathBuf> = all
        .into_iter()
        .filter(|p| {
            let big = std::fs::metadata(p).map_or(0, |m| m.len()) > DEBUG_MAX_BYTES;
            if big && !full {
                out.skipped.push(format!(
                    "{}: larger than {DEBUG_MAX_BYTES} bytes in a debug run (set ENVELOPE_FULL_CORPUS=1)",
                    name(p)
                ));
            }
            !big || full
        })
        .collect();
    let topo: Vec<OracleTopology> = o.topology_batch(&paths);
    for (path, ot) in paths.iter().zip(topo) {
        let n = name(path);
        let (soup, report) = match envelope_io::read_path(path) {
            Ok(r) => r,
            Err(e) => {
                out.skipped.push(format!("{n}: our reader rejects it: {e}"));
                continue;
            }
        };
        let (ours, manifold) = our_counts(&soup);
        let fan_extra = report.triangles_from_polygons - report.polygons_triangulated;

        // (a) topology.
        let om_complete = ot.openmesh.as_ref().ok().filter(|c| {
            ot.file_polygons.is_some_and(|fp| c.f >= fp) && c.f == ours.f && c.v == ours.v
        });
        match (&ot.cgal, report.polygons_triangulated) {
            (Ok(cg), 0) => {
                out.topo_compared += 1;
                if *cg != ours {
                    out.failures
                        .push(format!("{n}: topology ours {ours:?}\n    CGAL {cg:?}"));
                }
                if let Some(om) = om_complete
                    && !same_as_openmesh(&ours, om, manifold)
                {
                    out.failures
                        .push(format!("{n}: topology ours {ours:?}\n    OpenMesh {om:?}"));
                }
            }
            (cg, polys) => {
                // Different V/F than CGAL's Surface_mesh, or no Surface_mesh at all: say why.
                let (cv, cf) = match cg {
                    Ok(c) => (c.v, c.f),
                    Err(_) => ot.soup_counts.unwrap_or((u64::MAX, u64::MAX)),
                };
                let why = if polys > 0 {
                    format!(
                        "our reader fan-triangulated {polys} polygons into {} triangles (CGAL keeps polygons)",
                        report.triangles_from_polygons
                    )
                } else {
                    format!("CGAL: {}", cg.as_ref().err().map_or("?", |s| s.as_str()))
                };
                if cv != ours.v || cf + fan_extra != ours.f {
                    out.failures.push(format!(
                        "{n}: V/F ours {}/{} vs CGAL {cv}/{cf} not explained by {why}",
                        ours.v, ours.f
                    ));
                }
                match om_complete {
                    Some(om) => {
                        out.topo_compared += 1;
                        out.notes.push(format!(
                            "{n}: {why}; topology compared with OpenMesh{}",
                            if manifold {
                                ""
                            } else {
                                " (non-manifold: V, F, E, isolated, chi only)"
                            }
                        ));
                        if !same_as_openmesh(&ours, om, manifold) {
                            out.failures
                                .push(format!("{n}: topology ours {ours:?}\n    OpenMesh {om:?}"));
                        }
                    }
                    None => {
                        out.notes.push(format!(
                            "{n}: {why}; OpenMesh {}: topology not compared",
                            match &ot.openmesh {
                                Ok(c) => format!(
                                    "read V={} F={} (ours V={} F={})",
                                    c.v, c.f, ours.v, ours.f
                                ),
                                Err(e) => format!("failed ({e})"),
                            }
                        ))
                    }
                }
            }
        }

        // (b) self-intersections (the oracle rejects files with non-triangle faces).
        if report.polygons_triangulated > 0 {
            out.skipped.push(format!(
                "{n}: self-intersections not compared: polygon faces (CGAL's oracle refuses them)"
            ));
            continue;
        }
        match compare_self_intersections(&o, path, &soup) {
            Ok(a) => {
                out.selfint_compared += 1;
                out.total_pairs += a.pairs.len();
                if !a.pairs.is_empty() || !a.degenerate.is_empty() {
                    out.notes.push(format!(
                        "{n}: {} intersecting pairs, {} degenerate faces ({} of our pairs involve one), CGAL {:?} path",
                        a.pairs.len(),
                        a.degenerate.len(),
                        a.ours_with_degenerate,
                        a.kind
                    ));
                }
            }
            Err(e) => out.failures.push(format!("{n}: {e}")),
        }
    }
    Some(out)
}

fn report_and_assert(out: Outcome) {
    eprintln!(
        "corpus: topology compared on {} meshes, self-intersections on {} ({} pairs in all)",
        out.topo_compared, out.selfint_compared, out.total_pairs
    );
    for s in &out.skipped {
        eprintln!("  skipped {s}");
    }
    for s in &out.notes {
        eprintln!("  note {s}");
    }
    assert!(
        out.topo_compared > 0 && out.selfint_compared > 0,
        "nothing compared"
    );
    assert!(
        out.failures.is_empty(),
        "{} corpus disagreements with CGAL/OpenMesh:\n{}",
        out.failures.len(),
        out.failures.join("\n")
    );
}

#[test]
fn corpus_matches_cgal() {
    if let Some(out) = run(full_requested()) {
        report_and_assert(out);
    }
}

#[test]
#[ignore = "reads the whole corpus in debug builds (~minutes); run with --ignored or ENVELOPE_FULL_CORPUS=1"]
fn corpus_full() {
    if let Some(out) = run(true) {
        report_and_assert(out);
    }
}
