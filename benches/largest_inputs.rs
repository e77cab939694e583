//! Costs at the largest inputs validation accepts (`SceneLimits::FORMAT`): a floor plan of 256
//! vertices 50 m across, and 32 people of 1,562 frames each (50,000 in all) standing, sitting and
//! lying on one spot. Each command must stay within a few seconds on them; this bench times the
//! work behind the commands: reading and validating, conditioning, the check without its stability
//! run, one guided sample of the shipped bedroom model (all guidance, no repair), and repair.
//!
//! Run: `cargo bench --bench largest_inputs` (`-- largest_motion` for the second input only).

use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec2;
use shade_sim::generator::{Generator, shipped_model};
use shade_sim::human::Conditions;
use shade_sim::pipeline::{LayoutOptions, make_layouts};
use shade_sim::repair::{RepairConfig, repair_scene};
use shade_sim::scene::{ActionSpan, RoomType, Scene, SceneLimits};
use shade_sim::sim::{CheckConfig, SimPhysics, check_scene};
use std::hint::black_box;
use std::path::Path;

mod common;

fn reference_bedroom() -> Scene {
    common::named_scenes("scenes/reference").into_iter().find(|(n, _)| n == "bedroom_rect").unwrap().1
}

/// The reference bedroom in a floor plan of the most vertices validation accepts, 50 m across: a
/// star of alternating radii 24 and 23.5 m around its pieces and people.
fn largest_floor_plan() -> Scene {
    let mut scene = reference_bedroom();
    let (lo, hi) = scene.floor_plan.polygon().bounds();
    let shift = DVec2::splat(25.0) - (lo + hi) * 0.5;
    let n = SceneLimits::FORMAT.max_vertices;
    scene.floor_plan.polygon = (0..n)
        .map(|i| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 24.0 } else { 23.5 };
            [25.0 + r * a.cos(), 25.0 + r * a.sin()]
        })
        .collect();
    for o in &mut scene.objects {
        o.center[0] += shift.x;
        o.center[1] += shift.y;
    }
    for h in &mut scene.humans {
        for p in h.frames.iter_mut().flatten() {
            p[0] += shift.x;
            p[1] += shift.y;
        }
    }
    scene
}

/// The most people and frames validation accepts: the reference bedroom's people repeated to 32,
/// each clip looped to 1,562 frames, all on top of each other; no pieces.
fn largest_motion() -> Scene {
    let mut scene = reference_bedroom();
    let limits = SceneLimits::FORMAT;
    let frames = limits.max_total_frames / limits.max_humans;
    let originals = std::mem::take(&mut scene.humans);
    scene.objects.clear();
    scene.humans = (0..limits.max_humans)
        .map(|k| {
            let mut h = originals[k % originals.len()].clone();
            let n = h.frames.len();
            let spans = std::mem::take(&mut h.actions);
            h.id = format!("h{k}");
            h.frames = (0..frames).map(|f| h.frames[f % n].clone()).collect();
            h.actions = (0..frames.div_ceil(n))
                .flat_map(|round| {
                    spans.iter().map(move |s| ActionSpan { start: s.start + round * n, end: s.end + round * n, ..*s })
                })
                .filter(|s| s.start < frames)
                .map(|s| ActionSpan { end: s.end.min(frames), ..s })
                .collect();
            h
        })
        .collect();
    scene
}

/// `name/read_and_validate` (the scene's JSON text read back) and `name/check_without_stability`
/// (`checked`: the scene the check sees).
fn bench_read_and_check(c: &mut Criterion, name: &str, scene: &Scene, checked: &Scene) {
    let text = scene.to_json();
    let origin = Path::new("largest.json");
    c.bench_function(&format!("{name}/read_and_validate"), |b| {
        b.iter(|| Scene::from_json(black_box(&text), origin).unwrap())
    });
    let cfg = CheckConfig { stability: false, ..CheckConfig::default() };
    c.bench_function(&format!("{name}/check_without_stability"), |b| b.iter(|| check_scene(black_box(checked), &cfg)));
}

fn bench_largest_floor_plan(c: &mut Criterion) {
    let scene = largest_floor_plan();
    bench_read_and_check(c, "largest_floor_plan", &scene, &scene);
    c.bench_function("largest_floor_plan/conditions", |b| b.iter(|| Conditions::of(black_box(&scene))));
}

fn bench_largest_motion(c: &mut Criterion) {
    let input = largest_motion();
    let generator = Generator::new(shipped_model(RoomType::Bedroom).unwrap());
    let opts = LayoutOptions { repair: None, ..LayoutOptions::default() };
    let sample =
        || make_layouts(&generator, std::slice::from_ref(&input), &opts, &mut |_| {}).unwrap().kept[0][0].scene.clone();
    let layout = sample();
    bench_read_and_check(c, "largest_motion", &input, &layout);
    c.bench_function("largest_motion/generate_one_sample", |b| b.iter(sample));
    let config = RepairConfig::default();
    c.bench_function("largest_motion/repair", |b| {
        b.iter(|| repair_scene(&mut black_box(layout.clone()), &config, &SimPhysics))
    });
}

criterion_group! {
    name = floor_plan;
    config = Criterion::default().sample_size(30).measurement_time(std::time::Duration::from_secs(2));
    targets = bench_largest_floor_plan
}
criterion_group! {
    name = motion;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(20));
    targets = bench_largest_motion
}
criterion_main!(floor_plan, motion);
