//! `shade-sim train --data DIR --out models/ROOM [--steps N] [--resume] [--engine fused|candle]`:
//! trains the denoiser on a calibrated dataset with a progress bar, a JSON-lines log, a loss plot and checkpoints every few
//! minutes and on Ctrl-C.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use clap::Args;
use indicatif::ProgressBar;
use shade_sim::data::read_stats;
use shade_sim::export::{LossPoint, render_loss_png};
use shade_sim::generator::checkpoint::{CONFIG_FILE, read_meta};
use shade_sim::generator::train::LogLine;
use shade_sim::generator::{
    AnchoredYaw, Engine, GenError, ModelConfig, NoiseSchedule, Prediction, TrainObserver, TrainOptions, train,
};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

#[derive(Debug, Args)]
pub struct TrainArgs {
    /// Calibrated dataset (stats.json, train/, val/).
    #[arg(long)]
    pub data: PathBuf,
    /// Another calibrated dataset of the same room type whose every split joins the training set
    /// (--data's val split stays the validation set); repeatable.
    #[arg(long)]
    pub extra_data: Vec<PathBuf>,
    /// A calibrated dataset of another room type the model also serves (needs --room-token; living
    /// and dining rooms share their categories): its train split joins the training set, its val
    /// and test splits stay out; repeatable.
    #[arg(long, requires = "room_token")]
    pub joint_data: Vec<PathBuf>,
    /// One model for every room type with --data's categories (living and dining rooms): a learned
    /// vector per room type joins the condition.
    #[arg(long)]
    pub room_token: bool,
    /// Count conditioning: the condition also holds the layout's pieces per category; sampling
    /// draws them from the training rooms with the same contacts and a floor of about the same
    /// area (kept in config.json).
    #[arg(long)]
    pub count_condition: bool,
    /// Model folder to write (config.json, model.safetensors, log.jsonl, loss.png, train state).
    #[arg(long)]
    pub out: PathBuf,
    /// Total optimiser steps.
    #[arg(long, default_value_t = 12_000)]
    pub steps: u64,
    /// Scenes per batch.
    #[arg(long, default_value_t = 32)]
    pub batch: usize,
    /// Peak learning rate (warm-up, then cosine down to --lr-final of it).
    #[arg(long, default_value_t = 3e-4)]
    pub lr: f64,
    /// The learning rate at the last step, as a fraction of the peak (0 to 1).
    #[arg(long, default_value_t = 0.1)]
    pub lr_final: f64,
    /// Model size: small (shipped; the default), medium (wider), deep (8 blocks) or tiny (tests).
    #[arg(long)]
    pub preset: Option<String>,
    /// What the denoiser predicts: eps, x0 or v (default: the preset's, x0 for small and tiny).
    #[arg(long, value_parser = by_config_name::<Prediction>)]
    pub prediction: Option<Prediction>,
    /// The noise schedule: linear, log_snr or cosine (default: the preset's).
    #[arg(long, value_parser = by_config_name::<NoiseSchedule>)]
    pub schedule: Option<NoiseSchedule>,
    /// How an anchored slot's yaw is given: world or box (relative to its contact box's; default:
    /// the preset's, world).
    #[arg(long, value_parser = by_config_name::<AnchoredYaw>)]
    pub anchored_yaw: Option<AnchoredYaw>,
    /// Whether object tokens get the wall-distance embedding: true or false (default: the
    /// preset's, true).
    #[arg(long)]
    pub wall_features: Option<bool>,
    /// Whether each sitter's knees also anchor a slot, for the table over them: true or false
    /// (default false). True also reads twice the preset's contact boxes (at most the room's
    /// slots), since every sit box brings a knee box.
    #[arg(long)]
    pub table_slots: Option<bool>,
    /// Fourier features of the noisy tokens in this many octaves, the finest 1/2^N of a token
    /// unit (docs/RESULTS.md, "Fourier features"; default: the preset's, 0 = none).
    #[arg(long)]
    pub fourier_bands: Option<usize>,
    /// Whether object tokens get the embedding of their attributes in units of the step's noise
    /// (docs/RESULTS.md, "Noise-scaled features"): true or false (default: the preset's, false).
    #[arg(long)]
    pub noise_scaled_features: Option<bool>,
    /// Whether object tokens get the embedding of the gaps ahead of their piece's faces to the
    /// nearest other piece, measured in metres with the data's bounds (docs/RESULTS.md, "Gaps
    /// between pieces"): true or false (default: the preset's, false).
    #[arg(long)]
    pub gap_features: Option<bool>,
    /// Whether free slots hold their pieces round the room (by the angle about the window centre)
    /// and each gets an embedding of its rank, so that they are no longer each other's twins
    /// (docs/RESULTS.md, "Pieces that do not keep to each other"): true or false (default: the
    /// preset's, false).
    #[arg(long)]
    pub slot_roles: Option<bool>,
    /// Whether object tokens get the embedding of their centre and yaw in world form, an anchored
    /// slot's taken out of its contact box's frame (docs/RESULTS.md, "Pieces that do not keep to
    /// each other"): true or false (default: the preset's, false).
    #[arg(long)]
    pub world_features: Option<bool>,
    /// Whether every attention score gets a learned bias from the pair's relation (position and
    /// yaw of one piece in the other's frame, distance): true or false (default: the preset's,
    /// false).
    #[arg(long)]
    pub relation_bias: Option<bool>,
    /// Whether what each token takes from the others in attention also holds a learned map of
    /// their relation (the other's position and yaw in its frame), so that a nightstand reads its
    /// bed's offset in its own frame (docs/RESULTS.md, "Relations in the values"): true or false
    /// (default: the preset's, false).
    #[arg(long)]
    pub relation_values: Option<bool>,
    /// Whether the model is self-conditioned on its previous clean estimate: true or false
    /// (default: the preset's, false; needs x0-prediction).
    #[arg(long)]
    pub self_condition: Option<bool>,
    /// Min-SNR-γ loss weighting with this γ (e.g. 5): every step's clean-estimate error counts
    /// min(SNR, γ) (default: the preset's, none).
    #[arg(long)]
    pub min_snr: Option<f64>,
    /// A floor under the Min-SNR weight (e.g. 1): the clean-estimate error counts clamp(SNR,
    /// floor, γ), so the noisiest steps still count (needs --min-snr; default: none).
    #[arg(long)]
    pub min_snr_floor: Option<f64>,
    /// Train a low-noise expert: the steps below this one of the schedule alone, for `generate
    /// --expert` to hand it those steps (default: every step).
    #[arg(long)]
    pub expert_below: Option<usize>,
    /// Seed of initialisation, batches and noise.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Continue the run whose checkpoint is in --out, with its model config (flags that choose
    /// one must agree with it).
    #[arg(long)]
    pub resume: bool,
    /// Start from the weights of the model in this folder instead of random ones (fine-tuning, e.g.
    /// a shipped model on your own rooms): its network, token bounds and sampler are kept, so the
    /// flags that choose a network are refused beside it (--min-snr, --min-snr-floor and
    /// --expert-below may differ); the optimiser starts afresh.
    #[arg(long, value_name = "MODEL_DIR")]
    pub init: Option<PathBuf>,
    /// Minutes between checkpoints.
    #[arg(long, default_value_t = 5.0)]
    pub checkpoint_minutes: f64,
    /// Steps between log lines.
    #[arg(long, default_value_t = 50)]
    pub log_every: u64,
    /// Steps between validation losses.
    #[arg(long, default_value_t = 1000)]
    pub val_every: u64,
    /// Weigh the loss on rare categories' objects up: (median share / share)^B, at most 10×
    /// (0: every object alike). The validation loss stays unweighted.
    #[arg(long, default_value_t = 0.0)]
    pub category_balance: f64,
    /// EMA decay of the shipped weights: each step keeps DECAY of them and takes 1 − DECAY of the
    /// trained ones (0 < DECAY < 1: an average over about the last 1 / (1 − DECAY) steps).
    #[arg(long, default_value_t = 0.999, value_name = "DECAY")]
    pub ema_decay: f64,
    /// Input perturbation γ (DDPM-IP): every training input gets √(1 − ᾱ_t) γ ξ more noise than
    /// its step says, the target unchanged (0: none). The validation loss stays unperturbed.
    #[arg(long, default_value_t = 0.0)]
    pub input_perturbation: f64,
    /// The model's default sampler, recorded in config.json's `sampling`: DDIM's η on the pieces'
    /// geometry (0 to 2), the classes on DDPM's chain, as `generate --eta ETA --eta-geometry-only`
    /// (default: none, DDPM's chain; 2 for the shipped living and dining models).
    #[arg(long, value_name = "ETA")]
    pub geometry_eta: Option<f64>,
    /// Share of training scenes with one free piece moved 6 to 50 cm before the noise, the target
    /// still the scene's own layout, so that the model learns to put pieces back (0: none;
    /// docs/RESULTS.md, "Displaced pieces"). The validation loss sees none.
    #[arg(long, default_value_t = 0.0)]
    pub displaced_pieces: f64,
    /// Weight of the relation loss: the error of each pair of nearby pieces' relative place (their
    /// centres within half the window's half side) counts this many times as much as each piece's
    /// own (0: none; docs/RESULTS.md, "Pieces that do not keep to each other"). Needs the fused
    /// engine; the validation loss stays without it.
    #[arg(long, default_value_t = 0.0, value_name = "WEIGHT")]
    pub relation_loss: f64,
    /// Gradient engine: fused (the hand-written pass on every core) or candle (autograd, the
    /// slower reference it is tested against).
    #[arg(long, default_value = "fused", value_parser = by_config_name::<Engine>)]
    pub engine: Engine,
}

