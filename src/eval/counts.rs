//! How many pieces of each category a room has, against the reference's rooms: a count-aware KL
//! and the rooms with a count the data never has.
//!
//! CKL compares the pooled category shares only, so a set of living rooms with three dining tables
//! and no sofa can score as well as the data if other rooms make up the mix. Here each category's
//! *per-room count* distribution (how many rooms have 0, 1, 2, … of it) is compared with the
//! reference's, and each generated room is checked for a (category, count) that no room of a
//! second, larger set (the training data, when there is one) has: a test split of a few hundred
//! rooms misses counts the data does have, so that real val rooms would be flagged against it.
//! This module only counts; it judges nothing physical.

use super::category_kl;
use crate::scene::{Category, RoomType, Scene};
use serde::{Deserialize, Serialize};

/// Per category of a room type (its one-hot order), the share of rooms holding 0, 1, 2, … pieces
/// of it (counts above the room type's object limit count as the limit).
#[derive(Debug, Clone, PartialEq)]
pub struct CountDistribution {
    /// The room type.
    pub room: RoomType,
    /// `shares[c][k]`: share of the rooms with `k` pieces of category `c`.
    pub shares: Vec<Vec<f64>>,
    /// The rooms counted.
    pub rooms: usize,
}

impl CountDistribution {
    /// The distribution of `scenes`, all of `room`.
    pub fn of<'a>(scenes: impl IntoIterator<Item = &'a Scene>, room: RoomType) -> CountDistribution {
        let cats = room.categories();
        let mut shares = vec![vec![0.0; room.max_objects() + 1]; cats.len()];
        let mut rooms = 0;
        for s in scenes {
            rooms += 1;
            for (c, counts) in room_counts(s, room).into_iter().enumerate() {
                shares[c][counts] += 1.0;
            }
        }
        let n = rooms.max(1) as f64;
        shares.iter_mut().flatten().for_each(|v| *v /= n);
        CountDistribution { room, shares, rooms }
    }

    /// Whether some room here has exactly `count` pieces of category index `c`.
    pub fn has(&self, c: usize, count: usize) -> bool {
        self.shares[c].get(count).is_some_and(|&s| s > 0.0)
    }
}

/// The number of pieces of each of `room`'s categories in `scene` (one-hot order; capped at the
/// room type's object limit).
fn room_counts(scene: &Scene, room: RoomType) -> Vec<usize> {
    room.category_counts(&scene.objects).into_iter().map(|k| k.min(room.max_objects())).collect()
}

/// A (category, count) the reference never has, and how many generated rooms have it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnseenCount {
    /// The category.
    pub category: Category,
    /// The count per room.
    pub count: usize,
    /// Generated rooms with exactly that many.
    pub rooms: usize,
}

/// The count statistics of a set of generated rooms against the reference.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CountReport {
    /// The mean, over the room type's categories, of KL(reference ‖ generated) between the per-room
    /// count distributions (smoothed like CKL; 0 when they agree).
    pub count_kl: f64,
    /// Share of the generated rooms with some category's count that no room of the `seen` set
    /// ([`count_report`]) has.
    pub unseen_rooms: f64,
    /// The (category, count) pairs behind `unseen_rooms`, most rooms first (ties in category order).
    pub unseen: Vec<UnseenCount>,
}

