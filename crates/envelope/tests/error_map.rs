//! Error maps through the front door: a simplifier's output mapped against its input, the
//! map's guarantees, and its PLY file read back.

use envelope::advanced::render::ramp::{normalize, viridis};
use envelope::{Epsilon, Mesh, Simplifier, Verdict};

/// A torus simplified at 1 % of its diagonal, and the epsilon as a length.
fn simplified_torus() -> (Mesh, Mesh, f64) {
    let orig = Mesh::from_soup(envelope::advanced::mesh::generate::torus(2.0, 0.5, 48, 24));
    let epsilon = Epsilon::percent(1.0);
    let done = Simplifier::new(epsilon).threads(1).run(&orig).unwrap();
    assert!(done.is_certified());
    let approx = done.mesh().clone();
    assert!(
        approx.num_faces() < orig.num_faces() / 2,
        "barely simplified"
    );
    (orig.clone(), approx, 0.01 * orig.diagonal())
}

#[test]
fn a_simplified_mesh_maps_within_epsilon_and_reaches_the_lower_bound() {
    let (orig, approx, eps) = simplified_torus();
    let c = envelope::verify_with_map(&orig, &approx, Epsilon::percent(1.0)).unwrap();
    assert_eq!(c.verdict, Verdict::Holds, "{:?}", c.violations());
    let plain = envelope::verify(&orig, &approx, Epsilon::percent(1.0)).unwrap();
    assert_eq!(plain.verdict, c.verdict);
    assert!(plain.map.is_none());
    let map = c.map.as_ref().unwrap();
    assert_eq!(map.approx_vertices.len(), approx.num_vertices());
    assert!(
        map.approx_vertices.iter().all(|&x| x <= eps),
        "a value above epsilon"
    );
    let worst = map.max_vertex_value();
    assert!(worst >= c.approx_to_orig.lower && worst > 0.0, "{worst}");
    assert_eq!(map.approx_faces.len(), approx.num_faces());
    assert_eq!(map.orig_faces.as_ref().unwrap().len(), orig.num_faces());
    assert!(
        map.orig_faces
            .as_ref()
            .unwrap()
            .iter()
            .all(|b| b.upper <= eps)
    );
    // The JSON holds the per-face bounds both ways.
    let json = c.to_json();
    assert_eq!(
        json["map"]["orig_faces"]["upper"].as_array().unwrap().len(),
        orig.num_faces()
    );
}

#[test]
fn the_map_file_reads_back_with_its_bounds_colours_and_comments() {
    let (orig, approx, eps) = simplified_torus();
    let c = envelope::verify_with_map(&orig, &approx, Epsilon::percent(1.0)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("map.ply");
    envelope::save_error_map(&approx, &c, &path).unwrap();
    let back = envelope::load(&path).unwrap();
    let map = c.map.as_ref().unwrap();
    let q = back.attributes().quality.as_ref().expect("quality");
    let colours = back.attributes().colors.as_ref().expect("colours");
    assert_eq!(back.num_vertices(), approx.num_vertices());
    for (f, tri) in back.triangles().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let written = q.value(f, k)[0];
            let value = map.approx_vertices[v as usize];
            // Rounded up to a float, never down, and by at most one float step.
            assert!(written >= value, "{written} < {value}");
            assert!(written <= value * (1.0 + 2f64.powi(-23)) + f64::from(f32::MIN_POSITIVE));
            // The ramp over 0..epsilon.
            let rgb = viridis(normalize(value, 0.0, eps)).map(|x| f64::from(x) / 255.0);
            assert_eq!(colours.value(f, k), [rgb[0], rgb[1], rgb[2], 1.0]);
        }
    }
    let bytes = std::fs::read(&path).unwrap();
    let text = String::from_utf8_lossy(&bytes);
    let header = &text[..text.find("end_header").unwrap()];
    assert!(header.contains("property float quality"), "{header}");
    assert!(
        header.contains(&format!("comment ramp viridis 0 {eps:?}\n")),
        "{header}"
    );
    assert!(header.contains("comment quality: certified upper bound"));
    // A non-PLY path is refused and nothing is written.
    let off = dir.path().join("map.off");
    assert!(envelope::save_error_map(&approx, &c, &off).is_err());
    assert!(!off.exists());
    // A certificate without a map is refused.
    let plain = envelope::verify(&orig, &approx, Epsilon::percent(1.0)).unwrap();
    assert!(envelope::error_map(&approx, &plain).is_err());
}

#[test]
fn simplification_drops_quality() {
    let (orig, approx, _) = simplified_torus();
    let c = envelope::verify_with_map(&orig, &approx, Epsilon::percent(1.0)).unwrap();
    let mapped = envelope::error_map(&approx, &c).unwrap();
    let again = Simplifier::new(Epsilon::percent(2.0))
        .threads(1)
        .run(&mapped)
        .unwrap();
    assert!(again.mesh().attributes().quality.is_none());
}
