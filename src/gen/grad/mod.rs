//! Training without autograd: the denoiser's loss and its gradient with respect to every
//! parameter, computed by a forward pass that keeps its activations ([`forward`]) and a backward
//! pass written out by hand ([`backward`]), on flat `f32` vectors laid out by [`ParamLayout`].
//!
//! It computes the same function as [`super::Denoiser::forward`] and the same weighted L_simple as
//! the candle training path (tested: gradients equal candle's to 1e-4 of each tensor's scale).
//! What makes it faster at these sizes (≈ 20 tokens of width 128):
//! - the tokens of several batch items are stacked, so each linear layer is one `gemm` call over
//!   all their rows, forward and backward, with no per-operation tensor allocation or graph;
//! - padded contact tokens are left out (their attention weight is exactly 0, so is their gradient);
//! - the batch is cut into chunks of [`ITEMS_PER_CHUNK`] items that run on all cores, each with
//!   its own gradient buffer; buffers are summed in chunk order, so the result does not depend on
//!   the number of threads.
//!
//! Not here: the optimiser ([`super::optim`]), batches and noise ([`super::dataset::NoisyBatch`]).

mod backward;
mod forward;
mod ops;
mod relation_values;

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES, RELATION_HIDDEN};
use super::dataset::{NoisyBatch, RelationPair};
use super::flat::ParamLayout;
use super::gaps::GAP_FEATURES;
use super::matmul::LinearAt;
use super::relations::{RELATION_FEATURES, RELATION_VALUE_FEATURES};
use super::walls::WALL_FEATURES;
use super::{GenError, ModelConfig};
use crate::scene::RoomType;
pub(crate) use forward::ConditionTape;
use rayon::prelude::*;

/// Batch items per chunk of work.
pub const ITEMS_PER_CHUNK: usize = 16;

/// Where one DiT block's layers lie.
#[derive(Debug, Clone)]
struct BlockAt {
    modulation: LinearAt,
    qkv: LinearAt,
    proj: LinearAt,
    fc1: LinearAt,
    fc2: LinearAt,
    /// With relation values ([`relation_values`]).
    relation_values: Option<LinearAt>,
}

/// The denoiser as layers over a flat parameter vector.
#[derive(Debug, Clone)]
pub struct GradNet {
    cfg: ModelConfig,
    params: usize,
    input: LinearAt,
    anchor: Option<LinearAt>,
    relation: Option<[LinearAt; 2]>,
    walls: Option<LinearAt>,
    fourier: Option<LinearAt>,
    noise_scaled: Option<LinearAt>,
    gaps: Option<LinearAt>,
    roles: Option<LinearAt>,
    world: Option<LinearAt>,
    estimate: Option<LinearAt>,
    time: [LinearAt; 2],
    contact: [LinearAt; 2],
    contact_kind: usize,
    floor: [LinearAt; 3],
    free: [LinearAt; 3],
    blocks: Vec<BlockAt>,
    final_modulation: LinearAt,
    output: LinearAt,
    /// With a room token: the room vectors, one per [`RoomType::ALL`].
    room: Option<TableAt>,
    /// With count conditioning: one vector per category, weighed by its count.
    counts: Option<TableAt>,
}

/// A bias-free linear layer on a per-item input vector into the condition (the room token, the
/// count condition): the checkpoint's d × width matrix, stored transposed (width rows of d).
#[derive(Debug, Clone, Copy)]
pub(super) struct TableAt {
    at: usize,
    width: usize,
}

impl TableAt {
    /// Per item of `inputs` (items × width): Σ_r input_r × row r (items × d).
    pub(super) fn map(&self, p: &[f32], inputs: &[f32], d: usize) -> Vec<f32> {
        let mut out = vec![0f32; inputs.len() / self.width.max(1) * d];
        for (x, o) in inputs.chunks_exact(self.width).zip(out.chunks_exact_mut(d)) {
            for (r, &w) in x.iter().enumerate().filter(|(_, w)| **w != 0.0) {
                o.iter_mut().zip(&p[self.at + r * d..self.at + (r + 1) * d]).for_each(|(o, v)| *o += w * v);
            }
        }
        out
    }

