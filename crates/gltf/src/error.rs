//! [`GltfError`]: every refusal of the reader and the writer, naming the element.

use std::path::PathBuf;

use envelope_mesh::CoordError;

/// Where in the document an accessor is used: mesh, primitive and attribute (or
/// `"indices"`), all indices from 0 as in the JSON.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Use {
    /// `meshes[mesh]`.
    pub mesh: usize,
    /// `meshes[mesh].primitives[primitive]`.
    pub primitive: usize,
    /// The attribute semantic (`POSITION`, `NORMAL`, ...) or `indices`.
    pub semantic: String,
}

impl std::fmt::Display for Use {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "meshes[{}].primitives[{}] {}",
            self.mesh, self.primitive, self.semantic
        )
    }
}

/// Why a glTF file was refused or could not be written. Each kind names the element: the
/// byte offset in a GLB, the JSON path, the buffer, bufferView or accessor and where it is
/// used.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum GltfError {
    /// The file (or a side buffer) could not be read or written.
    #[error("{}: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// A `.glb` that does not start with `glTF`.
    #[error("not a GLB file: bytes 0..4 are {found:?}, expected \"glTF\"")]
    BadMagic {
        /// The first four bytes.
        found: [u8; 4],
    },
    /// A GLB container version other than 2.
    #[error("GLB version {0} at byte 4: only version 2 is glTF 2.0")]
    BadVersion(u32),
    /// The GLB ends before what its header or a chunk header announces.
    #[error("truncated GLB: byte {offset} needs {needed} more bytes, the file has {available}")]
    Truncated {
        /// Where the missing part begins.
        offset: u64,
        /// Bytes announced from there.
        needed: u64,
        /// Bytes present from there.
        available: u64,
    },
    /// A GLB chunk that breaks the container rules (first chunk not JSON, unaligned length,
    /// two BIN chunks, length field not the file's length).
    #[error("GLB chunk at byte {offset}: {reason}")]
    Chunk {
        /// The chunk header's offset.
        offset: u64,
        /// What is wrong.
        reason: String,
    },
    /// The JSON does not parse, or is not a glTF document (missing required properties,
    /// wrong types).
    #[error("glTF JSON: {0}")]
    Json(String),
    /// The document refers to something that does not exist, or breaks a rule of the
    /// specification the validator checks (the JSON path names it).
    #[error("glTF document: {path}: {reason}")]
    Invalid {
        /// JSON path, as `meshes[0].primitives[1].indices`.
        path: String,
        /// What is wrong.
        reason: String,
    },
    /// `extensionsRequired` names an extension this reader does not implement (Draco and
    /// meshopt compression, quantized geometry, ...).
    #[error("glTF document: extensionsRequired names {0:?}, which this reader does not implement")]
    RequiredExtension(String),
    /// A buffer's `uri` cannot be loaded (not a relative path or a base64 data URI, bad
    /// base64, no file name to resolve it against).
    #[error("buffers[{buffer}]: {reason}")]
    BufferUri {
        /// The buffer.
        buffer: usize,
        /// What is wrong.
        reason: String,
    },
    /// A buffer holds fewer bytes than its `byteLength`.
    #[error("buffers[{buffer}]: byteLength is {declared}, but {actual} bytes are present")]
    BufferTooShort {
        /// The buffer.
        buffer: usize,
        /// Its `byteLength`.
        declared: u64,
        /// Bytes present.
        actual: u64,
    },
    /// A bufferView that reaches past its buffer.
    #[error(
        "bufferViews[{view}]: bytes {offset}..{end} are outside buffers[{buffer}] ({length} bytes)"
    )]
    ViewOutOfBuffer {
        /// The bufferView.
        view: usize,
        /// Its buffer.
        buffer: usize,
        /// Its byteOffset.
        offset: u64,
        /// byteOffset + byteLength.
        end: u64,
        /// The buffer's length.
        length: u64,
    },
    /// An accessor whose elements reach past its bufferView (byte offset of the end of the
    /// last element, relative to the view).
    #[error(
        "accessors[{accessor}] ({used}): its {count} elements end at byte {end} of bufferViews[{view}], which has {length} bytes"
    )]
    AccessorOutOfView {
        /// The accessor.
        accessor: usize,
        /// Where it is used.
        used: Use,
        /// Its bufferView.
        view: usize,
        /// Its element count.
        count: u64,
        /// Where its last element ends.
        end: u64,
        /// The view's length.
        length: u64,
    },
    /// An accessor of a kind the reader does not take for its use (quantized or normalized
    /// positions, float indices, sparse storage, no bufferView).
    #[error("accessors[{accessor}] ({used}): {found}; expected {expected}")]
    AccessorKind {
        /// The accessor.
        accessor: usize,
        /// Where it is used.
        used: Use,
        /// What it is.
        found: String,
        /// What the reader takes.
        expected: &'static str,
    },
    /// Accessors of one primitive with different element counts.
    #[error("accessors[{accessor}] ({used}): {count} elements, but POSITION has {positions}")]
    CountMismatch {
        /// The accessor.
        accessor: usize,
        /// Where it is used.
        used: Use,
        /// Its count.
        count: u64,
        /// The POSITION accessor's count.
        positions: u64,
    },
    /// A primitive without a POSITION attribute.
    #[error("meshes[{mesh}].primitives[{primitive}]: no POSITION attribute")]
    NoPositions {
        /// The mesh.
        mesh: usize,
        /// The primitive.
        primitive: usize,
    },
    /// A triangle primitive whose triangle count is not whole.
    #[error(
        "meshes[{mesh}].primitives[{primitive}]: {corners} corners do not make whole triangles"
    )]
    PartialTriangle {
        /// The mesh.
        mesh: usize,
        /// The primitive.
        primitive: usize,
        /// Indices (or vertices) listed.
        corners: u64,
    },
    /// An index at or past the primitive's vertex count.
    #[error(
        "accessors[{accessor}] ({used}): element {element} is {index}, but there are {vertices} vertices"
    )]
    IndexOutOfRange {
        /// The indices accessor.
        accessor: usize,
        /// Where it is used.
        used: Use,
        /// The element (from 0).
        element: u64,
        /// Its value.
        index: u64,
        /// The primitive's vertex count.
        vertices: u64,
    },
    /// A position outside the exact predicates' range (NaN, infinite, above 2^120, below
    /// 2^-120), or a non-finite attribute value.
    #[error("accessors[{accessor}] ({used}): element {element} component {component}: {reason}")]
    BadValue {
        /// The accessor.
        accessor: usize,
        /// Where it is used.
        used: Use,
        /// The element (vertex), from 0.
        element: u64,
        /// The component (0 = x), from 0.
        component: usize,
        /// What is wrong.
        reason: String,
    },
    /// A coordinate a writer was given that the reader would refuse.
    #[error("meshes[{mesh}].primitives[{primitive}]: vertex {vertex}: {error}")]
    WriteCoordinate {
        /// The mesh.
        mesh: usize,
        /// The primitive.
        primitive: usize,
        /// The vertex.
        vertex: usize,
        /// Why.
        error: CoordError,
    },
    /// A replacement that does not fit (index out of range, attributes not one corner
    /// triple per face, a primitive that is not a triangle primitive).
    #[error("meshes[{mesh}].primitives[{primitive}]: {reason}")]
    BadReplacement {
        /// The mesh.
        mesh: usize,
        /// The primitive.
        primitive: usize,
        /// What is wrong.
        reason: String,
    },
    /// The output would be larger than a GLB (4 GiB) or this machine can address.
    #[error("the output would hold {0} bytes of binary data, more than a GLB can (2^32 - 1)")]
    TooLarge(u64),
    /// An output path whose extension is neither `.glb` nor `.gltf`.
    #[error("{}: a glTF output must end in .glb or .gltf", .0.display())]
    UnknownExtension(PathBuf),
}

impl GltfError {
    pub(crate) fn io(path: &std::path::Path, source: std::io::Error) -> Self {
        GltfError::Io {
            path: path.to_path_buf(),
            source,
        }
    }
}
