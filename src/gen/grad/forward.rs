//! The forward pass of one chunk of a batch, keeping what the backward pass reads.
//!
//! Two parts: [`ConditionTape`] encodes the conditions (contact boxes, PointNets), which stay the
//! same over a sampling run's steps; [`StepTape`] is one step's pass through the time embedding,
//! the modulations, the blocks and the output layer. Training keeps both for the backward pass;
//! sampling encodes once and runs a `StepTape` per step.
//!
//! Rows: the chunk's object tokens first (item by item, `slots` each), then its visible contact
//! tokens (item by item); `items[i]` lists item i's rows in the candle model's order (objects, then
//! contacts), and `row_item[r]` is the item of row r.

use super::ops::{self, Parts};
use super::relation_values;
use super::{ChunkInputs, ConditionInputs, GradNet};
use crate::generator::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES};
use crate::generator::matmul::LinearAt;
use crate::generator::model::time_feature_values;
use crate::generator::{anchors, fourier, gaps, noise_scaled, relations, roles, walls};

/// A PointNet's activations: ReLU outputs of the first two layers, the third's output and, per
/// item, the max over the points.
pub(super) struct PointTape {
    pub(super) h0: Vec<f32>,
    pub(super) h1: Vec<f32>,
    pub(super) out: Vec<f32>,
    pub(super) max: Vec<f32>,
}

impl PointTape {
    fn run(p: &[f32], layers: &[LinearAt; 3], points: &[f32], items: usize) -> PointTape {
        let mut h0 = layers[0].map(p, points);
        ops::relu(&mut h0);
        let mut h1 = layers[1].map(p, &h0);
        ops::relu(&mut h1);
        let out = layers[2].map(p, &h1);
        let d = layers[2].output;
        let per_item = out.len() / items.max(1);
        let mut max = vec![f32::NEG_INFINITY; items * d];
        for (item, values) in out.chunks_exact(per_item.max(1)).enumerate() {
            let m = &mut max[item * d..(item + 1) * d];
            for row in values.chunks_exact(d) {
                m.iter_mut().zip(row).for_each(|(m, v)| *m = m.max(*v));
            }
        }
        PointTape { h0, h1, out, max }
    }
}

/// One block's activations.
pub(super) struct BlockTape {
    pub(super) u1: Vec<f32>,
    pub(super) rstd1: Vec<f32>,
    pub(super) m1: Vec<f32>,
    pub(super) qkv: Vec<f32>,
    pub(super) probs: Vec<Vec<f32>>,
    /// The attention's output (with relation values: theirs added).
    pub(super) attended: Vec<f32>,
    /// With relation values: the relations weighed by each (item, head)'s attention weights.
    pub(super) weighted_relations: Vec<Vec<f32>>,
    pub(super) attention_out: Vec<f32>,
    pub(super) u2: Vec<f32>,
    pub(super) rstd2: Vec<f32>,
    pub(super) m2: Vec<f32>,
    pub(super) fc1_out: Vec<f32>,
    pub(super) hidden: Vec<f32>,
    pub(super) mlp_out: Vec<f32>,
}

/// A chunk's conditions, encoded: everything that does not change between diffusion steps.
pub(crate) struct ConditionTape {
    pub(super) items: Vec<Vec<usize>>,
    pub(super) row_item: Vec<usize>,
    /// Visible contact boxes: features, owning item, mask weight.
    pub(super) contact_in: Vec<f32>,
    pub(super) contact_item: Vec<usize>,
    pub(super) contact_weight: Vec<f32>,
    /// Every item's contact features and mask as given (padding included), and its floor-plan
    /// points.
    pub(super) contacts: Vec<f32>,
    pub(super) mask: Vec<f32>,
    pub(super) floor_in: Vec<f32>,
    /// The object row each visible box is anchored to (item × slots + box index).
    pub(super) contact_row: Vec<usize>,
    /// With anchored slots: each visible box's embedding × its mask weight, added to its row.
    pub(super) anchored: Vec<f32>,
    /// Per item: Σ mask + 1e-6.
    pub(super) contact_count: Vec<f32>,
    pub(super) contact_pre: Vec<f32>,
    pub(super) contact_act: Vec<f32>,
    /// The visible boxes' tokens: encoding + the contact-kind vector.
    pub(super) contact_tokens: Vec<f32>,
    pub(super) pooled: Vec<f32>,
    /// Per item: the room type, one-hot, and the count condition.
    pub(super) rooms: Vec<f32>,
    pub(super) counts: Vec<f32>,
    /// Per item: the room token's vector plus the count condition's (items × d; empty without
    /// either).
    pub(super) global: Vec<f32>,
    pub(super) floor: PointTape,
    pub(super) free: PointTape,
}

