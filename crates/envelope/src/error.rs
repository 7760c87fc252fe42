//! The one error type of the front door.

use std::path::PathBuf;

use envelope_genus::GenusError;
use envelope_gltf::GltfError;
use envelope_io::{ReadError, WriteError};
use envelope_repair::RepairError;
use envelope_simplify::DriverError;

use crate::{MeshError, Simplified};

/// Why a call produced no (trustworthy) result. Messages name the file, element or argument
/// as the user wrote it; the command line prints them as they are.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// A mesh file could not be read (the message names the file and the line or element).
    #[error(transparent)]
    Read(#[from] ReadError),
    /// A mesh file could not be written (nothing was put in its place).
    #[error(transparent)]
    Write(#[from] WriteError),
    /// `save` was given a path whose extension names no mesh format.
    #[error("{}: unknown mesh format (expected .obj, .off, .ply or .stl)", .0.display())]
    UnknownFormat(PathBuf),
    /// `Mesh::new` was given a non-finite coordinate or an index out of range.
    #[error("invalid mesh: {0}")]
    InvalidMesh(#[from] MeshError),
    /// An epsilon (or alpha) that is not a positive finite length, or that cannot be
    /// parsed.
    #[error("invalid epsilon: {0}")]
    InvalidEpsilon(String),
    /// An argument out of its range (the message names it).
    #[error("invalid argument: {0}")]
    InvalidArgument(String),
    /// The simplifier refused its input or could not prove its envelopes (no output is made
    /// from unproved envelopes).
    #[error(transparent)]
    Simplify(DriverError),
    /// The genus reduction refused its input.
    #[error(transparent)]
    Genus(#[from] GenusError),
    /// The repair refused: the named element cannot be repaired without moving the surface.
    #[error("cannot repair without moving the surface: {0}")]
    Repair(#[from] RepairError),
    /// The progress callback asked to stop.
    #[error("cancelled")]
    Cancelled,
    /// The output was made but its certificate found a violation: it is handed back for
    /// inspection and must not be used as a simplification within epsilon.
    #[error("the output FAILED its certificate ({})", .0.violations().join(", "))]
    CertificateViolated(Box<Simplified>),
    /// The thread pool could not be built.
    #[error("threads: {0}")]
    Threads(String),
    /// A batch manifest line that cannot be run.
    #[error(transparent)]
    Manifest(#[from] ManifestError),
    /// A glTF scene could not be read or written (the message names the file's element).
    #[error("{}{source}", prefix(.path))]
    Gltf {
        /// The file (empty when the scene was in memory).
        path: PathBuf,
        /// What is wrong, and where.
        source: GltfError,
    },
    /// A primitive of a scene could not be simplified: the primitive and why.
    #[error("{label}: {source}")]
    Primitive {
        /// `meshes[m].primitives[p]` and the mesh's name.
        label: String,
        /// Why.
        source: Box<Error>,
    },
    /// A file or folder other than a mesh could not be read or written.
    #[error("{}: {source}", .path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
}

fn prefix(path: &std::path::Path) -> String {
    if path.as_os_str().is_empty() {
        String::new()
    } else {
        format!("{}: ", path.display())
    }
}

impl Error {
    pub(crate) fn io(path: &std::path::Path, e: &std::io::Error) -> Error {
        Error::Io {
            path: path.to_path_buf(),
            source: std::io::Error::new(e.kind(), e.to_string()),
        }
    }
}

impl From<GltfError> for Error {
    /// A scene in memory (no file to name).
    fn from(source: GltfError) -> Self {
        Error::Gltf {
            path: PathBuf::new(),
            source,
        }
    }
}

impl From<DriverError> for Error {
    fn from(e: DriverError) -> Self {
        match e {
            DriverError::Cancelled => Error::Cancelled,
            e => Error::Simplify(e),
        }
    }
}

/// A batch manifest line that cannot be run, named by its line (from 1; 0 for the whole
/// file) and key (`envelope::batch`).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}: line {line}: {message}", .manifest.display())]
pub struct ManifestError {
    /// The manifest file.
    pub manifest: PathBuf,
    /// The line, from 1.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}
