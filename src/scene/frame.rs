//! The room's own frame: the turn about the vertical that lays a floor plan's walls along x and y.
//!
//! The generator is trained on floor plans whose walls run along the axes (the procedural rooms,
//! and 3D-FRONT's), with quarter turns and mirrors as augmentation. A user's plan — a scan, a
//! capture space such as PROX's — can stand at any angle. [`RoomFrame::of`] finds the turn that
//! squares the plan's walls (the length-weighted mean wall direction modulo a quarter turn), so
//! that a scene can be sampled in that frame ([`RoomFrame::to_frame`]) and its pieces turned back
//! ([`RoomFrame::to_world`]). A plan whose walls already run along the axes gets the identity, and
//! nothing is moved at all. This module only moves coordinates; it decides nothing about a layout.

use super::{FloorPlan, Object, Scene};
use crate::geom::{Polygon, wrap_angle};
use glam::DVec2;

/// Turns smaller than this (rad) are no turn: the plan is treated as square to the axes.
const SQUARE_TOLERANCE: f64 = 1e-9;

/// A turn `angle` about the vertical through `pivot`, from the room's frame to the world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoomFrame {
    /// Where the turn is about (the floor plan's bounding-box centre).
    pub pivot: DVec2,
    /// The world direction of the frame's x axis (rad, in (−π/4, π/4]); 0 for a plan square to the
    /// axes.
    pub angle: f64,
}

impl RoomFrame {
    /// The frame of a plan: its walls' mean direction modulo a quarter turn, each wall weighted by
    /// its length (so a short diagonal wall barely turns a room whose long walls are square).
    pub fn of(plan: &FloorPlan) -> RoomFrame {
        let points: Vec<DVec2> = plan.polygon.iter().map(|&p| DVec2::from(p)).collect();
        let (mut sin, mut cos) = (0.0, 0.0);
        for (k, &a) in points.iter().enumerate() {
            let d = points[(k + 1) % points.len()] - a;
            let (s, c) = (4.0 * d.y.atan2(d.x)).sin_cos();
            sin += d.length() * s;
            cos += d.length() * c;
        }
        let angle = if sin.abs() + cos.abs() > 0.0 { sin.atan2(cos) / 4.0 } else { 0.0 };
        let (lo, hi) = plan.polygon().bounds();
        let pivot = if points.is_empty() { DVec2::ZERO } else { (lo + hi) * 0.5 };
        if angle.abs() < SQUARE_TOLERANCE { RoomFrame { pivot, angle: 0.0 } } else { RoomFrame { pivot, angle } }
    }

    /// Whether the frame is the world's (nothing to turn).
    pub fn is_identity(&self) -> bool {
        self.angle == 0.0
    }

    /// `scene` in this frame: its floor plan, people and pieces turned by −angle about the pivot.
    pub fn to_frame(&self, scene: &Scene) -> Scene {
        self.turned(scene, -self.angle)
    }

    /// The sides of `plan`'s bounding box in this frame (m, along the frame's x then y): for a
    /// rectangle at any angle, its two sides.
    pub fn sides(&self, plan: &FloorPlan) -> [f64; 2] {
        let turned: Vec<DVec2> = plan.polygon.iter().map(|&p| self.turn_point(DVec2::from(p), -self.angle)).collect();
        let (lo, hi) = Polygon::new(turned).bounds();
        (hi - lo).to_array()
    }

    /// A piece in this frame as it stands in the world.
    pub fn to_world(&self, object: &Object) -> Object {
        self.turn_object(object, self.angle)
    }

    fn turned(&self, scene: &Scene, angle: f64) -> Scene {
        if self.is_identity() {
            return scene.clone();
        }
        let mut out = scene.clone();
        for p in &mut out.floor_plan.polygon {
            *p = self.turn_point(DVec2::from(*p), angle).to_array();
        }
        for frame in out.humans.iter_mut().flat_map(|h| h.frames.iter_mut()) {
            for j in frame.iter_mut() {
                let xy = self.turn_point(DVec2::new(j[0], j[1]), angle);
                *j = [xy.x, xy.y, j[2]];
            }
        }
        out.objects = scene.objects.iter().map(|o| self.turn_object(o, angle)).collect();
        out
    }

    fn turn_object(&self, object: &Object, angle: f64) -> Object {
        if self.is_identity() {
            return object.clone();
        }
        let xy = self.turn_point(DVec2::new(object.center[0], object.center[1]), angle);
        Object { center: [xy.x, xy.y, object.center[2]], yaw: wrap_angle(object.yaw + angle), ..object.clone() }
    }

