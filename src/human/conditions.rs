//! Conditioning extracted from a scene's humans (after MIME): the free-space mask, contact boxes
//! and floor-plan points.
//!
//! - Free space: every frame labelled walk or stand draws both feet (the ankle–toe capsule's
//!   shadow) into a 256² mask over the room window, and a body sitting or lying on the floor its
//!   every bone. Unlabelled frames are ignored.
//! - Contact boxes: one oriented box per contact span, yawed like the body (from the hip line),
//!   except for a sitting or lying body that rests on the floor ([`FLOOR_REST`]): no piece holds it;
//!   a person's sit or lie spans that need the same support (the same seat again) share one box.
//!   For sit and lie the box is the *support volume*: the footprint of the resting parts (pelvis and
//!   thighs; the whole body) and the 10 cm just below their lowest surface, where a seat or mattress
//!   must be. For touch it is a 12 cm cube just past the palm along the forearm: the volume the
//!   hand presses on. So a well-supported human has contact IoU ≈ 1, touching ones ≥ 0.5 whatever
//!   the angle of the arm.
//! - Floor plan: points on the boundary with outward normals, then interior grid points, relative
//!   to the window centre, in a fixed count for a PointNet.
//! - Knee boxes: for every sit box, a [`KNEE_BOX_SIDE`] cube standing on the sitter's knees (the
//!   two knees' midpoint in the middle frame of the span), where a table a person sits at reaches
//!   over them. Not a contact: no piece must hold it, `check` and the metrics never read it; models
//!   with table slots anchor a slot to each (`ModelConfig::table_slots`).
//!
//! Works on any skeleton that has the required joint names; it does not look at objects.

use crate::geom::{Mask, OBox, RoomWindow, iou_3d};
use crate::scene::{Action, ActionSpan, Human, Scene, Skeleton};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// Depth of the support volume under a sitting or lying body (m).
pub const SUPPORT_DEPTH: f64 = 0.10;
/// A sitting or lying body whose resting parts are at most this high (m) rests on the floor: the
/// floor holds it, so its span gets no contact box and needs no piece. The same height within
/// which `check` counts a resting body as held (`CheckConfig::support_distance`).
pub const FLOOR_REST: f64 = 0.05;
/// Side of the cube around a touching palm (m).
pub const TOUCH_SIDE: f64 = 0.12;
/// Two sit (or two lie) spans of one person whose support volumes share at least this IoU need one
/// support: their boxes become one. A seat sat on again 10 cm off shares about 0.6; the next place
/// on a sofa, 25 cm along, 0.2.
pub const SAME_SUPPORT_IOU: f64 = 0.5;
/// Palm distance past the wrist as a fraction of the forearm (0.054 H / 0.146 H).
const HAND_PER_FOREARM: f64 = 0.37;
/// Frames looked at per span (evenly spread): enough for slow motions, cheap for long ones.
const FRAMES_PER_SPAN: usize = 32;
/// Side of the cube on a sitter's knees (m): the data's diners have their knees 3 cm under their
/// table's edge and 7 cm past their seat's front, so a 10 cm cube there meets the table and not
/// the seat.
pub const KNEE_BOX_SIDE: f64 = 0.10;

/// A region that must be supported or touched by furniture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactBox {
    /// Id of the human.
    pub human: String,
    /// The contact action (sit, lie or touch).
    pub action: Action,
    /// The frames `[start, end)` it covers.
    pub frames: [usize; 2],
    /// The box.
    #[serde(rename = "box")]
    pub obox: OBox,
}

/// A floor-plan point for a PointNet, relative to the room window's centre.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FloorPoint {
    /// Position relative to the window centre (m).
    pub position: [f64; 2],
    /// Outward normal for boundary points, zero for interior points.
    pub normal: [f64; 2],
}

