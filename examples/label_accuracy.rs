//! How often the automatic action labels (`shade_sim::motion::label_frames`) agree with the
//! labels of scenes that have them: per action and overall, over every labelled frame of every
//! human in the given folders.
//!
//! Run: `cargo run --release --example label_accuracy -- DIR…` (e.g. a dataset's val split).

use shade_sim::motion::{LabelConfig, body_frames, label_frames, measured_stature};
use shade_sim::scene::{Action, Scene};
use std::collections::BTreeMap;

fn main() -> anyhow::Result<()> {
    let mut confusion: BTreeMap<(Action, Action), usize> = BTreeMap::new();
    let cfg = LabelConfig::default();
    for dir in std::env::args().skip(1) {
        let mut files: Vec<_> = std::fs::read_dir(&dir)?.filter_map(|e| e.ok().map(|e| e.path())).collect();
        files.retain(|f| f.extension().is_some_and(|e| e == "json"));
        files.sort();
        for file in files {
            let Ok(scene) = Scene::load(&file) else { continue };
            for human in &scene.humans {
                let Some(frames) = body_frames(human) else { continue };
                let labels = label_frames(&frames, human.fps, measured_stature(&frames), &cfg);
                for span in &human.actions {
                    for &label in labels.iter().take(span.end).skip(span.start) {
                        *confusion.entry((span.action, label)).or_default() += 1;
                    }
                }
            }
        }
    }
    let total: usize = confusion.values().sum();
    let right: usize = confusion.iter().filter(|((a, b), _)| a == b).map(|(_, n)| n).sum();
    println!("frames {total}, agreeing {:.2} %", 100.0 * right as f64 / total.max(1) as f64);
    for ((truth, label), n) in &confusion {
        println!("  {:>5} labelled {:>5}: {n}", truth.name(), label.name());
    }
    Ok(())
}
