//! The procedural human-populated room dataset (our stand-in for 3D-FRONT HUMAN) and SHADE's
//! calibration pipeline.
//!
//! Rooms follow 3D-FRONT's category figures and real furniture sizes, arranged by the rules real
//! interiors follow, populated with contact humans (MIME's affordance mapping) and walkers. The raw
//! dataset reproduces 3D-FRONT HUMAN's known defect (contact humans sunk into or floating beside
//! their furniture); calibration fixes it. Everything is deterministic for a seed.

mod calibrate;
mod calibrate_dataset;
mod error;
mod floor_gen;
mod import;
pub mod layout;
mod people;
mod rng;
mod rooms;
mod stats;
mod synth;
mod threedfront;

pub use calibrate::{
    HumanCalibration, MAX_POINT_DEPTH, MAX_TRANSLATION, SAFE_PENETRATION, SceneCalibration, calibrate_scene,
    contact_object, iou_target,
};
pub use calibrate_dataset::{CALIBRATION_DRAWS, CalibrationReport, Unfixable, calibrate_dataset, read_stats};
pub use error::DataError;
pub use floor_gen::{Shape, area_range, sample_floor};
pub use import::{floor_outline, import_dataset, import_room};
pub use people::{TOUCH_CHANCE, WALK_FPS, contact_pose, contact_probability, misplace, translate};
pub use rng::Rng;
pub use rooms::{
    CheckedRoom, RoomRecord, furnish, generate_checked_room, generate_room, generate_spaced_room, placed_against_wall,
    sample_categories, stands_against_wall,
};
pub use stats::{DATASET_FORMAT, DatasetStats, SplitStats};
pub use synth::{CLEAN_DRAWS, SynthConfig, split_of, synthesize, write_stats};
pub use threedfront::{kl_divergence, target_frequencies};
