//! Layout generation for input scenes (floor plan + humans): conditioning, batched sampling,
//! decoding into shade-scene/1 scenes that keep the input's floor plan and humans.

use super::count_prior::contact_kinds;
use super::count_projection::{CountRule, CountTargets};
use super::dataset::HostBatch;
use super::sampler::{Chain, Denoisers, Guidance, Projection, empty_projection_steps, sample_from};
use super::{Checkpoint, Features, FloorSize, GenError, Schedule, UnseenFloor, anchors, tokens};
use crate::data::Rng;
use crate::human::{Conditions, ContactBox};
use crate::scene::{RoomFrame, Scene};
use std::borrow::Cow;

/// Makes the guidance of one batch from its input scenes (`None`: unguided).
pub type GuidanceFactory = dyn FnMut(&[&Scene]) -> Option<Box<dyn Guidance>>;

/// The stream of an item's seed ([`Rng::for_item`]) that draws its counts.
const COUNT_STREAM: u64 = 1;

/// Scenes sampled together at most (bounded memory, full use of the matrix kernels).
pub const MAX_BATCH: usize = 64;

/// A loaded model ready to sample.
#[derive(Debug, Clone)]
pub struct Generator {
    /// The model.
    pub checkpoint: Checkpoint,
    schedule: Schedule,
    /// The steps the sampler visits ([`Schedule::respaced`]; all T by default) and its η (1).
    chain: Chain,
    empty_projection: bool,
    /// Whether the projection keeps each person's slot to a piece that affords what they do
    /// ([`super::affordance_projection`]).
    affordances: bool,
    input_counts: bool,
    seen_counts: bool,
    /// Whether the chain starts from each input's own pieces ([`Generator::refining`]).
    from_input: bool,
    /// A low-noise expert for the chain's last steps ([`Generator::with_expert`]).
    expert: Option<Box<Checkpoint>>,
}

impl Generator {
    /// A generator over `checkpoint`, sampling as its config's `sampling` says (DDPM's chain
    /// without one).
    pub fn new(checkpoint: Checkpoint) -> Generator {
        let schedule = Schedule::of(&checkpoint.meta.model);
        let chain = match &checkpoint.meta.sampling {
            Some(s) => Chain { eta: s.geometry_eta, ..Chain::full(&schedule) },
            None => Chain::full(&schedule),
        };
        Generator {
            checkpoint,
            schedule,
            chain,
            empty_projection: true,
            affordances: true,
            input_counts: false,
            seen_counts: true,
            from_input: false,
            expert: None,
        }
    }

    /// The same generator handing the steps below `expert`'s
    /// [`expert_below`](super::ModelConfig::expert_below) to that low-noise expert. The expert
    /// must be this model's kind: the same conditioning, tokens, bounds and schedule (only its
    /// architecture, prediction and loss weighting may differ); `path`, its folder, names it in
    /// the error. A self-conditioned expert starts its own chain of estimates from zeros at the
    /// hand-over.
    pub fn with_expert(self, expert: Checkpoint, path: &std::path::Path) -> Result<Generator, GenError> {
        let (main, theirs) = (&self.checkpoint.meta, &expert.meta);
        let fail = |message: String| Err(GenError::Checkpoint { path: path.to_path_buf(), message });
        let Some(below) = theirs.model.expert_below else {
            return fail("the expert model was not trained as a low-noise expert (train --expert-below)".into());
        };
        let (a, b) = (&main.model, &theirs.model);
        let same_kind = a.room_type == b.room_type
            && a.room_token == b.room_token
            && a.count_condition == b.count_condition
            && a.diffusion_steps == b.diffusion_steps
            && a.schedule == b.schedule
            && a.anchor_scale == b.anchor_scale
            && a.anchored_yaw == b.anchored_yaw
            && a.max_contacts == b.max_contacts
            && a.contact_tokens == b.contact_tokens
            && a.floor_points == b.floor_points
            && a.free_points == b.free_points
            && main.bounds == theirs.bounds;
        if !same_kind {
            return fail(format!(
                "the expert (steps below {below}) does not fit the {} model: its room, conditioning, schedule or bounds differ",
                a.room_names()
            ));
        }
        Ok(Generator { expert: Some(Box::new(expert)), ..self })
    }

