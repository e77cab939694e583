//! Where walking and standing people's bodies are, for polishing: over the 256² room window, the
//! lowest and highest point of any bone (capsule) above each pixel in any walking or standing frame.
//! A piece of furniture is in their way where its footprint covers a pixel and its height range
//! meets that pixel's. (The free-space mask of the conditioning holds the feet only; arms and hips
//! reach wider.) It knows nothing of sitters, sleepers or touches: their frames are left out.

use crate::geom::{OBox, RES, RoomWindow, point_segment_distance};
use crate::scene::Scene;
use glam::DVec2;

/// Per pixel, the height range the walking bodies occupy (empty where nobody walks).
#[derive(Debug, Clone)]
pub struct Clearance {
    window: RoomWindow,
    low: Vec<f32>,
    high: Vec<f32>,
}

impl Clearance {
    /// The field of `scene`'s walking and standing humans over `window`.
    pub fn of(scene: &Scene, window: &RoomWindow) -> Clearance {
        let mut c = Clearance {
            window: *window,
            low: vec![f32::INFINITY; RES * RES],
            high: vec![f32::NEG_INFINITY; RES * RES],
        };
        for human in &scene.humans {
            for f in human.free_space_frames() {
                for bone in &human.skeleton.bones {
                    let (a, b) = (human.joint_at(f, bone.a), human.joint_at(f, bone.b));
                    let (lo, hi) = ((a.z.min(b.z) - bone.radius) as f32, (a.z.max(b.z) + bone.radius) as f32);
                    let (a2, b2) = (a.truncate(), b.truncate());
                    let (cols, rows) = window.pixel_ranges(a2.min(b2) - bone.radius, a2.max(b2) + bone.radius);
                    for j in rows {
                        for i in cols.clone() {
                            if point_segment_distance(window.pixel_center(i, j), a2, b2) <= bone.radius {
                                let k = j * RES + i;
                                c.low[k] = c.low[k].min(lo);
                                c.high[k] = c.high[k].max(hi);
                            }
                        }
                    }
                }
            }
        }
        c
    }

    /// The pixels (centres) where `b` is in the bodies' way: inside its footprint, with a height
    /// range meeting theirs.
    pub fn blocked(&self, b: &OBox) -> Vec<DVec2> {
        let (z0, z1) = b.z_range();
        let (lo, hi) = b.footprint_aabb();
        let (cols, rows) = self.window.pixel_ranges(lo, hi);
        let mut out = Vec::new();
        for j in rows {
            for i in cols.clone() {
                let k = j * RES + i;
                let p = self.window.pixel_center(i, j);
                if (self.low[k] as f64) < z1 && (self.high[k] as f64) > z0 && b.footprint_contains(p) {
                    out.push(p);
                }
            }
        }
        out
    }

    /// The room window.
    pub fn window(&self) -> &RoomWindow {
        &self.window
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::geom::RoomWindow;
    use crate::scene::RoomType;
    use glam::DVec3;

    #[test]
    fn a_walker_blocks_a_table_on_the_path_but_not_a_lamp_above_their_head() {
        let scene = generate_room(RoomType::Living, 3, 2, false).scene;
        let window = RoomWindow::for_room(scene.room_type, &scene.floor_plan.polygon());
        let c = Clearance::of(&scene, &window);
        // A walking human's pelvis at some frame: a box there is blocked, the same box raised
        // above the tallest head is not.
        let h = scene.humans.iter().find(|h| h.free_space_frames().next().is_some()).expect("a walker");
        let f = h.free_space_frames().next().unwrap();
        let p = h.joint_at(f, 0);
        let table = OBox::new(DVec3::new(p.x, p.y, 0.4), DVec3::new(0.3, 0.3, 0.8), 0.0);
        assert!(!c.blocked(&table).is_empty());
        let lamp = OBox::new(DVec3::new(p.x, p.y, 2.6), DVec3::new(0.3, 0.3, 0.2), 0.0);
        assert!(c.blocked(&lamp).is_empty());
    }
}
