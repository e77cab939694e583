//! The checks: human penetration, human support, furniture overlaps, furniture in walls or outside
//! the floor, and (in `stability`) furniture stability.
//!
//! Penetration depths are exact capsule–box contact depths from parry (GJK/EPA), not the saturating
//! depths physics engines report for deep overlaps.

use super::solids::{Owner, Solid, furniture_solids, wall_solids};
use super::stability::unstable_objects;
use super::{Violation, ViolationKind};
use crate::human::palm_of;
use crate::scene::{Action, Human, Scene};
use glam::DVec3;
use rapier3d::parry::math::Pose;
use rapier3d::parry::query;
use rapier3d::parry::shape::Capsule;
use serde::{Deserialize, Serialize};

/// Settings of a check.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckConfig {
    /// Penetration deeper than this is a violation (m). Default 0.02.
    pub tolerance: f64,
    /// A sitting or lying body needs a surface within this distance below it; a touching palm
    /// within this distance of furniture (m). Default 0.05.
    pub support_distance: f64,
    /// Run the stability simulation. Default true.
    pub stability: bool,
    /// Simulated time for stability (s). Default 2.
    pub stability_seconds: f64,
    /// A piece that moves further than this is unstable (m). Default 0.05.
    pub max_displacement: f64,
    /// A piece that tilts more than this is unstable (degrees). Default 5.
    pub max_tilt_degrees: f64,
    /// How long (s) a walking, standing or touching person's feet may be off the floor, and off
    /// every piece under them, by more than `support_distance` before that is missing support: a
    /// jump's or a run's flight is shorter, a person who stands on something no piece holds (a
    /// climb onto a structure in a capture) is there for longer. Default 0.5.
    pub max_flight_seconds: f64,
}

impl Default for CheckConfig {
    fn default() -> CheckConfig {
        CheckConfig {
            tolerance: 0.02,
            support_distance: 0.05,
            stability: true,
            stability_seconds: 2.0,
            max_displacement: 0.05,
            max_tilt_degrees: 5.0,
            max_flight_seconds: 0.5,
        }
    }
}

/// The check of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CheckReport {
    /// Every violation, by kind, then human / object order, then frame.
    pub violations: Vec<Violation>,
    /// Frames replayed (over all humans).
    pub frames: usize,
}

impl CheckReport {
    /// Whether nothing was found.
    pub fn is_clean(&self) -> bool {
        self.violations.is_empty()
    }

    /// Violations of one kind.
    pub fn count(&self, kind: ViolationKind) -> usize {
        self.violations.iter().filter(|v| v.kind == kind).count()
    }
}

fn owner_id(scene: &Scene, owner: Owner) -> String {
    match owner {
        Owner::Object(i) => scene.objects[i].id.clone(),
        Owner::Wall(i) => format!("wall{i}"),
    }
}

/// What violations name the ceiling by (the floor plan's height): a person's bone in it is a
/// penetration of it (`object`), a piece through it is in it as in a wall (`other`).
pub const CEILING: &str = "ceiling";

/// What violations name the floor by: a person's bone below it (z = 0) is a penetration of it
/// (`object`).
pub const FLOOR: &str = "floor";

/// The violations no layout can mend: the people's bones deeper than `cfg.tolerance` in the walls,
/// the ceiling or the floor (an input whose people stand or sit in a wall, whose heads are above
/// the room's height, or whose knees go through the floor, has no layout that passes
/// [`check_scene`]).
pub fn people_in_walls(scene: &Scene, cfg: &CheckConfig) -> Vec<Violation> {
    let walls = wall_solids(scene);
    let bodies = scene.humans.iter().flat_map(|h| penetrations(scene, h, &walls, cfg.tolerance));
    bodies.chain(scene.humans.iter().flat_map(|h| body_through_floor_or_ceiling(scene, h, cfg.tolerance))).collect()
}

/// A person's bones above the ceiling (the floor plan's height) or below the floor by more than
/// `tolerance`: one penetration of `"ceiling"` or `"floor"` per run of frames where any is, at its
/// deepest bone and frame.
fn body_through_floor_or_ceiling(scene: &Scene, human: &Human, tolerance: f64) -> Vec<Violation> {
    let ceiling = scene.floor_plan.height;
    let above_ceiling = body_beyond(human, tolerance, CEILING, |f, k| human.bone_z_range(f, k).1 - ceiling);
    above_ceiling.into_iter().chain(body_beyond(human, tolerance, FLOOR, |f, k| -human.bone_z_range(f, k).0)).collect()
}

