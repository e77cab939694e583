//! `synth`: a whole procedural dataset on disk.
//!
//! Rooms are generated in parallel, each from its own seed stream (so the output does not depend on
//! the number of threads), written as `DIR/{train,val,test}/<room>-<index>.json` (80/10/10 by a
//! seeded shuffle of the indices) and summarised in `DIR/stats.json`. Every file is written
//! atomically. Progress is reported through a callback. With a judge (`synth --require-clean`),
//! a room whose clean version the check fails is drawn again ([`generate_checked_room`]), and
//! each split's stats count the rooms that pass and those drawn again.

use super::layout::Spacing;
use super::rooms::{generate_checked_room, generate_spaced_room};
use super::stats::{DATASET_FORMAT, DatasetStats, SplitStats};
use super::threedfront::{kl_divergence, target_frequencies};
use super::{DataError, Rng};
use crate::physics::Physics;
use crate::scene::{RoomType, write_atomic};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// What to synthesise.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthConfig {
    /// Room type.
    pub room: RoomType,
    /// Number of rooms.
    pub scenes: usize,
    /// Seed.
    pub seed: u64,
    /// How exactly the rules' gaps are kept (exact by default).
    pub spacing: Spacing,
    /// The command line, recorded in `stats.json`.
    pub command: String,
}

/// Draws of one room the check may send back before the last is kept (`synth --require-clean`).
pub const CLEAN_DRAWS: usize = 8;

/// The split of each room index: a seeded shuffle, then 80 % train, 10 % val, 10 % test.
pub fn split_of(scenes: usize, seed: u64) -> Vec<&'static str> {
    let mut order: Vec<usize> = (0..scenes).collect();
    Rng::new(seed ^ 0x5EED_5917).shuffle(&mut order);
    let n_train = (scenes as f64 * 0.8).round() as usize;
    let n_val = (scenes as f64 * 0.1).round() as usize;
    let mut split = vec!["train"; scenes];
    for (rank, &i) in order.iter().enumerate() {
        split[i] = if rank < n_train {
            "train"
        } else if rank < n_train + n_val {
            "val"
        } else {
            "test"
        };
    }
    split
}

/// Generates and writes the dataset; `progress(done)` is called after each room.
///
/// # Errors
/// [`DataError::Io`] when a folder or file cannot be written.
pub fn synthesize(
    cfg: &SynthConfig,
    out: &Path,
    judge: Option<&dyn Physics>,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<DatasetStats, DataError> {
    for s in DatasetStats::SPLITS {
        let dir = out.join(s);
        std::fs::create_dir_all(&dir).map_err(|e| DataError::io(&dir, e))?;
    }
    let split = split_of(cfg.scenes, cfg.seed);
    let done = AtomicUsize::new(0);
    let per_split: Mutex<BTreeMap<String, SplitStats>> = Mutex::new(BTreeMap::new());
    (0..cfg.scenes).into_par_iter().try_for_each(|i| -> Result<(), DataError> {
        let (record, check) = match judge {
            None => (generate_spaced_room(cfg.room, cfg.seed, i as u64, true, cfg.spacing), None),
            Some(judge) => {
                let c = generate_checked_room(cfg.room, cfg.seed, i as u64, true, cfg.spacing, judge, CLEAN_DRAWS);
                (c.record, Some((c.passes, c.draw > 0)))
            }
        };
        let path = out.join(split[i]).join(format!("{}-{i:05}.json", cfg.room));
        write_atomic(&path, record.scene.to_json().as_bytes()).map_err(|e| DataError::io(&path, e))?;
        {
            let mut splits = per_split.lock().expect("no panics while holding the lock");
            let stats = splits.entry(split[i].to_string()).or_default();
            stats.add(&record.scene);
            if let Some((passes, redrawn)) = check {
                stats.add_check(passes, redrawn);
            }
        }
        progress(done.fetch_add(1, Ordering::Relaxed) + 1);
        Ok(())
    })?;
    let mut splits = per_split.into_inner().expect("no panics while holding the lock");
    for s in DatasetStats::SPLITS {
        splits.entry(s.to_string()).or_default();
    }
    let mut result = DatasetStats {
        format: DATASET_FORMAT.to_string(),
        room_type: cfg.room,
        seed: cfg.seed,
        command: cfg.command.clone(),
        raw: true,
        splits,
        category_kl: 0.0,
    };
    result.category_kl = kl_divergence(&target_frequencies(cfg.room), &result.all().frequencies(cfg.room));
    write_stats(&result, out)?;
    Ok(result)
}

/// Writes `DIR/stats.json` atomically.
///
/// # Errors
/// [`DataError::Io`] when it cannot be written.
pub fn write_stats(stats: &DatasetStats, dir: &Path) -> Result<(), DataError> {
    let path = dir.join("stats.json");
    let mut text = serde_json::to_string_pretty(stats).expect("stats serialise");
    text.push('\n');
    write_atomic(&path, text.as_bytes()).map_err(|e| DataError::io(&path, e))
}
