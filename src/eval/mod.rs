//! Metrics: contact IoU and interpenetration (E_pen) so far; the layout metrics (Col_mot, R_out,
//! Col_obj, CKL) and the physics rates join with the evaluation command.

mod contact;
mod penetration;

pub use contact::{contact_iou, scene_contact_iou};
pub use penetration::{FurnitureField, SURFACE_POINTS, human_penetration, scene_penetration};
