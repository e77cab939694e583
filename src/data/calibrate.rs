//! SHADE's calibration of contact humans: translation modification, category augmentation and
//! orientation augmentation.
//!
//! - Translation modification: for each contact human, find its contact object (the piece that
//!   affords its action and covers its contact box most, else the nearest such piece within 2 m),
//!   compute the translation that puts the contact box onto the piece (sit, lie: the support volume
//!   right under the template's seat or mattress surface; touch: the palm on the nearest face, moved
//!   across the floor, the person standing on it), then
//!   search small corrections around it until E_pen is below [`SAFE_PENETRATION`] and the contact
//!   IoU reaches 0.9 (sit, lie) or 0.5 (touch). Translations beyond ±2 m are refused; humans that
//!   cannot be fixed are reported and left as they were.
//! - Category augmentation: half of the contact humans whose piece affords another action are
//!   replaced by that action (lying ↔ sitting on beds; sitting → lying on sofas long enough).
//! - Orientation augmentation: every contact human turns by a random yaw (σ = 10°) about its pelvis,
//!   then translation modification runs again.
//!
//! With `people_apart`, neither the translation nor an augmentation may put a person inside
//! another (`human::people_meeting`, by more than [`MAX_POINT_DEPTH`]): a sitter turned into a
//! sleeper along a sofa where two more people sit stays a sitter, a turn into the next sitter is not
//! made, and a person the translation would put inside someone stays where they were, unfixed.
//! (Without it, 11–14 % of the calibrated living and dining rooms held two people inside each
//! other, most of them a sleeper along a sofa where others sit.)

use super::Rng;
use super::layout::Placed;
use super::people::{contact_pose, translate};
use crate::furniture::template;
use crate::geom::OBox;
use crate::human::{Motion, SurfaceSampler, contact_boxes, meets_anyone, round_mm};
use crate::measure::{FurnitureField, contact_iou};
use crate::physics::Physics;
use crate::scene::{Action, Group, Human, Object, Scene};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};

/// E_pen (Σ metres over ≈ 1,000 surface points) below which a contact human counts as resting, not
/// sunk.
pub const SAFE_PENETRATION: f64 = 0.5;
/// Deepest any body-surface point of a calibrated human may be inside furniture (the physics
/// check's default tolerance).
pub const MAX_POINT_DEPTH: f64 = 0.02;
/// Largest translation searched, per axis.
pub const MAX_TRANSLATION: f64 = 2.0;
/// Surface points used while searching (the final figures use 1,000).
const SEARCH_POINTS: usize = 250;

/// The contact IoU a fixed human must reach.
pub fn iou_target(action: Action) -> f64 {
    if action == Action::Touch { 0.5 } else { 0.9 }
}

/// What calibration did to one contact human.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HumanCalibration {
    /// The human's id.
    pub human: String,
    /// Its action before calibration.
    pub action_before: Action,
    /// Its action after (differs when category augmentation replaced it).
    pub action: Action,
    /// Id of its contact object, if one was found.
    pub object: Option<String>,
    /// E_pen before and after.
    pub penetration: [f64; 2],
    /// Contact IoU before and after.
    pub iou: [f64; 2],
    /// The final translation applied.
    pub translation: [f64; 3],
    /// Whether the human now rests within the bounds (E_pen and IoU targets met).
    pub fixed: bool,
    /// Why not, when not.
    pub problem: Option<String>,
    /// Whether the human was left out of the calibrated scene: checked calibration found no
    /// placement the check passes even with them alone in the room.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub left_out: bool,
}

/// A calibrated scene and what happened to each contact human.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneCalibration {
    /// The calibrated scene.
    pub scene: Scene,
    /// One record per contact human, in scene order.
    pub humans: Vec<HumanCalibration>,
}

struct Judge<'a> {
    field: FurnitureField,
    objects: &'a [Object],
    /// The scene being calibrated and the check a placement must pass, when calibration is
    /// checked (`calibrate --require-clean`).
    check: Option<(&'a Scene, &'a dyn Physics)>,
}

impl Judge<'_> {
    fn contact(&self, h: &Human) -> Option<(Action, OBox)> {
        contact_boxes(h).first().map(|b| (b.action, b.obox))
    }

    /// Whether the check passes `h` alone with the scene's furniture (always, unchecked).
    fn passes(&self, h: &Human) -> bool {
        self.check.is_none_or(|(scene, physics)| passes_alone(scene, h, physics))
    }
}

