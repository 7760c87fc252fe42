//! [`RepairReport`]: every change each step made, counted in full, with the first few
//! examples named by the input's own indices.
//!
//! Indices are those of the mesh as read, from 0: vertex `v3` is the fourth vertex of the
//! file; face `f7` the eighth triangle (the file's eighth face when it holds only triangles;
//! readers cut polygons into triangles in order). A face made by splitting another keeps the
//! input face's index; a vertex made by splitting another keeps the input vertex's index.

use std::collections::BTreeMap;
use std::fmt;

use envelope_mesh::{FaceId, VertexId};
use glam::DVec3;
use serde_json::{Value, json};

/// The steps of [`crate::repair`], in the order they run ([`Step::ALL`]).
///
/// ```
/// use envelope_repair::Step;
/// assert_eq!(Step::ALL[0].key(), "weld");
/// assert_eq!(Step::ALL.last(), Some(&Step::UnreferencedVertices));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Step {
    /// Referenced vertices at bitwise-equal positions (`-0.0` as `0.0`) become one.
    Weld,
    /// Faces on the same three vertices (either orientation) after the weld: all but the
    /// first are dropped.
    DuplicateFaces,
    /// Faces of zero area (exactly collinear corners, or a repeated vertex) whose segment or
    /// point is proved to lie on the remaining faces: dropped.
    DegenerateFaces,
    /// Faces split at vertices lying exactly in the open interior of one of their border
    /// edges.
    TJunctions,
    /// Edges with more than two faces, separated into manifold sheets (by the vertex split).
    NonManifoldEdges,
    /// Vertices whose faces form several fans, split into one vertex per fan.
    NonManifoldVertices,
    /// Faces flipped so that each component is consistently oriented.
    Orientation,
    /// Vertices no face uses, dropped.
    UnreferencedVertices,
}

impl Step {
    /// Every step, in the order they run.
    pub const ALL: [Step; 8] = [
        Step::Weld,
        Step::DuplicateFaces,
        Step::DegenerateFaces,
        Step::TJunctions,
        Step::NonManifoldEdges,
        Step::NonManifoldVertices,
        Step::Orientation,
        Step::UnreferencedVertices,
    ];

    /// The stable key used in JSON and text.
    #[must_use]
    pub const fn key(self) -> &'static str {
        match self {
            Step::Weld => "weld",
            Step::DuplicateFaces => "duplicate_faces",
            Step::DegenerateFaces => "degenerate_faces",
            Step::TJunctions => "t_junctions",
            Step::NonManifoldEdges => "non_manifold_edges",
            Step::NonManifoldVertices => "non_manifold_vertices",
            Step::Orientation => "orientation",
            Step::UnreferencedVertices => "unreferenced_vertices",
        }
    }

    /// What the count counts.
    #[must_use]
    pub const fn counts(self) -> &'static str {
        match self {
            Step::Weld => "vertices merged into an earlier one at the same position",
            Step::DuplicateFaces => "duplicate faces dropped",
            Step::DegenerateFaces => "zero-area faces dropped, their points covered by others",
            Step::TJunctions => "vertices inserted into a border edge (faces split)",
            Step::NonManifoldEdges => "edges with more than two faces separated",
            Step::NonManifoldVertices => "vertices split into one per sheet",
            Step::Orientation => "faces flipped",
            Step::UnreferencedVertices => "unreferenced vertices dropped",
        }
    }
}

impl fmt::Display for Step {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.key())
    }
}

