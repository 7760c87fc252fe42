//! Mesh repair that never moves the surface.
//!
//! Every step leaves the point set of the surface (the union of its closed triangles)
//! exactly as it was, so a simplification within epsilon of the repaired mesh is within
//! epsilon of the original, and a certificate against the repaired mesh is one against the
//! original file. What cannot be repaired that way is refused with the element named
//! ([`RepairError`]). No face is dropped but an exact duplicate or a zero-area face proved to
//! lie on other faces; no vertex but one no face uses.
//!
//! A crate of its own rather than a module of a neighbour: `envelope-check` is the read-only
//! oracle that decides whether input is acceptable (and judges this crate's output), and
//! `envelope-mesh` makes no geometric decision (an architecture invariant), while three of
//! these steps are geometric.
//!
//! The steps run in this fixed order ([`Step::ALL`]), each its own module, each recording
//! into the [`RepairReport`]:
//!
//! 1. **weld**: referenced vertices at bitwise-equal positions become one (the corner moves
//!    to a vertex at the same point);
//! 2. **duplicate faces**: faces on the same three vertices after the weld, in either
//!    orientation, are dropped but the first (the same closed triangle stays);
//! 3. **degenerate faces**: a zero-area face (exactly collinear corners, or a repeated
//!    vertex) is dropped when each piece of its segment is proved, exactly, to lie in one
//!    closed non-degenerate face; otherwise the repair is refused naming it;
//! 4. **T-junctions**: a face is split at each border vertex lying exactly in the open
//!    interior of one of its border edges (the pieces cover the same triangle);
//! 5. and 6. **non-manifold edges and vertices**: each fan of faces around a vertex gets its
//!    own vertex (copies at the same position), which also separates the faces of an edge
//!    with more than two;
//! 7. **orientation**: each component's faces are flipped to agree (fewer flips chosen); a
//!    non-orientable component (a Möbius band) refuses the repair naming a face;
//! 8. **unreferenced vertices** are dropped and the vertices renumbered in order.
//!
//! The order matters: the weld makes duplicates and zero-area faces visible by index;
//! zero-area faces are gone before borders are looked at (a sliver filling a crack hides
//! the T-junction); the T-junction splits close cracks before fans are counted; orientation
//! needs at most two faces per edge. Geometric decisions are exact predicates of
//! `envelope-predicates`, and each geometric search goes through a bounding-volume
//! hierarchy, so time and memory stay O(n log n) plus the exact tests near each element;
//! faces stacked so densely that those tests would take quadratic time leave steps 3 and 4
//! undecided (the `density` module).
//!
//! What repair does not touch, because it cannot without moving the surface: faces that
//! cross or touch away from shared vertices (sheets split at a non-manifold vertex or edge
//! still touch there), vertices inside edges with two faces, coincident faces that are not
//! duplicates. `envelope check` still reports them after the repair.
//!
//! Indices in reports and errors are the input's, from 0 (see [`report`]).
//!
//! Attributes (normals, texture coordinates, colours) are corner data beside the position
//! index, which this crate does not see: the weld keys on positions alone, and
//! [`repair_traced`] gives each output face's input face, from which `envelope::repair`
//! carries a face's corner values (a flip permuting them, a T-junction piece interpolating
//! at the inserted vertex along its edge); an attribute seam stays a seam in the corners.
//!
//! ```
//! use envelope_mesh::generate;
//! use envelope_repair::{repair, RepairOptions, Step};
//! let mut soup = generate::icosphere(1, 1.0);
//! soup.faces[3].swap(1, 2); // one face flipped
//! let (repaired, report) = repair(&soup, &RepairOptions::default())?;
//! assert_eq!(report.step(Step::Orientation).count, 1);
//! assert_eq!(repaired, generate::icosphere(1, 1.0));
//! # Ok::<(), envelope_repair::RepairError>(())
//! ```
#![forbid(unsafe_code)]

mod degenerate;
mod density;
mod duplicates;
mod error;
mod orient;
pub mod report;
mod sheets;
mod tjunction;
mod unreferenced;
mod weld;
mod work;

use envelope_mesh::{FaceId, TriangleSoup, VertexId};

pub use error::RepairError;
pub use report::{Change, RepairReport, Step, StepReport};

/// How much [`repair`] reports.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RepairOptions {
    /// How many changes to keep as examples per step (the counts are always complete).
    pub max_examples: usize,
}

impl Default for RepairOptions {
    fn default() -> Self {
        RepairOptions { max_examples: 5 }
    }
}

