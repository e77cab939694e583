//! Polishing a generated layout (ours, after the last sampling step): rounds of small, exact
//! geometric corrections of what the model's few-centimetre imprecision leaves undone.
//!
//! Each contact box (sit, lie, touch) is given to an object that affords its action: best covered
//! pairs first, then nearest within 2 m; a chair or stool holds one person, a sofa or bed one per
//! 55 cm of its length, tables and cabinets any number of touches. A box no object can hold gets a
//! new piece of real furniture (`completion`). A chair, stool or sofa is turned to face like the
//! first sitter it holds (its front the way they face), a sofa to lie along its sleeper, a bed a
//! quarter turn where its sitter faces along it (the data seats people on a bed's side, against the
//! edge they face); then every piece is turned square to the walls (the longest wall's direction
//! plus quarter turns; every piece of the data stands so, and a diagonal wardrobe or bed was what
//! most walkers walked into), and every piece the data stands against a wall (beds, cabinets,
//! shelves, sofas, desks, dressing and console tables) is put back against the nearest wall behind
//! or in front of it, its back to it (`walls`; a piece holding people only backwards, within what
//! its people allow). A seat's or bed's surface goes to the top of its person's support
//! volume (within the heights of the category's real pieces, give or take 15 cm; a bed up to
//! 0.7 m tall has no headboard and its mattress is its top, so a high sitter gets a low bed where
//! a tall one cannot reach them), a low table's or cabinet's top comes down to a palm resting on it
//! where real pieces of its category are that low, other holders grow to the top of their box (at
//! most 15 cm), and width and depth grow by at most 20 cm where the box needs it. A piece taller
//! than a metre is touched on its front: the toucher's pressed volume must lie just behind its
//! front face. Every round then (1) moves each holder by the smallest shift that puts its boxes'
//! footprints on the part they must be on (a seat's surface clear of its backrest and near enough
//! its front edge for the knees to pass it by 7 cm, as in the data; a mattress; else the footprint)
//! and pushes pieces out of people's way (where footprint and height meet a walking or standing
//! body, or a sitter's or toucher's shins and feet for a piece solid to the floor, `Clearance`; a
//! holder only as far as its people stay on it), (2) separates overlapping pairs along the shortest
//! separating axis that keeps both inside the walls, and (3) moves every footprint inside the floor
//! plan (corners inside, and off an L-shaped room's inner corner). Holders move a fifth as much for
//! overlaps and paths; the last third of the rounds leaves contacts alone and the last five paths,
//! so the layout ends separated and inside. Rounds stop when nothing moves a millimetre. A box
//! still less than half covered by pieces that can hold it (a table top over a sitter's seat does
//! not count) after that gets a new piece and a second pass of rounds. A double
//! bed still in people's way becomes the narrowest real double bed where that clears all of the
//! way, else a single bed where that clears some of it (`bed_swap`); a chair or
//! sofa too deep for its sitters' knees to pass its front edge (one against a wall) loses depth at
//! the front, an L-shaped sofa or chaise too deep for any real one becoming a multi-seat sofa, and
//! a bed loses width on the side its sitter faces, down to the narrowest real one, and a sofa
//! whose sleeper lies behind its seat's middle loses depth at the front (`deep_seats`);
//! a tall piece whose touchers' palms are still inside it (its back at a wall) loses depth at the
//! front, down to the shallowest real one (`touched_fronts`);
//! a sofa whose people still overhang its seat at an end grows there until
//! the seat spans them, within its category's widest real piece (a loveseat too short for its
//! sleeper becoming a multi-seat sofa, `wide_seats`). A piece still
//! poking out of the floor plan is then moved back over its people and inside or narrowed by at
//! most 10 cm, a piece is narrowed off the walkers' feet where 10 cm do it (a holder only as far
//! as its people stay on it: a bed's foot end off a walkway beside its sleeper), one
//! that people's bones still enter (a diner's thighs under a table top) is pushed or narrowed out
//! of them (`off_bodies`), one they still enter is left out unless someone sits at it or it is the
//! room's last bed, dining table or sofa (`left_out`), and overlaps that survive are narrowed away
//! or lose their smaller piece (`overlaps`; never a piece that holds a person).
//!
//! It re-categorises nothing but a double bed in people's way, which may become a single bed, a
//! sofa too deep for its sitters and a loveseat too short for its sleeper, which may become a
//! multi-seat sofa, and adds only within the room type's object limit.

use super::bed_swap::single_beds_off_paths;
use super::clearance::Clearance;
use super::completion::{SeatGaps, TOP_TOUCH_HEIGHT, height_within, support_for};
use super::deep_seats::{trim_beds_to_sitters, trim_deep_seats, trim_sofas_to_sleepers};
use super::inside::{CLEARANCE, fits_inside, inside_push, worst_offence};
use super::left_out::leave_out_entered;
use super::occupancy::Occupancy;
use super::off_bodies::push_off_bodies;
use super::overlaps::{narrow_by, resolve_overlaps};
use super::relocate::{is_solid, relocate_off_paths};
use super::touched_fronts::trim_touched_fronts;
use super::walls::{stands_against_wall, to_wall_behind, wall_poses};
use super::wide_seats::widen_for_people;
use crate::eval::contact_iou;
use crate::furniture::{height_range, template};
use crate::geom::{OBox, facing, intersection_volume, iou_3d, wrap_angle};
use crate::human::{Conditions, ContactBox};
use crate::scene::{Action, Group, Object, Scene};
use glam::DVec2;
use serde::Serialize;

/// How far an object's height may grow to cover a contact box (m).
const MAX_GROW_HEIGHT: f64 = 0.15;
/// How far an object's width or depth may grow to cover a contact box (m).
const MAX_GROW_EXTENT: f64 = 0.2;
/// Farthest an object may be to be given a contact box it does not touch (m).
const MAX_ASSIGN_DISTANCE: f64 = 2.0;
/// Largest move of one round (m).
const MAX_STEP: f64 = 0.3;
/// Share of a move taken by an object that holds a contact.
const ANCHORED_MOBILITY: f64 = 0.2;

/// What polishing changed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct PolishReport {
    /// Rounds run.
    pub rounds: usize,
    /// Objects resized to cover a contact box.
    pub resized: usize,
    /// Seats turned to face like the person on them.
    pub turned: usize,
    /// Objects added for people nothing held (`completion`).
    pub added: usize,
    /// Pieces turned square to the walls (the data's all stand square).
    pub squared: usize,
    /// Pieces put back against a wall (`walls`; the data stands them so).
    pub walled: usize,
    /// Pieces holding nobody moved out of people's way to a free spot (`relocate`).
    pub relocated: usize,
    /// Pieces holding nobody moved or narrowed out of the bodies that entered them (`off_bodies`).
    pub pushed: usize,
    /// Double beds in people's way swapped for a single bed.
    pub swapped: usize,
    /// Deep seats trimmed at the front, and beds on their sitters' side, until the sitters' knees
    /// pass the edge (`deep_seats`).
    pub trimmed: usize,
    /// Sofas widened until their seat spans their sitters and sleepers (`wide_seats`).
    pub widened: usize,
    /// Objects narrowed to fit the floor plan, off the walkers' feet or out of an overlap (`overlaps`).
    pub narrowed: usize,
    /// Pieces holding nobody that people still passed through, left out (`left_out`).
    pub left_out: usize,
    /// Objects removed from an overlap nothing else undid (`overlaps`).
    pub removed: usize,
    /// Largest total move of one object (m).
    pub max_move: f64,
}

/// Contact IoU under which a held box counts as uncovered after a pass.
const COVERED: f64 = 0.5;

