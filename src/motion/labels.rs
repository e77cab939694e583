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
//! `smooth` seconds, and spans shorter than `min_span` joined to the span before them. It does not
//! know what the person touches or sits on: that is the generator's job.

use crate::human::Joint;
use crate::scene::{Action, ActionSpan};
use glam::DVec3;
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
    join_short(voted, ((cfg.min_span * fps).round() as usize).max(1))
}

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
}
