//! Object slots ↔ tokens: `[centre (3), size (3), cos yaw, sin yaw, one-hot of C+1 classes]`, the
//! continuous parts scaled to [-1, 1] by the training data's bounds, classes as ±1, the last class
//! meaning "empty slot".
//!
//! Centres are relative to the room window's centre. The x and y bounds are made symmetric and equal
//! (±the largest |x| or |y| seen), so rotating or mirroring a room about the window centre — the
//! training augmentation — maps tokens to tokens. Decoding snaps each object's height to what every
//! training scene has: floor pieces stand on the floor, lamps hang from the ceiling, and nothing
//! reaches through the ceiling (a piece taller than the room is cut to its height).

use super::ModelConfig;
use crate::data::SplitStats;
use crate::geom::OBox;
use crate::measure::contact_iou;
use crate::scene::{Object, Scene};
use glam::DVec2;
use serde::{Deserialize, Serialize};

/// Bounds that scale continuous attributes to [-1, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bounds {
    /// Smallest centre (relative to the window centre).
    pub center_min: [f64; 3],
    /// Largest centre.
    pub center_max: [f64; 3],
    /// Smallest full size.
    pub size_min: [f64; 3],
    /// Largest full size.
    pub size_max: [f64; 3],
}

impl Bounds {
    /// The bounds of a dataset split, with x and y made symmetric and equal.
    pub fn from_stats(split: &SplitStats) -> Bounds {
        let m = (0..2).map(|k| split.center_min[k].abs().max(split.center_max[k].abs())).fold(0.0, f64::max);
        Bounds {
            center_min: [-m, -m, split.center_min[2]],
            center_max: [m, m, split.center_max[2]],
            size_min: split.size_min,
            size_max: split.size_max,
        }
    }

    /// Whether every bound is finite and ordered.
    pub fn is_valid(&self) -> bool {
        let ok =
            |lo: &[f64; 3], hi: &[f64; 3]| (0..3).all(|k| lo[k].is_finite() && hi[k].is_finite() && lo[k] <= hi[k]);
        ok(&self.center_min, &self.center_max) && ok(&self.size_min, &self.size_max)
    }

    /// Centre (relative to the window) → [-1, 1]³.
    pub fn scale_center(&self, c: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| scale(c[k], self.center_min[k], self.center_max[k]))
    }

    /// Size → [-1, 1]³.
    pub fn scale_size(&self, s: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| scale(s[k], self.size_min[k], self.size_max[k]))
    }

    /// [-1, 1]³ → centre relative to the window.
    pub fn unscale_center(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| unscale(v[k], self.center_min[k], self.center_max[k]))
    }

    /// [-1, 1]³ → size.
    pub fn unscale_size(&self, v: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| unscale(v[k], self.size_min[k], self.size_max[k]))
    }
}

fn scale(v: f64, lo: f64, hi: f64) -> f64 {
    if hi - lo < 1e-9 { 0.0 } else { 2.0 * (v - lo) / (hi - lo) - 1.0 }
}

fn unscale(v: f64, lo: f64, hi: f64) -> f64 {
    lo + (v + 1.0) * 0.5 * (hi - lo)
}

/// Index of the first class feature in a token.
pub const CLASS_OFFSET: usize = 8;

