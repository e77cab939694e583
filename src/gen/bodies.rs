//! J_p (ours): how deep the people's bodies are inside the pieces, as a guidance term.
//!
//! The pieces' shapes are their furniture templates (`furniture::template_of`: a chair's seat, back
//! and legs, a bed's mattress and headboard); the bodies are the bone capsules the physics check
//! tests (`sim::check`), each as a row of balls along its bone no further apart than half its radius
//! (at most a quarter of the radius shallower than the capsule, where its axis grazes a corner, and
//! under 6 % where it stays half a radius off the piece), at every frame where the body
//! has moved 10 cm; a pose repeated exactly (held still, a clip looped) is tested once and counted
//! for each frame it stands for. J_p = Σ over pieces, bones and sampled frames of how far the bone reaches
//! within [`CLEARANCE`] of the piece: the capsule's depth, which is what the check measures, plus
//! the clearance — its deepest ball's reach, or, where the bone passes through a part that is not
//! a seat from below to above, how far the part must move sideways to let it out. A leg through a
//! table's 4 cm top is as deep as the top's nearest edge is far; its balls were only as deep as
//! the top is thin, the same wherever the table stood, so J_p could not push a table off a person
//! standing in it. A bone resting on a seat's top costs only when it is inside. Its gradient is a
//! central difference of the exact value over the balls near the piece; a query skips the rows of
//! balls (one per bone and frame) whose box is far.
//!
//! J_s (ours) is its other half, support: for a piece anchored to a sitter's or a sleeper's contact
//! box, how far the top of the piece's parts under the box's centre stays below the box's top (the
//! body's lowest point) beyond [`SUPPORT_TOLERANCE`]; for a toucher's, below the palm (the box's
//! centre), where the piece is under it (a tall piece touched on its front is not). J_c keeps the
//! piece under its person, J_p keeps it out of the body, J_s keeps it up against it.

use super::guidance::{GuidedObject, ObjectGradient};
use crate::furniture::{Part, PartRole, template_of};
use crate::scene::Human;
use glam::{DVec2, DVec3};
use std::collections::HashMap;
use std::ops::Range;

/// How far (m) bones are kept from pieces, except where they rest on a seat's top (the physics
/// check allows 2 cm of depth; the guidance stops short of contact, where its pull is weakest).
pub const CLEARANCE: f64 = 0.01;
/// How far (m) a seat's top may stay below the body resting on it (the physics check allows 5 cm).
pub const SUPPORT_TOLERANCE: f64 = 0.02;
/// A human's frames are sampled wherever some joint has moved this far (m) since the last sampled
/// frame (and at the middle of each contact span).
const STRIDE: f64 = 0.1;
/// Most frames of all humans together whose balls J_p tests: beyond, every human's sampled frames
/// are thinned evenly (the contact spans' middles kept). The calibrated test rooms and hand-built
/// inputs sample at most 276, so this only bounds the cost of the largest inputs validation accepts
/// (32 people, 50,000 frames: about 10,000 sampled, and sampling took over 10 minutes).
const MAX_SAMPLED_FRAMES: usize = 512;
/// How far (m) a part may move under the central differences' steps (1 mm of size or centre, a
/// milliradian of yaw at up to 3 m from the centre).
const DIFFERENCE_MARGIN: f64 = 0.005;

/// One ball of a bone capsule at one frame.
#[derive(Debug, Clone, Copy)]
struct Ball {
    center: DVec3,
    radius: f64,
}

/// The bodies of one scene as balls along their bones, one row of balls per bone and sampled
/// frame, each row with the box around its balls' centres (so a query skips whole bones).
#[derive(Debug, Clone, Default)]
pub struct BodyBalls {
    balls: Vec<Ball>,
    rows: Vec<BallRow>,
    /// The largest radius (m): a ball reaches this far beyond its centre.
    reach: f64,
}

/// One bone's balls at one frame: `BodyBalls::balls[range]`, their centres on the segment `a`..`b`.
#[derive(Debug, Clone)]
struct BallRow {
    range: Range<usize>,
    a: DVec3,
    b: DVec3,
    radius: f64,
    /// How many sampled frames hold this pose (a pose held still or a clip looped is tested once).
    weight: f64,
}