/// Polishes `scene`'s objects in place with at most `rounds` rounds per pass: a first pass, with a
/// new piece for every contact box no object can hold, and a second one only if some box is still
/// uncovered and a new piece can be added for it; then squares up what pokes out of the walls,
/// narrows free pieces off the walkers' feet and resolves the overlaps that are left.
pub fn polish_scene(scene: &mut Scene, rounds: usize) -> PolishReport {
    let mut people = Occupancy::of(scene);
    let mut report = PolishReport::default();
    let start: Vec<DVec2> = scene.objects.iter().map(|o| DVec2::new(o.center[0], o.center[1])).collect();
    for pass in 0..2 {
        people.holders = assign_contacts(scene, &people.cond);
        let missing: Vec<usize> = (0..people.cond.contact_boxes.len())
            .filter(|k| match pass {
                0 => !people.holders.iter().any(|(b, _)| b == k),
                // Covered by what can hold it: a table top over a sitter's seat does not count.
                _ => {
                    let b = &people.cond.contact_boxes[*k];
                    let holders: Vec<Object> =
                        scene.objects.iter().filter(|o| o.category.affords(b.action)).cloned().collect();
                    contact_iou(&b.obox, &holders) < COVERED
                }
            })
            .collect();
        let added = complete_supports(scene, &people.cond, &missing, &mut people.holders);
        if pass > 0 && added == 0 {
            break;
        }
        report.added += added;
        polish_rounds(scene, &people, rounds, &mut report);
    }
    report.max_move = scene
        .objects
        .iter()
        .zip(&start)
        .map(|(o, s)| DVec2::new(o.center[0], o.center[1]).distance(*s))
        .fold(0.0, f64::max);
    let mut holds = people.holding(scene.objects.len());
    report.relocated = relocate_off_paths(scene, &people.clearance, &holds);
    report.swapped = single_beds_off_paths(scene, &people);
    report.trimmed = trim_deep_seats(scene, &people);
    report.trimmed += trim_beds_to_sitters(scene, &people);
    report.trimmed += trim_sofas_to_sleepers(scene, &people);
    report.trimmed += trim_touched_fronts(scene, &people);
    report.widened = widen_for_people(scene, &people);
    report.narrowed += fit_into_room(scene, &people);
    report.narrowed += narrow_off_paths(scene, &people.cond, |i, o| keeps_its_people(&people, i, o));
    let (pushed, bones) = push_off_bodies(scene, &people.clearance, &holds);
    report.pushed = pushed;
    report.left_out = leave_out_entered(scene, &bones, &people.cond.contact_boxes, &mut holds);
    let overlaps = resolve_overlaps(scene, &holds);
    report.narrowed += overlaps.narrowed;
    report.removed = overlaps.removed;
    report
}

/// One pass: turning and fitting the holders, then up to `rounds` rounds of moves.
fn polish_rounds(scene: &mut Scene, people: &Occupancy, rounds: usize, report: &mut PolishReport) {
    let Occupancy { cond, gaps, clearance, holders } = people;
    let polygon = scene.floor_plan.polygon();
    let start_yaw: Vec<f64> = scene.objects.iter().map(|o| o.yaw).collect();
    // A bed with a sleeper keeps its orientation whatever its sitters face (beds are not turned to
    // sleepers: that made more bedrooms penetrate).
    let mut turned: Vec<bool> = (0..scene.objects.len())
        .map(|i| {
            scene.objects[i].category.group() == Group::Bed
                && holders.iter().any(|(b, h)| *h == i && cond.contact_boxes[*b].action == Action::Lie)
        })
        .collect();
    let kept = turned.clone();
    for (b, i) in holders {
        let contact = &cond.contact_boxes[*b];
        if let Some(yaw) = facing_yaw(&scene.objects[*i], contact).filter(|_| !turned[*i]) {
            scene.objects[*i].yaw = yaw;
            turned[*i] = true;
        }
        report.resized += fit_size(&mut scene.objects[*i], contact, &gaps[*b]) as usize;
    }
    report.turned += turned.iter().zip(&kept).filter(|(t, k)| **t && !**k).count();
    // The data's pieces all stand square to the walls; so do ours (seats the quarter turn nearest
    // their sitter).
    if let Some(wall) = longest_wall_direction(&polygon) {
        for (o, start) in scene.objects.iter_mut().zip(&start_yaw) {
            o.yaw = square_yaw(o.yaw, wall);
            report.squared += (wrap_angle(o.yaw - start).abs() > 1e-3) as usize;
        }
    }
    report.walled += back_to_walls(scene, people);
    let mobility: Vec<f64> =
        (0..scene.objects.len()).map(|i| if people.holds(i) { ANCHORED_MOBILITY } else { 1.0 }).collect();
    for round in 0..rounds {
        let before: Vec<[f64; 3]> = scene.objects.iter().map(|o| o.center).collect();
        // The last third of the rounds leaves the contacts where they are, the last five the paths.
        let mut moves = vec![DVec2::ZERO; scene.objects.len()];
        let mut counts = vec![0usize; scene.objects.len()];
        if round * 3 < rounds * 2 {
            for (b, i) in holders {
                moves[*i] += containment_shift(&cond.contact_boxes[*b], &gaps[*b], &scene.objects[*i]);
                counts[*i] += 1;
            }
        }
        for (i, o) in scene.objects.iter_mut().enumerate() {
            shift(o, (moves[i] / counts[i].max(1) as f64).clamp_length_max(MAX_STEP));
            if round + 5 < rounds {
                // A holder gives way to walkers only as far as its people stay on it.
                let push = within_slack(o, &people.held_by(i), path_push(o, clearance));
                shift(o, push.clamp_length_max(MAX_STEP));
            }
        }
        for i in 0..scene.objects.len() {
            for j in i + 1..scene.objects.len() {
                let (a, b) = (scene.objects[i].obox(), scene.objects[j].obox());
                if intersection_volume(&a, &b) <= 1e-9 {
                    continue;
                }
                let (wi, wj) = (mobility[i], mobility[j]);
                let (si, sj) = (wi / (wi + wj), wj / (wi + wj));
                // The shortest separation that keeps both inside the walls, else the shortest.
                let fits = |m: DVec2| {
                    let moved = |o: &OBox, d: DVec2| OBox::new(o.center + d.extend(0.0), o.size, o.yaw);
                    inside_push(&moved(&a, m * si), &polygon).length() < 1e-6
                        && inside_push(&moved(&b, -m * sj), &polygon).length() < 1e-6
                };
                let separations = footprint_separations(&a, &b);
                let Some(&mtv) = separations.iter().find(|m| fits(**m)).or(separations.first()) else { continue };
                shift(&mut scene.objects[i], mtv * si);
                shift(&mut scene.objects[j], -mtv * sj);
            }
        }
        for o in &mut scene.objects {
            let w = inside_push(&o.obox(), &polygon);
            shift(o, w);
        }
        report.rounds += 1;
        let moved = scene
            .objects
            .iter()
            .zip(&before)
            .map(|(o, c)| DVec2::new(o.center[0] - c[0], o.center[1] - c[1]).length())
            .fold(0.0, f64::max);
        if moved < 1e-3 {
            break;
        }
    }
}

