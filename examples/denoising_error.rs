//! How precise is a model's one-step clean estimate x̂₀ at each noise level, on real rooms?
//!
//! Every scene of a dataset split is noised to step t (one seeded draw), the model predicts once
//! (x̂₀ from its ε, x₀ or v output as sampling takes it, `Prediction::clean_estimate`), and the
//! estimate is compared with the scene itself, slot by slot: the error of a piece's centre and of
//! its size in centimetres (median and 90th percentile, anchored and free slots apart), and the
//! share of slots whose class is right. For bedrooms, also how the estimate keeps a nightstand
//! beside its bed (each nightstand against the room's own nearest bed): the median error of the
//! side gap against the room's (cm), and Pearson's r of the nightstand's distance from the bed's
//! centre line against the bed's half width (0.99 in the data; `examples/pair_gaps.rs` measures
//! the same on layouts). In every room type, the centre error of the hanging lamps that hang
//! within 2 cm of the floor's centre (the token origin), which a denoiser that knew the data's
//! most common lamp place would pull home. For the free pieces, two rules of the data that no
//! other piece's noise blurs, each beside the noisy input's own error: the yaw (every piece
//! stands square to the walls) and, for a piece whose back stands 5 cm off its nearest wall (to
//! within a centimetre: the wall pieces), its distance from that wall — the floor plan is given
//! exactly, so a denoiser that reads where its walls are puts such a piece back. And the centre
//! error of the dining tables, beside the noisy input's: the data stands every dining chair 4 cm
//! off its table and the chairs are anchored to their sitters, so a denoiser that read its
//! chairs would put their table back (with table slots, `train --table-slots`, the table is in
//! its diners' knee slots, each copy counted). Read
//! beside the sampled layouts' errors, it says whether a model's imprecision is its own (a large
//! one-step error near t = 0) or the sampling chain's (a small one, with layouts still off).
//!
//! ```sh
//! cargo run --release --example denoising_error -- models/bedroom data/bedroom [val] [scenes]
//! ```

use shade_sim::data::Rng;
use shade_sim::eval::pearson;
use shade_sim::generator::tokens::slot_class;
use shade_sim::generator::{Checkpoint, FastDenoiser, HostBatch, Schedule, anchors, load_split};
use shade_sim::geom::wrap_angle;
use shade_sim::scene::Category;
use std::path::PathBuf;

/// How far the data stands a wall piece's back off its wall (m).
const BACK_GAP: f64 = 0.05;

const STEPS: [usize; 9] = [0, 5, 10, 20, 40, 60, 80, 120, 160];

fn percentile(values: &mut [f64], q: f64) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    values[((values.len() - 1) as f64 * q).round() as usize]
}

/// "estimate / input (count)": the medians of an estimate's errors and of its noisy input's; "-"
/// when no piece was measured.
fn beside_input(estimate: &mut [f64], input: &mut [f64]) -> String {
    match input.len() {
        0 => "-".to_string(),
        n => format!("{:.1} / {:.1} ({n})", percentile(estimate, 0.5), percentile(input, 0.5)),
    }
}

/// A slot in metres: centre (x, y), width, yaw.
#[derive(Clone, Copy)]
struct Placed {
    x: f64,
    y: f64,
    width: f64,
    yaw: f64,
}

/// The side gap of a nightstand beside its bed (m) and its distance from the bed's centre line.
fn beside(nightstand: Placed, bed: Placed) -> (f64, f64) {
    let (dx, dy) = (nightstand.x - bed.x, nightstand.y - bed.y);
    let u = (bed.yaw.cos() * dx + bed.yaw.sin() * dy).abs();
    (u - bed.width / 2.0 - nightstand.width / 2.0, u)
}

/// A slot's yaw (rad) from its cos and sin.
fn yaw_of(v: &[f32]) -> f64 {
    f64::from(v[7]).atan2(f64::from(v[6]))
}

/// The floor-plan boundary point nearest slot `v`'s centre, with its outward normal (token units;
/// `floor` holds x, y and the normal's x, y per point; the interior points, whose normal is zero,
/// left out): the wall that slot stands nearest.
fn nearest_wall(floor: &[f32], v: &[f32]) -> [f64; 4] {
    let far = |q: &[f32]| f64::from(q[0] - v[0]).hypot(f64::from(q[1] - v[1]));
    let q = floor
        .chunks_exact(4)
        .filter(|q| q[2] != 0.0 || q[3] != 0.0)
        .min_by(|a, b| far(a).total_cmp(&far(b)))
        .expect("a floor plan has boundary points");
    std::array::from_fn(|k| f64::from(q[k]))
}

