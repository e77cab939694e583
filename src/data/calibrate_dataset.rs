//! `calibrate`: SHADE's calibration over a whole dataset folder, with a report like the paper's
//! Table 2 (E_pen and contact IoU before and after).
//!
//! With a judge (`calibrate --require-clean`), each human's placement is checked with them alone in
//! the room (`calibrate_scene`), and a scene the check still fails is calibrated again — with
//! fresh augmentation draws ([`CALIBRATION_DRAWS`] in all), then without the augmentations and
//! without the contact people the check fails wherever calibration puts them or who are inside
//! someone placed before them (left out, marked in `calibration.json`) — and the first that passes
//! the check with no two people inside each other is kept (the first draw when none does); each
//! split's stats count the scenes that pass and those calibrated again, and `calibration.json`
//! lists the ones that still fail.

use super::calibrate::{MAX_POINT_DEPTH, SceneCalibration, calibrate_scene, passes_alone};
use super::stats::{DatasetStats, SplitStats};
use super::synth::write_stats;
use super::{DataError, Rng};
use crate::human::{meets_anyone, people_meeting};
use crate::physics::Physics;
use crate::scene::{Action, Human, RoomType, Scene, write_atomic};
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
    /// With `--require-clean`: the scenes (`split/file`) the check still fails.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failing_check: Option<Vec<String>>,
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
/// `out/stats.json` and `out/calibration.json`, and returns the report. `people_apart` keeps the
/// people out of each other (`calibrate_scene`; with a judge, a scene is also clean only with no
/// two people inside each other): false reproduces the calibration before 2026-11-26.
///
/// # Errors
/// [`DataError`] for a missing or bad dataset, a bad scene, or a write failure. Files already
/// written stay complete (each is written atomically).
pub fn calibrate_dataset(
    src: &Path,
    out: &Path,
    command: &str,
    judge: Option<&dyn Physics>,
    people_apart: bool,
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
    let results: Vec<(String, &str, SceneCalibration, Option<Verdict>)> = jobs
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
            let (cal, check) = calibrate_checked(&scene, stats.seed, i as u64, judge, people_apart);
            let name = file.file_name().expect("listed files have names").to_string_lossy().into_owned();
            let target = out.join(split).join(&name);
            write_atomic(&target, cal.scene.to_json().as_bytes()).map_err(|e| DataError::io(&target, e))?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1, total);
            Ok((format!("{split}/{name}"), *split, cal, check))
        })
        .collect::<Result<_, _>>()?;

    let mut splits: BTreeMap<String, SplitStats> = BTreeMap::new();
    let (mut pen, mut iou, mut n_humans, mut fixed, mut augmented) = ([0.0; 2], [0.0; 2], 0usize, 0usize, 0usize);
    let mut by_action: BTreeMap<Action, ([f64; 2], usize)> = BTreeMap::new();
    let mut unfixable = Vec::new();
    let mut failing = judge.map(|_| Vec::new());
    for (file, split, cal, check) in &results {
        let split_stats = splits.entry(split.to_string()).or_default();
        split_stats.add(&cal.scene);
        if let Some(Verdict { passes, again }) = *check {
            split_stats.add_check(passes, again);
            if !passes {
                failing.get_or_insert_with(Vec::new).push(file.clone());
            }
        }
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
        failing_check: failing,
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

/// Draws of a scene's calibration the check may send back (`calibrate --require-clean`): this many
/// with augmentation (the first is the unchecked calibration's), then one without.
pub const CALIBRATION_DRAWS: u64 = 4;

/// What the check said of a scene's checked calibration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Verdict {
    /// The kept calibration passes the check.
    passes: bool,
    /// The scene was calibrated more than once.
    again: bool,
}

