//! Putting back against a wall the pieces the data always stands against one (ours, part of
//! repair): beds, cabinets, shelves, sofas, desks, dressing and console tables — in the
//! calibrated test splits every one of them has its back within 10 cm of a wall, while the models
//! leave two thirds of them out in the room, where walkers walk into them.
//!
//! For a square piece (repair squares every piece first) the walls parallel to its sides and
//! facing a side over most of its width are found: a piece that holds nobody may be turned to put
//! its back to any of them and moved there, `WALL_GAP` from it ([`wall_poses`]; the caller picks
//! the pose least in people's way); a piece that holds people is not turned and only moves towards
//! the wall behind its back, as far as its people stay on it (the caller limits the move). A wall
//! for relocating a piece anywhere along it: [`wall_spots`]. This module only computes poses; it
//! does not look at people or other pieces.

use super::config::WallsConfig;
use crate::data::layout::WALL_GAP;
pub use crate::data::stands_against_wall;
use crate::geom::{OBox, Polygon, yaw_facing};
use glam::DVec2;
use std::f64::consts::{FRAC_PI_2, PI};

/// The yaws and centre moves (world, m) that put `b`'s back `WALL_GAP` from a wall: the walls behind
/// it and in front of it (turned half round) nearest first, then the walls beside it (turned a
/// quarter, which swaps its footprint's axes) nearest first; empty when no wall faces any side.
/// The caller picks among them (repair: the first of those least in people's way).
pub fn wall_poses(b: &OBox, polygon: &Polygon, cfg: &WallsConfig) -> Vec<(f64, DVec2)> {
    let (ax, ay) = b.axes();
    let half = b.half().truncate();
    let centre = b.center.truncate();
    // (back normal, turn, quarter turn?): a turn by +π/2 puts the back (local −y) towards +x.
    let sides = [(-ay, 0.0, false), (ay, PI, false), (ax, FRAC_PI_2, true), (-ax, -FRAC_PI_2, true)];
    let mut poses: Vec<(bool, f64, f64, DVec2)> = sides
        .into_iter()
        .filter_map(|(n, turn, quarter)| {
            let gap = wall_gap(centre, n, half.y, half.x, polygon, cfg)?;
            Some((quarter, gap, b.yaw + turn, n * (gap - WALL_GAP)))
        })
        .collect();
    poses.sort_by(|x, y| x.0.cmp(&y.0).then(x.1.total_cmp(&y.1)));
    poses.into_iter().map(|(_, _, yaw, m)| (yaw, m)).collect()
}

/// The poses (yaw, centre) that stand a `width` × `depth` footprint with its back `WALL_GAP` from
/// a wall of `polygon`, facing into the room: along every wall longer than it, every `SPOT_STEP`
/// from one end and the spot nearest `near`. Whether a pose fits the room (corners, other walls) is
/// left to the caller.
pub fn wall_spots(width: f64, depth: f64, near: DVec2, polygon: &Polygon, cfg: &WallsConfig) -> Vec<(f64, DVec2)> {
    let mut spots = Vec::new();
    for wall in polygon.walls() {
        let (lo, hi) = (width * 0.5, wall.length - width * 0.5);
        if hi < lo {
            continue;
        }
        let at = |t: f64| (yaw_facing(wall.inward), wall.point(t, depth * 0.5 + WALL_GAP));
        let steps = ((hi - lo) / cfg.spot_step).floor() as usize;
        spots.extend((0..=steps).map(|k| at(lo + k as f64 * cfg.spot_step)));
        spots.push(at((near - wall.start).dot(wall.along).clamp(lo, hi)));
    }
    spots
}

/// The move (world, m) that puts `b`'s back `WALL_GAP` from the wall behind it, unturned; `None`
/// when no wall faces its back.
pub fn to_wall_behind(b: &OBox, polygon: &Polygon, cfg: &WallsConfig) -> Option<DVec2> {
    let (_, ay) = b.axes();
    let half = b.half().truncate();
    let gap = wall_gap(b.center.truncate(), -ay, half.y, half.x, polygon, cfg)?;
    Some(-ay * (gap - WALL_GAP))
}

