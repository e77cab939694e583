//! `shade-sim generate --input IN.json|DIR --out DIR [--samples K] [--seed S] [--model DIR]`:
//! layouts for an input's floor plan and humans, written as `DIR/<input>_<k>.json`. A folder may
//! mix room types: each type is sampled with its own shipped model (seeds per input within it).

use super::output::{print_json, print_text};
use super::scene_rows::{SceneRow, table};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use shade_sim::generator::{Checkpoint, Generator, GuidanceConfig, shipped_generator};
use shade_sim::human::{Meeting, SeatInTheWay, people_meeting, seats_in_the_way};
use shade_sim::pipeline::{
    LayoutOptions, input_notes, make_grouped_layouts, off_the_floor_warnings, people_in_walls_message,
    rejections_message, room_groups,
};
use shade_sim::repair::{RepairConfig, RepairTotals};
use shade_sim::scene::{RoomType, Scene};
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct GenerateArgs {
    /// Input scene (floor plan and humans; objects, if any, are ignored unless --refine), or a folder of them.
    #[arg(long)]
    pub input: PathBuf,
    /// Folder for the generated scenes.
    #[arg(long)]
    pub out: PathBuf,
    /// Layouts to sample.
    #[arg(long, default_value_t = 1)]
    pub samples: usize,
    /// Seed: the same seed gives the same layouts.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Model folder (config.json + model.safetensors); default: the shipped model of the input's room type.
    #[arg(long)]
    pub model: Option<PathBuf>,
    #[command(flatten)]
    pub guidance: GuidanceArgs,
    #[command(flatten)]
    pub repair: RepairFlags,
    /// Keep only layouts that pass `check`, resampling (new seeds) until each input has --samples
    /// of them or --attempts rounds are spent; exit 1 if an input got none.
    #[arg(long)]
    pub require_clean: bool,
    /// Sampling rounds for --require-clean.
    #[arg(long, default_value_t = 8)]
    pub attempts: usize,
    /// Sample without the empty-slot projection, nor the count projection (the model's raw
    /// output, 40–55 % more objects than the data; for comparisons, docs/RESULTS.md).
    #[arg(long)]
    pub no_empty_projection: bool,
    /// Keep a category count no training room has (one dining chair, three nightstands) instead
    /// of moving it to the nearest count the data has (for comparisons, docs/RESULTS.md).
    #[arg(long)]
    pub unseen_counts: bool,
    /// Keep the class the model gives a person's piece even where it does not afford what they
    /// do (a dining table under a diner) instead of the affording piece it scores highest (for
    /// comparisons, docs/RESULTS.md).
    #[arg(long)]
    pub unafforded_pieces: bool,
    /// Sample with this many model calls instead of the model's T (its chain respaced to N evenly
    /// spaced steps; faster, and a v model keeps its precision; default: T).
    #[arg(long)]
    pub sampling_steps: Option<usize>,
    /// How much of DDPM's fresh noise each step draws (DDIM's η, 0 to 2): 1 is DDPM's ancestral
    /// sampler, 0 the deterministic DDIM sampler, above 1 more fresh noise than DDPM's posterior
    /// (docs/RESULTS.md, "DDIM").
    /// (Default: the model's own, DDPM's unless its config.json says otherwise.)
    #[arg(long)]
    pub eta: Option<f64>,
    /// Apply --eta to the pieces' geometry only (centre, size, yaw), the classes keeping DDPM's
    /// chain (the shipped living and dining models sample with η 2 there).
    #[arg(long, requires = "eta")]
    pub eta_geometry_only: bool,
    /// With a count-conditioned model: condition each layout on the input's own pieces per
    /// category instead of a draw from the model's count prior (furnish a room with the pieces
    /// it has; the input's pieces are replaced as always).
    #[arg(long)]
    pub input_counts: bool,
    /// Refine each input's own pieces instead of sampling from pure noise (SDEdit): its layout
    /// is noised to the linear schedule's step STRENGTH × T (0 to 1) and denoised, guided, from
    /// there. Small values move pieces by centimetres and keep the make-up; 1 forgets the input.
    #[arg(long, value_name = "STRENGTH")]
    pub refine: Option<f64>,
    /// A low-noise expert's model folder (`train --expert-below N`): it takes the chain's steps
    /// below N, the model (shipped or --model) the rest.
    #[arg(long)]
    pub expert: Option<PathBuf>,
}

