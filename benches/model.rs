//! Speed of the SHADE denoiser (the shipped bedroom model's weights) against the same architecture
//! in PyTorch on the CPU (benches/reference/dit_reference.py): 200-step DDPM sampling of a batch of
//! 16 bedrooms, and one training step (forward, backward, AdamW) at the training batch of 32, on
//! the hand-written engine and through candle. Both sides use every core. Ratios (PyTorch time /
//! ours; > 1 means we are faster) are printed at the end of the run when the reference is
//! installed; they compare the fastest of several runs on each side (the machine is shared: other
//! work only ever slows a run down, and medians caught it in one side and not the other).
//!
//! Run: `bash benches/reference/setup.sh` once, then `cargo bench --bench model`.

use candle_core::{DType, Device, Tensor};
use criterion::{Criterion, criterion_group};

mod common;
use common::fastest;
use shade_sim::data::Rng;
use shade_sim::generator::{
    AdamW, AdamWConfig, Bounds, Chain, CondTensors, Denoiser, Engine, FastDenoiser, Features, Gradients, Guidance,
    GuidanceConfig, HostBatch, ModelConfig, NoisyBatch, ParamLayout, Params, Projection, Schedule, SpatialGuidance,
    empty_projection_steps, sample, tokens,
};
use shade_sim::scene::RoomType;
use shade_sim::scene::Scene;
use std::hint::black_box;
use std::path::Path;

const SAMPLE_BATCH: usize = 16;
const TRAIN_BATCH: usize = 32;

fn random(shape: &[usize], rng: &mut Rng) -> Tensor {
    let n = shape.iter().product();
    Tensor::from_vec((0..n).map(|_| rng.normal() as f32).collect::<Vec<_>>(), shape, &Device::Cpu).unwrap()
}

/// Random conditions like the reference's: 3 of 8 contact boxes real.
fn conditions(cfg: &ModelConfig, b: usize, rng: &mut Rng) -> CondTensors {
    let k = cfg.max_contacts;
    let mask: Vec<f32> = (0..b * k).map(|i| if i % k < 3 { 1.0 } else { 0.0 }).collect();
    CondTensors {
        contacts: random(&[b, k, 11], rng),
        contact_mask: Tensor::from_vec(mask, (b, k), &Device::Cpu).unwrap(),
        floor: random(&[b, cfg.floor_points, 4], rng),
        free: random(&[b, cfg.free_points, 3], rng),
        room: Tensor::from_vec([1.0f32, 0.0, 0.0].repeat(b), (b, 3), &Device::Cpu).unwrap(),
        counts: random(&[b, cfg.count_width()], rng),
    }
}

struct Setup {
    cfg: ModelConfig,
    /// The shipped bedroom model's weights (trained: real modulations; speed is the same).
    shipped: Denoiser,
    layout: ParamLayout,
    params: Vec<f32>,
    schedule: Schedule,
    /// Every step (DDPM's chain).
    chain: Chain,
}

fn setup() -> Setup {
    shade_sim::tune_allocator_for_tensors();
    let cfg = ModelConfig::small(RoomType::Bedroom);
    let mut init = Params::random(0);
    Denoiser::new(&cfg, &mut init).unwrap();
    let (layout, params) = ParamLayout::of(&init.snapshot().unwrap()).unwrap();
    let shipped = shade_sim::generator::shipped_model(RoomType::Bedroom).unwrap().denoiser;
    let schedule = Schedule::linear(cfg.diffusion_steps);
    let chain = Chain::full(&schedule);
    Setup { schedule, chain, cfg, layout, params, shipped }
}

/// A training run's state: an engine, the parameters and the optimiser.
struct Trainer {
    engine: Gradients,
    params: Vec<f32>,
    adam: AdamW,
}

impl Trainer {
    fn new(s: &Setup, engine: Engine) -> Trainer {
        Trainer {
            engine: Gradients::new(engine, &s.cfg, &s.layout).unwrap(),
            params: s.params.clone(),
            adam: AdamW::new(s.layout.len(), AdamWConfig::default()),
        }
    }
}

fn sample_once(s: &Setup, rng: &mut Rng) {
    let cond = conditions(&s.cfg, SAMPLE_BATCH, rng);
    let seeds: Vec<u64> = (0..SAMPLE_BATCH as u64).collect();
    let projection = empty_projection_steps(&s.schedule);
    black_box(
        sample(&s.shipped, &s.schedule, &s.chain, &cond, &seeds, &Projection::empty_slots(projection), None).unwrap(),
    );
}

