//! Sofas widened to their people. Repair keeps each sitter's or sleeper's support box on a
//! sofa's seat by moving the sofa, but a sofa with people at both ends, or one that cannot slide
//! along its wall (a side wall, a corner, a neighbour), leaves a box over an arm: the sitter's
//! hip and elbow or the sleeper's head and feet end up inside it. Such a sofa grows on the side
//! (or sides) where its people overhang the seat until the seat between the arms spans them all
//! (a sleeper's whole body, head and feet included, not only their support box), the other side
//! staying where it is — or as far towards that as the widest real piece of its category goes, each
//! end its share; a loveseat too short for its sleeper becomes a multi-seat sofa, as no real
//! loveseat seats an adult lying down — where the grown sofa stays inside the floor plan, is no
//! more in walking or standing people's way and no further into the pieces that hold people.
//! The other pieces it now overlaps are left to `overlaps`, which narrows or removes them.

use super::config::{RepairConfig, StepName};
use super::helpers::{fits_inside, is_solid, local_extent, shift};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::{size_range, template};
use crate::geom::intersection_volume;
use crate::human::ContactBox;
use crate::scene::{Action, Category, Group, Object, Scene};
use glam::DVec3;

/// Widens every sofa whose sitters' or sleepers' boxes overhang its seat at an end (up to the
/// category's widest real piece, inside the floor plan, no more in people's way and no further into
/// the pieces that hold people). Returns how many it widened.
fn widen_for_people(scene: &mut Scene, people: &Occupancy, config: &RepairConfig) -> usize {
    let cfg = &config.wide_seats;
    let polygon = scene.floor_plan.polygon();
    let mut widened = 0;
    for i in 0..scene.objects.len() {
        let o = &scene.objects[i];
        if o.category.group() != Group::Sofa {
            continue;
        }
        let held = people.held_by(i);
        let boxes: Vec<_> = held.iter().filter(|(c, _)| matches!(c.action, Action::Sit | Action::Lie)).collect();
        if boxes.is_empty() {
            continue;
        }
        // Sleepers' whole bodies lie on the seat between the arms, head and feet included.
        let bodies: Vec<(DVec3, f64)> =
            boxes.iter().filter(|(c, _)| c.action == Action::Lie).flat_map(|(c, _)| body_points(scene, c)).collect();
        let mut grown = o.clone();
        let (mut grown_low, mut grown_high) = (0.0, 0.0);
        for _ in 0..4 {
            let Some(surface) = template(&grown).surface else { break };
            let b = grown.obox();
            let (lo, hi) = boxes
                .iter()
                .map(|(c, _)| local_extent(&c.obox, &b))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (l, h)| (lo.min(l.x), hi.max(h.x)));
            let (lo, hi) = bodies.iter().fold((lo, hi), |(lo, hi), (p, r)| {
                let x = b.to_local(*p).x;
                (lo.min(x - r), hi.max(x + r))
            });
            let low = (surface.min.x + cfg.margin - lo).max(0.0);
            let high = (hi - surface.max.x + cfg.margin).max(0.0);
            if low + high <= 1e-3 {
                break;
            }
            grow_sides(&mut grown, low, high);
            grown_low += low;
            grown_high += high;
        }
        // No real loveseat is long enough for an adult to lie on (the data lays sleepers only on
        // seats longer than they are): one that would have to be becomes a multi-seat sofa.
        let sofa = Category::MultiSeatSofa;
        if !bodies.is_empty()
            && grown.size[0] > size_range(grown.category, 0).1
            && grown.size[0] <= size_range(sofa, 0).1
            && scene.room_type.categories().contains(&sofa)
        {
            grown.category = sofa;
        }
        let widest = size_range(grown.category, 0).1;
        if grown.size[0] > widest {
            // As far as the widest real piece goes, each end its share.
            let k = ((widest - o.size[0]) / (grown_low + grown_high)).max(0.0);
            grown = o.clone();
            grow_sides(&mut grown, grown_low * k, grown_high * k);
        }
        let solid = is_solid(o);
        let in_the_way = |x: &Object| people.clearance.blocked(&x.obox(), solid).len();
        // Pieces that hold people stay where they are, so the grown sofa must keep clear of them.
        let holders_overlapped = |x: &Object| -> f64 {
            let b = x.obox();
            (0..scene.objects.len())
                .filter(|&j| j != i && people.holds(j))
                .map(|j| intersection_volume(&b, &scene.objects[j].obox()))
                .sum()
        };
        if grown.size[0] - o.size[0] > 1e-3
            && fits_inside(&grown.obox(), &polygon, config.gap)
            && in_the_way(&grown) <= in_the_way(o)
            && holders_overlapped(&grown) <= holders_overlapped(o) + 1e-9
        {
            scene.objects[i] = grown;
            widened += 1;
        }
    }
    widened
}

