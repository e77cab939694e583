//! `calibrate`: SHADE's calibration over a whole dataset folder, with a report like the paper's
//! Table 2 (E_pen and contact IoU before and after).

use super::calibrate::{SceneCalibration, calibrate_scene};
use super::stats::{DatasetStats, SplitStats};
use super::synth::write_stats;
use super::{DataError, Rng};
use crate::scene::{Action, RoomType, Scene, write_atomic};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A contact human calibration could not fix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Unfixable {
    /// Split and file name (`train/bedroom-00042.json`).
    pub file: String,
    /// Human id.
    pub human: String,
    /// Its action.
    pub action: Action,
    /// Why.
    pub problem: String,
}

/// What `calibration.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationReport {
    /// Room type of the dataset.
    pub room_type: RoomType,
    /// Scenes calibrated.
    pub scenes: usize,
    /// Contact humans seen.
    pub contact_humans: usize,
    /// Contact humans that meet the bounds afterwards.
    pub fixed: usize,
    /// Mean over scenes of the summed E_pen of their contact humans: raw, calibrated.
    pub penetration: [f64; 2],
    /// Mean contact IoU over contact humans: raw, calibrated.
    pub iou: [f64; 2],
    /// Mean contact IoU per action: raw, calibrated.
    pub iou_by_action: BTreeMap<Action, [f64; 2]>,
    /// Humans whose action category augmentation changed.
    pub category_augmented: usize,
    /// The humans left as they were.
    pub unfixable: Vec<Unfixable>,
    /// The command that ran.
    pub command: String,
}

fn scene_files(dir: &Path) -> Result<Vec<PathBuf>, DataError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| DataError::io(dir, e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// Reads `DIR/stats.json`.
///
/// # Errors
/// [`DataError::Stats`] when it is missing or malformed.
pub fn read_stats(dir: &Path) -> Result<DatasetStats, DataError> {
    let path = dir.join("stats.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| DataError::Stats { path: path.clone(), message: format!("cannot read: {e}") })?;
    serde_json::from_str(&text).map_err(|e| DataError::Stats { path, message: e.to_string() })
}

/// Calibrates every scene of the dataset in `src` into `out` (same layout), writes
/// `out/stats.json` and `out/calibration.json`, and returns the report.
///
/// # Errors
/// [`DataError`] for a missing or bad dataset, a bad scene, or a write failure. Files already
/// written stay complete (each is written atomically).
pub fn calibrate_dataset(
    src: &Path,
    out: &Path,
    command: &str,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<CalibrationReport, DataError> {
    let stats = read_stats(src)?;
    let mut jobs: Vec<(&str, PathBuf)> = Vec::new();
    for split in DatasetStats::SPLITS {
        let dir = src.join(split);
        if !dir.is_dir() {
            return Err(DataError::NotADataset { path: dir, message: "missing split folder".into() });
        }
        jobs.extend(scene_files(&dir)?.into_iter().map(|f| (split, f)));
        std::fs::create_dir_all(out.join(split)).map_err(|e| DataError::io(out.join(split), e))?;
    }
    let total = jobs.len();
    let done = AtomicUsize::new(0);
    let results: Vec<(String, &str, SceneCalibration)> = jobs
        .par_iter()
        .enumerate()
        .map(|(i, (split, file))| -> Result<_, DataError> {
            let scene = Scene::load(file)?;
            if scene.room_type != stats.room_type {
                return Err(DataError::NotADataset {
                    path: file.clone(),
                    message: format!("a {} scene in a {} dataset", scene.room_type, stats.room_type),
                });
            }
            let mut rng = Rng::for_item(stats.seed ^ 0xCA11_B8A7, i as u64);
            let cal = calibrate_scene(&scene, &mut rng);
            let name = file.file_name().expect("listed files have names").to_string_lossy().into_owned();
            let target = out.join(split).join(&name);
            write_atomic(&target, cal.scene.to_json().as_bytes()).map_err(|e| DataError::io(&target, e))?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            Ok((format!("{split}/{name}"), *split, cal))
        })
        .collect::<Result<_, _>>()?;

    let mut splits: BTreeMap<String, SplitStats> = BTreeMap::new();
    let (mut pen, mut iou, mut n_humans, mut fixed, mut augmented) = ([0.0; 2], [0.0; 2], 0usize, 0usize, 0usize);
    let mut by_action: BTreeMap<Action, ([f64; 2], usize)> = BTreeMap::new();
    let mut unfixable = Vec::new();
    for (file, split, cal) in &results {
        splits.entry(split.to_string()).or_default().add(&cal.scene);
        for h in &cal.humans {
            n_humans += 1;
            fixed += h.fixed as usize;
            augmented += (h.action != h.action_before) as usize;
            for k in 0..2 {
                pen[k] += h.penetration[k];
                iou[k] += h.iou[k];
            }
            let e = by_action.entry(h.action).or_insert(([0.0; 2], 0));
            e.0[0] += h.iou[0];
            e.0[1] += h.iou[1];
            e.1 += 1;
            if !h.fixed {
                unfixable.push(Unfixable {
                    file: file.clone(),
                    human: h.human.clone(),
                    action: h.action,
                    problem: h.problem.clone().unwrap_or_default(),
                });
            }
        }
    }
    let scenes = results.len().max(1) as f64;
    let humans = n_humans.max(1) as f64;
    let report = CalibrationReport {
        room_type: stats.room_type,
        scenes: results.len(),
        contact_humans: n_humans,
        fixed,
        penetration: pen.map(|p| p / scenes),
        iou: iou.map(|x| x / humans),
        iou_by_action: by_action.into_iter().map(|(a, (s, n))| (a, s.map(|x| x / n as f64))).collect(),
        category_augmented: augmented,
        unfixable,
        command: command.to_string(),
    };
    for s in DatasetStats::SPLITS {
        splits.entry(s.to_string()).or_default();
    }
    let out_stats = DatasetStats { raw: false, splits, command: format!("{}; {command}", stats.command), ..stats };
    write_stats(&out_stats, out)?;
    let path = out.join("calibration.json");
    let mut text = serde_json::to_string_pretty(&report).expect("reports serialise");
    text.push('\n');
    write_atomic(&path, text.as_bytes()).map_err(|e| DataError::io(&path, e))?;
    Ok(report)
}
