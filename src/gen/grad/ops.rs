//! The element-wise and per-item pieces of the training pass, forward and backward: SiLU, ReLU,
//! parameter-free layer norm, adaLN modulation and gating with per-item vectors, and multi-head
//! attention within each item's rows. Matrix products are in [`super::super::matmul`].

/// Layer norm's ε under the square root (as the candle model).
const NORM_EPS: f32 = 1e-6;

/// Independent partial sums of [`sum`] and [`dot`]: a single running sum is one long chain of
/// dependent additions; eight of them let the compiler use vector lanes.
const LANES: usize = 8;

/// Σ a, in [`LANES`] partial sums (a fixed order: deterministic).
pub(super) fn sum(a: &[f32]) -> f32 {
    let mut acc = [0f32; LANES];
    let mut chunks = a.chunks_exact(LANES);
    for c in &mut chunks {
        acc.iter_mut().zip(c).for_each(|(s, v)| *s += v);
    }
    acc.iter().sum::<f32>() + chunks.remainder().iter().sum::<f32>()
}

/// Σ a·b, in [`LANES`] partial sums.
pub(super) fn dot(a: &[f32], b: &[f32]) -> f32 {
    debug_assert_eq!(a.len(), b.len());
    let mut acc = [0f32; LANES];
    let (mut ca, mut cb) = (a.chunks_exact(LANES), b.chunks_exact(LANES));
    for (x, y) in (&mut ca).zip(&mut cb) {
        for k in 0..LANES {
            acc[k] += x[k] * y[k];
        }
    }
    let tail: f32 = ca.remainder().iter().zip(cb.remainder()).map(|(x, y)| x * y).sum();
    acc.iter().sum::<f32>() + tail
}

/// eˣ to within a few units in the last place, for x clamped to [−87, 88]: a polynomial
/// (Cephes' expf) written so that loops over slices vectorise, where `f32::exp` is a call per
/// element.
#[inline(always)]
pub(super) fn exp(x: f32) -> f32 {
    const LOG2E: f32 = std::f32::consts::LOG2_E;
    // ln 2 split in two, so that n · LN2_HI is exact.
    const LN2_HI: f32 = 0.693_359_4;
    const LN2_LO: f32 = -2.121_944_4e-4;
    // Adding and subtracting 1.5 · 2²³ rounds to the nearest integer.
    const ROUND: f32 = 12_582_912.0;
    let x = x.clamp(-87.0, 88.0);
    let t = x * LOG2E + ROUND;
    let n = t - ROUND;
    let r = x - n * LN2_HI - n * LN2_LO;
    let mut p = 1.987_569_1e-4;
    for c in [1.398_199_9e-3, 8.333_452e-3, 4.166_579_6e-2, 1.666_666_5e-1, 0.5] {
        p = p * r + c;
    }
    let y = p * r * r + r + 1.0;
    // 2ⁿ from n's integer bits in t (integer operations: no float-to-int conversion).
    let n_bits = t.to_bits().wrapping_sub(ROUND.to_bits());
    y * f32::from_bits(n_bits.wrapping_add(127) << 23)
}

#[inline(always)]
pub(super) fn sigmoid(x: f32) -> f32 {
    1.0 / (1.0 + exp(-x))
}

/// SiLU of `pre` into a new vector.
pub(super) fn silu(pre: &[f32]) -> Vec<f32> {
    pre.iter().map(|&x| x * sigmoid(x)).collect()
}

/// `dy` · SiLU′(`pre`), in place in `dy`.
pub(super) fn silu_backward(pre: &[f32], dy: &mut [f32]) {
    for (g, &x) in dy.iter_mut().zip(pre) {
        let s = sigmoid(x);
        *g *= s * (1.0 + x * (1.0 - s));
    }
}

/// ReLU in place.
pub(super) fn relu(v: &mut [f32]) {
    v.iter_mut().for_each(|x| *x = x.max(0.0));
}