/// One change, named by input indices (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Change {
    /// `merged` now use `kept` (all at `position`).
    Weld {
        /// The vertex kept (the smallest index of the group).
        kept: VertexId,
        /// The vertices merged into it.
        merged: Vec<VertexId>,
        /// The shared position.
        position: DVec3,
    },
    /// `dropped` repeated `kept`'s vertices.
    DuplicateFace {
        /// The face kept (the first of its group).
        kept: FaceId,
        /// The face dropped.
        dropped: FaceId,
    },
    /// A zero-area face dropped: its points lie on `covered_by` (closed triangles).
    DegenerateFace {
        /// The face.
        face: FaceId,
        /// Its corners after the weld.
        corners: [VertexId; 3],
        /// Faces covering its segment (one per piece between consecutive corners) or point.
        covered_by: Vec<FaceId>,
    },
    /// `vertex` lies exactly inside border edge `edge` of `face`, which was split there.
    TJunction {
        /// The vertex.
        vertex: VertexId,
        /// The edge, as the face runs it.
        edge: [VertexId; 2],
        /// The face split.
        face: FaceId,
    },
    /// An edge with more than two faces; each fan around its ends became its own sheet.
    NonManifoldEdge {
        /// Its endpoints, smaller first.
        edge: [VertexId; 2],
        /// Its faces, increasing.
        faces: Vec<FaceId>,
    },
    /// A vertex whose faces formed `sheets` fans, now one vertex per fan (copies at the same
    /// position, appended after the input's vertices).
    VertexSplit {
        /// The vertex.
        vertex: VertexId,
        /// Its fans.
        sheets: usize,
    },
    /// A face whose corner order was reversed.
    FaceFlipped {
        /// The face.
        face: FaceId,
    },
    /// A vertex no face uses, dropped.
    VertexDropped {
        /// The vertex.
        vertex: VertexId,
        /// Its position.
        position: DVec3,
    },
}

impl Change {
    /// The change as JSON (input indices as numbers from 0).
    #[must_use]
    pub fn to_json(&self) -> Value {
        let ids = |v: &[VertexId]| v.iter().map(|v| v.0).collect::<Vec<_>>();
        let fids = |f: &[FaceId]| f.iter().map(|f| f.0).collect::<Vec<_>>();
        match self {
            Change::Weld {
                kept,
                merged,
                position,
            } => json!({ "kept": kept.0, "merged": ids(merged), "position": position.to_array() }),
            Change::DuplicateFace { kept, dropped } => {
                json!({ "kept": kept.0, "dropped": dropped.0 })
            }
            Change::DegenerateFace {
                face,
                corners,
                covered_by,
            } => {
                json!({ "face": face.0, "vertices": ids(corners), "covered_by": fids(covered_by) })
            }
            Change::TJunction { vertex, edge, face } => {
                json!({ "vertex": vertex.0, "edge": ids(edge), "face": face.0 })
            }
            Change::NonManifoldEdge { edge, faces } => {
                json!({ "edge": ids(edge), "faces": fids(faces) })
            }
            Change::VertexSplit { vertex, sheets } => {
                json!({ "vertex": vertex.0, "sheets": sheets })
            }
            Change::FaceFlipped { face } => json!({ "face": face.0 }),
            Change::VertexDropped { vertex, position } => {
                json!({ "vertex": vertex.0, "position": position.to_array() })
            }
        }
    }
}

impl fmt::Display for Change {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = |p: &DVec3| format!("({}, {}, {})", p.x, p.y, p.z);
        let list = |v: &[VertexId]| {
            v.iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(" ")
        };
        match self {
            Change::Weld {
                kept,
                merged,
                position,
            } => write!(f, "{} -> {kept} at {}", list(merged), p(position)),
            Change::DuplicateFace { kept, dropped } => write!(f, "{dropped} repeats {kept}"),
            Change::DegenerateFace {
                face,
                corners,
                covered_by,
            } => {
                let by: Vec<String> = covered_by.iter().map(ToString::to_string).collect();
                write!(f, "{face} [{}] on {}", list(corners), by.join(" "))
            }
            Change::TJunction { vertex, edge, face } => {
                write!(f, "{vertex} inside {}-{} of {face}", edge[0], edge[1])
            }
            Change::NonManifoldEdge { edge, faces } => {
                // The first few: a dense stack puts thousands of faces on one edge.
                let fs: Vec<String> = faces.iter().take(8).map(ToString::to_string).collect();
                let more = if faces.len() > 8 {
                    format!(" ... ({} faces)", faces.len())
                } else {
                    String::new()
                };
                write!(f, "{}-{} in {}{more}", edge[0], edge[1], fs.join(" "))
            }
            Change::VertexSplit { vertex, sheets } => write!(f, "{vertex} into {sheets}"),
            Change::FaceFlipped { face } => write!(f, "{face}"),
            Change::VertexDropped { vertex, position } => write!(f, "{vertex} at {}", p(position)),
        }
    }
}

/// One step's changes: the full count and the first examples, in input order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepReport {
    /// How many elements the step changed (see [`Step::counts`]).
    pub count: usize,
    /// The first [`crate::RepairOptions::max_examples`] changes.
    pub examples: Vec<Change>,
    /// The step was not run: the faces are stacked too densely to search them within the
    /// pair budget the input checker shares (its elements are left as they were).
    pub undecided: bool,
}

