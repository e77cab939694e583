//! The count projection: in the sampler's last steps (those of the empty-slot projection), the
//! slots' classes in x̂0 are matched to the pieces per category the sample must hold. What it must
//! hold is a [`CountRule`]: for a count-conditioned model ([`super::ModelConfig::count_condition`])
//! the make-up it is conditioned on, so that the layout holds the make-up it was asked for
//! (without it such a model keeps every count in only about half of its rooms; docs/RESULTS.md,
//! "Keeping to the counts"); for any other model its own make-up with every count the training
//! data never has moved to the nearest one it has ([`SeenRoom::nearest`]: one dining chair, three
//! nightstands).
//!
//! A category with too few pieces takes the free empty slots that lean to it most (its class score
//! over the empty class's); one with too many gives up its least certain free pieces. Pieces are
//! counted as [`decode_slots`] decodes them (one piece in several anchored slots is one piece), and
//! a piece in an anchored slot, one that serves a person, is never taken away. Where a piece
//! stands is left to the model: a slot that becomes a piece keeps its estimate, and the steps
//! that follow place it. Which rule a sample gets is the generator's ([`super::CountPrior`], the
//! input's own counts, or the model's [`super::SeenCounts`]).

use super::ModelConfig;
use super::seen_counts::SeenRoom;
use super::tokens::{Bounds, CLASS_OFFSET, decode_slots};
use glam::DVec2;

/// What one batch item's pieces per category must be.
#[derive(Debug, Clone, PartialEq)]
pub enum CountRule {
    /// Exactly these, in the model's class order (a count-conditioned model's counts).
    Asked(Vec<u8>),
    /// Its own, with each count the training data never has moved to the nearest one it has.
    Seen(SeenRoom),
}

impl CountRule {
    /// The pieces per category wanted of an item that holds `have`, `least` of them in anchored
    /// slots (they cannot go).
    pub fn want(&self, have: &[u8], least: &[u8]) -> Vec<u8> {
        match self {
            CountRule::Asked(want) => want.clone(),
            CountRule::Seen(room) => room.nearest(have, least),
        }
    }
}

/// What each batch item's pieces per category must be, and the bounds its slots decode with.
#[derive(Debug, Clone, PartialEq)]
pub struct CountTargets {
    /// One rule per batch item.
    pub per_item: Vec<CountRule>,
    /// The model's bounds ([`super::CheckpointMeta::bounds`]).
    pub bounds: Bounds,
}