/// Zeroes `dy` where the ReLU's output `out` is 0 (its input was not positive).
pub(super) fn relu_backward(out: &[f32], dy: &mut [f32]) {
    dy.iter_mut().zip(out).filter(|(_, o)| **o <= 0.0).for_each(|(g, _)| *g = 0.0);
}

/// Normalises each row of `x` (width `d`): `u = (x − mean) · rstd` with `rstd = 1/√(var + ε)`.
pub(super) fn layer_norm(x: &[f32], d: usize) -> (Vec<f32>, Vec<f32>) {
    let mut u = vec![0f32; x.len()];
    let mut rstd = Vec::with_capacity(x.len() / d);
    for (row, out) in x.chunks_exact(d).zip(u.chunks_exact_mut(d)) {
        let mean = sum(row) / d as f32;
        out.iter_mut().zip(row).for_each(|(o, v)| *o = v - mean);
        let r = 1.0 / (dot(out, out) / d as f32 + NORM_EPS).sqrt();
        out.iter_mut().for_each(|o| *o *= r);
        rstd.push(r);
    }
    (u, rstd)
}

/// Adds the layer norm's input gradient for output gradient `du` into `dx`:
/// `rstd · (du − mean(du) − u · mean(du · u))` per row.
pub(super) fn layer_norm_backward(u: &[f32], rstd: &[f32], du: &[f32], d: usize, dx: &mut [f32]) {
    for (((u, du), dx), r) in u.chunks_exact(d).zip(du.chunks_exact(d)).zip(dx.chunks_exact_mut(d)).zip(rstd) {
        let mean_du = sum(du) / d as f32;
        let mean_duu = dot(du, u) / d as f32;
        for ((x, g), v) in dx.iter_mut().zip(du).zip(u) {
            *x += r * (g - mean_du - v * mean_duu);
        }
    }
}

/// Per-item modulation vectors: item `i`'s part `j` (width `d`) of a `(items × parts·d)` matrix.
#[derive(Debug, Clone, Copy)]
pub(super) struct Parts<'a> {
    pub(super) values: &'a [f32],
    pub(super) parts: usize,
    pub(super) d: usize,
}

impl<'a> Parts<'a> {
    pub(super) fn get(&self, item: usize, part: usize) -> &'a [f32] {
        let at = (item * self.parts + part) * self.d;
        &self.values[at..at + self.d]
    }
}

/// The same matrix's gradient, written part by part.
pub(super) struct PartsGrad<'a> {
    pub(super) values: &'a mut [f32],
    pub(super) parts: usize,
    pub(super) d: usize,
}

impl PartsGrad<'_> {
    pub(super) fn get(&mut self, item: usize, part: usize) -> &mut [f32] {
        let at = (item * self.parts + part) * self.d;
        &mut self.values[at..at + self.d]
    }
}

/// `u · (1 + scale) + shift` per row, with row `r`'s item `row_item[r]` choosing the vectors.
pub(super) fn modulate(u: &[f32], m: Parts, shift: usize, row_item: &[usize]) -> Vec<f32> {
    let d = m.d;
    let mut out = vec![0f32; u.len()];
    for ((row, dst), &item) in u.chunks_exact(d).zip(out.chunks_exact_mut(d)).zip(row_item) {
        let (sh, sc) = (m.get(item, shift), m.get(item, shift + 1));
        for (((o, v), a), b) in dst.iter_mut().zip(row).zip(sc).zip(sh) {
            *o = v * (1.0 + a) + b;
        }
    }
    out
}

