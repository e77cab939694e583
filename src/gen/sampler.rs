//! DDPM ancestral sampling (or DDIM's, [`Chain::eta`]) with the guidance hook: at every step the
//! clean estimate x̂0 (from the model's output, clamped to [-1, 1]) may be replaced by a guided x̃0
//! before the next step is formed (DESIGN.md, "Guidance at step t"). In the last steps, slots
//! whose x̂0 reads "empty" get the zero attributes the training data has there
//! ([`empty_projection_steps`]), after the slots' classes are matched to the counts the item must
//! hold ([`super::count_projection`]).
//!
//! Noise comes from the crate's seeded generator, one stream per batch item, and the denoiser runs
//! as [`FastDenoiser`] (conditions encoded once, no item's numbers depending on another's), so item i of a seed is the
//! same whether it is sampled alone or in a batch.

use super::affordance_projection::keep_affordances;
use super::count_projection::{CountTargets, match_counts};
use super::model::CondTensors;
use super::tokens::{CLASS_OFFSET, slot_class};
use super::{Denoiser, FastDenoiser, GenError, Schedule, anchors};
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

/// What the sampler's last steps project x̂0 onto.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Projection {
    /// In steps t below this one the empty slots of x̂0 get zero attributes
    /// ([`empty_projection_steps`] is the default; 0 samples the model's raw output).
    pub steps: usize,
    /// In the same steps, x̂0's classes are first matched to each item's pieces per category as
    /// its rule says ([`match_counts`]). `None`: no count projection.
    pub counts: Option<CountTargets>,
    /// In the same steps, before the counts, each anchored slot holds a piece that affords its
    /// box's action ([`keep_affordances`]).
    pub affordances: bool,
}

impl Projection {
    /// The empty-slot projection alone, in the steps below `steps`.
    pub fn empty_slots(steps: usize) -> Projection {
        Projection { steps, counts: None, affordances: false }
    }
}

/// The steps a sampler visits and how much fresh noise each jump draws.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// The steps visited, ascending ([`Schedule::respaced`]; all T for DDPM's chain).
    pub visited: Vec<usize>,
    /// DDIM's η ([`Schedule::jump`]) of the pieces' geometry (centre, size, yaw): 1 draws DDPM's
    /// posterior noise at every jump (the default), 0 none (the deterministic DDIM sampler),
    /// above 1 more than DDPM's.
    pub eta: f64,
    /// The same for the class features (`eta` unless set apart).
    pub class_eta: f64,
}

impl Chain {
    /// DDPM's chain over all of `schedule`'s steps.
    pub fn full(schedule: &Schedule) -> Chain {
        Chain { visited: schedule.respaced(schedule.steps()), eta: 1.0, class_eta: 1.0 }
    }
}

/// Samples a batch; `seeds[i]` drives item i, visiting `chain`'s steps from the last down,
/// projecting x̂0 in the last steps as `projection` says. Returns the tokens in world form (B × slots × token_dim); the
/// diffusion itself runs in the model's frame ([`anchors`]), and the guidance sees world tokens.
pub fn sample(
    model: &Denoiser,
    schedule: &Schedule,
    chain: &Chain,
    cond: &CondTensors,
    seeds: &[u64],
    projection: &Projection,
    guidance: Option<&mut dyn Guidance>,
) -> Result<Vec<f32>, GenError> {
    sample_from(Denoisers::one(model), schedule, chain, cond, seeds, projection, guidance, None)
}

/// The denoisers a chain calls: one for every step, and optionally a low-noise expert
/// ([`ModelConfig::expert_below`](super::ModelConfig::expert_below)) that takes the steps below its
/// own bound instead.
#[derive(Debug, Clone, Copy)]
pub struct Denoisers<'a> {
    /// The model of the whole chain.
    pub main: &'a Denoiser,
    /// The low-noise expert, if any.
    pub expert: Option<&'a Denoiser>,
}

