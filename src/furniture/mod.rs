//! Furniture knowledge shared by every part of shade-sim: real dimensions per category, the
//! shape templates (parts fitted to a bounding box, support surfaces) and the room's walls.
//!
//! DESIGN.md puts the templates in `sim`; they live here, in the base, because the dataset
//! (placing people on seats), the physics worlds, the MJCF export and E_pen all need the same
//! shapes, and one definition must serve them all. This module does no physics and no IO.

mod catalog;
mod template;
mod walls;

pub use catalog::{
    CatalogItem, REAL_SIZE_MARGIN, SIZE_JITTER, beyond_real, catalog_items, drawn_range, height_range, size_range,
};
pub use template::{Part, PartRole, Surface, Template, template, template_of};
pub use walls::{WALL_THICKNESS, wall_boxes};