/// A config enum from its name in config files (`x0`, `log_snr`, `box`, `fused`, …), so that the
/// command line and config.json spell every choice alike.
fn by_config_name<T: serde::de::DeserializeOwned>(s: &str) -> Result<T, String> {
    serde_json::from_value(serde_json::Value::String(s.to_string())).map_err(|e| e.to_string())
}

/// The progress bar, and the model folder where each checkpoint's `loss.png` goes.
struct Bar(ProgressBar, PathBuf);

impl TrainObserver for Bar {
    fn started(&mut self, step: u64, total: u64, scenes: usize, parameters: usize) {
        self.0.set_length(total);
        self.0.set_position(step);
        self.0.reset_eta();
        tracing::info!("training on {scenes} scenes, {parameters} parameters, from step {step} to {total}");
    }
    fn logged(&mut self, line: &LogLine) {
        self.0.set_position(line.step);
        let val = line.val_loss.map_or(String::new(), |v| format!(" val {v:.4}"));
        self.0.set_message(format!("train loss {:.4}{val}", line.loss));
        tracing::info!(step = line.step, loss = line.loss, val = ?line.val_loss, "log");
    }
    fn checkpointed(&mut self, step: u64, log: &[LogLine]) -> Result<(), GenError> {
        tracing::info!("checkpoint at step {step}");
        let points: Vec<LossPoint> =
            log.iter().map(|l| LossPoint { step: l.step, loss: l.loss, val_loss: l.val_loss }).collect();
        let path = self.1.join("loss.png");
        render_loss_png(&points, &path).map_err(|e| GenError::io(path, e))
    }
}

