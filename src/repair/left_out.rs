//! Leaving out a piece that people still pass through (ours, the `left_out` repair step).
//!
//! After the rounds, relocation and `fit_to_bodies` have moved and reshaped what they could, a piece
//! that holds nobody and that a bone still enters deeper than the check's 2 cm is usually one the
//! model stood where the room has no place for it: a sofa across two diners' legs, a second bed
//! in a walkway, a wardrobe in the path to the door. Such a piece is taken out of the layout: a
//! room without it is one people can use, and one the check passes. Kept whatever enters them:
//!
//! - pieces that hold a person's contact (they are moved, never removed, by repair);
//! - a piece someone sits at: a top at least 15 cm above a sitter's seat whose footprint reaches
//!   the spot up to 0.8 m in front of their support box (a diner's thighs under the table top are
//!   a near miss, a dining room without its table is wrong; a coffee table in a sitter's shins is
//!   no piece they sit at);
//! - the last piece that makes the room what it is: a bedroom's last bed, a dining room's last
//!   dining table, a living room's last sofa;
//! - hanging pieces (no bone reaches them in the data's rooms).
//!
//! (The first three are `in_use`, which `overlaps` spares too.) It moves nothing.

use super::config::{LeftOutConfig, RepairConfig, StepName};
use super::in_use::in_use;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::human::ContactBox;
use crate::physics::{EngineContact, Owner, PHYS_TOLERANCE};
use crate::scene::Scene;

/// Removes, from the last to the first, every standing piece that holds nobody (`holds[i]`
/// false), that a bone of `bones` enters (the scene's exact contacts deeper than the check's
/// tolerance) and that none of the rules above keeps; `holds` loses the same entries. Returns how
/// many it removed.
fn leave_out_entered(
    scene: &mut Scene,
    bones: &[EngineContact],
    contacts: &[ContactBox],
    holds: &mut Vec<bool>,
    cfg: &LeftOutConfig,
) -> usize {
    let mut entered = vec![false; scene.objects.len()];
    for c in bones {
        if let Owner::Object(i) = c.owner {
            entered[i] = true;
        }
    }
    let mut removed = 0;
    for i in (0..scene.objects.len()).rev() {
        let o = &scene.objects[i];
        if !entered[i] || o.category.is_hanging() || in_use(scene, i, holds, contacts, cfg) {
            continue;
        }
        scene.objects.remove(i);
        holds.remove(i);
        removed += 1;
    }
    removed
}

/// The `left_out` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct LeftOut;

impl RepairStep for LeftOut {
    fn name(&self) -> StepName {
        StepName::LeftOut
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let bones = match work.bones.take() {
            Some(bones) => bones,
            None => work.physics.exact_contacts(scene, PHYS_TOLERANCE),
        };
        let (people, holds) = work.holds(scene.objects.len());
        let contacts = &people.cond.contact_boxes;
        StepReport::LeftOut { left_out: leave_out_entered(scene, &bones, contacts, holds, &config.left_out) }
    }
}

#[cfg(test)]
mod tests {
    use super::super::in_use::sits_at;
    use super::*;
    use crate::data::generate_room;
    use crate::human::{Body, Conditions, Motion, sit, stand};
    use crate::scene::{Action, Category, Object, RoomType};
    use crate::sim::exact_contacts;
    use glam::DVec2;

    /// A 5 × 4 m room of type `room` with a person standing at (2, 2) and a diner sitting at
    /// (4, 1) on a 47 cm seat, facing +y.
    fn room_with_people(room: RoomType) -> Scene {
        let mut scene = generate_room(room, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [5.0, 0.0], [5.0, 4.0], [0.0, 4.0]];
        let body = Body::default();
        let mut stander = Motion::new(body, 30.0);
        stander.hold(stand(&body, DVec2::new(2.0, 2.0), 0.0), 3, Action::Stand);
        let mut diner = Motion::new(body, 30.0);
        diner.hold(sit(&body, DVec2::new(4.0, 1.0), 0.47, 0.0), 3, Action::Sit);
        scene.humans = vec![stander.into_human("h0"), diner.into_human("h1")];
        scene.objects.clear();
        scene
    }

