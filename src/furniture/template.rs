//! Furniture shape templates: the parts a piece is made of, fitted to its bounding box.
//!
//! A bounding box alone says a chair fills the air above its seat. The templates split each category
//! into parts — beds into base + mattress and headboard, chairs into seat, back and four legs, sofas
//! into seat block, back and arms, tables into top and four legs, storage into one solid body, lamps
//! into a shade on a cord — so a person's legs can go under a table and a sitter's back can rest in
//! front of a backrest. Proportions (seat heights, back thickness) are fractions of the box, chosen
//! to match the real pieces in `catalog.csv` (median chair seat 0.52 × height, sofa seat 0.5 ×
//! height, bed mattress top 0.5 × height when a headboard rises above it).
//!
//! This is the one definition used by everything that needs furniture shapes: physics worlds, MJCF
//! export, interpenetration (E_pen) and the placement of humans in the procedural dataset.

use crate::geom::OBox;
use crate::scene::{Category, Group, Object};
use glam::{DVec2, DVec3};

/// What a part is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum PartRole {
    /// A bed's base and mattress, a sofa's seat block, a stool's seat.
    Seat,
    /// A backrest or a headboard.
    Back,
    /// A sofa or armchair arm.
    Arm,
    /// A leg.
    Leg,
    /// A table or desk top.
    Top,
    /// The solid body of storage furniture (cabinets, wardrobes, shelves).
    Body,
    /// A mirror or panel standing on a dressing table.
    Panel,
    /// A lamp's shade or fitting.
    Shade,
    /// The cord a pendant lamp hangs from.
    Cord,
}

/// One box of a template, in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Part {
    /// Its role.
    pub role: PartRole,
    /// Its box (same yaw as the object).
    pub obox: OBox,
}

/// The horizontal surface a person sits or lies on, or rests a hand on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Height above the floor.
    pub height: f64,
    /// The surface's rectangle in the object's local frame (x = width, y = depth): min corner.
    pub min: DVec2,
    /// Max corner of the rectangle in the local frame.
    pub max: DVec2,
}

/// A piece's template: its parts and its top surface.
#[derive(Debug, Clone, PartialEq)]
pub struct Template {
    /// The parts.
    pub parts: Vec<Part>,
    /// Where a person sits or lies (seats, beds, sofas) or where things rest (tables, storage);
    /// `None` for lamps.
    pub surface: Option<Surface>,
}

/// Builds parts in the object's local frame, measured from the middle of the box's bottom face.
struct Builder {
    obox: OBox,
    parts: Vec<Part>,
}

impl Builder {
    /// Adds a part of `size` whose bottom-face centre is at local (x, y) and height `z0`.
    fn part(&mut self, role: PartRole, size: [f64; 3], at: [f64; 3]) {
        let [w, d, h] = size;
        if w <= 0.0 || d <= 0.0 || h <= 0.0 {
            return;
        }
        let local = DVec3::new(at[0], at[1], at[2] + h * 0.5 - self.obox.size.z * 0.5);
        let center = self.obox.to_world(local);
        self.parts.push(Part { role, obox: OBox::new(center, DVec3::new(w, d, h), self.obox.yaw) });
    }

    fn legs(&mut self, w: f64, d: f64, height: f64) {
        let t = 0.04f64.min(w * 0.2).min(d * 0.2);
        for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            self.part(PartRole::Leg, [t, t, height], [sx * (w - t) * 0.5, sy * (d - t) * 0.5, 0.0]);
        }
    }
}

/// Seat height of a legged chair of height `h`.
fn chair_seat(h: f64) -> f64 {
    (0.52 * h).clamp(0.35, 0.5).min(0.9 * h)
}

/// Seat height of an upholstered sofa or armchair of height `h`.
fn sofa_seat(h: f64) -> f64 {
    (0.5 * h).clamp(0.28, 0.48).min(0.9 * h)
}

/// Mattress top of a bed of height `h` (beds lower than 0.7 m have no headboard above the mattress).
fn bed_top(h: f64) -> f64 {
    if h > 0.7 { (0.5 * h).clamp(0.35, 0.65) } else { h }
}

/// The template of an object.
pub fn template(object: &Object) -> Template {
    template_of(object.category, &object.obox())
}

