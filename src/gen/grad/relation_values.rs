//! Relation values ([`crate::generator::ModelConfig::relation_values`]) in the training engine:
//! what the pairs' relations add to an attention's output, and its backward pass.
//!
//! Head h of row i adds W_h ψ_hi + b_h, where ψ_hi = Σ_j p_hij f_ij weighs the pairs' value
//! features f_ij ([`crate::generator::relations::value_features`]) by the head's attention
//! weights, and W_h is the head's dh outputs of one linear layer (F → d) per block. The features
//! are computed from the noisy tokens and carry no gradient; the weights' gradient reaches the
//! scores through the attention's own backward pass ([`super::ops::attention_backward`]'s
//! `dprobs`). Not here: the features, the attention.

use crate::generator::matmul::LinearAt;

/// Adds the relation values into `attended` (rows × d) and returns ψ per (item, head) (n × F,
/// row-major), for the backward pass. `probs` are the attention's weights per (item, head) (n × n),
/// `pairs` each item's value features (n × n × F, its rows in `items` order).
pub(super) fn forward(
    p: &[f32],
    layer: &LinearAt,
    attended: &mut [f32],
    probs: &[Vec<f32>],
    pairs: &[Vec<f32>],
    items: &[Vec<usize>],
    heads: usize,
) -> Vec<Vec<f32>> {
    let (f, d) = (layer.input, layer.output);
    let dh = d / heads;
    let mut weighted = Vec::with_capacity(items.len() * heads);
    for (item, rows) in items.iter().enumerate() {
        let n = rows.len();
        let features = &pairs[item];
        for head in 0..heads {
            let probs = &probs[item * heads + head];
            let mut psi = vec![0f32; n * f];
            for (i, &ri) in rows.iter().enumerate() {
                let psi_i = &mut psi[i * f..(i + 1) * f];
                for (j, &w) in probs[i * n..(i + 1) * n].iter().enumerate() {
                    let f_ij = &features[(i * n + j) * f..(i * n + j + 1) * f];
                    psi_i.iter_mut().zip(f_ij).for_each(|(s, v)| *s += w * v);
                }
                let out = &mut attended[ri * d + head * dh..][..dh];
                out.iter_mut().zip(&p[layer.bias + head * dh..][..dh]).for_each(|(o, b)| *o += b);
                for (k, &s) in psi_i.iter().enumerate() {
                    let w = &p[layer.weight + k * d + head * dh..][..dh];
                    out.iter_mut().zip(w).for_each(|(o, w)| *o += w * s);
                }
            }
            weighted.push(psi);
        }
    }
    weighted
}

