//! Geometry core: oriented boxes, exact 2D/3D box intersections and IoU, simple polygons, signed
//! distances and 256 × 256 rasterisation over a room window.
//!
//! Everything is f64 and exact where an exact answer exists (box overlaps are polygon clipping, not
//! sampling). This module knows nothing about humans, physics engines or files.

mod clip;
mod intersection;
mod obox;
mod polygon;
mod polyline;
mod raster;
mod triangulate;

pub use clip::{clip_convex, footprint_intersection_area, signed_area};
pub use intersection::{intersection_volume, iou_3d};
pub use obox::{OBox, facing, wrap_angle, yaw_facing};
pub use polygon::{BoundarySample, Polygon, Wall, point_segment_distance, segments_intersect};
pub use polyline::Polyline;
pub use raster::{Mask, RES, RoomWindow};
