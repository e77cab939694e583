//! Model configuration: widths, depths, condition sizes and the diffusion length, with presets.

use super::tokens::Bounds;
use crate::scene::RoomType;
use serde::{Deserialize, Serialize};

/// Features of one contact box: centre (3), size (3), cos yaw, sin yaw, action one-hot (sit, lie, touch).
pub const CONTACT_FEATURES: usize = 11;
/// Features of one floor-plan point: position (2), outward normal (2).
pub const FLOOR_FEATURES: usize = 4;
/// Features of one free-space point: position (2), whether the mask had any pixel (1).
pub const FREE_FEATURES: usize = 3;
/// Hidden width of the relation-bias MLP ([`ModelConfig::relation_bias`]).
pub const RELATION_HIDDEN: usize = 32;
/// Sinusoidal time features.
pub const TIME_FEATURES: usize = 64;

/// Everything that fixes the denoiser's shape and the diffusion process.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelConfig {
    /// Room type the model generates.
    pub room_type: RoomType,
    /// Token width inside the transformer.
    pub d_model: usize,
    /// DiT blocks.
    pub blocks: usize,
    /// Attention heads (divides `d_model`).
    pub heads: usize,
    /// Hidden width of each block's MLP as a multiple of `d_model`.
    pub mlp_ratio: usize,
    /// Hidden width of the PointNets.
    pub pointnet_width: usize,
    /// Contact boxes read per scene (more are dropped, fewer are masked).
    pub max_contacts: usize,
    /// Whether contact boxes also join the attention as tokens (cross-attention); they always
    /// modulate every block through the pooled condition.
    pub contact_tokens: bool,
    /// Floor-plan points per scene.
    pub floor_points: usize,
    /// Free-space points per scene.
    pub free_points: usize,
    /// Diffusion steps T.
    pub diffusion_steps: usize,
    /// Contact-anchored slots ([`super::anchors`]): slot k of a scene with contact box k holds the
    /// piece serving that box, its centre predicted as an offset in the box's frame divided by this
    /// (token units, where the window's half side is 1), its yaw relative to the box's. 0 = off (every
    /// slot free, as in the models shipped before it; older configs read as 0).
    #[serde(default)]
    pub anchor_scale: f64,
    /// How an anchored slot's yaw is given: relative to its box's yaw (the first anchored models;
    /// older configs read so) or in the world, like every other slot's.
    #[serde(default)]
    pub anchored_yaw: AnchoredYaw,
    /// Whether every attention score gets a learned bias from the two tokens' relation (position
    /// and yaw of one in the other's frame, distance; [`super::relations`]). Off in older configs.
    #[serde(default)]
    pub relation_bias: bool,
    /// Relation values: in every block's attention, what a token takes from another also holds a
    /// learned linear map of the two pieces' relation (the other's position and yaw in its own
    /// frame; [`super::relations::value_features`]), so that a nightstand attending to its bed
    /// reads the bed's offset in its own frame, not only the bed's absolute place (Shaw et al.'s
    /// relative positions, on the values). Unlike the relation bias, which only chooses whom a
    /// token attends to, this hands the relation itself to the token. Off in older configs.
    #[serde(default)]
    pub relation_values: bool,
    /// Whether every object token gets an embedding of its centre's distances to the walls along
    /// its own axes, measured on the noisy tokens and the floor-plan points ([`super::walls`]).
    /// Off in older configs.
    #[serde(default)]
    pub wall_features: bool,
    /// Whether each sitter's knee box ([`crate::human::knee_box`]) also anchors a slot, after the
    /// contact boxes' slots: the slot holds the piece whose top reaches over the sitter's knees (a
    /// diner's table, a desk; one table in each of its diners' slots, as a sofa is in its
    /// sitters'), or nothing. The model then places a table in its diners' frame, as it places a
    /// seat in its sitter's ([`super::anchors`]). The knee boxes join the contact features with no
    /// action set. Off in older configs.
    #[serde(default)]
    pub table_slots: bool,
    /// Fourier features of the noisy tokens ([`super::fourier`]): every object token also gets an
    /// embedding of sin and cos of 2ᵏπ x, k = 1 … this, of each continuous attribute x. 0 (older
    /// configs): none.
    #[serde(default)]
    pub fourier_bands: usize,
    /// Whether every object token also gets an embedding of its continuous attributes in units of
    /// the step's noise, squashed ([`super::noise_scaled`]). Off in older configs.
    #[serde(default)]
    pub noise_scaled_features: bool,
    /// Gaps between pieces ([`super::gaps`]): every object token also gets an embedding of the
    /// gaps ahead of its piece's four faces to the nearest other piece, measured on the noisy
    /// tokens in metres with these bounds (the training data's, as the checkpoint's own). None
    /// (older configs): no gap features.
    #[serde(default)]
    pub gap_bounds: Option<Bounds>,
    /// Slot roles ([`super::roles`]): the training tokens hold the free pieces in one order, by
    /// the angle of their centre about the window centre, and every free slot gets a learned
    /// embedding of its rank among the free slots, so that free slots are no longer each other's
    /// twins. Off in older configs: the model is equivariant to the order of its free slots.
    #[serde(default)]
    pub slot_roles: bool,
    /// Whether every object token also gets an embedding of where its piece stands in the room —
    /// centre and yaw in world form, an anchored slot's taken out of its box's frame
    /// ([`super::anchors::world_slot_features`]) — so that anchored and free pieces meet in one
    /// frame. Off in older configs.
    #[serde(default)]
    pub world_features: bool,
    /// What the denoiser predicts: the noise ε (DDPM's choice, every model before it) or the clean
    /// tokens x₀. Older configs read as ε.
    #[serde(default)]
    pub prediction: Prediction,
    /// The noise schedule ([`super::Schedule::of`]). Older configs read as linear.
    #[serde(default)]
    pub schedule: NoiseSchedule,
    /// Self-conditioning (Chen et al., "Analog Bits"): every object token also gets an embedding
    /// of the model's own previous clean estimate x̂₀ of it (zeros at the first sampling step), so
    /// each step refines the last one's layout instead of starting over; trained on half of each
    /// batch with an estimate from a first pass without it. Needs x₀-prediction. Off in older
    /// configs.
    #[serde(default)]
    pub self_condition: bool,
    /// Min-SNR-γ loss weighting (Hang et al., 2023): each scene's loss is weighed so that its
    /// clean-estimate error counts min(SNR_t, γ), SNR_t = ᾱ_t / (1 − ᾱ_t) — for a v model
    /// min(SNR, γ) / (SNR + 1), for ε min(SNR, γ) / SNR, for x₀ min(SNR, γ). Without it (older
    /// configs) a v model's x̂₀ error counts SNR + 1, a thousand times more at the least noise than
    /// where the layout is decided, and an x₀ model's counts alike at every step.
    #[serde(default)]
    pub min_snr: Option<f64>,
    /// A floor under the Min-SNR weight: the clean-estimate error counts clamp(SNR, floor, γ)
    /// (Salimans & Ho's "truncated SNR" capped at γ). Min-SNR alone counts the noisiest steps
    /// SNR ≈ 0 times, so the steps where a room's make-up and the pieces under people are decided
    /// go almost untrained in a v model (docs/RESULTS.md); a floor of 1 counts them as an x₀ model
    /// does. Needs `min_snr`; none (0) in older configs.
    #[serde(default)]
    pub min_snr_floor: Option<f64>,
    /// A room token: a learned vector per room type ([`RoomType::ALL`]) added to the condition,
    /// so that one model serves every room type sharing its categories and slots (living and
    /// dining rooms), trained on all their rooms ([`ModelConfig::serves`]). Off in older configs:
    /// the model serves `room_type` alone.
    #[serde(default)]
    pub room_token: bool,
    /// Count conditioning: the condition also holds how many pieces of each category the layout
    /// has (a bias-free linear layer on the counts, added to the condition like the room token).
    /// Training reads a room's own counts; sampling draws them from the model's
    /// [`super::CountPrior`], the training rooms with the same people in them. Off in older
    /// configs: the model chooses the counts itself.
    #[serde(default)]
    pub count_condition: bool,
    /// A low-noise expert (the refiners of eDiff-I and SDXL): `Some(n)` trains the model on the
    /// steps t < n of its schedule alone, for sampling to hand it those steps beside a model of
    /// the whole chain ([`super::Generator::with_expert`]). None (older configs): every step.
    #[serde(default)]
    pub expert_below: Option<usize>,
}

