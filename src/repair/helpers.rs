//! Geometry every repair step shares (ours): moving and narrowing a piece, a contact box's extent
//! in a piece's frame and the part of the piece it must be on, the moves that keep people on their
//! pieces, separating two footprints, keeping a footprint inside the floor plan (a gap from the
//! walls, off an L-shaped room's inner corner).
//!
//! Steps import these; they decide nothing and read no configuration but what they are given.

use super::completion::SeatGaps;
use super::config::{HoldingConfig, NarrowingConfig};
use crate::furniture::{PartRole, template};
use crate::geom::{OBox, Polygon, facing};
use crate::human::ContactBox;
use crate::scene::{Action, Group, Object};
use glam::DVec2;

pub fn shift(o: &mut Object, m: DVec2) {
    o.center[0] += m.x;
    o.center[1] += m.y;
}

/// Whether `contact` is a palm on `o`'s front face: a touch of a cabinet, shelf or table taller
/// than `rules.top_touch_height` (the data touches such a piece on its front, facing it).
pub fn touches_front(o: &Object, contact: &ContactBox, rules: &HoldingConfig) -> bool {
    contact.action == Action::Touch
        && o.size[2] > rules.top_touch_height
        && matches!(o.category.group(), Group::Table | Group::Cabinet | Group::Shelf)
}

/// The part of `o`'s footprint (local min, max corners) the person of `contact` must be on: a
/// seat's or bed's surface for sitting and lying (on a chair or sofa, clear of the backrest and
/// near enough the front edge for the knees to pass it, [`SeatGaps`]), the whole footprint
/// otherwise.
pub fn holding_region(o: &Object, contact: &ContactBox, gaps: &SeatGaps, rules: &HoldingConfig) -> (DVec2, DVec2) {
    let half = DVec2::new(o.size[0], o.size[1]) * 0.5;
    let action = contact.action;
    if touches_front(o, contact, rules) {
        // The pressed volume just behind the front face (local +y), where the data puts the palm.
        let (lo, hi) = local_extent(&contact.obox, &o.obox());
        let depth = hi.y - lo.y + rules.front_touch_slack;
        return (DVec2::new(-half.x, (half.y - depth).max(-half.y)), half);
    }
    let Some(surface) = template(o).surface.filter(|_| matches!(action, Action::Sit | Action::Lie)) else {
        return (-half, half);
    };
    if action == Action::Sit && o.category.group() == Group::Bed {
        return bed_edge_region(o, contact, (surface.min, surface.max), rules);
    }
    let backed = action == Action::Sit && matches!(o.category.group(), Group::Chair | Group::Sofa);
    if !backed {
        return (surface.min, surface.max);
    }
    // The box's front at most `gaps.front` behind the seat's front edge (local +y), unless that
    // leaves no room behind: a seat too shallow for it.
    let (lo, hi) = local_extent(&contact.obox, &o.obox());
    let start = (surface.min.y + gaps.back).max(surface.max.y - gaps.front(contact, o) - (hi.y - lo.y));
    (DVec2::new(surface.min.x, start), surface.max)
}

/// Where a bed sitter's support box must be (local min, max corners): against the edge of the
/// mattress they face (overhanging it by up to `rules.bed_edge_overhang`, its front at most
/// `rules.bed_edge_band` behind it), so that their lower legs hang outside the bed, not in it.
pub fn bed_edge_region(
    o: &Object,
    contact: &ContactBox,
    (mut lo, mut hi): (DVec2, DVec2),
    rules: &HoldingConfig,
) -> (DVec2, DVec2) {
    let (k, ahead) = bed_edge_faced(o, contact);
    let (box_lo, box_hi) = local_extent(&contact.obox, &o.obox());
    let reach = box_hi[k] - box_lo[k] + rules.bed_edge_overhang + rules.bed_edge_band;
    if ahead {
        hi[k] += rules.bed_edge_overhang;
        lo[k] = lo[k].max(hi[k] - reach);
    } else {
        lo[k] -= rules.bed_edge_overhang;
        hi[k] = hi[k].min(lo[k] + reach);
    }
    (lo, hi)
}

/// The edge of bed `o` that `contact`'s person faces: its local axis (0: x, 1: y) and whether it is
/// the edge on that axis's positive side.
pub fn bed_edge_faced(o: &Object, contact: &ContactBox) -> (usize, bool) {
    let f = bed_local_facing(o, contact);
    let k = if f.x.abs() >= f.y.abs() { 0 } else { 1 };
    (k, f[k] > 0.0)
}

/// The way `contact`'s person faces, in `o`'s frame (unit).
pub fn bed_local_facing(o: &Object, contact: &ContactBox) -> DVec2 {
    facing(contact.obox.yaw - o.yaw)
}

/// The contact box's footprint corners in `o`'s frame: (min, max) per axis.
pub fn local_extent(contact: &OBox, o: &OBox) -> (DVec2, DVec2) {
    let corners = contact.footprint().map(|p| o.to_local(p.extend(o.center.z)).truncate());
    let lo = corners.iter().fold(DVec2::splat(f64::INFINITY), |a, p| a.min(*p));
    let hi = corners.iter().fold(DVec2::splat(f64::NEG_INFINITY), |a, p| a.max(*p));
    (lo, hi)
}

