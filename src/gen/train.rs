//! Training: L_simple (ε-prediction MSE, weighted so empty slots' attributes carry no loss) with
//! AdamW, linear warm-up then cosine decay, EMA weights, gradients from the chosen [`Engine`]
//! (the hand-written pass on all cores by default), validation loss of the EMA weights on a
//! fixed draw of the val split, a JSON-lines log, and checkpoints every few minutes, at the end
//! and when asked to stop.
//!
//! Step s draws its batch, augmentations, diffusion steps and noise from `Rng::for_item(seed, s)`,
//! and checkpoints are taken only right after a log line, so a resumed run continues exactly as an
//! uninterrupted one would. A run starts from random weights, or from a trained model's
//! ([`TrainOptions::init`], fine-tuning), whose network, token bounds and sampler it keeps.

use super::adamw::{AdamW, AdamWConfig};
use super::checkpoint::{
    CONFIG_FILE, Checkpoint, CheckpointMeta, InitialWeights, MODEL_FORMAT, STATE_FILE, STATE_META_FILE,
    SamplingDefaults, TrainingInfo, WEIGHTS_FILE, checked_tensors, fnv1a_hex, read_meta, read_tensors, write_json,
    write_tensors,
};
use super::dataset::{Example, HostBatch, NoisyBatch, balance_categories, load_split};
use super::engine::{Engine, Gradients};
use super::flat::ParamLayout;
use super::{Bounds, CountPrior, Denoiser, Dihedral, GenError, ModelConfig, Params, Schedule, SeenCounts, SeenFloors};
use crate::data::{DatasetStats, Rng, read_stats};
use candle_core::Tensor;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// What a training run does.
#[derive(Debug, Clone)]
pub struct TrainOptions {
    /// Calibrated dataset folder (with stats.json, train/ and val/).
    pub data: PathBuf,
    /// More datasets of the same room type whose every split (train, val, test) joins the
    /// training set, after `data`'s train split, each split in file-name order: more rooms to
    /// learn from while `data`'s val and test splits stay the ones every model is measured on.
    /// Their pieces are encoded within `data`'s bounds; their stats.json joins the data hash.
    pub extra_data: Vec<PathBuf>,
    /// Datasets of the other room types a model with a room token serves
    /// ([`ModelConfig::serves`]) whose train split alone joins the training set, after the extra
    /// data: their val and test splits stay out, to measure the model on them. Encoded within
    /// `data`'s bounds; their stats.json joins the data hash.
    pub joint_data: Vec<PathBuf>,
    /// Model folder to write.
    pub out: PathBuf,
    /// Model shape (its room type must be the dataset's).
    pub model: ModelConfig,
    /// Total optimiser steps.
    pub steps: u64,
    /// Scenes per batch.
    pub batch: usize,
    /// Peak learning rate.
    pub lr: f64,
    /// The learning rate at the last step, as a fraction of the peak: the cosine falls from `lr`
    /// to `lr * lr_final` (default 0.1).
    pub lr_final: f64,
    /// Linear warm-up steps.
    pub warmup: u64,
    /// EMA decay.
    pub ema_decay: f64,
    /// Seed of initialisation, batches and noise.
    pub seed: u64,
    /// Steps between log lines (and possible checkpoints).
    pub log_every: u64,
    /// Steps between validation losses.
    pub val_every: u64,
    /// Validation scenes used (from the start of the val split).
    pub val_scenes: usize,
    /// Wall time between checkpoints.
    pub checkpoint_every: Duration,
    /// Continue from the checkpoint in `out`.
    pub resume: bool,
    /// A model folder whose weights the run starts from instead of random ones (fine-tuning; None,
    /// the default, starts from random weights): its `config.json` must have the run's network
    /// ([`ModelConfig::same_network`]: only the loss weights and the steps trained may differ), the
    /// rooms are encoded in its token bounds, and the optimiser starts afresh. A resumed run takes
    /// it from the checkpoint it continues.
    pub init: Option<PathBuf>,
    /// The command line, recorded in config.json.
    pub command: String,
    /// Loss weight of rare categories' slots: (median share / share)^this (`balance_categories`);
    /// 0, the default, weighs every slot alike.
    pub category_balance: f64,
    /// Input perturbation γ ([`NoisyBatch::perturb_input`]; 0, the default, none): each training
    /// input gets √(1 − ᾱ_t) γ ξ more noise than its step says. Validation inputs get none.
    pub input_perturbation: f64,
    /// Weight of the relation loss ([`NoisyBatch::hold_relations`]; 0, the default, none): the error
    /// of each pair of pieces' relative place within [`relation_reach`](Self::relation_reach),
    /// counted this many times as much as each piece's own error. The fused engine's alone. The
    /// validation loss stays without it.
    pub relation_loss: f64,
    /// The pairs the relation loss holds: pieces whose clean centres lie within this many token
    /// units (the window's half side being 1; default 0.5: 1.4 m in a bedroom, 2.2 m in a dining
    /// room).
    pub relation_reach: f64,
    /// Share of training scenes with one piece displaced ([`NoisyBatch::displace_pieces`]; 0, the
    /// default, none). Validation scenes get none.
    pub displaced_pieces: f64,
    /// The sampler `generate` uses for the model by default, recorded in config.json's `sampling`
    /// (None, the default: the run's start's — a resumed run's own, an `init` model's — else DDPM's
    /// chain).
    pub sampling: Option<SamplingDefaults>,
    /// Where gradients come from.
    pub engine: Engine,
}