    fn leave_out(scene: &mut Scene, holds: &[bool]) -> (usize, Vec<bool>) {
        let contacts = Conditions::contact_boxes_of(scene);
        let bones = exact_contacts(scene, PHYS_TOLERANCE);
        let mut holds = holds.to_vec();
        let n = leave_out_entered(scene, &bones, &contacts, &mut holds, &LeftOutConfig::default());
        (n, holds)
    }

    fn ids(scene: &Scene) -> Vec<&str> {
        scene.objects.iter().map(|o| o.id.as_str()).collect()
    }

    #[test]
    fn a_sofa_the_stander_stands_in_is_left_out_unless_it_holds_someone_or_is_the_last() {
        let mut scene = room_with_people(RoomType::Living);
        let in_the_way = Object::standing("o0", Category::MultiSeatSofa, [2.0, 2.2], [2.0, 0.9, 0.85]);
        let clear = Object::standing("o1", Category::LoveseatSofa, [1.0, 3.5], [1.5, 0.9, 0.85]);
        scene.objects = vec![in_the_way.clone(), clear.clone()];
        // Holding someone: kept.
        assert_eq!(leave_out(&mut scene.clone(), &[true, false]).0, 0);
        // The living room's last sofa: kept.
        let mut alone = scene.clone();
        alone.objects = vec![in_the_way];
        assert_eq!(leave_out(&mut alone, &[false]).0, 0);
        // Another sofa stands clear: the one in the way goes, and `holds` follows.
        let (n, holds) = leave_out(&mut scene, &[false, true]);
        assert_eq!((n, holds), (1, vec![true]));
        assert_eq!(ids(&scene), ["o1"]);
    }

    #[test]
    fn a_table_the_diner_sits_at_stays_a_low_table_in_their_shins_goes() {
        let mut scene = room_with_people(RoomType::Living);
        let sofa = Object::standing("o9", Category::MultiSeatSofa, [1.0, 3.5], [1.5, 0.9, 0.85]);
        // Its near edge 5 cm in front of the diner's pelvis: their belly and forearms are in its top.
        let table = Object::standing("o0", Category::DiningTable, [4.0, 1.5], [1.2, 0.9, 0.75]);
        // Its near edge 15 cm in front of the pelvis: the shins are in it.
        let coffee = Object::standing("o1", Category::CoffeeTable, [4.0, 1.6], [1.0, 0.9, 0.42]);
        for (piece, kept) in [(table, true), (coffee, false)] {
            scene.objects = vec![piece.clone(), sofa.clone()];
            let contacts = Conditions::contact_boxes_of(&scene);
            let entered = exact_contacts(&scene, PHYS_TOLERANCE).iter().any(|c| c.owner == Owner::Object(0));
            assert!(entered, "{:?} is entered", piece.category);
            assert_eq!(
                contacts.iter().any(|c| sits_at(c, &piece, &LeftOutConfig::default())),
                kept,
                "{:?}",
                piece.category
            );
            assert_eq!(leave_out(&mut scene, &[false, false]).0, usize::from(!kept), "{:?}", piece.category);
        }
    }

    #[test]
    fn a_bedroom_keeps_its_last_bed_and_loses_a_second_one_in_the_way() {
        let mut scene = room_with_people(RoomType::Bedroom);
        let in_the_way = Object::standing("o0", Category::SingleBed, [2.0, 2.5], [1.0, 2.0, 0.5]);
        let other = Object::standing("o1", Category::DoubleBed, [0.9, 1.1], [1.6, 2.1, 0.9]);
        scene.objects = vec![in_the_way.clone()];
        assert_eq!(leave_out(&mut scene, &[false]).0, 0);
        scene.objects = vec![in_the_way, other];
        assert_eq!(leave_out(&mut scene, &[false, false]).0, 1);
        assert_eq!(ids(&scene), ["o1"]);
    }

    #[test]
    fn nothing_entered_nothing_left_out() {
        let mut scene = room_with_people(RoomType::Dining);
        scene.objects = vec![
            Object::standing("o0", Category::Cabinet, [0.5, 3.7], [0.8, 0.4, 0.8]),
            Object::standing("o1", Category::DiningChair, [0.5, 0.5], [0.45, 0.5, 0.9]),
        ];
        let before = scene.objects.clone();
        assert_eq!(leave_out(&mut scene, &[false, false]), (0, vec![false, false]));
        assert_eq!(scene.objects, before);
    }
}
