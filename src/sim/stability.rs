//! Stability: furniture simulated as dynamic bodies in Rapier for a few seconds under gravity, with
//! the floor, the walls and the humans (kinematic capsules in the pose that loads the furniture
//! most: the middle of their first contact span, or their first frame) present.
//!
//! Lamps hang from the ceiling and stay fixed. A piece that moves further than the limit or tilts
//! more than the limit is unstable.

use super::solids::{furniture_solids, pose_of, wall_solids};
use super::{CheckConfig, Violation, ViolationKind};
use crate::scene::Scene;
use glam::Vec3;
use rapier3d::prelude::*;

/// Density of furniture (kg/m³ of its template parts), like wood and upholstery.
const DENSITY: f32 = 300.0;

/// A Rapier world of the scene: floor, walls, furniture (dynamic unless hanging), humans
/// (kinematic, one capsule per bone). Returns the world and each object's body handle.
pub fn build_world(scene: &Scene) -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld { gravity: Vector::new(0.0, 0.0, -9.81), ..PhysicsWorld::default() };
    let (lo, hi) = scene.floor_plan.polygon().bounds();
    let mid = ((lo + hi) * 0.5).as_vec2();
    world.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(mid.x, mid.y, -0.5)),
        ColliderBuilder::cuboid(50.0, 50.0, 0.5).friction(0.7),
    );
    for w in wall_solids(scene) {
        let h = w.shape.half_extents;
        world.insert(RigidBodyBuilder::fixed().pose(w.pose), ColliderBuilder::cuboid(h.x, h.y, h.z));
    }
    let parts = furniture_solids(scene);
    let mut handles = Vec::new();
    for (i, o) in scene.objects.iter().enumerate() {
        let body_pose = pose_of(&o.obox());
        let shapes: Vec<(Pose, SharedShape)> = parts
            .iter()
            .filter(|p| p.owner == super::solids::Owner::Object(i))
            .map(|p| {
                let h = p.shape.half_extents;
                (body_pose.inv_mul(&p.pose), SharedShape::cuboid(h.x, h.y, h.z))
            })
            .collect();
        let builder = if o.category.is_hanging() { RigidBodyBuilder::fixed() } else { RigidBodyBuilder::dynamic() };
        let (handle, _) = world.insert(
            builder.pose(body_pose).can_sleep(false),
            ColliderBuilder::compound(shapes).density(DENSITY).friction(0.7),
        );
        handles.push(handle);
    }
    for human in &scene.humans {
        let f = human.contact_spans().next().map_or(0, |s| (s.start + s.end) / 2);
        for bone in &human.skeleton.bones {
            let (a, b) = (human.joint_at(f, bone.a).as_vec3(), human.joint_at(f, bone.b).as_vec3());
            world.insert(
                RigidBodyBuilder::kinematic_position_based(),
                ColliderBuilder::capsule_from_endpoints(a, b, bone.radius as f32)
                    .active_collision_types(ActiveCollisionTypes::all()),
            );
        }
    }
    (world, handles)
}

/// Pieces that move or tilt beyond the limits in `cfg.stability_seconds` of simulation.
pub fn unstable_objects(scene: &Scene, cfg: &CheckConfig) -> Vec<Violation> {
    let (mut world, handles) = build_world(scene);
    let start: Vec<(Vec3, Vec3)> =
        handles.iter().map(|&h| (world.bodies[h].translation(), *world.bodies[h].rotation() * Vec3::Z)).collect();
    let steps = (cfg.stability_seconds / world.integration_parameters.dt as f64).ceil() as usize;
    for _ in 0..steps {
        world.step();
    }
    let mut out = Vec::new();
    for (i, &h) in handles.iter().enumerate() {
        let body = &world.bodies[h];
        let moved = (body.translation() - start[i].0).length() as f64;
        let up = *body.rotation() * Vec3::Z;
        let tilt = (up.dot(start[i].1).clamp(-1.0, 1.0) as f64).acos().to_degrees();
        let finite = body.translation().is_finite();
        if !finite || moved > cfg.max_displacement || tilt > cfg.max_tilt_degrees {
            out.push(Violation {
                kind: ViolationKind::Unstable,
                human: None,
                bone: Some(if tilt > cfg.max_tilt_degrees { format!("tilt {tilt:.1}°") } else { "moved".into() }),
                object: Some(scene.objects[i].id.clone()),
                other: None,
                frame: None,
                frames: None,
                depth: if finite { moved } else { f64::INFINITY },
            });
        }
    }
    out
}
