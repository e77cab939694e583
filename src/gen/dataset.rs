//! Training examples: a dataset split read from disk and encoded once (tokens, loss weights,
//! conditioning features), and batches assembled from it with optional dihedral augmentation.

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES};
use super::count_prior::{PriorRoom, contact_kinds};
use super::model::CondTensors;
use super::{
    Bounds, Dihedral, Features, FloorSize, GenError, ModelConfig, Prediction, Schedule, anchors, roles, tokens,
};
use crate::data::{DataError, Rng};
use crate::geom::OBox;
use crate::human::Conditions;
use crate::scene::{RoomType, Scene};
use candle_core::{Device, Tensor};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// One encoded scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Example {
    /// Object tokens (slots × token_dim).
    pub tokens: Vec<f32>,
    /// Loss weights, same shape.
    pub weights: Vec<f32>,
    /// Conditioning features (with count conditioning: the room's own counts).
    pub features: Features,
    /// The room as a count prior keeps it (its counts are the tokens' pieces per category).
    pub make_up: PriorRoom,
    /// The scene's pieces per category (the room type's order), as [`super::SeenCounts`] counts
    /// them: a piece several people share is one piece.
    pub pieces: Vec<u8>,
    /// How large its floor is, as [`super::SeenFloors`] records it.
    pub floor: FloorSize,
}

impl Example {
    /// Encodes `scene` for `cfg` with `bounds`.
    pub fn of(scene: &Scene, bounds: &Bounds, cfg: &ModelConfig) -> Example {
        let cond = Conditions::of(scene);
        let boxes: Vec<OBox> = anchors::anchor_boxes(&cond, cfg).into_iter().map(|(b, _)| b).collect();
        let (tokens, weights) = tokens::encode(scene, cond.window.center, &boxes, bounds, cfg);
        let mut counts = vec![0u8; cfg.classes() - 1];
        for t in tokens.chunks_exact(cfg.token_dim()) {
            if let Some(n) = counts.get_mut(tokens::slot_class(t, cfg)) {
                *n = n.saturating_add(1);
            }
        }
        let mut features = Features::of(&cond, scene.room_type, bounds, cfg);
        if cfg.count_condition {
            features.set_counts(&counts);
        }
        let area = scene.floor_plan.polygon().area();
        let make_up = PriorRoom::new(scene.room_type, contact_kinds(&cond), area, counts);
        let pieces = scene.room_type.category_counts(&scene.objects).into_iter().map(|n| n.min(255) as u8).collect();
        Example { tokens, weights, features, make_up, pieces, floor: FloorSize::of(&scene.floor_plan) }
    }

    /// This example under the symmetry `g`.
    pub fn transformed(&self, g: Dihedral, cfg: &ModelConfig) -> Example {
        let mut out = self.clone();
        g.apply_tokens(&mut out.tokens, cfg.token_dim());
        out.features.transform(g);
        if cfg.slot_roles {
            // The turn or mirror moved the pieces round the window centre: their order again.
            let boxes = out.features.contact_mask.iter().filter(|&&m| m != 0.0).count();
            roles::order_free_slots(&mut out.tokens, &mut out.weights, cfg.anchored_slots(boxes), cfg);
        }
        out
    }
}

/// The largest factor [`balance_categories`] gives a slot.
pub const MAX_CATEGORY_WEIGHT: f32 = 10.0;

/// Scales the loss weights of every object slot of a category rarer than the median category
/// (among those present in `examples`) by (median share / its share)^`power`, at most
/// [`MAX_CATEGORY_WEIGHT`]: as if rare objects were drawn that much more often. Slots of the median
/// category or commoner ones, empty slots, and everything at `power` 0 keep their weights.
pub fn balance_categories(examples: &mut [Example], power: f64, cfg: &ModelConfig) {
    if power <= 0.0 {
        return;
    }
    let (dim, empty) = (cfg.token_dim(), cfg.classes() - 1);
    let classes: Vec<Vec<usize>> =
        examples.iter().map(|e| e.tokens.chunks_exact(dim).map(|t| tokens::slot_class(t, cfg)).collect()).collect();
    let mut counts = vec![0usize; empty];
    for &class in classes.iter().flatten().filter(|&&c| c < empty) {
        counts[class] += 1;
    }
    let mut present: Vec<usize> = counts.iter().copied().filter(|&n| n > 0).collect();
    if present.is_empty() {
        return;
    }
    present.sort_unstable();
    let median = present[present.len() / 2] as f64;
    let factor: Vec<f32> = counts
        .iter()
        .map(|&n| if n == 0 { 1.0 } else { ((median / n as f64).powf(power) as f32).clamp(1.0, MAX_CATEGORY_WEIGHT) })
        .collect();
    for (e, classes) in examples.iter_mut().zip(&classes) {
        for (w, &class) in e.weights.chunks_exact_mut(dim).zip(classes) {
            if class < empty {
                w.iter_mut().for_each(|x| *x *= factor[class]);
            }
        }
    }
}