    /// Adds into `g` the rows' gradient for the output gradient `dout` (items × d).
    pub(super) fn backward(&self, g: &mut [f32], inputs: &[f32], d: usize, dout: &[f32]) {
        for (x, dc) in inputs.chunks_exact(self.width).zip(dout.chunks_exact(d)) {
            for (r, &w) in x.iter().enumerate().filter(|(_, w)| **w != 0.0) {
                g[self.at + r * d..self.at + (r + 1) * d].iter_mut().zip(dc).for_each(|(g, v)| *g += w * v);
            }
        }
    }
}

/// One chunk's conditions.
pub(crate) struct ConditionInputs<'a> {
    pub(crate) items: usize,
    pub(crate) contacts: &'a [f32],
    pub(crate) mask: &'a [f32],
    pub(crate) floor: &'a [f32],
    pub(crate) free: &'a [f32],
    /// Items × [`RoomType::ALL`]: the room type, one-hot.
    pub(crate) rooms: &'a [f32],
    /// Items × [`ModelConfig::count_width`]: the count condition.
    pub(crate) counts: &'a [f32],
}

impl<'a> ConditionInputs<'a> {
    /// Items `start..end` of a batch's conditions, laid out as `HostBatch` keeps them (contact
    /// boxes, their mask, floor-plan points, free-space points, room types, counts; item after
    /// item).
    pub(crate) fn span(cfg: &ModelConfig, all: [&'a [f32]; 6], start: usize, end: usize) -> ConditionInputs<'a> {
        let [contacts, mask, floor, free, rooms, counts] = all;
        let span = |values: &'a [f32], width: usize| &values[start * width..end * width];
        ConditionInputs {
            items: end - start,
            contacts: span(contacts, cfg.max_contacts * CONTACT_FEATURES),
            mask: span(mask, cfg.max_contacts),
            floor: span(floor, cfg.floor_points * FLOOR_FEATURES),
            free: span(free, cfg.free_points * FREE_FEATURES),
            rooms: span(rooms, RoomType::ALL.len()),
            counts: span(counts, cfg.count_width()),
        }
    }
}

/// One chunk's slice of a training batch.
struct ChunkInputs<'a> {
    cond: ConditionInputs<'a>,
    t: &'a [usize],
    noisy: &'a [f32],
    target: &'a [f32],
    weights: &'a [f32],
    /// Per item: whether it is self-conditioned (empty: none is).
    self_condition: &'a [bool],
    /// The relation loss's pairs of this chunk's items, `item` counted from the chunk's first.
    relations: Vec<RelationPair>,
}

/// The relation loss of a chunk's output `out` against its `target` (the batch's share, divided by
/// `total`), and with `dout` its gradient added there: each pair's error of one centre less the
/// other's, in world form ([`RelationPair::maps`]), squared and weighed. The error of a clean
/// estimate is the output's error times one factor per scene and prediction, which the pair's
/// weight (the scene's own weight) already carries, as for the tokens' own loss.
fn relation_loss(
    cfg: &ModelConfig,
    out: &[f32],
    target: &[f32],
    pairs: &[RelationPair],
    total: f32,
    mut dout: Option<&mut [f32]>,
) -> f64 {
    let (dim, per_item) = (cfg.token_dim(), cfg.slots() * cfg.token_dim());
    let mut loss = 0.0;
    for pair in pairs {
        let at = |slot: usize| pair.item * per_item + slot * dim;
        let error = |k: usize| -> [f32; 2] {
            let m = &pair.maps[k];
            let at = at(pair.slots[k]);
            let e = [out[at] - target[at], out[at + 1] - target[at + 1]];
            [m[0] * e[0] + m[1] * e[1], m[2] * e[0] + m[3] * e[1]]
        };
        let (a, b) = (error(0), error(1));
        let r = [a[0] - b[0], a[1] - b[1]];
        loss += f64::from(pair.weight * (r[0] * r[0] + r[1] * r[1]) / total);
        if let Some(dout) = dout.as_deref_mut() {
            for (k, sign) in [(0, 1.0f32), (1, -1.0)] {
                let m = &pair.maps[k];
                let at = at(pair.slots[k]);
                let g = 2.0 * sign * pair.weight / total;
                dout[at] += g * (m[0] * r[0] + m[2] * r[1]);
                dout[at + 1] += g * (m[1] * r[0] + m[3] * r[1]);
            }
        }
    }
    loss
}

impl GradNet {
    /// The layers of a `cfg` model laid out by `layout` (the layout of its parameters' snapshot).
    pub fn new(cfg: &ModelConfig, layout: &ParamLayout) -> Result<GradNet, GenError> {
        let linear = |name: &str, input: usize, output: usize| -> Result<LinearAt, GenError> {
            let weight = find(layout, &format!("{name}.weight"), &[output, input])?;
            let bias = find(layout, &format!("{name}.bias"), &[output])?;
            Ok(LinearAt { weight, bias, input, output })
        };
        let (d, w) = (cfg.d_model, cfg.pointnet_width);
        let pointnet = |name: &str, input: usize| -> Result<[LinearAt; 3], GenError> {
            Ok([
                linear(&format!("{name}.0"), input, w)?,
                linear(&format!("{name}.1"), w, 2 * w)?,
                linear(&format!("{name}.2"), 2 * w, d)?,
            ])
        };
        let blocks = (0..cfg.blocks)
            .map(|i| {
                let name = |part: &str| format!("blocks.{i}.{part}");
                Ok(BlockAt {
                    modulation: linear(&name("modulation"), d, 6 * d)?,
                    qkv: linear(&name("qkv"), d, 3 * d)?,
                    proj: linear(&name("proj"), d, d)?,
                    fc1: linear(&name("fc1"), d, cfg.mlp_ratio * d)?,
                    fc2: linear(&name("fc2"), cfg.mlp_ratio * d, d)?,
                    relation_values: match cfg.relation_values {
                        true => Some(linear(&name("relation_values"), RELATION_VALUE_FEATURES, d)?),
                        false => None,
                    },
                })
            })
            .collect::<Result<_, GenError>>()?;
        Ok(GradNet {
            cfg: cfg.clone(),
            params: layout.len(),
            input: linear("input", cfg.token_dim(), d)?,
            anchor: if cfg.anchor_scale > 0.0 { Some(linear("anchor", CONTACT_FEATURES, d)?) } else { None },
            relation: match cfg.relation_bias {
                true => Some([
                    linear("relation.0", RELATION_FEATURES, RELATION_HIDDEN)?,
                    linear("relation.1", RELATION_HIDDEN, cfg.heads)?,
                ]),
                false => None,
            },
            walls: if cfg.wall_features { Some(linear("walls", WALL_FEATURES, d)?) } else { None },
            fourier: match cfg.fourier_bands {
                0 => None,
                _ => Some(linear("fourier", super::fourier::features_per_slot(cfg), d)?),
            },
            noise_scaled: match cfg.noise_scaled_features {
                true => Some(linear("noise_scaled", super::noise_scaled::features_per_slot(), d)?),
                false => None,
            },
            gaps: if cfg.gap_bounds.is_some() { Some(linear("gaps", GAP_FEATURES, d)?) } else { None },
            roles: if cfg.slot_roles { Some(linear("roles", cfg.slots(), d)?) } else { None },
            world: match cfg.world_features {
                true => Some(linear("world", super::anchors::WORLD_FEATURES, d)?),
                false => None,
            },
            estimate: if cfg.self_condition { Some(linear("estimate", cfg.token_dim(), d)?) } else { None },
            time: [linear("time.0", super::config::TIME_FEATURES, d)?, linear("time.1", d, d)?],
            contact: [linear("contact.0", CONTACT_FEATURES, d)?, linear("contact.1", d, d)?],
            contact_kind: find(layout, "contact_kind", &[1, 1, d])?,
            floor: pointnet("floor", FLOOR_FEATURES)?,
            free: pointnet("free", FREE_FEATURES)?,
            blocks,
            final_modulation: linear("final.modulation", d, 2 * d)?,
            output: linear("final.output", d, cfg.token_dim())?,
            room: match cfg.room_token {
                true => {
                    Some(TableAt { at: find(layout, "room", &[d, RoomType::ALL.len()])?, width: RoomType::ALL.len() })
                }
                false => None,
            },
            counts: match cfg.count_condition {
                true => {
                    Some(TableAt { at: find(layout, "counts", &[d, cfg.count_width()])?, width: cfg.count_width() })
                }
                false => None,
            },
        })
    }