/// The tokens of a scene's objects (slots × token_dim, empty slots after the objects) and the loss
/// weights: an empty slot's continuous attributes carry no loss, only its class does.
///
/// With anchored slots (`cfg.anchor_scale > 0`), slot k first holds the piece serving contact box k
/// of `contact_boxes` (the one covering most of the box, as contact IoU measures; a piece serving
/// several boxes is in each of their slots; a box nothing covers leaves its slot empty); the other
/// pieces follow in scene order, or with slot roles in role order ([`super::roles`]). Without, the
/// pieces fill the slots in that order. Tokens are in
/// world form either way ([`super::anchors`] converts). Pieces beyond the slot count are dropped.
pub fn encode(
    scene: &Scene,
    window_center: DVec2,
    contact_boxes: &[OBox],
    bounds: &Bounds,
    cfg: &ModelConfig,
) -> (Vec<f32>, Vec<f32>) {
    let dim = cfg.token_dim();
    let classes = cfg.classes();
    let categories = cfg.room_type.categories();
    let known: Vec<(usize, &Object)> = scene
        .objects
        .iter()
        .filter_map(|o| categories.iter().position(|&c| c == o.category).map(|class| (class, o)))
        .collect();
    let mut order: Vec<Option<usize>> = Vec::new();
    for b in &contact_boxes[..cfg.anchored_slots(contact_boxes.len())] {
        let serving = known
            .iter()
            .enumerate()
            .map(|(i, (_, o))| (i, contact_iou(b, std::slice::from_ref(o))))
            .filter(|(_, v)| *v > 0.0)
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)));
        order.push(serving.map(|(i, _)| i));
    }
    let anchored = order.len();
    let free: Vec<Option<usize>> = (0..known.len()).filter(|i| !order.contains(&Some(*i))).map(Some).collect();
    order.extend(free);
    order.resize(cfg.slots(), None);

    let mut tokens = vec![0f32; cfg.slots() * dim];
    let mut weights = vec![1f32; cfg.slots() * dim];
    for (slot, piece) in order.into_iter().enumerate() {
        let t = &mut tokens[slot * dim..(slot + 1) * dim];
        let Some((class, o)) = piece.map(|i| known[i]) else {
            for k in 0..classes {
                t[CLASS_OFFSET + k] = if k == classes - 1 { 1.0 } else { -1.0 };
            }
            weights[slot * dim..slot * dim + CLASS_OFFSET].fill(0.0);
            continue;
        };
        let rel = [o.center[0] - window_center.x, o.center[1] - window_center.y, o.center[2]];
        let c = bounds.scale_center(rel);
        let s = bounds.scale_size(o.size);
        let values = [c[0], c[1], c[2], s[0], s[1], s[2], o.yaw.cos(), o.yaw.sin()];
        for (dst, v) in t.iter_mut().zip(values) {
            *dst = v as f32;
        }
        for k in 0..classes {
            t[CLASS_OFFSET + k] = if k == class { 1.0 } else { -1.0 };
        }
    }
    if cfg.slot_roles {
        super::roles::order_free_slots(&mut tokens, &mut weights, anchored, cfg);
    }
    (tokens, weights)
}

/// The largest class of one slot's token (`cfg.classes() - 1`: empty).
pub fn slot_class(token: &[f32], cfg: &ModelConfig) -> usize {
    (0..cfg.classes())
        .max_by(|&a, &b| token[CLASS_OFFSET + a].total_cmp(&token[CLASS_OFFSET + b]))
        .expect("at least one class")
}

/// The objects of generated tokens (slots × token_dim): one per slot whose largest class is not
/// "empty", ids `o0`, `o1`, … in slot order — except that a slot whose piece is a copy of an
/// earlier slot's ([`is_copy`]) adds nothing: with anchored slots, a sofa serving two sitters is
/// predicted in both sitters' slots.
pub fn decode(tokens: &[f32], window_center: DVec2, ceiling: f64, bounds: &Bounds, cfg: &ModelConfig) -> Vec<Object> {
    decode_slots(tokens, window_center, ceiling, bounds, cfg).into_iter().map(|(_, o)| o).collect()
}

/// Like [`decode`], with the slots holding each object: its own first, then those holding copies of
/// it.
pub fn decode_slots(
    tokens: &[f32],
    window_center: DVec2,
    ceiling: f64,
    bounds: &Bounds,
    cfg: &ModelConfig,
) -> Vec<(Vec<usize>, Object)> {
    let dim = cfg.token_dim();
    let categories = cfg.room_type.categories();
    let mut objects: Vec<(Vec<usize>, Object)> = Vec::new();
    for (slot, t) in tokens.chunks_exact(dim).enumerate() {
        let class = slot_class(t, cfg);
        let Some(&category) = categories.get(class) else { continue };
        let v = |k: usize| (t[k] as f64).clamp(-1.0, 1.0);
        let c = bounds.unscale_center([v(0), v(1), v(2)]);
        let size = bounds.unscale_size([v(3), v(4), v(5)]).map(|s| s.max(0.02));
        let z = if category.is_hanging() { ceiling - size[2] * 0.5 } else { size[2] * 0.5 };
        let yaw = (t[7] as f64).atan2(t[6] as f64);
        let mut object = Object {
            id: format!("o{}", objects.len()),
            category,
            center: [c[0] + window_center.x, c[1] + window_center.y, z],
            size,
            yaw: if yaw.is_finite() { yaw } else { 0.0 },
        };
        // No training piece reaches through its ceiling: one taller than the room is cut to it.
        object.cut_to_ceiling(ceiling);
        match objects.iter_mut().find(|(_, kept)| is_copy(&object, kept)) {
            Some((slots, _)) => slots.push(slot),
            None => objects.push((vec![slot], object)),
        }
    }
    objects
}