/// The model config the flags ask for: `--preset`'s, with each architecture flag given.
fn model_config(args: &TrainArgs, room: shade_sim::scene::RoomType) -> anyhow::Result<ModelConfig> {
    let preset = args.preset.as_deref().unwrap_or("small");
    let mut model = ModelConfig::preset(preset, room)
        .ok_or_else(|| anyhow::anyhow!("--preset: unknown preset {preset:?} (small, medium, deep, tiny)"))?;
    if let Some(prediction) = args.prediction {
        model.prediction = prediction;
    }
    if let Some(schedule) = args.schedule {
        model.schedule = schedule;
    }
    if let Some(anchored_yaw) = args.anchored_yaw {
        model.anchored_yaw = anchored_yaw;
    }
    if let Some(wall_features) = args.wall_features {
        model.wall_features = wall_features;
    }
    if let Some(table_slots) = args.table_slots {
        model.table_slots = table_slots;
        if table_slots {
            model.max_contacts = (2 * model.max_contacts).min(model.slots());
        }
    }
    if let Some(slot_roles) = args.slot_roles {
        model.slot_roles = slot_roles;
    }
    if let Some(world_features) = args.world_features {
        model.world_features = world_features;
    }
    if let Some(bands) = args.fourier_bands {
        model.fourier_bands = bands;
    }
    if let Some(noise_scaled) = args.noise_scaled_features {
        model.noise_scaled_features = noise_scaled;
    }
    if let Some(gaps) = args.gap_features {
        model.gap_bounds = match gaps {
            true => Some(shade_sim::generator::data_bounds(&args.data)?),
            false => None,
        };
    }
    if let Some(relation_bias) = args.relation_bias {
        model.relation_bias = relation_bias;
    }
    if let Some(relation_values) = args.relation_values {
        model.relation_values = relation_values;
    }
    if let Some(self_condition) = args.self_condition {
        model.self_condition = self_condition;
    }
    model.room_token |= args.room_token;
    model.count_condition |= args.count_condition;
    with_training_flags(model, args)
}