/// Backward of [`modulate`]: adds the shift and scale gradients into `dm` and returns `du`.
pub(super) fn modulate_backward(
    u: &[f32],
    m: Parts,
    dm: &mut PartsGrad,
    shift: usize,
    row_item: &[usize],
    dout: &[f32],
) -> Vec<f32> {
    let d = m.d;
    let mut du = vec![0f32; u.len()];
    for (((row, g), dst), &item) in
        u.chunks_exact(d).zip(dout.chunks_exact(d)).zip(du.chunks_exact_mut(d)).zip(row_item)
    {
        let sc = m.get(item, shift + 1);
        dst.iter_mut().zip(g).zip(sc).for_each(|((o, g), a)| *o = g * (1.0 + a));
        dm.get(item, shift).iter_mut().zip(g).for_each(|(s, g)| *s += g);
        dm.get(item, shift + 1).iter_mut().zip(g).zip(row).for_each(|((s, g), v)| *s += g * v);
    }
    du
}

/// `h += gate · branch` per row.
pub(super) fn add_gated(h: &mut [f32], branch: &[f32], m: Parts, gate: usize, row_item: &[usize]) {
    let d = m.d;
    for ((row, add), &item) in h.chunks_exact_mut(d).zip(branch.chunks_exact(d)).zip(row_item) {
        row.iter_mut().zip(add).zip(m.get(item, gate)).for_each(|((v, a), g)| *v += g * a);
    }
}

/// Backward of [`add_gated`] for the branch and the gate (the residual passes `dh` on unchanged):
/// adds the gate's gradient into `dm`, returns the branch's.
pub(super) fn add_gated_backward(
    dh: &[f32],
    branch: &[f32],
    m: Parts,
    dm: &mut PartsGrad,
    gate: usize,
    row_item: &[usize],
) -> Vec<f32> {
    let d = m.d;
    let mut dbranch = vec![0f32; dh.len()];
    for (((g, b), dst), &item) in
        dh.chunks_exact(d).zip(branch.chunks_exact(d)).zip(dbranch.chunks_exact_mut(d)).zip(row_item)
    {
        dst.iter_mut().zip(g).zip(m.get(item, gate)).for_each(|((o, g), w)| *o = g * w);
        dm.get(item, gate).iter_mut().zip(g).zip(b).for_each(|((s, g), v)| *s += g * v);
    }
    dbranch
}

/// Multi-head self-attention among the rows of each item (`items[i]` lists item i's rows, in
/// order). `qkv` is rows × 3d (q | k | v, heads within each); returns the output (rows × d) and
/// each (item, head)'s softmax weights, row-major.
///
/// `bias`, when given, is added to the scores: `bias[item * heads + head]` is that item's n × n
/// matrix (row i: the query, column j: the key), n its number of rows.
pub(super) fn attention(
    qkv: &[f32],
    items: &[Vec<usize>],
    heads: usize,
    d: usize,
    bias: Option<&[Vec<f32>]>,
) -> (Vec<f32>, Vec<Vec<f32>>) {
    let dh = d / heads;
    let scale = 1.0 / (dh as f32).sqrt();
    let mut out = vec![0f32; qkv.len() / 3];
    let mut probs = Vec::with_capacity(items.len() * heads);
    for (item, rows) in items.iter().enumerate() {
        let n = rows.len();
        for head in 0..heads {
            let col = |row: usize, part: usize| &qkv[row * 3 * d + part * d + head * dh..][..dh];
            let mut p = vec![0f32; n * n];
            for (i, &ri) in rows.iter().enumerate() {
                let q = col(ri, 0);
                let weights = &mut p[i * n..(i + 1) * n];
                let mut max = f32::NEG_INFINITY;
                for (w, &rj) in weights.iter_mut().zip(rows) {
                    *w = dot(q, col(rj, 1)) * scale;
                    max = max.max(*w);
                }
                if let Some(bias) = bias {
                    max = f32::NEG_INFINITY;
                    for (w, b) in weights.iter_mut().zip(&bias[item * heads + head][i * n..(i + 1) * n]) {
                        *w += b;
                        max = max.max(*w);
                    }
                }
                let mut total = 0.0;
                for w in weights.iter_mut() {
                    *w = exp(*w - max);
                    total += *w;
                }
                weights.iter_mut().for_each(|w| *w /= total);
                let dst = &mut out[ri * d + head * dh..][..dh];
                for (w, &rj) in weights.iter().zip(rows) {
                    dst.iter_mut().zip(col(rj, 2)).for_each(|(o, v)| *o += w * v);
                }
            }
            probs.push(p);
        }
    }
    (out, probs)
}