/// A random training batch like the reference's: random tokens and conditions, every weight 1.
fn train_batch(s: &Setup, rng: &mut Rng) -> NoisyBatch {
    let cond = conditions(&s.cfg, TRAIN_BATCH, rng);
    let host_values = |t: &Tensor| t.flatten_all().unwrap().to_vec1::<f32>().unwrap();
    let (contacts, mask, floor, free) = (
        host_values(&cond.contacts),
        host_values(&cond.contact_mask),
        host_values(&cond.floor),
        host_values(&cond.free),
    );
    let mut host = HostBatch::default();
    let per = |v: &[f32]| v.len() / TRAIN_BATCH;
    for i in 0..TRAIN_BATCH {
        let part = |v: &[f32]| v[i * per(v)..(i + 1) * per(v)].to_vec();
        host.push_features(&Features {
            contacts: part(&contacts),
            contact_mask: part(&mask),
            floor: part(&floor),
            free: part(&free),
            room: vec![1.0, 0.0, 0.0],
            counts: Vec::new(),
        });
    }
    let per_item = s.cfg.slots() * s.cfg.token_dim();
    host.tokens = (0..TRAIN_BATCH * per_item).map(|_| rng.normal() as f32).collect();
    host.weights = vec![1.0; TRAIN_BATCH * per_item];
    NoisyBatch::draw(host, &s.schedule, rng, &s.cfg)
}

fn train_once(s: &Setup, trainer: &mut Trainer, rng: &mut Rng) {
    let batch = train_batch(s, rng);
    let (_, grads) = trainer.engine.loss_and_grad(&trainer.params, &batch).unwrap();
    trainer.adam.step(&mut trainer.params, &grads, 3e-4);
}

/// 16 procedural bedrooms and their tokens, jittered by 0.05 so objects overlap walls, paths and
/// each other the way a denoiser's estimate does.
fn guidance_batch(cfg: &ModelConfig) -> (Vec<Scene>, Bounds, Tensor) {
    let scenes: Vec<Scene> = (0..SAMPLE_BATCH as u64)
        .map(|i| shade_sim::data::generate_room(RoomType::Bedroom, 9, i, false).scene)
        .collect();
    let mut stats = shade_sim::data::SplitStats::default();
    scenes.iter().for_each(|s| stats.add(s));
    let bounds = Bounds::from_stats(&stats);
    let mut rng = Rng::new(3);
    let mut all = Vec::new();
    for s in &scenes {
        let window = s.room_window();
        let (t, _) = tokens::encode(s, window.center, &[], &bounds, cfg);
        all.extend(t.into_iter().map(|v| v + 0.05 * rng.normal() as f32));
    }
    let x0 = Tensor::from_vec(all, (SAMPLE_BATCH, cfg.slots(), cfg.token_dim()), &Device::Cpu).unwrap();
    (scenes, bounds, x0)
}

fn bench(c: &mut Criterion) {
    let s = setup();
    let mut rng = Rng::new(1);
    c.bench_function("sample 16 bedrooms, 200 steps", |b| b.iter(|| sample_once(&s, &mut rng)));
    let mut fused = Trainer::new(&s, Engine::Fused);
    c.bench_function("train step, batch 32 (fused)", |b| b.iter(|| train_once(&s, &mut fused, &mut rng)));
    let mut candle = Trainer::new(&s, Engine::Candle);
    c.bench_function("train step, batch 32 (candle)", |b| b.iter(|| train_once(&s, &mut candle, &mut rng)));
    let cond = conditions(&s.cfg, SAMPLE_BATCH, &mut rng);
    let x = random(&[SAMPLE_BATCH, s.cfg.slots(), s.cfg.token_dim()], &mut rng);
    let t = vec![50; SAMPLE_BATCH];
    c.bench_function("denoiser forward (candle), batch 16", |b| {
        b.iter(|| black_box(s.shipped.forward(&x, &t, &cond).unwrap()))
    });
    let fast = FastDenoiser::of(&s.shipped).unwrap();
    let mut prepared = fast.prepare(&cond).unwrap();
    let xs = x.flatten_all().unwrap().to_vec1::<f32>().unwrap();
    c.bench_function("denoiser forward (sampling path), batch 16", |b| {
        b.iter(|| black_box(fast.forward(&mut prepared, &xs, 50)))
    });
    let (scenes, bounds, x0) = guidance_batch(&s.cfg);
    let refs: Vec<&Scene> = scenes.iter().collect();
    let mut g = SpatialGuidance::new(GuidanceConfig::all(), &s.cfg, &bounds, &refs);
    c.bench_function("guidance J_m + J_b + J_o, batch 16", |b| b.iter(|| black_box(g.guide(&x0, 0).unwrap())));
}