    /// The low-noise expert that takes the chain's last steps, if any ([`Generator::with_expert`]).
    pub fn expert(&self) -> Option<&Checkpoint> {
        self.expert.as_deref()
    }

    /// The same generator refining each input's own pieces instead of sampling from pure noise
    /// (SDEdit): the input's layout is noised to the noise level of the linear schedule's step
    /// `strength` × T (0 < strength ≤ 1; 1 forgets the input, small values keep its make-up and
    /// move its pieces by about that noise) and the chain runs down from there, guided as
    /// usual. An input without pieces starts from an empty room.
    pub fn refining(self, strength: f64) -> Generator {
        let steps = self.schedule.steps();
        let top =
            self.schedule.at_linear_noise(((strength.clamp(0.0, 1.0) * steps as f64).round() as usize).min(steps - 1));
        let visited = self.chain.visited.iter().copied().filter(|&t| t <= top).collect();
        Generator { chain: Chain { visited, ..self.chain }, from_input: true, ..self }
    }

    /// The same generator sampling with `n` model calls instead of T: the chain respaced to `n`
    /// evenly spaced steps ([`Schedule::respaced`]); guidance and the empty-slot projection still
    /// act by noise level.
    pub fn with_sampling_steps(self, n: usize) -> Generator {
        let chain = Chain { visited: self.schedule.respaced(n), ..self.chain };
        Generator { chain, ..self }
    }

    /// The same generator drawing `eta` times DDPM's fresh noise at each step
    /// ([`Schedule::jump`]): 0 is the deterministic DDIM sampler, 1 (the default) DDPM's ancestral
    /// one, above 1 more noise drawn afresh.
    pub fn with_eta(self, eta: f64) -> Generator {
        let chain = Chain { eta, class_eta: eta, ..self.chain };
        Generator { chain, ..self }
    }

    /// The same generator drawing `eta` times DDPM's fresh noise on the pieces' geometry alone
    /// (centre, size, yaw), the classes keeping DDPM's chain.
    pub fn with_geometry_eta(self, eta: f64) -> Generator {
        let chain = Chain { eta, class_eta: 1.0, ..self.chain };
        Generator { chain, ..self }
    }

    /// The same generator without the sampler's empty-slot projection, nor its count projection
    /// (counts asked for or counts the data has): the model's raw output, which has 40–55 % more
    /// objects than the data ([`empty_projection_steps`]).
    pub fn without_empty_projection(self) -> Generator {
        Generator { empty_projection: false, ..self }
    }

    /// The same generator keeping the class the model gives a person's slot even where that piece
    /// does not afford what they do (a dining table under a diner), instead of the affording
    /// piece the slot scores highest ([`super::affordance_projection`]).
    pub fn without_affordances(self) -> Generator {
        Generator { affordances: false, ..self }
    }

    /// The same generator without the projection onto the counts the training data has (for a
    /// model without count conditioning; [`super::SeenCounts`]): each category's count is the
    /// model's own, even one no training room has.
    pub fn without_seen_counts(self) -> Generator {
        Generator { seen_counts: false, ..self }
    }

    /// The same generator conditioning a count-conditioned model on each input's own pieces per
    /// category instead of a draw from its count prior.
    pub fn with_input_counts(self) -> Generator {
        Generator { input_counts: true, ..self }
    }

    /// The seed of sample `k` of input `i` for the run seed `seed`.
    pub fn item_seed(seed: u64, input: usize, sample: usize) -> u64 {
        Rng::for_item(seed, ((input as u64) << 20) | sample as u64).next_u64()
    }