/// Everything the generator is conditioned on.
#[derive(Debug, Clone, PartialEq)]
pub struct Conditions {
    /// The rasterised room window.
    pub window: RoomWindow,
    /// Floor under walking and standing feet.
    pub free_space: Mask,
    /// The floor plan.
    pub floor: Mask,
    /// Contact boxes of all humans, in human then span order.
    pub contact_boxes: Vec<ContactBox>,
    /// Floor-plan points (boundary first).
    pub floor_points: Vec<FloorPoint>,
    /// A box on each sitter's knees, in the order of their sit boxes ([`knee_box`]).
    pub knee_boxes: Vec<OBox>,
}

impl Conditions {
    /// Boundary and interior floor points used by [`Conditions::of`].
    pub const FLOOR_POINTS: (usize, usize) = (128, 128);

    /// Conditioning of a (validated) scene.
    pub fn of(scene: &Scene) -> Conditions {
        let polygon = scene.floor_plan.polygon();
        let window = scene.room_window();
        let (nb, ni) = Self::FLOOR_POINTS;
        let contact_boxes: Vec<ContactBox> = scene.humans.iter().flat_map(contact_boxes).collect();
        Conditions {
            window,
            free_space: free_space_mask(scene, &window),
            floor: Mask::of_polygon(&window, &polygon),
            knee_boxes: contact_boxes.iter().filter_map(|b| knee_box(scene, b)).collect(),
            contact_boxes,
            floor_points: floor_points(&polygon, &window, nb, ni),
        }
    }
}

impl Conditions {
    /// Only the contact boxes of a scene (cheaper than [`Conditions::of`]).
    pub fn contact_boxes_of(scene: &Scene) -> Vec<ContactBox> {
        scene.humans.iter().flat_map(contact_boxes).collect()
    }
}

/// Where the sitter of a sit box has their knees: the two knees' midpoint in the middle frame of
/// the box's span; `None` for another action or a skeleton without knees.
pub fn knees_of(scene: &Scene, b: &ContactBox) -> Option<DVec3> {
    if b.action != Action::Sit {
        return None;
    }
    let human = scene.humans.iter().find(|h| h.id == b.human)?;
    let (left, right) = (human.skeleton.joint("left_knee")?, human.skeleton.joint("right_knee")?);
    let frame = ((b.frames[0] + b.frames[1]) / 2).min(human.frames.len().checked_sub(1)?);
    Some((human.joint_at(frame, left) + human.joint_at(frame, right)) * 0.5)
}

/// The knee box of a sit box: a [`KNEE_BOX_SIDE`] cube standing on the sitter's knees, yawed as
/// the sit box; `None` where [`knees_of`] has no knees.
pub fn knee_box(scene: &Scene, b: &ContactBox) -> Option<OBox> {
    let knees = knees_of(scene, b)?;
    let centre = knees + DVec3::Z * (KNEE_BOX_SIDE / 2.0);
    Some(OBox::new(centre, DVec3::splat(KNEE_BOX_SIDE), b.obox.yaw))
}

/// The feet of all walking and standing frames of all humans, and the whole body of one resting
/// on the floor.
pub fn free_space_mask(scene: &Scene, window: &RoomWindow) -> Mask {
    let mut mask = Mask::new();
    for human in &scene.humans {
        let feet = feet(&human.skeleton);
        for f in human.free_space_frames() {
            for &(ankle, toe, radius) in &feet {
                let (a, t) = (human.joint_at(f, ankle).truncate(), human.joint_at(f, toe).truncate());
                mask.fill_capsule(window, a, t, radius);
            }
        }
        let resting = |span: &&ActionSpan| contact_volume(human, span).is_some_and(|v| rests_on_floor(span, &v));
        for f in human.contact_spans().filter(resting).flat_map(span_frames) {
            for bone in &human.skeleton.bones {
                let (a, b) = (human.joint_at(f, bone.a).truncate(), human.joint_at(f, bone.b).truncate());
                mask.fill_capsule(window, a, b, bone.radius);
            }
        }
    }
    mask
}

