//! One row of the evaluation table: the metrics of a set of generated scenes against reference
//! category frequencies. Physics rates come from `sim` and are filled in by the caller.

use super::{FurnitureField, LayoutCounts, category_frequencies, category_kl, contact_iou, human_penetration};
use crate::human::contact_boxes;
use crate::scene::{RoomType, Scene};
use serde::{Deserialize, Serialize};

/// Physics rates of a set of scenes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PhysicsRates {
    /// Scenes with a human–furniture penetration deeper than the tolerance / scenes.
    pub penetrating_scenes: f64,
    /// Unsupported sitting, lying or touching humans / contact humans.
    pub unsupported_humans: f64,
    /// Unstable objects / objects.
    pub unstable_objects: f64,
}

/// The metrics of one set of scenes (one row of Table 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EvalRow {
    /// The set's name (its folder).
    pub name: String,
    /// Scenes evaluated.
    pub scenes: usize,
    /// Mean contact IoU over contact boxes.
    pub contact_iou: f64,
    /// Col_mot.
    pub col_mot: f64,
    /// R_out.
    pub r_out: f64,
    /// Col_obj.
    pub col_obj: f64,
    /// CKL against the reference frequencies.
    pub ckl: f64,
    /// Mean E_pen per scene (sum over humans).
    pub e_pen: f64,
    /// Physics rates, when checked.
    pub physics: Option<PhysicsRates>,
}

/// The metrics of `scenes` (all of `room`) against `reference` category frequencies.
pub fn evaluate(name: &str, scenes: &[Scene], room: RoomType, reference: &[f64]) -> EvalRow {
    let mut counts = LayoutCounts::default();
    let (mut iou, mut boxes, mut pen) = (0.0, 0usize, 0.0);
    for s in scenes {
        counts.add(&LayoutCounts::of(s));
        let field = FurnitureField::new(&s.objects);
        for h in &s.humans {
            for b in contact_boxes(h) {
                iou += contact_iou(&b.obox, &s.objects);
                boxes += 1;
            }
            pen += human_penetration(h, &field);
        }
    }
    let q = category_frequencies(scenes.iter(), room);
    EvalRow {
        name: name.to_string(),
        scenes: scenes.len(),
        contact_iou: if boxes == 0 { 0.0 } else { iou / boxes as f64 },
        col_mot: counts.col_mot(),
        r_out: counts.r_out(),
        col_obj: counts.col_obj(),
        ckl: category_kl(reference, &q),
        e_pen: if scenes.is_empty() { 0.0 } else { pen / scenes.len() as f64 },
        physics: None,
    }
}
