//! `sofas_to_sleepers` (ours): a sofa whose sleeper lies behind the middle of its seat (shoulders
//! in the backrest, the sofa's back at a wall) loses depth at the front until the seat's middle,
//! which moves back with it, is at them. Nothing moves.

use super::config::{RepairConfig, SofasToSleepersConfig, StepName};
use super::helpers::{local_extent, trim_front};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::{size_range, template};
use crate::scene::{Action, Group, Object, Scene};
use glam::DVec2;

/// Trims every sofa whose sleepers lie further back than the middle of its seat (the data lays
/// people along the seat's middle; further back, their shoulders are in the backrest) until the
/// seat's middle is at the sleeper furthest back, its back staying where it was: a sofa against a
/// wall cannot go back to them. No box it holds loses the seat, and no sofa gets shallower than
/// its category's shallowest real piece (turning a deep L-shaped sofa into a multi-seat one changed
/// no val room and raised CKL).
/// Returns how many it trimmed.
fn trim_sofas_to_sleepers(scene: &mut Scene, people: &Occupancy, cfg: &SofasToSleepersConfig) -> usize {
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let held = people.held_by(i);
        let o = &mut scene.objects[i];
        if o.category.group() != Group::Sofa || !held.iter().any(|(c, _)| c.action == Action::Lie) {
            continue;
        }
        let b = o.obox();
        let extents: Vec<(Action, DVec2, DVec2)> = held
            .iter()
            .map(|(c, _)| {
                let (lo, hi) = local_extent(&c.obox, &b);
                (c.action, lo, hi)
            })
            .collect();
        // Each sleeper's middle, from the back face; the furthest back of them decides.
        let lies = extents.iter().filter(|(a, _, _)| *a == Action::Lie);
        let wanted = lies.map(|(_, lo, hi)| (lo.y + hi.y) * 0.5 + o.size[1] * 0.5).fold(f64::INFINITY, f64::min);
        // The front of the box furthest forward stays on the seat.
        let keep = extents.iter().map(|(_, _, hi)| hi.y).fold(f64::NEG_INFINITY, f64::max);
        let middle = |o: &Object, cut: f64| {
            let mut t = o.clone();
            t.size[1] -= cut;
            template(&t).surface.map_or(0.0, |s| (s.min.y + s.max.y) * 0.5 + t.size[1] * 0.5)
        };
        if middle(o, 0.0) - wanted <= cfg.off_middle {
            continue;
        }
        // The middle moves back as the sofa gets shallower: bisect for the cut that puts it at
        // the sleeper, within what the other boxes and real pieces allow.
        let most = (o.size[1] * 0.5 - keep).min(o.size[1] - size_range(o.category, 1).0).max(0.0);
        let (mut lo, mut hi) = (0.0, most);
        if middle(o, most) >= wanted {
            lo = most;
        } else {
            for _ in 0..30 {
                let mid = 0.5 * (lo + hi);
                if middle(o, mid) > wanted { lo = mid } else { hi = mid }
            }
        }
        if lo > 1e-3 {
            trim_front(o, lo);
            trimmed += 1;
        }
    }
    trimmed
}

/// The `sofas_to_sleepers` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct SofasToSleepers;

impl RepairStep for SofasToSleepers {
    fn name(&self) -> StepName {
        StepName::SofasToSleepers
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::SofasToSleepers { trimmed: trim_sofas_to_sleepers(scene, &work.people, &config.sofas_to_sleepers) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Category;
    use crate::scene::RoomType;

    /// A 2.2 m multi-seat sofa `depth` (m) deep, its back 1 cm off the south wall of a 6 × 5 m
    /// living room, facing north, and a person lying along it `behind` (m) behind its seat's
    /// middle; the sofa holds them.
    fn sofa_with_sleeper(depth: f64, behind: f64) -> (Scene, Occupancy) {
        let sofa = Object::standing("o0", Category::MultiSeatSofa, [3.0, 0.01 + depth * 0.5], [2.2, depth, 0.85]);
        let seat = template(&sofa).surface.unwrap();
        let middle = sofa.center[1] + (seat.min.y + seat.max.y) * 0.5;
        let stature = crate::human::Body::default().stature;
        crate::repair::occupancy::sofa_with_sleeper(RoomType::Living, sofa, stature, DVec2::new(2.4, middle - behind))
    }

    /// The seat's middle (world y) and the sofa's back (world y) of the south-wall sofa.
    fn middle_and_back(o: &Object) -> (f64, f64) {
        let seat = template(o).surface.unwrap();
        (o.center[1] + (seat.min.y + seat.max.y) * 0.5, o.center[1] - o.size[1] * 0.5)
    }

    #[test]
    fn a_deep_sofa_whose_sleeper_lies_against_its_back_loses_depth_until_they_lie_in_the_middle() {
        let (mut scene, people) = sofa_with_sleeper(1.1, 0.1);
        let lie = people.cond.contact_boxes[0].obox.center.y;
        assert_eq!(trim_sofas_to_sleepers(&mut scene, &people, &SofasToSleepersConfig::default()), 1);
        let o = &scene.objects[0];
        let (middle, back) = middle_and_back(o);
        assert!((middle - lie).abs() < 0.005, "seat's middle {middle}, sleeper {lie}");
        assert!((back - 0.01).abs() < 1e-9, "its back stays at the wall: {back}");
        assert!(o.size[1] < 1.1 && o.size[1] >= size_range(Category::MultiSeatSofa, 1).0);
        // A sleeper already in the middle (or in front of it) leaves the sofa as it is.
        for behind in [0.0, -0.1] {
            let (mut scene, people) = sofa_with_sleeper(1.1, behind);
            let before = scene.objects.clone();
            assert_eq!(trim_sofas_to_sleepers(&mut scene, &people, &SofasToSleepersConfig::default()), 0);
            assert_eq!(scene.objects, before);
        }
        // Far behind a sofa only a little deeper than the shallowest real one: it stops there.
        let shallowest = size_range(Category::MultiSeatSofa, 1).0;
        let (mut scene, people) = sofa_with_sleeper(shallowest + 0.05, 0.3);
        trim_sofas_to_sleepers(&mut scene, &people, &SofasToSleepersConfig::default());
        assert!((scene.objects[0].size[1] - shallowest).abs() < 1e-9);
    }
}