/// Moves every piece the rounds left poking out of the floor plan back over the contact boxes it
/// holds and inside; where it still does not fit, narrows it by what sticks out (at most 10 cm and
/// a quarter of its size) if that makes it fit. Returns how many pieces were narrowed.
fn fit_into_room(scene: &mut Scene, people: &Occupancy) -> usize {
    let polygon = scene.floor_plan.polygon();
    let mut narrowed = 0;
    for i in 0..scene.objects.len() {
        if fits_inside(&scene.objects[i].obox(), &polygon) {
            continue;
        }
        let before = scene.objects[i].clone();
        let o = &mut scene.objects[i];
        let held = people.held_by(i);
        if !held.is_empty() {
            let m = held.iter().map(|(b, gap)| containment_shift(b, gap, o)).sum::<DVec2>() / held.len() as f64;
            shift(o, m);
        }
        let w = inside_push(&o.obox(), &polygon);
        shift(o, w);
        if fits_inside(&o.obox(), &polygon) {
            continue;
        }
        // A piece a few centimetres too big for its place is narrowed to fit.
        *o = before;
        let mut cut = o.clone();
        for _ in 0..3 {
            match worst_offence(&cut.obox(), &polygon) {
                None => {
                    *o = cut;
                    narrowed += 1;
                    break;
                }
                Some((_, push)) if narrow_by(&mut cut, push) => {}
                Some(_) => break,
            }
        }
    }
    narrowed
}

/// Puts every piece the data stands against a wall back against one (`walls`): a piece holding
/// nobody against the first of [`wall_poses`] (behind, in front, beside) least in people's way; a
/// holder towards the wall behind it as far as its people stay on it. Returns how many pieces moved
/// or turned.
fn back_to_walls(scene: &mut Scene, people: &Occupancy) -> usize {
    let polygon = scene.floor_plan.polygon();
    let mut walled = 0;
    for i in 0..scene.objects.len() {
        if !stands_against_wall(scene.objects[i].category) {
            continue;
        }
        let held = people.held_by(i);
        let o = &mut scene.objects[i];
        let (yaw, m) = if held.is_empty() {
            let in_the_way = |&(yaw, m): &(f64, DVec2)| {
                let b = o.obox();
                people.clearance.blocked(&OBox::new(b.center + m.extend(0.0), b.size, yaw), true).len()
            };
            // `min_by_key` keeps the first of equals: the nearer wall.
            let Some(pose) = wall_poses(&o.obox(), &polygon).into_iter().min_by_key(in_the_way) else { continue };
            pose
        } else {
            let Some(m) = to_wall_behind(&o.obox(), &polygon) else { continue };
            (o.yaw, within_slack(o, &held, m))
        };
        if m.length() > 1e-3 || wrap_angle(yaw - o.yaw).abs() > 1e-3 {
            walled += 1;
        }
        o.yaw = yaw;
        shift(o, m);
    }
    walled
}

/// The direction (rad) of the floor plan's longest wall.
fn longest_wall_direction(polygon: &crate::geom::Polygon) -> Option<f64> {
    let (a, b) = polygon.edges().max_by(|x, y| (x.1 - x.0).length().total_cmp(&(y.1 - y.0).length()))?;
    Some((b - a).to_angle())
}

/// The yaw nearest `yaw` among `wall` plus quarter turns, in (−π, π].
fn square_yaw(yaw: f64, wall: f64) -> f64 {
    let quarter = std::f64::consts::FRAC_PI_2;
    wrap_angle(wall + ((yaw - wall) / quarter).round() * quarter)
}

/// Whether `o`, standing in for object `i`, still has every box `i` holds on the part of it the
/// box must be on ([`holding_region`]); true for a piece that holds nobody.
fn keeps_its_people(people: &Occupancy, i: usize, o: &Object) -> bool {
    people.held_by(i).iter().all(|(c, gaps)| containment_shift(c, gaps, o).length() < 1e-3)
}

/// Narrows every standing piece off the walkers' feet (the free-space mask the Col_mot metric
/// counts), where cutting one side by at most 10 cm and a quarter of the piece clears every
/// covered pixel and the narrowed piece `keeps` its people (`keeps(i, narrowed)`: a holder's
/// people still on the part they must be on). Returns how many it narrowed.
fn narrow_off_paths(scene: &mut Scene, cond: &Conditions, keeps: impl Fn(usize, &Object) -> bool) -> usize {
    let (window, free) = (&cond.window, &cond.free_space);
    let mut narrowed = 0;
    for (i, o) in scene.objects.iter_mut().enumerate() {
        if o.category.is_hanging() {
            continue;
        }
        let b = o.obox();
        let (lo, hi) = b.footprint_aabb();
        let (cols, rows) = window.pixel_ranges(lo, hi);
        let covered: Vec<DVec2> = rows
            .flat_map(|j| cols.clone().map(move |i| (i, j)))
            .filter(|&(i, j)| free.get(i, j) && b.footprint_contains(window.pixel_center(i, j)))
            .map(|(i, j)| b.to_local(window.pixel_center(i, j).extend(b.center.z)).truncate())
            .collect();
        if covered.is_empty() {
            continue;
        }
        // The cheapest side to cut: past the farthest covered pixel from that side, half a pixel more.
        let (ax, ay) = b.axes();
        let half = b.half().truncate();
        let margin = window.pixel() * 0.5;
        let (min, max) = covered.iter().fold((half, -half), |(lo, hi), p| (lo.min(*p), hi.max(*p)));
        let cuts = [
            (half.x - min.x + margin, -ax),
            (max.x + half.x + margin, ax),
            (half.y - min.y + margin, -ay),
            (max.y + half.y + margin, ay),
        ];
        let (cut, dir) = cuts.into_iter().min_by(|a, b| a.0.total_cmp(&b.0)).expect("four sides");
        let mut cand = o.clone();
        if narrow_by(&mut cand, dir * cut) && keeps(i, &cand) {
            *o = cand;
            narrowed += 1;
        }
    }
    narrowed
}

pub(super) fn shift(o: &mut Object, m: DVec2) {
    o.center[0] += m.x;
    o.center[1] += m.y;
}

/// Adds a piece of furniture for each of the `missing` contact boxes (boxes at one place share
/// one), within the room type's object limit, and makes it their holder. Returns how many were added.
fn complete_supports(
    scene: &mut Scene,
    cond: &Conditions,
    missing: &[usize],
    holders: &mut Vec<(usize, usize)>,
) -> usize {
    let mut added: Vec<(usize, usize)> = Vec::new();
    for &k in missing {
        let contact = &cond.contact_boxes[k];
        let shared = added.iter().find(|(b, _)| iou_3d(&cond.contact_boxes[*b].obox, &contact.obox) >= 0.5);
        let holder = match shared {
            Some(&(_, i)) => i,
            None if scene.objects.len() < scene.room_type.max_objects() => {
                let Some(o) = support_for(scene, contact) else { continue };
                scene.objects.push(o);
                scene.objects.len() - 1
            }
            None => break,
        };
        added.push((k, holder));
    }
    holders.retain(|(b, _)| !added.iter().any(|(k, _)| k == b));
    let count = added.iter().map(|(_, i)| *i).collect::<std::collections::BTreeSet<_>>().len();
    holders.extend(added);
    holders.sort_unstable();
    count
}

/// Width of one person's place on a sofa or bed (m).
const PLACE_WIDTH: f64 = 0.55;

/// How many spatially distinct contact boxes `o` can hold: one per chair or stool, one per place
/// along a sofa or bed, any number of touches.
fn capacity(o: &Object) -> usize {
    match o.category.group() {
        Group::Chair | Group::Stool => 1,
        Group::Sofa | Group::Bed => ((o.size[0].max(o.size[1]) / PLACE_WIDTH).floor() as usize).max(1),
        _ => usize::MAX,
    }
}

