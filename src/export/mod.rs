//! Exports: MuJoCo worlds (MJCF), and pictures (a small deterministic canvas, masks as PNG, the
//! humans' top and side views). (robosuite arenas and glTF join here.)

mod canvas;
mod font;
mod humans_png;
mod loss_png;
mod mask_png;
mod mjcf;
mod plan_png;
#[cfg(feature = "mujoco")]
mod validate_mujoco;

pub use canvas::{Canvas, Color, View, png_bytes};
pub use font::{draw_text, text_width};
pub use humans_png::{action_color, render_humans, render_humans_sized};
pub use loss_png::{loss_canvas, render_loss_png};
pub use mask_png::{mask_png, save_mask_png};
pub use mjcf::{MjcfOptions, MocapMotion, PAIR_MARGIN, mocap_motion, part_names, scene_mjcf};
pub use plan_png::{group_color, render_plan};
#[cfg(feature = "mujoco")]
pub use validate_mujoco::{MAX_MOVE, MujocoValidation, validate_in_mujoco};