/// The template of a piece of `category` filling `obox`.
pub fn template_of(category: Category, obox: &OBox) -> Template {
    let [w, d, h] = obox.size.to_array();
    let mut b = Builder { obox: *obox, parts: Vec::new() };
    let rect = |x0: f64, y0: f64, x1: f64, y1: f64| (DVec2::new(x0, y0), DVec2::new(x1, y1));
    let full = rect(-w * 0.5, -d * 0.5, w * 0.5, d * 0.5);
    let surface = |height: f64, (min, max): (DVec2, DVec2)| Some(Surface { height, min, max });
    let upholstered = matches!(category, Category::Armchair | Category::LoungeChair);
    let group = if upholstered { Group::Sofa } else { category.group() };
    let surface = match group {
        Group::Bed => {
            let top = bed_top(h);
            let head = if h > top + 0.05 { 0.08f64.min(d * 0.05) } else { 0.0 };
            b.part(PartRole::Seat, [w, d - head, top], [0.0, head * 0.5, 0.0]);
            b.part(PartRole::Back, [w, head, h], [0.0, (head - d) * 0.5, 0.0]);
            surface(top, rect(-w * 0.5, -d * 0.5 + head, w * 0.5, d * 0.5))
        }
        Group::Sofa => {
            let seat = sofa_seat(h);
            let back = (0.25 * d).clamp(0.12, 0.3).min(0.4 * d);
            let arm = (0.1 * w).clamp(0.08, 0.2).min(0.2 * w);
            let arm_h = (seat + 0.2).min(h);
            b.part(PartRole::Seat, [w - 2.0 * arm, d - back, seat], [0.0, back * 0.5, 0.0]);
            b.part(PartRole::Back, [w, back, h], [0.0, (back - d) * 0.5, 0.0]);
            for s in [-1.0, 1.0] {
                b.part(PartRole::Arm, [arm, d - back, arm_h], [s * (w - arm) * 0.5, back * 0.5, 0.0]);
            }
            surface(seat, rect(-w * 0.5 + arm, -d * 0.5 + back, w * 0.5 - arm, d * 0.5))
        }
        Group::Chair => {
            let seat = chair_seat(h);
            let t = 0.05f64.min(seat * 0.5);
            let back = 0.06f64.min(d * 0.15);
            b.part(PartRole::Seat, [w, d, t], [0.0, 0.0, seat - t]);
            b.part(PartRole::Back, [w, back, h - seat], [0.0, (back - d) * 0.5, seat]);
            b.legs(w, d, seat - t);
            surface(seat, rect(-w * 0.5, -d * 0.5 + back, w * 0.5, d * 0.5))
        }
        Group::Stool => {
            let t = 0.05f64.min(h * 0.5);
            b.part(PartRole::Seat, [w, d, t], [0.0, 0.0, h - t]);
            b.legs(w, d, h - t);
            surface(h, full)
        }
        Group::Table => {
            let top = if category == Category::DressingTable && h > 1.0 { 0.75 } else { h };
            let t = 0.04f64.min(top * 0.5);
            b.part(PartRole::Top, [w, d, t], [0.0, 0.0, top - t]);
            b.legs(w, d, top - t);
            if top < h {
                b.part(
                    PartRole::Panel,
                    [w, 0.04f64.min(d * 0.2), h - top],
                    [0.0, (0.04f64.min(d * 0.2) - d) * 0.5, top],
                );
            }
            surface(top, full)
        }
        Group::Cabinet | Group::Shelf => {
            b.part(PartRole::Body, [w, d, h], [0.0, 0.0, 0.0]);
            surface(h, full)
        }
        Group::Lamp => {
            if category == Category::PendantLamp {
                let shade = 0.4 * h;
                b.part(PartRole::Shade, [w, d, shade], [0.0, 0.0, 0.0]);
                b.part(PartRole::Cord, [0.02, 0.02, h - shade], [0.0, 0.0, shade]);
            } else {
                b.part(PartRole::Shade, [w, d, h], [0.0, 0.0, 0.0]);
            }
            None
        }
    };
    Template { parts: b.parts, surface }
}

impl Surface {
    /// The surface's centre in world coordinates, on the surface, for an object box.
    pub fn world_point(&self, obox: &OBox, local: DVec2) -> DVec3 {
        let p = obox.to_world(local.extend(0.0));
        DVec3::new(p.x, p.y, self.height)
    }

    /// Width and depth of the surface rectangle.
    pub fn extent(&self) -> DVec2 {
        self.max - self.min
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::intersection_volume;

    fn boxed(size: [f64; 3], yaw: f64) -> OBox {
        OBox::new(DVec3::new(1.0, 2.0, size[2] * 0.5), DVec3::from(size), yaw)
    }

    #[test]
    fn parts_stay_inside_the_box_and_do_not_overlap() {
        for &c in Category::ALL {
            let b = boxed([0.9, 0.8, 0.95], 0.6);
            let t = template_of(c, &b);
            assert!(!t.parts.is_empty(), "{c}");
            for (i, p) in t.parts.iter().enumerate() {
                for corner in p.obox.footprint() {
                    assert!(b.footprint_signed_distance(corner) < 1e-9, "{c}: part leaves the box");
                }
                let (z0, z1) = p.obox.z_range();
                let (bz0, bz1) = b.z_range();
                assert!(z0 >= bz0 - 1e-9 && z1 <= bz1 + 1e-9, "{c}: part leaves the box vertically");
                for q in &t.parts[i + 1..] {
                    assert!(intersection_volume(&p.obox, &q.obox) < 1e-9, "{c}: {:?} overlaps {:?}", p.role, q.role);
                }
            }
        }
    }

    #[test]
    fn chair_seat_height_and_legroom_under_a_table() {
        let chair = template_of(Category::DiningChair, &boxed([0.45, 0.5, 0.88], 0.0));
        let s = chair.surface.unwrap();
        assert!((s.height - 0.4576).abs() < 1e-9);
        let table = template_of(Category::DiningTable, &boxed([1.6, 0.9, 0.75], 0.0));
        // A knee 0.55 m high under the middle of the table touches no part.
        let knee = DVec3::new(1.0, 2.0, 0.55);
        assert!(table.parts.iter().all(|p| p.obox.signed_distance(knee) > 0.1));
        assert_eq!(table.parts.iter().filter(|p| p.role == PartRole::Leg).count(), 4);
    }

    #[test]
    fn beds_have_a_headboard_and_a_mattress_top() {
        let bed = template_of(Category::DoubleBed, &boxed([1.6, 2.1, 1.1], 0.0));
        assert_eq!(bed.surface.unwrap().height, 0.55);
        let head = bed.parts.iter().find(|p| p.role == PartRole::Back).unwrap();
        assert!(head.obox.center.y < 2.0 - 1.0, "headboard at the back (local −y)");
        let low = template_of(Category::SingleBed, &boxed([0.9, 2.0, 0.5], 0.0));
        assert_eq!(low.parts.len(), 1);
        assert_eq!(low.surface.unwrap().height, 0.5);
    }
}
