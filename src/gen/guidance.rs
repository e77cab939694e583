//! SHADE's spatial collision guidance on the clean estimate x̂0: J_m (footprints on walking
//! humans' free space), J_b (footprints outside the floor plan) and J_o (pairwise 3D IoU), with
//! their gradients with respect to each object's centre, size and yaw, turned into a step on the
//! tokens: x̃0 = x̂0 − γ ∇J.
//!
//! - Footprints are soft: a pixel's occupancy is σ(−sd / τ), sd the signed distance from the pixel
//!   centre to the footprint's edge, τ one pixel. Value and analytic gradient are accumulated over
//!   the pixels of each footprint's own bounding window only (the dense 256² version gives the same
//!   numbers at ~200× the cost).
//! - J_m and J_b are summed as areas (m²) of soft coverage rather than as the fractions the metrics
//!   report: the fraction's denominator (free or outside pixels) differs from scene to scene, and
//!   would make the same overlap push harder in one room than in another. Lamps hang above people
//!   and are left out of J_m (as Col_mot leaves them out).
//! - J_o uses the exact oriented-box IoU; its gradient is a central difference of the exact value,
//!   computed only for pairs whose bounding boxes meet.
//! - J_c (ours, not SHADE's) holds the piece in an anchored slot under its person: by default the
//!   depths of its contact box's corners outside the piece's surface ([`super::boxes_uncovered`]),
//!   or softly, the area (m²) of the box's footprint that the piece's footprint does not cover.
//!   With it the pieces under people move like any other (out of a wall, off a nightstand) as far
//!   as their person still rests on them, instead of being frozen.
//! - By default J_b is measured exactly too ([`super::beyond_walls`]), and J_w draws wall pieces
//!   back to their wall ([`super::against_walls`]); `GuidanceConfig::soft` keeps the soft terms.
//!
//! Empty slots (largest class "empty") are left alone. The physics-feedback term lives elsewhere,
//! the settings in [`super::guidance_config`].

use super::against_walls::gap_to_wall_behind;
use super::at_table::{knees_of, tables_short_of_knees};
use super::beyond_walls::depth_beyond_walls;
use super::bodies::{BodyBalls, SupportNeed, body_penetration, support_shortfall};
use super::boxes_uncovered::box_corners_outside;
pub use super::guidance_config::{GuidanceConfig, Overlap};
use super::tokens::{CLASS_OFFSET, decode_slots};
use super::{Bounds, GenError, Guidance, ModelConfig, Schedule};
use crate::geom::{Mask, OBox, Polygon, RoomWindow};
use crate::human::{Conditions, ContactBox};
use crate::scene::{Action, Category, Object, Scene};
use candle_core::Tensor;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

/// An object as the guidance sees it: world centre, full size, yaw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuidedObject {
    /// Centre (m).
    pub center: DVec3,
    /// Full size (m).
    pub size: DVec3,
    /// Yaw (rad).
    pub yaw: f64,
    /// Hangs from the ceiling (left out of J_m and J_p).
    pub hanging: bool,
    /// Its category (its template's shape, for J_p).
    pub category: Category,
}

#[cfg(test)]
impl GuidedObject {
    /// A piece standing on the floor, `size` its width, depth and height: the terms' tests' pieces.
    pub(crate) fn standing(category: Category, x: f64, y: f64, size: [f64; 3], yaw: f64) -> GuidedObject {
        GuidedObject { center: DVec3::new(x, y, size[2] * 0.5), size: DVec3::from(size), yaw, hanging: false, category }
    }
}

impl GuidedObject {
    /// The guidance's view of a decoded object.
    pub fn of(o: &Object) -> GuidedObject {
        GuidedObject {
            center: DVec3::from(o.center),
            size: DVec3::from(o.size),
            yaw: o.yaw,
            hanging: o.category.is_hanging(),
            category: o.category,
        }
    }

    /// Its box.
    pub fn obox(&self) -> OBox {
        OBox::new(self.center, self.size, self.yaw)
    }

    /// The same piece with attribute `k` of an [`ObjectGradient`] (centre x, y, z; width, depth,
    /// height; yaw) changed by `d`, a size kept at 1 mm at least.
    pub fn nudged(&self, k: usize, d: f64) -> GuidedObject {
        let mut o = *self;
        match k {
            0..=2 => o.center[k] += d,
            3..=5 => o.size[k - 3] = (o.size[k - 3] + d).max(1e-3),
            _ => o.yaw += d,
        }
        o
    }

    /// The central differences (step `h`) of `cost` with respect to the attributes `ks` (the
    /// others 0), for the terms whose exact value has no handier derivative.
    pub fn central_differences(&self, ks: &[usize], h: f64, cost: impl Fn(&GuidedObject) -> f64) -> ObjectGradient {
        let mut g = [0.0; 7];
        for &k in ks {
            g[k] = (cost(&self.nudged(k, h)) - cost(&self.nudged(k, -h))) / (2.0 * h);
        }
        g
    }
}

/// Gradient with respect to (cx, cy, cz, w, d, h, yaw).
pub type ObjectGradient = [f64; 7];

/// The masks one scene is guided by.
#[derive(Debug, Clone)]
pub struct SceneMasks {
    /// The room window.
    pub window: RoomWindow,
    /// Walking and standing humans' foot space.
    pub free: Mask,
    /// Outside the floor plan.
    pub outside: Mask,
    /// The floor plan itself (J_b's pull on pieces wholly outside it).
    pub floor: Polygon,
    /// The direction of the room's longest wall (J_q); `None` for a plan without edges.
    pub wall: Option<f64>,
    /// The footprints of the contact boxes, in the scene's box order (box k anchors slot k).
    pub contacts: Vec<Footprint>,
    /// The people's bones as balls (J_p).
    pub bodies: BodyBalls,
}

/// A contact box's footprint as pixels, with its area (counted once, not at every guided step).
#[derive(Debug, Clone)]
pub struct Footprint {
    /// The pixels under the box.
    pub mask: Mask,
    /// Their area (m²).
    pub area: f64,
    /// What the person needs of the piece's height (J_s): a sitter's or sleeper's support
    /// surface, a toucher's palm (the box's centre), where the piece is under it.
    pub support: Option<SupportNeed>,
    /// The box's centre (x, y).
    pub center: DVec2,
    /// The box's footprint corners.
    pub corners: [DVec2; 4],
    /// A sitter's knees (J_t; [`super::at_table::knees_of`]); `None` for other boxes.
    pub knees: Option<DVec2>,
    /// What the person does there.
    pub action: Action,
}

impl Footprint {
    /// The footprint of contact box `b` in `window`.
    pub fn of(window: &RoomWindow, b: &ContactBox) -> Footprint {
        let mask = Mask::of_footprint(window, &b.obox);
        let area = mask.count() as f64 * window.pixel_area();
        let height = match b.action {
            Action::Touch => b.obox.center.z,
            _ => b.obox.z_range().1,
        };
        let support = Some(SupportNeed { at: b.obox.center.truncate(), height });
        let (center, corners) = (b.obox.center.truncate(), b.obox.footprint());
        Footprint { mask, area, support, center, corners, knees: None, action: b.action }
    }
}

impl SceneMasks {
    /// The masks of `scene`.
    pub fn of(scene: &Scene) -> SceneMasks {
        let c = Conditions::of(scene);
        let contacts = c
            .contact_boxes
            .iter()
            .map(|b| Footprint { knees: knees_of(scene, b), ..Footprint::of(&c.window, b) })
            .collect();
        let bodies = BodyBalls::of(&scene.humans);
        let floor = scene.floor_plan.polygon();
        let wall = floor.longest_edge_direction();
        SceneMasks { window: c.window, free: c.free_space, outside: c.floor.inverted(), floor, wall, contacts, bodies }
    }
}