/// The count statistics of `scenes` against `reference` (the count KL) and `seen` (the counts
/// some real room has: the training data's, for `shade-sim eval` on a dataset), all of one room
/// type.
pub fn count_report(scenes: &[Scene], reference: &CountDistribution, seen: &CountDistribution) -> CountReport {
    let room = reference.room;
    let generated = CountDistribution::of(scenes, room);
    let count_kl = reference.shares.iter().zip(&generated.shares).map(|(p, q)| category_kl(p, q)).sum::<f64>()
        / reference.shares.len().max(1) as f64;
    let mut unseen: Vec<UnseenCount> = Vec::new();
    let mut odd_rooms = 0;
    for s in scenes {
        let mut odd = false;
        for (c, k) in room_counts(s, room).into_iter().enumerate() {
            if seen.has(c, k) {
                continue;
            }
            odd = true;
            let category = room.categories()[c];
            match unseen.iter_mut().find(|u| u.category == category && u.count == k) {
                Some(u) => u.rooms += 1,
                None => unseen.push(UnseenCount { category, count: k, rooms: 1 }),
            }
        }
        odd_rooms += usize::from(odd);
    }
    unseen.sort_by(|a, b| {
        b.rooms
            .cmp(&a.rooms)
            .then(room.category_index(a.category).cmp(&room.category_index(b.category)))
            .then(a.count.cmp(&b.count))
    });
    CountReport {
        count_kl,
        unseen_rooms: if scenes.is_empty() { 0.0 } else { odd_rooms as f64 / scenes.len() as f64 },
        unseen,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{FloorPlan, Object};

    fn room(categories: &[Category]) -> Scene {
        let floor = FloorPlan { polygon: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]], height: 2.7 };
        let mut s = Scene::new(RoomType::Living, floor);
        for (k, &c) in categories.iter().enumerate() {
            s.objects.push(Object::standing(format!("o{k}"), c, [0.5 + 0.6 * k as f64, 1.0], [0.5, 0.5, 0.5]));
        }
        s
    }

    #[test]
    fn the_same_rooms_score_zero_and_nothing_unseen() {
        use Category::*;
        let rooms = vec![room(&[MultiSeatSofa, CoffeeTable]), room(&[MultiSeatSofa, DiningTable, DiningChair])];
        let reference = CountDistribution::of(&rooms, RoomType::Living);
        let r = count_report(&rooms, &reference, &reference);
        assert!(r.count_kl.abs() < 1e-9, "{r:?}");
        assert_eq!((r.unseen_rooms, r.unseen.len()), (0.0, 0));
        // By hand: half the rooms have one dining table, half none.
        let table = RoomType::Living.category_index(DiningTable).unwrap();
        assert_eq!(&reference.shares[table][..3], &[0.5, 0.5, 0.0]);
    }

    #[test]
    fn rooms_with_three_dining_tables_are_flagged() {
        use Category::*;
        let data: Vec<Scene> = (0..10)
            .map(|k| if k % 2 == 0 { room(&[MultiSeatSofa, CoffeeTable]) } else { room(&[DiningTable, DiningChair]) })
            .collect();
        let reference = CountDistribution::of(&data, RoomType::Living);
        let odd = vec![room(&[DiningTable, DiningTable, DiningTable, DiningChair]); 4];
        let r = count_report(&odd, &reference, &reference);
        assert_eq!(r.unseen_rooms, 1.0);
        assert_eq!(r.unseen, vec![UnseenCount { category: DiningTable, count: 3, rooms: 4 }]);
        // Judged against a larger set that has three tables somewhere, nothing is unseen; the
        // count KL still compares with the reference.
        let mut larger = data.clone();
        larger.push(room(&[DiningTable, DiningTable, DiningTable]));
        let seen = CountDistribution::of(&larger, RoomType::Living);
        let wider = count_report(&odd, &reference, &seen);
        assert_eq!((wider.unseen_rooms, wider.unseen.len(), wider.count_kl), (0.0, 0, r.count_kl));
        // The pooled shares hardly tell (dining tables and chairs are in the data), the counts do:
        // every category's KL by hand, over the room type's categories.
        let n = RoomType::Living.categories().len() as f64;
        let kl = |p: &[f64], q: &[f64]| category_kl(p, q);
        // Sofa, coffee table: data 0.5 none / 0.5 one, generated all none; dining table: data
        // 0.5 / 0.5 at 0 and 1, generated all at 3; dining chair: data 0.5 / 0.5, generated all one.
        let expected =
            (kl(&[0.5, 0.5], &[1.0, 0.0]) * 2.0 + kl(&[0.5, 0.5], &[0.0, 0.0]) + kl(&[0.5, 0.5], &[0.0, 1.0])) / n;
        assert!((r.count_kl - expected).abs() < 1e-9, "{} vs {expected}", r.count_kl);
        assert!(r.count_kl > 1.0);
    }
}
