//! The counts a model's training data has: for each room type it was trained on and each
//! category, how many training rooms hold 0, 1, 2, … pieces of it. The sampler keeps a layout's
//! counts among them ([`super::count_projection`]): a count the data never has (one dining chair,
//! three nightstands) is moved to the nearest count it has.
//!
//! It knows counts one category at a time, not which make-ups go together (that is
//! [`super::CountPrior`]'s, for count-conditioned models), and nothing about where pieces stand.

use crate::scene::RoomType;
use serde::{Deserialize, Serialize};

/// Per room type and category, the counts the training rooms hold and how many rooms hold each.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenCounts {
    /// One entry per room type the model was trained on.
    pub rooms: Vec<SeenRoom>,
}

/// One room type's counts: `categories[c]` lists `[count, rooms]` pairs, ascending by count, for
/// category c of the room type's order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenRoom {
    /// The room type.
    pub room: RoomType,
    /// Per category: `[count, rooms holding it]`, ascending by count.
    pub categories: Vec<Vec<[u32; 2]>>,
}

impl SeenCounts {
    /// The counts of `rooms`: each a room type and its pieces per category (that type's order).
    pub fn of<'a>(rooms: impl IntoIterator<Item = (RoomType, &'a [u8])>) -> SeenCounts {
        let mut out = SeenCounts::default();
        for (room, counts) in rooms {
            let at = match out.rooms.iter().position(|r| r.room == room) {
                Some(at) => at,
                None => {
                    let categories = vec![Vec::new(); room.categories().len()];
                    out.rooms.push(SeenRoom { room, categories });
                    out.rooms.len() - 1
                }
            };
            for (seen, &n) in out.rooms[at].categories.iter_mut().zip(counts) {
                let n = u32::from(n);
                match seen.binary_search_by_key(&n, |pair| pair[0]) {
                    Ok(k) => seen[k][1] += 1,
                    Err(k) => seen.insert(k, [n, 1]),
                }
            }
        }
        out.rooms.sort_by_key(|r| r.room);
        out
    }

    /// The counts of room type `room`, if the model was trained on it.
    pub fn of_room(&self, room: RoomType) -> Option<&SeenRoom> {
        self.rooms.iter().find(|r| r.room == room)
    }

    /// Why these counts cannot serve a model of `rooms` with `width` categories, if they cannot.
    pub fn problem(&self, rooms: &[RoomType], width: usize) -> Option<String> {
        if let Some(r) = self.rooms.iter().find(|r| r.categories.len() != width) {
            return Some(format!("seen_counts for {} has {} categories, not {width}", r.room, r.categories.len()));
        }
        rooms.iter().find(|&&room| self.of_room(room).is_none()).map(|room| format!("seen_counts has no {room} room"))
    }
}

impl SeenRoom {
    /// The make-up nearest `have` whose every count the data has: each category's count is kept
    /// if some training room has it, and otherwise moved to the nearest count one has that is at
    /// least `least` (the pieces that cannot go); of two equally near, the one more rooms hold,
    /// then the smaller. A category with no such count keeps `have`'s.
    pub fn nearest(&self, have: &[u8], least: &[u8]) -> Vec<u8> {
        let seen = |c: usize| self.categories.get(c).map(Vec::as_slice).unwrap_or_default();
        have.iter()
            .enumerate()
            .map(|(c, &n)| {
                let floor = u32::from(least.get(c).copied().unwrap_or(0));
                let pairs = seen(c);
                if pairs.is_empty() || pairs.iter().any(|p| p[0] == u32::from(n)) {
                    return n;
                }
                let best = pairs
                    .iter()
                    .filter(|p| p[0] >= floor)
                    .min_by_key(|p| (p[0].abs_diff(u32::from(n)), std::cmp::Reverse(p[1]), p[0]));
                best.map_or(n, |p| p[0].min(u32::from(u8::MAX)) as u8)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dining() -> SeenRoom {
        // Chairs (category 0): 0 in 5 rooms, 2 in 30, 4 in 20; tables (1): 1 in every room.
        let width = RoomType::Dining.categories().len();
        let mut rooms: Vec<(RoomType, Vec<u8>)> = Vec::new();
        for (chairs, n) in [(0u8, 5), (2, 30), (4, 20)] {
            let mut counts = vec![0u8; width];
            counts[0] = chairs;
            counts[1] = 1;
            rooms.extend(std::iter::repeat_n((RoomType::Dining, counts), n));
        }
        let seen = SeenCounts::of(rooms.iter().map(|(r, c)| (*r, c.as_slice())));
        assert_eq!(seen.rooms.len(), 1);
        assert_eq!(seen.rooms[0].categories[0], [[0, 5], [2, 30], [4, 20]]);
        assert_eq!(seen.rooms[0].categories[1], [[1, 55]]);
        seen.rooms[0].clone()
    }

    fn make_up(chairs: u8, tables: u8) -> Vec<u8> {
        let mut v = vec![0u8; RoomType::Dining.categories().len()];
        v[0] = chairs;
        v[1] = tables;
        v
    }

    #[test]
    fn seen_counts_stay_and_unseen_ones_go_to_the_nearest_seen_one() {
        let room = dining();
        let none = make_up(0, 0);
        assert_eq!(room.nearest(&make_up(2, 1), &none), make_up(2, 1), "both seen: unchanged");
        assert_eq!(room.nearest(&make_up(3, 1), &none)[0], 2, "3 is as near 2 as 4; more rooms hold 2");
        assert_eq!(room.nearest(&make_up(7, 2), &none), make_up(4, 1), "7 chairs → 4, 2 tables → 1");
        assert_eq!(room.nearest(&make_up(1, 1), &none)[0], 2, "1 is as near 0 as 2; more rooms hold 2");
    }

    #[test]
    fn pieces_that_cannot_go_set_a_floor() {
        let room = dining();
        // One chair serves a seated person: the nearest seen count that keeps it is 2, never 0.
        assert_eq!(room.nearest(&make_up(1, 1), &make_up(1, 0))[0], 2);
        // Five chairs of which five are held: no seen count is that high, so five stay.
        assert_eq!(room.nearest(&make_up(5, 1), &make_up(5, 0))[0], 5);
    }

    #[test]
    fn a_category_the_data_never_counted_keeps_its_count_and_json_round_trips() {
        let mut room = dining();
        room.categories[2].clear();
        assert_eq!(room.nearest(&make_up(2, 1).iter().map(|&v| v.max(3)).collect::<Vec<_>>(), &[])[2], 3);
        let seen = SeenCounts { rooms: vec![room] };
        let back: SeenCounts = serde_json::from_str(&serde_json::to_string(&seen).unwrap()).unwrap();
        assert_eq!(back, seen);
        let width = RoomType::Dining.categories().len();
        assert_eq!(seen.problem(&[RoomType::Dining], width), None);
        assert!(seen.problem(&[RoomType::Dining, RoomType::Living], width).unwrap().contains("no living room"));
        assert!(seen.problem(&[RoomType::Dining], width + 1).unwrap().contains("categories"));
    }
}
