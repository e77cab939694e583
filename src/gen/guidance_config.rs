//! The guidance's settings: the weights of SHADE's spatial terms and of ours, how each term
//! measures, how far and how often a step moves the pieces ([`GuidanceConfig`]), and how J_o
//! measures two pieces' overlap ([`Overlap`]). It parses `--guidance` lists and checks a guidance
//! file's values; it does not compute a term (that is [`super::guidance`] and the term modules).

use super::guidance::SpatialGuidance;
use super::{Bounds, Guidance, ModelConfig};
use crate::geom::{OBox, intersection_volume, iou_3d};
use crate::physics::Physics;
use crate::scene::Scene;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Weights of the terms and the step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuidanceConfig {
    /// Weight of J_m (walking humans' free space), per m².
    pub motion: f64,
    /// Weight of J_b (outside the floor plan): per m² of soft coverage, or per metre of depth
    /// with `bound_margin`.
    pub bound: f64,
    /// How J_b measures a piece beyond the walls. `None`: SHADE's soft area of outside pixels
    /// under the footprint, which keeps pushing a piece a few pixels into the room (guided wall
    /// pieces ended 8–16 cm off the wall). `Some(m)`: exactly, the depth of each footprint corner
    /// past the line `m` inside the walls (and of an L-shaped room's inner corner into the
    /// footprint, and in a room with such a corner the part of the footprint outside), zero for a
    /// piece at least `m` inside ([`super::beyond_walls`]). `all()`: 5 cm, the data's gap.
    #[serde(default)]
    pub bound_margin: Option<f64>,
    /// Weight of J_w (ours; per m²): pieces the data stands against a wall drawn back to the wall
    /// behind them, to the data's gap ([`super::against_walls`]; 0 = off, 0.2 in `all()`).
    #[serde(default)]
    pub against_wall: f64,
    /// How far (m) beyond the data's gap a piece's back may be from the wall behind it for J_w to
    /// draw it back; farther, the model put it out in the room and J_w leaves it there (0.6 in
    /// [`all`](Self::all); absent from a file: 0.3, the default until 2026-12-05).
    #[serde(default = "GuidanceConfig::default_against_wall_reach")]
    pub against_wall_reach: f64,
    /// The gap (m) J_w draws a wall piece's back to: the data's own (`None`, the default:
    /// [`WALL_GAP`](crate::data::layout::WALL_GAP)); for data whose gaps are drawn (`synth
    /// --gap-spread`), the widest of them.
    #[serde(default)]
    pub against_wall_gap: Option<f64>,
    /// Weight of J_o (Σ pairwise IoU).
    pub object: f64,
    /// How J_o measures a pair's overlap.
    #[serde(default)]
    pub overlap: Overlap,
    /// The gap (m) J_o keeps between pieces' footprints: each footprint is grown by half of it on
    /// every side before the overlap is measured (3 cm in `all()`, as the data's pieces stand; 0 in
    /// `shade()` and in files without the field: touching is enough).
    #[serde(default)]
    pub object_gap: f64,
    /// Largest distance (m) a piece's centre moves, and any of its sizes changes, in one gradient
    /// step; `None` = unbounded.
    #[serde(default)]
    pub max_step: Option<f64>,
    /// Gradient steps on x̂0 per guided diffusion step (stopping early at J = 0).
    #[serde(default = "GuidanceConfig::default_iterations")]
    pub iterations: usize,
    /// Weight of J_c (contact-box footprint left uncovered by the piece anchored to it), per m².
    /// On whenever a spatial term is; 0 leaves anchored pieces free.
    #[serde(default = "GuidanceConfig::default_contact")]
    pub contact: f64,
    /// How J_c measures a box the piece leaves uncovered. `None`: the soft area of its footprint
    /// pixels outside the piece's, plus the distance of its centre (per m² and m), which keeps
    /// growing a piece that covers its box (guided dining chairs 0.74 m wide). `Some(m)`:
    /// exactly, the depth of each corner of the box's footprint beyond the line `m` inside the
    /// piece's surface (its seat, mattress or top; per m; [`super::boxes_uncovered`]), zero for a
    /// piece whose surface covers it. `all()`: 0.
    #[serde(default)]
    pub contact_margin: Option<f64>,
    /// Weight of J_p (people's bones inside pieces, metres of depth; [`super::bodies`]).
    #[serde(default)]
    pub body: f64,
    /// Weight of J_s (a sitter's, sleeper's or toucher's piece too low under them, metres;
    /// [`super::bodies`]).
    #[serde(default)]
    pub support: f64,
    /// Weight of J_t (ours; metres): a diner's table drawn until its top reaches over their knees
    /// ([`super::at_table`]; 0 = off, as in files without the field).
    #[serde(default)]
    pub table: f64,
    /// How far (m) a diner's knees may be from the nearest table for J_t to draw it to them;
    /// farther, the model gave them none and J_t leaves the layout as it is.
    #[serde(default = "GuidanceConfig::default_table_reach")]
    pub table_reach: f64,
    /// Step size γ: per unit of weighted J gradient, a piece's centre moves γ · ℓ² metres (ℓ =
    /// [`CENTRE_STEP_LENGTH`], the same in every model), its sizes γ token units (scaled by
    /// `size_mobility`), its yaw about γ radians.
    pub scale: f64,
    /// Guide only at steps t < `until_step` (steps count down from T − 1 to 0) of the linear
    /// schedule; under another schedule, at the steps with less noise than the linear schedule's
    /// step `until_step` ([`super::Schedule::at_linear_noise`]), so that the guidance starts at the
    /// same noise level whatever the model's schedule.
    pub until_step: usize,
    /// Guide only at the window's steps t that are multiples of `every` (1, the default: at each).
    /// A model with many steps inside the window (the log-SNR schedule has 84 of 200) can be
    /// guided at every other one for half the cost.
    #[serde(default = "GuidanceConfig::default_every")]
    pub every: usize,
    /// Share of its step a piece in an anchored slot takes (the piece serving a contact box, whose
    /// person holds it in place; 1 = like any piece, 0 = not moved). Only models with anchored
    /// slots have such pieces.
    #[serde(default = "GuidanceConfig::default_anchored_mobility")]
    pub anchored_mobility: f64,
    /// Share of its step a piece's width, depth and height take (1 = as its centre and yaw, 0 =
    /// the sizes the model drew are kept). Guided sizes shrink where the terms push pieces apart:
    /// a piece smaller by a centimetre overlaps less, just as one moved by a centimetre does. 0.3
    /// in [`all`](Self::all): the log-SNR chains guide at 84 steps, and at 1 the shrinking left a
    /// fifth of the pieces at sizes the data never draws (docs/RESULTS.md, "Sizes the guidance
    /// keeps").
    #[serde(default = "GuidanceConfig::default_size_mobility")]
    pub size_mobility: f64,
    /// Weight of J_q (ours): pieces turned from the walls' directions, Σ (1 − cos 4Δ) / 4 over
    /// pieces, Δ their yaw less the longest wall's (0 = off; [`squareness`]).
    #[serde(default)]
    pub square: f64,
    /// Weight of the physics-feedback displacements (J_phys; 0 = off).
    #[serde(default)]
    pub phys: f64,
    /// Physics feedback only at steps t < `phys_until`…
    #[serde(default)]
    pub phys_until: usize,
    /// …that are multiples of `phys_every`.
    #[serde(default)]
    pub phys_every: usize,
    /// How far (m) a guided piece's width, depth and height may leave the range of its category's
    /// real pieces (`furniture::size_range`); `None` = anywhere within the decoding bounds. The
    /// terms have no notion of what a piece is: J_p, asked to get a dining table out of its
    /// diners' thighs, lowered it to the floor (5 cm dining tables, 0.05–0.35 m double beds in
    /// 36 of 492 guided val bedrooms); kept within what real pieces are, it must move instead.
    #[serde(default)]
    pub real_sizes: Option<f64>,
    /// Share of the smaller piece's volume above which two pieces in anchored slots are folded
    /// into one, the larger (footprint) kept in all their slots; `None` = never. Two people on one
    /// sofa are two anchored slots, which the training data always gives the same piece; when the
    /// model puts a loveseat in one and an armchair in the other on top of each other, the
    /// overlap term would push the two apart, away from their people.
    #[serde(default)]
    pub fold_anchored: Option<f64>,
}

