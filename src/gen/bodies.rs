//! J_p (ours): how deep the people's bodies are inside the pieces, as a guidance term.
//!
//! The pieces' shapes are their furniture templates (`furniture::template_of`: a chair's seat, back
//! and legs, a bed's mattress and headboard), the bodies are surface points of every human at a few
//! frames (`human::SurfaceSampler`), and J_p = Σ over points inside a piece of the depth beyond
//! [`TOLERANCE`], each human's points weighted by one over its sampled frames (so a human counts
//! like one frame of E_pen). Its gradient is a central difference of the exact value, for the
//! pieces whose bounding box holds any point; the points are bucketed once per scene on a grid.
//!
//! J_s (ours) is its other half, support: for a piece anchored to a sitter's or a sleeper's contact
//! box, how far the top of the piece's parts under the box's centre stays below the box's top (the
//! body's lowest point) beyond [`SUPPORT_TOLERANCE`]. J_c keeps the piece under its person, J_p
//! keeps it out of the body, J_s keeps it up against it.

use super::guidance::{GuidedObject, ObjectGradient};
use crate::furniture::{Part, PartRole, template_of};
use crate::human::SurfaceSampler;
use crate::scene::Human;
use glam::{DVec2, DVec3};
use std::collections::HashMap;

/// Depth (m) a body point may reach inside a piece before it costs (the physics check allows 2 cm).
pub const TOLERANCE: f64 = 0.01;
/// How far (m) a seat's top may stay below the body resting on it (the physics check allows 5 cm).
pub const SUPPORT_TOLERANCE: f64 = 0.02;
/// Frames sampled per human, evenly over its clip, besides the middle of each contact span.
const FRAMES: usize = 8;
/// Surface points per body and frame.
const POINTS: usize = 150;
/// Side (m) of the grid the points are bucketed on.
const CELL: f64 = 0.25;

/// The body points of one scene, bucketed on a horizontal grid.
#[derive(Debug, Clone, Default)]
pub struct BodyPoints {
    cells: HashMap<(i32, i32), Vec<(DVec3, f64)>>,
}

impl BodyPoints {
    /// The points of `humans` (a scene's).
    pub fn of(humans: &[Human]) -> BodyPoints {
        let mut cells: HashMap<(i32, i32), Vec<(DVec3, f64)>> = HashMap::new();
        for human in humans {
            let n = human.frames.len();
            if n == 0 {
                continue;
            }
            let mut frames: Vec<usize> = (0..FRAMES.min(n)).map(|i| i * n / FRAMES.min(n)).collect();
            frames.extend(human.contact_spans().map(|s| (s.start + s.end) / 2));
            frames.sort_unstable();
            frames.dedup();
            let reference: Vec<DVec3> = human.frame(0).collect();
            let sampler = SurfaceSampler::new(&human.skeleton, &reference, POINTS);
            let weight = 1.0 / frames.len() as f64;
            for f in frames {
                let joints: Vec<DVec3> = human.frame(f).collect();
                for p in sampler.points(&human.skeleton, &joints) {
                    cells.entry(cell_of(p.truncate())).or_default().push((p, weight));
                }
            }
        }
        BodyPoints { cells }
    }

    /// The points within the horizontal rectangle `min`..`max`.
    fn within(&self, min: DVec2, max: DVec2) -> Vec<(DVec3, f64)> {
        let (lo, hi) = (cell_of(min), cell_of(max));
        let mut out = Vec::new();
        for i in lo.0..=hi.0 {
            for j in lo.1..=hi.1 {
                if let Some(points) = self.cells.get(&(i, j)) {
                    out.extend(
                        points.iter().filter(|(p, _)| p.x >= min.x && p.y >= min.y && p.x <= max.x && p.y <= max.y),
                    );
                }
            }
        }
        out
    }
}

fn cell_of(p: DVec2) -> (i32, i32) {
    ((p.x / CELL).floor() as i32, (p.y / CELL).floor() as i32)
}

/// J_p of one piece against `points`: Σ weight · (depth − [`TOLERANCE`]) over the points deeper
/// than that inside its template.
fn piece_cost(o: &GuidedObject, points: &[(DVec3, f64)]) -> f64 {
    let parts = template_of(o.category, &o.obox()).parts;
    points
        .iter()
        .map(|&(p, w)| {
            let depth = parts.iter().map(|part| depth_inside(part, p)).fold(0.0, f64::max);
            w * (depth - TOLERANCE).max(0.0)
        })
        .sum()
}

/// How deep `p` is inside `part` (0 outside): the distance to its nearest face, but a seat (a bed's
/// mattress, a sofa's seat block, a stool's seat) is left through its top or sides only. A body
/// rests on a seat from above, so a sitter's thighs inside a seat too high ask for a lower seat,
/// not one pushed up through them.
fn depth_inside(part: &Part, p: DVec3) -> f64 {
    let l = part.obox.to_local(p);
    let h = part.obox.half();
    let (x, y) = (h.x - l.x.abs(), h.y - l.y.abs());
    let (top, bottom) = (h.z - l.z, h.z + l.z);
    if x <= 0.0 || y <= 0.0 || top <= 0.0 || bottom <= 0.0 {
        return 0.0;
    }
    match part.role {
        PartRole::Seat => x.min(y).min(top),
        _ => x.min(y).min(top).min(bottom),
    }
}