/// How far (m) the nearest wall lies beyond the side of a footprint centred at `center` whose
/// outward normal is `n`, `reach` from the centre, `across` half wide: walls parallel to the side
/// (within 0.06°), facing at least `FACING_SHARE` of its width, beyond the centre (a piece the model
/// pushed through a wall goes back to that wall, not across the room to the next one).
fn wall_gap(center: DVec2, n: DVec2, reach: f64, across: f64, polygon: &Polygon, cfg: &WallsConfig) -> Option<f64> {
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
            (gap > -reach && facing >= cfg.facing_share * (hi - lo)).then_some(gap)
        })
        .min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Category;
    use glam::DVec3;

    fn room() -> Polygon {
        crate::scene::FloorPlan { polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], height: 2.8 }.polygon()
    }

    #[test]
    fn a_wardrobe_out_in_the_room_may_turn_its_back_to_any_wall_the_nearest_in_front_or_behind_first() {
        // 1.6 × 0.6 m facing −y (yaw π) at (2, 1.2) in a 4 × 3 m room: its front 0.9 m from the
        // south wall (y = 0), its back 1.5 m from the north one, its sides (after a quarter turn,
        // 0.3 m from the centre) 1.7 m from the west and east walls.
        let b = OBox::new(DVec3::new(2.0, 1.2, 1.0), DVec3::new(1.6, 0.6, 2.0), PI);
        let poses = wall_poses(&b, &room(), &WallsConfig::default());
        let expected = [
            (2.0 * PI, DVec2::new(0.0, -(0.9 - WALL_GAP))),
            (PI, DVec2::new(0.0, 1.5 - WALL_GAP)),
            // Turned +π/2 (yaw 3π/2, facing +x): the back goes west; −π/2: east.
            (PI + FRAC_PI_2, DVec2::new(-(1.7 - WALL_GAP), 0.0)),
            (PI - FRAC_PI_2, DVec2::new(1.7 - WALL_GAP, 0.0)),
        ];
        assert_eq!(poses.len(), expected.len(), "{poses:?}");
        for ((yaw, m), (want_yaw, want_m)) in poses.iter().zip(expected) {
            assert!((yaw - want_yaw).abs() < 1e-12 && (*m - want_m).length() < 1e-12, "{poses:?}");
        }
        // Already against the south wall with its back, 5 cm off it, beside the east wall: stays.
        let b = OBox::new(DVec3::new(3.2, 0.35, 1.0), DVec3::new(1.6, 0.6, 2.0), 0.0);
        let (yaw, m) = wall_poses(&b, &room(), &WallsConfig::default())[0];
        assert!(yaw.abs() < 1e-12 && m.length() < 1e-12, "{yaw} {m}");
        // Pushed 10 cm through the south wall: back to it, not across the room.
        let b = OBox::new(DVec3::new(2.0, 0.2, 1.0), DVec3::new(1.6, 0.6, 2.0), 0.0);
        let (yaw, m) = wall_poses(&b, &room(), &WallsConfig::default())[0];
        assert!(yaw.abs() < 1e-12 && (m - DVec2::new(0.0, 0.1 + WALL_GAP)).length() < 1e-12, "{yaw} {m}");
    }

    #[test]
    fn a_holder_moves_only_to_the_wall_behind_it() {
        // Facing +y, back 0.9 m from the south wall: 0.85 m back.
        let b = OBox::new(DVec3::new(2.0, 1.2, 0.4), DVec3::new(1.6, 0.6, 0.8), 0.0);
        assert!(
            (to_wall_behind(&b, &room(), &WallsConfig::default()).unwrap() - DVec2::new(0.0, -0.85)).length() < 1e-12
        );
        // In an L-shaped room, walls facing less than 60 % of the back do not count.
        let l = crate::scene::FloorPlan {
            polygon: vec![[0.0, 0.0], [0.5, 0.0], [0.5, 1.0], [4.0, 1.0], [4.0, 3.0], [0.0, 3.0]],
            height: 2.8,
        }
        .polygon();
        // Back at y = 1.7 over x 0.4..2.0: the inner wall y = 1 (x 0.5..4) faces 94 % of it.
        let sofa = OBox::new(DVec3::new(1.2, 2.0, 0.4), DVec3::new(1.6, 0.6, 0.8), 0.0);
        assert!(
            (to_wall_behind(&sofa, &l, &WallsConfig::default()).unwrap() - DVec2::new(0.0, -(0.7 - WALL_GAP))).length()
                < 1e-12
        );
        // Over x 0..1: the wall y = 0 faces half of it, the wall y = 1 the other half: none.
        let corner = OBox::new(DVec3::new(0.5, 2.0, 0.4), DVec3::new(1.0, 0.6, 0.8), 0.0);
        assert_eq!(to_wall_behind(&corner, &l, &WallsConfig::default()), None);
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
