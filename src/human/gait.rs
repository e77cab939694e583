//! Walking: a gait cycle along a polyline path with planted feet.
//!
//! The pelvis moves along the path at constant speed with the vertical bob and lateral sway of a
//! real gait; each foot alternates a stance phase (60 % of the cycle, planted flat, the heel rising
//! about the toe when the leg cannot reach) and a swing phase (the ankle arcs to the next plant).
//! Knees come from two-bone IK, arms swing opposite to the legs. Step length scales with stature
//! and speed (≈ 0.7 m for a 1.75 m adult at 1.2 m/s, a cadence of ≈ 1.7 steps per second).

use super::pose::{stand_local, two_bone_ik};
use super::{Body, Joint, Pose, Side};
use crate::geom::Polyline;
use glam::{DVec2, DVec3};
use std::f64::consts::TAU;

/// Fraction of the gait cycle a foot is on the ground.
const STANCE: f64 = 0.6;

/// Parameters of a walk.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gait {
    /// Walking speed in m/s (people walk indoors at about 1.0–1.4 m/s).
    pub speed: f64,
    /// Frames per second of the produced motion.
    pub fps: f64,
}

impl Default for Gait {
    /// 1.2 m/s at 30 fps.
    fn default() -> Gait {
        Gait { speed: 1.2, fps: 30.0 }
    }
}

impl Gait {
    /// Step length (one foot's plant to the other's) for `body` at this speed.
    pub fn step_length(&self, body: &Body) -> f64 {
        (0.4 * body.stature * (self.speed / 1.2).sqrt()).clamp(0.25 * body.stature, 0.5 * body.stature)
    }

    /// Number of frames walking `path` takes.
    pub fn frames(&self, path: &Polyline) -> usize {
        (path.length() / self.speed * self.fps).ceil() as usize + 1
    }

    /// Poses of `body` walking `path` from its start to its end, one per frame.
    pub fn walk(&self, body: &Body, path: &Polyline) -> Vec<Pose> {
        let n = self.frames(path);
        (0..n)
            .map(|f| {
                let s = (f as f64 * self.speed / self.fps).min(path.length());
                self.pose_at(body, path, s)
            })
            .collect()
    }

    /// The pose with the pelvis at arc length `s` of `path`.
    pub fn pose_at(&self, body: &Body, path: &Polyline, s: f64) -> Pose {
        let h = body.stature;
        let step = self.step_length(body);
        let stride = 2.0 * step;
        let smooth = 0.35;
        let dir = path.direction_at(s, smooth);
        let yaw = (-dir.x).atan2(dir.y);
        let right = DVec2::new(dir.y, -dir.x);
        let phase_left = (s / stride).rem_euclid(1.0);
        let bob = -0.008 * h * (2.0 * TAU * phase_left).cos();
        let sway = 0.01 * h * (TAU * (phase_left - 0.3)).sin();
        let base = path.point_at(s) - right * sway;
        let hip_z = body.hip_height() * 0.985 + bob;

        let mut local = stand_local(body);
        let pelvis0 = local.get(Joint::Pelvis);
        let lift = hip_z + body.pelvis_above_hips() - pelvis0.z;
        for j in [Joint::Pelvis, Joint::Spine, Joint::Chest, Joint::Neck, Joint::Head] {
            local.set(j, local.get(j) + DVec3::Z * lift);
        }
        for side in [Side::Left, Side::Right] {
            let [hip, ..] = side.leg();
            local.set(hip, local.get(hip) + DVec3::Z * lift);
            let [shoulder, elbow, wrist] = side.arm();
            let sh = local.get(shoulder) + DVec3::Z * lift;
            local.set(shoulder, sh);
            // Arm swing opposite to the leg of the same side.
            let phase = leg_phase(phase_left, side);
            let swing = -0.35 * (TAU * phase).cos();
            let flex = 0.25 + 0.3 * swing.max(0.0);
            let upper = DVec3::new(0.08 * side.sign(), swing.sin(), -swing.cos()).normalize();
            let fore = DVec3::new(0.0, (swing + flex).sin(), -(swing + flex).cos());
            let e = sh + upper * body.upper_arm();
            local.set(elbow, e);
            local.set(wrist, e + fore * body.forearm());
        }
        let mut pose = local.placed(base.extend(0.0), yaw);

        for side in [Side::Left, Side::Right] {
            let [hip, knee, ankle, toe] = side.leg();
            let (a, t) = self.foot(body, path, s, side, pose.get(hip));
            let forward = dir.extend(0.15).normalize();
            let (k, a) = two_bone_ik(pose.get(hip), a, body.thigh(), body.shank(), forward);
            pose.set(knee, k);
            pose.set(ankle, a);
            pose.set(toe, t);
        }
        pose
    }