/// Which noise levels the T steps visit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NoiseSchedule {
    /// DDPM's linear betas rescaled to T: the least noise, at step 0, is already σ ≈ 0.022 token
    /// units (6 cm in a bedroom), and only a couple of steps lie below 10 cm.
    #[default]
    Linear,
    /// log(ᾱ / (1 − ᾱ)) falling linearly from σ = [`LOG_SNR_SIGMA_MIN`] at step 0 to the linear
    /// schedule's ᾱ at step T − 1: a third of the steps lie below 3 cm of noise, where a layout's
    /// last centimetres are decided.
    LogSnr,
    /// Nichol & Dhariwal's cosine schedule: ᾱ_t = f(t + 1) / f(0), f(t) = cos²((t / T + s) / (1 + s)
    /// · π / 2), s = [`COSINE_OFFSET`], each β at most 0.999. Between the two above: the least noise
    /// is σ ≈ 0.016, ten steps lie below σ 0.1 (linear: five), and noise falls evenly over the
    /// middle of the chain instead of reaching pure noise by step 120.
    Cosine,
}

/// The offset s of the [`NoiseSchedule::Cosine`] schedule (Nichol & Dhariwal's 0.008).
pub const COSINE_OFFSET: f64 = 0.008;

/// The least noise of the [`NoiseSchedule::LogSnr`] schedule, in token units (8 mm in a bedroom).
pub const LOG_SNR_SIGMA_MIN: f64 = 0.003;

