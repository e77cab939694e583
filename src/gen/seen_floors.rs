//! The floor areas a model's training rooms have, per room type: the least and the largest. An
//! input whose floor is outside them is one the model never saw a room like, and `generate` says
//! so before sampling ([`crate::pipeline::input_notes`]); its layouts may still pass `check`.
//!
//! It knows the areas only, not the plans' shapes or proportions, and changes nothing sampled.

use crate::scene::RoomType;
use serde::{Deserialize, Serialize};

/// Per room type, the floor areas of the training rooms.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenFloors {
    /// One entry per room type the model was trained on.
    pub rooms: Vec<SeenFloor>,
}

/// One room type's floor areas.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenFloor {
    /// The room type.
    pub room: RoomType,
    /// How many training rooms of it there were.
    pub rooms: usize,
    /// The least and the largest floor area among them (m², to 0.1 as the encoded rooms keep it).
    pub area: [f32; 2],
}

/// An input's floor outside the training rooms' areas.
#[derive(Debug, Clone, PartialEq)]
pub struct UnseenFloor {
    /// The input's room type.
    pub room: RoomType,
    /// Its floor area (m²).
    pub area: f32,
    /// The training rooms' least and largest area (m²).
    pub seen: [f32; 2],
}

impl SeenFloors {
    /// The areas of `rooms`: each a room type and its floor area (m²).
    pub fn of(rooms: impl IntoIterator<Item = (RoomType, f32)>) -> SeenFloors {
        let mut out = SeenFloors::default();
        for (room, area) in rooms {
            match out.rooms.iter_mut().find(|r| r.room == room) {
                Some(r) => {
                    r.rooms += 1;
                    r.area = [r.area[0].min(area), r.area[1].max(area)];
                }
                None => out.rooms.push(SeenFloor { room, rooms: 1, area: [area, area] }),
            }
        }
        out.rooms.sort_by_key(|r| r.room);
        out
    }

    /// What is wrong with these areas, if anything: an area that is not a finite positive number,
    /// a least above its largest, no rooms, or a room type twice.
    pub fn problem(&self) -> Option<String> {
        for (k, r) in self.rooms.iter().enumerate() {
            let [least, most] = r.area;
            if !(least.is_finite() && most.is_finite() && least > 0.0 && least <= most) {
                return Some(format!(
                    "seen_floors for {}: area [{least}, {most}] is not a range of m² above 0",
                    r.room
                ));
            }
            if r.rooms == 0 {
                return Some(format!("seen_floors for {} counts no rooms", r.room));
            }
            if self.rooms[..k].iter().any(|o| o.room == r.room) {
                return Some(format!("seen_floors has {} twice", r.room));
            }
        }
        None
    }

    /// A floor of `area` m² in a room of type `room`, if it is outside the training rooms' areas
    /// (`None` too when the model saw no room of that type: nothing to compare with).
    pub fn unseen(&self, room: RoomType, area: f32) -> Option<UnseenFloor> {
        let seen = self.rooms.iter().find(|r| r.room == room)?.area;
        (area < seen[0] || area > seen[1]).then_some(UnseenFloor { room, area, seen })
    }
}

impl std::fmt::Display for UnseenFloor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let than = if self.area > self.seen[1] { "larger than any" } else { "smaller than any" };
        write!(
            f,
            "the floor plan's {:.1} m² is {than} of the model's {} training rooms ({:.1}–{:.1} m²): its layouts may be less like real rooms",
            self.area, self.room, self.seen[0], self.seen[1]
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_areas_are_each_room_types_least_and_largest() {
        let seen = SeenFloors::of([
            (RoomType::Dining, 25.0),
            (RoomType::Bedroom, 12.0),
            (RoomType::Dining, 10.0),
            (RoomType::Dining, 40.0),
        ]);
        assert_eq!(
            seen.rooms,
            vec![
                SeenFloor { room: RoomType::Bedroom, rooms: 1, area: [12.0, 12.0] },
                SeenFloor { room: RoomType::Dining, rooms: 3, area: [10.0, 40.0] },
            ]
        );
        assert_eq!(seen.unseen(RoomType::Dining, 40.0), None);
        assert_eq!(seen.unseen(RoomType::Dining, 10.0), None);
        let big = seen.unseen(RoomType::Dining, 80.0).expect("beyond");
        assert_eq!(big.seen, [10.0, 40.0]);
        assert_eq!(
            big.to_string(),
            "the floor plan's 80.0 m² is larger than any of the model's dining training rooms (10.0–40.0 m²): its layouts may be less like real rooms"
        );
        assert!(seen.unseen(RoomType::Bedroom, 6.0).expect("below").to_string().contains("smaller than any"));
        assert_eq!(seen.unseen(RoomType::Living, 500.0), None, "no living rooms seen: nothing to say");
    }

    #[test]
    fn bad_areas_are_named() {
        let room = |area: [f32; 2], rooms: usize| SeenFloor { room: RoomType::Dining, rooms, area };
        let problem = |rooms: Vec<SeenFloor>| SeenFloors { rooms }.problem();
        assert_eq!(problem(vec![room([10.0, 40.0], 3)]), None);
        assert_eq!(
            problem(vec![room([40.0, 10.0], 3)]).as_deref(),
            Some("seen_floors for dining: area [40, 10] is not a range of m² above 0")
        );
        assert!(problem(vec![room([f32::NAN, 10.0], 3)]).is_some());
        assert!(problem(vec![room([0.0, 10.0], 3)]).is_some());
        assert_eq!(problem(vec![room([10.0, 40.0], 0)]).as_deref(), Some("seen_floors for dining counts no rooms"));
        assert_eq!(
            problem(vec![room([10.0, 40.0], 3), room([10.0, 40.0], 3)]).as_deref(),
            Some("seen_floors has dining twice")
        );
    }

    #[test]
    fn it_reads_back_what_it_writes() {
        let seen = SeenFloors::of([(RoomType::Living, 15.5), (RoomType::Living, 60.0)]);
        let text = serde_json::to_string(&seen).unwrap();
        assert_eq!(text, r#"{"rooms":[{"room":"living","rooms":2,"area":[15.5,60.0]}]}"#);
        assert_eq!(serde_json::from_str::<SeenFloors>(&text).unwrap(), seen);
    }
}