/// The joints of `contact`'s person over its span, each with the radius of its thickest bone.
fn body_points(scene: &Scene, contact: &ContactBox) -> Vec<(DVec3, f64)> {
    let Some(h) = scene.humans.iter().find(|h| h.id == contact.human) else { return Vec::new() };
    let mut radius = vec![0.0f64; h.skeleton.joints.len()];
    for b in &h.skeleton.bones {
        for j in [b.a, b.b] {
            radius[j] = radius[j].max(b.radius);
        }
    }
    let [start, end] = contact.frames;
    (start..end.min(h.frames.len()))
        .flat_map(|f| radius.iter().enumerate().map(move |(j, &r)| (h.joint_at(f, j), r)))
        .collect()
}

/// Makes `o` `low` wider at its local −x end and `high` wider at its +x end, the rest where it was.
fn grow_sides(o: &mut Object, low: f64, high: f64) {
    let (ax, _) = o.obox().axes();
    o.size[0] += low + high;
    shift(o, ax * ((high - low) * 0.5));
}

/// The `wide_seats` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct WideSeats;

impl RepairStep for WideSeats {
    fn name(&self) -> StepName {
        StepName::WideSeats
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        StepReport::WideSeats { widened: widen_for_people(scene, &work.people, config) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::geom::OBox;
    use crate::human::{Body, Motion, sit};
    use crate::scene::{Category, RoomType};
    use glam::DVec2;

    /// A 6 × 5 m living room (x from `west`) with a 1.9 m multi-seat sofa 1 cm off the south wall,
    /// centred at x = 2, facing north, and sitters at the given x on it; every sitter held by it.
    fn sofa_with_sitters(west: f64, xs: &[f64]) -> (Scene, Occupancy) {
        let mut scene = generate_room(RoomType::Living, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[west, 0.0], [6.0, 0.0], [6.0, 5.0], [west, 5.0]];
        let sofa = Object::standing("o0", Category::MultiSeatSofa, [2.0, 0.46], [1.9, 0.9, 0.85]);
        let seat = template(&sofa).surface.expect("a sofa has a seat");
        let body = Body::default();
        scene.humans = xs
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let mut m = Motion::new(body, 30.0);
                m.hold(sit(&body, DVec2::new(x, 0.5), seat.height, 0.0), 3, Action::Sit);
                m.into_human(format!("h{k}"))
            })
            .collect();
        scene.objects = vec![sofa];
        let mut people = Occupancy::of(&scene, &Default::default());
        people.holders = (0..people.cond.contact_boxes.len())
            .filter(|&b| people.cond.contact_boxes[b].action == Action::Sit)
            .map(|b| (b, 0))
            .collect();
        assert_eq!(people.holders.len(), xs.len());
        (scene, people)
    }

    /// The seat's ends (world x) of an unturned sofa.
    fn seat_ends(o: &Object) -> (f64, f64) {
        let s = template(o).surface.expect("a sofa has a seat");
        (o.center[0] + s.min.x, o.center[0] + s.max.x)
    }

    /// The sitters' boxes' ends (world x).
    fn boxes_ends(people: &Occupancy) -> (f64, f64) {
        let boxes: Vec<&OBox> = people.holders.iter().map(|(b, _)| &people.cond.contact_boxes[*b].obox).collect();
        let lo = boxes.iter().map(|b| b.center.x - b.size.x * 0.5).fold(f64::INFINITY, f64::min);
        let hi = boxes.iter().map(|b| b.center.x + b.size.x * 0.5).fold(f64::NEG_INFINITY, f64::max);
        (lo, hi)
    }

