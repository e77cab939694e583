//! One table row per generated scene: objects, contact IoU, Col_mot, R_out, Col_obj and, when
//! checked, the physics violations. Shared by `generate` and `demo`.

use serde::Serialize;
use shade_sim::eval::{LayoutCounts, scene_contact_iou};
use shade_sim::scene::Scene;
use shade_sim::sim::CheckReport;

#[derive(Debug, Clone, Serialize)]
pub struct SceneRow {
    pub scene: String,
    pub objects: usize,
    /// Mean over the scene's contact boxes; absent when nobody touches anything.
    pub contact_iou: Option<f64>,
    pub col_mot: f64,
    pub r_out: f64,
    pub col_obj: f64,
    /// Physics violations (absent when not checked).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub violations: Option<usize>,
}

impl SceneRow {
    pub fn of(name: &str, scene: &Scene, check: Option<&CheckReport>) -> SceneRow {
        let counts = LayoutCounts::of(scene);
        SceneRow {
            scene: name.to_string(),
            objects: scene.objects.len(),
            contact_iou: scene_contact_iou(scene),
            col_mot: counts.col_mot(),
            r_out: counts.r_out(),
            col_obj: counts.col_obj(),
            violations: check.map(|r| r.violations.len()),
        }
    }
}

/// The rows as an aligned text table.
pub fn table(rows: &[SceneRow]) -> String {
    let width = rows.iter().map(|r| r.scene.len()).max().unwrap_or(5).max(5);
    let mut t = format!("{:<width$}  objects  contact IoU  Col_mot  R_out  Col_obj  violations\n", "scene");
    for r in rows {
        let iou = r.contact_iou.map_or("-".to_string(), |v| format!("{v:.3}"));
        let violations = r.violations.map_or("-".to_string(), |v| v.to_string());
        t.push_str(&format!(
            "{:<width$}  {:>7}  {:>11}  {:>7.3}  {:>5.3}  {:>7.3}  {:>10}\n",
            r.scene, r.objects, iou, r.col_mot, r.r_out, r.col_obj, violations
        ));
    }
    t
}
