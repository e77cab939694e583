//! Wall distances for the attention-free part of the denoiser: how far each noisy object slot's
//! centre is from the floor plan's walls along its own four axes.
//!
//! With `wall_features` on (see [`ModelConfig::wall_features`]), every object token gets a learned
//! embedding of four numbers computed on the host from the noisy tokens and the floor-plan points
//! the model is conditioned on: the distance from the slot's centre to the nearest wall ahead of
//! it along +x, −x, +y and −y of its own frame (anchored slots taken to world form first, see
//! [`super::anchors`]). The floor plan otherwise reaches the model only as one pooled PointNet
//! vector, which cannot say to within centimetres where a wall is; a bed's headboard then sits
//! 10 cm inside the wall. With the distance in hand, "back against the wall" is a linear function
//! of the token (distance − half depth), which the first layer can compute exactly.
//!
//! A wall is the line through a floor-plan point along its edge (the point's outward normal is
//! the line's normal); a ray meets it where the line crosses the ray, if the point is within
//! [`LATERAL_REACH`] of the ray (so that a wall elsewhere in the room, on the same line, is not
//! taken) and its normal faces the ray's direction. Distances are in token units (positions are
//! scaled like object centres), clamped to [−[`BEHIND`], [`FAR`]]. Not here: the embedding (both
//! engines) and the floor-plan points themselves ([`super::features`]).

use super::ModelConfig;
use super::config::FLOOR_FEATURES;
use super::relations::{self, TokenPose};

/// Features per object slot: the distances along its +x, −x, +y and −y.
pub const WALL_FEATURES: usize = 4;

/// How far (token units) a wall point may lie beside a ray and still count as the wall it meets.
pub const LATERAL_REACH: f32 = 0.1;

/// Distances beyond this (token units) read as this: nothing near that way.
pub const FAR: f32 = 1.0;

/// How far (token units) a centre may be beyond a wall it faces (a slot outside the room while
/// noisy) and still measure it, as a negative distance.
pub const BEHIND: f32 = 0.25;

/// The wall features of one item's object slots (`tokens`, the model's frame) in the room of its
/// floor-plan points (`floor`, `floor_points × 4`): `slots × WALL_FEATURES`, row-major.
pub fn slot_features(cfg: &ModelConfig, tokens: &[f32], contacts: &[f32], mask: &[f32], floor: &[f32]) -> Vec<f32> {
    let poses = relations::poses(cfg, tokens, contacts, mask, false);
    let mut out = Vec::with_capacity(cfg.slots() * WALL_FEATURES);
    for pose in &poses[..cfg.slots()] {
        out.extend(distances(pose, floor));
    }
    out
}

/// The four distances of one pose.
fn distances(pose: &TokenPose, floor: &[f32]) -> [f32; WALL_FEATURES] {
    let (c, s) = (pose.cos, pose.sin);
    [(c, s), (-c, -s), (-s, c), (s, -c)].map(|dir| along(pose.x, pose.y, dir, floor))
}

/// Distance from (x, y) along unit `dir` to the nearest wall it meets.
fn along(x: f32, y: f32, (dx, dy): (f32, f32), floor: &[f32]) -> f32 {
    let mut best = FAR;
    for point in floor.chunks_exact(FLOOR_FEATURES) {
        let (px, py, nx, ny) = (point[0] - x, point[1] - y, point[2], point[3]);
        let facing = nx * dx + ny * dy;
        if facing < 0.5 {
            continue;
        }
        let (ahead, beside) = (px * dx + py * dy, px * dy - py * dx);
        // The line {q : n·(q − p) = 0} meets the ray at t = n·p / n·dir; the point must lie
        // within LATERAL_REACH of where it does.
        let t = (nx * px + ny * py) / facing;
        if t < -BEHIND || (t - ahead).hypot(beside) > LATERAL_REACH {
            continue;
        }
        best = best.min(t);
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The points of a square room [−0.5, 0.5]² (token units) with outward normals, 10 per side.
    fn square() -> Vec<f32> {
        let mut v = Vec::new();
        for i in 0..10 {
            let a = -0.5 + (i as f32 + 0.5) / 10.0;
            v.extend([a, -0.5, 0.0, -1.0, 0.5, a, 1.0, 0.0, -a, 0.5, 0.0, 1.0, -0.5, -a, -1.0, 0.0]);
        }
        v
    }

    #[test]
    fn distances_in_a_square_room_are_hand_computed() {
        let floor = square();
        // Centre (0.2, 0.1) facing +x: 0.3 ahead, 0.7 behind, 0.4 to its left (+y), 0.6 right.
        let pose = TokenPose::new(0.2, 0.1, 1.0, 0.0);
        let d = distances(&pose, &floor);
        for (got, want) in d.iter().zip([0.3, 0.7, 0.4, 0.6]) {
            assert!((got - want).abs() < 1e-5, "{d:?}");
        }
        // Facing +y: ahead is +y (0.4), behind −y (0.6), left is −x (0.7), right +x (0.3).
        let pose = TokenPose::new(0.2, 0.1, 0.0, 1.0);
        let d = distances(&pose, &floor);
        for (got, want) in d.iter().zip([0.4, 0.6, 0.7, 0.3]) {
            assert!((got - want).abs() < 1e-5, "{d:?}");
        }
        // Facing 45°: the ray along (1, 1)/√2 from the centre meets x = 0.5 first, at 0.3·√2.
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let d = distances(&TokenPose::new(0.2, 0.1, h, h), &floor);
        assert!((d[0] - 0.3 * 2f32.sqrt()).abs() < 1e-4, "{d:?}");
    }

    #[test]
    fn a_centre_beyond_a_wall_reads_a_negative_distance_and_far_walls_read_far() {
        let floor = square();
        // 0.1 beyond x = 0.5: the wall ahead is 0.1 behind the centre.
        let d = distances(&TokenPose::new(0.6, 0.0, 1.0, 0.0), &floor);
        assert!((d[0] + 0.1).abs() < 1e-5, "{d:?}");
        // A big room: nothing within FAR.
        let big: Vec<f32> = square().chunks_exact(4).flat_map(|p| [p[0] * 5.0, p[1] * 5.0, p[2], p[3]]).collect();
        assert_eq!(distances(&TokenPose::new(0.0, 0.0, 1.0, 0.0), &big), [FAR; 4]);
    }

    #[test]
    fn a_wall_on_the_same_line_elsewhere_is_not_taken() {
        // An L-shaped room: [−0.5, 0.5] × [−0.5, 0] plus [−0.5, 0] × [0, 0.5]. Its wall y = 0
        // (x in [0, 0.5]) faces +y; a centre at (−0.25, 0.25) looking +y meets y = 0.5 (0.25
        // away), not the line y = 0 behind it, and looking +x meets x = 0 (0.25 away).
        let mut floor = Vec::new();
        for i in 0..10 {
            let a = (i as f32 + 0.5) / 20.0;
            floor.extend([a, 0.0, 0.0, 1.0]); // y = 0 for x in [0, 0.5], outward +y
            floor.extend([0.0, a, 1.0, 0.0]); // x = 0 for y in [0, 0.5], outward +x
            floor.extend([-0.5 + a, 0.5, 0.0, 1.0]); // y = 0.5 for x in [−0.5, 0]
        }
        let d = distances(&TokenPose::new(-0.25, 0.25, 0.0, 1.0), &floor);
        assert!((d[0] - 0.25).abs() < 1e-5, "{d:?}");
        assert!((d[3] - 0.25).abs() < 1e-5, "{d:?}");
    }
}
