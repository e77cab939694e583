//! The SHADE denoiser: a DiT over object-slot tokens with adaLN-Zero, conditioned on the diffusion
//! time, the contact boxes, the floor plan and the free-space mask.
//!
//! The condition vector c = time MLP + floor-plan PointNet + free-space PointNet + pooled contact
//! encoding modulates every block (shift, scale and gate of attention and MLP, all zero-initialised,
//! so every block starts as the identity). With `contact_tokens` the encoded contact boxes also join
//! the attention as extra tokens (masked where a scene has fewer boxes); only object tokens are read
//! out. There are no positional embeddings: the model is equivariant to the order of the slots.
//!
//! This module only maps tensors to tensors; tokens, features and sampling live beside it.

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES, RELATION_HIDDEN, TIME_FEATURES};
use super::fourier;
use super::gaps::{self, GAP_FEATURES};
use super::noise_scaled;
use super::params::{Init, Linear, Params, layer_norm};
use super::relations::{self, RELATION_FEATURES, RELATION_VALUE_FEATURES};
use super::walls::{self, WALL_FEATURES};
use super::{GenError, ModelConfig};
use super::{anchors, roles};
use crate::scene::RoomType;
use candle_core::{D, Device, Tensor};
use std::collections::BTreeMap;

/// The conditioning of a batch, as tensors.
#[derive(Debug, Clone)]
pub struct CondTensors {
    /// Contact boxes (B, K, 11).
    pub contacts: Tensor,
    /// 1 for a real contact box, 0 for padding (B, K).
    pub contact_mask: Tensor,
    /// Floor-plan points (B, P, 4).
    pub floor: Tensor,
    /// Free-space points (B, Q, 3).
    pub free: Tensor,
    /// The room type, one-hot over [`RoomType::ALL`] (B, 3).
    pub room: Tensor,
    /// With count conditioning: pieces per category × [`super::COUNT_SCALE`] (B, categories;
    /// B × 0 without).
    pub counts: Tensor,
}

/// A PointNet: a shared per-point MLP followed by a max over the points.
#[derive(Debug, Clone)]
pub(super) struct PointNet {
    pub(super) layers: [Linear; 3],
}

impl PointNet {
    fn new(p: &mut Params, name: &str, input: usize, width: usize, out: usize) -> Result<PointNet, GenError> {
        Ok(PointNet {
            layers: [
                p.linear(&format!("{name}.0"), input, width, false)?,
                p.linear(&format!("{name}.1"), width, 2 * width, false)?,
                p.linear(&format!("{name}.2"), 2 * width, out, false)?,
            ],
        })
    }

    fn forward(&self, points: &Tensor) -> Result<Tensor, GenError> {
        let h = self.layers[0].forward(points)?.relu()?;
        let h = self.layers[1].forward(&h)?.relu()?;
        Ok(self.layers[2].forward(&h)?.max(1)?)
    }
}

/// One DiT block with adaLN-Zero.
#[derive(Debug, Clone)]
pub(super) struct Block {
    pub(super) modulation: Linear,
    pub(super) qkv: Linear,
    pub(super) proj: Linear,
    pub(super) fc1: Linear,
    pub(super) fc2: Linear,
    /// With relation values: the map from a pair's value features to what the pair adds to the
    /// attention's values (d outputs, head h's in its dh columns), zero at the start.
    pub(super) relation_values: Option<Linear>,
    heads: usize,
}

impl Block {
    fn new(p: &mut Params, name: &str, cfg: &ModelConfig) -> Result<Block, GenError> {
        let d = cfg.d_model;
        Ok(Block {
            modulation: p.linear(&format!("{name}.modulation"), d, 6 * d, true)?,
            qkv: p.linear(&format!("{name}.qkv"), d, 3 * d, false)?,
            proj: p.linear(&format!("{name}.proj"), d, d, false)?,
            fc1: p.linear(&format!("{name}.fc1"), d, cfg.mlp_ratio * d, false)?,
            fc2: p.linear(&format!("{name}.fc2"), cfg.mlp_ratio * d, d, false)?,
            relation_values: match cfg.relation_values {
                true => Some(p.linear(&format!("{name}.relation_values"), RELATION_VALUE_FEATURES, d, true)?),
                false => None,
            },
            heads: cfg.heads,
        })
    }