impl TrainOptions {
    /// Defaults for `model` on `data` → `out`.
    pub fn new(data: PathBuf, out: PathBuf, model: ModelConfig) -> TrainOptions {
        TrainOptions {
            data,
            extra_data: Vec::new(),
            joint_data: Vec::new(),
            out,
            model,
            steps: 12_000,
            batch: 32,
            lr: 3e-4,
            lr_final: 0.1,
            warmup: 500,
            ema_decay: 0.999,
            seed: 0,
            log_every: 50,
            val_every: 1_000,
            val_scenes: 256,
            checkpoint_every: Duration::from_secs(300),
            resume: false,
            init: None,
            command: String::new(),
            category_balance: 0.0,
            input_perturbation: 0.0,
            displaced_pieces: 0.0,
            relation_loss: 0.0,
            relation_reach: 0.5,
            sampling: None,
            engine: Engine::Fused,
        }
    }

    /// Learning rate at `step`: linear warm-up, then cosine down to `lr * lr_final`.
    pub fn lr_at(&self, step: u64) -> f64 {
        if step < self.warmup {
            return self.lr * (step + 1) as f64 / self.warmup as f64;
        }
        let span = self.steps.saturating_sub(self.warmup).max(1) as f64;
        let progress = ((step - self.warmup) as f64 / span).min(1.0);
        let cosine = 0.5 * (1.0 + (std::f64::consts::PI * progress).cos());
        self.lr * (self.lr_final + (1.0 - self.lr_final) * cosine)
    }
}

/// One line of `log.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogLine {
    /// Steps done.
    pub step: u64,
    /// Mean training loss over the steps since the last line.
    pub loss: f64,
    /// Validation loss of the EMA weights, on validation steps.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub val_loss: Option<f64>,
    /// Learning rate of the last step.
    pub lr: f64,
    /// Training wall time so far (s).
    pub seconds: f64,
}

/// `train_state.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct StateMeta {
    step: u64,
    adam_steps: u64,
    seconds: f64,
    val_loss: Option<f64>,
    data_hash: String,
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainOutcome {
    /// Steps done in total.
    pub step: u64,
    /// Whether it stopped early (asked to) rather than finishing.
    pub stopped: bool,
    /// Last validation loss.
    pub val_loss: Option<f64>,
    /// Total training wall time (s).
    pub seconds: f64,
}

