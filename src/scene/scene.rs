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
    /// ([`crate::geom::RoomWindow::around_focus`]). Where everyone together spans more than the
    /// window, the people in contact (sitting, lying, touching) come first: the pieces under them
    /// are the model's to place, and a walker's path is kept clear by guidance and repair as well.
    /// Last, the window moves as little as keeps the people in contact (their pelvis in every
    /// frame of a contact span) within the room type's [`RoomType::reach`] of its centre: in a
    /// plan longer than the training rooms the window would otherwise leave a person near an end
    /// wall where no piece's centre can go. In the training rooms it never moves
    /// (a test holds it).
    pub fn room_window(&self) -> crate::geom::RoomWindow {
        let side = self.room_type.window_side();
        let everyone = self.people_bounds();
        let spans_more = everyone.is_some_and(|(lo, hi)| (hi - lo).max_element() > side);
        let focus = if spans_more { self.contact_bounds().or(everyone) } else { everyone };
        crate::geom::RoomWindow::around_focus(side, &self.floor_plan.polygon(), focus)
            .reaching(self.contact_pelvis_bounds(), self.room_type.reach())
    }

    /// The horizontal bounding box of the pelvis in every frame of a contact span (`None` without
    /// one).
    pub fn contact_pelvis_bounds(&self) -> Option<(glam::DVec2, glam::DVec2)> {
        let pelvis = self.humans.iter().flat_map(|h| {
            let j = h.skeleton.joint("pelvis");
            h.contact_frames().filter_map(move |f| f.get(j?))
        });
        bounds(pelvis)
    }

    /// The horizontal bounding box of every joint of every person in every frame (`None` without
    /// people).
    pub fn people_bounds(&self) -> Option<(glam::DVec2, glam::DVec2)> {
        bounds(self.humans.iter().flat_map(|h| h.frames.iter().flatten()))
    }

    /// The horizontal bounding box of every joint in every frame of a contact span (sit, lie,
    /// touch; `None` without one).
    pub fn contact_bounds(&self) -> Option<(glam::DVec2, glam::DVec2)> {
        bounds(self.humans.iter().flat_map(|h| h.contact_frames().flatten()))
    }

    /// An empty scene of `room_type` over `floor_plan`.
    pub fn new(room_type: RoomType, floor_plan: FloorPlan) -> Scene {
        Scene { format: FORMAT.to_string(), room_type, floor_plan, objects: Vec::new(), humans: Vec::new() }
    }
}

/// The horizontal bounding box of `joints` (`None` for none).
fn bounds<'a>(joints: impl Iterator<Item = &'a [f64; 3]>) -> Option<(glam::DVec2, glam::DVec2)> {
    let mut points = joints.map(|j| glam::DVec2::new(j[0], j[1]));
    let first = points.next()?;
    Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
}