    /// (ankle, toe) of one foot when the pelvis is at arc length `s`.
    fn foot(&self, body: &Body, path: &Polyline, s: f64, side: Side, hip: DVec3) -> (DVec3, DVec3) {
        let step = self.step_length(body);
        let stride = 2.0 * step;
        let cycle = s / stride + if side == Side::Right { 0.5 } else { 0.0 };
        let k = cycle.floor();
        let phase = cycle - k;
        // Heel strike of cycle k happened with the pelvis at `strike`; the foot lands half a step ahead.
        let strike = (k - if side == Side::Right { 0.5 } else { 0.0 }) * stride;
        // Plants before the start or past the end of the path stay at its ends (the first and last
        // steps are shorter), so no foot lands outside the path's span.
        let plant = |arc: f64| -> (DVec3, DVec2) {
            let arc = arc.clamp(0.0, path.length());
            let d = path.direction_at(arc, 0.35);
            let right = DVec2::new(d.y, -d.x);
            let p = path.point_at(arc) + right * (side.sign() * body.hip_half_width() * 1.1);
            (p.extend(body.ankle_height()), d)
        };
        let reach = body.thigh() + body.shank() - 1e-3;
        let (this_ankle, this_dir) = plant(strike + 0.5 * step);
        let this_toe = toe_of(body, this_ankle, this_dir, 0.0);
        if phase < STANCE {
            // Stance: foot flat, or heel rising about the toe when the hip has moved on.
            let pitch = heel_pitch(body, hip, this_toe, this_dir, reach);
            return (ankle_of(body, this_toe, this_dir, pitch), this_toe);
        }
        // Swing: from where the foot left the ground to the next plant.
        let u = (phase - STANCE) / (1.0 - STANCE);
        let off_pitch = 0.6;
        let from = ankle_of(body, this_toe, this_dir, off_pitch);
        let (to, to_dir) = plant(strike + stride + 0.5 * step);
        let smooth = u * u * (3.0 - 2.0 * u);
        let mut a = from.lerp(to, smooth);
        a.z += 0.05 * body.stature * (std::f64::consts::PI * u).sin();
        let d = this_dir.lerp(to_dir, smooth).normalize_or(to_dir);
        let pitch = off_pitch * (1.0 - u).powi(2);
        (a, a + foot_vector(body, d, pitch))
    }
}

fn leg_phase(phase_left: f64, side: Side) -> f64 {
    if side == Side::Left { phase_left } else { (phase_left + 0.5).rem_euclid(1.0) }
}

/// Ankle → toe with the heel raised by `pitch` radians.
fn foot_vector(body: &Body, dir: DVec2, pitch: f64) -> DVec3 {
    let (x, z) = (body.foot(), body.foot_radius() - body.ankle_height());
    let (s, c) = pitch.sin_cos();
    (dir * (x * c + z * s)).extend(-x * s + z * c)
}

fn toe_of(body: &Body, ankle: DVec3, dir: DVec2, pitch: f64) -> DVec3 {
    ankle + foot_vector(body, dir, pitch)
}

fn ankle_of(body: &Body, toe: DVec3, dir: DVec2, pitch: f64) -> DVec3 {
    toe - foot_vector(body, dir, pitch)
}

/// Smallest heel pitch (up to 70°) that brings the ankle within `reach` of the hip.
fn heel_pitch(body: &Body, hip: DVec3, toe: DVec3, dir: DVec2, reach: f64) -> f64 {
    let fits = |p: f64| ankle_of(body, toe, dir, p).distance(hip) <= reach;
    if fits(0.0) {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0, 70f64.to_radians());
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if fits(mid) { hi = mid } else { lo = mid }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walk_speed_step_length_and_planted_feet() {
        let body = Body::default();
        let gait = Gait::default();
        let path = Polyline::new(vec![DVec2::ZERO, DVec2::new(4.0, 0.0)]).unwrap();
        let poses = gait.walk(&body, &path);
        assert_eq!(poses.len(), 101);
        // The pelvis covers the path at the given speed.
        let p0 = poses[0].get(Joint::Pelvis).truncate();
        let p30 = poses[30].get(Joint::Pelvis).truncate();
        assert!(((p30.x - p0.x) - 1.2).abs() < 1e-9);
        assert!(p0.y.abs() < 0.03, "sway stays small");
        // Facing +x along the path.
        assert!((poses[50].facing() - DVec2::X).length() < 1e-6);
        // Bone lengths hold and the feet never go through the floor.
        for p in &poses {
            assert!((p.get(Joint::LeftHip).distance(p.get(Joint::LeftKnee)) - body.thigh()).abs() < 1e-6);
            assert!((p.get(Joint::RightKnee).distance(p.get(Joint::RightAnkle)) - body.shank()).abs() < 1e-6);
            assert!(p.get(Joint::LeftToe).z >= body.foot_radius() - 1e-9);
        }
        // A planted toe stays put between consecutive stance frames: count frames where the left toe
        // did not move (stance ≈ 60 % of frames).
        let still =
            poses.windows(2).filter(|w| w[0].get(Joint::LeftToe).distance(w[1].get(Joint::LeftToe)) < 1e-9).count();
        let ratio = still as f64 / (poses.len() - 1) as f64;
        assert!((0.45..0.7).contains(&ratio), "stance ratio {ratio}");
        // Step length ≈ 0.7 m.
        assert!((gait.step_length(&body) - 0.7).abs() < 0.01);
    }
}