    #[test]
    fn a_sofa_with_sitters_over_both_arms_grows_at_both_ends_to_span_them() {
        let (mut scene, people) = sofa_with_sitters(0.0, &[1.2, 2.8]);
        let (lo, hi) = boxes_ends(&people);
        let (start, end) = seat_ends(&scene.objects[0]);
        assert!(start > lo + 0.1 && end < hi - 0.1, "both sitters overhang the seat: {lo} {start} {end} {hi}");
        assert_eq!(widen_for_people(&mut scene, &people, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        let (start, end) = seat_ends(o);
        assert!(start <= lo + 1e-6 && end >= hi - 1e-6, "the seat spans both: {lo} {start} {end} {hi}");
        // No wider than that (the margin each side), the middle where it was, nothing else changed.
        assert!(start >= lo - 0.02 && end <= hi + 0.02, "{lo} {start} {end} {hi}");
        assert!((o.center[0] - 2.0).abs() < 0.01 && o.center[1] == 0.46 && o.size[1] == 0.9 && o.yaw == 0.0);
        assert!(o.size[0] <= size_range(Category::MultiSeatSofa, 0).1);
    }

    #[test]
    fn a_sofa_grows_only_on_the_side_its_sitter_overhangs() {
        let (mut scene, people) = sofa_with_sitters(0.0, &[2.8]);
        let west_end = scene.objects[0].center[0] - scene.objects[0].size[0] * 0.5;
        assert_eq!(widen_for_people(&mut scene, &people, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert!((o.center[0] - o.size[0] * 0.5 - west_end).abs() < 1e-9, "the west end stays");
        assert!(seat_ends(o).1 >= boxes_ends(&people).1 - 1e-6);
    }

    #[test]
    fn a_sofa_that_would_leave_the_room_stays_as_it_is() {
        // The west wall 3 cm beyond the sofa's west end: growing west would cross it.
        let (mut scene, people) = sofa_with_sitters(1.03, &[1.2]);
        let before = scene.objects.clone();
        assert_eq!(widen_for_people(&mut scene, &people, &RepairConfig::default()), 0);
        assert_eq!(scene.objects, before);
    }

    #[test]
    fn a_sofa_grows_no_wider_than_the_widest_real_one() {
        // Sitters 3 m apart need a seat wider than any real multi-seat sofa (2.79 m): it grows
        // to that, by the same at both ends (they overhang alike).
        let (mut scene, people) = sofa_with_sitters(0.0, &[0.5, 3.5]);
        let widest = size_range(Category::MultiSeatSofa, 0).1;
        assert!(widest < 3.2, "{widest}");
        assert_eq!(widen_for_people(&mut scene, &people, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert!((o.size[0] - widest).abs() < 1e-9 && (o.center[0] - 2.0).abs() < 1e-9, "{:?}", o);
    }

    /// A 1.7 m `category` sofa 1 cm off the south wall of a 6 × 5 m room of type `room`, centred
    /// at x = 3, facing north, and a 1.75 m person lying along its seat's middle, centred on it,
    /// held by it.
    fn sofa_with_sleeper(room: RoomType, category: Category) -> (Scene, Occupancy) {
        let sofa = Object::standing("o0", category, [3.0, 0.46], [1.7, 0.9, 0.85]);
        let seat = template(&sofa).surface.expect("a sofa has a seat");
        // The pelvis 0.45 statures from the head: the body centred on the sofa.
        let at = DVec2::new(3.0 - 0.05 * 1.75, 0.46 + (seat.min.y + seat.max.y) * 0.5);
        crate::repair::occupancy::sofa_with_sleeper(room, sofa, 1.75, at)
    }

    /// The world x range of the joints of the scene's first person.
    fn body_ends(scene: &Scene) -> (f64, f64) {
        let h = &scene.humans[0];
        let xs = (0..h.skeleton.joints.len()).map(|j| h.joint_at(0, j).x);
        xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| (lo.min(x), hi.max(x)))
    }

    #[test]
    fn a_loveseat_too_short_for_its_sleeper_becomes_a_multi_seat_sofa_spanning_them() {
        let (mut scene, people) = sofa_with_sleeper(RoomType::Living, Category::LoveseatSofa);
        let (head, feet) = body_ends(&scene);
        assert!(seat_ends(&scene.objects[0]).0 > head, "the head is over the arm first");
        assert_eq!(widen_for_people(&mut scene, &people, &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        assert_eq!(o.category, Category::MultiSeatSofa);
        let (west, east) = seat_ends(o);
        assert!(west < head && east > feet, "the seat {west}..{east} spans the body {head}..{feet}");
        assert!(o.size[0] <= size_range(Category::MultiSeatSofa, 0).1);
        // A bedroom has no multi-seat sofas: its sofa grows only as far as real ones go.
        let (mut scene, people) = sofa_with_sleeper(RoomType::Bedroom, Category::Sofa);
        widen_for_people(&mut scene, &people, &RepairConfig::default());
        let o = &scene.objects[0];
        assert_eq!(o.category, Category::Sofa);
        assert!(o.size[0] <= size_range(Category::Sofa, 0).1 + 1e-9, "{:?}", o);
    }
}
