//! `shade-sim polish SCENE|DIR --out DIR [--rounds N]`: small exact corrections of any layout
//! (furniture under its contact humans, inside the walls, apart, off walking paths), written to
//! `DIR/<file name>`. The same polishing `generate --guidance …,polish` applies to its samples.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;
use shade_sim::generator::{PolishReport, polish_scene};
use shade_sim::scene::Scene;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct PolishArgs {
    /// A scene file or a folder of scene files.
    pub input: PathBuf,
    /// Output folder (polished scenes keep their file names).
    #[arg(long)]
    pub out: PathBuf,
    /// Rounds of corrections at most.
    #[arg(long, default_value_t = shade_sim::generator::GuidanceConfig::POLISH_ROUNDS)]
    pub rounds: usize,
}

#[derive(Serialize)]
struct FileReport {
    file: String,
    #[serde(flatten)]
    report: PolishReport,
}

pub fn run(args: &PolishArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let files = if args.input.is_dir() { super::eval::scene_files(&args.input)? } else { vec![args.input.clone()] };
    // Everything is read and validated before anything is written.
    let scenes: Vec<Scene> = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    std::fs::create_dir_all(&args.out).with_context(|| format!("{}: cannot create folder", args.out.display()))?;
    let reports: Vec<FileReport> = files
        .par_iter()
        .zip(scenes)
        .map(|(file, mut scene)| -> anyhow::Result<FileReport> {
            let r = polish_scene(&mut scene, args.rounds);
            let out = args.out.join(file.file_name().context("a scene file has a name")?);
            scene.save(&out)?;
            Ok(FileReport { file: out.display().to_string(), report: r })
        })
        .collect::<anyhow::Result<_>>()?;
    if global.json {
        print_json(&reports)?;
    } else if global.quiet == 0 {
        let moved = reports.iter().filter(|r| r.report.max_move > 1e-3).count();
        let largest = reports.iter().map(|r| r.report.max_move).fold(0.0, f64::max);
        print_text(&format!(
            "{} scenes polished into {}: {moved} changed, largest move {largest:.3} m; objects: {} resized, {} added, \
             {} trimmed, {} widened, {} narrowed, {} left out, {} removed\n",
            reports.len(),
            args.out.display(),
            reports.iter().map(|r| r.report.resized).sum::<usize>(),
            reports.iter().map(|r| r.report.added).sum::<usize>(),
            reports.iter().map(|r| r.report.trimmed).sum::<usize>(),
            reports.iter().map(|r| r.report.widened).sum::<usize>(),
            reports.iter().map(|r| r.report.narrowed).sum::<usize>(),
            reports.iter().map(|r| r.report.left_out).sum::<usize>(),
            reports.iter().map(|r| r.report.removed).sum::<usize>()
        ))?;
    }
    Ok(ExitStatus::Success)
}