/// Σ over objects of the soft area (m²) of `mask` pixels under each footprint, with gradients.
/// `skip` leaves objects out.
pub fn soft_coverage(
    objects: &[GuidedObject],
    mask: &Mask,
    window: &RoomWindow,
    skip: impl Fn(&GuidedObject) -> bool,
) -> (f64, Vec<ObjectGradient>) {
    let tau = window.pixel();
    let area = window.pixel_area();
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        if skip(o) {
            continue;
        }
        let (cos, sin) = (o.yaw.cos(), o.yaw.sin());
        let (a, b) = (o.size.x * 0.5, o.size.y * 0.5);
        // The footprint's axis-aligned bounds grown by 4τ: pixels beyond are ignored anyway.
        let reach = DVec2::new((a * cos).abs() + (b * sin).abs(), (a * sin).abs() + (b * cos).abs()) + 4.0 * tau;
        let c = o.center.truncate();
        let (cols, rows) = window.pixel_ranges(c - reach, c + reach);
        for j in rows {
            for i in cols.clone() {
                if !mask.get(i, j) {
                    continue;
                }
                let p = window.pixel_center(i, j) - c;
                let (qx, qy) = (cos * p.x + sin * p.y, -sin * p.x + cos * p.y);
                let (ex, ey) = (qx.abs() - a, qy.abs() - b);
                let (sd, dex, dey) = if ex > 0.0 || ey > 0.0 {
                    let (mx, my) = (ex.max(0.0), ey.max(0.0));
                    let l = mx.hypot(my);
                    (l, mx / l, my / l)
                } else if ex >= ey {
                    (ex, 1.0, 0.0)
                } else {
                    (ey, 0.0, 1.0)
                };
                if sd > 4.0 * tau {
                    continue;
                }
                let occ = 1.0 / (1.0 + (sd / tau).exp());
                total += occ * area;
                // d(area·occ)/d sd, then the chain through ex, ey to the parameters.
                let ds = -occ * (1.0 - occ) / tau * area;
                let (gx, gy) = (ds * dex * qx.signum(), ds * dey * qy.signum());
                g[0] += gx * -cos + gy * sin;
                g[1] += gx * -sin + gy * -cos;
                g[3] += ds * dex * -0.5;
                g[4] += ds * dey * -0.5;
                g[6] += gx * qy + gy * -qx;
            }
        }
    }
    (total, grads)
}

/// Σ_{i<j} overlap(o_i, o_j) (each unordered pair once; the paper's Σ_{i≠j} of IoU is twice this),
/// with central-difference gradients of the exact value.
///
/// `gap` (m) grows each footprint by half of it on every side first, so that pieces closer than
/// `gap` count as overlapping.
pub fn pairwise_overlap(objects: &[GuidedObject], overlap: Overlap, gap: f64) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let grown: Vec<GuidedObject> =
        objects.iter().map(|o| GuidedObject { size: o.size + DVec3::new(gap, gap, 0.0), ..*o }).collect();
    let objects = &grown[..];
    let mut grads = vec![[0.0; 7]; objects.len()];
    let boxes: Vec<OBox> = objects.iter().map(GuidedObject::obox).collect();
    let reach: Vec<f64> = objects.iter().map(|o| o.size.x.hypot(o.size.y) * 0.5).collect();
    for i in 0..objects.len() {
        for j in i + 1..objects.len() {
            let (a, b) = (&objects[i], &objects[j]);
            let apart = a.center.truncate().distance(b.center.truncate()) > reach[i] + reach[j]
                || (a.center.z - b.center.z).abs() > (a.size.z + b.size.z) * 0.5;
            if apart {
                continue;
            }
            let value = overlap.of(&boxes[i], &boxes[j]);
            if value <= 0.0 {
                continue;
            }
            total += value;
            for (me, other) in [(i, j), (j, i)] {
                let d = objects[me]
                    .central_differences(&[0, 1, 2, 3, 4, 5, 6], 1e-3, |o| overlap.of(&o.obox(), &boxes[other]));
                for (g, d) in grads[me].iter_mut().zip(d) {
                    *g += d;
                }
            }
        }
    }
    (total, grads)
}

/// J_b's second half: Σ over pieces whose centre lies outside the floor plan of that centre's
/// distance to it (m), with gradients. A piece wholly outside covers as much of the outside mask
/// wherever it moves, so the soft coverage has no gradient to bring it back (a console table or a
/// pendant lamp sampled in the missing corner of an L-shaped room stayed there); this pulls its
/// centre in, and the coverage does the rest.
pub fn centres_outside(objects: &[GuidedObject], floor: &Polygon) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        let c = o.center.truncate();
        if floor.contains(c) {
            continue;
        }
        let away = c - floor.nearest_boundary_point(c);
        let d = away.length();
        if d > 0.0 {
            total += d;
            g[0] = away.x / d;
            g[1] = away.y / d;
        }
    }
    (total, grads)
}

/// J_q (ours): Σ over pieces of (1 − cos 4Δ) / 4, Δ the piece's yaw less `wall`'s direction, with
/// gradients: 0 for a piece square to the walls, at its worst half-way between quarter turns. Every
/// piece of the training data stands square to the walls, and repair turns the model's pieces so
/// (`repair::settle`); turned there during sampling, the other terms see the piece as it will stand.
pub fn squareness(objects: &[GuidedObject], wall: f64) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        let delta = 4.0 * (o.yaw - wall);
        total += (1.0 - delta.cos()) * 0.25;
        g[6] = delta.sin();
    }
    (total, grads)
}

/// J_c: Σ over anchored objects of the soft area (m²) of their contact boxes' footprints that
/// their own footprint leaves uncovered, plus the distance (m) from each box's centre to the
/// footprint when the centre is outside it, with gradients. `boxes[i]` are the footprints of the
/// boxes object i serves (several for a sofa in several sitters' slots; none for a free piece).
/// The soft area has a gradient only within a few pixels of the piece's edge; the distance pulls
/// a piece towards a box it misses by more (a sofa centred on one of three sitters).
pub fn contact_shortfall(
    objects: &[GuidedObject],
    boxes: &[Vec<&Footprint>],
    window: &RoomWindow,
) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for ((o, footprints), g) in objects.iter().zip(boxes).zip(&mut grads) {
        for footprint in footprints {
            let (covered, cg) = soft_coverage(std::slice::from_ref(o), &footprint.mask, window, |_| false);
            total += footprint.area - covered;
            for k in 0..7 {
                g[k] -= cg[0][k];
            }
            let (d, toward) = distance_outside(o, footprint.center);
            total += d;
            g[0] -= toward.x;
            g[1] -= toward.y;
        }
    }
    (total, grads)
}

/// The distance (m) from `p` to the footprint of `o` (0 inside) and its unit direction from the
/// footprint towards `p` (zero inside): moving the piece's centre that way shortens the distance
/// at rate 1.
pub(super) fn distance_outside(o: &GuidedObject, p: DVec2) -> (f64, DVec2) {
    let excess = excess_outside(o, p);
    let d = excess.length();
    if d <= 0.0 {
        return (0.0, DVec2::ZERO);
    }
    let (ax, ay) = o.obox().axes();
    (d, ax * (excess.x / d) + ay * (excess.y / d))
}

/// How far `p` lies beyond the footprint of `o` along the piece's own width and depth axes (signed
/// as `p` lies from the centre; 0 on an axis whose extent takes it in).
pub(super) fn excess_outside(o: &GuidedObject, p: DVec2) -> DVec2 {
    let b = o.obox();
    let local = b.to_local(p.extend(b.center.z));
    DVec2::new(
        (local.x.abs() - o.size.x * 0.5).max(0.0) * local.x.signum(),
        (local.y.abs() - o.size.y * 0.5).max(0.0) * local.y.signum(),
    )
}

/// The weighted J of one scene's objects and its gradient; `anchors[i]` are the contact boxes
/// object i is anchored to (the anchored slots that hold it).
pub fn guidance_cost(
    objects: &[GuidedObject],
    anchors: &[Vec<usize>],
    masks: &SceneMasks,
    cfg: &GuidanceConfig,
) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    let mut add = |w: f64, (v, g): (f64, Vec<ObjectGradient>)| {
        if w > 0.0 {
            total += w * v;
            for (acc, gi) in grads.iter_mut().zip(g) {
                for k in 0..7 {
                    acc[k] += w * gi[k];
                }
            }
        }
    };
    if cfg.motion > 0.0 {
        add(cfg.motion, soft_coverage(objects, &masks.free, &masks.window, |o| o.hanging));
    }
    if cfg.bound > 0.0 {
        match cfg.bound_margin {
            Some(margin) => add(cfg.bound, depth_beyond_walls(objects, &masks.floor, margin)),
            None => {
                add(cfg.bound, soft_coverage(objects, &masks.outside, &masks.window, |_| false));
                add(cfg.bound, centres_outside(objects, &masks.floor));
            }
        }
    }
    if cfg.object > 0.0 {
        add(cfg.object, pairwise_overlap(objects, cfg.overlap, cfg.object_gap));
    }
    if cfg.contact > 0.0 {
        let boxes: Vec<Vec<&Footprint>> =
            anchors.iter().map(|a| a.iter().filter_map(|&k| masks.contacts.get(k)).collect()).collect();
        match cfg.contact_margin {
            Some(margin) => {
                let corners: Vec<Vec<[DVec2; 4]>> =
                    boxes.iter().map(|b| b.iter().map(|f| f.corners).collect()).collect();
                add(cfg.contact, box_corners_outside(objects, &corners, margin));
            }
            None => add(cfg.contact, contact_shortfall(objects, &boxes, &masks.window)),
        }
    }
    if cfg.body > 0.0 {
        add(cfg.body, body_penetration(objects, &masks.bodies));
    }
    if cfg.table > 0.0 {
        let knees: Vec<Vec<DVec2>> =
            anchors.iter().map(|a| a.iter().filter_map(|&k| masks.contacts.get(k)?.knees).collect()).collect();
        add(cfg.table, tables_short_of_knees(objects, &knees, cfg.table_reach));
    }
    if cfg.against_wall > 0.0 {
        let wall_gap = cfg.against_wall_gap.unwrap_or(crate::data::layout::WALL_GAP);
        add(cfg.against_wall, gap_to_wall_behind(objects, &masks.floor, wall_gap, cfg.against_wall_reach));
    }
    if let Some(wall) = masks.wall.filter(|_| cfg.square > 0.0) {
        add(cfg.square, squareness(objects, wall));
    }
    if cfg.support > 0.0 {
        let needs: Vec<Vec<SupportNeed>> = anchors
            .iter()
            .map(|a| a.iter().filter_map(|&k| masks.contacts.get(k).and_then(|f| f.support)).collect())
            .collect();
        add(cfg.support, support_shortfall(objects, &needs));
    }
    (total, grads)
}

