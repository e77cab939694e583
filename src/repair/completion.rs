//! Completing a layout's supports (ours; `settle` uses it, it is not a step): a person who sits, lies or touches
//! where no generated object can hold them gets a piece of real furniture placed the way the
//! calibrated data places one under such a person.
//!
//! - A sitter gets a seat of the category the room already seats people on, else a chair, stool or
//!   sofa drawn as the data gives sitters one (`drawn`), facing like the sitter, its seat at the
//!   top of the sitter's support volume, the backrest clear of the sitter's back.
//! - A sleeper gets a bed along the body (the room's bed category, else one drawn like a seat) in
//!   bedrooms, or a sofa with the body along its seat in living and dining rooms, the mattress or
//!   seat at the box's bottom.
//! - A toucher gets a piece in front of them, drawn among those up to 1 m tall for a palm below
//!   1 m (`holding.top_touch_height`; its top just above the pressed volume) and among the taller
//!   ones above, the pressed volume just inside its front face (`completion`'s margins).
//!
//! The draws follow the data's own rates, so that added pieces keep the room type's category mix
//! (always a chair for a bedroom sitter made chairs twice as common as in the data).
//!
//! Sizes are the median of the category's real pieces (the furniture catalog), widened or deepened to
//! cover the box and stretched in height to meet it. Nothing is added beyond the room type's object
//! limit. This module only makes the objects; repair moves them with the rest.

use super::config::{CompletionConfig, HoldingConfig};
use crate::data::{Rng, TOUCH_CHANCE, contact_probability, target_frequencies};
use crate::furniture::{catalog_items, template_of};
use crate::geom::{OBox, facing, wrap_angle};
use crate::human::{ContactBox, KNEE_OVERHANG};
use crate::scene::{Action, Category, Group, Human, Object, RoomType, Scene};
use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_PI_2, PI};

/// How far in front of the backrest a sitter's support volume must start (m): as far as their
/// torso (the capsules from pelvis to neck) reaches behind the volume's back edge over the span,
/// plus `rules.back_margin` — people lean back and their back is wider than their seat bones;
/// `rules.unknown_back_gap` for a person without those joints.
pub(super) fn back_gap(scene: &Scene, contact: &ContactBox, rules: &HoldingConfig) -> f64 {
    const TORSO: [&str; 4] = ["pelvis", "spine", "chest", "neck"];
    let Some(human) = scene.humans.iter().find(|h| h.id == contact.human) else { return rules.unknown_back_gap };
    let s = &human.skeleton;
    let torso: Vec<usize> = TORSO.iter().filter_map(|n| s.joint(n)).collect();
    let bones: Vec<_> = s.bones.iter().filter(|b| torso.contains(&b.a) && torso.contains(&b.b)).collect();
    if bones.is_empty() {
        return rules.unknown_back_gap;
    }
    let b = &contact.obox;
    let back = -facing(b.yaw);
    let edge = b.center.truncate().dot(back) + b.size.y * 0.5;
    let mut reach: f64 = 0.0;
    for f in span_frames(human, contact) {
        for bone in &bones {
            for j in [bone.a, bone.b] {
                reach = reach.max(human.joint_at(f, j).truncate().dot(back) + bone.radius - edge);
            }
        }
    }
    reach + rules.back_margin
}

/// Where a sitter's support box may lie on a backed seat, back to front: at least `back` (m) in
/// front of the backrest ([`back_gap`]) and near enough the front edge for the knees to pass it
/// ([`SeatGaps::front`]). Not a sitter's box: no limits.
#[derive(Debug, Clone, PartialEq)]
pub struct SeatGaps {
    /// Clearance from the backrest (m).
    pub back: f64,
    /// The sitter's knees (world xy) over the span; none for anyone else.
    pub knees: Vec<DVec2>,
}

impl SeatGaps {
    /// The gaps of `contact`'s person in `scene`.
    pub fn of(scene: &Scene, contact: &ContactBox, rules: &HoldingConfig) -> SeatGaps {
        SeatGaps { back: back_gap(scene, contact, rules), knees: knees(scene, contact) }
    }