/// (ankle, toe, radius) of both feet.
fn feet(skeleton: &Skeleton) -> Vec<(usize, usize, f64)> {
    ["left", "right"]
        .iter()
        .filter_map(|side| {
            let ankle = skeleton.joint(&format!("{side}_ankle"))?;
            let toe = skeleton.joint(&format!("{side}_toe"))?;
            Some((ankle, toe, radius_between(skeleton, &[ankle, toe]).unwrap_or(0.04)))
        })
        .collect()
}

/// Largest radius of a bone with both ends in `joints`.
fn radius_between(skeleton: &Skeleton, joints: &[usize]) -> Option<f64> {
    skeleton.bones.iter().filter(|b| joints.contains(&b.a) && joints.contains(&b.b)).map(|b| b.radius).reduce(f64::max)
}

/// The contact boxes of one human, one per support it needs: a sit or lie span's box takes in a
/// later span's of the same action whose box shares at least [`SAME_SUPPORT_IOU`] of their volume
/// (the same seat sat on again, a sit split by a moment's shift of weight), so that one seat is one
/// box and one anchored piece. A touch keeps one box per span.
pub fn contact_boxes(human: &Human) -> Vec<ContactBox> {
    let mut boxes: Vec<ContactBox> = Vec::new();
    for b in human.contact_spans().filter_map(|span| contact_box(human, span)) {
        let same = |k: &&mut ContactBox| {
            k.action == b.action && b.action != Action::Touch && iou_3d(&k.obox, &b.obox) >= SAME_SUPPORT_IOU
        };
        match boxes.iter_mut().find(same) {
            Some(k) => {
                k.obox = union_in_frame_of(&k.obox, &b.obox);
                k.frames = [k.frames[0].min(b.frames[0]), k.frames[1].max(b.frames[1])];
            }
            None => boxes.push(b),
        }
    }
    boxes
}

/// The least box in `a`'s frame (its yaw) that holds both `a` and `b`.
fn union_in_frame_of(a: &OBox, b: &OBox) -> OBox {
    let ((a0, a1), (b0, b1)) = (a.z_range(), b.z_range());
    let corners = a.footprint().into_iter().chain(b.footprint());
    let local = corners.flat_map(|p| [a.to_local(p.extend(a0.min(b0))), a.to_local(p.extend(a1.max(b1)))]);
    let (lo, hi) = local.fold((DVec3::MAX, DVec3::MIN), |(lo, hi), p| (lo.min(p), hi.max(p)));
    OBox::new(a.to_world((lo + hi) * 0.5), hi - lo, a.yaw)
}

fn span_frames(span: &ActionSpan) -> impl Iterator<Item = usize> {
    let n = span.end - span.start;
    let k = n.min(FRAMES_PER_SPAN);
    (0..k).map(move |i| span.start + i * n / k)
}

/// Yaw of the body in frame `f`, from the hip line (0 when facing +y).
pub fn body_yaw(human: &Human, f: usize) -> f64 {
    let s = &human.skeleton;
    let (Some(l), Some(r)) = (s.joint("left_hip"), s.joint("right_hip")) else { return 0.0 };
    let right = (human.joint_at(f, r) - human.joint_at(f, l)).truncate();
    let facing = DVec2::new(-right.y, right.x).normalize_or(DVec2::Y);
    (-facing.x).atan2(facing.y)
}

fn contact_box(human: &Human, span: &ActionSpan) -> Option<ContactBox> {
    let obox = contact_volume(human, span)?;
    let frames = [span.start, span.end];
    (!rests_on_floor(span, &obox)).then(|| ContactBox { human: human.id.clone(), action: span.action, frames, obox })
}

/// Whether a span's body rests on the floor: sitting or lying with its support volume's top at
/// most [`FLOOR_REST`] high.
fn rests_on_floor(span: &ActionSpan, volume: &OBox) -> bool {
    matches!(span.action, Action::Sit | Action::Lie) && volume.z_range().1 <= FLOOR_REST
}