/// Things a caller may want to show while training runs.
pub trait TrainObserver {
    /// The data is loaded and training starts at `step`.
    fn started(&mut self, _step: u64, _total: u64, _train_scenes: usize, _parameters: usize) {}
    /// A log line was written.
    fn logged(&mut self, _line: &LogLine) {}
    /// A checkpoint was written at `step`; `log` is every line logged so far (the CLI draws
    /// `loss.png` from it). An error stops training.
    fn checkpointed(&mut self, _step: u64, _log: &[LogLine]) -> Result<(), GenError> {
        Ok(())
    }
}

impl TrainObserver for () {}

/// The bounds a model trained on the dataset in `data` encodes its tokens in: its train split's
/// ([`Bounds::from_stats`]).
pub fn data_bounds(data: &Path) -> Result<Bounds, GenError> {
    bounds_of(&read_stats(data)?, data)
}

fn bounds_of(stats: &DatasetStats, data: &Path) -> Result<Bounds, GenError> {
    let train_split = stats
        .splits
        .get("train")
        .filter(|s| s.rooms > 0)
        .ok_or_else(|| GenError::Input { path: data.join("stats.json"), message: "the train split is empty".into() })?;
    Ok(Bounds::from_stats(train_split))
}

/// The training rooms `opts` names, encoded for its model (its data's train split, then every
/// split of each extra dataset, then each joint dataset's train split, each in file-name order),
/// with the bounds they are encoded in (from the data's train split), the data's stats and the
/// hash that identifies them (`stats.json`, with the extra and joint ones when there are any).
pub fn training_rooms(opts: &TrainOptions) -> Result<TrainingRooms, GenError> {
    training_rooms_in(opts, None)
}

/// [`training_rooms`], encoded in `bounds` when given (a fine-tuned model's, its start's) instead
/// of the data's.
fn training_rooms_in(opts: &TrainOptions, bounds: Option<&Bounds>) -> Result<TrainingRooms, GenError> {
    let cfg = &opts.model;
    let stats = read_stats(&opts.data)?;
    let stats_bytes =
        std::fs::read(opts.data.join("stats.json")).map_err(|e| GenError::io(opts.data.join("stats.json"), e))?;
    let data_hash = fnv1a_hex(&stats_bytes);
    if stats.room_type != cfg.room_type {
        return Err(GenError::Input {
            path: opts.data.clone(),
            message: format!("dataset is {} but the model is for {}", stats.room_type, cfg.room_type),
        });
    }
    let bounds = match bounds {
        Some(b) => b.clone(),
        None => bounds_of(&stats, &opts.data)?,
    };
    let mut train_set = load_split(&opts.data, "train", &bounds, cfg)?;
    let mut hashed = stats_bytes.clone();
    let more = opts.extra_data.iter().map(|d| (d, &["train", "val", "test"][..]));
    for (extra, splits) in more.chain(opts.joint_data.iter().map(|d| (d, &["train"][..]))) {
        let extra_stats = read_stats(extra)?;
        if !cfg.serves(extra_stats.room_type) {
            return Err(GenError::Input {
                path: extra.clone(),
                message: format!("dataset is {} but the model is for {}", extra_stats.room_type, cfg.room_names()),
            });
        }
        hashed.extend(std::fs::read(extra.join("stats.json")).map_err(|e| GenError::io(extra.join("stats.json"), e))?);
        for split in splits {
            train_set.extend(load_split(extra, split, &bounds, cfg)?);
        }
    }
    let more_data = !opts.extra_data.is_empty() || !opts.joint_data.is_empty();
    let data_hash = if more_data { fnv1a_hex(&hashed) } else { data_hash };
    Ok(TrainingRooms { examples: train_set, bounds, stats, data_hash })
}

/// What [`training_rooms`] loads.
#[derive(Debug, Clone)]
pub struct TrainingRooms {
    /// The encoded rooms, in training order.
    pub examples: Vec<Example>,
    /// The token bounds they are encoded in.
    pub bounds: Bounds,
    /// The data's `stats.json`.
    pub stats: DatasetStats,
    /// FNV-1a hash of the stats files.
    pub data_hash: String,
}

