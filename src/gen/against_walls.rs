//! J_w (ours): pieces the data always stands against a wall are drawn back to the wall behind
//! them, with gradients.
//!
//! Every bed, cabinet, shelf, sofa, desk, dressing and console table of the training data stands
//! with its back exactly [`WALL_GAP`](crate::data::layout::WALL_GAP) (5 cm) from a wall
//! ([`stands_against_wall`]; unless `synth --gap-spread` drew the gaps). The model puts them near
//! one but not on the centimetre (unguided val bedrooms: the wall pieces' distance spreads from
//! 15 cm in the wall to 11 cm out between the 10th and 90th percentiles), and repair
//! puts them back (`repair::walls`). This term does it during sampling, so that the other terms
//! see the piece where it will stand: for each of the two corners of such a piece's back edge
//! whose nearest wall is behind it (within [`BEHIND_COS`] of straight back) and no more than
//! `reach` beyond `WALL_GAP`, half the square of how much farther than `WALL_GAP` it is. Both
//! corners at the gap is the data's rule: the piece's back flush and parallel to the wall. It only
//! pulls (a corner nearer than `WALL_GAP` is J_b's), moves and turns; it does not resize.
//!
//! It is quadratic, and weighted low, because a guidance step moves a piece by γ × ℓ² ≈ 0.77 m
//! per unit of gradient ([`CENTRE_STEP_LENGTH`](super::guidance::CENTRE_STEP_LENGTH) ℓ): a term
//! whose slope does not fall to zero at its target overshoots it every step (weighted 1 with a
//! 5 cm Huber zone, it jolted wall pieces into J_b's margin and back, and the two together shrank
//! them: val bedrooms' cabinets 0.45 → 0.25 m deep). Not here: the weights and steps
//! ([`super::guidance`]).

use super::guidance::{GuidedObject, ObjectGradient};
use crate::data::stands_against_wall;
use crate::geom::Polygon;
use glam::DVec2;

/// The nearest wall counts as behind a piece when the direction to it is within about 25° of
/// straight back (the cosine).
pub const BEHIND_COS: f64 = 0.9;

