//! `shade-sim calibrate --data DIR --out DIR [--require-clean]`: SHADE's calibration of a
//! procedural (or imported) dataset, with a Table-2-style report on stdout and in
//! `OUT/calibration.json`.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use clap::Args;
use shade_sim::data::{CalibrationReport, calibrate_dataset};
use shade_sim::physics::Physics;
use shade_sim::sim::SimPhysics;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// The raw dataset (with stats.json and train/val/test).
    #[arg(long)]
    pub data: PathBuf,
    /// Where the calibrated dataset goes.
    #[arg(long)]
    pub out: PathBuf,
    /// Calibrate a scene again (fresh augmentation draws, then none) while `check` fails it;
    /// stats.json counts the scenes that pass, calibration.json lists those that still fail.
    #[arg(long)]
    pub require_clean: bool,
    /// Let the augmentations put people inside each other, as calibration did before 2026-11-26
    /// (the data of the shipped models trained before then; models/MODEL_CARD.md says which).
    #[arg(long)]
    pub people_may_overlap: bool,
}

pub fn run(args: &CalibrateArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    anyhow::ensure!(
        args.data.canonicalize().ok() != args.out.canonicalize().ok() || !args.out.exists(),
        "{}: --out must differ from --data",
        args.out.display()
    );
    let command = format!(
        "shade-sim calibrate --data {} --out {}{}",
        args.data.display(),
        args.out.display(),
        if args.require_clean { " --require-clean" } else { "" }
    ) + if args.people_may_overlap { " --people-may-overlap" } else { "" };
    let judge = args.require_clean.then_some(&SimPhysics as &dyn Physics);
    let bar = super::progress::bar(global, 0, "calibrate");
    let report =
        calibrate_dataset(&args.data, &args.out, &command, judge, !args.people_may_overlap, &|done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
        })?;
    bar.finish_and_clear();
    if global.json {
        print_json(&report)?;
    } else if global.quiet == 0 {
        print_text(&table(&report))?;
    }
    Ok(ExitStatus::Success)
}

pub fn table(r: &CalibrationReport) -> String {
    let ratio = r.penetration[0] / r.penetration[1].max(1e-9);
    let mut t = String::new();
    t.push_str(
        "room      scenes  contact humans  fixed   E_pen raw → calibrated        contact IoU raw → calibrated\n",
    );
    t.push_str(&format!(
        "{:<9} {:>6}  {:>14}  {:>5}   {:>7.2} → {:<6.2} ({:>5.1}× less)   {:.3} → {:.3}\n",
        r.room_type.name(),
        r.scenes,
        r.contact_humans,
        r.fixed,
        r.penetration[0],
        r.penetration[1],
        ratio,
        r.iou[0],
        r.iou[1]
    ));
    for (a, v) in &r.iou_by_action {
        t.push_str(&format!("  {:<6} contact IoU {:.3} → {:.3}\n", a.name(), v[0], v[1]));
    }
    t.push_str(&format!(
        "{} humans changed action (category augmentation); {} could not be fixed (see calibration.json)\n",
        r.category_augmented,
        r.unfixable.len()
    ));
    if let Some(failing) = &r.failing_check {
        t.push_str(&format!(
            "check: {} of {} calibrated scenes pass ({} still fail, listed in calibration.json)\n",
            r.scenes - failing.len(),
            r.scenes,
            failing.len()
        ));
    }
    t
}