impl GuidanceConfig {
    /// All three spatial terms with the default settings, chosen on the val splits
    /// (docs/RESULTS.md, "Guidance that converges", "Bodies and support" and "Bones, not surface
    /// points", "J_b weighted 8", "J_o's gap, the default" and "The exact terms, the default"):
    /// J_b weighted 8, exact, 5 cm inside the walls; J_w 0.2 drawing wall pieces back to their
    /// wall from up to 60 cm beyond the data's gap (docs/RESULTS.md, "J_w reaching 60 cm, once
    /// the steps converge"); J_o as the share of the smaller piece with footprints kept 3 cm
    /// apart; J_c 4, exact, holding the pieces under people (which otherwise move like any piece)
    /// until their surface covers the contact box; J_p and J_s 1 keeping them out of the bodies
    /// and up against them; J_t 1 drawing a diner's table over their knees from up to 50 cm
    /// (docs/RESULTS.md, "Diners at their table"); J_q 1 turning pieces square to the walls; in each of the last 20
    /// steps up to 128 gradient steps of at most 3 cm; pieces in anchored slots overlapping by
    /// more than a quarter of the smaller are folded into one (docs/RESULTS.md, "One piece for
    /// the people on it").
    pub fn all() -> GuidanceConfig {
        GuidanceConfig {
            motion: 1.0,
            bound: 8.0,
            bound_margin: Some(crate::data::layout::WALL_GAP),
            against_wall: 0.2,
            against_wall_reach: 0.6,
            against_wall_gap: None,
            object: 1.0,
            overlap: Overlap::Smaller,
            object_gap: 0.03,
            max_step: Some(0.03),
            iterations: 128,
            contact: 4.0,
            contact_margin: Some(0.0),
            body: 1.0,
            support: 1.0,
            table: 1.0,
            table_reach: 0.5,
            scale: 0.1,
            until_step: 20,
            every: 1,
            anchored_mobility: 1.0,
            size_mobility: 0.3,
            square: 1.0,
            phys: 0.0,
            phys_until: 20,
            phys_every: 4,
            real_sizes: Some(crate::furniture::REAL_SIZE_MARGIN),
            fold_anchored: Some(0.25),
        }
    }