impl BallRow {
    /// At least how far (m) each of the row's balls stays beyond [`CLEARANCE`] of `part` (≤ 0
    /// where one may reach it): the distance from the part's box to the box around the segment in
    /// the part's frame, less the radius and the clearance.
    fn clearance_from(&self, part: &PartFrame) -> f64 {
        let (a, b) = (part.to_local(self.a), part.to_local(self.b));
        let gap = (a.min(b) - part.half).max(-a.max(b) - part.half).max(DVec3::ZERO);
        gap.length() - self.radius - CLEARANCE
    }
}

impl BodyBalls {
    /// The balls of `humans` (a scene's).
    pub fn of(humans: &[Human]) -> BodyBalls {
        let mut out = BodyBalls::default();
        let poses: Vec<Vec<Pose>> = humans.iter().map(|h| distinct_poses(h, sampled_frames(h))).collect();
        let total: usize = poses.iter().map(Vec::len).sum();
        let keep_every = total.div_ceil(MAX_SAMPLED_FRAMES).max(1);
        for (human, poses) in humans.iter().zip(poses) {
            let kept = poses.into_iter().enumerate().filter(|(i, p)| i % keep_every == 0 || p.contact);
            for (_, pose) in kept {
                for bone in &human.skeleton.bones {
                    out.reach = out.reach.max(bone.radius);
                    let (a, b) = (pose.joints[bone.a], pose.joints[bone.b]);
                    let start = out.balls.len();
                    out.balls.extend(balls_along(a, b, bone.radius));
                    let (range, radius, weight) = (start..out.balls.len(), bone.radius, pose.weight);
                    out.rows.push(BallRow { range, a, b, radius, weight });
                }
            }
        }
        out
    }

    /// How many balls there are.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.balls.len()
    }

    /// The bones (one per bone and sampled frame) whose balls may reach into the horizontal
    /// rectangle `min`..`max` and come within `margin` of costing against `parts` (within
    /// `margin` + [`CLEARANCE`] of them), each with those balls.
    fn near(&self, min: DVec2, max: DVec2, parts: &[PartFrame], margin: f64) -> Vec<NearBone> {
        let low = parts.iter().map(|p| p.center.z - p.half.z).fold(f64::INFINITY, f64::min);
        let high = parts.iter().map(|p| p.center.z + p.half.z).fold(f64::NEG_INFINITY, f64::max);
        let lo = (min - self.reach).extend(low - self.reach - CLEARANCE - margin);
        let hi = (max + self.reach).extend(high + self.reach + CLEARANCE + margin);
        let inside = |c: DVec3| c.cmpge(lo).all() && c.cmple(hi).all();
        let mut out = Vec::new();
        for row in &self.rows {
            let far = row.a.min(row.b).cmpgt(hi).any() || row.a.max(row.b).cmplt(lo).any();
            if far || parts.iter().all(|p| row.clearance_from(p) > margin) {
                continue;
            }
            let balls = self.balls[row.range.clone()].iter();
            let balls: Vec<Ball> =
                balls.filter(|b| inside(b.center) && deepest_part(parts, b) > -margin).copied().collect();
            if !balls.is_empty() {
                out.push(NearBone { a: row.a, b: row.b, radius: row.radius, weight: row.weight, balls });
            }
        }
        out
    }
}

/// One bone at one sampled frame near a piece: its axis `a`..`b`, radius, and the balls of it that
/// may cost.
#[derive(Debug, Clone)]
struct NearBone {
    a: DVec3,
    b: DVec3,
    radius: f64,
    weight: f64,
    balls: Vec<Ball>,
}

impl NearBone {
    /// How far the bone reaches within [`CLEARANCE`] of `part`: its deepest ball's reach, or where
    /// it passes through a part that is not a seat from below its bottom to above its top (a leg
    /// through a table's top), how far the part must move sideways to let it out, plus its radius
    /// and the clearance — the capsule's depth, as the check measures it. The balls in a 4 cm top
    /// are only as deep as the top is thin wherever the table stands, and their one slope, up or
    /// down, moves the top along the leg: J_p could not push a table off a person standing in it.
    fn reach(&self, part: &PartFrame) -> f64 {
        let balls = self.balls.iter().map(|ball| ball_depth(part, ball)).fold(f64::NEG_INFINITY, f64::max);
        let through = if part.seat { None } else { sideways_depth(part, self.a, self.b) };
        through.map_or(balls, |depth| balls.max(self.radius + CLEARANCE + depth))
    }
}

