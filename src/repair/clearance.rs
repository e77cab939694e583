//! Where people's bodies are, for repair: over the 256² room window, the lowest and highest
//! point of any bone (capsule) above each pixel in any walking or standing frame, and separately of
//! the shins and feet in sitting and touching frames (a sitter's lower legs hang in front of the
//! seat, a toucher stands; a sleeper's rest on the bed). A piece of furniture is in the way where its footprint covers a pixel and its
//! height range meets that pixel's — of the walkers always, of the shins and feet only for a solid
//! piece (no legs to put feet between: a cabinet, a sofa; a table's or chair's legroom is not in the
//! way). (The free-space mask of the conditioning holds the walkers' feet only; arms and hips reach
//! wider.) Sleepers' and sitters' other bones rest on their furniture and are left out.

use crate::geom::{OBox, RES, RoomWindow, point_segment_distance};
use crate::scene::{Action, Scene};
use glam::{DVec2, DVec3};

/// Per pixel, the height range the walking bodies occupy (empty where nobody walks), and the one
/// the contact people's shins and feet occupy.
#[derive(Debug, Clone)]
pub struct Clearance {
    window: RoomWindow,
    walking: HeightField,
    legs: HeightField,
}

/// Per pixel, the lowest and highest point of some bones.
#[derive(Debug, Clone)]
struct HeightField {
    low: Vec<f32>,
    high: Vec<f32>,
}

impl HeightField {
    fn new() -> HeightField {
        HeightField { low: vec![f32::INFINITY; RES * RES], high: vec![f32::NEG_INFINITY; RES * RES] }
    }

    /// Adds the capsule from `a` to `b` of `radius`.
    fn add(&mut self, window: &RoomWindow, a: DVec3, b: DVec3, radius: f64) {
        let (lo, hi) = ((a.z.min(b.z) - radius) as f32, (a.z.max(b.z) + radius) as f32);
        let (a2, b2) = (a.truncate(), b.truncate());
        let (cols, rows) = window.pixel_ranges(a2.min(b2) - radius, a2.max(b2) + radius);
        for j in rows {
            for i in cols.clone() {
                if point_segment_distance(window.pixel_center(i, j), a2, b2) <= radius {
                    let k = j * RES + i;
                    self.low[k] = self.low[k].min(lo);
                    self.high[k] = self.high[k].max(hi);
                }
            }
        }
    }

    /// Whether pixel `k`'s range meets [z0, z1].
    fn meets(&self, k: usize, z0: f64, z1: f64) -> bool {
        (self.low[k] as f64) < z1 && (self.high[k] as f64) > z0
    }
}

/// Joints of the shins and feet.
const LOWER_LEGS: [&str; 6] = ["left_knee", "right_knee", "left_ankle", "right_ankle", "left_toe", "right_toe"];

impl Clearance {
    /// The fields of `scene`'s humans over `window`.
    pub fn of(scene: &Scene, window: &RoomWindow) -> Clearance {
        let mut c = Clearance { window: *window, walking: HeightField::new(), legs: HeightField::new() };
        for human in &scene.humans {
            let walking: Vec<usize> = human.free_space_frames().collect();
            for &f in &walking {
                for bone in &human.skeleton.bones {
                    c.walking.add(window, human.joint_at(f, bone.a), human.joint_at(f, bone.b), bone.radius);
                }
            }
            let s = &human.skeleton;
            let legs: Vec<usize> = LOWER_LEGS.iter().filter_map(|n| s.joint(n)).collect();
            let shins = s.bones.iter().filter(|b| legs.contains(&b.a) && legs.contains(&b.b));
            // Sitting and touching frames: a sleeper's legs rest on the bed.
            let still: Vec<usize> = human
                .actions
                .iter()
                .filter(|a| matches!(a.action, Action::Sit | Action::Touch))
                .flat_map(|a| a.start..a.end.min(human.frames.len()))
                .collect();
            // Static poses repeat: a few frames of each stretch are enough.
            let sampled = still.iter().step_by((still.len() / 16).max(1));
            for &f in sampled {
                for bone in shins.clone() {
                    c.legs.add(window, human.joint_at(f, bone.a), human.joint_at(f, bone.b), bone.radius);
                }
            }
        }
        c
    }

    /// The pixels (centres) where `b` is in the bodies' way: inside its footprint, with a height
    /// range meeting the walkers' or, for a `solid` piece, the contact people's shins and feet.
    pub fn blocked(&self, b: &OBox, solid: bool) -> Vec<DVec2> {
        let (z0, z1) = b.z_range();
        let (lo, hi) = b.footprint_aabb();
        let (cols, rows) = self.window.pixel_ranges(lo, hi);
        let mut out = Vec::new();
        for j in rows {
            for i in cols.clone() {
                let k = j * RES + i;
                let p = self.window.pixel_center(i, j);
                let hit = self.walking.meets(k, z0, z1) || (solid && self.legs.meets(k, z0, z1));
                if hit && b.footprint_contains(p) {
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
    use crate::scene::RoomType;

    #[test]
    fn a_walker_blocks_a_table_on_the_path_but_not_a_lamp_above_their_head() {
        let scene = generate_room(RoomType::Living, 3, 2, false).scene;
        let window = scene.room_window();
        let c = Clearance::of(&scene, &window);
        // A walking human's pelvis at some frame: a box there is blocked, the same box raised
        // above the tallest head is not.
        let h = scene.humans.iter().find(|h| h.free_space_frames().next().is_some()).expect("a walker");
        let f = h.free_space_frames().next().unwrap();
        let p = h.joint_at(f, 0);
        let table = OBox::new(DVec3::new(p.x, p.y, 0.4), DVec3::new(0.3, 0.3, 0.8), 0.0);
        assert!(!c.blocked(&table, false).is_empty());
        let lamp = OBox::new(DVec3::new(p.x, p.y, 2.6), DVec3::new(0.3, 0.3, 0.2), 0.0);
        assert!(c.blocked(&lamp, true).is_empty());
    }

    #[test]
    fn a_sitters_shins_block_a_cabinet_but_not_a_table() {
        let scene = generate_room(RoomType::Dining, 3, 1, false).scene;
        let window = scene.room_window();
        let c = Clearance::of(&scene, &window);
        let sitter = scene.humans.iter().find(|h| h.actions.iter().any(|a| a.action == Action::Sit)).expect("a sitter");
        let f = sitter.actions.iter().find(|a| a.action == Action::Sit).unwrap().start;
        let ankle = sitter.joint_at(f, sitter.skeleton.joint("left_ankle").unwrap());
        let cabinet = OBox::new(DVec3::new(ankle.x, ankle.y, 0.4), DVec3::new(0.2, 0.2, 0.8), 0.0);
        assert!(!c.blocked(&cabinet, true).is_empty());
        assert!(c.blocked(&cabinet, false).is_empty(), "nobody walks there");
    }
}
