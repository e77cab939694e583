//! Contact IoU: how well furniture covers a contact box.
//!
//! Per contact box: the largest, over objects, of intersection volume / contact-box volume (the
//! anchors' definition: a box fully inside some object scores 1). A scene's contact IoU is the mean
//! over its contact boxes.

use crate::geom::{OBox, intersection_volume};
use crate::human::Conditions;
use crate::scene::{Object, Scene};

/// Contact IoU of one box against `objects` (0 when there are none).
pub fn contact_iou(contact: &OBox, objects: &[Object]) -> f64 {
    let volume = contact.volume();
    if volume <= 0.0 {
        return 0.0;
    }
    objects.iter().map(|o| intersection_volume(contact, &o.obox()) / volume).fold(0.0, f64::max).min(1.0)
}

/// Mean contact IoU of a scene's contact boxes, `None` without contact humans.
pub fn scene_contact_iou(scene: &Scene) -> Option<f64> {
    let boxes = Conditions::contact_boxes_of(scene);
    if boxes.is_empty() {
        return None;
    }
    Some(boxes.iter().map(|b| contact_iou(&b.obox, &scene.objects)).sum::<f64>() / boxes.len() as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Category;
    use glam::DVec3;

    #[test]
    fn half_inside_is_one_half() {
        let o = Object {
            id: "o".into(),
            category: Category::Table,
            center: [0.0, 0.0, 0.375],
            size: [1.0, 1.0, 0.75],
            yaw: 0.3,
        };
        let b = OBox::new(DVec3::new(0.0, 0.0, 0.75), DVec3::splat(0.12), 0.3);
        assert!((contact_iou(&b, std::slice::from_ref(&o)) - 0.5).abs() < 1e-9);
        let inside = OBox::new(DVec3::new(0.0, 0.0, 0.5), DVec3::splat(0.12), 1.0);
        assert!((contact_iou(&inside, &[o]) - 1.0).abs() < 1e-9);
        assert_eq!(contact_iou(&inside, &[]), 0.0);
    }
}