/// Where the segment `a`..`b` passes through `part`'s box from below its bottom to above its top:
/// the least horizontal distance the box must move for the segment to pass beside it (`None`
/// where it does not pass through, or passes beside already). Exact: the separating axes of the
/// box's footprint and the segment's piece within the box's heights, projected on the floor.
fn sideways_depth(part: &PartFrame, a: DVec3, b: DVec3) -> Option<f64> {
    let (a, b, h) = (part.to_local(a), part.to_local(b), part.half);
    if !(a.z.min(b.z) < -h.z && a.z.max(b.z) > h.z) {
        return None;
    }
    let at = |z: f64| a.lerp(b, (z - a.z) / (b.z - a.z)).truncate();
    let (p, q) = (at(-h.z), at(h.z));
    let along = q - p;
    let mut depth = f64::INFINITY;
    for n in [DVec2::X, DVec2::Y, along.perp()] {
        let length = n.length();
        if length < 1e-9 {
            continue;
        }
        let n = n / length;
        let (pp, pq) = (n.dot(p), n.dot(q));
        let r = n.abs().dot(h.truncate());
        let overlap = (pp.max(pq) + r).min(r - pp.min(pq));
        if overlap <= 0.0 {
            return None;
        }
        depth = depth.min(overlap);
    }
    Some(depth)
}

/// The balls of a capsule from `a` to `b`: centres on the segment, no more than half the radius
/// apart, ends included.
fn balls_along(a: DVec3, b: DVec3, radius: f64) -> impl Iterator<Item = Ball> {
    let gaps = (a.distance(b) / (0.5 * radius)).ceil().max(1.0) as usize;
    (0..=gaps).map(move |i| Ball { center: a.lerp(b, i as f64 / gaps as f64), radius })
}

/// One distinct pose of a human among its sampled frames: its joints, how many sampled frames
/// hold exactly these joints, and whether one of them is a contact span's middle.
struct Pose {
    joints: Vec<DVec3>,
    weight: f64,
    contact: bool,
}

/// `frames` of `human` with exact repeats (a person held still, a clip looped) folded into the
/// first frame of their pose, in frame order.
fn distinct_poses(human: &Human, frames: Vec<usize>) -> Vec<Pose> {
    let middles: Vec<usize> = contact_middles(human).collect();
    let mut poses: Vec<Pose> = Vec::new();
    // A pose's coordinates as bits (−0 as 0, so that equal numbers are one key) → its index.
    let mut seen: HashMap<Vec<u64>, usize> = HashMap::new();
    for f in frames {
        let joints: Vec<DVec3> = human.frame(f).collect();
        let key = joints.iter().flat_map(|p| p.to_array()).map(|x| (x + 0.0).to_bits()).collect();
        let contact = middles.contains(&f);
        match seen.get(&key) {
            Some(&k) => {
                poses[k].weight += 1.0;
                poses[k].contact |= contact;
            }
            None => {
                seen.insert(key, poses.len());
                poses.push(Pose { joints, weight: 1.0, contact });
            }
        }
    }
    poses
}

/// The frames of `human` J_p looks at: the first and the last, each one where some joint has moved
/// [`STRIDE`] since the previous one taken, and the middle of each contact span.
fn sampled_frames(human: &Human) -> Vec<usize> {
    let n = human.frames.len();
    if n == 0 {
        return Vec::new();
    }
    let mut frames = vec![0];
    let mut last: Vec<DVec3> = human.frame(0).collect();
    for f in 1..n {
        let joints: Vec<DVec3> = human.frame(f).collect();
        if f == n - 1 || joints.iter().zip(&last).any(|(p, q)| p.distance(*q) >= STRIDE) {
            frames.push(f);
            last = joints;
        }
    }
    frames.extend(contact_middles(human));
    frames.sort_unstable();
    frames.dedup();
    frames
}

/// The middle frame of each of `human`'s contact spans.
fn contact_middles(human: &Human) -> impl Iterator<Item = usize> + '_ {
    let last = human.frames.len().saturating_sub(1);
    human.contact_spans().map(move |s| ((s.start + s.end) / 2).min(last))
}

