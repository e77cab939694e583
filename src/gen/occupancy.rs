//! What polishing knows of a scene's people (ours): their conditions (contact boxes, free-space
//! mask), each contact box's seat gaps, where their bodies need the room clear, and which object
//! holds which contact box.
//!
//! It decides nothing: `polish` assigns the holders and every polishing step reads them here. The
//! people never move, so all but the holders are fixed once made.

use super::clearance::Clearance;
use super::completion::SeatGaps;
use crate::human::{Conditions, ContactBox};
use crate::scene::Scene;

/// A scene's people and what holds them.
#[derive(Debug, Clone)]
pub(super) struct Occupancy {
    /// The scene's conditioning: contact boxes, free-space mask, room window.
    pub cond: Conditions,
    /// Seat gaps of each contact box, by index into `cond.contact_boxes`.
    pub gaps: Vec<SeatGaps>,
    /// Where the people's bodies need the room clear.
    pub clearance: Clearance,
    /// (contact box index, object index) of every held box, sorted; empty until polishing assigns it.
    pub holders: Vec<(usize, usize)>,
}

impl Occupancy {
    /// The people of `scene`, nobody held yet.
    pub fn of(scene: &Scene) -> Occupancy {
        let cond = Conditions::of(scene);
        let clearance = Clearance::of(scene, &cond.window);
        let gaps = cond.contact_boxes.iter().map(|c| SeatGaps::of(scene, c)).collect();
        Occupancy { cond, gaps, clearance, holders: Vec::new() }
    }

    /// The contact boxes object `i` holds, each with its seat gaps.
    pub fn held_by(&self, i: usize) -> Vec<(&ContactBox, &SeatGaps)> {
        self.holders
            .iter()
            .filter(|(_, h)| *h == i)
            .map(|(b, _)| (&self.cond.contact_boxes[*b], &self.gaps[*b]))
            .collect()
    }

    /// Whether object `i` holds anybody.
    pub fn holds(&self, i: usize) -> bool {
        self.holders.iter().any(|(_, h)| *h == i)
    }

    /// Whether each of the first `n` objects holds anybody.
    pub fn holding(&self, n: usize) -> Vec<bool> {
        (0..n).map(|i| self.holds(i)).collect()
    }
}

/// A 6 × 5 m room of type `room` with `sofa` alone in it and a person of `stature` (m) lying along
/// world +x (head west), pelvis at `at`, on its seat; the sofa holds them. For tests of the steps that fit sofas to sleepers.
#[cfg(test)]
pub(super) fn sofa_with_sleeper(
    room: crate::scene::RoomType,
    sofa: crate::scene::Object,
    stature: f64,
    at: glam::DVec2,
) -> (Scene, Occupancy) {
    use crate::geom::yaw_facing;
    use crate::human::{Body, Motion, lie};
    use crate::scene::Action;
    let mut scene = crate::data::generate_room(room, 3, 0, false).scene;
    scene.floor_plan.polygon = vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]];
    let seat = crate::furniture::template(&sofa).surface.expect("a sofa has a seat");
    let body = Body::new(stature);
    let mut m = Motion::new(body, 30.0);
    m.hold(lie(&body, at, seat.height, yaw_facing(glam::DVec2::X)), 3, Action::Lie);
    scene.humans = vec![m.into_human("h0")];
    scene.objects = vec![sofa];
    let mut people = Occupancy::of(&scene);
    people.holders = vec![(0, 0)];
    (scene, people)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::RoomType;

    #[test]
    fn an_object_holds_exactly_the_boxes_assigned_to_it() {
        let scene = generate_room(RoomType::Dining, 4, 3, false).scene;
        let mut people = Occupancy::of(&scene);
        assert!(people.cond.contact_boxes.len() >= 2 && scene.objects.len() >= 3);
        assert_eq!(people.gaps.len(), people.cond.contact_boxes.len());
        assert!(people.held_by(1).is_empty() && !people.holds(1));
        people.holders = vec![(0, 1), (1, 1)];
        assert_eq!(people.holding(3), vec![false, true, false]);
        let held = people.held_by(1);
        assert_eq!(held.len(), 2);
        assert_eq!(held[1].0, &people.cond.contact_boxes[1]);
        assert_eq!(held[1].1, &people.gaps[1]);
    }
}
