//! Derived exact predicates, generic over the [`Kernel`](crate::Kernel).
//!
//! The crate root re-exports each of these instantiated with the default
//! [`Filtered`](crate::Filtered) kernel; call these to choose a kernel, e.g.
//! `generic::triangles_intersect::<Checked<Filtered, Exact>>(t1, t2)`.

mod basic;
mod distance;
mod intersect;
mod surface;

pub use basic::{
    TriangleLocation, collinear, point_in_triangle, point_on_segment,
    point_strictly_inside_segment, segments_intersect,
};
pub use distance::{
    cmp_point_segment, cmp_point_triangle, cmp_segment_segment, cmp_segment_triangle,
    cmp_triangle_triangle,
};
pub(crate) use intersect::polyline_crossings_prefiltered;
pub use intersect::{
    SegmentTriangle, Shared, adjacent_triangles_intersect, polyline_crossings, segment_triangle,
    strictly_one_side_of_plane, triangles_intersect, triangles_overlap_with_area,
};
pub use surface::{Containment, point_in_surface};
