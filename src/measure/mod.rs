//! Measures that generation, repair, the dataset and evaluation share (base layer): contact IoU
//! (how well furniture covers a contact box) and E_pen (how deep bodies sink into furniture).
//! `eval` re-exports them with its other metrics and tables.

mod contact;
mod penetration;

pub use contact::{contact_iou, scene_contact_iou};
pub use penetration::{FurnitureField, SURFACE_POINTS, human_penetration, scene_penetration};
