//! The conditioning of one scene as fixed-size feature arrays (contact boxes, floor-plan points,
//! free-space points), and the dihedral transforms (quarter turns, mirror) the training augments by.
//!
//! Positions are relative to the room window's centre and scaled like object centres ([`Bounds`]),
//! so a contact box and the object that supports it have matching coordinates.

use super::config::{CONTACT_FEATURES, FLOOR_FEATURES, FREE_FEATURES};
use super::{Bounds, ModelConfig};
use crate::human::Conditions;
use crate::scene::{Action, RoomType};

/// The conditioning features of one scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Features {
    /// `max_contacts × 11`: centre, size, cos, sin, one-hot (sit, lie, touch; none for a knee
    /// box, [`super::anchors::anchor_boxes`]); zeros when padded.
    pub contacts: Vec<f32>,
    /// `max_contacts`: 1 for a real box.
    pub contact_mask: Vec<f32>,
    /// `floor_points × 4`: position, outward normal.
    pub floor: Vec<f32>,
    /// `free_points × 3`: position, 1 (or a single zero point repeated when nobody walks).
    pub free: Vec<f32>,
    /// The room type, one-hot over [`RoomType::ALL`] (read by models with a room token).
    pub room: Vec<f32>,
    /// Pieces per category ([`ModelConfig::count_width`]; × [`COUNT_SCALE`]), read by models with
    /// count conditioning; zeros until [`Features::set_counts`].
    pub counts: Vec<f32>,
}

/// How a piece count enters the count condition: 4 pieces of a category read as 1.
pub const COUNT_SCALE: f32 = 0.25;

impl Features {
    /// Features of `cond`, the conditions of a room of type `room`, for a model of `cfg` with
    /// `bounds`.
    pub fn of(cond: &Conditions, room: RoomType, bounds: &Bounds, cfg: &ModelConfig) -> Features {
        let center = cond.window.center;
        let xy = |x: f64, y: f64| {
            let s = bounds.scale_center([x, y, 0.0]);
            [s[0] as f32, s[1] as f32]
        };
        let mut contacts = vec![0f32; cfg.max_contacts * CONTACT_FEATURES];
        let mut contact_mask = vec![0f32; cfg.max_contacts];
        for (i, (b, action)) in super::anchors::anchor_boxes(cond, cfg).into_iter().take(cfg.max_contacts).enumerate() {
            let rel = [b.center.x - center.x, b.center.y - center.y, b.center.z];
            let c = bounds.scale_center(rel);
            let s = bounds.scale_size(b.size.to_array());
            let kind = [Action::Sit, Action::Lie, Action::Touch].map(|a| if Some(a) == action { 1.0 } else { 0.0 });
            let values = [c[0], c[1], c[2], s[0], s[1], s[2], b.yaw.cos(), b.yaw.sin()];
            let row = &mut contacts[i * CONTACT_FEATURES..(i + 1) * CONTACT_FEATURES];
            for (dst, v) in row.iter_mut().zip(values.into_iter().chain(kind)) {
                *dst = v as f32;
            }
            contact_mask[i] = 1.0;
        }

        let mut floor = Vec::with_capacity(cfg.floor_points * FLOOR_FEATURES);
        for i in 0..cfg.floor_points {
            let p = &cond.floor_points[spread(i, cfg.floor_points, cond.floor_points.len())];
            let [x, y] = xy(p.position[0], p.position[1]);
            floor.extend([x, y, p.normal[0] as f32, p.normal[1] as f32]);
        }

        let pixels: Vec<(usize, usize)> = cond
            .free_space
            .rows()
            .enumerate()
            .flat_map(|(j, row)| row.iter().enumerate().filter(|(_, set)| **set).map(move |(i, _)| (i, j)))
            .collect();
        let mut free = Vec::with_capacity(cfg.free_points * FREE_FEATURES);
        for k in 0..cfg.free_points {
            if pixels.is_empty() {
                free.extend([0.0, 0.0, 0.0]);
            } else {
                let (i, j) = pixels[spread(k, cfg.free_points, pixels.len())];
                let p = cond.window.pixel_center(i, j) - center;
                let [x, y] = xy(p.x, p.y);
                free.extend([x, y, 1.0]);
            }
        }
        let room = RoomType::ALL.map(|r| if r == room { 1.0 } else { 0.0 }).to_vec();
        let counts = vec![0.0; cfg.count_width()];
        Features { contacts, contact_mask, floor, free, room, counts }
    }

    /// Sets the count condition to `counts` pieces per category (the model's class order).
    pub fn set_counts(&mut self, counts: &[u8]) {
        debug_assert_eq!(counts.len(), self.counts.len());
        for (dst, &n) in self.counts.iter_mut().zip(counts) {
            *dst = f32::from(n) * COUNT_SCALE;
        }
    }

