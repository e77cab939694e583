//! AdamW on flat `f32` vectors (parameters, gradients and both moments laid out alike by a
//! [`super::flat::ParamLayout`]), with global-norm gradient clipping. The moments are plain
//! vectors, so checkpoints save and restore them exactly.

use rayon::prelude::*;

/// Elements per parallel piece of the update (fixed, so the gradient norm sums in the same order
/// on any number of threads).
const PIECE: usize = 1 << 14;

/// Hyper-parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdamWConfig {
    /// β₁.
    pub beta1: f64,
    /// β₂.
    pub beta2: f64,
    /// ε.
    pub eps: f64,
    /// Decoupled weight decay.
    pub weight_decay: f64,
    /// Largest global gradient norm (larger gradients are scaled down).
    pub clip_norm: f64,
}

impl Default for AdamWConfig {
    fn default() -> Self {
        AdamWConfig { beta1: 0.9, beta2: 0.999, eps: 1e-8, weight_decay: 0.0, clip_norm: 1.0 }
    }
}

/// The optimiser and its state.
#[derive(Debug, Clone)]
pub struct AdamW {
    cfg: AdamWConfig,
    /// First moments.
    pub m: Vec<f32>,
    /// Second moments.
    pub v: Vec<f32>,
    /// Updates done.
    pub steps: u64,
}

impl AdamW {
    /// A fresh optimiser for `len` parameters.
    pub fn new(len: usize, cfg: AdamWConfig) -> AdamW {
        AdamW { cfg, m: vec![0.0; len], v: vec![0.0; len], steps: 0 }
    }

    /// One update of `params` with `grads` and learning rate `lr`; returns the gradient norm
    /// before clipping.
    pub fn step(&mut self, params: &mut [f32], grads: &[f32], lr: f64) -> f64 {
        assert!(params.len() == self.m.len() && grads.len() == self.m.len(), "vectors of the optimiser's length");
        let squares: Vec<f64> =
            grads.par_chunks(PIECE).map(|g| g.iter().map(|&x| (x as f64) * (x as f64)).sum()).collect();
        let norm = squares.iter().sum::<f64>().sqrt();
        let clip = if norm > self.cfg.clip_norm { self.cfg.clip_norm / norm } else { 1.0 };
        self.steps += 1;
        let t = self.steps as i32;
        let (b1, b2) = (self.cfg.beta1, self.cfg.beta2);
        let (c1, c2) = ((1.0 - b1.powi(t)) as f32, (1.0 - b2.powi(t)) as f32);
        let (b1, b2, clip) = (b1 as f32, b2 as f32, clip as f32);
        let (eps, lr_f, decay) = (self.cfg.eps as f32, lr as f32, (1.0 - lr * self.cfg.weight_decay) as f32);
        params
            .par_chunks_mut(PIECE)
            .zip(grads.par_chunks(PIECE))
            .zip(self.m.par_chunks_mut(PIECE).zip(self.v.par_chunks_mut(PIECE)))
            .for_each(|((p, g), (m, v))| {
                for (((p, &g), m), v) in p.iter_mut().zip(g).zip(m.iter_mut()).zip(v.iter_mut()) {
                    let g = g * clip;
                    *m = *m * b1 + g * (1.0 - b1);
                    *v = *v * b2 + g * g * (1.0 - b2);
                    let update = (*m / c1) / ((*v / c2).sqrt() + eps);
                    *p = *p * decay - update * lr_f;
                }
            });
        norm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_step_moves_each_parameter_by_the_learning_rate_against_its_gradient() {
        // After one step m̂ = g and v̂ = g², so the update is lr · sign(g) (ε aside).
        let mut adam = AdamW::new(3, AdamWConfig::default());
        let mut p = vec![1.0, 2.0, 3.0];
        let norm = adam.step(&mut p, &[0.3, -0.4, 0.0], 0.1);
        assert!((norm - 0.5).abs() < 1e-7);
        assert!((p[0] - 0.9).abs() < 1e-6 && (p[1] - 2.1).abs() < 1e-6 && p[2] == 3.0, "{p:?}");
        // A gradient of norm 10 is clipped to 1: the moments see g / 10.
        let mut clipped = AdamW::new(1, AdamWConfig::default());
        clipped.step(&mut [0.0], &[10.0], 0.1);
        assert!((clipped.m[0] - 0.1).abs() < 1e-6, "{}", clipped.m[0]);
    }
}
