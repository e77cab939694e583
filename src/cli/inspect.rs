//! `shade-sim inspect SCENE [--json]`: a scene's summary.

use super::output::{print_json, print_text};
use super::{ExitStatus, GlobalArgs};
use clap::Args;
use serde::Serialize;
use shade_sim::scene::{Scene, SceneSummary};
use std::fmt::Write;
use std::path::PathBuf;

#[derive(Debug, Args)]
pub struct InspectArgs {
    /// The scene file (shade-scene/1 JSON).
    pub scene: PathBuf,
}

#[derive(Serialize)]
struct Report<'a> {
    file: &'a str,
    #[serde(flatten)]
    summary: SceneSummary,
}

pub fn run(args: &InspectArgs, global: &GlobalArgs) -> anyhow::Result<ExitStatus> {
    let scene = Scene::load(&args.scene)?;
    let summary = scene.summary();
    let file = args.scene.display().to_string();
    if global.json {
        print_json(&Report { file: &file, summary })?;
    } else {
        print_text(&format_summary(&file, &summary))?;
    }
    Ok(ExitStatus::Success)
}

fn format_summary(file: &str, s: &SceneSummary) -> String {
    let mut t = String::new();
    let f = &s.floor;
    let _ = writeln!(
        t,
        "{file}: {} room, floor {:.2} × {:.2} m ({:.2} m², {} vertices), ceiling {:.2} m",
        s.room_type, f.size[0], f.size[1], f.area, f.vertices, f.height
    );
    let cats: Vec<String> = s.objects_by_category.iter().map(|(c, n)| format!("{c} {n}")).collect();
    let _ = writeln!(t, "objects: {}{}{}", s.objects, if cats.is_empty() { "" } else { "  " }, cats.join(", "));
    let _ = writeln!(t, "humans: {}", s.humans.len());
    for h in &s.humans {
        let spans: Vec<String> = h.actions.iter().map(|(a, s, e)| format!("{a} {s}–{e}")).collect();
        let _ = writeln!(
            t,
            "  {:<6} {:>5} frames {:>6.1} s @ {} fps  {}",
            h.id,
            h.frames,
            h.seconds,
            h.fps,
            spans.join(", ")
        );
    }
    let actions: Vec<String> = s.action_frames.iter().map(|(a, n)| format!("{a} {n}")).collect();
    let _ = writeln!(t, "action frames: {}", if actions.is_empty() { "none".into() } else { actions.join(", ") });
    let [lo, hi] = s.extents;
    let _ = writeln!(
        t,
        "extents: x [{:.2}, {:.2}]  y [{:.2}, {:.2}]  z [{:.2}, {:.2}] m",
        lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]
    );
    t
}
