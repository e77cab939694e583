//! Metrics: contact IoU, interpenetration (E_pen), the layout metrics of SHADE's Table 1 (Col_mot,
//! R_out, Col_obj, CKL, and the CKL that real layouts score), realism beyond them (per-room category
//! counts, `counts`; pieces of sizes no real piece has, `sizes`; the SCA two-sample test, `sca`) and, in `table`, the evaluation of generated
//! scene sets with the physics rates.

mod ckl_floor;
mod correlation;
mod counts;
mod layout_metrics;
mod sca;
mod sizes;
mod table;

pub use crate::furniture::beyond_real;
pub use crate::measure::{FurnitureField, SURFACE_POINTS, human_penetration, scene_penetration};
pub use crate::measure::{contact_iou, scene_contact_iou};
pub use ckl_floor::{CklFloor, ckl_floor, contact_floor, contact_pieces};
pub use correlation::{pearson, rank_auc};
pub use counts::{CountDistribution, CountReport, UnseenCount, count_report};
pub use layout_metrics::{
    CategoryShare, LayoutCounts, category_frequencies, category_kl, category_shares, frequencies_of,
};
pub use sca::{SCA_MIN_LAYOUTS, Sca, ScaConfig, layout_feature_names, layout_features, sca};
pub use sizes::{SizeReport, UnrealSize, size_report};
pub use table::{EvalRow, PhysicsRates, evaluate};