/// The runs of frames where some bone is more than `tolerance` beyond a surface (`depth(frame,
/// bone)`, positive beyond it), as penetrations of `surface`.
fn body_beyond(human: &Human, tolerance: f64, surface: &str, depth: impl Fn(usize, usize) -> f64) -> Vec<Violation> {
    // Per frame: how far the deepest bone is beyond the surface, past the tolerance (0: none), and which.
    let deepest: Vec<(f64, usize)> = (0..human.frames.len())
        .map(|f| {
            let (d, k) = (0..human.skeleton.bones.len())
                .map(|k| (depth(f, k), k))
                .fold((0.0, 0), |m, b| if b.0 > m.0 { b } else { m });
            (if d > tolerance { d } else { 0.0 }, k)
        })
        .collect();
    runs(deepest.iter().map(|d| d.0))
        .into_iter()
        .map(|r| Violation {
            kind: ViolationKind::Penetration,
            human: Some(human.id.clone()),
            bone: Some(human.skeleton.bone_name(deepest[r.worst].1)),
            object: Some(surface.to_string()),
            other: None,
            frame: Some(r.worst),
            frames: Some([r.start, r.end]),
            depth: r.amount,
        })
        .collect()
}

/// A run of consecutive frames in which a per-frame amount (a depth, a height) is above 0.
struct Run {
    /// First frame.
    start: usize,
    /// One past the last frame.
    end: usize,
    /// The frame where the amount is largest.
    worst: usize,
    /// That amount.
    amount: f64,
}

/// The runs of `amounts` (one per frame; 0 where there is nothing), in frame order.
fn runs(amounts: impl IntoIterator<Item = f64>) -> Vec<Run> {
    let mut out = Vec::new();
    let mut open: Option<Run> = None;
    let mut frames = 0;
    for (f, a) in amounts.into_iter().enumerate() {
        frames = f + 1;
        if a > 0.0 {
            match &mut open {
                Some(r) if a > r.amount => (r.worst, r.amount) = (f, a),
                Some(_) => {}
                None => open = Some(Run { start: f, end: f, worst: f, amount: a }),
            }
        } else if let Some(r) = open.take() {
            out.push(Run { end: f, ..r });
        }
    }
    out.extend(open.map(|r| Run { end: frames, ..r }));
    out
}

/// The people of `scene` whose feet are off the floor for longer than a flight in an empty room
/// (the violations `unsupported … feet` of [`footing`] without furniture): someone who climbs onto
/// or stands on something in a capture. No piece the generator places is for standing on, so such
/// an input's layouts fail [`check_scene`] unless a piece happens to stand under the feet.
pub fn people_off_the_floor(scene: &Scene, cfg: &CheckConfig) -> Vec<Violation> {
    scene.humans.iter().flat_map(|h| footing(h, &[], cfg.support_distance, cfg.max_flight_seconds)).collect()
}

/// Runs every check on a (validated) scene.
pub fn check_scene(scene: &Scene, cfg: &CheckConfig) -> CheckReport {
    let furniture = furniture_solids(scene);
    let walls = wall_solids(scene);
    let solids: Vec<Solid> = furniture.iter().chain(&walls).cloned().collect();
    let mut violations = Vec::new();
    let mut frames = 0;
    for human in &scene.humans {
        frames += human.frames.len();
        violations.extend(penetrations(scene, human, &solids, cfg.tolerance));
        violations.extend(body_through_floor_or_ceiling(scene, human, cfg.tolerance));
        violations.extend(support(human, &furniture, cfg.support_distance));
        violations.extend(footing(human, &furniture, cfg.support_distance, cfg.max_flight_seconds));
    }
    violations.extend(furniture_overlaps(scene, &furniture, &walls, cfg.tolerance));
    violations.extend(pieces_through_ceiling(scene, cfg.tolerance));
    violations.extend(outside_floor(scene, cfg.tolerance));
    if cfg.stability {
        violations.extend(unstable_objects(scene, cfg));
    }
    violations.sort_by(|a, b| {
        (a.kind, &a.human, &a.object, a.frame)
            .partial_cmp(&(b.kind, &b.human, &b.object, b.frame))
            .expect("no NaN keys")
    });
    CheckReport { violations, frames }
}

