//! Where a training step's loss and gradient come from: the hand-written pass over flat vectors
//! ([`GradNet`], the default) or candle's autograd through [`Denoiser`] (the reference the first
//! is tested against, kept to compare runs). Both read and write parameters laid out by one
//! [`ParamLayout`], so the optimiser, EMA and checkpoints are the same for both.

use super::dataset::NoisyBatch;
use super::flat::ParamLayout;
use super::grad::GradNet;
use super::{Denoiser, GenError, ModelConfig, Params};
use candle_core::{Tensor, Var};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Which gradient engine a training run uses.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Engine {
    /// The hand-written forward and backward pass on all cores (default).
    #[default]
    Fused,
    /// candle's autograd (the reference; slower).
    Candle,
}

/// A gradient engine ready for one model's layout.
#[derive(Debug)]
pub enum Gradients {
    /// See [`Engine::Fused`].
    Fused(GradNet),
    /// See [`Engine::Candle`].
    Candle(CandleGradients),
}

impl Gradients {
    /// `engine` for a `cfg` model whose parameters are laid out by `layout`.
    pub fn new(engine: Engine, cfg: &ModelConfig, layout: &ParamLayout) -> Result<Gradients, GenError> {
        Ok(match engine {
            Engine::Fused => Gradients::Fused(GradNet::new(cfg, layout)?),
            Engine::Candle => Gradients::Candle(CandleGradients::new(cfg, layout)?),
        })
    }

    /// The batch's weighted L_simple at `params` and its gradient, laid out like `params`.
    pub fn loss_and_grad(&mut self, params: &[f32], batch: &NoisyBatch) -> Result<(f64, Vec<f32>), GenError> {
        match self {
            Gradients::Fused(net) => Ok(net.loss_and_grad(params, batch)),
            Gradients::Candle(c) => c.loss_and_grad(params, batch),
        }
    }

    /// The batch's weighted L_simple at `params`.
    pub fn loss(&mut self, params: &[f32], batch: &NoisyBatch) -> Result<f64, GenError> {
        match self {
            Gradients::Fused(net) => Ok(net.loss(params, batch)),
            Gradients::Candle(c) => Ok(c.loss_tensor(params, batch)?.to_scalar::<f32>()? as f64),
        }
    }
}

/// The candle model with trainable variables, loaded from the flat vector at every call.
#[derive(Debug)]
pub struct CandleGradients {
    cfg: ModelConfig,
    layout: ParamLayout,
    model: Denoiser,
    vars: BTreeMap<String, Var>,
}

impl CandleGradients {
    fn new(cfg: &ModelConfig, layout: &ParamLayout) -> Result<CandleGradients, GenError> {
        let mut params = Params::random(0);
        let model = Denoiser::new(cfg, &mut params)?;
        let vars = params.vars().clone();
        let (own, _) = ParamLayout::of(&params.snapshot()?)?;
        if own != *layout {
            return Err(GenError::checkpoint("", "parameters laid out unlike the model's"));
        }
        Ok(CandleGradients { cfg: cfg.clone(), layout: layout.clone(), model, vars })
    }

    fn loss_tensor(&mut self, params: &[f32], batch: &NoisyBatch) -> Result<Tensor, GenError> {
        if !batch.relations.is_empty() {
            return Err(GenError::Input {
                path: Default::default(),
                message: "the relation loss is the fused engine's alone; train with --engine fused".into(),
            });
        }
        for (name, tensor) in self.layout.tensors(params)? {
            self.vars[&name].set(&tensor)?;
        }
        let (cfg, host) = (&self.cfg, &batch.host);
        let (noisy, cond) = (host.token_tensor(&batch.noisy, cfg)?, host.cond(cfg)?);
        // Self-conditioning: the marked scenes get a first pass's clean estimate, held fixed.
        let estimate = match batch.self_condition.iter().any(|&on| on) {
            true => {
                let first = self.model.forward(&noisy, &batch.t, &cond)?.clamp(-1f32, 1f32)?.detach();
                let per_item = cfg.slots() * cfg.token_dim();
                let on: Vec<f32> = batch
                    .self_condition
                    .iter()
                    .flat_map(|&on| std::iter::repeat_n(if on { 1f32 } else { 0.0 }, per_item))
                    .collect();
                Some((first * host.token_tensor(&on, cfg)?)?)
            }
            false => None,
        };
        let pred = self.model.forward_with(&noisy, &batch.t, &cond, estimate.as_ref())?;
        let weights = host.token_tensor(&batch.loss_weights, cfg)?;
        let err = (pred - host.token_tensor(&batch.target, cfg)?)?.sqr()?;
        Ok(((err * weights)?.sum_all()? / batch.weight_total() as f64)?)
    }

    fn loss_and_grad(&mut self, params: &[f32], batch: &NoisyBatch) -> Result<(f64, Vec<f32>), GenError> {
        let loss = self.loss_tensor(params, batch)?;
        let grads = loss.backward()?;
        let flat = self.layout.gather(|name, shape| match grads.get(self.vars[name].as_tensor()) {
            Some(g) => Ok(g.flatten_all()?.to_vec1::<f32>()?),
            None => Ok(vec![0f32; shape.iter().product()]),
        })?;
        Ok((loss.to_scalar::<f32>()? as f64, flat))
    }
}