impl ConditionTape {
    pub(super) fn run(net: &GradNet, p: &[f32], inp: &ConditionInputs) -> ConditionTape {
        let cfg = &net.cfg;
        let (d, slots, b) = (cfg.d_model, cfg.slots(), inp.items);
        let (mut contact_in, mut contact_item, mut contact_weight) = (Vec::new(), Vec::new(), Vec::new());
        let mut contact_row = Vec::new();
        for (k, (features, &w)) in inp.contacts.chunks_exact(CONTACT_FEATURES).zip(inp.mask).enumerate() {
            if w != 0.0 {
                contact_in.extend_from_slice(features);
                contact_item.push(k / cfg.max_contacts);
                contact_weight.push(w);
                contact_row.push(k / cfg.max_contacts * slots + k % cfg.max_contacts);
            }
        }
        let mut anchored = match &net.anchor {
            Some(anchor) => anchor.map(p, &contact_in),
            None => Vec::new(),
        };
        for (row, &w) in anchored.chunks_exact_mut(d).zip(&contact_weight) {
            row.iter_mut().for_each(|v| *v *= w);
        }
        // Σ mask + 1e-6 in the candle model's order: the sum first, then the ε.
        let contact_count: Vec<f32> =
            inp.mask.chunks_exact(cfg.max_contacts).map(|m| m.iter().sum::<f32>() + 1e-6).collect();
        let contact_pre = net.contact[0].map(p, &contact_in);
        let contact_act = ops::silu(&contact_pre);
        let mut contact_tokens = net.contact[1].map(p, &contact_act);
        let mut pooled = vec![0f32; b * d];
        for ((row, &item), &w) in contact_tokens.chunks_exact(d).zip(&contact_item).zip(&contact_weight) {
            pooled[item * d..(item + 1) * d].iter_mut().zip(row).for_each(|(s, v)| *s += v * w);
        }
        for (row, count) in pooled.chunks_exact_mut(d).zip(&contact_count) {
            row.iter_mut().for_each(|v| *v /= count);
        }
        let kind = &p[net.contact_kind..net.contact_kind + d];
        for row in contact_tokens.chunks_exact_mut(d) {
            row.iter_mut().zip(kind).for_each(|(v, k)| *v += k);
        }

        debug_assert_eq!(inp.floor.len(), b * cfg.floor_points * FLOOR_FEATURES);
        debug_assert_eq!(inp.free.len(), b * cfg.free_points * FREE_FEATURES);
        let floor = PointTape::run(p, &net.floor, inp.floor, b);
        let free = PointTape::run(p, &net.free, inp.free, b);
        let (rooms, counts) = (inp.rooms.to_vec(), inp.counts.to_vec());
        let global = [(net.room, &rooms), (net.counts, &counts)]
            .into_iter()
            .filter_map(|(table, inputs)| table.map(|t| t.map(p, inputs, d)))
            .reduce(|mut sum, rows| {
                sum.iter_mut().zip(rows).for_each(|(s, r)| *s += r);
                sum
            })
            .unwrap_or_default();

        // Rows: objects, then visible contact boxes.
        let objects = b * slots;
        let mut row_item: Vec<usize> = (0..objects).map(|r| r / slots).collect();
        row_item.extend_from_slice(&contact_item);
        let mut items: Vec<Vec<usize>> = (0..b).map(|i| (i * slots..(i + 1) * slots).collect()).collect();
        for (v, &item) in contact_item.iter().enumerate() {
            items[item].push(objects + v);
        }
        ConditionTape {
            items,
            row_item,
            contact_in,
            contact_item,
            contact_weight,
            contacts: inp.contacts.to_vec(),
            mask: inp.mask.to_vec(),
            floor_in: if net.walls.is_some() { inp.floor.to_vec() } else { Vec::new() },
            contact_row,
            anchored,
            contact_count,
            contact_pre,
            contact_act,
            contact_tokens,
            pooled,
            rooms,
            counts,
            global,
            floor,
            free,
        }
    }
}