/// Penetration depth of a capsule into a solid (0 when apart).
pub fn capsule_depth(a: DVec3, b: DVec3, radius: f64, solid: &Solid) -> f64 {
    let capsule = Capsule::new(a.as_vec3(), b.as_vec3(), radius as f32);
    match query::contact(&Pose::IDENTITY, &capsule, &solid.pose, &solid.shape, 0.0) {
        Ok(Some(c)) if c.dist < 0.0 => -(c.dist as f64),
        _ => 0.0,
    }
}

/// The penetration depth of a capsule into a solid where it is deeper than `tolerance` (`None`
/// otherwise), with two cheap bounds before parry's exact query: the boxes around both, and the
/// distance from the segment's midpoint.
pub fn capsule_depth_beyond(a: DVec3, b: DVec3, radius: f64, solid: &Solid, tolerance: f64) -> Option<f64> {
    if !solid.near(a.min(b) - radius, a.max(b) + radius, 0.0) {
        return None;
    }
    // The box's signed distance is 1-Lipschitz: if the segment's midpoint is further than half the
    // segment plus the radius plus the tolerance, no point can be deeper.
    if solid.obox.signed_distance((a + b) * 0.5) - a.distance(b) * 0.5 - radius > -tolerance {
        return None;
    }
    Some(capsule_depth(a, b, radius, solid)).filter(|&depth| depth > tolerance)
}

/// Bone penetrations of one human, one violation per (bone, solid) episode at its deepest frame.
///
/// Per frame, only the solids near the whole body's bounding box are tested against its bones.
fn penetrations(scene: &Scene, human: &Human, solids: &[Solid], tolerance: f64) -> Vec<Violation> {
    let sk = &human.skeleton;
    let reach = sk.bones.iter().map(|b| b.radius).fold(0.0, f64::max);
    let n = solids.len();
    // Open episodes per (bone, solid): (start frame, worst frame, worst depth).
    let mut open: Vec<Option<(usize, usize, f64)>> = vec![None; sk.bones.len() * n];
    let mut out = Vec::new();
    let close = |k: usize, ep: (usize, usize, f64), end: usize, out: &mut Vec<Violation>| {
        out.push(Violation {
            kind: ViolationKind::Penetration,
            human: Some(human.id.clone()),
            bone: Some(sk.bone_name(k / n)),
            object: Some(owner_id(scene, solids[k % n].owner)),
            other: None,
            frame: Some(ep.1),
            frames: Some([ep.0, end]),
            depth: ep.2,
        });
    };
    let mut near = Vec::with_capacity(n);
    let mut hit = vec![false; open.len()];
    let (mut open_keys, mut newly): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    for f in 0..human.frames.len() {
        let joints: Vec<DVec3> = human.frame(f).collect();
        let lo = joints.iter().fold(DVec3::splat(f64::INFINITY), |m, &p| m.min(p)) - reach;
        let hi = joints.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, &p| m.max(p)) + reach;
        near.clear();
        near.extend((0..n).filter(|&s| solids[s].near(lo, hi, 0.0)));
        for (b, bone) in sk.bones.iter().enumerate() {
            let (pa, pb) = (joints[bone.a], joints[bone.b]);
            for &s in &near {
                if let Some(depth) = capsule_depth_beyond(pa, pb, bone.radius, &solids[s], tolerance) {
                    let k = b * n + s;
                    hit[k] = true;
                    match &mut open[k] {
                        Some(ep) if depth > ep.2 => {
                            ep.1 = f;
                            ep.2 = depth;
                        }
                        Some(_) => {}
                        None => {
                            open[k] = Some((f, f, depth));
                            newly.push(k);
                        }
                    }
                }
            }
        }
        open_keys.retain(|&k| {
            if hit[k] {
                return true;
            }
            if let Some(ep) = open[k].take() {
                close(k, ep, f, &mut out);
            }
            false
        });
        for &k in &newly {
            open_keys.push(k);
        }
        newly.clear();
        for &k in &open_keys {
            hit[k] = false;
        }
    }
    for (k, ep) in open.into_iter().enumerate() {
        if let Some(ep) = ep {
            close(k, ep, human.frames.len(), &mut out);
        }
    }
    out
}

/// Lowest surface point under a set of joints (joint z minus the largest radius of its bones).
fn lowest_under(human: &Human, f: usize, joints: &[usize]) -> (DVec3, f64) {
    let sk = &human.skeleton;
    let mut best = (DVec3::ZERO, f64::INFINITY);
    for &j in joints {
        let p = human.joint_at(f, j);
        let z = p.z - sk.joint_radius(j);
        if z < best.1 {
            best = (p, z);
        }
    }
    best
}

