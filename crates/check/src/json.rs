//! The JSON form of a [`CheckReport`]. Field names are stable: `vertices`, `faces`, `edges`,
//! `border_loops`, `components`, `euler`, `genus`, `manifold`, `orientable`, `acceptable`,
//! `degeneracies` (an object keyed by [`crate::DegeneracyClass::key`], each
//! `{ "count", "severity", "examples", "undecided" }`).

use serde_json::{Map, Value, json};

use crate::{CheckReport, Element, Severity};

fn element(e: &Element) -> Value {
    match e {
        Element::Vertex { vertex, position } => {
            json!({ "vertex": vertex.0, "position": position.to_array() })
        }
        Element::VertexGroup { vertices, position } => json!({
            "vertices": vertices.iter().map(|v| v.0).collect::<Vec<_>>(),
            "position": position.to_array(),
        }),
        Element::Face {
            face,
            vertices,
            quality,
        } => {
            let mut o = json!({ "face": face.0, "vertices": vertices.map(|v| v.0) });
            if let Some(q) = quality {
                o["quality"] = json!(q);
            }
            o
        }
        Element::FacePair { faces } => json!({ "faces": faces.map(|f| f.0) }),
        Element::Edge { edge, faces } => json!({
            "edge": edge.map(|v| v.0),
            "faces": faces.iter().map(|f| f.0).collect::<Vec<_>>(),
        }),
        Element::VertexOnEdge {
            vertex,
            position,
            edge,
        } => json!({
            "vertex": vertex.0,
            "position": position.to_array(),
            "edge": edge.map(|v| v.0),
        }),
    }
}

/// The report as a JSON value (the CLI adds file and reader fields to it).
pub(crate) fn value(r: &CheckReport) -> Value {
    let mut degeneracies = Map::new();
    for (class, finding) in &r.degeneracies {
        degeneracies.insert(
            class.key().to_owned(),
            json!({
                "count": finding.count,
                "severity": match class.severity() { Severity::Error => "error", Severity::Warning => "warning" },
                "examples": finding.examples.iter().map(element).collect::<Vec<_>>(),
                "undecided": finding.undecided,
            }),
        );
    }
    json!({
        "vertices": r.vertices,
        "faces": r.faces,
        "edges": r.edges,
        "border_loops": r.border_loops,
        "components": r.components,
        "euler": r.euler,
        "genus": r.genus,
        "manifold": r.manifold,
        "orientable": r.orientable,
        "acceptable": r.acceptable(),
        "degeneracies": Value::Object(degeneracies),
    })
}
