//! Tall pieces trimmed to their touchers. The data touches a cabinet, shelf or table taller than
//! a metre on its front face, the palm on it; polishing puts the pressed volume behind the face
//! ([`touches_front`]), but a piece against a wall cannot always move back that far, and the
//! toucher's palm and forearm stay inside it. Then the piece loses depth at the front, its back
//! where it was, until its front face is at the nearest toucher's palm — never below the
//! category's shallowest real piece. Nothing moves; low pieces (the palm rests on their top) are
//! left alone.

use super::deep_seats::trim_front;
use super::occupancy::Occupancy;
use super::polish::{local_extent, touches_front};
use crate::furniture::size_range;
use crate::scene::{Action, Scene};

/// Trims every piece touched on its front whose touchers' pressed volumes lie behind the face.
/// Returns how many it trimmed.
pub(super) fn trim_touched_fronts(scene: &mut Scene, people: &Occupancy) -> usize {
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let held = people.held_by(i);
        let o = &mut scene.objects[i];
        let b = o.obox();
        // The front of each touch box (local +y, towards its person) behind the face: the cut
        // that brings the face to the nearest of them.
        let behind = held
            .iter()
            .filter(|(c, _)| c.action == Action::Touch && touches_front(o, c))
            .map(|(c, _)| o.size[1] * 0.5 - local_extent(&c.obox, &b).1.y)
            .fold(f64::INFINITY, f64::min);
        if !behind.is_finite() {
            continue;
        }
        let cut = behind.min(o.size[1] - size_range(o.category, 1).0);
        if cut > 1e-3 {
            trim_front(o, cut);
            trimmed += 1;
        }
    }
    trimmed
}
