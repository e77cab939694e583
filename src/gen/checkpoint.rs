//! A model folder: `config.json` (model config, bounds, categories, how it was trained) and
//! `model.safetensors` (the EMA weights), plus, while training, `train_state.safetensors` and
//! `train_state.json` (raw weights, optimiser moments, step) that `--resume` continues from.
//!
//! Every file is written to a temporary name and renamed, so a stop never leaves half a checkpoint.

use super::{Bounds, CountPrior, Denoiser, GenError, ModelConfig, Params, SeenCounts, SeenFloors};
use crate::scene::Category;
use crate::scene::write_atomic;
use candle_core::{Device, Tensor};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};

/// Format tag of `config.json`.
pub const MODEL_FORMAT: &str = "shade-model/1";

/// How a checkpoint was trained.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrainingInfo {
    /// The command line that trained it.
    pub command: String,
    /// The dataset's `command` from its stats.json.
    pub dataset_command: String,
    /// The dataset's seed.
    pub dataset_seed: u64,
    /// FNV-1a hash of the dataset's stats.json (hex).
    pub data_hash: String,
    /// Scenes in the training split.
    pub train_scenes: usize,
    /// Optimiser steps done.
    pub steps: u64,
    /// Steps the run was asked for.
    pub target_steps: u64,
    /// Scenes per batch.
    pub batch: usize,
    /// Peak learning rate.
    pub lr: f64,
    /// The learning rate at the last step as a fraction of the peak (`train --lr-final`; 0.1 in
    /// files written before it was a setting, the only end the schedule then had).
    #[serde(default = "default_lr_final")]
    pub lr_final: f64,
    /// EMA decay of the shipped weights.
    pub ema_decay: f64,
    /// Seed of initialisation, batches and noise.
    pub seed: u64,
    /// `--category-balance`: rare categories' loss weight exponent (0 when absent: files written
    /// before it existed were trained without).
    #[serde(default)]
    pub category_balance: f64,
    /// Training wall time so far (s).
    pub wall_seconds: f64,
    /// Last validation loss of the EMA weights.
    pub val_loss: Option<f64>,
    /// The model the run started from (`train --init`), when it did not start from random
    /// weights; absent in files written before fine-tuning existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub init: Option<InitialWeights>,
}

fn default_lr_final() -> f64 {
    0.1
}

/// The model folder a fine-tuning run started from, and the hash of the weights it took.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialWeights {
    /// The folder, as given.
    pub model: String,
    /// FNV-1a hash of its `model.safetensors` (hex).
    pub weights_hash: String,
}

/// `config.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckpointMeta {
    /// Always [`MODEL_FORMAT`].
    pub format: String,
    /// The model's shape.
    pub model: ModelConfig,
    /// Token scaling bounds.
    pub bounds: Bounds,
    /// Class order of the one-hot (the room type's categories; "empty" follows).
    pub categories: Vec<Category>,
    /// How it was trained.
    pub training: TrainingInfo,
    /// FNV-1a hash of `model.safetensors` (hex), checked on load; absent in folders written before
    /// it existed, which load unchecked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights_hash: Option<String>,
    /// With count conditioning: the training rooms' make-ups that sampling draws counts from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count_prior: Option<CountPrior>,
    /// The counts per category the training rooms have, which sampling keeps a layout's counts
    /// among; absent in folders written before it existed, which sample without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seen_counts: Option<SeenCounts>,
    /// The floor areas the training rooms have, against which `generate` names an input's floor
    /// the model never saw the like of; absent in folders written before it existed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seen_floors: Option<SeenFloors>,
    /// How the model samples by default, chosen on its val split after training; absent: DDPM's
    /// chain. `train` writes it when asked (`train --geometry-eta`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sampling: Option<SamplingDefaults>,
}

/// A model's default sampler settings (`config.json`'s `sampling`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SamplingDefaults {
    /// DDIM's η on the pieces' geometry (centre, size, yaw; 0 to 2), the classes keeping DDPM's
    /// chain ([`super::Generator::with_geometry_eta`]).
    pub geometry_eta: f64,
}

