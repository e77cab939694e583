//! Static poses of the default skeleton: stand, sit, lie and touch.
//!
//! Poses are built in the body frame (x = the person's right, y = forward, z = up, origin on the
//! floor under the pelvis) and placed in the world by a position and a yaw with the same convention
//! as objects: yaw 0 faces +y, and a chair and the person sitting on it share their yaw. Walking is
//! in `gait`. These are geometric poses, not simulated ones.

use super::{Body, Joint, Side};
use glam::{DVec2, DVec3};

/// Joint positions of the default skeleton, in [`super::JOINT_NAMES`] order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose(pub [DVec3; 19]);

impl Pose {
    /// Position of `j`.
    pub fn get(&self, j: Joint) -> DVec3 {
        self.0[j.index()]
    }

    /// Sets the position of `j`.
    pub fn set(&mut self, j: Joint, p: DVec3) {
        self.0[j.index()] = p;
    }

    /// The pose rotated by `yaw` about +z and moved by `offset` (a body-frame pose into the world).
    pub fn placed(&self, offset: DVec3, yaw: f64) -> Pose {
        let (s, c) = yaw.sin_cos();
        Pose(self.0.map(|p| DVec3::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z) + offset))
    }

    /// The pose moved by `offset`.
    pub fn translated(&self, offset: DVec3) -> Pose {
        Pose(self.0.map(|p| p + offset))
    }

    /// Linear blend between two poses (`t` = 0 gives `self`).
    pub fn lerp(&self, other: &Pose, t: f64) -> Pose {
        let mut out = *self;
        for (o, b) in out.0.iter_mut().zip(other.0) {
            *o = o.lerp(b, t);
        }
        out
    }

    /// Facing direction (unit, horizontal) from the hip line: perpendicular to left_hip → right_hip.
    pub fn facing(&self) -> DVec2 {
        let right = (self.get(Joint::RightHip) - self.get(Joint::LeftHip)).truncate();
        DVec2::new(-right.y, right.x).normalize_or(DVec2::Y)
    }

    /// Yaw of the body (0 when facing +y), from the hip line.
    pub fn yaw(&self) -> f64 {
        let f = self.facing();
        (-f.x).atan2(f.y)
    }

    /// Where the palm of the given hand is: past the wrist along the forearm.
    pub fn hand_point(&self, body: &Body, side: Side) -> DVec3 {
        let [_, elbow, wrist] = side.arm();
        let (e, w) = (self.get(elbow), self.get(wrist));
        w + (w - e).normalize_or(DVec3::NEG_Z) * body.hand()
    }
}

/// Solves a two-segment chain from `root` towards `target`: returns (middle joint, end joint).
///
/// The chain bends towards `pole`. An unreachable target is approached along the straight line.
pub fn two_bone_ik(root: DVec3, target: DVec3, l1: f64, l2: f64, pole: DVec3) -> (DVec3, DVec3) {
    let to = target - root;
    let dir = to.normalize_or(DVec3::NEG_Z);
    let d = to.length().clamp((l1 - l2).abs() + 1e-6, l1 + l2 - 1e-6);
    let end = root + dir * d;
    let cos_a = ((l1 * l1 + d * d - l2 * l2) / (2.0 * l1 * d)).clamp(-1.0, 1.0);
    let sin_a = (1.0 - cos_a * cos_a).sqrt();
    let perp = (pole - dir * pole.dot(dir)).normalize_or(dir.any_orthonormal_vector());
    (root + dir * (l1 * cos_a) + perp * (l1 * sin_a), end)
}

/// Standing upright in the body frame, arms hanging.
pub fn stand_local(body: &Body) -> Pose {
    let h = body.stature;
    let mut p = Pose([DVec3::ZERO; 19]);
    p.set(Joint::Pelvis, DVec3::new(0.0, 0.0, body.hip_height() + body.pelvis_above_hips()));
    p.set(Joint::Spine, DVec3::new(0.0, -0.01 * h, 0.64 * h));
    p.set(Joint::Chest, DVec3::new(0.0, -0.005 * h, 0.73 * h));
    p.set(Joint::Neck, DVec3::new(0.0, 0.0, 0.83 * h));
    p.set(Joint::Head, DVec3::new(0.0, 0.01 * h, 0.945 * h));
    for side in [Side::Left, Side::Right] {
        let s = side.sign();
        let [hip, knee, ankle, toe] = side.leg();
        let x = s * body.hip_half_width();
        p.set(hip, DVec3::new(x, 0.0, body.hip_height()));
        p.set(knee, DVec3::new(x, 0.005 * h, body.knee_height()));
        p.set(ankle, DVec3::new(x, 0.0, body.ankle_height()));
        p.set(toe, DVec3::new(x * 1.3, body.foot(), body.foot_radius()));
        let [shoulder, elbow, wrist] = side.arm();
        let sx = s * body.shoulder_half_width();
        let sz = body.shoulder_height();
        p.set(shoulder, DVec3::new(sx, 0.0, sz));
        p.set(elbow, DVec3::new(sx * 1.05, -0.01 * h, sz - body.upper_arm()));
        p.set(wrist, DVec3::new(sx * 1.02, 0.02 * h, sz - body.upper_arm() - body.forearm()));
    }
    p
}

