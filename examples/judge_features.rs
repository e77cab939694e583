//! Which of the judge's features tell a folder of generated scenes from a reference folder: for
//! every value of [`layout_features`] (at the judge's resolution), the rank AUC between the two
//! sets (0.5: the feature alone cannot tell them apart; 0 or 1: it always can), the features
//! sorted by |AUC − 0.5|, with each set's median. SCA is the judge's verdict on all of them
//! together; this says where it comes from. It judges nothing itself.
//!
//! Run: `cargo run --release --example judge_features -- GENERATED REFERENCE [TOP]` (folders of
//! scene files, the same room type; TOP features printed, default 20).

use shade_sim::eval::{ScaConfig, layout_feature_names, layout_features, rank_auc};
use shade_sim::scene::Scene;
use std::path::Path;

fn scenes(dir: &Path) -> anyhow::Result<Vec<Scene>> {
    Ok(Scene::files_in(dir)?.iter().map(Scene::load).collect::<Result<_, _>>()?)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    anyhow::ensure!(args.len() >= 2, "usage: judge_features GENERATED REFERENCE [TOP]");
    let top: usize = args.get(2).map(|t| t.parse()).transpose()?.unwrap_or(20);
    let (generated, reference) = (scenes(Path::new(&args[0]))?, scenes(Path::new(&args[1]))?);
    let room = reference.first().ok_or_else(|| anyhow::anyhow!("{}: no scenes", args[1]))?.room_type;
    let cfg = ScaConfig::default();
    let features = |set: &[Scene]| -> Vec<Vec<f32>> {
        set.iter().map(|s| layout_features(s, cfg.resolution, cfg.share_resolution)).collect()
    };
    let (g, r) = (features(&generated), features(&reference));
    let names = layout_feature_names(room);
    let column = |set: &[Vec<f32>], k: usize| -> Vec<f64> { set.iter().map(|f| f64::from(f[k])).collect() };
    let mut rows: Vec<(f64, &str, f64, f64)> = (0..names.len())
        .map(|k| {
            let (a, b) = (column(&g, k), column(&r, k));
            (rank_auc(&a, &b), names[k].as_str(), median(a), median(b))
        })
        .collect();
    rows.sort_by(|x, y| (y.0 - 0.5).abs().total_cmp(&(x.0 - 0.5).abs()));
    println!("{} generated, {} reference {room:?} rooms; AUC of generated > reference", g.len(), r.len());
    println!("{:<28} {:>6} {:>10} {:>10}", "feature", "AUC", "generated", "reference");
    for (a, name, mg, mr) in rows.iter().take(top) {
        println!("{name:<28} {a:>6.3} {mg:>10.3} {mr:>10.3}");
    }
    Ok(())
}
