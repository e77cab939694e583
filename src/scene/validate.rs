//! The rules of `shade-scene/1` beyond what the JSON shape enforces.
//!
//! Unknown fields, wrong types and unknown category or action names are caught while parsing; this
//! checks values: finiteness, positivity, the floor polygon, ids, skeletons, frames and action ranges.

use super::JOINT_NAMES;
use super::{FORMAT, Human, Problem, ProblemKind, Scene};
use std::collections::HashSet;

/// Smallest floor area (m²) that counts as an area.
const MIN_AREA: f64 = 1e-6;

/// Every problem of `scene`, in document order; empty when the scene is valid.
pub fn validate(scene: &Scene) -> Vec<Problem> {
    let mut out = Problems(Vec::new());
    if scene.format != FORMAT {
        out.push("format", ProblemKind::WrongFormat { found: scene.format.clone() });
    }
    floor_plan(scene, &mut out);
    objects(scene, &mut out);
    let mut ids = HashSet::new();
    for (i, human) in scene.humans.iter().enumerate() {
        let path = format!("humans[{i}]");
        if !ids.insert(human.id.as_str()) {
            out.push(format!("{path}.id"), ProblemKind::DuplicateId { id: human.id.clone() });
        }
        self::human(&path, human, &mut out);
    }
    out.0
}

struct Problems(Vec<Problem>);

impl Problems {
    fn push(&mut self, path: impl Into<String>, kind: ProblemKind) {
        self.0.push(Problem { path: path.into(), kind });
    }

    fn finite(&mut self, path: impl Fn() -> String, values: &[f64]) -> bool {
        let ok = values.iter().all(|v| v.is_finite());
        if !ok {
            self.push(path(), ProblemKind::NotFinite);
        }
        ok
    }

    fn positive(&mut self, path: impl Fn() -> String, value: f64) {
        if !value.is_finite() {
            self.push(path(), ProblemKind::NotFinite);
        } else if value <= 0.0 {
            self.push(path(), ProblemKind::NotPositive { value });
        }
    }
}

fn floor_plan(scene: &Scene, out: &mut Problems) {
    let plan = &scene.floor_plan;
    out.positive(|| "floor_plan.height".into(), plan.height);
    let mut finite = true;
    for (i, p) in plan.polygon.iter().enumerate() {
        finite &= out.finite(|| format!("floor_plan.polygon[{i}]"), p);
    }
    let path = "floor_plan.polygon";
    if plan.polygon.len() < 3 {
        out.push(path, ProblemKind::TooFewVertices { count: plan.polygon.len() });
        return;
    }
    if !finite {
        return;
    }
    let polygon = plan.polygon();
    if polygon.is_degenerate() {
        out.push(path, ProblemKind::ZeroArea);
        return;
    }
    if let Some((a, b)) = polygon.first_self_intersection() {
        out.push(path, ProblemKind::SelfIntersecting { edge_a: a, edge_b: b });
        return;
    }
    let area = polygon.signed_area();
    if area.abs() < MIN_AREA {
        out.push(path, ProblemKind::ZeroArea);
    } else if area < 0.0 {
        out.push(path, ProblemKind::Clockwise);
    }
}

fn objects(scene: &Scene, out: &mut Problems) {
    let mut ids = HashSet::new();
    for (i, o) in scene.objects.iter().enumerate() {
        if !ids.insert(o.id.as_str()) {
            out.push(format!("objects[{i}].id"), ProblemKind::DuplicateId { id: o.id.clone() });
        }
        if scene.room_type.category_index(o.category).is_none() {
            out.push(
                format!("objects[{i}].category"),
                ProblemKind::CategoryNotInRoom { category: o.category, room: scene.room_type },
            );
        }
        out.finite(|| format!("objects[{i}].center"), &o.center);
        for (k, &s) in o.size.iter().enumerate() {
            out.positive(|| format!("objects[{i}].size[{k}]"), s);
        }
        out.finite(|| format!("objects[{i}].yaw"), &[o.yaw]);
    }
}

fn human(path: &str, h: &Human, out: &mut Problems) {
    out.positive(|| format!("{path}.fps"), h.fps);
    let joints = &h.skeleton.joints;
    let mut names = HashSet::new();
    for (j, name) in joints.iter().enumerate() {
        if !names.insert(name.as_str()) {
            out.push(format!("{path}.skeleton.joints[{j}]"), ProblemKind::DuplicateJoint { name: name.clone() });
        }
    }
    for name in JOINT_NAMES {
        if !names.contains(name) {
            out.push(format!("{path}.skeleton.joints"), ProblemKind::MissingJoint { name });
        }
    }
    for (k, bone) in h.skeleton.bones.iter().enumerate() {
        let bone_path = format!("{path}.skeleton.bones[{k}]");
        for index in [bone.a, bone.b] {
            if index >= joints.len() {
                out.push(bone_path.clone(), ProblemKind::BoneOutOfRange { index, joints: joints.len() });
            }
        }
        if bone.a == bone.b {
            out.push(bone_path.clone(), ProblemKind::DegenerateBone);
        }
        out.positive(|| format!("{bone_path}.radius"), bone.radius);
    }
    if h.frames.is_empty() {
        out.push(format!("{path}.frames"), ProblemKind::EmptyMotion);
    }
    for (f, frame) in h.frames.iter().enumerate() {
        if frame.len() != joints.len() {
            out.push(
                format!("{path}.frames[{f}]"),
                ProblemKind::FrameJointCount { expected: joints.len(), got: frame.len() },
            );
        }
        for (j, p) in frame.iter().enumerate() {
            if !out.finite(|| format!("{path}.frames[{f}][{j}]"), p) {
                break;
            }
        }
    }
    for (k, span) in h.actions.iter().enumerate() {
        let span_path = format!("{path}.actions[{k}]");
        if span.start >= span.end || span.end > h.frames.len() {
            out.push(
                span_path,
                ProblemKind::ActionOutOfRange { start: span.start, end: span.end, frames: h.frames.len() },
            );
        } else if let Some(other) = h.actions[..k].iter().position(|o| o.start < span.end && span.start < o.end) {
            out.push(span_path, ProblemKind::OverlappingActions { other });
        }
    }
}
