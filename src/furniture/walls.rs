//! The room's walls: a box outside each floor-plan edge, as tall as the room.

use crate::geom::OBox;
use crate::scene::Scene;
use glam::{DVec2, DVec3};

/// Wall thickness (m).
pub const WALL_THICKNESS: f64 = 0.1;

/// One wall box per floor-plan edge (index = edge index), standing outside the floor. Walls are
/// exactly as long as their edge: longer ones would poke into the room at inner corners.
pub fn wall_boxes(scene: &Scene) -> Vec<(usize, OBox)> {
    let h = scene.floor_plan.height;
    scene
        .floor_plan
        .polygon()
        .edges()
        .enumerate()
        .filter_map(|(i, (a, b))| {
            let len = a.distance(b);
            if len == 0.0 {
                return None;
            }
            let dir = (b - a) / len;
            let outward = DVec2::new(dir.y, -dir.x);
            let center = (a + b) * 0.5 + outward * (WALL_THICKNESS * 0.5);
            let size = DVec3::new(len, WALL_THICKNESS, h);
            Some((i, OBox::new(center.extend(h * 0.5), size, dir.y.atan2(dir.x))))
        })
        .collect()
}
