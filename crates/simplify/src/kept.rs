//! Faces kept as they are: around a self-intersecting input's intersecting pairs, and where
//! the envelopes cannot be proved.
//!
//! The envelopes of section 3 cannot be proved free of intersections where the input meets
//! itself, and the paper refuses such input (7.1). Instead the faces of every intersecting
//! pair are kept unchanged and the rest is simplified as usual: its envelopes are built and
//! proved for the rest alone (which meets itself nowhere), the kept faces are barriers no new
//! triangle may touch except at the vertices it shares with them, and those shared vertices
//! are kept (never removed nor moved), so the rest's border along the kept faces is unchanged
//! and the two parts join as they did. Every intersecting pair of the output is then a pair
//! of unchanged input faces that met in the input already, which the certificate checks
//! (`envelope_verify::Options::allow_input_intersections`).
//!
//! The same serves an input that meets itself nowhere but whose envelopes cannot be proved
//! (parts closer together than the offsets can resolve): the faces the proof names are kept,
//! the rest tried again, and nothing is ever made from unproved envelopes.
//!
//! Choices the papers leave open (they refuse such input):
//! * no margin at first: the kept faces are barriers, so the rest needs none for the proof;
//! * when the rest's envelopes cannot be proved, the rest faces the proof names in its
//!   contacts are kept too (for two border tubes that meet, or one that meets itself where
//!   the border turns back on itself, the faces around their segments' vertices on the
//!   input's own border), then one ring of faces around every kept one, and the envelopes
//!   are built again, at most [`MAX_ROUNDS`] times: the rest near a crossing is close to
//!   the other sheet there (and so are the border tubes along its cut), and a thin part
//!   elsewhere needs the same. Every round keeps more than the one before. Eight rounds,
//!   not fewer: finer scans need more (the measurements are in the CHANGELOG);
//! * faces are added to the kept set until every shared vertex has one fan of rest faces, so
//!   the rest is a manifold with border (a vertex the kept faces cut into two fans would be
//!   non-manifold there).

use envelope_mesh::{FaceId, TriangleSoup, VertexFaces, VertexId};

/// Envelope builds after the first one before giving up on the rest's proof.
pub(crate) const MAX_ROUNDS: usize = 8;

/// The input split into the faces kept as they are and the rest to simplify.
#[derive(Clone, Debug)]
pub(crate) struct KeptRegion {
    /// Per input face: kept as it is.
    pub kept_face: Vec<bool>,
    /// The rest: every input position (ids unchanged), the faces not kept, in input order.
    pub rest: TriangleSoup,
    /// The input face of each face of `rest`.
    pub rest_faces: Vec<FaceId>,
    /// The kept faces, on every input position.
    pub kept: TriangleSoup,
    /// Per input vertex: a corner of both a kept face and a rest face (never removed nor
    /// moved).
    pub shared: Vec<bool>,
}

impl KeptRegion {
    /// The faces of `pairs` kept, grown until every shared vertex has one fan of rest faces;
    /// `soup` must be a manifold (possibly with border).
    pub(crate) fn around(soup: &TriangleSoup, pairs: &[(FaceId, FaceId)]) -> Self {
        let mut kept_face = vec![false; soup.num_faces()];
        for &(a, b) in pairs {
            kept_face[a.index()] = true;
            kept_face[b.index()] = true;
        }
        let faces_of = VertexFaces::new(soup.num_vertices(), &soup.faces);
        Self::new(soup, &faces_of, kept_face)
    }

    /// This region with the input faces `more` and those around the vertices `at` kept too
    /// (what the envelope proof named) and then one ring of faces around all kept ones: the
    /// faces next to a named one are as close to what the proof found, and a cut border near
    /// another sheet (whose border tube the proof may find there) moves away from it.
    pub(crate) fn grown(&self, soup: &TriangleSoup, more: &[FaceId], at: &[VertexId]) -> Self {
        let mut kept_face = self.kept_face.clone();
        for f in more {
            kept_face[f.index()] = true;
        }
        let faces_of = VertexFaces::new(soup.num_vertices(), &soup.faces);
        for v in at {
            for &f in faces_of.of(v.index()) {
                kept_face[f as usize] = true;
            }
        }
        let touched = touched_vertices(soup, &kept_face);
        keep_faces_at(&mut kept_face, &faces_of, &touched);
        Self::new(soup, &faces_of, kept_face)
    }

    fn new(soup: &TriangleSoup, faces_of: &VertexFaces, mut kept_face: Vec<bool>) -> Self {
        let n = soup.num_vertices();
        // Until every vertex on both sides has one fan of rest faces.
        loop {
            let touched = touched_vertices(soup, &kept_face);
            let split: Vec<bool> = (0..n)
                .map(|v| touched[v] && rest_fans(soup, faces_of.of(v), &kept_face, v) > 1)
                .collect();
            if !split.contains(&true) {
                break;
            }
            keep_faces_at(&mut kept_face, faces_of, &split);
        }
        let pick = |keep: bool| TriangleSoup {
            positions: soup.positions.clone(),
            faces: soup
                .faces
                .iter()
                .zip(&kept_face)
                .filter(|(_, k)| **k == keep)
                .map(|(f, _)| *f)
                .collect(),
        };
        let (kept, rest) = (pick(true), pick(false));
        let rest_faces = soup.face_ids().filter(|f| !kept_face[f.index()]).collect();
        let on_kept = touched_vertices(soup, &kept_face);
        let mut shared = vec![false; n];
        for f in &rest.faces {
            for v in f {
                shared[v.index()] = on_kept[v.index()];
            }
        }
        KeptRegion {
            kept_face,
            rest,
            rest_faces,
            kept,
            shared,
        }
    }