/// The volume a span's contact needs filled: under a sitting or lying body, or past a palm.
fn contact_volume(human: &Human, span: &ActionSpan) -> Option<OBox> {
    let s = &human.skeleton;
    let yaw = body_yaw(human, (span.start + span.end) / 2);
    let obox = match span.action {
        Action::Sit => {
            let names = ["pelvis", "left_hip", "right_hip", "left_knee", "right_knee"];
            let joints: Vec<usize> = names.iter().filter_map(|n| s.joint(n)).collect();
            let r = radius_between(s, &joints).unwrap_or(0.07);
            // Buttocks and the back of the thighs rest on the seat; the knees overhang its edge,
            // so a third of each resting thigh counts.
            let (Some(lh), Some(lk), Some(rh), Some(rk), Some(p)) = (
                s.joint("left_hip"),
                s.joint("left_knee"),
                s.joint("right_hip"),
                s.joint("right_knee"),
                s.joint("pelvis"),
            ) else {
                return None;
            };
            let points = |f: usize| {
                let at = |j| human.joint_at(f, j);
                let resting = |hip: usize, knee: usize| {
                    let (h, k) = (at(hip), at(knee));
                    ((h.z - k.z) < RESTING_THIGH_SLOPE * h.distance(k)).then(|| h.lerp(k, SEATED_THIGH))
                };
                let mut out = vec![at(p), at(lh), at(rh)];
                out.extend(resting(lh, lk).into_iter().chain(resting(rh, rk)));
                out
            };
            support_box_of(span, &points, r, yaw)
        }
        Action::Lie => {
            let parts: Vec<(usize, f64)> = (0..s.joints.len()).map(|j| (j, s.joint_radius(j))).collect();
            support_box(human, span, &parts, yaw)
        }
        Action::Touch => {
            let palm = touching_palm(human, span)?;
            OBox::new(palm, DVec3::splat(TOUCH_SIDE), yaw)
        }
        Action::Walk | Action::Stand => return None,
    };
    Some(obox)
}

/// Fraction of the thigh (hip → knee) that rests on a seat.
pub const SEATED_THIGH: f64 = 0.35;
/// A thigh dropping more than this over its length (37°) does not rest on the seat: a real sitter
/// with one knee on the floor or a leg stretched down is held by the buttocks and the other thigh
/// (the synthetic sitters' thighs are level: at most 0.004).
pub const RESTING_THIGH_SLOPE: f64 = 0.6;

/// The support volume under `points(frame)` (each inflated by `r`) over the span's frames.
fn support_box_of(span: &ActionSpan, points: &dyn Fn(usize) -> Vec<DVec3>, r: f64, yaw: f64) -> OBox {
    let (sn, cs) = yaw.sin_cos();
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let mut bottom = f64::INFINITY;
    for f in span_frames(span) {
        for p in points(f) {
            let l = DVec2::new(cs * p.x + sn * p.y, -sn * p.x + cs * p.y);
            lo = lo.min(l - r);
            hi = hi.max(l + r);
            bottom = bottom.min(p.z - r);
        }
    }
    support_obox(lo, hi, bottom, yaw)
}

fn support_obox(lo: DVec2, hi: DVec2, bottom: f64, yaw: f64) -> OBox {
    let (sn, cs) = yaw.sin_cos();
    let mid = (lo + hi) * 0.5;
    let center = DVec2::new(cs * mid.x - sn * mid.y, sn * mid.x + cs * mid.y);
    OBox::new(center.extend(bottom - SUPPORT_DEPTH * 0.5), (hi - lo).extend(SUPPORT_DEPTH), yaw)
}