/// The frame of an anchored slot's yaw.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AnchoredYaw {
    /// Relative to the box's yaw. People lie and sit at any small angle to the piece under them,
    /// so the relative yaw of a bed varies where its world yaw is square to the walls: sampled
    /// beds were 6° off square (median, 17° at the 90th percentile) and their corners went
    /// through the walls (docs/RESULTS.md, "Anchored yaw").
    #[default]
    Box,
    /// In the world, as in free slots (the box's yaw still orients the centre's offset).
    World,
}

/// The denoiser's output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Prediction {
    /// The noise ε; x̂₀ = (x_t − √(1 − ᾱ_t) ε̂) / √ᾱ_t. Its x̂₀ at the last steps is only as
    /// precise as ε̂ times √(1 − ᾱ_t) / √ᾱ_t allows (docs/RESULTS.md, "x₀-prediction").
    #[default]
    #[serde(alias = "eps")]
    Epsilon,
    /// The clean tokens x₀ themselves (the loss is then on x₀, with the same weights).
    X0,
    /// The velocity v = √ᾱ_t ε − √(1 − ᾱ_t) x₀; x̂₀ = √ᾱ_t x_t − √(1 − ᾱ_t) v̂. At low noise x̂₀
    /// is then x_t plus a small correction (a skip connection the x₀ output lacks); at high noise
    /// it is the network's own estimate.
    V,
}

impl Prediction {
    /// The clean estimate x̂₀ of one token value from the denoiser's output `out` for the noisy
    /// value `x` at a step whose ᾱ is `alpha_bar` (unclamped; in f32 as the sampler had it on tensors).
    pub fn clean_estimate(self, out: f32, x: f32, alpha_bar: f64) -> f32 {
        let (a, s) = (alpha_bar.sqrt(), (1.0 - alpha_bar).sqrt());
        match self {
            Prediction::Epsilon => (x - out * s as f32) * (1.0 / a) as f32,
            Prediction::X0 => out,
            Prediction::V => x * a as f32 - out * s as f32,
        }
    }

    /// The loss weight of a scene at a step whose signal-to-noise ratio is `snr`, under Min-SNR-γ
    /// with an optional floor ([`ModelConfig::min_snr`], [`ModelConfig::min_snr_floor`]; no γ: 1).
    pub fn loss_weight(self, snr: f64, min_snr: Option<f64>, floor: Option<f64>) -> f64 {
        let Some(gamma) = min_snr else { return 1.0 };
        let x0_weight = snr.min(gamma).max(floor.unwrap_or(0.0));
        match self {
            Prediction::X0 => x0_weight,
            Prediction::Epsilon => x0_weight / snr.max(1e-12),
            Prediction::V => x0_weight / (snr + 1.0),
        }
    }
}

impl ModelConfig {
    /// Whether a model of `other` has this one's network (the same tensors, meaning the same): the
    /// configs may differ only in what training weighs and draws (`min_snr`, `min_snr_floor`,
    /// `expert_below`), as a low-noise expert fine-tuned from a model of the whole chain does.
    pub fn same_network(&self, other: &ModelConfig) -> bool {
        let trained_as_other = ModelConfig {
            min_snr: other.min_snr,
            min_snr_floor: other.min_snr_floor,
            expert_below: other.expert_below,
            ..self.clone()
        };
        trained_as_other == *other
    }

