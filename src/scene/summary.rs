//! A scene's vital statistics as data (what `shade-sim inspect` prints).

use super::{Action, Category, RoomType, Scene};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Summary of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneSummary {
    /// Room type.
    pub room_type: RoomType,
    /// Floor plan figures.
    pub floor: FloorSummary,
    /// Number of objects.
    pub objects: usize,
    /// Objects per category (categories with none are left out), sorted by name.
    pub objects_by_category: BTreeMap<Category, usize>,
    /// Each human.
    pub humans: Vec<HumanSummary>,
    /// Frames per action over all humans.
    pub action_frames: BTreeMap<Action, usize>,
    /// Axis-aligned bounds of everything (floor, objects, joints): min and max corner.
    pub extents: [[f64; 3]; 2],
}

/// Floor plan figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorSummary {
    /// Vertices of the polygon.
    pub vertices: usize,
    /// Area in m².
    pub area: f64,
    /// Width and depth of the bounding box in m.
    pub size: [f64; 2],
    /// Ceiling height in m.
    pub height: f64,
}

/// One human's figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HumanSummary {
    /// Id.
    pub id: String,
    /// Frames.
    pub frames: usize,
    /// Frames per second.
    pub fps: f64,
    /// Duration in seconds.
    pub seconds: f64,
    /// Action spans as (action, start, end).
    pub actions: Vec<(Action, usize, usize)>,
}

impl Scene {
    /// The scene's summary.
    pub fn summary(&self) -> SceneSummary {
        let polygon = self.floor_plan.polygon();
        let (min, max) = polygon.bounds();
        let mut lo = [min.x, min.y, 0.0];
        let mut hi = [max.x, max.y, self.floor_plan.height];
        let mut grow = |p: [f64; 3]| {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        };
        let mut objects_by_category = BTreeMap::new();
        for o in &self.objects {
            *objects_by_category.entry(o.category).or_insert(0) += 1;
            let b = o.obox();
            let (fmin, fmax) = b.footprint_aabb();
            let (z0, z1) = b.z_range();
            grow([fmin.x, fmin.y, z0]);
            grow([fmax.x, fmax.y, z1]);
        }
        let mut action_frames = BTreeMap::new();
        let mut humans = Vec::new();
        for h in &self.humans {
            for frame in &h.frames {
                frame.iter().for_each(|&p| grow(p));
            }
            for s in &h.actions {
                *action_frames.entry(s.action).or_insert(0) += s.end - s.start;
            }
            humans.push(HumanSummary {
                id: h.id.clone(),
                frames: h.frames.len(),
                fps: h.fps,
                seconds: h.frames.len() as f64 / h.fps,
                actions: h.actions.iter().map(|s| (s.action, s.start, s.end)).collect(),
            });
        }
        SceneSummary {
            room_type: self.room_type,
            floor: FloorSummary {
                vertices: polygon.points.len(),
                area: polygon.area(),
                size: (max - min).to_array(),
                height: self.floor_plan.height,
            },
            objects: self.objects.len(),
            objects_by_category,
            humans,
            action_frames,
            extents: [lo, hi],
        }
    }
}