/// The support volume under the listed (joint, radius) parts over the span's frames.
fn support_box(human: &Human, span: &ActionSpan, parts: &[(usize, f64)], yaw: f64) -> OBox {
    let (sn, cs) = yaw.sin_cos();
    let to_local = |p: DVec2| DVec2::new(cs * p.x + sn * p.y, -sn * p.x + cs * p.y);
    let mut lo = DVec2::splat(f64::INFINITY);
    let mut hi = DVec2::splat(f64::NEG_INFINITY);
    let mut bottom = f64::INFINITY;
    for f in span_frames(span) {
        for &(j, r) in parts {
            let p = human.joint_at(f, j);
            let l = to_local(p.truncate());
            lo = lo.min(l - r);
            hi = hi.max(l + r);
            bottom = bottom.min(p.z - r);
        }
    }
    support_obox(lo, hi, bottom, yaw)
}

/// Where the palm of the `side` (`"left"` / `"right"`) hand is in frame `f`: past the wrist along
/// the forearm by 0.37 forearm lengths (0.054 H / 0.146 H); `None` without elbow and wrist joints.
pub fn palm_of(human: &Human, f: usize, side: &str) -> Option<DVec3> {
    let s = &human.skeleton;
    let e = human.joint_at(f, s.joint(&format!("{side}_elbow"))?);
    let w = human.joint_at(f, s.joint(&format!("{side}_wrist"))?);
    Some(w + (w - e) * HAND_PER_FOREARM)
}

/// Centre of the touch box of the hand that reaches furthest forward during the span: half a box
/// past the palm along the forearm, averaged over the span.
fn touching_palm(human: &Human, span: &ActionSpan) -> Option<DVec3> {
    let s = &human.skeleton;
    let pelvis = s.joint("pelvis")?;
    let mid = (span.start + span.end) / 2;
    let yaw = body_yaw(human, mid);
    let facing = DVec2::new(-yaw.sin(), yaw.cos());
    let palm = |side: &str, f: usize| palm_of(human, f, side);
    // The volume the hand presses on: half a cube past the palm, along the forearm.
    let pressed = |side: &str, f: usize| -> Option<DVec3> {
        let e = human.joint_at(f, s.joint(&format!("{side}_elbow"))?);
        let p = palm(side, f)?;
        Some(p + (p - e).normalize_or(DVec3::NEG_Z) * (TOUCH_SIDE * 0.5))
    };
    let reach = |side: &str| -> Option<f64> {
        let p = palm(side, mid)?;
        Some((p - human.joint_at(mid, pelvis)).truncate().dot(facing))
    };
    let side = match (reach("left"), reach("right")) {
        (Some(l), Some(r)) => {
            if l > r {
                "left"
            } else {
                "right"
            }
        }
        (Some(_), None) => "left",
        (None, Some(_)) => "right",
        (None, None) => return None,
    };
    let frames: Vec<usize> = span_frames(span).collect();
    let sum = frames.iter().filter_map(|&f| pressed(side, f)).fold(DVec3::ZERO, |a, p| a + p);
    Some(sum / frames.len() as f64)
}

/// `boundary` points along the floor-plan boundary (with outward normals) followed by `interior`
/// points of an interior grid, relative to the window centre.
pub fn floor_points(
    polygon: &crate::geom::Polygon,
    window: &RoomWindow,
    boundary: usize,
    interior: usize,
) -> Vec<FloorPoint> {
    let c = window.center;
    let mut out: Vec<FloorPoint> = polygon
        .sample_boundary(boundary)
        .into_iter()
        .map(|b| FloorPoint { position: (b.point - c).to_array(), normal: b.normal.to_array() })
        .collect();
    let area = polygon.area().max(1e-6);
    let grid = polygon.sample_interior((area / (interior as f64 * 2.0)).sqrt());
    if !grid.is_empty() {
        out.extend((0..interior).map(|i| {
            let p = grid[i * grid.len() / interior];
            FloorPoint { position: (p - c).to_array(), normal: [0.0, 0.0] }
        }));
    }
    out
}
