//! Repair that never moves the surface, and what the input checker says afterwards.

use envelope_check::{CheckReport, DegeneracyClass};
use envelope_repair::{RepairOptions, RepairReport};
use serde_json::{Value, json};

use crate::{Error, Mesh};

/// A repaired mesh, what the repair changed, and the input check of the result.
///
/// The repaired mesh has exactly the original's point set (see [`repair`]), so certificates
/// against it hold against the original; its topology (components, border loops, genus) is
/// its own, measured after the repair.
#[derive(Clone, Debug)]
pub struct Repaired {
    mesh: Mesh,
    report: RepairReport,
    check: CheckReport,
}

impl Repaired {
    /// The repaired mesh.
    #[must_use]
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The repaired mesh, owned.
    #[must_use]
    pub fn into_mesh(self) -> Mesh {
        self.mesh
    }

    /// Every change, step by step, named by the input's indices.
    #[must_use]
    pub fn report(&self) -> &RepairReport {
        &self.report
    }

    /// [`crate::check`] of the repaired mesh.
    #[must_use]
    pub fn check(&self) -> &CheckReport {
        &self.check
    }

    /// Whether the repaired mesh is acceptable input for the simplifiers.
    #[must_use]
    pub fn acceptable(&self) -> bool {
        self.check.acceptable()
    }

    /// The error classes the checker still finds (what repair cannot change without moving
    /// the surface, such as intersecting faces), in report order.
    #[must_use]
    pub fn left(&self) -> Vec<DegeneracyClass> {
        self.check.errors().collect()
    }

    /// The repair report's JSON ([`RepairReport::to_json`]) with `acceptable` and `left`
    /// (`{ "class", "count", "undecided" }` for each class still found).
    #[must_use]
    pub fn to_json(&self) -> Value {
        let mut v = self.report.to_json();
        v["acceptable"] = self.acceptable().into();
        v["left"] = self
            .left()
            .into_iter()
            .map(|c| {
                let f = self.check.finding(c);
                json!({ "class": c.key(), "count": f.count, "undecided": f.undecided })
            })
            .collect::<Vec<_>>()
            .into();
        v
    }
}

/// Repairs `mesh` without moving its surface (`envelope_repair`): welds bitwise-equal
/// vertices, drops exact duplicate faces, zero-area faces proved to lie on others and
/// unreferenced vertices, splits faces at T-junctions and non-manifold vertices and edges
/// into manifold sheets, and orients each component consistently. Then checks the result.
/// Per-corner attributes follow their faces: a kept or flipped face keeps its corners'
/// values, a T-junction piece's new corner gets the value interpolated along its edge.
///
/// ```
/// // A square whose second triangle is written with a copy of vertex 2 and the wrong winding.
/// let mesh = envelope::Mesh::new(
///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
///     vec![[0, 1, 2], [0, 3, 4]],
/// )?;
/// assert!(!envelope::check(&mesh).acceptable());
/// let repaired = envelope::repair(&mesh)?;
/// assert!(repaired.acceptable());
/// assert_eq!(repaired.mesh().num_vertices(), 4);
/// assert_eq!(repaired.report().step(envelope::RepairStep::Orientation).count, 1);
/// # Ok::<(), envelope::Error>(())
/// ```
///
/// # Errors
/// [`Error::Repair`] naming the input element that cannot be repaired without moving the
/// surface: a zero-area face whose points are not proved to lie on other faces, or a
/// non-orientable component.
pub fn repair(mesh: &Mesh) -> Result<Repaired, Error> {
    let (soup, report, origin) =
        envelope_repair::repair_traced(mesh.soup(), &RepairOptions::default())?;
    let attributes = crate::attributes::carry_through_repair(mesh, &soup, &origin);
    let mesh = Mesh::from_parts(soup, attributes);
    let check = crate::check(&mesh);
    Ok(Repaired {
        mesh,
        report,
        check,
    })
}
