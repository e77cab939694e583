//! The room's floor plan: a simple counter-clockwise polygon and the ceiling height.

use crate::geom::Polygon;
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Floor polygon (metres, counter-clockwise, simple) and ceiling height.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorPlan {
    /// Vertices of the floor polygon, counter-clockwise, without repeating the first one.
    pub polygon: Vec<[f64; 2]>,
    /// Ceiling height above the floor (z = 0), metres.
    pub height: f64,
}

impl FloorPlan {
    /// A `w` × `d` m rectangle with its corner at the origin, `height` m of ceiling.
    pub fn rectangle(w: f64, d: f64, height: f64) -> FloorPlan {
        FloorPlan { polygon: vec![[0.0, 0.0], [w, 0.0], [w, d], [0.0, d]], height }
    }

    /// The floor polygon as a geometry value.
    pub fn polygon(&self) -> Polygon {
        Polygon::new(self.polygon.iter().map(|&p| DVec2::from(p)).collect())
    }
}
