//! Action labels from kinematics: for each frame of a retargeted clip (z-up, metres), whether the
//! person walks, stands, sits, lies or touches something, from the pelvis's height and speed, the
//! trunk's inclination, the thighs' slope and the hands' reach — so that contact boxes and free
//! floor come out right for clips nobody labelled.
//!
//! Per frame, in this order:
//! - **lie** where the trunk leans more than `lie_incline` from upright, the pelvis is below
//!   `lie_pelvis` of the stature and no ankle is more than `lie_ankles` below the pelvis (a sitter
//!   leaning far back in a lounge chair keeps a foot on the floor);
//! - **sit** where the pelvis is below `sit_pelvis` and the thighs slope less than `sit_thigh`
//!   (their drop over their length: 1 standing, about 0 on a chair);
//! - **walk** where the pelvis moves faster than `walk_speed` over `speed_window`;
//! - **touch** where a wrist is `touch_reach` of the stature or more from the chest, horizontally,
//!   and slower than `touch_still` (a hand raised overhead close to the body is not on a piece a
//!   layout could hold: a piece under it would hold the person too), unless both arms are spread
//!   sideways (each wrist `spread_arms` of its arm's length or more out along the shoulders: the
//!   T- or A-pose many captures start in);
//! - **stand** otherwise.
//!
//! Sitting and lying also need the pelvis settled, moving up or down slower than `settle_speed`
//! (a person sitting down is not yet supported where they will sit). Then a majority vote over
//! `smooth` seconds, and spans shorter than `min_span` joined to the span before them.
//!
//! Last, a touch needs room for what is touched: a span stays a touch only if the column under its
//! contact box (`human::contact_boxes`: the 12 cm cube the palm presses on), down to the floor and
//! on beyond the palm, away from the person, by `touch_room_depth` (the shallowest real piece a
//! hand rests on: the least a standing piece under the hand fills), stays clear of the same
//! person's bones, by more than `touch_room_tolerance`, at every frame more than
//! `touch_room_margin` seconds from the span. Otherwise no piece could hold the hand without
//! standing in the person's way at another time (a hand on playground bars the person later walks
//! under, an arm held out in a gesture where they then walk), and the span is standing. The
//! labeller does not know what the person touches or sits on: that is the generator's job.

use crate::geom::OBox;
use crate::human::{Body, ContactBox, Joint, contact_boxes};
use crate::scene::{Action, ActionSpan, Human};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// The labeller's thresholds (chosen on the calibrated val split's humans; docs/RESULTS.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LabelConfig {
    /// Trunk inclination from upright (degrees) beyond which a low pelvis is lying. Default 55.
    pub lie_incline: f64,
    /// Pelvis height (fraction of stature) below which an inclined trunk is lying. Default 0.6.
    pub lie_pelvis: f64,
    /// How far (fraction of stature) a lier's lower ankle may be below the pelvis. Default 0.15.
    pub lie_ankles: f64,
    /// Pelvis height (fraction of stature) below which level thighs are sitting. Default 0.5.
    pub sit_pelvis: f64,
    /// Largest thigh slope (drop over length) of a sitter. Default 0.6.
    pub sit_thigh: f64,
    /// Vertical pelvis speed (m/s) below which a sitter or lier has settled. Default 0.15.
    pub settle_speed: f64,
    /// Pelvis speed (m/s, horizontal) above which a person walks. Default 0.3.
    pub walk_speed: f64,
    /// Seconds over which speeds are measured (centred). Default 0.4.
    pub speed_window: f64,
    /// A wrist's horizontal distance from the chest (fraction of stature) that reaches out.
    /// Default 0.2.
    pub touch_reach: f64,
    /// Wrist speed (m/s) below which a reaching hand holds still. Default 0.3.
    pub touch_still: f64,
    /// How far out along the shoulder line (fraction of the arm's length) both wrists are in a
    /// spread-arms pose, which is not a touch. Default 0.6 (the val split's touchers: at most one
    /// arm out sideways).
    pub spread_arms: f64,
    /// Seconds of the majority vote. Default 0.5.
    pub smooth: f64,
    /// Shortest span (s); shorter ones join the span before them. Default 0.3.
    pub min_span: f64,
    /// Seconds either side of a touch span in which the person's bones may enter the column under
    /// its contact box (reaching for it, letting go). Default 0.5.
    pub touch_room_margin: f64,
    /// How deep (m) a bone may reach into that column at other times: the check's tolerance.
    /// Default 0.02.
    pub touch_room_tolerance: f64,
    /// How far (m) that column reaches beyond the palm, away from the person (horizontally from
    /// the pelvis to the palm, at the span's middle frame): the depth of the shallowest piece a
    /// hand rests on (the catalog's shelves, 30 cm). Default 0.3.
    pub touch_room_depth: f64,
}

