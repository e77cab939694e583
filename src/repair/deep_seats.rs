//! `deep_seats` (ours): deep seats trimmed to their sitters. `settle` puts a sitter's support box
//! on a chair or sofa near enough its front edge for the knees to pass it
//! ([`SeatGaps`](super::completion::SeatGaps)), but a deep seat against a wall cannot always move
//! that far: then the seat loses depth at the front, its back staying where it is, until the
//! sitters' lower legs hang clear of it as the data's do. Only depth, never below the category's
//! shallowest real piece; a sofa that would have to be shallower than that (an L-shaped sofa or a
//! chaise longue, 1.4 m and more) becomes a multi-seat sofa. Nothing moves.

use super::config::{RepairConfig, StepName};
use super::helpers::{local_extent, trim_front_within_real};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::{size_range, template};
use crate::scene::{Action, Category, Group, Scene};

/// Trims every chair and sofa whose sitters sit further back than [`SeatGaps::front`](super::completion::SeatGaps::front) allows
/// (a sofa too deep for any real piece of its category becomes a multi-seat sofa). Returns how
/// many it trimmed.
fn trim_deep_seats(scene: &mut Scene, people: &Occupancy) -> usize {
    let swap_to = Some(Category::MultiSeatSofa).filter(|c| scene.room_type.categories().contains(c));
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let held = people.held_by(i);
        let sitters: Vec<_> = held.iter().filter(|(c, _)| c.action == Action::Sit).collect();
        let o = &mut scene.objects[i];
        if sitters.is_empty() || !matches!(o.category.group(), Group::Chair | Group::Sofa) {
            continue;
        }
        let Some(surface) = template(o).surface else { continue };
        let b = o.obox();
        // Each sitter asks for the front edge at most `front` past their box, and no sitter's box
        // may lose its seat: the smallest front any of them allows, the largest any of them needs.
        let fronts = sitters.iter().map(|(c, g)| (local_extent(&c.obox, &b).1.y, g.front(c, o)));
        let (need, keep) = fronts.fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |(need, keep), (hi, front)| {
            (need.max(surface.max.y - hi - front), keep.max(hi))
        });
        let cut = need.min(surface.max.y - keep);
        if cut <= 1e-3 {
            continue;
        }
        let shallowest = |c| size_range(c, 1).0;
        if let Some(sofa) = swap_to.filter(|_| o.category.group() == Group::Sofa) {
            if o.size[1] - cut < shallowest(o.category) {
                o.category = sofa;
            }
        }
        trimmed += usize::from(trim_front_within_real(o, cut));
    }
    trimmed
}

/// The `deep_seats` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct DeepSeats;

impl RepairStep for DeepSeats {
    fn name(&self) -> StepName {
        StepName::DeepSeats
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, _config: &RepairConfig) -> StepReport {
        StepReport::DeepSeats { trimmed: trim_deep_seats(scene, &work.people) }
    }
}

#[cfg(test)]
mod tests {
    use super::super::completion::SeatGaps;
    use super::super::helpers::shift;
    use super::*;
    use crate::data::generate_room;
    use crate::human::Conditions;
    use crate::human::KNEE_OVERHANG;
    use crate::repair::tests::repair_with_rounds;
    use crate::scene::Object;
    use crate::scene::RoomType;

    /// How far `contact`'s knees pass the front edge of `o`'s seat (m; the knee that passes least).
    fn knee_overhang(scene: &Scene, o: &Object) -> f64 {
        let cond = Conditions::of(scene);
        let b = o.obox();
        let (_, ay) = b.axes();
        let edge = template(o).surface.unwrap().max.y + b.center.truncate().dot(ay);
        let on_it = cond
            .contact_boxes
            .iter()
            .filter(|c| c.action == Action::Sit && b.footprint_contains(c.obox.center.truncate()));
        on_it
            .flat_map(|c| SeatGaps::of(scene, c, &Default::default()).knees)
            .map(|k| k.dot(ay) - edge)
            .fold(f64::INFINITY, f64::min)
    }

    /// The first sofa with a sitter on it in the index-th generated living room.
    fn sofa_with_sitter(index: u64) -> Option<(Scene, usize)> {
        let scene = generate_room(RoomType::Living, 3, index, false).scene;
        let i = scene
            .objects
            .iter()
            .position(|o| o.category.group() == Group::Sofa && knee_overhang(&scene, o).is_finite())?;
        Some((scene, i))
    }

    /// Makes object `i` `extra` (m) deeper at the front, its back where it was.
    fn deepen(scene: &mut Scene, i: usize, extra: f64) {
        let o = &mut scene.objects[i];
        let (_, ay) = o.obox().axes();
        o.size[1] += extra;
        shift(o, ay * (extra * 0.5));
        assert!(knee_overhang(scene, &scene.objects[i]) < 0.0);
    }

    #[test]
    fn a_sofa_too_deep_for_its_sitter_against_a_wall_loses_depth_at_the_front() {
        let mut trimmed = 0;
        for index in 0..12 {
            let Some((mut scene, i)) = sofa_with_sitter(index) else { continue };
            let (depth, overhang) = (scene.objects[i].size[1], knee_overhang(&scene, &scene.objects[i]));
            assert!(overhang >= KNEE_OVERHANG - 0.02, "the data's sitters clear the edge: {overhang}");
            deepen(&mut scene, i, 0.35);
            let r = repair_with_rounds(&mut scene, 30);
            let o = &scene.objects[i];
            assert!(knee_overhang(&scene, o) >= KNEE_OVERHANG - 0.01, "{index}: {} {r:?}", knee_overhang(&scene, o));
            assert!(o.size[1] <= depth + 0.35 + 1e-9 && o.size[1] >= size_range(o.category, 1).0 - 1e-9);
            trimmed += r.trimmed;
        }
        assert!(trimmed > 0, "some sofa stood against a wall and was trimmed");
    }

    #[test]
    fn an_l_shaped_sofa_too_deep_for_its_sitter_becomes_a_multi_seat_sofa() {
        let mut swapped = 0;
        for index in 0..12 {
            let Some((mut scene, i)) = sofa_with_sitter(index) else { continue };
            scene.objects[i].category = Category::LShapedSofa;
            // As deep as the shallowest real L-shaped sofa (1.44 m), far deeper than its sitter can use.
            let extra = size_range(Category::LShapedSofa, 1).0 - scene.objects[i].size[1];
            deepen(&mut scene, i, extra);
            let r = repair_with_rounds(&mut scene, 30);
            let o = &scene.objects[i];
            if r.trimmed > 0 {
                assert_eq!(o.category, Category::MultiSeatSofa, "{index}");
                assert!(knee_overhang(&scene, o) >= KNEE_OVERHANG - 0.01, "{index}: {r:?}");
                swapped += 1;
            } else {
                assert_eq!(o.category, Category::LShapedSofa, "{index}: moved forward, kept");
            }
        }
        assert!(swapped > 0);
    }
}