/// Repair flags (shared with `demo`).
#[derive(Debug, Clone, Args)]
pub struct RepairFlags {
    /// Keep the sampled layouts as they are: no repair after sampling.
    #[arg(long)]
    pub no_repair: bool,
    /// A JSON repair config (which steps run, their settings; docs/FORMAT.md); default: every step
    /// with its documented defaults.
    #[arg(long, conflicts_with = "no_repair")]
    pub repair_config: Option<PathBuf>,
}

impl RepairFlags {
    /// The repair these flags ask for (`None`: no repair).
    pub fn config(&self) -> anyhow::Result<Option<RepairConfig>> {
        if self.no_repair {
            return Ok(None);
        }
        Ok(Some(RepairConfig::load_or_default(self.repair_config.as_deref())?))
    }
}

/// Collision guidance flags (shared with `demo`).
#[derive(Debug, Clone, Args)]
pub struct GuidanceArgs {
    /// Guidance terms during sampling: none, all (= mot,bound,obj), or a list of mot, bound, obj
    /// and phys (physics feedback in the last steps). The terms are measured exactly: pieces kept
    /// 5 cm inside the walls and 3 cm apart, wall pieces drawn back to their wall, contact boxes
    /// just covered by their piece's seat or top; add `soft` for SHADE's soft J_b and J_c without
    /// the wall pull (the default before 2026-11-27; `exact` and `walls` are accepted and change
    /// nothing). Repair after sampling is separate (--no-repair).
    #[arg(long, default_value = "all")]
    pub guidance: String,
    /// Step size γ of the guidance (default: the tuned value in docs/RESULTS.md).
    #[arg(long)]
    pub guidance_scale: Option<f64>,
    /// A JSON file with every guidance setting (per-term weights, γ, step windows); --guidance is
    /// then ignored and --guidance-scale still applies.
    #[arg(long)]
    pub guidance_config: Option<PathBuf>,
}

impl GuidanceArgs {
    /// The configuration these flags ask for.
    pub fn config(&self) -> anyhow::Result<GuidanceConfig> {
        let mut cfg = match &self.guidance_config {
            Some(file) => {
                let text = std::fs::read_to_string(file).with_context(|| format!("{}: cannot read", file.display()))?;
                serde_json::from_str(&text).with_context(|| format!("{}: not a guidance config", file.display()))?
            }
            None => GuidanceConfig::parse(&self.guidance).map_err(|e| anyhow::anyhow!("--guidance: {e}"))?,
        };
        if let Some(scale) = self.guidance_scale {
            anyhow::ensure!(scale.is_finite() && scale >= 0.0, "--guidance-scale: must be a non-negative number");
            cfg.scale = scale;
        }
        if let (Some(problem), Some(file)) = (cfg.problem(), &self.guidance_config) {
            anyhow::bail!("{}: {problem}", file.display());
        }
        Ok(cfg)
    }
}

/// The model `custom` (loaded from `--model`), or the shipped one for `room` with its shipped
/// low-noise expert if it has one; fails when it does not generate `room`.
pub fn load_model(custom: Option<&Checkpoint>, room: RoomType, input: &Path) -> anyhow::Result<Generator> {
    let generator = match custom {
        Some(c) => Generator::new(c.clone()),
        None => shipped_generator(room)?,
    };
    let model = &generator.checkpoint.meta.model;
    anyhow::ensure!(
        model.serves(room),
        "{}: is a {room} but the model generates {}",
        input.display(),
        model.room_names()
    );
    Ok(generator)
}

