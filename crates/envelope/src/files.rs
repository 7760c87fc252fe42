//! Reading and writing meshes by file extension.

use std::path::Path;

use envelope_io::{Format, ReadReport, read_path_with_attributes, write_path_with_attributes};

use crate::{Error, Mesh};

/// Reads a mesh: OBJ, OFF, PLY (ASCII or binary) or STL (ASCII or binary), by the file's
/// content and extension, with its per-corner [`Attributes`](crate::Attributes) (OBJ `vt`,
/// `vn`; PLY texture coordinates, normals, colours; see
/// [`envelope_io::read_with_attributes`]). Polygons are triangulated without overlaps;
/// anything that could change the surface and cannot be read is refused with its line or
/// element, and so is an attribute reference naming no value.
///
/// # Errors
/// [`Error::Read`], naming the file and the element as written in it.
pub fn load(path: impl AsRef<Path>) -> Result<Mesh, Error> {
    Ok(load_with_report(path)?.0)
}

/// [`load`], with what the reader skipped or repaired on the way (comments, statements that
/// cannot change the surface, welded STL vertices).
///
/// # Errors
/// As [`load`].
pub fn load_with_report(path: impl AsRef<Path>) -> Result<(Mesh, ReadReport), Error> {
    let (soup, attributes, report) = read_path_with_attributes(path)?;
    Ok((Mesh::from_parts(soup, attributes), report))
}

/// Writes a mesh in the format its extension names (`.obj`, `.off`, `.ply`, `.stl`; binary
/// PLY and STL), through a temporary file renamed into place only when complete, with the
/// attributes the format holds (OBJ: texture coordinates and normals; PLY: all three, a seam
/// vertex written once per value combination; OFF, STL: none, see
/// [`Format::dropped_attributes`]).
///
/// # Errors
/// [`Error::UnknownFormat`] for another extension, [`Error::Write`] when writing fails.
pub fn save(mesh: &Mesh, path: impl AsRef<Path>) -> Result<(), Error> {
    let path = path.as_ref();
    let format = Format::from_path(path).ok_or_else(|| Error::UnknownFormat(path.to_path_buf()))?;
    write_path_with_attributes(path, mesh.soup(), mesh.attributes(), format)?;
    Ok(())
}
