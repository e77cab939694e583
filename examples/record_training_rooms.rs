//! Records in a model folder trained before `seen_counts` and `seen_floors` existed what its
//! training rooms have, as `train` now records it: the counts per category
//! (`CheckpointMeta::seen_counts`), so that sampling keeps its layouts to counts the data has, and
//! the floor sizes (`CheckpointMeta::seen_floors`: areas, widths and lengths), so that `generate`
//! names an input's floor unlike any of them; the rest of `config.json` is written as `train`
//! writes it now (fields added since the model was trained, at their defaults, which mean what
//! their absence meant). The data
//! must be the model's own: as many training rooms as `config.json` recorded at training, or
//! nothing is written. (Not its hash: that covers the datasets' `stats.json`, whose commands name
//! this machine's paths and flags, and data made again elsewhere, room for room the same, hashes
//! otherwise.)
//!
//! Run: `cargo run --release --example record_training_rooms -- MODEL_DIR DATA [--extra-data DIR]…
//! [--joint-data DIR]…` (the folders the model's `train` command named).

use anyhow::bail;
use shade_sim::generator::checkpoint::{CONFIG_FILE, read_meta, write_json};
use shade_sim::generator::{TrainOptions, training_rooms};
use std::path::{Path, PathBuf};

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: record_training_rooms MODEL_DIR DATA [--extra-data DIR]… [--joint-data DIR]…";
    let [model, data, rest @ ..] = &args[..] else { bail!(usage) };
    let config = Path::new(model).join(CONFIG_FILE);
    let mut meta = read_meta(Path::new(model))?;
    let mut opts = TrainOptions::new(PathBuf::from(data), PathBuf::from(model), meta.model.clone());
    for pair in rest.chunks(2) {
        match pair {
            [flag, dir] if flag == "--extra-data" => opts.extra_data.push(PathBuf::from(dir)),
            [flag, dir] if flag == "--joint-data" => opts.joint_data.push(PathBuf::from(dir)),
            _ => bail!(usage),
        }
    }
    let rooms = training_rooms(&opts)?;
    if rooms.examples.len() != meta.training.train_scenes {
        bail!(
            "{data}: {} training rooms, but the model was trained on {}",
            rooms.examples.len(),
            meta.training.train_scenes
        );
    }
    meta.seen_counts = Some(rooms.seen_counts());
    meta.seen_floors = Some(rooms.seen_floors());
    write_json(&meta, &config)?;
    println!("{}: counts and floor sizes of {} training rooms recorded", config.display(), rooms.examples.len());
    Ok(())
}
