//! The scene's solid geometry for collision queries: furniture template parts and walls as parry
//! cuboids, human bones as capsules.
//!
//! Walls are 10 cm thick boxes standing outside each floor-plan edge, as tall as the room.

use crate::furniture::{template, wall_boxes};
use crate::geom::OBox;
use crate::scene::Scene;
use glam::{DVec3, Quat, Vec3};
use rapier3d::parry::math::Pose;
use rapier3d::parry::shape::Cuboid;

pub use crate::physics::Owner;

/// One box of the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Solid {
    /// What it belongs to.
    pub owner: Owner,
    /// The box in f64.
    pub obox: OBox,
    /// The same box for parry.
    pub shape: Cuboid,
    /// Its pose for parry.
    pub pose: Pose,
    /// World AABB (min, max).
    pub aabb: (DVec3, DVec3),
}

/// A parry pose of a yaw-only box.
pub fn pose_of(b: &OBox) -> Pose {
    Pose::from_parts(b.center.as_vec3(), Quat::from_rotation_z(b.yaw as f32))
}

impl Solid {
    /// A solid for `obox`.
    pub fn new(owner: Owner, obox: OBox) -> Solid {
        let (lo, hi) = obox.footprint_aabb();
        let (z0, z1) = obox.z_range();
        Solid {
            owner,
            obox,
            shape: Cuboid::new(Vec3::new(obox.size.x as f32 * 0.5, obox.size.y as f32 * 0.5, obox.size.z as f32 * 0.5)),
            pose: pose_of(&obox),
            aabb: (lo.extend(z0), hi.extend(z1)),
        }
    }

    /// Whether its AABB comes within `margin` of the box `lo`..`hi`.
    pub fn near(&self, lo: DVec3, hi: DVec3, margin: f64) -> bool {
        let (a, b) = self.aabb;
        a.x <= hi.x + margin
            && b.x >= lo.x - margin
            && a.y <= hi.y + margin
            && b.y >= lo.y - margin
            && a.z <= hi.z + margin
            && b.z >= lo.z - margin
    }
}

/// Every template part of every object.
pub fn furniture_solids(scene: &Scene) -> Vec<Solid> {
    scene
        .objects
        .iter()
        .enumerate()
        .flat_map(|(i, o)| template(o).parts.into_iter().map(move |p| Solid::new(Owner::Object(i), p.obox)))
        .collect()
}

/// One wall box per floor-plan edge, outside the floor.
pub fn wall_solids(scene: &Scene) -> Vec<Solid> {
    wall_boxes(scene).into_iter().map(|(i, b)| Solid::new(Owner::Wall(i), b)).collect()
}