/// Σ over pieces of J_p, with central-difference gradients (centre x, y, size, yaw; the height of a
/// standing piece follows its size).
pub fn body_penetration(objects: &[GuidedObject], bodies: &BodyPoints) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        if o.hanging {
            continue;
        }
        let reach = DVec2::splat(o.size.x.hypot(o.size.y) * 0.5 + 0.01);
        let c = o.center.truncate();
        let points = bodies.within(c - reach, c + reach);
        let cost = piece_cost(o, &points);
        if cost <= 0.0 {
            continue;
        }
        total += cost;
        *g = central_differences(o, |moved| piece_cost(moved, &points));
    }
    (total, grads)
}

/// Where a sitter or sleeper needs support: the centre of their contact box and its top (the
/// body's lowest point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportNeed {
    /// The contact box's centre on the floor.
    pub at: DVec2,
    /// The height of the body's lowest point.
    pub height: f64,
}

/// J_s of one piece: how far the top of its highest part over `need.at` stays below `need.height`
/// beyond [`SUPPORT_TOLERANCE`] (0 where no part is over it: J_c's business).
fn support_gap(o: &GuidedObject, need: &SupportNeed) -> f64 {
    let top = template_of(o.category, &o.obox())
        .parts
        .iter()
        .filter(|p| p.obox.footprint_contains(need.at))
        .map(|p| p.obox.z_range().1)
        .fold(f64::NEG_INFINITY, f64::max);
    if top.is_finite() { (need.height - SUPPORT_TOLERANCE - top).max(0.0) } else { 0.0 }
}

/// Σ over anchored pieces of J_s; `needs[i]` is what piece i's person needs, `None` for free
/// pieces and touched ones. Gradients as [`body_penetration`]'s.
pub fn support_shortfall(objects: &[GuidedObject], needs: &[Option<SupportNeed>]) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for ((o, need), g) in objects.iter().zip(needs).zip(&mut grads) {
        let Some(need) = need else { continue };
        let gap = support_gap(o, need);
        if gap <= 0.0 {
            continue;
        }
        total += gap;
        *g = central_differences(o, |moved| support_gap(moved, need));
    }
    (total, grads)
}

/// ∂cost/∂(centre x, y, size, yaw) of one piece by central differences; a standing piece keeps its
/// base on the floor as its height changes.
fn central_differences(o: &GuidedObject, cost: impl Fn(&GuidedObject) -> f64) -> ObjectGradient {
    let mut g = [0.0; 7];
    for k in [0, 1, 3, 4, 5, 6] {
        let h = 1e-3;
        let at = |delta: f64| {
            let mut moved = *o;
            match k {
                0 | 1 => moved.center[k] += delta,
                3..=5 => moved.size[k - 3] = (moved.size[k - 3] + delta).max(1e-3),
                _ => moved.yaw += delta,
            }
            if k == 5 {
                moved.center.z += delta * 0.5;
            }
            cost(&moved)
        };
        g[k] = (at(h) - at(-h)) / (2.0 * h);
    }
    g
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::human::{Body, Motion, sit};
    use crate::scene::{Action, Category};

    /// One sitter on a 0.45 m seat at the origin.
    fn sitter(seat: f64) -> BodyPoints {
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(sit(&body, DVec2::new(0.0, -0.05), seat, 0.0), 4, Action::Sit);
        BodyPoints::of(&[m.into_human("h0")])
    }

    fn stool(height: f64) -> GuidedObject {
        GuidedObject {
            center: DVec3::new(0.0, 0.0, height * 0.5),
            size: DVec3::new(0.4, 0.4, height),
            yaw: 0.0,
            hanging: false,
            category: Category::Stool,
        }
    }

    #[test]
    fn a_seat_under_its_sitter_costs_nothing_and_a_high_one_is_lowered() {
        let bodies = sitter(0.45);
        assert_eq!(body_penetration(&[stool(0.45)], &bodies).0, 0.0);
        // 3 to 13 cm too high, the thighs are inside the 5 cm seat slab, and at every height a lower
        // stool costs less: a seat is left through its top, never pushed up through the body.
        for height in [0.48, 0.50, 0.52, 0.55, 0.58] {
            let (cost, grads) = body_penetration(&[stool(height)], &bodies);
            assert!(cost > 0.005, "{height}: {cost}");
            assert!(grads[0][5] > 0.0, "{height}: ∂J/∂height {}", grads[0][5]);
        }
        // A stool a metre away costs nothing.
        let mut away = stool(0.55);
        away.center.x += 1.0;
        assert_eq!(body_penetration(&[away], &bodies).0, 0.0);
    }

    #[test]
    fn a_low_seat_is_raised_towards_its_sitter() {
        let need = SupportNeed { at: DVec2::ZERO, height: 0.45 };
        // A stool's seat is its top: 10 cm short costs 8 cm (2 cm are tolerated); 1 cm short nothing.
        let (gap, grads) = support_shortfall(&[stool(0.35)], &[Some(need)]);
        assert!((gap - 0.08).abs() < 1e-9, "{gap}");
        assert!(grads[0][5] < -0.9, "growing it closes the gap: {}", grads[0][5]);
        assert_eq!(support_shortfall(&[stool(0.44)], &[Some(need)]).0, 0.0);
        // Nothing of it under the box, or a free piece: J_c's business, not this term's.
        let mut beside = stool(0.35);
        beside.center.x += 1.0;
        assert_eq!(support_shortfall(&[beside], &[Some(need)]).0, 0.0);
        assert_eq!(support_shortfall(&[stool(0.35)], &[None]).0, 0.0);
    }
}
