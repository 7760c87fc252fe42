//! [`Attributes`]: per-corner (wedge) texture coordinates, normals, colours and a scalar
//! quality beside a [`crate::TriangleSoup`].
//!
//! Each attribute is stored the way OBJ stores it: a table of distinct values and, per face,
//! the value index of each of its three corners ([`Wedges`]). A vertex whose faces give it
//! different values of an attribute lies on a *seam* of that attribute (a texture chart's
//! edge, a sharp normal crease, a colour boundary); formats that store one value per vertex
//! (PLY, glTF) split such vertices, and welding them back by position keeps the seam in the
//! corner indices. Values are plain f64: readers convert `f32`, `u8` and normalized integers
//! exactly (colours in `0..=1`).

/// One per-corner attribute: `values[corners[f][k] as usize]` is the value at corner `k` of
/// face `f`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Wedges<const N: usize> {
    /// The distinct values (not necessarily distinct: readers keep the file's table).
    pub values: Vec<[f64; N]>,
    /// Per face, the value index of each corner, in the face's corner order.
    pub corners: Vec<[u32; 3]>,
}

impl<const N: usize> Wedges<N> {
    /// The value at corner `k` of face `f`.
    #[must_use]
    pub fn value(&self, f: usize, k: usize) -> [f64; N] {
        self.values[self.corners[f][k] as usize]
    }

    /// Whether there is a corner list per face of a soup of `faces` faces, every index is in
    /// range and every value is finite.
    #[must_use]
    pub fn is_valid_for(&self, faces: usize) -> bool {
        let n = self.values.len();
        self.corners.len() == faces
            && self.corners.iter().flatten().all(|&i| (i as usize) < n)
            && self.values.iter().flatten().all(|x| x.is_finite())
    }
}

/// The attributes of a mesh's corners; each is optional (absent in the file).
///
/// ```
/// use envelope_mesh::{Attributes, Wedges};
/// let uv = Wedges { values: vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]], corners: vec![[0, 1, 2]] };
/// let a = Attributes { texcoords: Some(uv), ..Attributes::default() };
/// assert!(!a.is_empty() && a.is_valid_for(1) && !a.is_valid_for(2));
/// assert_eq!(a.texcoords.as_ref().unwrap().value(0, 1), [1.0, 0.0]);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attributes {
    /// Texture coordinates (OBJ `vt`, PLY `u v`/`s t`/`texture_u texture_v`, glTF
    /// `TEXCOORD_0`).
    pub texcoords: Option<Wedges<2>>,
    /// Normals (OBJ `vn`, PLY `nx ny nz`, glTF `NORMAL`), not necessarily of unit length.
    pub normals: Option<Wedges<3>>,
    /// Colours as RGBA in `0..=1` (PLY `red green blue [alpha]`, glTF `COLOR_0`; alpha 1
    /// where the file has none).
    pub colors: Option<Wedges<4>>,
    /// A per-vertex scalar (PLY `quality`), such as the certified distance bound of an error
    /// map (`envelope verify --map`). It is derived from the mesh it describes, so commands
    /// that change the surface drop it rather than carry it.
    pub quality: Option<Wedges<1>>,
}

impl Attributes {
    /// Whether no attribute is present.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.texcoords.is_none()
            && self.normals.is_none()
            && self.colors.is_none()
            && self.quality.is_none()
    }

    /// Whether every present attribute [`Wedges::is_valid_for`] a soup of `faces` faces.
    #[must_use]
    pub fn is_valid_for(&self, faces: usize) -> bool {
        self.texcoords
            .as_ref()
            .is_none_or(|w| w.is_valid_for(faces))
            && self.normals.as_ref().is_none_or(|w| w.is_valid_for(faces))
            && self.colors.as_ref().is_none_or(|w| w.is_valid_for(faces))
            && self.quality.as_ref().is_none_or(|w| w.is_valid_for(faces))
    }
}