impl TrainingRooms {
    /// The counts per category these rooms have, as a model trained on them records them.
    pub fn seen_counts(&self) -> SeenCounts {
        SeenCounts::of(self.examples.iter().map(|e| (e.make_up.0, e.pieces.as_slice())))
    }

    /// The floor sizes these rooms have, as a model trained on them records them.
    pub fn seen_floors(&self) -> SeenFloors {
        SeenFloors::of(self.examples.iter().map(|e| (e.make_up.0, e.floor)))
    }
}

/// Trains (or resumes) a model as `opts` says, until done or `stop` is set.
pub fn train(
    opts: &TrainOptions,
    stop: &AtomicBool,
    observer: &mut dyn TrainObserver,
) -> Result<TrainOutcome, GenError> {
    let cfg = &opts.model;
    if let Some(problem) = cfg.problem() {
        return Err(GenError::checkpoint(&opts.out, format!("bad model config: {problem}")));
    }
    // Where the weights start: a resumed run's checkpoint says (its start's bounds, record and
    // sampler are kept); else the model `init` names (its bounds and sampler), or random weights.
    let resumed = opts.resume.then(|| read_meta(&opts.out)).transpose()?;
    let (start_bounds, started_from, start_sampling, start_tensors) = match (&resumed, &opts.init) {
        (Some(meta), _) => (
            meta.training.init.is_some().then(|| meta.bounds.clone()),
            meta.training.init.clone(),
            meta.sampling.clone(),
            None,
        ),
        (None, Some(dir)) => {
            let (meta, record, tensors) = initial_weights(dir, cfg)?;
            (Some(meta.bounds), Some(record), meta.sampling, Some(tensors))
        }
        (None, None) => (None, None, None, None),
    };
    let sampling = opts.sampling.clone().or(start_sampling);
    let rooms = training_rooms_in(opts, start_bounds.as_ref())?;
    let seen_counts = rooms.seen_counts();
    let seen_floors = rooms.seen_floors();
    let TrainingRooms { examples: mut train_set, bounds, stats, data_hash } = rooms;
    balance_categories(&mut train_set, opts.category_balance, cfg);
    let count_prior =
        cfg.count_condition.then(|| CountPrior { rooms: train_set.iter().map(|e| e.make_up.clone()).collect() });
    if train_set.is_empty() {
        return Err(GenError::Input { path: opts.data.join("train"), message: "no scenes".into() });
    }
    let mut val_set = load_split(&opts.data, "val", &bounds, cfg)?;
    val_set.truncate(opts.val_scenes);
    std::fs::create_dir_all(&opts.out).map_err(|e| GenError::io(&opts.out, e))?;

    let schedule = Schedule::of(cfg);
    let mut init = match start_tensors {
        Some(tensors) => Params::loaded(tensors),
        None => Params::random(opts.seed),
    };
    Denoiser::new(cfg, &mut init)?;
    let (layout, mut params) = ParamLayout::of(&init.snapshot()?)?;
    let mut engine = Gradients::new(opts.engine, cfg, &layout)?;
    let mut adam = AdamW::new(layout.len(), AdamWConfig::default());
    let mut ema = params.clone();
    let mut step = 0;
    let mut seconds = 0.0;
    let mut val_loss = None;
    let log_path = opts.out.join("log.jsonl");
    let mut log: Vec<LogLine> = Vec::new();
    if let Some(meta) = &resumed {
        let state = restore(opts, meta, &data_hash, &layout, &mut params, &mut adam, &mut ema)?;
        step = state.step;
        seconds = state.seconds;
        val_loss = state.val_loss;
        log = read_log(&log_path)?.into_iter().filter(|l| l.step <= step).collect();
    }
    let info = |step: u64, seconds: f64, val_loss: Option<f64>| TrainingInfo {
        command: opts.command.clone(),
        dataset_command: stats.command.clone(),
        dataset_seed: stats.seed,
        data_hash: data_hash.clone(),
        train_scenes: train_set.len(),
        steps: step,
        target_steps: opts.steps,
        batch: opts.batch,
        lr: opts.lr,
        lr_final: opts.lr_final,
        ema_decay: opts.ema_decay,
        seed: opts.seed,
        category_balance: opts.category_balance,
        wall_seconds: seconds,
        val_loss,
        init: started_from.clone(),
    };
    observer.started(step, opts.steps, train_set.len(), layout.len());

    let started = Instant::now();
    let base_seconds = seconds;
    let mut last_checkpoint = Instant::now();
    let (mut loss_sum, mut loss_n) = (0.0, 0u64);
    let mut stopped = false;
    while step < opts.steps {
        let mut rng = Rng::for_item(opts.seed, step);
        let host = draw_batch(&train_set, opts.batch, &mut rng, cfg, true);
        let mut batch = NoisyBatch::draw(host, &schedule, &mut rng, cfg);
        if opts.input_perturbation > 0.0 {
            batch.perturb_input(opts.input_perturbation, &schedule, &mut rng);
        }
        if opts.displaced_pieces > 0.0 {
            batch.displace_pieces(opts.displaced_pieces, &schedule, cfg, &mut rng);
        }
        if opts.relation_loss > 0.0 {
            batch.hold_relations(opts.relation_loss, opts.relation_reach, &schedule, cfg);
        }
        let lr = opts.lr_at(step);
        let (loss, grads) = engine.loss_and_grad(&params, &batch)?;
        loss_sum += loss;
        loss_n += 1;
        adam.step(&mut params, &grads, lr);
        let decay = opts.ema_decay.min((1.0 + step as f64) / (10.0 + step as f64));
        update_ema(&mut ema, &params, decay);
        step += 1;
        stopped = stop.load(Ordering::Relaxed);
        if step % opts.log_every == 0 || step == opts.steps || stopped {
            seconds = base_seconds + started.elapsed().as_secs_f64();
            let validate = step % opts.val_every == 0 || step == opts.steps;
            if validate && !val_set.is_empty() {
                val_loss = Some(validation_loss(&mut engine, cfg, &ema, &schedule, &val_set, opts.seed)?);
            }
            let line = LogLine {
                step,
                loss: loss_sum / loss_n.max(1) as f64,
                val_loss: if validate { val_loss } else { None },
                lr,
                seconds,
            };
            (loss_sum, loss_n) = (0.0, 0);
            log.push(line.clone());
            write_log(&log, &log_path)?;
            observer.logged(&line);
            if stopped || step == opts.steps || last_checkpoint.elapsed() >= opts.checkpoint_every {
                let meta = CheckpointMeta {
                    format: MODEL_FORMAT.into(),
                    model: cfg.clone(),
                    bounds: bounds.clone(),
                    categories: cfg.room_type.categories().to_vec(),
                    training: info(step, seconds, val_loss),
                    weights_hash: None,
                    count_prior: count_prior.clone(),
                    seen_counts: Some(seen_counts.clone()),
                    seen_floors: Some(seen_floors.clone()),
                    sampling: sampling.clone(),
                };
                let state = StateMeta { step, adam_steps: adam.steps, seconds, val_loss, data_hash: data_hash.clone() };
                save(&opts.out, &meta, &state, &layout, &params, &adam, &ema)?;
                last_checkpoint = Instant::now();
                observer.checkpointed(step, &log)?;
            }
            if stopped {
                break;
            }
        }
    }
    Ok(TrainOutcome { step, stopped, val_loss, seconds })
}

