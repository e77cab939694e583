//! The count prior of a count-conditioned model ([`super::ModelConfig::count_condition`]): the
//! piece counts of its training rooms, keyed by the contacts in them and their floor area, from
//! which sampling draws the make-up a layout is conditioned on.
//!
//! It proposes how many pieces of each category a room holds — a make-up some training room with
//! the same sitters, liers and touchers and a floor of about the same size had — and nothing
//! else: where the pieces stand, which one serves whom and whether the model keeps to the counts
//! are the model's.

use crate::data::Rng;
use crate::human::Conditions;
use crate::scene::{Action, RoomType};
use serde::{Deserialize, Serialize};

/// Training rooms the draw chooses among: the nearest in floor area of those whose contacts
/// match best.
pub const NEAREST_ROOMS: usize = 16;

/// The make-ups of a model's training rooms.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CountPrior {
    /// One row per training room.
    pub rooms: Vec<PriorRoom>,
}

/// One training room as the prior keeps it: its type, its contact boxes by action, its floor
/// area (m², to 0.1) and its pieces per category (the model's class order). Written as one
/// string, `"dining 1 0 0 18.3: 0 0 1 …"` (type, sit, lie, touch, area: counts), so that a prior
/// of ten thousand rooms stays ten thousand lines of config.json.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(into = "String", try_from = "String")]
pub struct PriorRoom(pub RoomType, pub ContactKinds, pub f32, pub Vec<u8>);

impl From<PriorRoom> for String {
    fn from(r: PriorRoom) -> String {
        let counts: Vec<String> = r.3.iter().map(|n| n.to_string()).collect();
        format!("{} {} {} {} {}: {}", r.0.name(), r.1[0], r.1[1], r.1[2], r.2, counts.join(" "))
    }
}

impl TryFrom<String> for PriorRoom {
    type Error = String;

    fn try_from(text: String) -> Result<PriorRoom, String> {
        let bad = || format!("count prior room {text:?} is not \"ROOM SIT LIE TOUCH AREA: COUNTS…\"");
        let (head, counts) = text.split_once(':').ok_or_else(bad)?;
        let head: Vec<&str> = head.split_whitespace().collect();
        let [room, sit, lie, touch, area] = head[..] else { return Err(bad()) };
        let room = RoomType::ALL.into_iter().find(|r| r.name() == room).ok_or_else(bad)?;
        let kinds = [sit, lie, touch].map(|k| k.parse::<u8>());
        let [Ok(sit), Ok(lie), Ok(touch)] = kinds else { return Err(bad()) };
        let area: f32 = area.parse().map_err(|_| bad())?;
        let counts: Result<Vec<u8>, _> = counts.split_whitespace().map(str::parse).collect();
        Ok(PriorRoom(room, [sit, lie, touch], area, counts.map_err(|_| bad())?))
    }
}

/// Contact boxes by action: sit, lie, touch.
pub type ContactKinds = [u8; 3];

/// The contact boxes of `cond` by action.
pub fn contact_kinds(cond: &Conditions) -> ContactKinds {
    let mut kinds = [0u8; 3];
    for b in &cond.contact_boxes {
        let k = match b.action {
            Action::Sit => 0,
            Action::Lie => 1,
            _ => 2,
        };
        kinds[k] = kinds[k].saturating_add(1);
    }
    kinds
}

/// A floor area (m²) as a model records its training rooms' (here and in
/// [`super::SeenFloors`]): to 0.1 m².
pub fn recorded_area(area: f64) -> f32 {
    to_tenth(area)
}

/// A floor measure as a model records it: to a tenth of its unit (m² or m).
pub fn to_tenth(v: f64) -> f32 {
    ((v * 10.0).round() / 10.0) as f32
}

impl PriorRoom {
    /// A room of type `room` with `kinds` of contact boxes, `area` m² of floor and `counts`
    /// pieces per category.
    pub fn new(room: RoomType, kinds: ContactKinds, area: f64, counts: Vec<u8>) -> PriorRoom {
        PriorRoom(room, kinds, recorded_area(area), counts)
    }
}