/// The guidance of one batch: each item's masks, the decoding bounds and the weights.
#[derive(Debug, Clone)]
pub struct SpatialGuidance {
    cfg: GuidanceConfig,
    model: ModelConfig,
    bounds: Bounds,
    masks: Vec<SceneMasks>,
    ceilings: Vec<f64>,
    /// Per item: what the person of each of its first slots, those anchored to contact boxes, does.
    anchored: Vec<Vec<Action>>,
    /// Guide at the model's steps t < this: `cfg.until_step` as a noise level.
    until: usize,
    /// Weighted J summed over the batch at each guided step (for inspection and tests).
    pub history: Vec<(usize, f64)>,
}

impl SpatialGuidance {
    /// Guidance for a batch of `scenes` (in batch order).
    pub fn new(cfg: GuidanceConfig, model: &ModelConfig, bounds: &Bounds, scenes: &[&Scene]) -> SpatialGuidance {
        let masks: Vec<SceneMasks> = scenes.iter().map(|s| SceneMasks::of(s)).collect();
        let until = Schedule::of(model).at_linear_noise(cfg.until_step);
        SpatialGuidance {
            cfg,
            model: model.clone(),
            bounds: bounds.clone(),
            anchored: masks
                .iter()
                .map(|m| m.contacts.iter().take(model.anchored_slots(m.contacts.len())).map(|f| f.action).collect())
                .collect(),
            until,
            masks,
            ceilings: scenes.iter().map(|s| s.floor_plan.height).collect(),
            history: Vec::new(),
        }
    }
}

impl Guidance for SpatialGuidance {
    fn guide(&mut self, x0: &Tensor, t: usize) -> Result<Tensor, GenError> {
        if t >= self.until || t % self.cfg.every != 0 || !self.cfg.is_active() {
            return Ok(x0.clone());
        }
        let dims = x0.dims().to_vec();
        let mut v = x0.flatten_all()?.to_vec1::<f32>()?;
        let dim = self.model.token_dim();
        let per_item = self.model.slots() * dim;
        let (model, bounds, cfg) = (&self.model, &self.bounds, &self.cfg);
        let total: f64 = v
            .par_chunks_exact_mut(per_item)
            .zip(self.masks.par_iter().zip(&self.ceilings).zip(&self.anchored))
            .map(|(tokens, ((masks, &ceiling), anchored))| {
                let mut first = None;
                for _ in 0..cfg.iterations.max(1) {
                    let j = guide_item(tokens, masks, ceiling, anchored, model, bounds, cfg);
                    first.get_or_insert(j);
                    if j <= 0.0 {
                        break;
                    }
                }
                first.unwrap_or(0.0)
            })
            .sum();
        tracing::debug!(step = t, j = total, "guidance");
        self.history.push((t, total));
        Ok(Tensor::from_vec(v, dims, x0.device())?)
    }
}

/// One gradient step on one item's tokens (world form), `anchored` what the person of each of its
/// anchored slots does; returns J before the step.
fn guide_item(
    tokens: &mut [f32],
    masks: &SceneMasks,
    ceiling: f64,
    anchored: &[Action],
    model: &ModelConfig,
    bounds: &Bounds,
    cfg: &GuidanceConfig,
) -> f64 {
    let dim = model.token_dim();
    let mut decoded = decode_slots(tokens, masks.window.center, ceiling, bounds, model);
    if let Some(share) = cfg.fold_anchored {
        fold_anchored(&mut decoded, tokens, anchored, share, dim);
    }
    let anchored = anchored.len();
    let objects: Vec<GuidedObject> = decoded.iter().map(|(_, o)| GuidedObject::of(o)).collect();
    let anchors: Vec<Vec<usize>> =
        decoded.iter().map(|(slots, _)| slots.iter().copied().filter(|&s| s < anchored).collect()).collect();
    let (j, grads) = guidance_cost(&objects, &anchors, masks, cfg);
    for ((held_in, piece), g) in decoded.iter().zip(&grads) {
        let slot = held_in[0];
        let t = &mut tokens[slot * dim..(slot + 1) * dim];
        let mut step = token_gradient(t, g, bounds);
        // The token's sizes are its attributes 3..6 (width, depth, height).
        step[3..6].iter_mut().for_each(|s| *s *= cfg.size_mobility);
        let mut scale = if slot < anchored { cfg.scale * cfg.anchored_mobility } else { cfg.scale };
        if let Some(cap) = cfg.max_step {
            scale *= capped(&step, scale, cap, bounds);
        }
        for (x, s) in t.iter_mut().zip(step) {
            *x = (*x - (scale * s) as f32).clamp(-1.0, 1.0);
        }
        if let Some(margin) = cfg.real_sizes {
            keep_real_size(t, piece.category, margin, bounds);
        }
        // The slots holding copies of the piece (a sofa in each of its sitters' slots) take its new
        // place and size: one piece, guided once, as the training data has it in every slot.
        let guided: [f32; CLASS_OFFSET] = t[..CLASS_OFFSET].try_into().expect("a token has a centre, size and yaw");
        for &copy in &held_in[1..] {
            tokens[copy * dim..copy * dim + CLASS_OFFSET].copy_from_slice(&guided);
        }
    }
    j
}

/// Folds pieces in anchored slots (`slot < actions.len()`, `actions[s]` what slot s's person does)
/// that overlap by more than `share` of the smaller one's volume into one: the one with the larger
/// footprint (the earlier on a tie) keeps its place, and its whole token (classes too) is written
/// into the other's slots, which join its list of copies. A pair folds only where the kept piece
/// affords what the other's people do: two sitters' sofa and armchair fold into the sofa, a
/// diner's chair never into the table a hand rests on.
fn fold_anchored(
    decoded: &mut Vec<(Vec<usize>, Object)>,
    tokens: &mut [f32],
    actions: &[Action],
    share: f64,
    dim: usize,
) {
    let anchored = actions.len();
    let is_anchored = |slots: &[usize]| slots.iter().any(|&s| s < anchored);
    let footprint = |o: &Object| o.size[0] * o.size[1];
    let kept_and_dropped = |decoded: &[(Vec<usize>, Object)], i: usize, j: usize| {
        if footprint(&decoded[j].1) > footprint(&decoded[i].1) { (j, i) } else { (i, j) }
    };
    let serves = |decoded: &[(Vec<usize>, Object)], keep: usize, drop: usize| {
        decoded[drop].0.iter().filter(|&&s| s < anchored).all(|&s| decoded[keep].1.category.affords(actions[s]))
    };
    let mut i = 0;
    while i < decoded.len() {
        let partner = is_anchored(&decoded[i].0)
            .then(|| {
                let first = decoded[i].1.obox();
                (i + 1..decoded.len()).find(|&j| {
                    is_anchored(&decoded[j].0) && Overlap::Smaller.of(&first, &decoded[j].1.obox()) > share && {
                        let (keep, drop) = kept_and_dropped(decoded, i, j);
                        serves(decoded, keep, drop)
                    }
                })
            })
            .flatten();
        let Some(j) = partner else {
            i += 1;
            continue;
        };
        let (keep, drop) = kept_and_dropped(decoded, i, j);
        let source = decoded[keep].0[0];
        let token: Vec<f32> = tokens[source * dim..(source + 1) * dim].to_vec();
        let (slots, _) = decoded.remove(drop);
        for &s in &slots {
            tokens[s * dim..(s + 1) * dim].copy_from_slice(&token);
        }
        let keep = if drop < keep { keep - 1 } else { keep };
        decoded[keep].0.extend(slots);
        // The kept piece may now overlap another: look at the pair from the start again.
        i = 0;
    }
}