    /// The batch's weighted L_simple at `params`.
    pub fn loss(&self, params: &[f32], batch: &NoisyBatch) -> f64 {
        let total = batch.weight_total();
        let parts: Vec<f64> = self
            .chunks(batch)
            .par_iter()
            .map(|c| forward::Tape::run(self, params, c).loss(&self.cfg, c, total))
            .collect();
        parts.iter().sum()
    }

    /// The batch's weighted L_simple at `params` and its gradient (laid out like `params`).
    pub fn loss_and_grad(&self, params: &[f32], batch: &NoisyBatch) -> (f64, Vec<f32>) {
        assert_eq!(params.len(), self.params, "parameters of this layout");
        let total = batch.weight_total();
        let parts: Vec<(f64, Vec<f32>)> = self
            .chunks(batch)
            .par_iter()
            .map(|c| {
                let tape = forward::Tape::run(self, params, c);
                let mut grads = vec![0f32; self.params];
                backward::run(self, params, &tape, c, total, &mut grads);
                (tape.loss(&self.cfg, c, total), grads)
            })
            .collect();
        let mut parts = parts.into_iter();
        let (mut loss, mut grads) = parts.next().unwrap_or((0.0, vec![0f32; self.params]));
        for (l, g) in parts {
            loss += l;
            grads.iter_mut().zip(&g).for_each(|(a, b)| *a += b);
        }
        (loss, grads)
    }