    /// The shipped size: d 128, 4 blocks (≈ 1.3 M parameters, ≈ 5 MB).
    pub fn small(room_type: RoomType) -> ModelConfig {
        ModelConfig {
            room_type,
            d_model: 128,
            blocks: 4,
            heads: 4,
            mlp_ratio: 4,
            pointnet_width: 64,
            max_contacts: 8,
            contact_tokens: true,
            floor_points: 128,
            free_points: 64,
            diffusion_steps: 200,
            anchor_scale: Self::ANCHOR_SCALE,
            anchored_yaw: AnchoredYaw::World,
            relation_bias: false,
            relation_values: false,
            wall_features: true,
            table_slots: false,
            fourier_bands: 0,
            noise_scaled_features: false,
            gap_bounds: None,
            slot_roles: false,
            world_features: false,
            prediction: Prediction::X0,
            schedule: NoiseSchedule::Linear,
            self_condition: false,
            min_snr: None,
            min_snr_floor: None,
            room_token: false,
            count_condition: false,
            expert_below: None,
        }
    }

    /// A wider model for the training budget's headroom: d 192, 6 heads of 32 as in `small`,
    /// 4 blocks (≈ 2.9 M parameters, ≈ 12 MB; about 2× `small`'s training time).
    pub fn medium(room_type: RoomType) -> ModelConfig {
        ModelConfig { d_model: 192, heads: 6, pointnet_width: 96, ..Self::small(room_type) }
    }

    /// A deeper model: `small`'s width with 8 blocks instead of 4 (≈ 2.5 M parameters, ≈ 10 MB;
    /// about 2× `small`'s training time), for relations that take more than one hop (a nightstand
    /// beside a bed against a wall).
    pub fn deep(room_type: RoomType) -> ModelConfig {
        ModelConfig { blocks: 8, ..Self::small(room_type) }
    }

    /// The default [`anchor_scale`](Self::anchor_scale): 0.4 of the window's half side, which
    /// covers the largest offset between a contact box and the piece serving it in the training
    /// data (0.99 / 1.49 / 1.29 m in bedrooms / living / dining rooms, whose windows' half sides are
    /// 2.8 / 5.2 / 4.3 m).
    pub const ANCHOR_SCALE: f64 = 0.4;

    /// The longest diffusion chain a config may ask for: the schedule and the sampler keep one
    /// value per step, and a chain of 10¹² steps would allocate terabytes.
    pub const MAX_DIFFUSION_STEPS: usize = 10_000;

    /// A tiny model for tests: `small`'s settings at a fraction of its size, with the relation
    /// bias on so that tests exercise it.
    pub fn tiny(room_type: RoomType) -> ModelConfig {
        ModelConfig {
            d_model: 32,
            blocks: 2,
            heads: 2,
            mlp_ratio: 2,
            pointnet_width: 16,
            max_contacts: 4,
            floor_points: 32,
            free_points: 16,
            relation_bias: true,
            ..Self::small(room_type)
        }
    }

    /// A preset by name (`small`, `medium`, `deep`, `tiny`).
    pub fn preset(name: &str, room_type: RoomType) -> Option<ModelConfig> {
        match name {
            "small" => Some(Self::small(room_type)),
            "medium" => Some(Self::medium(room_type)),
            "deep" => Some(Self::deep(room_type)),
            "tiny" => Some(Self::tiny(room_type)),
            _ => None,
        }
    }

    /// Whether the model generates rooms of type `room`: its own, or with a room token any type
    /// with the same categories, slots and window (living and dining rooms).
    pub fn serves(&self, room: RoomType) -> bool {
        let same = |r: RoomType| {
            r.categories() == self.room_type.categories()
                && r.max_objects() == self.room_type.max_objects()
                && r.window_side() == self.room_type.window_side()
        };
        room == self.room_type || (self.room_token && same(room))
    }

    /// The room types the model generates ([`ModelConfig::serves`]), in [`RoomType::ALL`]'s order.
    pub fn rooms(&self) -> Vec<RoomType> {
        RoomType::ALL.into_iter().filter(|&r| self.serves(r)).collect()
    }

