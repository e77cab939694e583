//! A human in a scene: a self-describing skeleton, its joint positions per frame and action labels.
//!
//! This is the stored form. Building poses and motions is `crate::human`'s job.

use super::Action;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The joint names every skeleton must have, in the default skeleton's order.
pub const JOINT_NAMES: [&str; 19] = [
    "pelvis",
    "spine",
    "chest",
    "neck",
    "head",
    "left_hip",
    "left_knee",
    "left_ankle",
    "left_toe",
    "right_hip",
    "right_knee",
    "right_ankle",
    "right_toe",
    "left_shoulder",
    "left_elbow",
    "left_wrist",
    "right_shoulder",
    "right_elbow",
    "right_wrist",
];

/// A recorded or generated human motion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Human {
    /// Stable identifier, unique within the scene (`"h0"`, ...).
    pub id: String,
    /// Joint names and capsule bones.
    pub skeleton: Skeleton,
    /// Frames per second of `frames`.
    pub fps: f64,
    /// One entry per frame, one `[x, y, z]` per joint in `skeleton.joints` order.
    pub frames: Vec<Vec<[f64; 3]>>,
    /// Labelled half-open frame ranges.
    pub actions: Vec<ActionSpan>,
}

/// Joint names and the capsules between them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Skeleton {
    /// Joint names; must include the 19 names of [`JOINT_NAMES`].
    pub joints: Vec<String>,
    /// Capsule bones between two joints.
    pub bones: Vec<Bone>,
}

/// A capsule between joints `a` and `b` with the given radius.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bone {
    /// Index of the first joint.
    pub a: usize,
    /// Index of the second joint.
    pub b: usize,
    /// Capsule radius in metres.
    pub radius: f64,
}

/// An action label on frames `[start, end)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActionSpan {
    /// First frame (inclusive).
    pub start: usize,
    /// One past the last frame.
    pub end: usize,
    /// What the human does.
    pub action: Action,
}

impl Skeleton {
    /// Index of the joint called `name`.
    pub fn joint(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j == name)
    }

    /// Bone `k`'s name, its joints' names joined by `-` (`"right_knee-right_ankle"`), as the check's
    /// violations and the input warnings name bones.
    pub fn bone_name(&self, k: usize) -> String {
        let bone = &self.bones[k];
        format!("{}-{}", self.joints[bone.a], self.joints[bone.b])
    }

    /// Largest radius of the bones touching joint `j` (0 when none does).
    pub fn joint_radius(&self, j: usize) -> f64 {
        self.bones.iter().filter(|b| b.a == j || b.b == j).map(|b| b.radius).fold(0.0, f64::max)
    }
}

impl Human {
    /// Joint positions of frame `f` as vectors.
    pub fn frame(&self, f: usize) -> impl Iterator<Item = DVec3> + '_ {
        self.frames[f].iter().map(|&p| DVec3::from(p))
    }

    /// Position of joint `j` in frame `f`.
    pub fn joint_at(&self, f: usize, j: usize) -> DVec3 {
        DVec3::from(self.frames[f][j])
    }

    /// The lowest and the highest point of bone `k`'s capsule in frame `f` (z, m).
    pub fn bone_z_range(&self, f: usize, k: usize) -> (f64, f64) {
        let bone = &self.skeleton.bones[k];
        let (a, b) = (self.joint_at(f, bone.a).z, self.joint_at(f, bone.b).z);
        (a.min(b) - bone.radius, a.max(b) + bone.radius)
    }

    /// The lowest point of the body in frame `f` (z of its lowest capsule's bottom, m): 0 for
    /// someone standing on the floor.
    pub fn lowest_point(&self, f: usize) -> f64 {
        (0..self.skeleton.bones.len()).map(|k| self.bone_z_range(f, k).0).fold(f64::INFINITY, f64::min)
    }

    /// The action label of frame `f`, if any span covers it.
    pub fn action_at(&self, f: usize) -> Option<Action> {
        self.actions.iter().find(|s| (s.start..s.end).contains(&f)).map(|s| s.action)
    }

    /// Spans whose action is a contact action (sit, lie, touch).
    pub fn contact_spans(&self) -> impl Iterator<Item = &ActionSpan> {
        self.actions.iter().filter(|s| s.action.is_contact())
    }

    /// The joint positions of every frame of a contact span, span by span.
    pub fn contact_frames(&self) -> impl Iterator<Item = &Vec<[f64; 3]>> + '_ {
        self.contact_spans().flat_map(|s| self.frames.get(s.start..s.end).unwrap_or(&[]))
    }

    /// Frames labelled walk or stand.
    pub fn free_space_frames(&self) -> impl Iterator<Item = usize> + '_ {
        self.actions.iter().filter(|s| s.action.is_free_space()).flat_map(|s| s.start..s.end)
    }
}
