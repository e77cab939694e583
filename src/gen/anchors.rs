//! Contact-anchored slots: the frame in which the model sees and predicts the piece serving each
//! contact box.
//!
//! With `anchor_scale > 0` (see [`ModelConfig::anchor_scale`]), slot k of a scene that has contact
//! box k holds the piece that serves that box ([`super::tokens::encode`] puts it there), and the
//! model works on that slot in the box's frame: its centre as the offset from the box centre,
//! rotated into the box's frame and divided by `anchor_scale`, and (with `anchored_yaw: box`, the
//! first anchored models) its yaw relative to the box's yaw, else its world yaw. Height, size and classes stay as they are. A chair under a sitter is then "offset ≈ 0,
//! relative yaw ≈ 0" in every room, wherever the sitter is, and the noise of a diffusion step moves
//! it by `anchor_scale` as much as it moves a free slot.
//!
//! The map is affine per slot and exactly invertible. Everything outside the model (guidance,
//! decoding, the loss weights) works on world tokens; [`to_model`] and [`to_world`] convert a batch
//! in place. Slots without a box (k ≥ the scene's boxes, or anchoring off) are left alone.

use super::ModelConfig;
use super::config::{AnchoredYaw, CONTACT_FEATURES};
use crate::geom::OBox;
use crate::human::Conditions;
use crate::scene::Action;

/// The boxes that anchor a scene's slots, in slot order, each with its action: the contact boxes,
/// then, for a model with [`ModelConfig::table_slots`], the knee boxes (no action). The model
/// reads the first `max_contacts` of them.
pub fn anchor_boxes(cond: &Conditions, cfg: &ModelConfig) -> Vec<(OBox, Option<Action>)> {
    let contacts = cond.contact_boxes.iter().map(|b| (b.obox, Some(b.action)));
    let knees = cond.knee_boxes.iter().filter(|_| cfg.table_slots).map(|&b| (b, None));
    contacts.chain(knees).collect()
}

/// One anchored slot's box: centre (token units, relative to the window centre) and yaw.
#[derive(Debug, Clone, Copy)]
struct Anchor {
    x: f32,
    y: f32,
    cos: f32,
    sin: f32,
}

/// The anchors of one item's slots, from its contact features (`max_contacts × 11`) and mask.
fn anchors<'a>(cfg: &ModelConfig, contacts: &'a [f32], mask: &'a [f32]) -> impl Iterator<Item = (usize, Anchor)> + 'a {
    let slots = cfg.slots();
    contacts
        .chunks_exact(CONTACT_FEATURES)
        .zip(mask)
        .enumerate()
        .filter(move |(k, (_, m))| **m != 0.0 && *k < slots)
        .map(|(k, (row, _))| {
            let norm = (row[6] * row[6] + row[7] * row[7]).sqrt().max(1e-6);
            (k, Anchor { x: row[0], y: row[1], cos: row[6] / norm, sin: row[7] / norm })
        })
}

/// Converts world tokens (items × slots × token_dim) to the model's frame, item by item, given the
/// items' contact features and masks laid out as [`super::Features`] has them.
pub fn to_model(cfg: &ModelConfig, contacts: &[f32], mask: &[f32], tokens: &mut [f32]) {
    convert(cfg, contacts, mask, tokens, true);
}

/// The inverse of [`to_model`].
pub fn to_world(cfg: &ModelConfig, contacts: &[f32], mask: &[f32], tokens: &mut [f32]) {
    convert(cfg, contacts, mask, tokens, false);
}

/// Per object slot of one item, the 2 × 2 map (row-major) from a change of its centre's x, y in
/// the model's frame to the change in world form: `anchor_scale` times its box's rotation for an
/// anchored slot (the map is affine, this is its linear part), the identity for a free one.
pub fn error_maps(cfg: &ModelConfig, contacts: &[f32], mask: &[f32]) -> Vec<[f32; 4]> {
    let mut maps = vec![[1.0, 0.0, 0.0, 1.0]; cfg.slots()];
    if cfg.anchor_scale > 0.0 {
        let scale = cfg.anchor_scale as f32;
        for (slot, a) in anchors(cfg, contacts, mask) {
            maps[slot] = [scale * a.cos, -scale * a.sin, scale * a.sin, scale * a.cos];
        }
    }
    maps
}

/// World features per object slot ([`world_slot_features`]): centre x, y and yaw's cos, sin.
pub const WORLD_FEATURES: usize = 4;