    /// [`ModelConfig::rooms`] for messages: "living or dining".
    pub fn room_names(&self) -> String {
        self.rooms().iter().map(|r| r.to_string()).collect::<Vec<_>>().join(" or ")
    }

    /// Object slots (tokens) per scene.
    pub fn slots(&self) -> usize {
        self.room_type.max_objects()
    }

    /// How many of the first slots are anchored for a scene with `boxes` contact boxes (0 without
    /// anchored slots; boxes beyond `max_contacts` are not read).
    pub fn anchored_slots(&self, boxes: usize) -> usize {
        if self.anchor_scale > 0.0 { boxes.min(self.max_contacts) } else { 0 }
    }

    /// Width of the count condition: one value per category with [`Self::count_condition`], none
    /// without.
    pub fn count_width(&self) -> usize {
        if self.count_condition { self.classes() - 1 } else { 0 }
    }

    /// Classes including the final "empty" class.
    pub fn classes(&self) -> usize {
        self.room_type.categories().len() + 1
    }

    /// Width of one object token: centre (3), size (3), cos, sin, classes.
    pub fn token_dim(&self) -> usize {
        8 + self.classes()
    }

    /// Why the configuration cannot build a model, if it cannot.
    pub fn problem(&self) -> Option<String> {
        if self.d_model == 0 || self.heads == 0 || self.d_model % self.heads != 0 {
            return Some(format!("d_model {} is not a positive multiple of heads {}", self.d_model, self.heads));
        }
        if self.blocks == 0 || self.mlp_ratio == 0 || self.pointnet_width == 0 {
            return Some("blocks, mlp_ratio and pointnet_width must be positive".into());
        }
        if self.max_contacts == 0 || self.floor_points == 0 || self.free_points == 0 {
            return Some("max_contacts, floor_points and free_points must be positive".into());
        }
        if !(self.anchor_scale.is_finite() && self.anchor_scale >= 0.0) {
            return Some(format!("anchor_scale {} is not a finite number ≥ 0", self.anchor_scale));
        }
        if self.anchor_scale > 0.0 && self.max_contacts > self.slots() {
            return Some(format!(
                "anchored slots need max_contacts ({}) ≤ slots ({})",
                self.max_contacts,
                self.slots()
            ));
        }
        if self.fourier_bands > super::fourier::MAX_BANDS {
            return Some(format!("fourier_bands {} is over {}", self.fourier_bands, super::fourier::MAX_BANDS));
        }
        if self.gap_bounds.as_ref().is_some_and(|b| !b.is_valid()) {
            return Some("gap_bounds are not finite and ordered".into());
        }
        if self.self_condition && self.prediction != Prediction::X0 {
            return Some("self_condition needs prediction x0".into());
        }
        if let Some(gamma) = self.min_snr
            && !(gamma.is_finite() && gamma > 0.0)
        {
            return Some(format!("min_snr {gamma} is not a finite number > 0"));
        }
        if let Some(floor) = self.min_snr_floor
            && !(floor.is_finite() && floor >= 0.0 && self.min_snr.is_some_and(|gamma| floor <= gamma))
        {
            return Some(format!("min_snr_floor {floor} is not a number in [0, min_snr]"));
        }
        if let Some(n) = self.expert_below
            && !(1..=self.diffusion_steps).contains(&n)
        {
            return Some(format!("expert_below {n} is outside 1 to diffusion_steps {}", self.diffusion_steps));
        }
        if !(2..=Self::MAX_DIFFUSION_STEPS).contains(&self.diffusion_steps) {
            return Some(format!(
                "diffusion_steps {} is outside 2 to {}",
                self.diffusion_steps,
                Self::MAX_DIFFUSION_STEPS
            ));
        }
        let widths = [
            ("d_model", self.d_model, 4096),
            ("blocks", self.blocks, 64),
            ("heads", self.heads, 64),
            ("mlp_ratio", self.mlp_ratio, 16),
            ("pointnet_width", self.pointnet_width, 4096),
            ("floor_points", self.floor_points, 4096),
            ("free_points", self.free_points, 4096),
            ("max_contacts", self.max_contacts, 64),
        ];
        if let Some((name, value, max)) = widths.into_iter().find(|&(_, value, max)| value > max) {
            return Some(format!("{name} {value} is more than {max}"));
        }
        if self.anchor_scale > 10.0 {
            return Some(format!("anchor_scale {} is more than 10", self.anchor_scale));
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn min_snr_weights_count_the_clean_estimate_error_min_snr_gamma() {
        // SNR 100 and 0.5 against γ 5, by hand.
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(Prediction::V.loss_weight(100.0, Some(5.0), None), 5.0 / 101.0));
        assert!(close(Prediction::Epsilon.loss_weight(100.0, Some(5.0), None), 0.05));
        assert!(close(Prediction::X0.loss_weight(100.0, Some(5.0), None), 5.0));
        assert!(close(Prediction::V.loss_weight(0.5, Some(5.0), None), 1.0 / 3.0));
        assert!(close(Prediction::Epsilon.loss_weight(0.5, Some(5.0), None), 1.0));
        assert!(close(Prediction::X0.loss_weight(0.5, Some(5.0), None), 0.5));
        assert_eq!(Prediction::V.loss_weight(100.0, None, None), 1.0);
        let bad = ModelConfig { min_snr: Some(0.0), ..ModelConfig::tiny(RoomType::Bedroom) };
        assert!(bad.problem().unwrap().contains("min_snr"));
    }

    #[test]
    fn a_min_snr_floor_counts_the_noisiest_steps_as_an_x0_model_does() {
        // clamp(SNR, 1, 5) at SNR 0.01, 2 and 100, by hand: 1, 2, 5 on the clean estimate.
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(Prediction::V.loss_weight(0.01, Some(5.0), Some(1.0)), 1.0 / 1.01));
        assert!(close(Prediction::V.loss_weight(2.0, Some(5.0), Some(1.0)), 2.0 / 3.0));
        assert!(close(Prediction::V.loss_weight(100.0, Some(5.0), Some(1.0)), 5.0 / 101.0));
        assert!(close(Prediction::X0.loss_weight(0.01, Some(5.0), Some(1.0)), 1.0));
        assert!(close(Prediction::Epsilon.loss_weight(0.01, Some(5.0), Some(1.0)), 100.0));
        let tiny = ModelConfig::tiny(RoomType::Bedroom);
        let no_gamma = ModelConfig { min_snr_floor: Some(1.0), ..tiny.clone() };
        assert!(no_gamma.problem().unwrap().contains("min_snr_floor"));
        let above = ModelConfig { min_snr: Some(5.0), min_snr_floor: Some(6.0), ..tiny.clone() };
        assert!(above.problem().unwrap().contains("min_snr_floor"));
        // A low-noise expert takes at least one step and at most all.
        for (below, bad) in [(0, true), (1, false), (200, false), (201, true)] {
            let expert = ModelConfig { expert_below: Some(below), ..tiny.clone() };
            assert_eq!(expert.problem().is_some_and(|p| p.contains("expert_below")), bad, "{below}");
        }
        let good = ModelConfig { min_snr: Some(5.0), min_snr_floor: Some(1.0), ..tiny };
        assert_eq!(good.problem(), None);
    }

