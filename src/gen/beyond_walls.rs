//! J_b measured exactly (ours): how far each piece's footprint reaches past a margin inside the
//! floor plan's walls, with gradients.
//!
//! SHADE's J_b is the soft area of outside pixels under a footprint
//! ([`super::guidance::soft_coverage`]). Its sigmoid reaches a few pixels into the room, so it
//! keeps pushing a piece that is already inside: guided beds, wardrobes and nightstands ended
//! 8–16 cm from the wall they stand against (median 10 cm), where every piece of the training data
//! stands exactly [`WALL_GAP`](crate::data::layout::WALL_GAP) (5 cm) from it. This term is zero
//! for a piece at least `margin` inside every wall and grows with the depth beyond that:
//!
//! - each footprint corner: its depth past the line `margin` inside the walls (the floor plan's
//!   signed distance, plus `margin`);
//! - the footprint's centre, the same way: a piece that fills a notch of a U- or L-shaped floor
//!   plan has its four corners just beyond the notch's walls, centimetres deep, while the whole
//!   piece is outside (val dining rooms: an L-shaped sofa 3.6 m wide in a 3.65 m notch); its
//!   centre is a metre deep. For a piece wholly inside the room the centre lies half the piece's
//!   smaller side further in than its edges, so it adds nothing;
//! - each reflex corner of the floor plan (an L-shaped room's inner corner, which can poke into a
//!   footprint whose own corners are all inside): its depth inside the footprint plus `margin`;
//! - in a floor plan with a reflex corner, the part of the footprint outside the walls: the Huber
//!   loss of each point's depth beyond the walls integrated over the footprint, each 10 × 10 cm
//!   counting as one point ([`outside_mass`]). In a convex room a footprint corner is the deepest
//!   point of the footprint, so the corners say it all. In a U- or L-shaped room they do not: a
//!   corner in a notch is drawn to the notch's nearest wall, which may be the side the piece cannot
//!   leave by, and a piece widened over a notch brings its corners back inside while its middle
//!   stays out (val living rooms: a pendant lamp pulled into a 0.9 m notch and widened from 0.41
//!   to 0.75 m; a 3.1 m bookshelf along a notch's wall). The integral grows with the area outside,
//!   so it moves a piece out the way most of it is nearest and never widens it over the notch.
//!
//! Each depth d counts as a Huber loss: d² / 2δ up to [`SOFT_DEPTH`] δ (10 cm), d − δ/2 beyond,
//! so a piece far out is pushed at a steady rate and one that has just crossed the line gently.
//! Counted linearly, a piece hovering at the line got the full push at each crossing, its step
//! was cut to `max_step`, and the turn J_q asked for with it shrank in proportion (val bedrooms:
//! beds left 5–15° off square, their sleepers inside them). The gradient moves, resizes and turns
//! a piece: a piece turned against its wall has one corner past the line and is turned back flush
//! (without the turn, beds under sleepers drifted off square again, J_c turning them to their
//! sleepers), and moving alone is not enough for a bed the model drew longer than the floor
//! between its sleeper and the wall.
//! Not here: the weights and steps ([`super::guidance`]).

use super::guidance::{GuidedObject, ObjectGradient};
use crate::geom::{Polygon, point_segment_distance};
use glam::DVec2;

/// Depth (m) up to which a depth counts quadratically (the Huber loss's δ).
pub const SOFT_DEPTH: f64 = 0.1;

/// The Huber loss of a depth (m) and its derivative; 0 for depths ≤ 0.
pub(super) fn huber(depth: f64) -> (f64, f64) {
    if depth <= 0.0 {
        (0.0, 0.0)
    } else if depth < SOFT_DEPTH {
        (depth * depth / (2.0 * SOFT_DEPTH), depth / SOFT_DEPTH)
    } else {
        (depth - SOFT_DEPTH * 0.5, 1.0)
    }
}

/// Σ over pieces of the Huber losses of the depths (m) past `margin` inside the walls of `floor` (see the module
/// header), with each piece's gradient (centre x and y, width and depth, yaw).
pub fn depth_beyond_walls(objects: &[GuidedObject], floor: &Polygon, margin: f64) -> (f64, Vec<ObjectGradient>) {
    let reflex = reflex_corners(floor);
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        total += corners_beyond(o, floor, margin, g);
        total += walls_inside(o, &reflex, margin, g);
        if !reflex.is_empty() {
            total += outside_mass(o, floor, g);
        }
    }
    (total, grads)
}

/// Spacing (m) of the points the outside mass samples a footprint at.
const MASS_SPACING: f64 = 0.05;