/// A template part ready for many distance queries: its box's rotation computed once (the cost's
/// hot loop tests every nearby ball against every part, and recomputing the yaw's sine and cosine
/// per test took half of `generate`'s time on crowded inputs).
#[derive(Debug, Clone, Copy)]
struct PartFrame {
    center: DVec3,
    /// The box's yaw as (cos, sin).
    rotation: DVec2,
    half: DVec3,
    seat: bool,
}

impl PartFrame {
    fn of(part: &Part) -> PartFrame {
        let (s, c) = part.obox.yaw.sin_cos();
        PartFrame {
            center: part.obox.center,
            rotation: DVec2::new(c, s),
            half: part.obox.half(),
            seat: part.role == PartRole::Seat,
        }
    }

    /// `p` in the box's frame (as `OBox::to_local`).
    fn to_local(self, p: DVec3) -> DVec3 {
        let d = p - self.center;
        let (c, s) = (self.rotation.x, self.rotation.y);
        DVec3::new(c * d.x + s * d.y, -s * d.x + c * d.y, d.z)
    }
}

/// The parts of `o`'s template, ready for distance queries.
fn part_frames(o: &GuidedObject) -> Vec<PartFrame> {
    template_of(o.category, &o.obox()).parts.iter().map(PartFrame::of).collect()
}

/// How far `ball` reaches within [`CLEARANCE`] of the piece's template parts (negative: how far it
/// stays beyond).
fn deepest_part(parts: &[PartFrame], ball: &Ball) -> f64 {
    parts.iter().map(|part| ball_depth(part, ball)).fold(f64::NEG_INFINITY, f64::max)
}

/// J_p of one piece against `bones`: Σ over bones of how far they reach within [`CLEARANCE`] of
/// its template ([`NearBone::reach`]) — one term per bone, frame and piece, so a long bone along a
/// surface counts no more than a short one.
fn piece_cost(o: &GuidedObject, bones: &[NearBone]) -> f64 {
    let parts = part_frames(o);
    bones.iter().map(|bone| bone.weight * parts.iter().map(|p| bone.reach(p)).fold(0.0, f64::max)).sum()
}

/// How deep `ball` reaches into `part` plus [`CLEARANCE`] (negative when further apart): its
/// radius less its centre's distance to the part, or plus its centre's depth inside. A seat (a
/// bed's mattress, a sofa's seat block, a stool's seat) is left through its top or sides only, and
/// a ball on or in it from above needs no clearance: a body rests on a seat, so a sitter's thighs
/// inside a seat too high ask for a lower seat by their depth, not one pushed up through them.
fn ball_depth(part: &PartFrame, ball: &Ball) -> f64 {
    let l = part.to_local(ball.center);
    let (h, seat) = (part.half, part.seat);
    let outside = (l.abs() - h).max(DVec3::ZERO);
    if outside != DVec3::ZERO {
        let resting = seat && outside.x == 0.0 && outside.y == 0.0 && l.z > 0.0;
        return ball.radius - outside.length() + if resting { 0.0 } else { CLEARANCE };
    }
    let sides = (h.x - l.x.abs()).min(h.y - l.y.abs());
    let (top, bottom) = (h.z - l.z, h.z + l.z);
    match seat {
        true if top <= sides => ball.radius + top,
        true => ball.radius + CLEARANCE + sides,
        false => ball.radius + CLEARANCE + sides.min(top).min(bottom),
    }
}

/// Σ over pieces of J_p, with central-difference gradients (centre x, y, size, yaw; the height of a
/// standing piece follows its size).
pub fn body_penetration(objects: &[GuidedObject], bodies: &BodyBalls) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        if o.hanging {
            continue;
        }
        let reach = DVec2::splat(o.size.x.hypot(o.size.y) * 0.5 + 0.01);
        let c = o.center.truncate();
        // Only balls within a few millimetres of costing can change the cost as the gradient's
        // central differences move the piece.
        let bones = bodies.near(c - reach, c + reach, &part_frames(o), DIFFERENCE_MARGIN);
        let cost = piece_cost(o, &bones);
        if cost <= 0.0 {
            continue;
        }
        total += cost;
        *g = central_differences(o, |moved| piece_cost(moved, &bones));
    }
    (total, grads)
}

/// Where a person needs support: the centre of their contact box and the height the piece's top
/// must reach (a sitter's or sleeper's box top, the body's lowest point; a toucher's palm).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportNeed {
    /// The contact box's centre on the floor.
    pub at: DVec2,
    /// The height the top of the piece under `at` must reach.
    pub height: f64,
}

