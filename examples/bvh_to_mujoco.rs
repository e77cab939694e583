//! From a BVH file to a furnished, checked MuJoCo world with the library: import the clip into a
//! living room, furnish it with the shipped model until a layout passes the check, write the MJCF.
//!
//! Run: `cargo run --release --example bvh_to_mujoco -- [CLIP.bvh] [OUT.xml]`
//! (default: scenes/motion/assimp_boxing.bvh → out/bvh_to_mujoco.xml).

use anyhow::Context;
use glam::DVec2;
use shade_sim::export::{MjcfOptions, scene_mjcf};
use shade_sim::generator::shipped_generator;
use shade_sim::motion::{ImportOptions, Placement, import_motion};
use shade_sim::pipeline::{LayoutOptions, make_layouts};
use shade_sim::scene::{FloorPlan, RoomType};
use std::path::PathBuf;

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let clip = PathBuf::from(args.next().unwrap_or_else(|| "scenes/motion/assimp_boxing.bvh".into()));
    let out = PathBuf::from(args.next().unwrap_or_else(|| "out/bvh_to_mujoco.xml".into()));

    // 1. The clip as a generation input: a 6 × 5 m living room, the clip starting in its middle.
    let floor = FloorPlan { polygon: vec![[0.0, 0.0], [6.0, 0.0], [6.0, 5.0], [0.0, 5.0]], height: 2.8 };
    let mut opts = ImportOptions::new(RoomType::Living, floor);
    opts.places = vec![Some(Placement { at: DVec2::new(3.0, 2.5), yaw_degrees: 0.0 })];
    let (input, reports) = import_motion(std::slice::from_ref(&clip), &opts)?;
    let r = &reports[0];
    println!("{}: {} rig, {:.2} m tall, {} frames", clip.display(), r.rig, r.stature, r.frames.1);

    // 2. Furnished by the shipped living-room model, repaired, resampled until the check passes.
    let generator = shipped_generator(RoomType::Living)?;
    let layouts = make_layouts(
        &generator,
        &[input],
        &LayoutOptions { require_clean: true, ..LayoutOptions::default() },
        &mut |_| {},
    )?;
    let layout = layouts.kept[0].first().context("no layout passed the check in 8 rounds")?;
    println!(
        "{} pieces, clean ({} of {} sampled layouts passed)",
        layout.scene.objects.len(),
        layouts.accepted,
        layouts.sampled
    );

    // 3. The MuJoCo world: furniture bodies, walls, the person as mocap capsules with the motion as keyframes.
    if let Some(dir) = out.parent() {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&out, scene_mjcf(&layout.scene, MjcfOptions::default()))?;
    println!("wrote {}", out.display());
    Ok(())
}
