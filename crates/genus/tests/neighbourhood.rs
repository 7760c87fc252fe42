//! Alpha-neighbourhoods (4.2): the grid finds exactly the pairs a brute-force all-pairs
//! exact prism test finds, and prism contact agrees with the L-infinity distance of points.

use envelope_genus::{AlphaPrism, alpha_close_pairs};
use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use glam::DVec3;
use proptest::prelude::*;

fn brute_force(soup: &TriangleSoup, alpha: f64) -> Vec<(FaceId, FaceId)> {
    let prisms: Vec<AlphaPrism> = soup
        .face_ids()
        .map(|f| AlphaPrism::new(soup.triangle(f), alpha).unwrap())
        .collect();
    let mut out = Vec::new();
    for i in 0..prisms.len() {
        for j in i + 1..prisms.len() {
            if prisms[i].intersects(&prisms[j]) {
                out.push((FaceId::from_index(i), FaceId::from_index(j)));
            }
        }
    }
    out
}

fn soup_strategy() -> impl Strategy<Value = TriangleSoup> {
    prop::collection::vec((-8i32..8, -8i32..8, -8i32..8), 3..24).prop_map(|pts| {
        let positions: Vec<DVec3> = pts
            .iter()
            .map(|&(x, y, z)| DVec3::new(x.into(), y.into(), z.into()) * 0.5)
            .collect();
        let n = positions.len() as u32;
        let faces = (0..n / 3)
            .map(|k| [VertexId(3 * k), VertexId(3 * k + 1), VertexId(3 * k + 2)])
            .collect();
        TriangleSoup::new(positions, faces)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn grid_equals_brute_force(soup in soup_strategy(),
                               alpha in prop_oneof![Just(0.25), Just(0.5), Just(1.0), 0.05f64..2.0]) {
        prop_assert_eq!(alpha_close_pairs(&soup, alpha, None).unwrap(), brute_force(&soup, alpha));
    }
}

#[test]
fn parallel_plates_touch_exactly_at_two_alpha() {
    // Two unit triangles 1.0 apart along z: close iff alpha >= 0.5 (dyadic, so exact).
    let s = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
        ],
        &[[0, 1, 2], [3, 4, 5]],
    );
    assert_eq!(alpha_close_pairs(&s, 0.5, None).unwrap().len(), 1);
    assert_eq!(
        alpha_close_pairs(&s, 0.5 - 1.0 / 1024.0, None)
            .unwrap()
            .len(),
        0
    );
    // Skew edges: the edge (0,0,0)-(1,0,0) and the edge (0.5,-1,1)-(0.5,1,1) are 1.0 apart
    // in z; the prisms meet through edge-facet contact, with no corner of either inside.
    let s = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.0, -4.0],
            [0.5, -1.0, 1.0],
            [0.5, 1.0, 1.0],
            [0.5, 0.0, 5.0],
        ],
        &[[0, 1, 2], [3, 4, 5]],
    );
    assert_eq!(alpha_close_pairs(&s, 0.5, None).unwrap().len(), 1);
    assert!(alpha_close_pairs(&s, 0.49, None).unwrap().is_empty());
}

#[test]
fn tiny_alpha_on_long_triangles_stays_bounded() {
    let s = TriangleSoup::from_raw(
        &[
            [0.0, 0.0, 0.0],
            [1000.0, 0.0, 0.0],
            [0.0, 1000.0, 0.0],
            [0.0, 0.0, 1e-7],
            [1000.0, 0.0, 1e-7],
            [0.0, 1000.0, 1e-7],
            [5000.0, 0.0, 0.0],
            [5001.0, 0.0, 0.0],
            [5000.0, 1.0, 0.0],
        ],
        &[[0, 1, 2], [3, 4, 5], [6, 7, 8]],
    );
    assert_eq!(
        alpha_close_pairs(&s, 1e-6, None).unwrap(),
        brute_force(&s, 1e-6)
    );
    assert_eq!(alpha_close_pairs(&s, 1e-6, None).unwrap().len(), 1);
}