/// The scene files of a split folder, sorted by name.
pub fn split_files(dir: &Path, split: &str) -> Result<Vec<PathBuf>, GenError> {
    let folder = dir.join(split);
    let entries = std::fs::read_dir(&folder).map_err(|e| GenError::Data(DataError::io(&folder, e)))?;
    let mut files: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// Reads and encodes every scene of `dir/split` (in file-name order), in parallel.
pub fn load_split(dir: &Path, split: &str, bounds: &Bounds, cfg: &ModelConfig) -> Result<Vec<Example>, GenError> {
    let files = split_files(dir, split)?;
    files
        .par_iter()
        .map(|f| {
            let scene = Scene::load(f).map_err(|e| GenError::Data(DataError::Scene(e)))?;
            if !cfg.serves(scene.room_type) {
                return Err(GenError::Input {
                    path: f.clone(),
                    message: format!("room type {} but the model is for {}", scene.room_type, cfg.room_names()),
                });
            }
            Ok(Example::of(&scene, bounds, cfg))
        })
        .collect()
}

/// A batch on the host, ready to become tensors.
#[derive(Debug, Clone, Default)]
pub struct HostBatch {
    /// Scenes in the batch.
    pub size: usize,
    /// Clean tokens in the model's frame ([`super::anchors`]), B × slots × token_dim.
    pub tokens: Vec<f32>,
    /// Loss weights, same shape.
    pub weights: Vec<f32>,
    pub(super) contacts: Vec<f32>,
    pub(super) contact_mask: Vec<f32>,
    pub(super) floor: Vec<f32>,
    pub(super) free: Vec<f32>,
    pub(super) rooms: Vec<f32>,
    pub(super) counts: Vec<f32>,
}

impl HostBatch {
    /// Appends one example, its tokens turned into the model's frame.
    pub fn push(&mut self, e: &Example, cfg: &ModelConfig) {
        let start = self.tokens.len();
        self.tokens.extend_from_slice(&e.tokens);
        anchors::to_model(cfg, &e.features.contacts, &e.features.contact_mask, &mut self.tokens[start..]);
        self.weights.extend_from_slice(&e.weights);
        self.push_features(&e.features);
    }

    /// Appends the conditioning of one scene (for sampling, where there are no tokens).
    pub fn push_features(&mut self, f: &Features) {
        self.size += 1;
        self.contacts.extend_from_slice(&f.contacts);
        self.contact_mask.extend_from_slice(&f.contact_mask);
        self.floor.extend_from_slice(&f.floor);
        self.free.extend_from_slice(&f.free);
        self.rooms.extend_from_slice(&f.room);
        self.counts.extend_from_slice(&f.counts);
    }

    /// The conditioning as tensors.
    pub fn cond(&self, cfg: &ModelConfig) -> Result<CondTensors, GenError> {
        let b = self.size;
        let dev = &Device::Cpu;
        Ok(CondTensors {
            contacts: Tensor::from_slice(&self.contacts, (b, cfg.max_contacts, CONTACT_FEATURES), dev)?,
            contact_mask: Tensor::from_slice(&self.contact_mask, (b, cfg.max_contacts), dev)?,
            floor: Tensor::from_slice(&self.floor, (b, cfg.floor_points, FLOOR_FEATURES), dev)?,
            free: Tensor::from_slice(&self.free, (b, cfg.free_points, FREE_FEATURES), dev)?,
            room: Tensor::from_slice(&self.rooms, (b, RoomType::ALL.len()), dev)?,
            counts: Tensor::from_slice(&self.counts, (b, cfg.count_width()), dev)?,
        })
    }

    /// A tensor of shape (B, slots, token_dim) from host values laid out like the tokens.
    pub fn token_tensor(&self, values: &[f32], cfg: &ModelConfig) -> Result<Tensor, GenError> {
        Ok(Tensor::from_slice(values, (self.size, cfg.slots(), cfg.token_dim()), &Device::Cpu)?)
    }
}

/// The farthest [`NoisyBatch::displace_pieces`] moves a piece (token units, the window's half
/// side being 1: 28 to 52 cm).
pub const DISPLACE_REACH: f64 = 0.1;

/// A training batch: clean scenes, one diffusion step per scene, the noise the model must predict
/// and the noisy tokens it sees.
#[derive(Debug, Clone)]
pub struct NoisyBatch {
    /// The clean batch (tokens, loss weights, conditions).
    pub host: HostBatch,
    /// Diffusion step of each scene.
    pub t: Vec<usize>,
    /// ε, laid out like the tokens.
    pub noise: Vec<f32>,
    /// What the denoiser must output: ε, or the clean tokens (in the model's frame) for an x₀ model.
    pub target: Vec<f32>,
    /// x_t = √ᾱ_t x₀ + √(1 − ᾱ_t) ε.
    pub noisy: Vec<f32>,
    /// The loss weights: the host's, times each scene's Min-SNR weight where the model has one
    /// ([`ModelConfig::min_snr`]). The loss is still divided by [`weight_total`](Self::weight_total).
    pub loss_weights: Vec<f32>,
    /// For a self-conditioned model: whether each scene gets the model's own first clean estimate
    /// (half of them, drawn); empty otherwise.
    pub self_condition: Vec<bool>,
    /// The pairs of pieces whose relative places the relation loss holds
    /// ([`NoisyBatch::hold_relations`]); empty without it.
    pub relations: Vec<RelationPair>,
}

/// Two pieces of a training scene whose relative place the relation loss holds: the error of the
/// one's clean estimate of its centre less the other's, in world form, counts on top of each one's
/// own error ([`NoisyBatch::hold_relations`]).
#[derive(Debug, Clone, PartialEq)]
pub struct RelationPair {
    /// The scene (batch item).
    pub item: usize,
    /// The two slots.
    pub slots: [usize; 2],
    /// How much the pair's squared error counts: the loss's weight times the scene's own weight
    /// (its Min-SNR weight, as its tokens' errors count).
    pub weight: f32,
    /// Per slot, the 2 × 2 map (row-major) from an error in its centre's x, y in the model's frame
    /// to the error in world form: the identity for a free slot, `anchor_scale` times the box's
    /// rotation for an anchored one ([`anchors`]).
    pub maps: [[f32; 4]; 2],
}

impl NoisyBatch {
    /// Draws the steps, then the noise, then (self-conditioned models only) which scenes are
    /// self-conditioned, from `rng` (in that order: runs and resumes depend on it).
    pub fn draw(host: HostBatch, schedule: &Schedule, rng: &mut Rng, cfg: &ModelConfig) -> NoisyBatch {
        let per_item = cfg.slots() * cfg.token_dim();
        let steps = cfg.expert_below.map_or(schedule.steps(), |n| n.min(schedule.steps()));
        let t: Vec<usize> = (0..host.size).map(|_| rng.index(steps)).collect();
        let noise: Vec<f32> = (0..host.size * per_item).map(|_| rng.normal() as f32).collect();
        let noisy = host
            .tokens
            .iter()
            .zip(&noise)
            .enumerate()
            .map(|(k, (&x0, &n))| {
                let ab = schedule.alpha_bars[t[k / per_item]];
                (ab.sqrt() as f32) * x0 + ((1.0 - ab).sqrt() as f32) * n
            })
            .collect();
        let target = match cfg.prediction {
            Prediction::Epsilon => noise.clone(),
            Prediction::X0 => host.tokens.clone(),
            Prediction::V => host
                .tokens
                .iter()
                .zip(&noise)
                .enumerate()
                .map(|(k, (&x0, &n))| {
                    let ab = schedule.alpha_bars[t[k / per_item]];
                    (ab.sqrt() as f32) * n - ((1.0 - ab).sqrt() as f32) * x0
                })
                .collect(),
        };
        let self_condition = match cfg.self_condition {
            true => (0..host.size).map(|_| rng.index(2) == 1).collect(),
            false => Vec::new(),
        };
        let loss_weights = match cfg.min_snr {
            None => host.weights.clone(),
            Some(_) => host
                .weights
                .iter()
                .enumerate()
                .map(|(k, &w)| {
                    let ab = schedule.alpha_bars[t[k / per_item]];
                    w * cfg.prediction.loss_weight(ab / (1.0 - ab), cfg.min_snr, cfg.min_snr_floor) as f32
                })
                .collect(),
        };
        NoisyBatch { host, t, noise, target, noisy, loss_weights, self_condition, relations: Vec::new() }
    }

    /// The relation loss: every pair of pieces of a scene whose clean centres lie within `reach`
    /// token units of each other becomes a [`RelationPair`] of weight `weight` (times the scene's
    /// own weight). Without it the loss counts each piece's error alone, so a nightstand's estimate
    /// may move with the noise while its bed's moves the other way — and a sampled nightstand
    /// stands in its bed (docs/RESULTS.md, "Pieces that do not keep to each other"). Draws nothing.
    pub fn hold_relations(&mut self, weight: f64, reach: f64, schedule: &Schedule, cfg: &ModelConfig) {
        let (dim, slots, k) = (cfg.token_dim(), cfg.slots(), cfg.max_contacts);
        let per_item = slots * dim;
        let empty = cfg.classes() - 1;
        for item in 0..self.host.size {
            let clean = &self.host.tokens[item * per_item..(item + 1) * per_item];
            let contacts = &self.host.contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES];
            let mask = &self.host.contact_mask[item * k..(item + 1) * k];
            let mut world = clean.to_vec();
            anchors::to_world(cfg, contacts, mask, &mut world);
            let maps = anchors::error_maps(cfg, contacts, mask);
            let ab = schedule.alpha_bars[self.t[item]];
            let scene_weight = cfg.prediction.loss_weight(ab / (1.0 - ab), cfg.min_snr, cfg.min_snr_floor);
            let real: Vec<usize> =
                (0..slots).filter(|&s| tokens::slot_class(&clean[s * dim..(s + 1) * dim], cfg) != empty).collect();
            for (n, &i) in real.iter().enumerate() {
                for &j in &real[n + 1..] {
                    let (a, b) = (&world[i * dim..], &world[j * dim..]);
                    if ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt() as f64 <= reach {
                        self.relations.push(RelationPair {
                            item,
                            slots: [i, j],
                            weight: (weight * scene_weight) as f32,
                            maps: [maps[i], maps[j]],
                        });
                    }
                }
            }
        }
    }

    /// Input perturbation (Ning et al. 2023, DDPM-IP): adds √(1 − ᾱ_t) γ ξ to the noisy tokens, ξ
    /// drawn from `rng` after everything [`draw`](Self::draw) drew, and leaves the noise and the
    /// target as they were. The denoiser so learns to take inputs a little off the noise level
    /// it is told, as its own earlier steps give it when sampling (exposure bias).
    pub fn perturb_input(&mut self, gamma: f64, schedule: &Schedule, rng: &mut Rng) {
        let per_item = self.noisy.len() / self.host.size.max(1);
        for (k, x) in self.noisy.iter_mut().enumerate() {
            let ab = schedule.alpha_bars[self.t[k / per_item]];
            *x += ((1.0 - ab).sqrt() * gamma * rng.normal()) as f32;
        }
    }

    /// Displaced pieces: in a `share` of the scenes, drawn from `rng` after everything
    /// [`draw`](Self::draw) drew, one free slot's piece has its centre moved by 0.02 to
    /// [`DISPLACE_REACH`] token units in a random direction before the noise is added, and the
    /// target stays what gives the scene's own clean tokens back (for ε and v models the target
    /// changes with the input; for x₀ it is the clean tokens as before). The denoiser so learns to
    /// put a piece back where the rest of the room says it goes — from a place no real room has,
    /// as a sampling chain reaches (a chair inside its table) — at every noise level, the least
    /// included, where it otherwise copies its input.
    pub fn displace_pieces(&mut self, share: f64, schedule: &Schedule, cfg: &ModelConfig, rng: &mut Rng) {
        let (dim, slots, k) = (cfg.token_dim(), cfg.slots(), cfg.max_contacts);
        let empty = cfg.classes() - 1;
        for item in 0..self.host.size {
            if rng.uniform(0.0, 1.0) >= share {
                continue;
            }
            let boxes = self.host.contact_mask[item * k..(item + 1) * k].iter().filter(|&&m| m != 0.0).count();
            let tokens = &self.host.tokens[item * slots * dim..(item + 1) * slots * dim];
            let free: Vec<usize> = (cfg.anchored_slots(boxes)..slots)
                .filter(|&s| super::tokens::slot_class(&tokens[s * dim..(s + 1) * dim], cfg) != empty)
                .collect();
            let (angle, reach) = (rng.uniform(0.0, std::f64::consts::TAU), rng.uniform(0.02, DISPLACE_REACH));
            let Some(&slot) = free.get(rng.index(free.len().max(1))) else { continue };
            let ab = schedule.alpha_bars[self.t[item]];
            let sigma = (1.0 - ab).sqrt().max(1e-6);
            for (axis, shift) in [angle.cos() * reach, angle.sin() * reach].into_iter().enumerate() {
                let at = (item * slots + slot) * dim + axis;
                self.noisy[at] += (ab.sqrt() * shift) as f32;
                // The target whose clean estimate from the moved input is the scene's own.
                self.target[at] += match cfg.prediction {
                    Prediction::Epsilon => ab.sqrt() * shift / sigma,
                    Prediction::X0 => 0.0,
                    Prediction::V => ab * shift / sigma,
                } as f32;
            }
        }
    }

    /// The loss's denominator: the sum of the host's loss weights (before any Min-SNR weight), at
    /// least 1.
    pub fn weight_total(&self) -> f32 {
        self.host.weights.iter().sum::<f32>().max(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{SplitStats, generate_room};
    use crate::scene::{Category, Object, RoomType};

    /// Eight procedural bedrooms as a training batch for `cfg`, in their own bounds.
    fn eight_bedrooms(cfg: &ModelConfig) -> HostBatch {
        let scenes: Vec<Scene> = (0..8).map(|i| generate_room(RoomType::Bedroom, 3, i, false).scene).collect();
        let mut stats = SplitStats::default();
        scenes.iter().for_each(|s| stats.add(s));
        let bounds = Bounds::from_stats(&stats);
        let mut host = HostBatch::default();
        scenes.iter().for_each(|s| host.push(&Example::of(s, &bounds, cfg), cfg));
        host
    }

    #[test]
    fn a_low_noise_expert_draws_only_its_steps() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let schedule = Schedule::linear(cfg.diffusion_steps);
        let expert = ModelConfig { expert_below: Some(3), ..cfg.clone() };
        let (mut all, mut low) = (Vec::new(), Vec::new());
        for seed in 0..20 {
            all.extend(NoisyBatch::draw(eight_bedrooms(&cfg), &schedule, &mut Rng::new(seed), &cfg).t);
            low.extend(NoisyBatch::draw(eight_bedrooms(&expert), &schedule, &mut Rng::new(seed), &expert).t);
        }
        // 160 draws: every one of steps 0, 1, 2 and nothing above for the expert; the whole model
        // draws from all 200.
        assert_eq!((low.iter().max(), (0..3).all(|t| low.contains(&t))), (Some(&2), true));
        assert!(all.iter().any(|&t| t > 100));
    }

    #[test]
    fn input_perturbation_moves_the_noisy_tokens_by_gamma_times_the_noise_and_nothing_else() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let host = eight_bedrooms(&cfg);
        let schedule = Schedule::linear(cfg.diffusion_steps);
        let plain = NoisyBatch::draw(host.clone(), &schedule, &mut Rng::new(4), &cfg);
        let mut rng = Rng::new(4);
        let mut moved = NoisyBatch::draw(host, &schedule, &mut rng, &cfg);
        moved.perturb_input(0.5, &schedule, &mut rng);
        assert_eq!((&moved.noise, &moved.target, &moved.t), (&plain.noise, &plain.target, &plain.t));
        // Each change over its step's √(1 − ᾱ_t) is γ ξ: mean 0, standard deviation γ.
        let per_item = moved.noisy.len() / moved.t.len();
        let z: Vec<f64> = (0..moved.noisy.len())
            .map(|k| {
                let ab = schedule.alpha_bars[moved.t[k / per_item]];
                f64::from(moved.noisy[k] - plain.noisy[k]) / (1.0 - ab).sqrt()
            })
            .collect();
        let mean = z.iter().sum::<f64>() / z.len() as f64;
        let sd = (z.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / z.len() as f64).sqrt();
        assert!(z.len() > 1000 && mean.abs() < 0.05 && (sd - 0.5).abs() < 0.05, "{mean} {sd} over {}", z.len());
    }

    #[test]
    fn a_displaced_piece_moves_in_the_input_only_and_the_target_still_gives_the_scene_back() {
        for prediction in [Prediction::V, Prediction::Epsilon, Prediction::X0] {
            let cfg = ModelConfig { prediction, ..ModelConfig::tiny(RoomType::Bedroom) };
            let host = eight_bedrooms(&cfg);
            let schedule = Schedule::of(&cfg);
            let plain = NoisyBatch::draw(host.clone(), &schedule, &mut Rng::new(4), &cfg);
            let mut rng = Rng::new(4);
            let mut moved = NoisyBatch::draw(host, &schedule, &mut rng, &cfg);
            moved.displace_pieces(1.0, &schedule, &cfg, &mut rng);
            let (dim, per_item) = (cfg.token_dim(), cfg.slots() * cfg.token_dim());
            let changed: Vec<usize> = (0..moved.noisy.len()).filter(|&k| moved.noisy[k] != plain.noisy[k]).collect();
            // Every scene has a free piece: one slot's centre x and y move in each, nothing else.
            assert_eq!(changed.len(), 2 * moved.t.len(), "{changed:?}");
            for pair in changed.chunks(2) {
                assert_eq!((pair[0] % dim, pair[1]), (0, pair[0] + 1));
                let item = pair[0] / per_item;
                let ab = schedule.alpha_bars[moved.t[item]];
                let shift = |k: usize| f64::from(moved.noisy[k] - plain.noisy[k]) / ab.sqrt();
                let reach = shift(pair[0]).hypot(shift(pair[1]));
                assert!((0.02 - 1e-4..=DISPLACE_REACH + 1e-4).contains(&reach), "{reach}");
                // The clean estimate from the moved input and the new target is the scene's own.
                for &k in pair {
                    let x0 = prediction.clean_estimate(moved.target[k], moved.noisy[k], ab);
                    assert!(
                        (x0 - moved.host.tokens[k]).abs() < 1e-3,
                        "{prediction:?} t {}: {x0} vs {}",
                        moved.t[item],
                        moved.host.tokens[k]
                    );
                }
            }
            let unchanged = (0..moved.target.len()).filter(|k| !changed.contains(k));
            assert!(unchanged.into_iter().all(|k| moved.target[k] == plain.target[k]));
        }
    }

    #[test]
    fn rare_categories_weigh_more_and_nothing_else_changes() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let piece = |category: Category, x: f64| Object {
            id: format!("o{x}"),
            category,
            center: [x, 1.0, 0.3],
            size: [0.5, 0.5, 0.6],
            yaw: 0.0,
        };
        // Beds 3, nightstands 6, a wardrobe 1: median count 3, so the wardrobe's slot weighs
        // (3 / 1)^power, beds (3 / 3) and nightstands (3 / 6 → at least 1) stay.
        let scenes: Vec<Scene> = (0..3)
            .map(|i| {
                let mut s = generate_room(RoomType::Bedroom, 3, i, false).scene;
                s.objects = vec![
                    piece(Category::DoubleBed, 1.0),
                    piece(Category::Nightstand, 2.0),
                    piece(Category::Nightstand, 2.6),
                ];
                if i == 0 {
                    s.objects.push(piece(Category::Wardrobe, 3.2));
                }
                s
            })
            .collect();
        let mut stats = SplitStats::default();
        scenes.iter().for_each(|s| stats.add(s));
        let bounds = Bounds::from_stats(&stats);
        let plain: Vec<Example> = scenes.iter().map(|s| Example::of(s, &bounds, &cfg)).collect();
        let mut weighted = plain.clone();
        balance_categories(&mut weighted, 0.0, &cfg);
        assert_eq!(weighted, plain);
        balance_categories(&mut weighted, 1.0, &cfg);
        let dim = cfg.token_dim();
        for (scene, (w, p)) in weighted.iter().zip(&plain).enumerate() {
            for (slot, (ws, ps)) in w.weights.chunks_exact(dim).zip(p.weights.chunks_exact(dim)).enumerate() {
                let want = if scene == 0 && slot == 3 { 3.0 } else { 1.0 };
                assert!(
                    ws.iter().zip(ps).all(|(a, b)| (a - b * want).abs() < 1e-6),
                    "scene {scene} slot {slot}: {ws:?}"
                );
            }
        }
        // The cap.
        balance_categories(&mut weighted, 3.0, &cfg);
        assert_eq!(weighted[0].weights[3 * dim], 3.0 * MAX_CATEGORY_WEIGHT);
    }

    #[test]
    fn the_target_is_the_noise_the_clean_tokens_or_the_velocity_and_the_noisy_tokens_mix_them() {
        let scene = generate_room(RoomType::Bedroom, 3, 1, false).scene;
        let mut stats = SplitStats::default();
        stats.add(&scene);
        let bounds = Bounds::from_stats(&stats);
        for prediction in [Prediction::Epsilon, Prediction::X0, Prediction::V] {
            let cfg = ModelConfig { prediction, ..ModelConfig::tiny(RoomType::Bedroom) };
            let mut host = HostBatch::default();
            host.push(&Example::of(&scene, &bounds, &cfg), &cfg);
            let schedule = Schedule::linear(cfg.diffusion_steps);
            let b = NoisyBatch::draw(host, &schedule, &mut Rng::new(2), &cfg);
            let ab = schedule.alpha_bars[b.t[0]] as f32;
            match prediction {
                Prediction::Epsilon => assert_eq!(b.target, b.noise),
                Prediction::X0 => assert_eq!(b.target, b.host.tokens),
                Prediction::V => {
                    for ((v, x0), n) in b.target.iter().zip(&b.host.tokens).zip(&b.noise) {
                        assert!((v - (ab.sqrt() * n - (1.0 - ab).sqrt() * x0)).abs() < 1e-6);
                    }
                }
            }
            for (((x, x0), n), v) in b.noisy.iter().zip(&b.host.tokens).zip(&b.noise).zip(&b.target) {
                assert!((x - (ab.sqrt() * x0 + (1.0 - ab).sqrt() * n)).abs() < 1e-5);
                if prediction == Prediction::V {
                    // The sampler's inversion gives x₀ back.
                    assert!((Prediction::V.clean_estimate(*v, *x, schedule.alpha_bars[b.t[0]]) - x0).abs() < 1e-5);
                }
            }
        }
    }

    #[test]
    fn min_snr_weighs_each_scene_by_its_step_and_leaves_the_denominator() {
        let scenes: Vec<Scene> = (0..6).map(|i| generate_room(RoomType::Bedroom, 3, i, false).scene).collect();
        let mut stats = SplitStats::default();
        scenes.iter().for_each(|s| stats.add(s));
        let bounds = Bounds::from_stats(&stats);
        let plain = ModelConfig { prediction: Prediction::V, ..ModelConfig::tiny(RoomType::Bedroom) };
        let cfg = ModelConfig { min_snr: Some(5.0), ..plain.clone() };
        let mut host = HostBatch::default();
        scenes.iter().for_each(|s| host.push(&Example::of(s, &bounds, &cfg), &cfg));
        let schedule = Schedule::linear(cfg.diffusion_steps);
        let a = NoisyBatch::draw(host.clone(), &schedule, &mut Rng::new(3), &plain);
        let b = NoisyBatch::draw(host, &schedule, &mut Rng::new(3), &cfg);
        assert_eq!((&a.t, &a.noisy), (&b.t, &b.noisy), "the same draws");
        assert_eq!(a.loss_weights, a.host.weights);
        assert_eq!(a.weight_total(), b.weight_total());
        let per_item = cfg.slots() * cfg.token_dim();
        for (item, &t) in b.t.iter().enumerate() {
            let ab = schedule.alpha_bars[t];
            let snr = ab / (1.0 - ab);
            let want = (snr.min(5.0) / (snr + 1.0)) as f32;
            let range = item * per_item..(item + 1) * per_item;
            for (w, h) in b.loss_weights[range.clone()].iter().zip(&b.host.weights[range]) {
                assert!((w - h * want).abs() <= 1e-6 * h.max(1.0), "item {item} at step {t}");
            }
        }
        assert!(b.t.iter().any(|&t| t < 60) && b.t.iter().any(|&t| t > 100), "{:?}", b.t);
    }
}
