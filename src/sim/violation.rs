//! What a physical check finds: typed violations, as data.

use serde::{Deserialize, Serialize};

/// The kinds of violation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ViolationKind {
    /// A human bone deeper than the tolerance in furniture or a wall.
    Penetration,
    /// A sitting or lying human without a surface under it, a touching hand far from furniture, or
    /// feet off the floor and every piece for longer than a flight (`bone` "feet").
    Unsupported,
    /// Two pieces of furniture inside each other.
    ObjectOverlap,
    /// A piece of furniture inside a wall, or through the ceiling (`other` "ceiling").
    ObjectWall,
    /// A piece of furniture outside the floor plan.
    OutsideFloor,
    /// A piece that moves or tilts when simulated under gravity with the humans present.
    Unstable,
}

impl ViolationKind {
    /// All kinds, in report order.
    pub const ALL: [ViolationKind; 6] = [
        ViolationKind::Penetration,
        ViolationKind::Unsupported,
        ViolationKind::ObjectOverlap,
        ViolationKind::ObjectWall,
        ViolationKind::OutsideFloor,
        ViolationKind::Unstable,
    ];

    /// The name used in reports.
    pub fn name(self) -> &'static str {
        match self {
            ViolationKind::Penetration => "penetration",
            ViolationKind::Unsupported => "unsupported",
            ViolationKind::ObjectOverlap => "object_overlap",
            ViolationKind::ObjectWall => "object_wall",
            ViolationKind::OutsideFloor => "outside_floor",
            ViolationKind::Unstable => "unstable",
        }
    }
}

/// One violation. Human penetrations are reported once per (human, bone, object) episode of
/// consecutive frames, at its deepest frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Violation {
    /// What is wrong.
    pub kind: ViolationKind,
    /// The human's id, for human violations.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub human: Option<String>,
    /// The bone (`"left_knee-left_ankle"`) or body part (`"pelvis"`, `"palm"`).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub bone: Option<String>,
    /// The object's id (or `"wall3"` for the wall on floor-plan edge 3).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub object: Option<String>,
    /// The second object, for overlaps.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub other: Option<String>,
    /// The worst frame.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub frame: Option<usize>,
    /// The frames `[start, end)` of the episode.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub frames: Option<[usize; 2]>,
    /// Penetration depth, missing-support distance, distance outside, displacement (m) or tilt
    /// (degrees, for `unstable` when larger than the displacement limit's meaning).
    pub depth: f64,
}