/// `model` with what `--min-snr`, `--min-snr-floor` and `--expert-below` ask training to weigh
/// and draw, where given.
fn with_training_flags(mut model: ModelConfig, args: &TrainArgs) -> anyhow::Result<ModelConfig> {
    anyhow::ensure!(args.min_snr.is_none_or(|g| g.is_finite() && g > 0.0), "--min-snr: must be a positive number");
    if args.min_snr.is_some() {
        model.min_snr = args.min_snr;
    }
    anyhow::ensure!(
        args.min_snr_floor.is_none_or(|f| f.is_finite() && f > 0.0 && model.min_snr.is_some_and(|g| f <= g)),
        "--min-snr-floor: must be a positive number no larger than --min-snr, which it needs"
    );
    if args.min_snr_floor.is_some() {
        model.min_snr_floor = args.min_snr_floor;
    }
    if args.expert_below.is_some() {
        model.expert_below = args.expert_below;
    }
    Ok(model)
}

/// The model config of the model `--init` names, which a fine-tuning run keeps: refused beside
/// `--resume` (the run in --out records its start) and beside any flag that would choose another
/// architecture.
fn initial_model(args: &TrainArgs, dir: &Path) -> anyhow::Result<ModelConfig> {
    anyhow::ensure!(!args.resume, "--init: a resumed run continues from its own checkpoint; leave out --init");
    if let Some(flag) = architecture_flag(args) {
        anyhow::bail!("--init: the model's architecture is {}'s; leave out {flag}", dir.display());
    }
    // What training weighs and which steps it draws are the run's own (a low-noise expert
    // fine-tuned from a model of the whole chain).
    with_training_flags(read_meta(dir)?.model, args)
}

/// The model config of the run `--resume` continues when no flag chooses its network: its own (a
/// fine-tuned run's is its start's, which no preset gives), with the training flags given (which
/// the resumed run then refuses if they differ from its own).
fn resumed_model(out: &Path, args: &TrainArgs) -> anyhow::Result<Option<ModelConfig>> {
    if !out.join(CONFIG_FILE).exists() {
        return Ok(None);
    }
    Ok(Some(with_training_flags(read_meta(out)?.model, args)?))
}

/// The first flag given that chooses the model's network (not `--min-snr`, `--min-snr-floor` or
/// `--expert-below`, which only change what training weighs and draws).
fn architecture_flag(args: &TrainArgs) -> Option<&'static str> {
    let given = [
        ("--preset", args.preset.is_some()),
        ("--prediction", args.prediction.is_some()),
        ("--schedule", args.schedule.is_some()),
        ("--anchored-yaw", args.anchored_yaw.is_some()),
        ("--wall-features", args.wall_features.is_some()),
        ("--table-slots", args.table_slots.is_some()),
        ("--slot-roles", args.slot_roles.is_some()),
        ("--world-features", args.world_features.is_some()),
        ("--fourier-bands", args.fourier_bands.is_some()),
        ("--noise-scaled-features", args.noise_scaled_features.is_some()),
        ("--gap-features", args.gap_features.is_some()),
        ("--relation-bias", args.relation_bias.is_some()),
        ("--relation-values", args.relation_values.is_some()),
        ("--self-condition", args.self_condition.is_some()),
        ("--room-token", args.room_token),
        ("--count-condition", args.count_condition),
    ];
    given.into_iter().find(|(_, given)| *given).map(|(flag, _)| flag)
}