/// Calibration of scene `index` of a dataset seeded `seed`; with a `judge`, drawn again while the
/// check fails it (see the module's header). Returns it and, with a judge, the check's verdict.
fn calibrate_checked(
    scene: &Scene,
    seed: u64,
    index: u64,
    judge: Option<&dyn Physics>,
    people_apart: bool,
) -> (SceneCalibration, Option<Verdict>) {
    let draw = |k: u64, augment: bool| {
        let mut rng = Rng::for_item(seed ^ 0xCA11_B8A7 ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15), index);
        calibrate_scene(scene, &mut rng, augment, judge, people_apart)
    };
    let first = draw(0, true);
    let Some(judge) = judge else { return (first, None) };
    // Each human's placement was checked alone; the scene is checked whole (people near each
    // other, furniture the replay pushes), and no two people may be inside each other.
    let clean = |s: &Scene| judge.passes_check(s) && (!people_apart || people_meeting(s, MAX_POINT_DEPTH).is_empty());
    if clean(&first.scene) {
        return (first, Some(Verdict { passes: true, again: false }));
    }
    let plain = || {
        let mut cal = draw(CALIBRATION_DRAWS, false);
        let mut unplaced: Vec<String> = cal
            .humans
            .iter()
            .filter_map(|r| cal.scene.humans.iter().find(|h| h.id == r.human))
            .filter(|h| !passes_alone(&cal.scene, h, judge))
            .map(|h| h.id.clone())
            .collect();
        // And a contact person inside someone kept before them.
        let mut kept: Vec<&Human> = Vec::new();
        for h in &cal.scene.humans {
            if unplaced.contains(&h.id) {
                continue;
            }
            let contact = cal.humans.iter().any(|r| r.human == h.id);
            if people_apart && contact && meets_anyone(h, kept.iter().copied(), MAX_POINT_DEPTH) {
                unplaced.push(h.id.clone());
            } else {
                kept.push(h);
            }
        }
        cal.scene.humans.retain(|h| !unplaced.contains(&h.id));
        for r in cal.humans.iter_mut().filter(|r| unplaced.contains(&r.human)) {
            r.left_out = true;
            r.fixed = false;
            r.problem = Some(
                "left out: the check fails them wherever calibration puts them, or they are inside someone".into(),
            );
        }
        cal
    };
    let again = (1..CALIBRATION_DRAWS).map(|k| draw(k, true)).chain(std::iter::once_with(plain));
    for cal in again {
        if clean(&cal.scene) {
            return (cal, Some(Verdict { passes: true, again: true }));
        }
    }
    (first, Some(Verdict { passes: false, again: true }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::physics::testing::FailFirst;

    #[test]
    fn a_calibration_the_check_fails_is_drawn_again_then_made_without_augmentation() {
        let scene = generate_room(RoomType::Living, 3, 5, true).scene;
        assert!(scene.humans.len() >= 2);
        let (unchecked, none) = calibrate_checked(&scene, 3, 5, None, true);
        assert_eq!(none, None);
        let (passing, check) = calibrate_checked(&scene, 3, 5, Some(&FailFirst::rooms(0)), true);
        assert_eq!((passing, check), (unchecked.clone(), Some(Verdict { passes: true, again: false })));
        // Every augmented draw refused: the one without augmentation, which augments nobody.
        let (plain, check) = calibrate_checked(&scene, 3, 5, Some(&FailFirst::rooms(CALIBRATION_DRAWS as usize)), true);
        assert_eq!(check, Some(Verdict { passes: true, again: true }));
        assert!(plain.humans.iter().all(|h| h.action == h.action_before));
        assert_eq!(
            plain,
            calibrate_scene(&scene, &mut Rng::new(0), false, Some(&FailFirst::rooms(0)), true),
            "no draws without augmentation"
        );
        // Nothing passes: the first draw, said to fail.
        let (kept, check) = calibrate_checked(&scene, 3, 5, Some(&FailFirst::rooms(100)), true);
        assert_eq!((kept, check), (unchecked, Some(Verdict { passes: false, again: true })));
    }
}
