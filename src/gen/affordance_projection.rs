//! The affordance projection: in the sampler's last steps (those of the empty-slot projection),
//! an anchored slot whose x̂0 class is "empty" or a category that does not afford its contact
//! box's action takes the affording category it scores highest. Every anchored slot of the
//! training data holds the piece its person uses, and that piece affords what they do
//! ([`Category::affords`]: calibration seats people only on such pieces, and a person resting on
//! the floor has no contact box); the model alone, on inputs unlike its data (four diners and a
//! hand on the table's head), put the dining table under a diner in 14 of 208 sitters and nothing
//! in 5 (docs/RESULTS.md, "Seats that seat").
//!
//! It changes classes only: where the piece stands and how large it is stay the model's estimate,
//! which the steps that follow and the guidance place. Knee boxes and other anchors without an
//! action are left alone.

use super::ModelConfig;
use super::config::CONTACT_FEATURES;
use super::tokens::{CLASS_OFFSET, slot_class};
use crate::scene::{Action, Category};

/// The action of contact row `row` (its one-hot of sit, lie, touch), if it has one.
fn action_of(row: &[f32]) -> Option<Action> {
    let kind = &row[CONTACT_FEATURES - 3..CONTACT_FEATURES];
    [Action::Sit, Action::Lie, Action::Touch].into_iter().zip(kind).find(|(_, k)| **k > 0.5).map(|(a, _)| a)
}

/// Projects the anchored slots of a batch's x̂0 (`tokens`, B × slots × token_dim, either frame:
/// only the classes are read and written) onto pieces that afford their box's action; `contacts`
/// (B × max_contacts × [`CONTACT_FEATURES`]) and `mask` (B × max_contacts) are the batch's contact
/// features. A slot that must change swaps its scores of its current class and of the affording
/// category it scores highest, so that its scores keep the values the model gave them. Returns how
/// many slots changed.
pub fn keep_affordances(tokens: &mut [f32], contacts: &[f32], mask: &[f32], cfg: &ModelConfig) -> usize {
    let (dim, k) = (cfg.token_dim(), cfg.max_contacts);
    let per_item = cfg.slots() * dim;
    let categories = cfg.room_type.categories();
    let mut changed = 0;
    for (item, tokens) in tokens.chunks_exact_mut(per_item).enumerate() {
        let boxes = mask[item * k..(item + 1) * k].iter().filter(|&&m| m > 0.5).count();
        for slot in 0..cfg.anchored_slots(boxes) {
            let row = &contacts[(item * k + slot) * CONTACT_FEATURES..(item * k + slot + 1) * CONTACT_FEATURES];
            let Some(action) = action_of(row) else { continue };
            let t = &mut tokens[slot * dim..(slot + 1) * dim];
            let affords = |class: usize| categories.get(class).is_some_and(|c: &Category| c.affords(action));
            let current = slot_class(t, cfg);
            if affords(current) {
                continue;
            }
            let best = (0..categories.len())
                .filter(|&c| affords(c))
                .max_by(|&a, &b| t[CLASS_OFFSET + a].total_cmp(&t[CLASS_OFFSET + b]));
            if let Some(best) = best {
                t.swap(CLASS_OFFSET + current, CLASS_OFFSET + best);
                changed += 1;
            }
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{SplitStats, generate_room};
    use crate::generator::tokens::{Bounds, encode};
    use crate::generator::{Features, anchors};
    use crate::human::Conditions;
    use crate::scene::RoomType;

    fn cfg(room: RoomType) -> ModelConfig {
        ModelConfig { max_contacts: room.max_objects(), ..ModelConfig::tiny(room) }
    }

    /// One room's tokens and contact features, as the sampler sees them.
    fn encoded(room: RoomType, index: u64, cfg: &ModelConfig) -> (Vec<f32>, Vec<f32>, Vec<f32>) {
        let scene = generate_room(room, 5, index, false).scene;
        let mut stats = SplitStats::default();
        stats.add(&scene);
        let bounds = Bounds::from_stats(&stats);
        let cond = Conditions::of(&scene);
        let boxes: Vec<_> = anchors::anchor_boxes(&cond, cfg).into_iter().map(|(b, _)| b).collect();
        let (tokens, _) = encode(&scene, cond.window.center, &boxes, &bounds, cfg);
        let f = Features::of(&cond, room, &bounds, cfg);
        (tokens, f.contacts, f.contact_mask)
    }

    #[test]
    fn the_data_s_own_anchored_slots_afford_their_boxes_and_are_left_alone() {
        let mut anchored = 0;
        for room in [RoomType::Bedroom, RoomType::Living, RoomType::Dining] {
            let cfg = cfg(room);
            for index in 0..20 {
                let (tokens, contacts, mask) = encoded(room, index, &cfg);
                anchored += cfg.anchored_slots(mask.iter().filter(|&&m| m > 0.5).count());
                let mut projected = tokens.clone();
                assert_eq!(keep_affordances(&mut projected, &contacts, &mask, &cfg), 0, "{room:?} room {index}");
                assert_eq!(projected, tokens);
            }
        }
        assert!(anchored > 40, "{anchored} anchored slots");
    }

    #[test]
    fn a_table_under_a_diner_becomes_the_seat_it_scores_highest_and_other_slots_stay() {
        let room = RoomType::Dining;
        let cfg = cfg(room);
        let categories = room.categories();
        let class = |c: Category| categories.iter().position(|&x| x == c).unwrap();
        let (table, chair, stool) =
            (class(Category::DiningTable), class(Category::DiningChair), class(Category::Stool));
        let dim = cfg.token_dim();
        // A diner's room: its first box is a sit box.
        let (index, (tokens, contacts, mask)) = (0..40)
            .map(|i| (i, encoded(room, i, &cfg)))
            .find(|(_, (_, c, _))| action_of(&c[..CONTACT_FEATURES]) == Some(Action::Sit))
            .expect("a room with a sitter first");
        let mut t = tokens.clone();
        // Slot 0 scores: the table 0.9, a stool 0.5, a dining chair 0.2, everything else −1.
        let scores = &mut t[CLASS_OFFSET..dim];
        scores.fill(-1.0);
        scores[table] = 0.9;
        scores[stool] = 0.5;
        scores[chair] = 0.2;
        assert_eq!(keep_affordances(&mut t, &contacts, &mask, &cfg), 1, "room {index}");
        assert_eq!(slot_class(&t[..dim], &cfg), stool);
        assert_eq!((t[CLASS_OFFSET + stool], t[CLASS_OFFSET + table]), (0.9, 0.5), "the scores swapped");
        assert_eq!(t[dim..], tokens[dim..], "the other slots are as they were");
        // Read "empty", the slot takes a seat as well.
        let mut empty = tokens.clone();
        empty[CLASS_OFFSET..dim].fill(-1.0);
        empty[dim - 1] = 1.0;
        empty[CLASS_OFFSET + chair] = 0.1;
        assert_eq!(keep_affordances(&mut empty, &contacts, &mask, &cfg), 1);
        assert_eq!(slot_class(&empty[..dim], &cfg), chair);
    }
}
