//! Conditioning and rasterisation cost per scene: the free-space mask, the floor mask, contact
//! boxes and all conditioning of each example scene; the footprints of 12 objects; 3D IoU of all
//! pairs of 21 objects. (The largest inputs validation accepts are `benches/largest_inputs.rs`'.)
//!
//! Run: `cargo bench --bench raster`

use criterion::{Criterion, criterion_group, criterion_main};
use glam::{DVec2, DVec3};
use shade_sim::geom::{Mask, OBox, RoomWindow, iou_3d};
use shade_sim::human::{Conditions, contact_boxes, free_space_mask};
use std::hint::black_box;

mod common;

fn boxes(n: usize) -> Vec<OBox> {
    (0..n)
        .map(|i| {
            let t = i as f64;
            OBox::new(
                DVec3::new((t * 0.77).sin() * 2.0, (t * 1.31).cos() * 2.0, 0.4),
                DVec3::new(0.5 + (t * 0.3).sin().abs(), 0.4 + (t * 0.7).cos().abs(), 0.8),
                t * 0.5,
            )
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let scenes = common::named_scenes("scenes/examples");
    let (name, scene) = &scenes[0];
    let polygon = scene.floor_plan.polygon();
    let window = RoomWindow::around(scene.room_type.window_side(), &polygon);
    c.bench_function(&format!("free_space_mask/{name}"), |b| b.iter(|| free_space_mask(black_box(scene), &window)));
    c.bench_function(&format!("floor_mask/{name}"), |b| b.iter(|| Mask::of_polygon(&window, black_box(&polygon))));
    c.bench_function(&format!("contact_boxes/{name}"), |b| {
        b.iter(|| scene.humans.iter().map(|h| contact_boxes(black_box(h)).len()).sum::<usize>())
    });
    for (name, scene) in &scenes {
        c.bench_function(&format!("conditions/{name}"), |b| b.iter(|| Conditions::of(black_box(scene))));
    }
    let objects = boxes(12);
    let w = RoomWindow { center: DVec2::ZERO, side: 6.2 };
    c.bench_function("footprints/12_objects", |b| {
        b.iter(|| {
            let mut m = Mask::new();
            for o in &objects {
                m.fill_footprint(&w, black_box(o));
            }
            m
        })
    });
    let objects = boxes(21);
    c.bench_function("iou_3d/21_objects_all_pairs", |b| {
        b.iter(|| {
            let mut s = 0.0;
            for i in 0..objects.len() {
                for j in i + 1..objects.len() {
                    s += iou_3d(black_box(&objects[i]), &objects[j]);
                }
            }
            s
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
