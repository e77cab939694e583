//! Pictures of scenes: a small deterministic canvas, masks as PNG and the humans' top and side
//! views. (MJCF, robosuite and glTF exports join here.)

mod canvas;
mod humans_png;
mod mask_png;

pub use canvas::{Canvas, Color, View, png_bytes};
pub use humans_png::{action_color, render_humans, render_humans_sized};
pub use mask_png::{mask_png, save_mask_png};
