//! Deep seats trimmed to their sitters. Repair puts a sitter's support box on a chair or sofa
//! near enough its front edge for the knees to pass it ([`SeatGaps`](super::completion::SeatGaps)), but a deep seat against a
//! wall cannot always move that far: then the seat loses depth at the front, its back staying
//! where it is, until the sitters' lower legs hang clear of it as the data's do. Only depth, never
//! below the category's shallowest real piece; a sofa that would have to be shallower than that (an
//! L-shaped sofa or a chaise longue, 1.4 m and more) becomes a multi-seat sofa. Likewise a bed whose
//! sitter's knees do not pass the edge they face by those 7 cm (its other side at a wall) is
//! narrowed on their side, keeping everyone it holds on it (a sitter's box over that edge by no
//! more than repair allows) and no narrower than the category's narrowest real piece. A sofa
//! whose sleeper lies behind the middle of its seat (shoulders in the backrest, the sofa's back at a
//! wall) loses depth at the front until the seat's middle, which moves back with it, is at them.
//! Nothing moves.

use super::config::{RepairConfig, SofasToSleepersConfig, StepName};
use super::helpers::{BED_EDGE_OVERHANG, bed_edge_faced, local_extent, shift, trim_front, trim_front_within_real};
use super::occupancy::Occupancy;
use super::pipeline::{RepairStep, StepReport, Workspace};
use crate::furniture::{size_range, template};
use crate::human::KNEE_OVERHANG;
use crate::scene::{Action, Category, Group, Object, Scene};
use glam::DVec2;

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

/// Narrows every bed whose sitters' knees do not pass the edge they face by [`KNEE_OVERHANG`]
/// (a bed that could not move out from under their lower legs: its other side at a wall), on that
/// side, as far as keeps its other people on it and no narrower than its category's narrowest
/// real piece. Returns how many it narrowed.
fn trim_beds_to_sitters(scene: &mut Scene, people: &Occupancy) -> usize {
    let mut trimmed = 0;
    for i in 0..scene.objects.len() {
        let o = &scene.objects[i];
        let held = people.held_by(i);
        if o.category.group() != Group::Bed || !held.iter().any(|(c, _)| c.action == Action::Sit) {
            continue;
        }
        let b = o.obox();
        let half = DVec2::new(o.size[0], o.size[1]) * 0.5;
        // Per side (axis k, sign s): the cut its sitters need and the edge its people need kept.
        let mut cuts = [[0.0f64; 2]; 2];
        let mut keep = [[f64::NEG_INFINITY; 2]; 2];
        for (c, gaps) in &held {
            let (lo, hi) = local_extent(&c.obox, &b);
            // The side a sitter faces: their box may overhang its edge as repair lets it.
            let (k, ahead) = bed_edge_faced(o, c);
            let (s, sign) = if ahead { (1, 1.0) } else { (0, -1.0) };
            let sits = c.action == Action::Sit;
            for k2 in 0..2 {
                let overhang = |s2: usize| if sits && (k2, s2) == (k, s) { BED_EDGE_OVERHANG } else { 0.0 };
                keep[k2][0] = keep[k2][0].max(-lo[k2] - overhang(0));
                keep[k2][1] = keep[k2][1].max(hi[k2] - overhang(1));
            }
            if !sits || gaps.knees.is_empty() {
                continue;
            }
            let reach = gaps.knees.iter().map(|p| sign * b.to_local(p.extend(b.center.z)).truncate()[k]);
            let reach = reach.fold(f64::INFINITY, f64::min);
            cuts[k][s] = cuts[k][s].max(half[k] - (reach - KNEE_OVERHANG));
        }
        let o = &mut scene.objects[i];
        let mut any = false;
        for k in 0..2 {
            for s in 0..2 {
                let narrowest = size_range(o.category, k).0;
                let edge = o.size[k] * 0.5;
                let cut = cuts[k][s].min(edge - keep[k][s]).min(o.size[k] - narrowest);
                if cut > 1e-3 {
                    let (ax, ay) = o.obox().axes();
                    let axis = if k == 0 { ax } else { ay };
                    let sign = if s == 1 { 1.0 } else { -1.0 };
                    o.size[k] -= cut;
                    shift(o, -axis * (sign * cut * 0.5));
                    any = true;
                }
            }
        }
        trimmed += usize::from(any);
    }
    trimmed
}

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

/// The `beds_to_sitters` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct BedsToSitters;

impl RepairStep for BedsToSitters {
    fn name(&self) -> StepName {
        StepName::BedsToSitters
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, _config: &RepairConfig) -> StepReport {
        StepReport::BedsToSitters { trimmed: trim_beds_to_sitters(scene, &work.people) }
    }
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
    use super::super::completion::SeatGaps;
    use super::*;
    use crate::data::generate_room;
    use crate::human::Conditions;
    use crate::human::KNEE_OVERHANG;
    use crate::repair::tests::repair_with_rounds;
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
        on_it.flat_map(|c| SeatGaps::of(scene, c).knees).map(|k| k.dot(ay) - edge).fold(f64::INFINITY, f64::min)
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

    /// A 1.8 m double bed against the west wall of a 5 × 4 m bedroom, and a person sitting on its
    /// east side `inset` (m) in from the edge, facing east; the bed holds them.
    fn bed_with_side_sitter(inset: f64) -> (Scene, Occupancy) {
        use crate::human::{Body, Motion, sit};
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[1.09, 0.0], [6.0, 0.0], [6.0, 4.0], [1.09, 4.0]];
        let bed = Object::standing("o0", Category::DoubleBed, [2.0, 1.5], [1.8, 2.1, 0.9]);
        let top = template(&bed).surface.unwrap().height;
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(sit(&body, DVec2::new(2.9 - inset, 1.5), top, -std::f64::consts::FRAC_PI_2), 3, Action::Sit);
        scene.humans = vec![m.into_human("h0")];
        scene.objects = vec![bed];
        let mut people = Occupancy::of(&scene);
        people.holders = vec![(0, 0)];
        assert_eq!(people.cond.contact_boxes.len(), 1);
        (scene, people)
    }

    #[test]
    fn a_bed_under_its_sitters_lower_legs_is_narrowed_on_their_side() {
        let (mut scene, people) = bed_with_side_sitter(0.5);
        let knee = people.gaps[0].knees.iter().map(|k| k.x).fold(f64::INFINITY, f64::min);
        assert!(knee < 2.9, "the knees are over the bed: {knee}");
        assert_eq!(trim_beds_to_sitters(&mut scene, &people), 1);
        let o = &scene.objects[0];
        let (west, east) = (o.center[0] - o.size[0] * 0.5, o.center[0] + o.size[0] * 0.5);
        assert!((east - (knee - KNEE_OVERHANG)).abs() < 1e-9, "east edge {east}, knees {knee}");
        assert!((west - 1.1).abs() < 1e-9 && o.size[1] == 2.1 && o.size[0] >= size_range(Category::DoubleBed, 0).0);
        // Still on the mattress: the support box overhangs the edge by no more than repair allows.
        let b = &people.cond.contact_boxes[0].obox;
        assert!(b.center.x + b.size.x * 0.5 - east <= crate::repair::helpers::BED_EDGE_OVERHANG + 1e-9);
    }

    #[test]
    fn a_bed_whose_sitter_sits_at_its_edge_stays_as_it_is() {
        let (mut scene, people) = bed_with_side_sitter(0.15);
        let before = scene.objects.clone();
        assert_eq!(trim_beds_to_sitters(&mut scene, &people), 0);
        assert_eq!(scene.objects, before);
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
