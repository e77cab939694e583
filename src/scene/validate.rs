//! The rules of `shade-scene/1` beyond what the JSON shape enforces.
//!
//! Unknown fields, wrong types and unknown category or action names are caught while parsing; this
//! checks values: finiteness, positivity, the physical bounds of [`SceneLimits::FORMAT`], the floor
//! polygon, ids, skeletons, frames and action ranges. The cost is linear in the file's numbers, but
//! for the polygon's self-intersection test, which runs only within the vertex limit.

use super::JOINT_NAMES;
use super::{FORMAT, FloorPlan, Human, Problem, ProblemKind, Scene, SceneLimits};
use std::collections::HashSet;

const LIMITS: SceneLimits = SceneLimits::FORMAT;

/// The floor plan's bounding box and height, where they are valid numbers: what objects and joints
/// are measured against.
#[derive(Clone, Copy)]
struct RoomBounds {
    min: [f64; 2],
    max: [f64; 2],
    height: f64,
}

impl RoomBounds {
    fn of(plan: &FloorPlan) -> Option<RoomBounds> {
        if plan.polygon.is_empty() || !plan.height.is_finite() || plan.polygon.iter().flatten().any(|v| !v.is_finite())
        {
            return None;
        }
        let mut b = RoomBounds { min: [f64::INFINITY; 2], max: [f64::NEG_INFINITY; 2], height: plan.height.max(0.0) };
        for p in &plan.polygon {
            for ((lo, hi), &v) in b.min.iter_mut().zip(&mut b.max).zip(p) {
                (*lo, *hi) = (lo.min(v), hi.max(v));
            }
        }
        Some(b)
    }

    /// The allowed range of coordinate `k` (0 x, 1 y, 2 z) `margin` beyond the room.
    fn range(&self, k: usize, margin: f64) -> (f64, f64) {
        if k == 2 { (-margin, self.height + margin) } else { (self.min[k] - margin, self.max[k] + margin) }
    }

    /// The first coordinate of `p` outside the room grown by `margin`, with its range.
    fn outside(&self, p: &[f64; 3], margin: f64) -> Option<(usize, f64, f64)> {
        (0..3).find_map(|k| {
            let (lo, hi) = self.range(k, margin);
            (!(lo..=hi).contains(&p[k])).then_some((k, lo, hi))
        })
    }
}

/// Smallest floor area (m²) that counts as an area.
const MIN_AREA: f64 = 1e-6;