/// Standing at `at` (floor position under the pelvis), facing `yaw`.
pub fn stand(body: &Body, at: DVec2, yaw: f64) -> Pose {
    stand_local(body).placed(at.extend(0.0), yaw)
}

/// Lowest point of the capsules between the listed joint pairs (joint z minus capsule radius).
fn lowest(pose: &Pose, body: &Body, bones: &[(Joint, Joint)]) -> f64 {
    bones
        .iter()
        .map(|&(a, b)| {
            let r = body.bone_radius(a, b).expect("seat bones exist in the default skeleton");
            pose.get(a).z.min(pose.get(b).z) - r
        })
        .fold(f64::INFINITY, f64::min)
}

/// Bones that rest on a seat.
pub const SEAT_BONES: [(Joint, Joint); 5] = [
    (Joint::Pelvis, Joint::Spine),
    (Joint::Pelvis, Joint::LeftHip),
    (Joint::Pelvis, Joint::RightHip),
    (Joint::LeftHip, Joint::LeftKnee),
    (Joint::RightHip, Joint::RightKnee),
];

/// How far a sitter's knees reach past the front edge of a seat deeper than their thighs are long
/// (m): the lower legs hang clear of it. The data seats people so; repair keeps it.
pub const KNEE_OVERHANG: f64 = 0.07;

/// Sitting on a seat whose top is `seat_height` above the floor: the pelvis above `at` (world xy),
/// facing `yaw`, thighs horizontal, lower legs down, feet on the floor where they reach it (they
/// hang on a high seat; the knees rise on a low one), hands resting on the thighs.
pub fn sit(body: &Body, at: DVec2, seat_height: f64, yaw: f64) -> Pose {
    let h = body.stature;
    let mut p = Pose([DVec3::ZERO; 19]);
    let hips_z = 0.0;
    p.set(Joint::Pelvis, DVec3::new(0.0, -0.01 * h, hips_z + body.pelvis_above_hips()));
    // Upper body leaning back 4° about the hip line.
    let lean = 4f64.to_radians();
    let up = DVec3::new(0.0, -lean.sin(), lean.cos());
    let stand = stand_local(body);
    let pelvis0 = stand.get(Joint::Pelvis);
    let pelvis = p.get(Joint::Pelvis);
    let torso = |j: Joint| {
        let d = stand.get(j) - pelvis0;
        pelvis + up * d.z + DVec3::new(d.x, d.y, 0.0)
    };
    for j in [Joint::Spine, Joint::Chest, Joint::Neck, Joint::Head, Joint::LeftShoulder, Joint::RightShoulder] {
        p.set(j, torso(j));
    }
    for side in [Side::Left, Side::Right] {
        let x = side.sign() * body.hip_half_width();
        let [hip, knee, _, _] = side.leg();
        p.set(hip, DVec3::new(x, 0.0, hips_z));
        let spread = 0.2 * x;
        p.set(knee, DVec3::new(x + spread, (body.thigh().powi(2) - spread * spread).sqrt(), hips_z));
    }
    // Rest the seat bones on the seat, then put the feet down.
    let shift = seat_height - lowest(&p, body, &SEAT_BONES);
    p = p.translated(DVec3::Z * shift);
    for side in [Side::Left, Side::Right] {
        let [hip, knee, ankle, toe] = side.leg();
        let k = p.get(knee);
        let floor = DVec3::new(k.x, k.y + 0.02 * h, body.ankle_height());
        let (knee_pos, ankle_pos) = if k.z - floor.z > body.shank() {
            (k, k - DVec3::Z * body.shank())
        } else {
            two_bone_ik(p.get(hip), floor, body.thigh(), body.shank(), DVec3::new(0.0, 0.5, 1.0))
        };
        p.set(knee, knee_pos);
        p.set(ankle, ankle_pos);
        let toe_z = (ankle_pos.z - body.ankle_height() + body.foot_radius()).max(body.foot_radius());
        p.set(toe, DVec3::new(ankle_pos.x * 1.1, ankle_pos.y + body.foot(), toe_z));
        let [shoulder, elbow, wrist] = side.arm();
        let rest = p.get(knee).lerp(p.get(hip), 0.45)
            + DVec3::new(0.0, 0.0, body.bone_radius(hip, knee).unwrap_or(0.0) + 0.02 * h);
        let (e, w) = two_bone_ik(
            p.get(shoulder),
            rest,
            body.upper_arm(),
            body.forearm(),
            DVec3::new(side.sign() * 0.3, -1.0, -0.3),
        );
        p.set(elbow, e);
        p.set(wrist, w);
    }
    p.placed(at.extend(0.0), yaw)
}

