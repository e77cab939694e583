//! How one piece meets the people of its scene ([`PieceFit`]), for a repair that tries many
//! shapes of one piece: the check's exact capsule depths against that piece's parts only, and the
//! check's support test for everybody. It judges; it changes nothing.

use super::check::{CheckConfig, capsule_depth_beyond, support};
use super::solids::{Owner, Solid, furniture_solids};
use crate::furniture::template;
use crate::physics::PieceFit;
use crate::scene::{Human, Scene};
use glam::DVec3;

/// How far (m) every joint may be from the last pose tested for a frame to count as that pose.
pub const STILL: f64 = 0.01;

/// Most poses of one person [`piece_fit`] tests: beyond, every k-th is tested for k of them (the
/// shipped real clips have at most 451 frames; this bounds the largest inputs validation accepts).
pub const MAX_POSES: usize = 1024;

/// The frames of `human` a search needs to test, each with how many frames it stands for: a frame
/// whose every joint is within [`STILL`] of the last frame kept counts as that one (a person
/// sitting still through 180 frames of motion capture is tested once); at most [`MAX_POSES`].
fn distinct_poses(human: &Human) -> Vec<(usize, f64)> {
    let mut poses: Vec<(usize, f64)> = Vec::new();
    for f in 0..human.frames.len() {
        match poses.last_mut() {
            Some((kept, weight)) if human.frame(*kept).zip(human.frame(f)).all(|(a, b)| a.distance(b) <= STILL) => {
                *weight += 1.0
            }
            _ => poses.push((f, 1.0)),
        }
    }
    if poses.len() > MAX_POSES {
        let k = poses.len().div_ceil(MAX_POSES);
        let total: f64 = poses.iter().map(|p| p.1).sum();
        poses = poses.into_iter().step_by(k).collect();
        let kept: f64 = poses.iter().map(|p| p.1).sum();
        poses.iter_mut().for_each(|p| p.1 *= total / kept);
    }
    poses
}

/// How object `object` of `scene` meets the people: the sum over humans, frames and bones of how
/// far each bone enters the piece's parts beyond `tolerance` (m; its deepest part; a frame within
/// [`STILL`] of the last pose tested counts as that pose), and the people the check's support test
/// fails (with the check's default distance).
pub fn piece_fit(scene: &Scene, object: usize, tolerance: f64) -> PieceFit {
    let parts: Vec<Solid> =
        template(&scene.objects[object]).parts.into_iter().map(|p| Solid::new(Owner::Object(object), p.obox)).collect();
    let lo = parts.iter().fold(DVec3::splat(f64::INFINITY), |m, s| m.min(s.aabb.0));
    let hi = parts.iter().fold(DVec3::splat(f64::NEG_INFINITY), |m, s| m.max(s.aabb.1));
    let mut depth = 0.0;
    for human in &scene.humans {
        let sk = &human.skeleton;
        let reach = sk.bones.iter().map(|b| b.radius).fold(0.0, f64::max);
        for (f, weight) in distinct_poses(human) {
            let body_lo = human.frame(f).fold(DVec3::splat(f64::INFINITY), DVec3::min) - reach;
            let body_hi = human.frame(f).fold(DVec3::splat(f64::NEG_INFINITY), DVec3::max) + reach;
            if (body_lo.cmpgt(hi) | body_hi.cmplt(lo)).any() {
                continue;
            }
            for bone in &sk.bones {
                let (a, b) = (human.joint_at(f, bone.a), human.joint_at(f, bone.b));
                let deepest = parts
                    .iter()
                    .filter_map(|s| capsule_depth_beyond(a, b, bone.radius, s, tolerance))
                    .fold(0.0, f64::max);
                if deepest > 0.0 {
                    depth += (deepest - tolerance) * weight;
                }
            }
        }
    }
    let furniture = furniture_solids(scene);
    let limit = CheckConfig::default().support_distance;
    let unsupported = (0..scene.humans.len())
        .filter(|&h| scene.humans[h].contact_spans().next().is_some())
        .filter(|&h| !support(&scene.humans[h], &furniture, limit).is_empty())
        .collect();
    PieceFit { depth, unsupported }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::RoomType;
    use crate::sim::{check_scene, exact_contacts};

    #[test]
    fn depth_is_the_exact_contacts_depth_beyond_the_tolerance_and_support_is_the_checks() {
        let mut scene = generate_room(RoomType::Dining, 3, 2, false).scene;
        for o in &mut scene.objects {
            o.center[0] += 0.35;
        }
        let tolerance = 0.015;
        let contacts = exact_contacts(&scene, tolerance);
        let mut entered = 0;
        for i in 0..scene.objects.len() {
            let want: f64 = contacts.iter().filter(|c| c.owner == Owner::Object(i)).map(|c| c.depth - tolerance).sum();
            let got = piece_fit(&scene, i, tolerance);
            assert!((got.depth - want).abs() < 1e-9, "{i}: {} vs {want}", got.depth);
            entered += usize::from(want > 0.0);
        }
        assert!(entered > 0, "the shift puts some piece into somebody");
        let report = check_scene(&scene, &CheckConfig::default());
        let mut unsupported: Vec<usize> = report
            .violations
            .iter()
            .filter(|v| v.kind == crate::sim::ViolationKind::Unsupported)
            .map(|v| scene.humans.iter().position(|h| Some(&h.id) == v.human.as_ref()).unwrap())
            .collect();
        unsupported.dedup();
        assert!(!unsupported.is_empty(), "the shift leaves somebody without support");
        assert_eq!(piece_fit(&scene, 0, tolerance).unsupported, unsupported);
    }
}
