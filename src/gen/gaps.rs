//! Gaps between the noisy pieces: how much floor each object slot's piece has ahead of each of its
//! four faces before the next piece.
//!
//! With `gap_bounds` set (see [`ModelConfig::gap_bounds`]), every object token gets a learned
//! embedding of four numbers computed on the host from the noisy tokens: the slots are decoded as
//! sampling decodes them ([`super::tokens::decode_slots`], anchored slots taken to world form
//! first, copies of one piece folded), and for each floor-standing piece and each of its faces
//! (+x, −x, +y, −y of its own frame) the gap from that face to the nearest other floor-standing
//! piece ahead of it — one whose footprint reaches past the piece's centre along that axis and
//! overlaps its width across it — negative where the two overlap. The data puts a chair exactly
//! 4 cm from its table and a nightstand 4 cm beside its bed; a transformer that sees only absolute
//! centres and sizes must learn rotations, differences and footprints to read such a gap, and the
//! model alone drew tables into their chairs in two thirds of the val dining rooms
//! (docs/RESULTS.md, "Gaps between pieces"). Here the gap is handed to it.
//!
//! A gap g (m, clamped to [−[`BEHIND`], [`FAR`]]) reads tanh(g / [`SCALE`]): about linear over the
//! centimetres between a chair and its table, −1 to 1 whatever the room, so that no feature
//! outweighs the token's own embedding; empty slots and hanging pieces read the far value on every
//! face. Not here: the embedding itself (both engines).

use super::ModelConfig;
use super::anchors;
use super::tokens::{Bounds, decode_slots};
use crate::scene::Object;
use glam::DVec2;

/// Features per object slot: the gaps ahead of its +x, −x, +y and −y faces.
pub const GAP_FEATURES: usize = 4;

/// The gap (m) that reads tanh(1): a 4 cm gap reads 0.197, a centimetre more about 0.05 more.
pub const SCALE: f64 = 0.2;

/// Gaps beyond this (m) read as this: nothing near that way.
pub const FAR: f64 = 1.0;

/// Overlaps deeper than this (m) read as this.
pub const BEHIND: f64 = 0.5;

/// The gap features of one item's object slots (`tokens`, the model's frame, anchored slots as
/// offsets from their contact boxes `contacts` / `mask`): `slots × GAP_FEATURES`, row-major.
pub fn slot_features(cfg: &ModelConfig, bounds: &Bounds, tokens: &[f32], contacts: &[f32], mask: &[f32]) -> Vec<f32> {
    let mut world = tokens.to_vec();
    anchors::to_world(cfg, contacts, mask, &mut world);
    let pieces: Vec<(Vec<usize>, Object)> = decode_slots(&world, DVec2::ZERO, 0.0, bounds, cfg)
        .into_iter()
        .filter(|(_, o)| !o.category.is_hanging())
        .collect();
    let mut out = vec![feature(FAR); cfg.slots() * GAP_FEATURES];
    for (i, (slots, piece)) in pieces.iter().enumerate() {
        let others = pieces.iter().enumerate().filter(|&(j, _)| j != i).map(|(_, (_, o))| o);
        let gaps = gaps_ahead(piece, others);
        for &slot in slots {
            for (face, gap) in gaps.iter().enumerate() {
                out[slot * GAP_FEATURES + face] = feature(*gap);
            }
        }
    }
    out
}

/// What a gap `g` (m) reads.
fn feature(g: f64) -> f32 {
    (g / SCALE).tanh() as f32
}

