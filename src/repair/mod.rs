//! Repair (ours): exact, small corrections of a layout after sampling — what the model's
//! few-centimetre imprecision leaves undone. Generation is `generator`'s job; judging the result is
//! `sim`'s; repair only changes objects (never people or the floor plan), and asks about bodies
//! in pieces through the [`Physics`] trait.
//!
//! A [`Pipeline`] runs [`RepairStep`]s in order, each in its own file, with the settings of one
//! [`RepairConfig`] (`config.rs`; `{}` in JSON is the default; every number the steps were tuned
//! with is a field there, with its default). The default order:
//!
//! | step | does | reads (`RepairConfig` sections) |
//! |---|---|---|
//! | `settle` | contact boxes given to pieces that afford them (a real piece added for a box none can hold), seats turned and fitted to their people, pieces squared and put back against walls, rounds of moves: under their people, off paths, apart, inside | `settle`, `holding`, `completion`, `walls`, `gap` |
//! | `relocate` | a piece holding nobody still in people's way moved to a free spot | `relocate`, `walls`, `gap` |
//! | `fit_into_room` | a piece poking out of the floor plan is moved back or narrowed; one taller than the room is cut to the ceiling | `fit_into_room`, `narrowing`, `holding`, `gap` |
//! | `fit_to_bodies` | a piece that bones still enter is moved, turned or reshaped a few centimetres at a time, everybody supported kept supported (a piece that holds people may become another category that affords what they do) | `fit_to_bodies`, `gap` |
//! | `left_out` | a piece holding nobody that people still pass through is left out | `left_out` |
//! | `overlaps` | overlaps that survive are narrowed away, or the smaller piece goes | `narrowing`, `gap` |
//!
//! What steps share lives beside them and is not a step: the people and who holds whom
//! (`occupancy`, `clearance`), which pieces a removal spares (`in_use`), new pieces and seat gaps (`completion`), the walls (`walls`) and the
//! geometry of moves, extents and separations (`helpers`). No step imports another step.

mod clearance;
mod completion;
mod config;
mod fit_into_room;
mod fit_to_bodies;
mod helpers;
mod in_use;
mod left_out;
mod occupancy;
mod overlaps;
mod pipeline;
mod relocate;
mod settle;
#[cfg(test)]
pub(crate) mod tests;
mod walls;

pub use clearance::Clearance;
pub use completion::SeatGaps;
pub use config::{
    CompletionConfig, FitIntoRoomConfig, FitToBodiesConfig, HoldingConfig, LeftOutConfig, NarrowingConfig,
    RelocateConfig, RepairConfig, RepairConfigError, SettleConfig, StepName, WallsConfig,
};
pub use occupancy::Occupancy;
pub use pipeline::{Pipeline, RepairReport, RepairStep, RepairTotals, SettleReport, StepReport, Workspace};

use crate::physics::Physics;
use crate::scene::Scene;

/// The step called `name`.
pub fn step(name: StepName) -> Box<dyn RepairStep> {
    match name {
        StepName::Settle => Box::new(settle::Settle),
        StepName::Relocate => Box::new(relocate::Relocate),
        StepName::FitIntoRoom => Box::new(fit_into_room::FitIntoRoom),
        StepName::FitToBodies => Box::new(fit_to_bodies::FitToBodies),
        StepName::LeftOut => Box::new(left_out::LeftOut),
        StepName::Overlaps => Box::new(overlaps::Overlaps),
    }
}

/// Repairs `scene`'s objects in place with the steps and settings of `config`.
pub fn repair_scene(scene: &mut Scene, config: &RepairConfig, physics: &dyn Physics) -> RepairReport {
    Pipeline::of(config).run(scene, config, physics)
}