    /// How far behind the front edge (local +y) of `o` the front of `contact`'s box may be (m):
    /// as far as the knees reach past it along `o`'s depth (the knee and frame that reach least),
    /// less [`KNEE_OVERHANG`], so that the lower legs hang clear of a deep seat as in the data.
    /// Unlimited for anyone but a sitter.
    pub fn front(&self, contact: &ContactBox, o: &Object) -> f64 {
        let b = o.obox();
        let (_, ay) = b.axes();
        let front = contact.obox.footprint().iter().map(|p| p.dot(ay)).fold(f64::NEG_INFINITY, f64::max);
        let reach = self.knees.iter().map(|k| k.dot(ay) - front).fold(f64::INFINITY, f64::min);
        (reach - KNEE_OVERHANG).max(0.0)
    }
}

/// A sitter's knees (world xy) over the span of `contact`; none for anyone else or a person
/// without knees.
fn knees(scene: &Scene, contact: &ContactBox) -> Vec<DVec2> {
    let Some(human) = scene.humans.iter().find(|h| h.id == contact.human) else { return Vec::new() };
    if contact.action != Action::Sit {
        return Vec::new();
    }
    let joints: Vec<usize> = ["left_knee", "right_knee"].iter().filter_map(|n| human.skeleton.joint(n)).collect();
    span_frames(human, contact).flat_map(|f| joints.iter().map(move |&k| human.joint_at(f, k).truncate())).collect()
}

/// Up to about nine frames spread over `contact`'s span.
fn span_frames<'a>(human: &'a Human, contact: &ContactBox) -> impl Iterator<Item = usize> + 'a {
    let [start, end] = contact.frames;
    (start..end.max(start + 1)).step_by(((end - start) / 8).max(1)).filter(|&f| f < human.frames.len())
}

/// A new object that holds `contact` in `scene`, or `None` where the room type has no piece for it.
pub fn support_for(
    scene: &Scene,
    contact: &ContactBox,
    rules: &HoldingConfig,
    sizing: &CompletionConfig,
) -> Option<Object> {
    let category = category_for(scene, contact, rules.top_touch_height)?;
    let margin = sizing.side_margin;
    let b = &contact.obox;
    // Sit and lie boxes are the support volume under the body: the surface goes at their top.
    let top = b.z_range().1;
    let [w, d, h] = median_size(category);
    let (size, yaw, box_at) = match (contact.action, category.group()) {
        (Action::Sit, _) => {
            let gap = back_gap(scene, contact, rules);
            let mut size = [w.max(b.size.x + margin), d, h];
            size[2] = height_for_surface(category, size, top);
            let surface = template_of(category, &boxed(size)).surface?;
            // Wide enough between the arms, deep enough for the box in front of the backrest.
            size[0] += (b.size.x + margin - surface.extent().x).max(0.0);
            size[1] += (surface.min.y + gap + b.size.y + margin - surface.max.y).max(0.0);
            let surface = template_of(category, &boxed(size)).surface?;
            // Facing like the sitter, the box's back edge `gap` in front of the backrest.
            (size, b.yaw, DVec2::new(0.0, surface.min.y + gap + b.size.y * 0.5))
        }
        (Action::Lie, Group::Sofa) => {
            // Along the seat (the body along the sofa's local x), as the data lays people on sofas.
            let mut size = [w.max(b.size.y + 2.0 * margin), d, h];
            size[2] = height_for_surface(category, size, top);
            let surface = template_of(category, &boxed(size)).surface?;
            size[1] += (b.size.x + margin - surface.extent().y).max(0.0);
            let surface = template_of(category, &boxed(size)).surface?;
            (size, b.yaw + FRAC_PI_2, (surface.min + surface.max) * 0.5)
        }
        (Action::Lie, _) => {
            let mut size = [w.max(b.size.x + 2.0 * margin), d.max(b.size.y + 2.0 * margin), h];
            size[2] = height_for_surface(category, size, top);
            (size, b.yaw, DVec2::ZERO)
        }
        (Action::Touch, _) => {
            // The pressed volume inside, just behind the front face (local +y, towards the person),
            // under the top for a low palm.
            let height = if b.center.z <= rules.top_touch_height {
                top + sizing.low_touch_top
            } else {
                h.max(top + sizing.high_touch_top)
            };
            let inset = b.size.y * 0.5 + sizing.touch_inset;
            ([w.max(b.size.x + 2.0 * margin), d, height], b.yaw + PI, DVec2::new(0.0, d * 0.5 - inset))
        }
        (Action::Walk | Action::Stand, _) => return None,
    };
    // The piece's centre puts the box at `box_at` in the piece's frame.
    let center = b.center.truncate() - DVec2::from_angle(yaw).rotate(box_at);
    Some(Object {
        id: free_id(scene),
        category,
        center: [center.x, center.y, size[2] * 0.5],
        size,
        yaw: wrap_angle(yaw),
    })
}