/// Whether `physics`' check passes `h` alone with `scene`'s floor plan and furniture.
pub fn passes_alone(scene: &Scene, h: &Human, physics: &dyn Physics) -> bool {
    let mut alone = Scene::new(scene.room_type, scene.floor_plan.clone());
    alone.objects = scene.objects.clone();
    alone.humans = vec![h.clone()];
    physics.passes_check(&alone)
}

/// Placements that meet the E_pen and IoU bounds the check may refuse before the nearest of them is
/// taken anyway (checked calibration).
const CHECKED_CANDIDATES: usize = 12;

/// The piece a contact box belongs to: the affording piece covering it most, else the nearest one
/// within 2 m.
pub fn contact_object(objects: &[Object], action: Action, b: &OBox) -> Option<usize> {
    let affording: Vec<usize> = (0..objects.len()).filter(|&i| objects[i].category.affords(action)).collect();
    let cover = |i: &usize| crate::geom::intersection_volume(b, &objects[*i].obox());
    if let Some(&best) = affording.iter().filter(|i| cover(i) > 0.0).max_by(|x, y| cover(x).total_cmp(&cover(y))) {
        return Some(best);
    }
    let dist = |i: &usize| objects[*i].obox().footprint_signed_distance(b.center.truncate());
    affording.into_iter().filter(|i| dist(i) <= MAX_TRANSLATION).min_by(|x, y| dist(x).total_cmp(&dist(y)))
}

/// The translation that puts a contact box onto its piece (before the local search).
fn target_translation(b: &OBox, action: Action, object: &Object) -> Option<DVec3> {
    let ob = object.obox();
    match action {
        Action::Sit | Action::Lie => {
            let s = template(object).surface?;
            let dz = s.height - b.z_range().1;
            let corners: Vec<DVec2> = b.footprint().iter().map(|c| ob.to_local(c.extend(0.0)).truncate()).collect();
            let lo = corners.iter().fold(DVec2::splat(f64::INFINITY), |m, &c| m.min(c));
            let hi = corners.iter().fold(DVec2::splat(f64::NEG_INFINITY), |m, &c| m.max(c));
            // Inside the piece's footprint (the contact IoU's reference), on its surface.
            let margin = 0.02;
            let half = ob.half().truncate();
            let (rmin, rmax) = (-half + margin, half - margin);
            let axis = |lo: f64, hi: f64, rmin: f64, rmax: f64| {
                if hi - lo > rmax - rmin {
                    (rmin + rmax) * 0.5 - (lo + hi) * 0.5
                } else {
                    (rmin - lo).max(0.0) + (rmax - hi).min(0.0)
                }
            };
            let local = DVec2::new(axis(lo.x, hi.x, rmin.x, rmax.x), axis(lo.y, hi.y, rmin.y, rmax.y));
            let world = ob.to_world(local.extend(0.0)) - ob.to_world(DVec3::ZERO);
            Some(world.truncate().extend(dz))
        }
        Action::Touch => {
            let q = ob.to_local(b.center);
            let h = ob.half();
            let mut s = q.clamp(-h, h);
            let inside = q.abs().cmple(h).all();
            if inside {
                // Out through the nearest face.
                let gap = h - q.abs();
                let a = if gap.x <= gap.y && gap.x <= gap.z {
                    0
                } else if gap.y <= gap.z {
                    1
                } else {
                    2
                };
                s[a] = h[a] * q[a].signum();
            }
            // The face the point lies on; the pressed volume goes just inside it (the palm on the
            // face when the forearm meets it square).
            let rel = (s / h).abs();
            let a = if rel.x >= rel.y && rel.x >= rel.z {
                0
            } else if rel.y >= rel.z {
                1
            } else {
                2
            };
            s[a] -= (b.size[a] * 0.5 + 0.005).min(h[a]) * s[a].signum();
            Some(ob.to_world(s) - b.center)
        }
        Action::Walk | Action::Stand => None,
    }
}