/// The footprint area (m²) that counts as much as one footprint corner as deep.
const MASS_UNIT_AREA: f64 = SOFT_DEPTH * SOFT_DEPTH;

/// The Huber loss of each footprint point's depth beyond the walls of `floor` (not the margin
/// line: near the walls the corners' term measures the gap), integrated over the footprint on a
/// grid of at most [`MASS_SPACING`], in units of [`MASS_UNIT_AREA`]; its gradient (central
/// differences, the grid held fixed) added to `g`. Zero, and not sampled, for a footprint inside
/// the floor plan: all its corners inside and no floor-plan corner within it.
fn outside_mass(o: &GuidedObject, floor: &Polygon, g: &mut ObjectGradient) -> f64 {
    let b = o.obox();
    let inside = b.footprint().iter().all(|&c| floor.contains(c))
        && floor.points.iter().all(|&v| b.footprint_signed_distance(v) >= 0.0);
    if inside {
        return 0.0;
    }
    let cells = |length: f64| ((length / MASS_SPACING).ceil() as usize).clamp(1, 64);
    let (nu, nv) = (cells(o.size.x), cells(o.size.y));
    let cost = |o: &GuidedObject| {
        let (ax, ay) = o.obox().axes();
        let centre = o.center.truncate();
        let mut sum = 0.0;
        for i in 0..nu {
            let u = ((i as f64 + 0.5) / nu as f64 - 0.5) * o.size.x;
            for j in 0..nv {
                let v = ((j as f64 + 0.5) / nv as f64 - 0.5) * o.size.y;
                sum += huber(floor.signed_distance(centre + ax * u + ay * v)).0;
            }
        }
        sum * o.size.x * o.size.y / (nu * nv) as f64 / MASS_UNIT_AREA
    };
    let total = cost(o);
    if total <= 0.0 {
        return 0.0;
    }
    for (g, d) in g.iter_mut().zip(o.central_differences(&[0, 1, 3, 4, 6], 1e-5, cost)) {
        *g += d;
    }
    total
}

/// The Huber losses of the footprint corners' and centre's depths past the margin line, their
/// gradients added to `g` (the centre's moves the piece only).
fn corners_beyond(o: &GuidedObject, floor: &Polygon, margin: f64, g: &mut ObjectGradient) -> f64 {
    // A corner at local (x, y) stands at centre + x·ax + y·ay; turning moves it along x·ay − y·ax.
    let (ax, ay) = o.obox().axes();
    let rotate = |v: DVec2| ax * v.x + ay * v.y;
    let turned = |v: DVec2| ay * v.x - ax * v.y;
    let centre = o.center.truncate();
    let (a, b) = (o.size.x * 0.5, o.size.y * 0.5);
    let mut total = 0.0;
    for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (0.0, 0.0)] {
        let local = DVec2::new(sx * a, sy * b);
        let p = centre + rotate(local);
        let q = floor.nearest_boundary_point(p);
        let inside = floor.contains(p);
        let distance = p.distance(q);
        let depth = margin + if inside { -distance } else { distance };
        let (cost, slope) = huber(depth);
        if slope <= 0.0 {
            continue;
        }
        total += cost;
        // The signed distance grows along the outward normal; on the boundary itself, the normal
        // of the nearest edge.
        let outward = slope
            * if distance > 1e-12 {
                if inside { (q - p) / distance } else { (p - q) / distance }
            } else {
                outward_normal_nearest(floor, p)
            };
        g[0] += outward.x;
        g[1] += outward.y;
        g[3] += outward.dot(rotate(DVec2::new(sx * 0.5, 0.0)));
        g[4] += outward.dot(rotate(DVec2::new(0.0, sy * 0.5)));
        g[6] += outward.dot(turned(local));
    }
    total
}

/// The outward unit normal of the wall of `floor` nearest `p`.
fn outward_normal_nearest(floor: &Polygon, p: DVec2) -> DVec2 {
    floor
        .walls()
        .map(|w| (point_segment_distance(p, w.start, w.start + w.along * w.length), -w.inward))
        .min_by(|x, y| x.0.total_cmp(&y.0))
        .map_or(DVec2::ZERO, |(_, n)| n)
}

/// The Huber losses of the reflex floor-plan corners' depths inside the footprint plus the
/// margin, their gradients
/// (central differences of the exact value) added to `g`.
fn walls_inside(o: &GuidedObject, reflex: &[DVec2], margin: f64, g: &mut ObjectGradient) -> f64 {
    let cost =
        |o: &GuidedObject| reflex.iter().map(|&v| huber(margin - o.obox().footprint_signed_distance(v)).0).sum::<f64>();
    let total = cost(o);
    if total <= 0.0 {
        return 0.0;
    }
    for (g, d) in g.iter_mut().zip(o.central_differences(&[0, 1, 3, 4], 1e-5, cost)) {
        *g += d;
    }
    total
}