    /// `x` (B, N, d), `c` = SiLU(condition) (B, d), `bias` (B, 1, 1, N) additive attention mask,
    /// `pairs` (B, N, N, [`RELATION_VALUE_FEATURES`]) the pairs' value features where the model
    /// has relation values.
    fn forward(
        &self,
        x: &Tensor,
        c: &Tensor,
        bias: Option<&Tensor>,
        pairs: Option<&Tensor>,
    ) -> Result<Tensor, GenError> {
        let d = x.dim(D::Minus1)?;
        let m = self.modulation.forward(c)?;
        let part = |i: usize| -> Result<Tensor, GenError> { Ok(m.narrow(1, i * d, d)?.unsqueeze(1)?) };
        let (shift1, scale1, gate1) = (part(0)?, part(1)?, part(2)?);
        let (shift2, scale2, gate2) = (part(3)?, part(4)?, part(5)?);
        let h = modulate(&layer_norm(x)?, &shift1, &scale1)?;
        let x = (x + self.attention(&h, bias, pairs)?.broadcast_mul(&gate1)?)?;
        let h = modulate(&layer_norm(&x)?, &shift2, &scale2)?;
        let h = self.fc2.forward(&self.fc1.forward(&h)?.silu()?)?;
        Ok((x + h.broadcast_mul(&gate2)?)?)
    }

    fn attention(&self, h: &Tensor, bias: Option<&Tensor>, pairs: Option<&Tensor>) -> Result<Tensor, GenError> {
        let (b, n, d) = h.dims3()?;
        let dh = d / self.heads;
        let qkv = self.qkv.forward(h)?.reshape((b, n, 3, self.heads, dh))?;
        let take = |i: usize| -> Result<Tensor, GenError> {
            Ok(qkv.narrow(2, i, 1)?.squeeze(2)?.transpose(1, 2)?.contiguous()?)
        };
        let (q, k, v) = (take(0)?, take(1)?, take(2)?);
        let mut scores = (q.matmul(&k.t()?)? * (1.0 / (dh as f64).sqrt()))?;
        if let Some(bias) = bias {
            scores = scores.broadcast_add(bias)?;
        }
        let weights = candle_nn::ops::softmax(&scores, D::Minus1)?;
        let mut out = weights.matmul(&v)?;
        if let (Some(layer), Some(pairs)) = (&self.relation_values, pairs) {
            // Head h adds W_h Σ_j p_ij f_ij + b_h: the weighted relations (B, heads, N, F), then
            // each head's rows of the map.
            let f = pairs.dim(3)?;
            let weighted = weights.unsqueeze(4)?.broadcast_mul(&pairs.unsqueeze(1)?)?.sum(3)?;
            let map = layer.weight().reshape((self.heads, dh, f))?.transpose(1, 2)?.unsqueeze(0)?;
            let bias = layer.bias().reshape((1, self.heads, 1, dh))?;
            out = (out + weighted.broadcast_matmul(&map)?.broadcast_add(&bias)?)?;
        }
        let out = out.transpose(1, 2)?.reshape((b, n, d))?;
        self.proj.forward(&out)
    }
}

fn modulate(x: &Tensor, shift: &Tensor, scale: &Tensor) -> Result<Tensor, GenError> {
    Ok(x.broadcast_mul(&(scale + 1.0)?)?.broadcast_add(shift)?)
}

