use super::*;
use crate::data::{Rng, generate_room};
use crate::generator::shipped::shipped_weights;
use crate::generator::{Engine, Example, Gradients, HostBatch, Params, Schedule, shipped_model};
use crate::scene::RoomType;
use std::collections::BTreeMap;

/// A batch of `n` real examples of `rooms` (in turn) with every corner case in it: items with 0
/// contact boxes and with the most, a free-space mask with nobody walking (every point the same:
/// ties in the PointNet's max), steps from 0 to T − 1.
fn batch(rooms: &[RoomType], cfg: &ModelConfig, bounds: &crate::generator::Bounds, n: usize) -> NoisyBatch {
    let mut host = HostBatch::default();
    for seed in 0..n as u64 {
        let scene = generate_room(rooms[seed as usize % rooms.len()], 11, seed, false).scene;
        let mut e = Example::of(&scene, bounds, cfg);
        if seed == 1 {
            e.features.contact_mask.fill(0.0);
            e.features.contacts.fill(0.0);
        }
        if seed == 2 {
            e.features.contact_mask.fill(1.0);
        }
        if seed == 3 {
            e.features.free.chunks_exact_mut(3).for_each(|p| p.copy_from_slice(&[0.0, 0.0, 0.0]));
        }
        host.push(&e, cfg);
    }
    let mut b = NoisyBatch::draw(host, &Schedule::linear(cfg.diffusion_steps), &mut Rng::new(5), cfg);
    (b.t[0], b.t[n - 1]) = (0, cfg.diffusion_steps - 1);
    b
}

/// Worst |fused − candle| of each tensor over that tensor's largest |candle| value.
fn compare(
    layout: &ParamLayout,
    params: &[f32],
    batch: &NoisyBatch,
    cfg: &ModelConfig,
) -> BTreeMap<String, (f32, f32)> {
    let net = GradNet::new(cfg, layout).unwrap();
    let (loss, fused) = net.loss_and_grad(params, batch);
    let mut candle = Gradients::new(Engine::Candle, cfg, layout).unwrap();
    let (want_loss, want) = candle.loss_and_grad(params, batch).unwrap();
    assert!((loss - want_loss).abs() < 1e-5 * want_loss.max(1e-3), "loss {loss} vs {want_loss}");
    assert!((net.loss(params, batch) - loss).abs() < 1e-9, "loss alone");
    layout
        .ranges()
        .map(|(name, range)| {
            let scale = want[range.clone()].iter().fold(0f32, |m, v| m.max(v.abs()));
            let worst = want[range.clone()].iter().zip(&fused[range]).fold(0f32, |m, (a, b)| m.max((a - b).abs()));
            (name.to_string(), (worst, scale))
        })
        .collect()
}

#[test]
fn gradients_equal_candles_on_a_trained_model() {
    for room in [RoomType::Bedroom, RoomType::Living] {
        let checkpoint = shipped_model(room).unwrap();
        let cfg = &checkpoint.meta.model;
        let (layout, params) = ParamLayout::of(&shipped_weights(room)).unwrap();
        let b = batch(&[room], cfg, &checkpoint.meta.bounds, 11);
        for (name, (worst, scale)) in compare(&layout, &params, &b, cfg) {
            assert!(scale > 0.0, "{room} {name}: no gradient");
            assert!(worst <= 1e-4 * scale, "{room} {name}: worst {worst:e} of {scale:e}");
        }
    }
}

#[test]
fn gradients_equal_candles_at_initialisation() {
    // adaLN-Zero: only the final layers get a gradient at the very start; both engines agree.
    let cfg = ModelConfig::tiny(RoomType::Dining);
    let mut init = Params::random(3);
    crate::generator::Denoiser::new(&cfg, &mut init).unwrap();
    let (layout, params) = ParamLayout::of(&init.snapshot().unwrap()).unwrap();
    let checkpoint = shipped_model(RoomType::Dining).unwrap();
    let b = batch(&[RoomType::Dining], &cfg, &checkpoint.meta.bounds, 5);
    let grads = compare(&layout, &params, &b, &cfg);
    for (name, (worst, scale)) in &grads {
        assert!(*worst <= 1e-4 * scale.max(1e-6), "{name}: worst {worst:e} of {scale:e}");
    }
    assert!(grads["final.output.weight"].1 > 0.0 && grads["blocks.0.qkv.weight"].1 == 0.0);
}