/// The corners of `floor` whose inside angle exceeds a half turn.
fn reflex_corners(floor: &Polygon) -> Vec<DVec2> {
    let n = floor.points.len();
    let turn = floor.signed_area().signum();
    (0..n)
        .filter_map(|i| {
            let (prev, at, next) = (floor.points[(i + n - 1) % n], floor.points[i], floor.points[(i + 1) % n]);
            ((at - prev).perp_dot(next - at) * turn < 0.0).then_some(at)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Category;
    use glam::DVec3;

    fn piece(x: f64, y: f64, w: f64, d: f64, yaw: f64) -> GuidedObject {
        GuidedObject {
            center: DVec3::new(x, y, 0.4),
            size: DVec3::new(w, d, 0.8),
            yaw,
            hanging: false,
            category: Category::Wardrobe,
        }
    }

    fn square_room() -> Polygon {
        Polygon { points: vec![DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0), DVec2::new(4.0, 4.0), DVec2::new(0.0, 4.0)] }
    }

    /// An L: the 4 × 4 square without its top-right 2 × 2 quarter; (2, 2) is its reflex corner.
    fn l_room() -> Polygon {
        let p = [(0.0, 0.0), (4.0, 0.0), (4.0, 2.0), (2.0, 2.0), (2.0, 4.0), (0.0, 4.0)];
        Polygon { points: p.iter().map(|&(x, y)| DVec2::new(x, y)).collect() }
    }

    #[test]
    fn a_piece_at_the_margin_costs_nothing_and_one_past_it_costs_its_corners_depths_huber_losses() {
        let room = square_room();
        // A 1 × 0.6 piece with its back 5.1 cm from the wall y = 0: nothing.
        let at = piece(2.0, 0.351, 1.0, 0.6, 0.0);
        assert_eq!(depth_beyond_walls(&[at], &room, 0.05).0, 0.0);
        // 2 cm further back: two corners, each 2 cm past the line: 2 × 0.02² / 0.2.
        let (j, g) = depth_beyond_walls(&[piece(2.0, 0.33, 1.0, 0.6, 0.0)], &room, 0.05);
        assert!((j - 0.004).abs() < 1e-12, "{j}");
        // Moving it into the room (+y) lowers J at rate 2 × 0.02 / 0.1; deepening it raises J at
        // half that rate.
        assert!((g[0][1] + 0.4).abs() < 1e-9 && g[0][0].abs() < 1e-9, "{:?}", g[0]);
        assert!((g[0][4] - 0.2).abs() < 1e-9 && g[0][3].abs() < 1e-9, "{:?}", g[0]);
        // 10 cm through the wall: the corners are 15 cm past the line, beyond δ: 2 × (0.15 − 0.05).
        let (j, g) = depth_beyond_walls(&[piece(2.0, 0.2, 1.0, 0.6, 0.0)], &room, 0.05);
        assert!((j - 0.20).abs() < 1e-12 && (g[0][1] + 2.0).abs() < 1e-9, "{j} {:?}", g[0]);
        // Its back exactly on the wall: pushed out along the wall's normal.
        let (j, g) = depth_beyond_walls(&[piece(2.0, 0.3, 1.0, 0.6, 0.0)], &room, 0.05);
        assert!((j - 0.025).abs() < 1e-12 && (g[0][1] + 1.0).abs() < 1e-9, "{j} {:?}", g[0]);
    }

    /// A U: the 6 × 4 rectangle without x 2–4, y 2–4.
    fn u_room() -> Polygon {
        let p = [(0.0, 0.0), (6.0, 0.0), (6.0, 4.0), (4.0, 4.0), (4.0, 2.0), (2.0, 2.0), (2.0, 4.0), (0.0, 4.0)];
        Polygon { points: p.iter().map(|&(x, y)| DVec2::new(x, y)).collect() }
    }

    #[test]
    fn a_piece_filling_a_notch_is_pushed_out_of_it_by_its_centre_and_the_part_outside() {
        // A 1.96 × 1.3 piece in the notch, its corners 2 cm past the notch's side walls.
        let room = u_room();
        let o = piece(3.0, 2.9, 1.96, 1.3, 0.0);
        let mut corners = [0.0; 7];
        // Each corner 0.02 + 0.05 past the line (quadratic); the centre 0.9 m from the notch's
        // bottom edge (y = 2), plus the margin, beyond δ: 0.95 − 0.05.
        let corner = 0.07 * 0.07 / 0.2;
        assert!((corners_beyond(&o, &room, 0.05, &mut corners) - (4.0 * corner + 0.9)).abs() < 1e-9);
        // The corners' pushes cancel; the centre pulls the piece down, into the room, at rate 1.
        assert!((corners[1] - 1.0).abs() < 1e-9 && corners[0].abs() < 1e-9, "{corners:?}");
        // All its 2.5 m² are outside, most points 0.1–0.5 m from the notch's walls: ~60 points' worth.
        let (j, g) = depth_beyond_walls(&[o], &room, 0.05);
        assert!(j > 40.0, "{j}");
        // Pulled down by it, and never sideways (the piece is symmetric about x = 3).
        assert!(g[0][1] > 40.0 && g[0][0].abs() < 1e-6 * g[0][1], "{:?}", g[0]);
    }

    #[test]
    fn a_piece_over_a_notch_moves_out_the_way_most_of_it_is_nearest_and_is_not_widened() {
        // The val living room's pendant lamp: 0.75 × 0.42 at x 2.18–2.93 across a 0.9 m notch
        // (x 2–2.9 here as x 2–4 is in the U above, so a room with its notch at x 2–2.9).
        let p = [(0.0, 0.0), (4.9, 0.0), (4.9, 7.2), (2.9, 7.2), (2.9, 2.2), (2.0, 2.2), (2.0, 7.2), (0.0, 7.2)];
        let room = Polygon { points: p.iter().map(|&(x, y)| DVec2::new(x, y)).collect() };
        let lamp = piece(2.555, 4.71, 0.75, 0.42, 0.0);
        // The corners alone pull it left, into the notch (its left corners are nearest the notch's
        // left wall), and widen it.
        let mut corners = [0.0; 7];
        corners_beyond(&lamp, &room, 0.05, &mut corners);
        assert!(corners[0] > 0.0 && corners[3] < 0.0, "{corners:?}");
        // With the part outside, it moves right, where most of it is nearest, and narrows.
        let (_, g) = depth_beyond_walls(&[lamp], &room, 0.05);
        assert!(g[0][0] < 0.0 && g[0][3] > 0.0, "{:?}", g[0]);
        // Wholly in the right wing, it costs only its corners (and nothing 5 cm from the walls).
        assert_eq!(depth_beyond_walls(&[piece(3.4, 4.71, 0.75, 0.42, 0.0)], &room, 0.05).0, 0.0);
    }

    #[test]
    fn gradients_match_finite_differences() {
        let room = l_room();
        // Turned, across the reflex corner and past the wall x = 0.
        // Sizes off the outside mass's 5 cm grid, which the finite differences would re-cut.
        let objects = [piece(2.1, 2.3, 1.21, 0.71, 0.3), piece(0.3, 1.0, 0.93, 0.52, -0.2)];
        let (_, g) = depth_beyond_walls(&objects, &room, 0.05);
        for i in 0..objects.len() {
            // Piece 0 is across the inner corner, whose term does not turn it.
            for k in if i == 0 { vec![0, 1, 3, 4] } else { vec![0, 1, 3, 4, 6] } {
                let at = |d: f64| {
                    let mut o = objects;
                    match k {
                        0 | 1 => o[i].center[k] += d,
                        3 | 4 => o[i].size[k - 3] += d,
                        _ => o[i].yaw += d,
                    }
                    depth_beyond_walls(&o, &room, 0.05).0
                };
                let fd = (at(1e-6) - at(-1e-6)) / 2e-6;
                assert!(
                    (fd - g[i][k]).abs() < 1e-4 * (1.0 + fd.abs()),
                    "piece {i}, k {k}: fd {fd}, analytic {}",
                    g[i][k]
                );
            }
        }
    }

    #[test]
    fn the_inner_corner_of_an_l_counts_when_it_pokes_into_a_piece() {
        let room = l_room();
        assert_eq!(reflex_corners(&room), vec![DVec2::new(2.0, 2.0)]);
        // A 1 × 1 piece centred at (1.6, 1.6), the reflex corner 0.1 m inside it: that depth plus
        // the margin, 0.15 m, beyond δ.
        let o = piece(1.6, 1.6, 1.0, 1.0, 0.0);
        let mut g = [0.0; 7];
        assert!((walls_inside(&o, &reflex_corners(&room), 0.05, &mut g) - 0.10).abs() < 1e-12);
        // Moved away from the corner (−x), the piece loses that depth.
        assert!(g[0] > 0.0 && g[1] > 0.0, "{g:?}");
        // Clear of it by 5 cm in both directions: nothing.
        let clear = piece(1.4, 1.4, 1.0, 1.0, 0.0);
        assert_eq!(depth_beyond_walls(&[clear], &room, 0.05).0, 0.0);
    }
}