    fn turn_point(&self, p: DVec2, angle: f64) -> DVec2 {
        self.pivot + DVec2::from_angle(angle).rotate(p - self.pivot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn plan(points: &[[f64; 2]]) -> FloorPlan {
        FloorPlan { polygon: points.to_vec(), height: 2.6 }
    }

    fn l_shape() -> Vec<[f64; 2]> {
        vec![[0.0, 0.0], [5.0, 0.0], [5.0, 2.0], [3.0, 2.0], [3.0, 4.0], [0.0, 4.0]]
    }

    fn turned(points: &[[f64; 2]], angle: f64, shift: DVec2) -> Vec<[f64; 2]> {
        points.iter().map(|&p| (DVec2::from_angle(angle).rotate(DVec2::from(p)) + shift).to_array()).collect()
    }

    #[test]
    fn a_plans_sides_are_its_own_at_any_turn() {
        for deg in [0.0_f64, 30.0, -12.5, 90.0, 135.0] {
            let p = plan(&turned(&l_shape(), deg.to_radians(), DVec2::new(4.0, -2.0)));
            let [a, b] = RoomFrame::of(&p).sides(&p);
            let (short, long) = (a.min(b), a.max(b));
            assert!((short - 4.0).abs() < 1e-9 && (long - 5.0).abs() < 1e-9, "{deg}°: {a} × {b}");
        }
    }

    #[test]
    fn a_plan_square_to_the_axes_is_its_own_frame_at_any_quarter_turn() {
        for quarter in 0..4 {
            let points = turned(&l_shape(), quarter as f64 * PI / 2.0, DVec2::new(3.0, -7.0));
            assert!(RoomFrame::of(&plan(&points)).is_identity(), "quarter turn {quarter}");
        }
    }

    #[test]
    fn a_turned_plan_is_found_at_its_turn_modulo_a_quarter() {
        for deg in [30.0_f64, -30.0, 12.5, 44.0, 60.0, 100.0] {
            let frame = RoomFrame::of(&plan(&turned(&l_shape(), deg.to_radians(), DVec2::new(40.0, 25.0))));
            let expected = wrap_angle(4.0 * deg.to_radians()) / 4.0;
            assert!((frame.angle - expected).abs() < 1e-12, "{deg}°: {} against {expected}", frame.angle);
        }
    }

    #[test]
    fn long_walls_outweigh_a_short_diagonal() {
        // A 6 × 4 room with one corner cut by a 0.5 m diagonal.
        let points = [[0.0, 0.0], [6.0, 0.0], [6.0, 3.65], [5.65, 4.0], [0.0, 4.0]];
        let frame = RoomFrame::of(&plan(&points));
        // Each 45° wall adds cos 4φ = −1: 19.3 m square, 0.5 m against, so no turn.
        assert!(frame.is_identity(), "{}", frame.angle);
    }

    #[test]
    fn to_frame_squares_the_walls_and_to_world_turns_pieces_back() {
        let angle = 30f64.to_radians();
        let points = turned(&l_shape(), angle, DVec2::new(40.0, 25.0));
        let scene = Scene {
            format: crate::scene::FORMAT.to_string(),
            room_type: crate::scene::RoomType::Bedroom,
            floor_plan: plan(&points),
            objects: vec![Object {
                id: "o0".into(),
                category: crate::scene::Category::Wardrobe,
                center: [41.0, 27.0, 1.0],
                size: [1.2, 0.6, 2.0],
                yaw: 0.5,
            }],
            humans: Vec::new(),
        };
        let frame = RoomFrame::of(&scene.floor_plan);
        let framed = frame.to_frame(&scene);
        let ps: Vec<DVec2> = framed.floor_plan.polygon.iter().map(|&p| DVec2::from(p)).collect();
        for (k, &a) in ps.iter().enumerate() {
            let d = ps[(k + 1) % ps.len()] - a;
            assert!(d.x.abs() < 1e-9 || d.y.abs() < 1e-9, "wall {k} not square: {d}");
        }
        let piece = &framed.objects[0];
        assert!((piece.yaw - (0.5 - angle)).abs() < 1e-12);
        let back = frame.to_world(piece);
        for k in 0..3 {
            assert!((back.center[k] - scene.objects[0].center[k]).abs() < 1e-9);
        }
        assert!((back.yaw - 0.5).abs() < 1e-12);
        assert_eq!((back.size, back.category), (scene.objects[0].size, scene.objects[0].category));
    }
}
