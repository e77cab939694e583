//! shade-sim: furniture layouts for rooms in which given human motions can happen, proven physically.
//!
//! The crate reads and writes `shade-scene/1` files ([`scene`]), does exact box and polygon
//! geometry and 256² rasterisation ([`geom`]), builds human bodies, poses and motions and extracts
//! the conditioning a SHADE generator reads ([`human`]), and renders pictures ([`export`]).
//! The command-line tool `shade-sim` is a thin layer over this library.
#![warn(missing_docs)]

mod alloc_tuning;
pub mod data;
pub mod eval;
pub mod export;
pub mod furniture;
#[path = "gen/mod.rs"]
pub mod generator;
pub mod geom;
pub mod human;
pub mod measure;
pub mod motion;
pub mod physics;
pub mod pipeline;
pub mod repair;
pub mod scene;
pub mod sim;
pub use alloc_tuning::tune_allocator_for_tensors;