    /// With count conditioning, the pieces per category (the model's class order) that sample `k`
    /// of input `i` is conditioned on for the run seed `seed`: drawn from the model's
    /// [`CountPrior`](super::CountPrior) for the input's room type, contacts and floor area, or
    /// the input's own with [`Generator::with_input_counts`]. `None` for a model without count
    /// conditioning.
    pub fn counts_of(&self, input: &Scene, i: usize, k: usize, seed: u64) -> Result<Option<Vec<u8>>, GenError> {
        self.drawn_counts(input, &Conditions::of(input), Self::item_seed(seed, i, k))
    }

    fn drawn_counts(&self, input: &Scene, cond: &Conditions, item_seed: u64) -> Result<Option<Vec<u8>>, GenError> {
        let meta = &self.checkpoint.meta;
        if !meta.model.count_condition {
            return Ok(None);
        }
        if self.input_counts {
            // A served room type has the model's categories in the model's order.
            let counts = input.room_type.category_counts(&input.objects);
            return Ok(Some(counts.into_iter().map(|n| n.min(usize::from(u8::MAX)) as u8).collect()));
        }
        let area = input.floor_plan.polygon().area();
        let mut rng = Rng::for_item(item_seed, COUNT_STREAM);
        let prior = meta.count_prior.as_ref();
        match prior.and_then(|p| p.draw(input.room_type, contact_kinds(cond), area, &mut rng)) {
            Some(counts) => Ok(Some(counts.to_vec())),
            None => Err(GenError::Input {
                path: Default::default(),
                message: format!("the model's count prior has no {} room", input.room_type),
            }),
        }
    }

    /// The contact spans of `scene` the model does not condition on: those beyond its
    /// `max_contacts` (its contact-anchored slots), in the order conditioning takes them; empty for
    /// most inputs. Their pieces come from guidance and repair alone.
    pub fn unseen_contacts(&self, scene: &Scene) -> Vec<ContactBox> {
        let seen = self.checkpoint.meta.model.max_contacts;
        Conditions::contact_boxes_of(scene).into_iter().skip(seen).collect()
    }

    /// `scene`'s floor, if its area, width or length (to 0.1, as the training rooms' are
    /// recorded) is outside the training rooms' ([`super::SeenFloors`]; `None` too for a model
    /// folder that does not record them).
    pub fn unseen_floor(&self, scene: &Scene) -> Option<UnseenFloor> {
        self.checkpoint.meta.seen_floors.as_ref()?.unseen(scene.room_type, FloorSize::of(&scene.floor_plan))
    }

    /// `samples` layouts per input, in input order then sample order. Deterministic for `seed`.
    /// Inputs must have the model's room type. A floor plan at an angle is sampled in its own frame
    /// ([`RoomFrame`]) and its pieces turned back; each layout keeps its input's plan and people.
    pub fn generate(&self, inputs: &[Scene], samples: usize, seed: u64) -> Result<Vec<Vec<Scene>>, GenError> {
        self.generate_with(inputs, samples, seed, &mut |_| None, &mut |_| {})
    }

