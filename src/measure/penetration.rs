//! E_pen: how deep a body sinks into furniture.
//!
//! For one frame, E_pen = Σ over body-surface sample points inside furniture of |signed distance|
//! to the furniture (the union of every object's template parts). A human's E_pen is the mean over
//! its frames, a scene's the sum over its humans. Metres; ≈ 1,000 surface points per body.

use crate::furniture::{Part, template};
use crate::human::SurfaceSampler;
use crate::scene::{Human, Object, Scene};
use glam::DVec3;

/// Surface points per body.
pub const SURFACE_POINTS: usize = 1000;

/// Furniture as template parts with a bounding sphere each, for fast distance queries.
#[derive(Debug, Clone)]
pub struct FurnitureField {
    parts: Vec<(Part, DVec3, f64)>,
}

impl FurnitureField {
    /// The parts of all `objects`.
    pub fn new(objects: &[Object]) -> FurnitureField {
        let parts = objects
            .iter()
            .flat_map(|o| template(o).parts)
            .map(|p| (p, p.obox.center, p.obox.half().length()))
            .collect();
        FurnitureField { parts }
    }

    /// Signed distance from `p` to the union of the parts (positive outside; `f64::INFINITY` with
    /// no parts).
    pub fn signed_distance(&self, p: DVec3) -> f64 {
        let mut best = f64::INFINITY;
        for (part, center, radius) in &self.parts {
            // A part whose bounding sphere is farther than the best so far cannot be nearer.
            if p.distance(*center) - radius >= best {
                continue;
            }
            best = best.min(part.obox.signed_distance(p));
        }
        best
    }

    /// Σ |sdf| over the points inside the furniture.
    pub fn penetration(&self, points: &[DVec3]) -> f64 {
        points.iter().map(|&p| self.signed_distance(p)).filter(|&d| d < 0.0).map(|d| -d).sum()
    }
}

/// E_pen of one human: the mean over its frames of the summed penetration depth of its surface points.
pub fn human_penetration(human: &Human, field: &FurnitureField) -> f64 {
    if human.frames.is_empty() {
        return 0.0;
    }
    let reference: Vec<DVec3> = human.frame(0).collect();
    let sampler = SurfaceSampler::new(&human.skeleton, &reference, SURFACE_POINTS);
    let total: f64 = (0..human.frames.len())
        .map(|f| {
            let joints: Vec<DVec3> = human.frame(f).collect();
            field.penetration(&sampler.points(&human.skeleton, &joints))
        })
        .sum();
    total / human.frames.len() as f64
}

/// E_pen of a scene: the sum over its humans.
pub fn scene_penetration(scene: &Scene) -> f64 {
    let field = FurnitureField::new(&scene.objects);
    scene.humans.iter().map(|h| human_penetration(h, &field)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, Motion, sit};
    use crate::scene::{Action, Category};
    use glam::DVec2;

    fn chair() -> Object {
        Object {
            id: "o0".into(),
            category: Category::Stool,
            center: [0.0, 0.0, 0.225],
            size: [0.4, 0.4, 0.45],
            yaw: 0.0,
        }
    }

    #[test]
    fn union_distance_by_hand() {
        let field = FurnitureField::new(&[chair()]);
        // Above the seat: 10 cm over its top.
        assert!((field.signed_distance(DVec3::new(0.0, 0.0, 0.55)) - 0.1).abs() < 1e-9);
        // Inside the 5 cm seat slab, 1 cm below its top.
        assert!((field.signed_distance(DVec3::new(0.0, 0.0, 0.44)) + 0.01).abs() < 1e-9);
        // Under the seat, between the legs: free.
        assert!(field.signed_distance(DVec3::new(0.0, 0.0, 0.2)) > 0.1);
    }

    #[test]
    fn a_sitter_on_the_seat_barely_penetrates_and_a_sunk_one_does() {
        let body = Body::default();
        let field = FurnitureField::new(&[chair()]);
        let mut on = Motion::new(body, 30.0);
        on.hold(sit(&body, DVec2::new(0.0, -0.05), 0.45, 0.0), 1, Action::Sit);
        let on = human_penetration(&on.into_human("h0"), &field);
        let mut sunk = Motion::new(body, 30.0);
        sunk.hold(sit(&body, DVec2::new(0.0, -0.05), 0.35, 0.0), 1, Action::Sit);
        let sunk = human_penetration(&sunk.into_human("h1"), &field);
        assert!(on < 0.05, "resting on the seat: {on}");
        assert!(sunk > 20.0 * on.max(0.01), "sunk 10 cm: {sunk} vs {on}");
    }
}
