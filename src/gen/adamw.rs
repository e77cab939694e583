//! AdamW with its moments kept by parameter name, so they can be saved and restored exactly
//! (candle's optimiser keeps them private), plus global-norm gradient clipping.

use super::GenError;
use candle_core::backprop::GradStore;
use candle_core::{Tensor, Var};
use std::collections::BTreeMap;

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
#[derive(Debug)]
pub struct AdamW {
    cfg: AdamWConfig,
    vars: BTreeMap<String, Var>,
    /// First moments by parameter name.
    pub m: BTreeMap<String, Tensor>,
    /// Second moments by parameter name.
    pub v: BTreeMap<String, Tensor>,
    /// Updates done.
    pub steps: u64,
}

impl AdamW {
    /// A fresh optimiser over `vars`.
    pub fn new(vars: &BTreeMap<String, Var>, cfg: AdamWConfig) -> Result<AdamW, GenError> {
        let zeros = |v: &Var| v.as_tensor().zeros_like();
        let m = vars.iter().map(|(k, v)| Ok((k.clone(), zeros(v)?))).collect::<Result<_, GenError>>()?;
        let s = vars.iter().map(|(k, v)| Ok((k.clone(), zeros(v)?))).collect::<Result<_, GenError>>()?;
        Ok(AdamW { cfg, vars: vars.clone(), m, v: s, steps: 0 })
    }

    /// Whether no stored moment keeps a computation graph alive.
    #[cfg(test)]
    pub fn is_detached(&self) -> bool {
        self.m.values().chain(self.v.values()).all(|t| !t.track_op())
    }

    /// One update with learning rate `lr`; returns the gradient norm before clipping.
    pub fn step(&mut self, grads: &GradStore, lr: f64) -> Result<f64, GenError> {
        let mut squared = 0.0;
        let mut found = BTreeMap::new();
        for (name, var) in &self.vars {
            if let Some(g) = grads.get(var.as_tensor()) {
                squared += g.sqr()?.sum_all()?.to_scalar::<f32>()? as f64;
                found.insert(name.clone(), g.clone());
            }
        }
        let norm = squared.sqrt();
        let clip = if norm > self.cfg.clip_norm { self.cfg.clip_norm / norm } else { 1.0 };
        self.steps += 1;
        let t = self.steps as i32;
        let (b1, b2) = (self.cfg.beta1, self.cfg.beta2);
        let (c1, c2) = (1.0 - b1.powi(t), 1.0 - b2.powi(t));
        for (name, g) in found {
            // Moments are detached: a gradient may carry the graph that made it, and a moment that
            // kept it would keep every earlier step's graph alive.
            let g = (g.detach() * clip)?;
            let m = ((&self.m[&name] * b1)? + (&g * (1.0 - b1))?)?.detach();
            let v = ((&self.v[&name] * b2)? + (g.sqr()? * (1.0 - b2))?)?.detach();
            let var = &self.vars[&name];
            let update = ((&m / c1)? / ((&v / c2)?.sqrt()? + self.cfg.eps)?)?;
            let decayed = (var.as_tensor() * (1.0 - lr * self.cfg.weight_decay))?;
            var.set(&(decayed - (update * lr)?)?)?;
            self.m.insert(name.clone(), m);
            self.v.insert(name, v);
        }
        Ok(norm)
    }
}