/// Lying on the back on a surface `surface_height` above the floor, the pelvis above `at`, the feet
/// towards `yaw`'s facing direction and the head opposite (on a bed with the same yaw, the head lies
/// at the headboard end).
pub fn lie(body: &Body, at: DVec2, surface_height: f64, yaw: f64) -> Pose {
    let stand = stand_local(body);
    let pelvis_z = stand.get(Joint::Pelvis).z;
    // Body up (head) becomes −y, body forward (face) becomes +z.
    let mut p = Pose(stand.0.map(|q| DVec3::new(q.x, -(q.z - pelvis_z), q.y)));
    let all: Vec<(Joint, Joint)> = BODY_BONES.to_vec();
    let shift = surface_height - lowest(&p, body, &all);
    p = p.translated(DVec3::Z * shift);
    p.placed(at.extend(0.0), yaw)
}

/// Every bone of the default skeleton as joint pairs.
pub const BODY_BONES: [(Joint, Joint); 18] = {
    use Joint::*;
    [
        (Pelvis, Spine),
        (Spine, Chest),
        (Chest, Neck),
        (Neck, Head),
        (Pelvis, LeftHip),
        (LeftHip, LeftKnee),
        (LeftKnee, LeftAnkle),
        (LeftAnkle, LeftToe),
        (Pelvis, RightHip),
        (RightHip, RightKnee),
        (RightKnee, RightAnkle),
        (RightAnkle, RightToe),
        (Chest, LeftShoulder),
        (LeftShoulder, LeftElbow),
        (LeftElbow, LeftWrist),
        (Chest, RightShoulder),
        (RightShoulder, RightElbow),
        (RightElbow, RightWrist),
    ]
};

