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
    // the anchored slots' box embedding, the relation bias, the self-conditioning estimate's
    // embedding, the Fourier and gap features', the slot roles', the world features' and the room token included —
    // carries a gradient.
    let checkpoint = shipped_model(RoomType::Living).unwrap();
    let cfg = ModelConfig {
        self_condition: true,
        min_snr: Some(5.0),
        room_token: true,
        count_condition: true,
        fourier_bands: 3,
        gap_bounds: Some(checkpoint.meta.bounds.clone()),
        slot_roles: true,
        world_features: true,
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
    assert!(grads.contains_key("world.weight"));
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