/// Keeps a token's size (entries 3..6) within `margin` (m) of its category's real pieces' range on
/// each axis, as far as the decoding bounds allow.
fn keep_real_size(t: &mut [f32], category: Category, margin: f64, bounds: &Bounds) {
    let size = bounds.unscale_size(std::array::from_fn(|k| f64::from(t[3 + k])));
    let kept: [f64; 3] = std::array::from_fn(|k| {
        let (lo, hi) = crate::furniture::size_range(category, k);
        size[k].clamp((lo - margin).max(0.0), hi + margin)
    });
    let scaled = bounds.scale_size(kept);
    for k in (0..3).filter(|&k| kept[k] != size[k]) {
        t[3 + k] = (scaled[k] as f32).clamp(-1.0, 1.0);
    }
}

/// The factor (≤ 1) that keeps a token step of `scale · step` within `cap` metres: the piece's
/// centre moving at most `cap` on the floor and none of its sizes changing by more. Uncapped, a
/// bed's height changed by 14.5 cm in one gradient step and crossed the 0.7 m at which its
/// template moves the mattress from half its height to its top, and the sleeper sank into it
/// (val bedrooms: 83 against 92 rooms failing without repair).
fn capped(step: &[f64; 8], scale: f64, cap: f64, bounds: &Bounds) -> f64 {
    // A token unit is half the decoding range.
    let centre = (0..2)
        .map(|k| scale * step[k] * (bounds.center_max[k] - bounds.center_min[k]) * 0.5)
        .fold(0.0, |acc: f64, d| acc.hypot(d));
    let resized = (0..3)
        .map(|k| (scale * step[3 + k] * (bounds.size_max[k] - bounds.size_min[k]) * 0.5).abs())
        .fold(0.0, f64::max);
    let moved = centre.max(resized);
    if moved > cap { cap / moved } else { 1.0 }
}

/// A guidance step moves a piece's centre γ · ℓ² metres per unit of weighted gradient, ℓ this
/// length (m), in every model. ℓ is the bedroom model's decoding half-range, with which γ and the
/// terms' weights were tuned. It used to be each model's own half-range, so the same γ moved a
/// living room's pieces (5.2 m) 3.6 times as far: J_w then overshot the wall and J_b pushed the
/// piece back 3 cm, turn about, and two in five wall pieces ended 8 cm from their wall, not 5
/// (docs/RESULTS.md, "One step length for every model").
pub const CENTRE_STEP_LENGTH: f64 = 2.77;