impl CountPrior {
    /// The counts of a training room like a room of type `room` with `kinds` of contact boxes and
    /// `area` m² of floor: among the rooms of that type whose contact kinds differ least from
    /// `kinds` (summed over the actions), one of the [`NEAREST_ROOMS`] nearest in floor area (by
    /// ratio), chosen by `rng`. `None` when the prior has no room of that type.
    pub fn draw(&self, room: RoomType, kinds: ContactKinds, area: f64, rng: &mut Rng) -> Option<&[u8]> {
        let mismatch = |r: &PriorRoom| r.1.iter().zip(kinds).map(|(&a, b)| a.abs_diff(b) as u32).sum::<u32>();
        let of_room = || self.rooms.iter().filter(|r| r.0 == room);
        let best = of_room().map(mismatch).min()?;
        let far = |r: &PriorRoom| (area.max(1e-3) / f64::from(r.2).max(1e-3)).ln().abs();
        let mut near: Vec<(f64, &PriorRoom)> = of_room().filter(|r| mismatch(r) == best).map(|r| (far(r), r)).collect();
        // Stable: rooms equally far keep the prior's order, so a draw depends on the seed alone.
        near.sort_by(|a, b| a.0.total_cmp(&b.0));
        near.truncate(NEAREST_ROOMS);
        Some(&near[rng.index(near.len())].1.3)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn prior() -> CountPrior {
        let row = |room, kinds, area, first| PriorRoom::new(room, kinds, area, vec![first, 1]);
        let mut rooms = vec![row(RoomType::Dining, [2, 0, 0], 30.0, 9), row(RoomType::Living, [1, 0, 0], 20.0, 8)];
        // Twenty dining rooms with one sitter, 10 to 29 m²: the first count is the area.
        rooms.extend((10..30).map(|a| row(RoomType::Dining, [1, 0, 0], f64::from(a), a as u8)));
        CountPrior { rooms }
    }

    #[test]
    fn a_draw_is_one_of_the_rooms_with_the_same_contacts_nearest_in_area() {
        let prior = prior();
        let mut seen = std::collections::BTreeSet::new();
        for seed in 0..400 {
            let counts = prior.draw(RoomType::Dining, [1, 0, 0], 20.0, &mut Rng::new(seed)).unwrap();
            seen.insert(counts[0]);
        }
        // By ratio, the 16 nearest to 20 m² of 10..=29 m² are 14..=29 (29/20 = 1.45 against
        // 20/13 = 1.54): not 13 m² or smaller, never the two-sitter or living room.
        assert_eq!(seen, (14..30).collect());
    }

    #[test]
    fn without_an_exact_match_the_nearest_contacts_serve_and_another_room_type_gets_none() {
        let prior = prior();
        let counts = prior.draw(RoomType::Dining, [3, 0, 0], 30.0, &mut Rng::new(1)).unwrap();
        assert_eq!(counts, [9, 1], "two sitters are nearer three than one is");
        assert!(prior.draw(RoomType::Bedroom, [0, 1, 0], 20.0, &mut Rng::new(1)).is_none());
    }

    #[test]
    fn a_draw_depends_on_the_seed_alone_and_rows_are_one_string_each() {
        let prior = prior();
        let draw = |seed| prior.draw(RoomType::Dining, [1, 0, 0], 17.0, &mut Rng::new(seed)).unwrap().to_vec();
        assert_eq!(draw(7), draw(7));
        assert!((0..20).map(draw).collect::<std::collections::BTreeSet<_>>().len() > 5);
        let json = serde_json::to_string(&prior.rooms[0]).unwrap();
        assert_eq!(json, r#""dining 2 0 0 30: 9 1""#);
        let back: CountPrior = serde_json::from_str(&serde_json::to_string(&prior).unwrap()).unwrap();
        assert_eq!(back, prior);
        for bad in ["dining 2 0 30: 9 1", "attic 2 0 0 30: 9", "dining 2 0 0 30 9 1", "dining 2 0 0 30: 9 x"] {
            let error = serde_json::from_str::<PriorRoom>(&format!("{bad:?}")).unwrap_err().to_string();
            assert!(error.contains("is not \"ROOM SIT LIE TOUCH AREA"), "{bad}: {error}");
        }
    }
}
