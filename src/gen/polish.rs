//! Polishing a generated layout (ours, after the last sampling step): rounds of small, exact
//! geometric corrections of what the model's few-centimetre imprecision leaves undone.
//!
//! Each contact box (sit, lie, touch) is given to an object that affords its action: best covered
//! pairs first, then nearest within 2 m; a chair or stool holds one person, a sofa or bed one per
//! 55 cm of its length, tables and cabinets any number of touches. A box no object can hold gets a
//! new piece of real furniture (`completion`). A chair, stool or sofa is turned to face like the
//! first sitter it holds (its front the way they face), a sofa to lie along its sleeper. The holder
//! grows by at most 15 cm in height and 20 cm in width or depth where the box is taller or wider.
//! Every round then (1) moves each holder by the smallest shift that puts its boxes' footprints
//! inside its own and pushes pieces out of walking people's way (where footprint and height meet a
//! walking or standing body, `Clearance`), (2) separates overlapping pairs along the shortest
//! separating axis that keeps both inside the walls, and (3) moves every footprint inside the floor
//! plan (corners inside, and off an L-shaped room's inner corner). Holders move a fifth as much for
//! overlaps and paths; the last third of the rounds leaves contacts alone and the last five paths,
//! so the layout ends separated and inside. Rounds stop when nothing moves a millimetre. A box
//! still less than half covered after that gets a new piece and a second pass of rounds.
//!
//! It never removes or re-categorises objects, adds only within the room type's object limit, and
//! turns only seats and sofas.

use super::clearance::Clearance;
use super::completion::support_for;
use crate::eval::contact_iou;
use crate::geom::{OBox, Polygon, intersection_volume, iou_3d};
use crate::human::{Conditions, ContactBox};
use crate::scene::{Action, Group, Object, Scene};
use glam::DVec2;

/// How far an object's height may grow to cover a contact box (m).
const MAX_GROW_HEIGHT: f64 = 0.15;
/// How far an object's width or depth may grow to cover a contact box (m).
const MAX_GROW_EXTENT: f64 = 0.2;
/// Farthest an object may be to be given a contact box it does not touch (m).
const MAX_ASSIGN_DISTANCE: f64 = 2.0;
/// Largest move of one round (m).
const MAX_STEP: f64 = 0.3;
/// Clearance kept from walls and between pushed-apart objects (m).
const CLEARANCE: f64 = 0.005;
/// Share of a move taken by an object that holds a contact.
const ANCHORED_MOBILITY: f64 = 0.2;

/// What polishing changed.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PolishReport {
    /// Rounds run.
    pub rounds: usize,
    /// Objects resized to cover a contact box.
    pub resized: usize,
    /// Seats turned to face like the person on them.
    pub turned: usize,
    /// Objects added for people nothing held (`completion`).
    pub added: usize,
    /// Largest total move of one object (m).
    pub max_move: f64,
}

/// Contact IoU under which a held box counts as uncovered after a pass.
const COVERED: f64 = 0.5;

/// Polishes `scene`'s objects in place with at most `rounds` rounds per pass: a first pass, with a
/// new piece for every contact box no object can hold, and a second one only if some box is still
/// uncovered and a new piece can be added for it.
pub fn polish_scene(scene: &mut Scene, rounds: usize) -> PolishReport {
    let cond = Conditions::of(scene);
    let clearance = Clearance::of(scene, &cond.window);
    let mut report = PolishReport::default();
    let start: Vec<DVec2> = scene.objects.iter().map(|o| DVec2::new(o.center[0], o.center[1])).collect();
    for pass in 0..2 {
        let mut holders = assign_contacts(scene, &cond);
        let missing: Vec<usize> = (0..cond.contact_boxes.len())
            .filter(|k| match pass {
                0 => !holders.iter().any(|(b, _)| b == k),
                _ => contact_iou(&cond.contact_boxes[*k].obox, &scene.objects) < COVERED,
            })
            .collect();
        let added = complete_supports(scene, &cond, &missing, &mut holders);
        if pass > 0 && added == 0 {
            break;
        }
        report.added += added;
        polish_rounds(scene, &cond, &clearance, &holders, rounds, &mut report);
    }
    report.max_move = scene
        .objects
        .iter()
        .zip(&start)
        .map(|(o, s)| DVec2::new(o.center[0], o.center[1]).distance(*s))
        .fold(0.0, f64::max);
    report
}

