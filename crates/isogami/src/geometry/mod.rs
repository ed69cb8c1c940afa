//! Plane geometry on simple polygons: areas, simplicity, containment, interior overlap and
//! its depth, triangulation.
//!
//! Pure functions on slices of points; tolerances are absolute lengths chosen by the caller
//! from its length scale. Nothing here knows about tilings or mechanisms.

mod depth;
mod polygon;
mod segment;
mod triangulate;

pub use depth::overlap_depth;
pub use polygon::{
    centroid, convex_hull, interiors_overlap, is_simple_problem, point_in_polygon_strict,
    signed_area, SimplicityProblem,
};
pub use segment::{point_segment_distance, segment_distance, segments_properly_cross};
pub use triangulate::triangulate;
