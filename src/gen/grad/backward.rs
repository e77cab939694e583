//! The backward pass of one chunk: from the loss through the output layer, the blocks in reverse,
//! the tokens and the conditions, adding every parameter's gradient into a flat buffer.

use super::forward::{PointTape, Tape};
use super::ops::{self, Parts, PartsGrad};
use super::relation_values;
use super::{ChunkInputs, GradNet};
use crate::generator::matmul::LinearAt;

/// Adds the gradient of the chunk's share of the loss (divided by `total`) into `g`.
pub(super) fn run(net: &GradNet, p: &[f32], tape: &Tape, inp: &ChunkInputs, total: f32, g: &mut [f32]) {
    let cfg = &net.cfg;
    let (d, b) = (cfg.d_model, inp.cond.items);
    let objects = b * cfg.slots();
    let (cond, step) = (&tape.cond, &tape.step);
    let rows = cond.row_item.len();
    let row_item = &cond.row_item;

    let mut dout: Vec<f32> =
        step.out.iter().zip(inp.target).zip(inp.weights).map(|((o, n), w)| 2.0 * w * (o - n) / total).collect();
    super::relation_loss(cfg, &step.out, inp.target, &inp.relations, total, Some(&mut dout));
    let mut dfinal = vec![0f32; objects * d];
    net.output.backward(p, g, &step.final_m, &dout, Some(&mut dfinal));
    let mut dmod: Vec<Vec<f32>> = step.modulation.iter().map(|m| vec![0f32; m.len()]).collect();
    let last = step.modulation.len() - 1;
    let du = ops::modulate_backward(
        &step.final_u,
        Parts { values: &step.modulation[last], parts: 2, d },
        &mut PartsGrad { values: &mut dmod[last], parts: 2, d },
        0,
        &row_item[..objects],
        &dfinal,
    );
    let mut dbias: Vec<Vec<f32>> = step.relation_bias.iter().map(|b| vec![0f32; b.len()]).collect();
    let mut dh = vec![0f32; rows * d];
    ops::layer_norm_backward(&step.final_u, &step.final_rstd, &du, d, &mut dh[..objects * d]);

    for ((layers, bt), (m, dm)) in
        net.blocks.iter().zip(&step.blocks).zip(step.modulation.iter().zip(dmod.iter_mut())).rev()
    {
        let m = Parts { values: m, parts: 6, d };
        let mut dm = PartsGrad { values: dm, parts: 6, d };
        // h ← h + gate₂ · fc2(SiLU(fc1(modulate(LN(h)))))
        let dmlp = ops::add_gated_backward(&dh, &bt.mlp_out, m, &mut dm, 5, row_item);
        let mut dhidden = vec![0f32; bt.hidden.len()];
        layers.fc2.backward(p, g, &bt.hidden, &dmlp, Some(&mut dhidden));
        ops::silu_backward(&bt.fc1_out, &mut dhidden);
        let mut dm2 = vec![0f32; rows * d];
        layers.fc1.backward(p, g, &bt.m2, &dhidden, Some(&mut dm2));
        let du2 = ops::modulate_backward(&bt.u2, m, &mut dm, 3, row_item, &dm2);
        ops::layer_norm_backward(&bt.u2, &bt.rstd2, &du2, d, &mut dh);
        // h ← h + gate₁ · proj(attention(qkv(modulate(LN(h)))))
        let dattn = ops::add_gated_backward(&dh, &bt.attention_out, m, &mut dm, 2, row_item);
        let mut dattended = vec![0f32; rows * d];
        layers.proj.backward(p, g, &bt.attended, &dattn, Some(&mut dattended));
        let dbias = net.relation.as_ref().map(|_| &mut dbias[..]);
        let dprobs = layers.relation_values.as_ref().map(|layer| {
            let (weighted, pairs) = (&bt.weighted_relations, &step.relation_values_in);
            relation_values::backward(p, g, layer, weighted, pairs, &cond.items, cfg.heads, &dattended)
        });
        let dqkv = ops::attention_backward(
            &bt.qkv,
            &bt.probs,
            &cond.items,
            cfg.heads,
            d,
            &dattended,
            dbias,
            dprobs.as_deref(),
        );
        let mut dm1 = vec![0f32; rows * d];
        layers.qkv.backward(p, g, &bt.m1, &dqkv, Some(&mut dm1));
        let du1 = ops::modulate_backward(&bt.u1, m, &mut dm, 0, row_item, &dm1);
        ops::layer_norm_backward(&bt.u1, &bt.rstd1, &du1, d, &mut dh);
    }

    // Tokens: the object rows came from the input layer, the contact rows from the encoded boxes
    // plus the learned contact-kind vector.
    net.input.backward(p, g, inp.noisy, &dh[..objects * d], None);
    if let Some(walls) = &net.walls {
        walls.backward(p, g, &step.wall_in, &dh[..objects * d], None);
    }
    if let Some(fourier) = &net.fourier {
        fourier.backward(p, g, &step.fourier_in, &dh[..objects * d], None);
    }
    if let Some(layer) = &net.noise_scaled {
        layer.backward(p, g, &step.noise_scaled_in, &dh[..objects * d], None);
    }
    if let Some(gaps) = &net.gaps {
        gaps.backward(p, g, &step.gap_in, &dh[..objects * d], None);
    }
    if let Some(world) = &net.world {
        world.backward(p, g, &step.world_in, &dh[..objects * d], None);
    }
    if let Some(roles) = &net.roles {
        roles.backward(p, g, &step.role_in, &dh[..objects * d], None);
    }
    if let Some(estimate) = &net.estimate {
        estimate.backward(p, g, &step.estimate_in, &dh[..objects * d], None);
    }
    if let Some(anchor) = &net.anchor {
        let danchored: Vec<f32> = cond
            .contact_row
            .iter()
            .zip(&cond.contact_weight)
            .flat_map(|(&r, &w)| dh[r * d..(r + 1) * d].iter().map(move |v| v * w))
            .collect();
        anchor.backward(p, g, &cond.contact_in, &danchored, None);
    }
    let mut dencoded = dh[objects * d..].to_vec();
    let kind = &mut g[net.contact_kind..net.contact_kind + d];
    for row in dencoded.chunks_exact(d) {
        kind.iter_mut().zip(row).for_each(|(k, v)| *k += v);
    }

    // The relation bias is shared by every block's attention.
    if let Some(layers) = &net.relation {
        let heads = cfg.heads;
        let mut dout = vec![0f32; step.relation_act.len() / layers[1].input * heads];
        let mut at = 0;
        for (item, rows) in cond.items.iter().enumerate() {
            let pairs = rows.len() * rows.len();
            for head in 0..heads {
                for (q, v) in dbias[item * heads + head].iter().enumerate() {
                    dout[(at + q) * heads + head] = *v;
                }
            }
            at += pairs;
        }
        let mut dact = vec![0f32; step.relation_act.len()];
        layers[1].backward(p, g, &step.relation_act, &dout, Some(&mut dact));
        ops::silu_backward(&step.relation_pre, &mut dact);
        layers[0].backward(p, g, &step.relation_in, &dact, None);
    }

    // The condition c = SiLU(time + pooled contacts + floor + free) feeds every modulation.
    let mut dc = vec![0f32; b * d];
    for (layers, dm) in net.blocks.iter().zip(&dmod) {
        layers.modulation.backward(p, g, &step.c, dm, Some(&mut dc));
    }
    net.final_modulation.backward(p, g, &step.c, &dmod[last], Some(&mut dc));
    ops::silu_backward(&step.c_pre, &mut dc);
    for (table, inputs) in [(net.room, &cond.rooms), (net.counts, &cond.counts)] {
        if let Some(table) = table {
            table.backward(g, inputs, d, &dc);
        }
    }

    let mut dtime = vec![0f32; b * d];
    net.time[1].backward(p, g, &step.time_act, &dc, Some(&mut dtime));
    ops::silu_backward(&step.time_pre, &mut dtime);
    net.time[0].backward(p, g, &step.time_in, &dtime, None);

    for ((row, &item), &w) in dencoded.chunks_exact_mut(d).zip(&cond.contact_item).zip(&cond.contact_weight) {
        let scale = w / cond.contact_count[item];
        row.iter_mut().zip(&dc[item * d..(item + 1) * d]).for_each(|(r, v)| *r += v * scale);
    }
    let mut dcontact = vec![0f32; cond.contact_act.len()];
    net.contact[1].backward(p, g, &cond.contact_act, &dencoded, Some(&mut dcontact));
    ops::silu_backward(&cond.contact_pre, &mut dcontact);
    net.contact[0].backward(p, g, &cond.contact_in, &dcontact, None);

    pointnet_backward(p, g, &net.floor, &cond.floor, inp.cond.floor, &dc);
    pointnet_backward(p, g, &net.free, &cond.free, inp.cond.free, &dc);
}

