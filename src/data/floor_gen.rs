//! Procedural floor plans: rectangles, L shapes and U shapes with realistic areas.
//!
//! Areas: bedrooms 8–30 m² within 6 m × 6 m; living rooms 15–60 m² and dining rooms 10–40 m² within
//! 12 m × 12 m; ceilings 2.6–3.0 m. Polygons are counter-clockwise with the bounding box's lower-left
//! corner at the origin.

use super::Rng;
use crate::scene::{FloorPlan, RoomType};

/// Area range (m²) and largest side (m) of a room type.
pub fn area_range(room: RoomType) -> (f64, f64, f64) {
    match room {
        RoomType::Bedroom => (8.0, 30.0, 6.0),
        RoomType::Living => (15.0, 60.0, 12.0),
        RoomType::Dining => (10.0, 40.0, 12.0),
    }
}

/// The shape families.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// A rectangle.
    Rectangle,
    /// A rectangle with one corner cut out.
    L,
    /// A rectangle with a notch in the middle of one side.
    U,
}

/// Samples a floor plan: 60 % rectangles, 30 % L shapes, 10 % U shapes.
pub fn sample_floor(room: RoomType, rng: &mut Rng) -> FloorPlan {
    let (lo, hi, max_side) = area_range(room);
    let height = (rng.uniform(2.6, 3.0) * 100.0).round() / 100.0;
    let shape = [Shape::Rectangle, Shape::L, Shape::U][rng.weighted(&[0.6, 0.3, 0.1])];
    for _ in 0..100 {
        let area = rng.uniform(lo, hi);
        let aspect = rng.uniform(1.0, 1.6);
        // The bounding box is larger than the area for L and U shapes.
        let fill: f64 = match shape {
            Shape::Rectangle => 1.0,
            Shape::L | Shape::U => rng.uniform(0.7, 0.85),
        };
        let box_area = area / fill;
        let mut w = (box_area * aspect).sqrt();
        let mut d = box_area / w;
        if rng.chance(0.5) {
            std::mem::swap(&mut w, &mut d);
        }
        let (w, d) = (snap(w), snap(d));
        if w > max_side || d > max_side || w.min(d) < 2.4 {
            continue;
        }
        let polygon = match shape {
            Shape::Rectangle => vec![[0.0, 0.0], [w, 0.0], [w, d], [0.0, d]],
            Shape::L => {
                // Cut a corner of area (1 − fill) × box, keeping both arms at least 2 m wide.
                let cut = (1.0 - fill) * w * d;
                let cw = snap((cut * rng.uniform(0.6, 1.6)).sqrt().min(w - 2.0));
                let cd = snap((cut / cw.max(0.5)).min(d - 2.0));
                if cw < 0.8 || cd < 0.8 {
                    continue;
                }
                vec![[0.0, 0.0], [w, 0.0], [w, d - cd], [w - cw, d - cd], [w - cw, d], [0.0, d]]
            }
            Shape::U => {
                let cut = (1.0 - fill) * w * d;
                let cw = snap((cut * 1.5).sqrt().min(w - 4.0));
                let cd = snap((cut / cw.max(0.5)).min(d - 2.2));
                if cw < 0.8 || cd < 0.6 {
                    continue;
                }
                let x0 = snap((w - cw) * 0.5);
                vec![[0.0, 0.0], [w, 0.0], [w, d], [x0 + cw, d], [x0 + cw, d - cd], [x0, d - cd], [x0, d], [0.0, d]]
            }
        };
        let plan = FloorPlan { polygon, height };
        let a = plan.polygon().area();
        if a >= lo && a <= hi {
            return plan;
        }
    }
    // Fallback: a plain rectangle in the middle of the range.
    let side = snap(((lo + hi) * 0.5).sqrt());
    FloorPlan { polygon: vec![[0.0, 0.0], [side, 0.0], [side, side], [0.0, side]], height }
}

/// Rounds to 5 cm, as floor plans are drawn.
fn snap(x: f64) -> f64 {
    (x * 20.0).round() / 20.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Scene, validate};

    #[test]
    fn plans_are_valid_with_areas_in_range_and_all_shapes_occur() {
        for room in RoomType::ALL {
            let (lo, hi, max_side) = area_range(room);
            let mut rng = Rng::new(3);
            let mut vertex_counts = std::collections::BTreeSet::new();
            for _ in 0..300 {
                let plan = sample_floor(room, &mut rng);
                let p = plan.polygon();
                let a = p.area();
                assert!(a >= lo && a <= hi, "{room}: area {a}");
                let (min, max) = p.bounds();
                assert!((max - min).max_element() <= max_side + 1e-9);
                assert!((2.6..=3.0).contains(&plan.height));
                vertex_counts.insert(plan.polygon.len());
                assert!(validate(&Scene::new(room, plan)).is_empty());
            }
            assert_eq!(vertex_counts.into_iter().collect::<Vec<_>>(), vec![4, 6, 8], "{room}");
        }
    }
}