impl<'a> Denoisers<'a> {
    /// `main` alone.
    pub fn one(main: &'a Denoiser) -> Denoisers<'a> {
        Denoisers { main, expert: None }
    }
}

/// [`sample`] from given layouts instead of pure noise (SDEdit, Meng et al. 2022): `start` holds
/// world tokens (B × slots × token_dim), noised to the chain's highest visited step with each
/// item's own seeded draw before the chain runs from there. `None` is [`sample`].
#[allow(clippy::too_many_arguments)]
pub fn sample_from(
    denoisers: Denoisers,
    schedule: &Schedule,
    chain: &Chain,
    cond: &CondTensors,
    seeds: &[u64],
    projection: &Projection,
    mut guidance: Option<&mut dyn Guidance>,
    start: Option<&[f32]>,
) -> Result<Vec<f32>, GenError> {
    let cfg = denoisers.main.config();
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
    // The diffusion runs in the model's frame (anchored slots relative to their boxes); guidance
    // and the caller see world tokens.
    let contacts = cond.contacts.flatten_all()?.to_vec1::<f32>()?;
    let mask = cond.contact_mask.flatten_all()?.to_vec1::<f32>()?;
    let frame = |x: &Tensor, into_model: bool| -> Result<Tensor, GenError> {
        let mut v = x.flatten_all()?.to_vec1::<f32>()?;
        match into_model {
            true => anchors::to_model(cfg, &contacts, &mask, &mut v),
            false => anchors::to_world(cfg, &contacts, &mask, &mut v),
        }
        Ok(Tensor::from_vec(v, shape, &Device::Cpu)?)
    };
    let fast = FastDenoiser::of(denoisers.main)?;
    let mut prepared = fast.prepare(cond)?;
    let mut expert = match denoisers.expert {
        Some(e) => {
            let fast = FastDenoiser::of(e)?;
            let prepared = fast.prepare(cond)?;
            Some((fast, prepared, e.config().expert_below.unwrap_or(0)))
        }
        None => None,
    };
    let visited = &chain.visited;
    let mut x = gaussian(&mut rngs)?;
    if let (Some(start), Some(&top)) = (start, visited.last()) {
        if start.len() != b * per_item {
            return Err(GenError::Input {
                path: Default::default(),
                message: format!("{} start values for {b} items of {per_item}", start.len()),
            });
        }
        let clean = frame(&Tensor::from_vec(start.to_vec(), shape, &Device::Cpu)?, true)?;
        let ab = schedule.alpha_bars[top];
        x = ((clean * ab.sqrt())? + (x * (1.0 - ab).sqrt())?)?;
    }
    for (i, &t) in visited.iter().enumerate().rev() {
        let noisy: Vec<f32> = x.flatten_all()?.to_vec1()?;
        let (model, batch) = match expert.as_mut() {
            Some((fast, prepared, below)) if t < *below => (&*fast, prepared),
            _ => (&fast, &mut prepared),
        };
        let out = model.forward(batch, &noisy, t);
        let (ab, prediction) = (schedule.alpha_bars[t], model.config().prediction);
        let x0: Vec<f32> =
            out.iter().zip(&noisy).map(|(&o, &x)| prediction.clean_estimate(o, x, ab).clamp(-1.0, 1.0)).collect();
        let x0 = Tensor::from_vec(x0, shape, &Device::Cpu)?;
        let x0 = if t < projection.steps {
            let x0 = match projection.affordances {
                true => {
                    let mut v = x0.flatten_all()?.to_vec1::<f32>()?;
                    keep_affordances(&mut v, &contacts, &mask, cfg);
                    Tensor::from_vec(v, shape, &Device::Cpu)?
                }
                false => x0,
            };
            let x0 = match &projection.counts {
                Some(targets) => match_batch_counts(&x0, &frame(&x0, false)?, targets, &mask, cfg)?,
                None => x0,
            };
            zero_empty_attributes(&x0, cfg)?
        } else {
            x0
        };
        let x0 = match guidance.as_deref_mut() {
            Some(g) => frame(&g.guide(&frame(&x0, false)?, t)?, true)?,
            None => x0,
        };
        // The jump's coefficients (of x̂0, of x_t, the fresh noise's variance) with the geometry's η
        // on the first CLASS_OFFSET features of each token and the classes' on the rest.
        let next = i.checked_sub(1).map(|j| visited[j]);
        let (geometry, classes) = (schedule.jump(t, next, chain.eta), schedule.jump(t, next, chain.class_eta));
        let per_feature = |pick: fn((f64, f64, f64)) -> f64| -> Result<Tensor, GenError> {
            let v: Vec<f32> =
                (0..cfg.token_dim()).map(|k| pick(if k < CLASS_OFFSET { geometry } else { classes }) as f32).collect();
            Ok(Tensor::from_vec(v, cfg.token_dim(), &Device::Cpu)?)
        };
        let mean = (x0.broadcast_mul(&per_feature(|c| c.0)?)? + x.broadcast_mul(&per_feature(|c| c.1)?)?)?;
        // Detached so that nothing (a guidance gradient) chains the steps' graphs. DDIM's chain
        // (η 0) draws nothing after its start.
        x = match i > 0 && (geometry.2 > 0.0 || classes.2 > 0.0) {
            true => (mean + gaussian(&mut rngs)?.broadcast_mul(&per_feature(|c| c.2.sqrt())?)?)?,
            false => mean,
        }
        .detach();
    }
    Ok(frame(&x, false)?.flatten_all()?.to_vec1::<f32>()?)
}

/// The last steps in which [`zero_empty_attributes`] projects x̂0: those with less noise than the
/// linear schedule's step 0.4 T (so 80 of 200 on the linear schedule itself).
///
/// Without it the shipped models sample 40–55 % more objects than their data has (6.3 vs 4.4 per
/// val bedroom, 11.7 vs 7.4 living, 13.7 vs 9.7 dining); an empty slot's attributes carry no loss,
/// so the model's estimate there is arbitrary, drifts away from the zeros it was trained on, and
/// the slot turns into an object. Projecting in every step undershoots (6.1 per living room: early
/// on, a slot that is momentarily empty stays so; so does setting the whole token to "empty":
/// 3.0 per bedroom even from 0.15 T); from step 0.4 T down the val splits get 4.29 / 7.28 / 9.56
/// objects per room against 4.39 / 7.45 / 9.73 in the data, and fewer layouts penetrate a person
/// (docs/RESULTS.md, "Empty-slot projection"). The threshold is a noise level, not a step count,
/// because what decides whether a slot is still open is how much noise is left.
pub fn empty_projection_steps(schedule: &Schedule) -> usize {
    schedule.at_linear_noise(schedule.steps() * 2 / 5)
}

/// [`match_counts`] for every item of a batch: `x0` in the model's frame, `world` the same in world
/// form, `mask` the contact mask (B × K) that says how many slots are anchored.
fn match_batch_counts(
    x0: &Tensor,
    world: &Tensor,
    targets: &CountTargets,
    mask: &[f32],
    cfg: &super::ModelConfig,
) -> Result<Tensor, GenError> {
    let (shape, per_item) = (x0.shape().clone(), cfg.slots() * cfg.token_dim());
    let world = world.flatten_all()?.to_vec1::<f32>()?;
    let mut v = x0.flatten_all()?.to_vec1::<f32>()?;
    let k = mask.len() / targets.per_item.len().max(1);
    for (item, rule) in targets.per_item.iter().enumerate() {
        let anchored = cfg.anchored_slots(mask[item * k..(item + 1) * k].iter().filter(|&&m| m > 0.5).count());
        let r = item * per_item..(item + 1) * per_item;
        match_counts(&world[r.clone()], &mut v[r], rule, anchored, &targets.bounds, cfg);
    }
    Ok(Tensor::from_vec(v, shape, &Device::Cpu)?)
}

/// Sets the continuous attributes of every slot whose largest class is "empty" to 0, as in the
/// training data (where they carry no loss, so the model's own estimate there is arbitrary).
fn zero_empty_attributes(x0: &Tensor, cfg: &super::ModelConfig) -> Result<Tensor, GenError> {
    let shape = x0.shape().clone();
    let mut v = x0.flatten_all()?.to_vec1::<f32>()?;
    let dim = cfg.token_dim();
    for t in v.chunks_exact_mut(dim) {
        if slot_class(t, cfg) == cfg.classes() - 1 {
            t[..CLASS_OFFSET].fill(0.0);
        }
    }
    Ok(Tensor::from_vec(v, shape, &Device::Cpu)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generator::ModelConfig;
    use crate::scene::RoomType;

    #[test]
    fn empty_slots_lose_their_attributes_and_objects_keep_theirs() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let (dim, classes) = (cfg.token_dim(), cfg.classes());
        let mut v: Vec<f32> = (0..cfg.slots() * dim).map(|i| ((i % 7) as f32 - 3.0) / 4.0).collect();
        for (slot, t) in v.chunks_exact_mut(dim).enumerate() {
            t[CLASS_OFFSET..].fill(-0.5);
            // Even slots lean to class 2, odd ones to "empty" (by a hair in slot 1).
            let winner = if slot % 2 == 0 { 2 } else { classes - 1 };
            t[CLASS_OFFSET + winner] = if slot == 1 { -0.49 } else { 0.9 };
        }
        let x0 = Tensor::from_vec(v.clone(), (1, cfg.slots(), dim), &Device::Cpu).unwrap();
        let out = zero_empty_attributes(&x0, &cfg).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        for (slot, (before, after)) in v.chunks_exact(dim).zip(out.chunks_exact(dim)).enumerate() {
            assert_eq!(before[CLASS_OFFSET..], after[CLASS_OFFSET..], "classes are never touched");
            if slot % 2 == 0 {
                assert_eq!(before, after, "slot {slot} is an object");
            } else {
                assert!(after[..CLASS_OFFSET].iter().all(|&a| a == 0.0), "slot {slot} is empty");
                assert!(before[..CLASS_OFFSET].iter().any(|&a| a != 0.0));
            }
        }
    }
}
