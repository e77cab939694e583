//! The humans replayed in a Rapier world, frame by frame: each bone a kinematic capsule, the
//! furniture and walls fixed. After posing the bones, the collision pipeline runs and the
//! narrow phase's deepest contacts are read.
//!
//! This is the engine-side view of penetration, used to cross-check the exact analytic depths of
//! `check` (engines agree with exact geometry on shallow overlaps; their depths saturate on deep
//! ones) and, with the `mujoco` feature, MuJoCo's.

use super::solids::{Owner, furniture_solids, wall_solids};
use crate::scene::Scene;
use glam::{Quat, Vec3};
use rapier3d::prelude::*;
use std::collections::HashMap;

pub use crate::physics::EngineContact;

/// Replays every human of `scene` in a Rapier world and returns the contacts deeper than
/// `tolerance`, frame by frame: the deepest per bone and owner (an object's parts are one owner,
/// as in `exact_contacts` and the MuJoCo replay).
pub fn rapier_replay(scene: &Scene, tolerance: f64) -> Vec<EngineContact> {
    let mut deepest: HashMap<(usize, usize, Owner, usize), f64> = HashMap::new();
    replay(scene, tolerance, |c, _| {
        let e = deepest.entry((c.human, c.bone, c.owner, c.frame)).or_insert(c.depth);
        *e = e.max(c.depth);
    });
    let mut out: Vec<EngineContact> = deepest
        .into_iter()
        .map(|((human, bone, owner, frame), depth)| EngineContact { human, bone, owner, frame, depth })
        .collect();
    sort_contacts(&mut out);
    out
}

/// For every object a human penetrates deeper than `tolerance` in the Rapier replay: a horizontal
/// push (m) as long as its deepest contact, in the direction of the depth-weighted sum of the
/// directions from each penetrating bone to the object's centre. (Contact normals flip as a walker
/// passes through an object and cancel out; the direction to the centre keeps the side the object
/// is on.) Walls are left out: they do not move.
pub fn rapier_pushes(scene: &Scene, tolerance: f64) -> Vec<(usize, glam::DVec2)> {
    let mut sums: HashMap<usize, (glam::DVec2, f64)> = HashMap::new();
    replay(scene, tolerance, |contact, bone_middle| {
        if let Owner::Object(i) = contact.owner {
            let c = scene.objects[i].center;
            let away = glam::DVec2::new(c[0] - bone_middle.x as f64, c[1] - bone_middle.y as f64);
            let e = sums.entry(i).or_insert((glam::DVec2::ZERO, 0.0));
            e.0 += away.normalize_or_zero() * contact.depth;
            e.1 = e.1.max(contact.depth);
        }
    });
    let mut out: Vec<(usize, glam::DVec2)> =
        sums.into_iter().map(|(i, (sum, deepest))| (i, sum.normalize_or_zero() * deepest)).collect();
    out.sort_by_key(|(i, _)| *i);
    out
}

/// The replay: calls `found(contact, bone_middle)` for every bone–solid contact deeper than
/// `tolerance`.
fn replay(scene: &Scene, tolerance: f64, mut found: impl FnMut(EngineContact, Vec3)) {
    let mut world = PhysicsWorld::default();
    let mut owners: HashMap<ColliderHandle, Owner> = HashMap::new();
    for solid in furniture_solids(scene).into_iter().chain(wall_solids(scene)) {
        let h = solid.shape.half_extents;
        let (_, c) = world.insert(RigidBodyBuilder::fixed().pose(solid.pose), ColliderBuilder::cuboid(h.x, h.y, h.z));
        owners.insert(c, solid.owner);
    }
    // One kinematic body per bone, its capsule along the body's z axis.
    let mut bones: HashMap<ColliderHandle, (usize, usize)> = HashMap::new();
    let mut bodies: Vec<Vec<RigidBodyHandle>> = Vec::new();
    for (hi, human) in scene.humans.iter().enumerate() {
        let mut handles = Vec::new();
        for (bi, bone) in human.skeleton.bones.iter().enumerate() {
            let half = (human.joint_at(0, bone.a).distance(human.joint_at(0, bone.b)) * 0.5) as f32;
            let collider = ColliderBuilder::capsule_z(half.max(1e-4), bone.radius as f32)
                .active_collision_types(ActiveCollisionTypes::all());
            let (b, c) = world.insert(RigidBodyBuilder::kinematic_position_based(), collider);
            bones.insert(c, (hi, bi));
            handles.push(b);
        }
        bodies.push(handles);
    }
    let frames = scene.humans.iter().map(|h| h.frames.len()).max().unwrap_or(0);
    for f in 0..frames {
        for (hi, human) in scene.humans.iter().enumerate() {
            let frame = f.min(human.frames.len() - 1);
            for (bi, bone) in human.skeleton.bones.iter().enumerate() {
                let (a, b) = (human.joint_at(frame, bone.a).as_vec3(), human.joint_at(frame, bone.b).as_vec3());
                let dir = (b - a).normalize_or(Vec3::Z);
                let pose = Pose::from_parts((a + b) * 0.5, Quat::from_rotation_arc(Vec3::Z, dir));
                world.bodies[bodies[hi][bi]].set_position(pose, true);
            }
        }
        world.detect_collisions(&(), &());
        for pair in world.contact_pairs() {
            let (bone, owner) = match (
                bones.get(&pair.collider1),
                owners.get(&pair.collider2),
                bones.get(&pair.collider2),
                owners.get(&pair.collider1),
            ) {
                (Some(b), Some(o), _, _) | (_, _, Some(b), Some(o)) => (*b, *o),
                _ => continue,
            };
            if let Some((_, contact)) = pair.find_deepest_contact() {
                let depth = -contact.dist as f64;
                let human = &scene.humans[bone.0];
                if depth > tolerance && f < human.frames.len() {
                    let middle = world.bodies[bodies[bone.0][bone.1]].translation();
                    found(EngineContact { human: bone.0, bone: bone.1, owner, frame: f, depth }, middle);
                }
            }
        }
    }
}

/// The same contacts computed exactly (parry's capsule–box contact on every bone, solid and frame):
/// the reference the engines are compared with.
pub fn exact_contacts(scene: &Scene, tolerance: f64) -> Vec<EngineContact> {
    let solids: Vec<_> = furniture_solids(scene).into_iter().chain(wall_solids(scene)).collect();
    let mut out = Vec::new();
    for (hi, human) in scene.humans.iter().enumerate() {
        for f in 0..human.frames.len() {
            for (bi, bone) in human.skeleton.bones.iter().enumerate() {
                let (a, b) = (human.joint_at(f, bone.a), human.joint_at(f, bone.b));
                // Deepest solid per owner, like the engine's deepest contact per collider pair.
                let mut best: HashMap<Owner, f64> = HashMap::new();
                for s in &solids {
                    if let Some(d) = super::capsule_depth_beyond(a, b, bone.radius, s, tolerance) {
                        let e = best.entry(s.owner).or_insert(0.0);
                        *e = e.max(d);
                    }
                }
                out.extend(best.into_iter().map(|(owner, depth)| EngineContact {
                    human: hi,
                    bone: bi,
                    owner,
                    frame: f,
                    depth,
                }));
            }
        }
    }
    sort_contacts(&mut out);
    out
}

/// Frame, human, bone, then owner order.
pub(crate) fn sort_contacts(contacts: &mut [EngineContact]) {
    contacts.sort_by_key(|c| (c.frame, c.human, c.bone, c.owner));
}