/// With `world_features` on (see [`ModelConfig::world_features`]): one item's object slots
/// (`tokens`, the model's frame) as the world sees them — each slot's centre (x, y, token units
/// about the window centre) and yaw (cos, sin) in world form, `slots × WORLD_FEATURES`. A free
/// slot's are its own token's; an anchored slot's are what its box-frame offset means in the room,
/// so that every token carries where its piece stands in one frame, and a nightstand's token can
/// be compared with the anchored bed's beside it.
pub fn world_slot_features(cfg: &ModelConfig, tokens: &[f32], contacts: &[f32], mask: &[f32]) -> Vec<f32> {
    let mut world = tokens.to_vec();
    to_world(cfg, contacts, mask, &mut world);
    world.chunks_exact(cfg.token_dim()).flat_map(|t| [t[0], t[1], t[6], t[7]]).collect()
}

fn convert(cfg: &ModelConfig, contacts: &[f32], mask: &[f32], tokens: &mut [f32], into_model: bool) {
    if cfg.anchor_scale <= 0.0 {
        return;
    }
    let (dim, k) = (cfg.token_dim(), cfg.max_contacts);
    let per_item = cfg.slots() * dim;
    let scale = cfg.anchor_scale as f32;
    for (item, tokens) in tokens.chunks_exact_mut(per_item).enumerate() {
        let features = &contacts[item * k * CONTACT_FEATURES..(item + 1) * k * CONTACT_FEATURES];
        for (slot, a) in anchors(cfg, features, &mask[item * k..(item + 1) * k]) {
            let t = &mut tokens[slot * dim..(slot + 1) * dim];
            let turn_yaw = cfg.anchored_yaw == AnchoredYaw::Box;
            if into_model {
                let (dx, dy) = (t[0] - a.x, t[1] - a.y);
                t[0] = (a.cos * dx + a.sin * dy) / scale;
                t[1] = (-a.sin * dx + a.cos * dy) / scale;
                if !turn_yaw {
                    continue;
                }
                let (c, s) = (t[6], t[7]);
                t[6] = a.cos * c + a.sin * s;
                t[7] = -a.sin * c + a.cos * s;
            } else {
                let (u, v) = (t[0] * scale, t[1] * scale);
                t[0] = a.x + a.cos * u - a.sin * v;
                t[1] = a.y + a.sin * u + a.cos * v;
                if !turn_yaw {
                    continue;
                }
                let (c, s) = (t[6], t[7]);
                t[6] = a.cos * c - a.sin * s;
                t[7] = a.sin * c + a.cos * s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::RoomType;

    fn cfg() -> ModelConfig {
        ModelConfig { anchor_scale: 0.4, anchored_yaw: AnchoredYaw::Box, ..ModelConfig::tiny(RoomType::Bedroom) }
    }

    /// Two items; item 0 has boxes in slots 0 and 1, item 1 none.
    fn boxes(cfg: &ModelConfig) -> (Vec<f32>, Vec<f32>) {
        let k = cfg.max_contacts;
        let mut contacts = vec![0f32; 2 * k * CONTACT_FEATURES];
        let mut mask = vec![0f32; 2 * k];
        // Box 0 at (0.5, -0.2) facing +90°, box 1 at (-0.3, 0.1) facing 0°.
        contacts[..8].copy_from_slice(&[0.5, -0.2, 0.1, 0.0, 0.0, 0.0, 0.0, 1.0]);
        contacts[CONTACT_FEATURES..CONTACT_FEATURES + 8].copy_from_slice(&[-0.3, 0.1, 0.1, 0.0, 0.0, 0.0, 1.0, 0.0]);
        mask[..2].fill(1.0);
        (contacts, mask)
    }

    #[test]
    fn hand_computed_offsets_in_the_box_frame() {
        let cfg = cfg();
        let (contacts, mask) = boxes(&cfg);
        let dim = cfg.token_dim();
        let mut tokens = vec![0f32; 2 * cfg.slots() * dim];
        // Slot 0: a piece 0.2 further along world +y than box 0 (which faces +y: its local +x is
        // world +y), facing world −x (yaw 180°): local offset (0.2, 0) / 0.4, relative yaw 90°.
        tokens[..8].copy_from_slice(&[0.5, 0.0, 0.3, 0.1, 0.2, 0.3, -1.0, 0.0]);
        let world = tokens.clone();
        to_model(&cfg, &contacts, &mask, &mut tokens);
        let want = [0.5, 0.0, 0.3, 0.1, 0.2, 0.3, 0.0, 1.0];
        for (got, want) in tokens[..8].iter().zip(want) {
            assert!((got - want).abs() < 1e-6, "{:?}", &tokens[..8]);
        }
        // Slot 1 (box 1 at (-0.3, 0.1), yaw 0): an empty world token moves by the box centre.
        assert!((tokens[dim] - 0.3 / 0.4).abs() < 1e-6 && (tokens[dim + 1] + 0.1 / 0.4).abs() < 1e-6);
        // Slots without a box and the second item (no boxes) are untouched.
        assert_eq!(tokens[2 * dim..], world[2 * dim..]);
        to_world(&cfg, &contacts, &mask, &mut tokens);
        for (a, b) in tokens.iter().zip(&world) {
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn a_world_yaw_stays_as_it_is_while_the_offset_turns() {
        let cfg = ModelConfig { anchored_yaw: AnchoredYaw::World, ..cfg() };
        let (contacts, mask) = boxes(&cfg);
        let mut tokens = vec![0f32; 2 * cfg.slots() * cfg.token_dim()];
        tokens[..8].copy_from_slice(&[0.5, 0.0, 0.3, 0.1, 0.2, 0.3, -1.0, 0.0]);
        let world = tokens.clone();
        to_model(&cfg, &contacts, &mask, &mut tokens);
        let want = [0.5, 0.0, 0.3, 0.1, 0.2, 0.3, -1.0, 0.0];
        for (got, want) in tokens[..8].iter().zip(want) {
            assert!((got - want).abs() < 1e-6, "{:?}", &tokens[..8]);
        }
        to_world(&cfg, &contacts, &mask, &mut tokens);
        for (a, b) in tokens.iter().zip(&world) {
            assert!((a - b).abs() < 1e-6);
        }
    }

    #[test]
    fn world_features_are_an_anchored_slot_in_the_room_and_a_free_slot_as_it_is() {
        let cfg = cfg();
        let (contacts, mask) = boxes(&cfg);
        let dim = cfg.token_dim();
        let mut tokens: Vec<f32> = (0..2 * cfg.slots() * dim).map(|i| (i % 5) as f32 * 0.1).collect();
        // Slot 0 of item 0 in box 0's frame (box at (0.5, -0.2) facing +y): local offset (0.5, 0)
        // × 0.4 is 0.2 along world +y, and a relative yaw of 90° from +y faces world −x.
        tokens[..8].copy_from_slice(&[0.5, 0.0, 0.3, 0.1, 0.2, 0.3, 0.0, 1.0]);
        let f = world_slot_features(
            &cfg,
            &tokens[..cfg.slots() * dim],
            &contacts[..cfg.max_contacts * CONTACT_FEATURES],
            &mask[..cfg.max_contacts],
        );
        assert_eq!(f.len(), cfg.slots() * WORLD_FEATURES);
        for (got, want) in f[..4].iter().zip([0.5, 0.0, -1.0, 0.0]) {
            assert!((got - want).abs() < 1e-6, "{:?}", &f[..4]);
        }
        // A free slot (2 and on: item 0 has two boxes) reads its own centre and yaw.
        let t = &tokens[2 * dim..3 * dim];
        assert_eq!(f[2 * WORLD_FEATURES..3 * WORLD_FEATURES], [t[0], t[1], t[6], t[7]]);
    }

    #[test]
    fn an_error_map_is_the_linear_part_of_to_world() {
        let cfg = cfg();
        let (contacts, mask) = boxes(&cfg);
        let (k, dim) = (cfg.max_contacts, cfg.token_dim());
        let (contacts, mask) = (&contacts[..k * CONTACT_FEATURES], &mask[..k]);
        let maps = error_maps(&cfg, contacts, mask);
        let base: Vec<f32> = (0..cfg.slots() * dim).map(|i| (i % 7) as f32 * 0.05).collect();
        let mut moved = base.clone();
        // Every slot's centre moves by (0.1, −0.2) in the model's frame.
        for t in moved.chunks_exact_mut(dim) {
            t[0] += 0.1;
            t[1] -= 0.2;
        }
        let (mut a, mut b) = (base, moved);
        to_world(&cfg, contacts, mask, &mut a);
        to_world(&cfg, contacts, mask, &mut b);
        for (slot, m) in maps.iter().enumerate() {
            let want = [m[0] * 0.1 - m[1] * 0.2, m[2] * 0.1 - m[3] * 0.2];
            let got = [b[slot * dim] - a[slot * dim], b[slot * dim + 1] - a[slot * dim + 1]];
            assert!(
                (got[0] - want[0]).abs() < 1e-6 && (got[1] - want[1]).abs() < 1e-6,
                "slot {slot}: {got:?} {want:?}"
            );
        }
        assert_eq!(maps[2], [1.0, 0.0, 0.0, 1.0], "a free slot");
        assert!((maps[0][2] - 0.4).abs() < 1e-6, "box 0 faces +y: model x is world y, × 0.4");
    }

    #[test]
    fn off_means_the_identity() {
        let cfg = ModelConfig { anchor_scale: 0.0, ..cfg() };
        let (contacts, mask) = boxes(&cfg);
        let mut tokens: Vec<f32> = (0..2 * cfg.slots() * cfg.token_dim()).map(|i| (i % 5) as f32 * 0.1).collect();
        let before = tokens.clone();
        to_model(&cfg, &contacts, &mask, &mut tokens);
        assert_eq!(tokens, before);
    }
}