/// The category of the piece that holds `contact` in `scene`'s room type (a palm up to
/// `top_touch_height` high rests on a piece no taller, a higher one on a taller piece).
fn category_for(scene: &Scene, contact: &ContactBox, top_touch_height: f64) -> Option<Category> {
    let room = scene.room_type;
    let present = |groups: &[Group]| {
        // The most common category of those groups in the scene (first in category order on ties).
        let mut best: Option<(usize, Category)> = None;
        for &c in room.categories() {
            let n = scene.objects.iter().filter(|o| o.category == c).count();
            if n > 0 && groups.contains(&c.group()) && best.is_none_or(|(m, _)| n > m) {
                best = Some((n, c));
            }
        }
        best.map(|(_, c)| c)
    };
    let low_touch = contact.obox.center.z <= top_touch_height;
    let chosen = match contact.action {
        Action::Sit => present(&[Group::Chair, Group::Stool])
            .or_else(|| drawn(room, contact, |c| matches!(c.group(), Group::Chair | Group::Stool | Group::Sofa))),
        Action::Lie => match room {
            RoomType::Bedroom => present(&[Group::Bed]).or_else(|| drawn(room, contact, |c| c.group() == Group::Bed)),
            RoomType::Living | RoomType::Dining => present(&[Group::Sofa]).or(Some(Category::MultiSeatSofa)),
        },
        // A low palm rests on the top of a piece up to 1 m tall, a high one on the front of a taller one.
        Action::Touch => drawn(room, contact, |c| (median_size(c)[2] <= top_touch_height) == low_touch),
        Action::Walk | Action::Stand => return None,
    }?;
    (room.categories().contains(&chosen) && chosen.affords(contact.action)).then_some(chosen)
}

/// A category of `room` that `accepts`, drawn as often as the data gives a person doing
/// `contact`'s action such a piece: its 3D-FRONT frequency × the chance the data puts a contact
/// person on it × the action's share of its affordances. The draw is seeded by where the box is,
/// so the same scene always gets the same piece.
fn drawn(room: RoomType, contact: &ContactBox, accepts: impl Fn(Category) -> bool) -> Option<Category> {
    let frequencies = target_frequencies(room);
    let weights: Vec<f64> = room
        .categories()
        .iter()
        .zip(&frequencies)
        .map(|(&c, &f)| {
            let total: f64 = c.affordances().iter().map(|&a| c.affordance_probability(a)).sum();
            let share = if total > 0.0 { c.affordance_probability(contact.action) / total } else { 0.0 };
            if accepts(c) { f * contact_probability(c, TOUCH_CHANCE) * share } else { 0.0 }
        })
        .collect();
    if weights.iter().all(|w| *w <= 0.0) {
        return None;
    }
    let at = contact.obox.center;
    let seed = [at.x, at.y, at.z].iter().fold(0u64, |h, v| h.rotate_left(21) ^ ((v * 1e4).round() as i64 as u64));
    Some(room.categories()[Rng::new(seed).weighted(&weights)])
}

/// The median width, depth and height of the category's real pieces.
pub(super) fn median_size(category: Category) -> [f64; 3] {
    let items = catalog_items(category);
    std::array::from_fn(|k| {
        let mut v: Vec<f64> = items.iter().map(|i| i.size[k]).collect();
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied().unwrap_or(0.5)
    })
}