/// The token step per unit of γ (first 8 entries: centre, size, cos, sin) from ∂J/∂(world
/// parameters): ∂J/∂token for the sizes and the yaw; for the centre, the move of γ · ℓ² metres per
/// unit of gradient ([`CENTRE_STEP_LENGTH`]) in token units, whatever the model's decoding range.
/// Heights are decoded from the size (floor or ceiling), so ∂J/∂cz is not passed on.
fn token_gradient(t: &[f32], g: &ObjectGradient, bounds: &Bounds) -> [f64; 8] {
    let half = |lo: f64, hi: f64| (hi - lo) * 0.5;
    let mut out = [0.0; 8];
    for k in 0..2 {
        out[k] = g[k] * CENTRE_STEP_LENGTH.powi(2) / half(bounds.center_min[k], bounds.center_max[k]);
    }
    for k in 0..3 {
        out[3 + k] = g[3 + k] * half(bounds.size_min[k], bounds.size_max[k]);
    }
    let (c, s) = (t[6] as f64, t[7] as f64);
    let r2 = c * c + s * s;
    if r2 > 1e-6 {
        out[6] = g[6] * -s / r2;
        out[7] = g[6] * c / r2;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Polygon, iou_3d};
    use crate::scene::RoomType;

    #[test]
    fn a_gradient_step_moves_a_piece_and_changes_each_size_by_at_most_the_cap() {
        // Decoding ranges 6 m for the centre and 2.95 m for sizes: a token unit is 3 m and 1.475 m.
        let bounds = Bounds { center_min: [-3.0; 3], center_max: [3.0; 3], size_min: [0.05; 3], size_max: [3.0; 3] };
        // A step that only lowers the piece, by 0.1 × 1 token unit = 14.75 cm: cut to 3 cm.
        let tall = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
        assert!((capped(&tall, 0.1, 0.03, &bounds) * 0.1 * 1.475 - 0.03).abs() < 1e-12);
        // A move of 0.01 × 3 m = 3 cm in x and 4 cm in y (5 cm): cut to 3 cm.
        let moved = [0.01, 0.04 / 3.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        assert!((capped(&moved, 1.0, 0.03, &bounds) - 0.6).abs() < 1e-12, "{}", capped(&moved, 1.0, 0.03, &bounds));
        // Within the cap (turns are not capped): left as it is.
        let small = [0.001, 0.0, 0.0, 0.005, 0.0, 0.0, 0.3, 0.0];
        assert_eq!(capped(&small, 1.0, 0.03, &bounds), 1.0);
    }

    #[test]
    fn guided_sizes_stay_within_their_category_s_real_pieces() {
        // Decoding bounds from 5 cm to 3 m on every axis; real dining tables are 0.7–0.8 m tall.
        let bounds = Bounds { center_min: [-3.0; 3], center_max: [3.0; 3], size_min: [0.05; 3], size_max: [3.0; 3] };
        let (lo, hi) = crate::furniture::size_range(Category::DiningTable, 2);
        let mut t = vec![0.0f32; 8];
        let flat = bounds.scale_size([1.6, 0.9, 0.05]);
        for k in 0..3 {
            t[3 + k] = flat[k] as f32;
        }
        keep_real_size(&mut t, Category::DiningTable, 0.15, &bounds);
        let size = bounds.unscale_size(std::array::from_fn(|k| f64::from(t[3 + k])));
        assert!((size[2] - (lo - 0.15)).abs() < 1e-5 && lo > 0.5, "a 5 cm table comes up to {} ({lo}–{hi})", size[2]);
        // A real one is left exactly as it was.
        let real = bounds.scale_size([1.6, 0.9, (lo + hi) * 0.5]);
        let mut t: Vec<f32> = (0..8).map(|k| if (3..6).contains(&k) { real[k - 3] as f32 } else { 0.0 }).collect();
        let before = t.clone();
        keep_real_size(&mut t, Category::DiningTable, 0.15, &bounds);
        assert_eq!(t, before);
    }

    fn window() -> RoomWindow {
        RoomWindow { center: DVec2::new(2.0, 2.0), side: RoomType::Bedroom.window_side() }
    }

    fn objects() -> Vec<GuidedObject> {
        let o = |x: f64, y: f64, w: f64, d: f64, yaw: f64| GuidedObject {
            center: DVec3::new(x, y, 0.4),
            size: DVec3::new(w, d, 0.8),
            yaw,
            hanging: false,
            category: Category::Stool,
        };
        vec![o(0.3, 2.0, 1.0, 0.6, 0.4), o(2.0, 2.1, 1.6, 2.0, -0.3), o(2.9, 2.6, 0.5, 0.5, 1.1)]
    }

    /// A floor plan 0..4 × 0..4 m: the outside mask, which the first object pokes into.
    fn outside() -> Mask {
        let square =
            Polygon::new(vec![DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0), DVec2::new(4.0, 4.0), DVec2::new(0.0, 4.0)]);
        Mask::of_polygon(&window(), &square).inverted()
    }

    fn perturbed(objects: &[GuidedObject], i: usize, k: usize, h: f64) -> Vec<GuidedObject> {
        let mut o = objects.to_vec();
        match k {
            0..=2 => o[i].center[k] += h,
            3..=5 => o[i].size[k - 3] += h,
            _ => o[i].yaw += h,
        }
        o
    }

    #[test]
    fn soft_coverage_gradient_matches_finite_differences() {
        let (w, mask) = (window(), outside());
        let objs = objects();
        let (value, grads) = soft_coverage(&objs, &mask, &w, |_| false);
        // The first object reaches 0.2 m past x = 0 over about 0.9 m of depth (rotated 0.4 rad).
        assert!(value > 0.05 && value < 0.4, "{value}");
        for k in [0, 1, 3, 4, 6] {
            let h = 1e-4;
            let plus = soft_coverage(&perturbed(&objs, 0, k, h), &mask, &w, |_| false).0;
            let minus = soft_coverage(&perturbed(&objs, 0, k, -h), &mask, &w, |_| false).0;
            let fd = (plus - minus) / (2.0 * h);
            assert!((fd - grads[0][k]).abs() < 1e-3 * (1.0 + fd.abs()), "k {k}: fd {fd} analytic {}", grads[0][k]);
        }
        // Moving the first object into the room (+x) lowers J_b.
        assert!(grads[0][0] < 0.0);
    }

    #[test]
    fn culled_coverage_equals_the_dense_sum() {
        let (w, mask) = (window(), outside());
        let objs = objects();
        let culled = soft_coverage(&objs, &mask, &w, |_| false).0;
        let tau = w.pixel();
        let mut dense = 0.0;
        for o in &objs {
            for j in 0..crate::geom::RES {
                for i in 0..crate::geom::RES {
                    if mask.get(i, j) {
                        let p = w.pixel_center(i, j) - o.center.truncate();
                        let (c, s) = (o.yaw.cos(), o.yaw.sin());
                        let q = DVec2::new(c * p.x + s * p.y, -s * p.x + c * p.y);
                        let e = q.abs() - DVec2::new(o.size.x, o.size.y) * 0.5;
                        let sd = e.max(DVec2::ZERO).length() + e.x.max(e.y).min(0.0);
                        dense += w.pixel_area() / (1.0 + (sd / tau).exp());
                    }
                }
            }
        }
        // The window stops at 4 τ, where the sigmoid is below 2 %; a few boundary pixels differ.
        assert!((culled - dense).abs() < 0.02 * dense, "culled {culled} dense {dense}");
    }

    #[test]
    fn pairwise_iou_gradient_points_apart() {
        let objs = objects();
        let (value, grads) = pairwise_overlap(&objs, Overlap::Iou, 0.0);
        let exact = iou_3d(&objs[1].obox(), &objs[2].obox()) + iou_3d(&objs[0].obox(), &objs[1].obox());
        assert!((value - exact).abs() < 1e-12 && value > 0.0);
        // A small step against the gradient lowers the total IoU.
        let mut moved = objs.clone();
        for (o, g) in moved.iter_mut().zip(&grads) {
            o.center.x -= 0.01 * g[0];
            o.center.y -= 0.01 * g[1];
            o.yaw -= 0.01 * g[6];
        }
        assert!(pairwise_overlap(&moved, Overlap::Iou, 0.0).0 < value);
    }

    #[test]
    fn a_gap_makes_pieces_closer_than_it_overlap_and_pushes_them_apart() {
        let piece = |x: f64| GuidedObject {
            center: DVec3::new(x, 0.0, 0.4),
            size: DVec3::new(0.5, 0.5, 0.8),
            yaw: 0.0,
            hanging: false,
            category: Category::DiningChair,
        };
        // 2 cm apart: nothing without a gap.
        let pair = [piece(0.0), piece(0.52)];
        assert_eq!(pairwise_overlap(&pair, Overlap::Smaller, 0.0).0, 0.0);
        // With a 3 cm gap each footprint grows by 1.5 cm a side: 1 cm of the 0.53 m grown width
        // is shared.
        let (value, grads) = pairwise_overlap(&pair, Overlap::Smaller, 0.03);
        assert!((value - 0.01 / 0.53).abs() < 1e-9, "{value}");
        assert!(grads[0][0] > 0.0 && grads[1][0] < 0.0, "{grads:?}");
        // 3 cm apart or more: nothing again.
        assert_eq!(pairwise_overlap(&[piece(0.0), piece(0.531)], Overlap::Smaller, 0.03).0, 0.0);
    }

    #[test]
    fn overlap_of_a_small_piece_inside_a_large_one() {
        // A 0.4 m cube half inside a 2 × 2 × 0.4 m slab: half the cube is inside the slab.
        let big = OBox::new(DVec3::new(0.0, 0.0, 0.2), DVec3::new(2.0, 2.0, 0.4), 0.0);
        let small = OBox::new(DVec3::new(1.0, 0.0, 0.2), DVec3::new(0.4, 0.4, 0.4), 0.0);
        assert!((Overlap::Smaller.of(&big, &small) - 0.5).abs() < 1e-9);
        // IoU: 0.032 m³ over 1.6 + 0.064 − 0.032 m³.
        assert!((Overlap::Iou.of(&big, &small) - 0.032 / 1.632).abs() < 1e-9);
        let apart = OBox::new(DVec3::new(1.5, 0.0, 0.2), DVec3::new(0.4, 0.4, 0.4), 0.0);
        assert_eq!(Overlap::Smaller.of(&big, &apart), 0.0);
    }

    #[test]
    fn squareness_is_zero_at_quarter_turns_and_its_gradient_matches_finite_differences() {
        let piece = |yaw: f64| GuidedObject {
            center: DVec3::new(1.0, 1.0, 0.4),
            size: DVec3::new(0.5, 0.5, 0.8),
            yaw,
            hanging: false,
            category: Category::Cabinet,
        };
        let wall = 0.3;
        for k in -2..=2 {
            let (j, g) = squareness(&[piece(wall + k as f64 * std::f64::consts::FRAC_PI_2)], wall);
            assert!(j < 1e-12 && g[0][6].abs() < 1e-9, "quarter turn {k}: {j}");
        }
        // Half-way between quarter turns it is at its worst, ½.
        assert!((squareness(&[piece(wall + std::f64::consts::FRAC_PI_4)], wall).0 - 0.5).abs() < 1e-12);
        for yaw in [0.1, 0.5, 1.0, 2.0, -2.5] {
            let (_, g) = squareness(&[piece(yaw)], wall);
            let h = 1e-6;
            let fd = (squareness(&[piece(yaw + h)], wall).0 - squareness(&[piece(yaw - h)], wall).0) / (2.0 * h);
            assert!((g[0][6] - fd).abs() < 1e-6, "{yaw}: {} vs {fd}", g[0][6]);
            // Descending turns it towards the nearest quarter turn.
            let next = yaw - 0.01 * g[0][6];
            assert!(squareness(&[piece(next)], wall).0 < squareness(&[piece(yaw)], wall).0);
        }
    }

    #[test]
    fn a_piece_wholly_outside_is_pulled_back_by_its_centre() {
        let floor = Polygon::rectangle(DVec2::ZERO, DVec2::new(4.0, 3.0));
        let piece = |x: f64, y: f64| GuidedObject {
            center: DVec3::new(x, y, 0.4),
            size: DVec3::new(0.5, 0.5, 0.8),
            yaw: 0.0,
            hanging: false,
            category: Category::Cabinet,
        };
        // 0.6 m beyond the wall at x = 4 and 0.5 m below y = 0: the distances, pointing away.
        let (j, g) = centres_outside(&[piece(4.6, 1.5), piece(2.0, -0.5), piece(2.0, 1.5)], &floor);
        assert!((j - 1.1).abs() < 1e-12, "{j}");
        assert_eq!((g[0][0], g[0][1]), (1.0, 0.0));
        assert_eq!((g[1][0], g[1][1]), (0.0, -1.0));
        assert_eq!(g[2], [0.0; 7], "a piece whose centre is inside is the coverage's business");
        // The soft coverage of the outside alone has next to no pull on the wholly outside piece.
        let window = RoomWindow::around(6.0, &floor);
        let outside = Mask::of_polygon(&window, &floor).inverted();
        let (_, cg) = soft_coverage(&[piece(4.6, 1.5)], &outside, &window, |_| false);
        assert!(cg[0][0].abs() < 0.05 && cg[0][1].abs() < 1e-9, "{:?}", cg[0]);
    }

    #[test]
    fn contact_shortfall_is_the_uncovered_area_with_its_gradient() {
        let w = window();
        // A 0.6 × 0.4 m contact box at (2, 2) and a 1 × 1 m piece covering it, then shifted so that
        // its edge cuts the box.
        let b = ContactBox {
            human: "h".into(),
            action: Action::Sit,
            frames: [0, 1],
            obox: OBox::new(DVec3::new(2.0, 2.0, 0.5), DVec3::new(0.6, 0.4, 0.3), 0.0),
        };
        let mask = Footprint::of(&w, &b);
        let piece = |x: f64| GuidedObject {
            center: DVec3::new(x, 2.0, 0.4),
            size: DVec3::new(1.0, 1.0, 0.8),
            yaw: 0.0,
            hanging: false,
            category: Category::Stool,
        };
        let (covered, _) = contact_shortfall(&[piece(2.0)], &[vec![&mask]], &w);
        assert!(covered.abs() < 0.01 * 0.24, "covered box leaves {covered} m²");
        // Centred at x = 1.5 the piece ends at x = 2.0: the box's half beyond (0.3 × 0.4 m) is
        // uncovered, and each metre the piece moves towards it uncovers 0.4 m² less.
        let objs = [piece(1.5)];
        let (half, grads) = contact_shortfall(&objs, &[vec![&mask]], &w);
        assert!((half - 0.12).abs() < 0.01, "{half}");
        // The gradient against a central difference, 5 cm further off (where the box's centre is
        // outside the piece and both parts of J_c count).
        let h = 1e-4;
        let shifted = |d: f64| contact_shortfall(&[piece(1.45 + d)], &[vec![&mask]], &w).0;
        let fd = (shifted(h) - shifted(-h)) / (2.0 * h);
        let analytic = contact_shortfall(&[piece(1.45)], &[vec![&mask]], &w).1[0][0];
        assert!((fd - analytic).abs() < 1e-3 * (1.0 + fd.abs()), "fd {fd} analytic {analytic}");
        // Moving the piece towards the box (+x) uncovers less; a free piece costs nothing.
        assert!(grads[0][0] < -0.3);
        assert_eq!(contact_shortfall(&objs, &[vec![]], &w).0, 0.0);
        // A metre away (the piece ends at x = 1.0, the box spans 1.7..2.3), the whole box is
        // uncovered (its 0.24 m² as pixels) and the box's centre is 1 m off: J = area + 1, and the
        // distance pulls the piece on at rate 1 where the soft area no longer does.
        let far = [piece(0.5)];
        let (j, grads) = contact_shortfall(&far, &[vec![&mask]], &w);
        assert!((j - (mask.area + 1.0)).abs() < 1e-3 && (mask.area - 0.24).abs() < 0.02, "{j}");
        assert!((grads[0][0] + 1.0).abs() < 1e-3 && grads[0][1].abs() < 1e-9, "{:?}", grads[0]);
        // Turned a quarter, the piece's footprint is the same square: the same distance.
        let turned = GuidedObject { yaw: std::f64::consts::FRAC_PI_2, ..far[0] };
        assert!((contact_shortfall(&[turned], &[vec![&mask]], &w).0 - j).abs() < 1e-3);
    }

    #[test]
    fn a_touched_piece_must_reach_up_to_the_palm() {
        // A palm (its 12 cm box centred at 0.85 m) over a table 0.65 m tall: J_s is the 20 cm the
        // top stays below the palm, less the 2 cm tolerated, and growing the table lowers it.
        let b = ContactBox {
            human: "h".into(),
            action: Action::Touch,
            frames: [0, 1],
            obox: OBox::new(DVec3::new(2.0, 2.0, 0.85), DVec3::splat(0.12), 0.0),
        };
        let need = Footprint::of(&window(), &b).support.expect("a touch needs its piece up to the palm");
        assert!((need.height - 0.85).abs() < 1e-12);
        let table = |h: f64| GuidedObject::standing(Category::Table, 2.0, 2.1, [1.2, 0.8, h], 0.0);
        let (j, g) = support_shortfall(&[table(0.65)], &[vec![need]]);
        assert!((j - 0.18).abs() < 1e-9, "{j}");
        assert!(g[0][5] < 0.0, "{:?}", g[0]);
        assert_eq!(support_shortfall(&[table(0.84)], &[vec![need]]).0, 0.0);
    }

    #[test]
    fn parse_terms() {
        let c = GuidanceConfig::parse("mot,obj").unwrap();
        assert!(c.motion > 0.0 && c.bound == 0.0 && c.object > 0.0);
        assert!(!GuidanceConfig::parse("none").unwrap().is_active());
        assert!(GuidanceConfig::parse("all").unwrap().is_active());
        assert!(GuidanceConfig::parse("floor").unwrap_err().contains("floor"));
        assert_eq!(GuidanceConfig::parse("all,exact").unwrap(), GuidanceConfig::all());
        assert_eq!(GuidanceConfig::parse("all,walls").unwrap(), GuidanceConfig::all());
        assert_eq!(GuidanceConfig::parse("all,soft").unwrap(), GuidanceConfig::soft());
        assert_eq!(GuidanceConfig::parse("all").unwrap(), GuidanceConfig::all());
        let p = GuidanceConfig::parse("all,phys").unwrap();
        assert!(p.is_active() && p.phys > 0.0);
        assert!(!GuidanceConfig::parse("phys").unwrap().is_active());
        // Repair is not a guidance term.
        assert!(GuidanceConfig::parse("all,polish").unwrap_err().contains("polish"));
    }

    #[test]
    fn a_config_file_without_the_newer_fields_means_what_it_meant_and_all_round_trips() {
        let old = r#"{"motion": 1.0, "bound": 1.0, "object": 1.0, "scale": 0.1, "until_step": 100}"#;
        let cfg: GuidanceConfig = serde_json::from_str(old).unwrap();
        // (The physics window of a file without it is 0: J_phys is off there anyway.)
        assert_eq!(cfg, GuidanceConfig { phys_until: 0, phys_every: 0, ..GuidanceConfig::shade() });
        assert_eq!((cfg.bound_margin, cfg.against_wall, cfg.against_wall_reach), (None, 0.0, 0.3));
        assert_eq!((cfg.contact_margin, cfg.object_gap), (None, 0.0));
        assert_eq!((cfg.table, GuidanceConfig::all().table), (0.0, 1.0), "J_t is off in an older file");
        for cfg in [GuidanceConfig::all(), GuidanceConfig::soft()] {
            assert_eq!(serde_json::from_str::<GuidanceConfig>(&serde_json::to_string(&cfg).unwrap()).unwrap(), cfg);
        }
        let e = GuidanceConfig::all();
        assert_eq!((e.bound_margin, e.against_wall), (Some(crate::data::layout::WALL_GAP), 0.2));
        assert_eq!((e.contact_margin, e.object_gap), (Some(0.0), 0.03));
        let soft = GuidanceConfig { bound_margin: None, against_wall: 0.0, contact_margin: None, ..e };
        assert_eq!(soft, GuidanceConfig::soft());
        assert_eq!((GuidanceConfig::all().object_gap, GuidanceConfig::shade().object_gap), (0.03, 0.0));
    }

    #[test]
    fn configs_that_cannot_guide_say_why() {
        assert_eq!(GuidanceConfig::all().problem(), None);
        assert_eq!(GuidanceConfig::shade().problem(), None);
        let bad = |c: GuidanceConfig| c.problem().unwrap();
        assert!(bad(GuidanceConfig { bound: -1.0, ..GuidanceConfig::all() }).starts_with("bound:"));
        assert!(bad(GuidanceConfig { scale: f64::NAN, ..GuidanceConfig::all() }).starts_with("scale:"));
        assert!(bad(GuidanceConfig { max_step: Some(-0.03), ..GuidanceConfig::all() }).starts_with("max_step:"));
        assert!(bad(GuidanceConfig { real_sizes: Some(f64::NAN), ..GuidanceConfig::all() }).starts_with("real_sizes:"));
        assert!(
            bad(GuidanceConfig { contact_margin: Some(-0.01), ..GuidanceConfig::all() }).starts_with("contact_margin:")
        );
        assert!(bad(GuidanceConfig { object_gap: f64::INFINITY, ..GuidanceConfig::all() }).starts_with("object_gap:"));
        assert!(
            bad(GuidanceConfig { bound_margin: Some(-0.05), ..GuidanceConfig::all() }).starts_with("bound_margin:")
        );
        assert!(
            bad(GuidanceConfig { against_wall: f64::INFINITY, ..GuidanceConfig::all() }).starts_with("against_wall:")
        );
        assert!(
            bad(GuidanceConfig { against_wall_reach: -0.3, ..GuidanceConfig::all() })
                .starts_with("against_wall_reach:")
        );
        assert!(
            bad(GuidanceConfig { fold_anchored: Some(1.5), ..GuidanceConfig::all() }).starts_with("fold_anchored:")
        );
        assert!(
            bad(GuidanceConfig { fold_anchored: Some(f64::NAN), ..GuidanceConfig::all() })
                .starts_with("fold_anchored:")
        );
        assert!(bad(GuidanceConfig { iterations: 1_000_000_000, ..GuidanceConfig::all() }).starts_with("iterations:"));
        assert!(bad(GuidanceConfig { table: -1.0, ..GuidanceConfig::all() }).starts_with("table:"));
        assert!(
            bad(GuidanceConfig { table_reach: f64::INFINITY, ..GuidanceConfig::all() }).starts_with("table_reach:")
        );
        assert!(
            bad(GuidanceConfig { anchored_mobility: 2.0, ..GuidanceConfig::all() }).starts_with("anchored_mobility:")
        );
    }
}

