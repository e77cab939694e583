//! `fit_into_room` (ours): a piece the rounds left poking out of the floor plan is moved back over
//! the contact boxes it holds and inside; where it still does not fit, it is narrowed by what sticks
//! out (within `narrowing`, [`narrow_by`]; at most `fit_into_room.cuts` cuts) if that makes it
//! fit, an L-shaped room's inner corner included ([`worst_offence`]). A piece taller than the room
//! is cut to the ceiling first, as decoding cuts the model's ([`under_the_ceiling`]).

use super::config::{RepairConfig, StepName};
use super::helpers::{containment_shift, fits_inside, inside_push, narrow_by, shift, worst_offence};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::scene::Scene;
use glam::DVec2;

/// The `fit_into_room` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct FitIntoRoom;

impl RepairStep for FitIntoRoom {
    fn name(&self) -> StepName {
        StepName::FitIntoRoom
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::FitIntoRoom { narrowed: fit_into_room(scene, &work.people, config) }
    }
}

/// Moves every piece the rounds left poking out of the floor plan back over the contact boxes it
/// holds and inside; where it still does not fit, narrows it by what sticks out if that makes it
/// fit. Returns how many pieces were narrowed.
fn fit_into_room(scene: &mut Scene, people: &Occupancy, config: &RepairConfig) -> usize {
    let polygon = scene.floor_plan.polygon();
    let gap = config.gap;
    let mut narrowed = 0;
    let ceiling = scene.floor_plan.height;
    for i in 0..scene.objects.len() {
        narrowed += usize::from(under_the_ceiling(&mut scene.objects[i], ceiling));
        if fits_inside(&scene.objects[i].obox(), &polygon, gap) {
            continue;
        }
        let before = scene.objects[i].clone();
        let o = &mut scene.objects[i];
        let held = people.held_by(i);
        if !held.is_empty() {
            let m = held.iter().map(|(b, seat)| containment_shift(b, seat, o, &config.holding)).sum::<DVec2>()
                / held.len() as f64;
            shift(o, m);
        }
        let w = inside_push(&o.obox(), &polygon, gap);
        shift(o, w);
        if fits_inside(&o.obox(), &polygon, gap) {
            continue;
        }
        // A piece a few centimetres too big for its place is narrowed to fit.
        *o = before;
        let mut cut = o.clone();
        for _ in 0..config.fit_into_room.cuts {
            match worst_offence(&cut.obox(), &polygon, gap) {
                None => {
                    *o = cut;
                    narrowed += 1;
                    break;
                }
                Some((_, push)) if narrow_by(&mut cut, push, &config.narrowing) => {}
                Some(_) => break,
            }
        }
    }
    narrowed
}

/// Cuts a piece whose top is above `ceiling` to end there: a floor piece keeps standing on the
/// floor, a hanging lamp keeps hanging from the ceiling. Whether it was cut.
pub(super) fn under_the_ceiling(o: &mut crate::scene::Object, ceiling: f64) -> bool {
    if o.center[2] + o.size[2] * 0.5 <= ceiling + 1e-9 {
        return false;
    }
    o.size[2] = o.size[2].min(ceiling).max(0.02);
    o.center[2] = if o.category.is_hanging() { ceiling - o.size[2] * 0.5 } else { o.size[2] * 0.5 };
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Category, Object};

    #[test]
    fn a_piece_taller_than_the_room_is_cut_to_the_ceiling_standing_or_hanging() {
        let piece = |category, height: f64, z: f64| Object {
            id: "o0".into(),
            category,
            center: [1.0, 1.0, z],
            size: [1.0, 0.6, height],
            yaw: 0.0,
        };
        let mut wardrobe = piece(Category::Wardrobe, 2.4, 1.2);
        assert!(under_the_ceiling(&mut wardrobe, 2.3));
        assert_eq!((wardrobe.size[2], wardrobe.center[2]), (2.3, 1.15));
        let mut lamp = piece(Category::PendantLamp, 0.5, 2.5);
        assert!(under_the_ceiling(&mut lamp, 2.3));
        assert_eq!((lamp.size[2], lamp.center[2]), (0.5, 2.05));
        let mut low = piece(Category::Wardrobe, 2.0, 1.0);
        assert!(!under_the_ceiling(&mut low, 2.3));
        assert_eq!((low.size[2], low.center[2]), (2.0, 1.0));
    }
}