impl Default for LabelConfig {
    fn default() -> LabelConfig {
        LabelConfig {
            lie_incline: 55.0,
            lie_pelvis: 0.6,
            lie_ankles: 0.15,
            sit_pelvis: 0.5,
            sit_thigh: 0.6,
            settle_speed: 0.15,
            walk_speed: 0.3,
            speed_window: 0.4,
            touch_reach: 0.2,
            touch_still: 0.3,
            spread_arms: 0.6,
            smooth: 0.5,
            min_span: 0.3,
            touch_room_margin: 0.5,
            touch_room_tolerance: 0.02,
            touch_room_depth: 0.3,
        }
    }
}

const ACTIONS: [Action; 5] = [Action::Walk, Action::Stand, Action::Sit, Action::Lie, Action::Touch];

/// One action per frame of `frames` (z-up, metres; `JOINT_NAMES` order), for a person of
/// `stature` m recorded at `fps`.
pub fn label_frames(frames: &[[DVec3; 19]], fps: f64, stature: f64, cfg: &LabelConfig) -> Vec<Action> {
    let n = frames.len();
    let half = ((cfg.speed_window * fps * 0.5).round() as usize).max(1);
    /// Which part of a joint's displacement a speed measures.
    #[derive(Clone, Copy)]
    enum Along {
        All,
        Horizontal,
        Vertical,
    }
    let speed = |f: usize, joint: Joint, along: Along| -> f64 {
        let (a, b) = (f.saturating_sub(half), (f + half).min(n - 1));
        if a == b {
            return 0.0;
        }
        let d = frames[b][joint.index()] - frames[a][joint.index()];
        let d = match along {
            Along::All => d.length(),
            Along::Horizontal => d.truncate().length(),
            Along::Vertical => d.z.abs(),
        };
        d * fps / (b - a) as f64
    };
    let raw: Vec<Action> =
        (0..n)
            .map(|f| {
                let p = &frames[f];
                let at = |j: Joint| p[j.index()];
                let trunk = at(Joint::Neck) - at(Joint::Pelvis);
                let incline = trunk.angle_between(DVec3::Z).to_degrees();
                let pelvis = at(Joint::Pelvis).z / stature;
                let drop = |a: Joint, b: Joint| (at(a).z - at(b).z) / at(a).distance(at(b)).max(1e-6);
                let slope = 0.5 * (drop(Joint::LeftHip, Joint::LeftKnee) + drop(Joint::RightHip, Joint::RightKnee));
                let ankles = (at(Joint::Pelvis).z - at(Joint::LeftAnkle).z.min(at(Joint::RightAnkle).z)) / stature;
                let reach = |wrist: Joint| {
                    at(wrist).truncate().distance(at(Joint::Chest).truncate()) >= cfg.touch_reach * stature
                        && speed(f, wrist, Along::All) < cfg.touch_still
                };
                // How far out sideways a wrist is, along its shoulder's line from the other shoulder.
                let out = |shoulder: Joint, other: Joint, elbow: Joint, wrist: Joint| {
                    let line = (at(shoulder) - at(other)).truncate().normalize_or_zero();
                    let arm = at(shoulder).distance(at(elbow)) + at(elbow).distance(at(wrist));
                    (at(wrist) - at(shoulder)).truncate().dot(line) / arm.max(1e-6)
                };
                let spread = out(Joint::LeftShoulder, Joint::RightShoulder, Joint::LeftElbow, Joint::LeftWrist)
                    .min(out(Joint::RightShoulder, Joint::LeftShoulder, Joint::RightElbow, Joint::RightWrist))
                    >= cfg.spread_arms;
                let settled = speed(f, Joint::Pelvis, Along::Vertical) < cfg.settle_speed;
                if settled && incline > cfg.lie_incline && pelvis < cfg.lie_pelvis && ankles < cfg.lie_ankles {
                    Action::Lie
                } else if settled && pelvis < cfg.sit_pelvis && slope < cfg.sit_thigh {
                    Action::Sit
                } else if speed(f, Joint::Pelvis, Along::Horizontal) > cfg.walk_speed {
                    Action::Walk
                } else if !spread && (reach(Joint::LeftWrist) || reach(Joint::RightWrist)) {
                    Action::Touch
                } else {
                    Action::Stand
                }
            })
            .collect();
    let voted = majority(&raw, (cfg.smooth * fps * 0.5).round() as usize);
    let mut labels = join_short(voted, ((cfg.min_span * fps).round() as usize).max(1));
    for span in touches_without_room(frames, &labels, fps, stature, cfg) {
        labels[span.start..span.end].fill(Action::Stand);
    }
    labels
}

