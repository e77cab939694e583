//! The `shade-scene/1` document: room type, floor plan, objects and humans.

use super::{FloorPlan, Human, Object, RoomType};
use serde::{Deserialize, Serialize};

/// The format tag every scene file carries.
pub const FORMAT: &str = "shade-scene/1";

/// A scene: what `generate` reads (no objects) and writes (with objects).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Always [`FORMAT`].
    pub format: String,
    /// Room type; selects the category vocabulary.
    pub room_type: RoomType,
    /// Floor polygon and ceiling height.
    pub floor_plan: FloorPlan,
    /// Furniture (empty in a generation input).
    #[serde(default)]
    pub objects: Vec<Object>,
    /// Human motions.
    #[serde(default)]
    pub humans: Vec<Human>,
}

impl Scene {
    /// The room window the scene is rasterised in: its room type's side, centred on the floor
    /// plan's bounding box — or, along an axis on which the plan is wider than the window (the
    /// training rooms never are), on the people, as far as the plan allows
    /// ([`crate::geom::RoomWindow::around_focus`]).
    pub fn room_window(&self) -> crate::geom::RoomWindow {
        crate::geom::RoomWindow::around_focus(
            self.room_type.window_side(),
            &self.floor_plan.polygon(),
            self.people_bounds(),
        )
    }

    /// The horizontal bounding box of every joint of every person in every frame (`None` without
    /// people).
    pub fn people_bounds(&self) -> Option<(glam::DVec2, glam::DVec2)> {
        let mut joints =
            self.humans.iter().flat_map(|h| h.frames.iter().flatten()).map(|j| glam::DVec2::new(j[0], j[1]));
        let first = joints.next()?;
        Some(joints.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// An empty scene of `room_type` over `floor_plan`.
    pub fn new(room_type: RoomType, floor_plan: FloorPlan) -> Scene {
        Scene { format: FORMAT.to_string(), room_type, floor_plan, objects: Vec::new(), humans: Vec::new() }
    }
}