    #[test]
    fn gap_bounds_must_be_finite_and_ordered() {
        let ok = Bounds {
            center_min: [-3.0, -3.0, 0.0],
            center_max: [3.0, 3.0, 3.0],
            size_min: [0.0; 3],
            size_max: [3.0; 3],
        };
        let tiny = ModelConfig::tiny(RoomType::Dining);
        assert_eq!(ModelConfig { gap_bounds: Some(ok.clone()), ..tiny.clone() }.problem(), None);
        let nan = Bounds { size_max: [f64::NAN, 3.0, 3.0], ..ok.clone() };
        assert!(ModelConfig { gap_bounds: Some(nan), ..tiny.clone() }.problem().unwrap().contains("gap_bounds"));
        let reversed = Bounds { center_min: [4.0, -3.0, 0.0], ..ok };
        assert!(ModelConfig { gap_bounds: Some(reversed), ..tiny }.problem().unwrap().contains("gap_bounds"));
    }

    #[test]
    fn a_room_token_serves_the_room_types_that_share_the_categories() {
        let living = ModelConfig::tiny(RoomType::Living);
        assert_eq!(living.rooms(), [RoomType::Living]);
        let joint = ModelConfig { room_token: true, ..living };
        assert_eq!(joint.rooms(), [RoomType::Living, RoomType::Dining]);
        assert_eq!(joint.room_names(), "living or dining");
        let bedroom = ModelConfig { room_token: true, ..ModelConfig::tiny(RoomType::Bedroom) };
        assert_eq!(bedroom.rooms(), [RoomType::Bedroom]);
    }
}