/// (contact box index, object index) for every contact box some object can hold: greedily, best
/// covered pairs first, then nearest (within 2 m), each object holding at most its capacity of
/// boxes (boxes of one place at different times count once).
fn assign_contacts(scene: &Scene, cond: &Conditions) -> Vec<(usize, usize)> {
    let boxes = &cond.contact_boxes;
    let mut candidates: Vec<(f64, f64, usize, usize)> = Vec::new();
    for (k, b) in boxes.iter().enumerate() {
        if !matches!(b.action, Action::Sit | Action::Lie | Action::Touch) {
            continue;
        }
        for (i, o) in scene.objects.iter().enumerate().filter(|(_, o)| o.category.affords(b.action)) {
            let cover = contact_iou(&b.obox, std::slice::from_ref(o));
            let distance = DVec2::from_slice(&o.center[..2]).distance(b.obox.center.truncate());
            if cover > 0.0 || distance < MAX_ASSIGN_DISTANCE {
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
        if same.contains(&true) || places < capacity(&scene.objects[i]) {
            held.push((k, i));
        }
    }
    held.sort_unstable();
    held
}

/// The yaw `o` takes for the person of `contact`: a chair, stool or sofa faces like its sitter (its
/// front the way they face), a sofa lies along its sleeper (the body along its local x, as the data
/// lays people on sofas), a bed a quarter turn where its sitter faces along it, a touched table,
/// cabinet or shelf faces its toucher (its front towards them, as the data touches pieces). Beds are
/// not turned to their sleepers (that made penetrating bedrooms more frequent: 0.886 → 0.909 of the
/// test split).
fn facing_yaw(o: &Object, contact: &ContactBox) -> Option<f64> {
    match (o.category.group(), contact.action) {
        (Group::Table | Group::Cabinet | Group::Shelf, Action::Touch) => Some(contact.obox.yaw + std::f64::consts::PI),
        (Group::Chair | Group::Stool | Group::Sofa, Action::Sit) => Some(contact.obox.yaw),
        (Group::Sofa, Action::Lie) => Some(contact.obox.yaw + std::f64::consts::FRAC_PI_2),
        // A quarter turn where the sitter faces along the bed: the data seats people on its sides.
        (Group::Bed, Action::Sit) => {
            let f = bed_local_facing(o, contact);
            (f.y.abs() > f.x.abs()).then_some(o.yaw + std::f64::consts::FRAC_PI_2)
        }
        _ => None,
    }
}

/// The way `contact`'s person faces, in `o`'s frame (unit).
fn bed_local_facing(o: &Object, contact: &ContactBox) -> DVec2 {
    facing(contact.obox.yaw - o.yaw)
}

/// Fits a floor-standing object to `contact`: a seat's or bed's surface goes to the top of a sitter's
/// or sleeper's support volume (up or down), a low piece's top down to a palm resting on it
/// ([`rests_palm_on_top`]; only where the category's real pieces, less 15 cm, are that low),
/// anything else grows to the top of the box; width and
/// depth grow until the box fits the part it must be on ([`holding_region`]). A surface's height
/// stays within the category's real pieces' (± 15 cm), any other height changes by at most 15 cm,
/// width and depth by at most 20 cm. Returns whether it changed.
fn fit_size(o: &mut Object, contact: &ContactBox, gaps: &SeatGaps) -> bool {
    if o.category.is_hanging() {
        return false;
    }
    let before = o.size;
    let top = contact.obox.z_range().1;
    let surface = template(o).surface.filter(|_| matches!(contact.action, Action::Sit | Action::Lie));
    let height = match surface {
        // Any height real pieces of the category have, give or take MAX_GROW_HEIGHT.
        // A top above a resting palm comes down to it where the category's real pieces (give or
        // take MAX_GROW_HEIGHT) are that low; part of the way would only put it in the forearm.
        _ if rests_palm_on_top(o, contact) && o.size[2] > top => {
            Some(top).filter(|&h| h >= height_range(o.category).0 - MAX_GROW_HEIGHT)
        }
        Some(_) => {
            let (lo, hi) = height_range(o.category);
            Some(height_within(o.category, o.size, top, (lo - MAX_GROW_HEIGHT, hi + MAX_GROW_HEIGHT)))
        }
        None => Some(o.size[2].max(top)).filter(|h| h - o.size[2] <= MAX_GROW_HEIGHT),
    };
    if let Some(height) = height {
        o.size[2] = height;
        o.center[2] = height * 0.5;
    }
    let (lo, hi) = local_extent(&contact.obox, &o.obox());
    let (region_lo, region_hi) = holding_region(o, contact, gaps);
    for k in 0..2 {
        let need = (hi[k] - lo[k]) + (o.size[k] - (region_hi[k] - region_lo[k]));
        if need > o.size[k] && need - o.size[k] <= MAX_GROW_EXTENT {
            o.size[k] = need;
        }
    }
    o.size != before
}

/// Whether `contact` is a palm resting on `o`'s top: a touch at most [`TOP_TOUCH_HEIGHT`] high on
/// a table, cabinet or shelf no taller than that (the data rests the palm on the top of such a
/// piece, the top at the touch box's top, and touches a taller one's front).
fn rests_palm_on_top(o: &Object, contact: &ContactBox) -> bool {
    contact.action == Action::Touch
        && contact.obox.center.z <= TOP_TOUCH_HEIGHT
        && o.size[2] <= TOP_TOUCH_HEIGHT
        && matches!(o.category.group(), Group::Table | Group::Cabinet | Group::Shelf)
}

/// Whether `contact` is a palm on `o`'s front face: a touch of a cabinet, shelf or table taller
/// than [`TOP_TOUCH_HEIGHT`] (the data touches such a piece on its front, facing it).
pub(super) fn touches_front(o: &Object, contact: &ContactBox) -> bool {
    contact.action == Action::Touch
        && o.size[2] > TOP_TOUCH_HEIGHT
        && matches!(o.category.group(), Group::Table | Group::Cabinet | Group::Shelf)
}

/// How much deeper than a front touch's pressed volume the band behind the front face is (m).
const FRONT_TOUCH_SLACK: f64 = 0.03;

/// The part of `o`'s footprint (local min, max corners) the person of `contact` must be on: a
/// seat's or bed's surface for sitting and lying (on a chair or sofa, clear of the backrest and
/// near enough the front edge for the knees to pass it, [`SeatGaps`]), the whole footprint
/// otherwise.
fn holding_region(o: &Object, contact: &ContactBox, gaps: &SeatGaps) -> (DVec2, DVec2) {
    let half = DVec2::new(o.size[0], o.size[1]) * 0.5;
    let action = contact.action;
    if touches_front(o, contact) {
        // The pressed volume just behind the front face (local +y), where the data puts the palm.
        let (lo, hi) = local_extent(&contact.obox, &o.obox());
        let depth = hi.y - lo.y + FRONT_TOUCH_SLACK;
        return (DVec2::new(-half.x, (half.y - depth).max(-half.y)), half);
    }
    let Some(surface) = template(o).surface.filter(|_| matches!(action, Action::Sit | Action::Lie)) else {
        return (-half, half);
    };
    if action == Action::Sit && o.category.group() == Group::Bed {
        return bed_edge_region(o, contact, (surface.min, surface.max));
    }
    let backed = action == Action::Sit && matches!(o.category.group(), Group::Chair | Group::Sofa);
    if !backed {
        return (surface.min, surface.max);
    }
    // The box's front at most `gaps.front` behind the seat's front edge (local +y), unless that
    // leaves no room behind: a seat too shallow for it.
    let (lo, hi) = local_extent(&contact.obox, &o.obox());
    let start = (surface.min.y + gaps.back).max(surface.max.y - gaps.front(contact, o) - (hi.y - lo.y));
    (DVec2::new(surface.min.x, start), surface.max)
}

/// How far a bed sitter's support box may overhang the edge they sit on (m): the box reaches a
/// third down the thighs, which the data seats 20 cm from the edge.
pub(super) const BED_EDGE_OVERHANG: f64 = 0.1;
/// How far behind the edge the front of a bed sitter's support box may be (m).
const BED_EDGE_BAND: f64 = 0.05;

/// Where a bed sitter's support box must be (local min, max corners): against the edge of the
/// mattress they face, so that their lower legs hang outside the bed, not in it.
fn bed_edge_region(o: &Object, contact: &ContactBox, (mut lo, mut hi): (DVec2, DVec2)) -> (DVec2, DVec2) {
    let (k, ahead) = bed_edge_faced(o, contact);
    let (box_lo, box_hi) = local_extent(&contact.obox, &o.obox());
    let reach = box_hi[k] - box_lo[k] + BED_EDGE_OVERHANG + BED_EDGE_BAND;
    if ahead {
        hi[k] += BED_EDGE_OVERHANG;
        lo[k] = lo[k].max(hi[k] - reach);
    } else {
        lo[k] -= BED_EDGE_OVERHANG;
        hi[k] = hi[k].min(lo[k] + reach);
    }
    (lo, hi)
}

/// The edge of bed `o` that `contact`'s person faces: its local axis (0: x, 1: y) and whether it is
/// the edge on that axis's positive side.
pub(super) fn bed_edge_faced(o: &Object, contact: &ContactBox) -> (usize, bool) {
    let f = bed_local_facing(o, contact);
    let k = if f.x.abs() >= f.y.abs() { 0 } else { 1 };
    (k, f[k] > 0.0)
}

/// The contact box's footprint corners in `o`'s frame: (min, max) per axis.
pub(super) fn local_extent(contact: &OBox, o: &OBox) -> (DVec2, DVec2) {
    let corners = contact.footprint().map(|p| o.to_local(p.extend(o.center.z)).truncate());
    let lo = corners.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = corners.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    (lo, hi)
}

/// The smallest move of `o` (world, m) that puts `contact`'s footprint inside the part of `o` it
/// must be on ([`holding_region`]), or centres it there where it cannot fit.
fn containment_shift(contact: &ContactBox, gaps: &SeatGaps, o: &Object) -> DVec2 {
    let b = o.obox();
    let (lo, hi) = local_extent(&contact.obox, &b);
    let (region_lo, region_hi) = holding_region(o, contact, gaps);
    let mut s = DVec2::ZERO;
    for k in 0..2 {
        // Any shift in [hi − region_hi, lo − region_lo] contains the box; an empty range: centre it.
        let (from, to) = (hi[k] - region_hi[k], lo[k] - region_lo[k]);
        s[k] = if from > to { (hi[k] + lo[k] - region_hi[k] - region_lo[k]) * 0.5 } else { 0.0f64.clamp(from, to) };
    }
    let (ax, ay) = b.axes();
    ax * s.x + ay * s.y
}

/// `m` (world) limited, along each of `o`'s axes, to the moves that keep every `held` box on the
/// part of `o` it must be on ([`holding_region`]); `m` itself when `o` holds nothing.
fn within_slack(o: &Object, held: &[(&ContactBox, &SeatGaps)], m: DVec2) -> DVec2 {
    if held.is_empty() {
        return m;
    }
    let b = o.obox();
    let (ax, ay) = b.axes();
    let mut local = DVec2::new(m.dot(ax), m.dot(ay));
    for (contact, gaps) in held {
        let (lo, hi) = local_extent(&contact.obox, &b);
        let (region_lo, region_hi) = holding_region(o, contact, gaps);
        for k in 0..2 {
            // Moving o by s moves the box by −s in o's frame: s ∈ [hi − region_hi, lo − region_lo].
            let (from, to) = ((hi[k] - region_hi[k]).min(0.0), (lo[k] - region_lo[k]).max(0.0));
            local[k] = local[k].clamp(from, to);
        }
    }
    ax * local.x + ay * local.y
}

/// The moves of `a` (m) that separate its footprint from `b`'s along each separating axis (both
/// directions), with a little clearance, shortest first; empty if the footprints do not overlap.
pub(super) fn footprint_separations(a: &OBox, b: &OBox) -> Vec<DVec2> {
    let (pa, pb) = (a.footprint(), b.footprint());
    let (a1, a2) = a.axes();
    let (b1, b2) = b.axes();
    let mut out = Vec::with_capacity(8);
    for axis in [a1, a2, b1, b2] {
        let span = |ps: &[DVec2; 4]| {
            ps.iter().map(|p| p.dot(axis)).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)))
        };
        let ((la, ha), (lb, hb)) = (span(&pa), span(&pb));
        if ha.min(hb) - la.max(lb) <= 0.0 {
            return Vec::new();
        }
        // Moving a along +axis until its low end passes b's high end, or along −axis.
        out.push(axis * (hb - la + CLEARANCE));
        out.push(-axis * (ha - lb + CLEARANCE));
    }
    out.sort_by(|x, y| x.length().total_cmp(&y.length()));
    out
}

