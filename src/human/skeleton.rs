//! The default skeleton: 19 named joints, 19 capsule bones, proportions that scale with stature.
//!
//! Segment lengths follow the classic stature fractions of Drillis & Contini (hip height 0.530 H,
//! knee 0.285 H, ankle 0.039 H, shoulder 0.818 H, upper arm 0.186 H, forearm 0.146 H, hand 0.108 H);
//! capsule radii are fractions of stature chosen so the capsules fill a typical adult's silhouette.

use crate::scene::{Bone, Skeleton};

pub use crate::scene::JOINT_NAMES;

/// Index of each joint of the default skeleton.
#[allow(missing_docs)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(usize)]
pub enum Joint {
    Pelvis,
    Spine,
    Chest,
    Neck,
    Head,
    LeftHip,
    LeftKnee,
    LeftAnkle,
    LeftToe,
    RightHip,
    RightKnee,
    RightAnkle,
    RightToe,
    LeftShoulder,
    LeftElbow,
    LeftWrist,
    RightShoulder,
    RightElbow,
    RightWrist,
}

impl Joint {
    /// Position in [`JOINT_NAMES`].
    pub const fn index(self) -> usize {
        self as usize
    }
}

/// Left or right.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// The person's left.
    Left,
    /// The person's right.
    Right,
}

impl Side {
    /// (hip, knee, ankle, toe) of this side.
    pub fn leg(self) -> [Joint; 4] {
        match self {
            Side::Left => [Joint::LeftHip, Joint::LeftKnee, Joint::LeftAnkle, Joint::LeftToe],
            Side::Right => [Joint::RightHip, Joint::RightKnee, Joint::RightAnkle, Joint::RightToe],
        }
    }

    /// (shoulder, elbow, wrist) of this side.
    pub fn arm(self) -> [Joint; 3] {
        match self {
            Side::Left => [Joint::LeftShoulder, Joint::LeftElbow, Joint::LeftWrist],
            Side::Right => [Joint::RightShoulder, Joint::RightElbow, Joint::RightWrist],
        }
    }

    /// −1 for left, +1 for right: the sign of the body-frame x coordinate.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => -1.0,
            Side::Right => 1.0,
        }
    }
}

/// The default bones: (joint a, joint b, radius as a fraction of stature).
const BONES: [(Joint, Joint, f64); 19] = {
    use Joint::*;
    [
        (Pelvis, Spine, 0.065),
        (Spine, Chest, 0.068),
        (Chest, Neck, 0.05),
        (Neck, Head, 0.055),
        (Pelvis, LeftHip, 0.05),
        (LeftHip, LeftKnee, 0.04),
        (LeftKnee, LeftAnkle, 0.029),
        (LeftAnkle, LeftToe, 0.022),
        (Pelvis, RightHip, 0.05),
        (RightHip, RightKnee, 0.04),
        (RightKnee, RightAnkle, 0.029),
        (RightAnkle, RightToe, 0.022),
        (Chest, LeftShoulder, 0.035),
        (LeftShoulder, LeftElbow, 0.026),
        (LeftElbow, LeftWrist, 0.021),
        (Chest, RightShoulder, 0.035),
        (RightShoulder, RightElbow, 0.026),
        (RightElbow, RightWrist, 0.021),
        (LeftShoulder, RightShoulder, 0.04),
    ]
};

/// A body of a given stature: segment lengths, joint heights and capsule radii.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// Standing height in metres.
    pub stature: f64,
}

impl Default for Body {
    /// An adult of 1.75 m.
    fn default() -> Body {
        Body { stature: 1.75 }
    }
}

impl Body {
    /// A body of the given stature (metres).
    pub fn new(stature: f64) -> Body {
        Body { stature }
    }

    fn h(&self, fraction: f64) -> f64 {
        self.stature * fraction
    }

