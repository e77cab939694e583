//! DDPM ancestral sampling with the guidance hook: at every step the clean estimate x̂0 (from the
//! predicted noise, clamped to [-1, 1]) may be replaced by a guided x̃0 before the posterior mean
//! is formed (DESIGN.md, "Guidance at step t").
//!
//! Noise comes from the crate's seeded generator, one stream per batch item, and the denoiser runs
//! as [`FastDenoiser`] (conditions encoded once, each item on its own), so item i of a seed is the
//! same whether it is sampled alone or in a batch.

use super::model::CondTensors;
use super::{Denoiser, FastDenoiser, GenError, Schedule};
use crate::data::Rng;
use candle_core::{Device, Tensor};

/// Changes the clean estimate x̂0 (B, slots, token_dim) at step `t` (counting down from T − 1),
/// and may adjust each decoded scene after the last step.
pub trait Guidance {
    /// The guided estimate x̃0.
    fn guide(&mut self, x0: &Tensor, t: usize) -> Result<Tensor, GenError>;

    /// Adjusts the decoded scene of batch item `item` after sampling (default: nothing).
    fn finish(&mut self, _item: usize, _scene: &mut crate::scene::Scene) {}
}

/// Samples a batch; `seeds[i]` drives item i. Returns the tokens (B × slots × token_dim).
pub fn sample(
    model: &Denoiser,
    schedule: &Schedule,
    cond: &CondTensors,
    seeds: &[u64],
    mut guidance: Option<&mut dyn Guidance>,
) -> Result<Vec<f32>, GenError> {
    let cfg = model.config();
    let b = seeds.len();
    let per_item = cfg.slots() * cfg.token_dim();
    let shape = (b, cfg.slots(), cfg.token_dim());
    let mut rngs: Vec<Rng> = seeds.iter().map(|&s| Rng::new(s)).collect();
    let gaussian = |rngs: &mut Vec<Rng>| -> Result<Tensor, GenError> {
        let mut v = Vec::with_capacity(b * per_item);
        for rng in rngs.iter_mut() {
            v.extend((0..per_item).map(|_| rng.normal() as f32));
        }
        Ok(Tensor::from_vec(v, shape, &Device::Cpu)?)
    };
    let fast = FastDenoiser::of(model)?;
    let mut prepared = fast.prepare(cond)?;
    let mut x = gaussian(&mut rngs)?;
    for t in (0..schedule.steps()).rev() {
        let eps = Tensor::from_vec(fast.forward(&mut prepared, &x.flatten_all()?.to_vec1()?, t), shape, &Device::Cpu)?;
        let ab = schedule.alpha_bars[t];
        let x0 = ((&x - (eps * (1.0 - ab).sqrt())?)? / ab.sqrt())?.clamp(-1f32, 1f32)?;
        let x0 = match guidance.as_deref_mut() {
            Some(g) => g.guide(&x0, t)?,
            None => x0,
        };
        let (c0, ct, var) = schedule.posterior(t);
        let mean = ((x0 * c0)? + (&x * ct)?)?;
        // Detached so that nothing (a guidance gradient) chains the steps' graphs.
        x = if t > 0 { (mean + (gaussian(&mut rngs)? * var.sqrt())?)? } else { mean }.detach();
    }
    Ok(x.flatten_all()?.to_vec1::<f32>()?)
}