/// The `config.json`, record and weights of the model in `dir` that a run of `cfg` starts from:
/// its network must be `cfg`'s ([`ModelConfig::same_network`]: a checkpoint of another
/// architecture has other tensors).
fn initial_weights(
    dir: &Path,
    cfg: &ModelConfig,
) -> Result<(CheckpointMeta, InitialWeights, HashMap<String, Tensor>), GenError> {
    let meta = read_meta(dir)?;
    if !meta.model.same_network(cfg) {
        return Err(GenError::checkpoint(dir.join(CONFIG_FILE), "model config differs from the one asked for"));
    }
    let path = dir.join(WEIGHTS_FILE);
    let bytes = std::fs::read(&path).map_err(|e| GenError::io(&path, e))?;
    // Checked as `Checkpoint::load` checks a model (hash, f32, finite, shapes), from the one read.
    let tensors = checked_tensors(&meta, &bytes, &path)?;
    let meta = Checkpoint::from_tensors(meta, tensors.clone(), &path)?.meta;
    let record = InitialWeights { model: dir.display().to_string(), weights_hash: fnv1a_hex(&bytes) };
    Ok((meta, record, tensors))
}

/// A random batch (with a random symmetry per scene when `augment`).
fn draw_batch(set: &[Example], size: usize, rng: &mut Rng, cfg: &ModelConfig, augment: bool) -> HostBatch {
    let mut batch = HostBatch::default();
    for _ in 0..size {
        let e = &set[rng.index(set.len())];
        if augment {
            let g = Dihedral { quarter_turns: rng.index(4) as u8, mirror: rng.chance(0.5) };
            batch.push(&e.transformed(g, cfg), cfg);
        } else {
            batch.push(e, cfg);
        }
    }
    batch
}