    /// Like [`Generator::generate`], with a guidance made per batch from its input scenes and a
    /// callback after every batch with the number of samples done.
    pub fn generate_with(
        &self,
        inputs: &[Scene],
        samples: usize,
        seed: u64,
        guidance: &mut GuidanceFactory,
        progress: &mut dyn FnMut(usize),
    ) -> Result<Vec<Vec<Scene>>, GenError> {
        let model = &self.checkpoint.meta.model;
        if let Some(bad) = inputs.iter().find(|s| !model.serves(s.room_type)) {
            return Err(GenError::Input {
                path: Default::default(),
                message: format!("input is a {} but the model generates {}", bad.room_type, model.room_names()),
            });
        }
        // Sampled in each room's own frame, walls along the axes as in training; pieces turned back.
        let world = inputs;
        let frames: Vec<RoomFrame> = world.iter().map(|s| RoomFrame::of(&s.floor_plan)).collect();
        let framed: Vec<Cow<Scene>> = world
            .iter()
            .zip(&frames)
            .map(|(s, f)| if f.is_identity() { Cow::Borrowed(s) } else { Cow::Owned(f.to_frame(s)) })
            .collect();
        let inputs: Vec<&Scene> = framed.iter().map(|s| s.as_ref()).collect();
        let jobs: Vec<(usize, usize)> = (0..inputs.len()).flat_map(|i| (0..samples).map(move |k| (i, k))).collect();
        let features: Vec<(Conditions, Features)> = inputs
            .iter()
            .map(|s| {
                let cond = Conditions::of(s);
                let f = Features::of(&cond, s.room_type, &self.checkpoint.meta.bounds, model);
                (cond, f)
            })
            .collect();
        let meta = &self.checkpoint.meta;
        let mut out: Vec<Vec<Scene>> = vec![Vec::with_capacity(samples); inputs.len()];
        let mut done = 0;
        for chunk in jobs.chunks(MAX_BATCH) {
            let mut batch = HostBatch::default();
            let mut start = Vec::new();
            let mut seeds = Vec::with_capacity(chunk.len());
            let mut rules = Vec::with_capacity(chunk.len());
            for &(i, k) in chunk {
                let item_seed = Self::item_seed(seed, i, k);
                match self.drawn_counts(inputs[i], &features[i].0, item_seed)? {
                    Some(c) => {
                        let mut f = features[i].1.clone();
                        f.set_counts(&c);
                        batch.push_features(&f);
                        rules.push(Some(CountRule::Asked(c)));
                    }
                    None => {
                        batch.push_features(&features[i].1);
                        let seen = meta.seen_counts.as_ref().filter(|_| self.seen_counts);
                        rules.push(seen.and_then(|s| s.of_room(inputs[i].room_type)).cloned().map(CountRule::Seen));
                    }
                }
                seeds.push(item_seed);
                if self.from_input {
                    let (input, cond) = (inputs[i], &features[i].0);
                    let boxes: Vec<_> = anchors::anchor_boxes(cond, model).into_iter().map(|(b, _)| b).collect();
                    start.extend(tokens::encode(input, cond.window.center, &boxes, &meta.bounds, model).0);
                }
            }
            // The projection also keeps the slots to the counts asked for, or to counts the data has.
            let per_item: Option<Vec<CountRule>> = rules.into_iter().collect();
            let projection = match self.empty_projection {
                false => Projection::default(),
                true => Projection {
                    steps: empty_projection_steps(&self.schedule),
                    counts: per_item.map(|per_item| CountTargets { per_item, bounds: meta.bounds.clone() }),
                    affordances: self.affordances,
                },
            };
            let scenes: Vec<&Scene> = chunk.iter().map(|&(i, _)| inputs[i]).collect();
            let mut guide = guidance(&scenes);
            let cond = batch.cond(&meta.model)?;
            let denoisers =
                Denoisers { main: &self.checkpoint.denoiser, expert: self.expert.as_ref().map(|e| &e.denoiser) };
            let tokens = sample_from(
                denoisers,
                &self.schedule,
                &self.chain,
                &cond,
                &seeds,
                &projection,
                guide.as_mut().map(|g| g.as_mut() as &mut dyn Guidance),
                self.from_input.then_some(&start[..]),
            )?;
            let per_item = meta.model.slots() * meta.model.token_dim();
            for (item, (&(i, _), t)) in chunk.iter().zip(tokens.chunks_exact(per_item)).enumerate() {
                let mut scene = inputs[i].clone();
                let center = features[i].0.window.center;
                scene.objects = tokens::decode(t, center, scene.floor_plan.height, &meta.bounds, &meta.model);
                if let Some(g) = guide.as_mut() {
                    g.finish(item, &mut scene);
                }
                if !frames[i].is_identity() {
                    scene = Scene {
                        objects: scene.objects.iter().map(|o| frames[i].to_world(o)).collect(),
                        ..world[i].clone()
                    };
                }
                out[i].push(scene);
            }
            done += chunk.len();
            progress(done);
        }
        Ok(out)
    }
}