/// The touch spans of `labels` whose contact box has no room under it (module header).
fn touches_without_room(
    frames: &[[DVec3; 19]],
    labels: &[Action],
    fps: f64,
    stature: f64,
    cfg: &LabelConfig,
) -> Vec<ActionSpan> {
    let spans = runs(labels);
    if !spans.iter().any(|s| s.action == Action::Touch) {
        return Vec::new();
    }
    let human = Human {
        id: "h".into(),
        skeleton: Body::new(stature).skeleton(),
        fps,
        frames: frames.iter().map(|f| f.iter().map(|p| p.to_array()).collect()).collect(),
        actions: spans.clone(),
    };
    let margin = (cfg.touch_room_margin * fps).round() as usize;
    // Each frame's body as a horizontal box (joints ± the thickest bone): most frames are far from
    // a given column and are skipped by one comparison.
    let thickest = human.skeleton.bones.iter().map(|b| b.radius).fold(0.0, f64::max);
    let extents: Vec<(DVec2, DVec2)> = frames
        .iter()
        .map(|f| {
            let (lo, hi) =
                f.iter().fold((DVec2::MAX, DVec2::MIN), |(lo, hi), p| (lo.min(p.truncate()), hi.max(p.truncate())));
            (lo - thickest, hi + thickest)
        })
        .collect();
    // The frames where some joint has moved more than `KEY_MOVE` since the last one kept, each
    // standing for the frames up to the next (a person standing still is one pose to test, not
    // thousands).
    let mut keys = vec![0];
    for f in 1..frames.len() {
        let last = &frames[*keys.last().expect("frame 0")];
        if frames[f].iter().zip(last).any(|(p, q)| p.distance(*q) > KEY_MOVE) {
            keys.push(f);
        }
    }
    let boxes: Vec<_> = contact_boxes(&human).into_iter().filter(|b| b.action == Action::Touch).collect();
    // Very long and busy clips with many touches: every k-th key, so that at most `MAX_TESTS`
    // (span, key) pairs are tested (each then stands for k keys' frames).
    let every = (boxes.len() * keys.len()).div_ceil(MAX_TESTS).max(1);
    let keys: Vec<usize> = keys.into_iter().step_by(every).collect();
    let until: Vec<usize> = keys.iter().skip(1).copied().chain([frames.len()]).collect();
    boxes
        .into_iter()
        .filter(|b| {
            let [start, end] = b.frames;
            let room = touch_room(b, frames[(start + end) / 2][Joint::Pelvis.index()], cfg.touch_room_depth);
            let ((lo0, hi0), (lo1, hi1)) = (room[0].footprint_aabb(), room[1].footprint_aabb());
            let (lo, hi) = (lo0.min(lo1), hi0.max(hi1));
            let near = |f: &usize| extents[*f].0.cmple(hi).all() && extents[*f].1.cmpge(lo).all();
            // A key stands for frames `key..next`; it is tested when one of them is away from the span.
            let away = keys.iter().zip(&until).filter(|&(&f, &next)| f + margin < start || next > end + margin);
            away.map(|(&f, _)| f).filter(near).any(|f| {
                human.skeleton.bones.iter().any(|bone| {
                    let (a, c) = (frames[f][bone.a], frames[f][bone.b]);
                    (0..=BONE_SAMPLES).any(|i| {
                        let p = a.lerp(c, i as f64 / BONE_SAMPLES as f64);
                        let depth = bone.radius - room[0].signed_distance(p).min(room[1].signed_distance(p));
                        depth > cfg.touch_room_tolerance
                    })
                })
            })
        })
        .filter_map(|b| spans.iter().find(|s| [s.start, s.end] == b.frames).cloned())
        .collect()
}