/// A PointNet's backward pass for the gradient `dmax` (items × d) of its max over the points.
/// Every point that attains an item's max gets the gradient (as candle's max does on ties).
///
/// Only those (point, feature) pairs carry a gradient, so the last layer's backward pass runs
/// over them alone (about one in `points` of the dense product), and the first two layers' over
/// the points that attain at least one max.
fn pointnet_backward(p: &[f32], g: &mut [f32], layers: &[LinearAt; 3], tape: &PointTape, points: &[f32], dmax: &[f32]) {
    let last = &layers[2];
    let (d, width) = (last.output, last.input);
    let items = dmax.len() / d;
    let rows = tape.out.len() / d;
    let per_item = rows / items.max(1);
    let mut dh1 = vec![0f32; tape.h1.len()];
    let mut active = vec![false; rows];
    let mut entries: Vec<(usize, f32)> = Vec::with_capacity(d);
    for item in 0..items {
        let (max, dm) = (&tape.max[item * d..(item + 1) * d], &dmax[item * d..(item + 1) * d]);
        for r in item * per_item..(item + 1) * per_item {
            let values = &tape.out[r * d..(r + 1) * d];
            entries.clear();
            entries.extend(
                values
                    .iter()
                    .zip(max)
                    .zip(dm)
                    .enumerate()
                    .filter(|(_, ((v, m), dv))| v == m && **dv != 0.0)
                    .map(|(j, (_, dv))| (j, *dv)),
            );
            if entries.is_empty() {
                continue;
            }
            active[r] = true;
            // Wᵀ is stored input-major: row i holds every output's weight of input i.
            let h1 = &tape.h1[r * width..(r + 1) * width];
            for (i, (&h, dh)) in h1.iter().zip(&mut dh1[r * width..(r + 1) * width]).enumerate() {
                let at = last.weight + i * d;
                for &(j, dv) in &entries {
                    g[at + j] += dv * h;
                    *dh += dv * p[at + j];
                }
            }
            for &(j, dv) in &entries {
                g[last.bias + j] += dv;
            }
        }
    }
    let keep: Vec<usize> = (0..rows).filter(|&r| active[r]).collect();
    let gather = |values: &[f32], cols: usize| -> Vec<f32> {
        keep.iter().flat_map(|&r| values[r * cols..(r + 1) * cols].iter().copied()).collect()
    };
    let (h0, h1) = (gather(&tape.h0, layers[1].input), gather(&tape.h1, width));
    let mut dh1 = gather(&dh1, width);
    ops::relu_backward(&h1, &mut dh1);
    let mut dh0 = vec![0f32; h0.len()];
    layers[1].backward(p, g, &h0, &dh1, Some(&mut dh0));
    ops::relu_backward(&h0, &mut dh0);
    layers[0].backward(p, g, &gather(points, layers[0].input), &dh0, None);
}