/// One diffusion step's pass over a chunk whose conditions are encoded.
pub(super) struct StepTape {
    pub(super) time_in: Vec<f32>,
    pub(super) time_pre: Vec<f32>,
    pub(super) time_act: Vec<f32>,
    pub(super) c_pre: Vec<f32>,
    pub(super) c: Vec<f32>,
    /// With the relation bias: the pairs' features, the MLP's pre-activation and activation, and
    /// the bias per item and head (n × n each).
    pub(super) relation_in: Vec<f32>,
    pub(super) relation_pre: Vec<f32>,
    pub(super) relation_act: Vec<f32>,
    pub(super) relation_bias: Vec<Vec<f32>>,
    /// With relation values: every item's pairs' value features (n × n × F, its rows in order).
    pub(super) relation_values_in: Vec<Vec<f32>>,
    /// With wall features: every object row's ([`walls::slot_features`]).
    pub(super) wall_in: Vec<f32>,
    /// With Fourier features: every object row's ([`fourier::slot_features`]).
    pub(super) fourier_in: Vec<f32>,
    /// With noise-scaled features: every object row's ([`noise_scaled::slot_features`]).
    pub(super) noise_scaled_in: Vec<f32>,
    /// With gap features: every object row's ([`gaps::slot_features`]).
    pub(super) gap_in: Vec<f32>,
    /// With world features: every object row's ([`anchors::world_slot_features`]).
    pub(super) world_in: Vec<f32>,
    /// With slot roles: every object row's rank features ([`roles::slot_features`]).
    pub(super) role_in: Vec<f32>,
    /// With self-conditioning: the previous clean estimate of every object row (zeros: none).
    pub(super) estimate_in: Vec<f32>,
    /// Per block (items × 6d), then the final layer's (items × 2d).
    pub(super) modulation: Vec<Vec<f32>>,
    pub(super) blocks: Vec<BlockTape>,
    pub(super) final_u: Vec<f32>,
    pub(super) final_rstd: Vec<f32>,
    pub(super) final_m: Vec<f32>,
    /// Predicted noise, items × slots × token_dim.
    pub(super) out: Vec<f32>,
}