/// Loss of the EMA weights on the validation scenes, with fixed steps and noise.
fn validation_loss(
    engine: &mut Gradients,
    cfg: &ModelConfig,
    ema: &[f32],
    schedule: &Schedule,
    val: &[Example],
    seed: u64,
) -> Result<f64, GenError> {
    let (mut sum, mut n) = (0.0, 0.0);
    for (k, chunk) in val.chunks(64).enumerate() {
        let mut host = HostBatch::default();
        chunk.iter().for_each(|e| host.push(e, cfg));
        let mut rng = Rng::for_item(seed ^ 0x5641_4c49_4441_5445, k as u64);
        let batch = NoisyBatch::draw(host, schedule, &mut rng, cfg);
        sum += engine.loss(ema, &batch)? * chunk.len() as f64;
        n += chunk.len() as f64;
    }
    Ok(sum / n)
}

fn update_ema(ema: &mut [f32], params: &[f32], decay: f64) {
    let (keep, take) = (decay as f32, (1.0 - decay) as f32);
    ema.iter_mut().zip(params).for_each(|(e, p)| *e = *e * keep + p * take);
}

fn save(
    dir: &Path,
    meta: &CheckpointMeta,
    state: &StateMeta,
    layout: &ParamLayout,
    params: &[f32],
    adam: &AdamW,
    ema: &[f32],
) -> Result<(), GenError> {
    let mut tensors = BTreeMap::new();
    for (prefix, values) in [("param", params), ("adam_m", &adam.m), ("adam_v", &adam.v), ("ema", ema)] {
        for (name, t) in layout.tensors(values)? {
            tensors.insert(format!("{prefix}.{name}"), t);
        }
    }
    let ema = layout.tensors(ema)?;
    // State first: a stop between the writes leaves a resumable folder whose weights lag by one
    // checkpoint at worst.
    write_tensors(&tensors, &dir.join(STATE_FILE))?;
    write_json(state, &dir.join(STATE_META_FILE))?;
    let weights_hash = write_tensors(&ema, &dir.join(WEIGHTS_FILE))?;
    write_json(&CheckpointMeta { weights_hash: Some(weights_hash), ..meta.clone() }, &dir.join(CONFIG_FILE))
}