/// The denoiser ε_θ(x_t, t, conditions).
#[derive(Debug, Clone)]
pub struct Denoiser {
    pub(super) cfg: ModelConfig,
    pub(super) input: Linear,
    /// With anchored slots: the embedding of a slot's contact box, added to its token.
    pub(super) anchor: Option<Linear>,
    /// With the relation bias: the MLP from a pair's relation to one score bias per head.
    pub(super) relation: Option<[Linear; 2]>,
    /// With wall features: the embedding of a slot's wall distances, added to its token.
    pub(super) walls: Option<Linear>,
    /// With Fourier features: the embedding of a slot's sines and cosines, added to its token.
    pub(super) fourier: Option<Linear>,
    /// With noise-scaled features: the embedding of a slot's attributes in units of the noise.
    pub(super) noise_scaled: Option<Linear>,
    /// With gap features: the embedding of the gaps ahead of a slot's piece, added to its token.
    pub(super) gaps: Option<Linear>,
    /// With self-conditioning: the embedding of the previous clean estimate of a slot, added to
    /// its token.
    pub(super) estimate: Option<Linear>,
    /// With slot roles: the embedding of a free slot's rank among the free slots, added to its
    /// token.
    pub(super) roles: Option<Linear>,
    /// With world features: the embedding of a slot's centre and yaw in world form, added to its
    /// token.
    pub(super) world: Option<Linear>,
    pub(super) time: [Linear; 2],
    pub(super) contact: [Linear; 2],
    pub(super) contact_kind: Tensor,
    pub(super) floor: PointNet,
    pub(super) free: PointNet,
    pub(super) blocks: Vec<Block>,
    pub(super) final_modulation: Linear,
    pub(super) output: Linear,
    /// With a room token: one learned vector per room type ([`RoomType::ALL`]), added to the
    /// condition; a bias-free linear layer's weight (d × rooms) applied to the one-hot room.
    pub(super) room: Option<Tensor>,
    /// With count conditioning: a bias-free linear layer's weight (d × categories) applied to
    /// the counts, added to the condition.
    pub(super) counts: Option<Tensor>,
    /// Every parameter by name (the checkpoint's names).
    pub(super) named: BTreeMap<String, Tensor>,
}

impl Denoiser {
    /// Builds the model, taking every parameter from `p` (fresh or loaded).
    pub fn new(cfg: &ModelConfig, p: &mut Params) -> Result<Denoiser, GenError> {
        if let Some(problem) = cfg.problem() {
            return Err(GenError::checkpoint("", format!("bad model config: {problem}")));
        }
        let d = cfg.d_model;
        let w = cfg.pointnet_width;
        let model = Denoiser {
            cfg: cfg.clone(),
            input: p.linear("input", cfg.token_dim(), d, false)?,
            anchor: match cfg.anchor_scale > 0.0 {
                true => Some(p.linear("anchor", CONTACT_FEATURES, d, false)?),
                false => None,
            },
            relation: match cfg.relation_bias {
                true => Some([
                    p.linear("relation.0", RELATION_FEATURES, RELATION_HIDDEN, false)?,
                    p.linear("relation.1", RELATION_HIDDEN, cfg.heads, true)?,
                ]),
                false => None,
            },
            walls: match cfg.wall_features {
                true => Some(p.linear("walls", WALL_FEATURES, d, false)?),
                false => None,
            },
            fourier: match cfg.fourier_bands {
                0 => None,
                _ => Some(p.linear("fourier", fourier::features_per_slot(cfg), d, false)?),
            },
            noise_scaled: match cfg.noise_scaled_features {
                true => Some(p.linear("noise_scaled", noise_scaled::features_per_slot(), d, false)?),
                false => None,
            },
            gaps: match cfg.gap_bounds {
                Some(_) => Some(p.linear("gaps", GAP_FEATURES, d, false)?),
                None => None,
            },
            estimate: match cfg.self_condition {
                true => Some(p.linear("estimate", cfg.token_dim(), d, true)?),
                false => None,
            },
            roles: match cfg.slot_roles {
                true => Some(p.linear("roles", cfg.slots(), d, false)?),
                false => None,
            },
            world: match cfg.world_features {
                true => Some(p.linear("world", anchors::WORLD_FEATURES, d, false)?),
                false => None,
            },
            time: [p.linear("time.0", TIME_FEATURES, d, false)?, p.linear("time.1", d, d, false)?],
            contact: [p.linear("contact.0", CONTACT_FEATURES, d, false)?, p.linear("contact.1", d, d, false)?],
            contact_kind: p.get("contact_kind", &[1, 1, d], Init::Normal(0.02))?,
            floor: PointNet::new(p, "floor", FLOOR_FEATURES, w, d)?,
            free: PointNet::new(p, "free", FREE_FEATURES, w, d)?,
            blocks: (0..cfg.blocks).map(|i| Block::new(p, &format!("blocks.{i}"), cfg)).collect::<Result<_, _>>()?,
            final_modulation: p.linear("final.modulation", d, 2 * d, true)?,
            output: p.linear("final.output", d, cfg.token_dim(), true)?,
            // Drawn last, so that a model without it starts from the same weights as before.
            room: match cfg.room_token {
                true => Some(p.get("room", &[d, RoomType::ALL.len()], Init::Normal(0.02))?),
                false => None,
            },
            counts: match cfg.count_condition {
                true => Some(p.get("counts", &[d, cfg.count_width()], Init::Normal(0.02))?),
                false => None,
            },
            named: BTreeMap::new(),
        };
        p.finish()?;
        let model = Denoiser { named: p.tensors(), ..model };
        Ok(model)
    }

