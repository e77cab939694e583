//! The denoiser's forward pass for sampling, in plain Rust on `f32` slices: the same function as
//! [`Denoiser::forward`] (within float rounding), without autograd, tensors or per-operation
//! allocation.
//!
//! Three things make it faster than the candle graph at these sizes (≈ 20 tokens of width 128):
//! - the conditions (contact boxes, floor-plan and free-space PointNets) are encoded once per batch,
//!   not once per step — only the time embedding changes between steps;
//! - padded contact tokens are left out: their attention bias of −10⁹ gives them weight exactly 0
//!   in every visible token's softmax, so they never reach the object tokens;
//! - each batch item runs its blocks on its own thread-local buffers (items in parallel), with layer
//!   norm, modulation, gating and residuals fused into single passes around `gemm`'s matrix products.
//!
//! Each item's result depends on that item only, so an item sampled alone or in a batch gets the
//! same numbers. Training keeps using candle (it needs gradients).

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES, TIME_FEATURES};
use super::model::{CondTensors, Denoiser, time_feature_values};
use super::params::Linear;
use super::{GenError, ModelConfig};
use rayon::prelude::*;

/// A linear layer `y = x Wᵀ + b` with Wᵀ stored input-major (`input × output`).
#[derive(Debug, Clone)]
struct Dense {
    weight_t: Vec<f32>,
    bias: Vec<f32>,
    input: usize,
    output: usize,
}

impl Dense {
    fn of(linear: &Linear) -> Result<Dense, GenError> {
        let (weight, bias, output, input) = linear.host()?;
        let mut weight_t = vec![0f32; input * output];
        for o in 0..output {
            for i in 0..input {
                weight_t[i * output + o] = weight[o * input + i];
            }
        }
        Ok(Dense { weight_t, bias, input, output })
    }

    /// Several layers with the same input as one (outputs side by side, in order).
    fn side_by_side(parts: &[Dense]) -> Dense {
        let input = parts[0].input;
        let output: usize = parts.iter().map(|p| p.output).sum();
        let mut weight_t = Vec::with_capacity(input * output);
        for i in 0..input {
            for p in parts {
                weight_t.extend_from_slice(&p.weight_t[i * p.output..(i + 1) * p.output]);
            }
        }
        Dense { weight_t, bias: parts.iter().flat_map(|p| p.bias.iter().copied()).collect(), input, output }
    }

    /// `y` (rows × output) = `x` (rows × input) Wᵀ + b.
    fn apply(&self, x: &[f32], y: &mut [f32]) {
        let rows = x.len() / self.input;
        assert_eq!(x.len(), rows * self.input, "input width");
        assert_eq!(y.len(), rows * self.output, "output size");
        for row in y.chunks_exact_mut(self.output) {
            row.copy_from_slice(&self.bias);
        }
        if rows == 0 {
            return;
        }
        let (k, n) = (self.input as isize, self.output as isize);
        // SAFETY: `x` holds rows × input, `weight_t` input × output and `y` rows × output values
        // (checked above), all row-major with the strides given; `y` does not alias the inputs.
        unsafe {
            gemm::gemm(
                rows,
                self.output,
                self.input,
                y.as_mut_ptr(),
                1,
                n,
                true,
                x.as_ptr(),
                1,
                k,
                self.weight_t.as_ptr(),
                1,
                n,
                1.0,
                1.0,
                false,
                false,
                false,
                gemm::Parallelism::None,
            );
        }
    }

    /// `apply` into a new vector.
    fn map(&self, x: &[f32]) -> Vec<f32> {
        let mut y = vec![0f32; x.len() / self.input * self.output];
        self.apply(x, &mut y);
        y
    }
}

#[derive(Debug, Clone)]
struct FastBlock {
    qkv: Dense,
    proj: Dense,
    fc1: Dense,
    fc2: Dense,
}

/// The denoiser's weights laid out for [`FastDenoiser::forward`].
#[derive(Debug, Clone)]
pub struct FastDenoiser {
    cfg: ModelConfig,
    input: Dense,
    time: [Dense; 2],
    contact: [Dense; 2],
    contact_kind: Vec<f32>,
    floor: [Dense; 3],
    free: [Dense; 3],
    blocks: Vec<FastBlock>,
    /// Every block's modulation, then the final one, as one layer of c.
    modulation: Dense,
    output: Dense,
}

