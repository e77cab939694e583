//! The SHADE generator: token encoding, the DiT denoiser, DDPM training and sampling, checkpoints.
//!
//! Data flow: a scene's humans and floor plan → [`Features`] (contact boxes, floor-plan and
//! free-space points) and its objects ↔ tokens ([`tokens`]); [`train`] fits a [`Denoiser`] on a
//! calibrated dataset and writes a model folder ([`Checkpoint`]); a [`Generator`] samples tokens for
//! new inputs ([`sample`], with a [`Guidance`] hook) and decodes them into scenes.
//! Guidance terms themselves, physics and metrics live elsewhere.

mod adamw;
pub mod affordance_projection;
pub mod against_walls;
pub mod anchors;
pub mod at_table;
pub mod beyond_walls;
pub mod bodies;
pub mod boxes_uncovered;
pub mod checkpoint;
mod config;
pub mod count_prior;
pub mod count_projection;
mod dataset;
pub mod engine;
mod error;
mod features;
mod flat;
pub mod fourier;
pub mod gaps;
mod generate;
mod grad;
pub mod guidance;
mod guidance_config;
pub mod inference;
mod matmul;
mod model;
pub mod noise_scaled;
mod params;
pub mod phys_guidance;
pub mod relations;
pub mod roles;
mod sampler;
mod schedule;
pub mod seen_counts;
pub mod seen_floors;
mod shipped;
pub mod tokens;
pub mod train;
pub mod walls;

pub use adamw::{AdamW, AdamWConfig};
pub use checkpoint::{Checkpoint, CheckpointMeta, InitialWeights, SamplingDefaults, TrainingInfo};
pub use config::{AnchoredYaw, ModelConfig, NoiseSchedule, Prediction};
pub use count_prior::CountPrior;
pub use dataset::{Example, HostBatch, NoisyBatch, RelationPair, load_split, split_files};
pub use engine::{Engine, Gradients};
pub use error::GenError;
pub use features::{COUNT_SCALE, Dihedral, Features};
pub use flat::ParamLayout;
pub use generate::{Generator, GuidanceFactory};
pub use grad::GradNet;
pub use guidance::{GuidanceConfig, SpatialGuidance};
pub use inference::{FastDenoiser, PreparedBatch};
pub use model::{CondTensors, Denoiser, time_features};
pub use params::Params;
pub use phys_guidance::{PhysicsGuidance, physics_displacements};
pub use sampler::{Chain, Denoisers, Guidance, Projection, empty_projection_steps, sample, sample_from};
pub use schedule::Schedule;
pub use seen_counts::{SeenCounts, SeenRoom};
pub use seen_floors::{Beyond, FloorMeasure, FloorSize, SeenFloor, SeenFloors, UnseenFloor};
pub use shipped::{shipped_expert, shipped_generator, shipped_model, shipped_rooms};
pub use tokens::Bounds;
pub use train::{TrainObserver, TrainOptions, TrainOutcome, TrainingRooms, data_bounds, train, training_rooms};