impl StepTape {
    /// The pass for noisy tokens `noisy` at steps `t` (one per item), with the previous clean
    /// estimate `estimate` (laid out like `noisy`; empty: zeros) where the model is self-conditioned.
    pub(super) fn run(
        net: &GradNet,
        p: &[f32],
        cond: &ConditionTape,
        t: &[usize],
        noisy: &[f32],
        estimate: &[f32],
    ) -> StepTape {
        let cfg = &net.cfg;
        let (d, b) = (cfg.d_model, t.len());
        let objects = b * cfg.slots();
        let row_item = &cond.row_item;

        let time_in = time_feature_values(t);
        let time_pre = net.time[0].map(p, &time_in);
        let time_act = ops::silu(&time_pre);
        let time = net.time[1].map(p, &time_act);
        let (floor, free) = (&cond.floor.max, &cond.free.max);
        let mut c_pre: Vec<f32> = (0..b * d).map(|i| ((time[i] + cond.pooled[i]) + floor[i]) + free[i]).collect();
        c_pre.iter_mut().zip(&cond.global).for_each(|(c, r)| *c += r);
        let c = ops::silu(&c_pre);
        let mut modulation: Vec<Vec<f32>> = net.blocks.iter().map(|block| block.modulation.map(p, &c)).collect();
        modulation.push(net.final_modulation.map(p, &c));

        let (relation_in, relation_pre, relation_act, relation_bias) = match &net.relation {
            Some(layers) => relation_bias(net, p, layers, cond, noisy),
            None => Default::default(),
        };
        let bias = net.relation.as_ref().map(|_| &relation_bias[..]);
        let relation_values_in = match cfg.relation_values {
            true => item_pair_features(net, cond, noisy, relations::value_features),
            false => Vec::new(),
        };

        let mut h = vec![0f32; row_item.len() * d];
        net.input.forward(p, noisy, &mut h[..objects * d]);
        // Each optional per-slot embedding: its layer over features of the noisy tokens, added to
        // the object rows; the features are kept for the backward pass (empty where it is off).
        let mut embed = |layer: Option<&LinearAt>, features: &dyn Fn() -> Vec<f32>| match layer {
            Some(layer) => {
                let features = features();
                let embedded = layer.map(p, &features);
                h[..objects * d].iter_mut().zip(&embedded).for_each(|(v, e)| *v += e);
                features
            }
            None => Vec::new(),
        };
        let wall_in = embed(net.walls.as_ref(), &|| {
            slot_features(net, cond, noisy, |tokens, contacts, mask, floor| {
                walls::slot_features(cfg, tokens, contacts, mask, floor)
            })
        });
        let fourier_in = embed(net.fourier.as_ref(), &|| fourier::slot_features(cfg, noisy));
        let noise_scaled_in = embed(net.noise_scaled.as_ref(), &|| noise_scaled::slot_features(cfg, t, noisy));
        let gap_in = match &cfg.gap_bounds {
            Some(bounds) => embed(net.gaps.as_ref(), &|| {
                slot_features(net, cond, noisy, |tokens, contacts, mask, _| {
                    gaps::slot_features(cfg, bounds, tokens, contacts, mask)
                })
            }),
            None => Vec::new(),
        };
        let world_in = embed(net.world.as_ref(), &|| {
            slot_features(net, cond, noisy, |tokens, contacts, mask, _| {
                anchors::world_slot_features(cfg, tokens, contacts, mask)
            })
        });
        let role_in = embed(net.roles.as_ref(), &|| {
            slot_features(net, cond, noisy, |_, _, mask, _| roles::slot_features(cfg, mask))
        });
        let estimate_in = embed(net.estimate.as_ref(), &|| match estimate.is_empty() {
            true => vec![0f32; noisy.len()],
            false => estimate.to_vec(),
        });
        for (&r, e) in cond.contact_row.iter().zip(cond.anchored.chunks_exact(d)) {
            h[r * d..(r + 1) * d].iter_mut().zip(e).for_each(|(v, e)| *v += e);
        }
        h[objects * d..].copy_from_slice(&cond.contact_tokens);
        let mut blocks = Vec::with_capacity(net.blocks.len());
        for (layers, m) in net.blocks.iter().zip(&modulation) {
            let m = Parts { values: m, parts: 6, d };
            let (u1, rstd1) = ops::layer_norm(&h, d);
            let m1 = ops::modulate(&u1, m, 0, row_item);
            let qkv = layers.qkv.map(p, &m1);
            let (mut attended, probs) = ops::attention(&qkv, &cond.items, cfg.heads, d, bias);
            let weighted_relations = match &layers.relation_values {
                Some(layer) => relation_values::forward(
                    p,
                    layer,
                    &mut attended,
                    &probs,
                    &relation_values_in,
                    &cond.items,
                    cfg.heads,
                ),
                None => Vec::new(),
            };
            let attention_out = layers.proj.map(p, &attended);
            ops::add_gated(&mut h, &attention_out, m, 2, row_item);
            let (u2, rstd2) = ops::layer_norm(&h, d);
            let m2 = ops::modulate(&u2, m, 3, row_item);
            let fc1_out = layers.fc1.map(p, &m2);
            let hidden = ops::silu(&fc1_out);
            let mlp_out = layers.fc2.map(p, &hidden);
            ops::add_gated(&mut h, &mlp_out, m, 5, row_item);
            blocks.push(BlockTape {
                u1,
                rstd1,
                m1,
                qkv,
                probs,
                attended,
                weighted_relations,
                attention_out,
                u2,
                rstd2,
                m2,
                fc1_out,
                hidden,
                mlp_out,
            });
        }

        let (final_u, final_rstd) = ops::layer_norm(&h[..objects * d], d);
        let last = Parts { values: modulation.last().expect("the final modulation"), parts: 2, d };
        let final_m = ops::modulate(&final_u, last, 0, &row_item[..objects]);
        let out = net.output.map(p, &final_m);
        StepTape {
            time_in,
            time_pre,
            time_act,
            c_pre,
            c,
            relation_in,
            relation_pre,
            relation_act,
            relation_bias,
            relation_values_in,
            wall_in,
            fourier_in,
            noise_scaled_in,
            gap_in,
            world_in,
            role_in,
            estimate_in,
            modulation,
            blocks,
            final_u,
            final_rstd,
            final_m,
            out,
        }
    }
}

