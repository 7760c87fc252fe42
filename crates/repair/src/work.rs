//! The mesh the steps edit: positions and triangles, each with the input element it came
//! from, so that every change is reported by the input's own indices.

use envelope_mesh::{FaceId, TriangleSoup, VertexId};
use glam::DVec3;

/// Positions and triangles under repair. Vertex copies (split non-manifold vertices) and
/// triangle pieces (split at T-junctions) keep the input vertex or face they came from.
#[derive(Clone, Debug)]
pub(crate) struct Work {
    /// Positions; input positions, never changed, and copies of them.
    pub positions: Vec<DVec3>,
    /// The input vertex of each working vertex.
    pub vertex_origin: Vec<VertexId>,
    /// Triangles as working vertex indices.
    pub faces: Vec<[u32; 3]>,
    /// The input face of each working triangle.
    pub face_origin: Vec<FaceId>,
    /// Working vertices merged into another by the weld (reported there, not as unreferenced).
    pub welded_away: Vec<bool>,
}

impl Work {
    /// The input as it is: working ids are input ids.
    pub fn new(soup: &TriangleSoup) -> Work {
        Work {
            positions: soup.positions.clone(),
            vertex_origin: (0..soup.positions.len())
                .map(VertexId::from_index)
                .collect(),
            faces: soup.faces.iter().map(|f| f.map(|v| v.0)).collect(),
            face_origin: soup.face_ids().collect(),
            welded_away: vec![false; soup.positions.len()],
        }
    }

    /// Position of working vertex `v`.
    pub fn pos(&self, v: u32) -> DVec3 {
        self.positions[v as usize]
    }

    /// The corner positions of working triangle `f`.
    pub fn triangle(&self, f: usize) -> [DVec3; 3] {
        self.faces[f].map(|v| self.pos(v))
    }

    /// The input vertex of working vertex `v`.
    pub fn input_vertex(&self, v: u32) -> VertexId {
        self.vertex_origin[v as usize]
    }

    /// The input corners of working triangle `f` (after the weld: each corner's kept vertex).
    pub fn input_corners(&self, f: usize) -> [VertexId; 3] {
        self.faces[f].map(|v| self.input_vertex(v))
    }

    /// Keeps the triangles with `keep[f]`, in order.
    pub fn retain_faces(&mut self, keep: &[bool]) {
        let mut k = keep.iter();
        self.faces.retain(|_| *k.next().unwrap_or(&true));
        let mut k = keep.iter();
        self.face_origin.retain(|_| *k.next().unwrap_or(&true));
    }

    /// The soup the steps produced.
    pub fn into_soup(self) -> TriangleSoup {
        TriangleSoup::new(
            self.positions,
            self.faces.into_iter().map(|f| f.map(VertexId)).collect(),
        )
    }
}

/// Orders vertices lying inside segment `ab` from `a` to `b`: along the axis where `a` and
/// `b` differ most the coordinate is strictly monotone on the segment (exact comparisons).
pub(crate) fn sort_along(work: &Work, a: u32, b: u32, points: &mut [u32]) {
    let d = work.pos(b) - work.pos(a);
    let axis = (0..3)
        .max_by(|&i, &j| d[i].abs().total_cmp(&d[j].abs()))
        .unwrap_or(0);
    let rising = d[axis] > 0.0;
    points.sort_by(|&x, &y| {
        let o = work.pos(x)[axis].total_cmp(&work.pos(y)[axis]);
        if rising { o } else { o.reverse() }
    });
}

/// One side of an undirected edge: triangle `face` runs it from corner `corner` to the next.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Side {
    /// Smaller endpoint.
    pub lo: u32,
    /// Larger endpoint.
    pub hi: u32,
    /// The triangle.
    pub face: u32,
    /// The corner the triangle runs the edge from (0, 1 or 2).
    pub corner: u8,
}

impl Side {
    /// The corner slot `3 face + corner` (the corner at [`Side::from`]).
    pub fn slot(self) -> u32 {
        3 * self.face + u32::from(self.corner)
    }

    /// The corner slot at the edge's other end.
    pub fn next_slot(self) -> u32 {
        3 * self.face + (u32::from(self.corner) + 1) % 3
    }
}

/// The undirected edges of the triangles with three distinct corners, as groups of sides
/// sorted by `(lo, hi)`, then face and corner: O(n log n), no hashing, deterministic.
pub(crate) struct Edges {
    sides: Vec<Side>,
    /// Start of each group in `sides`, and `sides.len()` at the end.
    starts: Vec<usize>,
}

impl Edges {
    pub fn build(work: &Work) -> Edges {
        let mut sides = Vec::with_capacity(3 * work.faces.len());
        for (f, t) in work.faces.iter().enumerate() {
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            for i in 0..3 {
                let (a, b) = (t[i], t[(i + 1) % 3]);
                sides.push(Side {
                    lo: a.min(b),
                    hi: a.max(b),
                    face: f as u32,
                    corner: i as u8,
                });
            }
        }
        sides.sort_unstable();
        let mut starts: Vec<usize> = (0..sides.len())
            .filter(|&i| i == 0 || (sides[i - 1].lo, sides[i - 1].hi) != (sides[i].lo, sides[i].hi))
            .collect();
        starts.push(sides.len());
        Edges { sides, starts }
    }

    /// Every edge's sides.
    pub fn groups(&self) -> impl Iterator<Item = &[Side]> + '_ {
        self.starts.windows(2).map(|w| &self.sides[w[0]..w[1]])
    }

    /// The vertex side `s`'s triangle runs the edge from.
    pub fn from(work: &Work, s: Side) -> u32 {
        work.faces[s.face as usize][s.corner as usize]
    }
}