/// Standing and reaching with one hand so that its palm touches `target`, facing `yaw`.
///
/// The feet are placed so the target is at a comfortable reach in front of the shoulder; targets
/// above the reach of the arm are approached as far as the arm allows.
pub fn touch(body: &Body, target: DVec3, yaw: f64, side: Side) -> Pose {
    let mut p = stand_local(body);
    let [shoulder, elbow, wrist] = side.arm();
    let reach = 0.85 * (body.upper_arm() + body.forearm() + body.hand());
    // Bend forward at the hips until a low target is within reach of the shoulder.
    let pelvis = p.get(Joint::Pelvis);
    let bent = |angle: f64, q: DVec3| {
        let d = q - pelvis;
        let (s, c) = angle.sin_cos();
        pelvis + DVec3::new(d.x, d.y * c + d.z * s, -d.y * s + d.z * c)
    };
    let mut angle = 0.0;
    while angle < 80f64.to_radians() && bent(angle, p.get(shoulder)).z - target.z > 0.8 * reach {
        angle += 1f64.to_radians();
    }
    let upper = [Joint::Spine, Joint::Chest, Joint::Neck, Joint::Head];
    for j in upper.into_iter().chain(Side::Left.arm()).chain(Side::Right.arm()) {
        p.set(j, bent(angle, p.get(j)));
    }
    let s = p.get(shoulder);
    let dz = target.z - s.z;
    let ahead = (reach * reach - dz * dz).max(0.0).sqrt().max(0.15 * body.stature);
    // In the body frame the target is straight ahead of the shoulder.
    let target_local = DVec3::new(s.x, s.y + ahead, target.z);
    // Forearm and hand in line: solve for the palm, then put the wrist on the way there.
    let pole = DVec3::new(side.sign(), 0.0, -1.0);
    let (e, palm) = two_bone_ik(s, target_local, body.upper_arm(), body.forearm() + body.hand(), pole);
    p.set(elbow, e);
    p.set(wrist, e + (palm - e).normalize_or(DVec3::NEG_Z) * body.forearm());
    // Put the body-frame target onto the world target.
    let (sn, cs) = yaw.sin_cos();
    let rotated = DVec2::new(cs * target_local.x - sn * target_local.y, sn * target_local.x + cs * target_local.y);
    p.placed((target.truncate() - rotated).extend(0.0), yaw)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(p: &Pose, a: Joint, b: Joint) -> f64 {
        p.get(a).distance(p.get(b))
    }

    #[test]
    fn ik_preserves_lengths_and_reaches() {
        let (m, e) = two_bone_ik(DVec3::ZERO, DVec3::new(0.5, 0.0, 0.0), 0.4, 0.3, DVec3::Z);
        assert!((m.length() - 0.4).abs() < 1e-9);
        assert!((m.distance(e) - 0.3).abs() < 1e-9);
        assert!(e.distance(DVec3::new(0.5, 0.0, 0.0)) < 1e-9);
        assert!(m.z > 0.0, "bends towards the pole");
        let (_, far) = two_bone_ik(DVec3::ZERO, DVec3::new(2.0, 0.0, 0.0), 0.4, 0.3, DVec3::Z);
        assert!((far.x - 0.7).abs() < 1e-5);
    }

    #[test]
    fn sitting_pelvis_rests_on_the_seat_with_level_thighs() {
        let b = Body::default();
        let p = sit(&b, DVec2::new(1.0, 2.0), 0.45, 0.0);
        assert!((lowest(&p, &b, &SEAT_BONES) - 0.45).abs() < 1e-9);
        let (hip, knee) = (p.get(Joint::LeftHip), p.get(Joint::LeftKnee));
        assert!((hip.z - knee.z).abs() < 1e-9, "thigh horizontal");
        assert!(knee.y > hip.y, "thigh points forward (yaw 0 faces +y)");
        assert!((seg(&p, Joint::LeftHip, Joint::LeftKnee) - b.thigh()).abs() < 1e-9);
        assert!((seg(&p, Joint::LeftKnee, Joint::LeftAnkle) - b.shank()).abs() < 1e-6);
        // A 45 cm seat is a little above knee height minus the thigh's thickness: feet near the floor.
        assert!(p.get(Joint::LeftAnkle).z < b.ankle_height() + 0.05);
        assert!((p.yaw()).abs() < 1e-9);
        // A low seat: feet flat on the floor, knees up.
        let low = sit(&b, DVec2::ZERO, 0.35, 0.0);
        assert!((low.get(Joint::RightAnkle).z - b.ankle_height()).abs() < 1e-6);
        assert!((seg(&low, Joint::RightHip, Joint::RightKnee) - b.thigh()).abs() < 1e-6);
    }

    #[test]
    fn lying_body_is_flat_on_the_surface() {
        let b = Body::default();
        let yaw = 1.0;
        let p = lie(&b, DVec2::new(2.0, 2.0), 0.55, yaw);
        assert!((lowest(&p, &b, &BODY_BONES) - 0.55).abs() < 1e-9);
        let head = p.get(Joint::Head);
        assert!(head.z < 0.55 + 0.25, "head is down");
        assert!((p.yaw() - yaw).abs() < 1e-9);
        // The head lies opposite the facing direction.
        let to_head = (head - p.get(Joint::Pelvis)).truncate();
        assert!(to_head.dot(p.facing()) < -0.7 * b.stature * 0.4);
    }

    #[test]
    fn touching_hand_reaches_the_target() {
        let b = Body::default();
        for (target, yaw) in
            [(DVec3::new(1.0, 1.0, 0.75), 0.3), (DVec3::new(-2.0, 0.5, 1.4), -2.0), (DVec3::new(0.0, 0.0, 0.5), 2.0)]
        {
            let p = touch(&b, target, yaw, Side::Right);
            assert!(p.hand_point(&b, Side::Right).distance(target) < 1e-6);
            assert!((seg(&p, Joint::RightShoulder, Joint::RightElbow) - b.upper_arm()).abs() < 1e-9);
            assert!((p.yaw() - yaw).abs() < 1e-9);
        }
    }
}