/// The smallest move of `o` (world, m) that puts `contact`'s footprint inside the part of `o` it
/// must be on ([`holding_region`]), or centres it there where it cannot fit.
pub fn containment_shift(contact: &ContactBox, gaps: &SeatGaps, o: &Object, rules: &HoldingConfig) -> DVec2 {
    let b = o.obox();
    let (lo, hi) = local_extent(&contact.obox, &b);
    let (region_lo, region_hi) = holding_region(o, contact, gaps, rules);
    let mut s = DVec2::ZERO;
    for k in 0..2 {
        // Any shift in [hi − region_hi, lo − region_lo] contains the box; an empty range: centre it.
        let (from, to) = (hi[k] - region_hi[k], lo[k] - region_lo[k]);
        s[k] = if from > to { (hi[k] + lo[k] - region_hi[k] - region_lo[k]) * 0.5 } else { 0.0f64.clamp(from, to) };
    }
    let (ax, ay) = b.axes();
    ax * s.x + ay * s.y
}

/// `m` (world) limited, along each of `o`'s axes, to the moves that keep every `held` box on the
/// part of `o` it must be on ([`holding_region`]); `m` itself when `o` holds nothing.
pub fn within_slack(o: &Object, held: &[(&ContactBox, &SeatGaps)], m: DVec2, rules: &HoldingConfig) -> DVec2 {
    if held.is_empty() {
        return m;
    }
    let b = o.obox();
    let (ax, ay) = b.axes();
    let mut local = DVec2::new(m.dot(ax), m.dot(ay));
    for (contact, gaps) in held {
        let (lo, hi) = local_extent(&contact.obox, &b);
        let (region_lo, region_hi) = holding_region(o, contact, gaps, rules);
        for k in 0..2 {
            // Moving o by s moves the box by −s in o's frame: s ∈ [hi − region_hi, lo − region_lo].
            let (from, to) = ((hi[k] - region_hi[k]).min(0.0), (lo[k] - region_lo[k]).max(0.0));
            local[k] = local[k].clamp(from, to);
        }
    }
    ax * local.x + ay * local.y
}

/// The moves of `a` (m) that separate its footprint from `b`'s along each separating axis (both
/// directions), `gap` (m) apart, shortest first; empty if the footprints do not overlap.
pub fn footprint_separations(a: &OBox, b: &OBox, gap: f64) -> Vec<DVec2> {
    let (pa, pb) = (a.footprint(), b.footprint());
    let (a1, a2) = a.axes();
    let (b1, b2) = b.axes();
    let mut out = Vec::with_capacity(8);
    for axis in [a1, a2, b1, b2] {
        let span = |ps: &[DVec2; 4]| {
            ps.iter().map(|p| p.dot(axis)).fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| (l.min(v), h.max(v)))
        };
        let ((la, ha), (lb, hb)) = (span(&pa), span(&pb));
        if ha.min(hb) - la.max(lb) <= 0.0 {
            return Vec::new();
        }
        // Moving a along +axis until its low end passes b's high end, or along −axis.
        out.push(axis * (hb - la + gap));
        out.push(-axis * (ha - lb + gap));
    }
    out.sort_by(|x, y| x.length().total_cmp(&y.length()));
    out
}

/// The move that brings `b`'s footprint inside `polygon` with `gap` (m) to spare, a few steps of
/// the worst offence first: a footprint corner outside (or too near the boundary), or a polygon
/// corner inside the footprint (an L-shaped room's inner corner, which all four footprint corners
/// can miss).
pub fn inside_push(b: &OBox, polygon: &Polygon, gap: f64) -> DVec2 {
    let mut total = DVec2::ZERO;
    for _ in 0..12 {
        let moved = OBox::new(b.center + total.extend(0.0), b.size, b.yaw);
        let Some((_, push)) = worst_offence(&moved, polygon, gap) else { break };
        total += push;
    }
    total
}

/// Whether `b`'s footprint lies inside `polygon` with `gap` (m) to spare.
pub fn fits_inside(b: &OBox, polygon: &Polygon, gap: f64) -> bool {
    worst_offence(b, polygon, gap).is_none()
}

/// The worst way `b`'s footprint fails to lie inside `polygon` with `gap` (m) to spare (a corner
/// outside or too near the boundary, a polygon corner inside the footprint): how far, and the move
/// that mends it; `None` when it fits.
pub fn worst_offence(b: &OBox, polygon: &Polygon, gap: f64) -> Option<(f64, DVec2)> {
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
        let excess = if inside { gap - distance } else { distance + gap };
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
            -ax * local.x.signum() * (exit.x + gap)
        } else {
            -ay * local.y.signum() * (exit.y + gap)
        };
        consider(exit.x.min(exit.y) + gap, push);
    }
    worst
}

/// The most a piece `size` long along an axis may be cut along it (m; by default 10 cm and a
/// quarter of it).
pub fn max_cut(size: f64, limits: &NarrowingConfig) -> f64 {
    limits.max.min(limits.max_share * size)
}

/// Cuts `o` so that the side it would move away from by `m` (world) comes in by `m`, its other
/// side staying put, if each cut along its own axes is at most [`max_cut`] there. Returns whether
/// it cut.
pub fn narrow_by(o: &mut Object, m: DVec2, limits: &NarrowingConfig) -> bool {
    let (ax, ay) = o.obox().axes();
    let cuts = [ax.dot(m), ay.dot(m)];
    if cuts.iter().zip(o.size).any(|(c, size)| c.abs() > max_cut(size, limits)) {
        return false;
    }
    for (k, c) in cuts.into_iter().enumerate() {
        o.size[k] -= c.abs();
    }
    o.center[0] += m.x * 0.5;
    o.center[1] += m.y * 0.5;
    true
}

/// Whether `o` stands solid to the floor (no legs to put feet between): sitters' and touchers'
/// shins and feet are in its way too.
pub fn is_solid(o: &Object) -> bool {
    !template(o).parts.iter().any(|p| p.role == PartRole::Leg)
}