#[test]
fn gradients_equal_candles_with_anchored_slots_relations_self_conditioning_rooms_and_every_weight_set() {
    // Every parameter random (the zero-initialised modulations and outputs too), so every path —
    // the anchored slots' box embedding, the relation bias and values, the self-conditioning
    // estimate's embedding, the Fourier and gap features', the slot roles', the world features'
    // and the room token included —
    // carries a gradient.
    let checkpoint = shipped_model(RoomType::Living).unwrap();
    let cfg = ModelConfig {
        self_condition: true,
        min_snr: Some(5.0),
        room_token: true,
        count_condition: true,
        fourier_bands: 3,
        noise_scaled_features: true,
        gap_bounds: Some(checkpoint.meta.bounds.clone()),
        slot_roles: true,
        world_features: true,
        relation_values: true,
        ..ModelConfig::tiny(RoomType::Living)
    };
    assert!(cfg.anchor_scale > 0.0);
    let mut init = Params::random(4);
    crate::generator::Denoiser::new(&cfg, &mut init).unwrap();
    let (layout, _) = ParamLayout::of(&init.snapshot().unwrap()).unwrap();
    let mut rng = Rng::new(8);
    let params: Vec<f32> = (0..layout.len()).map(|_| 0.2 * rng.normal() as f32).collect();
    let b = batch(&[RoomType::Living, RoomType::Dining], &cfg, &checkpoint.meta.bounds, 7);
    assert!(b.self_condition.contains(&true) && b.self_condition.contains(&false), "{:?}", b.self_condition);
    assert_ne!(b.loss_weights, b.host.weights, "Min-SNR weights");
    let grads = compare(&layout, &params, &b, &cfg);
    for (name, (worst, scale)) in &grads {
        if name == "relation.1.bias" {
            // One constant per head added to every score of a row: the softmax does not see it,
            // so its gradient is zero up to rounding in both engines.
            assert!(*worst < 1e-7 && *scale < 1e-7, "{name}: {worst:e} {scale:e}");
            continue;
        }
        assert!(*scale > 0.0, "{name}: no gradient");
        assert!(*worst <= 1e-4 * scale, "{name}: worst {worst:e} of {scale:e}");
    }
    assert!(grads.contains_key("anchor.weight") && grads.contains_key("relation.0.weight"));
    assert!(cfg.wall_features && grads.contains_key("walls.weight"));
    assert!(grads.contains_key("estimate.weight") && grads.contains_key("fourier.weight"));
    assert!(grads.contains_key("gaps.weight") && grads.contains_key("roles.weight"));
    assert!(grads.contains_key("world.weight") && grads.contains_key("noise_scaled.weight"));
    assert!(
        grads.contains_key("blocks.1.relation_values.weight") && grads.contains_key("blocks.0.relation_values.bias")
    );
    // Living and dining rooms in one batch: both rows of the room table learn, the bedroom's not.
    let (room, _) = layout.find("room").unwrap();
    let net = GradNet::new(&cfg, &layout).unwrap();
    let (_, fused) = net.loss_and_grad(&params, &b);
    let d = cfg.d_model;
    let row = |r: usize| fused[room.start + r * d..room.start + (r + 1) * d].iter().any(|&g| g != 0.0);
    assert_eq!([row(0), row(1), row(2)], [false, true, true]);
    // The count condition: a category's row learns where some room holds that category.
    assert!(grads.contains_key("counts"));
    let (counts, _) = layout.find("counts").unwrap();
    let held: Vec<bool> =
        (0..cfg.count_width()).map(|c| b.host.counts.chunks_exact(cfg.count_width()).any(|n| n[c] > 0.0)).collect();
    let learns: Vec<bool> = (0..cfg.count_width())
        .map(|c| fused[counts.start + c * d..counts.start + (c + 1) * d].iter().any(|&g| g != 0.0))
        .collect();
    assert_eq!(learns, held);
    assert!(held.iter().filter(|&&h| h).count() >= 3, "{held:?}");
}

