//! What repair knows of a scene's people (ours): their conditions (contact boxes, free-space
//! mask), each contact box's seat gaps, where their bodies need the room clear, and which object
//! holds which contact box.
//!
//! It decides only who holds whom ([`Occupancy::assign`], which `settle` calls each pass); every
//! step reads it here. The
//! people never move, so all but the holders are fixed once made.

use super::clearance::Clearance;
use super::completion::SeatGaps;
use super::config::{HoldingConfig, SettleConfig};
use crate::geom::iou_3d;
use crate::human::{Conditions, ContactBox};
use crate::measure::contact_iou;
use crate::scene::{Action, Group, Object, Scene};
use glam::DVec2;

/// A scene's people and what holds them.
#[derive(Debug, Clone)]
pub struct Occupancy {
    /// The scene's conditioning: contact boxes, free-space mask, room window.
    pub cond: Conditions,
    /// Seat gaps of each contact box, by index into `cond.contact_boxes`.
    pub gaps: Vec<SeatGaps>,
    /// Where the people's bodies need the room clear.
    pub clearance: Clearance,
    /// (contact box index, object index) of every held box, sorted; empty until [`Occupancy::assign`].
    pub holders: Vec<(usize, usize)>,
}

impl Occupancy {
    /// The people of `scene`, nobody held yet, their seat gaps as `rules` has them.
    pub fn of(scene: &Scene, rules: &HoldingConfig) -> Occupancy {
        let cond = Conditions::of(scene);
        let clearance = Clearance::of(scene, &cond.window);
        let gaps = cond.contact_boxes.iter().map(|c| SeatGaps::of(scene, c, rules)).collect();
        Occupancy { cond, gaps, clearance, holders: Vec::new() }
    }

    /// Gives each contact box some object can hold to one ([`assign_contacts`]).
    pub fn assign(&mut self, scene: &Scene, cfg: &SettleConfig) {
        self.holders = assign_contacts(scene, &self.cond, cfg);
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

/// How many spatially distinct contact boxes `o` can hold: one per chair or stool, one per place
/// (`place_width` wide) along a sofa or bed, any number of touches.
fn capacity(o: &Object, place_width: f64) -> usize {
    match o.category.group() {
        Group::Chair | Group::Stool => 1,
        Group::Sofa | Group::Bed => ((o.size[0].max(o.size[1]) / place_width).floor() as usize).max(1),
        _ => usize::MAX,
    }
}

/// (contact box index, object index) for every contact box some object can hold: greedily, best
/// covered pairs first, then nearest (within 2 m), each object holding at most its capacity of
/// boxes (boxes of one place at different times count once).
fn assign_contacts(scene: &Scene, cond: &Conditions, cfg: &SettleConfig) -> Vec<(usize, usize)> {
    let boxes = &cond.contact_boxes;
    let mut candidates: Vec<(f64, f64, usize, usize)> = Vec::new();
    for (k, b) in boxes.iter().enumerate() {
        if !matches!(b.action, Action::Sit | Action::Lie | Action::Touch) {
            continue;
        }
        for (i, o) in scene.objects.iter().enumerate().filter(|(_, o)| o.category.affords(b.action)) {
            let cover = contact_iou(&b.obox, std::slice::from_ref(o));
            let distance = DVec2::from_slice(&o.center[..2]).distance(b.obox.center.truncate());
            if cover > 0.0 || distance < cfg.max_assign_distance {
                candidates.push((cover, distance, k, i));
            }
        }
    }
    candidates.sort_by(|x, y| y.0.total_cmp(&x.0).then(x.1.total_cmp(&y.1)).then((x.2, x.3).cmp(&(y.2, y.3))));
    let mut held: Vec<(usize, usize)> = Vec::new();
    for (_, _, k, i) in candidates {
        if held.iter().any(|(b, _)| *b == k) {
            continue;
        }
        // The boxes `i` already holds, by whether each is at the same place as box k.
        let same: Vec<bool> =
            held.iter().filter(|(_, j)| *j == i).map(|(b, _)| iou_3d(&boxes[*b].obox, &boxes[k].obox) >= 0.5).collect();
        let places = same.iter().filter(|s| !**s).count();
        if same.contains(&true) || places < capacity(&scene.objects[i], cfg.place_width) {
            held.push((k, i));
        }
    }
    held.sort_unstable();
    held
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
    let mut people = Occupancy::of(&scene, &HoldingConfig::default());
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
        let mut people = Occupancy::of(&scene, &HoldingConfig::default());
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
