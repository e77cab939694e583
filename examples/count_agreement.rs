//! How closely a count-conditioned model's layouts keep to the counts they were conditioned on:
//! for each input, the counts `generate` drew for its first sample (`Generator::counts_of`)
//! against the pieces per category in that sample as written.
//!
//! Run: `cargo run --release --example count_agreement -- MODEL_DIR INPUT_DIR GENERATED_DIR SEED`
//! (`generate --input INPUT_DIR --out GENERATED_DIR --seed SEED --model MODEL_DIR`, one room type).

use anyhow::Context;
use shade_sim::generator::{Checkpoint, Generator};
use shade_sim::scene::Scene;
use std::path::{Path, PathBuf};

fn json_files(dir: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)?.filter_map(|e| e.ok().map(|e| e.path())).collect();
    files.retain(|f| f.extension().is_some_and(|e| e == "json"));
    files.sort();
    Ok(files)
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [model, inputs, generated, seed] = &args[..] else {
        anyhow::bail!("usage: count_agreement MODEL_DIR INPUT_DIR GENERATED_DIR SEED");
    };
    let checkpoint = Checkpoint::load(Path::new(model))?;
    let generator = Generator::new(checkpoint);
    let seed: u64 = seed.parse().context("SEED")?;
    let (mut rooms, mut exact, mut pieces_off, mut drawn_pieces, mut made_pieces) = (0, 0, 0usize, 0usize, 0usize);
    for (i, file) in json_files(Path::new(inputs))?.iter().enumerate() {
        let input = Scene::load(file)?;
        let drawn = generator.counts_of(&input, i, 0, seed)?.context("the model has no count conditioning")?;
        let stem = file.file_stem().and_then(|s| s.to_str()).context("file name")?;
        let out = Scene::load(Path::new(generated).join(format!("{stem}_0.json")))?;
        let made = out.room_type.category_counts(&out.objects);
        let off: usize = drawn.iter().zip(&made).map(|(&d, &m)| (d as usize).abs_diff(m)).sum();
        rooms += 1;
        exact += usize::from(off == 0);
        pieces_off += off;
        drawn_pieces += drawn.iter().map(|&d| d as usize).sum::<usize>();
        made_pieces += made.iter().sum::<usize>();
    }
    println!(
        "{rooms} rooms: {:.1} % with every count as drawn; {:.2} pieces off per room; {:.2} pieces drawn, {:.2} made",
        100.0 * exact as f64 / rooms.max(1) as f64,
        pieces_off as f64 / rooms.max(1) as f64,
        drawn_pieces as f64 / rooms.max(1) as f64,
        made_pieces as f64 / rooms.max(1) as f64,
    );
    Ok(())
}
