//! Speed of the physical check: a 300-frame, 19-capsule walking motion against 20 pieces of
//! furniture (MuJoCo from Python: 3.2–3.9 ms on this machine; a brute-force analytic C checker:
//! 0.84 ms; target ≤ 0.5 ms). Also the full check with the 2 s Rapier stability simulation.
//!
//! Run: `cargo bench --bench check`

use criterion::{Criterion, criterion_group, criterion_main};
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
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(3));
    targets = bench
}
criterion_main!(benches);
