//! Physical validation of scenes: human penetration and support, furniture overlaps, walls, the
//! floor plan, and furniture stability in a Rapier world.
//!
//! Checks return typed [`Violation`]s; formatting is the CLI's job. Geometry comes from the shared
//! furniture templates (`crate::furniture`).

mod check;
#[cfg(feature = "mujoco")]
mod mujoco;
mod physics;
mod piece_fit;
mod replay;
mod solids;
mod stability;
mod violation;

pub use check::{
    CEILING, CheckConfig, CheckReport, FLOOR, capsule_depth, capsule_depth_beyond, check_scene, people_in_walls,
    people_off_the_floor,
};
#[cfg(feature = "mujoco")]
pub use mujoco::mujoco_replay;
pub use physics::SimPhysics;
pub use piece_fit::piece_fit;
pub use replay::{EngineContact, exact_contacts, rapier_pushes, rapier_replay};
pub use solids::{Owner, Solid, furniture_solids, pose_of, wall_solids};
pub use stability::{build_world, unstable_objects};
pub use violation::{Violation, ViolationKind};