/// Backward of [`attention`]: the gradient of `qkv` for the output gradient `dout`; when `dbias` is
/// given (laid out like the bias), the scores' gradient is added into it. `dprobs`, when given
/// (laid out like `probs`), is a gradient of the softmax weights from elsewhere (the relation
/// values), added to the one through the values.
#[allow(clippy::too_many_arguments)]
pub(super) fn attention_backward(
    qkv: &[f32],
    probs: &[Vec<f32>],
    items: &[Vec<usize>],
    heads: usize,
    d: usize,
    dout: &[f32],
    mut dbias: Option<&mut [Vec<f32>]>,
    dprobs: Option<&[Vec<f32>]>,
) -> Vec<f32> {
    let dh = d / heads;
    let scale = 1.0 / (dh as f32).sqrt();
    let mut dqkv = vec![0f32; qkv.len()];
    let mut dp = Vec::new();
    for (item, rows) in items.iter().enumerate() {
        let n = rows.len();
        for head in 0..heads {
            let at = |row: usize, part: usize| row * 3 * d + part * d + head * dh;
            let p = &probs[item * heads + head];
            for (i, &ri) in rows.iter().enumerate() {
                let dout_i = &dout[ri * d + head * dh..][..dh];
                let pi = &p[i * n..(i + 1) * n];
                // dP_ij = dout_i · v_j ; dv_j += P_ij dout_i.
                dp.clear();
                for (&w, &rj) in pi.iter().zip(rows) {
                    let v = &qkv[at(rj, 2)..][..dh];
                    dp.push(dot(dout_i, v));
                    dqkv[at(rj, 2)..][..dh].iter_mut().zip(dout_i).for_each(|(g, o)| *g += w * o);
                }
                if let Some(dprobs) = dprobs {
                    let extra = &dprobs[item * heads + head][i * n..(i + 1) * n];
                    dp.iter_mut().zip(extra).for_each(|(g, e)| *g += e);
                }
                // dS_ij = P_ij (dP_ij − Σ_k P_ik dP_ik), then through S = q·k · scale.
                let inner = dot(pi, &dp);
                if let Some(dbias) = dbias.as_deref_mut() {
                    let row = &mut dbias[item * heads + head][i * n..(i + 1) * n];
                    for ((b, &w), &g) in row.iter_mut().zip(pi).zip(&dp) {
                        *b += w * (g - inner);
                    }
                }
                for ((&w, &g), &rj) in pi.iter().zip(&dp).zip(rows) {
                    let ds = w * (g - inner) * scale;
                    if ds == 0.0 {
                        continue;
                    }
                    for c in 0..dh {
                        let (q, k) = (qkv[at(ri, 0) + c], qkv[at(rj, 1) + c]);
                        dqkv[at(ri, 0) + c] += ds * k;
                        dqkv[at(rj, 1) + c] += ds * q;
                    }
                }
            }
        }
    }
    dqkv
}

#[cfg(test)]
mod tests {
    use super::*;

    fn loss(values: &[f32], r: &[f32]) -> f64 {
        values.iter().zip(r).map(|(a, b)| (a * b) as f64).sum()
    }

    fn numeric(f: impl Fn(&[f32]) -> f64, x: &[f32], i: usize) -> f64 {
        let (mut up, mut down) = (x.to_vec(), x.to_vec());
        up[i] += 1e-2;
        down[i] -= 1e-2;
        (f(&up) - f(&down)) / 2e-2
    }