#[cfg(test)]
mod batch_tests {
    use super::*;
    use crate::data::{SplitStats, generate_room};
    use crate::generator::tokens;
    use crate::scene::RoomType;

    /// A bedroom whose only piece stands through the wall at x = min x (its centre 10 cm inside),
    /// a model config with free slots only, the bounds, masks and world tokens.
    fn piece_through_the_wall() -> (Scene, ModelConfig, Bounds, SceneMasks, Vec<f32>) {
        let mut scene = generate_room(RoomType::Bedroom, 2, 1, false).scene;
        let cfg = ModelConfig { anchor_scale: 0.0, ..ModelConfig::tiny(RoomType::Bedroom) };
        let mut stats = SplitStats::default();
        stats.add(&scene);
        let bounds = Bounds::from_stats(&stats);
        let (min, _) = scene.floor_plan.polygon().bounds();
        scene.objects.truncate(1);
        scene.objects[0].center[0] = min.x + 0.1;
        scene.objects[0].yaw = 0.0;
        let masks = SceneMasks::of(&scene);
        let (tok, _) = tokens::encode(&scene, masks.window.center, &[], &bounds, &cfg);
        (scene, cfg, bounds, masks, tok)
    }

    #[test]
    fn guiding_a_batch_moves_an_object_back_inside_the_room() {
        // Free slots only: a piece in an anchored slot is held by its person (below).
        let (scene, cfg, bounds, masks, tok) = piece_through_the_wall();
        let x0 = Tensor::from_vec(tok.clone(), (1, cfg.slots(), cfg.token_dim()), &candle_core::Device::Cpu).unwrap();
        let mut g = SpatialGuidance::new(GuidanceConfig::all(), &cfg, &bounds, &[&scene]);
        let mut x = x0.clone();
        for t in (0..50).rev() {
            x = g.guide(&x, t).unwrap();
        }
        let first = g.history.first().unwrap().1;
        let last = g.history.last().unwrap().1;
        assert!(first > 0.0 && last < 0.5 * first, "J {first} → {last}");
        let out = x.flatten_all().unwrap().to_vec1::<f32>().unwrap();
        let moved = tokens::decode(&out, masks.window.center, 2.6, &bounds, &cfg);
        assert!(moved[0].center[0] > scene.objects[0].center[0] + 0.05, "{:?}", moved[0].center);
        // Steps at or above `until_step` are left alone.
        let mut late = SpatialGuidance::new(GuidanceConfig::all(), &cfg, &bounds, &[&scene]);
        let same = late.guide(&x0, 150).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        assert_eq!(same, tok);
        // With `every` 3, only the window's multiples of 3 are guided, and the others left alone.
        let every = GuidanceConfig { every: 3, ..GuidanceConfig::all() };
        let mut sparse = SpatialGuidance::new(every, &cfg, &bounds, &[&scene]);
        let same = sparse.guide(&x0, 10).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        assert_eq!(same, tok);
        let mut x = x0.clone();
        for t in (0..20).rev() {
            x = sparse.guide(&x, t).unwrap();
        }
        let guided: Vec<usize> = sparse.history.iter().map(|&(t, _)| t).collect();
        assert_eq!(guided, vec![18, 15, 12, 9, 6, 3, 0]);
        assert!(GuidanceConfig { every: 0, ..GuidanceConfig::all() }.problem().unwrap().starts_with("every:"));
        // With anchored slots, the scene's contact boxes hold the first slots: at mobility 0 the
        // piece in slot 0 stays through the wall, at mobility 1 it is moved like a free one.
        let anchored = ModelConfig::tiny(RoomType::Bedroom);
        assert!(!Conditions::contact_boxes_of(&scene).is_empty(), "the scene has a contact box");
        for (mobility, moves) in [(0.0, false), (1.0, true)] {
            let cfg_g = GuidanceConfig { anchored_mobility: mobility, ..GuidanceConfig::all() };
            let mut g = SpatialGuidance::new(cfg_g, &anchored, &bounds, &[&scene]);
            let out = g.guide(&x0, 10).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
            assert_eq!(out[..8] != tok[..8], moves, "mobility {mobility}");
        }
    }

