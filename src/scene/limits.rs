//! The physical bounds a valid scene keeps: how large a room, a piece, a motion may be.
//!
//! Finite is not enough: an object 10²⁰ m wide or a joint at 10³⁰⁸ m is a finite number that no
//! collision library or rasteriser handles, and a floor plan of a million vertices is a file no
//! command should spend minutes on. These bounds are generous for any real room and motion (the
//! largest 3D-FRONT room is under 20 m across, the largest piece under 4 m) and are checked by
//! [`super::validate`], so every command rejects the same files with the same line. This module
//! only states the numbers; docs/FORMAT.md ("Validation") repeats them.

/// The bounds of `shade-scene/1`. The format has one set, [`SceneLimits::FORMAT`]; the type keeps
/// them together and documented.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneLimits {
    /// Largest absolute value of a floor-plan coordinate (m): rooms sit near the origin.
    pub max_coordinate: f64,
    /// Longest side of the floor plan's bounding box (m).
    pub max_room_side: f64,
    /// Most floor-plan vertices.
    pub max_vertices: usize,
    /// Highest ceiling (m).
    pub max_height: f64,
    /// Largest object extent on any axis (m).
    pub max_object_size: f64,
    /// How far outside the floor plan's bounding box (m), and below the floor or above the
    /// ceiling, an object's centre may lie: generated pieces can stand partly outside the walls.
    pub object_margin: f64,
    /// Largest absolute yaw (rad) of an object: sixteen turns.
    pub max_yaw: f64,
    /// Most humans in a scene.
    pub max_humans: usize,
    /// Most joints in a skeleton.
    pub max_joints: usize,
    /// Most bones in a skeleton.
    pub max_bones: usize,
    /// Thickest bone radius (m).
    pub max_bone_radius: f64,
    /// Highest frame rate (frames per second).
    pub max_fps: f64,
    /// Most frames of all humans together.
    pub max_total_frames: usize,
    /// How far outside the floor plan's bounding box (m), below the floor or above the ceiling a
    /// joint may be.
    pub joint_margin: f64,
}

impl SceneLimits {
    /// The bounds every `shade-scene/1` file keeps.
    pub const FORMAT: SceneLimits = SceneLimits {
        max_coordinate: 1_000.0,
        max_room_side: 50.0,
        max_vertices: 256,
        max_height: 10.0,
        max_object_size: 10.0,
        object_margin: 5.0,
        max_yaw: 100.0,
        max_humans: 32,
        max_joints: 128,
        max_bones: 256,
        max_bone_radius: 0.5,
        max_fps: 1_000.0,
        max_total_frames: 50_000,
        joint_margin: 2.0,
    };
}
