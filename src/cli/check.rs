//! `shade-sim check SCENE|DIR… [--json] [--tolerance M] [--no-stability]`: physical validation.
//!
//! Exit 0 when every scene is clean, 1 when any has a violation, 2 on bad input. Folders are
//! searched for scene files (not `stats.json` / `calibration.json`) and checked in parallel.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;
use shade_sim::human::{Meeting, people_meeting};
use shade_sim::scene::Scene;
use shade_sim::sim::{CheckConfig, CheckReport, ViolationKind, check_scene};
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Scene files or folders of scene files.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Penetration deeper than this (m) is a violation.
    #[arg(long, default_value_t = 0.02)]
    pub tolerance: f64,
    /// Skip the stability simulation.
    #[arg(long)]
    pub no_stability: bool,
}

#[derive(Serialize)]
struct FileReport {
    file: String,
    #[serde(flatten)]
    report: CheckReport,
    /// The scene's people inside each other (not a violation: no layout causes or mends it).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    people_meeting: Vec<Meeting>,
}

pub fn run(args: &CheckArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    anyhow::ensure!(
        args.tolerance.is_finite() && args.tolerance >= 0.0,
        "--tolerance: must be a non-negative number of metres"
    );
    let mut files = Vec::new();
    for p in &args.paths {
        if p.is_dir() { files.extend(super::eval::scene_files(p)?) } else { files.push(p.clone()) }
    }
    let cfg = CheckConfig { tolerance: args.tolerance, stability: !args.no_stability, ..CheckConfig::default() };
    let bar = super::progress::bar(global, files.len() as u64, "check");
    // Load everything first: bad input fails before any checking.
    let scenes: Vec<Scene> = files.iter().map(Scene::load).collect::<Result<_, _>>()?;
    let reports: Vec<anyhow::Result<FileReport>> = files
        .par_iter()
        .zip(&scenes)
        .map(|(f, s)| {
            let checked = super::guarded(f, || Ok((check_scene(s, &cfg), people_meeting(s, cfg.tolerance))));
            bar.inc(1);
            let (report, people_meeting) = checked?;
            Ok(FileReport { file: f.display().to_string(), report, people_meeting })
        })
        .collect();
    let reports = super::all_or_first_error(reports)?;
    bar.finish_and_clear();
    let dirty = reports.iter().filter(|r| !r.report.is_clean()).count();
    for r in &reports {
        for m in &r.people_meeting {
            tracing::warn!("{}: {m}", r.file);
        }
    }
    if global.json {
        print_json(&reports)?;
    } else if global.quiet == 0 {
        print_text(&summary(&reports, dirty))?;
    }
    Ok(if dirty == 0 { ExitStatus::Success } else { ExitStatus::Found })
}

fn summary(reports: &[FileReport], dirty: usize) -> String {
    let mut t = String::new();
    for r in reports {
        if r.report.is_clean() {
            t.push_str(&format!("{}: clean ({} frames)\n", r.file, r.report.frames));
            continue;
        }
        let counts: Vec<String> = ViolationKind::ALL
            .iter()
            .filter(|&&k| r.report.count(k) > 0)
            .map(|&k| format!("{} {}", k.name(), r.report.count(k)))
            .collect();
        t.push_str(&format!("{}: {} violations ({})\n", r.file, r.report.violations.len(), counts.join(", ")));
        let mut worst: Vec<_> = r.report.violations.iter().collect();
        worst.sort_by(|a, b| b.depth.total_cmp(&a.depth));
        for v in worst.iter().take(5) {
            let who = [v.human.as_deref(), v.bone.as_deref(), v.object.as_deref(), v.other.as_deref()]
                .iter()
                .flatten()
                .copied()
                .collect::<Vec<_>>()
                .join(" / ");
            let when = v.frame.map(|f| format!(" at frame {f}")).unwrap_or_default();
            let depth = if v.depth < 0.0 { "nothing below".to_string() } else { format!("{:.3} m", v.depth) };
            t.push_str(&format!("  {:<15} {who}{when}: {depth}\n", v.kind.name()));
        }
    }
    t.push_str(&format!("{} scenes, {} clean, {} with violations\n", reports.len(), reports.len() - dirty, dirty));
    t
}
