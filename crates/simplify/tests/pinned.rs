//! A vertex without a valid normal (a fold) is pinned by the envelopes; the simplifier
//! keeps it and may still use it as a corner of fill triangles (`Barriers::with_pins`).
use envelope_mesh::generate;
use envelope_offset::EpsilonField;
use envelope_simplify::{SimplifyOptions, simplify};
use envelope_verify::Verdict;

#[test]
fn a_folded_vertex_is_kept_and_its_neighbours_can_go() {
    let soup = generate::folded_vertex();
    let pin = soup.positions[4];
    let mut options = SimplifyOptions::new(EpsilonField::Constant(0.4 * soup.diagonal()));
    options.verify = true;
    let (out, report) =
        simplify(&soup, &options, &mut ()).expect("a folded vertex is no longer refused");
    assert_eq!(report.envelope.pinned, 1);
    assert!(report.envelope.proved);
    assert_eq!(
        report.verify.as_ref().map(|v| v.verdict),
        Some(Verdict::Holds)
    );
    assert!(out.num_faces() < soup.num_faces(), "nothing was removed");
    // The pinned vertex stays, and some fill triangle has it as a corner.
    let kept = out
        .positions
        .iter()
        .position(|&p| p == pin)
        .expect("the pin is kept");
    let removed: Vec<usize> = (0..soup.num_vertices())
        .filter(|&v| !out.positions.contains(&soup.positions[v]))
        .collect();
    assert!(!removed.is_empty());
    let new_faces: Vec<_> = out
        .faces
        .iter()
        .filter(|f| {
            let mut c = f.map(|v| out.positions[v.index()].to_array().map(f64::to_bits));
            c.sort_unstable();
            !soup.faces.iter().any(|g| {
                let mut d = g.map(|v| soup.positions[v.index()].to_array().map(f64::to_bits));
                d.sort_unstable();
                c == d
            })
        })
        .collect();
    assert!(
        new_faces
            .iter()
            .any(|f| f.iter().any(|v| v.index() == kept)),
        "no new triangle at the pin: {new_faces:?}"
    );
}
