//! Outputs are byte-identical for any number of threads (an ARCHITECTURE.md invariant): the
//! front door's `threads(n)` for 1, 2 and 4 on corpus meshes at a small and a large epsilon
//! (the large one runs the moving phase of the default placement), a level-of-detail chain
//! and a genus reduction.

use envelope::{Epsilon, Genus, Lod, Mesh, Simplifier};
use envelope_tests::oracle::corpus_dir;

const THREADS: [usize; 3] = [1, 2, 4];

/// The mesh as OFF bytes (what `envelope simplify` writes).
fn bytes(mesh: &Mesh, dir: &tempfile::TempDir, name: &str) -> Vec<u8> {
    let path = dir.path().join(format!("{name}.off"));
    envelope::save(mesh, &path).expect("write the output");
    std::fs::read(&path).expect("read it back")
}

/// The report without its clocks and memory.
fn report_without_times(mut v: serde_json::Value) -> serde_json::Value {
    fn strip(v: &mut serde_json::Value) {
        if let Some(o) = v.as_object_mut() {
            o.retain(|k, _| !k.contains("seconds") && !k.contains("memory"));
            o.values_mut().for_each(strip);
        }
    }
    strip(&mut v);
    v
}

#[test]
fn simplify_outputs_are_the_same_for_any_thread_count() {
    let Some(dir) = corpus_dir() else { return };
    let tmp = tempfile::tempdir().expect("temporary directory");
    let mut runs = 0;
    for name in ["holes", "elephant", "mech-holes-shark", "fandisk"] {
        let mesh = envelope::load(dir.join(format!("{name}.off"))).expect("corpus mesh");
        for (eps, certify) in [("1/16%", true), ("1%", false)] {
            let outputs: Vec<(Vec<u8>, serde_json::Value)> = THREADS
                .iter()
                .map(|&n| {
                    let done = Simplifier::new(eps.parse().expect("epsilon"))
                        .certify(certify)
                        .threads(n)
                        .run(&mesh)
                        .unwrap_or_else(|e| panic!("{name} at {eps}, {n} threads: {e}"));
                    runs += 1;
                    (
                        bytes(done.mesh(), &tmp, &format!("{name}-{n}")),
                        report_without_times(done.report().to_json()),
                    )
                })
                .collect();
            for (k, n) in THREADS.iter().enumerate().skip(1) {
                assert!(
                    outputs[k].0 == outputs[0].0,
                    "{name} at {eps}: the output on {n} threads differs from the one on 1"
                );
                assert_eq!(
                    outputs[k].1, outputs[0].1,
                    "{name} at {eps}: the report on {n} threads differs from the one on 1"
                );
            }
        }
    }
    assert_eq!(runs, 4 * 2 * THREADS.len());
}

#[test]
fn lod_and_genus_outputs_are_the_same_for_any_thread_count() {
    let Some(dir) = corpus_dir() else { return };
    let tmp = tempfile::tempdir().expect("temporary directory");
    let cup = Mesh::demo();
    let chains: Vec<Vec<Vec<u8>>> = THREADS
        .iter()
        .map(|&n| {
            Lod::new(vec![Epsilon::percent(0.25), Epsilon::percent(1.0)])
                .certify(false)
                .threads(n)
                .run(&cup)
                .expect("chain")
                .iter()
                .map(|l| bytes(&Mesh::from_soup(l.mesh.clone()), &tmp, "level"))
                .collect()
        })
        .collect();
    assert_eq!(chains[0].len(), 2);
    assert!(
        chains.iter().all(|c| *c == chains[0]),
        "levels differ between thread counts"
    );

    let shark = envelope::load(dir.join("mech-holes-shark.off")).expect("corpus mesh");
    let filled: Vec<Vec<u8>> = THREADS
        .iter()
        .map(|&n| {
            let (out, _) = Genus::new(Epsilon::percent(2.0))
                .threads(n)
                .run(&shark)
                .expect("genus reduction");
            bytes(&out, &tmp, "genus")
        })
        .collect();
    assert!(
        filled.iter().all(|f| *f == filled[0]),
        "genus outputs differ between thread counts"
    );
}
