#![doc = include_str!("../../../README.md")]
//!
//! # The front door
//!
//! * [`Mesh`], [`load`], [`save`]: a triangle mesh and its files (OBJ, OFF, PLY, STL), with
//!   per-corner [`Attributes`] (texture coordinates, normals, colours) that every command
//!   carries to its output ([`carry_attributes`], [`seam_vertices`]).
//! * [`Epsilon`]: the tolerance, absolute or a part of the bounding-box diagonal.
//! * [`Simplifier`]: simplification within epsilon, certified ([`Simplified`]).
//! * [`Lod`]: levels of detail with nested vertex sets and switching distances.
//! * [`verify`]: the certificate of any simplifier's output; [`check`]: is a mesh acceptable
//!   input. [`verify_with_map`], [`error_map`], [`save_error_map`]: the certified bounds per
//!   face and vertex, as a coloured PLY.
//! * [`repair`]: repair that never moves the surface ([`Repaired`], [`RepairReport`]).
//! * [`Genus`]: fill holes and tunnels smaller than alpha (El-Sana and Varshney 1997).
//! * [`Scene`], [`load_scene`], [`save_scene`]: glTF 2.0 scenes (`.gltf`, `.glb`);
//!   [`SceneSimplifier`] and [`SceneLod`] simplify every triangle primitive, certified after
//!   rounding to f32 ([`EpsilonScope`]: per primitive or for the whole scene).
//! * [`batch`]: many meshes from a JSON Lines manifest, resumable, in shards.
//! * [`Error`]: one error type; [`Event`]: what a progress callback is told.
//!
//! The defaults of every setting are in [`defaults`], shared with the command line. The
//! engine's crates, for people who write their own policies, are under [`advanced`].
#![forbid(unsafe_code)]

mod attributes;
pub mod batch;
mod epsilon;
mod error;
mod error_map;
mod files;
mod genus;
mod lod;
mod mesh;
mod oracle;
mod progress;
mod repair;
mod scene;
mod scene_lod;
mod simplified;
mod simplifier;
mod threads;

pub use envelope_check::CheckReport;
pub use envelope_genus::{GenusReport, TessellationSource};
pub use envelope_global::Method;
pub use envelope_mesh::{Attributes, Wedges};
pub use envelope_offset::EnvelopeMethod;
pub use envelope_repair::{RepairError, RepairReport, Step as RepairStep};
pub use envelope_simplify::{
    Correspondence, HoleFilling, Level, LodRule, Placement, Screen, SimplifyReport, VerifyReport,
};
pub use envelope_verify::{Certificate, ErrorMap, FaceBound, OneSided, Verdict, Witness};

pub use attributes::{carry_attributes, seam_vertices};
pub use envelope_gltf::{GltfError, Scene};
pub use epsilon::Epsilon;
pub use error::Error;
pub use error_map::{error_map, save_error_map, verify_with_map};
pub use files::{load, load_with_report, save};
pub use genus::Genus;
pub use lod::Lod;
pub use mesh::{Mesh, MeshError};
pub use oracle::{check, verify};
pub use progress::{Event, Stage};
pub use repair::{Repaired, repair};
pub use scene::{
    EpsilonScope, PrimitiveReport, SceneSimplifier, SimplifiedScene, load_scene, save_scene,
};
pub use scene_lod::{LevelReport, PrimitiveLevels, SceneLevels, SceneLod};
pub use simplified::Simplified;
pub use simplifier::Simplifier;

/// The default of every setting, defined once: the builders here and the command line take
/// them from this module.
pub mod defaults {
    use super::{EnvelopeMethod, EpsilonScope, HoleFilling, Method, Placement};

    /// A scene's epsilon is relative to each primitive's own diagonal.
    pub const EPSILON_SCOPE: EpsilonScope = EpsilonScope::Primitive;

    /// The local algorithm (5.2).
    pub const METHOD: Method = Method::Local;
    /// The analytical offsets (4.1), grown numerically (4.2) where they fall short.
    pub const ENVELOPE_METHOD: EnvelopeMethod = EnvelopeMethod::Auto;
    /// Input vertices, then moved ones: every collapse position when the subset run left few
    /// vertices, the cheapest only otherwise.
    pub const PLACEMENT: Placement = Placement::Auto;
    /// Vertices per border-tube ring (6.2).
    pub const TUBE_SEGMENTS: u32 = 8;
    /// The valid tube rings (the envelope builder's range).
    pub const TUBE_SEGMENTS_RANGE: std::ops::RangeInclusive<u32> = envelope_offset::TUBE_SEGMENTS;
    /// Every output is certified.
    pub const CERTIFY: bool = true;
    /// The tolerance phase runs after the simplification (where the epsilon is uniform).
    pub const TOLERANCE_PHASE: bool = true;
    /// The paper's bunny epsilons (Table 1, Figure 11), for level-of-detail chains.
    pub const LOD_EPSILONS: &str = "1/64%,1/32%,1/16%,1/8%,1/4%,1/2%,1%";
    /// The genus reduction's sharp-edge angle between face normals, in degrees (the paper's).
    pub const GENUS_BETA_DEGREES: f64 = 70.0;

    /// The paper's greedy hole filling, with a look-ahead for forced triangles.
    #[must_use]
    pub fn hole_filling() -> HoleFilling {
        HoleFilling::default()
    }
}

/// The engine's crates, for people who write their own policies (queue orders, hole fillers,
/// filters, simplification steps) or need a single stage (envelopes alone, the exact
/// predicates). Their interfaces change more often than the front door's.
pub mod advanced {
    pub use envelope_check as check;
    pub use envelope_genus as genus;
    pub use envelope_global as global;
    pub use envelope_gltf as gltf;
    pub use envelope_io as io;
    pub use envelope_mesh as mesh;
    pub use envelope_offset as offset;
    pub use envelope_predicates as predicates;
    pub use envelope_prism as prism;
    pub use envelope_render as render;
    pub use envelope_repair as repair;
    pub use envelope_simplify as simplify;
    pub use envelope_verify as verify;

    pub use crate::threads::run as in_pool;
}
