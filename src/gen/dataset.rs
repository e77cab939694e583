//! Training examples: a dataset split read from disk and encoded once (tokens, loss weights,
//! conditioning features), and batches assembled from it with optional dihedral augmentation.

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES};
use super::model::CondTensors;
use super::{Bounds, Dihedral, Features, GenError, ModelConfig, tokens};
use crate::data::DataError;
use crate::human::Conditions;
use crate::scene::Scene;
use candle_core::{Device, Tensor};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// One encoded scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Example {
    /// Object tokens (slots × token_dim).
    pub tokens: Vec<f32>,
    /// Loss weights, same shape.
    pub weights: Vec<f32>,
    /// Conditioning features.
    pub features: Features,
}

impl Example {
    /// Encodes `scene` for `cfg` with `bounds`.
    pub fn of(scene: &Scene, bounds: &Bounds, cfg: &ModelConfig) -> Example {
        let cond = Conditions::of(scene);
        let (tokens, weights) = tokens::encode(scene, cond.window.center, bounds, cfg);
        Example { tokens, weights, features: Features::of(&cond, bounds, cfg) }
    }

    /// This example under the symmetry `g`.
    pub fn transformed(&self, g: Dihedral, cfg: &ModelConfig) -> Example {
        let mut out = self.clone();
        g.apply_tokens(&mut out.tokens, cfg.token_dim());
        out.features.transform(g);
        out
    }
}

/// The scene files of a split folder, sorted by name.
pub fn split_files(dir: &Path, split: &str) -> Result<Vec<PathBuf>, GenError> {
    let folder = dir.join(split);
    let entries = std::fs::read_dir(&folder).map_err(|e| GenError::Data(DataError::io(&folder, e)))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// Reads and encodes every scene of `dir/split` (in file-name order), in parallel.
pub fn load_split(dir: &Path, split: &str, bounds: &Bounds, cfg: &ModelConfig) -> Result<Vec<Example>, GenError> {
    let files = split_files(dir, split)?;
    files
        .par_iter()
        .map(|f| {
            let scene = Scene::load(f).map_err(|e| GenError::Data(DataError::Scene(e)))?;
            if scene.room_type != cfg.room_type {
                return Err(GenError::Input {
                    path: f.clone(),
                    message: format!("room type {} but the model is for {}", scene.room_type, cfg.room_type),
                });
            }
            Ok(Example::of(&scene, bounds, cfg))
        })
        .collect()
}

/// A batch on the host, ready to become tensors.
#[derive(Debug, Clone, Default)]
pub struct HostBatch {
    /// Scenes in the batch.
    pub size: usize,
    /// Clean tokens, B × slots × token_dim.
    pub tokens: Vec<f32>,
    /// Loss weights, same shape.
    pub weights: Vec<f32>,
    contacts: Vec<f32>,
    contact_mask: Vec<f32>,
    floor: Vec<f32>,
    free: Vec<f32>,
}

impl HostBatch {
    /// Appends one example.
    pub fn push(&mut self, e: &Example) {
        self.tokens.extend_from_slice(&e.tokens);
        self.weights.extend_from_slice(&e.weights);
        self.push_features(&e.features);
    }

    /// Appends the conditioning of one scene (for sampling, where there are no tokens).
    pub fn push_features(&mut self, f: &Features) {
        self.size += 1;
        self.contacts.extend_from_slice(&f.contacts);
        self.contact_mask.extend_from_slice(&f.contact_mask);
        self.floor.extend_from_slice(&f.floor);
        self.free.extend_from_slice(&f.free);
    }

    /// The conditioning as tensors.
    pub fn cond(&self, cfg: &ModelConfig) -> Result<CondTensors, GenError> {
        let b = self.size;
        let dev = &Device::Cpu;
        Ok(CondTensors {
            contacts: Tensor::from_slice(&self.contacts, (b, cfg.max_contacts, CONTACT_FEATURES), dev)?,
            contact_mask: Tensor::from_slice(&self.contact_mask, (b, cfg.max_contacts), dev)?,
            floor: Tensor::from_slice(&self.floor, (b, cfg.floor_points, FLOOR_FEATURES), dev)?,
            free: Tensor::from_slice(&self.free, (b, cfg.free_points, FREE_FEATURES), dev)?,
        })
    }

    /// A tensor of shape (B, slots, token_dim) from host values laid out like the tokens.
    pub fn token_tensor(&self, values: &[f32], cfg: &ModelConfig) -> Result<Tensor, GenError> {
        Ok(Tensor::from_slice(values, (self.size, cfg.slots(), cfg.token_dim()), &Device::Cpu)?)
    }
}