/// The room a touch needs (module header), as two boxes from the floor to the top of touch box `b`:
/// the column under the box, and the column from the palm to `depth` beyond it, away from `pelvis`
/// (in the box's facing where the palm is above the pelvis).
fn touch_room(b: &ContactBox, pelvis: DVec3, depth: f64) -> [OBox; 2] {
    let palm = b.obox.center.truncate();
    let (sn, cs) = b.obox.yaw.sin_cos();
    let away = (palm - pelvis.truncate()).try_normalize().unwrap_or(DVec2::new(-sn, cs));
    let top = b.obox.center.z + b.obox.half().z;
    let column = OBox::new(palm.extend(top * 0.5), b.obox.size.truncate().extend(top), b.obox.yaw);
    let beyond = OBox::new(
        (palm + away * (depth * 0.5)).extend(top * 0.5),
        DVec3::new(b.obox.size.x, depth, top),
        (-away.x).atan2(away.y),
    );
    [column, beyond]
}

/// Most (touch span, key frame) pairs the room test looks at: beyond, keys are thinned evenly. The
/// shipped clips need at most 2,000; 50,000 frames of a person fidgeting through 400 touches
/// would need 20 million (about 15 s).
const MAX_TESTS: usize = 1 << 21;

/// How far (m) a joint moves before the room test looks at a frame again: the frames between are
/// within this of one tested, so a depth it misses is at most this much deeper than one it sees.
const KEY_MOVE: f64 = 0.01;

/// Points tested along a bone against a touch's column (ends included): 2 cm apart or closer on
/// a forearm, which is what a 12 cm column needs.
const BONE_SAMPLES: usize = 16;

/// Each frame's most common label within `half` frames either side (ties: its own, then the
/// earliest in `ACTIONS`).
fn majority(labels: &[Action], half: usize) -> Vec<Action> {
    let n = labels.len();
    (0..n)
        .map(|f| {
            let window = &labels[f.saturating_sub(half)..(f + half + 1).min(n)];
            let count = |a: Action| window.iter().filter(|&&x| x == a).count();
            let own = count(labels[f]);
            ACTIONS
                .into_iter()
                .map(|a| (count(a), a))
                .filter(|(c, _)| *c > own)
                .max_by_key(|(c, _)| *c)
                .map_or(labels[f], |(_, a)| a)
        })
        .collect()
}

/// Runs shorter than `min` frames take the label of the run before them (the first run, of the
/// run after it).
fn join_short(mut labels: Vec<Action>, min: usize) -> Vec<Action> {
    loop {
        let runs = runs(&labels);
        if runs.len() <= 1 {
            return labels;
        }
        let Some(k) = runs.iter().position(|r| r.end - r.start < min) else {
            return labels;
        };
        let with = if k == 0 { runs[1].action } else { runs[k - 1].action };
        labels[runs[k].start..runs[k].end].fill(with);
    }
}