    /// Height of the hip joints when standing.
    pub fn hip_height(&self) -> f64 {
        self.h(0.530)
    }
    /// Height of the knee joints when standing.
    pub fn knee_height(&self) -> f64 {
        self.h(0.285)
    }
    /// Height of the ankle joints when standing.
    pub fn ankle_height(&self) -> f64 {
        self.h(0.039)
    }
    /// Hip joint to knee joint.
    pub fn thigh(&self) -> f64 {
        self.hip_height() - self.knee_height()
    }
    /// Knee joint to ankle joint.
    pub fn shank(&self) -> f64 {
        self.knee_height() - self.ankle_height()
    }
    /// Ankle joint to toe joint, horizontally.
    pub fn foot(&self) -> f64 {
        self.h(0.11)
    }
    /// Shoulder joint to elbow joint.
    pub fn upper_arm(&self) -> f64 {
        self.h(0.186)
    }
    /// Elbow joint to wrist joint.
    pub fn forearm(&self) -> f64 {
        self.h(0.146)
    }
    /// Wrist joint to the palm's centre, where a touching hand meets a surface.
    pub fn hand(&self) -> f64 {
        self.h(0.054)
    }
    /// Lateral distance of each hip joint from the body's midline.
    pub fn hip_half_width(&self) -> f64 {
        self.h(0.05)
    }
    /// Lateral distance of each shoulder joint from the midline.
    pub fn shoulder_half_width(&self) -> f64 {
        self.h(0.115)
    }
    /// Height of the shoulder joints when standing.
    pub fn shoulder_height(&self) -> f64 {
        self.h(0.818)
    }
    /// How far the pelvis joint sits above the hip joints.
    pub fn pelvis_above_hips(&self) -> f64 {
        self.h(0.02)
    }

    /// Radius of the capsule between `a` and `b` in the default skeleton, if that bone exists.
    pub fn bone_radius(&self, a: Joint, b: Joint) -> Option<f64> {
        BONES.iter().find(|(x, y, _)| (*x, *y) == (a, b) || (*y, *x) == (a, b)).map(|&(_, _, r)| self.h(r))
    }

    /// Radius of the foot capsule (ankle–toe); the toe joint sits this high above the floor.
    pub fn foot_radius(&self) -> f64 {
        self.h(0.022)
    }

    /// The default skeleton of this body, as stored in scene files.
    pub fn skeleton(&self) -> Skeleton {
        Skeleton {
            joints: JOINT_NAMES.iter().map(|s| s.to_string()).collect(),
            bones: BONES
                .iter()
                .map(|&(a, b, r)| Bone { a: a.index(), b: b.index(), radius: round_mm(self.h(r)) })
                .collect(),
        }
    }
}

/// Rounds to 0.1 mm: stored numbers stay short and byte-stable.
pub fn round_mm(x: f64) -> f64 {
    (x * 1e4).round() / 1e4
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joints_and_bones_are_consistent() {
        for (i, name) in JOINT_NAMES.iter().enumerate() {
            assert!(!name.is_empty());
            assert!(JOINT_NAMES[..i].iter().all(|n| n != name), "{name} twice");
        }
        assert_eq!(Joint::RightWrist.index(), 18);
        let s = Body::default().skeleton();
        assert_eq!(s.bones.len(), 19);
        assert_eq!(s.joint("left_toe"), Some(Joint::LeftToe.index()));
        // Every joint is on some bone.
        for j in 0..19 {
            assert!(s.bones.iter().any(|b| b.a == j || b.b == j), "joint {j} has no bone");
        }
    }

    #[test]
    fn proportions_scale_with_stature() {
        let a = Body::new(1.5);
        let b = Body::new(1.8);
        assert!((b.thigh() / a.thigh() - 1.2).abs() < 1e-12);
        assert!((b.bone_radius(Joint::LeftHip, Joint::LeftKnee).unwrap() / 1.8 - 0.04).abs() < 1e-12);
        // Leg segments add up to the standing hip height.
        assert!((a.thigh() + a.shank() + a.ankle_height() - a.hip_height()).abs() < 1e-12);
    }
}