fn restore(
    opts: &TrainOptions,
    meta: &CheckpointMeta,
    data_hash: &str,
    layout: &ParamLayout,
    params: &mut Vec<f32>,
    adam: &mut AdamW,
    ema: &mut Vec<f32>,
) -> Result<StateMeta, GenError> {
    let meta_path = opts.out.join(STATE_META_FILE);
    let text = std::fs::read_to_string(&meta_path).map_err(|e| GenError::io(&meta_path, e))?;
    let state: StateMeta = serde_json::from_str(&text)
        .map_err(|e| GenError::checkpoint(&meta_path, format!("not a training state: {e}")))?;
    if state.data_hash != data_hash {
        return Err(GenError::checkpoint(&meta_path, "was trained on a different dataset (stats.json differs)"));
    }
    let config_path = opts.out.join(CONFIG_FILE);
    if meta.model != opts.model {
        return Err(GenError::checkpoint(&config_path, "model config differs from the one asked for"));
    }
    if meta.training.category_balance != opts.category_balance {
        return Err(GenError::checkpoint(
            &config_path,
            format!(
                "was trained with --category-balance {}, not {}: resume with the same",
                meta.training.category_balance, opts.category_balance
            ),
        ));
    }
    let path = opts.out.join(STATE_FILE);
    let bytes = std::fs::read(&path).map_err(|e| GenError::io(&path, e))?;
    let mut tensors = read_tensors(&bytes, &path)?;
    let mut take = |prefix: &str| {
        layout.gather(|name, shape| {
            let key = format!("{prefix}.{name}");
            let t = tensors.remove(&key).ok_or_else(|| GenError::checkpoint(&path, format!("lacks tensor {key}")))?;
            if t.dims() != shape {
                return Err(GenError::checkpoint(&path, format!("{key} has shape {:?}, expected {shape:?}", t.dims())));
            }
            Ok(t.flatten_all()?.to_vec1::<f32>()?)
        })
    };
    *params = take("param")?;
    adam.m = take("adam_m")?;
    adam.v = take("adam_v")?;
    *ema = take("ema")?;
    adam.steps = state.adam_steps;
    Ok(state)
}

/// Reads `log.jsonl` (missing → empty).
pub fn read_log(path: &Path) -> Result<Vec<LogLine>, GenError> {
    let text = match std::fs::read_to_string(path) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(GenError::io(path, e)),
    };
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| serde_json::from_str(l).map_err(|e| GenError::checkpoint(path, format!("bad log line: {e}"))))
        .collect()
}

fn write_log(log: &[LogLine], path: &Path) -> Result<(), GenError> {
    let mut text = String::new();
    for l in log {
        text.push_str(&serde_json::to_string(l).expect("plain data serialises"));
        text.push('\n');
    }
    crate::scene::write_atomic(path, text.as_bytes()).map_err(|e| GenError::io(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RoomType;

    #[test]
    fn learning_rate_warms_up_then_decays_to_a_tenth() {
        let mut o = TrainOptions::new(PathBuf::new(), PathBuf::new(), ModelConfig::tiny(RoomType::Bedroom));
        (o.steps, o.warmup, o.lr) = (1100, 100, 1e-3);
        assert!((o.lr_at(0) - 1e-5).abs() < 1e-12);
        assert!((o.lr_at(99) - 1e-3).abs() < 1e-12);
        assert!((o.lr_at(100) - 1e-3).abs() < 1e-12);
        assert!((o.lr_at(600) - 0.55e-3).abs() < 1e-12);
        assert!((o.lr_at(1100) - 1e-4).abs() < 1e-12);
    }

    #[test]
    fn learning_rate_ends_at_the_chosen_fraction_of_the_peak() {
        let mut o = TrainOptions::new(PathBuf::new(), PathBuf::new(), ModelConfig::tiny(RoomType::Bedroom));
        (o.steps, o.warmup, o.lr, o.lr_final) = (1100, 100, 1e-3, 0.01);
        assert!((o.lr_at(100) - 1e-3).abs() < 1e-12);
        assert!((o.lr_at(600) - 0.505e-3).abs() < 1e-12);
        assert!((o.lr_at(1100) - 1e-5).abs() < 1e-12);
        o.lr_final = 1.0;
        assert!((o.lr_at(850) - 1e-3).abs() < 1e-12);
    }
}