/// Repairs `soup` without moving its surface: the steps of the crate docs, in order. The
/// output's vertices are input vertices (the kept one of each weld group, in input order),
/// then the copies made by splitting non-manifold vertices; its faces come in input order,
/// the pieces of a split face in its place.
///
/// ```
/// use envelope_mesh::{generate, FaceId};
/// use envelope_repair::{repair, RepairError, RepairOptions, Step};
/// // Two triangles sharing only a vertex: one vertex per sheet afterwards.
/// let (out, report) = repair(&generate::bow_tie(), &RepairOptions::default())?;
/// assert_eq!(out.num_vertices(), 6);
/// assert_eq!(report.step(Step::NonManifoldVertices).count, 1);
/// // A Möbius band has no consistent orientation: refused, named.
/// let err = repair(&generate::moebius_strip(5), &RepairOptions::default()).unwrap_err();
/// assert!(matches!(err, RepairError::NonOrientable { first: FaceId(0), .. }));
/// # Ok::<(), RepairError>(())
/// ```
///
/// # Errors
/// A [`RepairError`] naming the input element: a coordinate that is not finite, an index
/// out of range, a zero-area face whose points are not proved to lie on other faces, a
/// non-orientable component.
pub fn repair(
    soup: &TriangleSoup,
    options: &RepairOptions,
) -> Result<(TriangleSoup, RepairReport), RepairError> {
    repair_traced(soup, options).map(|(out, report, _)| (out, report))
}

/// [`repair`], with the input face each output face comes from (a kept, flipped or split
/// face's own; the faces keep their corners' positions), so that per-corner attributes can
/// follow their faces.
///
/// ```
/// use envelope_mesh::{generate, FaceId};
/// use envelope_repair::{repair_traced, RepairOptions};
/// let mut soup = generate::icosphere(1, 1.0);
/// soup.faces.push(soup.faces[0]); // a duplicate, dropped
/// let (repaired, _, origin) = repair_traced(&soup, &RepairOptions::default())?;
/// assert_eq!(origin.len(), repaired.num_faces());
/// assert_eq!(origin[5], FaceId(5));
/// # Ok::<(), envelope_repair::RepairError>(())
/// ```
///
/// # Errors
/// As [`repair`].
pub fn repair_traced(
    soup: &TriangleSoup,
    options: &RepairOptions,
) -> Result<(TriangleSoup, RepairReport, Vec<FaceId>), RepairError> {
    validate(soup)?;
    let mut report = RepairReport::new(soup.num_vertices(), soup.num_faces(), options.max_examples);
    let mut work = work::Work::new(soup);
    weld::weld(&mut work, &mut report);
    duplicates::drop_duplicates(&mut work, &mut report);
    if density::too_dense(&work) {
        report.undecided(Step::DegenerateFaces);
        report.undecided(Step::TJunctions);
    } else {
        degenerate::drop_covered(&mut work, &mut report)?;
        tjunction::split_t_junctions(&mut work, &mut report);
    }
    sheets::split_sheets(&mut work, &mut report);
    orient::orient(&mut work, &mut report)?;
    unreferenced::drop_unreferenced(&mut work, &mut report);
    report.output_vertices = work.positions.len();
    report.output_faces = work.faces.len();
    let origin = work.face_origin.clone();
    let out = work.into_soup();
    #[cfg(any(test, fuzzing))]
    sanity_check(&out, &report);
    Ok((out, report, origin))
}

/// The boundary: finite coordinates and indices in range (a `Mesh` or a reader guarantees
/// both; a hand-built soup may not).
fn validate(soup: &TriangleSoup) -> Result<(), RepairError> {
    if let Some(v) = soup.positions.iter().position(|p| !p.is_finite()) {
        return Err(RepairError::NonFiniteCoordinate {
            vertex: VertexId::from_index(v),
        });
    }
    if let Some(f) = soup
        .faces
        .iter()
        .position(|t| t.iter().any(|v| v.index() >= soup.num_vertices()))
    {
        return Err(RepairError::IndexOutOfRange {
            face: FaceId::from_index(f),
            vertices: soup.num_vertices(),
        });
    }
    Ok(())
}

/// The output's invariants: three distinct corners per face (unless the zero-area step was
/// undecided), every vertex used, every edge with at most two faces running it in opposite
/// directions, one fan per vertex.
#[cfg(any(test, fuzzing))]
pub fn sanity_check(soup: &TriangleSoup, report: &RepairReport) {
    use envelope_mesh::{analyze, degeneracy};
    let t = analyze(soup);
    assert!(
        t.excluded_faces.is_empty() || report.step(Step::DegenerateFaces).undecided,
        "repeated corners: {:?}",
        t.excluded_faces
    );
    assert!(
        t.unreferenced_vertices.is_empty(),
        "unreferenced: {:?}",
        t.unreferenced_vertices
    );
    assert!(
        t.manifold,
        "not manifold: {:?}",
        degeneracy::edge_findings(soup)
    );
    assert!(
        t.consistently_oriented,
        "{:?}",
        degeneracy::inconsistent_orientations(soup)
    );
}

#[cfg(test)]
mod tests;