    /// [`all`](Self::all) with J_b and J_c measured softly, as SHADE's J_b is (the soft area of
    /// footprint pixels beyond the walls, of a contact box's pixels the piece leaves uncovered),
    /// and no J_w: the default until the exact terms replaced it (docs/RESULTS.md, "The exact
    /// terms, the default"). The soft terms never quite let go, so guided wall pieces ended 10 cm
    /// off their walls and chairs under diners grew 0.74 m wide, and the judge told the model's
    /// own layouts from real ones almost every time (val SCA alone 0.98 / 0.89 / 0.93).
    pub fn soft() -> GuidanceConfig {
        GuidanceConfig { bound_margin: None, against_wall: 0.0, contact_margin: None, ..Self::all() }
    }

    /// SHADE's guidance as the paper gives it and as this crate had it before the settings above:
    /// unit weights, IoU, one step of γ 0.1 in each of the last 100 steps, nothing holding the
    /// pieces under people but `anchored_mobility` 0. A config file that leaves the newer fields
    /// out gets these.
    pub fn shade() -> GuidanceConfig {
        GuidanceConfig {
            bound: 1.0,
            bound_margin: None,
            against_wall: 0.0,
            against_wall_reach: 0.3,
            contact_margin: None,
            overlap: Overlap::Iou,
            object_gap: 0.0,
            max_step: None,
            iterations: 1,
            contact: 0.0,
            body: 0.0,
            support: 0.0,
            table: 0.0,
            until_step: 100,
            anchored_mobility: 0.0,
            size_mobility: 1.0,
            square: 0.0,
            real_sizes: None,
            fold_anchored: None,
            ..Self::all()
        }
    }