/// Features of a chunk's object rows computed on the host, item by item, by
/// `per_item(tokens, contacts, mask, floor)` (the floor-plan points empty unless the wall features
/// keep them).
fn slot_features(
    net: &GradNet,
    cond: &ConditionTape,
    noisy: &[f32],
    per_item: impl Fn(&[f32], &[f32], &[f32], &[f32]) -> Vec<f32>,
) -> Vec<f32> {
    let cfg = &net.cfg;
    let (k, per_slots) = (cfg.max_contacts, cfg.slots() * cfg.token_dim());
    // The floor-plan points are kept only where the wall features need them.
    let f = if cond.floor_in.is_empty() { 0 } else { cfg.floor_points * FLOOR_FEATURES };
    (0..cond.items.len())
        .flat_map(|item| {
            per_item(
                &noisy[item * per_slots..(item + 1) * per_slots],
                &cond.contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES],
                &cond.mask[item * k..(item + 1) * k],
                &cond.floor_in[item * f..(item + 1) * f],
            )
        })
        .collect()
}

/// Every item's features of its ordered pairs of rows (in `cond.items` order), computed on the
/// host from the rows' poses by `of_poses`.
fn item_pair_features(
    net: &GradNet,
    cond: &ConditionTape,
    noisy: &[f32],
    of_poses: fn(&[relations::TokenPose]) -> Vec<f32>,
) -> Vec<Vec<f32>> {
    let cfg = &net.cfg;
    let (k, per_item) = (cfg.max_contacts, cfg.slots() * cfg.token_dim());
    cond.items
        .iter()
        .enumerate()
        .map(|(item, rows)| {
            let poses = relations::poses(
                cfg,
                &noisy[item * per_item..(item + 1) * per_item],
                &cond.contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES],
                &cond.mask[item * k..(item + 1) * k],
                false,
            );
            debug_assert_eq!(poses.len(), rows.len());
            of_poses(&poses)
        })
        .collect()
}

/// The relation bias of a chunk: every item's pair features (its rows in `cond.items` order),
/// the MLP over all pairs at once, and the bias regrouped per item and head.
fn relation_bias(
    net: &GradNet,
    p: &[f32],
    layers: &[LinearAt; 2],
    cond: &ConditionTape,
    noisy: &[f32],
) -> (Vec<f32>, Vec<f32>, Vec<f32>, Vec<Vec<f32>>) {
    let features = item_pair_features(net, cond, noisy, relations::pair_features).concat();
    let pre = layers[0].map(p, &features);
    let act = ops::silu(&pre);
    let out = layers[1].map(p, &act);
    let heads = net.cfg.heads;
    let mut bias = Vec::with_capacity(cond.items.len() * heads);
    let mut at = 0;
    for rows in &cond.items {
        let pairs = rows.len() * rows.len();
        for head in 0..heads {
            bias.push((0..pairs).map(|q| out[(at + q) * heads + head]).collect());
        }
        at += pairs;
    }
    (features, pre, act, bias)
}

/// Everything the forward pass of a training chunk computed that its backward pass needs.
pub(super) struct Tape {
    pub(super) cond: ConditionTape,
    pub(super) step: StepTape,
}

impl Tape {
    /// A self-conditioned model first runs without an estimate; the items that `inp` marks then
    /// get that pass's clean estimate (clamped to [−1, 1], as sampling clamps it), held fixed.
    pub(super) fn run(net: &GradNet, p: &[f32], inp: &ChunkInputs) -> Tape {
        let cond = ConditionTape::run(net, p, &inp.cond);
        let mut estimate = Vec::new();
        if net.estimate.is_some() && inp.self_condition.iter().any(|&on| on) {
            estimate = StepTape::run(net, p, &cond, inp.t, inp.noisy, &[]).out;
            let per_item = estimate.len() / inp.t.len().max(1);
            for (values, &on) in estimate.chunks_exact_mut(per_item).zip(inp.self_condition) {
                values.iter_mut().for_each(|v| *v = if on { v.clamp(-1.0, 1.0) } else { 0.0 });
            }
        }
        let step = StepTape::run(net, p, &cond, inp.t, inp.noisy, &estimate);
        Tape { cond, step }
    }

    /// This chunk's share of the batch loss Σ w (output − target)² / `total`.
    pub(super) fn loss(&self, cfg: &crate::generator::ModelConfig, inp: &ChunkInputs, total: f32) -> f64 {
        let sum: f64 = self
            .step
            .out
            .iter()
            .zip(inp.target)
            .zip(inp.weights)
            .map(|((o, n), w)| (w * (o - n) * (o - n)) as f64)
            .sum();
        sum / total as f64 + super::relation_loss(cfg, &self.step.out, inp.target, &inp.relations, total, None)
    }
}