    #[test]
    fn layer_norm_and_its_backward_match_finite_differences() {
        let x = [0.3, -1.2, 2.0, 0.7, 1.0, 1.5, -0.5, 0.0];
        let r = [1.0, 0.5, -2.0, 0.25, -1.0, 2.0, 0.5, 1.5];
        let (u, rstd) = layer_norm(&x, 4);
        assert!(u[..4].iter().sum::<f32>().abs() < 1e-5);
        let mut dx = vec![0.0; 8];
        layer_norm_backward(&u, &rstd, &r, 4, &mut dx);
        for (i, g) in dx.iter().enumerate() {
            let n = numeric(|x| loss(&layer_norm(x, 4).0, &r), &x, i);
            assert!((n - *g as f64).abs() < 2e-3, "{i}: {n} vs {g}");
        }
    }

    #[test]
    fn attention_backward_matches_finite_differences() {
        // Two items (3 rows and 2 rows, the second's rows not contiguous), d 4, 2 heads.
        let items = vec![vec![0, 1, 4], vec![2, 3]];
        let qkv: Vec<f32> = (0..5 * 12).map(|i| ((i * 37 % 23) as f32 / 11.0) - 1.0).collect();
        let r: Vec<f32> = (0..5 * 4).map(|i| ((i * 13 % 7) as f32 / 3.0) - 1.0).collect();
        // A bias per item and head (n × n), of mixed signs.
        let bias: Vec<Vec<f32>> = [3usize, 3, 2, 2]
            .iter()
            .enumerate()
            .map(|(k, &n)| (0..n * n).map(|i| ((i * 7 + k * 3) % 5) as f32 / 2.0 - 1.0).collect())
            .collect();
        for bias in [None, Some(&bias[..])] {
            let (_, probs) = attention(&qkv, &items, 2, 4, bias);
            assert!(
                probs.iter().all(|p| p.chunks(p.len().isqrt()).all(|row| (row.iter().sum::<f32>() - 1.0).abs() < 1e-6))
            );
            let mut dbias: Vec<Vec<f32>> = bias.iter().flat_map(|b| b.iter().map(|m| vec![0.0; m.len()])).collect();
            let grad = attention_backward(&qkv, &probs, &items, 2, 4, &r, bias.map(|_| &mut dbias[..]), None);
            for (i, g) in grad.iter().enumerate() {
                let n = numeric(|q| loss(&attention(q, &items, 2, 4, bias).0, &r), &qkv, i);
                assert!((n - *g as f64).abs() < 2e-3, "{i}: {n} vs {g}");
            }
            if let Some(bias) = bias {
                for (m, row) in dbias.iter().enumerate() {
                    for (i, g) in row.iter().enumerate() {
                        let f = |b: &[f32]| {
                            let mut all = bias.to_vec();
                            all[m] = b.to_vec();
                            loss(&attention(&qkv, &items, 2, 4, Some(&all)).0, &r)
                        };
                        let n = numeric(f, &bias[m], i);
                        assert!((n - *g as f64).abs() < 2e-3, "bias {m} {i}: {n} vs {g}");
                    }
                }
            }
        }
    }

    #[test]
    fn exp_is_within_a_few_ulp_of_the_library_one() {
        for i in -8700..8800 {
            let x = i as f32 / 100.0 + 0.003;
            let (want, got) = (x.exp(), exp(x));
            assert!((got - want).abs() <= 4.0 * f32::EPSILON * want, "{x}: {got} vs {want}");
        }
        assert_eq!(exp(0.0), 1.0);
        assert!(exp(-1e9) < 1e-37 && exp(1e9).is_finite());
    }

    #[test]
    fn silu_backward_matches_finite_differences() {
        let x = [-3.0, -0.5, 0.0, 0.8, 4.0];
        let mut g = [1.0; 5];
        silu_backward(&x, &mut g);
        for (i, g) in g.iter().enumerate() {
            let n = numeric(|x| silu(x).iter().map(|v| *v as f64).sum(), &x, i);
            assert!((n - *g as f64).abs() < 1e-3, "{i}");
        }
    }
}