#[test]
fn the_relation_loss_counts_one_centre_less_the_other_in_world_form() {
    let cfg = ModelConfig::tiny(RoomType::Bedroom);
    let (dim, per_item) = (cfg.token_dim(), cfg.slots() * cfg.token_dim());
    let (mut out, target) = (vec![0f32; 2 * per_item], vec![0f32; 2 * per_item]);
    // Item 1: slot 0 is 0.3 off in the model's x, slot 2 is 0.1 off in y. Slot 0 is anchored to a
    // box facing +y (world = 0.4 × the turn of a quarter: model x is world y), slot 2 is free.
    out[per_item] = 0.3;
    out[per_item + 2 * dim + 1] = 0.1;
    let pair =
        RelationPair { item: 1, slots: [0, 2], weight: 2.0, maps: [[0.0, -0.4, 0.4, 0.0], [1.0, 0.0, 0.0, 1.0]] };
    // World errors: slot 0 (0, 0.12), slot 2 (0, 0.1); their difference (0, 0.02), squared 4e-4,
    // times the weight 2, over the total 10.
    let mut dout = vec![0f32; 2 * per_item];
    let loss = relation_loss(&cfg, &out, &target, std::slice::from_ref(&pair), 10.0, Some(&mut dout));
    assert!((loss - 2.0 * 4e-4 / 10.0).abs() < 1e-9, "{loss}");
    // d/d out: 2 × 2 / 10 × Mᵀ r for slot 0 (Mᵀ (0, 0.02) = (0.008, 0)), minus the same with the
    // identity for slot 2; nothing else moves.
    let g = 0.4f32;
    let want =
        [(per_item, g * 0.008), (per_item + 1, 0.0), (per_item + 2 * dim, 0.0), (per_item + 2 * dim + 1, -g * 0.02)];
    for (at, v) in want {
        assert!((dout[at] - v).abs() < 1e-7, "{at}: {} against {v}", dout[at]);
    }
    let touched: Vec<usize> = want.iter().map(|w| w.0).collect();
    assert!(dout.iter().enumerate().all(|(k, &v)| v == 0.0 || touched.contains(&k)));
    // A finite difference of the loss along slot 0's x agrees with the gradient.
    let eps = 1e-3;
    out[per_item] += eps;
    let up = relation_loss(&cfg, &out, &target, std::slice::from_ref(&pair), 10.0, None);
    out[per_item] -= 2.0 * eps;
    let down = relation_loss(&cfg, &out, &target, std::slice::from_ref(&pair), 10.0, None);
    assert!(((up - down) / (2.0 * eps as f64) - f64::from(dout[per_item])).abs() < 1e-5);
}

#[test]
fn held_relations_pair_the_nearby_pieces_of_each_scene_with_its_own_weight() {
    let cfg = ModelConfig {
        min_snr: Some(5.0),
        min_snr_floor: Some(1.0),
        prediction: crate::generator::Prediction::V,
        ..ModelConfig::tiny(RoomType::Bedroom)
    };
    let checkpoint = shipped_model(RoomType::Bedroom).unwrap();
    let mut b = batch(&[RoomType::Bedroom], &cfg, &checkpoint.meta.bounds, 6);
    let schedule = Schedule::linear(cfg.diffusion_steps);
    b.hold_relations(2.0, 0.5, &schedule, &cfg);
    assert!(!b.relations.is_empty());
    let (dim, per_item) = (cfg.token_dim(), cfg.slots() * cfg.token_dim());
    for r in &b.relations {
        let ab = schedule.alpha_bars[b.t[r.item]];
        let want = 2.0 * cfg.prediction.loss_weight(ab / (1.0 - ab), cfg.min_snr, cfg.min_snr_floor);
        assert!((f64::from(r.weight) - want).abs() < 1e-6 * want.max(1.0));
        assert!(r.slots[0] < r.slots[1]);
        for &s in &r.slots {
            let t = &b.host.tokens[r.item * per_item + s * dim..r.item * per_item + (s + 1) * dim];
            assert_ne!(crate::generator::tokens::slot_class(t, &cfg), cfg.classes() - 1, "pieces only");
        }
    }
    // Far apart is left out: with no reach no pair is held.
    let mut none = batch(&[RoomType::Bedroom], &cfg, &checkpoint.meta.bounds, 6);
    none.hold_relations(2.0, 0.0, &schedule, &cfg);
    assert!(none.relations.iter().all(|r| r.weight > 0.0) && none.relations.len() < b.relations.len());
}