/// Whether `a` and `b` are one piece: the same category, each one's centre inside the other's
/// footprint. The training data never has two such pieces (they would overlap by half or more).
pub fn is_copy(a: &Object, b: &Object) -> bool {
    let inside = |p: &Object, q: &Object| q.obox().footprint_contains(DVec2::new(p.center[0], p.center[1]));
    a.category == b.category && inside(a, b) && inside(b, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::{SplitStats, generate_room};
    use crate::geom::RoomWindow;
    use crate::scene::{Action, Category, RoomType};

    fn bounds_of(scenes: &[Scene]) -> Bounds {
        let mut stats = SplitStats::default();
        scenes.iter().for_each(|s| stats.add(s));
        Bounds::from_stats(&stats)
    }

    #[test]
    fn encode_then_decode_gives_the_scene_back() {
        for room in RoomType::ALL {
            let scenes: Vec<Scene> = (0..20).map(|i| generate_room(room, 3, i, false).scene).collect();
            let bounds = bounds_of(&scenes);
            let cfg = ModelConfig::tiny(room);
            for scene in &scenes {
                let window = RoomWindow::around(room.window_side(), &scene.floor_plan.polygon());
                let (tokens, weights) = encode(scene, window.center, &[], &bounds, &cfg);
                assert_eq!(tokens.len(), cfg.slots() * cfg.token_dim());
                assert!(tokens.iter().all(|v| (-1.0 - 1e-6..=1.0 + 1e-6).contains(v)));
                let back = decode(&tokens, window.center, scene.floor_plan.height, &bounds, &cfg);
                assert_eq!(back.len(), scene.objects.len().min(cfg.slots()));
                for (a, b) in scene.objects.iter().zip(&back) {
                    assert_eq!(a.category, b.category);
                    for k in 0..3 {
                        assert!((a.center[k] - b.center[k]).abs() < 1e-5, "{room} {a:?} {b:?}");
                        assert!((a.size[k] - b.size[k]).abs() < 1e-5);
                    }
                    let dyaw = (a.yaw - b.yaw).sin().abs() + (1.0 - (a.yaw - b.yaw).cos());
                    assert!(dyaw < 1e-5);
                }
                // Empty slots weigh only their classes.
                let dim = cfg.token_dim();
                let empty = cfg.slots() - back.len();
                let zero: usize = weights.iter().filter(|w| **w == 0.0).count();
                assert_eq!(zero, empty * CLASS_OFFSET);
                assert_eq!(weights.len(), cfg.slots() * dim);
            }
        }
    }

    #[test]
    fn a_piece_taller_than_the_room_is_cut_to_the_ceiling_and_lamps_hang_from_it() {
        let room = RoomType::Bedroom;
        let scenes: Vec<Scene> = (0..20).map(|i| generate_room(room, 3, i, false).scene).collect();
        let (bounds, cfg) = (bounds_of(&scenes), ModelConfig::tiny(room));
        let scene = scenes.iter().find(|s| s.objects.iter().any(|o| o.size[2] > 2.0)).expect("a tall piece");
        let window = RoomWindow::around(room.window_side(), &scene.floor_plan.polygon());
        let (tokens, _) = encode(scene, window.center, &[], &bounds, &cfg);
        // The same tokens in a 1.5 m high room: every floor piece ends at or under 1.5 m, the
        // shorter ones as they were; a lamp hangs from 1.5 m.
        let low = decode(&tokens, window.center, 1.5, &bounds, &cfg);
        let high = decode(&tokens, window.center, scene.floor_plan.height, &bounds, &cfg);
        for (a, b) in low.iter().zip(&high) {
            let top = a.center[2] + a.size[2] * 0.5;
            assert!(top <= 1.5 + 1e-9 && a.center[2] - a.size[2] * 0.5 >= -1e-9, "{a:?}");
            assert!((a.size[2] - b.size[2].min(1.5)).abs() < 1e-9, "{a:?} {b:?}");
            if a.category.is_hanging() {
                assert!((top - 1.5).abs() < 1e-9, "{a:?}");
            }
        }
        assert!(high.iter().any(|o| o.size[2] > 1.5), "the room has a piece to cut");
    }

    #[test]
    fn anchored_slots_hold_each_boxs_piece_and_decode_to_the_scene() {
        let room = RoomType::Living;
        let scenes: Vec<Scene> = (0..40).map(|i| generate_room(room, 3, i, false).scene).collect();
        let bounds = bounds_of(&scenes);
        let cfg = ModelConfig::tiny(room);
        assert!(cfg.anchor_scale > 0.0);
        let dim = cfg.token_dim();
        let key = |o: &Object| (o.category, (o.center[0] * 1e3).round() as i64, (o.center[1] * 1e3).round() as i64);
        let mut shared = 0;
        for scene in &scenes {
            let cond = crate::human::Conditions::of(scene);
            let boxes: Vec<OBox> = cond.contact_boxes.iter().map(|b| b.obox).take(cfg.max_contacts).collect();
            let (tokens, _) = encode(scene, cond.window.center, &boxes, &bounds, &cfg);
            let slots = decode_slots(&tokens, cond.window.center, scene.floor_plan.height, &bounds, &cfg);
            // Every piece once, duplicates folded.
            let mut want: Vec<_> = scene.objects.iter().map(key).collect();
            let mut got: Vec<_> = slots.iter().map(|(_, o)| key(o)).collect();
            want.sort();
            got.sort();
            assert_eq!(got, want);
            // Slot k's token is the piece covering most of box k.
            for (k, b) in boxes.iter().enumerate() {
                let best = scene.objects.iter().map(|o| contact_iou(b, std::slice::from_ref(o))).fold(0.0, f64::max);
                let one = decode(&tokens[k * dim..(k + 1) * dim], cond.window.center, 2.6, &bounds, &cfg);
                assert!((contact_iou(b, &one) - best).abs() < 1e-4, "box {k}");
            }
            shared += boxes.len() - slots.iter().filter(|(s, _)| s[0] < boxes.len()).count();
            // A shared piece lists every slot that holds it: each box something covers is in a list.
            for (k, b) in boxes.iter().enumerate() {
                if scene.objects.iter().any(|o| contact_iou(b, std::slice::from_ref(o)) > 0.0) {
                    assert!(slots.iter().any(|(s, _)| s.contains(&k)), "box {k}'s slot");
                }
            }
        }
        assert!(shared > 0, "some sofa serves two sitters in 40 living rooms");
    }

    #[test]
    fn a_diners_knee_slot_holds_their_table_and_no_sitters_slot_holds_their_seat() {
        let room = RoomType::Dining;
        let scenes: Vec<Scene> = (0..30).map(|i| generate_room(room, 3, i, false).scene).collect();
        let bounds = bounds_of(&scenes);
        let cfg = ModelConfig { table_slots: true, max_contacts: room.max_objects(), ..ModelConfig::tiny(room) };
        let dim = cfg.token_dim();
        let (mut diners, mut empty) = (0, 0);
        for scene in &scenes {
            let cond = crate::human::Conditions::of(scene);
            let anchors = super::super::anchors::anchor_boxes(&cond, &cfg);
            let sits: Vec<usize> =
                (0..cond.contact_boxes.len()).filter(|&k| anchors[k].1 == Some(Action::Sit)).collect();
            // One knee box per sit box, after the contact boxes, with no action.
            assert_eq!(anchors.len(), cond.contact_boxes.len() + sits.len());
            assert!(anchors[cond.contact_boxes.len()..].iter().all(|(_, action)| action.is_none()));
            let boxes: Vec<OBox> = anchors.iter().map(|(b, _)| *b).collect();
            let (tokens, _) = encode(scene, cond.window.center, &boxes, &bounds, &cfg);
            let piece = |k: usize| decode(&tokens[k * dim..(k + 1) * dim], cond.window.center, 2.6, &bounds, &cfg);
            for (n, &k) in sits.iter().enumerate() {
                let (seat, at_knees) = (piece(k), piece(cond.contact_boxes.len() + n));
                if seat.first().is_some_and(|o| o.category == Category::DiningChair) {
                    diners += 1;
                    assert_eq!(at_knees.iter().map(|o| o.category).collect::<Vec<_>>(), [Category::DiningTable]);
                }
                empty += at_knees.is_empty() as usize;
                assert!(at_knees.iter().all(|o| seat.iter().all(|s| !is_copy(o, s))), "a seat at its sitter's knees");
            }
        }
        assert!(diners > 20 && empty > 0, "{diners} diners, {empty} sitters with nothing at their knees");
    }

    #[test]
    fn symmetric_bounds_and_hand_computed_scaling() {
        let b = Bounds {
            center_min: [-2.0, -3.0, 0.0],
            center_max: [2.0, 3.0, 2.0],
            size_min: [0.5, 0.5, 0.5],
            size_max: [2.5, 1.5, 2.5],
        };
        assert_eq!(b.scale_center([1.0, -1.5, 0.5]), [0.5, -0.5, -0.5]);
        assert_eq!(b.scale_size([1.5, 1.0, 2.5]), [0.0, 0.0, 1.0]);
        assert_eq!(b.unscale_size([0.0, 0.0, 1.0]), [1.5, 1.0, 2.5]);
        let mut stats = SplitStats::default();
        stats.add(&generate_room(RoomType::Bedroom, 1, 0, false).scene);
        let s = Bounds::from_stats(&stats);
        assert_eq!(s.center_min[0], -s.center_max[0]);
        assert_eq!(s.center_min[0], s.center_min[1]);
    }
}
