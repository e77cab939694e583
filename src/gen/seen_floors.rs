//! The floors a model's training rooms have, per room type: the least and the largest area, and
//! the least and the largest short and long side of the plan in its own frame. An input whose
//! floor is outside them — a hall larger than any training room, a 2 m corridor narrower than any —
//! is one the model never saw a room like, and `generate` says so before sampling
//! ([`crate::pipeline::input_notes`]); its layouts may still pass `check`.
//!
//! It knows sizes only, not the plans' shapes (an L and a rectangle of one size are alike to it),
//! and changes nothing sampled.

use super::count_prior::{recorded_area, to_tenth};
use crate::scene::{FloorPlan, RoomFrame, RoomType};
use serde::{Deserialize, Serialize};

/// How large one floor plan is, as a model records its training rooms': its area (m², to 0.1)
/// and the short and long side of its bounding box in its own frame ([`RoomFrame`]; m, to 0.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorSize {
    /// Floor area (m²).
    pub area: f32,
    /// The bounding box's short side in the room's frame (m): how wide the room is.
    pub width: f32,
    /// Its long side (m): how long the room is.
    pub length: f32,
}

impl FloorSize {
    /// The size of `plan`.
    pub fn of(plan: &FloorPlan) -> FloorSize {
        let [a, b] = RoomFrame::of(plan).sides(plan);
        FloorSize { area: recorded_area(plan.polygon().area()), width: to_tenth(a.min(b)), length: to_tenth(a.max(b)) }
    }
}

/// Per room type, the floor sizes of the training rooms.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenFloors {
    /// One entry per room type the model was trained on.
    pub rooms: Vec<SeenFloor>,
}

/// One room type's floor sizes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeenFloor {
    /// The room type.
    pub room: RoomType,
    /// How many training rooms of it there were.
    pub rooms: usize,
    /// The least and the largest floor area among them (m², to 0.1 as [`FloorSize`] keeps it).
    pub area: [f32; 2],
    /// The least and the largest width ([`FloorSize::width`], m); absent in folders recorded
    /// before it, which then say nothing of widths.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub width: Option<[f32; 2]>,
    /// The least and the largest length ([`FloorSize::length`], m); absent like `width`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<[f32; 2]>,
}

/// What an input's floor has outside the training rooms' sizes: one entry per measure.
#[derive(Debug, Clone, PartialEq)]
pub struct UnseenFloor {
    /// The input's room type.
    pub room: RoomType,
    /// Each measure outside the seen range, in the order area, width, length.
    pub beyond: Vec<Beyond>,
}

/// One measure of a floor outside the training rooms' range of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beyond {
    /// Which measure.
    pub measure: FloorMeasure,
    /// The input's value.
    pub value: f32,
    /// The training rooms' least and largest.
    pub seen: [f32; 2],
}

/// A measure of a floor's size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FloorMeasure {
    /// Area (m²).
    Area,
    /// Width (m).
    Width,
    /// Length (m).
    Length,
}

impl SeenFloors {
    /// The sizes of `rooms`: each a room type and its floor's size.
    pub fn of(rooms: impl IntoIterator<Item = (RoomType, FloorSize)>) -> SeenFloors {
        let widen = |r: [f32; 2], v: f32| [r[0].min(v), r[1].max(v)];
        let mut out = SeenFloors::default();
        for (room, size) in rooms {
            match out.rooms.iter_mut().find(|r| r.room == room) {
                Some(r) => {
                    r.rooms += 1;
                    r.area = widen(r.area, size.area);
                    r.width = r.width.map(|w| widen(w, size.width));
                    r.length = r.length.map(|l| widen(l, size.length));
                }
                None => out.rooms.push(SeenFloor {
                    room,
                    rooms: 1,
                    area: [size.area; 2],
                    width: Some([size.width; 2]),
                    length: Some([size.length; 2]),
                }),
            }
        }
        out.rooms.sort_by_key(|r| r.room);
        out
    }