    #[test]
    fn a_piece_held_in_two_slots_is_guided_once_and_its_copy_follows() {
        // The piece through the wall in slot 0 and again, a centimetre off, in slot 1 (as a sofa
        // is in each of its sitters' slots).
        let (scene, cfg, bounds, masks, mut tok) = piece_through_the_wall();
        let dim = cfg.token_dim();
        let first: Vec<f32> = tok[..dim].to_vec();
        tok[dim..2 * dim].copy_from_slice(&first);
        tok[dim] += 0.01 / (bounds.center_max[0] - bounds.center_min[0]) as f32;
        assert_eq!(tokens::decode(&tok, masks.window.center, 2.6, &bounds, &cfg).len(), 1, "one piece");
        let x0 = Tensor::from_vec(tok.clone(), (1, cfg.slots(), dim), &candle_core::Device::Cpu).unwrap();
        // The wall alone moves it (the people in the room would push it too).
        let walls = GuidanceConfig { motion: 0.0, object: 0.0, body: 0.0, ..GuidanceConfig::all() };
        let mut g = SpatialGuidance::new(walls, &cfg, &bounds, &[&scene]);
        let out = g.guide(&x0, 0).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        assert!(out[0] > tok[0] + 0.01, "the piece moved out of the wall: {} → {}", tok[0], out[0]);
        assert_eq!(out[..CLASS_OFFSET], out[dim..dim + CLASS_OFFSET], "the copy took the piece's place");
        assert_eq!(tokens::decode(&out, masks.window.center, 2.6, &bounds, &cfg).len(), 1, "still one piece");
    }

    #[test]
    fn size_mobility_zero_moves_a_piece_out_of_the_wall_at_the_size_it_was_drawn() {
        let (scene, cfg, bounds, _, tok) = piece_through_the_wall();
        let dim = cfg.token_dim();
        let x0 = Tensor::from_vec(tok.clone(), (1, cfg.slots(), dim), &candle_core::Device::Cpu).unwrap();
        let walls = |size_mobility| GuidanceConfig {
            motion: 0.0,
            object: 0.0,
            body: 0.0,
            size_mobility,
            ..GuidanceConfig::all()
        };
        let guided = |size_mobility| {
            let mut g = SpatialGuidance::new(walls(size_mobility), &cfg, &bounds, &[&scene]);
            g.guide(&x0, 0).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap()
        };
        // As it was: the wall term moves the piece and shrinks it.
        let (free, fixed) = (guided(1.0), guided(0.0));
        assert!(free[0] > tok[0] + 0.01 && free[3..6] != tok[3..6], "{:?} → {:?}", &tok[..8], &free[..8]);
        // Sizes held: the piece moves out all the same, its sizes the model's to the bit.
        assert!(fixed[0] > tok[0] + 0.01, "moved: {} → {}", tok[0], fixed[0]);
        assert_eq!(fixed[3..6], tok[3..6]);
        let bad = GuidanceConfig { size_mobility: 1.5, ..GuidanceConfig::all() };
        assert!(bad.problem().unwrap().starts_with("size_mobility:"));
    }

    #[test]
    fn overlapping_pieces_in_anchored_slots_fold_into_the_larger() {
        use Category::*;
        // Slots 0–2 anchored: an armchair (0.8 × 0.8) inside a loveseat (1.6 × 0.8), an armchair
        // 2 m away; slot 3 (free) a stool inside the loveseat.
        let piece = |c, x: f64, w: f64| Object::standing("o", c, [x, 0.0], [w, 0.8, 0.8]);
        let mut decoded = vec![
            (vec![0], piece(Armchair, 0.4, 0.8)),
            (vec![1], piece(LoveseatSofa, 0.6, 1.6)),
            (vec![2], piece(Armchair, 3.0, 0.8)),
            (vec![3], piece(Stool, 0.8, 0.4)),
        ];
        let dim = 3;
        let mut tokens: Vec<f32> = (0..4 * dim).map(|v| v as f32).collect();
        fold_anchored(&mut decoded, &mut tokens, &[Action::Sit; 3], 0.25, dim);
        let kept: Vec<(Vec<usize>, Category)> = decoded.iter().map(|(s, o)| (s.clone(), o.category)).collect();
        assert_eq!(kept, vec![(vec![1, 0], LoveseatSofa), (vec![2], Armchair), (vec![3], Stool)]);
        assert_eq!(tokens[..dim], tokens[dim..2 * dim], "slot 0 holds the loveseat's whole token");
        assert_eq!(tokens[dim..2 * dim], [3.0, 4.0, 5.0]);
        assert_eq!(tokens[2 * dim..], [6.0, 7.0, 8.0, 9.0, 10.0, 11.0], "the far and the free slots are untouched");
        // Overlapping by less than the share (0.1 m of the armchair's 0.8): nothing folds.
        let mut apart = vec![(vec![0], piece(Armchair, -0.5, 0.8)), (vec![1], piece(LoveseatSofa, 0.6, 1.6))];
        let before = apart.clone();
        fold_anchored(&mut apart, &mut tokens, &[Action::Sit; 2], 0.25, dim);
        assert_eq!(apart, before);
    }

