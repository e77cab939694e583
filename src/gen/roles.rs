//! Slot roles: free slots that hold their pieces in one order, each slot with its own embedding.
//!
//! Without roles the denoiser is equivariant to the order of its free slots, so every free slot
//! of a room is every other one's twin: while the noise is large, each slot's clean estimate is
//! the mean over all the places a free piece may take — for a spare dining chair, the mean of the
//! places around its table, which lies inside the table (docs/RESULTS.md, "Gaps between pieces").
//! With `slot_roles` on (see [`ModelConfig::slot_roles`]), the training tokens hold the free pieces
//! by the angle of their centre about the window centre ([`order_free_slots`], counter-clockwise
//! from −x, the empty slots last), and every free slot gets a learned embedding of its rank among
//! the free slots ([`slot_features`]): slot j is "the j-th piece round the room", whose places are
//! far fewer than every piece's. Anchored slots keep their contact box's embedding and no rank.
//!
//! Not here: the embedding layer itself (both engines), the anchored slots ([`super::anchors`]).

use super::ModelConfig;
use super::tokens::slot_class;

/// The rank features of one item's object slots: `slots × slots`, row-major, the row of a free
/// slot one-hot at its rank among the free slots (slot − anchored slots), an anchored slot's row
/// zero. `mask` is the item's contact mask; every real box anchors one slot up to the model's
/// limit ([`ModelConfig::anchored_slots`]).
pub fn slot_features(cfg: &ModelConfig, mask: &[f32]) -> Vec<f32> {
    let slots = cfg.slots();
    let anchored = cfg.anchored_slots(mask.iter().filter(|&&m| m != 0.0).count());
    let mut out = vec![0f32; slots * slots];
    for slot in anchored..slots {
        out[slot * slots + slot - anchored] = 1.0;
    }
    out
}

/// Puts one item's free pieces (the slots from `anchored` on) in role order: the pieces by the
/// angle of their centre about the window centre, atan2(y, x) ascending, ties by slot, then the
/// empty slots. `tokens` are in world form (slots × token_dim); `weights`, laid out alike, move
/// with their slots.
pub fn order_free_slots(tokens: &mut [f32], weights: &mut [f32], anchored: usize, cfg: &ModelConfig) {
    let dim = cfg.token_dim();
    let slots = tokens.len() / dim;
    let empty = cfg.classes() - 1;
    let mut order: Vec<usize> = (anchored.min(slots)..slots).collect();
    let key = |slot: usize| {
        let t = &tokens[slot * dim..(slot + 1) * dim];
        match slot_class(t, cfg) == empty {
            true => (1, 0.0),
            false => (0, f32::atan2(t[1], t[0])),
        }
    };
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1)).then(a.cmp(&b))
    });
    let permute = |values: &mut [f32]| {
        let moved: Vec<f32> = order.iter().flat_map(|&s| values[s * dim..(s + 1) * dim].to_vec()).collect();
        values[anchored.min(slots) * dim..].copy_from_slice(&moved);
    };
    permute(tokens);
    permute(weights);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generator::tokens::CLASS_OFFSET;
    use crate::scene::RoomType;

    fn token(cfg: &ModelConfig, x: f32, y: f32, class: usize) -> Vec<f32> {
        let mut t = vec![0f32; cfg.token_dim()];
        t[0] = x;
        t[1] = y;
        for k in 0..cfg.classes() {
            t[CLASS_OFFSET + k] = if k == class { 1.0 } else { -1.0 };
        }
        t
    }

    #[test]
    fn free_pieces_go_round_the_room_and_empty_slots_last() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let empty = cfg.classes() - 1;
        // Slot 0 anchored (stays, though its angle is the largest); free slots: east (angle 0),
        // empty, north (π/2), south (−π/2), west (π, the largest), then empty slots.
        let placed = [(0.0, 0.5, 0), (0.5, 0.0, 1), (0.0, 0.0, empty), (0.0, 0.5, 2), (0.0, -0.5, 3), (-0.5, 0.0, 4)];
        let mut tokens: Vec<f32> = placed.iter().flat_map(|&(x, y, c)| token(&cfg, x, y, c)).collect();
        tokens.extend((placed.len()..cfg.slots()).flat_map(|_| token(&cfg, 0.0, 0.0, empty)));
        let mut weights: Vec<f32> = (0..cfg.slots()).flat_map(|s| vec![s as f32; cfg.token_dim()]).collect();
        order_free_slots(&mut tokens, &mut weights, 1, &cfg);
        let classes: Vec<usize> = tokens.chunks_exact(cfg.token_dim()).map(|t| slot_class(t, &cfg)).collect();
        assert_eq!(classes[..5], [0, 3, 1, 2, 4], "anchored first, then south, east, north, west");
        assert!(classes[5..].iter().all(|&c| c == empty));
        // The weights moved with their slots: south was slot 4, east 1, north 3, west 5, empty 2.
        let moved: Vec<f32> = weights.chunks_exact(cfg.token_dim()).map(|w| w[0]).collect();
        assert_eq!(moved[..6], [0.0, 4.0, 1.0, 3.0, 5.0, 2.0]);
    }

    #[test]
    fn ranks_start_after_the_anchored_slots() {
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let slots = cfg.slots();
        let mut mask = vec![0f32; cfg.max_contacts];
        mask[..2].fill(1.0);
        let f = slot_features(&cfg, &mask);
        assert_eq!(f.len(), slots * slots);
        for slot in 0..slots {
            let row = &f[slot * slots..(slot + 1) * slots];
            match slot < 2 {
                true => assert!(row.iter().all(|&v| v == 0.0), "anchored slot {slot} has no rank"),
                false => {
                    assert_eq!(row[slot - 2], 1.0);
                    assert_eq!(row.iter().sum::<f32>(), 1.0);
                }
            }
        }
        // No boxes: every slot is free, ranked by its own index.
        let f = slot_features(&cfg, &vec![0f32; cfg.max_contacts]);
        assert!((0..slots).all(|s| f[s * slots + s] == 1.0));
    }
}