/// The labels as spans of equal actions.
pub fn runs(labels: &[Action]) -> Vec<ActionSpan> {
    let mut out: Vec<ActionSpan> = Vec::new();
    for (f, &a) in labels.iter().enumerate() {
        match out.last_mut() {
            Some(span) if span.action == a => span.end = f + 1,
            _ => out.push(ActionSpan { start: f, end: f + 1, action: a }),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, Side, stand};
    use glam::DVec2;

    /// A standing pose of a 1.75 m body held for a second at 30 fps, its arms set by `arms`.
    fn held(arms: impl Fn(&mut [DVec3; 19])) -> Vec<[DVec3; 19]> {
        let mut pose = stand(&Body::default(), DVec2::ZERO, 0.0).0;
        arms(&mut pose);
        vec![pose; 30]
    }

    /// Puts `side`'s elbow and wrist straight out from the shoulder along `dir`.
    fn reach(pose: &mut [DVec3; 19], side: Side, dir: DVec3) {
        let [shoulder, elbow, wrist] = side.arm();
        let s = pose[shoulder.index()];
        pose[elbow.index()] = s + dir * 0.32;
        pose[wrist.index()] = s + dir * 0.58;
    }

    #[test]
    fn a_hand_held_out_is_a_touch_but_spread_arms_and_a_raised_hand_are_not() {
        let cfg = LabelConfig::default();
        let label = |frames: &[[DVec3; 19]]| label_frames(frames, 30.0, 1.75, &cfg);
        assert!(label(&held(|_| {})).iter().all(|&a| a == Action::Stand));
        // One hand forward (+y, the way a body at yaw 0 faces): a touch.
        let forward = held(|p| reach(p, Side::Right, DVec3::Y));
        assert!(label(&forward).iter().all(|&a| a == Action::Touch));
        // Both arms out to the sides (a T-pose; the left is −x): standing, not touching.
        let t_pose = held(|p| {
            reach(p, Side::Left, -DVec3::X);
            reach(p, Side::Right, DVec3::X);
        });
        assert!(label(&t_pose).iter().all(|&a| a == Action::Stand));
        // A hand raised straight up, close to the body: no piece could be under it without
        // holding the person too, so not a touch.
        let overhead = held(|p| reach(p, Side::Right, DVec3::Z));
        assert!(label(&overhead).iter().all(|&a| a == Action::Stand));
        // Both hands forward (pushing a table): a touch.
        let both = held(|p| {
            reach(p, Side::Left, DVec3::Y);
            reach(p, Side::Right, DVec3::Y);
        });
        assert!(label(&both).iter().all(|&a| a == Action::Touch));
    }

    #[test]
    fn a_touch_needs_room_for_a_piece_the_person_does_not_stand_in_later() {
        let cfg = LabelConfig::default();
        // A second of a hand held forward (+y), then a second standing elsewhere.
        let touch_then_stand_at = |y: f64| {
            let mut frames = held(|p| reach(p, Side::Right, DVec3::Y));
            let later = stand(&Body::default(), DVec2::new(0.0, y), 0.0).0;
            frames.extend(std::iter::repeat_n(later, 30));
            label_frames(&frames, 30.0, 1.75, &cfg)
        };
        // Stepping back 1 m leaves room for a piece under the hand: the touch stays.
        let back = touch_then_stand_at(-1.0);
        assert!(back[..20].iter().all(|&a| a == Action::Touch), "{back:?}");
        // Standing where the hand was (0.75 m ahead): no piece could have been there.
        let ahead = touch_then_stand_at(0.75);
        assert!(!ahead.contains(&Action::Touch), "{ahead:?}");
        // The same with a tolerance the standing body stays within: the touch stays.
        let lax = LabelConfig { touch_room_tolerance: 1.0, ..cfg };
        let mut frames = held(|p| reach(p, Side::Right, DVec3::Y));
        frames.extend(std::iter::repeat_n(stand(&Body::default(), DVec2::new(0.0, 0.75), 0.0).0, 30));
        assert!(label_frames(&frames, 30.0, 1.75, &lax)[..20].iter().all(|&a| a == Action::Touch));
    }

    #[test]
    fn a_touch_needs_room_beyond_the_hand_for_the_shallowest_piece() {
        let cfg = LabelConfig::default();
        let hand = held(|p| reach(p, Side::Right, DVec3::Y));
        let palm = hand[0][Joint::RightWrist.index()].y;
        // A second of the hand held forward (+y), then a second standing with the back of the body
        // `gap` beyond the palm (the torso is about 0.15 m deep behind the pelvis).
        let touch_then_stand_beyond = |gap: f64, cfg: &LabelConfig| {
            let mut frames = hand.clone();
            let later = stand(&Body::default(), DVec2::new(0.0, palm + gap + 0.15), 0.0).0;
            frames.extend(std::iter::repeat_n(later, 30));
            label_frames(&frames, 30.0, 1.75, cfg)
        };
        // 15 cm beyond the palm: clear of the column under the hand, but inside a 30 cm shelf.
        let near = touch_then_stand_beyond(0.15, &cfg);
        assert!(!near.contains(&Action::Touch), "{near:?}");
        // Without the depth (the column alone) that touch stayed.
        let column_only = touch_then_stand_beyond(0.15, &LabelConfig { touch_room_depth: 0.0, ..cfg });
        assert!(column_only[..20].iter().all(|&a| a == Action::Touch), "{column_only:?}");
        // 60 cm beyond: room for the shelf, and the touch stays.
        let far = touch_then_stand_beyond(0.6, &cfg);
        assert!(far[..20].iter().all(|&a| a == Action::Touch), "{far:?}");
    }

    #[test]
    fn the_touch_room_depth_is_the_shallowest_touchable_piece() {
        let shallowest = crate::scene::Category::ALL
            .iter()
            .filter(|c| c.affords(Action::Touch))
            .map(|&c| crate::furniture::size_range(c, 1).0.min(crate::furniture::size_range(c, 0).0))
            .fold(f64::INFINITY, f64::min);
        assert!((LabelConfig::default().touch_room_depth - shallowest).abs() < 0.005, "{shallowest}");
    }
}