/// One batch's encoded conditions and its working buffers, made by [`FastDenoiser::prepare`].
#[derive(Debug, Clone)]
pub struct PreparedBatch {
    items: Vec<ItemBuffers>,
}

/// One item's encoded conditions and the scratch space of its forward pass.
#[derive(Debug, Clone)]
struct ItemBuffers {
    /// Pooled contact encoding, floor PointNet and free-space PointNet (d each), kept apart so that
    /// c sums in the same order as the candle model.
    pooled: Vec<f32>,
    floor: Vec<f32>,
    free: Vec<f32>,
    /// The visible contact boxes' tokens.
    contact_tokens: Vec<f32>,
    c: Vec<f32>,
    modulation: Vec<f32>,
    h: Vec<f32>,
    normed: Vec<f32>,
    qkv: Vec<f32>,
    attended: Vec<f32>,
    branch: Vec<f32>,
    hidden: Vec<f32>,
    weights: Vec<f32>,
}

impl FastDenoiser {
    /// The weights of `model`, copied out of its tensors.
    pub fn of(model: &Denoiser) -> Result<FastDenoiser, GenError> {
        let pointnet = |p: &super::model::PointNet| -> Result<[Dense; 3], GenError> {
            Ok([Dense::of(&p.layers[0])?, Dense::of(&p.layers[1])?, Dense::of(&p.layers[2])?])
        };
        let mut modulations: Vec<Dense> =
            model.blocks.iter().map(|b| Dense::of(&b.modulation)).collect::<Result<_, _>>()?;
        modulations.push(Dense::of(&model.final_modulation)?);
        Ok(FastDenoiser {
            cfg: model.cfg.clone(),
            input: Dense::of(&model.input)?,
            time: [Dense::of(&model.time[0])?, Dense::of(&model.time[1])?],
            contact: [Dense::of(&model.contact[0])?, Dense::of(&model.contact[1])?],
            contact_kind: model.contact_kind.flatten_all()?.to_vec1()?,
            floor: pointnet(&model.floor)?,
            free: pointnet(&model.free)?,
            blocks: model
                .blocks
                .iter()
                .map(|b| {
                    Ok(FastBlock {
                        qkv: Dense::of(&b.qkv)?,
                        proj: Dense::of(&b.proj)?,
                        fc1: Dense::of(&b.fc1)?,
                        fc2: Dense::of(&b.fc2)?,
                    })
                })
                .collect::<Result<_, GenError>>()?,
            modulation: Dense::side_by_side(&modulations),
            output: Dense::of(&model.output)?,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &ModelConfig {
        &self.cfg
    }

    /// Encodes the conditions of a batch once, for every step that follows.
    pub fn prepare(&self, cond: &CondTensors) -> Result<PreparedBatch, GenError> {
        let (b, k, _) = cond.contacts.dims3()?;
        let contacts: Vec<f32> = cond.contacts.flatten_all()?.to_vec1()?;
        let mask: Vec<f32> = cond.contact_mask.flatten_all()?.to_vec1()?;
        let floor: Vec<f32> = cond.floor.flatten_all()?.to_vec1()?;
        let free: Vec<f32> = cond.free.flatten_all()?.to_vec1()?;
        let per_item = |v: &[f32]| (v.len() / b.max(1)).max(1);
        let items = contacts
            .par_chunks_exact(per_item(&contacts))
            .zip(mask.par_chunks_exact(k.max(1)))
            .zip(floor.par_chunks_exact(per_item(&floor)))
            .zip(free.par_chunks_exact(per_item(&free)))
            .map(|(((contacts, mask), floor), free)| self.prepare_item(contacts, mask, floor, free))
            .collect();
        Ok(PreparedBatch { items })
    }

    /// One item's encoded conditions (every item is computed alone: its numbers never depend on the
    /// rest of the batch).
    fn prepare_item(&self, contacts: &[f32], mask: &[f32], floor: &[f32], free: &[f32]) -> ItemBuffers {
        let d = self.cfg.d_model;
        debug_assert_eq!(contacts.len(), mask.len() * CONTACT_FEATURES);
        let mut encoded = self.contact[0].map(contacts);
        silu(&mut encoded);
        let encoded = self.contact[1].map(&encoded);
        let count: f32 = mask.iter().sum::<f32>() + 1e-6;
        let mut pooled = vec![0f32; d];
        for (row, &w) in encoded.chunks_exact(d).zip(mask) {
            pooled.iter_mut().zip(row).for_each(|(p, v)| *p += v * w);
        }
        pooled.iter_mut().for_each(|p| *p /= count);
        let mut contact_tokens = Vec::new();
        if self.cfg.contact_tokens {
            for (row, &w) in encoded.chunks_exact(d).zip(mask) {
                if w != 0.0 {
                    contact_tokens.extend(row.iter().zip(&self.contact_kind).map(|(v, kind)| v + kind));
                }
            }
        }
        let n = self.cfg.slots() + contact_tokens.len() / d;
        ItemBuffers {
            pooled,
            floor: pointnet(&self.floor, floor, FLOOR_FEATURES),
            free: pointnet(&self.free, free, FREE_FEATURES),
            contact_tokens,
            c: vec![0.0; d],
            modulation: vec![0.0; self.modulation.output],
            h: vec![0.0; n * d],
            normed: vec![0.0; n * d],
            qkv: vec![0.0; n * 3 * d],
            attended: vec![0.0; n * d],
            branch: vec![0.0; n * d],
            hidden: vec![0.0; n * self.cfg.mlp_ratio * d],
            weights: vec![0.0; n],
        }
    }

    /// Predicted noise (B × slots × token_dim) for noisy tokens `x` (B × slots × token_dim), every
    /// item at step `t`.
    pub fn forward(&self, batch: &mut PreparedBatch, x: &[f32], t: usize) -> Vec<f32> {
        let cfg = &self.cfg;
        let b = batch.items.len();
        let per_item = cfg.slots() * cfg.token_dim();
        assert_eq!(x.len(), b * per_item, "tokens of the prepared batch");

        let features = time_feature_values(&[t]);
        debug_assert_eq!(features.len(), TIME_FEATURES);
        let mut time = self.time[0].map(&features);
        silu(&mut time);
        let time = self.time[1].map(&time);

        let mut out = vec![0f32; b * per_item];
        batch.items.par_iter_mut().zip(out.par_chunks_exact_mut(per_item)).enumerate().for_each(
            |(item, (buf, eps))| {
                for (i, c) in buf.c.iter_mut().enumerate() {
                    *c = time[i] + buf.pooled[i] + buf.floor[i] + buf.free[i];
                }
                silu(&mut buf.c);
                self.modulation.apply(&buf.c, &mut buf.modulation);
                self.item_forward(buf, &x[item * per_item..(item + 1) * per_item], eps);
            },
        );
        out
    }

    /// One item's pass through the blocks and the output layer, modulated by `buf.modulation`.
    fn item_forward(&self, buf: &mut ItemBuffers, x: &[f32], eps: &mut [f32]) {
        let (d, m) = (self.cfg.d_model, &buf.modulation);
        let slots = self.cfg.slots();
        let objects = slots * d;
        self.input.apply(x, &mut buf.h[..objects]);
        buf.h[objects..].copy_from_slice(&buf.contact_tokens);
        for (i, block) in self.blocks.iter().enumerate() {
            let part = |j: usize| &m[(6 * i + j) * d..(6 * i + j + 1) * d];
            norm_modulate(&buf.h, part(0), part(1), &mut buf.normed, d);
            block.qkv.apply(&buf.normed, &mut buf.qkv);
            attention(&buf.qkv, self.cfg.heads, d, &mut buf.weights, &mut buf.attended);
            block.proj.apply(&buf.attended, &mut buf.branch);
            add_gated(&mut buf.h, &buf.branch, part(2));
            norm_modulate(&buf.h, part(3), part(4), &mut buf.normed, d);
            block.fc1.apply(&buf.normed, &mut buf.hidden);
            silu(&mut buf.hidden);
            block.fc2.apply(&buf.hidden, &mut buf.branch);
            add_gated(&mut buf.h, &buf.branch, part(5));
        }
        let last = 6 * self.blocks.len() * d;
        let (shift, scale) = (&m[last..last + d], &m[last + d..last + 2 * d]);
        norm_modulate(&buf.h[..objects], shift, scale, &mut buf.normed[..objects], d);
        self.output.apply(&buf.normed[..objects], eps);
    }
}

/// A PointNet over one item's points with `features` values each: max over points of the MLP.
fn pointnet(layers: &[Dense; 3], points: &[f32], features: usize) -> Vec<f32> {
    let mut h = layers[0].map(points);
    relu(&mut h);
    let mut h = layers[1].map(&h);
    relu(&mut h);
    let h = layers[2].map(&h);
    debug_assert_eq!(points.len() % features, 0);
    let mut max = vec![f32::NEG_INFINITY; layers[2].output];
    for row in h.chunks_exact(layers[2].output) {
        max.iter_mut().zip(row).for_each(|(m, v)| *m = m.max(*v));
    }
    max
}

/// Parameter-free layer norm of each row of `x`, then `· (1 + scale) + shift`, into `out`.
fn norm_modulate(x: &[f32], shift: &[f32], scale: &[f32], out: &mut [f32], d: usize) {
    for (row, dst) in x.chunks_exact(d).zip(out.chunks_exact_mut(d)) {
        let mean = row.iter().sum::<f32>() / d as f32;
        let var = row.iter().map(|v| (v - mean) * (v - mean)).sum::<f32>() / d as f32;
        let inv = 1.0 / (var + 1e-6).sqrt();
        for (((o, v), sc), sh) in dst.iter_mut().zip(row).zip(scale).zip(shift) {
            *o = (v - mean) * inv * (1.0 + sc) + sh;
        }
    }
}

/// `h += gate · branch`, the gate broadcast over rows.
fn add_gated(h: &mut [f32], branch: &[f32], gate: &[f32]) {
    let d = gate.len();
    for (row, add) in h.chunks_exact_mut(d).zip(branch.chunks_exact(d)) {
        for ((v, a), g) in row.iter_mut().zip(add).zip(gate) {
            *v += g * a;
        }
    }
}

/// Multi-head self-attention over all rows of `qkv` (n × 3d, laid out q | k | v, heads within
/// each), into `out` (n × d). `weights` holds one row of scores.
fn attention(qkv: &[f32], heads: usize, d: usize, weights: &mut [f32], out: &mut [f32]) {
    let n = qkv.len() / (3 * d);
    let dh = d / heads;
    let scale = 1.0 / (dh as f32).sqrt();
    for head in 0..heads {
        let (q_at, k_at, v_at) = (head * dh, d + head * dh, 2 * d + head * dh);
        for i in 0..n {
            let q = &qkv[i * 3 * d + q_at..i * 3 * d + q_at + dh];
            let mut max = f32::NEG_INFINITY;
            for (j, w) in weights.iter_mut().enumerate().take(n) {
                let k = &qkv[j * 3 * d + k_at..j * 3 * d + k_at + dh];
                *w = q.iter().zip(k).map(|(a, b)| a * b).sum::<f32>() * scale;
                max = max.max(*w);
            }
            let mut total = 0.0;
            for w in weights.iter_mut().take(n) {
                *w = (*w - max).exp();
                total += *w;
            }
            let dst = &mut out[i * d + head * dh..i * d + (head + 1) * dh];
            dst.fill(0.0);
            for (j, w) in weights.iter().enumerate().take(n) {
                let v = &qkv[j * 3 * d + v_at..j * 3 * d + v_at + dh];
                let w = w / total;
                dst.iter_mut().zip(v).for_each(|(o, x)| *o += w * x);
            }
        }
    }
}

fn silu(v: &mut [f32]) {
    v.iter_mut().for_each(|x| *x /= 1.0 + (-*x).exp());
}

fn relu(v: &mut [f32]) {
    v.iter_mut().for_each(|x| *x = x.max(0.0));
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::generator::{Features, HostBatch, shipped_model};
    use crate::human::Conditions;
    use crate::scene::RoomType;
    use candle_core::{Device, Tensor};

    /// The shipped living-room model (trained weights: every modulation and gate is non-zero) on
    /// real conditions with 1 to 8 contact boxes, at several steps.
    #[test]
    fn the_fast_pass_computes_what_the_candle_model_computes() {
        let checkpoint = shipped_model(RoomType::Living).unwrap();
        let (model, cfg) = (&checkpoint.denoiser, &checkpoint.meta.model);
        let fast = FastDenoiser::of(model).unwrap();
        let mut batch = HostBatch::default();
        let mut contacts = Vec::new();
        for seed in 0..6 {
            let scene = generate_room(RoomType::Living, 3, seed, false).scene;
            let f = Features::of(&Conditions::of(&scene), &checkpoint.meta.bounds, cfg);
            contacts.push(f.contact_mask.iter().sum::<f32>() as usize);
            batch.push_features(&f);
        }
        assert!(contacts.iter().any(|&k| k < cfg.max_contacts) && contacts.iter().all(|&k| k > 0), "{contacts:?}");
        let cond = batch.cond(cfg).unwrap();
        let mut prepared = fast.prepare(&cond).unwrap();
        let mut rng = crate::data::Rng::new(4);
        let n = 6 * cfg.slots() * cfg.token_dim();
        let x: Vec<f32> = (0..n).map(|_| rng.normal() as f32).collect();
        let xt = Tensor::from_vec(x.clone(), (6, cfg.slots(), cfg.token_dim()), &Device::Cpu).unwrap();
        for t in [0, 57, 199] {
            let want: Vec<f32> = model.forward(&xt, &[t; 6], &cond).unwrap().flatten_all().unwrap().to_vec1().unwrap();
            let got = fast.forward(&mut prepared, &x, t);
            let scale = want.iter().fold(0f32, |m, v| m.max(v.abs()));
            let worst = want.iter().zip(&got).fold(0f32, |m, (a, b)| m.max((a - b).abs()));
            assert!(scale > 0.1 && worst < 1e-4 * scale, "t {t}: worst {worst} of {scale}");
        }
    }

    #[test]
    fn an_item_gets_the_same_numbers_alone_and_in_a_batch() {
        let checkpoint = shipped_model(RoomType::Bedroom).unwrap();
        let cfg = &checkpoint.meta.model;
        let fast = FastDenoiser::of(&checkpoint.denoiser).unwrap();
        let features: Vec<Features> = (0..3)
            .map(|seed| {
                let scene = generate_room(RoomType::Bedroom, 5, seed, false).scene;
                Features::of(&Conditions::of(&scene), &checkpoint.meta.bounds, cfg)
            })
            .collect();
        let per_item = cfg.slots() * cfg.token_dim();
        let x: Vec<f32> = (0..3 * per_item).map(|i| ((i * 7919) % 200) as f32 / 100.0 - 1.0).collect();
        let mut all = HostBatch::default();
        features.iter().for_each(|f| all.push_features(f));
        let together = fast.forward(&mut fast.prepare(&all.cond(cfg).unwrap()).unwrap(), &x, 80);
        let mut one = HostBatch::default();
        one.push_features(&features[1]);
        let alone = fast.forward(&mut fast.prepare(&one.cond(cfg).unwrap()).unwrap(), &x[per_item..2 * per_item], 80);
        assert!(together[per_item..2 * per_item] == alone[..]);
    }

    #[test]
    fn merged_layers_apply_like_the_parts() {
        let part = |seed: u64, output: usize| {
            let mut rng = crate::data::Rng::new(seed);
            let mut v = |n: usize| (0..n).map(|_| rng.normal() as f32).collect::<Vec<f32>>();
            Dense { weight_t: v(3 * output), bias: v(output), input: 3, output }
        };
        let (a, b) = (part(1, 2), part(2, 4));
        let x = [1.0, -2.0, 0.5, 0.0, 3.0, 1.0];
        let merged = Dense::side_by_side(&[a.clone(), b.clone()]).map(&x);
        let (ya, yb) = (a.map(&x), b.map(&x));
        for row in 0..2 {
            let want: Vec<f32> = ya[row * 2..row * 2 + 2].iter().chain(&yb[row * 4..row * 4 + 4]).copied().collect();
            assert_eq!(&merged[row * 6..row * 6 + 6], &want[..]);
        }
        // Hand-computed: first row of `a` is x·column 0 of Wᵀ plus the bias.
        let w = &a.weight_t;
        let first = x[0] * w[0] + x[1] * w[2] + x[2] * w[4] + a.bias[0];
        assert!((ya[0] - first).abs() < 1e-5);
    }
}
