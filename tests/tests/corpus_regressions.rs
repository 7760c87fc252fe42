//! Corpus inputs that once failed, each with what failed. They need the corpus
//! (`scripts/corpus.sh`); under `CI=true` a missing corpus fails them.

use envelope_io::read_path;
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, simplify};
use envelope_tests::oracle::corpus_dir;
use envelope_verify::Verdict;

/// `b9_mesh.off` (47 components, 76 border loops, one intersecting pair) at 1 %: a
/// two-face component's border vertex was removed by a new border edge that touched no
/// tube, and ended 2.05 from the output against an epsilon of 1.46 (the certificate failed).
/// A new border edge must now pass through the tube ring of every input border vertex it
/// stands for (`envelope_simplify::policy::BorderCover`).
#[test]
fn b9_mesh_border_vertices_stay_within_epsilon() {
    let Some(dir) = corpus_dir() else {
        return;
    };
    let (soup, _) = read_path(dir.join("b9_mesh.off")).expect("b9_mesh.off reads");
    for percent in [0.25, 1.0] {
        let options = SimplifyOptions {
            verify: true,
            ..SimplifyOptions::new(EpsilonField::Constant(percent / 100.0 * soup.diagonal()))
        };
        let (out, report) = simplify(&soup, &options, &mut ()).expect("simplified");
        let verify = report.verify.expect("certified");
        assert_eq!(verify.verdict, Verdict::Holds, "{percent} %: {verify:?}");
        assert!(out.num_faces() < soup.num_faces(), "{percent} %");
    }
}