/// Translation modification of one human against `objects` (the human is moved in place).
/// Returns (object index, translation applied, fixed, problem).
fn fix_translation(h: &mut Human, judge: &Judge) -> (Option<usize>, DVec3, bool, Option<String>) {
    let Some((action, b)) = judge.contact(h) else { return (None, DVec3::ZERO, false, Some("no contact box".into())) };
    let Some(obj) = contact_object(judge.objects, action, &b) else {
        return (None, DVec3::ZERO, false, Some(format!("no piece that affords {action} within 2 m")));
    };
    let Some(mut base) = target_translation(&b, action, &judge.objects[obj]) else {
        return (Some(obj), DVec3::ZERO, false, Some("the piece has no surface".into()));
    };
    let f = h.contact_spans().next().map_or(0, |s| (s.start + s.end) / 2);
    if action == Action::Touch {
        // A toucher stands: the translation puts their lowest bone back on the floor, as the
        // touch pose was drawn, and moves the palm onto the face across the floor only. (Moving
        // it in 3D put the palm on a front face at the height it was misplaced to, and left 5 % of
        // the calibrated bedrooms and 13 % of the dining rooms with a foot up to 18 cm in the
        // floor.)
        base.z = -h.lowest_point(f);
    }
    // Surface points of the contact frame, sampled once: a translation moves them rigidly.
    let joints: Vec<DVec3> = h.frame(f).collect();
    let sampler = SurfaceSampler::new(&h.skeleton, &joints, SEARCH_POINTS);
    let points = sampler.points(&h.skeleton, &joints);
    let scale = crate::measure::SURFACE_POINTS as f64 / points.len().max(1) as f64;
    // E_pen (scaled to 1,000 points), or infinity when any point is deeper than the physics
    // check's tolerance: a resting body may press into a cushion, not sink through it.
    let penetration = |t: DVec3| -> f64 {
        let mut sum = 0.0;
        for &p in &points {
            let d = judge.field.signed_distance(p + t);
            if d < -MAX_POINT_DEPTH {
                return f64::INFINITY;
            }
            if d < 0.0 {
                sum -= d;
            }
        }
        sum * scale
    };
    let iou = |t: DVec3| contact_iou(&OBox::new(b.center + t, b.size, b.yaw), judge.objects);
    // Corrections around the target, nearest first: 3 cm steps within ±0.3 m, then 6 cm steps
    // within ±1 m, each at three heights.
    let ob = judge.objects[obj].obox();
    let mut offsets: Vec<DVec3> = Vec::new();
    for (step, n) in [(0.03, 10i32), (0.06, 16)] {
        for i in -n..=n {
            for j in -n..=n {
                let local = DVec2::new(i as f64 * step, j as f64 * step);
                let xy = (ob.to_world(local.extend(0.0)) - ob.to_world(DVec3::ZERO)).truncate();
                for k in 0..3 {
                    offsets.push(xy.extend(k as f64 * 0.01));
                }
            }
        }
    }
    offsets.sort_by(|a, c| a.length_squared().total_cmp(&c.length_squared()));
    let candidates: Vec<DVec3> = offsets
        .into_iter()
        .map(|d| base + d)
        .filter(|t| t.abs().max_element() <= MAX_TRANSLATION)
        .filter(|&t| iou(t) >= iou_target(action))
        .collect();
    // First a resting placement (a tenth of the bound), then one within the bound; checked, the
    // nearest of the first few that the check passes, else the nearest.
    for bound in [0.1 * SAFE_PENETRATION, SAFE_PENETRATION] {
        let resting: Vec<DVec3> =
            candidates.iter().copied().filter(|&t| penetration(t) < bound).take(CHECKED_CANDIDATES).collect();
        let moved = |t: DVec3| {
            let mut moved = h.clone();
            translate(&mut moved, t);
            moved
        };
        let Some(&nearest) = resting.first() else { continue };
        let t = resting.iter().copied().find(|&t| judge.passes(&moved(t))).unwrap_or(nearest);
        translate(h, t);
        return (Some(obj), t, true, None);
    }
    (Some(obj), DVec3::ZERO, false, Some("no translation within ±2 m meets the E_pen and IoU bounds".into()))
}

/// Turns a human by `yaw` about the vertical through its pelvis (first frame).
fn turn(h: &mut Human, yaw: f64) {
    let Some(p) = h.skeleton.joint("pelvis") else { return };
    let pivot = h.joint_at(0, p).truncate();
    let (s, c) = yaw.sin_cos();
    for frame in &mut h.frames {
        for q in frame.iter_mut() {
            let d = DVec2::new(q[0], q[1]) - pivot;
            let r = pivot + DVec2::new(c * d.x - s * d.y, s * d.x + c * d.y);
            *q = [round_mm(r.x), round_mm(r.y), q[2]];
        }
    }
}

