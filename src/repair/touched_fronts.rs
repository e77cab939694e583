//! Tall pieces trimmed to their touchers. The data touches a cabinet, shelf or table taller than
//! a metre on its front face, the palm on it; repair puts the pressed volume behind the face
//! ([`touches_front`]), but a piece against a wall cannot always move back that far, and the
//! toucher's palm and forearm stay inside it. Then the piece loses depth at the front, its back
//! where it was, until its front face is at the nearest toucher's palm — never below the
//! category's shallowest real piece. Nothing moves; low pieces (the palm rests on their top) are
//! left alone.

use super::config::{HoldingConfig, RepairConfig, StepName};
use super::helpers::{local_extent, touches_front, trim_front_within_real};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::scene::{Action, Scene};

/// Trims every piece touched on its front whose touchers' pressed volumes lie behind the face.
/// Returns how many it trimmed.
fn trim_touched_fronts(scene: &mut Scene, people: &Occupancy, rules: &HoldingConfig) -> usize {
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let held = people.held_by(i);
        let o = &mut scene.objects[i];
        let b = o.obox();
        // The front of each touch box (local +y, towards its person) behind the face: the cut
        // that brings the face to the nearest of them.
        let behind = held
            .iter()
            .filter(|(c, _)| c.action == Action::Touch && touches_front(o, c, rules))
            .map(|(c, _)| o.size[1] * 0.5 - local_extent(&c.obox, &b).1.y)
            .fold(f64::INFINITY, f64::min);
        if !behind.is_finite() {
            continue;
        }
        trimmed += usize::from(trim_front_within_real(o, behind));
    }
    trimmed
}

/// The `touched_fronts` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct TouchedFronts;

impl RepairStep for TouchedFronts {
    fn name(&self) -> StepName {
        StepName::TouchedFronts
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::TouchedFronts { trimmed: trim_touched_fronts(scene, &work.people, &config.holding) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::furniture::size_range;
    use crate::human::{Body, Motion, Side, palm_of, touch};
    use crate::repair::tests::repair_with_rounds;
    use crate::scene::{Category, Object, RoomType};
    use crate::sim::{CheckConfig, check_scene};
    use glam::DVec3;

    /// A 5 × 4 m bedroom with a wardrobe `depth` (m) deep against the north wall (facing south,
    /// 5 cm off the wall) and a person facing north who touches it at 1.2 m, `inside` (m) behind
    /// its front face.
    fn touched_wardrobe(depth: f64, inside: f64) -> Scene {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [5.0, 0.0], [5.0, 4.0], [0.0, 4.0]];
        let mut wardrobe = Object::standing("o0", Category::Wardrobe, [2.5, 3.95 - depth * 0.5], [1.8, depth, 2.1]);
        wardrobe.yaw = std::f64::consts::PI;
        let front = 3.95 - depth;
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(touch(&body, DVec3::new(2.5, front + inside, 1.2), 0.0, Side::Right), 3, Action::Touch);
        scene.humans = vec![m.into_human("h0")];
        scene.objects = vec![wardrobe];
        scene
    }

    fn palm_y(scene: &Scene) -> f64 {
        palm_of(&scene.humans[0], 0, "right").unwrap().y
    }

    #[test]
    fn a_wardrobe_against_the_wall_with_the_palm_inside_loses_depth_at_the_front() {
        let mut scene = touched_wardrobe(0.62, 0.1);
        let check = CheckConfig { stability: false, ..CheckConfig::default() };
        assert!(!check_scene(&scene, &check).violations.is_empty(), "the forearm is in the wardrobe first");
        let r = repair_with_rounds(&mut scene, 30);
        let o = &scene.objects[0];
        let (back, front) = (o.center[1] + o.size[1] * 0.5, o.center[1] - o.size[1] * 0.5);
        assert!((3.94..=4.0).contains(&back), "its back at the wall: {back} {r:?}");
        assert!(o.size[1] < 0.59 && o.size[1] >= size_range(Category::Wardrobe, 1).0, "{}", o.size[1]);
        // The front face at the palm (within the half-cube the touch box reaches past it).
        assert!((palm_y(&scene) - front).abs() < 0.07, "palm {} front {front}", palm_y(&scene));
        assert_eq!(check_scene(&scene, &check).violations, vec![], "{r:?}");
        assert!(r.trimmed >= 1);
    }

    #[test]
    fn a_wardrobe_touched_on_its_face_or_too_deep_inside_keeps_what_it_can() {
        // Palm on the face already: nothing to trim.
        let mut scene = touched_wardrobe(0.6, 0.0);
        let before = scene.objects[0].size;
        repair_with_rounds(&mut scene, 30);
        assert!((scene.objects[0].size[1] - before[1]).abs() < 1e-9);
        // Palm 40 cm inside a 60 cm wardrobe: no real wardrobe is 20 cm deep; it stops at the
        // shallowest real one.
        let mut scene = touched_wardrobe(0.6, 0.4);
        repair_with_rounds(&mut scene, 30);
        assert!((scene.objects[0].size[1] - size_range(Category::Wardrobe, 1).0).abs() < 1e-9);
    }
}
