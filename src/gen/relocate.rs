//! Moving a wall piece that is still in people's way after polishing's rounds to a free spot along
//! the walls (ours, part of polishing).
//!
//! Polishing's rounds push a piece off the walkers only as far as the pieces around it let it go;
//! a wardrobe or a sofa the model stood across a walkway often ends up in it still, or pushed out
//! into the room. A piece the data stands against a wall (`walls`) that holds nobody and is in the
//! bodies' way is moved to the nearest spot, with its back to a wall, where it is in nobody's way,
//! inside the floor plan and clear of every other standing piece. Where no such spot exists it
//! stays. This module does not move pieces that hold people, nor free-standing ones.

use super::clearance::Clearance;
use super::inside::fits_inside;
use super::walls::{stands_against_wall, wall_spots};
use crate::furniture::{PartRole, template};
use crate::geom::{OBox, intersection_volume};
use crate::scene::{Object, Scene};

/// Moves every piece the data stands against a wall that holds nobody (`holds[i]` false) and is in
/// the bodies' way to the nearest free spot along the walls. Returns how many it moved.
pub(super) fn relocate_off_paths(scene: &mut Scene, clearance: &Clearance, holds: &[bool]) -> usize {
    let polygon = scene.floor_plan.polygon();
    let mut moved = 0;
    for (i, &held) in holds.iter().enumerate() {
        let o = &scene.objects[i];
        if held || !stands_against_wall(o.category) || o.category.is_hanging() {
            continue;
        }
        let solid = is_solid(o);
        let b = o.obox();
        if clearance.blocked(&b, solid).is_empty() {
            continue;
        }
        let others: Vec<OBox> = scene
            .objects
            .iter()
            .enumerate()
            .filter(|(j, x)| *j != i && !x.category.is_hanging())
            .map(|(_, x)| x.obox())
            .collect();
        let free = |c: &OBox| {
            fits_inside(c, &polygon)
                && clearance.blocked(c, solid).is_empty()
                && others.iter().all(|x| intersection_volume(c, x) <= 1e-9)
        };
        let here = b.center.truncate();
        let best = wall_spots(b.size.x, b.size.y, b.center.truncate(), &polygon)
            .into_iter()
            .map(|(yaw, centre)| OBox::new(centre.extend(b.center.z), b.size, yaw))
            .filter(free)
            .min_by(|x, y| x.center.truncate().distance(here).total_cmp(&y.center.truncate().distance(here)));
        if let Some(spot) = best {
            let o = &mut scene.objects[i];
            o.center = spot.center.to_array();
            o.yaw = spot.yaw;
            moved += 1;
        }
    }
    moved
}

/// Whether `o` stands solid to the floor (no legs to put feet between): sitters' and touchers'
/// shins and feet are in its way too.
pub(super) fn is_solid(o: &Object) -> bool {
    !template(o).parts.iter().any(|p| p.role == PartRole::Leg)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::geom::{RoomWindow, facing};
    use crate::human::{Body, Motion};
    use crate::scene::{Category, RoomType};
    use glam::DVec2;

    #[test]
    fn a_wardrobe_across_a_walkway_goes_to_the_nearest_free_spot_against_a_wall() {
        let mut scene = generate_room(RoomType::Bedroom, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]];
        // Someone walking the length of the room at y = 1.5.
        let path = crate::geom::Polyline::new(vec![DVec2::new(0.3, 1.5), DVec2::new(3.7, 1.5)]).unwrap();
        let mut walk = Motion::new(Body::default(), 30.0);
        walk.walk(&path, 1.2);
        scene.humans = vec![walk.into_human("h0")];
        let wardrobe = Object {
            id: "o0".into(),
            category: Category::Wardrobe,
            center: [2.0, 1.5, 1.0],
            size: [1.6, 0.6, 2.0],
            yaw: 0.0,
        };
        // A cabinet against the south wall where the wardrobe would otherwise go first.
        let cabinet = Object {
            id: "o1".into(),
            category: Category::Cabinet,
            center: [2.0, 0.25, 0.4],
            size: [1.0, 0.4, 0.8],
            yaw: 0.0,
        };
        scene.objects = vec![wardrobe.clone(), cabinet.clone()];
        let polygon = scene.floor_plan.polygon();
        let clearance = Clearance::of(&scene, &RoomWindow::for_room(RoomType::Bedroom, &polygon));
        assert!(!clearance.blocked(&wardrobe.obox(), true).is_empty());
        // Holding someone: it stays.
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[true, false]), 0);
        assert_eq!(scene.objects[0], wardrobe);
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[false, false]), 1);
        let o = &scene.objects[0];
        // Out of the way, inside, clear of the cabinet, its back 5 cm from a wall, facing the room.
        assert!(clearance.blocked(&o.obox(), true).is_empty(), "{o:?}");
        assert!(fits_inside(&o.obox(), &polygon), "{o:?}");
        assert!(intersection_volume(&o.obox(), &cabinet.obox()) <= 1e-9, "{o:?}");
        let back = o.obox().center.truncate() - facing(o.yaw) * (o.size[1] * 0.5 + 0.05);
        assert!(polygon.distance_to_boundary(back) < 1e-9, "{o:?}");
        assert!(polygon.contains(o.obox().center.truncate() + facing(o.yaw)), "faces the room: {o:?}");
        // The nearest such spot: the north wall straight behind it, facing south, 1.15 m away (the
        // south wall beside the cabinet is 1.73 m away, the west and east walls are in the way).
        assert!((o.center[0] - 2.0).abs() < 1e-9 && (o.center[1] - 2.65).abs() < 1e-9, "{o:?}");
        assert!((facing(o.yaw) - DVec2::new(0.0, -1.0)).length() < 1e-9, "{o:?}");
        assert_eq!(o.center[2], wardrobe.center[2]);
        // The cabinet, out of everybody's way, stays.
        assert_eq!(scene.objects[1], cabinet);
    }
}