/// Σ over the pieces that stand against a wall, over the two corners of their back edge, of half
/// the square of the corner's distance beyond `gap` (m; the data's gap, [`WALL_GAP`](crate::data::layout::WALL_GAP) unless its
/// gaps are drawn) to the wall behind it, when that is at most `reach` (m) beyond it, with each
/// piece's gradient (centre x and y, and yaw: a piece turned off its wall has one corner farther
/// than the other, and is turned back parallel to it).
pub fn gap_to_wall_behind(
    objects: &[GuidedObject],
    floor: &Polygon,
    gap: f64,
    reach: f64,
) -> (f64, Vec<ObjectGradient>) {
    let mut total = 0.0;
    let mut grads = vec![[0.0; 7]; objects.len()];
    for (o, g) in objects.iter().zip(&mut grads) {
        if !stands_against_wall(o.category) {
            continue;
        }
        // A corner at local (x, y) stands at centre + x·ax + y·ay; turning moves it along x·ay − y·ax.
        let (ax, ay) = o.obox().axes();
        let rotate = |v: DVec2| ax * v.x + ay * v.y;
        let turned = |v: DVec2| ay * v.x - ax * v.y;
        let back = -ay;
        for side in [-1.0, 1.0] {
            let local = DVec2::new(side * o.size.x * 0.5, -o.size.y * 0.5);
            let corner = o.center.truncate() + rotate(local);
            if !floor.contains(corner) {
                continue;
            }
            let wall = floor.nearest_boundary_point(corner);
            let distance = corner.distance(wall);
            let excess = distance - gap;
            if excess <= 0.0 || excess > reach || (wall - corner).dot(back) < BEHIND_COS * distance {
                continue;
            }
            total += excess * excess * 0.5;
            // Moving the corner towards the wall shortens the distance at rate 1.
            let away = (corner - wall) / distance * excess;
            g[0] += away.x;
            g[1] += away.y;
            g[6] += away.dot(turned(local));
        }
    }
    (total, grads)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::layout::WALL_GAP;
    use crate::scene::Category;
    use glam::DVec3;

    fn piece(category: Category, x: f64, y: f64, yaw: f64) -> GuidedObject {
        GuidedObject { center: DVec3::new(x, y, 0.5), size: DVec3::new(1.0, 0.6, 1.0), yaw, hanging: false, category }
    }

    fn room() -> Polygon {
        Polygon { points: vec![DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0), DVec2::new(4.0, 3.0), DVec2::new(0.0, 3.0)] }
    }

    #[test]
    fn a_wardrobe_off_the_wall_behind_it_is_drawn_back_to_the_data_gap() {
        // Facing +y (yaw 0), its back 13 cm from the wall y = 0: both corners 8 cm too far.
        let (j, g) = gap_to_wall_behind(&[piece(Category::Wardrobe, 2.0, 0.43, 0.0)], &room(), WALL_GAP, 0.3);
        assert!((j - 0.08 * 0.08).abs() < 1e-12, "{j}");
        assert!((g[0][1] - 0.16).abs() < 1e-12 && g[0][0].abs() < 1e-12 && g[0][6].abs() < 1e-12, "{:?}", g[0]);
        // At the gap, nearer (J_b's), or beyond the reach: nothing.
        for y in [0.35, 0.32, 0.7] {
            assert_eq!(
                gap_to_wall_behind(&[piece(Category::Wardrobe, 2.0, y, 0.0)], &room(), WALL_GAP, 0.3).0,
                0.0,
                "{y}"
            );
        }
    }

    #[test]
    fn a_wider_gap_draws_back_only_beyond_it() {
        // The same wardrobe, its back 13 cm from the wall: 3 cm beyond a 10 cm gap, within 15 cm.
        let w = [piece(Category::Wardrobe, 2.0, 0.43, 0.0)];
        let (j, g) = gap_to_wall_behind(&w, &room(), 0.10, 0.3);
        assert!((j - 0.03 * 0.03).abs() < 1e-12 && (g[0][1] - 0.06).abs() < 1e-12, "{j} {:?}", g[0]);
        assert_eq!(gap_to_wall_behind(&w, &room(), 0.15, 0.3).0, 0.0);
    }

    #[test]
    fn only_pieces_the_data_stands_against_a_wall_and_only_the_wall_behind() {
        // A dining table 13 cm from a wall: the data stands it anywhere.
        assert_eq!(gap_to_wall_behind(&[piece(Category::DiningTable, 2.0, 0.43, 0.0)], &room(), WALL_GAP, 0.3).0, 0.0);
        // A wardrobe facing the wall (yaw π): the wall is in front of it, not behind.
        assert_eq!(
            gap_to_wall_behind(&[piece(Category::Wardrobe, 2.0, 0.43, std::f64::consts::PI)], &room(), WALL_GAP, 0.3).0,
            0.0
        );
        // Facing −x (yaw π/2, its back towards +x), 13 cm from the wall x = 4.
        let (j, g) = gap_to_wall_behind(
            &[piece(Category::Wardrobe, 4.0 - 0.43, 1.5, std::f64::consts::FRAC_PI_2)],
            &room(),
            WALL_GAP,
            0.3,
        );
        assert!(j > 0.0 && (g[0][0] + 0.16).abs() < 1e-9, "{j} {:?}", g[0]);
    }

    #[test]
    fn a_piece_turned_off_its_wall_is_turned_back_and_the_gradient_is_exact() {
        let o = [piece(Category::DoubleBed, 2.0, 0.45, 0.08), piece(Category::Bookshelf, 3.5, 1.4, 1.5)];
        let (_, g) = gap_to_wall_behind(&o, &room(), WALL_GAP, 0.3);
        // Turned +0.08 rad (counter-clockwise), its right back corner is the farther: turning it
        // back (clockwise) lowers J.
        assert!(g[0][6] > 0.0, "{:?}", g[0]);
        for i in 0..2 {
            for k in [0, 1, 6] {
                let at = |d: f64| {
                    let mut p = o;
                    if k == 6 {
                        p[i].yaw += d
                    } else {
                        p[i].center[k] += d
                    }
                    gap_to_wall_behind(&p, &room(), WALL_GAP, 0.3).0
                };
                let fd = (at(1e-6) - at(-1e-6)) / 2e-6;
                assert!(
                    (fd - g[i][k]).abs() < 1e-5 * (1.0 + fd.abs()),
                    "piece {i}, k {k}: fd {fd}, analytic {}",
                    g[i][k]
                );
            }
        }
    }
}
