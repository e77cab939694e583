//! Physics-feedback guidance (J_phys, ours): in the last sampling steps, the decoded clean estimate
//! is built as a scene, the humans are replayed against it in Rapier, and what the replay and the
//! geometry find is turned into displacements of the offending objects' centres:
//!
//! - a bone penetrating an object pushes it horizontally away from the bone by the depth
//!   (averaged over the object's contacts, [`Physics::pushes`], which `sim` answers with a
//!   Rapier replay);
//! - two objects that overlap push each other apart along the line between their centres, each by
//!   half the square root of their footprint overlap;
//! - a sitting or lying human with no support (contact IoU below one half) pulls the nearest object
//!   that affords its action halfway towards its contact box.
//!
//! The displacement is applied to the tokens' centres (scaled by the bounds) times a weight. Yaw is
//! left to the spatial terms. Batch items are handled in parallel.

use super::tokens::decode_slots;
use super::{Bounds, GenError, Guidance, ModelConfig, Schedule};
use crate::geom::{footprint_intersection_area, intersection_volume};
use crate::human::Conditions;
use crate::measure::contact_iou;
use crate::physics::Physics;
use crate::scene::{Action, Scene};
use candle_core::Tensor;
use glam::DVec2;
use rayon::prelude::*;
use std::sync::Arc;

pub use crate::physics::PHYS_TOLERANCE;

/// Displacements (m) of each object of `scene` (by index) that would fix what the replay finds.
pub fn physics_displacements(scene: &Scene, physics: &dyn Physics) -> Vec<DVec2> {
    let n = scene.objects.len();
    let mut moves = vec![DVec2::ZERO; n];
    for (i, push) in physics.pushes(scene, PHYS_TOLERANCE) {
        moves[i] += push;
    }
    let boxes: Vec<_> = scene.objects.iter().map(|o| o.obox()).collect();
    for i in 0..n {
        for j in i + 1..n {
            if intersection_volume(&boxes[i], &boxes[j]) <= 0.0 {
                continue;
            }
            let apart = (boxes[i].center - boxes[j].center).truncate();
            let dir = if apart.length() > 1e-6 { apart.normalize() } else { DVec2::X };
            let step = footprint_intersection_area(&boxes[i], &boxes[j]).sqrt() * 0.5;
            moves[i] += dir * step * 0.5;
            moves[j] -= dir * step * 0.5;
        }
    }
    for b in Conditions::contact_boxes_of(scene) {
        if !matches!(b.action, Action::Sit | Action::Lie) || contact_iou(&b.obox, &scene.objects) >= 0.5 {
            continue;
        }
        let target = b.obox.center.truncate();
        let nearest = (0..n).filter(|&i| scene.objects[i].category.affords(b.action)).min_by(|&x, &y| {
            let d = |i: usize| boxes[i].center.truncate().distance(target);
            d(x).total_cmp(&d(y))
        });
        if let Some(i) = nearest {
            moves[i] += (target - boxes[i].center.truncate()) * 0.5;
        }
    }
    moves
}

/// The physics-feedback guidance of one batch.
#[derive(Clone)]
pub struct PhysicsGuidance {
    physics: Arc<dyn Physics>,
    model: ModelConfig,
    bounds: Bounds,
    scenes: Vec<Scene>,
    weight: f64,
    until_step: usize,
    every: usize,
    /// Objects moved at each guided step.
    pub history: Vec<(usize, usize)>,
}

impl PhysicsGuidance {
    /// Guidance for `scenes` (batch order) moving objects by `weight` × the displacement at the
    /// steps t < `until_step` (of the linear schedule, as a noise level: [`Schedule::at_linear_noise`])
    /// that are multiples of `every`.
    pub fn new(
        model: &ModelConfig,
        bounds: &Bounds,
        scenes: &[&Scene],
        weight: f64,
        until_step: usize,
        every: usize,
        physics: Arc<dyn Physics>,
    ) -> PhysicsGuidance {
        PhysicsGuidance {
            physics,
            model: model.clone(),
            bounds: bounds.clone(),
            scenes: scenes.iter().map(|s| (*s).clone()).collect(),
            weight,
            until_step: Schedule::of(model).at_linear_noise(until_step),
            every: every.max(1),
            history: Vec::new(),
        }
    }
}

