//! Pushing pieces out of the people who pass through them (ours, a repair step).
//!
//! `settle`'s rounds keep pieces off walking and standing people's paths and off sitters' shins
//! (`Clearance`, a per-pixel height map), but a diner's thighs and forearms under a table top or a
//! sitter's knees in the coffee table in front of them are only found by replaying the bodies
//! against the pieces' parts (`sim::exact_contacts`, the check's own depths). A piece that holds
//! nobody and that a bone enters deeper than the check's 2 cm moves horizontally away from those
//! bones by the deepest depth plus 1 cm, where it stays inside the floor plan, clear of every other
//! piece and no more in people's way, else loses that much on the side they enter (at most 10 cm
//! and a quarter of its size in all: a table wedged between diners); up to four times, as a piece pushed
//! off one person may meet another. Where that leaves the bodies no less deep in the pieces
//! altogether, nothing changes.
//!
//! Pieces that hold people stay where repair put them; hanging pieces are not moved.

use super::clearance::Clearance;
use super::config::{RepairConfig, StepName};
use super::helpers::{fits_inside, is_solid, narrow_by, narrowed_within, shift};
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::geom::intersection_volume;
use crate::physics::{EngineContact, Owner, PHYS_TOLERANCE, Physics};
use crate::scene::{Object, Scene};
use glam::DVec2;

/// Moves every standing piece that holds nobody (`holds[i]` false) out of the bones that enter it,
/// where that keeps it inside, apart from the others and no more in people's way, else narrows it
/// on their side. Returns how many pieces moved or narrowed (none when the bodies would end no less
/// deep in the pieces) and the bones still deeper than the check's tolerance in the scene it leaves.
fn push_off_bodies(
    scene: &mut Scene,
    clearance: &Clearance,
    holds: &[bool],
    physics: &dyn Physics,
    config: &RepairConfig,
) -> (usize, Vec<EngineContact>) {
    let (cfg, limits) = (&config.off_bodies, &config.narrowing);
    let before = scene.objects.clone();
    let first = physics.exact_contacts(scene, PHYS_TOLERANCE);
    let start = free_depth(holds, &first);
    if start <= 0.0 {
        return (0, first);
    }
    let mut contacts = first.clone();
    let polygon = scene.floor_plan.polygon();
    let mut moved = vec![false; scene.objects.len()];
    for _ in 0..cfg.rounds {
        let pushes = pushes(scene, holds, &contacts, cfg.margin);
        let mut any = false;
        for (i, push) in pushes {
            let o = &scene.objects[i];
            if o.category.is_hanging() {
                continue;
            }
            let mut candidate = o.clone();
            shift(&mut candidate, push);
            let b = candidate.obox();
            let apart = scene
                .objects
                .iter()
                .enumerate()
                .all(|(j, other)| j == i || intersection_volume(&b, &other.obox()) <= 1e-9);
            let solid = is_solid(o);
            let in_the_way = |x: &Object| clearance.blocked(&x.obox(), solid).len();
            if fits_inside(&b, &polygon, config.gap) && apart && in_the_way(&candidate) <= in_the_way(o) {
                scene.objects[i] = candidate;
            } else {
                // Wedged in: the side the bones enter comes in instead (within `narrowing` in
                // all), which keeps it inside, apart and out of the way.
                let mut cut = o.clone();
                if !narrow_by(&mut cut, push, limits) || !narrowed_within(&before[i], &cut, limits) {
                    continue;
                }
                scene.objects[i] = cut;
            }
            moved[i] = true;
            any = true;
        }
        if !any {
            break;
        }
        contacts = physics.exact_contacts(scene, PHYS_TOLERANCE);
    }
    if free_depth(holds, &contacts) >= start {
        scene.objects = before;
        return (0, first);
    }
    (moved.iter().filter(|m| **m).count(), contacts)
}

/// The sum of the depths (m, over bones and frames) by which the bodies enter pieces that hold nobody.
fn free_depth(holds: &[bool], contacts: &[EngineContact]) -> f64 {
    contacts.iter().filter(|c| matches!(c.owner, Owner::Object(i) if !holds[i])).map(|c| c.depth).sum()
}

/// For each piece that holds nobody and that `contacts`' bones enter: the horizontal move away from them (the
/// depth-weighted mean direction from the bones' middles to its centre) by the deepest depth plus
/// `margin`, in object order.
fn pushes(scene: &Scene, holds: &[bool], contacts: &[EngineContact], margin: f64) -> Vec<(usize, DVec2)> {
    let mut sums = vec![(DVec2::ZERO, 0.0f64); scene.objects.len()];
    for c in contacts {
        let Owner::Object(i) = c.owner else { continue };
        if holds[i] {
            continue;
        }
        let human = &scene.humans[c.human];
        let bone = &human.skeleton.bones[c.bone];
        let middle = ((human.joint_at(c.frame, bone.a) + human.joint_at(c.frame, bone.b)) * 0.5).truncate();
        let o = &scene.objects[i];
        let away = (DVec2::new(o.center[0], o.center[1]) - middle).normalize_or_zero();
        sums[i].0 += away * c.depth;
        sums[i].1 = sums[i].1.max(c.depth);
    }
    sums.into_iter()
        .enumerate()
        .filter(|(_, (_, deepest))| *deepest > 0.0)
        .map(|(i, (dir, deepest))| (i, dir.normalize_or_zero() * (deepest + margin)))
        .filter(|(_, m)| m.length() > 0.0)
        .collect()
}

