//! `fit_into_room` (ours): a piece the rounds left poking out of the floor plan is moved back over
//! the contact boxes it holds and inside; where it still does not fit, it is narrowed by what sticks
//! out (within `narrowing`, [`narrow_by`]; at most `fit_into_room.cuts` cuts) if that makes it
//! fit, an L-shaped room's inner corner included ([`worst_offence`]). A piece taller than the room
//! is cut to the ceiling first, as decoding cuts the model's (`Object::cut_to_ceiling`).

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
        narrowed += usize::from(scene.objects[i].cut_to_ceiling(ceiling));
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