/// The height (near `size[2]`) at which the category's sitting or lying surface is at `target`.
pub(super) fn height_for_surface(category: Category, size: [f64; 3], target: f64) -> f64 {
    let (lo, hi) = (size[2] * 0.6, size[2] * 1.5);
    let mut h = size[2];
    for _ in 0..6 {
        let Some(s) = template_of(category, &boxed([size[0], size[1], h])).surface else { break };
        if s.height <= 1e-6 {
            break;
        }
        h = (h * target / s.height).clamp(lo, hi);
    }
    h
}

/// The height within `lo..=hi` at which the category's sitting or lying surface comes nearest
/// `target`. The surface is not one smooth function of the height: a bed no taller than 0.7 m has
/// no headboard and its mattress is its top, a taller one's mattress is at half its height, so a
/// low bed can seat a person higher than a tall one and a tall one lower than a low one. Candidates,
/// in order, each taken only where it comes strictly nearer than those before: [`height_for_surface`]
/// from the piece's own height, `target` itself, and [`height_for_surface`] from every
/// [`HEIGHT_START_STEP`] across the range (which reaches the other branch: a 0.5 m bed under a
/// sleeper whose mattress must be at 0.355 m becomes a 0.71 m one, not the lowest real one with
/// its mattress 2.3 cm into the sleeper's back).
pub(super) fn height_within(category: Category, size: [f64; 3], target: f64, (lo, hi): (f64, f64)) -> f64 {
    let miss = |h: f64| {
        template_of(category, &boxed([size[0], size[1], h]))
            .surface
            .map_or(f64::INFINITY, |s| (s.height - target).abs())
    };
    let scaled_from = |start: f64| height_for_surface(category, [size[0], size[1], start], target).clamp(lo, hi);
    let starts = ((hi - lo) / HEIGHT_START_STEP).ceil().max(0.0) as usize;
    let across = (0..=starts).map(|k| scaled_from(lo + (hi - lo) * k as f64 / starts.max(1) as f64));
    let candidates = [scaled_from(size[2]), target.clamp(lo, hi)].into_iter().chain(across);
    let mut best = (f64::INFINITY, size[2]);
    for h in candidates {
        let m = miss(h);
        if m < best.0 - 1e-9 {
            best = (m, h);
        }
    }
    best.1
}

/// Spacing of the heights [`height_within`] also scales from (m).
const HEIGHT_START_STEP: f64 = 0.1;

/// A box of `size` standing at the origin, unturned.
fn boxed(size: [f64; 3]) -> OBox {
    OBox::new(DVec3::new(0.0, 0.0, size[2] * 0.5), DVec3::from(size), 0.0)
}