    fn chunks<'a>(&self, batch: &'a NoisyBatch) -> Vec<ChunkInputs<'a>> {
        let cfg = &self.cfg;
        let per_item = cfg.slots() * cfg.token_dim();
        let host = &batch.host;
        (0..host.size)
            .step_by(ITEMS_PER_CHUNK)
            .map(|start| {
                let end = (start + ITEMS_PER_CHUNK).min(host.size);
                let span = |values: &'a [f32], width: usize| &values[start * width..end * width];
                let conditions =
                    [&host.contacts[..], &host.contact_mask, &host.floor, &host.free, &host.rooms, &host.counts];
                ChunkInputs {
                    cond: ConditionInputs::span(cfg, conditions, start, end),
                    t: &batch.t[start..end],
                    noisy: span(&batch.noisy, per_item),
                    target: span(&batch.target, per_item),
                    weights: span(&batch.loss_weights, per_item),
                    self_condition: match batch.self_condition.is_empty() {
                        true => &[],
                        false => &batch.self_condition[start..end],
                    },
                    relations: batch
                        .relations
                        .iter()
                        .filter(|r| (start..end).contains(&r.item))
                        .map(|r| RelationPair { item: r.item - start, ..r.clone() })
                        .collect(),
                }
            })
            .collect()
    }
}

impl GradNet {
    /// The model's configuration.
    pub fn config(&self) -> &ModelConfig {
        &self.cfg
    }

    /// Encodes one chunk's conditions (for sampling, once per batch).
    pub(crate) fn encode(&self, params: &[f32], inputs: &ConditionInputs) -> ConditionTape {
        ConditionTape::run(self, params, inputs)
    }

    /// The output (items × slots × token_dim) of a chunk whose conditions are `cond`, given the
    /// previous clean estimate `estimate` of a self-conditioned model (empty: zeros).
    pub(crate) fn predict(
        &self,
        params: &[f32],
        cond: &ConditionTape,
        t: &[usize],
        noisy: &[f32],
        estimate: &[f32],
    ) -> Vec<f32> {
        forward::StepTape::run(self, params, cond, t, noisy, estimate).out
    }
}

fn find(layout: &ParamLayout, name: &str, shape: &[usize]) -> Result<usize, GenError> {
    match layout.find(name) {
        Some((range, found)) if found == shape => Ok(range.start),
        Some((_, found)) => {
            Err(GenError::checkpoint("", format!("{name} has shape {found:?}, the model needs {shape:?}")))
        }
        None => Err(GenError::checkpoint("", format!("checkpoint lacks tensor {name}"))),
    }
}

#[cfg(test)]
mod tests;