pub fn run(args: &GenerateArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    anyhow::ensure!(args.samples > 0, "--samples: must be at least 1");
    anyhow::ensure!(args.sampling_steps.is_none_or(|n| n >= 2), "--sampling-steps: must be at least 2");
    if let Some(eta) = args.eta {
        anyhow::ensure!((0.0..=2.0).contains(&eta), "--eta: must be between 0 and 2, not {eta}");
    }
    anyhow::ensure!(
        args.refine.is_none_or(|r| r > 0.0 && r <= 1.0),
        "--refine: must be a number above 0 and at most 1"
    );
    let files = if args.input.is_dir() { super::eval::scene_files(&args.input)? } else { vec![args.input.clone()] };
    let inputs: Vec<Scene> = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    let opts = LayoutOptions {
        samples: args.samples,
        seed: args.seed,
        guidance: args.guidance.config()?,
        repair: args.repair.config()?,
        require_clean: args.require_clean,
        attempts: args.attempts,
        ..LayoutOptions::default()
    };
    // One model per room type, in the order the types first appear (with --model: that model for
    // each, which must generate them all).
    let groups = room_groups(&inputs);
    let custom = args.model.as_deref().map(Checkpoint::load).transpose()?;
    let expert = args.expert.as_deref().map(|dir| Checkpoint::load(dir).map(|c| (dir, c))).transpose()?;
    let generators: Vec<Generator> = groups
        .iter()
        .map(|(room, members)| -> anyhow::Result<_> {
            let generator = load_model(custom.as_ref(), *room, &files[members[0]])?;
            let generator = if args.no_empty_projection { generator.without_empty_projection() } else { generator };
            let generator = if args.unseen_counts { generator.without_seen_counts() } else { generator };
            let generator = if args.unafforded_pieces { generator.without_affordances() } else { generator };
            anyhow::ensure!(
                !args.input_counts || generator.checkpoint.meta.model.count_condition,
                "--input-counts: the {room} model has no count conditioning (train one with --count-condition)"
            );
            let generator = if args.input_counts { generator.with_input_counts() } else { generator };
            let generator = match (args.eta, args.eta_geometry_only) {
                (Some(eta), true) => generator.with_geometry_eta(eta),
                (Some(eta), false) => generator.with_eta(eta),
                (None, _) => generator,
            };
            let generator = match args.sampling_steps {
                Some(n) => generator.with_sampling_steps(n),
                None => generator,
            };
            let generator = match args.refine {
                Some(strength) => generator.refining(strength),
                None => generator,
            };
            Ok(match &expert {
                Some((dir, e)) => generator.with_expert(e.clone(), dir)?,
                None => generator,
            })
        })
        .collect::<anyhow::Result<_>>()?;
    // Counting or refining an input's pieces needs pieces: an empty room would be asked to hold
    // nothing.
    let uses_pieces = [(args.input_counts, "--input-counts", "count"), (args.refine.is_some(), "--refine", "refine")];
    for (_, flag, verb) in uses_pieces.into_iter().filter(|(on, _, _)| *on) {
        for (file, input) in files.iter().zip(&inputs) {
            let pieces: usize = input.room_type.category_counts(&input.objects).iter().sum();
            anyhow::ensure!(
                pieces > 0,
                "{}: {flag}: the input has no {} pieces to {verb} (list the room's pieces in its objects)",
                file.display(),
                input.room_type
            );
        }
    }
    // More people in contact than the model conditions on, a floor unlike its training rooms':
    // said before sampling.
    for (g, (_, members)) in groups.iter().enumerate() {
        for &i in members {
            for note in input_notes(&generators[g], &inputs[i]) {
                tracing::warn!("{}: {note}", files[i].display());
            }
        }
    }
    // People inside each other: no layout mends it (`human::people_meeting`); said before sampling.
    let meetings: Vec<Vec<Meeting>> = inputs.par_iter().map(|s| people_meeting(s, opts.check.tolerance)).collect();
    for (file, found) in files.iter().zip(&meetings) {
        for m in found {
            tracing::warn!("{}: {m}", file.display());
        }
    }
    // Someone walking or standing where a seat must be for someone else's sitting (or their own):
    // no layout holds both (`human::seats_in_the_way`); said before sampling.
    let in_the_way: Vec<Vec<SeatInTheWay>> =
        inputs.par_iter().map(|s| seats_in_the_way(s, opts.check.tolerance)).collect();
    for (file, found) in files.iter().zip(&in_the_way) {
        for s in found {
            tracing::warn!("{}: {s}", file.display());
        }
    }
    // Someone standing on something no piece is for (a climb in a capture): said before sampling.
    for (file, input) in files.iter().zip(&inputs) {
        for w in off_the_floor_warnings(input, &opts.check) {
            tracing::warn!("{}: {w}", file.display());
        }
    }
    let bar = super::progress::bar(global, (inputs.len() * args.samples) as u64, "generate");
    let layouts =
        make_grouped_layouts(&inputs, &groups, &generators, &opts, &mut |done| bar.set_position(done as u64))?;
    bar.finish_and_clear();
    // Why an input got no clean layout: its people in a wall, else what its rejected layouts hit.
    let mut unfurnished = Vec::new();
    for (((file, walls), rejected), kept) in
        files.iter().zip(&layouts.people_in_walls).zip(&layouts.rejected).zip(&layouts.kept)
    {
        let why = people_in_walls_message(walls)
            .or_else(|| (args.require_clean && kept.is_empty()).then(|| rejections_message(rejected)).flatten());
        if let Some(why) = why {
            tracing::warn!("{}: {why}", file.display());
            if kept.is_empty() {
                unfurnished.push(serde_json::json!({"input": file.display().to_string(), "why": why}));
            }
        }
    }
    let (kept, sampled, accepted) = (layouts.kept, layouts.sampled, layouts.accepted);
    std::fs::create_dir_all(&args.out).with_context(|| format!("{}: cannot create folder", args.out.display()))?;
    let mut rows = Vec::new();
    let mut repaired = Vec::new();
    for (input, samples) in files.iter().zip(&kept) {
        let stem = input.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        for (k, layout) in samples.iter().enumerate() {
            let file = args.out.join(format!("{stem}_{k}.json"));
            layout.scene.save(&file)?;
            rows.push(SceneRow::of(&file.display().to_string(), &layout.scene, layout.check.as_ref()));
            repaired.extend(layout.repair.as_ref().map(|r| (file.display().to_string(), r.clone())));
        }
    }
    let repair_totals = (!repaired.is_empty()).then(|| repaired.iter().map(|(_, r)| r.totals()).sum::<RepairTotals>());
    let empty = kept.iter().filter(|k| k.is_empty()).count();
    let acceptance = args.require_clean.then(|| accepted as f64 / sampled.max(1) as f64);
    if global.json {
        print_json(&serde_json::json!({
            "input": args.input,
            "seed": args.seed,
            "scenes": rows,
            "guidance": opts.guidance,
            "repair": opts.repair.as_ref().map(|cfg| serde_json::json!({
                "config": cfg,
                "totals": repair_totals,
                "scenes": repaired.iter().map(|(f, r)| serde_json::json!({"file": f, "steps": r.steps})).collect::<Vec<_>>(),
            })),
            "sampled": sampled,
            "acceptance_rate": acceptance,
            "inputs_without_clean_layout": args.require_clean.then_some(empty),
            "without_clean_layout": args.require_clean.then_some(&unfurnished),
        }))?;
    } else if global.quiet == 0 {
        print_text(&table(&rows))?;
        if let Some(rate) = acceptance {
            print_text(&format!(
                "{accepted} of {sampled} sampled layouts passed the check (acceptance {:.1} %); {empty} inputs without one\n",
                rate * 100.0
            ))?;
        }
    }
    Ok(if args.require_clean && empty > 0 { ExitStatus::Found } else { ExitStatus::Success })
}