/// The first id `o<k>` the scene does not use.
fn free_id(scene: &Scene) -> String {
    (scene.objects.len()..).map(|k| format!("o{k}")).find(|id| scene.objects.iter().all(|o| &o.id != id)).expect("ids")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::human::Conditions;
    use crate::measure::contact_iou;
    use crate::repair::tests::repair_with_rounds;

    /// Synthetic rooms with a person doing `action`, and the index of the object under them.
    fn rooms_with(room: RoomType, action: Action, groups: &[Group]) -> Vec<(Scene, ContactBox, usize)> {
        let mut found = Vec::new();
        for index in 0..80 {
            let scene = generate_room(room, 11, index, false).scene;
            for b in Conditions::contact_boxes_of(&scene).into_iter().filter(|b| b.action == action) {
                let holder = (0..scene.objects.len()).find(|&i| {
                    groups.contains(&scene.objects[i].category.group())
                        && contact_iou(&b.obox, std::slice::from_ref(&scene.objects[i])) > 0.9
                });
                if let Some(i) = holder {
                    found.push((scene.clone(), b, i));
                    break;
                }
            }
            if found.len() == 3 {
                break;
            }
        }
        assert_eq!(found.len(), 3, "{room} {action:?}");
        found
    }

    #[test]
    fn a_low_bed_without_a_headboard_seats_a_person_higher_than_a_tall_one_can() {
        // Real single beds are 0.70–0.87 m tall, so 0.55–1.02 m within 15 cm. A tall bed's mattress
        // is at half its height: 0.51 m at most; a bed up to 0.7 m has no headboard, its top at 0.63.
        let range = (0.70 - 0.15, 0.874 + 0.15);
        let size = [0.95, 2.0, 0.87];
        let h = height_within(Category::SingleBed, size, 0.63, range);
        assert!((h - 0.63).abs() < 1e-9, "{h}");
        assert!((height_for_surface(Category::SingleBed, size, 0.63).clamp(range.0, range.1) - 1.024).abs() < 1e-9);
        // A mattress at 0.45 m: the tall bed (0.9 m) gets it exactly, the low one could not (0.55).
        let h = height_within(Category::SingleBed, size, 0.45, range);
        assert!((h - 0.9).abs() < 1e-6, "{h}");
        // A chair's seat is not its top: scaled as before.
        let chair = [0.45, 0.5, 0.9];
        let (lo, hi) = (0.6, 1.2);
        let h = height_within(Category::DiningChair, chair, 0.47, (lo, hi));
        assert_eq!(h, height_for_surface(Category::DiningChair, chair, 0.47).clamp(lo, hi));
    }

    #[test]
    fn a_low_bed_under_a_low_mattress_becomes_a_tall_one_with_its_mattress_at_half_height() {
        // Real double beds are 0.528–1.16 m tall: 0.378–1.31 m within 15 cm. A sleeper whose
        // support must end at 0.355 m on a 0.5 m bed (no headboard, the mattress its top): the
        // lowest such bed (0.378 m) leaves the mattress 2.3 cm into them; a 0.71 m bed's
        // mattress is at half its height, exactly 0.355 m.
        let range = (0.528 - 0.15, 1.16 + 0.15);
        let h = height_within(Category::DoubleBed, [1.6, 2.1, 0.5], 0.355, range);
        assert!((h - 0.71).abs() < 1e-6, "{h}");
        // Within reach of the low branch it stays low: a mattress at 0.45 m on a 0.5 m bed.
        let h = height_within(Category::DoubleBed, [1.6, 2.1, 0.5], 0.45, range);
        assert!((h - 0.45).abs() < 1e-6, "{h}");
    }

    #[test]
    fn new_pieces_follow_the_data_mix_and_a_place_always_gets_the_same_one() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.objects.clear();
        let boxed_at = |action: Action, x: f64, y: f64, z: f64| ContactBox {
            human: "h0".into(),
            action,
            frames: [0, 1],
            obox: OBox::new(DVec3::new(x, y, z), DVec3::new(0.4, 0.4, 0.1), 0.0),
        };
        let mut seats = std::collections::BTreeMap::new();
        for k in 0..400 {
            let b = boxed_at(Action::Sit, 1.0 + 0.013 * k as f64, 2.0 + 0.007 * k as f64, 0.4);
            let c = category_for(&scene, &b, 1.0).unwrap();
            assert_eq!(category_for(&scene, &b, 1.0), Some(c), "the same place, the same piece");
            assert!(matches!(c.group(), Group::Chair | Group::Stool | Group::Sofa) && c.affords(Action::Sit), "{c}");
            *seats.entry(c).or_insert(0) += 1;
        }
        // Bedroom sitters in the data mostly sit on chairs, but not only (sofas, stools, armchairs).
        let chairs = seats[&Category::Chair];
        assert!(seats.values().all(|&n| n <= chairs) && chairs < 400 && seats.len() >= 3, "{seats:?}");
        for (z, tall) in [(0.8, false), (1.3, true)] {
            for k in 0..50 {
                let c = category_for(&scene, &boxed_at(Action::Touch, 1.0 + 0.03 * k as f64, 2.0, z), 1.0).unwrap();
                assert_eq!(median_size(c)[2] > 1.0, tall, "{c} for a palm at {z} m");
            }
        }
    }

    fn turn_distance(a: f64, b: f64, period: f64) -> f64 {
        let d = (a - b).rem_euclid(period);
        d.min(period - d)
    }

    #[test]
    fn a_new_piece_holds_the_person_like_the_piece_it_replaces() {
        let cases = [
            (RoomType::Dining, Action::Sit, vec![Group::Chair, Group::Stool], 2.0 * PI),
            (RoomType::Bedroom, Action::Lie, vec![Group::Bed], PI),
            (RoomType::Bedroom, Action::Touch, vec![Group::Cabinet, Group::Shelf, Group::Table], 2.0 * PI),
        ];
        for (room, action, groups, period) in cases {
            for (mut scene, contact, i) in rooms_with(room, action, &groups) {
                let removed = scene.objects.remove(i);
                let new = support_for(&scene, &contact, &Default::default(), &Default::default()).unwrap();
                assert!(new.category.affords(action) && room.categories().contains(&new.category), "{new:?}");
                let cover = contact_iou(&contact.obox, std::slice::from_ref(&new));
                assert!(cover > 0.95, "{room} {action:?}: covers {cover}");
                assert!(scene.objects.iter().all(|o| o.id != new.id), "a fresh id");
                if action != Action::Touch {
                    // Turned like the piece it replaces (seats face their sitter, beds lie along
                    // the sleeper) and standing on the floor.
                    let d = turn_distance(new.yaw, removed.yaw, period);
                    assert!(d < 0.2, "{room} {action:?}: yaw {} vs {}", new.yaw, removed.yaw);
                }
                assert!((new.center[2] - new.size[2] * 0.5).abs() < 1e-12);
                if action == Action::Sit {
                    // The seat is at the top of the sitter's support volume (within 2 cm).
                    let seat = template_of(new.category, &new.obox()).surface.unwrap().height;
                    assert!((seat - contact.obox.z_range().1).abs() < 0.02, "seat {seat}");
                }
            }
        }
    }

    #[test]
    fn repair_seats_every_sitter_of_a_room_without_seats_and_adds_nothing_to_a_complete_one() {
        for (mut scene, _, _) in rooms_with(RoomType::Dining, Action::Sit, &[Group::Chair]) {
            assert_eq!(repair_with_rounds(&mut scene.clone(), 30).settle.added, 0);
            scene.objects.retain(|o| !matches!(o.category.group(), Group::Chair | Group::Stool | Group::Sofa));
            let sits: Vec<ContactBox> =
                Conditions::contact_boxes_of(&scene).into_iter().filter(|b| b.action == Action::Sit).collect();
            assert!(sits.iter().all(|b| contact_iou(&b.obox, &scene.objects) < 0.5));
            let before = scene.objects.len();
            let report = repair_with_rounds(&mut scene, 30);
            assert!(report.settle.added >= 1 && report.settle.added <= sits.len(), "{report:?}");
            assert_eq!(scene.objects.len(), before + report.settle.added);
            for b in &sits {
                assert!(contact_iou(&b.obox, &scene.objects) > 0.9, "{}", contact_iou(&b.obox, &scene.objects));
            }
        }
    }

    #[test]
    fn sleepers_on_sofas_get_a_sofa_along_them() {
        let contact = ContactBox {
            human: "h0".into(),
            action: Action::Lie,
            frames: [0, 1],
            obox: OBox::new(DVec3::new(1.0, 2.0, 0.55), DVec3::new(0.5, 1.7, 0.25), 0.3),
        };
        let mut scene = generate_room(RoomType::Living, 1, 0, false).scene;
        scene.objects.clear();
        let sofa = support_for(&scene, &contact, &Default::default(), &Default::default()).unwrap();
        assert_eq!(sofa.category, Category::MultiSeatSofa);
        // Its length (local x) runs along the body (the box's local y).
        assert!(turn_distance(sofa.yaw, 0.3 + FRAC_PI_2, 2.0 * PI) < 1e-9);
        assert!(sofa.size[0] >= 1.7 && contact_iou(&contact.obox, &[sofa]) > 0.95);
    }
}