/// The clamped gaps (m) ahead of `piece`'s +x, −x, +y and −y faces to the nearest of `others`.
fn gaps_ahead<'a>(piece: &Object, others: impl Iterator<Item = &'a Object>) -> [f64; GAP_FEATURES] {
    let obox = piece.obox();
    let (ax, ay) = obox.axes();
    let centre = obox.center.truncate();
    let half = [obox.size.x * 0.5, obox.size.y * 0.5];
    // Per face: the direction ahead, the half extent along it, the axis across and its half extent.
    let faces = [
        (ax, half[0], ay, half[1]),
        (-ax, half[0], ay, half[1]),
        (ay, half[1], ax, half[0]),
        (-ay, half[1], ax, half[0]),
    ];
    let mut gaps = [FAR; GAP_FEATURES];
    for other in others {
        let corners = other.obox().footprint().map(|p| p - centre);
        for (gap, &(ahead, depth, across, width)) in gaps.iter_mut().zip(&faces) {
            let along = corners.map(|p| p.dot(ahead));
            let beside = corners.map(|p| p.dot(across));
            let (near, far) =
                (along.iter().copied().fold(f64::MAX, f64::min), along.iter().copied().fold(f64::MIN, f64::max));
            let (lo, hi) =
                (beside.iter().copied().fold(f64::MAX, f64::min), beside.iter().copied().fold(f64::MIN, f64::max));
            if far <= 0.0 || hi <= -width || lo >= width {
                continue;
            }
            *gap = gap.min(near - depth);
        }
    }
    gaps.map(|g| g.max(-BEHIND))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Category, RoomType};

    fn piece(category: Category, x: f64, y: f64, w: f64, d: f64, yaw: f64) -> Object {
        Object { id: String::new(), category, center: [x, y, 0.4], size: [w, d, 0.8], yaw }
    }

    #[test]
    fn a_chair_before_its_table_reads_the_gap_on_its_facing_side_only() {
        // A 1.6 × 0.9 table at the origin; a 0.4 × 0.4 chair whose back is at y = −0.89, its front
        // 4 cm from the table's edge at y = −0.45.
        let table = piece(Category::DiningTable, 0.0, 0.0, 1.6, 0.9, 0.0);
        let chair = piece(Category::DiningChair, 0.3, -0.69, 0.4, 0.4, 0.0);
        let g = gaps_ahead(&chair, [&table].into_iter());
        assert!((g[2] - 0.04).abs() < 1e-9, "{g:?}");
        assert_eq!([g[0], g[1], g[3]], [FAR; 3]);
        // The table sees the chair 4 cm beyond its −y face.
        let g = gaps_ahead(&table, [&chair].into_iter());
        assert!((g[3] - 0.04).abs() < 1e-9, "{g:?}");
        assert_eq!([g[0], g[1], g[2]], [FAR; 3]);
        // Turned half a turn, the chair's faces swap: the gap is now ahead of its −y face.
        let turned = piece(Category::DiningChair, 0.3, -0.69, 0.4, 0.4, std::f64::consts::PI);
        let g = gaps_ahead(&turned, [&table].into_iter());
        assert!((g[3] - 0.04).abs() < 1e-9, "{g:?}");
    }

    #[test]
    fn overlaps_read_negative_and_pieces_beside_or_behind_are_not_ahead() {
        let table = piece(Category::DiningTable, 0.0, 0.0, 1.6, 0.9, 0.0);
        // 10 cm into the table.
        let chair = piece(Category::DiningChair, 0.3, -0.55, 0.4, 0.4, 0.0);
        assert!((gaps_ahead(&chair, [&table].into_iter())[2] + 0.10).abs() < 1e-9);
        // Beside the table's end, not across its width: nothing ahead along y.
        let beside = piece(Category::DiningChair, 1.2, -0.69, 0.4, 0.4, 0.0);
        assert_eq!(gaps_ahead(&beside, [&table].into_iter())[2], FAR);
        // Deep inside: clamped.
        let inside = piece(Category::DiningChair, 0.0, 0.0, 0.4, 0.4, 0.0);
        assert_eq!(gaps_ahead(&inside, [&table].into_iter()), [-BEHIND; 4]);
    }

    /// Tokens for `objects` in slots 0, 1, … (the rest empty) with bounds ±3 m and sizes 0–3 m.
    fn tokens_of(objects: &[Object], cfg: &ModelConfig) -> (Bounds, Vec<f32>) {
        let bounds = Bounds {
            center_min: [-3.0, -3.0, 0.0],
            center_max: [3.0, 3.0, 3.0],
            size_min: [0.0; 3],
            size_max: [3.0; 3],
        };
        let (dim, categories) = (cfg.token_dim(), cfg.room_type.categories());
        let mut tokens = vec![-1f32; cfg.slots() * dim];
        for (slot, t) in tokens.chunks_exact_mut(dim).enumerate() {
            let class = match objects.get(slot) {
                Some(o) => {
                    let c = bounds.scale_center(o.center);
                    let size = bounds.scale_size(o.size);
                    let v = [c[0], c[1], c[2], size[0], size[1], size[2], o.yaw.cos(), o.yaw.sin()];
                    t[..8].iter_mut().zip(v).for_each(|(t, v)| *t = v as f32);
                    categories.iter().position(|&c| c == o.category).unwrap()
                }
                None => cfg.classes() - 1,
            };
            t[8 + class] = 1.0;
        }
        (bounds, tokens)
    }

    #[test]
    fn empty_slots_and_hanging_pieces_read_far() {
        let cfg = ModelConfig { anchor_scale: 0.0, ..ModelConfig::tiny(RoomType::Dining) };
        let objects = [
            piece(Category::DiningTable, 0.0, 0.0, 1.6, 0.9, 0.0),
            piece(Category::DiningChair, 0.3, -0.69, 0.4, 0.4, 0.0),
            piece(Category::PendantLamp, 0.0, 0.0, 0.5, 0.5, 0.0),
        ];
        let (bounds, tokens) = tokens_of(&objects, &cfg);
        let f = slot_features(&cfg, &bounds, &tokens, &[], &[]);
        assert_eq!(f.len(), cfg.slots() * GAP_FEATURES);
        let far = feature(FAR);
        let slot = |k: usize| &f[k * GAP_FEATURES..(k + 1) * GAP_FEATURES];
        // The table's −y face and the chair's +y face: 4 cm, tanh(0.2).
        assert!((slot(0)[3] - 0.2f32.tanh()).abs() < 1e-4, "{:?}", slot(0));
        assert!((slot(1)[2] - 0.2f32.tanh()).abs() < 1e-4, "{:?}", slot(1));
        assert_eq!(slot(2), [far; 4]);
        assert!((3..cfg.slots()).all(|k| slot(k) == [far; 4]));
    }
}
