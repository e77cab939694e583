//! One row of the evaluation table: the metrics of a set of generated scenes against reference
//! category frequencies. Physics rates come from `sim` and are filled in by the caller.

use super::{
    CategoryShare, CklFloor, CountReport, FurnitureField, LayoutCounts, Sca, SizeReport, category_frequencies,
    category_kl, category_shares, contact_iou, human_penetration,
};
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
    /// Scenes with a violation of any kind (those `shade-sim check` fails) / scenes.
    #[serde(default)]
    pub violating_scenes: f64,
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
    /// CKL by category: every category the reference or the row has, its two shares and its term,
    /// largest term first (`eval::category_shares`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub categories: Vec<CategoryShare>,
    /// Mean E_pen per scene (sum over humans).
    pub e_pen: f64,
    /// Physics rates, when checked.
    pub physics: Option<PhysicsRates>,
    /// Against a baseline row (`eval --baseline`): the mean of this row's Col_mot, R_out and
    /// Col_obj each over the baseline's (1 = as the baseline, lower is better; SHADE's three
    /// layout metrics weighed alike).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layout_ratio: Option<f64>,
    /// What real layouts score on CKL at this row's size (`eval::ckl_floor`), when the caller
    /// has a pool of them (`eval` with a dataset as reference).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ckl_floor: Option<CklFloor>,
    /// What a generator that got every test scene's contact pieces right and drew the rest like the
    /// data scores on CKL (`eval::contact_floor`), for a row of the reference's own size.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ckl_contact_floor: Option<CklFloor>,
    /// Per-room category counts against the reference's (`eval::count_report`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub counts: Option<CountReport>,
    /// Rooms with a piece of a size no real piece of its category has (`eval::size_report`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sizes: Option<SizeReport>,
    /// The SCA two-sample test against the reference's layouts (`eval::sca`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sca: Option<Sca>,
}

impl EvalRow {
    /// The mean of Col_mot, R_out and Col_obj each over `base`'s (a metric that is 0 in both
    /// counts as 1; 0 in `base` only, as the row's value over 0.001).
    pub fn layout_ratio_to(&self, base: &EvalRow) -> f64 {
        let ratio = |a: f64, b: f64| match (a, b) {
            (a, b) if b > 0.0 => a / b,
            (a, _) if a > 0.0 => a / 0.001,
            _ => 1.0,
        };
        (ratio(self.col_mot, base.col_mot) + ratio(self.r_out, base.r_out) + ratio(self.col_obj, base.col_obj)) / 3.0
    }
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
        categories: category_shares(reference, &q, room),
        e_pen: if scenes.is_empty() { 0.0 } else { pen / scenes.len() as f64 },
        physics: None,
        layout_ratio: None,
        ckl_floor: None,
        ckl_contact_floor: None,
        counts: None,
        sizes: None,
        sca: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(col_mot: f64, r_out: f64, col_obj: f64) -> EvalRow {
        EvalRow {
            name: String::new(),
            scenes: 1,
            contact_iou: 0.0,
            col_mot,
            r_out,
            col_obj,
            ckl: 0.0,
            categories: Vec::new(),
            e_pen: 0.0,
            physics: None,
            layout_ratio: None,
            ckl_floor: None,
            ckl_contact_floor: None,
            counts: None,
            sizes: None,
            sca: None,
        }
    }

    #[test]
    fn layout_ratio_weighs_the_three_metrics_alike() {
        let base = row(0.1, 0.4, 0.0);
        // (0.05 / 0.1 + 0.1 / 0.4 + 1) / 3 for a metric 0 in both; 0.002 over a zero baseline counts
        // as 0.002 / 0.001.
        assert!((row(0.05, 0.1, 0.0).layout_ratio_to(&base) - (0.5 + 0.25 + 1.0) / 3.0).abs() < 1e-12);
        assert!((row(0.1, 0.4, 0.002).layout_ratio_to(&base) - (1.0 + 1.0 + 2.0) / 3.0).abs() < 1e-12);
        assert_eq!(base.layout_ratio_to(&base), 1.0);
    }
}