    /// The configuration.
    pub fn config(&self) -> &ModelConfig {
        &self.cfg
    }

    /// The output (B, S, token_dim: ε or x₀, as the config's `prediction` says) for noisy tokens `x` (B, S, token_dim) at steps `t`.
    /// A self-conditioned model gets no previous estimate (zeros), as at the first sampling step.
    pub fn forward(&self, x: &Tensor, t: &[usize], cond: &CondTensors) -> Result<Tensor, GenError> {
        self.forward_with(x, t, cond, None)
    }

    /// [`forward`](Self::forward) with the previous clean estimate (B, S, token_dim) of a
    /// self-conditioned model (`None`: zeros; ignored by a model without self-conditioning).
    pub fn forward_with(
        &self,
        x: &Tensor,
        t: &[usize],
        cond: &CondTensors,
        estimate: Option<&Tensor>,
    ) -> Result<Tensor, GenError> {
        let (b, slots, _) = x.dims3()?;
        let time = self.time[1].forward(&self.time[0].forward(&time_features(t, x.device())?)?.silu()?)?;
        let contacts = self.contact[1].forward(&self.contact[0].forward(&cond.contacts)?.silu()?)?;
        let mask = cond.contact_mask.unsqueeze(2)?;
        let count = (mask.sum(1)? + 1e-6)?;
        let pooled = contacts.broadcast_mul(&mask)?.sum(1)?.broadcast_div(&count)?;
        let mut c = (time + pooled + self.floor.forward(&cond.floor)? + self.free.forward(&cond.free)?)?;
        if let Some(room) = &self.room {
            c = (c + cond.room.matmul(&room.t()?)?)?;
        }
        if let Some(counts) = &self.counts {
            c = (c + cond.counts.matmul(&counts.t()?)?)?;
        }
        let c = c.silu()?;

        let mut h = self.input.forward(x)?;
        if let Some(anchor) = &self.anchor {
            // Slot k < K gets the embedding of contact box k (nothing where the box is padding).
            let k = cond.contact_mask.dim(1)?;
            let embedded = anchor.forward(&cond.contacts)?.broadcast_mul(&mask)?;
            let padding = Tensor::zeros((b, slots - k, self.cfg.d_model), x.dtype(), x.device())?;
            h = (h + Tensor::cat(&[&embedded, &padding], 1)?)?;
        }
        if let Some(walls) = &self.walls {
            let features = self.slot_features(x, cond, WALL_FEATURES, |tokens, contacts, mask, floor| {
                walls::slot_features(&self.cfg, tokens, contacts, mask, floor)
            })?;
            h = (h + walls.forward(&features)?)?;
        }
        if let (Some(layer), Some(bounds)) = (&self.gaps, &self.cfg.gap_bounds) {
            let features = self.slot_features(x, cond, GAP_FEATURES, |tokens, contacts, mask, _| {
                gaps::slot_features(&self.cfg, bounds, tokens, contacts, mask)
            })?;
            h = (h + layer.forward(&features)?)?;
        }
        if let Some(layer) = &self.fourier {
            let (b, slots, _) = x.dims3()?;
            let features = fourier::slot_features(&self.cfg, &x.flatten_all()?.to_vec1::<f32>()?);
            let width = fourier::features_per_slot(&self.cfg);
            h = (h + layer.forward(&Tensor::from_vec(features, (b, slots, width), x.device())?)?)?;
        }
        if let Some(layer) = &self.noise_scaled {
            let (b, slots, _) = x.dims3()?;
            let features = noise_scaled::slot_features(&self.cfg, t, &x.flatten_all()?.to_vec1::<f32>()?);
            let width = noise_scaled::features_per_slot();
            h = (h + layer.forward(&Tensor::from_vec(features, (b, slots, width), x.device())?)?)?;
        }
        if let Some(layer) = &self.world {
            let features = self.slot_features(x, cond, anchors::WORLD_FEATURES, |tokens, contacts, mask, _| {
                anchors::world_slot_features(&self.cfg, tokens, contacts, mask)
            })?;
            h = (h + layer.forward(&features)?)?;
        }
        if let Some(layer) = &self.roles {
            let features =
                self.slot_features(x, cond, self.cfg.slots(), |_, _, mask, _| roles::slot_features(&self.cfg, mask))?;
            h = (h + layer.forward(&features)?)?;
        }
        if let Some(layer) = &self.estimate {
            let zeros;
            let estimate = match estimate {
                Some(e) => e,
                None => {
                    zeros = x.zeros_like()?;
                    &zeros
                }
            };
            h = (h + layer.forward(estimate)?)?;
        }
        let mut bias = None;
        if self.cfg.contact_tokens {
            let k = cond.contact_mask.dim(1)?;
            h = Tensor::cat(&[&h, &contacts.broadcast_add(&self.contact_kind)?], 1)?;
            let visible = Tensor::cat(&[&Tensor::ones((b, slots), x.dtype(), x.device())?, &cond.contact_mask], 1)?;
            bias = Some(((visible - 1.0)? * 1e9)?.reshape((b, 1, 1, slots + k))?);
        }
        if let Some(relation) = &self.relation {
            let rel = self.relation_bias(relation, x, cond)?;
            bias = Some(match bias {
                Some(mask) => rel.broadcast_add(&mask)?,
                None => rel,
            });
        }
        let pairs = match self.cfg.relation_values {
            true => Some(self.pair_tensor(x, cond, RELATION_VALUE_FEATURES, relations::value_features)?),
            false => None,
        };
        for block in &self.blocks {
            h = block.forward(&h, &c, bias.as_ref(), pairs.as_ref())?;
        }
        let h = h.narrow(1, 0, slots)?;
        let d = self.cfg.d_model;
        let m = self.final_modulation.forward(&c)?;
        let (shift, scale) = (m.narrow(1, 0, d)?.unsqueeze(1)?, m.narrow(1, d, d)?.unsqueeze(1)?);
        self.output.forward(&modulate(&layer_norm(&h)?, &shift, &scale)?)
    }
}

