//! People inside each other: the pairs of an input's people in which one holds a pose (every joint
//! within the tolerance of where it starts: a sitter, a sleeper, a toucher) that the other's body
//! enters at some frame — two diners whose legs meet under a too-narrow table, a walker through a
//! sitter, two sitters put on one spot.
//!
//! No layout causes or mends this, so it is not one of the check's violations: the command line
//! warns about it where inputs are made and used (`import-motion`, `generate`, `check`), and
//! calibration keeps the people it moves and augments out of each other (`data::calibrate`).
//! People who move are traces of where people go, not one choreography (3D-FRONT HUMAN's
//! walkers, and ours, cross each other's paths at the same moment 1 to 3 times per room), so two
//! moving people never meet here; a held pose is there all the time, so whoever comes through it
//! meets it.

use crate::scene::{Human, Scene};
use glam::DVec3;
use rapier3d::parry::math::Pose;
use rapier3d::parry::query;
use rapier3d::parry::shape::Capsule;
use serde::{Deserialize, Serialize};

/// Two people inside each other: the deepest frame of their overlap.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Meeting {
    /// The two people's ids, in scene order.
    pub humans: [String; 2],
    /// The bone of each (`"left_knee-left_ankle"`) at the deepest frame.
    pub bones: [String; 2],
    /// The deepest frame, counted in the clip of the one who moves (the longer clip where both
    /// hold a pose).
    pub frame: usize,
    /// How far (m) the two bones' capsules overlap there.
    pub depth: f64,
    /// How many frames overlap by more than the tolerance.
    pub frames_inside: usize,
}

impl std::fmt::Display for Meeting {
    /// `s0 and w1 are inside each other: s0's right_knee-right_ankle is 0.061 m into w1's
    /// pelvis-left_hip at frame 12 (4 frames)`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b] = &self.humans;
        write!(
            f,
            "{a} and {b} are inside each other: {a}'s {} is {:.3} m into {b}'s {} at frame {} ({} frames)",
            self.bones[0], self.depth, self.bones[1], self.frame, self.frames_inside
        )
    }
}

/// Every pair of `scene`'s people in which one holds a pose and their bones overlap by more than
/// `tolerance` (m) at some frame (module header), in scene order of the pairs.
pub fn people_meeting(scene: &Scene, tolerance: f64) -> Vec<Meeting> {
    let humans = &scene.humans;
    let mut out = Vec::new();
    for i in 0..humans.len() {
        for j in i + 1..humans.len() {
            out.extend(meeting(&humans[i], &humans[j], tolerance));
        }
    }
    out
}

fn dist(p: &[f64; 3], q: &[f64; 3]) -> f64 {
    DVec3::from(*p).distance(DVec3::from(*q))
}

/// The joints' box of frame `f` of `h`, grown by its thickest bone.
fn extent(h: &Human, f: usize) -> (DVec3, DVec3) {
    let thickest = h.skeleton.bones.iter().map(|b| b.radius).fold(0.0, f64::max);
    let (lo, hi) = h.frame(f).fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| (lo.min(p), hi.max(p)));
    (lo - thickest, hi + thickest)
}

/// Whether `h` is inside any of `others` (by more than `tolerance`, one of the two holding still).
pub fn meets_anyone<'a>(h: &Human, others: impl IntoIterator<Item = &'a Human>, tolerance: f64) -> bool {
    others.into_iter().any(|o| meeting(h, o, tolerance).is_some())
}

/// Whether `a` and `b` are inside each other (by more than `tolerance`) at some moment, whether
/// they hold a pose or move: frame f of one against frame f of the other, a clip that has ended
/// holding its last frame. Stricter than [`people_meeting`], which lets two moving people pass
/// through each other as two traces: this is the test for putting a clip somewhere new
/// (`pipeline::place_to_fit`), where two people on top of each other are a placement's doing.
pub fn inside_each_other_at_once(a: &Human, b: &Human, tolerance: f64) -> bool {
    if a.frames.is_empty() || b.frames.is_empty() {
        return false;
    }
    (0..a.frames.len().max(b.frames.len())).any(|f| {
        let frames = [f.min(a.frames.len() - 1), f.min(b.frames.len() - 1)];
        deepest_overlap(a, b, frames, tolerance).is_some()
    })
}

