//! Renders a few procedural rooms (top and side views with furniture and people) to look at.
//!
//! Run: `cargo run --release --example synth_gallery -- bedroom 6 out/gallery`

use shade_sim::data::generate_room;
use shade_sim::export::render_humans;
use shade_sim::scene::RoomType;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let room = match args.get(1).map(String::as_str).unwrap_or("bedroom") {
        "living" => RoomType::Living,
        "dining" => RoomType::Dining,
        _ => RoomType::Bedroom,
    };
    let n: u64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(6);
    let dir = std::path::PathBuf::from(args.get(3).cloned().unwrap_or_else(|| "out/gallery".into()));
    std::fs::create_dir_all(&dir)?;
    for i in 0..n {
        let raw = args.get(4).is_some_and(|s| s == "raw");
        let record = generate_room(room, 1, i, raw);
        let path = dir.join(format!("{room}-{i}.png"));
        render_humans(&record.scene).save_png(&path)?;
        let cats: Vec<String> = record.scene.objects.iter().map(|o| o.category.to_string()).collect();
        println!("{} objects={} humans={} {:?}", path.display(), cats.len(), record.scene.humans.len(), cats);
    }
    Ok(())
}