impl Denoiser {
    /// Features (B, S, `width`) of the noisy tokens `x` computed on the host, item by item, by
    /// `per_item(tokens, contacts, mask, floor)` (one item's slots, contact boxes, their mask and
    /// floor-plan points).
    fn slot_features(
        &self,
        x: &Tensor,
        cond: &CondTensors,
        width: usize,
        per_item: impl Fn(&[f32], &[f32], &[f32], &[f32]) -> Vec<f32>,
    ) -> Result<Tensor, GenError> {
        let cfg = &self.cfg;
        let (b, slots, dim) = x.dims3()?;
        let (k, f) = (cfg.max_contacts, cfg.floor_points * FLOOR_FEATURES);
        let values = x.flatten_all()?.to_vec1::<f32>()?;
        let contacts = cond.contacts.flatten_all()?.to_vec1::<f32>()?;
        let mask = cond.contact_mask.flatten_all()?.to_vec1::<f32>()?;
        let floor = cond.floor.flatten_all()?.to_vec1::<f32>()?;
        let mut features = Vec::with_capacity(b * slots * width);
        for item in 0..b {
            features.extend(per_item(
                &values[item * slots * dim..(item + 1) * slots * dim],
                &contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES],
                &mask[item * k..(item + 1) * k],
                &floor[item * f..(item + 1) * f],
            ));
        }
        Ok(Tensor::from_vec(features, (b, slots, width), x.device())?)
    }

    /// The relation bias (B, heads, N, N) of the noisy tokens `x` and the contact boxes (which
    /// are rows only with `contact_tokens`), from features computed on the host.
    fn relation_bias(&self, relation: &[Linear; 2], x: &Tensor, cond: &CondTensors) -> Result<Tensor, GenError> {
        let f = self.pair_tensor(x, cond, RELATION_FEATURES, relations::pair_features)?;
        let out = relation[1].forward(&relation[0].forward(&f)?.silu()?)?;
        Ok(out.permute((0, 3, 1, 2))?.contiguous()?)
    }

    /// Features (B, N, N, `width`) of every ordered pair of tokens (the object slots, then the
    /// contact boxes where they are rows), computed on the host from their poses by `of_poses`.
    fn pair_tensor(
        &self,
        x: &Tensor,
        cond: &CondTensors,
        width: usize,
        of_poses: fn(&[relations::TokenPose]) -> Vec<f32>,
    ) -> Result<Tensor, GenError> {
        let cfg = &self.cfg;
        let (b, slots, dim) = x.dims3()?;
        let k = cfg.max_contacts;
        let values = x.flatten_all()?.to_vec1::<f32>()?;
        let contacts = cond.contacts.flatten_all()?.to_vec1::<f32>()?;
        let mask = cond.contact_mask.flatten_all()?.to_vec1::<f32>()?;
        let n = if cfg.contact_tokens { slots + k } else { slots };
        let mut features = Vec::with_capacity(b * n * n * width);
        for item in 0..b {
            let mut poses = relations::poses(
                cfg,
                &values[item * slots * dim..(item + 1) * slots * dim],
                &contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES],
                &mask[item * k..(item + 1) * k],
                true,
            );
            poses.truncate(n);
            features.extend(of_poses(&poses));
        }
        Ok(Tensor::from_vec(features, (b, n, n, width), x.device())?)
    }
}