    /// Number of kept faces.
    pub(crate) fn num_kept(&self) -> usize {
        self.kept.num_faces()
    }
}

/// Keeps every face around each vertex `v` with `at[v]`.
fn keep_faces_at(kept_face: &mut [bool], faces_of: &VertexFaces, at: &[bool]) {
    for (v, _) in at.iter().enumerate().filter(|(_, a)| **a) {
        for &f in faces_of.of(v) {
            kept_face[f as usize] = true;
        }
    }
}

/// Vertices that are a corner of a kept face.
fn touched_vertices(soup: &TriangleSoup, kept_face: &[bool]) -> Vec<bool> {
    let mut touched = vec![false; soup.num_vertices()];
    for (f, _) in soup.faces.iter().zip(kept_face).filter(|(_, k)| **k) {
        for v in f {
            touched[v.index()] = true;
        }
    }
    touched
}

/// The number of fans the rest faces around `v` form: groups joined through edges at `v`
/// that two rest faces share.
fn rest_fans(soup: &TriangleSoup, around: &[u32], kept_face: &[bool], v: usize) -> usize {
    let rest: Vec<u32> = around
        .iter()
        .copied()
        .filter(|&f| !kept_face[f as usize])
        .collect();
    // Union-find over the few rest faces at `v`.
    let mut parent: Vec<usize> = (0..rest.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let others = |f: u32| -> Vec<VertexId> {
        soup.faces[f as usize]
            .iter()
            .copied()
            .filter(|w| w.index() != v)
            .collect()
    };
    for i in 0..rest.len() {
        for j in i + 1..rest.len() {
            let (a, b) = (others(rest[i]), others(rest[j]));
            if a.iter().any(|w| b.contains(w)) {
                let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                parent[ri] = rj;
            }
        }
    }
    (0..rest.len())
        .filter(|&i| root(&mut parent, i) == i)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use envelope_mesh::{analyze, generate};

    #[test]
    fn kept_faces_cover_the_pairs_and_the_rest_is_manifold() {
        let soup = generate::icosphere(2, 1.0);
        let pairs = [(FaceId(3), FaceId(40)), (FaceId(41), FaceId(100))];
        let mut r = KeptRegion::around(&soup, &pairs);
        for round in 0..3 {
            for &(a, b) in &pairs {
                assert!(r.kept_face[a.index()] && r.kept_face[b.index()]);
            }
            assert_eq!(r.num_kept() + r.rest.num_faces(), soup.num_faces());
            assert_eq!(r.rest_faces.len(), r.rest.num_faces());
            for (k, f) in r.rest_faces.iter().enumerate() {
                assert_eq!(r.rest.faces[k], soup.faces[f.index()]);
            }
            assert!(analyze(&r.rest).manifold, "round {round}");
            assert!(r.shared.iter().any(|&s| s));
            // Nothing named: one more ring.
            let next = r.grown(&soup, &[], &[]);
            assert!(next.num_kept() > r.num_kept());
            r = next;
        }
        // Named faces are kept with their neighbours, and a ring around the rest.
        let r = KeptRegion::around(&soup, &pairs);
        let named = r.rest_faces[r.rest_faces.len() / 2];
        let g = r.grown(&soup, &[named], &[]);
        assert!(g.kept_face[named.index()]);
        let ring = r.grown(&soup, &[], &[]);
        assert!(g.num_kept() > ring.num_kept() + 1 && g.num_kept() < ring.num_kept() + 20);
        // Named vertices: all their faces are kept.
        let v = soup.faces[r.rest_faces[0].index()][0];
        let at = r.grown(&soup, &[], &[v]);
        for (f, face) in soup.faces.iter().enumerate() {
            assert!(!face.contains(&v) || at.kept_face[f]);
        }
        assert!(at.num_kept() > ring.num_kept());
    }

    #[test]
    fn a_vertex_cut_into_two_fans_is_kept_whole() {
        // Two faces of a vertex's fan that share no edge kept: its rest faces form two fans,
        // so all its faces are kept.
        let soup = generate::icosphere(1, 1.0);
        let v = 0u32;
        let fan: Vec<u32> = soup
            .faces
            .iter()
            .enumerate()
            .filter(|(_, f)| f.contains(&VertexId(v)))
            .map(|(i, _)| i as u32)
            .collect();
        assert!(fan.len() >= 5);
        let others = |f: u32| {
            soup.faces[f as usize]
                .map(|w| w.0)
                .into_iter()
                .filter(|&w| w != v)
        };
        let apart = fan[1..]
            .iter()
            .copied()
            .find(|&g| others(fan[0]).all(|w| !others(g).any(|x| x == w)))
            .expect("a face of the fan apart from the first");
        let r = KeptRegion::around(&soup, &[(FaceId(fan[0]), FaceId(apart))]);
        for &f in &fan {
            assert!(r.kept_face[f as usize]);
        }
        assert!(analyze(&r.rest).manifold);
    }
}