/// The `off_bodies` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct OffBodies;

impl RepairStep for OffBodies {
    fn name(&self) -> StepName {
        StepName::OffBodies
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let physics = work.physics;
        let (people, holds) = work.holds(scene.objects.len());
        let (pushed, bones) = push_off_bodies(scene, &people.clearance, holds, physics, config);
        work.bones = Some(bones);
        StepReport::OffBodies { pushed }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::human::{Body, Motion, stand};
    use crate::scene::{Action, Category, RoomType};
    use crate::sim::{SimPhysics, exact_contacts};

    /// The pieces `push_off_bodies` moved with the default settings and `sim`'s physics.
    fn pushed(scene: &mut Scene, clearance: &Clearance, holds: &[bool]) -> usize {
        push_off_bodies(scene, clearance, holds, &SimPhysics, &RepairConfig::default()).0
    }

    /// A room from y = `south` to 3 m, 4 m wide, with a person standing at (2, 1.5) and a cabinet
    /// south of them, its north face as far into them as makes the deepest bone 5–6 cm deep.
    fn cabinet_into_a_stander(south: f64) -> (Scene, f64) {
        let mut scene = generate_room(RoomType::Living, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, south], [4.0, south], [4.0, 3.0], [0.0, 3.0]];
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(stand(&body, DVec2::new(2.0, 1.5), 0.0), 3, Action::Stand);
        scene.humans = vec![m.into_human("h0")];
        for k in 0..200 {
            let north = 1.2 + 0.002 * k as f64;
            let size = [0.8, 0.4, 0.8];
            let cabinet = Object {
                id: "o0".into(),
                category: Category::Cabinet,
                center: [2.0, north - size[1] * 0.5, size[2] * 0.5],
                size,
                yaw: 0.0,
            };
            scene.objects = vec![cabinet];
            let d = deepest(&scene);
            if d > 0.05 {
                return (scene, d);
            }
        }
        panic!("the cabinet never reaches the person");
    }

    fn deepest(scene: &Scene) -> f64 {
        exact_contacts(scene, 0.0).iter().map(|c| c.depth).fold(0.0, f64::max)
    }

    fn clearance_of(scene: &Scene) -> Clearance {
        Clearance::of(scene, &scene.room_window())
    }

    #[test]
    fn a_cabinet_in_a_standing_person_moves_away_by_the_depth_and_a_centimetre() {
        let (mut scene, depth) = cabinet_into_a_stander(0.0);
        let before = scene.objects[0].clone();
        let clearance = clearance_of(&scene);
        // Holding someone: it stays.
        assert_eq!(pushed(&mut scene, &clearance, &[true]), 0);
        assert_eq!(scene.objects[0], before);
        assert_eq!(pushed(&mut scene, &clearance, &[false]), 1);
        let o = &scene.objects[0];
        let m = DVec2::new(o.center[0] - before.center[0], o.center[1] - before.center[1]);
        // One push, straight away from the person (south), by the depth plus 1 cm; size unchanged.
        assert!((m.length() - (depth + RepairConfig::default().off_bodies.margin)).abs() < 1e-9, "{m} vs {depth}");
        assert!(m.y < 0.0 && m.x.abs() < 0.2 * m.length(), "{m}");
        assert_eq!((o.size, o.yaw, o.center[2]), (before.size, before.yaw, before.center[2]));
        assert!(deepest(&scene) <= PHYS_TOLERANCE, "{}", deepest(&scene));
    }

    #[test]
    fn a_cabinet_against_the_wall_behind_it_loses_depth_on_the_persons_side() {
        let (probe, depth) = cabinet_into_a_stander(0.0);
        // The south wall at the cabinet's back: it cannot move away.
        let back = probe.objects[0].center[1] - probe.objects[0].size[1] * 0.5;
        let (mut scene, again) = cabinet_into_a_stander(back);
        assert_eq!(again, depth);
        let before = scene.objects[0].clone();
        let clearance = clearance_of(&scene);
        assert_eq!(pushed(&mut scene, &clearance, &[false]), 1);
        let o = &scene.objects[0];
        // Its back stays at the wall, its front comes in by the push's southward part.
        assert!((o.center[1] - o.size[1] * 0.5 - back).abs() < 1e-9, "{o:?}");
        let cut = before.size[1] - o.size[1];
        assert!(cut > depth && cut <= depth + RepairConfig::default().off_bodies.margin + 1e-9, "{cut} vs {depth}");
        assert!(deepest(&scene) <= PHYS_TOLERANCE + 0.005, "{}", deepest(&scene));
    }
}