/// Sets the classes of one item's x̂0 so that it decodes to the pieces per category `rule` wants,
/// as far as its free slots allow. `world` is the item's x̂0 in world form (slots × token_dim)
/// and decides which slots hold which pieces; `tokens` is the same estimate in the model's frame,
/// whose class features are changed (a slot's classes become ±1, as in the training data);
/// `anchored` is the number of anchored slots.
pub fn match_counts(
    world: &[f32],
    tokens: &mut [f32],
    rule: &CountRule,
    anchored: usize,
    bounds: &Bounds,
    cfg: &ModelConfig,
) {
    let dim = cfg.token_dim();
    let empty = cfg.classes() - 1;
    let pieces = decode_slots(world, DVec2::ZERO, 0.0, bounds, cfg);
    let scores = tokens.to_vec();
    let lean = |slot: usize, class: usize| {
        scores[slot * dim + CLASS_OFFSET + class] - scores[slot * dim + CLASS_OFFSET + empty]
    };
    let mut set_class = |slot: usize, class: usize| {
        for (k, v) in tokens[slot * dim + CLASS_OFFSET..(slot + 1) * dim].iter_mut().enumerate() {
            *v = if k == class { 1.0 } else { -1.0 };
        }
    };
    let categories = cfg.room_type.categories();
    let (mut have, mut least) = (vec![0u8; categories.len()], vec![0u8; categories.len()]);
    for (slots, piece) in &pieces {
        if let Some(class) = categories.iter().position(|&c| c == piece.category) {
            have[class] = have[class].saturating_add(1);
            if slots.iter().any(|&s| s < anchored) {
                least[class] = least[class].saturating_add(1);
            }
        }
    }
    let want = rule.want(&have, &least);
    let held: Vec<usize> = pieces.iter().flat_map(|(slots, _)| slots.iter().copied()).collect();
    let mut open: Vec<usize> = (anchored..cfg.slots()).filter(|s| !held.contains(s)).collect();
    for (class, (&category, &n)) in categories.iter().zip(&want).enumerate() {
        let n = usize::from(n);
        let mut mine: Vec<&Vec<usize>> =
            pieces.iter().filter(|(_, o)| o.category == category).map(|(slots, _)| slots).collect();
        if mine.len() > n {
            let certainty = |slots: &Vec<usize>| slots.iter().map(|&s| lean(s, class)).fold(f32::MIN, f32::max);
            mine.sort_by(|a, b| certainty(a).total_cmp(&certainty(b)));
            let extra = mine.len() - n;
            let free: Vec<&Vec<usize>> =
                mine.into_iter().filter(|slots| slots.iter().all(|&s| s >= anchored)).collect();
            for slots in free.into_iter().take(extra) {
                slots.iter().for_each(|&s| set_class(s, empty));
            }
        } else if mine.len() < n {
            open.sort_by(|&a, &b| lean(b, class).total_cmp(&lean(a, class)).then(a.cmp(&b)));
            let take = (n - mine.len()).min(open.len());
            open.drain(..take).for_each(|s| set_class(s, class));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RoomType;

    fn setup() -> (ModelConfig, Bounds) {
        let mut cfg = ModelConfig::tiny(RoomType::Dining);
        cfg.count_condition = true;
        let bounds = Bounds {
            center_min: [-3.0, -3.0, 0.0],
            center_max: [3.0, 3.0, 3.0],
            size_min: [0.1; 3],
            size_max: [3.1; 3],
        };
        (cfg, bounds)
    }

    fn class_of(name: &str, cfg: &ModelConfig) -> usize {
        cfg.room_type.categories().iter().position(|c| c.name() == name).expect("a dining category")
    }

    /// Empty slots everywhere (class "empty" at 0.2 over the rest), then `pieces`: (slot, class,
    /// x in the window's scaled frame, that class's score).
    fn tokens(pieces: &[(usize, usize, f32, f32)], cfg: &ModelConfig) -> Vec<f32> {
        let dim = cfg.token_dim();
        let mut t = vec![0f32; cfg.slots() * dim];
        for slot in t.chunks_exact_mut(dim) {
            slot[CLASS_OFFSET..].fill(-1.0);
            slot[CLASS_OFFSET + cfg.classes() - 1] = 0.2;
        }
        for &(slot, class, x, score) in pieces {
            let s = &mut t[slot * dim..(slot + 1) * dim];
            s[..8].copy_from_slice(&[x, 0.0, -0.5, -0.7, -0.7, -0.5, 1.0, 0.0]);
            s[CLASS_OFFSET + class] = score;
        }
        t
    }

    fn classes(tokens: &[f32], cfg: &ModelConfig) -> Vec<usize> {
        tokens.chunks_exact(cfg.token_dim()).map(|t| super::super::tokens::slot_class(t, cfg)).collect()
    }

    #[test]
    fn a_missing_chair_takes_the_open_slot_that_leans_to_chairs_most() {
        let (cfg, bounds) = setup();
        let (chair, table, empty) = (class_of("dining_chair", &cfg), class_of("dining_table", &cfg), cfg.classes() - 1);
        let mut t = tokens(&[(0, chair, -0.5, 0.9), (3, table, 0.0, 0.9)], &cfg);
        // Slots 5 and 7 lean to chairs (by 0.3 and 0.1 under "empty"); slot 5 leans more.
        let dim = cfg.token_dim();
        t[5 * dim + CLASS_OFFSET + chair] = -0.1;
        t[7 * dim + CLASS_OFFSET + chair] = 0.1;
        let mut want = vec![0u8; cfg.count_width()];
        want[chair] = 2;
        want[table] = 1;
        let world = t.clone();
        match_counts(&world, &mut t, &CountRule::Asked(want), 1, &bounds, &cfg);
        let got = classes(&t, &cfg);
        assert_eq!(got[7], chair, "the slot leaning most to chairs becomes one");
        assert_eq!((got[0], got[3], got[5]), (chair, table, empty));
        assert_eq!(t[7 * dim + CLASS_OFFSET..8 * dim].iter().filter(|&&v| v == 1.0).count(), 1, "one-hot ±1");
        let decoded = decode_slots(&t, DVec2::ZERO, 0.0, &bounds, &cfg);
        assert_eq!(decoded.len(), 3);
    }

    #[test]
    fn extra_pieces_go_least_certain_first_and_never_from_an_anchored_slot() {
        let (cfg, bounds) = setup();
        let chair = class_of("dining_chair", &cfg);
        // Anchored slot 0 (least certain of all), free slots 2, 4 and 6 at different places.
        let mut t =
            tokens(&[(0, chair, -0.8, 0.3), (2, chair, -0.3, 0.9), (4, chair, 0.2, 0.5), (6, chair, 0.7, 0.8)], &cfg);
        let mut want = vec![0u8; cfg.count_width()];
        want[chair] = 2;
        let world = t.clone();
        match_counts(&world, &mut t, &CountRule::Asked(want), 1, &bounds, &cfg);
        let got = classes(&t, &cfg);
        let empty = cfg.classes() - 1;
        assert_eq!(
            (got[0], got[2], got[4], got[6]),
            (chair, chair, empty, empty),
            "the two least certain free chairs go"
        );
    }

    #[test]
    fn one_piece_in_two_anchored_slots_counts_once() {
        let (cfg, bounds) = setup();
        let sofa = class_of("multi_seat_sofa", &cfg);
        // Slots 0 and 1 hold the same sofa (two sitters on it): one sofa, as asked.
        let mut t = tokens(&[(0, sofa, 0.1, 0.9), (1, sofa, 0.1, 0.9)], &cfg);
        let dim = cfg.token_dim();
        t[4 * dim + CLASS_OFFSET + sofa] = 0.15;
        let mut want = vec![0u8; cfg.count_width()];
        want[sofa] = 1;
        let before = t.clone();
        match_counts(&before, &mut t, &CountRule::Asked(want), 2, &bounds, &cfg);
        assert_eq!(t, before, "the make-up is already as asked");
    }

    #[test]
    fn under_the_seen_rule_a_lone_chair_serving_a_person_gets_a_second_and_a_second_table_goes() {
        let (cfg, bounds) = setup();
        let (chair, table, empty) = (class_of("dining_chair", &cfg), class_of("dining_table", &cfg), cfg.classes() - 1);
        // The data: 0, 2 or 4 chairs and one table, in every room.
        let width = cfg.count_width();
        let rooms: Vec<Vec<u8>> = [0u8, 2, 4]
            .into_iter()
            .map(|n| {
                let mut v = vec![0u8; width];
                v[chair] = n;
                v[table] = 1;
                v
            })
            .collect();
        let seen = super::super::SeenCounts::of(rooms.iter().map(|v| (RoomType::Dining, v.as_slice())));
        let rule = CountRule::Seen(seen.of_room(RoomType::Dining).unwrap().clone());
        // Anchored slot 0 holds the seated person's chair; free slots 3, 4 hold tables far apart.
        let mut t = tokens(&[(0, chair, -0.8, 0.9), (3, table, 0.0, 0.9), (4, table, 0.7, 0.4)], &cfg);
        let dim = cfg.token_dim();
        t[6 * dim + CLASS_OFFSET + chair] = 0.1;
        let world = t.clone();
        match_counts(&world, &mut t, &rule, 1, &bounds, &cfg);
        let got = classes(&t, &cfg);
        assert_eq!((got[0], got[6]), (chair, chair), "one chair is unseen; the one in use stays, so two");
        assert_eq!((got[3], got[4]), (table, empty), "two tables are unseen: the less certain goes");
        // A seen make-up is left as it is.
        let before = t.clone();
        match_counts(&before, &mut t, &rule, 1, &bounds, &cfg);
        assert_eq!(t, before);
    }
}
