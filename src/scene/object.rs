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

    /// Cuts a piece taller than the room, or reaching above its `ceiling`, to end at the ceiling:
    /// a floor piece then stands on the floor, a hanging lamp hangs from the ceiling. Whether it
    /// was cut (a piece under the ceiling is left as it is).
    pub fn cut_to_ceiling(&mut self, ceiling: f64) -> bool {
        if self.size[2] <= ceiling && self.center[2] + self.size[2] * 0.5 <= ceiling + 1e-9 {
            return false;
        }
        self.size[2] = self.size[2].min(ceiling).max(0.02);
        self.center[2] = if self.category.is_hanging() { ceiling - self.size[2] * 0.5 } else { self.size[2] * 0.5 };
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_piece_taller_than_the_room_is_cut_to_the_ceiling_standing_or_hanging() {
        let piece = |category, height: f64, z: f64| Object {
            id: "o0".into(),
            category,
            center: [1.0, 1.0, z],
            size: [1.0, 0.6, height],
            yaw: 0.0,
        };
        let mut wardrobe = piece(Category::Wardrobe, 2.4, 1.2);
        assert!(wardrobe.cut_to_ceiling(2.3));
        assert_eq!((wardrobe.size[2], wardrobe.center[2]), (2.3, 1.15));
        let mut lamp = piece(Category::PendantLamp, 0.5, 2.5);
        assert!(lamp.cut_to_ceiling(2.3));
        assert_eq!((lamp.size[2], lamp.center[2]), (0.5, 2.05));
        let mut long_lamp = piece(Category::PendantLamp, 2.5, 1.05);
        assert!(long_lamp.cut_to_ceiling(2.3));
        assert_eq!((long_lamp.size[2], long_lamp.center[2]), (2.3, 1.15));
        // Under the ceiling, or touching it: as it was.
        for (mut o, z) in [(piece(Category::Wardrobe, 2.0, 1.0), 1.0), (piece(Category::PendantLamp, 0.5, 2.05), 2.05)]
        {
            assert!(!o.cut_to_ceiling(2.3));
            assert_eq!(o.center[2], z);
        }
    }
}