    #[test]
    fn a_diner_s_chair_never_folds_into_the_table_a_hand_rests_on() {
        use Category::*;
        // Slot 0 a diner's chair half under a 1.6 × 0.9 m table in slot 1, which a hand touches.
        let mut decoded = vec![
            (vec![0], Object::standing("o", DiningChair, [0.7, 0.0], [0.5, 0.5, 0.9])),
            (vec![1], Object::standing("o", DiningTable, [0.0, 0.0], [1.6, 0.9, 0.75])),
        ];
        let dim = 3;
        let mut tokens: Vec<f32> = (0..2 * dim).map(|v| v as f32).collect();
        let (before, tokens_before) = (decoded.clone(), tokens.clone());
        fold_anchored(&mut decoded, &mut tokens, &[Action::Sit, Action::Touch], 0.25, dim);
        assert_eq!((decoded, tokens), (before.clone(), tokens_before.clone()), "a table seats no one");
        // The same two pieces under two hands fold into the table, which both may touch.
        let mut decoded = before;
        let mut tokens = tokens_before;
        fold_anchored(&mut decoded, &mut tokens, &[Action::Touch, Action::Touch], 0.25, dim);
        assert_eq!(decoded.len(), 1);
        assert_eq!((decoded[0].0.clone(), decoded[0].1.category), (vec![1, 0], DiningTable));
    }

    #[test]
    fn a_diner_s_table_shrunk_short_of_them_is_grown_back_and_the_data_s_own_costs_nothing() {
        // Synthetic dining rooms: every diner's table reaches over their knees, as in the data.
        let only_table = GuidanceConfig {
            motion: 0.0,
            bound: 0.0,
            object: 0.0,
            contact: 0.0,
            body: 0.0,
            support: 0.0,
            against_wall: 0.0,
            square: 0.0,
            ..GuidanceConfig::all()
        };
        let mut diners = 0;
        for index in 0..12 {
            let scene = generate_room(RoomType::Dining, 3, index, false).scene;
            let masks = SceneMasks::of(&scene);
            let mut objects: Vec<GuidedObject> = scene.objects.iter().map(GuidedObject::of).collect();
            // Each object's boxes: those whose centre its footprint holds (the data's own anchors).
            let anchors: Vec<Vec<usize>> = objects
                .iter()
                .map(|o| {
                    (0..masks.contacts.len())
                        .filter(|&k| o.obox().footprint_contains(masks.contacts[k].center))
                        .collect()
                })
                .collect();
            let seated: usize = objects
                .iter()
                .zip(&anchors)
                .filter(|(o, _)| o.category == Category::DiningChair)
                .map(|(_, a)| a.iter().filter(|&&k| masks.contacts[k].knees.is_some()).count())
                .sum();
            let Some(t) = objects.iter().position(|o| o.category == Category::DiningTable) else { continue };
            if seated == 0 {
                continue;
            }
            diners += seated;
            assert_eq!(guidance_cost(&objects, &anchors, &masks, &only_table).0, 0.0, "room {index}");
            // The table at half its width and depth stops short of its diners' knees (by less
            // than the reach); the gradient grows it.
            objects[t].size.x *= 0.5;
            objects[t].size.y *= 0.5;
            let (j, grads) = guidance_cost(&objects, &anchors, &masks, &only_table);
            assert!(j > 0.0, "room {index}");
            assert!(grads[t][3] <= 0.0 && grads[t][4] <= 0.0 && grads[t][3] + grads[t][4] < 0.0, "{:?}", grads[t]);
        }
        assert!(diners >= 3, "the rooms seat {diners} diners");
    }

    #[test]
    fn the_contact_term_pulls_an_anchored_piece_back_under_its_person() {
        let mut scene = generate_room(RoomType::Bedroom, 2, 1, false).scene;
        let boxes = Conditions::contact_boxes_of(&scene);
        assert!(!boxes.is_empty(), "the scene has a contact box");
        let b = boxes[0].obox;
        // The piece in slot 0 (anchored to box 0): the box's footprint grown by 0.1 m each side,
        // shifted 0.3 m along the box's own x axis, so that a 0.2 m strip of the box is uncovered.
        scene.objects.truncate(1);
        let o = &mut scene.objects[0];
        let shifted = b.to_world(DVec3::new(0.3, 0.0, 0.0));
        o.center = [shifted.x, shifted.y, o.center[2]];
        o.size = [b.size.x + 0.2, b.size.y + 0.2, o.size[2]];
        o.yaw = b.yaw;
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let mut stats = SplitStats::default();
        stats.add(&scene);
        let bounds = Bounds::from_stats(&stats);
        let masks = SceneMasks::of(&scene);
        let (tok, _) = tokens::encode(&scene, masks.window.center, &[], &bounds, &cfg);
        let x0 = Tensor::from_vec(tok, (1, cfg.slots(), cfg.token_dim()), &candle_core::Device::Cpu).unwrap();
        let shortfall = |tokens: &[f32]| {
            let piece = GuidedObject::of(&tokens::decode(tokens, masks.window.center, 2.6, &bounds, &cfg)[0]);
            contact_shortfall(&[piece], &[vec![&masks.contacts[0]]], &masks.window).0
        };
        let before = shortfall(&x0.flatten_all().unwrap().to_vec1::<f32>().unwrap());
        // Only J_c can move the lone piece (J_o has no pair; J_m and J_b off).
        let only_contact = GuidanceConfig { motion: 0.0, bound: 0.0, ..GuidanceConfig::all() };
        let mut g = SpatialGuidance::new(only_contact.clone(), &cfg, &bounds, &[&scene]);
        let out = g.guide(&x0, 0).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        let after = shortfall(&out);
        assert!(before > 0.1 * b.size.y && after < 0.1 * before, "uncovered {before} → {after} m²");
        // Without J_c, nothing holds it.
        let mut none = SpatialGuidance::new(GuidanceConfig { contact: 0.0, ..only_contact }, &cfg, &bounds, &[&scene]);
        let kept = none.guide(&x0, 0).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
        assert!((shortfall(&kept) - before).abs() < 1e-6);
    }

    #[test]
    fn a_wall_piece_is_drawn_back_to_the_data_s_gap_whatever_the_model_s_decoding_range() {
        // A bedroom's wall pieces alone, each moved out from its wall by 1–7 cm; the wall terms
        // alone guide them, under the bedroom's decoding range and under one as wide as a living
        // room model's (±5.245 m), where a step of γ token units used to move a piece 3.6 times as
        // far: J_w overshot the gap, J_b pushed the piece back 3 cm, and it ended 8 cm out.
        let mut scene = generate_room(RoomType::Bedroom, 2, 1, false).scene;
        scene.objects.retain(|o| crate::data::stands_against_wall(o.category));
        assert!(scene.objects.len() >= 2, "a bed and a cabinet or more");
        let cfg = ModelConfig { anchor_scale: 0.0, ..ModelConfig::tiny(RoomType::Bedroom) };
        let mut stats = SplitStats::default();
        stats.add(&scene);
        let own = Bounds::from_stats(&stats);
        let wide = Bounds {
            center_min: [-5.245, -5.245, own.center_min[2]],
            center_max: [5.245, 5.245, own.center_max[2]],
            ..own.clone()
        };
        let walls =
            GuidanceConfig { motion: 0.0, object: 0.0, body: 0.0, contact: 0.0, support: 0.0, ..GuidanceConfig::all() };
        for bounds in [&own, &wide] {
            for offset in [0.01, 0.029, 0.045, 0.07] {
                let mut moved = scene.clone();
                for o in &mut moved.objects {
                    let (_, ay) = o.obox().axes();
                    o.center[0] += ay.x * offset;
                    o.center[1] += ay.y * offset;
                }
                let masks = SceneMasks::of(&moved);
                let (tok, _) = tokens::encode(&moved, masks.window.center, &[], bounds, &cfg);
                let x0 = Tensor::from_vec(tok, (1, cfg.slots(), cfg.token_dim()), &candle_core::Device::Cpu).unwrap();
                let mut g = SpatialGuidance::new(walls.clone(), &cfg, bounds, &[&moved]);
                let out = g.guide(&x0, 0).unwrap().flatten_all().unwrap().to_vec1::<f32>().unwrap();
                let guided = tokens::decode(&out, masks.window.center, moved.floor_plan.height, bounds, &cfg);
                assert_eq!(guided.len(), scene.objects.len());
                // Each piece back where the data stands it, its back WALL_GAP from its wall.
                for o in &guided {
                    let home = scene.objects.iter().filter(|h| h.category == o.category);
                    let miss = home
                        .map(|h| (h.center[0] - o.center[0]).hypot(h.center[1] - o.center[1]))
                        .fold(f64::MAX, f64::min);
                    assert!(
                        miss < 0.005,
                        "{} moved out {offset} m under ±{} m: {miss:.4} m from where it stood",
                        o.category,
                        bounds.center_max[0]
                    );
                }
            }
        }
    }
}