/// The other action a piece affords for category augmentation, if any.
fn alternative(object: &Object, action: Action) -> Option<Action> {
    match (object.category.group(), action) {
        (Group::Bed, Action::Lie) => Some(Action::Sit),
        (Group::Bed, Action::Sit) => Some(Action::Lie),
        (Group::Sofa, Action::Sit) if object.size[0] >= 1.6 => Some(Action::Lie),
        _ => None,
    }
}

/// Calibrates one scene; `rng` drives the augmentations, which run only with `augment`
/// (translation modification always does). With `check`, each human's placement is the nearest
/// of the first few within the bounds that the check passes with that human alone in the room.
/// With `people_apart`, no one is put inside another (module header).
pub fn calibrate_scene(
    scene: &Scene,
    rng: &mut Rng,
    augment: bool,
    check: Option<&dyn Physics>,
    people_apart: bool,
) -> SceneCalibration {
    let judge = Judge {
        field: FurnitureField::new(&scene.objects),
        objects: &scene.objects,
        check: check.map(|physics| (scene, physics)),
    };
    let mut out = scene.clone();
    let mut records = Vec::new();
    for k in 0..out.humans.len() {
        // This human, and everyone else as they stand now (calibrated before it, or not yet).
        let (earlier, rest) = out.humans.split_at_mut(k);
        let (h, later) = rest.split_first_mut().expect("k is a human's index");
        let (earlier, later) = (&*earlier, &*later);
        let apart = |h: &Human| !people_apart || !meets_anyone(h, earlier.iter().chain(later), MAX_POINT_DEPTH);
        let Some((action_before, b)) = judge.contact(h) else { continue };
        let before = (crate::measure::human_penetration(h, &judge.field), contact_iou(&b, &scene.objects));
        let original = h.clone();
        // 1. Translation modification.
        let (mut object, mut t, mut fixed, mut problem) = fix_translation(h, &judge);
        if fixed && !apart(h) && apart(&original) {
            // Put inside someone: left where it was, as a human calibration cannot fix.
            (fixed, problem) = (false, Some("inside another person where calibration puts them".into()));
        }
        let mut action = action_before;
        // 2. Category augmentation on half of the humans whose piece affords another action.
        if let Some(o) = object.filter(|_| fixed && augment)
            && let Some(alt) = alternative(&scene.objects[o], action)
            && rng.chance(0.5)
        {
            let piece = Placed {
                category: scene.objects[o].category,
                obox: scene.objects[o].obox(),
                access: Vec::new(),
                anchor: None,
            };
            if let Some((body, pose)) = contact_pose(&piece, alt, rng.uniform(-1.0, 1.0), rng) {
                let mut m = Motion::new(body, h.fps);
                m.hold(pose, 1, alt);
                let mut replaced = m.into_human(h.id.clone());
                let (o2, t2, ok, _) = fix_translation(&mut replaced, &judge);
                if ok && o2 == Some(o) && apart(&replaced) {
                    *h = replaced;
                    action = alt;
                    t = t2;
                }
            }
        }
        // 3. Orientation augmentation, then translation modification again.
        if fixed && augment {
            let kept = h.clone();
            turn(h, (10.0 * rng.normal()).to_radians());
            let (o3, t3, ok, p3) = fix_translation(h, &judge);
            if ok && (apart(h) || !apart(&kept)) {
                object = o3;
                t += t3;
            } else if ok {
                *h = kept;
            } else {
                *h = kept;
                problem = p3.map(|p| format!("after turning: {p}"));
            }
        } else if !fixed {
            *h = original;
        }
        let after_box = judge.contact(h).map(|(_, b)| b);
        let after = (
            crate::measure::human_penetration(h, &judge.field),
            after_box.map_or(0.0, |b| contact_iou(&b, &scene.objects)),
        );
        fixed = fixed && after.0 < SAFE_PENETRATION * 1.5 && after.1 >= iou_target(action) - 1e-9;
        records.push(HumanCalibration {
            human: h.id.clone(),
            action_before,
            action,
            object: object.map(|o| scene.objects[o].id.clone()),
            penetration: [before.0, after.0],
            iou: [before.1, after.1],
            translation: t.to_array().map(round_mm),
            fixed,
            problem: if fixed { None } else { problem.or(Some("bounds not met after augmentation".into())) },
            left_out: false,
        });
    }
    SceneCalibration { scene: out, humans: records }
}