/// A loaded model: metadata and the denoiser with its EMA weights.
#[derive(Debug, Clone)]
pub struct Checkpoint {
    /// `config.json`.
    pub meta: CheckpointMeta,
    /// The denoiser.
    pub denoiser: Denoiser,
}

/// File names inside a model folder.
pub const CONFIG_FILE: &str = "config.json";
/// The shipped weights.
pub const WEIGHTS_FILE: &str = "model.safetensors";
/// Raw weights and optimiser moments.
pub const STATE_FILE: &str = "train_state.safetensors";
/// Step and progress of an interrupted run.
pub const STATE_META_FILE: &str = "train_state.json";

impl Checkpoint {
    /// Loads the model in `dir`.
    pub fn load(dir: &Path) -> Result<Checkpoint, GenError> {
        let meta = read_meta(dir)?;
        let weights = dir.join(WEIGHTS_FILE);
        let bytes = std::fs::read(&weights).map_err(|e| GenError::io(&weights, e))?;
        Self::from_parts(meta, &bytes, &weights)
    }

    /// A model from its `config.json` and weight bytes; `origin` names them in errors. The bytes
    /// must match the config's hash (when it has one), and every tensor must be f32 and finite.
    pub fn from_parts(meta: CheckpointMeta, weights: &[u8], origin: &Path) -> Result<Checkpoint, GenError> {
        let tensors = checked_tensors(&meta, weights, origin)?;
        Self::from_tensors(meta, tensors, origin)
    }

    /// The model of `meta` with the weights `tensors` (from [`checked_tensors`]), their shapes
    /// checked against its network; errors name `origin`.
    pub(crate) fn from_tensors(
        meta: CheckpointMeta,
        tensors: HashMap<String, Tensor>,
        origin: &Path,
    ) -> Result<Checkpoint, GenError> {
        let denoiser = Denoiser::new(&meta.model, &mut Params::loaded(tensors)).map_err(|e| at(e, origin))?;
        Ok(Checkpoint { meta, denoiser })
    }
}

/// The tensors of a weights file's bytes, checked against `meta`'s `weights_hash` and found f32 and
/// finite (not yet against the network's shapes: [`Checkpoint::from_tensors`]).
pub(crate) fn checked_tensors(
    meta: &CheckpointMeta,
    weights: &[u8],
    origin: &Path,
) -> Result<HashMap<String, Tensor>, GenError> {
    if let Some(expected) = &meta.weights_hash
        && fnv1a_hex(weights) != *expected
    {
        return Err(GenError::checkpoint(
            origin,
            format!("does not match the weights_hash {expected} in config.json (corrupt or replaced)"),
        ));
    }
    let tensors = read_tensors(weights, origin)?;
    let mut names: Vec<&String> = tensors.keys().collect();
    names.sort();
    for name in names {
        let t = &tensors[name];
        if t.dtype() != candle_core::DType::F32 {
            return Err(GenError::checkpoint(origin, format!("tensor {name} is {:?}, not f32", t.dtype())));
        }
        let values = t.flatten_all().and_then(|v| v.to_vec1::<f32>()).map_err(|e| at(e.into(), origin))?;
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(GenError::checkpoint(origin, format!("tensor {name} has a non-finite value at {k}")));
        }
    }
    Ok(tensors)
}

/// The checked `config.json` of the model folder `dir`, without its weights.
pub fn read_meta(dir: &Path) -> Result<CheckpointMeta, GenError> {
    let config = dir.join(CONFIG_FILE);
    let text = std::fs::read_to_string(&config).map_err(|e| GenError::io(&config, e))?;
    parse_meta(&text, &config)
}