    /// Applies `g` to every position and direction.
    pub fn transform(&mut self, g: Dihedral) {
        for row in self.contacts.chunks_exact_mut(CONTACT_FEATURES) {
            g.apply(row, 0);
            g.apply_yaw(row, 6);
        }
        for row in self.floor.chunks_exact_mut(FLOOR_FEATURES) {
            g.apply(row, 0);
            g.apply(row, 2);
        }
        for row in self.free.chunks_exact_mut(FREE_FEATURES) {
            g.apply(row, 0);
        }
    }
}

/// Index of item `i` of `n` spread evenly over `len` items (cycling when `len < n`).
fn spread(i: usize, n: usize, len: usize) -> usize {
    if len >= n { i * len / n } else { i % len }
}

/// A symmetry of the square window about its centre: an optional mirror (x → −x) then
/// `quarter_turns` counter-clockwise quarter turns.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dihedral {
    /// Counter-clockwise quarter turns (0–3).
    pub quarter_turns: u8,
    /// Mirror x → −x first.
    pub mirror: bool,
}

impl Dihedral {
    /// All eight symmetries, identity first.
    pub fn all() -> impl Iterator<Item = Dihedral> {
        (0..8u8).map(|k| Dihedral { quarter_turns: k % 4, mirror: k >= 4 })
    }

    /// Transforms the point stored at `v[at], v[at + 1]`.
    pub fn apply(&self, v: &mut [f32], at: usize) {
        let (mut x, mut y) = (v[at], v[at + 1]);
        if self.mirror {
            x = -x;
        }
        for _ in 0..self.quarter_turns {
            (x, y) = (-y, x);
        }
        v[at] = x;
        v[at + 1] = y;
    }

    /// Transforms the yaw stored as (cos, sin) at `v[at], v[at + 1]`. A mirrored box keeps its front
    /// (local +y) mirrored, which is yaw → −yaw.
    pub fn apply_yaw(&self, v: &mut [f32], at: usize) {
        if self.mirror {
            v[at + 1] = -v[at + 1];
        }
        for _ in 0..self.quarter_turns {
            let (c, s) = (v[at], v[at + 1]);
            v[at] = -s;
            v[at + 1] = c;
        }
    }

    /// Transforms object tokens (slots × `dim`) in place.
    pub fn apply_tokens(&self, tokens: &mut [f32], dim: usize) {
        for t in tokens.chunks_exact_mut(dim) {
            self.apply(t, 0);
            self.apply_yaw(t, 6);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::generate_room;
    use crate::generator::{Example, tokens};
    use crate::scene::{Object, RoomType};

    #[test]
    fn eight_distinct_symmetries_that_compose_to_identity() {
        let mut seen = Vec::new();
        for g in Dihedral::all() {
            let mut v = [0.3f32, 0.7];
            g.apply(&mut v, 0);
            seen.push(((v[0] * 1000.0) as i32, (v[1] * 1000.0) as i32));
            // Four turns bring any point back; a mirror twice too.
            let mut w = [0.3f32, 0.7];
            for _ in 0..4 {
                Dihedral { quarter_turns: 1, mirror: false }.apply(&mut w, 0);
            }
            assert_eq!(w, [0.3, 0.7]);
        }
        seen.sort();
        seen.dedup();
        assert_eq!(seen.len(), 8);
    }

    #[test]
    fn transforming_tokens_moves_the_boxes_like_the_world() {
        // A box transformed through its tokens has the corners of the box transformed in the world.
        let scene = generate_room(RoomType::Bedroom, 5, 2, false).scene;
        let cfg = ModelConfig::tiny(RoomType::Bedroom);
        let mut stats = crate::data::SplitStats::default();
        stats.add(&scene);
        let bounds = Bounds::from_stats(&stats);
        let e = Example::of(&scene, &bounds, &cfg);
        for g in Dihedral::all() {
            let t = e.transformed(g, &cfg);
            let decoded = tokens::decode(&t.tokens, glam::DVec2::ZERO, 2.6, &bounds, &cfg);
            let original = tokens::decode(&e.tokens, glam::DVec2::ZERO, 2.6, &bounds, &cfg);
            for (a, b) in original.iter().zip(&decoded) {
                let corners = |o: &Object| {
                    let mut c: Vec<(i64, i64)> = o
                        .obox()
                        .footprint()
                        .iter()
                        .map(|p| ((p.x * 1e4).round() as i64, (p.y * 1e4).round() as i64))
                        .collect();
                    c.sort();
                    c
                };
                let moved: Vec<(i64, i64)> = {
                    let mut c: Vec<(i64, i64)> = a
                        .obox()
                        .footprint()
                        .iter()
                        .map(|p| {
                            let mut v = [p.x as f32, p.y as f32];
                            g.apply(&mut v, 0);
                            ((v[0] as f64 * 1e4).round() as i64, (v[1] as f64 * 1e4).round() as i64)
                        })
                        .collect();
                    c.sort();
                    c
                };
                let got = corners(b);
                for (m, g2) in moved.iter().zip(&got) {
                    assert!((m.0 - g2.0).abs() <= 2 && (m.1 - g2.1).abs() <= 2, "{g:?} {moved:?} {got:?}");
                }
            }
        }
    }
}