/// `a` and `b` inside each other, where one of them holds a pose (module header).
fn meeting(a: &Human, b: &Human, tolerance: f64) -> Option<Meeting> {
    let held = |h: &Human| h.frames.iter().all(|f| f.iter().zip(&h.frames[0]).all(|(p, q)| dist(p, q) <= tolerance));
    if !(held(a) || held(b)) {
        return None;
    }
    // Every frame of the one who moves against the other's held pose (a clip that has ended holds
    // its last frame).
    let mut deepest: Option<(f64, usize, [usize; 2])> = None;
    let mut frames_inside = 0;
    for f in 0..a.frames.len().max(b.frames.len()) {
        let frames = [f.min(a.frames.len() - 1), f.min(b.frames.len() - 1)];
        if let Some((depth, bones)) = deepest_overlap(a, b, frames, tolerance) {
            frames_inside += 1;
            if deepest.is_none_or(|d| depth > d.0) {
                deepest = Some((depth, f, bones));
            }
        }
    }
    let (depth, frame, bones) = deepest?;
    Some(Meeting {
        humans: [a.id.clone(), b.id.clone()],
        bones: [a.skeleton.bone_name(bones[0]), b.skeleton.bone_name(bones[1])],
        frame,
        depth,
        frames_inside,
    })
}