    /// What is wrong with these sizes, if anything: a range that is not of finite positive numbers
    /// with its least at most its largest, no rooms, or a room type twice.
    pub fn problem(&self) -> Option<String> {
        for (k, r) in self.rooms.iter().enumerate() {
            let ranges = [("area", Some(r.area), "m²"), ("width", r.width, "m"), ("length", r.length, "m")];
            for (name, range, unit) in ranges {
                let Some([least, most]) = range else { continue };
                if !(least.is_finite() && most.is_finite() && least > 0.0 && least <= most) {
                    return Some(format!(
                        "seen_floors for {}: {name} [{least}, {most}] is not a range of {unit} above 0",
                        r.room
                    ));
                }
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

    /// A floor of `size` in a room of type `room`, if any of its measures is outside the training
    /// rooms' (`None` too when the model saw no room of that type: nothing to compare with).
    pub fn unseen(&self, room: RoomType, size: FloorSize) -> Option<UnseenFloor> {
        let seen = self.rooms.iter().find(|r| r.room == room)?;
        let measures = [
            (FloorMeasure::Area, size.area, Some(seen.area)),
            (FloorMeasure::Width, size.width, seen.width),
            (FloorMeasure::Length, size.length, seen.length),
        ];
        let beyond: Vec<Beyond> = measures
            .into_iter()
            .filter_map(|(measure, value, seen)| {
                let seen = seen?;
                (value < seen[0] || value > seen[1]).then_some(Beyond { measure, value, seen })
            })
            .collect();
        (!beyond.is_empty()).then_some(UnseenFloor { room, beyond })
    }
}

impl std::fmt::Display for Beyond {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let above = self.value > self.seen[1];
        let ([lo, hi], v) = (self.seen, self.value);
        match self.measure {
            FloorMeasure::Area => {
                let than = if above { "larger" } else { "smaller" };
                write!(f, "its {v:.1} m² is {than} than any ({lo:.1}–{hi:.1} m²)")
            }
            FloorMeasure::Width => {
                let than = if above { "wider" } else { "narrower" };
                write!(f, "it is {v:.1} m wide, {than} than any ({lo:.1}–{hi:.1} m)")
            }
            FloorMeasure::Length => {
                let than = if above { "longer" } else { "shorter" };
                write!(f, "it is {v:.1} m long, {than} than any ({lo:.1}–{hi:.1} m)")
            }
        }
    }
}

impl std::fmt::Display for UnseenFloor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let parts: Vec<String> = self.beyond.iter().map(Beyond::to_string).collect();
        write!(
            f,
            "the floor plan is unlike the model's {} training rooms: {}; its layouts may be less like real rooms",
            self.room,
            parts.join(", and ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn size(area: f32, width: f32, length: f32) -> FloorSize {
        FloorSize { area, width, length }
    }

    #[test]
    fn a_floors_size_is_its_area_and_sides_in_its_own_frame() {
        let rect = FloorPlan::rectangle(4.04, 2.96, 2.6);
        assert_eq!(FloorSize::of(&rect), size(12.0, 3.0, 4.0), "12.0 m² to 0.1; the short side first");
        // The same rectangle turned by 30° about the origin: the same size, not its world box's.
        let (s, c) = 30f64.to_radians().sin_cos();
        let turned = FloorPlan {
            polygon: rect.polygon.iter().map(|&[x, y]| [c * x - s * y, s * x + c * y]).collect(),
            height: 2.6,
        };
        assert_eq!(FloorSize::of(&turned), size(12.0, 3.0, 4.0));
        // An L: its bounding box's sides.
        let l = FloorPlan {
            polygon: vec![[0.0, 0.0], [5.0, 0.0], [5.0, 2.0], [3.0, 2.0], [3.0, 4.0], [0.0, 4.0]],
            height: 2.6,
        };
        assert_eq!(FloorSize::of(&l), size(16.0, 4.0, 5.0));
    }

    #[test]
    fn the_sizes_are_each_room_types_least_and_largest() {
        let seen = SeenFloors::of([
            (RoomType::Dining, size(25.0, 4.0, 6.2)),
            (RoomType::Bedroom, size(12.0, 3.0, 4.0)),
            (RoomType::Dining, size(10.0, 2.8, 3.6)),
            (RoomType::Dining, size(40.0, 5.0, 8.0)),
        ]);
        let floor = |room, rooms, area, width, length| SeenFloor {
            room,
            rooms,
            area,
            width: Some(width),
            length: Some(length),
        };
        assert_eq!(
            seen.rooms,
            vec![
                floor(RoomType::Bedroom, 1, [12.0, 12.0], [3.0, 3.0], [4.0, 4.0]),
                floor(RoomType::Dining, 3, [10.0, 40.0], [2.8, 5.0], [3.6, 8.0]),
            ]
        );
        assert_eq!(seen.unseen(RoomType::Dining, size(40.0, 5.0, 8.0)), None, "the ranges hold their ends");
        assert_eq!(seen.unseen(RoomType::Dining, size(10.0, 2.8, 3.6)), None);
        let big = seen.unseen(RoomType::Dining, size(80.0, 8.0, 10.0)).expect("beyond");
        assert_eq!(big.beyond.len(), 3);
        assert_eq!(
            big.to_string(),
            "the floor plan is unlike the model's dining training rooms: its 80.0 m² is larger than any (10.0–40.0 m²), and it is 8.0 m wide, wider than any (2.8–5.0 m), and it is 10.0 m long, longer than any (3.6–8.0 m); its layouts may be less like real rooms"
        );
        // A 2 × 20 m corridor has an area the dining rooms have, and neither their width nor length.
        let corridor = seen.unseen(RoomType::Dining, size(40.0, 2.0, 20.0)).expect("a corridor");
        assert_eq!(
            corridor.to_string(),
            "the floor plan is unlike the model's dining training rooms: it is 2.0 m wide, narrower than any (2.8–5.0 m), and it is 20.0 m long, longer than any (3.6–8.0 m); its layouts may be less like real rooms"
        );
        let small = seen.unseen(RoomType::Bedroom, size(6.0, 2.0, 3.0)).expect("below").to_string();
        assert!(
            small.contains("smaller than any") && small.contains("narrower") && small.contains("shorter"),
            "{small}"
        );
        assert_eq!(
            seen.unseen(RoomType::Living, size(500.0, 20.0, 25.0)),
            None,
            "no living rooms seen: nothing to say"
        );
    }

    #[test]
    fn a_folder_recorded_before_widths_judges_areas_only() {
        let old: SeenFloors =
            serde_json::from_str(r#"{"rooms":[{"room":"dining","rooms":3,"area":[10.0,40.0]}]}"#).unwrap();
        assert_eq!(old.rooms[0].width, None);
        assert_eq!(old.problem(), None);
        assert_eq!(old.unseen(RoomType::Dining, size(40.0, 2.0, 20.0)), None, "a corridor it cannot see");
        assert_eq!(old.unseen(RoomType::Dining, size(80.0, 8.0, 10.0)).unwrap().beyond.len(), 1);
    }

    #[test]
    fn bad_sizes_are_named() {
        let room = |area: [f32; 2], rooms: usize| SeenFloor {
            room: RoomType::Dining,
            rooms,
            area,
            width: Some([2.8, 5.0]),
            length: Some([3.6, 8.0]),
        };
        let problem = |rooms: Vec<SeenFloor>| SeenFloors { rooms }.problem();
        assert_eq!(problem(vec![room([10.0, 40.0], 3)]), None);
        assert_eq!(
            problem(vec![room([40.0, 10.0], 3)]).as_deref(),
            Some("seen_floors for dining: area [40, 10] is not a range of m² above 0")
        );
        assert!(problem(vec![room([f32::NAN, 10.0], 3)]).is_some());
        assert!(problem(vec![room([0.0, 10.0], 3)]).is_some());
        let narrow = SeenFloor { width: Some([5.0, 2.8]), ..room([10.0, 40.0], 3) };
        assert_eq!(
            problem(vec![narrow]).as_deref(),
            Some("seen_floors for dining: width [5, 2.8] is not a range of m above 0")
        );
        let endless = SeenFloor { length: Some([3.6, f32::INFINITY]), ..room([10.0, 40.0], 3) };
        assert!(problem(vec![endless]).unwrap().contains("length"));
        assert_eq!(problem(vec![room([10.0, 40.0], 0)]).as_deref(), Some("seen_floors for dining counts no rooms"));
        assert_eq!(
            problem(vec![room([10.0, 40.0], 3), room([10.0, 40.0], 3)]).as_deref(),
            Some("seen_floors has dining twice")
        );
    }

    #[test]
    fn it_reads_back_what_it_writes() {
        let seen =
            SeenFloors::of([(RoomType::Living, size(15.5, 3.1, 5.0)), (RoomType::Living, size(60.0, 6.0, 10.0))]);
        let text = serde_json::to_string(&seen).unwrap();
        assert_eq!(
            text,
            r#"{"rooms":[{"room":"living","rooms":2,"area":[15.5,60.0],"width":[3.1,6.0],"length":[5.0,10.0]}]}"#
        );
        assert_eq!(serde_json::from_str::<SeenFloors>(&text).unwrap(), seen);
    }
}