/// The top (m) of the highest part of a piece over `need.at`, if any part is over it.
fn top_over(o: &GuidedObject, need: &SupportNeed) -> Option<f64> {
    template_of(o.category, &o.obox())
        .parts
        .iter()
        .filter(|p| p.obox.footprint_contains(need.at))
        .map(|p| p.obox.z_range().1)
        .reduce(f64::max)
}

/// J_s of one piece: how far the top of its highest part over `need.at` stays below `need.height`
/// beyond [`SUPPORT_TOLERANCE`] (0 where no part is over it: J_c's business).
fn support_gap(o: &GuidedObject, need: &SupportNeed) -> f64 {
    top_over(o, need).map_or(0.0, |top| (need.height - SUPPORT_TOLERANCE - top).max(0.0))
}

/// Σ over anchored pieces of J_s; `needs[i]` is what piece i's sitters, sleepers and touchers need
/// (none for free pieces). Gradients as [`body_penetration`]'s, except that a piece too low is
/// always asked to grow: a template holds a seat at its least height below some piece height
/// (a chair's seat is 0.35 m for any chair under 0.67 m, a sofa's 0.28 m under 0.56 m), where
/// the seat's slope is zero and J_s would leave the sitter unsupported (val living rooms: 24 of
/// 112 samples of 28 rooms). No part's top falls as a piece grows taller, so where the template's
/// slope is less, J_s takes it as if the top scaled with the piece (top / height).
pub fn support_shortfall(objects: &[GuidedObject], needs: &[Vec<SupportNeed>]) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for ((o, needs), g) in objects.iter().zip(needs).zip(&mut grads) {
        let gap = |o: &GuidedObject| needs.iter().map(|need| support_gap(o, need)).sum::<f64>();
        let here = gap(o);
        if here <= 0.0 {
            continue;
        }
        total += here;
        *g = central_differences(o, gap);
        let scaled: f64 = needs
            .iter()
            .filter_map(|need| top_over(o, need).filter(|top| need.height - SUPPORT_TOLERANCE - top > 0.0))
            .map(|top| top / o.size.z)
            .sum();
        g[5] = g[5].min(-scaled);
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
            let mut moved = o.nudged(k, delta);
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
    fn sitter(seat: f64) -> BodyBalls {
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(sit(&body, DVec2::new(0.0, -0.05), seat, 0.0), 4, Action::Sit);
        BodyBalls::of(&[m.into_human("h0")])
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
    fn many_people_are_thinned_to_a_bounded_number_of_frames_keeping_their_contact_frames() {
        let body = Body::default();
        // Each sitter slides 20 cm a frame over 4 frames: 4 distinct poses, one contact span.
        let sitters = |n: usize| -> Vec<Human> {
            (0..n)
                .map(|k| {
                    let mut m = Motion::new(body, 30.0);
                    for f in 0..4 {
                        m.hold(sit(&body, DVec2::new(k as f64, 0.2 * f as f64), 0.45, 0.0), 1, Action::Sit);
                    }
                    m.into_human(format!("h{k}"))
                })
                .collect()
        };
        let per_frame = BodyBalls::of(&sitters(1)).len() / 4;
        assert_eq!(BodyBalls::of(&sitters(100)).len(), 100 * 4 * per_frame, "400 frames: all kept");
        // 600 × 4 = 2,400 frames: every 5th kept (frame 0) and the span's middle (frame 2).
        assert_eq!(BodyBalls::of(&sitters(600)).len(), 600 * 2 * per_frame);
    }

    #[test]
    fn a_pose_held_or_looped_is_tested_once_and_counted_for_each_frame_sampled() {
        let body = Body::default();
        let pose = sit(&body, DVec2::new(0.0, -0.05), 0.45, 0.0);
        let held = |frames: usize| {
            let mut m = Motion::new(body, 30.0);
            m.hold(pose, frames, Action::Sit);
            BodyBalls::of(&[m.into_human("h0")])
        };
        // Held for 4 frames, the pose is sampled at frames 0, 2 (the span's middle) and 3.
        let (once, thrice) = (held(1), held(4));
        assert_eq!(thrice.len(), once.len(), "one pose's balls");
        let (single, triple) = (body_penetration(&[stool(0.55)], &once), body_penetration(&[stool(0.55)], &thrice));
        assert!(single.0 > 0.005);
        assert_eq!(triple.0, 3.0 * single.0);
        // A clip looped three times (sit, stand, sit, stand, ...) holds two poses.
        let stand = crate::human::stand(&body, DVec2::new(0.0, 0.6), 0.0);
        let mut m = Motion::new(body, 30.0);
        for _ in 0..3 {
            m.hold(pose, 1, Action::Sit).hold(stand, 1, Action::Stand);
        }
        let looped = BodyBalls::of(&[m.into_human("h0")]);
        let mut m = Motion::new(body, 30.0);
        m.hold(pose, 1, Action::Sit).hold(stand, 1, Action::Stand);
        assert_eq!(looped.len(), BodyBalls::of(&[m.into_human("h0")]).len());
    }

    #[test]
    fn a_seat_under_its_sitter_costs_nothing_and_a_high_one_is_lowered() {
        let bodies = sitter(0.45);
        assert!(body_penetration(&[stool(0.45)], &bodies).0 < 1e-9);
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
    fn a_row_of_balls_is_as_deep_as_the_checks_capsule() {
        use crate::physics::Owner;
        use crate::sim::{Solid, capsule_depth};
        let wardrobe = GuidedObject {
            center: DVec3::new(0.0, 0.0, 1.0),
            size: DVec3::new(1.2, 0.6, 2.0),
            yaw: 0.3,
            hanging: false,
            category: Category::Wardrobe,
        };
        let parts = template_of(wardrobe.category, &wardrobe.obox()).parts;
        let solids: Vec<Solid> = parts.iter().map(|p| Solid::new(Owner::Object(0), p.obox)).collect();
        let mut compared = 0;
        for i in 0..200 {
            // Shins and thighs (radius 5–7 cm) at spread positions and slants around the front face.
            let t = i as f64 * 0.61803;
            let a = DVec3::new((t * 7.0).sin() * 0.7, (t * 3.0).cos() * 0.45, 0.1 + (t * 5.0).sin().abs() * 1.5);
            let b = a + DVec3::new((t * 11.0).cos() * 0.3, 0.25, (t * 13.0).sin() * 0.3);
            let radius = 0.05 + 0.02 * (t * 17.0).sin().abs();
            let check = solids.iter().map(|s| capsule_depth(a, b, radius, s)).fold(0.0, f64::max);
            let frames: Vec<PartFrame> = parts.iter().map(PartFrame::of).collect();
            let balls =
                balls_along(a, b, radius).map(|ball| deepest_part(&frames, &ball) - CLEARANCE).fold(0.0, f64::max);
            // The row's union lies inside the capsule: never deeper than it.
            assert!(balls <= check + 1e-4, "{i}: balls {balls}, capsule {check}");
            // While the bone's axis is outside the piece, at distance d = radius − depth, the check's
            // depth is the radius less d, and the row of balls (spaced ≤ radius / 2) misses at most
            // √(d² + (radius / 4)²) − d of it, where the axis passes the piece's nearest point between
            // two balls. Deeper, the check measures how far the whole capsule must move to get out.
            if check > 0.0 && check < radius {
                compared += 1;
                let d = radius - check;
                let miss = (d * d + radius * radius / 16.0).sqrt() - d;
                assert!(balls >= check - miss - 1e-4, "{i}: balls {balls}, capsule {check}");
            }
        }
        assert!(compared > 20, "only {compared} capsules grazed the wardrobe");
    }

    #[test]
    fn a_bone_through_a_tables_top_is_as_deep_as_the_checks_capsule() {
        use crate::physics::Owner;
        use crate::sim::{Solid, capsule_depth};
        let table = GuidedObject::standing(Category::DiningTable, 0.1, -0.2, [1.6, 0.8, 0.75], 0.4);
        let parts = template_of(table.category, &table.obox()).parts;
        let top = parts.iter().find(|p| p.role == PartRole::Top).unwrap();
        let (frame, solid) = (PartFrame::of(top), Solid::new(Owner::Object(0), top.obox));
        let mut through = 0;
        for i in 0..200 {
            // Bones from the floor's height to above the top, every fourth vertical, at spread
            // places over the table: going up or down is further out of the top than sideways.
            let t = i as f64 * 0.61803;
            let a = DVec3::new((t * 7.0).sin() * 0.9, (t * 3.0).cos() * 0.6 - 0.2, (t * 5.0).sin().abs() * 0.2);
            let lean = if i % 4 == 0 { 0.0 } else { 0.2 };
            let b = a + DVec3::new((t * 11.0).cos() * lean, (t * 13.0).sin() * lean, 1.3);
            let radius = 0.05 + 0.02 * (t * 17.0).sin().abs();
            let bone = NearBone { a, b, radius, weight: 1.0, balls: balls_along(a, b, radius).collect() };
            if sideways_depth(&frame, a, b).is_none() {
                continue;
            }
            through += 1;
            let check = capsule_depth(a, b, radius, &solid);
            let reach = bone.reach(&frame) - CLEARANCE;
            // Sideways is the way out of the top for a vertical bone; a slanted one may leave it a
            // little sooner along a tilted direction, which the floor's projection does not see.
            let slant = (b - a).truncate().length() / (b - a).length();
            assert!(reach > check - 2e-3 && reach < check + 2e-3 + 0.03 * slant, "{i}: reach {reach}, capsule {check}");
            // Its balls alone are only as deep as the top is thin.
            let balls = bone.balls.iter().map(|ball| ball_depth(&frame, ball)).fold(0.0, f64::max) - CLEARANCE;
            assert!(balls < radius + top.obox.half().z + 1e-9, "{i}: balls {balls}");
        }
        assert!(through > 40, "only {through} bones passed through the top");
        // A bone beside the top, or standing on the floor under it, does not pass through.
        let beside = DVec3::new(2.0, 2.0, 0.0);
        assert_eq!(sideways_depth(&frame, beside, beside + DVec3::Z * 1.3), None);
        assert_eq!(sideways_depth(&frame, table.center.with_z(0.0), table.center.with_z(0.5)), None);
    }

    #[test]
    fn a_table_over_a_standing_persons_legs_is_pushed_off_them() {
        use crate::human::stand;
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(stand(&body, DVec2::ZERO, 0.0), 2, Action::Stand);
        let bodies = BodyBalls::of(&[m.into_human("h0")]);
        // A dining table whose near edge is 25 cm past the person's centre line: the thighs cross
        // its top. The balls in the 4 cm top were as deep as it is thin wherever the table stood;
        // the capsules are as deep as the edge is far, so the table is pushed off along x.
        let table = |x: f64| GuidedObject::standing(Category::DiningTable, x, 0.0, [1.6, 0.9, 0.75], 0.0);
        let (cost, grads) = body_penetration(&[table(0.55)], &bodies);
        assert!(cost > 0.2, "{cost}");
        assert!(grads[0][0] < -0.5, "∂J/∂x {}", grads[0][0]);
        let (nearer, _) = body_penetration(&[table(0.65)], &bodies);
        assert!(nearer < cost - 0.05, "{nearer} against {cost}");
    }

    #[test]
    fn bones_are_kept_clear_of_pieces_except_on_a_seats_top() {
        let bodies = sitter(0.45);
        // The front of the sitter's shins and feet (their balls' furthest reach along +y).
        let front = bodies.balls.iter().map(|b| b.center.y + b.radius).fold(f64::MIN, f64::max);
        // A wardrobe 5 mm in front of them costs (clearance); 2 cm away, nothing.
        let near = GuidedObject {
            center: DVec3::new(0.0, front + 0.005 + 0.3, 1.0),
            size: DVec3::new(1.0, 0.6, 2.0),
            yaw: 0.0,
            hanging: false,
            category: Category::Wardrobe,
        };
        let mut far = near;
        far.center.y += 0.015;
        let (cost, _) = body_penetration(&[near], &bodies);
        assert!(cost > 0.0, "{cost}");
        assert_eq!(body_penetration(&[far], &bodies).0, 0.0);
        // A seat 5 mm under the sitter's resting thighs costs nothing: no clearance on a seat's top.
        assert!(body_penetration(&[stool(0.445)], &bodies).0 < 1e-9);
    }

    #[test]
    fn a_low_seat_is_raised_towards_its_sitter() {
        let need = SupportNeed { at: DVec2::ZERO, height: 0.45 };
        // A stool's seat is its top: 10 cm short costs 8 cm (2 cm are tolerated); 1 cm short nothing.
        let (gap, grads) = support_shortfall(&[stool(0.35)], &[vec![need]]);
        assert!((gap - 0.08).abs() < 1e-9, "{gap}");
        assert!(grads[0][5] < -0.9, "growing it closes the gap: {}", grads[0][5]);
        assert_eq!(support_shortfall(&[stool(0.44)], &[vec![need]]).0, 0.0);
        // Nothing of it under the box, or a free piece: J_c's business, not this term's.
        let mut beside = stool(0.35);
        beside.center.x += 1.0;
        assert_eq!(support_shortfall(&[beside], &[vec![need]]).0, 0.0);
        assert_eq!(support_shortfall(&[stool(0.35)], &[vec![]]).0, 0.0);
    }

    #[test]
    fn a_chair_whose_seat_the_template_holds_at_its_least_height_is_still_raised() {
        // A 0.65 m dining chair: its seat is 0.35 m (the template's least), as for any chair
        // under 0.67 m, so the seat's own slope is zero; a sitter needs 0.415 m.
        let chair = |h: f64| GuidedObject::standing(Category::DiningChair, 0.0, 0.0, [0.47, 0.52, h], 0.0);
        let need = SupportNeed { at: DVec2::new(0.0, 0.05), height: 0.415 };
        let (gap, g) = support_shortfall(&[chair(0.65)], &[vec![need]]);
        assert!((gap - 0.045).abs() < 1e-9, "{gap}");
        // Asked to grow at the seat's share of the chair's height, 0.35 / 0.65.
        assert!((g[0][5] + 0.35 / 0.65).abs() < 1e-9, "{:?}", g[0]);
        // Above 0.67 m the template's own slope, 0.52, is used.
        let (_, g) = support_shortfall(&[chair(0.72)], &[vec![need]]);
        assert!((g[0][5] + 0.52).abs() < 1e-6, "{:?}", g[0]);
    }

    #[test]
    fn the_balls_near_a_piece_give_the_cost_and_gradient_of_all_balls() {
        use crate::human::{lie, stand};
        let body = Body::default();
        let mut m = Motion::new(body, 30.0);
        m.hold(sit(&body, DVec2::new(0.0, -0.05), 0.45, 0.0), 3, Action::Sit);
        m.hold(lie(&body, DVec2::new(0.3, 0.2), 0.5, 0.7), 3, Action::Lie);
        m.hold(stand(&body, DVec2::new(-0.4, 0.5), 2.0), 3, Action::Stand);
        let bodies = BodyBalls::of(&[m.into_human("h0")]);
        // Every ball that may cost, bone by bone, with no window and no test of whole rows.
        let brute = |o: &GuidedObject| -> (f64, ObjectGradient) {
            let parts = part_frames(o);
            let bones: Vec<NearBone> = bodies
                .rows
                .iter()
                .filter_map(|row| {
                    let balls: Vec<Ball> = bodies.balls[row.range.clone()]
                        .iter()
                        .filter(|b| deepest_part(&parts, b) > -DIFFERENCE_MARGIN)
                        .copied()
                        .collect();
                    (!balls.is_empty()).then_some(NearBone {
                        a: row.a,
                        b: row.b,
                        radius: row.radius,
                        weight: row.weight,
                        balls,
                    })
                })
                .collect();
            let cost = piece_cost(o, &bones);
            (cost, if cost > 0.0 { central_differences(o, |moved| piece_cost(moved, &bones)) } else { [0.0; 7] })
        };
        let mut costly = 0;
        for i in 0..120 {
            let t = i as f64 * 0.618034;
            let category = [Category::DoubleBed, Category::Chair, Category::Wardrobe, Category::Sofa][i % 4];
            let size =
                DVec3::new(0.5 + (t * 3.0).sin().abs() * 1.5, 0.5 + (t * 5.0).cos().abs(), 0.4 + (t * 7.0).sin().abs());
            let piece = GuidedObject {
                center: DVec3::new((t * 11.0).sin() * 0.8, (t * 13.0).cos() * 0.8, size.z * 0.5),
                size,
                yaw: t * 2.0,
                hanging: false,
                category,
            };
            let (cost, grads) = body_penetration(&[piece], &bodies);
            let (want, want_grads) = brute(&piece);
            assert_eq!((cost, grads[0]), (want, want_grads), "{i}: {category:?}");
            costly += usize::from(cost > 0.0);
        }
        assert!(costly > 40, "only {costly} placements touched a body");
    }
}
