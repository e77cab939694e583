//! Pairwise relations for the attention: where each token is relative to each other one.
//!
//! With `relation_bias` on (see [`ModelConfig::relation_bias`]), every attention score between
//! two tokens i and j gets a learned bias per head, a small MLP of their relation: j's position in
//! i's frame (2), j's yaw relative to i's (cos, sin) and their distance — 5 features, computed on
//! the host from the noisy object tokens (anchored slots taken to world form first, see
//! [`super::anchors`]) and the contact boxes. A transformer that sees only absolute positions must
//! learn rotations and differences to put a nightstand beside a bed's head; this hands it the
//! relation directly. Not here: the MLP itself (both engines) and the attention.
//!
//! With `relation_values` on ([`ModelConfig::relation_values`]), the pairs' [`value_features`]
//! also reach what a token takes from the others: head h of token i adds W_h Σ_j p_ij f_ij to its
//! attention output, a learned linear map of the relations weighed by its own attention weights.

use super::config::CONTACT_FEATURES;
use super::{ModelConfig, anchors};

/// Features of one ordered pair of tokens.
pub const RELATION_FEATURES: usize = 5;

/// Value features of one ordered pair: [`pair_features`]' five, then how far j is from i along
/// each of i's axes whichever side it is on (|x|, |y| in i's frame).
pub const RELATION_VALUE_FEATURES: usize = 7;

/// Where a token is: position (token units, relative to the window centre) and unit yaw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TokenPose {
    pub(super) x: f32,
    pub(super) y: f32,
    pub(super) cos: f32,
    pub(super) sin: f32,
}

impl TokenPose {
    pub(super) fn new(x: f32, y: f32, cos: f32, sin: f32) -> TokenPose {
        let norm = (cos * cos + sin * sin).sqrt();
        let (cos, sin) = if norm > 1e-3 { (cos / norm, sin / norm) } else { (1.0, 0.0) };
        TokenPose { x, y, cos, sin }
    }
}

/// The poses of one item's tokens: its object slots (from `tokens`, one item's slots in the
/// model's frame), then its contact boxes — every one when `padded`, else only the real ones (the
/// rows the fused engine keeps).
pub fn poses(cfg: &ModelConfig, tokens: &[f32], contacts: &[f32], mask: &[f32], padded: bool) -> Vec<TokenPose> {
    let dim = cfg.token_dim();
    let mut world = tokens.to_vec();
    anchors::to_world(cfg, contacts, mask, &mut world);
    let mut poses: Vec<TokenPose> = world.chunks_exact(dim).map(|t| TokenPose::new(t[0], t[1], t[6], t[7])).collect();
    for (row, &m) in contacts.chunks_exact(CONTACT_FEATURES).zip(mask) {
        if padded || m != 0.0 {
            poses.push(TokenPose::new(row[0], row[1], row[6], row[7]));
        }
    }
    poses
}

/// The features of every ordered pair (i, j) of `poses`, row-major over i then j
/// (n² × [`RELATION_FEATURES`]).
pub fn pair_features(poses: &[TokenPose]) -> Vec<f32> {
    let mut out = Vec::with_capacity(poses.len() * poses.len() * RELATION_FEATURES);
    for a in poses {
        for b in poses {
            let (dx, dy) = (b.x - a.x, b.y - a.y);
            out.extend([
                a.cos * dx + a.sin * dy,
                -a.sin * dx + a.cos * dy,
                a.cos * b.cos + a.sin * b.sin,
                a.cos * b.sin - a.sin * b.cos,
                (dx * dx + dy * dy).sqrt(),
            ]);
        }
    }
    out
}

/// The value features of every ordered pair (i, j) of `poses`, row-major over i then j
/// (n² × [`RELATION_VALUE_FEATURES`]). A nightstand beside its bed's either side, or a chair at
/// either end of its table, is as far along the axis on both sides: the sign says which side, the
/// magnitude how far, and a linear map of the two can say "4 cm beside it" for both.
pub fn value_features(poses: &[TokenPose]) -> Vec<f32> {
    pair_features(poses)
        .chunks_exact(RELATION_FEATURES)
        .flat_map(|f| [f[0], f[1], f[2], f[3], f[4], f[0].abs(), f[1].abs()])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_relations() {
        // a at the origin facing +y (yaw 90°), b at (1, 1) facing −x (yaw 180°).
        let a = TokenPose::new(0.0, 0.0, 0.0, 2.0);
        let b = TokenPose::new(1.0, 1.0, -1.0, 0.0);
        let f = pair_features(&[a, b]);
        // (a, a): nothing apart, same yaw.
        assert_eq!(&f[..5], &[0.0, 0.0, 1.0, 0.0, 0.0]);
        // (a, b): b is 1 ahead of a (local +x is world +y) and 1 to its right (local y = −1);
        // b's yaw is 90° more than a's.
        let ab = &f[5..10];
        for (got, want) in ab.iter().zip([1.0, -1.0, 0.0, 1.0, 2f32.sqrt()]) {
            assert!((got - want).abs() < 1e-6, "{ab:?}");
        }
        // (b, a): a is 1 ahead of b and 1 to its left; a's yaw 90° less.
        let ba = &f[10..15];
        for (got, want) in ba.iter().zip([1.0, 1.0, 0.0, -1.0, 2f32.sqrt()]) {
            assert!((got - want).abs() < 1e-6, "{ba:?}");
        }
    }

    #[test]
    fn value_features_add_the_distances_along_each_axis() {
        // The pair (a, b) of the test above: b 1 ahead of a and 1 to its right.
        let a = TokenPose::new(0.0, 0.0, 0.0, 2.0);
        let b = TokenPose::new(1.0, 1.0, -1.0, 0.0);
        let f = value_features(&[a, b]);
        assert_eq!(f.len(), 4 * RELATION_VALUE_FEATURES);
        let ab = &f[RELATION_VALUE_FEATURES..2 * RELATION_VALUE_FEATURES];
        for (got, want) in ab.iter().zip([1.0, -1.0, 0.0, 1.0, 2f32.sqrt(), 1.0, 1.0]) {
            assert!((got - want).abs() < 1e-6, "{ab:?}");
        }
        // A piece 0.3 to either side of a reads the same distance, the opposite sign.
        let left = value_features(&[TokenPose::new(0.0, 0.0, 1.0, 0.0), TokenPose::new(0.0, 0.3, 1.0, 0.0)]);
        let right = value_features(&[TokenPose::new(0.0, 0.0, 1.0, 0.0), TokenPose::new(0.0, -0.3, 1.0, 0.0)]);
        let (l, r) = (&left[RELATION_VALUE_FEATURES..], &right[RELATION_VALUE_FEATURES..]);
        assert!((l[1] + r[1]).abs() < 1e-6 && (l[1] - 0.3).abs() < 1e-6);
        assert!((l[6] - r[6]).abs() < 1e-6 && (l[6] - 0.3).abs() < 1e-6);
    }

    #[test]
    fn relations_do_not_change_when_the_room_turns() {
        // Turning every pose about the window centre leaves every relation as it was.
        let poses = [TokenPose::new(0.3, -0.2, 0.6, 0.8), TokenPose::new(-0.5, 0.1, 1.0, 0.0)];
        let turn = |p: &TokenPose| TokenPose::new(-p.y, p.x, -p.sin, p.cos);
        let turned: Vec<TokenPose> = poses.iter().map(turn).collect();
        for (a, b) in pair_features(&poses).iter().zip(pair_features(&turned)) {
            assert!((a - b).abs() < 1e-6);
        }
    }
}