/// Gap from a body point at height `z` down to the nearest furniture top under `p` (negative when
/// the point is inside a part; infinite when nothing is under it).
fn gap_below(p: DVec3, z: f64, furniture: &[Solid]) -> f64 {
    furniture
        .iter()
        .filter(|s| s.obox.footprint_contains(p.truncate()))
        .map(|s| {
            let (bottom, top) = s.obox.z_range();
            if z < bottom { f64::INFINITY } else { z - top }
        })
        .filter(|g| g.is_finite())
        .fold(f64::INFINITY, |best, g| if g.abs() < best.abs() { g } else { best })
}

/// Missing support of sitting and lying humans and far-off touching hands. The floor holds a
/// body whose resting parts are within `limit` of it (a person sitting or lying on the floor),
/// as a piece's top within `limit` below them does.
pub(super) fn support(human: &Human, furniture: &[Solid], limit: f64) -> Vec<Violation> {
    let sk = &human.skeleton;
    let ids = |names: &[&str]| names.iter().filter_map(|n| sk.joint(n)).collect::<Vec<_>>();
    let mut out = Vec::new();
    for span in human.contact_spans() {
        let mut worst: Option<(usize, f64, &str)> = None;
        for f in span.start..span.end {
            let on_floor = |z: f64| if z <= limit { 0.0 } else { f64::INFINITY };
            let (part, gap) = match span.action {
                Action::Sit => {
                    let (p, z) = lowest_under(human, f, &ids(&["pelvis", "left_hip", "right_hip"]));
                    let pelvis = sk.joint("pelvis").map_or(p, |j| human.joint_at(f, j));
                    ("pelvis", gap_below(pelvis, z, furniture).min(on_floor(z)))
                }
                Action::Lie => {
                    let (p, z) = lowest_under(human, f, &ids(&["pelvis", "spine", "chest"]));
                    let chest = sk.joint("spine").map_or(p, |j| human.joint_at(f, j));
                    ("torso", gap_below(chest, z, furniture).min(on_floor(z)))
                }
                Action::Touch => ("palm", palm_distance(human, f, furniture)),
                Action::Walk | Action::Stand => continue,
            };
            let missing = if gap.is_finite() { gap.max(0.0) } else { f64::INFINITY };
            if missing > limit && worst.is_none_or(|w| missing > w.1) {
                worst = Some((f, missing, part));
            }
        }
        if let Some((f, missing, part)) = worst {
            out.push(Violation {
                kind: ViolationKind::Unsupported,
                human: Some(human.id.clone()),
                bone: Some(part.to_string()),
                object: None,
                other: None,
                frame: Some(f),
                frames: Some([span.start, span.end]),
                depth: if missing.is_finite() { missing } else { -1.0 },
            });
        }
    }
    out
}

/// Feet with nothing under them ([`CheckConfig::max_flight_seconds`]): runs of frames in which
/// a person walks, stands or touches (not sitting or lying, whose feet may hang) and the lowest
/// point of their feet (ankles and toes less their bones' radius) is more than `limit` above the
/// floor and above the top of every piece under it, longer than `max_flight` seconds. One
/// violation per run, at its highest frame; `depth` is that height over what is under the foot.
pub(super) fn footing(human: &Human, furniture: &[Solid], limit: f64, max_flight: f64) -> Vec<Violation> {
    let sk = &human.skeleton;
    let feet: Vec<usize> =
        ["left_ankle", "left_toe", "right_ankle", "right_toe"].iter().filter_map(|n| sk.joint(n)).collect();
    if feet.is_empty() {
        return Vec::new();
    }
    let n = human.frames.len();
    let mut standing = vec![true; n];
    for span in human.actions.iter().filter(|s| matches!(s.action, Action::Sit | Action::Lie)) {
        standing[span.start.min(n)..span.end.min(n)].iter_mut().for_each(|s| *s = false);
    }
    let off = |f: usize| -> f64 {
        let (p, z) = lowest_under(human, f, &feet);
        let gap = gap_below(p, z, furniture).min(z);
        if gap > limit { gap } else { 0.0 }
    };
    let longest = (max_flight * human.fps).floor() as usize;
    // How far each frame's feet are off (0 while held, sitting or lying).
    let heights = standing.iter().enumerate().map(|(f, &s)| if s { off(f) } else { 0.0 });
    runs(heights)
        .into_iter()
        .filter(|r| r.end - r.start > longest)
        .map(|r| Violation {
            kind: ViolationKind::Unsupported,
            human: Some(human.id.clone()),
            bone: Some("feet".to_string()),
            object: None,
            other: None,
            frame: Some(r.worst),
            frames: Some([r.start, r.end]),
            depth: r.amount,
        })
        .collect()
}