    fn default_against_wall_reach() -> f64 {
        Self::shade().against_wall_reach
    }

    fn default_table_reach() -> f64 {
        Self::all().table_reach
    }

    fn default_every() -> usize {
        1
    }

    fn default_size_mobility() -> f64 {
        Self::shade().size_mobility
    }

    fn default_anchored_mobility() -> f64 {
        Self::shade().anchored_mobility
    }

    fn default_iterations() -> usize {
        Self::shade().iterations
    }

    fn default_contact() -> f64 {
        Self::shade().contact
    }

    /// The weight `phys` takes when the term is asked for.
    pub const PHYS_WEIGHT: f64 = 1.0;

    /// Only the named terms (`mot`, `bound`, `obj`, `all`, `phys`, `none`), comma-separated; `soft`
    /// measures them as [`soft`](Self::soft) does, without J_w; `exact` (or its older name
    /// `walls`) as the default does.
    /// Repair after sampling is not a guidance term: it is `repair`'s job.
    pub fn parse(list: &str) -> Result<GuidanceConfig, String> {
        let mut cfg = GuidanceConfig { motion: 0.0, bound: 0.0, object: 0.0, ..Self::all() };
        let full = Self::all();
        for term in list.split(',').map(str::trim) {
            match term {
                "none" => {}
                "all" => (cfg.motion, cfg.bound, cfg.object) = (full.motion, full.bound, full.object),
                "mot" | "motion" => cfg.motion = full.motion,
                "bound" => cfg.bound = full.bound,
                "obj" | "object" => cfg.object = full.object,
                "phys" => cfg.phys = Self::PHYS_WEIGHT,
                "exact" | "walls" | "soft" => {
                    let m = if term == "soft" { Self::soft() } else { full.clone() };
                    (cfg.bound_margin, cfg.against_wall) = (m.bound_margin, m.against_wall);
                    cfg.contact_margin = m.contact_margin;
                }
                other => {
                    return Err(format!(
                        "unknown guidance term {other:?} (none, all, mot, bound, obj, phys, soft, exact; repair \
                         after sampling is separate: --no-repair, --repair-config)"
                    ));
                }
            }
        }
        Ok(cfg)
    }

    /// Most gradient steps per guided diffusion step a config may ask for (64 is the default; each
    /// costs one evaluation of J per scene).
    pub const MAX_ITERATIONS: usize = 1000;

