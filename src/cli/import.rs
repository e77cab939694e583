//! `shade-sim import-3dfront-human SRC --out DIR --room R`: the licensed MIME release of 3D-FRONT
//! HUMAN (folders of `boxes.npz`) as a shade-scene/1 dataset.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs, RoomArg};
use clap::Args;
use shade_sim::data::import_dataset;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct ImportArgs {
    /// Folder holding one sub-folder with a `boxes.npz` per room (searched recursively).
    pub src: PathBuf,
    /// Output dataset folder.
    #[arg(long)]
    pub out: PathBuf,
    /// Room type of the rooms (selects the class order).
    #[arg(long, value_enum)]
    pub room: RoomArg,
    /// Ceiling height to give the rooms (not stored in the release), metres.
    #[arg(long, default_value_t = 2.8)]
    pub height: f64,
    /// Seed of the 80/10/10 split.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

pub fn run(args: &ImportArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    anyhow::ensure!(args.height.is_finite() && args.height > 0.0, "--height: must be a positive number of metres");
    let command = format!(
        "shade-sim import-3dfront-human {} --out {} --room {} --height {} --seed {}",
        args.src.display(),
        args.out.display(),
        args.room.name(),
        args.height,
        args.seed
    );
    let stats = import_dataset(&args.src, &args.out, args.room.into(), args.height, args.seed, &command)?;
    if global.json {
        print_json(&stats)?;
    } else if global.quiet == 0 {
        let all = stats.all();
        print_text(&format!(
            "{}: {} {} rooms imported, {} objects, category KL to 3D-FRONT {:.4}\n",
            args.out.display(),
            all.rooms,
            stats.room_type,
            all.category_counts.values().sum::<usize>(),
            stats.category_kl
        ))?;
    }
    Ok(ExitStatus::Success)
}
