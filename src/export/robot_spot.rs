//! Where a robot's base can stand in a scene: the floor point furthest from the walls, the
//! furniture and every place a person's body passes over (any joint at any frame), for placing a
//! robosuite robot in a generated room.
//!
//! It looks at footprints on the floor only (a robot under a hanging shelf counts as blocked),
//! and it does not plan a path or check a reach.

use crate::scene::Scene;
use glam::DVec2;
use std::collections::HashSet;

/// Most floor points tested: the grid spacing grows with the room beyond 5 cm.
const MAX_CANDIDATES: f64 = 10_000.0;
/// Distances within this share of the grid spacing count as equal (a long free strip has many
/// equally good points); the one nearest the middle of the floor plan's bounds wins.
const TIE: f64 = 0.5;

/// The floor point of `scene` furthest from its walls, its pieces' footprints and its people's
/// joints (less each joint's radius), if that distance is at least `clearance` (m); of points
/// about as far, the one nearest the middle of the plan's bounds (deterministic).
pub fn robot_spot(scene: &Scene, clearance: f64) -> Option<[f64; 2]> {
    let floor = scene.floor_plan.polygon();
    let spacing = (floor.area() / MAX_CANDIDATES).sqrt().max(0.05);
    // People as the grid cells their joints cover, each with the largest joint radius in it.
    let cell = |p: DVec2| ((p.x / spacing).floor() as i64, (p.y / spacing).floor() as i64);
    let mut covered: HashSet<(i64, i64)> = HashSet::new();
    let mut joint_radius = 0.0f64;
    for human in &scene.humans {
        for j in 0..human.skeleton.joints.len() {
            joint_radius = joint_radius.max(human.skeleton.joint_radius(j));
        }
        for frame in &human.frames {
            covered.extend(frame.iter().map(|p| cell(DVec2::new(p[0], p[1]))));
        }
    }
    let mut people: Vec<DVec2> =
        covered.into_iter().map(|(i, j)| DVec2::new((i as f64 + 0.5) * spacing, (j as f64 + 0.5) * spacing)).collect();
    people.sort_by(|a, b| (a.x, a.y).partial_cmp(&(b.x, b.y)).expect("finite"));
    // A joint anywhere in its cell: half the cell's diagonal more.
    let person_margin = joint_radius + spacing * std::f64::consts::FRAC_1_SQRT_2;
    let distance = |p: DVec2| {
        let walls = floor.distance_to_boundary(p);
        let pieces = scene.objects.iter().map(|o| o.obox().footprint_signed_distance(p).max(0.0));
        let bodies = people.iter().map(|q| q.distance(p) - person_margin);
        pieces.chain(bodies).fold(walls, f64::min)
    };
    let (min, max) = floor.bounds();
    let middle = (min + max) * 0.5;
    let mut best: Option<(f64, DVec2)> = None;
    for p in floor.sample_interior(spacing) {
        let d = distance(p);
        let better = best.is_none_or(|(b, q)| {
            d > b + TIE * spacing || (d >= b - TIE * spacing && p.distance(middle) < q.distance(middle))
        });
        if better {
            best = Some((d, p));
        }
    }
    best.filter(|&(d, _)| d >= clearance).map(|(_, p)| [p.x, p.y])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, Motion};
    use crate::scene::{Category, FloorPlan, Object, RoomType};

    fn room(width: f64, depth: f64) -> Scene {
        let plan = FloorPlan { height: 2.7, polygon: vec![[0.0, 0.0], [width, 0.0], [width, depth], [0.0, depth]] };
        Scene::new(RoomType::Bedroom, plan)
    }

    #[test]
    fn an_empty_room_gives_its_centre() {
        let spot = robot_spot(&room(4.0, 3.0), 0.3).unwrap();
        assert!((spot[0] - 2.0).abs() <= 0.05 && (spot[1] - 1.5).abs() <= 0.05, "{spot:?}");
        // 1.5 m is the most a 3 m deep room has.
        assert!(robot_spot(&room(4.0, 3.0), 1.6).is_none());
    }

    #[test]
    fn the_spot_keeps_away_from_pieces_and_from_where_people_walk() {
        // A 6 × 3 m room: a bed filling the left third, a walker along x = 4 m.
        let mut scene = room(6.0, 3.0);
        scene.objects.push(Object::standing("bed", Category::DoubleBed, [1.0, 1.5], [2.0, 3.0, 0.5]));
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        let path = crate::geom::Polyline::new(vec![DVec2::new(4.0, 0.4), DVec2::new(4.0, 2.6)]).unwrap();
        m.walk(&path, 1.0);
        scene.humans.push(m.into_human("walker"));
        let [x, y] = robot_spot(&scene, 0.3).unwrap();
        let p = DVec2::new(x, y);
        // Between the bed's edge (x = 2) and the walker's feet (about x = 3.8), or beyond the
        // walker (x from 4.2 to 6): the 1.8 m gap is the wider.
        assert!(x > 2.3 && x < 3.6, "{p}");
        assert!((y - 1.5).abs() < 0.6, "{p}");
        let frames = &scene.humans[0].frames;
        let nearest = frames.iter().flatten().map(|q| DVec2::new(q[0], q[1]).distance(p)).fold(f64::MAX, f64::min);
        assert!(nearest > 0.3, "{nearest}");
    }
}
