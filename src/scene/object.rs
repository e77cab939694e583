//! A piece of furniture in a scene: category and oriented bounding box.

use super::Category;
use crate::geom::OBox;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// One object: an oriented box (centre, full extents, yaw about +z) and its category.
///
/// Local frame: x = width, y = depth, z = height; the front faces local +y.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Stable identifier, unique within the scene (`"o0"`, ...).
    pub id: String,
    /// Furniture category; must belong to the scene's room type.
    pub category: Category,
    /// Centre of the bounding box in world coordinates (metres).
    pub center: [f64; 3],
    /// Full extents (width, depth, height) in metres, all positive.
    pub size: [f64; 3],
    /// Rotation about +z from local to world, counter-clockwise, radians.
    pub yaw: f64,
}

impl Object {
    /// A piece standing on the floor with its footprint centred at `xy`, unturned.
    pub fn standing(id: impl Into<String>, category: Category, xy: [f64; 2], size: [f64; 3]) -> Object {
        Object { id: id.into(), category, center: [xy[0], xy[1], size[2] * 0.5], size, yaw: 0.0 }
    }

    /// Centre of the bounding box as a vector.
    pub fn center(&self) -> DVec3 {
        DVec3::from(self.center)
    }

    /// The object's oriented bounding box.
    pub fn obox(&self) -> OBox {
        OBox::new(DVec3::from(self.center), DVec3::from(self.size), self.yaw)
    }
}