pub fn run(args: &TrainArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let stats = read_stats(&args.data)?;
    let resumed = match args.resume && architecture_flag(args).is_none() {
        true => resumed_model(&args.out, args)?,
        false => None,
    };
    let model = match (&args.init, resumed) {
        (Some(dir), _) => initial_model(args, dir)?,
        (None, Some(model)) => model,
        (None, None) => model_config(args, stats.room_type)?,
    };
    let state = args.out.join(shade_sim::generator::checkpoint::STATE_META_FILE);
    anyhow::ensure!(
        args.resume || !state.exists(),
        "{}: holds a training run; pass --resume to continue it or choose another --out",
        args.out.display()
    );
    anyhow::ensure!(
        args.batch > 0 && args.log_every > 0 && args.val_every > 0,
        "--batch, --log-every and --val-every must be positive"
    );
    let mut opts = TrainOptions::new(args.data.clone(), args.out.clone(), model);
    opts.extra_data = args.extra_data.clone();
    opts.joint_data = args.joint_data.clone();
    opts.steps = args.steps;
    opts.batch = args.batch;
    anyhow::ensure!(args.lr.is_finite() && args.lr > 0.0, "--lr: must be a positive number");
    opts.lr = args.lr;
    anyhow::ensure!((0.0..=1.0).contains(&args.lr_final), "--lr-final: must be a fraction of the peak, from 0 to 1");
    opts.lr_final = args.lr_final;
    opts.seed = args.seed;
    opts.resume = args.resume;
    opts.init = args.init.clone();
    anyhow::ensure!(
        args.category_balance.is_finite() && args.category_balance >= 0.0,
        "--category-balance: must be a non-negative number"
    );
    opts.category_balance = args.category_balance;
    anyhow::ensure!(
        args.input_perturbation.is_finite() && (0.0..=1.0).contains(&args.input_perturbation),
        "--input-perturbation: must be a number between 0 and 1"
    );
    opts.input_perturbation = args.input_perturbation;
    anyhow::ensure!(
        args.ema_decay.is_finite() && args.ema_decay > 0.0 && args.ema_decay < 1.0,
        "--ema-decay: must be a number between 0 and 1, not {}",
        args.ema_decay
    );
    opts.ema_decay = args.ema_decay;
    anyhow::ensure!(
        args.displaced_pieces.is_finite() && (0.0..=1.0).contains(&args.displaced_pieces),
        "--displaced-pieces: must be a number between 0 and 1"
    );
    opts.displaced_pieces = args.displaced_pieces;
    anyhow::ensure!(
        args.relation_loss.is_finite() && args.relation_loss >= 0.0,
        "--relation-loss: must be a non-negative number, not {}",
        args.relation_loss
    );
    anyhow::ensure!(args.relation_loss == 0.0 || args.engine == Engine::Fused, "--relation-loss: needs --engine fused");
    opts.relation_loss = args.relation_loss;
    anyhow::ensure!(
        args.geometry_eta.is_none_or(|eta| (0.0..=2.0).contains(&eta)),
        "--geometry-eta: must be between 0 and 2"
    );
    opts.sampling = args.geometry_eta.map(|geometry_eta| shade_sim::generator::SamplingDefaults { geometry_eta });
    opts.engine = args.engine;
    opts.log_every = args.log_every;
    opts.val_every = args.val_every;
    anyhow::ensure!(
        args.checkpoint_minutes.is_finite() && args.checkpoint_minutes >= 0.0,
        "--checkpoint-minutes: must be a non-negative number"
    );
    opts.checkpoint_every = Duration::from_secs_f64(args.checkpoint_minutes * 60.0);
    opts.command = std::env::args().map(|a| shell_word(&a)).collect::<Vec<_>>().join(" ").replacen(
        &shell_word(&std::env::args().next().unwrap_or_default()),
        "shade-sim",
        1,
    );
    let stop = Arc::new(AtomicBool::new(false));
    let flag = stop.clone();
    // A second Ctrl-C while the checkpoint is written falls through to the default (exit).
    let _ = ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
        eprintln!("stopping: writing a checkpoint at the next log step (Ctrl-C again to quit now)");
    });
    let bar = super::progress::bar(global, args.steps, "train");
    let outcome = train(&opts, &stop, &mut Bar(bar.clone(), args.out.clone()))?;
    bar.finish_and_clear();
    if global.json {
        print_json(&serde_json::json!({
            "out": args.out,
            "step": outcome.step,
            "stopped": outcome.stopped,
            "val_loss": outcome.val_loss,
            "seconds": outcome.seconds,
        }))?;
    } else if global.quiet == 0 {
        let val = outcome.val_loss.map_or("-".to_string(), |v| format!("{v:.4}"));
        let how = if outcome.stopped { "stopped (resume with --resume)" } else { "done" };
        print_text(&format!(
            "{how}: step {} of {}, val loss {val}, {:.0} s of training; model in {}\n",
            outcome.step,
            args.steps,
            outcome.seconds,
            args.out.display()
        ))?;
    }
    Ok(ExitStatus::Success)
}

/// `a` quoted for a shell when it needs it.
fn shell_word(a: &str) -> String {
    if !a.is_empty() && a.chars().all(|c| c.is_ascii_alphanumeric() || "-_./=:".contains(c)) {
        a.to_string()
    } else {
        format!("'{}'", a.replace('\'', "'\\''"))
    }
}