/// Sinusoidal features of the steps `t`: (B, TIME_FEATURES), half sines, half cosines.
pub fn time_features(t: &[usize], device: &Device) -> Result<Tensor, GenError> {
    Ok(Tensor::from_vec(time_feature_values(t), (t.len(), TIME_FEATURES), device)?)
}

/// The values of [`time_features`], row-major.
pub(super) fn time_feature_values(t: &[usize]) -> Vec<f32> {
    let half = TIME_FEATURES / 2;
    let mut values = Vec::with_capacity(t.len() * TIME_FEATURES);
    for &step in t {
        let freqs = (0..half).map(|i| (-(10_000f64.ln()) * i as f64 / half as f64).exp() * step as f64);
        let angles: Vec<f64> = freqs.collect();
        values.extend(angles.iter().map(|a| a.sin() as f32));
        values.extend(angles.iter().map(|a| a.cos() as f32));
    }
    values
}

#[cfg(test)]
mod tests {
    use super::*;

    fn random(shape: &[usize], seed: u64) -> Tensor {
        let mut rng = crate::data::Rng::new(seed);
        let n = shape.iter().product();
        Tensor::from_vec((0..n).map(|_| rng.normal() as f32).collect::<Vec<_>>(), shape, &Device::Cpu).unwrap()
    }

    fn cond(cfg: &ModelConfig, b: usize, contacts: usize) -> CondTensors {
        let k = cfg.max_contacts;
        let mask: Vec<f32> = (0..b * k).map(|i| if i % k < contacts { 1.0 } else { 0.0 }).collect();
        CondTensors {
            contacts: random(&[b, k, CONTACT_FEATURES], 1),
            contact_mask: Tensor::from_vec(mask, (b, k), &Device::Cpu).unwrap(),
            floor: random(&[b, cfg.floor_points, FLOOR_FEATURES], 2),
            free: random(&[b, cfg.free_points, FREE_FEATURES], 3),
            room: Tensor::from_vec(
                (0..b * 3).map(|i| if i % 3 == (i / 3) % 3 { 1.0 } else { 0.0 }).collect::<Vec<f32>>(),
                (b, 3),
                &Device::Cpu,
            )
            .unwrap(),
            counts: random(&[b, cfg.count_width()], 4),
        }
    }