/// One pass: turning and fitting the holders, then up to `rounds` rounds of moves.
fn polish_rounds(
    scene: &mut Scene,
    cond: &Conditions,
    clearance: &Clearance,
    holders: &[(usize, usize)],
    rounds: usize,
    report: &mut PolishReport,
) {
    let polygon = scene.floor_plan.polygon();
    let mut turned = vec![false; scene.objects.len()];
    for (b, i) in holders {
        let contact = &cond.contact_boxes[*b];
        if let Some(yaw) = facing_yaw(&scene.objects[*i], contact).filter(|_| !turned[*i]) {
            scene.objects[*i].yaw = yaw;
            turned[*i] = true;
        }
        report.resized += fit_size(&mut scene.objects[*i], &contact.obox) as usize;
    }
    report.turned += turned.iter().filter(|t| **t).count();
    let mobility: Vec<f64> = (0..scene.objects.len())
        .map(|i| if holders.iter().any(|(_, h)| *h == i) { ANCHORED_MOBILITY } else { 1.0 })
        .collect();
    for round in 0..rounds {
        let before: Vec<[f64; 3]> = scene.objects.iter().map(|o| o.center).collect();
        // The last third of the rounds leaves the contacts where they are, the last five the paths.
        let mut moves = vec![DVec2::ZERO; scene.objects.len()];
        let mut counts = vec![0usize; scene.objects.len()];
        if round * 3 < rounds * 2 {
            for (b, i) in holders {
                moves[*i] += containment_shift(&cond.contact_boxes[*b].obox, &scene.objects[*i].obox());
                counts[*i] += 1;
            }
        }
        for (i, o) in scene.objects.iter_mut().enumerate() {
            let mut m = moves[i] / counts[i].max(1) as f64;
            if round + 5 < rounds {
                m += path_push(&o.obox(), clearance) * mobility[i];
            }
            shift(o, m.clamp_length_max(MAX_STEP));
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

fn shift(o: &mut Object, m: DVec2) {
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
/// lays people on sofas). Beds are left as they are (people sit across their side; turning them to
/// their sleepers made penetrating bedrooms more frequent: 0.886 → 0.909 of the test split).
fn facing_yaw(o: &Object, contact: &ContactBox) -> Option<f64> {
    match (o.category.group(), contact.action) {
        (Group::Chair | Group::Stool | Group::Sofa, Action::Sit) => Some(contact.obox.yaw),
        (Group::Sofa, Action::Lie) => Some(contact.obox.yaw + std::f64::consts::FRAC_PI_2),
        _ => None,
    }
}

/// Grows a floor-standing object that is a little too low, narrow or shallow for `contact`.
/// Returns whether it changed.
fn fit_size(o: &mut Object, contact: &OBox) -> bool {
    if o.category.is_hanging() {
        return false;
    }
    let before = o.size;
    let top = contact.z_range().1;
    if top > o.size[2] && top - o.size[2] <= MAX_GROW_HEIGHT {
        o.size[2] = top;
        o.center[2] = top * 0.5;
    }
    let (lo, hi) = local_extent(contact, &o.obox());
    for k in 0..2 {
        let need = hi[k] - lo[k];
        if need > o.size[k] && need - o.size[k] <= MAX_GROW_EXTENT {
            o.size[k] = need;
        }
    }
    o.size != before
}

/// The contact box's footprint corners in `o`'s frame: (min, max) per axis.
fn local_extent(contact: &OBox, o: &OBox) -> (DVec2, DVec2) {
    let corners = contact.footprint().map(|p| o.to_local(p.extend(o.center.z)).truncate());
    let lo = corners.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = corners.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    (lo, hi)
}

/// The smallest move of `o` (world, m) that puts `contact`'s footprint inside its footprint (or
/// centres it where it cannot fit).
fn containment_shift(contact: &OBox, o: &OBox) -> DVec2 {
    let (lo, hi) = local_extent(contact, o);
    let half = o.half().truncate();
    let mut s = DVec2::ZERO;
    for k in 0..2 {
        // Any shift in [hi − half, lo + half] contains the box; an empty range: centre it.
        let (from, to) = (hi[k] - half[k], lo[k] + half[k]);
        s[k] = if from > to { (hi[k] + lo[k]) * 0.5 } else { 0.0f64.clamp(from, to) };
    }
    let (ax, ay) = o.axes();
    ax * s.x + ay * s.y
}

/// The moves of `a` (m) that separate its footprint from `b`'s along each separating axis (both
/// directions), with a little clearance, shortest first; empty if the footprints do not overlap.
fn footprint_separations(a: &OBox, b: &OBox) -> Vec<DVec2> {
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

/// A push of `b` out of the walking people's way: away from the centroid of the pixels where it
/// meets their bodies, by their area over its longer side.
fn path_push(b: &OBox, clearance: &Clearance) -> DVec2 {
    let blocked = clearance.blocked(b);
    if blocked.is_empty() {
        return DVec2::ZERO;
    }
    let w = clearance.window();
    let centroid = blocked.iter().sum::<DVec2>() / blocked.len() as f64;
    let dir = (b.center.truncate() - centroid).try_normalize().unwrap_or(DVec2::X);
    let depth = blocked.len() as f64 * w.pixel_area() / b.size.x.max(b.size.y);
    dir * depth.clamp(w.pixel(), MAX_STEP)
}

/// The move that brings `b`'s footprint inside `polygon` with `CLEARANCE` to spare, a few steps of
/// the worst offence first: a footprint corner outside (or too near the boundary), or a polygon
/// corner inside the footprint (an L-shaped room's inner corner, which all four footprint corners
/// can miss).
fn inside_push(b: &OBox, polygon: &Polygon) -> DVec2 {
    let mut total = DVec2::ZERO;
    let (ax, ay) = b.axes();
    let half = b.half().truncate();
    for _ in 0..4 {
        let centre = b.center.truncate() + total;
        let mut worst: Option<(f64, DVec2)> = None;
        let mut consider = |excess: f64, push: DVec2| {
            if excess > 1e-9 && worst.is_none_or(|(e, _)| excess > e) {
                worst = Some((excess, push));
            }
        };
        for p in b.footprint().map(|p| p + total) {
            let inside = polygon.contains(p);
            let distance = polygon.distance_to_boundary(p);
            let excess = if inside { CLEARANCE - distance } else { distance + CLEARANCE };
            let q = nearest_boundary_point(polygon, p);
            let inward = if inside { p - q } else { q - p };
            consider(excess, inward.try_normalize().unwrap_or(DVec2::ZERO) * excess);
        }
        for &v in &polygon.points {
            let local = DVec2::new((v - centre).dot(ax), (v - centre).dot(ay));
            let exit = half - local.abs();
            if exit.x <= 0.0 || exit.y <= 0.0 {
                continue;
            }
            // Move the footprint off the corner through its nearer side.
            let push = if exit.x < exit.y {
                -ax * local.x.signum() * (exit.x + CLEARANCE)
            } else {
                -ay * local.y.signum() * (exit.y + CLEARANCE)
            };
            consider(exit.x.min(exit.y) + CLEARANCE, push);
        }
        let Some((_, push)) = worst else { break };
        total += push;
    }
    total
}

fn nearest_boundary_point(polygon: &Polygon, p: DVec2) -> DVec2 {
    polygon
        .edges()
        .map(|(a, b)| {
            let ab = b - a;
            let t = ((p - a).dot(ab) / ab.length_squared().max(1e-18)).clamp(0.0, 1.0);
            a + ab * t
        })
        .min_by(|x, y| x.distance_squared(p).total_cmp(&y.distance_squared(p)))
        .unwrap_or(p)
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
            assert!(r.max_move < 0.01, "{room}: {r:?}");
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
    fn containment_moves_a_seat_under_its_sitter_by_the_smallest_shift() {
        let chair = OBox::new(DVec3::new(0.0, 0.0, 0.25), DVec3::new(0.5, 0.5, 0.5), std::f64::consts::FRAC_PI_2);
        let sit = OBox::new(DVec3::new(0.3, 0.0, 0.3), DVec3::new(0.2, 0.2, 0.2), 0.0);
        // The box reaches x = 0.4, the chair 0.25: it must move 0.15 along world x.
        let s = containment_shift(&sit, &chair);
        assert!((s - DVec2::new(0.15, 0.0)).length() < 1e-12, "{s}");
    }
}