/// The deepest overlap (m, beyond `tolerance`) of a bone of `a` at frame `frames[0]` with one of
/// `b` at `frames[1]`, and the two bones.
fn deepest_overlap(a: &Human, b: &Human, frames: [usize; 2], tolerance: f64) -> Option<(f64, [usize; 2])> {
    let ((lo_a, hi_a), (lo_b, hi_b)) = (extent(a, frames[0]), extent(b, frames[1]));
    if lo_a.cmpgt(hi_b).any() || lo_b.cmpgt(hi_a).any() {
        return None;
    }
    let capsules = |h: &Human, f: usize| -> Vec<Capsule> {
        h.skeleton
            .bones
            .iter()
            .map(|bone| {
                Capsule::new(h.joint_at(f, bone.a).as_vec3(), h.joint_at(f, bone.b).as_vec3(), bone.radius as f32)
            })
            .collect()
    };
    let (caps_a, caps_b) = (capsules(a, frames[0]), capsules(b, frames[1]));
    let mut worst: Option<(f64, [usize; 2])> = None;
    for (ka, cap_a) in caps_a.iter().enumerate() {
        for (kb, cap_b) in caps_b.iter().enumerate() {
            let depth = match query::contact(&Pose::IDENTITY, cap_a, &Pose::IDENTITY, cap_b, 0.0) {
                Ok(Some(c)) if c.dist < 0.0 => -(c.dist as f64),
                _ => 0.0,
            };
            if depth > tolerance && worst.is_none_or(|(w, _)| depth > w) {
                worst = Some((depth, [ka, kb]));
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, stand};
    use crate::scene::{Action, ActionSpan, FloorPlan, RoomType};
    use glam::DVec2;

    /// A person of the default body standing at each of `spots` in turn, one frame each, at `fps`.
    fn person(id: &str, fps: f64, spots: &[DVec2]) -> Human {
        let body = Body::default();
        Human {
            id: id.into(),
            skeleton: body.skeleton(),
            fps,
            frames: spots.iter().map(|&p| stand(&body, p, 0.0).0.iter().map(|q| q.to_array()).collect()).collect(),
            actions: vec![ActionSpan { start: 0, end: spots.len(), action: Action::Stand }],
        }
    }

    fn scene(humans: Vec<Human>) -> Scene {
        let mut scene = Scene::new(
            RoomType::Living,
            FloorPlan { polygon: vec![[-5.0, -5.0], [5.0, -5.0], [5.0, 5.0], [-5.0, 5.0]], height: 2.8 },
        );
        scene.humans = humans;
        scene
    }

    /// Nine steps along x from −2 m to 2 m, 0.5 m apart.
    fn walk() -> Vec<DVec2> {
        (0..9).map(|k| DVec2::new(-2.0 + 0.5 * k as f64, 0.0)).collect()
    }

    #[test]
    fn people_apart_do_not_meet_and_people_on_one_spot_do() {
        let apart = scene(vec![person("a", 10.0, &[DVec2::ZERO]), person("b", 10.0, &[DVec2::new(1.0, 0.0)])]);
        assert!(people_meeting(&apart, 0.02).is_empty());
        let together = scene(vec![person("a", 10.0, &[DVec2::ZERO]), person("b", 10.0, &[DVec2::new(0.1, 0.0)])]);
        let found = people_meeting(&together, 0.02);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(found[0].humans, ["a".to_string(), "b".to_string()]);
        // Two trunks 10 cm apart: the capsules overlap by their two radii less 10 cm, at least.
        let trunk = Body::default().skeleton().bones.iter().map(|b| b.radius).fold(0.0, f64::max);
        assert!(found[0].depth >= 2.0 * trunk - 0.1 - 1e-6, "{found:?}");
    }

    #[test]
    fn a_walker_meets_a_held_pose_where_it_passes_and_other_walkers_never() {
        // A one-frame person stands at x = 0; the walker is there at frame 4, and side by side
        // with them 0.5 m away at frames 3 and 5 (their hanging arms meet), 1 m away at 2 and 6
        // (apart).
        let held = person("s", 10.0, &[DVec2::ZERO]);
        let found = people_meeting(&scene(vec![person("w", 10.0, &walk()), held.clone()]), 0.02);
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!((found[0].frame, found[0].frames_inside), (4, 3), "{found:?}");
        assert_eq!(found[0].humans, ["w".to_string(), "s".to_string()]);
        // Held 2 m aside of the walk: apart.
        let aside = person("s", 10.0, &[DVec2::new(0.0, 2.0)]);
        assert!(people_meeting(&scene(vec![person("w", 10.0, &walk()), aside]), 0.02).is_empty());
        // Two walkers passing through each other at the same moment are two traces: no meeting.
        let mut back = walk();
        back.reverse();
        assert!(people_meeting(&scene(vec![person("a", 10.0, &walk()), person("b", 10.0, &back)]), 0.02).is_empty());
    }

    #[test]
    fn at_once_counts_walkers_together_in_time_and_not_on_one_path_at_other_times() {
        let mut back = walk();
        back.reverse();
        // Through each other at frame 4 (both at x = 0).
        assert!(inside_each_other_at_once(&person("a", 10.0, &walk()), &person("b", 10.0, &back), 0.02));
        // The same path, one 1 m (two steps) behind the other all along: never at once.
        let behind: Vec<DVec2> = walk().iter().map(|p| *p - DVec2::new(1.0, 0.0)).collect();
        assert!(!inside_each_other_at_once(&person("a", 10.0, &walk()), &person("b", 10.0, &behind), 0.02));
        // Half a step behind: the hanging arms meet.
        let close: Vec<DVec2> = walk().iter().map(|p| *p - DVec2::new(0.25, 0.0)).collect();
        assert!(inside_each_other_at_once(&person("a", 10.0, &walk()), &person("b", 10.0, &close), 0.02));
        // A clip that has ended holds its last frame: a one-frame person at x = 2 meets the walker
        // when it arrives there at frame 8.
        let end = person("s", 10.0, &[DVec2::new(2.0, 0.0)]);
        assert!(inside_each_other_at_once(&person("a", 10.0, &walk()), &end, 0.02));
        assert!(!inside_each_other_at_once(
            &person("a", 10.0, &walk()),
            &person("s", 10.0, &[DVec2::new(0.0, 2.0)]),
            0.02
        ));
    }
}