/// Every problem of `scene`, in document order; empty when the scene is valid.
pub fn validate(scene: &Scene) -> Vec<Problem> {
    let mut out = Problems(Vec::new());
    if scene.format != FORMAT {
        out.push("format", ProblemKind::WrongFormat { found: scene.format.clone() });
    }
    let room = RoomBounds::of(&scene.floor_plan);
    floor_plan(&scene.floor_plan, room, &mut out);
    objects(scene, room, &mut out);
    out.at_most("humans", "humans", scene.humans.len(), LIMITS.max_humans);
    let total_frames: usize = scene.humans.iter().map(|h| h.frames.len()).sum();
    out.at_most("humans", "frames in all", total_frames, LIMITS.max_total_frames);
    let mut ids = HashSet::new();
    for (i, human) in scene.humans.iter().enumerate() {
        let path = format!("humans[{i}]");
        if !ids.insert(human.id.as_str()) {
            out.push(format!("{path}.id"), ProblemKind::DuplicateId { id: human.id.clone() });
        }
        self::human(&path, human, room, &mut out);
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

    /// A finite, positive value of at most `max`.
    fn positive(&mut self, path: impl Fn() -> String, value: f64, max: f64) {
        if !value.is_finite() {
            self.push(path(), ProblemKind::NotFinite);
        } else if value <= 0.0 {
            self.push(path(), ProblemKind::NotPositive { value });
        } else if value > max {
            self.push(path(), ProblemKind::OutOfRange { value, min: 0.0, max });
        }
    }

    /// A finite value within `min..=max`.
    fn within(&mut self, path: impl Fn() -> String, value: f64, min: f64, max: f64) {
        if !value.is_finite() {
            self.push(path(), ProblemKind::NotFinite);
        } else if !(min..=max).contains(&value) {
            self.push(path(), ProblemKind::OutOfRange { value, min, max });
        }
    }

    /// At most `max` of `what`; false when there are more.
    fn at_most(&mut self, path: &str, what: &'static str, count: usize, max: usize) -> bool {
        if count > max {
            self.push(path, ProblemKind::TooMany { what, count, max });
        }
        count <= max
    }
}

/// Every problem of a floor plan on its own (a plan given apart from a scene: `import-motion
/// --floor PLAN.json`, Python's `floor=`), as [`validate`] reports them in a scene.
pub fn validate_floor_plan(plan: &FloorPlan) -> Vec<Problem> {
    let mut out = Problems(Vec::new());
    floor_plan(plan, RoomBounds::of(plan), &mut out);
    out.0
}

fn floor_plan(plan: &FloorPlan, room: Option<RoomBounds>, out: &mut Problems) {
    out.positive(|| "floor_plan.height".into(), plan.height, LIMITS.max_height);
    let path = "floor_plan.polygon";
    if !out.at_most(path, "floor polygon vertices", plan.polygon.len(), LIMITS.max_vertices) {
        return;
    }
    let mut finite = true;
    for (i, p) in plan.polygon.iter().enumerate() {
        if out.finite(|| format!("floor_plan.polygon[{i}]"), p) {
            for (k, &v) in p.iter().enumerate() {
                out.within(
                    || format!("floor_plan.polygon[{i}][{k}]"),
                    v,
                    -LIMITS.max_coordinate,
                    LIMITS.max_coordinate,
                );
            }
        } else {
            finite = false;
        }
    }
    if plan.polygon.len() < 3 {
        out.push(path, ProblemKind::TooFewVertices { count: plan.polygon.len() });
        return;
    }
    if !finite {
        return;
    }
    if let Some(room) = room {
        for k in 0..2 {
            let side = room.max[k] - room.min[k];
            if side > LIMITS.max_room_side {
                out.push(path, ProblemKind::OutOfRange { value: side, min: 0.0, max: LIMITS.max_room_side });
                return;
            }
        }
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

fn objects(scene: &Scene, room: Option<RoomBounds>, out: &mut Problems) {
    out.at_most("objects", "objects", scene.objects.len(), scene.room_type.max_objects());
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
        if out.finite(|| format!("objects[{i}].center"), &o.center) {
            if let Some((k, lo, hi)) = room.and_then(|r| r.outside(&o.center, LIMITS.object_margin)) {
                out.push(
                    format!("objects[{i}].center[{k}]"),
                    ProblemKind::OutOfRange { value: o.center[k], min: lo, max: hi },
                );
            }
        }
        for (k, &s) in o.size.iter().enumerate() {
            out.positive(|| format!("objects[{i}].size[{k}]"), s, LIMITS.max_object_size);
        }
        out.within(|| format!("objects[{i}].yaw"), o.yaw, -LIMITS.max_yaw, LIMITS.max_yaw);
    }
}

fn human(path: &str, h: &Human, room: Option<RoomBounds>, out: &mut Problems) {
    out.positive(|| format!("{path}.fps"), h.fps, LIMITS.max_fps);
    let joints = &h.skeleton.joints;
    out.at_most(&format!("{path}.skeleton.joints"), "joints", joints.len(), LIMITS.max_joints);
    out.at_most(&format!("{path}.skeleton.bones"), "bones", h.skeleton.bones.len(), LIMITS.max_bones);
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
        out.positive(|| format!("{bone_path}.radius"), bone.radius, LIMITS.max_bone_radius);
    }
    if h.frames.is_empty() {
        out.push(format!("{path}.frames"), ProblemKind::EmptyMotion);
    }
    let mut far_joint = false;
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
            if let Some((k, lo, hi)) = room.and_then(|r| r.outside(p, LIMITS.joint_margin)) {
                // One such problem per human: a motion in the wrong place is wrong in every frame.
                if !far_joint {
                    out.push(
                        format!("{path}.frames[{f}][{j}][{k}]"),
                        ProblemKind::OutOfRange { value: p[k], min: lo, max: hi },
                    );
                }
                far_joint = true;
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
