//! `shade-sim export SCENE --format mjcf|robosuite|png|glb --out FILE [--free-furniture] [--validate]`.

use super::output::{print_json, print_text, same_file};
use super::{ExitStatus, GlobalArgs};
use anyhow::Context;
use clap::{Args, ValueEnum};
use serde::Serialize;
use shade_sim::export::{MjcfOptions, scene_mjcf};
use shade_sim::scene::{Scene, write_atomic};
use std::path::PathBuf;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// A MuJoCo world (MJCF XML) with the humans' motion as keyframes.
    Mjcf,
    /// A robosuite arena (MJCF without keyframes, for `robosuite.models.arenas.Arena`) plus the
    /// humans' motion in `<out>.motion.json`.
    Robosuite,
    /// A top-down plan (PNG): floor, labelled furniture, walking paths, contact humans, scale.
    Png,
    /// glTF 2.0 binary: floor, walls, furniture parts and the humans' bones as capsules, their
    /// motion as the animation "motion".
    #[value(alias = "gltf")]
    Glb,
}

#[derive(Debug, Args)]
pub struct ExportArgs {
    /// The scene file.
    pub scene: PathBuf,
    /// Output format.
    #[arg(long, value_enum, default_value = "mjcf")]
    pub format: Format,
    /// Output file.
    #[arg(long)]
    pub out: PathBuf,
    /// Give furniture free joints (it can be pushed) instead of fixing it.
    #[arg(long)]
    pub free_furniture: bool,
    /// Load the world in MuJoCo, step it 1,000 times and fail if anything is non-finite or any
    /// furniture moves (needs the `mujoco` feature).
    #[arg(long)]
    pub validate: bool,
}

#[derive(Serialize)]
struct Report {
    scene: String,
    out: String,
    bytes: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    validation: Option<serde_json::Value>,
}

pub fn run(args: &ExportArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let scene = Scene::load(&args.scene)?;
    let motion = (args.format == Format::Robosuite).then(|| motion_path(&args.out));
    for out in std::iter::once(&args.out).chain(&motion) {
        anyhow::ensure!(
            !same_file(out, &args.scene),
            "{}: is the scene being exported; choose another --out",
            out.display()
        );
    }
    let (bytes, validation) = match args.format {
        Format::Mjcf | Format::Robosuite => {
            let robosuite = args.format == Format::Robosuite;
            let opts = if robosuite { MjcfOptions::robosuite() } else { MjcfOptions::default() };
            let text = scene_mjcf(&scene, MjcfOptions { free_furniture: args.free_furniture, ..opts });
            let validation = if args.validate { Some(validate(&scene, &text, &args.out)?) } else { None };
            if robosuite {
                let motion = motion_path(&args.out);
                let mut json = serde_json::to_string(&shade_sim::export::mocap_motion(&scene))?;
                json.push('\n');
                write_atomic(&motion, json.as_bytes())
                    .with_context(|| format!("{}: cannot write", motion.display()))?;
            }
            (text.into_bytes(), validation)
        }
        Format::Png | Format::Glb => {
            anyhow::ensure!(!args.validate, "{}: --validate applies to --format mjcf", args.out.display());
            let bytes = match args.format {
                Format::Png => shade_sim::export::render_plan(&scene).png_bytes(),
                _ => shade_sim::export::scene_glb(&scene),
            };
            (bytes, None)
        }
    };
    write_atomic(&args.out, &bytes).with_context(|| format!("{}: cannot write", args.out.display()))?;
    let report = Report {
        scene: args.scene.display().to_string(),
        out: args.out.display().to_string(),
        bytes: bytes.len(),
        validation,
    };
    if global.json {
        print_json(&report)?;
    } else if global.quiet == 0 {
        let checked = if report.validation.is_some() { ", validated in MuJoCo (1,000 steps)" } else { "" };
        print_text(&format!("{}: wrote {} ({} bytes){checked}\n", report.scene, report.out, report.bytes))?;
    }
    Ok(ExitStatus::Success)
}

/// `room.xml` → `room.motion.json`.
fn motion_path(out: &std::path::Path) -> PathBuf {
    out.with_extension("motion.json")
}

#[cfg(feature = "mujoco")]
fn validate(scene: &Scene, text: &str, out: &std::path::Path) -> anyhow::Result<serde_json::Value> {
    let v = shade_sim::export::validate_in_mujoco(scene, text, 1000)
        .map_err(|e| anyhow::anyhow!("{}: MuJoCo rejects the world: {e}", out.display()))?;
    if v.non_finite {
        anyhow::bail!("{}: the world blows up in MuJoCo (non-finite positions within {} s)", out.display(), v.seconds);
    }
    if let Some((id, d)) = v.moved.first() {
        anyhow::bail!(
            "{}: {id} moves {d:.3} m in {} s of MuJoCo (limit {} m)",
            out.display(),
            v.seconds,
            shade_sim::export::MAX_MOVE
        );
    }
    Ok(serde_json::to_value(&v)?)
}

#[cfg(not(feature = "mujoco"))]
fn validate(_: &Scene, _: &str, out: &std::path::Path) -> anyhow::Result<serde_json::Value> {
    anyhow::bail!(
        "{}: --validate needs shade-sim built with the `mujoco` feature (see scripts/setup_mujoco.sh)",
        out.display()
    )
}