/// What [`crate::repair`] did, step by step.
///
/// ```
/// use envelope_mesh::TriangleSoup;
/// use envelope_repair::{repair, RepairOptions, Step};
/// // One triangle written twice, and a vertex no face uses.
/// let soup = TriangleSoup::from_raw(
///     &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [5.0, 5.0, 5.0]],
///     &[[0, 1, 2], [1, 2, 0]],
/// );
/// let (repaired, report) = repair(&soup, &RepairOptions::default())?;
/// assert_eq!((repaired.num_vertices(), repaired.num_faces()), (3, 1));
/// assert_eq!(report.step(Step::DuplicateFaces).count, 1);
/// assert_eq!(report.step(Step::UnreferencedVertices).count, 1);
/// assert_eq!(report.to_json()["steps"][1]["step"], "duplicate_faces");
/// # Ok::<(), envelope_repair::RepairError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RepairReport {
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Triangles of the input.
    pub input_faces: usize,
    /// Vertices of the output.
    pub output_vertices: usize,
    /// Triangles of the output.
    pub output_faces: usize,
    steps: BTreeMap<Step, StepReport>,
    max_examples: usize,
}

impl RepairReport {
    pub(crate) fn new(input_vertices: usize, input_faces: usize, max_examples: usize) -> Self {
        RepairReport {
            input_vertices,
            input_faces,
            output_vertices: input_vertices,
            output_faces: input_faces,
            steps: Step::ALL
                .iter()
                .map(|&s| (s, StepReport::default()))
                .collect(),
            max_examples,
        }
    }

    /// Counts `n` changed elements of `step`, described by `change`.
    pub(crate) fn record(&mut self, step: Step, n: usize, change: impl FnOnce() -> Change) {
        let max = self.max_examples;
        let s = self.steps.entry(step).or_default();
        s.count += n;
        if s.examples.len() < max {
            s.examples.push(change());
        }
    }

    /// Marks `step` as not run (see [`StepReport::undecided`]).
    pub(crate) fn undecided(&mut self, step: Step) {
        self.steps.entry(step).or_default().undecided = true;
    }

    /// One step's changes.
    #[must_use]
    pub fn step(&self, step: Step) -> &StepReport {
        &self.steps[&step]
    }

    /// Every step with its changes, in the order they ran.
    pub fn steps(&self) -> impl Iterator<Item = (Step, &StepReport)> + '_ {
        self.steps.iter().map(|(s, r)| (*s, r))
    }

    /// Whether any step changed anything.
    #[must_use]
    pub fn changed(&self) -> bool {
        self.steps.values().any(|s| s.count > 0)
    }

    /// The report as one JSON object with stable field names: `input` and `output`
    /// (`vertices`, `faces`), `changed`, `indices` (what the indices name), and `steps`, an
    /// array in run order of `{ "step", "counts", "count", "undecided", "examples" }`.
    #[must_use]
    pub fn to_json(&self) -> Value {
        json!({
            "input": { "vertices": self.input_vertices, "faces": self.input_faces },
            "output": { "vertices": self.output_vertices, "faces": self.output_faces },
            "changed": self.changed(),
            "indices": "vertices and faces of the input as read, from 0",
            "steps": self.steps().map(|(step, r)| json!({
                "step": step.key(),
                "counts": step.counts(),
                "count": r.count,
                "undecided": r.undecided,
                "examples": r.examples.iter().map(Change::to_json).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        })
    }
}

impl fmt::Display for RepairReport {
    /// One line of counts, then one line per step that changed something, with examples.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "repair: {} -> {} vertices, {} -> {} faces",
            self.input_vertices, self.output_vertices, self.input_faces, self.output_faces
        )?;
        for (step, r) in self.steps() {
            if r.undecided {
                write!(
                    f,
                    "\n  {:<22} {:>8}  undecided: faces stacked too densely to search",
                    step.key(),
                    "?"
                )?;
            }
            if r.count == 0 {
                continue;
            }
            let ex: Vec<String> = r.examples.iter().map(ToString::to_string).collect();
            let more = if r.count > ex.len() { ", ..." } else { "" };
            write!(
                f,
                "\n  {:<22} {:>8}  {}: {}{more}",
                step.key(),
                r.count,
                step.counts(),
                ex.join(", ")
            )?;
        }
        Ok(())
    }
}