    /// Why the configuration cannot guide, if it cannot: a weight, γ, `phys`,
    /// `against_wall_reach` or `table_reach` that is negative or not finite, `anchored_mobility` or
    /// `size_mobility` outside 0..1,
    /// `max_step` not a positive distance, `bound_margin`, `contact_margin`, `against_wall_gap`, `object_gap` or
    /// `real_sizes` not a distance ≥ 0,
    /// `every` 0, or `iterations` above [`MAX_ITERATIONS`](Self::MAX_ITERATIONS).
    pub fn problem(&self) -> Option<String> {
        let weights = [
            ("motion", self.motion),
            ("bound", self.bound),
            ("object", self.object),
            ("contact", self.contact),
            ("body", self.body),
            ("support", self.support),
            ("table", self.table),
            ("table_reach", self.table_reach),
            ("square", self.square),
            ("against_wall", self.against_wall),
            ("against_wall_reach", self.against_wall_reach),
            ("scale", self.scale),
            ("phys", self.phys),
            ("object_gap", self.object_gap),
        ];
        if let Some((name, w)) = weights.iter().find(|(_, w)| !(w.is_finite() && *w >= 0.0)) {
            return Some(format!("{name}: must be a non-negative number, not {w}"));
        }
        for (name, share) in [("anchored_mobility", self.anchored_mobility), ("size_mobility", self.size_mobility)] {
            if !(0.0..=1.0).contains(&share) {
                return Some(format!("{name}: must be within 0..1, not {share}"));
            }
        }
        if let Some(step) = self.max_step.filter(|s| !(s.is_finite() && *s > 0.0)) {
            return Some(format!("max_step: must be a positive distance in metres, not {step}"));
        }
        for (name, margin) in [
            ("bound_margin", self.bound_margin),
            ("contact_margin", self.contact_margin),
            ("against_wall_gap", self.against_wall_gap),
        ] {
            if let Some(m) = margin.filter(|m| !(m.is_finite() && *m >= 0.0)) {
                return Some(format!("{name}: must be a distance ≥ 0 in metres, not {m}"));
            }
        }
        if let Some(margin) = self.real_sizes.filter(|m| !(m.is_finite() && *m >= 0.0)) {
            return Some(format!("real_sizes: must be a distance ≥ 0 in metres, not {margin}"));
        }
        if let Some(share) = self.fold_anchored.filter(|f| !(0.0..=1.0).contains(f)) {
            return Some(format!("fold_anchored: must be a share within 0..1, not {share}"));
        }
        if self.every == 0 {
            return Some("every: must be at least 1".into());
        }
        if self.iterations > Self::MAX_ITERATIONS {
            return Some(format!("iterations: at most {}, not {}", Self::MAX_ITERATIONS, self.iterations));
        }
        None
    }

    /// Whether any spatial term (J_m, J_b, J_o) is on.
    pub fn is_active(&self) -> bool {
        self.scale > 0.0 && (self.motion > 0.0 || self.bound > 0.0 || self.object > 0.0)
    }

    /// The guidance of one batch of `scenes`: the spatial terms, then the physics feedback (asking
    /// `physics`); `None` when everything is off.
    pub fn for_batch(
        &self,
        model: &ModelConfig,
        bounds: &Bounds,
        scenes: &[&Scene],
        physics: &Arc<dyn Physics>,
    ) -> Option<Box<dyn Guidance>> {
        let mut chain: Vec<Box<dyn Guidance>> = Vec::new();
        if self.is_active() {
            chain.push(Box::new(SpatialGuidance::new(self.clone(), model, bounds, scenes)));
        }
        if self.phys > 0.0 {
            let phys = super::PhysicsGuidance::new(
                model,
                bounds,
                scenes,
                self.phys,
                self.phys_until,
                self.phys_every,
                physics.clone(),
            );
            chain.push(Box::new(phys));
        }
        match chain.len() {
            0 => None,
            1 => chain.pop(),
            _ => Some(Box::new(super::phys_guidance::Chain(chain))),
        }
    }
}

/// How J_o measures the overlap of two pieces.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Overlap {
    /// SHADE's 3D IoU: intersection over union. A nightstand half inside a double bed scores
    /// about 0.02 (the bed's volume dominates the union), so its gradient barely moves it.
    #[default]
    Iou,
    /// Intersection over the smaller piece's volume: the share of the smaller piece that is
    /// inside the other, whatever the other's size.
    Smaller,
}

impl Overlap {
    /// The overlap of `a` and `b`.
    pub fn of(self, a: &OBox, b: &OBox) -> f64 {
        match self {
            Overlap::Iou => iou_3d(a, b),
            Overlap::Smaller => {
                let v = a.volume().min(b.volume());
                if v > 0.0 { intersection_volume(a, b) / v } else { 0.0 }
            }
        }
    }
}
