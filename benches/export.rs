//! Export time per scene: MJCF text, robosuite arena, glb, plan PNG and (feature `mujoco`) the
//! `--validate` run (load + 1,000 MuJoCo steps), on the reference scenes in `scenes/reference/`.
//! Criterion times the formats on one scene; a table of medians for every reference scene is
//! printed at the end of the run.
//!
//! Run: `cargo bench --bench export [--features mujoco]`

use criterion::{Criterion, criterion_group};

mod common;
use common::median;
use shade_sim::export::{MjcfOptions, render_plan, scene_glb, scene_mjcf};
use std::hint::black_box;

const ARENA: MjcfOptions = MjcfOptions { free_furniture: false, keyframes: false, contact_pairs: false };

fn bench(c: &mut Criterion) {
    let scenes = common::named_scenes("scenes/reference");
    let (_, s) = scenes.iter().find(|(n, _)| n == "bedroom_rect").expect("the bedroom reference");
    c.bench_function("export/mjcf", |b| b.iter(|| scene_mjcf(black_box(s), MjcfOptions::default())));
    c.bench_function("export/robosuite_arena", |b| b.iter(|| scene_mjcf(black_box(s), ARENA)));
    c.bench_function("export/glb", |b| b.iter(|| scene_glb(black_box(s))));
    c.bench_function("export/png", |b| b.iter(|| render_plan(black_box(s)).png_bytes()));
}

/// Median milliseconds of each export for every reference scene.
fn table() {
    println!("scene          objects  frames  mjcf ms  arena ms  glb ms  png ms  validate ms");
    for (name, s) in common::named_scenes("scenes/reference") {
        let ms = |f: &mut dyn FnMut()| median(5, f) * 1e3;
        let mjcf = ms(&mut || {
            black_box(scene_mjcf(&s, MjcfOptions::default()));
        });
        let arena = ms(&mut || {
            black_box(scene_mjcf(&s, ARENA));
        });
        let glb = ms(&mut || {
            black_box(scene_glb(&s));
        });
        let png = ms(&mut || {
            black_box(render_plan(&s).png_bytes());
        });
        #[cfg(feature = "mujoco")]
        let validate = {
            let text = scene_mjcf(&s, MjcfOptions::default());
            format!(
                "{:11.1}",
                ms(&mut || {
                    black_box(shade_sim::export::validate_in_mujoco(&s, &text, 1000).expect("loads"));
                })
            )
        };
        #[cfg(not(feature = "mujoco"))]
        let validate = format!("{:>11}", "-");
        let frames = s.humans.iter().map(|h| h.frames.len()).max().unwrap_or(0);
        println!(
            "{name:<14} {:>7} {frames:>7} {mjcf:>8.1} {arena:>9.1} {glb:>7.1} {png:>7.1} {validate}",
            s.objects.len()
        );
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
fn main() {
    benches();
    table();
    Criterion::default().configure_from_args().final_summary();
}