    #[test]
    fn shapes_and_zero_output_at_initialisation() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let mut p = Params::random(7);
        let model = Denoiser::new(&cfg, &mut p).unwrap();
        let x = random(&[3, cfg.slots(), cfg.token_dim()], 4);
        let out = model.forward(&x, &[0, 50, 199], &cond(&cfg, 3, 2)).unwrap();
        assert_eq!(out.dims(), &[3, 12, 30]);
        // adaLN-Zero: the final modulation and output layer start at zero, so the prediction is zero.
        let max = out.abs().unwrap().max_all().unwrap().to_scalar::<f32>().unwrap();
        assert_eq!(max, 0.0);
    }

    #[test]
    fn every_block_starts_as_the_identity() {
        let cfg = ModelConfig::tiny(RoomType::Living);
        let mut p = Params::random(3);
        let model = Denoiser::new(&cfg, &mut p).unwrap();
        let x = random(&[2, 25, cfg.d_model], 5);
        let c = random(&[2, cfg.d_model], 6);
        for block in &model.blocks {
            let y = block.forward(&x, &c, None, None).unwrap();
            let diff = (y - &x).unwrap().abs().unwrap().max_all().unwrap().to_scalar::<f32>().unwrap();
            assert_eq!(diff, 0.0);
        }
    }

    #[test]
    fn masked_contact_tokens_do_not_change_the_objects() {
        // Perturb the padded contact boxes: object outputs must not move.
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let mut p = Params::random(1);
        let mut model = Denoiser::new(&cfg, &mut p).unwrap();
        // Give the output layers weights so outputs depend on the attention.
        model.final_modulation = Params::random(9).linear("m", cfg.d_model, 2 * cfg.d_model, false).unwrap();
        model.output = Params::random(10).linear("o", cfg.d_model, cfg.token_dim(), false).unwrap();
        for block in &mut model.blocks {
            block.modulation = Params::random(11).linear("b", cfg.d_model, 6 * cfg.d_model, false).unwrap();
        }
        let x = random(&[1, cfg.slots(), cfg.token_dim()], 4);
        let a = cond(&cfg, 1, 2);
        let mut b = a.clone();
        let k = cfg.max_contacts;
        let keep = a.contacts.narrow(1, 0, 2).unwrap();
        let noise = random(&[1, k - 2, CONTACT_FEATURES], 99);
        b.contacts = Tensor::cat(&[&keep, &noise], 1).unwrap();
        let ya = model.forward(&x, &[10], &a).unwrap();
        let yb = model.forward(&x, &[10], &b).unwrap();
        let diff = (ya - yb).unwrap().abs().unwrap().max_all().unwrap().to_scalar::<f32>().unwrap();
        assert!(diff < 1e-5, "{diff}");
    }

    #[test]
    fn the_same_seed_builds_the_same_model_and_checkpoints_must_fit() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let (mut a, mut b) = (Params::random(5), Params::random(5));
        Denoiser::new(&cfg, &mut a).unwrap();
        Denoiser::new(&cfg, &mut b).unwrap();
        let (sa, sb) = (a.snapshot().unwrap(), b.snapshot().unwrap());
        for (name, t) in &sa {
            let diff = (t - &sb[name]).unwrap().abs().unwrap().max_all().unwrap().to_scalar::<f32>().unwrap();
            assert_eq!(diff, 0.0, "{name}");
        }
        // A living-room checkpoint does not fit a bedroom model (token width differs).
        let mut living = Params::random(5);
        Denoiser::new(&ModelConfig::tiny(RoomType::Living), &mut living).unwrap();
        let tensors = living.snapshot().unwrap().into_iter().collect();
        let err = Denoiser::new(&cfg, &mut Params::loaded(tensors)).unwrap_err().to_string();
        // Loaded weights are frozen: inference records no graph (that would hold all 200 steps).
        let bedroom = a.snapshot().unwrap().into_iter().collect();
        let frozen = Denoiser::new(&cfg, &mut Params::loaded(bedroom)).unwrap();
        let x = random(&[1, cfg.slots(), cfg.token_dim()], 4);
        assert!(!frozen.forward(&x, &[3], &cond(&cfg, 1, 1)).unwrap().track_op());
        assert!(Denoiser::new(&cfg, &mut a).is_err(), "a second model from the same parameters redefines them");
        assert!(err.contains("input.weight has shape [32, 33], the model needs [32, 30]"), "{err}");
    }
}
