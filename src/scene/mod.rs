//! The scene format `shade-scene/1`: types, JSON input/output and validation.
//!
//! A scene is plain data: a room type, a floor plan, furniture as oriented boxes and humans as
//! self-describing skeletons with per-frame joint positions. Loading always validates; saving is
//! atomic. This module does not generate, simulate or render anything.

mod category;
mod error;
mod floor_plan;
mod frame;
mod human;
mod io;
mod limits;
mod object;
#[allow(clippy::module_inception)]
mod scene;
mod summary;
mod validate;

pub use category::{Action, Category, Group, RoomType};
pub use error::{Problem, ProblemKind, SceneError};
pub use floor_plan::FloorPlan;
pub use frame::RoomFrame;
pub use human::{ActionSpan, Bone, Human, JOINT_NAMES, Skeleton};
pub(crate) use io::failed_path;
pub use io::write_atomic;
pub use limits::SceneLimits;
pub use object::Object;
pub use scene::{FORMAT, Scene};
pub use summary::{FloorSummary, HumanSummary, SceneSummary};
pub use validate::{validate, validate_floor_plan};
