//! `shade-sim repair SCENE|DIR --out DIR [--config FILE]`: small exact corrections of any layout
//! (furniture under its contact humans, inside the walls, apart, off walking paths), written to
//! `DIR/<file name>`. The same repair `generate` applies to its samples unless `--no-repair`.
//! `shade-sim repair --print-config [--config FILE]` prints the config in effect (every step and
//! setting, the defaults filled in) and does nothing else.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;
use shade_sim::repair::{RepairConfig, RepairTotals, StepReport, repair_scene};
use shade_sim::scene::Scene;
use shade_sim::sim::SimPhysics;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct RepairArgs {
    /// A scene file or a folder of scene files.
    #[arg(required_unless_present = "print_config")]
    pub input: Option<PathBuf>,
    /// Output folder (repaired scenes keep their file names).
    #[arg(long, required_unless_present = "print_config")]
    pub out: Option<PathBuf>,
    /// A JSON repair config (which steps run, their settings; docs/FORMAT.md); default: every step
    /// with its documented defaults.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Print the config in effect as JSON (the defaults filled in) and exit.
    #[arg(long)]
    pub print_config: bool,
}

#[derive(Serialize)]
struct FileReport {
    file: String,
    totals: RepairTotals,
    steps: Vec<StepReport>,
}

pub fn run(args: &RepairArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let config = RepairConfig::load_or_default(args.config.as_deref())?;
    if args.print_config {
        print_text(&format!("{}\n", serde_json::to_string_pretty(&config)?))?;
        return Ok(ExitStatus::Success);
    }
    let (Some(input), Some(out_dir)) = (&args.input, &args.out) else {
        anyhow::bail!("repair: a scene or folder and --out are needed");
    };
    let files = if input.is_dir() { super::eval::scene_files(input)? } else { vec![input.clone()] };
    // Everything is read and validated before anything is written.
    let scenes: Vec<Scene> = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    std::fs::create_dir_all(out_dir).with_context(|| format!("{}: cannot create folder", out_dir.display()))?;
    // Every input is repaired and written (atomically) before the first failure is reported.
    let reports: Vec<anyhow::Result<FileReport>> = files
        .par_iter()
        .zip(scenes)
        .map(|(file, mut scene)| -> anyhow::Result<FileReport> {
            let r = super::guarded(file, || Ok(repair_scene(&mut scene, &config, &SimPhysics)))?;
            let out = out_dir.join(file.file_name().context("a scene file has a name")?);
            scene.save(&out)?;
            Ok(FileReport { file: out.display().to_string(), totals: r.totals(), steps: r.steps })
        })
        .collect();
    let reports = super::all_or_first_error(reports)?;
    if global.json {
        print_json(&reports)?;
    } else if global.quiet == 0 {
        let moved = reports.iter().filter(|r| r.totals.kept_as_given == 0 && r.totals.settle.max_move > 1e-3).count();
        let t: RepairTotals = reports.iter().map(|r| r.totals).sum();
        print_text(&format!(
            "{} scenes repaired into {}: {moved} changed, largest move {:.3} m; objects: {} resized, {} added, \
             {} relocated, {} narrowed, {} fitted to bodies, {} left out, {} removed; {} passing layouts kept as given (repair \
             made them fail)\n",
            reports.len(),
            out_dir.display(),
            t.settle.max_move,
            t.settle.resized,
            t.settle.added,
            t.relocated,
            t.narrowed,
            t.fitted,
            t.left_out,
            t.removed,
            t.kept_as_given
        ))?;
    }
    Ok(ExitStatus::Success)
}