/// The backward pass of [`forward`] for the output gradient `dattended` (rows × d): adds the
/// layer's gradient into `g` and returns the attention weights' gradient per (item, head) (n × n).
#[allow(clippy::too_many_arguments)]
pub(super) fn backward(
    p: &[f32],
    g: &mut [f32],
    layer: &LinearAt,
    weighted: &[Vec<f32>],
    pairs: &[Vec<f32>],
    items: &[Vec<usize>],
    heads: usize,
    dattended: &[f32],
) -> Vec<Vec<f32>> {
    let (f, d) = (layer.input, layer.output);
    let dh = d / heads;
    let mut dprobs = Vec::with_capacity(items.len() * heads);
    let mut dpsi = vec![0f32; f];
    for (item, rows) in items.iter().enumerate() {
        let n = rows.len();
        let features = &pairs[item];
        for head in 0..heads {
            let psi = &weighted[item * heads + head];
            let mut dp = vec![0f32; n * n];
            for (i, &ri) in rows.iter().enumerate() {
                let dout = &dattended[ri * d + head * dh..][..dh];
                g[layer.bias + head * dh..][..dh].iter_mut().zip(dout).for_each(|(g, v)| *g += v);
                for (k, (&s, ds)) in psi[i * f..(i + 1) * f].iter().zip(dpsi.iter_mut()).enumerate() {
                    let at = layer.weight + k * d + head * dh;
                    g[at..at + dh].iter_mut().zip(dout).for_each(|(g, v)| *g += s * v);
                    *ds = super::ops::dot(&p[at..at + dh], dout);
                }
                for (j, dp) in dp[i * n..(i + 1) * n].iter_mut().enumerate() {
                    *dp = super::ops::dot(&dpsi, &features[(i * n + j) * f..(i * n + j + 1) * f]);
                }
            }
            dprobs.push(dp);
        }
    }
    dprobs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_head_adds_its_rows_of_the_map_of_the_weighted_relations() {
        // One item of two rows, d 4, 2 heads, F 2. Row 0 attends to row 1 alone in head 0, to
        // both halves in head 1.
        let layer = LinearAt { weight: 0, bias: 8, input: 2, output: 4 };
        // Wᵀ (F × d) then b: W[k = 0] = (1, 2 | 3, 4), W[k = 1] = (0, 1 | 0, −1), b = (0.5, 0, 0, 0).
        let p = [1.0, 2.0, 3.0, 4.0, 0.0, 1.0, 0.0, -1.0, 0.5, 0.0, 0.0, 0.0];
        let items = vec![vec![0, 1]];
        let probs = vec![vec![0.0, 1.0, 1.0, 0.0], vec![0.5, 0.5, 0.0, 1.0]];
        // f_00 = (0, 0), f_01 = (2, 1), f_10 = (−2, 3), f_11 = (0, 0).
        let pairs = vec![vec![0.0, 0.0, 2.0, 1.0, -2.0, 3.0, 0.0, 0.0]];
        let mut attended = vec![0f32; 8];
        let psi = forward(&p, &layer, &mut attended, &probs, &pairs, &items, 2);
        // Head 0, row 0: ψ = f_01 = (2, 1): (1·2 + 0·1 + 0.5, 2·2 + 1·1) = (2.5, 5).
        // Head 1, row 0: ψ = (1, 0.5): (3·1 + 0, 4·1 − 0.5) = (3, 3.5).
        assert_eq!(psi[1][..2], [1.0, 0.5]);
        assert_eq!(attended[..4], [2.5, 5.0, 3.0, 3.5]);
        // Row 1: head 0 takes f_10 = (−2, 3): (−2 + 0.5, −4 + 3); head 1 f_11 = 0: (0, 0).
        assert_eq!(attended[4..], [-1.5, -1.0, 0.0, 0.0]);
    }

    #[test]
    fn the_backward_pass_matches_finite_differences() {
        // Two items (3 rows, 2 rows not contiguous), d 4, 2 heads, F 3, mixed signs everywhere.
        let layer = LinearAt { weight: 0, bias: 12, input: 3, output: 4 };
        let p: Vec<f32> = (0..16).map(|i| ((i * 7 % 11) as f32 / 5.0) - 1.0).collect();
        let items = vec![vec![0, 1, 4], vec![2, 3]];
        let softmax = |raw: Vec<f32>, n: usize| -> Vec<f32> {
            raw.chunks(n)
                .flat_map(|r| {
                    let total: f32 = r.iter().map(|v| v.exp()).sum();
                    r.iter().map(move |v| v.exp() / total).collect::<Vec<_>>()
                })
                .collect()
        };
        let probs: Vec<Vec<f32>> = [3usize, 3, 2, 2]
            .iter()
            .enumerate()
            .map(|(k, &n)| softmax((0..n * n).map(|i| ((i * 5 + k) % 7) as f32 / 3.0 - 1.0).collect(), n))
            .collect();
        let pairs: Vec<Vec<f32>> =
            [3usize, 2].iter().map(|&n| (0..n * n * 3).map(|i| ((i * 13 % 9) as f32 / 4.0) - 1.0).collect()).collect();
        let r: Vec<f32> = (0..5 * 4).map(|i| ((i * 13 % 7) as f32 / 3.0) - 1.0).collect();
        let loss = |p: &[f32], probs: &[Vec<f32>]| -> f64 {
            let mut out = vec![0f32; 20];
            forward(p, &layer, &mut out, probs, &pairs, &items, 2);
            out.iter().zip(&r).map(|(o, r)| f64::from(o * r)).sum()
        };
        let mut out = vec![0f32; 20];
        let psi = forward(&p, &layer, &mut out, &probs, &pairs, &items, 2);
        let mut g = vec![0f32; 16];
        let dprobs = backward(&p, &mut g, &layer, &psi, &pairs, &items, 2, &r);
        let eps = 1e-3;
        for i in 0..16 {
            let (mut up, mut down) = (p.clone(), p.clone());
            up[i] += eps;
            down[i] -= eps;
            let n = (loss(&up, &probs) - loss(&down, &probs)) / (2.0 * f64::from(eps));
            assert!((n - f64::from(g[i])).abs() < 1e-3, "param {i}: {n} vs {}", g[i]);
        }
        for (m, row) in dprobs.iter().enumerate() {
            for (i, &dp) in row.iter().enumerate() {
                let (mut up, mut down) = (probs.clone(), probs.clone());
                up[m][i] += eps;
                down[m][i] -= eps;
                let n = (loss(&p, &up) - loss(&p, &down)) / (2.0 * f64::from(eps));
                assert!((n - f64::from(dp)).abs() < 1e-3, "probs {m} {i}: {n} vs {dp}");
            }
        }
    }
}
