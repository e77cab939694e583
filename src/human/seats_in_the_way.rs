//! Seats in the way: where one of an input's people walks or stands through the volume a seat or
//! a mattress must fill for someone sitting or lying there at another time (a sit or lie contact
//! box: the 10 cm under the resting body). No layout holds both — the piece that holds the one
//! stands in the other's way — so, like people inside each other, it is the input's doing: the
//! command line and Python warn about it where inputs are made and furnished.
//!
//! Only walking and standing frames are looked at (the free-space frames): a body sitting down
//! comes onto its seat from above, and its own sit or lie span is the one the seat is for.
//! Examples: a walk to a desk chair through where the chair stands (a person pulls such a chair
//! out first, which a static layout cannot show); a capture in which the person stands with a
//! shin where the front of their seat will be.

use super::conditions::contact_boxes;
use crate::scene::{Action, Scene};
use rapier3d::parry::math::Pose;
use rapier3d::parry::query;
use rapier3d::parry::shape::{Capsule, Cuboid};
use serde::{Deserialize, Serialize};

/// A walking or standing body in a seat's (or a bed's) volume: the deepest frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeatInTheWay {
    /// The person in the way.
    pub human: String,
    /// Their bone deepest in the volume (`"right_knee-right_ankle"`).
    pub bone: String,
    /// The deepest frame.
    pub frame: usize,
    /// How far (m) the bone's capsule reaches into the volume there.
    pub depth: f64,
    /// How many of their frames reach in by more than the tolerance.
    pub frames_inside: usize,
    /// Who sits or lies there, how, and in which frames.
    pub seated: String,
    /// `sit` or `lie`.
    pub action: Action,
    /// The frames `[start, end)` of that sitting or lying.
    pub seated_frames: [usize; 2],
}

impl std::fmt::Display for SeatInTheWay {
    /// `h0's right_knee-right_ankle is 0.090 m into where h0 sits at frames 148–329 at frame 60
    /// (31 frames): no layout holds both`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let how = if self.action == Action::Lie { "lies" } else { "sits" };
        write!(
            f,
            "{}'s {} is {:.3} m into where {} {how} at frames {}–{}, at frame {} ({} frames): no layout holds both",
            self.human,
            self.bone,
            self.depth,
            self.seated,
            self.seated_frames[0],
            self.seated_frames[1],
            self.frame,
            self.frames_inside
        )
    }
}

/// Every (person, seat) pair of `scene` in which the person's walking or standing bones reach
/// more than `tolerance` (m) into the volume under someone's sit or lie span (module header).
pub fn seats_in_the_way(scene: &Scene, tolerance: f64) -> Vec<SeatInTheWay> {
    let seats: Vec<_> =
        scene.humans.iter().flat_map(contact_boxes).filter(|b| matches!(b.action, Action::Sit | Action::Lie)).collect();
    let mut out = Vec::new();
    for seat in &seats {
        let o = &seat.obox;
        let solid = Cuboid::new(o.half().as_vec3());
        let at = Pose::from_parts(o.center.as_vec3(), glam::Quat::from_rotation_z(o.yaw as f32));
        let (lo, hi) = o.footprint_aabb();
        let (z0, z1) = o.z_range();
        for h in &scene.humans {
            let mut deepest: Option<(f64, usize, usize)> = None;
            let mut frames_inside = 0;
            for f in h.free_space_frames() {
                let mut worst: Option<(f64, usize)> = None;
                for (k, bone) in h.skeleton.bones.iter().enumerate() {
                    let (a, b) = (h.joint_at(f, bone.a), h.joint_at(f, bone.b));
                    // Most bones are nowhere near the seat: one comparison of boxes skips them.
                    let (min, max) = (a.min(b) - bone.radius, a.max(b) + bone.radius);
                    if min.x > hi.x || max.x < lo.x || min.y > hi.y || max.y < lo.y || min.z > z1 || max.z < z0 {
                        continue;
                    }
                    let cap = Capsule::new(a.as_vec3(), b.as_vec3(), bone.radius as f32);
                    let depth = match query::contact(&Pose::IDENTITY, &cap, &at, &solid, 0.0) {
                        Ok(Some(c)) if c.dist < 0.0 => -(c.dist as f64),
                        _ => 0.0,
                    };
                    if depth > tolerance && worst.is_none_or(|(w, _)| depth > w) {
                        worst = Some((depth, k));
                    }
                }
                if let Some((depth, k)) = worst {
                    frames_inside += 1;
                    if deepest.is_none_or(|d| depth > d.0) {
                        deepest = Some((depth, f, k));
                    }
                }
            }
            if let Some((depth, frame, k)) = deepest {
                out.push(SeatInTheWay {
                    human: h.id.clone(),
                    bone: h.skeleton.bone_name(k),
                    frame,
                    depth,
                    frames_inside,
                    seated: seat.human.clone(),
                    action: seat.action,
                    seated_frames: seat.frames,
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Polyline;
    use crate::human::{Body, Joint, Motion, sit};
    use crate::scene::{FloorPlan, RoomType};
    use glam::DVec2;

    /// One person who walks from `from` to just before a desk chair at (1.8, 2.75) (via `via`) and
    /// sits on it, facing +y.
    fn visit(from: [f64; 2], via: [f64; 2]) -> Scene {
        let body = Body::new(1.72);
        let seated = sit(&body, DVec2::new(1.8, 2.75), 0.46, 0.0);
        let feet = (seated.get(Joint::LeftAnkle) + seated.get(Joint::RightAnkle)).truncate() * 0.5;
        let mut m = Motion::new(body, 10.0);
        let path = vec![DVec2::from(from), DVec2::from(via), feet + DVec2::new(0.0, 0.08)];
        m.walk(&Polyline::new(path).unwrap(), 1.0).hold(seated, 30, Action::Sit);
        let plan = FloorPlan { polygon: vec![[0.0, 0.0], [3.6, 0.0], [3.6, 3.6], [0.0, 3.6]], height: 2.6 };
        Scene { humans: vec![m.into_human("h0")], ..Scene::new(RoomType::Bedroom, plan) }
    }

    #[test]
    fn a_walk_through_where_the_seat_must_stand_is_found_and_one_beside_it_is_not() {
        let through = seats_in_the_way(&visit([1.8, 0.6], [1.8, 2.0]), 0.02);
        assert_eq!(through.len(), 1, "{through:?}");
        let s = &through[0];
        assert_eq!((s.human.as_str(), s.seated.as_str(), s.action), ("h0", "h0", Action::Sit));
        assert!(s.bone.contains("knee") || s.bone.contains("hip"), "a leg: {}", s.bone);
        assert!(s.depth > 0.1 && s.frames_inside >= 3, "{s:?}");
        assert!(s.frame < s.seated_frames[0], "walking in, before sitting: {s:?}");
        assert!(s.to_string().starts_with("h0's ") && s.to_string().ends_with("no layout holds both"));
        assert!(seats_in_the_way(&visit([0.6, 0.6], [0.6, 3.1]), 0.02).is_empty());
    }
}
