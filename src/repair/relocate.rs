//! Moving a piece that is still in people's way after `settle`'s rounds to a free spot nearby
//! (ours, the `relocate` repair step).
//!
//! `settle`'s rounds push a piece off the walkers only as far as the pieces around it let it go;
//! a wardrobe, a sofa or a coffee table the model stood across a walkway often ends up in it still,
//! or pushed out into the room. A piece that holds nobody and is in the bodies' way moves to the
//! nearest spot where it is in nobody's way, inside the floor plan and clear of every other
//! standing piece: a piece the data stands against a wall (`walls`) to a spot with its back to a
//! wall anywhere in the room, any other piece to one on a 10 cm grid around it, as it stands or
//! turned a quarter, at most 3 m away. Where no such spot exists it stays. This module does not
//! move pieces that hold people.

use super::clearance::Clearance;
use super::config::{RelocateConfig, RepairConfig, StepName};
use super::helpers::{fits_inside, is_solid};
use super::pipeline::{RepairStep, StepReport, Workspace};
use super::walls::{stands_against_wall, wall_spots};
use crate::geom::{OBox, Polygon, intersection_volume, wrap_angle};
use crate::scene::Scene;
use glam::DVec2;
use std::f64::consts::FRAC_PI_2;

/// Moves every standing piece that holds nobody (`holds[i]` false) and is in the bodies' way to
/// the nearest free spot. Returns how many it moved.
fn relocate_off_paths(scene: &mut Scene, clearance: &Clearance, holds: &[bool], config: &RepairConfig) -> usize {
    let polygon = scene.floor_plan.polygon();
    let mut moved = 0;
    for (i, &held) in holds.iter().enumerate() {
        let o = &scene.objects[i];
        let solid = is_solid(o);
        let b = o.obox();
        if held || o.category.is_hanging() || clearance.blocked(&b, solid).is_empty() {
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
            fits_inside(c, &polygon, config.gap)
                && clearance.blocked(c, solid).is_empty()
                && others.iter().all(|x| intersection_volume(c, x) <= 1e-9)
        };
        let here = b.center.truncate();
        let spots = if stands_against_wall(o.category) {
            wall_spots(b.size.x, b.size.y, here, &polygon, &config.walls)
        } else {
            grid_spots(&b, &polygon, &config.relocate)
        };
        let best = spots
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

/// Poses (yaw, centre) for a free-standing piece `b`: its centre moved by whole `cfg.grid_step`s at
/// most `cfg.max_move` and inside `polygon`, as it stands or turned a quarter.
fn grid_spots(b: &OBox, polygon: &Polygon, cfg: &RelocateConfig) -> Vec<(f64, DVec2)> {
    let here = b.center.truncate();
    let n = (cfg.max_move / cfg.grid_step).floor() as i32;
    let turned = wrap_angle(b.yaw + FRAC_PI_2);
    (-n..=n)
        .flat_map(|i| (-n..=n).map(move |j| here + DVec2::new(i as f64, j as f64) * cfg.grid_step))
        .filter(|c| c.distance(here) <= cfg.max_move && polygon.contains(*c))
        .flat_map(|c| [(b.yaw, c), (turned, c)])
        .collect()
}

/// The `relocate` step.
#[derive(Debug, Clone, Copy, Default)]
pub struct Relocate;

impl RepairStep for Relocate {
    fn name(&self) -> StepName {
        StepName::Relocate
    }

    fn run(&self, scene: &mut Scene, work: &mut Workspace<'_>, config: &RepairConfig) -> StepReport {
        let (people, holds) = work.holds(scene.objects.len());
        StepReport::Relocate { relocated: relocate_off_paths(scene, &people.clearance, holds, config) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::geom::facing;
    use crate::human::{Body, Motion};
    use crate::scene::Object;
    use crate::scene::{Category, RoomType};

    /// A `w` × `d` m room with someone walking its length along y = `d` / 2, 30 cm from its ends.
    fn walked_room(room: RoomType, w: f64, d: f64) -> Scene {
        let mut scene = generate_room(room, 3, 0, false).scene;
        scene.floor_plan.polygon = vec![[0.0, 0.0], [w, 0.0], [w, d], [0.0, d]];
        let path = crate::geom::Polyline::new(vec![DVec2::new(0.3, d * 0.5), DVec2::new(w - 0.3, d * 0.5)]).unwrap();
        let mut walk = Motion::new(Body::default(), 30.0);
        walk.walk(&path, 1.2);
        scene.humans = vec![walk.into_human("h0")];
        scene
    }

    fn piece(id: &str, category: Category, center: [f64; 3], size: [f64; 3]) -> Object {
        Object { id: id.into(), category, center, size, yaw: 0.0 }
    }

    fn clearance_of(scene: &Scene) -> Clearance {
        Clearance::of(scene, &scene.room_window())
    }

    #[test]
    fn a_wardrobe_across_a_walkway_goes_to_the_nearest_free_spot_against_a_wall() {
        let mut scene = walked_room(RoomType::Bedroom, 4.0, 3.0);
        let wardrobe = piece("o0", Category::Wardrobe, [2.0, 1.5, 1.0], [1.6, 0.6, 2.0]);
        // A cabinet against the south wall where the wardrobe would otherwise go first.
        let cabinet = piece("o1", Category::Cabinet, [2.0, 0.25, 0.4], [1.0, 0.4, 0.8]);
        scene.objects = vec![wardrobe.clone(), cabinet.clone()];
        let polygon = scene.floor_plan.polygon();
        let clearance = clearance_of(&scene);
        assert!(!clearance.blocked(&wardrobe.obox(), true).is_empty());
        // Holding someone: it stays.
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[true, false], &RepairConfig::default()), 0);
        assert_eq!(scene.objects[0], wardrobe);
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[false, false], &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        // Out of the way, inside, clear of the cabinet, its back 5 cm from a wall, facing the room.
        assert!(clearance.blocked(&o.obox(), true).is_empty(), "{o:?}");
        assert!(fits_inside(&o.obox(), &polygon, RepairConfig::default().gap), "{o:?}");
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

    #[test]
    fn a_coffee_table_in_a_walkway_steps_just_off_it_and_stays_where_nothing_is_free() {
        let mut scene = walked_room(RoomType::Living, 4.0, 3.0);
        let table = piece("o0", Category::CoffeeTable, [2.0, 1.4, 0.2], [1.0, 0.6, 0.4]);
        scene.objects = vec![table.clone()];
        let clearance = clearance_of(&scene);
        let solid = is_solid(&table);
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[false], &RepairConfig::default()), 1);
        let o = &scene.objects[0];
        // Straight off the walkway, to the side it leant to (south), by whole 10 cm steps: the
        // first spot clear of the walker, one step less is not.
        let dy = o.center[1] - table.center[1];
        assert!(
            dy < 0.0
                && (dy / RelocateConfig::default().grid_step - (dy / RelocateConfig::default().grid_step).round())
                    .abs()
                    < 1e-9,
            "{o:?}"
        );
        assert_eq!((o.center[0], o.center[2], o.yaw), (table.center[0], table.center[2], table.yaw));
        assert!(clearance.blocked(&o.obox(), solid).is_empty(), "{o:?}");
        let closer = OBox::new(
            o.obox().center + glam::DVec3::new(0.0, RelocateConfig::default().grid_step, 0.0),
            o.obox().size,
            0.0,
        );
        assert!(!clearance.blocked(&closer, solid).is_empty(), "{o:?}");
        // In a corridor the walker fills, nothing is free: it stays.
        let mut scene = walked_room(RoomType::Living, 4.0, 0.9);
        let table = Object { center: [2.0, 0.45, 0.2], size: [0.5, 0.5, 0.4], ..table };
        scene.objects = vec![table.clone()];
        let clearance = clearance_of(&scene);
        assert!(!clearance.blocked(&table.obox(), solid).is_empty());
        assert_eq!(relocate_off_paths(&mut scene, &clearance, &[false], &RepairConfig::default()), 0);
        assert_eq!(scene.objects[0], table);
    }
}
