//! `shade-sim demo [--inputs DIR] [--out DIR]`: the main job on the shipped models. For every
//! example input: generate layouts, check them physically, export MJCF, a PNG plan and a glb, and
//! print one table.

use super::output::{print_json, print_text};
use super::scene_rows::{SceneRow, table};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::Args;
use rayon::prelude::*;
use shade_sim::export::{MjcfOptions, render_plan, scene_glb, scene_mjcf};
use shade_sim::generator::{Generator, shipped_generator};
use shade_sim::pipeline::{LayoutOptions, make_grouped_layouts, room_groups};
use shade_sim::scene::{Scene, write_atomic};
use shade_sim::sim::{CheckConfig, check_scene};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct DemoArgs {
    /// Folder of input scenes (floor plan + humans).
    #[arg(long, default_value = "scenes/examples")]
    pub inputs: PathBuf,
    /// Where the generated scenes, MJCF worlds and plans go.
    #[arg(long, default_value = "out/demo")]
    pub out: PathBuf,
    /// Layouts per input.
    #[arg(long, default_value_t = 1)]
    pub samples: usize,
    /// Seed.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    #[command(flatten)]
    pub guidance: super::generate::GuidanceArgs,
    #[command(flatten)]
    pub repair: super::generate::RepairFlags,
}

pub fn run(args: &DemoArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let started = Instant::now();
    anyhow::ensure!(args.samples > 0, "--samples: must be at least 1");
    let files = super::eval::scene_files(&args.inputs)?;
    let inputs: Vec<Scene> = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    let opts = LayoutOptions {
        samples: args.samples,
        seed: args.seed,
        guidance: args.guidance.config()?,
        repair: args.repair.config()?,
        ..LayoutOptions::default()
    };
    std::fs::create_dir_all(&args.out).with_context(|| format!("{}: cannot create folder", args.out.display()))?;

    let bar = super::progress::bar(global, (inputs.len() * args.samples) as u64, "generate");
    let groups = room_groups(&inputs);
    let generators: Vec<Generator> =
        groups.iter().map(|(room, _)| Ok(shipped_generator(*room)?)).collect::<anyhow::Result<_>>()?;
    let layouts =
        make_grouped_layouts(&inputs, &groups, &generators, &opts, &mut |done| bar.set_position(done as u64))?;
    let generated: Vec<Vec<Scene>> =
        layouts.kept.into_iter().map(|kept| kept.into_iter().map(|l| l.scene).collect()).collect();
    bar.finish_and_clear();

    let jobs: Vec<(String, &Scene)> = files
        .iter()
        .zip(&generated)
        .flat_map(|(f, scenes)| {
            let stem = f.file_stem().map_or("scene".into(), |s| s.to_string_lossy().into_owned());
            scenes.iter().enumerate().map(move |(k, s)| (format!("{stem}_{k}"), s))
        })
        .collect();
    let cfg = CheckConfig::default();
    let rows: Vec<SceneRow> = jobs
        .par_iter()
        .map(|(name, scene)| -> anyhow::Result<SceneRow> {
            let report = check_scene(scene, &cfg);
            let base = args.out.join(name);
            scene.save(base.with_extension("json"))?;
            let xml = scene_mjcf(scene, MjcfOptions::default());
            let xml_path = base.with_extension("xml");
            write_atomic(&xml_path, xml.as_bytes()).with_context(|| format!("{}: cannot write", xml_path.display()))?;
            let png_path = base.with_extension("png");
            render_plan(scene).save_png(&png_path).with_context(|| format!("{}: cannot write", png_path.display()))?;
            let glb_path = base.with_extension("glb");
            write_atomic(&glb_path, &scene_glb(scene))
                .with_context(|| format!("{}: cannot write", glb_path.display()))?;
            Ok(SceneRow::of(name, scene, Some(&report)))
        })
        .collect::<anyhow::Result<_>>()?;
    if global.json {
        print_json(
            &serde_json::json!({ "out": args.out, "scenes": rows, "seconds": started.elapsed().as_secs_f64() }),
        )?;
    } else if global.quiet == 0 {
        print_text(&table(&rows))?;
        print_text(&format!(
            "{} scenes in {:.1} s; scenes (.json), MuJoCo worlds (.xml), plans (.png) and glTF (.glb) in {}\n",
            rows.len(),
            started.elapsed().as_secs_f64(),
            args.out.display()
        ))?;
    }
    Ok(ExitStatus::Success)
}