/// How far inside `wall`'s line slot `v`'s centre is (token units).
fn wall_distance(wall: [f64; 4], v: &[f32]) -> f64 {
    -((f64::from(v[0]) - wall[0]) * wall[2] + (f64::from(v[1]) - wall[1]) * wall[3])
}

fn main() -> std::process::ExitCode {
    match run() {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::from(2)
        }
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [model, data, rest @ ..] = &args[..] else {
        return Err("usage: denoising_error MODEL_DIR DATA_DIR [SPLIT] [SCENES]".into());
    };
    let split = rest.first().map_or("val", |s| s.as_str());
    let limit: usize = rest.get(1).map_or(Ok(usize::MAX), |s| s.parse().map_err(|e| format!("SCENES {s:?}: {e}")))?;
    let checkpoint = Checkpoint::load(&PathBuf::from(model))?;
    let (cfg, bounds) = (&checkpoint.meta.model, &checkpoint.meta.bounds);
    let schedule = Schedule::of(cfg);
    let examples = load_split(&PathBuf::from(data), split, bounds, cfg)?;
    let examples = &examples[..examples.len().min(limit)];
    let fast = FastDenoiser::of(&checkpoint.denoiser)?;
    let mut host = HostBatch::default();
    examples.iter().for_each(|e| host.push(e, cfg));
    let (dim, per_item, empty) = (cfg.token_dim(), cfg.slots() * cfg.token_dim(), cfg.classes() - 1);
    let world = |tokens: &mut [f32]| {
        for (e, t) in examples.iter().zip(tokens.chunks_exact_mut(per_item)) {
            anchors::to_world(cfg, &e.features.contacts, &e.features.contact_mask, t);
        }
    };
    let mut truth = host.tokens.clone();
    world(&mut truth);
    let metres = |v: &[f32]| bounds.unscale_center([v[0] as f64, v[1] as f64, v[2] as f64]);
    let size = |v: &[f32]| bounds.unscale_size([v[3] as f64, v[4] as f64, v[5] as f64]);
    let unit = bounds.unscale_center([1.0, 0.0, 0.0])[0] - bounds.unscale_center([0.0, 0.0, 0.0])[0];

    println!("{} scenes of {data}/{split}, model {model}", examples.len());
    let categories = cfg.room_type.categories();
    let class_of = |c: Category| categories.iter().position(|&k| k == c);
    let beds: Vec<usize> =
        [Category::DoubleBed, Category::SingleBed, Category::KidsBed].into_iter().filter_map(class_of).collect();
    let nightstand = class_of(Category::Nightstand);
    let dining_table = class_of(Category::DiningTable);
    let placed = |v: &[f32]| {
        let (c, s) = (metres(v), size(v));
        Placed { x: c[0], y: c[1], width: s[0], yaw: yaw_of(v) }
    };
    println!(
        "| t | σ (cm) | centre, anchored: median / p90 (cm) | centre, free | size, free | class right | empty right | nightstand gap error: median (cm), r | lamps at the centre | yaw, free: estimate / input (deg, median) | wall distance, free with the back 5 cm off a wall: estimate / input (cm, median) | centre, dining tables: estimate / input (cm, median) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for t in STEPS.into_iter().filter(|&t| t < schedule.steps()) {
        let ab = schedule.alpha_bars[t];
        let mut rng = Rng::new(7 + t as u64);
        let noisy: Vec<f32> = host
            .tokens
            .iter()
            .map(|&x| (ab.sqrt() as f32) * x + ((1.0 - ab).sqrt() as f32) * rng.normal() as f32)
            .collect();
        let mut prepared = fast.prepare(&host.cond(cfg)?)?;
        let out = fast.forward(&mut prepared, &noisy, t);
        let mut estimate: Vec<f32> =
            out.iter().zip(&noisy).map(|(&o, &x)| cfg.prediction.clean_estimate(o, x, ab).clamp(-1.0, 1.0)).collect();
        world(&mut estimate);
        let (mut anchored, mut free, mut sizes, mut centred) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut class_right, mut pieces, mut empty_right, mut slots) = (0usize, 0usize, 0usize, 0usize);
        let (mut gap_errors, mut from_centre, mut half_width) = (Vec::new(), Vec::new(), Vec::new());
        let (mut yaw_est, mut yaw_in) = (Vec::new(), Vec::new());
        let (mut wall_est, mut wall_in) = (Vec::new(), Vec::new());
        let (mut table_est, mut table_in) = (Vec::new(), Vec::new());
        let mut noisy_world = noisy.clone();
        world(&mut noisy_world);
        for (item, ((want, got), inp)) in truth
            .chunks_exact(per_item)
            .zip(estimate.chunks_exact(per_item))
            .zip(noisy_world.chunks_exact(per_item))
            .enumerate()
        {
            // Each nightstand against the room's own nearest bed, both as the model estimates them.
            let class_in = |slot: usize| slot_class(&want[slot * dim..(slot + 1) * dim], cfg);
            let truth_at = |s: usize| placed(&want[s * dim..(s + 1) * dim]);
            let bed_slots: Vec<usize> = (0..cfg.slots()).filter(|&s| beds.contains(&class_in(s))).collect();
            for ns in (0..cfg.slots()).filter(|&s| Some(class_in(s)) == nightstand) {
                let distance = |s: &usize| (truth_at(*s).x - truth_at(ns).x).hypot(truth_at(*s).y - truth_at(ns).y);
                let Some(&bed) = bed_slots.iter().min_by(|a, b| distance(a).total_cmp(&distance(b))) else {
                    continue;
                };
                let (true_gap, _) = beside(truth_at(ns), truth_at(bed));
                let estimated_at = |s: usize| placed(&got[s * dim..(s + 1) * dim]);
                let (gap, u) = beside(estimated_at(ns), estimated_at(bed));
                gap_errors.push(100.0 * (gap - true_gap).abs());
                from_centre.push(u);
                half_width.push(estimated_at(bed).width / 2.0);
            }
            let boxes = examples[item].features.contact_mask.iter().filter(|&&m| m != 0.0).count();
            let boxes = cfg.anchored_slots(boxes);
            for (slot, (w, g)) in want.chunks_exact(dim).zip(got.chunks_exact(dim)).enumerate() {
                let (wc, gc) = (slot_class(w, cfg), slot_class(g, cfg));
                slots += 1;
                empty_right += ((wc == empty) == (gc == empty)) as usize;
                if wc == empty {
                    continue;
                }
                pieces += 1;
                class_right += (wc == gc) as usize;
                let (a, b) = (metres(w), metres(g));
                let error = 100.0 * ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
                if categories.get(wc).is_some_and(|c| c.is_hanging()) && a[0].hypot(a[1]) < 0.02 {
                    centred.push(error);
                }
                if Some(wc) == dining_table {
                    let c = metres(&inp[slot * dim..(slot + 1) * dim]);
                    table_est.push(error);
                    table_in.push(100.0 * ((a[0] - c[0]).powi(2) + (a[1] - c[1]).powi(2)).sqrt());
                }
                if slot < boxes {
                    anchored.push(error);
                } else {
                    free.push(error);
                    let input = &inp[slot * dim..(slot + 1) * dim];
                    yaw_est.push(wrap_angle(yaw_of(g) - yaw_of(w)).abs().to_degrees());
                    yaw_in.push(wrap_angle(yaw_of(input) - yaw_of(w)).abs().to_degrees());
                    let wall = nearest_wall(&examples[item].features.floor, w);
                    let from_wall = |v: &[f32]| unit * wall_distance(wall, v);
                    let depth = size(w)[1];
                    if (from_wall(w) - depth / 2.0 - BACK_GAP).abs() < 0.01 {
                        wall_est.push(100.0 * (from_wall(g) - from_wall(w)).abs());
                        wall_in.push(100.0 * (from_wall(input) - from_wall(w)).abs());
                    }
                    let (a, b) = (size(w), size(g));
                    sizes.push(100.0 * (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max));
                }
            }
        }
        let pair = |v: &mut Vec<f64>| format!("{:.1} / {:.1}", percentile(v, 0.5), percentile(v, 0.9));
        let relation = match gap_errors.is_empty() {
            true => "-".to_string(),
            false => format!("{:.1}, {:.2}", percentile(&mut gap_errors, 0.5), pearson(&from_centre, &half_width)),
        };
        println!(
            "| {t} | {:.1} | {} | {} | {} | {:.3} | {:.3} | {relation} | {} | {:.2} / {:.2} | {} | {} |",
            100.0 * unit * (1.0 - ab).sqrt() / ab.sqrt(),
            pair(&mut anchored),
            pair(&mut free),
            pair(&mut sizes),
            class_right as f64 / pieces.max(1) as f64,
            empty_right as f64 / slots.max(1) as f64,
            pair(&mut centred),
            percentile(&mut yaw_est, 0.5),
            percentile(&mut yaw_in, 0.5),
            beside_input(&mut wall_est, &mut wall_in),
            beside_input(&mut table_est, &mut table_in),
        );
    }
    Ok(())
}