fn ratios() {
    let s = setup();
    let mut rng = Rng::new(2);
    let sampling = fastest(5, || sample_once(&s, &mut rng));
    let mut fused = Trainer::new(&s, Engine::Fused);
    let step = fastest(5, || (0..10).for_each(|_| train_once(&s, &mut fused, &mut rng))) / 10.0;
    let mut candle = Trainer::new(&s, Engine::Candle);
    let candle_step = fastest(3, || (0..5).for_each(|_| train_once(&s, &mut candle, &mut rng))) / 5.0;
    println!("ours: {} parameters, DType {:?}", s.layout.len(), DType::F32);
    let cond = conditions(&s.cfg, SAMPLE_BATCH, &mut rng);
    let x = random(&[SAMPLE_BATCH, s.cfg.slots(), s.cfg.token_dim()], &mut rng);
    let candle_forward = fastest(21, || {
        black_box(s.shipped.forward(&x, &[50; SAMPLE_BATCH], &cond).unwrap());
    });
    let fast = FastDenoiser::of(&s.shipped).unwrap();
    let mut prepared = fast.prepare(&cond).unwrap();
    let xs = x.flatten_all().unwrap().to_vec1::<f32>().unwrap();
    let forward = fastest(21, || {
        black_box(fast.forward(&mut prepared, &xs, 50));
    });
    println!(
        "ours: denoiser forward (batch 16) {:.2} ms on the sampling path, {:.2} ms through candle",
        forward * 1e3,
        candle_forward * 1e3
    );
    let (scenes, bounds, x0) = guidance_batch(&s.cfg);
    let refs: Vec<&Scene> = scenes.iter().collect();
    let mut g = SpatialGuidance::new(GuidanceConfig::all(), &s.cfg, &bounds, &refs);
    let guide = fastest(21, || {
        black_box(g.guide(&x0, 0).unwrap());
    });
    println!(
        "ratio: guidance / denoiser per step (batch 16) = {:.3} ({:.2} ms vs {:.2} ms; target ≤ 0.10)",
        guide / forward,
        guide * 1e3,
        forward * 1e3
    );
    println!(
        "ours: sample 16 × 200 steps {:.3} s, train step (batch 32) {:.1} ms fused, {:.1} ms through candle",
        sampling,
        step * 1e3,
        candle_step * 1e3
    );
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/reference");
    let python = root.join(".venv/bin/python");
    if !python.exists() {
        println!("reference not installed: run `bash benches/reference/setup.sh` for the PyTorch ratios");
        return;
    }
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()).to_string();
    let out = std::process::Command::new(&python)
        .arg(root.join("dit_reference.py"))
        .args(["--threads", &threads])
        .output()
        .expect("the reference runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: serde_json::Value = serde_json::from_slice(out.stdout.trim_ascii()).expect("one JSON line");
    let (ref_sample, ref_step) = (r["sample_seconds"].as_f64().unwrap(), r["train_step_seconds"].as_f64().unwrap());
    let ref_cached = r["sample_cached_seconds"].as_f64().unwrap();
    println!(
        "PyTorch {} ({} parameters, {threads} threads): sample {:.3} s ({:.3} s with conditions encoded once), \
         train step {:.1} ms",
        r["torch"],
        r["parameters"],
        ref_sample,
        ref_cached,
        ref_step * 1e3
    );
    println!("ratio: sampling PyTorch / ours = {:.2} (≥ 1: ours faster)", ref_sample / sampling);
    println!("ratio: sampling PyTorch with conditions encoded once / ours = {:.2}", ref_cached / sampling);
    println!("ratio: training steps per second ours (fused) / PyTorch = {:.2}", ref_step / step);
    println!("ratio: training steps per second ours (candle) / PyTorch = {:.2}", ref_step / candle_step);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(std::time::Duration::from_secs(10));
    targets = bench
}

fn main() {
    benches();
    ratios();
    Criterion::default().configure_from_args().final_summary();
}
