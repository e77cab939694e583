//! Keeping a footprint inside the floor plan: whether it fits with a 5 mm clearance, the worst way it
//! does not (a corner outside or too near a wall, or a polygon corner — an L-shaped room's inner
//! corner — inside the footprint) and the move that mends that, repeated into one push.
//!
//! Polishing uses these; they move nothing themselves.

use crate::geom::{OBox, Polygon};
use glam::DVec2;

/// Clearance kept from walls and between pushed-apart objects (m).
pub(super) const CLEARANCE: f64 = 0.005;

/// The move that brings `b`'s footprint inside `polygon` with `CLEARANCE` to spare, a few steps of
/// the worst offence first: a footprint corner outside (or too near the boundary), or a polygon
/// corner inside the footprint (an L-shaped room's inner corner, which all four footprint corners
/// can miss).
pub(super) fn inside_push(b: &OBox, polygon: &Polygon) -> DVec2 {
    let mut total = DVec2::ZERO;
    for _ in 0..12 {
        let moved = OBox::new(b.center + total.extend(0.0), b.size, b.yaw);
        let Some((_, push)) = worst_offence(&moved, polygon) else { break };
        total += push;
    }
    total
}

/// Whether `b`'s footprint lies inside `polygon` with `CLEARANCE` to spare.
pub(super) fn fits_inside(b: &OBox, polygon: &Polygon) -> bool {
    worst_offence(b, polygon).is_none()
}

/// The worst way `b`'s footprint fails to lie inside `polygon` with `CLEARANCE` to spare (a corner
/// outside or too near the boundary, a polygon corner inside the footprint): how far, and the move
/// that mends it; `None` when it fits.
pub(super) fn worst_offence(b: &OBox, polygon: &Polygon) -> Option<(f64, DVec2)> {
    let (ax, ay) = b.axes();
    let half = b.half().truncate();
    let centre = b.center.truncate();
    let mut worst: Option<(f64, DVec2)> = None;
    let mut consider = |excess: f64, push: DVec2| {
        if excess > 1e-9 && worst.is_none_or(|(e, _)| excess > e) {
            worst = Some((excess, push));
        }
    };
    for p in b.footprint() {
        let inside = polygon.contains(p);
        let q = polygon.nearest_boundary_point(p);
        let distance = p.distance(q);
        let excess = if inside { CLEARANCE - distance } else { distance + CLEARANCE };
        let inward = if inside { p - q } else { q - p };
        consider(excess, inward.try_normalize().unwrap_or(DVec2::ZERO) * excess);
    }
    for &v in &polygon.points {
        let local = DVec2::new((v - centre).dot(ax), (v - centre).dot(ay));
        let exit = half - local.abs();
        if exit.x <= 0.0 || exit.y <= 0.0 {
            continue;
        }
        // Move the footprint off the corner through its nearer side.
        let push = if exit.x < exit.y {
            -ax * local.x.signum() * (exit.x + CLEARANCE)
        } else {
            -ay * local.y.signum() * (exit.y + CLEARANCE)
        };
        consider(exit.x.min(exit.y) + CLEARANCE, push);
    }
    worst
}
