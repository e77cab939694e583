//! Speed of the physical check: a 300-frame, 19-capsule walking motion against 20 pieces of
//! furniture (MuJoCo from Python: 3.2–3.9 ms on this machine; a brute-force analytic C checker:
//! 0.84 ms; target ≤ 0.5 ms). Also the full check with the 2 s Rapier stability simulation, the
//! replay in a Rapier world and, with the `mujoco` feature, in MuJoCo; the ratios to our check
//! are printed at the end of the run.
//!
//! Run: `cargo bench --bench check --features mujoco` (after `bash scripts/setup_mujoco.sh`)

use criterion::{Criterion, criterion_group};

mod common;
use common::median;
use glam::DVec2;
use shade_sim::geom::Polyline;
use shade_sim::human::{Body, Motion};
use shade_sim::scene::{Category, FloorPlan, Object, RoomType, Scene};
use shade_sim::sim::{CheckConfig, check_scene};
use std::hint::black_box;

/// An 8 × 8 m room with 20 pieces on a 5 × 4 grid and a walker weaving between them for 300 frames.
fn scene() -> Scene {
    let mut s = Scene::new(
        RoomType::Living,
        FloorPlan { polygon: vec![[0.0, 0.0], [8.0, 0.0], [8.0, 8.0], [0.0, 8.0]], height: 2.8 },
    );
    let cats =
        [Category::DiningChair, Category::CoffeeTable, Category::Cabinet, Category::MultiSeatSofa, Category::Stool];
    for i in 0..20 {
        let (col, row) = (i % 5, i / 5);
        let size = [0.6, 0.5, 0.8];
        s.objects.push(Object {
            id: format!("o{i}"),
            category: cats[i % cats.len()],
            center: [0.8 + col as f64 * 1.6, 1.0 + row as f64 * 2.0, size[2] * 0.5],
            size,
            yaw: 0.3 * i as f64,
        });
    }
    let path = Polyline::new(vec![
        DVec2::new(0.5, 0.4),
        DVec2::new(7.5, 0.4),
        DVec2::new(7.5, 2.0),
        DVec2::new(0.5, 2.0),
        DVec2::new(0.5, 4.0),
    ])
    .expect("a path");
    let mut m = Motion::new(Body::default(), 30.0);
    m.walk(&path, 1.2);
    let mut h = m.into_human("h0");
    h.frames.truncate(300);
    h.actions[0].end = 300;
    s.humans.push(h);
    s
}

fn bench(c: &mut Criterion) {
    let s = scene();
    assert_eq!(s.humans[0].frames.len(), 300);
    assert_eq!(s.humans[0].skeleton.bones.len(), 19);
    let fast = CheckConfig { stability: false, ..CheckConfig::default() };
    c.bench_function("check/300_frames_19_capsules_20_objects", |b| b.iter(|| check_scene(black_box(&s), &fast)));
    c.bench_function("check/with_stability_2s", |b| b.iter(|| check_scene(black_box(&s), &CheckConfig::default())));
    c.bench_function("replay/rapier_world", |b| b.iter(|| shade_sim::sim::rapier_replay(black_box(&s), 0.02)));
    #[cfg(feature = "mujoco")]
    c.bench_function("replay/mujoco", |b| b.iter(|| shade_sim::sim::mujoco_replay(black_box(&s), 0.02)));
}

/// Prints the ratios of the engine replays to our check, measured in the same run.
fn ratios() {
    let s = scene();
    let fast = CheckConfig { stability: false, ..CheckConfig::default() };
    let ours = median(51, || {
        black_box(check_scene(&s, &fast));
    });
    let rapier = median(21, || {
        black_box(shade_sim::sim::rapier_replay(&s, 0.02));
    });
    println!(
        "ratio: rapier world replay / our check = {:.1} ({:.3} ms vs {:.3} ms)",
        rapier / ours,
        rapier * 1e3,
        ours * 1e3
    );
    #[cfg(feature = "mujoco")]
    {
        let mujoco = median(21, || {
            black_box(shade_sim::sim::mujoco_replay(&s, 0.02).expect("the model loads"));
        });
        println!(
            "ratio: mujoco replay / our check = {:.1} ({:.3} ms vs {:.3} ms)",
            mujoco / ours,
            mujoco * 1e3,
            ours * 1e3
        );
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = bench
}
fn main() {
    benches();
    ratios();
    Criterion::default().configure_from_args().final_summary();
}