/// A push of `o` out of people's way (walkers' bodies; for a solid piece also sitters' and
/// touchers' shins and feet): away from the centroid of the pixels where it meets them, by their
/// area over its longer side.
fn path_push(o: &Object, clearance: &Clearance) -> DVec2 {
    let b = o.obox();
    // A piece without legs is solid to the floor: a sitter's feet cannot go under it.
    let blocked = clearance.blocked(&b, is_solid(o));
    if blocked.is_empty() {
        return DVec2::ZERO;
    }
    let w = clearance.window();
    let centroid = blocked.iter().sum::<DVec2>() / blocked.len() as f64;
    let dir = (b.center.truncate() - centroid).try_normalize().unwrap_or(DVec2::X);
    let depth = blocked.len() as f64 * w.pixel_area() / b.size.x.max(b.size.y);
    dir * depth.clamp(w.pixel(), MAX_STEP)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::eval::{LayoutCounts, scene_contact_iou};
    use crate::scene::RoomType;
    use glam::DVec3;

    #[test]
    fn a_clean_room_stays_as_it_is() {
        let mut turned = 0;
        for (room, index) in [(RoomType::Bedroom, 0), (RoomType::Dining, 1), (RoomType::Living, 2)] {
            let mut scene = generate_room(room, 3, index, false).scene;
            let before = scene.clone();
            let r = polish_scene(&mut scene, 30);
            // The data lets a sitter's back press up to ~1 cm into a backrest; polishing keeps it
            // 1 cm clear, so a seat may move back by about 2 cm. Nothing else moves.
            assert!(r.max_move < 0.025, "{room}: {r:?}");
            assert_eq!((r.added, r.squared, r.narrowed, r.removed), (0, 0, 0, 0), "{room}");
            assert_eq!(scene.objects.len(), before.objects.len());
            // Seats already face their sitters: turning them changes nothing.
            for (o, b) in scene.objects.iter().zip(&before.objects) {
                let d = (o.yaw - b.yaw).rem_euclid(std::f64::consts::TAU);
                assert!(d.min(std::f64::consts::TAU - d) < 0.05, "{room}: {} turned from {} to {}", o.id, b.yaw, o.yaw);
            }
            turned += r.turned;
        }
        assert!(turned > 0, "some seat was checked");
    }

    #[test]
    fn shifted_furniture_comes_back_under_its_people_inside_the_walls_and_apart() {
        let mut scene = generate_room(RoomType::Dining, 4, 3, false).scene;
        let iou = scene_contact_iou(&scene).unwrap();
        // Shift everything by 12 cm towards a corner and push one piece half out of the room.
        for o in &mut scene.objects {
            o.center[0] -= 0.12;
            o.center[1] -= 0.12;
        }
        let (lo, _) = scene.floor_plan.polygon().bounds();
        scene.objects[0].center[0] = lo.x;
        let broken = LayoutCounts::of(&scene);
        assert!(broken.outside > 0 && scene_contact_iou(&scene).unwrap() < iou - 0.05);
        let r = polish_scene(&mut scene, 30);
        let fixed = LayoutCounts::of(&scene);
        assert_eq!(fixed.outside, 0, "{r:?}");
        assert!(fixed.colliding <= broken.colliding, "{fixed:?} vs {broken:?}");
        assert!(scene_contact_iou(&scene).unwrap() > iou - 0.05, "{} vs {iou}", scene_contact_iou(&scene).unwrap());
    }

    #[test]
    fn every_piece_ends_square_to_the_walls() {
        let mut scene = generate_room(RoomType::Bedroom, 4, 1, false).scene;
        for (k, o) in scene.objects.iter_mut().enumerate() {
            o.yaw += 0.05 + 0.1 * k as f64 % 0.6 - 0.3 + std::f64::consts::TAU * (k % 3) as f64;
        }
        let r = polish_scene(&mut scene, 30);
        assert!(r.squared >= scene.objects.len() - 1, "{r:?}");
        for o in &scene.objects {
            let off = o.yaw.rem_euclid(std::f64::consts::FRAC_PI_2);
            assert!(off.min(std::f64::consts::FRAC_PI_2 - off) < 1e-9, "{} at {}", o.id, o.yaw);
            assert!(o.yaw > -std::f64::consts::PI && o.yaw <= std::f64::consts::PI, "{} at {}", o.id, o.yaw);
        }
    }

    #[test]
    fn a_wardrobe_left_in_the_middle_of_the_room_goes_back_to_a_wall() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.humans.clear();
        scene.floor_plan.polygon = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.5], [0.0, 3.5]];
        scene.objects = vec![Object {
            id: "o0".into(),
            category: crate::scene::Category::Wardrobe,
            center: [2.0, 1.5, 1.0],
            size: [1.6, 0.6, 2.0],
            yaw: 0.2,
        }];
        let r = polish_scene(&mut scene, 30);
        assert_eq!((r.squared, r.walled), (1, 1), "{r:?}");
        // Square, its back (local −y) 5 cm from the south wall, the nearest one behind or in front.
        let o = &scene.objects[0];
        assert!(o.yaw.abs() < 1e-12, "{o:?}");
        assert!((o.center[1] - 0.3 - 0.05).abs() < 1e-9 && (o.center[0] - 2.0).abs() < 1e-9, "{o:?}");
    }

    #[test]
    fn separations_part_two_overlapping_boxes_shortest_first() {
        let a = OBox::new(DVec3::new(0.0, 0.0, 0.5), DVec3::new(1.0, 1.0, 1.0), 0.0);
        let b = OBox::new(DVec3::new(0.8, 0.1, 0.5), DVec3::new(1.0, 1.0, 1.0), 0.0);
        let all = footprint_separations(&a, &b);
        assert_eq!(all.len(), 8);
        // a spans [−0.5, 0.5]², b [0.3, 1.3] × [−0.4, 0.6] (both axes twice): 0.2 left, 0.9 down,
        // 1.1 up, 1.8 right.
        assert!((all[0] - DVec2::new(-(0.2 + CLEARANCE), 0.0)).length() < 1e-12, "{all:?}");
        assert!((all[2] - DVec2::new(0.0, -(0.9 + CLEARANCE))).length() < 1e-12, "{all:?}");
        for m in &all {
            let moved = OBox::new(a.center + m.extend(0.0), a.size, 0.0);
            assert!(intersection_volume(&moved, &b) <= 1e-12, "{m}");
            assert!(footprint_separations(&moved, &b).is_empty());
        }
    }

    #[test]
    fn a_diagonal_bed_too_wide_for_its_room_is_squared_and_a_slightly_long_one_narrowed() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.humans.clear();
        // A corridor-like room 2.2 m wide: a 1.4 × 2.0 m bed at 0.7 rad needs 2.36 m.
        scene.floor_plan.polygon = vec![[0.0, 0.0], [2.2, 0.0], [2.2, 4.0], [0.0, 4.0]];
        let bed = |yaw: f64, size: [f64; 3]| Object {
            id: "o0".into(),
            category: crate::scene::Category::DoubleBed,
            center: [1.1, 2.0, size[2] * 0.5],
            size,
            yaw,
        };
        scene.objects = vec![bed(0.7, [1.4, 2.0, 0.5])];
        let r = polish_scene(&mut scene, 30);
        assert_eq!(r.squared, 1, "{r:?}");
        assert_eq!(scene.objects[0].yaw, 0.0);
        assert_eq!(scene.objects[0].size, [1.4, 2.0, 0.5]);
        assert!(fits_inside(&scene.objects[0].obox(), &scene.floor_plan.polygon()));
        // Square already but 2.25 m wide in 2.2 m: narrowed by the 5 cm and twice the clearance.
        scene.objects = vec![bed(0.0, [2.25, 1.8, 0.5])];
        let r = polish_scene(&mut scene, 30);
        assert_eq!((r.squared, r.narrowed), (0, 1), "{r:?}");
        let w = scene.objects[0].size[0];
        assert!(w < 2.2 - 2.0 * CLEARANCE + 1e-9 && w > 2.15, "{w}");
        assert!(fits_inside(&scene.objects[0].obox(), &scene.floor_plan.polygon()));
    }

    #[test]
    fn a_wardrobe_whose_nearest_wall_is_a_walkway_goes_to_the_wall_behind_it() {
        use crate::human::{Body, Motion};
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.5], [0.0, 3.5]];
        let wardrobe = |center: [f64; 3], yaw: f64| Object {
            id: "o0".into(),
            category: crate::scene::Category::Wardrobe,
            center,
            size: [1.6, 0.6, 2.0],
            yaw,
        };
        // Facing −y, its front 1.2 m from the south wall and its back 1.7 m from the north one.
        let start = wardrobe([2.0, 1.5, 1.0], std::f64::consts::PI);
        // Nobody about: the nearer wall, south, turned half round (the test above).
        scene.humans.clear();
        scene.objects = vec![start.clone()];
        polish_scene(&mut scene, 30);
        assert!((scene.objects[0].center[1] - 0.35).abs() < 1e-9, "{:?}", scene.objects[0]);
        // Someone walking along the south wall, 40 cm off it: the north wall, unturned.
        let path = crate::geom::Polyline::new(vec![DVec2::new(0.4, 0.4), DVec2::new(3.6, 0.4)]).unwrap();
        let mut walk = Motion::new(Body::default(), 30.0);
        walk.walk(&path, 1.2);
        scene.humans = vec![walk.into_human("h0")];
        scene.objects = vec![start];
        let r = polish_scene(&mut scene, 30);
        assert_eq!(r.walled, 1, "{r:?}");
        assert_eq!(scene.objects[0], wardrobe([2.0, 3.5 - 0.3 - 0.05, 1.0], std::f64::consts::PI), "{r:?}");
    }

    #[test]
    fn a_piece_a_few_centimetres_over_the_walkers_feet_is_narrowed_off_them() {
        let mut scene = generate_room(RoomType::Living, 3, 2, false).scene;
        scene.humans.clear();
        let mut cond = Conditions::of(&scene);
        // A column of walked pixels at x ≈ 2.0 m.
        let w = cond.window;
        let column = (0..crate::geom::RES).find(|&i| w.pixel_center(i, 0).x > 2.0).unwrap();
        cond.free_space = crate::geom::Mask::new();
        for j in 0..crate::geom::RES {
            cond.free_space.set(column, j);
        }
        let x = w.pixel_center(column, 0).x;
        let cabinet = |center_x: f64| Object {
            id: "o0".into(),
            category: crate::scene::Category::Cabinet,
            center: [center_x, w.center.y, 0.4],
            size: [0.8, 0.4, 0.8],
            yaw: 0.0,
        };
        // Its +x side 4 cm past the column's centres: cut back to half a pixel short of them.
        scene.objects = vec![cabinet(x + 0.04 - 0.4)];
        assert_eq!(narrow_off_paths(&mut scene, &cond, |_, _| true), 1);
        let o = &scene.objects[0];
        assert!((o.center[0] + o.size[0] * 0.5 - (x - w.pixel() * 0.5)).abs() < 1e-9, "{o:?}");
        assert!((o.center[0] - o.size[0] * 0.5 - (x + 0.04 - 0.8)).abs() < 1e-9, "the far side stays");
        // A toucher's palm on the cabinet's top 20 cm in from its +x end: the same cut keeps it
        // there (it is polishing's rule for a holder), one 15 cm further would not.
        let mut held = scene.clone();
        held.objects = vec![cabinet(x + 0.04 - 0.4)];
        let body = crate::human::Body::default();
        let mut m = crate::human::Motion::new(body, 30.0);
        let palm = glam::DVec3::new(x + 0.04 - 0.2, w.center.y + 0.08, 0.8);
        m.hold(crate::human::touch(&body, palm, std::f64::consts::PI, crate::human::Side::Right), 3, Action::Touch);
        held.humans = vec![m.into_human("h0")];
        let mut people = Occupancy::of(&held);
        people.holders = vec![(0, 0)];
        let (mut cut, mut cut_more) = (held.objects[0].clone(), held.objects[0].clone());
        assert!(narrow_by(&mut cut, DVec2::new(-0.04, 0.0)));
        cut_more.size[0] -= 0.19;
        cut_more.center[0] -= 0.095;
        assert!(keeps_its_people(&people, 0, &held.objects[0]), "held at first");
        assert!(keeps_its_people(&people, 0, &cut) && !keeps_its_people(&people, 0, &cut_more));
        // 20 cm over: left alone; a piece whose people the cut would leave: left alone.
        for (center, keeps) in [(x + 0.2 - 0.4, true), (x + 0.04 - 0.4, false)] {
            scene.objects = vec![cabinet(center)];
            assert_eq!(narrow_off_paths(&mut scene, &cond, |_, _| keeps), 0);
            assert_eq!(scene.objects[0], cabinet(center));
        }
    }

    #[test]
    fn a_bed_on_the_wrong_side_of_its_sitter_goes_behind_them() {
        let mut checked = 0;
        for index in 0..40 {
            let mut scene = generate_room(RoomType::Bedroom, 5, index, false).scene;
            let boxes = Conditions::contact_boxes_of(&scene);
            let Some((sit, bed)) = boxes.iter().filter(|b| b.action == Action::Sit).find_map(|b| {
                let bed = scene.objects.iter().find(|o| {
                    o.category.group() == Group::Bed && contact_iou(&b.obox, std::slice::from_ref(*o)) > 0.9
                })?;
                Some((b.clone(), bed.clone()))
            }) else {
                continue;
            };
            // The bed moved across, in front of the sitter: now they sit on its far edge facing in,
            // their lower legs in the mattress.
            let mut moved = bed.clone();
            shift(&mut moved, facing(sit.obox.yaw) * (bed.size[0] - 0.4));
            if !fits_inside(&moved.obox(), &scene.floor_plan.polygon()) {
                continue;
            }
            let human = scene.humans.iter().find(|h| h.id == sit.human).unwrap().clone();
            scene.humans = vec![human.clone()];
            scene.objects = vec![moved];
            let feet = ["left_ankle", "right_ankle", "left_toe", "right_toe"]
                .map(|n| human.joint_at(0, human.skeleton.joint(n).unwrap()).truncate());
            assert!(feet.iter().any(|p| scene.objects[0].obox().footprint_contains(*p)));
            polish_scene(&mut scene, 30);
            let o = &scene.objects[0].obox();
            assert!(feet.iter().all(|p| !o.footprint_contains(*p)), "index {index}: feet still in the bed {o:?}");
            assert!(contact_iou(&sit.obox, &scene.objects) > 0.5, "index {index}: the sitter lost the bed");
            checked += 1;
        }
        assert!(checked >= 2, "{checked} rooms with a bed sitter checked");
    }

    /// Rooms of type `room` (seed 5) with a box of `action` that a piece `holds` covers over 90 %:
    /// (room index, scene, box, piece index), the first such box of each room.
    fn rooms_with_held(
        room: RoomType,
        action: Action,
        holds: fn(&Object, &ContactBox) -> bool,
    ) -> impl Iterator<Item = (u64, Scene, ContactBox, usize)> {
        (0..200).filter_map(move |index| {
            let scene = generate_room(room, 5, index, false).scene;
            let boxes = Conditions::contact_boxes_of(&scene);
            let (b, i) = boxes.into_iter().filter(|b| b.action == action).find_map(|b| {
                let covered = |o: &Object| holds(o, &b) && contact_iou(&b.obox, std::slice::from_ref(o)) > 0.9;
                let i = scene.objects.iter().position(covered)?;
                Some((b, i))
            })?;
            Some((index, scene, b, i))
        })
    }

    #[test]
    fn a_touched_piece_turned_away_turns_back_to_face_its_toucher() {
        let cabinet_like =
            |o: &Object, _: &ContactBox| matches!(o.category.group(), Group::Cabinet | Group::Shelf | Group::Table);
        let rooms = rooms_with_held(RoomType::Bedroom, Action::Touch, cabinet_like)
            .map(|r| (RoomType::Bedroom, r))
            .chain(rooms_with_held(RoomType::Living, Action::Touch, cabinet_like).map(|r| (RoomType::Living, r)));
        let mut checked = 0;
        for (room, (index, mut scene, touch, i)) in rooms.take(3) {
            // The data's piece faces its toucher; a quarter turn leaves it square, its side to them.
            assert!(facing(scene.objects[i].yaw).dot(facing(touch.obox.yaw)) < -0.99);
            scene.objects[i].yaw += std::f64::consts::FRAC_PI_2;
            polish_scene(&mut scene, 30);
            let o = &scene.objects[i];
            assert!(facing(o.yaw).dot(facing(touch.obox.yaw)) < -0.99, "{room} {index}: {o:?} vs {touch:?}");
            assert!(contact_iou(&touch.obox, std::slice::from_ref(o)) > 0.5, "{room} {index}: touch lost");
            checked += 1;
        }
        assert_eq!(checked, 3, "rooms with a touched piece checked");
    }

    #[test]
    fn a_sitter_under_a_table_top_gets_a_seat_though_the_table_covers_their_box() {
        use crate::human::{Body, Motion, sit};
        use crate::scene::Category;
        // Two people on a sofa against the south wall, and a third one 1.8 m away whose seat the
        // model put a dining table in: the sofa, which has room for three, is given them (nearer
        // than 2 m) but cannot move over to them, and the table top covers their support box.
        let mut scene = generate_room(RoomType::Dining, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [5.0, 0.0], [5.0, 4.0], [0.0, 4.0]];
        let sofa = Object::standing("o0", Category::MultiSeatSofa, [1.5, 0.46], [2.1, 0.9, 0.85]);
        let seat = template(&sofa).surface.unwrap().height;
        let body = Body::default();
        scene.humans = [(1.2, 0.55, seat), (1.8, 0.55, seat), (3.0, 1.3, 0.47)]
            .iter()
            .enumerate()
            .map(|(k, &(x, y, h))| {
                let mut m = Motion::new(body, 30.0);
                m.hold(sit(&body, DVec2::new(x, y), h, 0.0), 3, Action::Sit);
                m.into_human(format!("h{k}"))
            })
            .collect();
        let third = Conditions::contact_boxes_of(&scene).into_iter().find(|b| b.human == "h2").unwrap();
        let table = Object::standing(
            "o1",
            Category::DiningTable,
            [third.obox.center.x, third.obox.center.y + 0.1],
            [1.4, 0.9, 0.75],
        );
        scene.objects = vec![sofa, table];
        assert!(contact_iou(&third.obox, &scene.objects) > 0.9, "the table covers the box");
        let r = polish_scene(&mut scene, 30);
        let seats: Vec<Object> = scene.objects.iter().filter(|o| o.category.affords(Action::Sit)).cloned().collect();
        assert!(r.added >= 1, "{r:?}");
        assert!(contact_iou(&third.obox, &seats) >= COVERED, "{r:?} {:?}", scene.objects);
    }

    #[test]
    fn a_low_piece_touched_on_its_top_comes_down_to_the_palm_within_real_heights() {
        let mut checked = 0;
        for (index, mut scene, touch, i) in rooms_with_held(RoomType::Living, Action::Touch, rests_palm_on_top).take(3)
        {
            // The data rests the palm on the top: the top at the touch box's top.
            let right = scene.objects[i].size[2];
            assert!((right - touch.obox.z_range().1).abs() < 0.015, "{index} {:?} {touch:?}", scene.objects[i]);
            let o = &mut scene.objects[i];
            o.size[2] += 0.25;
            o.center[2] = o.size[2] * 0.5;
            polish_scene(&mut scene, 30);
            let now = scene.objects[i].size[2];
            assert!((now - right).abs() < 0.015, "room {index}: top at {now}, the palm's at {right}");
            checked += 1;
        }
        assert_eq!(checked, 3, "rooms with a low touched piece checked");
        // A dining table touched 45 cm up stays a dining table's height: no real one is that low,
        // and part of the way down would only put its top in the forearm.
        let mut scene = generate_room(RoomType::Dining, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [5.0, 0.0], [5.0, 4.0], [0.0, 4.0]];
        let body = crate::human::Body::default();
        let mut m = crate::human::Motion::new(body, 30.0);
        let target = glam::DVec3::new(2.5, 1.9, 0.45);
        m.hold(crate::human::touch(&body, target, 0.0, crate::human::Side::Right), 3, Action::Touch);
        scene.humans = vec![m.into_human("h0")];
        let table = Object::standing("o0", crate::scene::Category::DiningTable, [2.5, 2.3], [1.4, 0.9, 0.75]);
        scene.objects = vec![table];
        polish_scene(&mut scene, 30);
        assert_eq!(scene.objects[0].size[2], 0.75);
    }

    #[test]
    fn a_bed_too_tall_for_its_sleeper_comes_down_to_them() {
        let (mut scene, index) = (0..40)
            .map(|i| (generate_room(RoomType::Bedroom, 5, i, false).scene, i))
            .find(|(s, _)| Conditions::contact_boxes_of(s).iter().any(|b| b.action == Action::Lie))
            .expect("a bedroom with a sleeper");
        let lie = Conditions::contact_boxes_of(&scene).into_iter().find(|b| b.action == Action::Lie).unwrap();
        let bed = scene
            .objects
            .iter()
            .position(|o| o.category.group() == Group::Bed && contact_iou(&lie.obox, std::slice::from_ref(o)) > 0.9)
            .unwrap();
        let surface = |o: &Object| template(o).surface.unwrap().height;
        let right = surface(&scene.objects[bed]);
        // 25 cm too tall: more than the 15 cm a piece may grow or shrink, within real beds' heights.
        let o = &mut scene.objects[bed];
        o.size[2] = super::super::completion::height_for_surface(o.category, o.size, right + 0.25);
        o.center[2] = o.size[2] * 0.5;
        polish_scene(&mut scene, 30);
        let now = surface(&scene.objects[bed]);
        assert!((now - right).abs() < 0.01, "room {index}: surface at {now}, the sleeper's support at {right}");
    }

    fn back_only(back: f64) -> SeatGaps {
        SeatGaps { back, knees: Vec::new() }
    }

    #[test]
    fn a_sitter_on_a_deep_sofa_ends_with_the_knees_past_its_front_edge() {
        // A 1.1 m deep sofa facing +y, a sitter's box 14 cm deep whose front is at y = 0.1, the
        // knees 0.25 m further: the seat's front edge may be at most 0.25 − KNEE_OVERHANG past the
        // box, so the sofa moves back until its surface ends at y = 0.28.
        let sofa = Object {
            id: "o0".into(),
            category: crate::scene::Category::MultiSeatSofa,
            center: [0.0, 0.0, 0.42],
            size: [2.0, 1.1, 0.84],
            yaw: 0.0,
        };
        let contact = ContactBox {
            human: "h0".into(),
            action: Action::Sit,
            frames: [0, 1],
            obox: OBox::new(DVec3::new(0.0, 0.03, 0.45), DVec3::new(0.3, 0.14, 0.1), 0.0),
        };
        let gaps = SeatGaps { back: 0.05, knees: vec![DVec2::new(-0.1, 0.35), DVec2::new(0.1, 0.36)] };
        assert!((gaps.front(&contact, &sofa) - (0.25 - crate::human::KNEE_OVERHANG)).abs() < 1e-12);
        let mut moved = sofa.clone();
        shift(&mut moved, containment_shift(&contact, &gaps, &sofa));
        let front = template(&moved).surface.unwrap().max.y + moved.center[1];
        assert!((front - (0.35 - crate::human::KNEE_OVERHANG)).abs() < 1e-9, "{front}");
        // Without knees (or with a shallow seat's) the box may sit anywhere clear of the backrest.
        assert_eq!(containment_shift(&contact, &back_only(0.05), &sofa), DVec2::ZERO);
    }

    #[test]
    fn containment_moves_a_seat_under_its_sitter_by_the_smallest_shift() {
        let chair = Object {
            id: "o0".into(),
            category: crate::scene::Category::Stool,
            center: [0.0, 0.0, 0.25],
            size: [0.5, 0.5, 0.5],
            yaw: std::f64::consts::FRAC_PI_2,
        };
        let sit = |center: DVec3, yaw: f64| ContactBox {
            human: "h0".into(),
            action: Action::Sit,
            frames: [0, 1],
            obox: OBox::new(center, DVec3::new(0.2, 0.2, 0.1), yaw),
        };
        // A stool's seat is its whole top: the box reaches x = 0.4, the stool 0.25, so it must move
        // 0.15 along world x.
        let s = containment_shift(&sit(DVec3::new(0.3, 0.0, 0.45), 0.0), &back_only(0.08), &chair);
        assert!((s - DVec2::new(0.15, 0.0)).length() < 1e-12, "{s}");
        // A dining chair facing +y (yaw 0) 0.5 deep has a 6 cm back at −y; its seat starts at
        // y = −0.19, and the box must start a back gap of 8 cm further, at −0.11: a box from y = −0.2
        // moves the chair by −0.09 in y.
        let chair = Object { category: crate::scene::Category::DiningChair, yaw: 0.0, ..chair };
        let s = containment_shift(&sit(DVec3::new(0.0, -0.1, 0.45), 0.0), &back_only(0.08), &chair);
        assert!((s - DVec2::new(0.0, -0.09)).length() < 1e-12, "{s}");
    }
}