impl Guidance for PhysicsGuidance {
    fn guide(&mut self, x0: &Tensor, t: usize) -> Result<Tensor, GenError> {
        if t >= self.until_step || t % self.every != 0 || self.weight <= 0.0 {
            return Ok(x0.clone());
        }
        let dims = x0.dims().to_vec();
        let mut v = x0.flatten_all()?.to_vec1::<f32>()?;
        let dim = self.model.token_dim();
        let per_item = self.model.slots() * dim;
        let half = |k: usize| (self.bounds.center_max[k] - self.bounds.center_min[k]) * 0.5;
        let (hx, hy) = (half(0), half(1));
        let moved: usize = v
            .par_chunks_exact_mut(per_item)
            .zip(&self.scenes)
            .map(|(tokens, input)| {
                let center = input.room_window().center;
                let slots = decode_slots(tokens, center, input.floor_plan.height, &self.bounds, &self.model);
                let mut scene = input.clone();
                scene.objects = slots.iter().map(|(_, o)| o.clone()).collect();
                let moves = physics_displacements(&scene, self.physics.as_ref());
                let mut count = 0;
                for ((held_in, _), m) in slots.iter().zip(moves) {
                    if m == DVec2::ZERO {
                        continue;
                    }
                    count += 1;
                    for slot in held_in {
                        let t = &mut tokens[slot * dim..];
                        t[0] = (t[0] + (self.weight * m.x / hx) as f32).clamp(-1.0, 1.0);
                        t[1] = (t[1] + (self.weight * m.y / hy) as f32).clamp(-1.0, 1.0);
                    }
                }
                count
            })
            .sum();
        self.history.push((t, moved));
        Ok(Tensor::from_vec(v, dims, x0.device())?)
    }
}

/// Several guidances applied one after the other.
pub struct Chain(pub Vec<Box<dyn Guidance>>);

impl Guidance for Chain {
    fn guide(&mut self, x0: &Tensor, t: usize) -> Result<Tensor, GenError> {
        let mut x = x0.clone();
        for g in &mut self.0 {
            x = g.guide(&x, t)?;
        }
        Ok(x)
    }

    fn finish(&mut self, item: usize, scene: &mut Scene) {
        for g in &mut self.0 {
            g.finish(item, scene);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::scene::RoomType;

    #[test]
    fn a_walker_pushes_a_chair_out_of_the_way_and_overlaps_push_apart() {
        // A calibrated room is clean: nothing moves.
        let scene = generate_room(RoomType::Dining, 3, 0, false).scene;
        let clean = physics_displacements(&scene, &crate::sim::SimPhysics);
        assert!(clean.iter().all(|m| m.length() < 0.05), "{clean:?}");
        // Put a copy of an object onto a walker's path: it is pushed away from the path.
        let walker = scene.humans.iter().find(|h| h.actions.iter().any(|a| a.action == Action::Walk)).unwrap();
        let f = walker.frames.len() / 2;
        let pelvis_joint = walker.skeleton.joint("pelvis").unwrap();
        let pelvis = walker.joint_at(f, pelvis_joint);
        let heading = (walker.joint_at(f + 5, pelvis_joint) - walker.joint_at(f - 5, pelvis_joint)).truncate();
        let side = glam::DVec2::new(-heading.y, heading.x).normalize();
        let mut blocked = scene.clone();
        let mut chair = blocked.objects[0].clone();
        chair.id = "blocker".into();
        chair.size = [0.5, 0.5, 0.9];
        chair.center = [pelvis.x + 0.15 * side.x, pelvis.y + 0.15 * side.y, 0.45];
        blocked.objects.push(chair);
        let moves = physics_displacements(&blocked, &crate::sim::SimPhysics);
        let last = *moves.last().unwrap();
        assert!(last.length() > 0.05, "{moves:?}");
        // Pushed to the side it stands on, out of the path.
        assert!(last.normalize().dot(side) > 0.7, "{last:?} vs side {side:?}");
    }
}
