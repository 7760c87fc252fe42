//! Typed indices. No bare `usize` crosses an API: a vertex is a [`VertexId`], a face a [`FaceId`].

use std::fmt;

macro_rules! typed_id {
    ($(#[$doc:meta])* $name:ident, $prefix:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name(pub u32);

        impl $name {
            /// A sentinel that never names a live element.
            pub const INVALID: Self = Self(u32::MAX);

            /// The index as `usize`, for indexing arrays.
            #[inline]
            #[must_use]
            pub const fn index(self) -> usize {
                self.0 as usize
            }

            /// The id of array index `i`.
            ///
            /// # Panics
            /// If `i` does not fit in `u32` (readers reject such inputs before they get here).
            #[inline]
            #[must_use]
            pub fn from_index(i: usize) -> Self {
                Self(u32::try_from(i).expect(concat!(stringify!($name), " overflows u32")))
            }

            /// Whether this is not [`Self::INVALID`].
            #[inline]
            #[must_use]
            pub const fn is_valid(self) -> bool {
                self.0 != u32::MAX
            }
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                if self.is_valid() {
                    write!(f, concat!($prefix, "{}"), self.0)
                } else {
                    f.write_str(concat!($prefix, "-"))
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Debug::fmt(self, f)
            }
        }
    };
}

typed_id!(
    /// A vertex: index into a mesh's position array.
    VertexId,
    "v"
);
typed_id!(
    /// A triangle: index into a mesh's face array.
    FaceId,
    "f"
);
typed_id!(
    /// A directed half of an edge in a [`crate::HalfEdgeMesh`].
    HalfedgeId,
    "h"
);
typed_id!(
    /// An undirected edge (a pair of opposite half-edges).
    EdgeId,
    "e"
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_and_sentinel() {
        assert_eq!(VertexId(7).to_string(), "v7");
        assert_eq!(FaceId::INVALID.to_string(), "f-");
        assert!(!HalfedgeId::INVALID.is_valid());
        assert_eq!(EdgeId::from_index(3).index(), 3);
    }
}
