//! Which pieces a removal must spare (ours; shared by `left_out` and `overlaps`, not a step): a
//! piece that holds a person's contact, a piece someone sits at, and the last piece that makes the
//! room what it is. A dining room whose only table was taken out because it touched a bookshelf
//! passes the check and is no dining room.

use super::config::LeftOutConfig;
use crate::geom::facing;
use crate::human::ContactBox;
use crate::scene::{Action, Category, Group, Object, RoomType, Scene};

/// Whether object `i` is in use: it holds a contact (`holds[i]`), a sitter of `contacts` sits at
/// it ([`sits_at`]) or it is the room's last anchor ([`is_last_anchor`]).
pub fn in_use(scene: &Scene, i: usize, holds: &[bool], contacts: &[ContactBox], cfg: &LeftOutConfig) -> bool {
    holds[i] || contacts.iter().any(|c| sits_at(c, &scene.objects[i], cfg)) || is_last_anchor(scene, i)
}

/// Whether `contact` is a sitter who sits at `o`: its top at least `cfg.sits_at_above` above their
/// seat (the support box's top) and its footprint over a point on the line from the box's centre
/// to `cfg.sits_at_reach` beyond its front edge, the way they face.
pub fn sits_at(contact: &ContactBox, o: &Object, cfg: &LeftOutConfig) -> bool {
    let b = &contact.obox;
    if contact.action != Action::Sit || o.obox().z_range().1 < b.z_range().1 + cfg.sits_at_above {
        return false;
    }
    let ahead = facing(b.yaw);
    let reach = b.size.y * 0.5 + cfg.sits_at_reach;
    let footprint = o.obox();
    (0..=16).any(|k| footprint.footprint_contains(b.center.truncate() + ahead * (reach * k as f64 / 16.0)))
}

/// Whether `o` is a piece that makes a room of type `room` what it is.
fn anchors(room: RoomType, o: &Object) -> bool {
    match room {
        RoomType::Bedroom => o.category.group() == Group::Bed,
        RoomType::Dining => o.category == Category::DiningTable,
        RoomType::Living => o.category.group() == Group::Sofa,
    }
}

/// Whether object `i` is the last of the pieces that make its room what it is ([`anchors`]).
pub fn is_last_anchor(scene: &Scene, i: usize) -> bool {
    let anchor = |o: &Object| anchors(scene.room_type, o);
    anchor(&scene.objects[i]) && scene.objects.iter().filter(|o| anchor(o)).count() == 1
}