/// Distance from the palm of the hand that reaches furthest to the nearest furniture part.
fn palm_distance(human: &Human, f: usize, furniture: &[Solid]) -> f64 {
    let dist = |p: DVec3| furniture.iter().map(|s| s.obox.signed_distance(p)).fold(f64::INFINITY, f64::min);
    ["left", "right"].iter().filter_map(|side| palm_of(human, f, side)).map(dist).fold(f64::INFINITY, f64::min)
}

/// Furniture parts inside other furniture or walls.
fn furniture_overlaps(scene: &Scene, furniture: &[Solid], walls: &[Solid], tolerance: f64) -> Vec<Violation> {
    let mut worst: std::collections::BTreeMap<(Owner, Owner), f64> = std::collections::BTreeMap::new();
    let depth = |a: &Solid, b: &Solid| -> f64 {
        if !a.near(b.aabb.0, b.aabb.1, 0.0) {
            return 0.0;
        }
        match query::contact(&a.pose, &a.shape, &b.pose, &b.shape, 0.0) {
            Ok(Some(c)) if c.dist < 0.0 => -(c.dist as f64),
            _ => 0.0,
        }
    };
    for (i, a) in furniture.iter().enumerate() {
        for b in furniture[i + 1..].iter().chain(walls) {
            if a.owner == b.owner {
                continue;
            }
            let d = depth(a, b);
            if d > tolerance {
                let e = worst.entry((a.owner, b.owner)).or_insert(0.0);
                *e = e.max(d);
            }
        }
    }
    worst
        .into_iter()
        .map(|((a, b), d)| Violation {
            kind: if matches!(b, Owner::Wall(_)) { ViolationKind::ObjectWall } else { ViolationKind::ObjectOverlap },
            human: None,
            bone: None,
            object: Some(owner_id(scene, a)),
            other: Some(owner_id(scene, b)),
            frame: None,
            frames: None,
            depth: d,
        })
        .collect()
}

/// Pieces whose top is above the ceiling (the floor plan's height) by more than the tolerance, as
/// pieces in a wall (`object_wall`, the other being `"ceiling"`): a wardrobe taller than a low room.
fn pieces_through_ceiling(scene: &Scene, tolerance: f64) -> Vec<Violation> {
    let ceiling = scene.floor_plan.height;
    scene
        .objects
        .iter()
        .filter_map(|o| {
            let above = o.center[2] + o.size[2] * 0.5 - ceiling;
            (above > tolerance).then(|| Violation {
                kind: ViolationKind::ObjectWall,
                human: None,
                bone: None,
                object: Some(o.id.clone()),
                other: Some(CEILING.to_string()),
                frame: None,
                frames: None,
                depth: above,
            })
        })
        .collect()
}

/// Pieces whose footprint reaches beyond the floor plan by more than the tolerance.
fn outside_floor(scene: &Scene, tolerance: f64) -> Vec<Violation> {
    let polygon = scene.floor_plan.polygon();
    scene
        .objects
        .iter()
        .filter_map(|o| {
            let out =
                o.obox().footprint().iter().map(|&c| polygon.signed_distance(c)).fold(f64::NEG_INFINITY, f64::max);
            (out > tolerance).then(|| Violation {
                kind: ViolationKind::OutsideFloor,
                human: None,
                bone: None,
                object: Some(o.id.clone()),
                other: None,
                frame: None,
                frames: None,
                depth: out,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::runs;

    #[test]
    fn runs_are_the_stretches_above_zero_with_their_largest_frame() {
        let found: Vec<_> = runs([0.0, 0.2, 0.5, 0.5, 0.0, 0.0, 0.1, 0.3])
            .into_iter()
            .map(|r| (r.start, r.end, r.worst, r.amount))
            .collect();
        // The first run ends at the first 0; the second at the end; ties keep the first frame.
        assert_eq!(found, vec![(1, 4, 2, 0.5), (6, 8, 7, 0.3)]);
        assert!(runs([0.0; 4]).is_empty() && runs(std::iter::empty()).is_empty());
    }
}