/// Parses and checks `config.json` text.
pub fn parse_meta(text: &str, origin: &Path) -> Result<CheckpointMeta, GenError> {
    let meta: CheckpointMeta =
        serde_json::from_str(text).map_err(|e| GenError::checkpoint(origin, format!("not a model config: {e}")))?;
    if meta.format != MODEL_FORMAT {
        return Err(GenError::checkpoint(origin, format!("format is {:?}, expected {MODEL_FORMAT:?}", meta.format)));
    }
    if let Some(problem) = meta.model.problem() {
        return Err(GenError::checkpoint(origin, format!("bad model config: {problem}")));
    }
    if meta.categories != meta.model.room_type.categories() {
        return Err(GenError::checkpoint(origin, "categories differ from the room type's".to_string()));
    }
    if !meta.bounds.is_valid() {
        return Err(GenError::checkpoint(origin, "bounds are not finite and ordered".to_string()));
    }
    if let Some(s) = &meta.sampling
        && !(0.0..=2.0).contains(&s.geometry_eta)
    {
        return Err(GenError::checkpoint(origin, format!("sampling.geometry_eta {} is not in [0, 2]", s.geometry_eta)));
    }
    if let Some(problem) = count_prior_problem(&meta) {
        return Err(GenError::checkpoint(origin, problem));
    }
    if let Some(problem) = meta.seen_counts.as_ref().and_then(|s| s.problem(&meta.model.rooms(), meta.categories.len()))
    {
        return Err(GenError::checkpoint(origin, problem));
    }
    if let Some(problem) = meta.seen_floors.as_ref().and_then(SeenFloors::problem) {
        return Err(GenError::checkpoint(origin, problem));
    }
    Ok(meta)
}

/// What is wrong with `meta`'s count prior: a count-conditioned model needs one with rows of its
/// width for every room type it serves, and no room of a type it does not serve.
fn count_prior_problem(meta: &CheckpointMeta) -> Option<String> {
    let model = &meta.model;
    let Some(prior) = &meta.count_prior else {
        return model.count_condition.then(|| "count conditioning needs a count_prior".to_string());
    };
    let width = model.count_width();
    if let Some(bad) = prior.rooms.iter().find(|r| r.3.len() != width || !model.serves(r.0) || !r.2.is_finite()) {
        return Some(format!(
            "count_prior room {bad:?} is not a {} room with a finite area and {width} counts",
            model.room_names()
        ));
    }
    let missing = model.rooms().into_iter().find(|&room| !prior.rooms.iter().any(|r| r.0 == room));
    missing.map(|room| format!("count_prior has no {room} room"))
}

/// Tensors of a safetensors file's bytes.
pub fn read_tensors(bytes: &[u8], origin: &Path) -> Result<HashMap<String, Tensor>, GenError> {
    candle_core::safetensors::load_buffer(bytes, &Device::Cpu)
        .map_err(|e| GenError::checkpoint(origin, format!("not a readable safetensors file: {e}")))
}

/// Writes `tensors` as safetensors to `path`, atomically; returns the FNV-1a hash of the bytes
/// written.
pub fn write_tensors(tensors: &BTreeMap<String, Tensor>, path: &Path) -> Result<String, GenError> {
    let bytes = safetensors::serialize(tensors.iter().map(|(k, v)| (k.as_str(), v)), None)
        .map_err(|e| GenError::checkpoint(path, format!("cannot serialise: {e}")))?;
    write_atomic(path, &bytes).map_err(|e| GenError::io(path, e))?;
    Ok(fnv1a_hex(&bytes))
}

/// Writes `value` as pretty JSON to `path`, atomically.
pub fn write_json<T: Serialize>(value: &T, path: &Path) -> Result<(), GenError> {
    let mut text = serde_json::to_string_pretty(value).expect("plain data serialises");
    text.push('\n');
    write_atomic(path, text.as_bytes()).map_err(|e| GenError::io(path, e))
}

/// Puts `path` on a checkpoint error that lacks one.
pub fn at(e: GenError, path: &Path) -> GenError {
    match e {
        GenError::Checkpoint { path: p, message } if p.as_os_str().is_empty() => {
            GenError::Checkpoint { path: PathBuf::from(path), message }
        }
        other => other,
    }
}

/// FNV-1a 64-bit hash of `bytes`, in hex.
pub fn fnv1a_hex(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
}
